"""Live values while a lesson control is dragged: the page's part (the generated functions and what
they follow are solvers/live.py's; the browser's part is ui/plotly_component/live.js).

Mounted on the lesson page only (Study and Lecture), never in Practice, on a variant link or in an
assignment: it would give the answers away. A problem without ``LIVE`` gets nothing."""
from __future__ import annotations

import math

import orjson

from solvers import live
from solvers.core import Solution
from ui import figure
from ui.catalog import Problem
from ui.params import control_key
from viz.common import Figure, headline_text


def show(problem: Problem, solution: Solution, answers, system: str, stage: Figure | None = None) -> None:
    """``stage``: the figure on the stage, whose caption's headline follows too (viz.common.headline)."""
    if live.declared(problem.id) is None:
        return
    keys = {name: control_key(problem, system, name) for name in problem.primary}
    data = live.payload(problem.id, solution.params, answers, system, keys)
    # JSON has no infinity (μ = ∞ on the disk's page): sent as a word, read back by live.js
    data["params"] = {k: ("inf" if isinstance(v, float) and math.isinf(v) else v) for k, v in data["params"].items()}
    data["regime"] = solution.regime
    if stage is not None and stage.headline:
        data["headline"] = {"parts": stage.headline,
                            "text": headline_text(stage.headline, {**solution.params, **solution.answers})}
    figure.declared(figure.LIVE)(data=orjson.dumps(data), key="live")
