"""Judging a free-body diagram a student drew: the drawing in, a verdict with its named problems out.

The expected diagram is the problem's own declaration (``free_body_diagrams``, solvers/diagram.py),
the one its derivation's balance laws are written from; the classic slips are the problem's
``DIAGRAM_SLIPS`` beside its answers' ``MISTAKES``. The verdict says what is wrong in a tutor's words
and never shows the diagram: a load missing ("something else touches the ladder"), one too many, one
at the wrong point, the wrong way (a normal pulling into the floor), the wrong kind (a force where an
impact gives an impulse), and the slips by name (a "force of motion", a centripetal force drawn as a
force of its own, friction on a smooth surface, the weight away from the mass centre, the other body's
load of an interaction pair).

What the physics fixes is what is judged: a load of declared direction within ``TOLERANCE_DEG``
(a normal, a weight, an impact's push); a reaction of unknown direction is right in any direction as
one load at its point, or as two perpendicular components there; a couple by its presence (its sense
comes out of the balance laws). The student's names are theirs: they are quoted back, never judged.

Python API, for a course grading diagrams outside the page (``pid``: a registered problem's id;
the drawing as the page sends it, or as ``DrawnLoad``s)::

    from practice.diagram_judge import judge_problem
    verdict = judge_problem(pid, {"m": 12.0}, [
        {"kind": "force", "body": "the ladder", "at": "G", "angle": -90, "name": "W"}, ...])
    verdict.right                              # bool
    [(f.key, f.message) for f in verdict.findings]   # ("missing", "Something else touches ...")
"""
from __future__ import annotations

import hashlib
import itertools
import math
import re
from dataclasses import dataclass
from typing import Iterable, Mapping

import numpy as np
import sympy as sp
from scipy.optimize import linear_sum_assignment

from solvers import registry
from solvers.diagram import Diagram, DiagramSlip, Load, numbers, signed_direction, value_at

TOLERANCE_DEG = 20.0  # a drawn direction's allowance (the keyboard turns an arrow in 15° steps)
MAX_LOADS = 24  # a drawing with more is not read (no diagram here has more than six)
MAX_NAME = 40  # characters of a load's name kept
MAX_PAIRS = 12  # candidate component pairs weighed (a diagram here has at most two reactions of unknown direction)
KINDS = ("force", "impulse", "couple")
ARTICLE = {"force": "a force", "impulse": "an impulse", "couple": "a couple"}


@dataclass(frozen=True)
class DrawnLoad:
    """One load as the student drew it: its kind, the body it is drawn on and the named point it is
    placed at ("" for a couple: anywhere on the body), its direction in degrees from the basis's
    first vector, counter-clockwise (a couple's sense: +90 counter-clockwise, -90 clockwise; not
    judged), and the name the student gave it."""

    kind: str
    body: str
    at: str
    angle: float = 0.0
    name: str = ""

    @property
    def called(self) -> str:
        """How a message quotes it: its name, else its kind and point."""
        return f"“{self.name}”" if self.name else f"the {self.kind} at {self.at}" if self.at else f"the {self.kind}"


@dataclass(frozen=True)
class Finding:
    """One thing wrong: ``key`` names its class ("missing", "extra", "wrong point", "wrong way",
    "wrong kind", "components", or a declared slip's key), ``message`` the tutor's words, ``drawn``
    the index of the drawn load it concerns (None for a missing load)."""

    key: str
    message: str
    drawn: int | None = None


@dataclass(frozen=True)
class Verdict:
    """``right``: the drawing is the diagram. ``readable``: False for an empty or unreadable drawing,
    which an assignment neither records nor counts (``message`` says why)."""

    right: bool
    findings: tuple[Finding, ...] = ()
    readable: bool = True
    message: str = ""

    @property
    def keys(self) -> tuple[str, ...]:
        return tuple(f.key for f in self.findings)


class Unreadable(ValueError):
    """A drawing that cannot be read as loads on this diagram; the message says why."""


# ------------------------------------------------------------------------------------------------
# Reading what the page sends

def read_drawing(raw, diagram: Diagram) -> tuple[DrawnLoad, ...]:
    """The page's drawing (a list of {kind, body, at, angle, name}) as DrawnLoads on ``diagram``'s
    bodies and points; Unreadable, with the reason, for anything else. Names are kept as plain text
    (at most ``MAX_NAME`` characters), never evaluated."""
    if not isinstance(raw, (list, tuple)):
        raise Unreadable("The drawing did not arrive as a list of loads.")
    if len(raw) > MAX_LOADS:
        raise Unreadable(f"The drawing has {len(raw)} loads; at most {MAX_LOADS} are read.")
    bodies = {b.name: b for b in diagram.bodies}
    out = []
    for n, item in enumerate(raw, start=1):
        if not isinstance(item, Mapping):
            raise Unreadable(f"Load {n} is not a load.")
        kind, body, at, angle = item.get("kind"), item.get("body"), item.get("at", ""), item.get("angle", 0.0)
        name = item.get("name", "")
        if kind not in KINDS:
            raise Unreadable(f"Load {n}'s kind is not one of {', '.join(KINDS)}.")
        if body not in bodies:
            raise Unreadable(f"Load {n} is not on a body of this diagram.")
        if not isinstance(at, str) or (at and (at not in bodies[body].points or at.startswith("_"))):
            raise Unreadable(f"Load {n} is not at a named point of {body}.")
        if kind != "couple" and not at:
            raise Unreadable(f"Load {n} ({ARTICLE[kind]}) is not placed at a point.")
        if isinstance(angle, bool) or not isinstance(angle, (int, float)) or not math.isfinite(angle):
            raise Unreadable(f"Load {n}'s direction is not a number of degrees.")
        if not isinstance(name, str):
            raise Unreadable(f"Load {n}'s name is not text.")
        name = re.sub(r"[\x00-\x1f\x7f]", "", name).strip()[:MAX_NAME]
        out.append(DrawnLoad(kind, body, at if kind != "couple" else at, float(angle) % 360.0, name))
    return tuple(out)


# ------------------------------------------------------------------------------------------------
# The expected loads, as numbers

@dataclass(frozen=True)
class _Expected:
    load: Load
    body: str
    at: str
    kind: str
    direction: tuple[float, float] | None  # the unit vector the physics fixes; None: any (or a couple)


def _angle_between(a: float, b: float) -> float:
    """The angle between two directions in degrees, 0…180."""
    d = abs((a - b) % 360.0)
    return min(d, 360.0 - d)


def _degrees(v: tuple[float, float]) -> float:
    return math.degrees(math.atan2(v[1], v[0])) % 360.0


def _expected(diagram: Diagram, nums) -> list[_Expected]:
    out = []
    for load in diagram.loads:
        direction = None
        if load.kind != "couple" and load.direction is not None:
            x, y = signed_direction(load, nums)
            norm = math.hypot(x, y)
            direction = (x / norm, y / norm) if norm > 0 else None
        out.append(_Expected(load, load.on, load.at, load.kind, direction))
    return out


def _weights_as_one(expected: list[_Expected], drawn: tuple[DrawnLoad, ...], diagram: Diagram) -> list[_Expected]:
    """A body whose parts' weights are declared apart (a rod's and a sphere's) may have them drawn as one
    weight at its mass centre, as a professor accepts: then that one is expected instead (when no part's
    weight is drawn at the part's own centre)."""
    out = list(expected)
    for body in diagram.bodies:
        parts = [e for e in out if e.body == body.name and e.load.by == "gravity"]
        if len(parts) < 2 or any(e.at == body.centre for e in parts):
            continue
        down = parts[0].direction
        downward = lambda d: d.kind == "force" and _angle_between(d.angle, _degrees(down)) <= TOLERANCE_DEG  # noqa: E731
        if any(d.body == body.name and d.at in {e.at for e in parts} and downward(d) for d in drawn):
            continue  # a part's weight is drawn at its own centre: each is judged apart
        if any(d.body == body.name and d.at == body.centre and d.kind == "force"
               and _angle_between(d.angle, _degrees(down)) <= TOLERANCE_DEG for d in drawn):
            out = [e for e in out if e not in parts] + [_Expected(parts[0].load, body.name, body.centre, "force", down)]
    return out


# ------------------------------------------------------------------------------------------------
# Matching the drawing to the diagram

_NO = 9  # a pairing that is no match at all (a load on another body)
_FINDINGS_PER_UNMATCHED = 1


def _mismatches(e: _Expected, drawn: tuple[DrawnLoad, ...], unit: tuple[int, ...]) -> list[str] | None:
    """What differs between an expected load and a drawn unit (one load, or two perpendicular
    components at one point): a list of "kind", "point", "way"; None when they cannot be paired."""
    loads = [drawn[i] for i in unit]
    if any(d.body != e.body for d in loads):
        return None
    if len(loads) == 2 and (e.direction is not None or e.kind == "couple"):
        return None  # two components stand for a reaction of unknown direction only
    out = []
    if any(d.kind != e.kind for d in loads):
        out.append("kind")
    if e.kind != "couple" and any(d.kind == "couple" for d in loads):
        return out + ["point"]
    if e.kind != "couple" and loads[0].at != e.at:
        out.append("point")
    if e.direction is not None and loads[0].kind != "couple":
        if _angle_between(loads[0].angle, _degrees(e.direction)) > TOLERANCE_DEG:
            out.append("way")
    return out


def _component_pairs(drawn: tuple[DrawnLoad, ...], expected: list[_Expected]) -> list[tuple[int, int]]:
    """Pairs of drawn loads that could be one reaction's two components: same body, point and kind,
    perpendicular within the tolerance, where an unknown-direction reaction of that body is expected."""
    open_bodies = {e.body for e in expected if e.direction is None and e.kind != "couple"}
    pairs = []
    for i, j in itertools.combinations(range(len(drawn)), 2):
        a, b = drawn[i], drawn[j]
        if (a.body == b.body and a.body in open_bodies and a.at == b.at and a.kind == b.kind != "couple"
                and abs(_angle_between(a.angle, b.angle) - 90.0) <= TOLERANCE_DEG):
            pairs.append((i, j))
    return pairs


def _match(drawn, expected):
    """The pairing of drawn units to expected loads with the fewest findings: (pairs of (expected
    index, unit, mismatches)), unmatched expected indices, unmatched drawn indices."""
    best = None
    # (bounded: a drawing of many perpendicular loads at one pin would otherwise ask for millions of pairings)
    pairs = _component_pairs(drawn, expected)[:MAX_PAIRS]
    open_reactions = sum(1 for e in expected if e.direction is None and e.kind != "couple")
    choices = [()]
    for r in range(1, min(len(pairs), open_reactions, 3) + 1):
        choices += [c for c in itertools.combinations(pairs, r) if len({i for p in c for i in p}) == 2 * r]
    for chosen in choices:
        paired = {i for p in chosen for i in p}
        units = list(chosen) + [(i,) for i in range(len(drawn)) if i not in paired]
        cost = np.full((len(expected), len(units)), float(_NO))
        diffs = {}
        for a, e in enumerate(expected):
            for b, unit in enumerate(units):
                m = _mismatches(e, drawn, unit)
                if m is not None and len(m) <= 1:
                    cost[a, b] = len(m)
                    diffs[a, b] = m
        # each unmatched load (expected or drawn) is one finding; a match worth keeping costs less than two
        size = len(expected) + len(units)
        full = np.full((size, size), 0.0)
        full[: len(expected), : len(units)] = np.where(cost < _NO, cost, 2 * _FINDINGS_PER_UNMATCHED + 1)
        full[: len(expected), len(units):] = _FINDINGS_PER_UNMATCHED
        full[len(expected):, : len(units)] = _FINDINGS_PER_UNMATCHED
        rows, cols = linear_sum_assignment(full)
        matched, lost, extra = [], [], []
        for a, b in zip(rows, cols):
            if a < len(expected) and b < len(units):
                if (a, b) in diffs:
                    matched.append((a, units[b], diffs[a, b]))
                else:
                    lost.append(a)
                    extra.extend(units[b])
            elif a < len(expected):
                lost.append(a)
            elif b < len(units):
                extra.extend(units[b])
        total = sum(len(m) for _, _, m in matched) + len(lost) + len(extra)
        rank = (total, len(units))
        if best is None or rank < best[0]:
            best = (rank, matched, lost, extra)
    return best[1], best[2], best[3]


# ------------------------------------------------------------------------------------------------
# The tutor's words

def _pushes(e: _Expected, diagram: Diagram, nums) -> bool:
    """Whether a contact load pushes (points into the body from its point): a normal force, a strike."""
    if e.direction is None or e.load.by == "gravity":
        return False
    body = diagram.body(e.body)
    at, centre = body.points[e.at], body.points[body.centre]
    out = (value_at(at[0], nums) - value_at(centre[0], nums), value_at(at[1], nums) - value_at(centre[1], nums))
    return e.direction[0] * out[0] + e.direction[1] * out[1] < -1e-9


_HOW_MANY = {2: "two", 3: "three", 4: "four", 5: "five", 6: "six"}


def _missing(e: _Expected, diagram: Diagram, count: int = 1) -> Finding:
    """What a load left out asks the student; ``count``: how many left out would ask the same (said once, with
    how many: two identical lines would not tell the student there are two)."""
    if e.load.by == "gravity":
        return Finding("missing", f"Something acts on {e.body} without touching it: what pulls on every body with mass?")
    if e.kind == "couple":
        return Finding("missing", f"Something twists {e.body} without pushing it along: what is connected to it "
                                  "that resists turning?")
    what = "strikes" if e.kind == "impulse" else "touches"
    more = f" in {_HOW_MANY.get(count, count)} more ways" if count > 1 else ""
    return Finding("missing", f"Something else {what} {e.body}{more}: look at every point where it meets another "
                              "body or a support, and draw what each one exerts there.")


def _all_missing(expected: list[_Expected], lost, diagram: Diagram) -> list[Finding]:
    """A finding for each load left out, those that would read alike said once with their count."""
    said: dict[str, tuple[_Expected, int]] = {}
    for a in sorted(lost):
        message = _missing(expected[a], diagram).message
        e, count = said.get(message, (expected[a], 0))
        said[message] = (e, count + 1)
    return [_missing(e, diagram, count) for e, count in said.values()]


def _wrong_kind(e: _Expected, d: DrawnLoad, i: int, diagram: Diagram) -> Finding:
    if e.kind == "impulse":
        why = ("over the impact's instant what acts there is an impulse (a force's integral over the "
               "impact), and the balance laws are impulse–momentum")
    elif e.kind == "couple":
        why = "what acts there turns the body without pushing it along: a couple, not a force"
    else:
        why = f"what acts there is {ARTICLE[e.kind]}, not {ARTICLE[d.kind]}"
    return Finding("wrong kind", f"{d.called[:1].upper() + d.called[1:]} is drawn as {ARTICLE[d.kind]}: {why}.", i)


def _wrong_point(e: _Expected, d: DrawnLoad, i: int) -> Finding:
    if e.load.by == "gravity":
        return Finding("weight off the mass centre",
                       f"{d.called[:1].upper() + d.called[1:]} is drawn at {d.at}: gravity pulls on every particle of "
                       "what it weighs, and drawn as one force it acts at that part's mass centre.", i)
    return Finding("wrong point", f"{d.called[:1].upper() + d.called[1:]} is drawn at {d.at}: does anything touch "
                                  f"{e.body} there? A contact load acts where the contact is.", i)


def _wrong_way(e: _Expected, d: DrawnLoad, i: int, diagram: Diagram, nums) -> Finding:
    called = d.called[:1].upper() + d.called[1:]
    reversed_ = _angle_between(d.angle, _degrees(e.direction)) > 180.0 - TOLERANCE_DEG
    if reversed_ and e.load.pair:
        return Finding("other body's load of the pair",
                       f"{called} points the way {e.body} pushes on the other body. On {e.body}, draw what the other "
                       "body does to it: equal and opposite (Newton's third law).", i)
    if e.load.by == "gravity":
        return Finding("wrong way", f"{called}: gravity pulls down, along −{_basis_word(diagram, 1)}.", i)
    if reversed_ and _pushes(e, diagram, nums):
        return Finding("wrong way", f"{called} pulls {e.body} toward {e.load.by}: {e.load.by} can only push on it, "
                                    "so a contact force points into the body it acts on.", i)
    if reversed_:
        return Finding("wrong way", f"{called} points the wrong way: what fixes its sense?", i)
    return Finding("wrong way", f"{called} is at an angle the physics does not allow: what fixes its direction "
                                "at that point (a smooth surface, a contact, gravity)?", i)


def _basis_word(diagram: Diagram, n: int) -> str:
    """A basis vector in plain text (\\mathbf{E}_y -> E_y)."""
    return re.sub(r"\\mathbf\{(\w)\}", r"\1", diagram.basis[n])


def _slip_direction(slip: DiagramSlip, values) -> tuple[float, float] | None:
    if slip.direction is None:
        return None
    x, y = (float(sp.sympify(c).subs(values)) for c in slip.direction)
    n = math.hypot(x, y)
    return (x / n, y / n) if n > 0 else None


def _slip_for(d: DrawnLoad, slips: Iterable[DiagramSlip], values) -> DiagramSlip | None:
    for slip in slips:
        if (slip.on and slip.on != d.body) or (slip.at and slip.at != d.at) or d.kind not in slip.kinds:
            continue
        way = _slip_direction(slip, values)
        if way is not None:
            off = _angle_between(d.angle, _degrees(way))
            if off > TOLERANCE_DEG and not (slip.either_way and off >= 180.0 - TOLERANCE_DEG):
                continue
        return slip
    return None


def _extra(d: DrawnLoad, i: int, diagram: Diagram, slips, values) -> Finding:
    slip = _slip_for(d, slips, values)
    called = d.called[:1].upper() + d.called[1:]
    if slip is not None:
        return Finding(slip.key, f"{called}: {slip.message}", i)
    if diagram.law == "impulse" and d.kind == "force":
        return Finding("finite force in an impact",
                       f"{called} is a finite force: over the impact's instant its impulse is negligible against "
                       "the contact's, so an impact's diagram shows impulses only.", i)
    if d.kind == "couple":
        return Finding("extra", f"{called}: what twists {d.body} there? Draw a couple only where something "
                                "connected to the body resists its turning.", i)
    return Finding("extra", f"{called} at {d.at}: what exerts it? Each load on a free-body diagram is exerted by "
                            "something that touches the body there, or by gravity.", i)


# ------------------------------------------------------------------------------------------------
# The judge

def judge(diagram: Diagram, values: Mapping, drawing: Iterable[DrawnLoad],
          slips: Iterable[DiagramSlip] = ()) -> Verdict:
    """The drawing against ``diagram`` at ``values`` (``diagram.values(solution)``), with the problem's
    declared slips. Findings come in the drawing's order, the missing loads last."""
    drawn = tuple(drawing)
    if not drawn:
        return Verdict(False, readable=False, message="Nothing is drawn yet: add each load on the body, then Check.")
    values = {k: float(v) for k, v in values.items()}
    nums = numbers(diagram, values)
    expected = _expected(diagram, nums)
    slips = tuple(s for s in slips if not s.phase or s.phase == diagram.phase)
    expected = _weights_as_one(expected, drawn, diagram)
    matched, lost, extra = _match(drawn, expected)
    found: list[tuple[int, Finding]] = []
    for a, unit, diffs in matched:
        e, d, i = expected[a], drawn[unit[0]], unit[0]
        slip = _slip_for(d, slips, values) if diffs and "kind" not in diffs else None
        if slip is not None:  # drawn as a classic slip draws it (friction where a normal pushes): the load meant is missing
            found.append((i, Finding(slip.key, f"{d.called[:1].upper() + d.called[1:]}: {slip.message}", i)))
            lost.append(a)
        elif "kind" in diffs:
            found.append((i, _wrong_kind(e, d, i, diagram)))
        elif "point" in diffs:
            found.append((i, _wrong_point(e, d, i)))
        elif "way" in diffs:
            found.append((i, _wrong_way(e, d, i, diagram, nums)))
    for i in extra:
        found.append((i, _extra(drawn[i], i, diagram, slips, values)))
    found.sort(key=lambda f: f[0])
    findings = [f for _, f in found] + _all_missing(expected, lost, diagram)
    return Verdict(not findings, tuple(findings))


def exercise_diagram(solver, solution) -> Diagram:
    """The diagram the exercise asks for: the problem's ``EXERCISE_DIAGRAM`` phase, else its first."""
    diagrams = solver.free_body_diagrams(solution.params)
    wanted = getattr(solver, "EXERCISE_DIAGRAM", "")
    return next((d for d in diagrams if d.phase == wanted), diagrams[0])


def judge_problem(pid: str, params: Mapping, drawing) -> Verdict:
    """Judge a drawing of problem ``pid``'s exercise diagram at ``params`` (the defaults for those not
    given). ``drawing``: DrawnLoads, or the page's list of dicts (read by ``read_drawing``; an
    unreadable one gives a verdict with ``readable`` False and the reason)."""
    solver = registry.solver(pid)
    solution = solver.solve(**params)
    diagram = exercise_diagram(solver, solution)
    if not all(isinstance(d, DrawnLoad) for d in drawing):
        try:
            drawing = read_drawing(drawing, diagram)
        except Unreadable as why:
            return Verdict(False, readable=False, message=str(why))
    return judge(diagram, diagram.values(solution), drawing, getattr(solver, "DIAGRAM_SLIPS", ()))


def drawn_as_declared(diagram: Diagram, values: Mapping, components: bool = False) -> tuple[DrawnLoad, ...]:
    """The diagram drawn right, as a student would draw it: each load at its point in its direction;
    a reaction of unknown direction as one load along its value's direction, or (``components``) as
    its two components along the basis. For tests and for a course checking the judge."""
    values = {k: float(v) for k, v in values.items()}
    nums = numbers(diagram, values)
    out = []
    for e in _expected(diagram, nums):
        name = e.load.symbol
        if e.kind == "couple":
            out.append(DrawnLoad("couple", e.body, "", 90.0, name))
        elif e.direction is not None:
            out.append(DrawnLoad(e.kind, e.body, e.at, _degrees(e.direction), name))
        elif components:
            out += [DrawnLoad(e.kind, e.body, e.at, 0.0, name + "x"), DrawnLoad(e.kind, e.body, e.at, 90.0, name + "y")]
        else:
            x, y = (value_at(c, nums) for c in e.load.components)
            out.append(DrawnLoad(e.kind, e.body, e.at, _degrees((x, y)) if (x or y) else 90.0, name))
    return tuple(out)


def in_words(drawing: Iterable[DrawnLoad], bodies: int = 1) -> str:
    """A drawing as a line of text (what an assignment keeps as the attempt): "force “W” at G, 270°; …";
    with more than one body, each point with its body."""
    def one(d: DrawnLoad) -> str:
        name = f" “{d.name}”" if d.name else ""
        where = (f" at {d.at}" + (f" on {d.body}" if bodies > 1 else "")) if d.at else f" on {d.body}"
        way = ("counter-clockwise" if d.angle != 270 else "clockwise") if d.kind == "couple" else f"{d.angle:g}°"
        return f"{d.kind}{name}{where}, {way}"
    return "; ".join(one(d) for d in drawing)


def reading(drawing: Iterable[DrawnLoad]) -> str:
    """What a drawing says, as a short key: the same loads at the same points in the same directions
    (names and order aside) read alike, so the same drawing checked twice is one attempt."""
    loads = sorted((d.kind, d.body, d.at if d.kind != "couple" else "", round(d.angle) % 360) for d in drawing)
    return "fbd:" + hashlib.sha256(repr(loads).encode()).hexdigest()[:16]
