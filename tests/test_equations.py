"""Long display equations broken over rows (ui/equations.py), on every step of every problem.

The rows must say the same algebra: every symbol and number of the step, in the same order (a
fraction opened as 1/B · A puts its denominator first), and no row may end inside a group, which
KaTeX would refuse. Whether the rows really fit a phone is measured in the browser
(tests/test_browser.py: display equations against their boxes at 360 and 390 px).
"""
from __future__ import annotations

import re
from collections import Counter

import pytest
from hypothesis import given, settings, strategies as st

from tests import strategies
from ui.catalog import PROBLEMS
from ui.equations import PHONE_WIDTH_EM, broken, tokens, width

SCAFFOLD = {r"\begin", r"\end", "aligned", "&", r"\\", r"\quad", r"\small", r"\footnotesize", r"\scriptsize",
            r"\Bigl", r"\Bigr", r"\left", r"\right", r"\,", "{", "}", r"\qquad", r"\;", ","}  # layout only


def content(latex: str) -> Counter:
    """What the student reads: symbols, numbers, operators and brackets, without layout."""
    words = re.sub(r"\\begin\{aligned\}|\\end\{aligned\}", "", latex)
    return Counter(t for t in tokens(words) if t not in SCAFFOLD)


def rows(latex: str) -> list[str]:
    inner = latex.removeprefix(r"\begin{aligned}").removesuffix(r"\end{aligned}")
    return inner.split(r" \\ ")


def params_of(problem):
    strategy = getattr(strategies, problem.id, None)
    return strategy() if callable(strategy) and not isinstance(strategy, st.SearchStrategy) else strategy


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
@settings(max_examples=15)
@given(data=st.data())
def test_broken_steps_keep_the_algebra_and_close_every_group_on_its_row(problem, data):
    strategy = params_of(problem)
    params = data.draw(strategy) if strategy is not None else {}
    try:
        solution = problem.solver.solve(**params)
    except ValueError:
        return  # a refused case shows no derivation
    for step in solution.steps:
        shown = broken(step.latex)
        if shown == step.latex:
            assert width(tokens(shown)) <= PHONE_WIDTH_EM
            continue
        before, after = content(step.latex), content(shown)
        opened = shown.count(r"\frac {1}") - step.latex.count(r"\frac {1}") - step.latex.count(r"\frac{1}")
        assert after - before <= Counter({"1": max(opened, 0)}), (step.title, shown)
        assert before - after == Counter(), (step.title, shown)
        for row in rows(shown):
            toks = tokens(row)
            assert toks.count("{") == toks.count("}"), row
            assert toks.count(r"\left") == toks.count(r"\right"), row
            assert toks.count(r"\begin") == toks.count(r"\end"), row


def test_a_short_equation_is_left_alone():
    assert broken(r"v_{1y} = - V e \cos{\left(\theta \right)}") == r"v_{1y} = - V e \cos{\left(\theta \right)}"


def test_a_chain_puts_one_relation_per_row_aligned_on_it():
    latex = (r"N_{rear} = \frac{9.81 \cdot 1200 \cdot \left(0.5 \cdot 0.8 + 1.3\right)}"
             r"{2 \cdot \left(0.5 \cdot 0.8 + 2 \cdot 1.3\right)} = 3335\;\mathrm{N}")
    shown = broken(latex)
    formula, value = rows(shown)
    assert re.search(r"N_\{rear\}\s*&(\\small )?\s*=\\frac", formula), formula
    assert value == r"&=3335\;\mathrm {N}"


def test_a_list_of_results_gets_a_row_each_and_keeps_its_implication():
    latex = (r"g m r \cos{\left(\theta \right)} = \frac{m \omega_{p}^{2} r^{2} \sin{\left(\theta \right)} "
             r"\cos{\left(\theta \right)}}{4}\;\Rightarrow\; \omega_{p} = \sqrt{\frac{4 g}{r \sin{\left(\theta \right)}}}")
    first, second = rows(broken(latex))
    assert re.search(r"&(\\small )?=", first), first
    assert second.startswith(r"\Rightarrow\; \omega _{p} &=")
