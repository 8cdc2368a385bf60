"""Top view: the ball slides in, strikes the stick, and the pair translates and turns."""
from __future__ import annotations

import numpy as np

from solvers import stick_ball as solver
from solvers.core import plain_number as n
from viz.common import (COLORS, Figure, headline, headline_text, animated, base_layout, circles, column, line, moving, padded, points,
                         r, segments, thumbnail, trails)
from viz.sketch import Drawing, Sketch

THUMBNAIL = thumbnail(  # the home page's sketch (no physics)
    f'<line x1="120" y1="10" x2="120" y2="100" stroke="{COLORS["body"]}" stroke-width="7"/>'
    f'<circle cx="50" cy="22" r="8" fill="{COLORS["impulse"]}55" stroke="{COLORS["impulse"]}" stroke-width="2"/>'
    f'<line x1="62" y1="22" x2="100" y2="22" stroke="{COLORS["velocity"]}" stroke-width="3" marker-end="url(#g)"/>'
    f'<line x1="120" y1="78" x2="190" y2="78" stroke="{COLORS["velocity"]}" stroke-width="2" stroke-dasharray="6 4"/>',
    "A ball sliding toward the end of a stick")


def figures(solution, system: str = "si") -> list[Figure]:
    p, a = solution.params, solution.answers
    m = solver.motion(solution)
    ball_r = m["ball_radius"]
    xs = np.concatenate([m["top"][0], m["bottom"][0], m["ball"][0]])
    ys = np.concatenate([m["top"][1], m["bottom"][1], m["ball"][1]])
    x_range, y_range = padded(xs.min() - ball_r, xs.max() + ball_r), padded(ys.min() - ball_r, ys.max() + ball_r)
    cm_path = line(r(m["cm"][0]), r(m["cm"][1]), "path of the combined CM (straight)", COLORS["velocity"],
                   width=2, dash="dash")
    drawn = _bodies(m["bottom"], m["top"], m["ball"], m["mid"], m["cm"], ball_r)
    moving_traces = [
        moving(line(None, None, "trail of the stick's end", COLORS["trail"], width=2, dash="dot"), *trails(*m["top"])),
        moving(line(None, None, "stick", COLORS["body"], width=7), *drawn["stick"]),
        moving(line(None, None, "ball", COLORS["impulse"], width=2, fill="toself"), *drawn["ball"]),
        moving(points(None, None, "stick's midpoint", COLORS["ink"], size=7), *drawn["stick's midpoint"]),
        moving(points(None, None, "combined CM", COLORS["marker"], size=12, symbol="circle-x"), *drawn["combined CM"]),
    ]
    layout = base_layout(equal_axes=True, x_range=x_range, y_range=y_range)
    spec = animated([cm_path], moving_traces, m["t"], layout)
    head = headline("Top view. The ball slides at ", ("v", "n", 4), " m/s into the resting stick ", ("s", "n", 4),
                    " m from its midpoint")
    description = headline_text(head, {**p, **a}) + f"; {_after(p, a, m)}. Dotted: the trail of the stick's end."
    impact = int(np.argmin(np.abs(m["t"])))  # the impact is at t = 0
    return [Figure("stick_ball_motion", "Impact, then free motion (top view)", spec, description, height=520,
                   key_frame=impact, key_caption="the impact: the ball meets the stick", headline=head)]


def _bodies(bottom, top, ball, mid, cm, ball_r) -> dict:
    """The stick from its bottom to its top end, the ball (its centre), the stick's midpoint and the
    combined centre of mass, each an (x, y) pair with one value per frame."""
    return {"stick": segments(*bottom, *top), "ball": circles(*ball, ball_r, 24),
            "stick's midpoint": (column(mid[0]), column(mid[1])), "combined CM": (column(cm[0]), column(cm[1]))}


def key_pose(p, a, system: str = "si", xp=np) -> dict:
    """The stage figure at its key instant, the impact, in the motion's frame (solvers.stick_ball.motion:
    the stick along y at x = 0, its midpoint at the origin, the ball's front touching it at y = s; when
    the ball attaches, the combined centre of mass at d_cm along the stick), each a (x, y) row: numpy
    for the figure, solvers.live's symbols for the browser's drag. (After a bounce the combined centre
    is the model's mass average, not a live value: that marker waits, dimmed.)"""
    one = np.ones(1) if isinstance(p["l"], (int, float)) else np.ones(1, dtype=object)
    zero, rho = 0 * one, solver.BALL_RADIUS * p["l"]
    drawn = _bodies((zero, -p["l"] / 2 * one), (zero, p["l"] / 2 * one), (zero - rho, p["s"] * one), (zero, zero),
                    (zero, a["d_cm"] * one) if p["mode"] == "stick" else (zero, zero), rho)
    if p["mode"] != "stick":
        del drawn["combined CM"]
    return {name: (x[0], y[0]) for name, (x, y) in drawn.items()}


def _after(p, a, m) -> str:
    """What happens after the impact, in the words the motion bears out."""
    if p["mode"] == "stick":
        return (f"the ball attaches; the pair moves on at {n(a['v_cm'])} m/s and turns at {n(a['omega'])} rad/s "
                f"about the combined centre of mass, which travels {n(a['distance_per_rev'])} m per turn in a "
                "straight line")
    v_ball = a["v_ball"]
    if abs(v_ball) < 1e-9 * p["v"]:
        ball = "the ball stops dead"
    elif v_ball < 0:
        ball = f"the ball bounces back at {n(-v_ball)} m/s"
    else:
        ball = f"the ball carries on forward at {n(v_ball)} m/s"
    what = f"{ball}, while the stick's centre moves off at {n(a['v_stick'])} m/s, turning at {n(a['omega'])} rad/s"
    if m["second_contact"] is not None:
        what += (f". At t = {n(m['second_contact'], 3)} s the turning stick reaches the ball again: a second "
                 "impact, which this page does not model, so the motion stops there")
    return what


def sketch(params) -> Drawing:
    """The problem's sketch: the stick at rest, the ball sliding into it at v, a distance s from its middle."""
    l, s_ = params["l"], params["s"]
    s = Sketch(solver, "The ball slides into a free stick on a smooth table")
    s.rod((0.0, -l / 2), (0.0, l / 2))
    s.point((0.0, 0.0), "M", (1, 0))
    ball = (-0.42 * l, s_)
    s.disk(ball, 0.06 * l)
    s.velocity((ball[0] + 0.07 * l, ball[1]), 0.0, 0.2 * l, "v")
    s.length((0.0, -l / 2), (0.0, l / 2), "l", -0.16 * l)
    s.length((0.0, 0.0), (0.0, s_), "s", 0.1 * l)
    return s.drawing()
