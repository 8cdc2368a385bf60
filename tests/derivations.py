"""Checks on a derivation's steps, and on its free-body diagrams, that several problems' own tests share."""
from __future__ import annotations

import sympy as sp

from solvers import registry


def number(expr, values) -> float:
    """A declared expression's value at ``values`` (symbol -> number)."""
    return float(sp.sympify(expr).subs(values))


def declared_symbols(d) -> set:
    """Every symbol the diagram's points, loads and kinetic sides use."""
    exprs = []
    for body in d.bodies:
        exprs += [c for xy in body.points.values() for c in xy] + list(body.kinetic)
    for load in d.loads:
        exprs += [load.size, *(load.direction or ()), *load.components]
    return set().union(*(sp.sympify(x).free_symbols for x in exprs))


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
