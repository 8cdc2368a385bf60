"""Checks on a derivation's steps that several problems' own tests share."""
from __future__ import annotations

from solvers import registry


def no_title_states_an_answer(solution) -> None:
    """No step's title gives an answer away (practice's method shows the titles): neither its symbol set
    equal to something nor its number."""
    from solvers.core import plain_number

    for step in solution.steps:
        flat = step.title.replace(" ", "")
        for answer in registry.solver(solution.problem).ANSWERS:
            assert answer.symbol.replace(" ", "") + "=" not in flat, (step.title, answer.name)
            value = solution.answers[answer.name]
            if abs(value) > 1e-9:
                assert plain_number(abs(value), 3) not in step.title, (step.title, answer.name)
