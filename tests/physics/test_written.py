"""The derivations written as a person writes the physics (solvers.derivation.latex): the weight reads m g,
as the free-body diagram labels it, not sympy's alphabetical g m; a product's masses first (m L², not L² m), a sum
inside it in sympy's order."""
from __future__ import annotations

import itertools
import re

import pytest
import sympy as sp

from solvers.catalog import PROBLEMS
from solvers.core import Choice, latex

m, g, m_s, L, N_A, theta, mu = sp.symbols("m g m_s L N_A theta mu")


@pytest.mark.parametrize("expr, written", [
    (-m * g, "- m g"),
    (N_A - g * m_s, "N_{A} - m_{s} g"),
    (3 * g * m / 4, r"\frac{3 m g}{4}"),
    (-g * m * L * sp.cos(theta) / 2, r"- \frac{m g L \cos{\left(\theta \right)}}{2}"),
    (mu * m * g, r"m g \mu"),
    (L**2 * m / 3, r"\frac{m L^{2}}{3}"),  # the masses first: m L², not L² m
    (3 * g * m * (3 * sp.sin(theta) - 2) / 4, r"\frac{3 m g \left(3 \sin{\left(\theta \right)} - 2\right)}{4}"),
    (g / L, r"\frac{g}{L}"),  # no mass: as sympy writes it
    (g * (m + m_s), r"g \left(m + m_{s}\right)"),
])
def test_the_weight_is_written_m_g(expr, written):
    assert latex(expr) == written


G_BEFORE_MASS = re.compile(r"(?<![A-Za-z\\])g\s*(?:\\cdot\s*)?m(?:_|\b)")


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_no_step_of_any_derivation_writes_g_before_a_mass(problem):
    choices = [p for p in problem.solver.PARAMS if isinstance(p, Choice)]
    for combination in itertools.product(*(c.options for c in choices)):
        solution = problem.solver.solve(**dict(zip((c.name for c in choices), combination)))
        for step in solution.steps:
            assert not G_BEFORE_MASS.search(step.latex), (problem.id, combination, step.title, step.latex)
