"""Side view of the ladder sliding down the wall and landing flat, with its reactions to scale, and
the wall's and the floor's reactions against time."""
from __future__ import annotations

import numpy as np

from solvers import sliding_ladder as solver
from solvers.core import plain_number as n
from viz.common import (COLORS, Figure, headline, headline_text, animated, arrows, base_layout, column, line, moving, points, r,
                         thumbnail)
from viz.sketch import Drawing, Sketch

# The ladder is drawn as a strip THICKNESS × L wide on the side away from the corner, so its edge
# through A and B is the modelled rod and the drawing never enters the wall or the floor.
THICKNESS = 0.03

THUMBNAIL = thumbnail(
    f'<rect x="14" y="4" width="18" height="102" fill="{COLORS["ground"]}55"/>'
    f'<rect x="32" y="96" width="162" height="10" fill="{COLORS["ground"]}55"/>'
    f'<path d="M32,4 V96 H194" fill="none" stroke="{COLORS["ground"]}" stroke-width="2"/>'
    f'<path d="M32,54 A42,42 0 0 1 74,96" fill="none" stroke="{COLORS["accent"]}" stroke-width="2" '
    f'stroke-dasharray="4 3"/>'
    f'<polygon points="32,36 90,96 96,91 38,31" fill="{COLORS["body"]}55" stroke="{COLORS["body"]}" stroke-width="2"/>'
    f'<circle cx="62" cy="64" r="4" fill="{COLORS["marker"]}" stroke="#222" stroke-width="1"/>'
    f'<line x1="23" y1="30" x2="23" y2="56" stroke="{COLORS["velocity"]}" stroke-width="2.5" marker-end="url(#g)"/>'
    f'<line x1="100" y1="86" x2="136" y2="86" stroke="{COLORS["velocity"]}" stroke-width="2.5" marker-end="url(#g)"/>',
    "A ladder sliding down a smooth wall onto a smooth floor")


def figures(solution, system: str = "si") -> list[Figure]:
    motion = solver.motion(solution)
    return [_animation(solution, motion), _reactions(solution, motion)]


def _animation(solution, m) -> Figure:
    p, a = solution.params, solution.answers
    L = p["L"]
    k = m["leave_frame"]
    # The frame where the top leaves the wall is drawn at the closed form's instant (θ_leave, G on its
    # circle about the corner): the key pose the browser's generated code draws while a control is dragged.
    th, x_G, y_G = (m[name].copy() for name in ("theta", "x_G", "y_G"))
    th[k], x_G[k], y_G[k] = _leaving(p, a)
    drawn = _bodies(th, x_G, y_G, L)
    xs = drawn["ladder"][0]
    x_far = float(max(np.max(xs), L)) * 1.08
    band = 0.1 * L
    at_frames = np.interp(m["t"], m["curve_t"], m["N_wall"]), np.interp(m["t"], m["curve_t"], m["N_floor"])
    at_frames[0][k], at_frames[1][k] = _pushes_leaving(p)  # the closed form's, as the key pose draws them
    pushes = _pushes(th, x_G, y_G, *at_frames, p)
    far = 10 * x_far  # the wall and the floor run on beyond the view, however the equal axes widen it
    static = [
        line(r([-far, 0, 0, far, far, -far, -far]), r([far, far, 0, 0, -far, -far, far]), "smooth wall and floor",
             COLORS["ground"], width=1, fill="toself"),
        line(r(m["x_G"]), r(m["y_G"]), "path of G", COLORS["accent"], width=2, dash="dot"),
        line(*(row[k] for row in drawn["where the top leaves the wall"]), "where the top leaves the wall",
             COLORS["impulse"], width=2, dash="dash"),
    ]
    moving_traces = [
        moving(line(None, None, "ladder", COLORS["body"], width=1, fill="toself"), *drawn["ladder"]),
        moving(points(None, None, "G", COLORS["marker"], size=11, symbol="circle-x", show_legend=False), *drawn["G"]),
        moving(line(None, None, WALL_PUSH, COLORS["force"], width=4), *pushes[WALL_PUSH]),
        moving(line(None, None, FLOOR_PUSH, COLORS["velocity"], width=4), *pushes[FLOOR_PUSH]),
    ]
    force_scale = _force_scale(p)
    y_low = -max(float(np.max(at_frames[1])) * force_scale, band) - 0.05 * L
    x_low = -max(float(np.max(at_frames[0])) * force_scale, band) - 0.05 * L
    layout = base_layout(equal_axes=True, x_range=(x_low, x_far), y_range=(y_low, 1.18 * L))
    spec = animated(static, moving_traces, m["t"], layout, frame_ms=40)
    head = headline("Side view, wall on the left. Released at rest at θ₀ = ", ("theta0", "degn", 3), ", the ladder slides "
                    "down; G moves on a circle about the corner while the wall pushes (purple arrow, to scale with the "
                    "floor's green one).")
    description = (
        headline_text(head, {**p, **a}) + f" At t = {n(a['t_leave'])} s and θ = {n(np.degrees(a['theta_leave']))}° (dashed), with "
        f"the top at two-thirds of its initial height, the wall's push reaches zero and the top leaves the wall; "
        f"G then drifts away from it at a constant {n(a['vx_leave'])} m/s while the ladder falls, landing flat at "
        f"t = {n(a['t_floor'])} s turning at {n(a['omega_floor'])} rad/s.")
    return Figure("sliding_ladder_motion", "Sliding down, leaving the wall, landing flat", spec, description,
                  height=560, key_frame=k, key_caption="the top leaves the wall, at two-thirds of its initial height",
                  headline=head)


def _ends(th, x_G, y_G, L, xp=np):
    """The top A (on the wall's side) and the foot B of a ladder with centre G at angle θ from the floor."""
    c, s = xp.cos(th), xp.sin(th)
    return x_G - L / 2 * c, y_G + L / 2 * s, x_G + L / 2 * c, y_G - L / 2 * s


def _leaving(p, a, xp=np):
    """θ and G where the top leaves the wall: G still on its circle of radius L/2 about the corner."""
    th = a["theta_leave"]
    return th, p["L"] / 2 * xp.cos(th), p["L"] / 2 * xp.sin(th)


def _bodies(th, x_G, y_G, L, xp=np) -> dict:
    """The ladder (a strip THICKNESS × L wide on the side away from the corner, its edge through A and
    B the modelled rod), G, and the ladder's edge as a line, at angles θ and centres G (one per frame)."""
    x_A, y_A, x_B, y_B = _ends(th, x_G, y_G, L, xp)
    away_x, away_y = xp.sin(th) * THICKNESS * L, xp.cos(th) * THICKNESS * L  # away from the corner
    xs = np.stack([x_A, x_B, x_B + away_x, x_A + away_x, x_A], axis=1)
    ys = np.stack([y_A, y_B, y_B + away_y, y_A + away_y, y_A], axis=1)
    return {"ladder": (r(xs), r(ys)), "G": (column(x_G), column(y_G)),
            "where the top leaves the wall": (r(np.stack([x_A, x_B], axis=1)), r(np.stack([y_A, y_B], axis=1)))}


def key_pose(p, a, system: str = "si", xp=np) -> dict:
    """The stage figure at its key instant, the top leaving the wall: the ladder, G, the dashed line
    where it leaves and the two pushes there (the wall's zero, the floor's mg/4), each a (x, y) row
    (numpy for the figure, solvers.live's symbols for the browser's drag)."""
    th, x_G, y_G = (np.array([v]) for v in _leaving(p, a, xp))
    wall, floor = _pushes_leaving(p)
    drawn = {**_bodies(th, x_G, y_G, p["L"], xp), **_pushes(th, x_G, y_G, wall + 0 * th, floor + 0 * th, p, xp)}
    return {name: (x[0], y[0]) for name, (x, y) in drawn.items()}


WALL_PUSH, FLOOR_PUSH = "wall's push N<sub>A</sub>", "floor's push N<sub>B</sub>"  # (legend names: plotly's HTML)


def _force_scale(p):
    return 0.4 * p["L"] / (p["m"] * p["g"])  # the weight mg would be drawn 0.4 L long


def _pushes_leaving(p):
    """The wall's and the floor's push as the top leaves the wall: the wall's is zero (that is the
    instant), the floor's mg/4. G's height (L/2) sin θ falls with ÿ = −(3g/4) cos²θ − (L/2) sin θ θ̇²
    (θ̈ = −(3g/2L) cos θ, θ̇² = 3g (sin θ₀ − sin θ)/L), and at sin θ = (2/3) sin θ₀ the floor's push
    m (g + ÿ) is mg (1 − 3/4 + s₀²/3 − s₀²/3) = mg/4 whatever θ₀ (tests: the integration's, to 1e-9)."""
    return 0 * p["m"], p["m"] * p["g"] / 4


def _pushes(th, x_G, y_G, N_wall, N_floor, p, xp=np) -> dict:
    """The wall's push at the top A and the floor's at the foot B, to scale, at angles θ and centres
    G with these reactions (one per frame)."""
    scale = _force_scale(p)
    _, y_A, x_B, _ = _ends(th, x_G, y_G, p["L"], xp)
    return {WALL_PUSH: arrows(-N_wall * scale, y_A, N_wall * scale, 0.0, xp=xp),
            FLOOR_PUSH: arrows(x_B, -N_floor * scale, 0.0, N_floor * scale, xp=xp)}


def _reactions(solution, m) -> Figure:
    p, a = solution.params, solution.answers
    t, t_leave = m["curve_t"], m["t_leave"]
    top = float(max(np.max(m["N_floor"]), np.max(m["N_wall"]), p["m"] * p["g"])) * 1.08
    data = [
        line(r(t), r(m["N_wall"]), "wall, N<sub>A</sub>", COLORS["force"], width=3),
        line(r(t), r(m["N_floor"]), "floor, N<sub>B</sub>", COLORS["velocity"], width=3, dash="dash"),
        line(r([t_leave, t_leave]), r([0, top]), f"top leaves the wall, t = {n(t_leave)} s", COLORS["impulse"],
             width=2, dash="dot"),
        line(r([t[0], t[-1]]), r([p["m"] * p["g"]] * 2), "weight mg", COLORS["ink"], width=1, dash="longdash"),
    ]
    layout = base_layout(equal_axes=False, x_title="t (s)", y_title="reaction (N)", height=380)
    layout["margin"]["b"] = 60
    layout["yaxis"]["range"] = [0, top]
    low = float(np.min(m["N_floor"]))
    description = (
        f"The reactions against time. The wall pushes {n(a['N_wall0'])} N just after release, the floor "
        f"{n(a['N_floor0'])} N, less than the weight {n(p['m'] * p['g'])} N since G accelerates downward. The wall's "
        f"push falls to zero at t = {n(t_leave)} s and stays zero: the top has left. The floor never lets go "
        f"(its push stays at least {n(low)} N) until the ladder lands flat at t = {n(a['t_floor'])} s.")
    return Figure("sliding_ladder_reactions", "The wall's and the floor's reactions against time",
                  {"data": data, "layout": layout}, description, animated=False, height=380)


def sketch(params) -> Drawing:
    """The problem's sketch: the ladder released at θ₀ against the smooth wall, on the smooth floor."""
    L, th0 = params["L"], params["theta0"]
    s = Sketch(solver, "The ladder against a smooth wall, on a smooth floor")
    A, B = (0.0, L * np.sin(th0)), (L * np.cos(th0), 0.0)
    s.support((0.0, 0.0), (0.0, 1.15 * A[1]), side=1)
    s.support((0.0, 0.0), (1.2 * B[0], 0.0), side=-1)
    s.rod(B, A)
    s.point(A, "A", (1, 0.6))
    s.point(B, "B", (0.4, 1))
    s.point(((A[0] + B[0]) / 2, (A[1] + B[1]) / 2), "G", (-1, -0.8))
    s.angle(B, np.pi - th0, np.pi, "theta0", 0.2 * L)
    s.length(B, A, "L", -0.08 * L)
    return s.drawing()
