"""Top view of the disk sliding in, striking the wall at B, and leaving with its new velocity and spin."""
from __future__ import annotations

import math

import numpy as np

from solvers import disk_wall as solver
from solvers.core import plain_number as n
from viz.common import (COLORS, Figure, headline, headline_text, animated, arrows, as_one, base_layout, circles, holding, line, moving, padded,
                         r, segments, thumbnail, trails)
from viz.sketch import Drawing, Sketch

THUMBNAIL = thumbnail(  # the home page's sketch (no physics)
    f'<line x1="10" y1="14" x2="190" y2="14" stroke="{COLORS["ink"]}" stroke-width="5"/>'
    f'<circle cx="80" cy="68" r="26" fill="{COLORS["body"]}33" stroke="{COLORS["body"]}" stroke-width="3"/>'
    f'<line x1="80" y1="68" x2="100" y2="84" stroke="{COLORS["accent"]}" stroke-width="3"/>'
    f'<line x1="80" y1="68" x2="110" y2="34" stroke="{COLORS["velocity"]}" stroke-width="3" marker-end="url(#g)"/>'
    f'<path d="M120,96 a36,36 0 0 0 14,-30" fill="none" stroke="{COLORS["accent"]}" stroke-width="2" stroke-dasharray="4 3"/>',
    "A spinning disk moving toward a wall")


def figures(solution, system: str = "si") -> list[Figure]:
    p, a = solution.params, solution.answers
    m = solver.motion(solution)
    R = p["R"]
    x_lo, x_hi = padded(min(m["x"].min(), -2 * R) - R, max(m["x"].max(), 2 * R) + R)
    y_lo = min(m["y"].min(), -R) - 1.2 * R
    y_hi = m["wall_y"] + 0.8 * R
    wide = 3 * (x_hi - x_lo)  # the wall runs past the view whatever the window's aspect
    wall = line(r([x_lo - wide, x_hi + wide]), r([m["wall_y"]] * 2), "wall", COLORS["ground"], width=6)
    foot = np.linspace(x_lo - wide, x_hi + wide, 168)
    hatch = line(*as_one(*segments(foot, m["wall_y"], foot + 0.25 * R, m["wall_y"] + 0.25 * R)),
                 "wall (hatched)", COLORS["ground"], width=1, show_legend=False)
    at_impact = np.arange(len(m["t"])) == m["impact_index"]  # the impulse is drawn in that frame only
    drawn = _bodies(m["x"], m["y"], m["angle"], m["vx"], m["vy"], at_impact, m["wall_y"], p, a)
    moving_traces = [
        moving(line(None, None, "path of the centre", COLORS["trail"], width=2, dash="dot"), *trails(m["x"], m["y"])),
        moving(line(None, None, "disk", COLORS["body"], width=3, fill="toself"), *drawn["disk"]),
        moving(line(None, None, "marked radius", COLORS["accent"], width=4), *drawn["marked radius"]),
        moving(line(None, None, "velocity of the centre", COLORS["velocity"], width=3), *drawn["velocity of the centre"]),
        moving(line(None, None, "impulse on the disk at B", COLORS["impulse"], width=5), *drawn["impulse on the disk at B"]),
    ]
    (x_lo, x_hi), (y_lo, y_hi) = holding((x_lo, x_hi), (y_lo, y_hi), moving_traces)  # the arrows' tips too
    layout = base_layout(equal_axes=True, x_range=(x_lo, x_hi), y_range=(y_lo, y_hi),
                         x_title="x, along the wall (m)", y_title="y, toward the wall (m)")
    spec = animated([wall, hatch], moving_traces, m["t"], layout)
    regime = "sticks (B stops slipping)" if solution.regime == "stick" else "slides along the wall throughout"
    if p["e"] == 0:  # no normal velocity after: it stays against the wall
        after = f"with e = 0 it does not rebound: it runs on along the wall at {n(a['speed1'])} m/s"
    else:
        after = f"it rebounds and leaves at {n(a['speed1'])} m/s"
    head = headline("Top view. The disk slides toward the wall at ", ("V", "n", 4), " m/s, spinning at ",
                    ("omega", "n", 4), f" rad/s, strikes it at t = 0 and {regime}")
    description = (headline_text(head, {**p, **a}) + f"; {after}, spinning at "
                   f"{n(a['omega1'])} rad/s. The orange radius shows the spin, the green arrow the velocity, "
                   "the red arrow the wall's impulse.")
    return [Figure("disk_wall_motion", "The impact, slowed down", spec, description, height=520,
                   key_frame=int(m["impact_index"]), key_caption="the impact: the wall's impulse on the disk at B",
                   headline=head)]


def _bodies(x, y, angle, vx, vy, impulse_shown, wall_y, p, a, xp=np) -> dict:
    """The disk, its marked radius and velocity at centres (x, y), angles and velocities (one per frame),
    and the wall's impulse at B where ``impulse_shown`` (1 or 0 per frame)."""
    R = p["R"]
    scale = 1.6 * R / xp.maximum(p["V"], a["speed1"])  # velocity arrows: the faster one is 1.6 R long
    impulse_scale = 1.6 * R / xp.maximum(xp.hypot(a["impulse_t"], a["impulse_n"]), 1e-12)
    return {"disk": circles(x, y, R), "marked radius": segments(x, y, x + R * xp.cos(angle), y + R * xp.sin(angle)),
            "velocity of the centre": arrows(x, y, vx * scale, vy * scale, xp=xp),
            "impulse on the disk at B": arrows(0.0, wall_y, impulse_shown * a["impulse_t"] * impulse_scale,
                                               impulse_shown * a["impulse_n"] * impulse_scale, xp=xp)}


def key_pose(p, a, system: str = "si", xp=np) -> dict:
    """The stage figure at its key instant, the impact: in the motion's frame (solvers.disk_wall.motion:
    the impact at t = 0 with the centre at the origin, not yet turned, the wall at y = R), the disk
    arriving at V along θ and the wall's impulse on it, each a (x, y) row (numpy for the figure,
    solvers.live's symbols for the browser's drag)."""
    zero = np.zeros(1) if isinstance(p["V"], (int, float)) else np.zeros(1, dtype=object)
    drawn = _bodies(zero, zero, zero, p["V"] * xp.sin(p["theta"]) + zero, p["V"] * xp.cos(p["theta"]) + zero,
                    zero + 1, p["R"], p, a, xp)
    return {name: (x[0], y[0]) for name, (x, y) in drawn.items()}


def sketch(params) -> Drawing:
    """The problem's sketch: the disk sliding toward the wall at V, θ from the wall's normal, spinning at ω."""
    R, th = params["R"], params["theta"]
    s = Sketch(solver, "The disk slides toward a rough wall, spinning")
    C = (-2.6 * R * math.sin(th), -R - 2.6 * R * math.cos(th))
    s.support((C[0] - 1.6 * R, 0.0), (max(2.4 * R, C[0] + 2.4 * R), 0.0), side=1)
    s.disk(C, R)
    s.point(C, "C", (-1, 0.25), 30.0)
    s.dashed(C, (C[0], C[1] + 1.9 * R))  # the wall's normal through C
    s.velocity(C, math.pi / 2 - th, 1.6 * R, "V")
    if th > math.radians(2):
        s.angle(C, math.pi / 2 - th, math.pi / 2, "theta", 1.15 * R)
    s.spin(C, 0.32 * R, params["omega"] >= 0, "omega")
    s.length(C, (C[0] + R * math.cos(math.radians(-50)), C[1] + R * math.sin(math.radians(-50))), "R", 0.0)
    return s.drawing()
