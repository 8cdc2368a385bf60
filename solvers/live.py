"""Live values while a control is dragged: one JavaScript function per problem (and option), generated
from the solver's own sympy derivation, never typed by hand.

A problem opts in with ``LIVE = Live(follows, cases)`` in ``solvers/<pid>.py``: ``follows``, the
parameters whose controls the browser follows while they are dragged; ``cases(**options)``, the
regimes in order (the first whose ``when`` holds is the one), each with the ``Derivation`` whose
chain gives its values. A case without values (``values=False``) is a physical limit or a refusal:
the page marks the answers as waiting for the server. A chain link that needs an input the browser
does not have (an integral evaluated by quadrature) is left out, and its answers marked too.

``function_source(pid, options)`` turns that into the source of a JavaScript arrow function
``(p) => ({regime, values})`` (``p``: every parameter in SI, by name): for each case, its chain's
links as constants (``sympy.cse`` over the chain, ``sympy.printing.jscode``), then its condition.
The links are evaluated in the chain's order, as ``Derivation.evaluate`` does, so the browser's
numbers are the server's to a few units in the last place (tests/pages/test_live.py: 1e-9 relative).
Before the cases, the followed parameters' valid ranges (``Number.low``/``high``) are tested: a
value the solver would refuse gives the regime ``"refused"`` and no values.
"""
from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass, field
from typing import Callable, Mapping

import numpy as np
import sympy as sp
from sympy.printing.jscode import JavascriptCodePrinter

from . import registry, units
from .derivation import Derivation
from .formatting import GROUPED_BELOW
from .kept import kept_on_disk
from .specs import Choice, Number

REFUSED = "refused"


@dataclass(frozen=True)
class Stops:
    """A condition no closed form gives: ``expr`` (in the parameters and ``var``) is ≤ 0 somewhere on
    ``numpy.linspace(low, high, points)[1:]`` (e.g. the spring's rod stopping before θ₂, found on the
    solver's own grid)."""

    expr: sp.Expr
    var: sp.Symbol
    low: sp.Expr
    high: sp.Expr
    points: int


@dataclass(frozen=True)
class Case:
    """One regime: its name (``Solution.regime``'s word, or a limit's), what the live view says
    when a drag enters it, the derivation that gives its values (and its condition's results), the
    condition (sympy, in the parameters and that derivation's result symbols; or ``Stops``), and the
    chain's extra inputs as expressions in the parameters (the disk's slip direction)."""

    regime: str
    said: str
    derivation: Derivation | None = None
    when: object = sp.true
    inputs: Mapping[str, sp.Expr] = field(default_factory=dict)
    values: bool = True


@dataclass(frozen=True)
class Event:
    """A time a motion's frames depend on that no closed form gives (the stick swinging round into the
    bounced ball): the first instant in (0, ``until``] where ``crossing(p, a, t, xp)`` is below 0, on a
    grid of ``points`` steps, then to 1e-12 s; infinite where it never is, or where ``applies(p)`` (the
    options) is false. ``first_crossing`` finds it on the server (numpy, brentq), live.js's
    ``firstCrossing`` in the browser from the same functions generated (ui/live.py: motion_source)."""

    name: str
    crossing: Callable
    until: Callable
    points: int
    applies: Callable = lambda p: True


def first_crossing(event: Event, p: Mapping, a: Mapping) -> float:
    """``event``'s time for parameters ``p`` and answers ``a`` (numpy on the grid, brentq between its points)."""
    from scipy.optimize import brentq

    if not event.applies(p):
        return float("inf")
    t = np.linspace(0.0, float(event.until(p, a, np)), event.points + 1)[1:]
    below = np.nonzero(np.asarray(event.crossing(p, a, t, np)) < 0)[0]
    if not len(below):
        return float("inf")
    i = below[0]
    if i == 0:
        return float(t[0])
    return float(brentq(lambda q: float(np.ravel(event.crossing(p, a, q, np))[0]), t[i - 1], t[i], xtol=1e-12))


@dataclass(frozen=True)
class Leg:
    """One leg of a motion integrated in the browser (``Integrated``): it ends where ``ends(p, a, y, xp)``
    (``y``: the state, by the names ``Integrated.state`` gives) falls through zero from above; ``then``,
    the state the next leg starts from (an impact: ``(p, a, y, xp) -> y``), else the same; ``framed``, its
    end a frame of its own (an impact the animation must show); ``last(p, a, y, xp)``, true where the motion
    ends with it, ``y`` its end (e = 0: the sphere stays against the floor); ``opens``, the frames start at
    its end, not at t = 0 (a release that creeps unseen: the spring's rod nudged at upright)."""

    name: str
    ends: Callable
    then: Callable | None = None
    framed: bool = False
    last: Callable = lambda p, a, y, xp: False
    opens: bool = False


@dataclass(frozen=True)
class Integrated:
    """A motion no closed form gives, integrated in the browser from the solver's own equation of motion
    (issue 51): the state's names, ``start(p, a, xp)`` and ``rates(p, a, y, xp)`` (dy/dt), the legs in
    order, each at most ``horizon(p, a, xp)`` long, by an adaptive Dormand–Prince step to ``tolerances``
    (rtol, atol) with each leg's end found on the step by the Illinois method (live.js: ``integrated``).
    The frames: instants evenly over the motion (``frame_count``; from the end of a leg that ``opens`` it,
    else from t = 0), and each framed leg's end; a dense
    curve of ``curve`` such instants for a plot against time. The solver's own Python motion stays the
    reference (tests/pages/test_live.py compares the two)."""

    state: tuple[str, ...]
    start: Callable
    rates: Callable
    legs: tuple[Leg, ...]
    horizon: Callable
    frames: int
    curve: int = 0
    tolerances: tuple[float, float] = (1e-10, 1e-12)
    fastest: Callable | None = None  # (p, a, xp): the drawn angle's largest rate, |θ̇| (rad/s)
    turn: float = math.radians(8.0)  # the most that angle may turn from one frame to the next
    most: int = 300  # frames at most

    def frame_count(self, p, a, duration: float) -> int:
        """``frames``, or more where the angle would turn more than ``turn`` between two (a long swing
        from near upright: 60 frames over 11 s jumped 67° at a time), up to ``most``; live.js counts alike."""
        if self.fastest is None:
            return self.frames
        return int(max(self.frames, min(self.most, math.ceil(duration * float(self.fastest(p, a, np)) / self.turn) + 1)))


SAME_INSTANT = 1e-6  # of the span: an even instant this near a framed leg's end is that end


def frame_instants(begin: float, end: float, count: int, framed) -> np.ndarray:
    """An integrated motion's frames (``Integrated``): ``count`` instants evenly from ``begin`` to ``end``, and each
    framed leg's end, in order; an even instant within SAME_INSTANT of the span of a framed end is that end (the
    turn of a swing mirrored about it is its middle instant; a bounce at equal intervals may fall on one), so two
    integrations of the same motion, which agree on the instants to their tolerance, have the same frames where
    exact equality would tell their roundings apart. (Relative: the same in any unit of time.) live.js's
    ``instants`` alike."""
    times = list(np.linspace(begin, end, count))
    near = SAME_INSTANT * (end - begin)
    for t in framed:
        i = int(np.argmin(np.abs(np.asarray(times[:count]) - t)))
        if abs(times[i] - t) <= near:
            times[i] = t
        else:
            times.append(t)
    return np.unique(times)


@dataclass(frozen=True)
class Live:
    follows: tuple[str, ...]
    cases: Callable[..., tuple[Case, ...]]


def declared(pid: str) -> Live | None:
    return getattr(registry.solver(pid), "LIVE", None)


class _Printer(JavascriptCodePrinter):
    """sympy's JavaScript with every number a double literal (1/2 stays 1/2: JS divides in floats)."""

    def _print_Float(self, expr):
        return repr(float(expr))

    def _print_NaN(self, expr):  # a gap in a drawn polyline (a pose's arrow of no length)
        return "NaN"

    def _print_Function(self, expr):
        if isinstance(expr, _Rounded):
            return f"round({self._print(expr.args[0])})"
        return super()._print_Function(expr)


def _js(expr, printer=_Printer()) -> str:
    return printer.doprint(expr)


def _safe(prefix: str, name: str) -> str:
    return prefix + re.sub(r"\W", "_", name)


def _range_condition(param: Number, sym: sp.Symbol) -> sp.Basic:
    parts = []
    if param.low is not None:
        parts.append(sym >= param.low if param.low_inclusive else sym > param.low)
    if param.high is not None:
        parts.append(sym <= param.high if param.high_inclusive else sym < param.high)
    bounds = param.model_bounds()  # the magnitudes the model is meant for (validate_params refuses the rest)
    if bounds:
        parts.append(sp.Or(sp.Eq(sym, 0), sp.And(sp.Abs(sym) >= bounds[0], sp.Abs(sym) <= bounds[1]))
                     if not param.allow_inf else sp.Or(sp.Eq(sym, 0), sp.Eq(sym, sp.oo),
                                                      sp.And(sp.Abs(sym) >= bounds[0], sp.Abs(sym) <= bounds[1])))
    return sp.And(*parts)


def _case_block(case: Case, params: Mapping[str, sp.Symbol]) -> str:
    """A JS block: the case's chain evaluated (links whose inputs the browser lacks left out), then
    its condition; returns when it holds."""
    names = {sym: _safe("p_", name) for name, sym in params.items()}
    lines, known = [], dict(names)
    for name, expr in case.inputs.items():
        sym = case.derivation.symbols[name] if case.derivation else sp.Symbol(name)
        known[sym] = _safe("i_", name)
        lines.append(f"const {known[sym]} = {_js(expr.xreplace({s: sp.Symbol(n) for s, n in names.items()}))};")
    links = []
    for link in (case.derivation.chain if case.derivation else ()):
        if link.expr.free_symbols <= set(known):
            known[link.symbol] = _safe("r_", link.name)
            links.append(link)
    rename = {s: sp.Symbol(n) for s, n in known.items()}
    exprs = [link.expr.xreplace(rename) for link in links]
    when = case.when
    stops = None
    if isinstance(when, Stops):
        stops, when = when, sp.true
    for n, (link, expr) in enumerate(zip(links, exprs)):  # each link's own subexpressions, in the chain's order
        replacements, (reduced,) = sp.cse(expr, symbols=sp.numbered_symbols(f"c{n}_"), order="none")
        lines += [f"const {s} = {_js(e)};" for s, e in replacements]
        lines.append(f"const {rename[link.symbol]} = {_js(reduced)};")
    test = _js(when.xreplace(rename)) if when is not sp.true else "true"
    if stops is not None:
        var = _safe("v_", stops.var.name)
        inner = _js(stops.expr.xreplace(rename | {stops.var: sp.Symbol(var)}))
        low, high = _js(stops.low.xreplace(rename)), _js(stops.high.xreplace(rename))
        # numpy.linspace: low + i·(high − low)/(n − 1), its last point exactly high
        lines.append(f"let stops = false;\nfor (let i = 1; i < {stops.points} && !stops; i++) {{\n"
                     f"  const {var} = i === {stops.points - 1} ? {high} : {low} + i * (({high}) - ({low})) / {stops.points - 1};\n"
                     f"  if (!({inner} > 0)) stops = true;\n}}")
        test = "stops"
    values = ("{" + ", ".join(f"{n!r}: {known[link.symbol]}" for link in links for n in [link.name]) + "}"
              if case.values else "null")
    lines.append(f"if ({test}) return {{regime: {case.regime!r}, values: {values}}};")
    return "{\n" + "\n".join("  " + line for line in "\n".join(lines).split("\n")) + "\n}"


@functools.lru_cache(maxsize=64)
def cases(pid: str, options: tuple[tuple[str, str], ...] = ()) -> tuple[Case, ...]:
    """Problem ``pid``'s regimes for its options, made once: building them is sympy work (the spring's
    simplifies an expression, about 16 ms), which a page's run must not repeat."""
    return registry.solver(pid).LIVE.cases(**dict(options))


@functools.lru_cache(maxsize=64)
@kept_on_disk
def function_source(pid: str, options: tuple[tuple[str, str], ...] = ()) -> str:
    """The generated function for problem ``pid`` with its options (``(name, value)`` pairs of its
    ``Choice`` parameters, sorted), as JavaScript source: ``(p) => ({regime, values})``."""
    solver = registry.solver(pid)
    live = solver.LIVE
    numbers = {p.name: p for p in solver.PARAMS if isinstance(p, Number)}
    params = {name: sym for name, sym in solver.SYMBOLS.items() if name in numbers}
    head = [f"const {_safe('p_', name)} = p[{name!r}];" for name in params]
    # on symbols without the solver's assumptions (a positive e would make e ≥ 0 vanish)
    valid = sp.And(*(_range_condition(numbers[name], sp.Symbol(_safe("p_", name))) for name in live.follows))
    finite = [f"Number.isFinite({_safe('p_', n)})" if not numbers[n].allow_inf else f"!Number.isNaN({_safe('p_', n)})"
              for n in live.follows]  # an emptied box (NaN) is refused too
    head.append(f"if (!({' && '.join(finite)} && {_js(valid)})) return {{regime: {REFUSED!r}, values: null}};")
    blocks = [_case_block(case, params) for case in cases(pid, options)]
    body = "\n".join(["  " + line for line in head] + blocks)
    return f"(p) => {{\n{body}\nreturn {{regime: {REFUSED!r}, values: null}};\n}}"


@functools.lru_cache(maxsize=256)
def leads(pid: str, options: tuple[tuple[str, str], ...], regime: str, names: tuple[str, ...]) -> dict[str, int]:
    """For each followed parameter, the answer the stage's headline shows while its control is dragged:
    the first of ``names`` (the page's answers, in order) whose link in this regime's chain depends on
    it, through the links before it (the first answer where none does). What is in view while a
    control moves is what that control changes."""
    solver = registry.solver(pid)
    found = [c for c in cases(pid, options) if c.derivation is not None]
    case = next((c for c in found if c.regime == regime), found[0] if found else None)
    if case is None:
        return {}
    names_of = {sym: {name} for name, sym in solver.SYMBOLS.items()}
    depends: dict[sp.Symbol, set] = {}

    def on(expr) -> set:
        return set().union(*(depends[s] if s in depends else names_of.get(s, set()) for s in expr.free_symbols))
    for name, expr in case.inputs.items():
        depends[case.derivation.symbols[name]] = on(expr)
    by_answer = {}
    for link in case.derivation.chain:
        depends[link.symbol] = by_answer[link.name] = on(link.expr)
    return {p: next((i for i, n in enumerate(names) if p in by_answer.get(n, ())), 0) for p in solver.LIVE.follows}


def options_of(pid: str, params: Mapping[str, object]) -> tuple[tuple[str, str], ...]:
    return tuple(sorted((p.name, params[p.name]) for p in registry.solver(pid).PARAMS if isinstance(p, Choice)))


def payload(pid: str, params: Mapping[str, object], answers, system: str, control_keys: Mapping[str, str]) -> dict:
    """What the page's live module needs besides the generated function (``function_source``, which
    ui/live.py serves as a module of its own): the parameters now (SI), the
    followed controls (their Streamlit keys and the factor from what they show to SI), the answers'
    rows (name, unit shown, factor from SI, angle?) and the regimes' words. Units come from
    ``solvers.units`` and the number format's constants from ``solvers.formatting``."""
    solver = registry.solver(pid)
    live = solver.LIVE
    options = options_of(pid, params)
    numbers = {p.name: p for p in solver.PARAMS if isinstance(p, Number)}
    follows = [[name, control_keys[name], units.to_display(1.0, numbers[name].dimension, system)]
               for name in live.follows if name in control_keys]
    rows = [[a.name, units.unit(a.dimension, system), units.to_display(1.0, a.dimension, system),
             a.dimension == "angle", a.label] for a in answers]
    said = {case.regime: case.said for case in cases(pid, options)}
    return {"params": dict(params), "follows": follows,
            "answers": rows, "said": said, "grouped_below": GROUPED_BELOW}


# ------------------------------------------------------------------ the figure's pose at its key instant
# A viz module draws its stage figure's key instant with ``key_pose(params, answers, system, xp)``:
# numpy (``xp=np``) for the figure, and here the same function on symbols (``xp=SYMBOLIC``, arrays of
# expressions: dtype object) gives each point of each moving body as an expression in the parameters
# and the live values, printed to JavaScript as the values are (``sympy.cse``, the same printer).

def _elementwise(fn, nargs: int):
    return np.frompyfunc(fn, nargs, 1)


class _Symbolic:
    """The few numpy functions the figures' shapes use (viz.common: ``arrows``, ``xp=``), on arrays
    of sympy expressions."""

    cos = staticmethod(_elementwise(sp.cos, 1))
    sqrt = staticmethod(_elementwise(sp.sqrt, 1))
    log = staticmethod(_elementwise(sp.log, 1))
    degrees = staticmethod(_elementwise(lambda a: a * 180 / sp.pi, 1))
    sin = staticmethod(_elementwise(sp.sin, 1))
    abs = staticmethod(_elementwise(sp.Abs, 1))
    hypot = staticmethod(_elementwise(lambda a, b: sp.sqrt(a**2 + b**2), 2))
    minimum = staticmethod(_elementwise(sp.Min, 2))
    maximum = staticmethod(_elementwise(sp.Max, 2))
    less = staticmethod(_elementwise(lambda a, b: sp.StrictLessThan(a, b), 2))
    # rounded as viz.common.r rounds (numpy's round to DIGITS): the pose function's ``round`` argument
    rounded = staticmethod(_elementwise(lambda a: _Rounded(a), 1))
    # a gap (NaN) where the condition holds: a Piecewise (the printer's ternary)
    where = staticmethod(_elementwise(lambda c, a, b: sp.Piecewise((_expr(a), c), (_expr(b), True)), 3))

    @staticmethod
    def scalar(x):
        """One value as the shapes take it: an array of one expression."""
        return np.array([x], dtype=object)


class _Rounded(sp.Function):
    """A value rounded as the figure's coordinates are (printed as a call of the pose's ``round``)."""


SYMBOLIC = _Symbolic()


def _expr(x):
    return sp.nan if isinstance(x, float) and np.isnan(x) else sp.sympify(x, strict=True)  # numbers and expressions only, never text


class _Values(dict):
    """The live values by name (``answers`` for a pose): a symbol for each name asked for."""

    def __missing__(self, name: str) -> sp.Symbol:
        self[name] = sym = sp.Symbol(_safe("v_", name))
        return sym


TIME = sp.Symbol("t", real=True)  # a pose at a time: the generated function's argument ``t``


def pose_source(key_pose: Callable, params: Mapping[str, object], system: str, at_time: bool = False,
                unbounded: tuple[str, ...] = ()) -> str:
    """The JavaScript of ``key_pose`` (a viz module's) for these options: ``(p, v, round) => ({trace:
    [xs, ys]}) | null`` (``p``: the parameters in SI, ``v``: the live function's values; null if one
    it uses is not a finite number; ``round``: the figure's rounding, for a shape drawn from rounded
    numbers, a spring's turns). Numbers in ``params`` are symbols, options (strings) as given. With
    ``at_time``, a pose at any time (a viz module's ``pose_at``, called with ``TIME`` last):
    ``(p, v, round, t) => ...``. ``unbounded``: values that may be infinite (an ``Event`` never reached)."""
    symbols = {name: sp.Symbol(_safe("p_", name)) if not isinstance(value, str) else value
               for name, value in params.items()}
    values = _Values()
    drawn = key_pose(symbols, values, system, SYMBOLIC, *((TIME,) if at_time else ()))
    cells = []  # every coordinate: an expression, or a number (a gap is NaN)
    shapes = {}
    for name, coords in drawn.items():
        rows = [list(np.ravel(np.asarray(c, dtype=object))) for c in coords]
        shapes[name] = [(len(cells) + sum(map(len, rows[:i])), len(row)) for i, row in enumerate(rows)]
        cells += [c for row in rows for c in row]
    exprs = [sp.sympify(c, strict=True) for c in cells]  # the viz's numbers and expressions: never text
    replacements, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("c_"), order="none")
    used = set().union(*(e.free_symbols for e in exprs))
    inputs = ([(sym, f"p[{name!r}]") for name, sym in symbols.items() if isinstance(sym, sp.Symbol) and sym in used]
              + [(sym, f"v[{name!r}]") for name, sym in values.items() if sym in used])
    lines = [f"const {sym} = {source};" for sym, source in inputs]
    if inputs:
        finite = [f"!Number.isNaN({sym})" if str(sym) in {_safe("v_", n) for n in unbounded} else f"Number.isFinite({sym})"
                  for sym, _ in inputs]
        lines.append(f"if (!({' && '.join(finite)})) return null;")
    lines += [f"const {s} = {_js(e)};" for s, e in replacements]

    def cell(e) -> str:
        return "null" if e is sp.nan else repr(float(e)) if e.is_number and not e.has(sp.Piecewise) else _js(e)

    body = ", ".join(f"{name!r}: [" + ", ".join("[" + ", ".join(cell(reduced[i]) for i in range(start, start + n)) + "]"
                                            for start, n in parts) + "]" for name, parts in shapes.items())
    lines.append(f"return {{{body}}};")
    return f"(p, v, round{', t' if at_time else ''}) => {{\n" + "\n".join("  " + line for line in lines) + "\n}"


def integrated_source(spec: Integrated, params: Mapping[str, object], system: str) -> str:
    """``spec`` as the JavaScript object live.js's ``integrated`` reads: each of its functions generated as
    a pose is (``pose_source``: ``(p, v, round) => ({y: [[numbers]]})``), the state among the values by its
    names (``v.theta``); a leg that appears more than once, defined once."""
    def generated(fn, of_state: bool = True) -> str:
        def rows(p, a, system, xp):
            out = fn(p, a, {name: a[name] for name in spec.state}, xp) if of_state else fn(p, a, xp)
            out = [out[name] for name in spec.state] if isinstance(out, Mapping) else [out]
            return {"y": (np.array(out, dtype=object),)}
        return pose_source(rows, params, system)

    def ends_there(leg):  # the leg's ``last`` as a number the printer writes: 1 where the motion ends
        return lambda p, a, y, xp: sp.Piecewise((1, sp.sympify(leg.last(p, a, y, xp))), (0, True))
    legs = list(dict.fromkeys(spec.legs))  # each once, in order
    defined = []
    for leg in legs:
        then = generated(leg.then) if leg.then is not None else "null"
        defined.append(f"{{name: {leg.name!r}, framed: {str(leg.framed).lower()}, opens: {str(leg.opens).lower()}, "
                       f"ends: {generated(leg.ends)}, "
                       f"then: {then}, last: {generated(ends_there(leg))}}}")
    return (f"(() => {{\n  const legs = [{', '.join(defined)}];\n"
            f"  return {{state: {list(spec.state)!r}, frames: {spec.frames}, curve: {spec.curve}, turn: {spec.turn!r}, "
            f"most: {spec.most}, fastest: {generated(spec.fastest, of_state=False) if spec.fastest else 'null'},\n"
            f"    "
            f"tolerances: [{spec.tolerances[0]!r}, {spec.tolerances[1]!r}],\n"
            f"    start: {generated(spec.start, of_state=False)},\n    rates: {generated(spec.rates)},\n"
            f"    horizon: {generated(spec.horizon, of_state=False)},\n"
            f"    legs: [{', '.join(f'legs[{legs.index(leg)}]' for leg in spec.legs)}]}};\n}})()")
