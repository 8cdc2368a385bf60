"""Euler's disk in 3-D, slowed down, with a marked radius; and ω_p, |ω| and the energy against the
tilt, showing the finite-time singularity as θ → 0."""
from __future__ import annotations

import math

import numpy as np

from solvers import eulers_disk as solver
from solvers.core import plain_fixed, plain_number as n
from viz.catalog import OnRequest
from viz.common import COLORS, Figure, animated, base_layout, line, moving, r, thumbnail
from viz.sketch import Drawing, Sketch

PLAY_SECONDS = 4.0  # one precession lasts this long on screen
MM = 1000.0  # the 3-D view is drawn in millimetres

THUMBNAIL = thumbnail(  # the home page's sketch (no physics)
    f'<ellipse cx="100" cy="88" rx="70" ry="14" fill="none" stroke="{COLORS["velocity"]}" stroke-width="2" stroke-dasharray="5 4"/>'
    f'<ellipse cx="100" cy="70" rx="62" ry="22" fill="{COLORS["body"]}33" stroke="{COLORS["body"]}" stroke-width="3" transform="rotate(-12 100 70)"/>'
    f'<line x1="100" y1="70" x2="150" y2="64" stroke="{COLORS["accent"]}" stroke-width="3"/>'
    f'<circle cx="42" cy="86" r="4" fill="{COLORS["impulse"]}"/>',
    "Euler's disk spinning on a table")


def figures(solution, system: str = "si") -> list[Figure]:
    return [_animation(solution), _versus_tilt(solution)]


def _scatter3d(xyz, name, color, width=6, mode="lines", size=6):
    xyz = np.asarray(xyz)
    trace = {"type": "scatter3d", "mode": mode, "x": r(xyz[:, 0]), "y": r(xyz[:, 1]), "z": r(xyz[:, 2]),
             "name": name, "hoverinfo": "skip"}
    if "lines" in mode:
        trace["line"] = {"color": color, "width": width}
    if "markers" in mode:
        trace["marker"] = {"color": color, "size": size}
    return trace


def _animation(solution) -> Figure:
    p, a = solution.params, solution.answers
    m = solver.motion(solution, rim_points=RIM_POINTS)
    rad = p["r"] * MM
    slow = PLAY_SECONDS / a["period"]
    table = _scatter3d(np.stack(_contact_path(p), axis=1), "path of the contact point", COLORS["trail"], width=4)
    G = _scatter3d([np.asarray(m["G"]) * MM], "centre of mass G (at rest)", COLORS["ink"], mode="markers", size=5)
    def xyz(path):  # (frames, points, 3) -> one (frames, points) array per coordinate
        path = r(np.asarray(path) * MM)
        return [np.ascontiguousarray(path[..., k]) for k in range(3)]

    moving_traces = [
        moving(_scatter3d(np.zeros((1, 3)), "disk rim", COLORS["body"], width=8), *xyz(m["rim"])),
        moving(_scatter3d(np.zeros((1, 3)), "marked radius", COLORS["accent"], width=10), *xyz(m["mark"])),
        moving(_scatter3d(np.zeros((1, 3)), "contact point", COLORS["impulse"], mode="markers", size=7),
               *xyz(m["contact"][:, None, :])),
    ]
    span = 1.05 * rad
    top = max(span, 1.05 * 2 * rad * math.sin(p["theta"]))  # the rim's highest point, 2r sin θ, inside the box
    tick = _nice_below(span / 2)  # three labels a side (−20, 0, 20), clear of the corners where two axes meet
    z_ticks = [tick * k for k in range(1, int(top / tick) + 1)]
    axis = lambda lo, hi, ticks: {"range": r([lo, hi]), "title": {"text": ""}, "tickvals": ticks}  # noqa: E731
    # plotly.js hides a 3-D annotation outside its axes' ranges, and scales those ranges with a round-off
    # (210 became 209.99999999999997 at r = 0.2: "y (mm)" and "z (mm)" vanished): the titles are anchored a
    # ten-thousandth of the box inside its edges.
    inset = 1e-4 * span
    edge = span - inset
    layout = {
        "height": 560, "margin": {"l": 0, "r": 0, "t": 10, "b": 90},
        "legend": {"orientation": "h", "y": 1.0, "x": 0},
        # In mm, with short tick labels ("20", not "0.02"), a few ticks a side, and an orthographic
        # camera (no perspective: the near corner's labels are no larger than the far ones') close
        # enough that the disk fills the scene, aimed a little left of centre. The axis titles are the scene's annotations, not WebGL's
        # titles, which a phone cut off at the graph's edge ("z (mm)" gone, "y (mm" cut): each is
        # anchored at its axis (x and y at the middle of the edge that carries their ticks, beyond
        # the tick labels; z above its top), text the page lays out and keeps inside the graph.
        "scene": {"xaxis": axis(-span, span, [-tick, 0, tick]), "yaxis": axis(-span, span, [-tick, 0, tick]),
                  "zaxis": axis(0, top, z_ticks), "aspectmode": "manual",  # one scale on all three axes
                  "aspectratio": _box(1.1 * top / (2 * span)), "camera": CAMERA,
                  "annotations": [
                      {"x": 0, "y": r(-edge), "z": r(inset), "text": "x (mm)", "showarrow": False, "xshift": -40, "yshift": -42},
                      {"x": r(edge), "y": 0, "z": r(inset), "text": "y (mm)", "showarrow": False, "xshift": 40, "yshift": -42},
                      {"x": r(-edge), "y": r(-edge), "z": r(top - inset), "text": "z (mm)", "showarrow": False,
                       "xanchor": "left", "yanchor": "bottom", "xshift": 4}]},
    }
    # 3-D traces need redraw; the frame duration sets the slow motion.
    frame_ms = round(1000 * PLAY_SECONDS / (len(m["t"]) - 1))  # from the first frame to the last
    spec = animated([table, G], moving_traces, m["t"], layout, frame_ms=frame_ms, redraw=True)
    turn = math.degrees(solution.extras["turn_per_precession"])
    # The disk turns 360°(1 − cos θ) a precession (solvers.eulers_disk): little at a small tilt, most
    # of a turn near upright, where "barely turns" would be false.
    turned = (f"only {turn:.1f}° relative to the table: the contact whirls, the disk itself barely turns"
              if turn < 90 else f"{turn:.1f}° relative to the table: at this tilt the disk turns with it, "
              "and the smaller the tilt, the less it turns")
    description = (f"Slowed down {slow:.0f}×: one precession takes {n(a['period'] * 1000, 3)} ms in reality and "
                   f"{PLAY_SECONDS:.0f} s on screen. The contact point (red) runs once round its circle while "
                   f"the marked radius turns {turned}.")
    return Figure("eulers_disk_motion", f"One precession, slowed down {slow:.0f}×", spec, description,
                  height=560, extra={"slow_motion": slow},
                  key_caption="the steady precession: every instant looks alike, turned about the vertical")


def _box(height: float) -> dict:
    """The scene box's aspect ratio for a box 1.1 wide and ``height`` tall (one scale on all three
    axes), as large as a box 0.55 tall draws, and smaller as a taller box (a disk tilted past about
    32°) stands taller on screen from the camera: by that factor to the power 0.75, so the box and its
    labels fit a projector's first screen while the disk still fills half the scene (tests/browser/test_stage.py).
    An orthographic camera's size is the box's aspect ratio, not the eye's distance."""
    elevation = math.atan2(CAMERA["eye"]["z"], math.hypot(CAMERA["eye"]["x"], CAMERA["eye"]["y"]))
    depth = 1.1 * math.sqrt(2) * math.sin(elevation)  # the floor's diagonal on screen
    taller = (height * math.cos(elevation) + depth) / (0.55 * math.cos(elevation) + depth)
    shrink = taller ** 0.75
    return {"x": r(1.1 / shrink), "y": r(1.1 / shrink), "z": r(height / shrink)}


# Aimed a little left of centre; orthographic (no perspective: the near corner's labels are no larger
# than the far ones').
CAMERA = {"eye": {"x": 0.95, "y": -0.95, "z": 0.62}, "center": {"x": -0.04, "y": -0.04, "z": -0.05},
          "projection": {"type": "orthographic"}}


RIM_POINTS = 36  # the rim drawn as a polygon of this many points (the last the first again)


def _contact_path(p, xp=np):
    """The contact point's circle on the table (mm): radius r cos θ about the origin."""
    angles = np.linspace(0, 2 * np.pi, 60)
    radius = p["r"] * MM * xp.cos(p["theta"])
    return radius * np.cos(angles), radius * np.sin(angles), 0 * radius * angles


def key_pose(p, a, system: str = "si", xp=np) -> dict:
    """The stage figure at its key instant, its first frame (t = 0: every instant of the steady
    precession looks alike, turned about the vertical): the disk tilted θ from the table (attitude
    Rx(θ), before any precession or spin: solvers.eulers_disk.orientations at t = 0), its marked radius
    along body x, the contact point at the rim's lowest point, G at height r sin θ and the contact's
    circle, in mm, each an (x, y, z) row: numpy for the figure, solvers.live's symbols for the drag."""
    r_, c, s = p["r"] * MM, xp.cos(p["theta"]), xp.sin(p["theta"])
    angles = np.linspace(0.0, 2 * np.pi, RIM_POINTS)
    height = r_ * s  # G above the origin
    rim = (r_ * np.cos(angles), r_ * np.sin(angles) * c, r_ * np.sin(angles) * s + height)
    drawn = {"disk rim": rim, "marked radius": (np.array([0 * r_, r_]), np.array([0 * r_, 0 * r_]), np.array([height, height])),
            "contact point": (np.array([0 * r_]), np.array([-r_ * c]), np.array([height - r_ * s])),
            "centre of mass G (at rest)": (np.array([0 * r_]), np.array([0 * r_]), np.array([height])),
            "path of the contact point": _contact_path(p, xp)}
    return {name: tuple(r(np.asarray(v)) for v in xyz) for name, xyz in drawn.items()}  # rounded as drawn


def _versus_tilt(solution) -> Figure:
    p = dict(solution.params)
    tilts = np.radians(np.linspace(0.5, 60, 120))
    curves = solver.versus_tilt(p, tilts)
    deg = np.degrees(tilts)
    data = [
        line(r(deg), r(curves["omega_p"]), "ω<sub>p</sub>, precession of the contact (rad/s)", COLORS["impulse"], width=3),
        line(r(deg), r(curves["omega_total"]), "|ω|, the disk's own rotation (rad/s)", COLORS["body"], width=3,
             dash="dash"),
        line(r(deg), r(curves["energy"] * 1000), "energy (mJ)", COLORS["velocity"], width=3, dash="dot",
             xaxis="x2", yaxis="y2"),
        {"type": "scatter", "mode": "markers", "x": r([math.degrees(p["theta"])]),
         "y": r([solution.answers["omega_p"]]), "name": "this tilt", "hoverinfo": "skip",
         "marker": {"color": COLORS["marker"], "size": 12, "line": {"width": 1, "color": "#222"}}},
    ]
    layout = base_layout(equal_axes=False, x_title="", y_title="rate (rad/s, log)", height=460)
    rates = np.concatenate([curves["omega_p"], curves["omega_total"]])
    layout["yaxis"].update({"type": "log", "domain": [0.42, 1.0], **_log_ticks(rates.min(), rates.max())})
    layout["xaxis"].update({"matches": "x2", "showticklabels": False})
    layout["xaxis2"] = {"anchor": "y2", "title": {"text": "tilt θ (°)"}}
    layout["yaxis2"] = {"anchor": "x2", "domain": [0.0, 0.32], "title": {"text": "energy (mJ)"}, "rangemode": "tozero"}
    layout["margin"]["b"] = 60
    layout["margin"]["r"] = 60
    description = ("As the tilt θ falls toward 0, the precession rate ω_p grows without bound while the disk's "
                   "own angular velocity and the energy (3/2 m g r sin θ) shrink to zero: Moffatt's "
                   f"finite-time singularity. Marked: this disk at θ = {math.degrees(p['theta']):.3g}°, "
                   f"where ω_p = {solution.answers['omega_p']:.3g} rad/s.")
    return Figure("eulers_disk_versus_tilt", "As θ → 0: the contact whirls faster, the disk turns slower",
                  {"data": data, "layout": layout}, description, animated=False, height=460)


def _nice_below(value: float) -> float:
    """The largest of 1, 1.5, 2, 2.5, 3, 4, 5, 6 or 8 times a power of ten that is at most ``value``."""
    power = 10.0 ** math.floor(math.log10(value))
    return max(m * power for m in (1, 1.5, 2, 2.5, 3, 4, 5, 6, 8) if m * power <= value * (1 + 1e-12))


def _log_ticks(lo: float, hi: float) -> dict:
    """Labels on a log axis at 1, 2 and 5 times each power of ten, all written out: plotly's own
    labels the minor ticks with a bare digit (5, 10, 2, 5, 100, 2), which reads as nonsense."""
    values = [m * 10.0**k for k in range(math.floor(math.log10(lo)), math.ceil(math.log10(hi)) + 1) for m in (1, 2, 5)]
    values = [v for v in values if lo <= v <= hi]
    return {"tickvals": values, "ticktext": [f"{v:g}" for v in values]}


def on_request(solution, damping: float = 5e-6) -> Figure:
    """Letting it run down: the full equations with a resisting torque −c ω (costly: on request)."""
    from solvers import eulers_disk_dynamics as dynamics

    d = dynamics.decay(dict(solution.params), damping, t_max=120.0)
    # Stacked over one time axis, not two y-axes overlaid: each gets ticks of its own.
    data = [
        line(r(d["t"]), r(np.degrees(d["tilt"])), "tilt θ (°)", COLORS["body"], width=3),
        line(r(d["t"]), r(d["precession"]), "precession rate ω<sub>p</sub> (rad/s)", COLORS["impulse"], width=3,
             xaxis="x2", yaxis="y2"),
    ]
    layout = base_layout(equal_axes=False, x_title="", y_title="tilt θ (°)", height=420)
    layout["yaxis"].update({"domain": [0.55, 1.0], "rangemode": "tozero"})
    layout["xaxis"].update({"matches": "x2", "showticklabels": False})
    layout["xaxis2"] = {"anchor": "y2", "title": {"text": "t (s)"}}
    layout["yaxis2"] = {"anchor": "x2", "domain": [0.0, 0.45], "title": {"text": "ω<sub>p</sub> (rad/s)"}}
    layout["margin"]["b"] = 60
    start, end = n(d["precession"][0], 3), n(d["precession"][-1], 3)
    if d["time_to_stop"] == 0:  # it starts where a run-down ends: the start alone, as points
        for trace in data:
            trace["mode"] = "markers"
        said = (f"it starts at {plain_fixed(math.degrees(d['tilt'][0]), 1)}°, at or below the 1° where a run-down "
                f"ends (the disk's clatter and stop): nothing is left to run down, ω_p = {start} rad/s.")
    else:
        ending = (f"the tilt reaches 1° after {n(d['time_to_stop'], 3)} s" if d["reached"] else
                  f"after {n(d['time_to_stop'], 3)} s the tilt is {plain_fixed(math.degrees(d['tilt'][-1]), 1)}°")
        grown = "grown" if d["precession"][-1] > d["precession"][0] else "fallen"  # (it falls at a steep tilt)
        said = f"energy drains and the disk settles; {ending}, with ω_p {grown} from {start} to {end} rad/s."
    description = (f"Kane's equations of the rolling disk integrated with a resisting torque −cω (c = {n(damping)} "
                   f"N·m·s): {said}")
    return Figure("eulers_disk_decay", "Letting it run down (full equations, with dissipation)",
                  {"data": data, "layout": layout}, description, animated=False, height=420)


# behind a switch of these words; ?rundown=1 keeps it open in a shared link
ON_REQUEST = OnRequest("Letting it run down", "rundown", on_request)


def sketch(params) -> Drawing:
    """The problem's sketch: the disk seen edge-on, tilted at θ from the table, touching it at A."""
    r_, th = params["r"], params["theta"]
    s = Sketch(solver, "Euler's disk, edge-on, rolling on the table")
    top = (2 * r_ * math.cos(th), 2 * r_ * math.sin(th))
    G = (top[0] / 2, top[1] / 2)
    s.support((-0.4 * r_, 0.0), (2.4 * r_, 0.0), side=-1)
    s.rod((0.0, 0.0), top, 14.0)
    s.point((0.0, 0.0), "A", (-1, 0.2))
    s.point(G, "G", (-0.3, 1), 18.0)
    s.angle((0.0, 0.0), 0.0, th, "theta", 1.2 * r_)
    s.length(G, top, "r", 0.2 * r_)
    return s.drawing(basis=(r"\mathbf{e}_y", r"\mathbf{E}_z"))
