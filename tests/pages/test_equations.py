"""Long display equations broken over rows (ui/equations.py), on every step of every problem.

The rows must say the same algebra: every symbol and number of the step, in the same order (a
fraction opened as 1/B · A puts its denominator first), and no row may end inside a group, which
KaTeX would refuse. Whether the rows really fit a phone is measured in the browser
(tests/browser/test_browser.py: display equations against their boxes at 360 and 390 px).
"""
from __future__ import annotations

import re
from collections import Counter

import pytest
from hypothesis import given, settings, strategies as st

from tests import strategies
from solvers.catalog import PROBLEMS
from ui.equations import (PHONE_BOX_EM, PHONE_WIDTH_EM, WIDE_WIDTH_EM, _broken, broken, laid_out_width, tokens,
                          wide_too, width)

SCAFFOLD = {r"\begin", r"\end", "aligned", "&", r"\\", r"\quad", r"\small", r"\footnotesize", r"\scriptsize",
            r"\Bigl", r"\Bigr", r"\left", r"\right", r"\,", "{", "}", r"\qquad", r"\;", ","}  # layout only


def content(latex: str) -> Counter:
    """What the student reads: symbols, numbers, operators and brackets, without layout."""
    words = re.sub(r"\\begin\{aligned\}|\\end\{aligned\}", "", latex)
    return Counter(t for t in tokens(words) if t not in SCAFFOLD)


def rows(latex: str) -> list[str]:
    inner = latex.removeprefix(r"\begin{aligned}").removesuffix(r"\end{aligned}")
    return inner.split(r" \\ ")


# Each problem's random valid parameters (its tests' VALID), imported here, not inside a @given test.
VALID = {p.id: strategies.valid(p.id) for p in PROBLEMS}


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
@settings(max_examples=15)
@given(data=st.data())
def test_broken_steps_keep_the_algebra_and_close_every_group_on_its_row(problem, data):
    strategy = VALID[problem.id]
    params = data.draw(strategy) if strategy is not None else {}
    try:
        solution = problem.solver.solve(**params)
    except ValueError:
        return  # a refused case shows no derivation
    for step in solution.steps:
        variants = wide_too(step.latex)  # a phone's rows, and a wide column's where they differ
        assert variants[0] == broken(step.latex) and (len(variants) == 1) == (broken(step.latex, WIDE_WIDTH_EM) == variants[0])
        for shown, limit in zip(variants, (PHONE_WIDTH_EM, WIDE_WIDTH_EM)):
            check_rows(step, shown, limit)
        # As laid out on a phone: a row that starts in the second column starts after the first column's
        # widest cell (the cart's Step 3, its rows' left-hand sides 10 em wide and a long row in the second
        # column, drew 24 em where 18.8 fit; the estimate runs short of KaTeX, never long). The columns
        # may not make the block wider than the phone holds (unless a row is set at the smallest size,
        # ``_scaled``'s last resort for a fraction no sign or dot splits, which may not fit at all).
        if r"\scriptsize" not in variants[0]:
            assert laid_out_width(variants[0]) <= PHONE_BOX_EM, (step.title, variants[0])


SMALLER = r"\\(small|footnotesize|scriptsize)\b"


def check_rows(step, shown: str, limit: float) -> None:
    """``shown`` (``step`` broken to ``limit`` em) says the step's algebra, every group closed on its row."""
    if shown == step.latex:
        assert width(tokens(shown)) <= limit
    else:
        before, after = content(step.latex), content(shown)
        opened = shown.count(r"\frac {1}") - step.latex.count(r"\frac {1}") - step.latex.count(r"\frac{1}")
        # (½ · A where A opens with a number: the product said, so ½ 1 cannot read as a mixed number)
        assert after - before <= Counter({"1": max(opened, 0), r"\cdot": max(opened, 0)}), (step.title, shown)
        assert not re.search(r"\\frac \{1\}\{[^{}]*\}\\,[0-9]", shown), (step.title, shown)  # ½ 1 · (…)
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


def test_words_in_a_broken_step_keep_their_spaces():
    """Text mode's spaces are what it says: the loads' list broken into rows read "atG" where the step said
    "at G" (a step that fits kept them; the rows' tokens had dropped them)."""
    latex = r",\quad ".join(rf"\text{{at }}{p}:\; -g m_{{{p}}}\,\mathbf{{E}}_y" for p in "ABCD")
    shown = rows(broken(latex))
    assert len(shown) == 4 and all(rf"\text{{at }}{p}:" in row for p, row in zip("ABCD", shown)), shown
    assert width(tokens(r"\text{at the wall}")) > width(tokens(r"\text{at}"))


@pytest.mark.parametrize("problem", PROBLEMS, ids=[p.id for p in PROBLEMS])
@settings(max_examples=15, deadline=None)
@given(data=st.data())
def test_a_step_broken_by_its_shape_is_the_step_broken_itself(problem, data):
    """``broken`` breaks a step's shape (each digit a stand-in) once and puts the digits back; that
    must be exactly what breaking the step itself gives, on every step of random valid parameters."""
    try:
        solution = problem.solver.solve(**data.draw(VALID[problem.id]))
    except ValueError:
        return
    for step in solution.steps:
        assert broken(step.latex) == _broken(step.latex, PHONE_WIDTH_EM), step.title


def test_digits_go_back_where_their_group_went():
    """A fraction opened as 1/B · A moves its numerator after the denominator and adds a 1: the
    digits must travel with their groups, and the added 1 stay a 1."""
    latex = (r"v = \frac{12.34 \cdot 56.78 + 90.12 \cdot 34.56 + 78.9 \cdot 0.123 + 4.5 \cdot 6.7 + 8.9}{2.5}"
             r" = 987.6 + 543.2 + 109.8 + 765.4 + 321.0 + 111.1")
    shown = broken(latex)
    assert shown == _broken(latex, PHONE_WIDTH_EM) and shown != latex
    # The same shape with other digits is answered from the cache, with its own digits.
    other = latex.replace("12.34", "43.21").replace("987.6", "678.9")
    assert broken(other) == _broken(other, PHONE_WIDTH_EM)
    assert "43.21" in broken(other) and "12.34" not in broken(other)
