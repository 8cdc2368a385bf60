"""Free-body diagrams as data: the course's Step 2, declared once per problem and phase.

The worked solutions solve every problem in four steps: (1) origin, coordinates and basis, the
kinematics; (2) the free-body diagram; (3) the balance laws written from that diagram; (4) the
analysis. Here a problem module declares its diagrams (``free_body_diagrams(params)``, one per phase the
derivation uses: an impact's instant, a swing, the ladder against the wall…) as plain data:

- each ``Body`` isolated: its named points (positions in the basis, sympy expressions in the
  solver's symbols), its outline, its mass centre, the point moments are taken about, and the
  kinetic side of its balance laws (m a_G and the rate of change of angular momentum, or for an
  impact the changes of momentum and of angular momentum);
- each ``Load`` on it: a force, an impulse or a couple, with its symbol as the derivation writes it,
  the point where it acts, what exerts it, and its direction (a unit vector in the solver's symbols)
  and size, or, for a reaction whose direction the physics leaves open, its two components.

Step 2's text and Step 3's balance laws are generated from these declarations (``fbd_steps``,
``balance_steps``, ``balance``), so a force cannot be drawn and missing from the equations; every
drawing (the page's SVG, the stage's force arrows, TikZ, matplotlib) reads the same data through
``viz.diagram``. ``Diagram.values(solution)`` gives every symbol's number at the instant drawn,
computed by the solver's own physics; the tests put those numbers into the balance laws.

Plane problems only: vectors are (x, y) in the basis, moments their E_z components.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import Callable, Mapping

import sympy as sp

from .derivation import latex
from .solution import Step

KINDS = ("force", "impulse", "couple")

Vector = tuple[sp.Expr, sp.Expr]


@dataclass(frozen=True)
class Circle:
    """A round outline (a disk, a sphere, a wheel) about a named point."""

    centre: str
    radius: sp.Expr


@dataclass(frozen=True)
class Rod:
    """A slender straight outline between two named points."""

    ends: tuple[str, str]


@dataclass(frozen=True)
class Outline:
    """A closed polygon through named points (a cart's body)."""

    corners: tuple[str, ...]


@dataclass(frozen=True)
class Load:
    """A force, an impulse or a couple on one body.

    ``symbol``: LaTeX as the derivation writes it (``N_A``, ``m g``, ``P_n``). ``name``: in words,
    ``by``: what exerts it ("the wall"). ``at``: the point where it acts (a name of its body's
    ``points``; empty for a couple). Its vector is ``size`` times the unit ``direction`` (both sympy,
    in the solver's symbols: a normal force is ``N`` along the surface's normal into the body,
    gravity ``m g`` along −E_y); a reaction whose direction the physics leaves open has
    ``direction=None`` and ``components`` (its x and y symbols), and is drawn as the two. A couple's
    ``size`` is its E_z component (counter-clockwise +). ``pair``: the name of the opposite load on
    the other body of an interaction pair (both labelled by their magnitude, drawn opposite)."""

    symbol: str
    name: str
    by: str
    on: str
    at: str = ""
    kind: str = "force"
    direction: Vector | None = None
    size: sp.Expr = sp.Integer(0)
    components: tuple[sp.Expr, sp.Expr] = ()
    pair: str = ""

    @property
    def unknown_direction(self) -> bool:
        return self.kind != "couple" and self.direction is None

    @property
    def vector(self) -> Vector:
        """The load's (x, y) components (a couple: (0, 0))."""
        if self.kind == "couple":
            return (sp.Integer(0), sp.Integer(0))
        if self.direction is None:
            return tuple(self.components)
        return (self.size * self.direction[0], self.size * self.direction[1])


@dataclass(frozen=True)
class Body:
    """One body isolated: its points, outline, mass centre, moment point and kinetic side.

    ``kinetic`` is the right-hand side of its three balance laws, (x, y, moment about ``about``):
    for forces m a_Gx, m a_Gy and the rate of change of the angular momentum about ``about``; for
    an impulse m Δv_Gx, m Δv_Gy and the change of the angular momentum about ``about``.
    ``kinetic_latex`` writes each as the derivation does (``m\\ddot{x}_G``). A body at rest along a
    direction has 0 there. A point whose name starts with "_" only shapes the outline (a corner): it
    is neither marked nor named in the drawing."""

    name: str
    points: Mapping[str, Vector]
    centre: str
    about: str
    kinetic: tuple[sp.Expr, sp.Expr, sp.Expr]
    kinetic_latex: tuple[str, str, str]
    outline: tuple[Circle | Rod | Outline, ...] = ()


@dataclass(frozen=True)
class Diagram:
    """The free-body diagram of one phase: its bodies and the loads on them.

    ``phase``: a short key ("impact", "swing"); ``title``: in words ("At the impact"). ``law``:
    "force" (Newton–Euler: ΣF = m a_G, ΣM = Ḣ) or "impulse" (ΣP = m Δv, ΣM = ΔH). ``basis``: the
    LaTeX of the two unit vectors. ``values(solution)``: every symbol of the declarations at the
    instant drawn, as numbers from the solver's own physics (parameters included)."""

    phase: str
    title: str
    law: str
    bodies: tuple[Body, ...]
    loads: tuple[Load, ...]
    values: Callable[[object], Mapping[sp.Symbol, float]]
    basis: tuple[str, str] = (r"\mathbf{E}_x", r"\mathbf{E}_y")
    note: str = ""  # one sentence on what is left out and why ("gravity is negligible against the impulse")
    # Every symbol's value at each frame of ``motion(solution)`` (numpy arrays, one value per frame;
    # NaN in the frames outside this phase), for the stage's Forces overlay; None: not drawn there.
    frames: Callable[[object, Mapping], Mapping[sp.Symbol, object]] | None = None
    # The symbols at the stage figure's key frame (the impact, θ₂…) from the parameters ``p`` and the
    # answers ``a``: numbers, or solvers.live's symbols, when the browser poses the overlay while a
    # control is dragged (only answers the problem's live values give). None: no load at that frame.
    key: Callable[[Mapping, Mapping], Mapping[sp.Symbol, object]] | None = None

    def body(self, name: str) -> Body:
        return next(b for b in self.bodies if b.name == name)

    def loads_on(self, body: str) -> tuple[Load, ...]:
        return tuple(load for load in self.loads if load.on == body)


@dataclass(frozen=True)
class DiagramSlip:
    """A classic slip in drawing a problem's diagram, declared beside its answers' slips (MISTAKES):
    a load the physics does not put there, as a student draws it. ``key`` names the slip ("force of
    motion", "centripetal force", "friction on a smooth wall"); ``message`` is the tutor's words
    (never the diagram's answer). It matches a drawn load that no declared load accounts for, on
    ``on`` (a body's name; "" any), at ``at`` (a named point; "" anywhere on the body), of one of
    ``kinds``, along ``direction`` (a unit vector in the solver's symbols, within the judge's
    tolerance; ``either_way``: its opposite too; None: any direction)."""

    key: str
    message: str
    on: str = ""
    at: str = ""
    kinds: tuple[str, ...] = ("force", "impulse")
    direction: Vector | None = None
    either_way: bool = False
    phase: str = ""  # the diagram it belongs to ("" every diagram of the problem)


class Numbers(dict):
    """Every expression of a diagram evaluated at once (``numbers``): expression -> float."""


_COMPILED: dict[int, tuple] = {}  # id(diagram) -> (the diagram, its expressions, their function)


def _expressions(diagram: Diagram) -> list:
    out = []
    for body in diagram.bodies:
        out += [c for point in body.points.values() for c in point]
        out += [shape.radius for shape in body.outline if isinstance(shape, Circle)]
    for load in diagram.loads:
        out += [load.size, *(load.direction or ()), *load.components]
    return [sp.sympify(e) for e in out]


def numbers(diagram: Diagram, values) -> Numbers:
    """Every expression the drawing reads, at ``values``, by one function compiled once per diagram
    (sympy's ``subs`` on each cost a new state some 10 ms)."""
    compiled = _COMPILED.get(id(diagram))
    if compiled is None or compiled[0] is not diagram:
        exprs = list(dict.fromkeys(_expressions(diagram)))
        free = sorted(set().union(*(e.free_symbols for e in exprs)), key=lambda s: s.name)
        compiled = (diagram, exprs, free, sp.lambdify(free, exprs, modules="math"))
        if len(_COMPILED) > 512:
            _COMPILED.clear()
        _COMPILED[id(diagram)] = compiled
    _, exprs, free, fn = compiled
    return Numbers(zip(exprs, (float(x) for x in fn(*(float(values[s]) for s in free)))))


def value_at(expr, nums: Numbers) -> float:
    """A declared expression (or a plain number) at ``numbers``' values."""
    return float(expr) if isinstance(expr, (int, float)) else nums[sp.sympify(expr)]


def signed_direction(load: Load, nums: Numbers) -> tuple[float, float]:
    """A load of declared direction: its direction's components at ``numbers``' values, reversed where its
    size is negative (the way it really acts there; not normalised)."""
    x, y = (value_at(c, nums) for c in load.direction)
    return (-x, -y) if value_at(load.size, nums) < 0 else (x, y)


def _cross(r: Vector, f: Vector) -> sp.Expr:
    return r[0] * f[1] - r[1] * f[0]


_RESULTANTS: dict[tuple[int, str], tuple] = {}  # (id(diagram), body) -> (the diagram, its sums): simplified once


def resultant(diagram: Diagram, body: str) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    """The sums of the declared loads on ``body``: (ΣF_x, ΣF_y, ΣM about the body's ``about``)."""
    kept = _RESULTANTS.get((id(diagram), body))
    if kept is None or kept[0] is not diagram:
        kept = (diagram, _summed(diagram, body))
        if len(_RESULTANTS) > 256:
            _RESULTANTS.clear()
        _RESULTANTS[(id(diagram), body)] = kept
    return kept[1]


def _summed(diagram: Diagram, body: str) -> tuple[sp.Expr, sp.Expr, sp.Expr]:
    b = diagram.body(body)
    ref = b.points[b.about]
    fx = fy = moment = sp.Integer(0)
    for load in diagram.loads_on(body):
        if load.kind == "couple":
            moment += load.size
            continue
        vx, vy = load.vector
        fx, fy = fx + vx, fy + vy
        at = b.points[load.at]
        moment += _cross((at[0] - ref[0], at[1] - ref[1]), (vx, vy))
    return tuple(sp.simplify(s) for s in (fx, fy, moment))


def balance(diagram: Diagram, body: str) -> tuple[sp.Eq, sp.Eq, sp.Eq]:
    """The balance laws of ``body`` written from its declared loads: Σ = the kinetic side."""
    b = diagram.body(body)
    return tuple(sp.Eq(s, k, evaluate=False) for s, k in zip(resultant(diagram, body), b.kinetic))


def _axis(unit_vector: str) -> str:
    """A basis vector's subscript (\\mathbf{E}_x -> x), naming a component."""
    return unit_vector.rsplit("_", 1)[-1].strip("{}")


def _sum_labels(diagram: Diagram, about: str) -> tuple[str, str, str]:
    """The three sums as the balance laws write them, along the diagram's basis (an impulse's with a hat)."""
    x, y = (_axis(e) for e in diagram.basis)
    if diagram.law == "impulse":
        return (rf"\sum \hat{{P}}_{x}", rf"\sum \hat{{P}}_{y}", rf"\sum \hat{{M}}_{{{about}}}")
    return (rf"\sum F_{x}", rf"\sum F_{y}", rf"\sum M_{{{about}}}")


def _load_vector_latex(load: Load, basis: tuple[str, str]) -> str:
    """The load as a vector in the basis (a couple along E_z)."""
    if load.kind == "couple":
        return latex(load.size) + r"\,\mathbf{E}_z"
    if load.direction is None:
        pairs = list(zip(load.components, basis))
    else:
        pairs = [(sp.simplify(load.size * d), e) for d, e in zip(load.direction, basis)]
    text = ""
    for value, unit in pairs:
        if value == 0:
            continue
        term = latex(value)
        if value.could_extract_minus_sign():
            term = "-" + latex(-value) if text == "" else "- " + latex(-value)
        elif text:
            term = "+ " + term
        text += (" " if text else "") + rf"{term}\,{unit}"
    return text or "0"


def describe(load: Load) -> str:
    """The load in words, for a step's title and a drawing's text alternative."""
    kind = {"force": "a force", "impulse": "an impulse", "couple": "a couple"}[load.kind]
    where = (f" at ${load.at}$" if "_" in load.at else f" at {load.at}") if load.at else ""
    how = ", direction unknown: drawn as its two components" if load.unknown_direction else ""
    return f"{load.name} (${load.symbol}$, {kind} by {load.by}){where}{how}"


def fbd_steps(diagram: Diagram) -> tuple[Step, ...]:
    """Step 2 in words and vectors: each body isolated and every load on it (drawn beside), each
    load's vector at its point."""
    steps = []
    for n, b in enumerate(diagram.bodies):
        loads = diagram.loads_on(b.name)
        said = "; ".join(describe(l) for l in loads)
        title = (f"{diagram.title}: {b.name} isolated. " + said[:1].upper() + said[1:] + "."
                 + (f" {diagram.note}" if diagram.note and n == 0 else ""))  # (the diagram's note once, not per body)
        terms = [(rf"\text{{at }}{l.at}:\; " if l.at else "") + _load_vector_latex(l, diagram.basis) for l in loads]
        steps.append(Step(title, r",\quad ".join(terms), part=2))
    return tuple(steps)


def balance_steps(diagram: Diagram) -> tuple[Step, ...]:
    """Step 3: each body's balance laws, summed from its declared loads (nothing else in them)."""
    steps = []
    law = {"force": "Newton–Euler", "impulse": "Impulse–momentum"}[diagram.law]
    for b in diagram.bodies:
        laws = list(zip(_sum_labels(diagram, b.about), resultant(diagram, b.name), b.kinetic_latex))
        # a law with no load and nothing changing (a point ball's moments, a direction no load has) is 0 = 0:
        # said in words, not written as an equation
        idle = [label for label, total, kin in laws if total == 0 and kin.strip() == "0"]
        rows = [f"{label} = {latex(total)} = {kin}" for label, total, kin in laws if label not in idle] or [
            f"{label} = 0" for label in idle]
        about = f", moments about {b.about}"
        if idle and len(idle) < len(laws):
            about += (" (" + " and ".join(f"${label}$" for label in idle) + ": no load acts that way and nothing "
                      "changes, 0\u00a0=\u00a00)")
        steps.append(Step(f"{diagram.title}: {law} for {b.name}, from its diagram{about}", r",\quad ".join(rows), part=3))
    return tuple(steps)


def residuals(diagram: Diagram, solution) -> list[tuple[str, float, float]]:
    """Each body's three balance laws evaluated at ``diagram.values(solution)``: (law, left, right)."""
    values = diagram.values(solution)
    out = []
    for b in diagram.bodies:
        for name, eq in zip(("x", "y", "moment"), balance(diagram, b.name)):
            out.append((f"{b.name} {name}", float(eq.lhs.subs(values)), float(eq.rhs.subs(values))))
    return out
