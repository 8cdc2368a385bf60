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
from solvers.catalog import PROBLEMS


def shown_forms(value: float) -> set[str]:
    """How a description may write an answer: 2 to 4 significant figures, in degrees for an angle,
    in ms for a short time."""
    forms = {f"{value:.2g}", f"{value:.3g}", f"{value:.4g}", f"{math.degrees(value):.1f}", f"{value * 1000:.0f}",
             f"{value * 1000:.3g}"}
    # A lone digit would match almost any text; the exceptions are a state whose answers are all
    # zero (a disk that stops dead, which says "0") and an answer that is a whole number to three or
    # four figures (a cart accelerating at 2.998 m/s² says "3" to three), where a digit is all a page
    # writes.
    whole = any(f"{value:.{figures}g}".lstrip("-").isdigit() for figures in (3, 4))
    return {f for f in forms if len(f.lstrip("-")) > 1 or value == 0 or whole}


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


def test_a_whole_number_answer_is_found_as_the_page_writes_it():
    """Found by hypothesis: cart variants 374330767 (ẍ = 3.000136 m/s², "3 m/s²" to four figures) and
    4637880 (ẍ = 2.998 m/s², "3 m/s²" to three, in the figure of ẍ against μ)."""
    assert states("the cart accelerates at 3 m/s² for 1.5 s", 3.000136283334735)
    assert states("Marked: this cart, front-wheel drive at μ = 0.695, accelerating at 3 m/s².", 2.9981813270344637)
    assert not states("the cart accelerates at 3 m/s² for 1.5 s", 3.0136)
