"""The derivations written as a person writes the physics (solvers.derivation.latex): the weight reads m g,
as the free-body diagram labels it, not sympy's alphabetical g m; a product's masses first (m L², not L² m), a sum
inside it in sympy's order; a subscript that is a word or its abbreviation set upright (N_front, v_cm), as a
product of italic letters it would read as one (indices such as N_iz or v_Gx stay italic)."""
from __future__ import annotations

import itertools
import re

import pytest
import sympy as sp

from solvers.catalog import PROBLEMS
from solvers.core import Choice, latex

m, g, m_s, L, N_A, theta, mu, a, b = sp.symbols("m g m_s L N_A theta mu a b")


@pytest.mark.parametrize("expr, written", [
    (-m * g, "- m g"),
    (N_A - g * m_s, "N_{A} - m_{s} g"),
    (3 * g * m / 4, r"\frac{3 m g}{4}"),
    (-g * m * L * sp.cos(theta) / 2, r"- \frac{m g L \cos{\left(\theta \right)}}{2}"),
    (mu * m * g, r"\mu m g"),  # friction's coefficient first: μ m g, μ N
    (L**2 * m / 3, r"\frac{m L^{2}}{3}"),  # the masses first: m L², not L² m
    (3 * g * m * (3 * sp.sin(theta) - 2) / 4, r"\frac{3 m g \left(3 \sin{\left(\theta \right)} - 2\right)}{4}"),
    (g / L, r"\frac{g}{L}"),  # no mass: as sympy writes it
    (g * (m + m_s), r"g \left(m + m_{s}\right)"),
    (m_s * (sp.Symbol("s") - sp.Symbol("d")) ** 2, r"m_{s} \left(s - d\right)^{2}"),  # a difference: its positive term first
    (sp.sin(theta) - sp.sin(mu), r"\sin{\left(\theta \right)} - \sin{\left(\mu \right)}"),
    (-L - N_A, r"- L - N_{A}"),  # (nothing positive to put first)
    (sp.sqrt(2 * m / L), r"\sqrt{\frac{2 m}{L}}"),  # one root, not sympy's √2 √(m/L)
    (-sp.sqrt(3 * g * sp.sin(theta) / L), r"- \sqrt{\frac{3 g \sin{\left(\theta \right)}}{L}}"),
    (mu * sp.sqrt(L / g), r"\mu \sqrt{\frac{L}{g}}"),
    # a negative product's sign taken into its difference; a sum of negative terms written as a negated sum
    (-mu * g * b / (mu * a - 2 * b), r"\frac{\mu g b}{2 b - \mu a}"),
    (-m * g * (mu * a - b) / (4 * b), r"\frac{m g \left(b - \mu a\right)}{4 b}"),
    (g * (-m * L - 2 * m_s * (L + a)) / 2, r"- \frac{g \left(m L + 2 m_{s} \left(L + a\right)\right)}{2}"),
    ((mu * a - b) * (a - 2 * b), r"\left(a - 2 b\right) \left(\mu a - b\right)"),  # (positive: as it is)
    (g + L * (-a - b), r"g - L \left(a + b\right)"),  # a term that prints with a minus is subtracted: not g + − L (a + b)
    (sp.Mul(L, sp.Mul(-a - b, g, evaluate=False), evaluate=False), r"L \left(- g \left(a + b\right)\right)"),  # nor L − g (a + b)
    # a sum that would open with a minus: its positive terms first, in sympy's order
    (-a * L**2 + m * L**2 + 12 * m * b**2, r"m L^{2} + 12 m b^{2} - L^{2} a"),  # (sympy: −L² a + L² m + 12 b² m)
    (9 * sp.sin(theta)**2 - 6 * sp.sin(theta) * b + 1, r"9 \sin^{2}{\left(\theta \right)} + 1 - 6 b \sin{\left(\theta \right)}"),
    (m * L + 2 * g - m_s, r"m L + 2 g - m_{s}"),  # one that opens with a plus: as sympy writes it
])
def test_an_expression_is_written_as_a_person_writes_it(expr, written):
    assert latex(expr) == written


# a negative number put in as a whole term after a plus: 59.60 + (−24.67), where a person writes 59.60 − 24.67
PLUS_NEGATIVE = re.compile(r"\+ \\left\(-[\d.]+\\right\)(?!\^|\s*\\cdot)")


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_a_negative_number_put_in_after_a_plus_is_subtracted(problem):
    assert [t for t in _written(problem) if PLUS_NEGATIVE.search(t)] == []
    assert PLUS_NEGATIVE.search(r"T_{2} = 59.60 + \left(-24.67\right) = 34.92")
    assert not PLUS_NEGATIVE.search(r"1 + \left(-2\right)^{2} + \left(-2\right) \cdot 3")


G_BEFORE_MASS = re.compile(r"(?<![A-Za-z\\])g\s*(?:\\cdot\s*)?m(?:_|\b)")


def _solutions(problem):
    """The problem solved at its defaults for each combination of its options: (the combination, the solution)."""
    choices = [p for p in problem.solver.PARAMS if isinstance(p, Choice)]
    for combination in itertools.product(*(c.options for c in choices)):
        yield combination, problem.solver.solve(**dict(zip((c.name for c in choices), combination)))


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_no_step_of_any_derivation_writes_g_before_a_mass(problem):
    for combination, solution in _solutions(problem):
        for step in solution.steps:
            assert not G_BEFORE_MASS.search(step.latex), (problem.id, combination, step.title, step.latex)


# a word (three letters or more) or the centre of mass's abbreviation, as an italic subscript: N_{front}, v_{cm}
ITALIC_WORD = re.compile(r"_\{?(?:[a-z]{3,}|cm)\}?")


def _written(problem):
    """Every text of a problem's page in LaTeX, for each of its options: the steps and their titles, the answers'
    symbols, the checks' names, the worked solution's slips."""
    texts = [*problem.solver.ERRATA]
    for _, solution in _solutions(problem):
        texts += [t for step in solution.steps for t in (step.title, step.latex)]
        texts += [a.symbol for a in problem.answers_of(solution)] + [c.name for c in solution.checks]
    return texts


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_a_word_subscript_is_upright(problem):
    assert [t for t in _written(problem) if ITALIC_WORD.search(t)] == []


def test_an_italic_word_subscript_is_seen():
    assert ITALIC_WORD.search("N_2 = N_3 = N_{front}") and ITALIC_WORD.search("v_{cm} + \\omega")
    assert not ITALIC_WORD.search(r"N_\mathrm{front} = N_{\mathrm{rear}},\ N_{iz} = 0,\ v_{Gx}")


# two roots side by side in a product (sympy's √2 √(T₂/I_O), or with numbers √3 · √9.81 · …), or one over another
# (√3 √g / √L; with the numbers, … / √4)
TWO_ROOTS = re.compile(r"\\sqrt(?:\[[^\]]*\])?\{(?:[^{}]|\{(?:[^{}]|\{[^{}]*\})*\})*\}\s*(?:\\cdot\s*)?\\sqrt"
                       r"|\\frac\{[^{}]*\\sqrt(?:[^{}]|\{(?:[^{}]|\{[^{}]*\})*\})*\}\{\\sqrt")


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
def test_a_product_s_square_roots_stand_under_one_sign(problem):
    assert [t for t in _written(problem) if TWO_ROOTS.search(t)] == []
    assert TWO_ROOTS.search(r"\sqrt{2} \sqrt{\frac{T_{2}}{I_{O}}}") and TWO_ROOTS.search(r"\sqrt{3} \cdot \sqrt{9.81}")
    assert TWO_ROOTS.search(r"\sqrt{\frac{T_{2}}{I_{O}}} \sqrt{2}") and TWO_ROOTS.search(r"\frac{\sqrt{L}}{\sqrt{g}}")
    assert not TWO_ROOTS.search(r"\sqrt{\frac{2 T_{2}}{I_{O}}} = \frac{4}{\sqrt{9.81}}")


def test_roots_are_joined_only_where_that_keeps_the_value():
    """√a √b = √(ab) where a or b is not negative, 1/√b = √(1/b) where b is positive: else as sympy writes them."""
    Lp, gp = sp.symbols("L g", positive=True)
    x, y = sp.symbols("x y", real=True)
    assert latex(sp.sqrt(Lp / gp)) == r"\sqrt{\frac{L}{g}}"  # (sympy: √L / √g)
    assert latex(sp.sqrt(x) * sp.sqrt(y)) == r"\sqrt{x} \sqrt{y}"  # both may be negative: √x √y ≠ √(xy)
    assert latex(sp.sqrt(x) / sp.sqrt(Lp)) == r"\sqrt{\frac{x}{L}}"
    assert latex(sp.sqrt(Lp) / sp.sqrt(x)) == r"\frac{\sqrt{L}}{\sqrt{x}}"  # x may be negative: kept apart
