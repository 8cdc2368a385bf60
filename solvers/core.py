"""Shared machinery of the solvers: parameter specs and validation, the Solution record, and the
symbolic-derivation chain that turns one sympy derivation into both LaTeX steps and fast numbers.

Nothing here knows any physics; each problem module declares its parameters, derives its
equations once per process with sympy, and hands the result chain to :class:`Derivation`.
"""
from __future__ import annotations

import functools
import math
import numbers
import re
from dataclasses import dataclass, field
from types import MappingProxyType
from typing import Any, Callable, Iterable, Mapping, Sequence

import numpy as np
import sympy as sp

# Re-exported: problems and pages import these from solvers.core.
from .formatting import latex_number, plain_fixed, plain_number  # noqa: F401
from . import units
from .units import latex_quantity  # noqa: F401

# --------------------------------------------------------------------------------------------
# Errors


class ParameterError(ValueError):
    """A parameter is unknown, of the wrong type, not finite, or out of its allowed range."""


class PhysicalLimitError(ValueError):
    """The parameters are valid one by one, but the model cannot describe their combination.

    The limit the page should show is carried as attributes (e.g. ``mu_lift``, ``theta_max``),
    listed in ``limits`` as ``{name: value}`` (SI, radians).
    """

    def __init__(self, message: str, **limits: float):
        super().__init__(message)
        self.limits = dict(limits)
        for name, value in limits.items():
            setattr(self, name, value)


# --------------------------------------------------------------------------------------------
# Parameter specs: data, shared by validation here and by the controls in ui/


@dataclass(frozen=True)
class Number:
    """A real-valued parameter, SI units, radians for angles.

    ``low``/``high`` bound the physically valid range (``None`` = unbounded) and the flags say
    whether each bound is allowed; they are in SI units and radians, as the value. ``ui_low``/
    ``ui_high``/``step`` only suggest a control's range, in ``ui_unit``: the dimension's display
    unit in SI (degrees for angles, the SI unit otherwise).
    """

    name: str
    default: float
    label: str
    dimension: str  # key into solvers.units.DIMENSIONS: mass, length, angle, speed, ...
    symbol: str  # LaTeX
    low: float | None = None
    high: float | None = None
    low_inclusive: bool = False
    high_inclusive: bool = False
    allow_inf: bool = False
    ui_low: float | None = None
    ui_high: float | None = None
    step: float | None = None
    help: str = ""

    @property
    def ui_unit(self) -> str:
        """The unit ``ui_low``, ``ui_high`` and ``step`` are in ("°" for angles)."""
        return units.unit(self.dimension, "si")

    def range_text(self) -> str:
        """The allowed range in words, in the API's units (angles also in degrees)."""
        def show(v: float) -> str:
            if self.dimension == "angle":
                return f"{v:g} rad ({math.degrees(v):g}°)"
            return f"{v:g}"

        parts = []
        if self.low is not None:
            parts.append(("at least " if self.low_inclusive else "greater than ") + show(self.low))
        if self.high is not None:
            parts.append(("at most " if self.high_inclusive else "less than ") + show(self.high))
        text = " and ".join(parts) if parts else "any finite number"
        if self.allow_inf:
            text += ", or inf"
        return text

    def validate(self, value: Any) -> float:
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise ParameterError(
                f"{self.name} ({self.label}) must be a number, not {type(value).__name__} "
                f"{value!r}; allowed: {self.range_text()}."
            )
        x = float(value)
        if math.isnan(x):
            raise ParameterError(f"{self.name} ({self.label}) is NaN; allowed: {self.range_text()}.")
        if math.isinf(x) and not (self.allow_inf and x > 0):
            raise ParameterError(
                f"{self.name} ({self.label}) must be finite; allowed: {self.range_text()}."
            )
        too_low = self.low is not None and (x < self.low or (x == self.low and not self.low_inclusive))
        too_high = self.high is not None and (
            x > self.high or (x == self.high and not self.high_inclusive)
        ) and not (math.isinf(x) and self.allow_inf)
        if too_low or too_high:
            shown = f"{x:g} rad ({math.degrees(x):g}°)" if self.dimension == "angle" else f"{x:g}"
            raise ParameterError(
                f"{self.name} ({self.label}) = {shown} is out of range: it must be {self.range_text()}."
            )
        return x


@dataclass(frozen=True)
class Choice:
    """A parameter that takes one of a few exact lowercase strings."""

    name: str
    default: str
    label: str
    options: tuple[str, ...]
    option_labels: tuple[str, ...] = ()
    help: str = ""

    def validate(self, value: Any) -> str:
        if not isinstance(value, str) or value not in self.options:
            allowed = ", ".join(repr(o) for o in self.options)
            raise ParameterError(
                f"{self.name} ({self.label}) must be one of {allowed}, not {value!r}."
            )
        return value

    def label_of(self, option: str) -> str:
        labels = self.option_labels or self.options
        return dict(zip(self.options, labels))[option]


Param = Number | Choice


@dataclass(frozen=True)
class Answer:
    """How an answer is named, written and measured (for pages and the numeric steps)."""

    name: str
    label: str
    symbol: str  # LaTeX
    dimension: str


def validate_params(spec: Sequence[Param], given: Mapping[str, Any]) -> dict[str, Any]:
    """Check names, types and ranges; return every parameter with defaults filled in."""
    known = {p.name for p in spec}
    unknown = [k for k in given if k not in known]
    if unknown:
        raise ParameterError(
            f"unknown parameter{'s' if len(unknown) > 1 else ''} "
            f"{', '.join(repr(k) for k in unknown)}; this problem takes: "
            f"{', '.join(p.name for p in spec)}."
        )
    return {p.name: p.validate(given.get(p.name, p.default)) for p in spec}


def require(condition: bool, message: str) -> None:
    """Raise a ParameterError with ``message`` unless ``condition`` holds (cross-parameter rules)."""
    if not condition:
        raise ParameterError(message)


class OutOfModelRangeError(ParameterError):
    """Each value is allowed, but together they overflow floating point (a length of 1e300 m
    squared, a mass ratio of 1e-300): no physics limit, just past what the numbers can carry."""


ARITHMETIC_FAILURES = (OverflowError, ZeroDivisionError, FloatingPointError)


def within_model_range(compute: Callable[..., Any]) -> Callable[..., Any]:
    """Wrap a solver's ``solve`` (or anything computed from its parameters) so that floating-point
    overflow or a division by an underflowed zero becomes a plain refusal, never a traceback."""
    @functools.wraps(compute)
    def guarded(*args, **kwargs):
        try:
            return compute(*args, **kwargs)
        except ARITHMETIC_FAILURES as error:
            raise OutOfModelRangeError(
                "These values are too large (or too small) for the model: the arithmetic "
                f"overflows ({type(error).__name__}). Use magnitudes closer to a real "
                "laboratory set-up, e.g. within a factor of a million of the defaults.") from None
    return guarded


# --------------------------------------------------------------------------------------------
# The Solution record


@dataclass(frozen=True)
class Step:
    title: str
    latex: str
    numeric: bool = False  # the step puts in the numbers (hidden while a student practises)


@dataclass(frozen=True)
class Check:
    """One line of the conservation ledger: a closed-form value and an independent second method.

    ``tolerance`` is absolute, so a quantity whose true value is zero is checked fairly.
    """

    name: str
    closed_form: float
    second_method: float
    tolerance: float
    explanation: str = ""

    def __post_init__(self):
        for name in ("closed_form", "second_method", "tolerance"):
            object.__setattr__(self, name, float(getattr(self, name)))

    @property
    def ok(self) -> bool:
        return bool(abs(self.closed_form - self.second_method) <= self.tolerance)


@dataclass(frozen=True)
class LedgerRow:
    """Before and after an impact: is the quantity conserved, and why (or why not)."""

    quantity: str
    before: float
    after: float
    dimension: str
    why: str

    @property
    def conserved(self) -> bool:
        return abs(self.after - self.before) <= 1e-9 * max(abs(self.before), abs(self.after), 1e-300)


@dataclass(frozen=True)
class Solution:
    problem: str
    params: Mapping[str, Any]
    answers: Mapping[str, float]
    steps: tuple[Step, ...]
    checks: tuple[Check, ...] = ()
    regime: str = ""
    notes: tuple[str, ...] = ()
    ledger: tuple[LedgerRow, ...] = ()
    extras: Mapping[str, Any] = field(default_factory=dict)
    symbolic_steps: int = -1  # how many leading steps are symbolic (the rest put in the numbers)

    def __post_init__(self):
        if self.symbolic_steps < 0:
            count = next((i for i, s in enumerate(self.steps) if s.numeric), len(self.steps))
            object.__setattr__(self, "symbolic_steps", count)
        object.__setattr__(self, "answers", MappingProxyType({k: float(v) for k, v in self.answers.items()}))
        object.__setattr__(self, "params", MappingProxyType(dict(self.params)))


def relative_tolerance(value: float, rel: float = 1e-9, floor: float = 1e-12) -> float:
    """An absolute tolerance scaled to ``value``, never zero."""
    return max(abs(value) * rel, floor)


# --------------------------------------------------------------------------------------------
# The derivation chain


_DOUBLE_PARENS = re.compile(r"\\left\(\\left\(([^()]*)\\right\) \\right\)")


def latex_eq(lhs: sp.Expr, rhs: sp.Expr, **kw) -> str:
    return sp.latex(sp.Eq(lhs, rhs, evaluate=False), **kw)


def _only_inside_trig(expr: sp.Expr, sym: sp.Symbol) -> bool:
    """True when ``sym`` occurs in ``expr`` only as (part of) a trig function's argument."""
    stripped = expr.replace(
        lambda e: isinstance(e, sp.functions.elementary.trigonometric.TrigonometricFunction)
        and e.has(sym),
        lambda e: sp.Integer(1),
    )
    return not stripped.has(sym)


@dataclass(frozen=True)
class Result:
    """One link of a derivation chain: ``symbol = expr`` with expr in parameters and earlier results."""

    name: str
    symbol: sp.Symbol
    expr: sp.Expr
    dimension: str
    title: str = ""


class Derivation:
    """A symbolic derivation done once, evaluated many times.

    ``symbols`` maps parameter names to their sympy symbols; ``steps`` are the symbolic steps
    (already LaTeX); ``chain`` lists results in order. ``evaluate`` runs lambdified code only, and
    ``numeric_steps`` fills a LaTeX template built once from the same expressions. ``labels``
    names the results in words for the numeric steps' titles.
    """

    _PLACEHOLDER = "ZQ{}QZ"

    def __init__(
        self,
        symbols: Mapping[str, sp.Symbol],
        dimensions: Mapping[str, str],
        steps: Iterable[Step],
        chain: Sequence[Result],
        labels: Mapping[str, str] | None = None,
    ):
        self.steps = tuple(steps)
        self._labels = dict(labels or {})
        self._symbols = dict(symbols)
        self._vectorized: dict[str, Callable[..., np.ndarray]] = {}
        self.chain = tuple(chain)
        self._dimensions = dict(dimensions)
        known: dict[sp.Symbol, str] = {sym: name for name, sym in symbols.items()}
        self._compiled: list[tuple[str, Callable, tuple[str, ...]]] = []
        self._templates: list[tuple[Result, str, str, tuple[tuple[str, str, bool], ...]]] = []
        for link in self.chain:
            free = sorted(link.expr.free_symbols, key=lambda s: s.name)
            missing = [s for s in free if s not in known]
            if missing:
                raise RuntimeError(f"{link.name}: unknown symbols {missing}")
            arg_names = tuple(known[s] for s in free)
            func = sp.lambdify(free, link.expr, modules="math")
            self._compiled.append((link.name, func, arg_names))
            names = {s: self._PLACEHOLDER.format(i) for i, s in enumerate(free)}
            template = sp.latex(link.expr, symbol_names=names, mul_symbol="dot")
            slots = tuple(
                (names[s], known[s], _only_inside_trig(link.expr, s)) for s in free
            )
            self._templates.append((link, sp.latex(link.symbol), template, slots))
            known[link.symbol] = link.name
            self._dimensions[link.name] = link.dimension
        self._results = {link.name for link in self.chain}

    @property
    def symbols(self) -> dict[str, sp.Symbol]:
        """Every symbol of the chain by name: the parameters' and the results'."""
        return dict(self._symbols) | {link.name: link.symbol for link in self.chain}

    @functools.cached_property
    def _in_parameters(self) -> dict[sp.Symbol, sp.Expr]:
        """Each result's symbol -> its expression in the parameters alone (built once)."""
        full: dict[sp.Symbol, sp.Expr] = {}
        for link in self.chain:
            full[link.symbol] = link.expr.subs(full)
        return full

    def expression_of(self, name: str) -> sp.Expr:
        """Result ``name`` as an expression in the parameters alone (earlier results substituted)."""
        link = next((link for link in self.chain if link.name == name), None)
        if link is None:
            raise KeyError(name)
        return self._in_parameters[link.symbol]

    def in_parameters(self, expr: sp.Expr) -> sp.Expr:
        """``expr``, which may use result symbols, rewritten in the parameters alone."""
        return expr.subs(self._in_parameters)

    def vectorized(self, name: str) -> Callable[..., np.ndarray]:
        """Result ``name`` as a numpy function of the parameters (keyword arguments, arrays
        welcome), for curves over a range of one parameter; compiled once."""
        if name not in self._vectorized:
            expr = self.expression_of(name)
            names = {sym: pname for pname, sym in self._symbols.items()}
            args = sorted(expr.free_symbols, key=lambda s: s.name)
            func = sp.lambdify(args, expr, modules="numpy")
            arg_names = [names[a] for a in args]
            self._vectorized[name] = lambda **kw: np.broadcast_to(
                func(*(kw[n] for n in arg_names)), np.broadcast(*(np.asarray(v) for v in kw.values())).shape)
        return self._vectorized[name]

    def evaluate(self, values: Mapping[str, float], upto: str | None = None,
                 overrides: Mapping[str, float] | None = None) -> dict[str, float]:
        """Run the chain numerically; returns the parameters plus every result (or those up to
        and including ``upto``, to test a condition before the rest is meaningful). A result in
        ``overrides`` takes that value instead and the later links use it (a slip in one step, for
        tests that the shown checks catch it)."""
        out, overrides = dict(values), overrides or {}
        for name, func, arg_names in self._compiled:
            out[name] = float(overrides[name] if name in overrides else func(*(out[a] for a in arg_names)))
            if name == upto:
                break
        return out

    def numeric_steps(self, values: Mapping[str, float]) -> list[Step]:
        """One step per chain link: the expression with numbers substituted, then its value."""
        steps = []
        for link, symbol, template, slots in self._templates:
            text = template
            for placeholder, name, trig_only in slots:
                text = text.replace(placeholder, self._number_for(name, values[name], trig_only))
            text = _DOUBLE_PARENS.sub(r"\\left(\1\\right)", text)
            value = latex_quantity(values[link.name], link.dimension)
            title = link.title or f"With your numbers: {self._labels.get(link.name, link.name)}"
            steps.append(Step(title, f"{symbol} = {text} = {value}", numeric=True))
        return steps

    def _number_for(self, name: str, x: float, trig_only: bool) -> str:
        # Given parameters appear as typed (up to 6 figures); computed results with 4.
        sig, zeros = (4, True) if name in self._results else (6, False)
        if self._dimensions.get(name) == "angle" and trig_only and math.isfinite(x):
            text = latex_number(math.degrees(x), sig, zeros) + r"^{\circ}"
        else:
            text = latex_number(x, sig, zeros)
        if x < 0 or r"\times" in text:
            text = rf"\left({text}\right)"
        return text


def presentable(derived: sp.Expr, shown: sp.Expr, trials: int = 5) -> sp.Expr:
    """Return ``shown``, a readable arrangement of ``derived``, after checking they are equal.

    sympy's own arrangement of a solved expression is often hard to read; the derivation shows a
    form a professor would write, and this check (at random positive points) keeps it honest.
    """
    free = sorted(derived.free_symbols | shown.free_symbols, key=lambda s: s.name)
    rng = np.random.default_rng(12345)
    for _ in range(trials):
        point = dict(zip(free, (sp.Float(x) for x in rng.uniform(0.2, 0.9, len(free)))))
        a, b = complex(derived.evalf(subs=point)), complex(shown.evalf(subs=point))
        if not abs(a - b) <= 1e-9 * (1 + abs(a)):
            raise AssertionError(f"presentable form differs: {derived} vs {shown}")
    return shown


def root_with_sign(roots: Sequence[sp.Expr], sign: int) -> sp.Expr:
    """The one root of ``roots`` whose value has ``sign`` (+1/−1) at a generic point in the
    physical domain (all symbols between 0.2 and 0.9, where sin and cos are positive)."""
    chosen = []
    for root in roots:
        point = {s: sp.Rational(1, 2) + sp.Rational(i, 13) for i, s in enumerate(
            sorted(root.free_symbols, key=lambda s: s.name))}
        if sp.sign(complex(root.evalf(subs=point)).real) == sign:
            chosen.append(root)
    if len(chosen) != 1:
        raise AssertionError(f"expected one root of sign {sign} among {roots}")
    return chosen[0]
