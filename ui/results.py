"""How a Solution is shown: answers with units, the derivation step by step, the ledger of checks,
the worked solution's slips, and a refused case explained (never a traceback)."""
from __future__ import annotations

import re

import orjson
import streamlit as st

from solvers.core import Answer, PhysicalLimitError, Solution
from solvers import registry, units
from solvers.solution import PARTS
from ui import figure
from ui.equations import WIDE_WIDTH_EM, wide_too
from viz import diagram

ANSWERS_HEADING = "Answers"
LEDGER_HEADING = "Across the impact"
CHECKS_HEADING = "Checked a second way"


def answer_section(solution: Solution, answers: tuple[Answer, ...], system: str, live: dict | None = None) -> None:
    """Answers, notes, the ledger across an impact and the checks, in one element of our own
    (ui/plotly_component/text.js, as the derivation): the values go as data, each symbol is typeset
    once in the browser, and a cell a new value does not change is left alone. ``live``: what makes
    them follow a dragged lesson control (ui.live.payload; the lesson page's only)."""
    figure.declared(figure.ANSWERS)(data=answers_data(solution, answers, system, live), key="answers")


def answers_data(solution: Solution, answers: tuple[Answer, ...], system: str, live: dict | None = None) -> bytes:
    """What the answers' element is sent (``answer_section``)."""
    payload = {"view": "answers", "heading": ANSWERS_HEADING, "answers": answer_rows(solution, answers, system),
               "notes": list(solution.notes), "ledger_heading": LEDGER_HEADING, "ledger": ledger(solution, system),
               "checks_heading": CHECKS_HEADING, "checks": checks(solution), "katex": figure.katex_url()}
    if live is not None:
        payload["live"] = live
    return orjson.dumps(payload)


def answer_rows(solution: Solution, answers: tuple[Answer, ...], system: str) -> list[list[str]]:
    """[symbol (LaTeX), quantity, value with its unit] per answer; an angle in degrees and radians."""
    rows = []
    for a in answers:
        value = units.format_quantity(solution.answers[a.name], a.dimension, system)
        if a.dimension == "angle":
            value += f" ({units.format_value(solution.answers[a.name])} rad)"
        rows.append([a.symbol, a.label, value])
    return rows


_MARKDOWN_SPECIAL = re.compile(r"([\\`*_{}\[\]()#+!|<>~$-])")


def plain(text: str) -> str:
    """Text shown literally inside Streamlit's Markdown: no links, images, formatting or math."""
    return _MARKDOWN_SPECIAL.sub(r"\\\1", text)


def plain_with_math(text: str) -> str:
    """A solver's text (a step's title) in Streamlit's Markdown: its $inline math$ typeset, every
    other character shown literally."""
    return "".join(part if part.startswith("$") else plain(part) for part in re.split(r"(\$[^$]+\$)", text))


_ASCII_PUNCTUATION = re.compile(r"([!-/:-@\[-`{-~])")


def literal(text: str) -> str:
    """Stored text (what a student typed, a slip's name, a label) shown as it is in an ``st.table``
    cell, which Streamlit renders as Markdown: every ASCII punctuation mark escaped, as CommonMark
    allows, so no link, image, bare URL or e-mail address, entity, emphasis, math or directive."""
    return _ASCII_PUNCTUATION.sub(r"\\\1", text)


DERIVATION_HEADING = "Derivation, step by step"
SLIPS_HEADING = "Common slips in the worked solution"


def derivation(solution: Solution, caption: str = "", slips: tuple[str, ...] = ()) -> None:
    """The derivation, all steps under a grey caption, then the worked solution's common slips, in
    one element of our own (ui/plotly_component/text.js): the browser typesets each equation
    once per distinct text and leaves alone the steps a new value does not change (the symbolic
    ones), where Streamlit's Markdown would typeset and lay out the whole derivation again. A
    display equation too wide for a phone is broken over aligned rows (``broken``), and also at a laptop's
    width (``wide_too``: most, whole)."""
    figure.declared(figure.DERIVATION)(data=derivation_data(solution, caption, slips), key="derivation")


def parts(steps) -> list[list]:
    """[index of the first step, heading] for each of the course's four steps the derivation has."""
    out, last = [], None
    for i, step in enumerate(steps):
        if step.part != last:
            out.append([i, PARTS[step.part]])
            last = step.part
    return out


def diagrams(solution: Solution) -> list[list[str]]:
    """[SVG, its caption] for each free-body diagram of the solution (Step 2): the text alternative is the SVG's
    aria-label, the caption its head ("Free-body diagram, against the wall")."""
    if solution.problem not in registry.PROBLEM_IDS or not solution.answers:
        return []
    key = (solution.problem, tuple(sorted(solution.params.items())))
    drawn = _DRAWN.get(key)
    if drawn is None:  # drawn once per state, as the solution and its figures are (ui.page._computed)
        drawn = [[diagram.svg(d), diagram.caption(d.title)] for d in diagram.drawings(registry.solver(solution.problem), solution)]
        if len(_DRAWN) >= 256:
            _DRAWN.pop(next(iter(_DRAWN)), None)
        _DRAWN[key] = drawn
    return drawn


_DRAWN: dict[tuple, list[list[str]]] = {}  # (problem, parameters) -> the diagrams drawn, oldest first


def derivation_data(solution: Solution, caption: str = "", slips: tuple[str, ...] = ()) -> bytes:
    """What the derivation's element is sent (``derivation``): the steps under the course's four
    headings, the free-body diagrams drawn at the head of Step 2."""
    payload = {"view": "derivation", "heading": DERIVATION_HEADING, "caption": caption,
               "steps": [[step.title, *wide_too(step.latex)] for step in solution.steps], "wide_em": WIDE_WIDTH_EM,
               "parts": parts(solution.steps), "diagrams": diagrams(solution),
               "slips_heading": SLIPS_HEADING, "slips": list(slips), "katex": figure.katex_url()}
    return orjson.dumps(payload)


def checks(solution: Solution) -> list[list]:
    """The conservation ledger: [agrees?, name, closed form, second method, why] per check, each
    closed-form answer beside an independent second method."""
    return [[c.ok, c.name, units.format_value(c.closed_form, 8), units.format_value(c.second_method, 8), c.explanation]
            for c in solution.checks]


def ledger(solution: Solution, system: str) -> list[list]:
    """Before and after the impact: [quantity, before, after, conserved?, why] per row."""
    return [[row.quantity, units.format_quantity(row.before, row.dimension, system),
             units.format_quantity(row.after, row.dimension, system), row.conserved, row.why]
            for row in solution.ledger]


def refused(error: ValueError, system: str, limit_labels: dict[str, tuple[str, str]] | None = None) -> None:
    """A case the model cannot describe, or a value out of range: the reason, and the limit, named
    by the problem's ``LIMIT_LABELS`` (attribute -> (label, dimension))."""
    st.error(str(error), icon=":material/block:")
    if isinstance(error, PhysicalLimitError):
        cols = st.columns(max(1, len(error.limits)))
        for col, (name, value) in zip(cols, error.limits.items()):
            label, dimension = (limit_labels or {}).get(name, (name, "dimensionless"))
            col.metric(label, units.format_quantity(value, dimension, system))
