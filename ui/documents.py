"""The page taken home: one problem's state as a document (the givens, what to find, the answers,
the derivation, the checks and the worked solution's slips), written as standalone LaTeX (amsmath;
compiles with pdflatex as it is) or as Markdown with ``$$`` math.

Nothing here is typed twice: the steps are the solver's own LaTeX, the values are formatted by
``solvers.units`` as the page formats them, and an exercise (the Practice view before "Show the
solution", or a handout's statement) keeps the method's steps that the page's own filter keeps
(``practice.method.result_forms``). No Streamlit calls (ui/takehome.py offers the files on the page).
"""
from __future__ import annotations

import re
import unicodedata
from dataclasses import dataclass, replace

from solvers import units
from solvers.core import Choice, Solution
from ui import results
from solvers.catalog import Problem
from ui.equations import broken
from solvers.solution import PARTS
from practice.method import exercise_steps as method_steps
from viz import diagram as fbd
from viz.catalog import drawings


@dataclass(frozen=True)
class Document:
    """What a printed page says, as text and LaTeX. ``steps`` are (title, LaTeX or "" where an
    exercise keeps the title alone); an exercise has no answers, notes, checks or slips."""

    title: str
    blurb: str
    source: str
    link: str
    givens: tuple[tuple[str, str, str], ...]  # (label, symbol LaTeX, value as the page shows it)
    find: tuple[tuple[str, str], ...]  # (label, symbol LaTeX)
    steps: tuple[tuple[str, str], ...]
    answers: tuple[tuple[str, str, str], ...] = ()  # (symbol LaTeX, label, value)
    notes: tuple[str, ...] = ()
    checks: tuple[str, ...] = ()
    slips: tuple[str, ...] = ()
    exercise: bool = False
    heading: str = ""  # a handout's line above the title ("Variant 17", a roster's label)
    work_space: bool = False  # a student's sheet: room to work instead of the method
    parts: tuple[tuple[int, str], ...] = ()  # (index of a step, the heading of the course's step it opens)
    diagrams: tuple[fbd.Drawing, ...] = ()  # the free-body diagrams, drawn under Step 2's heading
    sketch: fbd.Drawing | None = None  # the problem's sketch, under "The problem" (viz/sketch.py)


def givens(problem: Problem, solution: Solution, system: str = "si") -> tuple[tuple[str, str, str], ...]:
    """(label, symbol, value) per parameter, in the page's units (an option as its words)."""
    rows = []
    for p in problem.solver.PARAMS:
        value = solution.params[p.name]
        if isinstance(p, Choice):
            rows.append((p.label, "", p.label_of(value)))
        else:
            rows.append((p.label, p.symbol, units.format_quantity(value, p.dimension, system, sig=6)))
    return tuple(rows)


def _parts(parts_of_steps) -> tuple[tuple[int, str], ...]:
    out, last = [], None
    for i, part in enumerate(parts_of_steps):
        if part != last:
            out.append((i, PARTS[part]))
            last = part
    return tuple(out)


def exercise_steps(solution: Solution, derivation) -> tuple[tuple[str, str], ...]:
    """The method as the Practice view shows it (``practice.method.exercise_steps``): (title, equation or "")."""
    return tuple((title, tex) for _, title, tex in method_steps(solution.steps[: solution.symbolic_steps], derivation))


def document(problem: Problem, solution: Solution, answers, system: str = "si", link: str = "",
             exercise: bool = False, heading: str = "") -> Document:
    """The page's state as a document; ``exercise``: the statement and the method only."""
    find = tuple((a.heading, a.symbol) for a in answers)
    common = dict(title=problem.title, blurb=problem.blurb, source=problem.source, link=link,
                  givens=givens(problem, solution, system), find=find, heading=heading,
                  sketch=drawings(problem.id).sketch(solution.params))
    if exercise:
        shown = method_steps(solution.steps[: solution.symbolic_steps], problem.solver.derivation_of(solution))
        return Document(**common, steps=tuple((title, tex) for _, title, tex in shown), exercise=True,
                        parts=_parts(part for part, _, _ in shown))
    checks = tuple(f"{'agrees' if ok else 'DIFFERS'}: {name}: {closed} vs {second}" + (f" ({why})" if why else "")
                   for ok, name, closed, second, why in results.checks(solution))
    return Document(**common, steps=tuple((s.title, s.latex) for s in solution.steps),
                    answers=tuple(map(tuple, results.answer_rows(solution, answers, system))),
                    notes=tuple(solution.notes), checks=checks, slips=tuple(problem.solver.ERRATA),
                    parts=_parts(s.part for s in solution.steps), diagrams=tuple(fbd.drawings(problem.solver, solution)))


# ------------------------------------------------------------------------------------------------
# Markdown with $$ math

def _data_uri(drawing) -> str:
    """A free-body diagram as an image a Markdown viewer shows (its SVG, base64 in a data: URI)."""
    import base64

    return "data:image/svg+xml;base64," + base64.b64encode(fbd.svg(drawing).encode()).decode()


def _cell(text: str) -> str:
    return text.replace("|", r"\|")


def markdown(doc: Document) -> str:
    heading = re.sub(r"([\\`*_])", r"\\\1", doc.heading)  # a roster's label as it is (s_01 is not emphasis)
    out = [f"*{heading}*\n" if heading else "", f"# {doc.title}", "", f"{doc.blurb} Source: {doc.source}.", ""]
    if doc.link:
        out += [f"This page, with these numbers: [{doc.link}]({doc.link})", ""]
    out += ["## The problem", ""]
    if doc.sketch is not None:
        out += [f"![{doc.sketch.text}]({_data_uri(doc.sketch)})", ""]
    out += ["| given | symbol | value |", "|---|---|---|"]
    out += [f"| {_cell(label)} | {f'${_cell(symbol)}$' if symbol else ''} | {_cell(value)} |"
            for label, symbol, value in doc.givens]
    out += ["", "**Find**", ""] + [f"- {label}, ${symbol}$" for label, symbol in doc.find] + [""]
    if doc.answers:
        out += ["## Answers", "", "| symbol | quantity | value |", "|---|---|---|"]
        out += [f"| ${_cell(symbol)}$ | {_cell(label)} | **{_cell(value)}** |" for symbol, label, value in doc.answers]
        out += [""] + [f"{note}\n" for note in doc.notes]
    if doc.work_space:
        return "\n".join(out + ["## Your work", ""]).lstrip("\n")
    out += ["## The method" if doc.exercise else "## Derivation, step by step", ""]
    if doc.exercise:
        out += ["The steps to take; equations that lead to a result come with the solution.", ""]
    heads = dict(doc.parts)
    for i, (title, tex) in enumerate(doc.steps, start=1):
        if i - 1 in heads:
            out += [f"### {heads[i - 1]}", ""]
            if heads[i - 1] == PARTS[2]:
                out += [f"![{d.text}]({_data_uri(d)})" for d in doc.diagrams] + ([""] if doc.diagrams else [])
        out += [f"**{i}.** {title}", ""] + ([f"$$\n{tex}\n$$", ""] if tex else [])
    if doc.checks:
        out += ["## Checked a second way", ""] + [f"- {check}" for check in doc.checks] + [""]
    if doc.slips:
        out += ["## Common slips in the worked solution", ""] + [f"- {slip}" for slip in doc.slips] + [""]
    return "\n".join(out).lstrip("\n")


# ------------------------------------------------------------------------------------------------
# LaTeX: a standalone article, amsmath and amssymb only (both in TeX Live's smallest LaTeX)

# Text the solvers write in Unicode, as LaTeX: math characters become math (runs of them merged),
# the rest plain text. A character missing here is written as "?" and named by ``unmapped`` (a test
# runs every problem's text through it).
_MATH = {
    "°": r"^{\circ}", "²": "^{2}", "⁶": "^{6}", "⁺": "^{+}", "⁻": "^{-}", "₀": "_{0}", "₁": "_{1}", "₂": "_{2}",
    "·": r"\cdot ", "×": r"\times ", "¼": r"\tfrac14", "½": r"\tfrac12", "¾": r"\tfrac34", "⅓": r"\tfrac13", "⅔": r"\tfrac23", "⅖": r"\tfrac25",
    "⅛": r"\tfrac18", "Σ": r"\Sigma ", "θ": r"\theta ",
    "μ": r"\mu ", "π": r"\pi ", "σ": r"\sigma ", "ψ": r"\psi ", "ω": r"\omega ", "ẋ": r"\dot{x}", "ẍ": r"\ddot{x}",
    "ÿ": r"\ddot{y}", "ℓ": r"\ell ", "→": r"\to ", "−": "-", "√": r"\surd ", "∞": r"\infty ", "∫": r"\int ",
    "≤": r"\le ", "α": r"\alpha ", "β": r"\beta ", "φ": r"\phi ", "Δ": r"\Delta ", "≥": r"\ge ", "≈": r"\approx ",
    "τ": r"\tau ", "λ": r"\lambda ", "ρ": r"\rho ", "³": "^{3}", "ᵢ": "_{i}",
}
_ACCENTS = {"\u0302": r"\hat", "\u0307": r"\dot", "\u0308": r"\ddot"}  # combining marks on the letter before
_TEXT = {"–": "--", "—": "---", "’": "'", "‘": "`", "“": "``", "”": "''", "…": r"\ldots{}", "\u00a0": "~",
         "\u2009": r"\,", "\u202f": r"\,"}
_SPECIAL = {"\\": r"\textbackslash{}", "{": r"\{", "}": r"\}", "$": r"\$", "&": r"\&", "#": r"\#", "^": r"\^{}",
            "_": r"\_", "%": r"\%", "~": r"\~{}", "<": r"\textless{}", ">": r"\textgreater{}", "|": r"\textbar{}"}
_SCRIPTS = re.compile(r"([\^_])\{([^{}]*)\}\1\{")  # ^{-}^{2} -> ^{-2}: one script, as LaTeX requires


def unmapped(text: str) -> set[str]:
    """The characters of ``text`` that ``tex_text`` cannot write (and writes as "?")."""
    return {c for c in text if ord(c) > 127 and c not in _MATH and c not in _TEXT and c not in _ACCENTS}


def tex_text(text: str) -> str:
    """Plain text (the solvers' Unicode) as LaTeX text; ASCII only."""
    pieces: list[tuple[bool, str]] = []  # (math?, LaTeX)
    chars = list(text)
    for i, c in enumerate(chars):
        if c in _ACCENTS:
            continue
        accent = _ACCENTS.get(chars[i + 1]) if i + 1 < len(chars) else None
        if accent:
            base = _MATH.get(c, c).strip()
            pieces.append((True, f"{accent}{{{base}}}"))
        elif c in _MATH:
            pieces.append((True, _MATH[c]))
        elif c in _TEXT:
            pieces.append((False, _TEXT[c]))
        elif c in _SPECIAL:
            pieces.append((False, _SPECIAL[c]))
        elif ord(c) > 127:
            pieces.append((False, "?"))
        else:
            pieces.append((False, c))
    out, run = [], []
    for is_math, tex in pieces + [(False, "")]:
        if is_math:
            run.append(tex)
            continue
        if run:
            out.append(r"\ensuremath{" + _SCRIPTS.sub(r"\1{\2", "".join(run)).strip() + "}")
            run = []
        out.append(tex)
    return "".join(out)


_INLINE = re.compile(r"\$([^$]+)\$|\*\*([^*]+)\*\*|\*([^*\s][^*]*)\*")


def tex_markdown(text: str) -> str:
    """A slip's text (plain text with $inline math$, **bold** and *emphasis*) as LaTeX."""
    out, at = [], 0
    for m in _INLINE.finditer(text):
        out.append(tex_text(text[at:m.start()]))
        if m.group(1) is not None:
            out.append(f"${m.group(1)}$")
        elif m.group(2) is not None:
            out.append(r"\textbf{" + tex_markdown(m.group(2)) + "}")
        else:
            out.append(r"\emph{" + tex_markdown(m.group(3)) + "}")
        at = m.end()
    return "".join(out) + tex_text(text[at:])


def tex_link(url: str) -> str:
    """A URL in typewriter type that may break after / ? & = (no url package needed)."""
    escaped = "".join(_SPECIAL.get(c, c) for c in url)
    return r"\texttt{" + re.sub(r"(/|\\&|=|\?)", r"\1\\allowbreak{}", escaped) + "}"


# An A4 text block 16 cm wide in 11 pt holds about 40 em of display math; ui/equations.py breaks a
# longer step over aligned rows as it does for a phone (its estimate runs up to 15 % short).
TEX_WIDTH_EM = 32.0
_SIZE_IN_MATH = re.compile(r"\\(small|footnotesize|scriptsize)\b\s*")

PREAMBLE = r"""\documentclass[11pt,a4paper]{article}
\usepackage{amsmath,amssymb}
\setlength{\textwidth}{16cm}\setlength{\oddsidemargin}{0cm}\setlength{\evensidemargin}{0cm}
\setlength{\textheight}{24cm}\setlength{\topmargin}{-1.5cm}
\setlength{\parindent}{0pt}\setlength{\parskip}{0.6ex}
\pagestyle{plain}
"""


def display_math(tex: str) -> str:
    """A step's equation for LaTeX: broken over aligned rows where too wide; a row still too wide is
    set smaller from outside the math (a size command is text mode only in LaTeX)."""
    rows = broken(tex, TEX_WIDTH_EM)
    sized = _SIZE_IN_MATH.search(rows)
    body = "\\begin{equation*}\n" + _SIZE_IN_MATH.sub("", rows) + "\n\\end{equation*}"
    return f"{{\\{sized.group(1)}\n{body}}}" if sized else body


def tex_body(doc: Document) -> str:
    """The document's content, without preamble (a handout puts several in one file)."""
    out = []
    if doc.heading:
        out.append(r"\noindent\textit{" + tex_text(doc.heading) + r"}\par")
    out += [r"\section*{" + tex_text(doc.title) + "}", tex_text(f"{doc.blurb} Source: {doc.source}.") + r"\par"]
    if doc.link:
        out.append(r"\textbf{This page, with these numbers:}\\" + "\n" + tex_link(doc.link) + r"\par")
    out.append(r"\subsection*{The problem}")
    if doc.sketch is not None:
        out += [r"\begin{center}", fbd.tikz(doc.sketch, 6.0), r"\end{center}"]
    out += [r"\begin{tabular}{p{6.3cm}ll}", r"\textbf{given} & \textbf{symbol} & \textbf{value}\\"]
    out += [f"{tex_text(label)} & {f'${symbol}$' if symbol else ''} & {tex_text(value)}\\\\"
            for label, symbol, value in doc.givens]
    out += [r"\end{tabular}", "", r"\textbf{Find}", r"\begin{itemize}"]  # a blank line ends a table's paragraph
    out += [rf"\item {tex_text(label)}, ${symbol}$" for label, symbol in doc.find]
    out.append(r"\end{itemize}")
    if doc.answers:
        out += [r"\subsection*{Answers}", r"\begin{tabular}{lp{6.3cm}l}"]
        out += [f"${symbol}$ & {tex_text(label)} & \\textbf{{{tex_text(value)}}}\\\\" for symbol, label, value in doc.answers]
        out += [r"\end{tabular}", ""]
        out += [tex_text(note) + r"\par" for note in doc.notes]
    if doc.work_space:
        return "\n".join(out + [r"\subsection*{Your work}", r"\vspace*{\fill}"]) + "\n"
    out.append(r"\subsection*{" + ("The method" if doc.exercise else "Derivation, step by step") + "}")
    if doc.exercise:
        out.append(r"The steps to take; equations that lead to a result come with the solution.\par")
    heads = dict(doc.parts)
    opened = False
    for i, (title, tex) in enumerate(doc.steps):
        if i in heads or not opened:
            if opened:
                out.append(r"\end{enumerate}")
            if i in heads:  # the course's step: its heading is kept with what follows it on paper
                out.append(r"\subsubsection*{" + tex_text(heads[i]) + "}")
                if heads[i] == PARTS[2] and doc.diagrams:
                    out += [r"\begin{center}", r"\quad".join(fbd.tikz(d) for d in doc.diagrams), r"\end{center}"]
            out += [r"\begin{enumerate}", r"\setcounter{enumi}{" + str(i) + "}"]
            opened = True
        out.append(r"\item " + tex_markdown(title) + ("\n" + display_math(tex) if tex else ""))
    if opened:
        out.append(r"\end{enumerate}")
    if doc.checks:
        out += [r"\subsection*{Checked a second way}", r"\begin{itemize}"]
        out += [r"\item " + tex_text(check) for check in doc.checks] + [r"\end{itemize}"]
    if doc.slips:
        out += [r"\subsection*{Common slips in the worked solution}", r"\begin{itemize}"]
        out += [r"\item " + tex_markdown(slip) for slip in doc.slips] + [r"\end{itemize}"]
    return "\n".join(out) + "\n"


def _preamble(docs) -> str:
    """The preamble, with TikZ where a free-body diagram is drawn."""
    return PREAMBLE + (r"\usepackage{tikz}" + "\n" if any(d.diagrams or d.sketch for d in docs) else "")


def latex(doc: Document) -> str:
    """A standalone .tex file: ``pdflatex`` compiles it as it is."""
    return _preamble([doc]) + "\\begin{document}\n" + tex_body(doc) + "\\end{document}\n"


def ascii_only(text: str) -> bool:
    return all(ord(c) < 128 for c in text)


def character_names(chars: set[str]) -> list[str]:
    return sorted(f"{c} ({unicodedata.name(c, hex(ord(c)))})" for c in chars)


# ------------------------------------------------------------------------------------------------
# Handouts: one file for a class, each variant on its own page(s)

def statement_sheet(doc: Document) -> Document:
    """A student's sheet: the statement with their givens, and room to work instead of the method."""
    return replace(doc, steps=(), answers=(), notes=(), checks=(), slips=(), exercise=True, work_space=True,
                   parts=(), diagrams=())


def key_sheet(doc: Document) -> Document:
    """A variant's answer key: the answers, the notes and the derivation (without the page's checks
    and the worked solution's slips)."""
    return replace(doc, checks=(), slips=())


def handout_latex(docs: list[Document]) -> str:
    """Several sheets in one .tex, each from a new page; a statement ends with room to work."""
    return _preamble(docs) + "\\begin{document}\n" + "\\newpage\n".join(tex_body(doc) for doc in docs) + "\\end{document}\n"


def handout_markdown(docs: list[Document]) -> str:
    return "\n\n---\n\n".join(markdown(doc) for doc in docs)
