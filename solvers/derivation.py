"""The derivation chain: one sympy derivation, done once per process, turned into both the LaTeX
steps and fast numbers (lambdified), with the substituted-number steps filled from templates."""
from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass
from typing import Callable, Iterable, Mapping, Sequence

import numpy as np
import sympy as sp
from sympy.printing.latex import LatexPrinter

from .formatting import latex_number
from .solution import Step
from .units import latex_quantity


_DOUBLE_PARENS = re.compile(r"\\left\(\\left\(([^()]*)\\right\) \\right\)")
# A negative number put in as a whole term after a binary sign: a + (−b) is written a − b, a − (−b) as a + b (not
# before a power: a + (−b)² is not a − b²; nor a factor, whose product keeps its brackets).
_SIGNED_NUMBER = re.compile(r"(?<=[\d})] )([+-]) \\left\(-([0-9.]+(?:\^\{\\circ\})?)\\right\)(?!\s*(?:\^|\\cdot))")


def _is_mass(factor: sp.Basic) -> bool:
    return isinstance(factor, sp.Symbol) and (factor.name == "m" or factor.name.startswith("m_"))


# The dimensionless coefficients a person writes first in a product: friction's μ N, restitution's e V
# (PROBLEMS.md's names).
_COEFFICIENTS = frozenset({"mu", "e"})


def _is_coefficient(factor: sp.Basic) -> bool:
    return isinstance(factor, sp.Symbol) and factor.name in _COEFFICIENTS


def _weight_as_written(product: sp.Basic) -> sp.Basic | None:
    """A product as a person writes it: the numbers, the coefficients μ and e, the masses, g, then the
    other factors in sympy's order (m g, m L², m_s g L cos θ, μ N_front, −e V cos θ, not sympy's alphabetical
    g m, L² m, L g m_s cos θ, N_front μ, −V e cos θ): the weight and the friction as the free-body diagram
    labels them. None where there is no mass or coefficient, or the order is that already."""
    if not (isinstance(product, sp.Mul) and product.is_commutative):
        return None
    factors = product.as_ordered_factors()
    if not any(_is_mass(f) or _is_coefficient(f) for f in factors):
        return None
    rank = lambda f: (0 if f.is_number else 1 if _is_coefficient(f) else 2 if _is_mass(f)  # noqa: E731
                      else 3 if isinstance(f, sp.Symbol) and f.name == "g" else 4)
    written = sorted(factors, key=rank)  # (stable: sympy's order within each kind)
    return None if written == factors else sp.Mul(*written, evaluate=False)


def _roots_together(product: sp.Basic) -> sp.Basic | None:
    """A product's square roots under one root sign, as a person writes it: √(2 T₂ / I_O), not sympy's
    √2 √(T₂/I_O); √(3 g (sin θ₀ − sin θ) / L), not √3 √g √(…) / √L (which, with the numbers put in, read
    √4 for L). None where the product has fewer than two, or where joining them could change its value:
    √a √b = √(ab) needs at most one of a, b negative, and 1/√b = √(1/b) needs b positive (sympy's assumptions
    on the symbols say so)."""
    if not isinstance(product, sp.Mul):
        return None
    roots = [f for f in product.args if f.is_Pow and f.exp in (sp.S.Half, -sp.S.Half)]
    if len(roots) < 2:
        return None
    if (any(root.exp < 0 and not root.base.is_positive for root in roots)
            or sum(1 for root in roots if root.exp > 0 and not root.base.is_nonnegative) > 1):
        return None
    rest = list(product.args)
    for root in roots:
        rest.remove(root)
    inside = sp.Mul(*(root.base if root.exp > 0 else 1 / root.base for root in roots))
    return sp.Mul(*rest, sp.Pow(inside, sp.S.Half, evaluate=False), evaluate=False)


def _sum_in(factor: sp.Basic) -> sp.Add | None:
    """The sum a factor is, to the first power or its reciprocal (whose sign negating the sum negates); else None."""
    base, exponent = factor.as_base_exp()
    return base if isinstance(base, sp.Add) and exponent in (1, -1) else None


def _difference(factor: sp.Basic) -> bool:
    """A two-term sum with one term negative (a − b), to the first power or its reciprocal."""
    base = _sum_in(factor)
    return base is not None and len(base.args) == 2 and sum(t.could_extract_minus_sign() for t in base.args) == 1


def _signs_as_written(product: sp.Basic) -> sp.Basic | None:
    """A product's signs where a person puts them: a sum whose every term is negative written as the
    negative of a sum (g (−m_r L − 2 m_s (L + r)) → −g (m_r L + 2 m_s (L + r))), and a negative product's sign
    taken into a difference among its factors (−μ g b / (μ a − 2b) → μ g b / (2b − μ a)). The same value;
    None where neither applies."""
    if not (isinstance(product, sp.Mul) and product.is_commutative):
        return None
    factors, flips = list(product.args), 0  # (each factor negated negates the product)

    def negate(n: int) -> None:
        nonlocal flips
        base, exponent = factors[n].as_base_exp()
        factors[n], flips = sp.Pow(-base, exponent), flips + 1

    for n, factor in enumerate(factors):
        base = _sum_in(factor)
        if base is not None and all(t.could_extract_minus_sign() for t in base.args):
            negate(n)
    if product.could_extract_minus_sign() != (flips % 2 == 1):  # written with a minus so far
        at = next((n for n, factor in enumerate(factors) if _difference(factor)), None)
        if at is not None:
            negate(at)
    if not flips:
        return None
    if flips % 2:  # the product's own sign changes with them: in its number, or a −1 of its own
        at = next((n for n, factor in enumerate(factors) if factor.is_Number), None)
        if at is None:
            factors.insert(0, sp.S.NegativeOne)
        else:
            factors[at] = -factors[at]
    return sp.Mul(*(f for f in factors if f != 1), evaluate=False)


def as_written(expr: sp.Basic) -> sp.Basic:
    """``expr`` with its signs where ``Printer`` writes them (``_signs_as_written``; the same value): what a sum,
    a product or a vector's components must ask whether it prints with a minus (x (−a − b) prints −x (a + b))."""
    signed = _signs_as_written(expr)
    return expr if signed is None else signed


class Printer(LatexPrinter):
    """sympy's LaTeX as a person writes it: a product's coefficients μ and e and its masses first, the weight
    m g (``_weight_as_written``); its square roots under one sign (``_roots_together``); its signs where a
    person puts them (``_signs_as_written``); a sum that would open with a minus, its positive terms first.
    Every derivation step, balance law and numeric template prints through it (``latex``)."""

    def __init__(self, settings=None):
        super().__init__(settings)
        self._order = self._settings["order"]

    def _print_Mul(self, expr):
        together = _roots_together(expr)
        if together is not None:
            return self._print(together)
        signed = _signs_as_written(expr)
        if signed is not None:
            return self._print(signed)
        if expr.could_extract_minus_sign() and _weight_as_written(-expr) is not None:
            return "- " + self._print(-expr)  # (as sympy writes a negative product: its sign, then the rest)
        written = _weight_as_written(expr)
        entry = self._settings["order"]
        # that product's factors as written ("none"); each factor, and any other product, in sympy's order
        self._settings["order"] = self._order if written is None else "none"
        try:
            return super()._print_Mul(expr if written is None else written)
        finally:
            self._settings["order"] = entry

    def _needs_mul_brackets(self, expr, first=False, last=False) -> bool:
        return super()._needs_mul_brackets(as_written(expr), first, last)  # (a factor that prints with a minus)

    def _as_ordered_terms(self, expr, order=None):
        entry = self._settings["order"]
        self._settings["order"] = self._order  # a sum inside a product written as it is: in sympy's order
        try:
            terms = super()._as_ordered_terms(expr, order=order)
        finally:
            self._settings["order"] = entry
        if not isinstance(expr, sp.Add):
            return terms
        terms = [as_written(term) for term in terms]  # each term's sign as it prints: + x (−a − b) is − x (a + b)
        if not (terms and terms[0].could_extract_minus_sign()):
            return terms
        # a sum that would open with a minus, as a person writes it: its positive terms first (stable: sympy's
        # order kept within each kind): s − d_cm, not −d_cm + s; m_b l² + 12 m_b s² − e m_s l²; with the numbers
        # put in, 2.062 − 2.021. A sum that opens with a plus keeps sympy's order (9 sin²θ − 6 sin θ sin θ₀ + 1).
        return sorted(terms, key=lambda term: term.could_extract_minus_sign())


def latex(expr, **settings) -> str:
    """``sp.latex`` through ``Printer``."""
    return Printer(settings).doprint(expr)


def latex_eq(lhs: sp.Expr, rhs: sp.Expr, **kw) -> str:
    return latex(sp.Eq(lhs, rhs, evaluate=False), **kw)


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
        self._made_of = (dict(symbols), dict(dimensions), self.steps, tuple(chain), dict(labels or {}))
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
            template = Printer({"symbol_names": names, "mul_symbol": "dot"}).doprint(link.expr)
            slots = tuple(
                (names[s], known[s], _only_inside_trig(link.expr, s)) for s in free
            )
            self._templates.append((link, latex(link.symbol), template, slots))
            known[link.symbol] = link.name
            self._dimensions[link.name] = link.dimension
        self._results = {link.name for link in self.chain}

    def __reduce__(self):
        """Pickled as what it is made of (solvers.kept): its compiled code is compiled again on loading."""
        return _made_again, self._made_of

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
            text = _SIGNED_NUMBER.sub(lambda m: ("- " if m[1] == "+" else "+ ") + m[2], text)
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


def _made_again(*made_of) -> Derivation:
    """A pickled derivation (``Derivation.__reduce__``), its expressions loaded as they were written
    (solvers.kept loads with sympy's evaluation off), compiled with it on."""
    with sp.evaluate(True):
        return Derivation(*made_of)
