"""Side view of the rod and disk falling against the spring, with the energy split over time."""
from __future__ import annotations

import functools
import math

import numpy as np

from solvers import rod_disk_spring as solver
from solvers.core import plain_fixed, plain_number as n, validate_params
from viz.common import (COLORS, Figure, Posed, headline, headline_text, animated, animated_in_browser, base_layout, circles, fitted,
                         line, moving, points, r, segments, spirals, STILL_HEIGHT, still_layout, symbolic, thumbnail)
from viz.sketch import Drawing, Sketch

THUMBNAIL = thumbnail(  # the home page's sketch (no physics)
    f'<path d="M70,60 m-10,0 a10,10 0 1 0 20,0 a14,14 0 1 0 -28,0 a18,18 0 1 0 36,0" fill="none" stroke="{COLORS["force"]}" stroke-width="2"/>'
    f'<line x1="70" y1="60" x2="140" y2="30" stroke="#555" stroke-width="4"/>'
    f'<circle cx="154" cy="24" r="15" fill="{COLORS["body"]}33" stroke="{COLORS["body"]}" stroke-width="3"/>'
    f'<line x1="70" y1="60" x2="70" y2="6" stroke="{COLORS["ink"]}" stroke-width="1" stroke-dasharray="4 3"/>',
    "A rod and disk on a torsional spring")


def figures(solution, system: str = "si", in_browser: bool = False) -> list[Figure]:
    """The swing with its energy bars; ``in_browser``: its frames left to the browser, which integrates the
    swing (solvers.rod_disk_spring.INTEGRATED) and draws ``pose_at``, in the axes the server's frames fit."""
    p, a = solution.params, solution.answers
    m, at_theta2 = _with_theta2(solver.motion(solution), p["theta2"])
    head = headline("Side view, θ from the upward vertical. The assembly passes θ₂ = ", ("theta2", "deg", 0),
                    " (dashed) at ", ("omega2", "n", 4), " rad/s.")
    return [_swing(p, m, head, headline_text(head, {**p, **a}), at_theta2,
                   f"passing θ₂ = {deg(p['theta2'])}, where the speed is asked for", in_browser)]


def at_limit(params, system: str = "si") -> list[Figure]:
    """Beside the refusal where the spring stops the rod short of θ₂: the swing as it is, to its largest
    angle and back, with θ₂ dashed where it never gets. The motion does not depend on θ₂ (it only names
    the angle asked about), so it is the motion solved for an angle the rod does reach, halfway to its
    stop. Where it does not fall toward θ₂ at all (the spring wins at release), the assembly at θ₁."""
    return list(_at_limit(tuple(sorted(params.items()))))


@functools.lru_cache(maxsize=64)
def _at_limit(key: tuple) -> tuple[Figure, ...]:
    """``at_limit``'s figures, kept by the parameters (a refused drag asks again on every run)."""
    params = dict(key)
    p = validate_params(solver.PARAMS, params)
    stop = solver.largest_angle(p)
    if stop is None:
        return ()
    if not stop > p["theta1"]:
        return (_held(p),)
    reached = solver.solve(**{**params, "theta2": (p["theta1"] + stop) / 2})
    m = solver.motion(reached)
    turn = int(np.argmax(m["theta"]))
    said = (f"Side view, θ from the upward vertical. The spring stops the assembly at θ = {n(math.degrees(stop), 4)}°, "
            f"short of θ₂ = {deg(p['theta2'])} (dashed).")
    return (_swing(p, m, (), said, turn, f"at its largest angle, short of θ₂ = {deg(p['theta2'])}"),)


def _held(p) -> Figure:
    """The assembly at θ₁ where it never falls toward θ₂: upright, held by the spring against a nudge, or
    released where the spring's moment kθ already beats the weights' and pushes it back. A still
    picture, θ₂ dashed."""
    drawn = _bodies(np.array([p["theta1"]]), p)
    mark = drawn.pop("θ₂")
    traces = [line(*(row[0] for row in drawn.pop("torsional spring")), "torsional spring", COLORS["force"], width=2),
              line(*(row[0] for row in drawn["rod"]), "rod", COLORS["ink"], width=5),
              line(*(row[0] for row in drawn["disk"]), "disk", COLORS["body"], width=3, fill="toself"),
              line(*(row[0] for row in drawn["marked radius"]), "marked radius", COLORS["accent"], width=4),
              line(*(row[0] for row in mark), "θ₂", COLORS["ground"], width=1, dash="dash"),
              points([0], [0], "pivot O", COLORS["ink"], size=9, symbol="x")]
    x_range, y_range = fitted(traces)
    layout = still_layout(x_range, y_range)
    if p["theta1"] == 0:
        title, said = "Held upright by the spring", "the spring holds the assembly upright, even nudged: it never falls"
    else:
        title = f"Released at θ₁ = {deg(p['theta1'])}, pushed back by the spring"
        said = (f"released at θ₁ = {deg(p['theta1'])}, the spring's moment kθ already beats the weights': it swings "
                "back, never")
    description = f"Side view, θ from the upward vertical: {said} toward θ₂ = {deg(p['theta2'])} (dashed)."
    return Figure("rod_disk_spring_held", title, {"data": traces, "layout": layout}, description, animated=False,
                  height=STILL_HEIGHT)


def _swing(p, m, head, said: str, key_frame: int, key_caption: str, in_browser: bool = False) -> Figure:
    """The stage figure: the assembly swinging (``m``: solver.motion's frames) with θ₂ = ``p["theta2"]``
    dashed, above the energy bars; ``said``: its first sentence, ``head`` its parts a drag follows."""
    pivot = points([0], [0], "pivot O", COLORS["ink"], size=9, symbol="x")
    top = float(max((m["kinetic"] + m["gravity"] + m["spring"]).max(), 1e-9))
    theta = m["theta"]
    drawn = _bodies(theta, p)
    theta2_mark = line(*(row[0] for row in drawn.pop("θ₂")), "θ₂", COLORS["ground"], width=1, dash="dash")
    energy = r(np.stack([m["kinetic"], m["gravity"], m["spring"]], axis=1))
    bars = {"type": "bar", "x": ["kinetic", "gravity", "spring"],
            "marker": {"color": [COLORS["velocity"], COLORS["body"], COLORS["force"]]},
            "name": "energy (J)", "xaxis": "x2", "yaxis": "y2", "showlegend": False, "hoverinfo": "skip"}
    spring = [moving(line(None, None, "torsional spring", COLORS["force"], width=2),
                     *drawn["torsional spring"])] * (p["k"] > 0)
    moving_traces = [
        *spring,  # k = 0: there is no spring to draw
        moving(line(None, None, "rod", COLORS["ink"], width=5), *drawn["rod"]),
        moving(line(None, None, "disk", COLORS["body"], width=3, fill="toself"), *drawn["disk"]),
        moving(line(None, None, "marked radius", COLORS["accent"], width=4), *drawn["marked radius"]),
        moving(bars, y=energy),
    ]
    # The stage fits the motion (the pivot, the spring, the rod and the disk over every frame) and the θ₂ mark.
    x_range, y_range = fitted([pivot, theta2_mark, *moving_traces[:-1]])
    layout = base_layout(equal_axes=True, x_range=x_range, y_range=y_range)
    layout["yaxis"]["domain"] = [0.40, 1.0]  # room between for the x title and the ticks, in lecture type too
    layout["xaxis"]["title"]["standoff"] = 4  # under its own tick labels: the rod's, not the bars' below
    layout["xaxis2"] = {"anchor": "y2"}
    layout["yaxis2"] = {"anchor": "x2", "domain": [0.0, 0.22], "range": [0, top * 1.05],
                        "title": {"text": "energy (J)"}}
    layout["height"] = 700
    if in_browser:  # the same styles, posed by name (``pose_at``); the axes the frames above fit
        names = ["torsional spring"] * (p["k"] > 0) + ["rod", "disk", "marked radius"]
        posed = [Posed(t.style, name) for t, name in zip(moving_traces, names)] + [Posed(bars, "energy (J)", axes="y")]
        spec = animated_in_browser([pivot, theta2_mark], posed, layout, p, hold=None, frame_ms=50)
    else:
        spec = animated([pivot, theta2_mark], moving_traces, m["t"], layout, frame_ms=50)
    description = (f"{said} {_release(p, m)}, it falls, {_after(p, m)}. Bars: kinetic, gravitational (zero hanging "
                   "straight down) and spring energy; their sum stays constant. Drawn: the rod (grey) and the disk (blue, "
                   "its marked radius orange) turning on the torsional spring (pink) about the pivot O.")
    return Figure("rod_disk_spring_motion", "The fall and the swing back, with the energy", spec, description,
                  height=700, key_frame=key_frame, key_caption=key_caption, headline=head)


def _with_theta2(m: dict, theta2: float) -> tuple[dict, int]:
    """The frames with one at θ₂ itself, where the falling rod first passes it (the key instant: the
    pose the browser's generated code draws while a control is dragged), between the frames either
    side of it (its time and energies interpolated between theirs); and that frame's index."""
    theta = m["theta"]
    reached = theta >= theta2
    if not reached.any():
        return m, len(theta) - 1
    i = int(np.argmax(reached))
    if theta[i] == theta2 or i == 0:
        return {**m, "theta": np.where(np.arange(len(theta)) == i, theta2, theta)}, i
    w = (theta2 - theta[i - 1]) / (theta[i] - theta[i - 1])
    per_frame = [k for k, v in m.items() if isinstance(v, np.ndarray) and v.shape == theta.shape]
    out = {**m, **{k: np.insert(m[k], i, m[k][i - 1] + w * (m[k][i] - m[k][i - 1])) for k in per_frame}}
    out["theta"][i] = theta2
    return out, i


def _bodies(theta, p, xp=np) -> dict:
    """The spring, the rod, the disk and its marked radius at angles ``theta`` (one per frame), and
    the dashed θ₂ mark."""
    L, R = p["L"], p["R"]
    reach = L + 2 * R
    coil = xp.minimum(0.16 * reach, 0.8 * L)  # the spring's outer radius: clear of the disk, which starts at L
    s, c = xp.sin(theta), xp.cos(theta)
    cx, cy = (L + R) * s, (L + R) * c
    spin = theta if p["disk"] == "welded" else 0 * theta  # a pinned disk keeps its orientation
    mark = 1.05 * reach * np.ones(1)
    return {"torsional spring": spirals(0.25 * coil, coil, 1.5 + theta / (2 * math.pi), math.pi / 2 - theta, xp=xp),
            "rod": segments(0.0, 0.0, L * s, L * c), "disk": circles(cx, cy, R),
            "marked radius": segments(cx, cy, cx + R * xp.sin(spin), cy + R * xp.cos(spin)),
            "θ₂": segments(0.0, 0.0, mark * xp.sin(p["theta2"]), mark * xp.cos(p["theta2"]))}


def key_pose(p, a, system: str = "si", xp=np) -> dict:
    """The stage figure at its key instant, passing θ₂: the spring (if any), rod, disk, its marked radius
    and the θ₂ mark, each a (x, y) row (numpy for the figure, solvers.live's symbols for the drag)."""
    drawn = _bodies(np.array([p["theta2"]]), p, xp)
    x, y = drawn.pop("torsional spring")
    if symbolic(x):  # the browser's: drawn where k > 0 only, as the figure is
        drawn["torsional spring"] = tuple(xp.where(xp.less(-p["k"] + 0 * v, 0), v, np.nan) for v in (x, y))
    elif p["k"] > 0:
        drawn["torsional spring"] = (x, y)
    return {name: (x[0], y[0]) for name, (x, y) in drawn.items()}


def pose_at(p, a, t, system: str = "si", xp=np) -> dict:
    """The stage at time ``t``, its state (θ, θ̇) among ``a`` by the names solvers.rod_disk_spring.INTEGRATED
    gives: the spring (where k > 0), the rod, the disk and its marked radius, each a (x, y) row, and the
    energy bars' heights, kinetic, gravitational and spring, as one row (the bars' y): solvers.live's
    symbols for the browser's motion."""
    theta, omega = a["theta"], a["omega"]
    drawn = _bodies(np.array([theta], dtype=object if xp is not np else float), p, xp)
    del drawn["θ₂"]  # (drawn once, not moving)
    x, y = drawn.pop("torsional spring")
    drawn["torsional spring"] = tuple(xp.where(xp.less(-p["k"] + 0 * v, 0), v, np.nan) for v in (x, y))
    energy = [0.5 * a["I_O"] * omega**2, solver.weight_moment(p) * (1 + xp.cos(theta)), 0.5 * p["k"] * theta**2]
    return {**{name: (x[0], y[0]) for name, (x, y) in drawn.items()}, "energy (J)": (np.array(energy, dtype=object),)}


def deg(angle: float) -> str:
    return f"{plain_fixed(math.degrees(angle), 0)}°"


def _release(p, m) -> str:
    if p["theta1"] == 0:
        return (f"Released upright, an equilibrium, with a nudge of {n(solver.NUDGE)} rad/s, it creeps for "
                f"{n(m['start'], 2)} s before the motion is visible; the animation starts there. From there")
    return f"Released at θ₁ = {deg(p['theta1'])}"


def _after(p, m) -> str:
    if m["over_the_top"] and p["k"] == 0 and p["theta1"] < solver.NEAR_UPRIGHT:
        return ("and with no spring swings right round to upright again (360°), where the nudge carries it "
                "over the top: it keeps turning")
    if m["over_the_top"]:  # (a spring too soft to stop it sooner, or none from a hair off upright)
        return ("swings right round to within a degree of upright again, an equilibrium it creeps near for seconds: "
                "the animation ends there")
    stopper = "the spring stops it" if p["k"] > 0 else "it comes to rest (as high as it started)"
    return f"swings on until {stopper} at about {deg(m['theta'].max())}, and returns"


def sketch(params) -> Drawing:
    """The problem's sketch: the rod and disk released at θ₁ from the upward vertical, the torsional
    spring k at the pin, and (dashed) the angle θ₂ where the speed is wanted."""
    L, R, th1, th2 = params["L"], params["R"], params["theta1"], params["theta2"]
    s = Sketch(solver, "The rod and disk on a torsional spring, released about the pin O")
    along = lambda rho, th: (rho * math.sin(th), rho * math.cos(th))  # noqa: E731
    s.polygon([(0.0, 0.0), (-0.06 * L, -0.1 * L), (0.06 * L, -0.1 * L)])
    s.dashed((0.0, 0.0), (0.0, 0.6 * L))  # the upward vertical
    s.dashed((0.0, 0.0), along(L + 2 * R, th2))
    s.rod((0.0, 0.0), along(L, th1))
    s.disk(along(L + R, th1), R)
    s.point((0.0, 0.0), "O", (-1, -0.2), 34.0)
    s.spin((0.0, 0.0), 0.12 * L, True, "k")
    if th1 > math.radians(2):
        s.angle((0.0, 0.0), math.pi / 2 - th1, math.pi / 2, "theta1", 0.3 * L)
    s.angle((0.0, 0.0), math.pi / 2 - th2, math.pi / 2, "theta2", 0.45 * L)
    s.length((0.0, 0.0), along(L, th1), "L", -0.12 * L)
    s.length(along(L + R, th1), along(L + 2 * R, th1), "R", -0.12 * L)
    return s.drawing()
