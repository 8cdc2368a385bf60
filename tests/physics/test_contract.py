"""The solver contract (docs/adding-a-problem.md) for every registered problem, against the CONTRACT its
own test module types from PROBLEMS.md: names, defaults, errors, steps."""
from __future__ import annotations

import importlib
import math
from unittest import mock

import numpy as np
import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from solvers import registry
from solvers.core import Choice, Number
from tests import strategies

PROBLEMS = registry.PROBLEM_IDS
# Imported here, not inside a @given test (hypothesis calls that nesting @given).
VALID = {pid: strategies.valid(pid) for pid in PROBLEMS}


def contract(pid):
    """The problem's spec as its own tests/physics/test_<pid>.py types it from PROBLEMS.md."""
    return strategies.problem_tests(pid).CONTRACT


def module(pid):
    return importlib.import_module(f"solvers.{pid}")


@pytest.mark.parametrize("pid", PROBLEMS)
def test_no_argument_call_matches_the_tables_defaults(pid):
    solved = module(pid).solve()
    explicit = module(pid).solve(**contract(pid)["defaults"])
    assert set(solved.answers) == contract(pid)["answers"]
    assert dict(solved.answers) == pytest.approx(dict(explicit.answers), rel=1e-14)
    assert all(isinstance(v, float) and math.isfinite(v) for v in solved.answers.values())


@pytest.mark.parametrize("pid", PROBLEMS)
def test_parameter_names_and_defaults_are_the_spec(pid):
    spec = {p.name: p.default for p in module(pid).PARAMS}
    defaults = contract(pid)["defaults"]
    assert spec.keys() == defaults.keys()
    for name, value in defaults.items():
        assert spec[name] == pytest.approx(value) if isinstance(value, float) else spec[name] == value


@pytest.mark.parametrize("pid", PROBLEMS)
def test_unknown_name_is_a_value_error_that_names_it(pid):
    with pytest.raises(ValueError, match="bogus"):
        module(pid).solve(bogus=1.0)


@pytest.mark.parametrize("pid", PROBLEMS)
@pytest.mark.parametrize("bad", [math.nan, -math.inf, True, "1.0", None, [1.0], 1 + 2j])
def test_bad_values_are_value_errors_with_plain_messages(pid, bad):
    for p in module(pid).PARAMS:
        with pytest.raises(ValueError) as err:
            module(pid).solve(**{p.name: bad})
        assert p.name in str(err.value)
        assert "Traceback" not in str(err.value)


@pytest.mark.parametrize("pid", PROBLEMS)
def test_infinity_is_refused_except_where_the_default_is_infinite(pid):
    for p in module(pid).PARAMS:
        if isinstance(p, Number) and contract(pid)["defaults"][p.name] != math.inf:
            with pytest.raises(ValueError, match=p.name):
                module(pid).solve(**{p.name: math.inf})


@pytest.mark.parametrize("pid", PROBLEMS)
def test_numpy_scalars_are_accepted(pid):
    p = next(p for p in module(pid).PARAMS if isinstance(p, Number))
    a = module(pid).solve(**{p.name: np.float64(p.default)}).answers
    b = module(pid).solve().answers
    assert dict(a) == dict(b)


@pytest.mark.parametrize("pid", PROBLEMS)
def test_choices_refuse_other_strings(pid):
    for p in module(pid).PARAMS:
        if isinstance(p, Choice):
            with pytest.raises(ValueError, match=p.name):
                module(pid).solve(**{p.name: p.default.upper()})


@pytest.mark.parametrize("pid,name,value", [
    (pid, name, value) for pid in PROBLEMS for name, value in contract(pid).get("out_of_range", ())])
def test_out_of_range_values_are_refused_with_the_range(pid, name, value):
    with pytest.raises(ValueError) as err:
        module(pid).solve(**{name: value})
    message = str(err.value)
    assert len(message) > 30 and ("must" in message or "never" in message)


@pytest.mark.parametrize("pid", PROBLEMS)
def test_steps_are_titled_latex_ending_with_numbers(pid):
    solution = module(pid).solve()
    steps = solution.steps
    assert 0 < solution.symbolic_steps < len(steps), "symbolic steps first, then the numbers"
    for step in steps:
        assert step.title.strip() and step.latex.strip()
        assert "$" not in step.latex
        assert step.latex.count("{") == step.latex.count("}")
    # The last steps show numbers substituted: digits on both sides of the final '='.
    last = steps[-1].latex
    assert any(ch.isdigit() for ch in last.rsplit("=", 1)[1])
    assert any(ch.isdigit() for ch in last.split("=", 1)[1])


@pytest.mark.parametrize("pid", PROBLEMS)
def test_steps_follow_the_numbers(pid):
    p = next(p for p in module(pid).PARAMS if isinstance(p, Number))
    a = module(pid).solve()
    b = module(pid).solve(**{p.name: p.default * 0.9 if p.default else 0.1})
    assert [s.latex for s in a.steps] != [s.latex for s in b.steps]


@pytest.mark.parametrize("pid", PROBLEMS)
def test_symbolic_work_is_done_once_per_process(pid):
    module(pid).solve()  # warm
    spec = [p for p in module(pid).PARAMS if isinstance(p, Number)]
    with mock.patch.object(sp, "solve", side_effect=AssertionError("sp.solve called")), \
         mock.patch.object(sp, "simplify", side_effect=AssertionError("sp.simplify called")):
        for scale in (0.97, 0.95):
            module(pid).solve(**{spec[0].name: spec[0].default * scale})


@pytest.mark.parametrize("pid", PROBLEMS)
@settings(max_examples=40, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=strategies.st.data())
def test_every_check_passes_over_random_valid_parameters(pid, data):
    params = data.draw(VALID[pid])
    solution = module(pid).solve(**params)
    assert solution.checks, "every problem shows at least one check"
    for check in solution.checks:
        assert check.ok, (check, params)
    assert all(math.isfinite(v) for v in solution.answers.values())


# ----------------------------------------------------------------------------------------------
# Extreme magnitudes: a result or a plain refusal, never an overflow's traceback


def _extreme_values(pid):
    """Some of the problem's numeric parameters, each put at ±10^k for k in −300 … 300 (a URL
    like ?V=1e200 is one click away); the others keep their defaults."""
    numeric = [p.name for p in module(pid).PARAMS if isinstance(p, Number)]
    magnitude = st.integers(-300, 300).map(lambda k: 10.0 ** k)
    value = st.tuples(st.sampled_from([1.0, -1.0]), magnitude).map(lambda t: t[0] * t[1])
    return st.dictionaries(st.sampled_from(numeric), value, min_size=1)


@pytest.mark.parametrize("pid", PROBLEMS)
@settings(max_examples=8, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(data=st.data())
def test_extreme_magnitudes_give_a_result_or_a_plain_refusal(pid, data):
    params = data.draw(_extreme_values(pid))
    try:
        solution = module(pid).solve(**params)
    except ValueError as error:
        assert str(error) and "Traceback" not in str(error)
        return
    assert all(math.isfinite(v) or v == math.inf for v in solution.answers.values()), solution.answers


@pytest.mark.parametrize("pid,params", [(pid, params) for pid in PROBLEMS for params in contract(pid).get("too_large", ())])
def test_the_reviewed_huge_values_are_refused_in_plain_words(pid, params):
    """The review's examples (each raised OverflowError or ZeroDivisionError)."""
    with pytest.raises(ValueError, match="too large|out of range|must be"):
        module(pid).solve(**params)


# ----------------------------------------------------------------------------------------------
# The magnitudes a model is meant for (Number.model_bounds): beyond them, a plain refusal


def _bounded(pid):
    return [p for p in module(pid).PARAMS if isinstance(p, Number) and p.model_bounds()]


@pytest.mark.parametrize("pid", PROBLEMS)
def test_beyond_a_thousand_times_the_textbook_value_is_refused_in_plain_words(pid):
    for p in _bounded(pid):
        beyond = [abs(p.default) * 1e3 * 1.5]  # 1.5 × the bound, written independently of it
        if p.low == 0 and not p.low_inclusive:
            beyond.append(abs(p.default) / 1e3 / 1.5)
        for value in beyond:
            physical = p.high is not None and value > p.high  # the physical range refuses it first
            with pytest.raises(ValueError, match=f"{p.name} .*out of range{'' if physical else ' for this model'}"):
                module(pid).solve(**{p.name: value})


@pytest.mark.parametrize("pid", PROBLEMS)
def test_the_controls_and_the_variants_stay_inside_the_model_bounds(pid):
    from practice.variants import variant
    for p in _bounded(pid):
        lo, hi = p.model_bounds()
        for v in (p.ui_low, p.ui_high):
            assert v in (None, 0) or lo <= abs(v) <= hi, (pid, p.name, v)
    for seed in range(20):  # variant() raises RuntimeError if the bounds left it no valid draw
        assert variant(module(pid), pid, seed)
