"""What a screen reader hears about each figure (its text description) follows the parameters and
says the outcome: the numbers of this state's answers, not only the inputs. The states are the
per-student variants (realistic numbers a class meets); the range extremes of tests/strategies
are for the physics."""
from __future__ import annotations

import importlib
import math
import re

import pytest
from hypothesis import given, settings, strategies as st

from practice.variants import MAX_SEED, variant
from ui.catalog import PROBLEMS


def shown_forms(value: float) -> set[str]:
    """How a description may write an answer: 2 to 4 significant figures, in degrees for an angle,
    in ms for a short time."""
    forms = {f"{value:.2g}", f"{value:.3g}", f"{value:.4g}", f"{math.degrees(value):.1f}", f"{value * 1000:.0f}",
             f"{value * 1000:.3g}"}
    # A lone digit would match almost any text; a state whose answers are all zero (a disk that
    # stops dead) is the exception, and says "0".
    return {f for f in forms if len(f.lstrip("-")) > 1 or value == 0}


def states(description: str, value: float) -> bool:
    """The value stands in the text as a number of its own (not inside a longer one)."""
    description = description.replace("\u2212", "-")  # the pages write a typographic minus
    return any(re.search(rf"(?<![\d.]){re.escape(form)}(?![\d])", description) for form in shown_forms(value))


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
@settings(max_examples=8)
@given(seed=st.integers(0, MAX_SEED))
def test_every_figure_description_states_an_answer_of_this_state(problem, seed):
    try:
        solution = problem.solver.solve(**variant(problem.solver, problem.id, seed))
    except ValueError:
        return
    answers = [v for v in solution.answers.values() if isinstance(v, float) and math.isfinite(v)]
    answers = [0.0 if abs(v) < 1e-9 else v for v in answers]
    for figure in importlib.import_module(f"viz.{problem.id}").figures(solution, "si"):
        said = [v for v in answers if states(figure.description, v)]
        assert said, (figure.key, figure.description, solution.answers)


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_every_description_changes_when_the_state_does(problem):
    viz = importlib.import_module(f"viz.{problem.id}")
    first, second = (viz.figures(problem.solver.solve(**variant(problem.solver, problem.id, seed)), "si")
                     for seed in (1, 2))
    for a, b in zip(first, second):
        assert a.description != b.description, a.key
