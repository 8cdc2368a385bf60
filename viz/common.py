"""Plain-data plotly figures: the animation frame (Play/Pause, a scrubbing slider with the time),
shapes (circles, arrows, springs) and a colour-blind-safe palette. No physics here: every number
drawn comes from a solver. Coordinates are rounded so equal inputs give byte-equal, small JSON.
"""
from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field
from typing import Iterable, Sequence

import numpy as np
import orjson

from solvers.formatting import plain_fixed, plain_number

# Okabe & Ito's palette, distinguishable with every common colour-vision deficiency.
COLORS = {
    "body": "#0072B2", "accent": "#E69F00", "velocity": "#009E73", "impulse": "#D55E00",
    "force": "#CC79A7", "trail": "#56B4E9", "ground": "#9a9a9a", "marker": "#F0E442", "ink": "#8a8a8a",
}
DIGITS = 4


@dataclass(frozen=True)
class Figure:
    """A figure as data, with the short text description a screen reader gets."""

    key: str
    title: str
    spec: dict
    description: str
    animated: bool = True
    height: int = 520
    extra: dict = field(default_factory=dict)
    # The instant that matters (the impact, the top leaving the wall), drawn on paper instead of the
    # animation (ui/plotly_component/figure.js prints it, with this caption beneath).
    key_frame: int = 0
    key_caption: str = ""
    # The words the description starts with, as ``headline_text`` writes them (``headline`` below):
    # followed by the browser while a lesson control is dragged.
    headline: tuple = ()

    def json_bytes(self) -> bytes:
        """The figure as JSON, serialised once and kept (figures are shared between sessions); an
        animation's rows go in their compact form (``compacted``)."""
        cached = self.__dict__.get("_json")
        if cached is None:
            cached = orjson.dumps(compacted(self.spec), option=orjson.OPT_SERIALIZE_NUMPY)
            object.__setattr__(self, "_json", cached)
        return cached

    def json(self) -> str:
        return self.json_bytes().decode()


# A caption's headline: the words its description starts with, whose numbers the browser follows while a
# lesson control is dragged (ui/plotly_component/live.js). Literal text (this run's words, for its regime
# and options) and slots (name, kind, digits) for a parameter or an answer in SI: "n", plain_number to
# ``digits`` figures; "deg", an angle in degrees to ``digits`` decimals; "degn", in degrees to ``digits``
# figures. The browser fills the slots only while the dragged values stay in this run's regime.
def headline(*parts) -> tuple:
    return tuple(p if isinstance(p, str) else tuple(p) for p in parts)


def headline_text(parts: tuple, values) -> str:
    """The headline as the description writes it, with ``values`` (parameters and answers, SI)."""
    out = []
    for part in parts:
        if isinstance(part, str):
            out.append(part)
            continue
        name, kind, digits = part
        x = values[name]
        if kind == "n":
            out.append(plain_number(x, digits))
        elif kind == "deg":
            out.append(plain_fixed(math.degrees(x), digits) + "°")
        else:
            out.append(plain_number(math.degrees(x), digits) + "°")
    return "".join(out)


def _instants(times: Iterable[float]) -> np.ndarray:
    """An animation's frame times, to the microsecond: DIGITS decimals (0.1 ms) made stick and ball's
    36 frames between two impacts 1.3 ms apart into a few instants, repeated."""
    return np.asarray(list(times), dtype=float).round(6)


def r(values) -> np.ndarray:
    """Round for JSON: arrays to DIGITS decimals; NaN (a gap in a polyline, or None given) is
    written as null by orjson. An array of symbols (a pose being generated, ``key_pose``) stays as it is."""
    if symbolic(values):
        return values
    return np.asarray(values, dtype=float).round(DIGITS)


def symbolic(values) -> bool:
    """An array of expressions (dtype object): the shapes below drawing a pose for solvers.live to
    turn into the browser's code, not numbers."""
    return isinstance(values, np.ndarray) and values.dtype == object


def _array(values) -> np.ndarray:
    if symbolic(values):
        return values
    try:
        return np.asarray(values, dtype=float)
    except TypeError:  # an expression (a pose being generated)
        return np.asarray(values, dtype=object)


# Shapes for every frame at once: each returns (x, y) arrays with one row per frame, rounded, which
# orjson writes straight from numpy (a row of a C-ordered array is contiguous).

_UNIT = {n: (np.cos(np.linspace(0, 2 * np.pi, n)), np.sin(np.linspace(0, 2 * np.pi, n))) for n in (24, 28, 32)}


def circles(cx, cy, radius: float, n: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Circles of one radius at many centres (one row each)."""
    c, s = _UNIT[n]
    return r(_array(cx)[:, None] + radius * c), r(_array(cy)[:, None] + radius * s)


def column(values) -> np.ndarray:
    """One point per frame: an (n, 1) array."""
    return r(values).reshape(-1, 1)


def segments(x0, y0, x1, y1) -> tuple[np.ndarray, np.ndarray]:
    """A straight segment per frame from (x0, y0) to (x1, y1); scalars stand for every frame."""
    x0, x1, y0, y1 = np.broadcast_arrays(*(_array(v) for v in (x0, x1, y0, y1)))
    return r(np.stack([x0, x1], axis=1)), r(np.stack([y0, y1], axis=1))


def arrows(x0, y0, dx, dy, head: float | None = None, xp=np) -> tuple[np.ndarray, np.ndarray]:
    """An arrow per frame as one polyline: shaft, a gap, then a V-shaped head (a quarter of the
    length, at most 0.45 of it). A frame whose arrow has no length draws nothing. ``xp``: numpy, or
    solvers.live's namespace for expressions (a pose being generated)."""
    x0, y0, dx, dy = np.broadcast_arrays(*(np.atleast_1d(_array(v)) for v in (x0, y0, dx, dy)))
    length = xp.hypot(dx, dy)
    none = xp.less(length, 1e-12)
    h = xp.minimum(0.25 * length if head is None else head, 0.45 * length)
    with np.errstate(invalid="ignore", divide="ignore"):
        ux, uy = dx / length, dy / length
    x1, y1 = x0 + dx, y0 + dy
    wing = 0.5
    gap = np.full(x0.shape, np.nan, dtype=x0.dtype)
    xs = np.stack([x0, x1, gap, x1 - h * (ux - wing * uy), x1, x1 - h * (ux + wing * uy)], axis=1)
    ys = np.stack([y0, y1, gap, y1 - h * (uy + wing * ux), y1, y1 - h * (uy - wing * ux)], axis=1)
    return r(xp.where(none[:, None], np.nan, xs)), r(xp.where(none[:, None], np.nan, ys))


def joined(*polylines: tuple[np.ndarray, np.ndarray]) -> tuple[np.ndarray, np.ndarray]:
    """Several polylines per frame in one trace, separated by gaps."""
    gap = np.full((polylines[0][0].shape[0], 1), np.nan)
    xs, ys = [], []
    for x, y in polylines:
        if xs:
            xs.append(gap)
            ys.append(gap)
        xs.append(x)
        ys.append(y)
    return np.hstack(xs), np.hstack(ys)


def as_one(xs: np.ndarray, ys: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Many polylines (one per row) drawn as one trace, separated by gaps."""
    gap = np.full((xs.shape[0], 1), np.nan)
    return np.hstack([xs, gap]).ravel()[:-1], np.hstack([ys, gap]).ravel()[:-1]


class Spirals(list):
    """Rows of flat spirals (``spirals``, one per frame) that also know their few numbers, so a
    change sends those."""

    def __init__(self, rows: np.ndarray, shape_of: dict):
        super().__init__(rows)
        self.shape_of = shape_of


def spiral_rows(inner: float, outer: float, turns, start, n: int, xp=np) -> tuple[np.ndarray, np.ndarray]:
    """Flat spirals about the origin, one row per frame: ``turns[i]`` turns from ``inner`` to
    ``outer`` radius, starting at angle ``start[i]`` (unrounded; ui/plotly_component draws the same)."""
    s = np.linspace(0.0, 1.0, n)[None, :]
    phase = _array(start)[:, None] + 2 * np.pi * _array(turns)[:, None] * s
    rad = inner + (outer - inner) * s
    return rad * xp.cos(phase), rad * xp.sin(phase)


def spirals(inner: float, outer: float, turns, start, n: int = 48, xp=np) -> tuple[Spirals, Spirals]:
    """Flat spirals about the origin (a torsional spring), one row per frame (at least 0.05 turn),
    drawn from their turns and start rounded as sent."""
    turns, start = np.broadcast_arrays(xp.maximum(_array(turns), 0.05), _array(start))
    if symbolic(turns):  # a pose being generated: the same rows, as expressions
        return spiral_rows(inner, outer, xp.rounded(turns), xp.rounded(start), n, xp)
    shape_of = {"inner": float(inner), "outer": float(outer), "turns": r(turns), "start": r(start), "n": n}
    x, y = spiral_rows(inner, outer, shape_of["turns"], shape_of["start"], n)
    return Spirals(r(x), shape_of), Spirals(r(y), shape_of)


class Trail(list):
    """Rows that are slices of one path: row i is ``path[starts[i]: i + 1]``. A list of the rows
    (as every other moving coordinate), which also knows its path, so it is sent once."""

    def __init__(self, path: np.ndarray, starts: list[int]):
        super().__init__(path[a: i + 1] for i, a in enumerate(starts))
        self.path, self.starts = path, starts


def trails(x, y, keep: int | None = None) -> tuple[Trail, Trail]:
    """The path so far in every frame (the last ``keep`` points, if given): views of one array."""
    x, y = r(x), r(y)
    starts = [0] * len(x) if keep is None else [max(0, i - keep) for i in range(len(x))]
    return Trail(x, starts), Trail(y, starts)


def line(x, y, name: str, color: str, width: float = 3, dash: str | None = None, show_legend: bool = True,
         fill: str | None = None, xaxis: str = "x", yaxis: str = "y") -> dict:
    """A polyline's trace; ``x`` and ``y`` may be None for a moving trace (see ``moving``)."""
    trace = {"type": "scatter", "mode": "lines", "x": x, "y": y, "name": name,
             "line": {"color": color, "width": width}, "hoverinfo": "skip", "showlegend": show_legend,
             "xaxis": xaxis, "yaxis": yaxis}
    if dash:
        trace["line"]["dash"] = dash
    if fill:
        trace["fill"] = fill
        trace["fillcolor"] = color + "33"
    return trace


def points(x, y, name: str, color: str, size: float = 10, symbol: str = "circle", show_legend: bool = True,
           xaxis: str = "x", yaxis: str = "y") -> dict:
    return {"type": "scatter", "mode": "markers", "x": None if x is None else r(x),
            "y": None if y is None else r(y), "name": name,
            "marker": {"color": color, "size": size, "symbol": symbol, "line": {"width": 1, "color": "#222"}},
            "hoverinfo": "skip", "showlegend": show_legend, "xaxis": xaxis, "yaxis": yaxis}


@dataclass(frozen=True)
class Moving:
    """A trace that moves: its style, and for each coordinate (x, y, z) one row per frame."""

    style: dict
    per_frame: dict

    def first(self) -> dict:
        return {**self.style, **{k: v[0] for k, v in self.per_frame.items()}}


def moving(style: dict, x=None, y=None, z=None) -> Moving:
    per_frame = {k: v for k, v in (("x", x), ("y", y), ("z", z)) if v is not None}
    counts = {len(v) for v in per_frame.values()}
    assert len(counts) == 1, f"{style.get('name')}: coordinates with different frame counts {counts}"
    return Moving(style, per_frame)


def _with_time_slider(layout: dict, time_label: str, time_unit: str) -> dict:
    return {
        **layout,
        "sliders": [{
            "active": 0, "x": 0.0, "len": 1.0, "y": -0.1, "yanchor": "top", "pad": {"t": 30, "b": 0},
            "currentvalue": {"prefix": time_label, "suffix": time_unit, "visible": True, "xanchor": "right",
                             "font": {"size": 14, "color": "#888888"}},
            # Every step keeps its label for the readout, but the row of tick labels is hidden.
            "font": {"color": "rgba(0,0,0,0)", "size": 8}, "tickcolor": "rgba(136,136,136,0.5)", "ticklen": 3,
        }],
    }


def animated(
    static: Sequence[dict],
    traces: Sequence[Moving],
    times: Iterable[float],
    layout: dict,
    frame_ms: int = 60,
    time_label: str = "t = ",
    time_unit: str = " s",
    redraw: bool = False,
) -> dict:
    """A figure whose ``static`` traces never move and whose ``traces`` move, as compact data: the
    plotly figure's ``data`` and ``layout``, and an ``animation`` holding, per moving trace, one row
    of coordinates per frame. The browser component (ui/plotly_component) unfolds it into plotly
    frames (each carries only the moving traces' coordinates; plotly merges them into the traces'
    style) and the time slider's steps, as ``expanded`` does here: the server builds a few arrays,
    not a few hundred dicts per change. Nothing plays by itself: Play starts the motion."""
    return {
        "data": [*static, *(t.first() for t in traces)],
        "layout": _with_time_slider(layout, time_label, time_unit),
        "animation": {"traces": list(range(len(static), len(static) + len(traces))), "times": _instants(times),
                      "coords": [t.per_frame for t in traces], "frame_ms": frame_ms, "redraw": redraw},
    }


@dataclass(frozen=True)
class Posed:
    """A moving trace whose frames the browser computes: its style, and the name of its shape in the
    viz module's ``pose_at`` (generated for the browser by ui/live.py); with ``trail``, the path so far
    of the point of that name instead (as ``trails`` draws it)."""

    style: dict
    name: str
    trail: bool = False
    keep: int | None = None  # a trail's last points (``trails``' keep)
    axes: str = "xyz"  # what the pose's rows are, in order: x and y (and z in a 3-D scene); "y" for bars' heights


def animated_in_browser(static: Sequence[dict], traces: Sequence[Posed], layout: dict, params: dict,
                        hold: float | None = 0.03, frame_ms: int = 60, redraw: bool = False,
                        traced: Sequence[tuple[int, str]] = ()) -> dict:
    """An animation whose frames the browser computes (issue 51): the static traces, the moving ones'
    styles and the pose names they are drawn from, the parameters (SI) the browser's generated motion
    starts from, and ``hold``: the axes widened where the frames reach past them, as ``holding`` widens
    them here. The server sends no frame (``animated``'s ``coords`` and ``times`` are the browser's).
    ``traced``: static traces the browser draws from an integrated motion's dense instants, each (its index
    among ``static``, the pose's point drawn at each instant): a plot against time."""
    return {
        "data": [*static, *(t.style for t in traces)],
        "layout": _with_time_slider(layout, "t = ", " s"),
        "animation": {"traces": list(range(len(static), len(static) + len(traces))),
                      "posed": [[t.name, t.trail, t.keep, t.axes] for t in traces], "hold": hold,
                      **({"traced": [[index, name] for index, name in traced]} if traced else {}),
                      "params": {k: ("inf" if isinstance(v, float) and math.isinf(v) else v) for k, v in params.items()},
                      "frame_ms": frame_ms, "redraw": redraw},
    }


# What a change sends: an animation's rows, compacted. Most moving bodies are rigid (a disk's rim,
# a ladder, a cart's wheels): every frame's points are one affine map of the first frame's, so a
# frame is sent as its map (6 numbers in the plane, 12 in space) instead of every point; a trail is
# sent once as its path, with where each frame's slice starts; a spiral spring as its turns and start. The browser (ui/plotly_component:
# ``unpack``) and ``unpacked`` here rebuild the rows; a rigid body is sent as maps only when its rebuilt
# rows are within ``REBUILT`` of the rounded rows, else it goes as it is (a trail and a spring are drawn
# from the numbers they are sent as).
REBUILT = 1.2e-4  # a little more than one unit of the rounding (DIGITS)


@functools.lru_cache(maxsize=1024)
def _pinv(homogeneous: bytes, shape: tuple[int, int]) -> np.ndarray:
    """The pseudo-inverse of a first frame's points (homogeneous coordinates), kept by their bytes:
    a body's first frame is often the same for many states (a cart at rest, a disk before impact),
    and the decomposition is the largest part of a trace's compaction. Read-only: it is shared."""
    inverse = np.linalg.pinv(np.frombuffer(homogeneous).reshape(shape), rcond=1e-6)
    inverse.flags.writeable = False
    return inverse


def _affine(coords: dict):
    """{"affine": ...} for rows that one affine map per frame takes from the first frame, else None.
    Worked axis first (axis, frame, point): numpy's loops then run along the points, where a last
    axis of two or three made each operation a thousand loops of two (twice as slow in all)."""
    keys = list(coords)
    try:
        points = np.stack([np.asarray(coords[k], dtype=float) for k in keys])  # axis, frame, point
    except ValueError:  # ragged rows
        return None
    d = len(keys)
    if points.ndim != 3 or points.shape[2] <= d + 2:
        return None
    gaps = np.isnan(points)
    # the same gaps in every frame, and a gap in every coordinate of its point
    if not (gaps == gaps[:, :1]).all() or not (gaps[1:] == gaps[:1]).all():
        return None
    keep = ~gaps[0, 0]
    count = int(keep.sum())
    if count <= d + 1:  # too few points to be worth a map (or none at all)
        return None
    kept = points if count == len(keep) else points[:, :, keep]
    homogeneous = np.vstack([kept[:, 0], np.ones(count)])  # the first frame's points, (x, y, 1) as columns
    maps = np.matmul(kept, _pinv(homogeneous.T.tobytes(), (count, d + 1)).T)  # axis, frame, d + 1
    maps[:, :, :-1] = maps[:, :, :-1].round(9)
    maps[:, :, -1] = maps[:, :, -1].round(7)
    if not np.abs(np.matmul(maps, homogeneous) - kept).max() <= REBUILT:
        return None
    # sent per frame as (d + 1) rows of d: the linear part, then the offset
    return {"affine": {"keys": keys, "template": list(points[:, 0]),
                       "maps": np.ascontiguousarray(maps.transpose(1, 2, 0)).reshape(points.shape[1], -1)}}


def _compact(coords: dict) -> dict:
    rows = list(coords.values())
    if all(isinstance(t, Trail) for t in rows) and all(t.starts == rows[0].starts for t in rows):
        return {"slices": {"keys": list(coords), "paths": [t.path for t in rows], "starts": rows[0].starts}}
    if list(coords) == ["x", "y"] and all(isinstance(t, Spirals) and t.shape_of is rows[0].shape_of for t in rows):
        # ``spirals`` drew these rows from these numbers as ``unpacked`` rebuilds them (rounded after):
        # rebuilding them again here to compare cost more than the rest of the figure's compaction
        return {"spirals": rows[0].shape_of}
    return _affine(coords) or coords


def compacted(spec: dict) -> dict:
    """The figure as sent: an animation's rows compacted (``_compact``), everything else as it is."""
    if "animation" not in spec or "posed" in spec["animation"]:  # (frames computed in the browser: none here)
        return spec
    anim = spec["animation"]
    return {**spec, "animation": {**anim, "coords": [_compact(c) for c in anim["coords"]]}}


def unpacked(coords: dict, frames: int) -> dict:
    """The rows (key -> one row per frame) that a compacted trace stands for."""
    if "slices" in coords:
        s = coords["slices"]
        return {k: [path[a: i + 1] for i, a in enumerate(s["starts"])] for k, path in zip(s["keys"], s["paths"])}
    if "spirals" in coords:
        s = coords["spirals"]
        x, y = spiral_rows(s["inner"], s["outer"], s["turns"], s["start"], s["n"])
        return {"x": x.tolist(), "y": y.tolist()}
    if "affine" in coords:
        a = coords["affine"]
        template = np.array(a["template"], dtype=float).T  # point, axis (None: a gap)
        homogeneous = np.hstack([template, np.ones((len(template), 1))])
        maps = np.asarray(a["maps"], dtype=float).reshape(frames, template.shape[1] + 1, template.shape[1])
        rows = np.einsum("kj,fjd->fkd", homogeneous, maps)
        return {k: [[None if np.isnan(v) else float(v) for v in row] for row in rows[:, :, n]]
                for n, k in enumerate(a["keys"])}
    return coords


def expanded(spec: dict) -> dict:
    """The plain plotly figure a compact animation stands for: frames, the slider's steps and
    Play/Pause buttons, for plotly in Python and the tests. The browser component builds the same
    frames, and draws the time slider and the buttons in HTML above the graph instead (a plotly
    slider's steps are redrawn as SVG on every change)."""
    if "animation" not in spec:
        return spec
    anim = spec["animation"]
    step = {"frame": {"duration": 0, "redraw": anim["redraw"]}, "mode": "immediate", "transition": {"duration": 0}}
    play = {**step, "frame": {"duration": anim["frame_ms"], "redraw": anim["redraw"]}, "fromcurrent": True}
    names = [str(i) for i in range(len(anim["times"]))]
    slider = {**spec["layout"]["sliders"][0], "x": 0.22, "len": 0.78, "steps": [
        {"label": f"{t:.2f}", "method": "animate", "args": [[name], step]} for name, t in zip(names, anim["times"])]}
    buttons = {"type": "buttons", "direction": "left", "showactive": False, "x": 0.0, "y": -0.13,
               "xanchor": "left", "yanchor": "top", "pad": {"r": 8, "t": 8},
               "buttons": [{"label": "▶ Play", "method": "animate", "args": [None, play]},
                           {"label": "❚❚ Pause", "method": "animate", "args": [[None], step]}]}
    kinds = [spec["data"][j].get("type", "scatter") for j in anim["traces"]]
    coords = [unpacked(c, len(names)) for c in anim["coords"]]
    frames = [{"name": name, "traces": anim["traces"],
               "data": [{"type": kind, **{k: rows[i] for k, rows in rows_of.items()}}
                        for kind, rows_of in zip(kinds, coords)]}
              for i, name in enumerate(names)]
    return {"data": spec["data"], "layout": {**spec["layout"], "sliders": [slider], "updatemenus": [buttons]},
            "frames": frames}


def base_layout(title: str = "", equal_axes: bool = True, x_range=None, y_range=None, height: int = 520,
                x_title: str = "x (m)", y_title: str = "y (m)") -> dict:
    layout = {
        "height": height,
        "margin": {"l": 50, "r": 20, "t": 40 if title else 20, "b": 140},
        "legend": {"orientation": "h", "y": 1.02, "yanchor": "bottom", "x": 0},
        "xaxis": {"title": {"text": x_title}, "zeroline": False, "showgrid": True},
        "yaxis": {"title": {"text": y_title}, "zeroline": False, "showgrid": True},
        "hovermode": False,
        "dragmode": False,
    }
    if title:
        layout["title"] = {"text": title, "x": 0}
    if equal_axes:
        layout["yaxis"]["scaleanchor"] = "x"
        layout["yaxis"]["scaleratio"] = 1
    if x_range is not None:
        layout["xaxis"]["range"] = r(x_range)
    if y_range is not None:
        layout["yaxis"]["range"] = r(y_range)
    return layout


STILL_HEIGHT = 460  # px: a still picture (beside a refusal: the model's limit, a body that never moves)


def still_layout(x_range, y_range, **titles) -> dict:
    """Equal axes for a still picture, STILL_HEIGHT tall, with no time slider's room below its x axis."""
    layout = base_layout(equal_axes=True, x_range=x_range, y_range=y_range, height=STILL_HEIGHT, **titles)
    layout["margin"]["b"] = 60
    return layout


def holding(x_range, y_range, traces: Sequence[Moving | dict], pad: float = 0.03) -> tuple[tuple[float, float], tuple[float, float]]:
    """``x_range`` and ``y_range`` widened where ``traces`` (every frame of each) reach past them, by
    ``pad`` of the larger span beyond their farthest point: an arrow or a body is never cut by the axes."""
    (fx_lo, fx_hi), (fy_lo, fy_hi) = fitted(traces, pad)
    return (min(x_range[0], fx_lo), max(x_range[1], fx_hi)), (min(y_range[0], fy_lo), max(y_range[1], fy_hi))


def fitted(traces: Sequence[Moving | dict], pad: float = 0.08) -> tuple[tuple[float, float], tuple[float, float]]:
    """The x and y ranges that hold every point of ``traces`` (moving ones over all their frames,
    static ones as drawn), each widened by ``pad`` of the larger span: the stage fits the motion, so
    the bodies fill the plot (with equal axes plotly widens the roomier axis to keep the aspect)."""
    def flat(rows) -> np.ndarray:
        if isinstance(rows, Trail):
            return np.asarray(rows.path, dtype=float).ravel()
        try:  # every frame's row at once (rows of one length: all but a trail's)
            return np.asarray(rows, dtype=float).ravel()
        except ValueError:  # ragged rows
            return np.concatenate([np.ravel(np.asarray(row, dtype=float)) for row in rows])

    xs, ys = [], []
    for trace in traces:
        if isinstance(trace, Moving):
            xs.append(flat(trace.per_frame["x"]))
            ys.append(flat(trace.per_frame["y"]))
        else:
            xs.append(np.asarray(trace["x"], dtype=float).ravel())
            ys.append(np.asarray(trace["y"], dtype=float).ravel())
    x, y = np.concatenate(xs), np.concatenate(ys)
    (x_lo, x_hi), (y_lo, y_hi) = (np.nanmin(x), np.nanmax(x)), (np.nanmin(y), np.nanmax(y))
    margin = pad * max(x_hi - x_lo, y_hi - y_lo, 1e-9)
    return (float(x_lo - margin), float(x_hi + margin)), (float(y_lo - margin), float(y_hi + margin))


def padded(lo: float, hi: float, pad: float = 0.08) -> tuple[float, float]:
    span = hi - lo or 1.0
    return lo - pad * span, hi + pad * span


# --------------------------------------------------------------------------------------------
# The home page's thumbnails: a small static SVG sketch per problem (no physics), declared by each
# viz module as THUMBNAIL. Drawn on a 200 × 110 canvas in the palette above; two arrowheads are
# defined for ``marker-end``: url(#g) (velocity green) and url(#r) (impulse red).

THUMBNAIL_SIZE = (200, 110)


def _arrowhead(name: str, color: str) -> str:
    return (f'<marker id="{name}" markerWidth="6" markerHeight="6" refX="5" refY="3" orient="auto">'
            f'<path d="M0,0 L6,3 L0,6" fill="none" stroke="{color}" stroke-width="1.2"/></marker>')


def thumbnail(body: str, label: str) -> str:
    """A home-page sketch: ``body`` (SVG elements on the 200 × 110 canvas) in an ``<svg>`` with
    role="img" and ``label`` as its aria-label, the text a screen reader reads for the picture."""
    if not label.strip() or '"' in label:
        raise ValueError("a thumbnail needs a label in words, without double quotes")
    width, height = THUMBNAIL_SIZE
    return (f'<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 {width} {height}" width="{width}" '
            f'height="{height}" role="img" aria-label="{label}"><defs>'
            f'{_arrowhead("g", COLORS["velocity"])}{_arrowhead("r", COLORS["impulse"])}</defs>{body}</svg>')
