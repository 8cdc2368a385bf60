"""Side view of the cart accelerating from rest, with the axle loads and the traction to scale, and
ẍ against μ for each drive with the lift-off limit μa = b."""
from __future__ import annotations

import numpy as np

from solvers import driven_cart as solver
from solvers.core import plain_number as n
from viz.common import (COLORS, Figure, headline, headline_text, animated, arrows, base_layout, circles, column, holding, joined, line, moving,
                         points, r, segments, thumbnail)
from viz.sketch import Drawing, Sketch

THUMBNAIL = thumbnail(  # the home page's sketch (no physics)
    f'<line x1="5" y1="96" x2="195" y2="96" stroke="{COLORS["ink"]}" stroke-width="4"/>'
    f'<rect x="35" y="44" width="130" height="34" rx="4" fill="{COLORS["body"]}33" stroke="{COLORS["body"]}" stroke-width="3"/>'
    f'<circle cx="60" cy="82" r="13" fill="white" stroke="#555" stroke-width="3"/>'
    f'<circle cx="140" cy="82" r="13" fill="white" stroke="#555" stroke-width="3"/>'
    f'<line x1="150" y1="60" x2="190" y2="60" stroke="{COLORS["impulse"]}" stroke-width="3" marker-end="url(#r)"/>',
    "A four-wheeled cart accelerating")


def figures(solution, system: str = "si") -> list[Figure]:
    return [_animation(solution), _versus_mu(solution)]


def _animation(solution) -> Figure:
    p, a = solution.params, solution.answers
    m = solver.motion(solution)
    b, h = p["b"], p["a"]
    wheel, body_top, force_scale, driven, traction_per_axle = _sizes(p, a)
    x_end = m["x"][-1]
    ground = line(r([min(-b, min(driven) - traction_per_axle * force_scale) - 1.5 * wheel, x_end + b + 1.5 * wheel]),
                  [0, 0], "ground", COLORS["ground"], width=4)
    drawn = _bodies(m["x"], p, a)
    moving_traces = [
        moving(line(None, None, "cart body", COLORS["body"], width=3, fill="toself"), *drawn["cart body"]),
        moving(line(None, None, "wheels", COLORS["ink"], width=3), *drawn["wheels"]),
        moving(line(None, None, "marked spokes", COLORS["accent"], width=3), *drawn["marked spokes"]),
        moving(points(None, None, "centre of mass", COLORS["marker"], size=12, symbol="circle-x"), *drawn["centre of mass"]),
        moving(line(None, None, "normal force per axle (2N)", COLORS["force"], width=4), *drawn["normal force per axle (2N)"]),
        moving(line(None, None, "traction at the driven wheels", COLORS["impulse"], width=4),
               *drawn["traction at the driven wheels"]),
    ]
    y_lo = -2 * max(a["N_rear"], a["N_front"]) * force_scale - 0.15 * b
    arrow_tail = min(xa for xa in driven) - traction_per_axle * force_scale  # the traction arrow's tail at rest
    x_range, y_range = holding((min(-b - 2 * wheel, arrow_tail - wheel), x_end + b + 2 * wheel), (y_lo, body_top * 1.4),
                               moving_traces)  # the arrowheads too (wider than a small wheel's margin)
    layout = base_layout(equal_axes=True, x_range=x_range, y_range=y_range, x_title="x (m)", y_title="height (m)")
    spec = animated([ground], moving_traces, m["t"], layout, frame_ms=70)
    head = headline("Side view, front to the right. From rest the cart accelerates at ", ("accel", "n", 4),
                    f" m/s² ({p['drive']}-wheel drive)")
    description = (headline_text(head, {**p, **a}) + f" for {n(m['t'][-1], 2)} s. Purple arrows: the ground's normal force on "
                   f"each axle, {n(2 * a['N_rear'])} N at the rear and {n(2 * a['N_front'])} N at the front, drawn to "
                   "scale below the ground line; red: the traction. Acceleration moves load to the rear.")
    return Figure("cart_motion", "Accelerating from rest (forces to scale)", spec, description, height=440,
                  key_frame=0, key_caption="at the start: the forces are the same at every instant", headline=head)


def _sizes(p, a, xp=np):
    """The wheels' radius, the body's top, the forces' scale, the driven axles and each one's traction."""
    b, h = p["b"], p["a"]
    wheel = xp.minimum(0.3 * b, 0.6 * h)
    body_top = xp.maximum(2 * h, 2.2 * wheel)  # the CM (height a) inside the body
    force_scale = 1.2 * xp.maximum(b, h) / (p["m"] * p["g"])  # mg would be drawn 1.2 b long (1.2 a, a tall cart's)
    driven = {"front": (b,), "rear": (-b,), "all": (-b, b)}[p["drive"]]
    return wheel, body_top, force_scale, driven, a["F_drive"] / len(driven)


def _bodies(x, p, a, xp=np) -> dict:
    """The cart with its centre at ``x`` (one per frame), its wheels rolling, and the forces on it to scale."""
    b, h = p["b"], p["a"]
    wheel, body_top, force_scale, driven, traction_per_axle = _sizes(p, a, xp)
    frames = len(x)
    one = np.ones(frames, dtype=x.dtype)
    spin = -x / wheel  # rolling: the wheels turn clockwise as the cart moves forward
    body_bottom = 0.9 * wheel
    corners = np.array([-b - wheel, b + wheel, b + wheel, -b - wheel, -b - wheel])
    body = (r(x[:, None] + corners), r(np.tile(np.array([body_bottom, body_bottom, body_top, body_top, body_bottom]), (frames, 1))))
    wheels = joined(*(circles(x + xa, wheel * one, wheel, 28) for xa in (-b, b)))
    c, s = xp.cos(spin), xp.sin(spin)
    spokes = joined(*(segments(x + xa - wheel * c, wheel - wheel * s, x + xa + wheel * c, wheel + wheel * s) for xa in (-b, b)))
    normals = joined(*(arrows(x + xa, -2 * N * force_scale * one, 0.0, 2 * N * force_scale * one, xp=xp)
                       for xa, N in ((-b, a["N_rear"]), (b, a["N_front"]))))
    traction = joined(*(arrows(x + xa - traction_per_axle * force_scale, 0.0, traction_per_axle * force_scale * one, 0.0, xp=xp)
                        for xa in driven))
    return {"cart body": body, "wheels": wheels, "marked spokes": spokes, "centre of mass": (column(x), column(h * one)),
            "normal force per axle (2N)": normals, "traction at the driven wheels": traction}


def key_pose(p, a, system: str = "si", xp=np) -> dict:
    """The stage figure at its key instant, the start (x = 0: the forces are the same at every instant):
    the cart, its wheels and the wheel loads and traction to scale, each a (x, y) row (numpy for the
    figure, solvers.live's symbols for the browser's drag)."""
    x = np.zeros(1) if isinstance(p["b"], (int, float)) else np.zeros(1, dtype=object)
    drawn = _bodies(x, p, a, xp)
    return {name: (xs[0], ys[0]) for name, (xs, ys) in drawn.items()}


def _versus_mu(solution) -> Figure:
    return versus_mu(solution.params, solution.answers["accel"])


def versus_mu(params, accel: float | None = None) -> Figure:
    """ẍ against μ for the three drives, with this cart's point (``accel``, if it has one: a cart
    past the lift-off has none, and its μ is marked on the axis instead)."""
    p = dict(params)
    mu_lift = p["b"] / p["a"]
    mu_max = max(1.5 * mu_lift, 1.2 * p["mu"], 1.0)
    mus = np.linspace(0.0, mu_max, 121)
    curves = solver.acceleration_versus_mu(p, mus)
    names = {"front": "front-wheel drive", "rear": "rear-wheel drive", "all": "all-wheel drive"}
    colors = {"front": COLORS["body"], "rear": COLORS["impulse"], "all": COLORS["velocity"]}
    dashes = {"front": None, "rear": "dash", "all": "dot"}
    data = [line(r(mus), r(curves[d]), names[d], colors[d], width=3, dash=dashes[d]) for d in curves]
    top = float(np.nanmax([np.nanmax(c) for c in curves.values()]))
    data.append(line(r([mu_lift, mu_lift]), r([0, top * 1.05]), f"front wheels lift: μ = b/a = {n(mu_lift, 3)}",
                     COLORS["ink"], width=2, dash="longdash"))
    if accel is not None:
        data.append(points([p["mu"]], [accel], "this cart", COLORS["marker"], size=13))
    else:
        # a line across the plot at its μ, not a point: a mark at ẍ = 0 read as "no acceleration"
        data.append(line(r([p["mu"], p["mu"]]), r([0, top * 1.05]), f"this cart's μ = {n(p['mu'], 3)}: past the lift-off",
                         COLORS["force"], width=3, dash="dot"))
    layout = base_layout(equal_axes=False, x_title="friction coefficient μ", y_title="ẍ<sub>C</sub> (m/s²)", height=380)
    layout["margin"]["b"] = 60
    description = (f"Acceleration against μ for the three drives. Rear and all-wheel drive end at "
                   f"μ = b/a = {n(mu_lift, 3)}, where the front wheels lift (a wheelie); front drive never lifts "
                   "but gains less and less, since it unloads the very wheels that push. Marked: this cart, "
                   f"{names[p['drive']]} at μ = {n(p['mu'], 3)}, "
                   + (f"accelerating at {n(accel, 3)} m/s²." if accel is not None else "past the lift-off."))
    return Figure("cart_versus_mu", "ẍ against μ: which drive wins, and where the front lifts",
                  {"data": data, "layout": layout}, description, animated=False, height=380)


def at_limit(params, system: str = "si") -> list[Figure]:
    """Beside a refusal (the front wheels lift): the curves that show where, and why."""
    return [versus_mu(params)]


def sketch(params) -> Drawing:
    """The problem's sketch: the cart at rest on level ground, its centre of mass C a height a up,
    midway between the axles 2b apart (the driven ones as the drive option says)."""
    a, b = params["a"], params["b"]
    at, wheel = solver.cart_shape(a, b)
    s = Sketch(solver, f"The cart on level ground ({params['drive']}-wheel drive)")
    s.support((at["_1"][0] - 0.4 * b, 0.0), (at["_2"][0] + 0.4 * b, 0.0), side=-1)
    s.polygon([at[k] for k in ("_1", "_2", "_3", "_4")])
    s.disk(at["_front_hub"], wheel)
    s.disk(at["_rear_hub"], wheel)
    s.point(at["C"], "C", (-1, 1))
    s.point(at["F"], "F", (1, -1))
    s.point(at["R"], "R", (-1, -1))
    side = at["_1"][0] - 0.3 * b  # the height marked left of the body, level with C
    s.dashed(at["C"], (side - 0.1 * b, a))
    s.length((side, 0.0), (side, a), "a", 0.0)
    s.length((-b, -0.7 * a), (0.0, -0.7 * a), "b", 0.0)
    s.length((0.0, -0.7 * a), (b, -0.7 * a), "b", 0.0)
    return s.drawing()
