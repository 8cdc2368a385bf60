"""The safe expression parser: hostile input is refused quickly with a ValueError and nothing is
executed; every well-formed expression is read as the expression it is."""
from __future__ import annotations

import builtins
import time
from pathlib import Path
from unittest import mock

import pytest
import sympy as sp
from hypothesis import HealthCheck, given, settings, strategies as st

from practice.parser import MAX_EXP_ARGUMENT, parse_expression

V, theta, R, omega, e, m_s, L = sp.symbols("V theta R omega e m_s L")
SYMBOLS = [V, theta, R, omega, e, m_s, L]
CANARY = Path("/tmp/dynamics-lab-pwned")

ATTACKS = [
    "__import__('os').system('touch /tmp/dynamics-lab-pwned')",
    "().__class__.__bases__[0].__subclasses__()",
    "V.__class__.__mro__",
    "lambda: 1",
    "exec('import os')",
    "eval('1')",
    "open('/etc/passwd')",
    "getattr(V, 'func')",
    "V.func",
    "9**9**9",
    "9^9^9",
    "10**10**10",
    "2**99999999",
    "(" * 5000 + "1" + ")" * 5000,
    "(" * 30 + "1" + ")" * 30,
    "-" * 150 + "1",
    "1" * 200,
    "x" * 1_000_000,
    "sin(" * 40 + "1" + ")" * 40,
    "exp(exp(exp(exp(100))))",
    "1e999999",
    "е*V",  # Cyrillic е
    "ℯ",  # script e
    "Ｖ",  # full-width V
    "V\u200b",  # zero-width space
    "𝑉",  # mathematical italic V
    "V; import os",
    "V # comment",
    "[V]",
    "{V: 1}",
    "'V'",
    "V if 1 else 2",
    "V and R",
    "\\x41",
    "%s",
    "V == R",
    "factorial(10000)",
    "Integral(V, V)",
    "sympify('1')",
    "",
    "   ",
    "V R (",
    "sqrt",
    "2 +",
    "1/0",
    "log(0)",
]


@pytest.fixture(autouse=True)
def no_canary():
    CANARY.unlink(missing_ok=True)
    yield
    assert not CANARY.exists(), "an attack executed code"


@pytest.mark.parametrize("text", ATTACKS, ids=range(len(ATTACKS)))
def test_attacks_are_refused_quickly_without_executing_anything(text):
    real_eval, real_exec = builtins.eval, builtins.exec

    def forbidden_eval(source, *args, **kwargs):
        if isinstance(source, str):  # text evaluated: what must never happen
            raise AssertionError("eval called on text while parsing")
        return real_eval(source, *args, **kwargs)

    def forbidden_exec(source, *args, **kwargs):
        if isinstance(source, str):  # (importlib execs compiled module code: that is fine)
            raise AssertionError("exec called on text while parsing")
        return real_exec(source, *args, **kwargs)

    started = time.perf_counter()
    with mock.patch.object(builtins, "eval", forbidden_eval), mock.patch.object(builtins, "exec", forbidden_exec):
        with pytest.raises(ValueError) as err:
            parse_expression(text, SYMBOLS)
    assert time.perf_counter() - started < 1.0
    assert str(err.value)  # says what is wrong


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(st.text(max_size=300))
def test_arbitrary_text_is_an_expression_or_a_value_error(text):
    started = time.perf_counter()
    try:
        result = parse_expression(text, SYMBOLS)
    except ValueError:
        pass
    else:
        assert isinstance(result, sp.Expr)
        assert result.free_symbols <= set(SYMBOLS)
    assert time.perf_counter() - started < 1.0


@settings(max_examples=200, deadline=None)
@given(st.text(alphabet="0123456789+-*/^()e.VRθω sincotaqrxplgb", max_size=120))
def test_operator_soup_is_an_expression_or_a_value_error(text):
    started = time.perf_counter()
    try:
        parse_expression(text, SYMBOLS)
    except ValueError:
        pass
    assert time.perf_counter() - started < 1.0


# -- well-formed expressions: generated as text and as sympy together

ATOMS = st.sampled_from([("V", V), ("R", R), ("theta", theta), ("θ", theta), ("omega", omega),
                         ("ω", omega), ("e", e), ("m_s", m_s), ("L", L), ("2", sp.Integer(2)),
                         ("3", sp.Integer(3)), ("0.5", sp.Rational(1, 2)), ("pi", sp.pi)])
FUNCS = st.sampled_from([("sin", sp.sin), ("cos", sp.cos), ("sqrt", sp.sqrt), ("exp", sp.exp),
                         ("atan", sp.atan), ("abs", sp.Abs)])


def expressions(depth=3):
    if depth == 0:
        return ATOMS
    inner = expressions(depth - 1)
    return st.one_of(
        ATOMS,
        st.tuples(inner, st.sampled_from(["+", "-", "*", "/", " * ", "−"]), inner).map(_binary),
        st.tuples(inner, st.sampled_from(["^", "**"]), st.integers(-3, 4)).map(_power),
        st.tuples(FUNCS, inner).map(lambda t: (f"{t[0][0]}({t[1][0]})", t[0][1](t[1][1]))),
        st.tuples(st.sampled_from(["2", "3"]), st.sampled_from(["V", "R", "ω", "(V+R)"])).map(
            lambda t: (t[0] + t[1], sp.Integer(t[0]) * parse_expression(t[1], SYMBOLS))),
    )


def _power(t):
    (a_text, a), op, p = t
    if a == 0 and p < 0:  # 0^(-1) is undefined, and sympy's (0^(-1))^0 = 1 would hide that from the oracle
        return a_text, a
    return f"({a_text}){op}{p if p >= 0 else f'({p})'}", a ** p


def _binary(t):
    (a_text, a), op, (b_text, b) = t
    text = f"({a_text}){op}({b_text})"
    op = op.strip()
    if op == "/" and b == 0:
        return a_text, a
    value = {"+": a + b, "-": a - b, "−": a - b, "*": a * b, "/": a / b}[op]
    return text, value


@settings(max_examples=300, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(expressions())
def test_well_formed_expressions_are_read_exactly(pair):
    text, expected = pair
    if len(text) > 200:
        return
    undefined = expected.has(sp.zoo, sp.nan, sp.oo, -sp.oo) or bool(expected.atoms(sp.AccumBounds))
    if undefined:  # e.g. 1/(V − V): refusing it is right
        try:
            assert parse_expression(text, SYMBOLS) == expected
        except ValueError as error:
            assert "undefined" in str(error) or "zero" in str(error)
        return
    try:
        assert parse_expression(text, SYMBOLS) == expected
    except ValueError as error:  # the parser's bound on exp's argument, e.g. exp(((2)^2)^4) = exp(256)
        assert "out of range" in str(error), error
        assert any(arg.is_number and abs(complex(sp.N(arg))) > MAX_EXP_ARGUMENT
                   for arg in (node.args[0] for node in sp.preorder_traversal(expected) if isinstance(node, sp.exp))), text


def test_the_problems_symbols_come_first_and_greek_is_understood():
    assert parse_expression("e", SYMBOLS) == e  # restitution, not Euler's number
    assert parse_expression("exp(1)", SYMBOLS) == sp.E
    assert parse_expression("2V sin(θ)/3 + Rω/3", SYMBOLS) == 2 * V * sp.sin(theta) / 3 + R * omega / 3
    assert parse_expression("−V", SYMBOLS) == -V
    assert parse_expression("2e - 3", SYMBOLS) == 2 * e - 3
    assert parse_expression("1.5e-3", SYMBOLS) == sp.Float("1.5e-3", 15)
    assert parse_expression("R(ω+1)", SYMBOLS) == R * (omega + 1)
    assert parse_expression("V^-1", SYMBOLS) == 1 / V
    assert parse_expression("2^3^2", SYMBOLS) == 2**9  # right-associative


def test_the_result_uses_the_given_symbol_objects():
    a = sp.Symbol("a", positive=True)
    assert parse_expression("a^2", [a]).free_symbols == {a}


def test_errors_point_at_the_problem():
    with pytest.raises(ValueError, match="position 3"):
        parse_expression("V+$", SYMBOLS)
    with pytest.raises(ValueError, match="Unknown name 'x'"):
        parse_expression("2*x", SYMBOLS)
    with pytest.raises(ValueError, match="Euler"):
        parse_expression("e", [V])


# -- how students write by hand (issue 29)

@pytest.mark.parametrize("text", ["1.0.8", "2.5.1", "1..5", "0.8.", "3 4", "2 .5", "1,5", "1.0.8*V"])
def test_a_number_written_twice_or_with_a_comma_is_refused_not_multiplied(text):
    """1.0.8 is a typo, not 1.0 × 0.8; 3 4 is two numbers, not 12; 1,5 is a decimal comma."""
    with pytest.raises(ValueError) as err:
        parse_expression(text, SYMBOLS)
    message = str(err.value)
    assert "decimal point" in message or "side by side" in message or "comma" in message, message


@pytest.mark.parametrize("text, expected", [
    ("(Rω+2Vsinθ)/3", (R * omega + 2 * V * sp.sin(theta)) / 3),
    ("2Vsin(θ)/3 + Rω/3", 2 * V * sp.sin(theta) / 3 + R * omega / 3),
    ("Vsintheta", V * sp.sin(theta)),
    ("Vcosθ", V * sp.cos(theta)),
    ("sinθcosθ", sp.sin(theta) * sp.cos(theta)),
    ("2πR", 2 * sp.pi * R),
    ("Rω^2", R * omega**2),
    ("m_sL^2", m_s * L**2),
    ("Vsqrt(R)", V * sp.sqrt(R)),
    ("sinθ", sp.sin(theta)),
    ("eVcosθ", e * V * sp.cos(theta)),
])
def test_juxtaposed_givens_and_functions_read_as_a_product(text, expected):
    """What a student writes by hand: R·ω, V·sin θ, the exponent on the last letter only."""
    assert sp.simplify(parse_expression(text, SYMBOLS) - expected) == 0


@pytest.mark.parametrize("text", ["sinθ^2", "Vsinθ^2"])
def test_a_power_after_a_bracketless_function_is_asked_about(text):
    with pytest.raises(ValueError, match=r"sin\(θ\)\^2 or sin\(θ\^2\)"):
        parse_expression(text, SYMBOLS)


NAMES = [("V", V), ("R", R), ("θ", theta), ("ω", omega), ("e", e), ("L", L)]


@settings(max_examples=200, deadline=None)
@given(st.lists(st.tuples(st.sampled_from([None, "sin", "cos", "tan", "sqrt"]), st.sampled_from(NAMES)),
                min_size=2, max_size=5))
def test_any_run_of_givens_and_bracketless_functions_is_their_product(run):
    text = "".join((f or "") + name for f, (name, _) in run)
    functions = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "sqrt": sp.sqrt}
    expected = sp.Mul(*(functions[f](sym) if f else sym for f, (_, sym) in run))
    assert parse_expression(text, SYMBOLS) == expected, text
