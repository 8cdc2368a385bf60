"""Figures as data: every animation has ≥ 30 frames, Play/Pause and a scrubbing slider, stays under
300 KB of JSON, is byte-identical for equal inputs, and viz/ holds no physics."""
from __future__ import annotations

import importlib
import json
from pathlib import Path

import pytest
from hypothesis import given, settings

import plotly.graph_objects as go

from solvers import registry
from tests import strategies
from viz.common import expanded

IDS = registry.PROBLEM_IDS
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


@pytest.mark.parametrize("pid", IDS)
def test_figures_of_the_defaults(pid):
    check_figures(build(pid))


@pytest.mark.parametrize("pid", IDS)
def test_equal_inputs_give_identical_figures(pid):
    assert [f.json() for f in build(pid)] == [f.json() for f in build(pid)]


@pytest.mark.parametrize("pid", IDS)
def test_viz_holds_no_physics(pid):
    source = (Path(__file__).resolve().parent.parent / "viz" / f"{pid}.py").read_text()
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
    params = data.draw(strategies.valid(pid))
    check_figures(build(pid, **params))

