"""The problem's sketch, as the worked solutions open each problem ("as shown in the figure below"): the
bodies in their starting configuration, the supports, the givens' lengths, angles and velocities marked
and named with the symbols the statement's table gives them (the problem's PARAMS), and the basis. It
heads Practice, an assignment's problem and a handout's statement, so it shows givens only: no answer,
no load, no later instant (tests/pages/test_sketch.py reads what it draws).

A problem's viz module declares ``sketch(params) -> Drawing`` with the ``Sketch`` builder below (metres,
y up); it is laid out as a viz.diagram ``Drawing``, so the page's SVG, the handouts' Markdown and their
TikZ draw it as they draw a free-body diagram."""
from __future__ import annotations

import math

from viz.diagram import (MARGIN, POINT_FONT, Arc, Arrow, Box, Curl, Dim, Drawing, Label,
                         Line, plain_label)

SIZE = 260.0  # the sketch's largest extent, in the drawing's units
GIVEN = "given"  # an arrow's kind: a given velocity


class Sketch:
    """A sketch built in metres (y up): call the shapes, then ``drawing()``."""

    def __init__(self, solver, title: str):
        self.symbols = {p.name: p.symbol for p in solver.PARAMS if hasattr(p, "symbol")}
        self.title = title
        self.shapes: list[tuple] = []
        self.said: list[str] = []

    def sym(self, name: str) -> str:
        """A given's symbol as the statement's table writes it."""
        return self.symbols[name]

    # -- bodies and supports
    def rod(self, a, b, width: float = 9.0):
        self.shapes.append(("rod", a, b, width))

    def disk(self, centre, radius: float):
        self.shapes.append(("circle", centre, radius))

    def polygon(self, corners):
        self.shapes.append(("polygon", list(corners)))

    def support(self, a, b, side: int = 1):
        """A fixed surface from a to b (a wall, the floor), hatched on its ``side`` (+1: to the left of a→b)."""
        self.shapes.append(("support", a, b, side))

    def point(self, p, name: str, away=(-1.0, -1.0), distance: float = 12.0):
        """A named point, its letter ``distance`` (the drawing's units) from it toward ``away``."""
        self.shapes.append(("point", p, name, away, distance))

    def dashed(self, a, b):
        self.shapes.append(("dashed", a, b))

    # -- the givens
    def length(self, a, b, given: str, offset: float = 0.0):
        """The distance a→b, marked with its symbol, ``offset`` (metres) to the left of a→b."""
        self.shapes.append(("dim", a, b, self.sym(given), offset))
        self.said.append(plain_label(self.sym(given)))

    def angle(self, vertex, start: float, end: float, given: str, radius: float):
        """The angle at ``vertex`` from direction ``start`` to ``end`` (radians, counter-clockwise)."""
        self.shapes.append(("arc", vertex, radius, start, end, self.sym(given)))
        self.said.append(plain_label(self.sym(given)))

    def velocity(self, p, direction: float, length: float, given: str):
        self.shapes.append(("velocity", p, direction, length, self.sym(given)))
        self.said.append(plain_label(self.sym(given)))

    def spin(self, centre, radius: float, ccw: bool, given: str):
        self.shapes.append(("spin", centre, radius, ccw, self.sym(given)))
        self.said.append(plain_label(self.sym(given)))

    # -- laid out
    def drawing(self, basis=(r"\mathbf{E}_x", r"\mathbf{E}_y")) -> Drawing:
        xs, ys = [], []
        for s in self.shapes:
            for v in s[1:3]:
                if isinstance(v, tuple) and len(v) == 2:
                    xs.append(v[0])
                    ys.append(v[1])
            if s[0] == "circle":
                xs += [s[1][0] - s[2], s[1][0] + s[2]]
                ys += [s[1][1] - s[2], s[1][1] + s[2]]
        k = SIZE / (max(max(xs) - min(xs), max(ys) - min(ys)) or 1.0)
        to = lambda p: (p[0] * k, p[1] * k)  # noqa: E731
        d = Drawing(self.title)
        for s in self.shapes:
            kind = s[0]
            if kind == "rod":
                d.rods.append((*to(s[1]), *to(s[2])))
            elif kind == "circle":
                d.circles.append((*to(s[1]), s[2] * k))
            elif kind == "polygon":
                d.polygons.append([to(c) for c in s[1]])
            elif kind == "support":
                d.lines.append(Line(to(s[1]), to(s[2]), "support", s[3]))
            elif kind == "dashed":
                d.lines.append(Line(to(s[1]), to(s[2]), "dashed"))
            elif kind == "point":
                x, y = to(s[1])
                ax, ay = s[3]
                n = math.hypot(ax, ay) or 1.0
                d.points.append((x, y, Label(s[2], x + s[4] * ax / n, y + s[4] * ay / n, POINT_FONT)))
            elif kind == "dim":
                (ax, ay), (bx, by) = to(s[1]), to(s[2])
                n = math.hypot(bx - ax, by - ay) or 1.0
                nx, ny = -(by - ay) / n, (bx - ax) / n  # to the left of a→b
                off = s[4] * k
                a2, b2 = (ax + nx * off, ay + ny * off), (bx + nx * off, by + ny * off)
                side = 1 if off >= 0 else -1
                mid = ((a2[0] + b2[0]) / 2 + nx * 13 * side, (a2[1] + b2[1]) / 2 + ny * 13 * side)
                d.dims.append(Dim(a2, b2, Label(s[3], *mid)))
            elif kind == "arc":
                (cx, cy), r = to(s[1]), s[2] * k
                middle = (s[3] + s[4]) / 2
                d.arcs.append(Arc((cx, cy), r, s[3], s[4], Label(s[5], cx + (r + 13) * math.cos(middle),
                                                                     cy + (r + 13) * math.sin(middle))))
            elif kind == "velocity":
                (x, y), length = to(s[1]), s[3] * k
                u = (math.cos(s[2]), math.sin(s[2]))
                head = (x + u[0] * length, y + u[1] * length)
                d.arrows.append(Arrow((x, y), head, GIVEN, Label(s[4], head[0] + u[0] * 12 - u[1] * 10,
                                                                  head[1] + u[1] * 12 + u[0] * 10)))
            elif kind == "spin":
                (cx, cy), r = to(s[1]), s[2] * k
                d.curls.append(Curl((cx, cy), r, s[3], Label(s[4], cx + r * 0.75 + 10, cy + r * 0.75 + 8), GIVEN))
        _separate(d.labels)
        _basis_corner(d, basis)
        d.box = _box(d)
        d.text = (f"{self.title}. Marked: {', '.join(self.said)}; the basis {plain_label(basis[0])}, "
                  f"{plain_label(basis[1])}.")
        return d


def _separate(labels: list[Label]) -> None:
    """Each label moved, if it lies on one placed before it, to the nearest free place around it (points'
    letters first, as laid out)."""
    placed: list[Box] = []
    for label in labels:
        x, y = label.x, label.y
        for radius in (0, 6, 10, 14, 18, 24, 30, 38, 46):
            options = [(x, y)] if radius == 0 else [(x + radius * math.cos(k * math.pi / 4), y + radius * math.sin(k * math.pi / 4))
                                                   for k in range(8)]
            free = next(((px, py) for px, py in options
                         if not any(Label(label.tex, px, py, label.size).box.overlaps(b, 1.0) for b in placed)), None)
            if free is not None:
                label.x, label.y = free
                break
        placed.append(label.box)


def _basis_corner(d: Drawing, basis) -> None:
    b = _box(d, margin=0)
    x0, y0, length = b.x0 - 62, b.y0 + 4, 36.0
    for (dx, dy), tex in (((1, 0), basis[0]), ((0, 1), basis[1])):
        head = (x0 + dx * length, y0 + dy * length)
        d.arrows.append(Arrow((x0, y0), head, "basis", Label(tex, head[0] + dx * 14 + dy * 2, head[1] + dy * 12, POINT_FONT)))


def _box(d: Drawing, margin: float = MARGIN) -> Box:
    xs, ys = [], []
    for x0, y0, x1, y1 in d.rods:
        xs += [x0, x1]
        ys += [y0, y1]
    for cx, cy, r in d.circles:
        xs += [cx - r, cx + r]
        ys += [cy - r, cy + r]
    for poly in d.polygons:
        xs += [p[0] for p in poly]
        ys += [p[1] for p in poly]
    for line in d.lines:
        xs += [line.a[0], line.b[0]]
        ys += [line.a[1], line.b[1]]
    for a in d.arrows:
        xs += [a.tail[0], a.head[0]]
        ys += [a.tail[1], a.head[1]]
    for c in d.curls:
        xs += [c.centre[0] - c.radius, c.centre[0] + c.radius]
        ys += [c.centre[1] - c.radius, c.centre[1] + c.radius]
    for label in d.labels:
        box = label.box
        xs += [box.x0, box.x1]
        ys += [box.y0, box.y1]
    return Box(min(xs) - margin - 8, min(ys) - margin - 8, max(xs) + margin + 8, max(ys) + margin + 8)


__all__ = ["Sketch", "Drawing"]
