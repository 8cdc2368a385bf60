"""Side view of the ladder sliding down the wall and landing flat, with its reactions to scale, and
the wall's and the floor's reactions against time."""
from __future__ import annotations

import numpy as np

from solvers import sliding_ladder as solver
from solvers.core import plain_number as n
from viz.common import (COLORS, Figure, headline, headline_text, animated, arrows, base_layout, column, line, moving, points, r,
                         thumbnail)

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
    th = m["theta"]
    away = np.stack([np.sin(th), np.cos(th)], axis=1) * THICKNESS * L  # the strip's offset, away from the corner
    xs = np.stack([m["x_A"], m["x_B"], m["x_B"] + away[:, 0], m["x_A"] + away[:, 0], m["x_A"]], axis=1)
    ys = np.stack([m["y_A"], m["y_B"], m["y_B"] + away[:, 1], m["y_A"] + away[:, 1], m["y_A"]], axis=1)
    x_far = float(max(np.max(xs), L)) * 1.08
    band = 0.1 * L
    force_scale = 0.4 * L / (p["m"] * p["g"])  # the weight mg would be drawn 0.4 L long
    at_frames = np.interp(m["t"], m["curve_t"], m["N_wall"]), np.interp(m["t"], m["curve_t"], m["N_floor"])
    wall_arrow = arrows(-at_frames[0] * force_scale, m["y_A"], at_frames[0] * force_scale, 0.0)
    floor_arrow = arrows(m["x_B"], -at_frames[1] * force_scale, 0.0, at_frames[1] * force_scale)
    k = m["leave_frame"]
    far = 10 * x_far  # the wall and the floor run on beyond the view, however the equal axes widen it
    static = [
        line(r([-far, 0, 0, far, far, -far, -far]), r([far, far, 0, 0, -far, -far, far]), "smooth wall and floor",
             COLORS["ground"], width=1, fill="toself"),
        line(r(m["x_G"]), r(m["y_G"]), "path of G", COLORS["accent"], width=2, dash="dot"),
        line(r([m["x_A"][k], m["x_B"][k]]), r([m["y_A"][k], m["y_B"][k]]), "where the top leaves the wall",
             COLORS["impulse"], width=2, dash="dash"),
    ]
    moving_traces = [
        moving(line(None, None, "ladder", COLORS["body"], width=1, fill="toself"), r(xs), r(ys)),
        moving(points(None, None, "G", COLORS["marker"], size=11, symbol="circle-x", show_legend=False),
               column(m["x_G"]), column(m["y_G"])),
        moving(line(None, None, "wall's push N_A", COLORS["force"], width=4), *wall_arrow),
        moving(line(None, None, "floor's push N_B", COLORS["velocity"], width=4), *floor_arrow),
    ]
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


def _reactions(solution, m) -> Figure:
    p, a = solution.params, solution.answers
    t, t_leave = m["curve_t"], m["t_leave"]
    top = float(max(np.max(m["N_floor"]), np.max(m["N_wall"]), p["m"] * p["g"])) * 1.08
    data = [
        line(r(t), r(m["N_wall"]), "wall, N_A", COLORS["force"], width=3),
        line(r(t), r(m["N_floor"]), "floor, N_B", COLORS["velocity"], width=3, dash="dash"),
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
