"""Reading the geometry of a figure as drawn (the rounded coordinates the browser gets), not from
the solvers' arrays, so a drawing that strays from the physics is caught too: the helpers each
problem's "what a student sees" tests use."""
from __future__ import annotations

import importlib
import json
import math

import numpy as np
from hypothesis import settings

from viz.common import unpacked

DRAWN = 2e-4  # coordinates are rounded to 4 decimals: a drawn gap may read this much short
EXAMPLES = settings(max_examples=25, deadline=None)


def figures(pid, **params):
    solution = importlib.import_module(f"solvers.{pid}").solve(**params)
    return solution, importlib.import_module(f"viz.{pid}").figures(solution)


def drawn(figure, name):
    """Per frame, the (x, y) points of the moving trace called ``name`` (NaN gaps dropped), rebuilt
    from the figure's JSON as the browser component rebuilds them (viz.common.unpacked)."""
    spec = json.loads(figure.json())
    anim = spec["animation"]
    index = next(i for i, j in enumerate(anim["traces"]) if spec["data"][j]["name"] == name)
    coords = unpacked(anim["coords"][index], len(anim["times"]))
    frames = []
    for xs, ys in zip(coords["x"], coords["y"]):
        xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
        keep = ~(np.isnan(xs) | np.isnan(ys))
        frames.append((xs[keep], ys[keep]))
    return frames


def static(figure, name):
    trace = next(t for t in figure.spec["data"] if t["name"] == name)
    return np.asarray(trace["x"], dtype=float), np.asarray(trace["y"], dtype=float)


def circle(xs, ys):
    """Centre and radius of a drawn circle (a closed polygon: the last point repeats the first)."""
    cx, cy = xs[:-1].mean(), ys[:-1].mean()
    return cx, cy, float(np.hypot(xs - cx, ys - cy).mean())


def distance_to_segment(px, py, ax, ay, bx, by) -> float:
    dx, dy = bx - ax, by - ay
    along = min(max(((px - ax) * dx + (py - ay) * dy) / (dx * dx + dy * dy), 0.0), 1.0)
    return math.hypot(px - ax - along * dx, py - ay - along * dy)


# ----------------------------------------------------------------------------------------------
# No two bodies overlap in any frame
