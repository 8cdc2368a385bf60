"""Top view: the ball slides in, strikes the stick, and the pair translates and turns."""
from __future__ import annotations

import numpy as np

from solvers import stick_ball as solver
from viz.common import (COLORS, Figure, animated, base_layout, circles, column, line, moving, padded, points, r,
                         segments, trails)


def figures(solution, system: str = "si") -> list[Figure]:
    p, a = solution.params, solution.answers
    m = solver.motion(solution)
    l_ = p["l"]
    ball_r = 0.04 * l_
    xs = np.concatenate([m["top"][0], m["bottom"][0], m["ball"][0]])
    ys = np.concatenate([m["top"][1], m["bottom"][1], m["ball"][1]])
    x_range, y_range = padded(xs.min() - ball_r, xs.max() + ball_r), padded(ys.min() - ball_r, ys.max() + ball_r)
    cm_path = line(r(m["cm"][0]), r(m["cm"][1]), "path of the combined CM (straight)", COLORS["velocity"],
                   width=2, dash="dash")
    moving_traces = [
        moving(line(None, None, "trail of the stick's end", COLORS["trail"], width=2, dash="dot"), *trails(*m["top"])),
        moving(line(None, None, "stick", COLORS["body"], width=7), *segments(*m["bottom"], *m["top"])),
        moving(line(None, None, "ball", COLORS["impulse"], width=2, fill="toself"), *circles(*m["ball"], ball_r, 24)),
        moving(points(None, None, "stick's midpoint", COLORS["ink"], size=7), column(m["mid"][0]), column(m["mid"][1])),
        moving(points(None, None, "combined CM", COLORS["marker"], size=12, symbol="circle-x"),
               column(m["cm"][0]), column(m["cm"][1])),
    ]
    layout = base_layout(equal_axes=True, x_range=x_range, y_range=y_range)
    spec = animated([cm_path], moving_traces, m["t"], layout)
    if p["mode"] == "stick":
        what = (f"the ball attaches; the pair moves on at {a['v_cm']:.3g} m/s and turns at {a['omega']:.3g} rad/s "
                f"about the combined centre of mass, which travels {a['distance_per_rev']:.3g} m per turn in a "
                "straight line")
    else:
        what = (f"the ball bounces off at {a['v_ball']:.3g} m/s while the stick moves off at {a['v_stick']:.3g} m/s "
                f"turning at {a['omega']:.3g} rad/s")
    description = (f"Top view. The ball slides at {p['v']:.3g} m/s into the resting stick {p['s']:.3g} m from its "
                   f"midpoint; {what}. Dotted: the trail of the stick's end.")
    return [Figure("stick_ball_motion", "Impact, then free motion (top view)", spec, description, height=520)]
