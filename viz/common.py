"""Plain-data plotly figures: the animation frame (Play/Pause, a scrubbing slider with the time),
shapes (circles, arrows, springs) and a colour-blind-safe palette. No physics here: every number
drawn comes from a solver. Coordinates are rounded so equal inputs give byte-equal, small JSON.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Iterable, Sequence

import numpy as np
import orjson

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

    def json_bytes(self) -> bytes:
        """The figure as JSON, serialised once and kept (figures are shared between sessions)."""
        cached = self.__dict__.get("_json")
        if cached is None:
            cached = orjson.dumps(self.spec, option=orjson.OPT_SERIALIZE_NUMPY)
            object.__setattr__(self, "_json", cached)
        return cached

    def json(self) -> str:
        return self.json_bytes().decode()


def r(values) -> np.ndarray:
    """Round for JSON: arrays to DIGITS decimals; NaN (a gap in a polyline, or None given) is
    written as null by orjson."""
    return np.round(np.asarray(values, dtype=float), DIGITS)


_UNIT = {n: (np.cos(np.linspace(0, 2 * np.pi, n)), np.sin(np.linspace(0, 2 * np.pi, n))) for n in (24, 28, 32)}


def circle(cx: float, cy: float, radius: float, n: int = 32) -> tuple[np.ndarray, np.ndarray]:
    c, s = _UNIT[n]
    return r(cx + radius * c), r(cy + radius * s)


def circles(cx, cy, radius: float, n: int = 32) -> tuple[np.ndarray, np.ndarray]:
    """Circles of one radius at many centres (one row each), computed and rounded at once."""
    c, s = _UNIT[n]
    return r(np.asarray(cx)[:, None] + radius * c), r(np.asarray(cy)[:, None] + radius * s)


def _round(v: float | None):
    return None if v is None or not math.isfinite(v) else round(v, DIGITS)


def arrow(x0: float, y0: float, dx: float, dy: float, head: float | None = None) -> tuple[list, list]:
    """An arrow as one polyline: shaft, a gap, then a V-shaped head. Empty when too short."""
    length = math.hypot(dx, dy)
    if length < 1e-12:
        return [], []
    head = min(head or 0.25 * length, 0.45 * length)
    ux, uy = dx / length, dy / length
    x1, y1 = x0 + dx, y0 + dy
    wing = 0.5
    lx, ly = x1 - head * (ux - wing * uy), y1 - head * (uy + wing * ux)
    rx, ry = x1 - head * (ux + wing * uy), y1 - head * (uy - wing * ux)
    return [_round(v) for v in (x0, x1, None, lx, x1, rx)], [_round(v) for v in (y0, y1, None, ly, y1, ry)]


def join(*polylines: tuple[list, list]) -> tuple[list, list]:
    """Several polylines in one trace, separated by gaps."""
    xs, ys = [], []
    for x, y in polylines:
        if len(xs) and len(x):
            xs.append(None)
            ys.append(None)
        xs.extend(x)
        ys.extend(y)
    return xs, ys


def spirals(inner: float, outer: float, turns, start, n: int = 48) -> tuple[np.ndarray, np.ndarray]:
    """Flat spirals about the origin (a torsional spring), one row per frame: ``turns[i]`` turns
    from ``inner`` to ``outer`` radius, starting at angle ``start[i]``."""
    s = np.linspace(0.0, 1.0, n)[None, :]
    a = 2 * np.pi * np.maximum(np.asarray(turns, dtype=float), 0.05)[:, None] * s
    rad = inner + (outer - inner) * s
    phase = np.asarray(start, dtype=float)[:, None] + a
    return r(rad * np.cos(phase)), r(rad * np.sin(phase))


def line(x, y, name: str, color: str, width: float = 3, dash: str | None = None, show_legend: bool = True,
         fill: str | None = None, xaxis: str = "x", yaxis: str = "y") -> dict:
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
    return {"type": "scatter", "mode": "markers", "x": [_round(float(v)) for v in x],
            "y": [_round(float(v)) for v in y], "name": name,
            "marker": {"color": color, "size": size, "symbol": symbol, "line": {"width": 1, "color": "#222"}},
            "hoverinfo": "skip", "showlegend": show_legend, "xaxis": xaxis, "yaxis": yaxis}


def animated(
    static: Sequence[dict],
    frames: Sequence[Sequence[dict]],
    times: Iterable[float],
    layout: dict,
    frame_ms: int = 60,
    time_label: str = "t = ",
    time_unit: str = " s",
) -> dict:
    """A figure whose first len(static) traces never move and whose moving traces are given per
    frame. Frames carry only the moving traces (``traces`` indices) and animate with
    ``redraw: False``. Nothing plays by itself: Play starts the motion."""
    moving = list(range(len(static), len(static) + len(frames[0])))
    names = [str(i) for i in range(len(frames))]
    times = list(times)
    play = {"frame": {"duration": frame_ms, "redraw": False}, "fromcurrent": True,
            "transition": {"duration": 0}, "mode": "immediate"}
    pause = {"frame": {"duration": 0, "redraw": False}, "mode": "immediate", "transition": {"duration": 0}}
    layout = {
        **layout,
        "updatemenus": [{
            "type": "buttons", "direction": "left", "showactive": False, "x": 0.0, "y": -0.13,
            "xanchor": "left", "yanchor": "top", "pad": {"r": 8, "t": 8},
            "buttons": [{"label": "▶ Play", "method": "animate", "args": [None, play]},
                        {"label": "❚❚ Pause", "method": "animate", "args": [[None], pause]}],
        }],
        "sliders": [{
            "active": 0, "x": 0.22, "len": 0.78, "y": -0.1, "yanchor": "top", "pad": {"t": 30, "b": 0},
            "currentvalue": {"prefix": time_label, "suffix": time_unit, "visible": True, "xanchor": "right",
                             "font": {"size": 14, "color": "#888888"}},
            # Every step keeps its label for the readout, but the row of tick labels is hidden.
            "font": {"color": "rgba(0,0,0,0)", "size": 8}, "tickcolor": "rgba(136,136,136,0.5)", "ticklen": 3,
            "steps": [{"label": f"{t:.2f}", "method": "animate",
                       "args": [[name], pause]} for name, t in zip(names, times)],
        }],
    }
    return {
        "data": [*static, *frames[0]],
        "layout": layout,
        "frames": [{"name": name, "data": list(data), "traces": moving} for name, data in zip(names, frames)],
    }


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


def padded(lo: float, hi: float, pad: float = 0.08) -> tuple[float, float]:
    span = hi - lo or 1.0
    return lo - pad * span, hi + pad * span
