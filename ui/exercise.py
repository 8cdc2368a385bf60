"""The problem as an exercise states it, for every view that asks a student for an answer (Practice,
an assignment, a question put to the room): its sketch above its givens, what to find, and the unit a
number typed alone is read in. A kit piece: no feature of its own."""
from __future__ import annotations

import base64

from practice.judge import Judge
from solvers.core import Choice
from solvers import units
from solvers.catalog import Problem
from ui.results import plain
from viz.catalog import drawings
from viz.diagram import svg


def read_in(answer, system: str) -> str:
    """The unit a number typed alone is read in, in words for degrees; "" for a number without one."""
    unit = units.unit(answer.dimension, system) if answer.dimension in units.DIMENSIONS else ""
    return "degrees" if unit == "°" else unit


def answer_choice(answer, system: str) -> str:
    """An answer as the answer box offers it: its label and the unit a number typed alone is read in
    ("Angular velocity just after impact, in rad/s")."""
    return answer.heading + (f", in {unit}" if (unit := read_in(answer, system)) else "")


def statement(problem: Problem, params: dict, answers, system: str, judge: Judge | None,
              heading: str = "### The problem") -> str:
    """The problem as an exercise: its sketch above its table, as the worked solutions open (an image with its
    text alternative: an SVG in the page's Markdown is taken out by Streamlit's sanitiser), every given with
    its value (and, with a ``judge``, the name to type it by), then what to find (``answers``, if any)."""
    rows = ["| given | symbol, typed as | value |", "|---|---|---|"]
    for p in problem.solver.PARAMS:
        value = params[p.name]
        if isinstance(p, Choice):
            rows.append(f"| {plain(p.label)} | | {plain(p.label_of(value))} |")
        else:
            sym = judge.givens.get(p.name) if judge is not None else None
            typed = f"`{judge.typed_name(sym)}`" if sym is not None else ""
            rows.append(f"| {plain(p.label)} | ${p.symbol}$ {typed} | {units.format_quantity(value, p.dimension, system)} |")
    find = "\n".join(f"- {plain(a.heading)}, ${a.symbol}$" + (f", in {plain(u)}" if (u := read_in(a, system)) else "")
                     for a in answers)
    return "\n\n".join([heading, sketch_image(problem, params), "\n".join(rows), *(["**Find**", find] if answers else [])])


_SKETCHES: dict[tuple[str, str], str] = {}  # (problem, its numbers) -> the sketch as Markdown: each Check reruns the page


def sketch_image(problem: Problem, params: dict) -> str:
    """The problem's sketch (viz/sketch.py) at ``params`` as a Markdown image: its SVG in a data: URI, its words
    as the alt text."""
    key = (problem.id, repr(sorted(params.items())))
    kept = _SKETCHES.get(key)
    if kept is None:
        drawing = drawings(problem.id).sketch(params)
        data = base64.b64encode(svg(drawing, "dl-sketch").encode()).decode()
        if len(_SKETCHES) > 512:
            _SKETCHES.clear()
        kept = _SKETCHES[key] = f"![{plain(drawing.text)}](data:image/svg+xml;base64,{data})"
    return kept
