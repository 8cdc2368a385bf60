"""Figures as data: every animation has ≥ 30 frames, Play/Pause and a scrubbing slider, a key instant
for paper with its caption, stays under 300 KB of JSON, is byte-identical for equal inputs, and viz/
holds no physics."""
from __future__ import annotations

import importlib
import json
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings

import plotly.graph_objects as go

from solvers import registry
from tests import strategies
from viz.common import REBUILT, compacted, expanded, unpacked

IDS = registry.PROBLEM_IDS
# Imported here, not inside a @given test (hypothesis calls that nesting @given).
VALID = {pid: strategies.valid(pid) for pid in IDS}
LIMIT = 300 * 1024


def build(pid, **params):
    solution = importlib.import_module(f"solvers.{pid}").solve(**params)
    return importlib.import_module(f"viz.{pid}").figures(solution)


def check_figures(figures):
    assert figures
    animations = [f for f in figures if f.animated]
    assert animations, "each problem has an animation"
    for f in figures:
        text = f.json()
        assert len(text.encode()) < LIMIT, (f.key, len(text))
        assert f.description and len(f.description) > 40
        json.loads(text)  # plain JSON: no NaN, no numpy types
        assert "NaN" not in text
    for f in animations:
        anim = f.spec["animation"]  # compact: one row of coordinates per frame for each moving trace
        assert all(len(rows) == len(anim["times"]) for coords in anim["coords"] for rows in coords.values())
        assert len(anim["coords"]) == len(anim["traces"])
        # On paper the animation is its key instant (ui/plotly_component/figure.js), said in words.
        assert 0 <= f.key_frame < len(anim["times"]) and len(f.key_caption) > 10, (f.key, f.key_frame)
        sent = json.loads(f.json())["animation"]  # compacted: rebuilt, each row is the row drawn
        for coords, packed in zip(anim["coords"], sent["coords"]):
            rebuilt = unpacked(packed, len(anim["times"]))
            assert rebuilt.keys() == coords.keys()
            for k, rows in coords.items():
                for row, again in zip(rows, rebuilt[k], strict=True):
                    row, again = np.asarray(row, dtype=float), np.asarray(again, dtype=float)
                    assert (np.isnan(row) == np.isnan(again)).all()
                    assert np.nanmax(np.abs(row - again), initial=0.0) <= REBUILT, (f.key, k)
        spec = expanded(json.loads(f.json()))  # the plotly figure the browser component unfolds
        go.Figure(spec)  # plotly's own validation of every trace, frame and slider step
        assert len(spec["frames"]) >= 30
        labels = [b["label"] for b in spec["layout"]["updatemenus"][0]["buttons"]]
        assert any("Play" in x for x in labels) and any("Pause" in x for x in labels)
        steps = spec["layout"]["sliders"][0]["steps"]
        assert len(steps) == len(spec["frames"])
        assert spec["layout"]["sliders"][0]["currentvalue"]["prefix"].startswith("t")
        moving = spec["frames"][0]["traces"]
        assert all(fr["traces"] == moving for fr in spec["frames"])
        assert len(moving) < len(spec["data"]) + 1
        # nothing plays by itself: no autoplay, and the slider starts at the first frame
        assert spec["layout"]["sliders"][0]["active"] == 0
        assert not cut_by_the_axes(spec), (f.key, cut_by_the_axes(spec)[:3])


def cut_by_the_axes(spec) -> list:
    """The moving traces (bodies, arrows, paths) of a planar animation that reach past its axes'
    ranges in some frame: (frame, trace, how many points). Scenery (a wall, a floor: static lines that
    run off the plot by design) is not counted."""
    xa, ya = spec["layout"].get("xaxis", {}), spec["layout"].get("yaxis", {})
    if "scene" in spec["layout"] or "range" not in xa or "range" not in ya:
        return []
    (x0, x1), (y0, y1) = sorted(xa["range"]), sorted(ya["range"])
    slack = 1e-6 * max(x1 - x0, y1 - y0)
    cut = []
    for frame in spec["frames"]:
        for t, d in zip(frame["traces"], frame["data"]):
            trace = {**spec["data"][t], **d}
            if trace.get("xaxis", "x") != "x" or trace.get("yaxis", "y") != "y":
                continue
            x, y = (np.array([np.nan if v is None else v for v in trace[k]], dtype=float) for k in ("x", "y"))
            out = (x < x0 - slack) | (x > x1 + slack) | (y < y0 - slack) | (y > y1 + slack)
            if out.any():
                cut.append((frame["name"], trace.get("name"), int(out.sum())))
    return cut


@pytest.mark.parametrize("pid", IDS)
def test_figures_of_the_defaults(pid):
    check_figures(build(pid))


@pytest.mark.parametrize("pid", IDS)
def test_a_moving_marker_on_an_autoranged_plot_is_drawn_whole(pid):
    """Found in Chromium: the pendulum's "now" marker on θ(t) was cut in half at the plot's right edge
    in the last frame (plotly ranges that plot by what its first frame shows, and clips markers to it).
    A moving marker on axes without a set range (where ``cut_by_the_axes`` cannot hold it inside) is
    drawn unclipped."""
    for f in build(pid):
        if not f.animated:
            continue
        anim, data, layout = f.spec["animation"], f.spec["data"], f.spec["layout"]
        for j in anim["traces"]:
            trace = data[j]
            if "markers" not in trace.get("mode", "") or trace.get("type") == "scatter3d":  # a scene: its own box
                continue
            axes = [layout.get(f"{a}axis{trace.get(a + 'axis', a)[1:]}", {}) for a in ("x", "y")]
            if not all("range" in axis for axis in axes):
                assert trace.get("cliponaxis") is False, (pid, f.key, trace["name"])


@pytest.mark.parametrize("pid,params", [("disk_wall", {}), ("disk_wall", {"V": 10, "omega": -50}),
                                        ("driven_cart", {"a": 3, "b": 0.1}), ("driven_cart", {"a": 0.05, "b": 3})])
def test_no_arrow_or_body_runs_past_the_axes(pid, params):
    """Found in Chromium: disk_wall's velocity arrow ran through the plot's foot in its last frames,
    and the cart's arrowheads past its ends where a small wheel set the margin (a = 0.05 m, b = 3 m);
    a cart 6 m tall and 0.2 m long drew its wheel loads 0.1 m long. Every frame inside the axes, and
    the weight drawn at least 1.2 × the cart's larger dimension."""
    spec = expanded(json.loads(build(pid, **params)[0].json()))
    assert cut_by_the_axes(spec) == []
    if pid == "driven_cart":
        normals = next(t for t in spec["data"] if t["name"].startswith("normal force"))
        lengths = [abs(v) for v in normals["y"] if v is not None]
        assert max(lengths) >= 0.5 * 1.2 * max(params["a"], params["b"]), lengths  # the larger axle's 2N ≥ mg/2


@pytest.mark.parametrize("pid", IDS)
def test_equal_inputs_give_identical_figures(pid):
    assert [f.json() for f in build(pid)] == [f.json() for f in build(pid)]


@pytest.mark.parametrize("pid", IDS)
def test_viz_holds_no_physics(pid):
    source = (Path(__file__).resolve().parents[2] / "viz" / f"{pid}.py").read_text()
    for forbidden in ("import sympy", "import scipy", "solve_ivp", "streamlit"):
        assert forbidden not in source


@pytest.mark.parametrize("pid", IDS)
def test_shapes_stay_round_where_they_must(pid):
    """A planar animation draws x and y to one scale (a 3-D scene keeps its own aspect)."""
    for f in build(pid):
        if f.animated and "scene" not in f.spec["layout"]:
            assert f.spec["layout"]["yaxis"].get("scaleanchor") == "x", (pid, f.key)


@pytest.mark.parametrize("pid", IDS)
@settings(max_examples=8, deadline=None)
@given(data=strategies.st.data())
def test_figures_over_random_valid_parameters(pid, data):
    params = data.draw(VALID[pid])
    check_figures(build(pid, **params))



SENT = 32 * 1024


@pytest.mark.parametrize("pid", IDS)
def test_a_change_sends_the_motion_compacted(pid):
    """What every change sends (issue 13): rigid bodies as one map per frame, trails once, a spring
    as its turns; each page's animation at its defaults stays under SENT (it was 26–142 KB as rows)."""
    for f in build(pid):
        if f.animated:
            assert len(f.json_bytes()) <= SENT, (f.key, len(f.json_bytes()))


def test_compacting_keeps_what_is_not_rigid():
    """A positive control: rows that no affine map takes from the first (a circle whose radius
    grows, random points) are sent as they are; a translated and turned polygon is sent as maps."""
    from viz.common import circles, r

    t = np.linspace(0, 1, 40)
    rng = np.random.default_rng(7)
    turned = np.exp(1j * 3 * t)[:, None] * (rng.normal(size=9) + 1j * rng.normal(size=9))[None, :] + 2 * t[:, None]
    kept = {"x": r(rng.normal(size=(40, 9))), "y": r(rng.normal(size=(40, 9)))}
    growing_x, growing_y = circles(t, t, 1.0)
    growing = {"x": growing_x * (1 + t[:, None]), "y": growing_y}
    spec = {"data": [], "layout": {}, "animation": {"traces": [0, 1, 2], "times": list(t), "frame_ms": 60,
            "redraw": False, "coords": [kept, growing, {"x": r(turned.real), "y": r(turned.imag)}]}}
    packed = compacted(spec)["animation"]["coords"]
    assert packed[0] is kept and packed[1] is growing
    assert "affine" in packed[2]
    rebuilt = unpacked(packed[2], 40)
    assert np.abs(np.asarray(rebuilt["x"]) - turned.real).max() <= REBUILT


def test_the_stage_fits_every_kind_of_rows():
    """``fitted`` reads a moving trace's frames as one array where the rows have one length, row by
    row where they do not (issue 28): the ranges are those of every point, gaps left out, whichever
    way the rows come (a 2-D array, equal lists, ragged lists with None, a trail)."""
    from viz.common import fitted, line, moving, trails

    rng = np.random.default_rng(3)
    grid = rng.normal(size=(12, 5))
    ragged = [[float(v) for v in rng.normal(size=n)] + [None] for n in range(2, 14)]
    grid[-1, 2], ragged[-1][0] = 40.0, -60.0  # the extremes in the last frames, the ranges' ends
    path_x, path_y = trails(rng.normal(size=12) * 4, rng.normal(size=12) - 9)
    traces = [moving(line(None, None, "grid", "#000"), grid, grid * 2),
              moving(line(None, None, "equal", "#000"), [list(row) for row in grid + 5], [list(row) for row in grid]),
              moving(line(None, None, "ragged", "#000"), ragged, ragged),
              moving(line(None, None, "trail", "#000"), path_x, path_y),
              {"x": [7.5, None], "y": [0.0, -1.0]}]
    every = lambda axis: np.array([v for t in traces for row in (  # noqa: E731  the plain reference
        [t[axis]] if isinstance(t, dict) else [t.per_frame[axis].path] if hasattr(t.per_frame[axis], "path")
        else t.per_frame[axis]) for v in np.ravel(np.asarray(row, dtype=float))])
    x, y = every("x"), every("y")
    x_lo, x_hi, y_lo, y_hi = np.nanmin(x), np.nanmax(x), np.nanmin(y), np.nanmax(y)
    margin = 0.08 * max(x_hi - x_lo, y_hi - y_lo)
    assert fitted(traces) == ((x_lo - margin, x_hi + margin), (y_lo - margin, y_hi + margin))


def test_the_shared_pseudo_inverse_cannot_be_changed():
    """The compaction's pseudo-inverse is kept per first frame and shared between figures (issue 28):
    it is the same numbers as numpy's, and read-only, so no caller can spoil it for the next."""
    from viz.common import _pinv

    homogeneous = np.hstack([np.random.default_rng(5).normal(size=(7, 2)), np.ones((7, 1))])
    kept = _pinv(homogeneous.tobytes(), homogeneous.shape)
    assert np.array_equal(kept, np.linalg.pinv(homogeneous, rcond=1e-6))
    assert _pinv(homogeneous.tobytes(), homogeneous.shape) is kept
    with pytest.raises(ValueError):
        kept[0, 0] = 1.0
