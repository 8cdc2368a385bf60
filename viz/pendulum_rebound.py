"""Side view of the pendulum: release, swing, bounce and rebound (several bounces), with θ(t)."""
from __future__ import annotations

import math

import numpy as np

from solvers import pendulum_rebound as solver
from solvers.core import plain_fixed, plain_number
from solvers import units
from viz.common import (COLORS, Figure, headline, headline_text, animated, arrows, base_layout, circles, column, fitted, line, moving, points,
                         r, segments, STILL_HEIGHT, still_layout, thumbnail, trails)
from viz.sketch import Drawing, Sketch

THUMBNAIL = thumbnail(  # the home page's sketch (no physics)
    f'<line x1="10" y1="100" x2="190" y2="100" stroke="{COLORS["ink"]}" stroke-width="5"/>'
    f'<line x1="60" y1="18" x2="120" y2="72" stroke="#555" stroke-width="4"/>'
    f'<circle cx="132" cy="82" r="15" fill="{COLORS["body"]}33" stroke="{COLORS["body"]}" stroke-width="3"/>'
    f'<path d="M170,20 a90,90 0 0 1 -20,46" fill="none" stroke="{COLORS["accent"]}" stroke-width="2" stroke-dasharray="4 3"/>'
    f'<text x="58" y="14" font-size="12" fill="{COLORS["ink"]}">O</text>',
    "A pendulum with a sphere about to strike the floor")


def figures(solution, system: str = "si") -> list[Figure]:
    p, a = solution.params, solution.answers
    m = solver.motion(solution)
    k = units.to_display(1.0, "length", system)  # lengths drawn in the page's unit
    L, rad = p["L"] * k, p["r"] * k
    u = units.unit("length", system)
    floor = p["surface"] == "floor"
    contact = ({"x": [0.0], "y": [-p["d"] * k]} if floor else {"x": [-rad], "y": [0.0]})  # where the surface is
    pivot = points([0], [0], "pivot O", COLORS["ink"], size=9, symbol="x")
    theta_deg = np.degrees(m["theta"])
    curve = line(r(m["t_curve"]), r(np.degrees(m["theta_curve"])), "θ(t)", COLORS["body"], width=2,
                 xaxis="x2", yaxis="y2")  # dense, with a point at each impact: the cusps land on θ_I
    impact_line = line(r([m["t"][0], m["t"][-1]]), r([math.degrees(a["theta_impact"])] * 2),
                       "impact angle θ<sub>I</sub>", COLORS["ground"], width=1, dash="dash", xaxis="x2", yaxis="y2")
    first_impact = int(np.argmin(np.abs(m["t"] - m["impact_times"][0]))) if m["impact_times"] else 0
    # The first impact's frame is drawn at the closed form's instant (the key pose, below): the same
    # numbers the browser's generated pose gives while a control is dragged.
    theta, omega = m["theta"].copy(), m["omega"].copy()
    theta[first_impact], omega[first_impact] = a["theta_impact"], a["omega_impact"]
    cx, cy = (L + rad) * np.cos(theta), (L + rad) * np.sin(theta)
    drawn = _bodies(theta, omega, p, a, k)
    moving_traces = [
        moving(line(None, None, "path of the sphere", COLORS["trail"], width=2, dash="dot"), *trails(cx, cy, keep=25)),
        moving(line(None, None, "rod", COLORS["ink"], width=5), *drawn["rod"]),
        moving(line(None, None, "sphere", COLORS["body"], width=3, fill="toself"), *drawn["sphere"]),
        moving(line(None, None, "marked radius", COLORS["accent"], width=4), *drawn["marked radius"]),
        moving(line(None, None, "velocity of the centre", COLORS["velocity"], width=3), *drawn["velocity of the centre"]),
        # unclipped: θ(t)'s plot is ranged by its curve, and the marker at either end would show a half
        moving({**points(None, None, "now", COLORS["impulse"], size=10, xaxis="x2", yaxis="y2"), "cliponaxis": False},
               column(m["t"]), column(theta_deg)),
    ]
    # The stage fits the motion (pivot, rod, sphere and its arrow over every frame) and the surface's
    # contact; the surface runs past the view whatever the window's aspect.
    x_range, y_range = fitted([pivot, *moving_traces[1:5], contact])
    ground = _surface(p, k, x_range, y_range)
    layout = base_layout(equal_axes=True, x_range=x_range, y_range=y_range, x_title=f"x ({u})", y_title=f"y ({u})")
    # Stacked, not side by side, so that a phone-width window keeps both readable.
    layout["yaxis"]["domain"] = [0.42, 1.0]
    layout["xaxis"]["title"]["standoff"] = 4  # under its own tick labels: the motion's, not the θ plot's below
    layout["xaxis2"] = {"anchor": "y2", "title": {"text": "t (s)"}}
    layout["yaxis2"] = {"anchor": "x2", "domain": [0.0, 0.22], "title": {"text": "θ (°)"}}
    layout["height"] = 700
    spec = animated([ground, pivot, curve, impact_line], moving_traces, m["t"], layout)
    head = headline("Side view. Released from rest at θ₀ = ", ("theta0", "deg", 1), ", the pendulum swings down and "
                    f"the sphere strikes the {p['surface']} at θ_I = ", ("theta_impact", "deg", 1))
    description = (headline_text(head, {**p, **a}) + f", {_rebounds(p, a, solution.extras['bounce_peaks'])}. "
                   "Below: θ against time, with the impact angle dashed.")
    return [Figure("pendulum_motion", "Release, bounce, rebound", spec, description, height=700,
                   key_frame=first_impact, key_caption=f"the first impact, at θ_I = {deg(a['theta_impact'])}",
                   headline=head)]


def at_limit(params, system: str = "si") -> list[Figure]:
    """Beside the refusal of a release angle at or below the impact angle: the pendulum at rest against
    the surface at θ_I, where its swing would end, with θ₀ dashed where it was asked for (inside the
    surface, or on it)."""
    p = solver.validated(params)
    theta_I, theta0 = solver.impact_angle(p), p["theta0"]
    k = units.to_display(1.0, "length", system)
    u = units.unit("length", system)
    L, rad = p["L"] * k, p["r"] * k
    drawn = _bodies(np.array([theta_I]), np.zeros(1), p, {"omega_impact": 0.0}, k)
    reach = 1.1 * (L + 2 * rad)
    bodies = [line(*(row[0] for row in drawn["rod"]), "rod", COLORS["ink"], width=5),
              line(*(row[0] for row in drawn["sphere"]), "sphere", COLORS["body"], width=3, fill="toself"),
              line(*(row[0] for row in drawn["marked radius"]), "marked radius", COLORS["accent"], width=4)]
    asked = line(r([0.0, reach * math.cos(theta0)]), r([0.0, reach * math.sin(theta0)]), "release angle θ₀ asked for",
                 COLORS["impulse"], width=2, dash="dash")
    pivot = points([0], [0], "pivot O", COLORS["ink"], size=9, symbol="x")
    x_range, y_range = fitted([pivot, asked, *bodies])
    ground = _surface(p, k, x_range, y_range)
    layout = still_layout(x_range, y_range, x_title=f"x ({u})", y_title=f"y ({u})")
    description = (f"Side view. The sphere touches the {p['surface']} at θ_I = {plain_number(math.degrees(theta_I))}°, "
                   f"where it is drawn: released at θ₀ = {plain_number(math.degrees(theta0))}° (dashed) it would start "
                   f"{'on' if theta0 == theta_I else 'inside'} the {p['surface']}, with no swing before an impact.")
    return [Figure("pendulum_at_limit", f"Where the sphere meets the {p['surface']}",
                   {"data": [ground, asked, *bodies, pivot], "layout": layout}, description, animated=False,
                   height=STILL_HEIGHT)]


def _surface(p, k: float, x_range, y_range) -> dict:
    """The floor (at −d) or the wall (at x = −r), lengths ``k`` times their SI value, running past the view
    ``x_range``, ``y_range`` whatever the window's aspect."""
    span = 3 * max(x_range[1] - x_range[0], y_range[1] - y_range[0])
    if p["surface"] == "floor":
        return line(r([x_range[0] - span, x_range[1] + span]), [-p["d"] * k] * 2, "floor", COLORS["ground"], width=6)
    return line([-p["r"] * k] * 2, r([y_range[0] - span, y_range[1] + span]), "wall", COLORS["ground"], width=6)


def _bodies(theta, omega, p, a, k: float, xp=np) -> dict:
    """The rod, the sphere, its marked radius and its velocity at angles ``theta`` and rates ``omega``
    (one per frame), lengths drawn ``k`` times their SI value (the page's unit)."""
    L, rad = p["L"] * k, p["r"] * k
    c, s = xp.cos(theta), xp.sin(theta)
    cx, cy = (L + rad) * c, (L + rad) * s
    v_scale = 0.35 * (L + 2 * rad) / xp.maximum(xp.abs(a["omega_impact"]) * (p["L"] + p["r"]), 1e-12)
    speed = omega * (p["L"] + p["r"])
    return {"rod": segments(0.0, 0.0, L * c, L * s), "sphere": circles(cx, cy, rad),
            "marked radius": segments(cx, cy, cx - rad * s, cy + rad * c),
            "velocity of the centre": arrows(cx, cy, -s * speed * v_scale, c * speed * v_scale, xp=xp)}


def key_pose(p, a, system: str = "si", xp=np) -> dict:
    """The stage figure's moving bodies at its key instant, the first impact (θ = θ_I, θ̇ = θ̇_I⁻),
    each a (x, y) row: numpy for the figure, solvers.live's symbols for the browser's drag."""
    drawn = _bodies(np.array([a["theta_impact"]]), np.array([a["omega_impact"]]), p, a,
                    units.to_display(1.0, "length", system), xp)
    return {name: (x[0], y[0]) for name, (x, y) in drawn.items()}


def _rebounds(p, a, peaks) -> str:
    """The rebounds a student can tell apart (to the 0.1° shown): none at e = 0, and the list ends
    where the peaks no longer rise visibly above the impact angle."""
    if p["e"] == 0:
        return "and stays there: with e = 0 it does not rebound"
    if p["e"] == 1:
        return f"rebounding to θ₀ = {deg(p['theta0'])} every time: with e = 1 no energy is lost"
    theta_I = math.degrees(a["theta_impact"])
    shown = [deg(q) for q in peaks[:3] if math.degrees(q) - theta_I >= 0.05]
    if not shown:
        return "and barely lifts off again: the rebounds are below 0.1°"
    return ("rebounding to " + ", ".join(shown) + (" on successive bounces" if len(shown) > 1 else "")
            + ("" if len(shown) == len(peaks[:3]) else ", then barely lifting off"))


def deg(angle: float) -> str:
    """An angle in degrees as the caption writes it (0.1°)."""
    return plain_fixed(math.degrees(angle), 1) + "°"


def sketch(params) -> Drawing:
    """The problem's sketch: the rod and sphere released at θ₀ about the pin O, the floor a depth d below O
    (or the wall the hanging sphere touches)."""
    L, r_, th0 = params["L"], params["r"], params["theta0"]
    s = Sketch(solver, "The rod and sphere, released about the pin O")
    u = (math.cos(th0), math.sin(th0))
    S = ((L + r_) * u[0], (L + r_) * u[1])
    reach = L + 2 * r_
    if params["surface"] == "wall":
        s.support((-r_, -1.05 * reach), (-r_, 0.15 * reach), side=1)
    else:
        d = params["d"]
        s.support((-0.25 * reach, -d), (1.05 * reach, -d), side=-1)
        s.length((0.0, 0.0), (0.0, -d), "d", -0.12 * reach)
    s.polygon([(0.0, 0.0), (-0.05 * reach, 0.08 * reach), (0.05 * reach, 0.08 * reach)])  # the pin's bracket
    s.rod((0.0, 0.0), (L * u[0], L * u[1]))
    s.disk(S, r_)
    s.point((0.0, 0.0), "O", (-1, -0.6), 16.0)
    s.dashed((0.0, 0.0), (0.45 * L, 0.0))
    if th0 > math.radians(2):
        s.angle((0.0, 0.0), 0.0, th0, "theta0", 0.3 * L)
    s.length((0.0, 0.0), (L * u[0], L * u[1]), "L", 0.09 * reach)
    s.length(S, (S[0] + r_ * math.cos(th0 - math.pi / 2), S[1] + r_ * math.sin(th0 - math.pi / 2)), "r", 0.0)
    return s.drawing()
