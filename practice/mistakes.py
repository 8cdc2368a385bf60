"""The typical slips of a problem, as its solver module declares them (MISTAKES), that apply to a
solution's parameters. One definition serves typed numbers (evaluated at the student's parameters)
and typed expressions (compared as expressions)."""
from __future__ import annotations

from solvers import registry
from solvers.protocol import Mistake


def mistakes_for(problem: str, answer: str, params: dict) -> list[Mistake]:
    """The slips of ``problem`` for ``answer`` that give a distinct value at ``params``."""
    return [m for m in registry.solver(problem).MISTAKES if m.answer == answer and m.applies(params)]
