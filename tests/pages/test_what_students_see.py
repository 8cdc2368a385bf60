"""What a student sees around the answers (issue 17), for every registered problem: moving shapes
stay in view, no number reads −0, a link carries what the controls show, every check shown compares
two computations that could disagree, a physical limit keeps the method, and on screen the course's
solution is "the worked solution". Each problem's own tests/physics/test_<pid>.py holds its drawing and
caption tests (no two bodies overlap) and the cases below beyond its defaults (optional
IN_VIEW, EDGE_LINKS, CHECK_CASES, LIMIT_LINKS; see docs/adding-a-problem.md).

The geometry is read from the figures as drawn (tests/drawing.py), not from the solvers' arrays.
"""
from __future__ import annotations

import importlib
import math
import re

import numpy as np
import sympy as sp
import pytest

from solvers.core import Choice, Number, plain_fixed, plain_number
from tests.drawing import figures
from tests.strategies import problem_tests
from tests.practice.test_practice import OPTIONS
from tests.pages.test_pages import (IDS, answer_section_text, answers_shown, assert_clean, derivation_shown, derivation_text,
                              derivations_shown, run_page, shown)
from ui.figure import ANSWERS
from solvers.catalog import BY_ID
from ui.params import as_shown, display_format

# ----------------------------------------------------------------------------------------------
# In view: nothing moving is cut off at the edge of the view


def cases(hook: str, first=()) -> list[tuple]:
    """(pid, case) for every registered problem: ``first`` and what its test module lists as ``hook``."""
    return [(pid, *case) if isinstance(case, tuple) else (pid, case)
            for pid in IDS for case in (*first, *getattr(problem_tests(pid), hook, ()))]


@pytest.mark.parametrize("pid,params", cases("IN_VIEW"))
def test_every_moving_shape_stays_inside_the_view(pid, params):
    _, figs = figures(pid, **params)
    figure = figs[0]
    layout = figure.spec["layout"]
    if "scene" in layout:
        pytest.skip("a 3-D scene: plotly fits its view to what it draws")
    (x_lo, x_hi), (y_lo, y_hi) = layout["xaxis"]["range"], layout["yaxis"]["range"]
    anim = figure.spec["animation"]
    for j, coords in zip(anim["traces"], anim["coords"]):
        if figure.spec["data"][j].get("xaxis", "x") != "x" or "x" not in coords:
            continue  # another subplot (the energy bars, θ(t))
        for xs, ys in zip(coords["x"], coords["y"]):
            xs, ys = np.asarray(xs, dtype=float), np.asarray(ys, dtype=float)
            if np.isnan(xs).all():
                continue  # nothing drawn in this frame (the impulse outside its instant)
            assert np.nanmin(xs) >= x_lo and np.nanmax(xs) <= x_hi, figure.spec["data"][j]["name"]
            assert np.nanmin(ys) >= y_lo and np.nanmax(ys) <= y_hi, figure.spec["data"][j]["name"]


# ----------------------------------------------------------------------------------------------
# Numbers: never −0, powers typeset, the URL carries what the control shows

# A minus after a digit, or after TeX's ``{}`` that opens a broken row, is a subtraction, not a sign;
# one before ``0^{2}`` negates the square of a substituted zero (−θ̇⁺² at e = 0), and one before ``0 \cdot``
# a product whose first factor is one (−e θ̇ at e = 0: −0 · (−4.158)), not a number −0.
MINUS_ZERO = re.compile(r"(?<![\d.}])[−-]0(?:\.0*)?(?![\d.^])(?!\s*\\cdot)")


def test_the_formatter_never_writes_minus_zero_and_groups_or_typesets_large_numbers():
    assert plain_number(-0.0) == "0" and plain_number(-0.00001, 1) == "−1\u202f×\u202f10⁻⁵"
    assert plain_number(-0.00004, 4) != "−0"
    assert plain_number(30490.3) == "30\u202f490" and plain_number(3.049e7) == "3.049\u202f×\u202f10⁷"
    assert plain_fixed(-0.04, 1) == "0.0" and plain_fixed(-35.62, 1) == "−35.6"


@pytest.mark.parametrize("pid,query", cases("EDGE_LINKS", first=({},)))
def test_no_shown_number_is_minus_zero(pid, query):
    at = run_page(pid, query)
    assert_clean(at)
    texts = [m.value for m in at.markdown] + [c.value for c in at.caption]
    texts += [derivation_text(at, d) for d in derivations_shown(at)]
    texts += [answer_section_text(section) for section in shown(at, ANSWERS)]
    solver = BY_ID[pid].solver
    params = {}
    for spec in solver.PARAMS:
        if spec.name in query:
            params[spec.name] = query[spec.name] if isinstance(spec, Choice) else float(query[spec.name])
    _, figs = figures(pid, **params)
    texts += [f.description for f in figs] + [f.title for f in figs]
    for text in texts:
        # Inside LaTeX a minus is '-' too; both must not stand before a bare zero.
        assert not MINUS_ZERO.search(text.replace("$", " ")), (pid, query, MINUS_ZERO.search(text), text[:300])
        assert "× 10^" not in text and not re.search(r"\de[+-]\d", text)  # no 3.049e+04 either


@pytest.mark.parametrize("pid", IDS)
def test_url_values_carry_what_the_controls_show(pid):
    system = "us" if BY_ID[pid].us_units else "si"  # the textbook's own units where it has them
    at = run_page(pid, {"units": "us"} if system == "us" else {})
    changed = 0
    for widget in [*at.number_input, *at.slider]:
        name = widget.key.split("__")[-1]
        spec = next((p for p in BY_ID[pid].solver.PARAMS if p.name == name), None)
        if not isinstance(spec, Number) or widget.value is None or math.isinf(widget.value):
            continue
        value = widget.value * 1.0137913 if widget.value else 0.0137913
        lo, hi = getattr(widget, "min", None), getattr(widget, "max", None)
        if lo is not None and not lo <= value <= hi:
            value = widget.value * 0.9862087
        widget.set_value(value).run()
        assert_clean(at)
        if name in at.query_params:
            changed += 1
            assert at.query_params[name] == f"{as_shown(spec, value):g}"
            # ... which is at most six figures, or the slider's own decimals
            assert float(at.query_params[name]) == pytest.approx(value, rel=1e-5, abs=0.5 * 10 ** -(
                int(display_format(spec)[2:-1]) if display_format(spec).endswith("f") else 99))
    assert changed
    assert system


# ----------------------------------------------------------------------------------------------
# Words: "the worked solution", never "the seed"; the run-down switch kept in the URL


@pytest.mark.parametrize("pid", IDS)
def test_on_screen_the_course_s_solution_is_the_worked_solution(pid):
    solver = BY_ID[pid].solver
    words = list(solver.ERRATA)
    for spec in solver.PARAMS:
        words += [spec.label, spec.help] + (list(spec.option_labels) if isinstance(spec, Choice) else [])
        if isinstance(spec, Choice):
            for option in spec.options:
                solution = solver.solve(**{spec.name: option})
                words += [s.title for s in solution.steps] + list(solution.notes)
                words += [c.name + c.explanation for c in solution.checks]
    at = run_page(pid)
    words += [m.value for m in at.markdown] + [r.label for r in at.radio] + [derivation_text(at)]
    words += [answer_section_text(answers_shown(at))]
    for text in words:
        assert "seed" not in text.lower(), text


# ----------------------------------------------------------------------------------------------
# Every shown check compares two computations that can disagree

@pytest.mark.parametrize("pid,params", cases("CHECK_CASES", first=({},)))
def test_every_check_fails_when_an_earlier_step_is_wrong(pid, params):
    """A check that cannot fail (a value against its own definition, or against a max that
    contains it) is caught. One given misread, or one step of the derivation's chain, at a time is
    put 0.1 % wrong and every later step is recomputed from it, as a slip would propagate (the
    checks' second methods still get the true givens); each check must flag some such slip other
    than in the very value it shows. A check of T₂ against
    U_g + U_s, with T₂ defined as that sum, never does: a wrong U_g carries into T₂."""
    solver = importlib.import_module(f"solvers.{pid}")
    solution = solver.solve(**params)
    p, answers = dict(solution.params), dict(solution.answers)
    chain = solver.derivation_of(solution)
    inputs = {**p, **solution.extras.get("chain_inputs", {})}
    values = chain.evaluate(inputs)
    assert all(c.ok for c in solver._checks(p, answers))
    caught: dict[int, set[str]] = {i: set() for i in range(len(solution.checks))}
    def nudged(x):
        return x * 1.001 + 1e-3 * (x == 0)
    numeric = [name for name, x in p.items() if isinstance(x, float) and math.isfinite(x)]
    slips = [(name, chain.evaluate({**inputs, name: nudged(p[name])})) for name in numeric]  # a misread given
    slips += [(link.name, chain.evaluate(inputs, overrides={link.name: nudged(values[link.name])}))
              for link in chain.chain]
    for slipped_name, slipped in slips:
        wrong = {name: slipped.get(name, value) for name, value in answers.items()}
        for i, check in enumerate(solver._checks(p, wrong)):
            if not check.ok:
                caught[i].add(slipped_name)
    for i, check in enumerate(solution.checks):
        shown = {name for name, value in answers.items() if value == check.closed_form}
        assert caught[i] - shown, f"{check.name!r} is failed by no slip but one in the value it shows"
        assert check.closed_form is not check.second_method  # and none compares a number with itself


@pytest.mark.parametrize("pid,query,figures_shown", cases("LIMIT_LINKS"))
def test_a_physical_limit_keeps_the_method_and_what_shows_why(pid, query, figures_shown):
    """At μ ≥ 2.6 (rear drive) only the error used to remain: the derivation and the plot went."""
    at = run_page(pid, query)
    assert_clean(at)
    assert at.error and at.metric
    method = derivation_shown(at)
    assert "without numbers" in method["caption"] and method["steps"] and all(tex for _, tex, *_ in method["steps"])
    assert sum(getattr(e, "type", None) == "bidi_component" for e in at.main) == figures_shown + 1  # figures, derivation




# ----------------------------------------------------------------------------------------------
# Symbols beside the typeset equations are typeset too (issue 29): no plain-text v_B or I_C


PLAIN_NOTATION = re.compile(r"\w[\u0300-\u036f]*_\{?\w|\^")  # v_B, I_{cm}, θ̇_ℓ, R^2 outside $…$


def words_beside_the_equations(solution) -> list[str]:
    """The step titles, the ledger's rows, the checks and the notes: the text the answers and the
    derivation show around their typeset equations."""
    texts = [step.title for step in solution.steps] + list(solution.notes)
    texts += [t for row in solution.ledger for t in (row.quantity, row.why)]
    texts += [t for check in solution.checks for t in (check.name, check.explanation)]
    return texts


@pytest.mark.parametrize("pid, options", OPTIONS)
def test_symbols_beside_the_equations_are_typeset_not_plain_notation(pid, options):
    solver = importlib.import_module(f"solvers.{pid}")
    solution = solver.solve(**options)
    texts = words_beside_the_equations(solution)
    method = getattr(solver, "method", None)
    if method is not None:
        texts += [step.title for step in method(dict(solution.params))]
    plain = [t for t in texts if PLAIN_NOTATION.search(re.sub(r"\$[^$]*\$", "", t))]
    assert plain == []


@pytest.mark.parametrize("pid, options", OPTIONS)
def test_a_sum_with_numbers_puts_its_positive_terms_first(pid, options):
    """ΔT = T⁻ − T⁺ with the numbers in reads 2.062 − 2.021 = 0.04167 J, not −2.021 + 2.062: a
    substituted sum opens with a minus only when every term of it is negative."""
    solver = importlib.import_module(f"solvers.{pid}")
    solution = solver.solve(**options)
    derivation = solver.derivation_of(solution)
    values = derivation.evaluate(dict(solution.params) | dict(solution.extras.get("chain_inputs", {})))
    for link, step in zip(derivation.chain, derivation.numeric_steps(values)):
        substituted = step.latex.split(" = ", 1)[1]
        if isinstance(link.expr, sp.Add) and substituted.startswith("-"):
            assert all(term.could_extract_minus_sign() for term in link.expr.args), step.latex
