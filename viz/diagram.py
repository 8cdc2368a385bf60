"""A free-body diagram drawn from a problem's declarations (solvers/diagram.py), for the page's
numbers: laid out once as plain shapes (``layout``), then written as SVG (the page, print, the
handouts), TikZ (the .tex) or drawn by matplotlib (the notebook), so every picture is the same.

How a professor draws it on the board: the body isolated and outlined, its named points, the basis
in a corner, each force as an arrow at its point with its label; a push (a normal force, a contact
reaction) has its head at the point and its tail outside the body, a pull or a body force (the
weight) its tail at the point; a reaction of unknown direction as its two components in the
positive basis directions (the solution's signs say which way they really act); an impulse with an
open head, distinct from a force's filled one; a couple as a curved arrow in its sense. Arrows have
one length (a diagram shows which forces and where, not their sizes; the stage's Forces overlay
draws them to size). Labels are placed where they overlap no other label, arrow or point, and the
picture's box holds them all.
"""
from __future__ import annotations

import functools
import html
import math
import re
from dataclasses import dataclass, field, replace

import sympy as sp

from solvers.diagram import Circle, Diagram, Numbers, Outline, Rod, numbers, signed_direction

BODY_SIZE = 180.0  # the largest body's extent, in the drawing's units (an SVG viewBox's)
ARROW = 62.0  # a load's length
FONT = 17.0  # a label's size
POINT_FONT = 15.0
GAP = 90.0  # between two bodies of one diagram (an interaction pair drawn apart)
MARGIN = 8.0
COUPLE_RADIUS = 24.0
LOAD_COLOR = "#b3261e"
BODY_FILL = "#e8eaed"
BODY_STROKE = "#3c4043"
BASIS_COLOR = "#3c4043"


@dataclass
class Box:
    x0: float
    y0: float
    x1: float
    y1: float

    def overlaps(self, other: "Box", pad: float = 0.0) -> bool:
        return not (self.x1 + pad <= other.x0 or other.x1 + pad <= self.x0 or
                    self.y1 + pad <= other.y0 or other.y1 + pad <= self.y0)

    def inside(self, other: "Box") -> bool:
        return self.x0 >= other.x0 - 1e-9 and self.y0 >= other.y0 - 1e-9 and self.x1 <= other.x1 + 1e-9 and self.y1 <= other.y1 + 1e-9


@dataclass
class Label:
    """A label's text (LaTeX as declared), its box's centre and size, in the drawing's units (y up)."""

    tex: str
    x: float
    y: float
    size: float = FONT

    @property
    def box(self) -> Box:
        w, h = label_width(self.tex, self.size), self.size * 1.15
        return Box(self.x - w / 2, self.y - h / 2, self.x + w / 2, self.y + h / 2)


@dataclass
class Arrow:
    tail: tuple[float, float]
    head: tuple[float, float]
    kind: str  # "force", "impulse" or "basis"
    label: Label | None = None
    load: str = ""  # the declared load's symbol this arrow draws (a component's for a reaction)


@dataclass
class Curl:
    centre: tuple[float, float]
    radius: float
    ccw: bool
    label: Label | None = None
    load: str = ""


@dataclass
class Line:
    """A sketch's line (viz/sketch.py): a fixed surface ("support", hatched on its ``side``: +1 to the left
    of a→b) or a "dashed" guide."""
    a: tuple[float, float]
    b: tuple[float, float]
    style: str = "support"
    side: int = 1


@dataclass
class Dim:
    """A length marked between two ends, with its symbol."""
    a: tuple[float, float]
    b: tuple[float, float]
    label: Label


@dataclass
class Arc:
    """An angle marked at ``centre`` from ``start`` to ``end`` (radians, counter-clockwise), with its symbol."""
    centre: tuple[float, float]
    radius: float
    start: float
    end: float
    label: Label


GIVEN_COLOR = "#0072B2"  # a sketch's given velocities and spins (a load's red is the diagram's)


@dataclass
class Drawing:
    """A diagram laid out: shapes in the drawing's units, y up; ``box`` holds everything."""

    title: str
    circles: list[tuple[float, float, float]] = field(default_factory=list)
    rods: list[tuple[float, float, float, float]] = field(default_factory=list)
    polygons: list[list[tuple[float, float]]] = field(default_factory=list)
    points: list[tuple[float, float, Label]] = field(default_factory=list)
    arrows: list[Arrow] = field(default_factory=list)
    curls: list[Curl] = field(default_factory=list)
    box: Box = field(default_factory=lambda: Box(0, 0, 1, 1))
    text: str = ""  # the text alternative
    lines: list[Line] = field(default_factory=list)  # a sketch's supports and guides
    dims: list[Dim] = field(default_factory=list)  # a sketch's marked lengths
    arcs: list[Arc] = field(default_factory=list)  # a sketch's marked angles

    @property
    def labels(self) -> list[Label]:
        return ([p[2] for p in self.points] + [a.label for a in self.arrows if a.label]
                + [c.label for c in self.curls if c.label] + [m.label for m in (*self.dims, *self.arcs)])


# ------------------------------------------------------------------------------------------------
# Labels: the declared LaTeX as runs of text, subscripts and superscripts

_GREEK = {r"\theta": "θ", r"\omega": "ω", r"\mu": "μ", r"\tau": "τ", r"\alpha": "α", r"\phi": "φ", r"\psi": "ψ",
          r"\Delta": "Δ", r"\sigma": "σ", r"\lambda": "λ", r"\rho": "ρ", r"\beta": "β", r"\ell": "ℓ",
          r"\hat": "", r"\mathbf": "", r"\mathrm": "", r"\mathit": "", r"\,": " ", r"\;": " ", r"\!": "", r"\cdot": "·"}
_LATEX_TOKEN = re.compile(r"\\[a-zA-Z]+|\\.|[{}_^]|[^\\{}_^\s]|\s+")


@functools.lru_cache(maxsize=512)
def runs(tex: str) -> tuple[tuple[str, str], ...]:
    """A label's LaTeX as (text, "" | "sub" | "sup") runs: enough for the symbols the solvers
    declare (N_A, m_s g, O_x, \\mu N_f, M_{k}); a script in \\mathrm is "sub upright" or "sup upright". Kept
    per label: a diagram measures each label at every spot it tries."""
    tokens = _LATEX_TOKEN.findall(tex)
    out: list[tuple[str, str]] = []
    i, mode = 0, ""

    def add(text: str, where: str):
        if out and out[-1][1] == where:
            out[-1] = (out[-1][0] + text, where)
        else:
            out.append((text, where))

    while i < len(tokens):
        t = tokens[i]
        if t == r"\hat" and i + 1 < len(tokens):  # \hat{P}: P with a circumflex
            j = i + 2 if tokens[i + 1] == "{" else i + 1
            add(_GREEK.get(tokens[j], tokens[j]) + "\u0302", mode)
            i = j + 2 if tokens[i + 1] == "{" else j + 1
            continue
        if t in ("_", "^"):
            where = "sub" if t == "_" else "sup"
            i += 1
            if i < len(tokens) and tokens[i] == "{":
                depth, j, inner = 1, i + 1, []
                while j < len(tokens) and depth:
                    depth += {"{": 1, "}": -1}.get(tokens[j], 0)
                    if depth:
                        inner.append(tokens[j])
                    j += 1
                # a word subscript set upright (N_{\mathrm{front}}), as the derivation sets it
                add("".join(_GREEK.get(x, x) for x in inner if x not in "{}" and not x.isspace()),
                    where + (" upright" if r"\mathrm" in inner else ""))
                i = j
            elif i < len(tokens):
                add(_GREEK.get(tokens[i], tokens[i]), where)
                i += 1
            continue
        if t in ("{", "}") or t.isspace():
            i += 1
            continue
        add(_GREEK.get(t, t.lstrip("\\") if t.startswith("\\") and len(t) > 2 else t), "")
        i += 1
    return tuple((text, where) for text, where in out if text)


def plain_label(tex: str) -> str:
    """A label as plain text (N_A -> N_A, m_{s} g -> m_s g): for the text alternative."""
    out = ""
    for t, w in runs(tex):
        if w == "":
            out += (" " if out and "_" in out.rsplit(" ", 1)[-1] else "") + t
        else:
            out += f"_{t}" if w.startswith("sub") else f"^{t}"
    return out


@functools.lru_cache(maxsize=512)
def _tex(symbol: sp.Basic) -> str:
    """A declared component's LaTeX (O_x), printed once per symbol rather than on every drawing."""
    return sp.latex(symbol)


def label_width(tex: str, size: float = FONT) -> float:
    return sum(len(text) * size * (0.62 if where == "" else 0.45) for text, where in runs(tex)) + 2


# ------------------------------------------------------------------------------------------------
# Layout

def _num(expr, values) -> float:
    if isinstance(expr, (int, float)):
        return float(expr)
    if isinstance(values, Numbers):
        return values[sp.sympify(expr)]
    return float(sp.sympify(expr).subs(values))


def _unit(x: float, y: float) -> tuple[float, float]:
    n = math.hypot(x, y)
    return (x / n, y / n) if n > 0 else (0.0, 0.0)


def _segment_hits_box(a, b, box: Box) -> bool:
    """Whether segment ab passes through the box (sampled: boxes are small against arrows). A segment
    whose own bounds miss the box has no sample in it: answered without sampling (most are)."""
    if (max(a[0], b[0]) <= box.x0 or min(a[0], b[0]) >= box.x1
            or max(a[1], b[1]) <= box.y0 or min(a[1], b[1]) >= box.y1):
        return False
    for k in range(41):
        t = k / 40
        x, y = a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t
        if box.x0 < x < box.x1 and box.y0 < y < box.y1:
            return True
    return False


def _from_segment(point, a, b) -> float:
    """How far ``point`` is from the segment a–b."""
    (px, py), (ax, ay), (bx, by) = point, a, b
    dx, dy = bx - ax, by - ay
    t = min(max(((px - ax) * dx + (py - ay) * dy) / ((dx * dx + dy * dy) or 1e-12), 0.0), 1.0)
    return math.hypot(px - ax - t * dx, py - ay - t * dy)


def _from_box(box: Box, point) -> float:
    """How far ``point`` is from ``box`` (0 inside it)."""
    return math.hypot(point[0] - min(max(point[0], box.x0), box.x1), point[1] - min(max(point[1], box.y0), box.y1))


def _nearer_arrow(own, others):
    """Whether a label's box has its centre nearer the arrow ``own`` (tail, head) than every one of ``others``:
    a label is read as naming what is nearest it."""
    def nearest(box: Box) -> bool:
        centre = ((box.x0 + box.x1) / 2, (box.y0 + box.y1) / 2)
        mine = _from_segment(centre, *own)
        return all(mine < _from_segment(centre, *other) for other in others)
    return nearest


def _nearer_point(own, others):
    """Whether a label's box is nearer the point ``own`` than every one of ``others`` (a point's letter)."""
    def nearest(box: Box) -> bool:
        mine = _from_box(box, own)
        return all(mine < _from_box(box, other) for other in others)
    return nearest


def layout(diagram: Diagram, values, every_point: bool = False) -> Drawing:
    """The diagram for these values (``diagram.values(solution)``), laid out; ``every_point``: every
    named point marked (the drawing exercise's blank body), not only those a load or a balance law uses.

    Laid out once for each shape it takes: the drawing reads of the values only the points' places, the
    circles' radii, the couples' senses and the loads' directions (an arrow's length is not a load's
    size), so a new spring stiffness or restitution draws the diagram it drew before, with its own words
    (the text alternative names the values). The drawing returned is shared: read it, or ``replace`` it."""
    values = numbers(diagram, {k: float(v) for k, v in values.items()})
    shape = _shape(diagram, values, every_point)
    drawn = _LAID_OUT.get(shape)
    if drawn is None:
        drawn = _LAID_OUT[shape] = _laid_out(diagram, values, every_point)
        if len(_LAID_OUT) > 512:
            _LAID_OUT.pop(next(iter(_LAID_OUT)))
    return replace(drawn, text=text_alternative(diagram, values))


_LAID_OUT: dict[tuple, Drawing] = {}  # a diagram's shape (``_shape``) -> its drawing, oldest first


def _shape(diagram: Diagram, values, every_point: bool) -> tuple:
    """All a diagram's drawing depends on: its declarations and, of the values, what ``_laid_out`` reads."""
    def at(x) -> str:  # (bit for bit: −0.0 is not 0.0 on the page, nor a last digit rounded the other way)
        return _num(x, values).hex()

    bodies = tuple((b.name, b.centre, b.about, tuple((n, at(x), at(y)) for n, (x, y) in b.points.items()),
                    tuple((s.centre, at(s.radius)) if isinstance(s, Circle) else repr(s) for s in b.outline))
                   for b in diagram.bodies)
    loads = tuple((l.symbol, l.on, l.at, l.kind, l.by, repr(l.components),
                   (_num(l.size, values) >= 0) if l.kind == "couple" else
                   None if l.direction is None else tuple(c.hex() for c in _unit(*signed_direction(l, values))))
                  for l in diagram.loads)
    return diagram.title, diagram.basis, every_point, bodies, loads


def _laid_out(diagram: Diagram, values: Numbers, every_point: bool) -> Drawing:
    """``layout``'s drawing, at these numbers (``numbers``), without its words."""
    bodies = []
    for body in diagram.bodies:
        pts = {name: (_num(x, values), _num(y, values)) for name, (x, y) in body.points.items()}
        xs = [p[0] for p in pts.values()]
        ys = [p[1] for p in pts.values()]
        for shape in body.outline:
            if isinstance(shape, Circle):
                r = _num(shape.radius, values)
                cx, cy = pts[shape.centre]
                xs += [cx - r, cx + r]
                ys += [cy - r, cy + r]
        bodies.append((body, pts, min(xs), max(xs), min(ys), max(ys)))
    extent = max(max(b[3] - b[2], b[5] - b[4]) for b in bodies) or 1.0
    scale = BODY_SIZE / extent
    drawing = Drawing(diagram.title)
    obstacles: list[Box] = []
    left = 0.0
    placed: dict[tuple[str, str], tuple[float, float]] = {}
    centres: dict[str, tuple[float, float]] = {}
    for body, pts, x0, x1, y0, y1 in bodies:
        dx = left - x0 * scale
        to = lambda p: (p[0] * scale + dx, p[1] * scale)  # (heights as they are: an interaction pair's point level)
        for name, p in pts.items():
            placed[(body.name, name)] = to(p)
        centres[body.name] = to(pts[body.centre])
        for shape in body.outline:
            if isinstance(shape, Circle):
                cx, cy = to(pts[shape.centre])
                drawing.circles.append((cx, cy, max(_num(shape.radius, values) * scale, 4.0)))
            elif isinstance(shape, Rod):
                (ax, ay), (bx, by) = to(pts[shape.ends[0]]), to(pts[shape.ends[1]])
                drawing.rods.append((ax, ay, bx, by))
            elif isinstance(shape, Outline):
                drawing.polygons.append([to(pts[c]) for c in shape.corners])
        left += (x1 - x0) * scale + GAP + ARROW  # room for a load pushing on the next body from this side
    # Named points: a dot and its letter (placed after the loads, where room is left).
    # the points a reader needs named: where a load acts, the mass centre, the moment point
    named = {(b.name, n) for b in diagram.bodies for n in (b.centre, b.about)} | {
        (load.on, load.at) for load in diagram.loads if load.at}
    used_points = {(b.name, n) for b in diagram.bodies for n in b.points
                   if (b.name, n) in named or (every_point and not n.startswith("_"))}
    # Loads
    pending: list[tuple[Arrow | Curl, tuple[float, float], tuple[float, float]]] = []
    for load in diagram.loads:
        at = placed[(load.on, load.at)] if load.at else centres[load.on]
        inward_ref = centres[load.on]
        if load.kind == "couple":
            value = _num(load.size, values)
            curl = Curl(at, COUPLE_RADIUS, value >= 0, Label(load.symbol, 0, 0), load.symbol)
            drawing.curls.append(curl)
            pending.append((curl, (at[0] + COUPLE_RADIUS * 0.7, at[1] + COUPLE_RADIUS * 0.7), (1.0, 1.0)))
            continue
        if load.direction is None:
            parts = [((1.0, 0.0), load.components[0]), ((0.0, 1.0), load.components[1])]
        else:
            parts = [(_unit(*signed_direction(load, values)), load.symbol)]
        for d, symbol in parts:
            out = (at[0] - inward_ref[0], at[1] - inward_ref[1])
            # a contact's push has its head at the point; a body force (the weight) starts there
            pushes = load.by != "gravity" and d[0] * out[0] + d[1] * out[1] < -1e-9
            if pushes:  # head at the point, tail outside
                head, tail = at, (at[0] - d[0] * ARROW, at[1] - d[1] * ARROW)
            else:  # tail at the point
                tail, head = at, (at[0] + d[0] * ARROW, at[1] + d[1] * ARROW)
            arrow = Arrow(tail, head, load.kind, Label(symbol if isinstance(symbol, str) else _tex(symbol), 0, 0),
                          load.symbol)
            drawing.arrows.append(arrow)
            free, outward = (tail, (-d[0], -d[1])) if pushes else (head, d)
            pending.append((arrow, free, outward))
    for x, y in {placed[k] for k in used_points}:
        obstacles.append(Box(x - 3, y - 3, x + 3, y + 3))
    labels: list[Box] = []
    shafts = [(a.tail, a.head) for a in drawing.arrows]
    for item, free, d in pending:
        label = item.label
        nearest = (_nearer_arrow((item.tail, item.head), [s for s in shafts if s != (item.tail, item.head)])
                   if isinstance(item, Arrow) else None)
        label.x, label.y = _place(label, free, d, labels, obstacles, item, drawing=drawing, nearest=nearest)
        labels.append(label.box)
    dots = {placed[k] for k in used_points}
    for (bname, name), (x, y) in placed.items():
        if (bname, name) not in used_points:  # an outline's corner or end, not a named point
            continue
        label = Label(name, 0, 0, POINT_FONT)
        centre = centres[bname]
        away = _unit(x - centre[0], y - centre[1]) if (x, y) != centre else (-0.7, -0.7)
        nearest = _nearer_point((x, y), [dot for dot in dots if dot != (x, y)])
        label.x, label.y = _place(label, (x, y), away, labels, obstacles, None, near=10.0, drawing=drawing,
                                  nearest=nearest)
        labels.append(label.box)
        drawing.points.append((x, y, label))
    _basis(drawing, diagram, labels, obstacles)
    boxes = labels + obstacles + [_arrow_box(a) for a in drawing.arrows] + [_shape_box(drawing)]
    drawing.box = Box(min(b.x0 for b in boxes) - MARGIN, min(b.y0 for b in boxes) - MARGIN,
                      max(b.x1 for b in boxes) + MARGIN, max(b.y1 for b in boxes) + MARGIN)
    return drawing


def _arrow_box(arrow: Arrow) -> Box:
    (x0, y0), (x1, y1) = arrow.tail, arrow.head
    return Box(min(x0, x1) - 2, min(y0, y1) - 2, max(x0, x1) + 2, max(y0, y1) + 2)


def _shape_box(d: Drawing) -> Box:
    xs, ys = [], []
    for cx, cy, r in d.circles:
        xs += [cx - r, cx + r]
        ys += [cy - r, cy + r]
    for ax, ay, bx, by in d.rods:
        xs += [ax, bx]
        ys += [ay, by]
    for poly in d.polygons:
        xs += [p[0] for p in poly]
        ys += [p[1] for p in poly]
    for c in d.curls:
        xs += [c.centre[0] - c.radius - 6, c.centre[0] + c.radius + 6]
        ys += [c.centre[1] - c.radius - 6, c.centre[1] + c.radius + 6]
    return Box(min(xs, default=0), min(ys, default=0), max(xs, default=0), max(ys, default=0))


def crosses_outline(drawing: "Drawing", box: Box, pad: float = 2.0) -> bool:
    """Whether the box crosses a body's outline (a circle's rim, a rod, a polygon's edge)."""
    for cx, cy, r in drawing.circles:
        nx, ny = min(max(cx, box.x0), box.x1), min(max(cy, box.y0), box.y1)
        near = math.hypot(nx - cx, ny - cy)
        far = max(math.hypot(x - cx, y - cy) for x in (box.x0, box.x1) for y in (box.y0, box.y1))
        if near < r + pad and far > r - pad:
            return True
    grown = Box(box.x0 - 4, box.y0 - 4, box.x1 + 4, box.y1 + 4)
    edges = [((ax, ay), (bx, by)) for ax, ay, bx, by in drawing.rods]
    for poly in drawing.polygons:
        edges += list(zip(poly, poly[1:] + poly[:1]))
    return any(_segment_hits_box(a, b, grown) for a, b in edges)


def _place(label: Label, free, d, labels: list[Box], obstacles: list[Box], item, near: float = 14.0,
           drawing: "Drawing | None" = None, nearest=None):
    """The first spot around ``free`` (beyond the arrow's free end along ``d`` first, then around it)
    where the label overlaps no placed label or point, crosses no arrow (its own included) and no
    body's outline, and is nearer what it names than anything else of its kind (``nearest``, of the
    spot: a weight's mg by its own arrow, not by the floor's push beside it), where such a spot is; the
    first candidate otherwise."""
    w, h = label_width(label.tex, label.size), label.size * 1.15
    reach = near + max(w, h) / 2
    first = (free[0] + d[0] * reach, free[1] + d[1] * reach)
    fixed = None
    if isinstance(item, Arrow):
        fixed = item.tail if tuple(free) == tuple(item.head) else item.head

    def crosses(box: Box) -> bool:  # (the costly test: last)
        grown = Box(box.x0 - 2, box.y0 - 2, box.x1 + 2, box.y1 + 2)
        return drawing is not None and (crosses_outline(drawing, box) or any(
            _segment_hits_box(a.tail, a.head, grown) for a in drawing.arrows))

    farther = []  # (spots nearer something else: the first of them that is clear, where no other is)
    for x, y in _spots(free, d, reach, w, h, fixed):
        box = Box(x - w / 2, y - h / 2, x + w / 2, y + h / 2)
        if any(box.overlaps(b, 2) for b in labels) or any(box.overlaps(o) for o in obstacles):
            continue
        if nearest is not None and not nearest(box):
            farther.append((x, y, box))
            continue
        if not crosses(box):
            return x, y
    return next(((x, y) for x, y, box in farther if not crosses(box)), first)


_AROUND = tuple((math.cos(2 * math.pi * k / 16), math.sin(2 * math.pi * k / 16)) for k in range(16))


def _spots(free, d, reach: float, w: float, h: float, fixed=None):
    """Where ``_place`` tries a label of ``w`` × ``h``, in order: beyond the free end along ``d``, beside it
    (across ``d``), then around it, the nearest ring first and on each ring the directions nearest ``d``
    first (a label stays by what it names, on its outer side: at the next ring out, not beside another
    point); then, for an arrow, the same rings around its ``fixed`` end (a weight drawn inside a narrow
    body, its head crowded by the contacts' pushes: its name by its tail). Generated as tried (the first
    usually serves)."""
    yield free[0] + d[0] * reach, free[1] + d[1] * reach
    yield free[0] - d[1] * (w / 2 + 6), free[1] + d[0] * (h / 2 + 6)
    for centre, out in ((free, d), *(((fixed, (-d[0], -d[1])),) if fixed is not None else ())):
        around = sorted(_AROUND, key=lambda u: -(u[0] * out[0] + u[1] * out[1]))
        for r in (reach, reach * 1.6, reach * 2.3):
            for c, s in around:
                yield centre[0] + c * r, centre[1] + s * r


def _basis(drawing: Drawing, diagram: Diagram, labels: list[Box], obstacles: list[Box]) -> None:
    """The basis's two unit vectors in the lower-left corner, clear of everything drawn."""
    everything = labels + obstacles + [_arrow_box(a) for a in drawing.arrows] + [_shape_box(drawing)]
    x0 = min(b.x0 for b in everything) - 60
    y0 = min(b.y0 for b in everything) - 10
    length = 40.0
    for (dx, dy), tex in (((1, 0), diagram.basis[0]), ((0, 1), diagram.basis[1])):
        head = (x0 + dx * length, y0 + dy * length)
        where = (head[0] + dx * 14 + dy * 2, head[1] + dy * 12 + dx * 0)
        arrow = Arrow((x0, y0), head, "basis", Label(tex, *where, POINT_FONT))
        drawing.arrows.append(arrow)
        labels.append(arrow.label.box)
        obstacles.append(_arrow_box(arrow))


def caption(title: str) -> str:
    """A free-body diagram's caption, from its title: the head of its text alternative."""
    return f"Free-body diagram, {title.lower()}"


def text_alternative(diagram: Diagram, values) -> str:
    """The diagram in words: each body, and each load, where it acts and which way."""
    sentences = []
    for body in diagram.bodies:
        loads = diagram.loads_on(body.name)
        parts = []
        for load in loads:
            where = f" at {load.at}" if load.at else ""
            if load.kind == "couple":
                value = _num(load.size, values)
                way = "counter-clockwise" if value >= 0 else "clockwise"
                parts.append(f"{load.name} {plain_label(load.symbol)}{where}, {way}")
            elif load.direction is None:
                c = [plain_label(_tex(x)) for x in load.components]
                parts.append(f"{load.name}{where}, direction unknown, drawn as its components {c[0]} along x "
                             f"and {c[1]} along y")
            else:
                d = _unit(*signed_direction(load, values))
                parts.append(f"{load.name} {plain_label(load.symbol)}{where}, {_way(d)}")
        kind = "impulses" if diagram.law == "impulse" else "forces"
        sentences.append(f"{caption(diagram.title)}: {body.name}, with the {kind} on it: "
                         + "; ".join(parts) + ".")
    return " ".join(sentences)


def _way(d) -> str:
    angle = math.degrees(math.atan2(d[1], d[0]))
    named = {0: "along +x", 90: "up", 180: "along −x", -180: "along −x", -90: "down"}
    for a, word in named.items():
        if abs(angle - a) < 0.5:
            return word
    return f"at {angle:.0f}° from +x"


# ------------------------------------------------------------------------------------------------
# SVG

def _svg_text(label: Label, flip, color: str, extra: str = "") -> str:
    x, y = flip(label.x, label.y)
    spans = []
    for text, where in runs(label.tex):
        t = html.escape(text)
        upright = ' font-style="normal"' if where.endswith("upright") else ""
        if where.startswith("sub"):
            spans.append(f'<tspan baseline-shift="sub" font-size="70%"{upright}>{t}</tspan>')
        elif where.startswith("sup"):
            spans.append(f'<tspan baseline-shift="super" font-size="70%"{upright}>{t}</tspan>')
        else:
            spans.append(t)
    return (f'<text x="{x:.1f}" y="{y + label.size * 0.35:.1f}" font-size="{label.size:.0f}" fill="{color}" '
            f'text-anchor="middle"{extra}>{"".join(spans)}</text>')


def _head(tail, head, size=11.0, width=0.42):
    d = _unit(head[0] - tail[0], head[1] - tail[1])
    n = (-d[1], d[0])
    base = (head[0] - d[0] * size, head[1] - d[1] * size)
    return [head, (base[0] + n[0] * size * width, base[1] + n[1] * size * width),
            (base[0] - n[0] * size * width, base[1] - n[1] * size * width)]


def svg(drawing: Drawing, css_class: str = "dl-fbd") -> str:
    """The drawing as an SVG element: scales to its container, a text alternative for screen readers (aria-label)."""
    b = drawing.box
    width, height = b.x1 - b.x0, b.y1 - b.y0
    flip = lambda x, y: (x - b.x0, b.y1 - y)
    out = [f'<svg class="{css_class}" viewBox="0 0 {width:.1f} {height:.1f}" width="{width:.0f}" height="{height:.0f}" role="img" '
           f'aria-label="{html.escape(drawing.text)}" xmlns="http://www.w3.org/2000/svg" '
           f'style="max-width:{width * 1.25:.0f}px" font-family="Times New Roman, serif" font-style="italic">',
           f'<rect width="{width:.1f}" height="{height:.1f}" fill="#ffffff"/>']
    for line in drawing.lines:
        out.append(_svg_line(line, flip))
    for poly in drawing.polygons:
        pts = " ".join(f"{x:.1f},{y:.1f}" for x, y in (flip(*p) for p in poly))
        out.append(f'<polygon points="{pts}" fill="{BODY_FILL}" stroke="{BODY_STROKE}" stroke-width="2"/>')
    for cx, cy, r in drawing.circles:
        x, y = flip(cx, cy)
        out.append(f'<circle cx="{x:.1f}" cy="{y:.1f}" r="{r:.1f}" fill="{BODY_FILL}" stroke="{BODY_STROKE}" stroke-width="2"/>')
    for ax, ay, bx, by in drawing.rods:
        (x0, y0), (x1, y1) = flip(ax, ay), flip(bx, by)
        out.append(f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="{BODY_STROKE}" '
                   f'stroke-width="9" stroke-linecap="round"/>'
                   f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="{BODY_FILL}" '
                   f'stroke-width="5" stroke-linecap="round"/>')
    for dim in drawing.dims:
        out.append(_svg_dim(dim, flip))
    for arc in drawing.arcs:
        out.append(_svg_arc(arc, flip))
    for x, y, label in drawing.points:
        px, py = flip(x, y)
        out.append(f'<circle cx="{px:.1f}" cy="{py:.1f}" r="3" fill="{BODY_STROKE}"/>')
        out.append(_svg_text(label, flip, BODY_STROKE, ' font-style="normal" class="dl-fbd-point"'))
    for arrow in drawing.arrows:
        color = {"basis": BASIS_COLOR, "given": GIVEN_COLOR}.get(arrow.kind, LOAD_COLOR)
        head = _head(arrow.tail, arrow.head, 12 if arrow.kind != "basis" else 9)
        d = _unit(arrow.head[0] - arrow.tail[0], arrow.head[1] - arrow.tail[1])
        stop = (arrow.head[0] - d[0] * 8, arrow.head[1] - d[1] * 8)
        (x0, y0), (x1, y1) = flip(*arrow.tail), flip(*stop)
        widths = {"force": 3, "impulse": 3, "basis": 1.6, "given": 2.4}
        out.append(f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="{color}" '
                   f'stroke-width="{widths[arrow.kind]}"/>')
        pts = " ".join(f"{x:.1f},{y:.1f}" for x, y in (flip(*p) for p in head))
        fill = "#ffffff" if arrow.kind == "impulse" else color
        out.append(f'<polygon points="{pts}" fill="{fill}" stroke="{color}" stroke-width="2"/>')
        if arrow.label:
            cls = ' class="dl-fbd-label"' if arrow.kind != "basis" else ' class="dl-fbd-basis" font-style="normal" font-weight="bold"'
            out.append(_svg_text(arrow.label, flip, color, cls))
    for curl in drawing.curls:
        color = GIVEN_COLOR if curl.load == "given" else LOAD_COLOR
        out.append(_svg_curl(curl, flip, color))
        out.append(_svg_text(curl.label, flip, color, ' class="dl-fbd-label"'))
    out.append("</svg>")
    # (its attributes in single quotes: the SVG travels in JSON, where a double quote costs a backslash; no value
    # holds one, html.escape writes it &#x27;)
    return "".join(out).replace('"', "'")


def _curl_points(curl: Curl, n: int = 24):
    start, end = (-0.6 * math.pi, 0.9 * math.pi)
    pts = [(curl.centre[0] + curl.radius * math.cos(a), curl.centre[1] + curl.radius * math.sin(a))
           for a in (start + (end - start) * k / n for k in range(n + 1))]
    return pts if curl.ccw else pts[::-1]


def _svg_curl(curl: Curl, flip, color: str = LOAD_COLOR) -> str:
    pts = _curl_points(curl)
    path = " ".join(f"{x:.1f},{y:.1f}" for x, y in (flip(*p) for p in pts[:-2]))
    head = " ".join(f"{x:.1f},{y:.1f}" for x, y in (flip(*p) for p in _head(pts[-6], pts[-1], 11)))
    return (f'<polyline points="{path}" fill="none" stroke="{color}" stroke-width="3"/>'
            f'<polygon points="{head}" fill="{color}" stroke="{color}" stroke-width="2"/>')


def _hatches(line: Line, step: float = 9.0, depth: float = 8.0):
    """A support's short strokes on its fixed side, as (tail, tip) pairs in the drawing's units."""
    (ax, ay), (bx, by) = line.a, line.b
    n = math.hypot(bx - ax, by - ay) or 1.0
    ux, uy = (bx - ax) / n, (by - ay) / n
    side = (-uy * line.side, ux * line.side)
    out, t = [], step / 2
    while t < n:
        x, y = ax + ux * t, ay + uy * t
        out.append(((x, y), (x + (side[0] - ux) * depth, y + (side[1] - uy) * depth)))
        t += step
    return out


def _svg_line(line: Line, flip) -> str:
    (x0, y0), (x1, y1) = flip(*line.a), flip(*line.b)
    if line.style == "dashed":
        return (f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="{BODY_STROKE}" '
                f'stroke-width="1.4" stroke-dasharray="6 4"/>')
    out = [f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="{BODY_STROKE}" stroke-width="2.4"/>']
    for a, b in _hatches(line):
        (p, q), (r, t) = flip(*a), flip(*b)
        out.append(f'<line x1="{p:.1f}" y1="{q:.1f}" x2="{r:.1f}" y2="{t:.1f}" stroke="{BODY_STROKE}" stroke-width="1"/>')
    return "".join(out)


def _svg_dim(dim: Dim, flip) -> str:
    (x0, y0), (x1, y1) = flip(*dim.a), flip(*dim.b)
    heads = "".join('<polygon points="' + " ".join(f"{x:.1f},{y:.1f}" for x, y in (flip(*p) for p in _head(a, b, 8))) +
                    f'" fill="{BASIS_COLOR}"/>' for a, b in ((dim.b, dim.a), (dim.a, dim.b)))
    return (f'<line x1="{x0:.1f}" y1="{y0:.1f}" x2="{x1:.1f}" y2="{y1:.1f}" stroke="{BASIS_COLOR}" stroke-width="1.2"/>'
            + heads + _svg_text(dim.label, flip, BASIS_COLOR, ' class="dl-sketch-given"'))


def _arc_points(arc: Arc, n: int = 20):
    return [(arc.centre[0] + arc.radius * math.cos(a), arc.centre[1] + arc.radius * math.sin(a))
            for a in (arc.start + (arc.end - arc.start) * k / n for k in range(n + 1))]


def _svg_arc(arc: Arc, flip) -> str:
    path = " ".join(f"{x:.1f},{y:.1f}" for x, y in (flip(*p) for p in _arc_points(arc)))
    return (f'<polyline points="{path}" fill="none" stroke="{BASIS_COLOR}" stroke-width="1.4"/>'
            + _svg_text(arc.label, flip, BASIS_COLOR, ' class="dl-sketch-given"'))


# ------------------------------------------------------------------------------------------------
# TikZ (the .tex): the same shapes, in cm

def tikz(drawing: Drawing, width_cm: float = 7.0) -> str:
    b = drawing.box
    k = width_cm / (b.x1 - b.x0)
    p = lambda x, y: f"({(x - b.x0) * k:.2f},{(y - b.y0) * k:.2f})"
    out = [r"\begin{tikzpicture}[line cap=round, >=latex]"]
    for line in drawing.lines:
        out.append((r"\draw[dashed] " if line.style == "dashed" else r"\draw[thick] ") + f"{p(*line.a)} -- {p(*line.b)};")
        if line.style != "dashed":
            out += [rf"\draw[thin] {p(*a)} -- {p(*b)};" for a, b in _hatches(line)]
    for poly in drawing.polygons:
        out.append(r"\draw[fill=black!8, thick] " + " -- ".join(p(*q) for q in poly) + " -- cycle;")
    for cx, cy, r in drawing.circles:
        out.append(rf"\draw[fill=black!8, thick] {p(cx, cy)} circle ({r * k:.2f});")
    for ax, ay, bx, by in drawing.rods:
        out.append(rf"\draw[line width=3pt, black!70] {p(ax, ay)} -- {p(bx, by)};")
    for x, y, label in drawing.points:
        out.append(rf"\fill {p(x, y)} circle (1.2pt);")
        out.append(rf"\node[font=\small] at {p(label.x, label.y)} {{${label.tex}$}};")
    for arrow in drawing.arrows:
        style = {"force": "->, very thick, red!70!black", "impulse": "-{Latex[open]}, very thick, red!70!black",
                 "basis": "->, thin", "given": "->, thick, blue!70!black"}[arrow.kind]
        style = style.replace("-{Latex[open]}", "->, double")  # without the arrows.meta library: a double shaft
        out.append(rf"\draw[{style}] {p(*arrow.tail)} -- {p(*arrow.head)};")
        if arrow.label:
            tex = arrow.label.tex if arrow.kind != "basis" else arrow.label.tex
            out.append(rf"\node[font=\small] at {p(arrow.label.x, arrow.label.y)} {{${tex}$}};")
    for curl in drawing.curls:
        pts = _curl_points(curl)
        color = "blue!70!black" if curl.load == "given" else "red!70!black"
        out.append(rf"\draw[->, very thick, {color}] " + " -- ".join(p(*q) for q in pts) + ";")
        out.append(rf"\node[font=\small] at {p(curl.label.x, curl.label.y)} {{${curl.label.tex}$}};")
    for dim in drawing.dims:
        out.append(rf"\draw[<->, thin] {p(*dim.a)} -- {p(*dim.b)};")
        out.append(rf"\node[font=\small] at {p(dim.label.x, dim.label.y)} {{${dim.label.tex}$}};")
    for arc in drawing.arcs:
        out.append(r"\draw[thin] " + " -- ".join(p(*q) for q in _arc_points(arc)) + ";")
        out.append(rf"\node[font=\small] at {p(arc.label.x, arc.label.y)} {{${arc.label.tex}$}};")
    out.append(r"\end{tikzpicture}")
    return "\n".join(out)


# ------------------------------------------------------------------------------------------------
# Plain data (the notebook draws it with matplotlib from this)

def as_data(drawing: Drawing) -> dict:
    """The drawing as JSON-able data: what the notebook's matplotlib cell draws."""
    lab = lambda l: [l.tex, round(l.x, 1), round(l.y, 1)] if l else None
    return {
        "title": drawing.title, "box": [drawing.box.x0, drawing.box.y0, drawing.box.x1, drawing.box.y1],
        "circles": [[round(v, 1) for v in c] for c in drawing.circles],
        "rods": [[round(v, 1) for v in r] for r in drawing.rods],
        "polygons": [[[round(x, 1), round(y, 1)] for x, y in poly] for poly in drawing.polygons],
        "points": [[round(x, 1), round(y, 1), lab(l)] for x, y, l in drawing.points],
        "arrows": [[[round(v, 1) for v in a.tail], [round(v, 1) for v in a.head], a.kind, lab(a.label)]
                   for a in drawing.arrows],
        "curls": [[[round(v, 1) for v in _xy] for _xy in _curl_points(c)] + [lab(c.label)] for c in drawing.curls],
        "text": drawing.text,
    }


# ------------------------------------------------------------------------------------------------
# The drawing exercise's blank: the bodies isolated, every named point and the basis, no load

def blank(diagram: Diagram, values) -> dict:
    """What the drawing exercise (ui/plotly_component/draw.js) is sent: the bodies isolated with every
    named point marked and the basis, as SVG with room around for the student's arrows, and each
    point's place in it (SVG units, y down). Nothing of the loads: not their number, kinds or places."""
    drawing = layout(replace(diagram, loads=()), values, every_point=True)
    room = ARROW + FONT * 1.5
    b = drawing.box
    drawing.box = Box(b.x0 - room, b.y0 - room, b.x1 + room, b.y1 + room)
    names = ", ".join(f"{body.name} with its points {', '.join(n for n in body.points if not n.startswith('_'))}"
                      for body in diagram.bodies)
    axes = " and ".join(plain_label(e) for e in diagram.basis)
    drawing.text = f"{names} isolated, to draw the loads on; the basis {axes}."
    spots = {}
    for body in diagram.bodies:
        for name in body.points:
            if not name.startswith("_"):
                spots[(body.name, name)] = None
    # the marked points, in the order laid out, matched back to their bodies by position
    placed = iter(drawing.points)
    points = []
    for (body_name, name), _ in spots.items():
        x, y, label = next(placed)
        assert label.tex == name
        points.append({"body": body_name, "name": name, "x": round(x - drawing.box.x0, 1),
                       "y": round(drawing.box.y1 - y, 1)})
    return {"svg": svg(drawing, "dl-draw-body"), "points": points, "bodies": [b.name for b in diagram.bodies],
            "basis": [plain_label(e) for e in diagram.basis], "law": diagram.law,
            "size": [round(drawing.box.x1 - drawing.box.x0, 1), round(drawing.box.y1 - drawing.box.y0, 1)]}


# ------------------------------------------------------------------------------------------------
# A solution's diagrams

def drawings(solver, solution) -> list[Drawing]:
    """The free-body diagrams of ``solution`` (its problem's ``free_body_diagrams``), laid out for its
    numbers; none for a solution without answers (the method shown past a physical limit)."""
    declare = getattr(solver, "free_body_diagrams", None)
    if declare is None or not solution.answers:
        return []
    return [layout(d, d.values(solution)) for d in declare(solution.params)]


# ------------------------------------------------------------------------------------------------
# The stage's Forces overlay: the same loads on the motion, each frame's to its size

OVERLAY_NAME = "forces (free-body diagram)"
OVERLAY_COLOR = "#b3261e"
_OVERLAY_LENGTH = 0.2  # the largest force (or impulse) drawn this fraction of the stage's width


def _html_label(tex: str) -> str:
    return "".join(f"<sub>{html.escape(t)}</sub>" if w.startswith("sub") else f"<sup>{html.escape(t)}</sup>" if w
                   else html.escape(t) for t, w in runs(tex))


def _per_frame(expr, values: dict, frames: int):
    import numpy as np

    expr = sp.sympify(expr)
    free = sorted(expr.free_symbols, key=lambda s: s.name)
    if not free:
        return np.full(frames, float(expr))
    fn = sp.lambdify(free, expr, modules="numpy")
    with np.errstate(all="ignore"):
        return np.broadcast_to(np.asarray(fn(*(np.asarray(values[s], dtype=float) for s in free)), dtype=float),
                               (frames,)).copy()


def overlaid(solver, params) -> list:
    """The diagrams the stage's overlay draws for these parameters' options (those that declare their
    frames); [] where the problem declares none."""
    declare = getattr(solver, "free_body_diagrams", None)
    return [] if declare is None else [d for d in declare(params) if d.frames is not None]


def _tracks(diagrams) -> dict:
    """Every arrow the overlay draws, in order: (kind, body, symbol) -> the loads it draws (one load a
    phase: the same symbol on the same body in two phases is one arrow), couples left to the diagram."""
    tracks: dict[tuple[str, str, str], list] = {}
    for d in diagrams:
        for load in d.loads:
            if load.kind != "couple":
                tracks.setdefault((load.kind, load.on, load.symbol), []).append((d, load))
    return tracks


def _geometry(d, load, at) -> tuple:
    """(point x, y, vector x, y, centre x, y) of ``load`` with ``at`` (expr -> its value: numbers per
    frame, or the key frame's expressions)."""
    body = d.body(load.on)
    return (*(at(c) for c in body.points[load.at]), *(at(c) for c in load.vector),
            *(at(c) for c in body.points[body.centre]))


def _drawn(kind: str, symbol: str, geometry, scale, length_scale: float, xp) -> tuple:
    """One arrow and its label's place: (arrow xs, ys, label x, y), each row a frame. A push (a contact)
    is drawn with its head at the point, a body force (the weight) from it. ``xp``: numpy, or
    solvers.live's namespace (the key frame's pose as expressions)."""
    from viz.common import arrows

    px, py, vx, vy, cx, cy, body_force = geometry
    dx, dy = vx * scale, vy * scale
    push = xp.where(xp.less(vx * (px - cx) + vy * (py - cy), 0), 1.0, 0.0) * (0.0 if body_force else 1.0)
    tail_x, tail_y = px * length_scale - push * dx, py * length_scale - push * dy
    xs, ys = arrows(tail_x, tail_y, dx, dy, xp=xp)
    beyond = 1.18 - 1.36 * push  # a label past the head, or before the tail of a push
    return xs, ys, tail_x + dx * beyond, tail_y + dy * beyond


def _label_side(away_x, away_y) -> str:
    """Where a label's text stands from its point: on the side away from its arrow (``away``: from the
    arrow's first point to the label's, per frame; the first frame that draws it decides), so that a
    name beside a short horizontal arrow is not written over its head ("2μN" under the traction's)."""
    import numpy as np

    drawn = np.flatnonzero(np.isfinite(away_x) & np.isfinite(away_y))
    if not len(drawn):
        return "middle center"
    ax, ay = away_x[drawn[0]], away_y[drawn[0]]
    if abs(ax) > abs(ay):  # (raised off the line the arrow lies on)
        return "top right" if ax > 0 else "top left"
    return "top center" if ay > 0 else "bottom center"


def _names(tracks) -> list[tuple[str, str]]:
    """(arrow's trace name, label's trace name) per track, each its own (a pose finds a trace by its
    name; a pair's two halves share a symbol): the first arrow carries the legend's entry."""
    return [(OVERLAY_NAME if n == 0 else f"{kind} on {on}: {plain_label(symbol)}", f"label {plain_label(symbol)} on {on}")
            for n, (kind, on, symbol) in enumerate(tracks)]


def overlay(solver, solution, motion: dict, width: float, length_scale: float = 1.0) -> tuple[list, dict]:
    """The loads of every phase's diagram on the stage's motion (``Diagram.frames``): one moving arrow
    per load (a reaction of unknown direction as its resultant) and its label, drawn in the frames of
    its phase, to one scale for the forces and one for the impulses (the largest of each
    ``_OVERLAY_LENGTH`` of the stage's ``width``); couples are left to the diagram. ``length_scale``:
    the page's length unit per metre. (traces, scales: kind -> drawn length per unit of load, what a
    drag's pose keeps, ``overlay_pose``); empty where the problem declares no frames (a 3-D stage)."""
    import numpy as np

    from viz.common import line, moving, r

    diagrams = overlaid(solver, solution.params)
    tracks = _tracks(diagrams)
    frames = len(motion["t"])
    values = {id(d): {k: np.asarray(v, dtype=float) for k, v in d.frames(solution, motion).items()} for d in diagrams}
    geometry = {}
    for key, loads in tracks.items():
        merged = np.full((6, frames), np.nan)
        for d, load in loads:  # each phase's frames (NaN outside it)
            new = np.array(_geometry(d, load, lambda c: _per_frame(c, values[id(d)], frames)))
            here = np.isfinite(new).all(axis=0)
            merged[:, here] = new[:, here]
        geometry[key] = (*merged, loads[0][1].by == "gravity")
    scales = {}
    for kind in ("force", "impulse"):
        sizes = [np.hypot(g[2], g[3]) for (k, _, _), g in geometry.items() if k == kind]
        biggest = max((np.nanmax(size, initial=0.0) for size in sizes), default=0.0)
        if sizes:  # (no arrow at all where every load of the kind is zero: NaN)
            scales[kind] = float(_OVERLAY_LENGTH * width / biggest) if biggest > 0 else float("nan")
    traces = []
    for ((kind, on, symbol), g), (name, label_name) in zip(geometry.items(), _names(tracks)):
        with np.errstate(invalid="ignore"):
            xs, ys, label_x, label_y = _drawn(kind, symbol, g, scales[kind], length_scale, np)
        style = line(None, None, name, OVERLAY_COLOR, width=3 if kind == "force" else 5, show_legend=not traces)
        style |= {"legendgroup": "forces", "meta": [on, symbol]}  # (which load: the tests read it)
        traces.append(moving(style, xs, ys))
        label = {"type": "scatter", "mode": "text", "x": None, "y": None, "text": [_html_label(symbol)],
                 "textfont": {"color": OVERLAY_COLOR, "size": 15}, "hoverinfo": "skip", "showlegend": False,
                 "legendgroup": "forces", "name": label_name, "cliponaxis": False,
                 "textposition": _label_side(label_x - xs[:, 0], label_y - ys[:, 0])}
        traces.append(moving(label, r(label_x)[:, None], r(label_y)[:, None]))
    return traces, scales


SCALE_NAMES = {"force": "overlay_force_scale", "impulse": "overlay_impulse_scale"}  # (a pose's parameters)


def overlay_pose(solver, p, a, length_scale: float, xp) -> dict:
    """The overlay's arrows and labels at the stage figure's key frame (``Diagram.key``), as
    ``key_pose`` draws a figure's bodies there: trace name -> (xs, ys), from the parameters ``p`` and
    the answers ``a`` (numbers; or solvers.live's symbols, the browser's drag, with ``xp`` its
    namespace), at the scales ``p[SCALE_NAMES[kind]]`` (the server's run's: an arrow keeps its scale
    while a control is dragged). An arrow no phase draws at that frame is left out."""
    import numpy as np

    diagrams = overlaid(solver, p)
    keyed = {id(d): {sym: sp.sympify(v) for sym, v in d.key(p, a).items()} for d in diagrams if d.key is not None}
    tracks, drawn = _tracks(diagrams), {}
    for ((kind, on, symbol), loads), (name, label_name) in zip(tracks.items(), _names(tracks)):
        d, load = next(((d, load) for d, load in loads if id(d) in keyed), (None, None))
        if d is None:
            continue
        at = lambda c: np.array([sp.sympify(c).xreplace(keyed[id(d)])], dtype=object)  # noqa: E731
        g = (*_geometry(d, load, at), load.by == "gravity")
        if xp is np:  # numbers (the server's check of the browser's pose)
            g = (*(np.asarray(v, dtype=float) for v in g[:6]), g[6])
        xs, ys, label_x, label_y = _drawn(kind, symbol, g, p[SCALE_NAMES[kind]], length_scale, xp)
        drawn[name] = (xs[0], ys[0])
        drawn[label_name] = (label_x, label_y)
    return drawn


def with_overlay(figure, traces: list, scales: dict | None = None):
    """The stage figure with the overlay's traces added to its animation (a new Figure), and their
    ``scales`` (``overlay``) in its ``extra``: what a drag's pose of them keeps (ui/live.py)."""
    from dataclasses import replace as _replace

    if not traces:
        return figure
    spec = dict(figure.spec)
    anim = dict(spec["animation"])
    frames = len(anim["times"])
    for trace in traces:  # one row per frame of the figure's own, or the arrows run out of step
        if any(len(rows) != frames for rows in trace.per_frame.values()):
            raise ValueError(f"the forces have {[len(r) for r in trace.per_frame.values()]} frames, the figure {frames}")
    data = list(spec["data"])
    start = len(data)
    data += [t.first() for t in traces]
    anim["traces"] = list(anim["traces"]) + list(range(start, start + len(traces)))
    anim["coords"] = list(anim["coords"]) + [t.per_frame for t in traces]
    spec["data"], spec["animation"] = data, anim
    layout = spec.get("layout", {})
    if "range" in layout.get("xaxis", {}) and "range" in layout.get("yaxis", {}):  # the arrows and their names held inside the axes
        from viz.common import holding, r

        labels = [t for t in traces if t.style.get("mode") == "text"]  # a name's text runs on past its point
        x_range, y_range = holding(tuple(layout["xaxis"]["range"]), tuple(layout["yaxis"]["range"]),
                                   [t for t in traces if t not in labels])
        x_range, y_range = holding(x_range, y_range, labels, pad=0.12)
        spec["layout"] = {**layout, "xaxis": {**layout["xaxis"], "range": r(x_range)},
                          "yaxis": {**layout["yaxis"], "range": r(y_range)}}
    words = " Red arrows: the forces of the free-body diagram, each drawn to its size in that frame."
    return _replace(figure, spec=spec, description=figure.description + words,
                    extra={**figure.extra, "overlay_scales": dict(scales or {})})
