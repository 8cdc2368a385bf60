"""Handouts for a class (instructor key; an LMS instructor's session: its course's assignments only): for a problem and a range of variants, or an assignment's
roster, each student's statement with their givens and room to work, and a separate answer key with
each variant's answers and derivation. A printable page (the browser's Print: one sheet per student,
ui/stylesheet.py PRINT_CSS) and the same as one LaTeX file or Markdown.

Students are named only by what the instructor's roster gives (its opaque labels); a range of
variants is labelled by variant number, with the ``?seed=N`` link that opens it. Assignments are read
through ``assignments.records``' public reads only (``assignments``, ``roster``)."""
from __future__ import annotations

import re

import streamlit as st

from assignments import records
from assignments.identity import parameters
from practice.variants import MAX_SEED, variant
from ui import documents
from solvers.catalog import BY_ID, PROBLEMS, Problem
from ui.session import course_assignments, instructor_key_entry, is_instructor, lms_course
from ui.stylesheet import PRINT_CSS
from edge.streamlit_dom import css

MAX_SHEETS = 60  # per handout: a longer class is printed in parts (each sheet is typeset in the page)
RANGE, ROSTER = "A range of variants", "An assignment's roster"
STATEMENTS, KEY = "Statements, for the students", "Answer key"
WHAT = {"statements": STATEMENTS, "key": KEY}  # the link's ?what=
# On paper each sheet starts a page and a statement's page is left blank below "Your work" (on
# screen a dashed box stands for it); the page's own heading and choices are not printed.
SHEET_CSS = css("""
<style>
  .dl-sheet-break { break-after: page; height: 0; }
  .dl-work { border: 1px dashed rgba(128, 128, 128, 0.6); border-radius: 4px; height: 6rem; margin: 0.5rem 0 1.5rem; }
  @media print {
    .dl-work { display: none; }
    $elementContainer:has(.dl-screen-only) { display: none !important; }
  }
</style>
""")


def _answers(problem: Problem, solution, counted: tuple[str, ...] = ()):
    """The answers a sheet asks for: an assignment's that count, else every one the page shows."""
    answers = problem.answers_of(solution)
    return tuple(a for a in answers if a.name in counted) if counted else answers


def sheets(problem: Problem, who: list[tuple[str, dict, str]], key: bool,
           counted: tuple[str, ...] = ()) -> list[documents.Document]:
    """One document per student: ``who`` is (heading, parameters, link); ``key``: the answer key."""
    out = []
    for heading, params, link in who:
        solution = problem.solver.solve(**params)
        doc = documents.document(problem, solution, _answers(problem, solution, counted), link=link, heading=heading)
        out.append(documents.key_sheet(doc) if key else documents.statement_sheet(doc))
    return out


def app_base() -> str:
    """The app's address as the browser reached this page, without the page's own path."""
    url = (st.context.url or "").split("?")[0].rstrip("/")
    return url[: -len("/handouts")] if url.endswith("/handouts") else url


def variant_range(problem: Problem, first: int, last: int, base: str = "") -> list[tuple[str, dict, str]]:
    """Variants first..last of ``?seed=N``: labelled by number, with the link that opens each."""
    return [(f"Variant {seed}", variant(problem.solver, problem.id, seed), f"{base}/{problem.id}?seed={seed}")
            for seed in range(first, last + 1)]


def roster_variants(problem: Problem, assignment_id: int) -> list[tuple[str, dict, str]]:
    """An assignment's students, by the roster's labels, with their assignment givens (no link: each
    student's signed link is theirs, sent by the instructor)."""
    return [(f"Student {s.label}", parameters(s, problem.solver, problem.id), "")
            for s in records.roster(assignment_id)]


def _whole(text: str | None) -> int | None:
    return int(text) if text and re.fullmatch(r"\d{1,10}", text) else None


def _from_link() -> None:
    """A handout's link sets the choices once: ?problem=<id>&first=1&last=30&what=key (a range of
    variants) or ?whose=roster&assignment=<id>&part=2&what=key (a roster); a value that is not one of
    them is ignored (an assignment or part that does not exist: in ``_whose``, where they are known)."""
    if st.session_state.get("handouts__linked"):
        return
    st.session_state["handouts__linked"] = True
    query = st.query_params
    if query.get("problem") in BY_ID:
        st.session_state["handouts__problem"] = query["problem"]
    for name in ("first", "last"):
        if (n := _whole(query.get(name))) is not None and n <= MAX_SEED:
            st.session_state[f"handouts__{name}"] = n
    if query.get("whose") == "roster":
        st.session_state["handouts__source"] = ROSTER
    for name, key in (("assignment", "handouts__assignment"), ("part", "handouts__part_number")):
        if (n := _whole(query.get(name))) is not None:
            st.session_state[key] = n
    if query.get("what") in WHAT:
        st.session_state["handouts__what"] = WHAT[query["what"]]


def _to_link(choices: dict[str, str]) -> None:
    """Every choice on the page into its address (as a problem page's parameters): the link reopens it."""
    if {k: st.query_params.get(k) for k in st.query_params.keys()} != choices:
        st.query_params.from_dict(choices)


def _whose(placed: set[int] | None, link: dict[str, str]) -> tuple[Problem, list[tuple[str, dict, str]], tuple[str, ...], str] | None:
    """The problem, the students, the answers that count and a file name's stem, as chosen (each
    choice also put in ``link``). ``placed``: an LMS instructor's session, its course's assignments
    only (no range of variants)."""
    source = ROSTER if placed is not None else st.radio("Whose numbers", (RANGE, ROSTER), horizontal=True,
                                                        key="handouts__source")
    if source == RANGE:
        problem = BY_ID[st.selectbox("Problem", [p.id for p in PROBLEMS], format_func=lambda i: BY_ID[i].title,
                                     key="handouts__problem")]
        c1, c2 = st.columns(2)
        first = int(c1.number_input("First variant", 0, MAX_SEED, 1, key="handouts__first"))
        last = int(c2.number_input("Last variant", 0, MAX_SEED, 30, key="handouts__last"))
        link.update(problem=problem.id, first=str(first), last=str(last))
        if not first <= last < first + MAX_SHEETS:
            st.error(f"Choose from 1 to {MAX_SHEETS} variants, the first no later than the last.")
            return None
        return problem, variant_range(problem, first, last, app_base()), (), f"{problem.id}-variants-{first}-{last}"
    try:
        existing = [(aid, s) for aid, s in records.assignments() if placed is None or aid in placed]
    except records.RecordingUnavailable as error:
        st.error(str(error))
        return None
    if not existing:
        st.markdown("No assignments yet: create one on the Assignments page." if placed is None else
                    "Your course has no Dynamics Lab assignments yet: add one with your LMS's “add external "
                    "tool” dialog.")
        return None
    link["whose"] = "roster"
    titles = {aid: f"{s.title} ({BY_ID[s.problem].title if s.problem in BY_ID else s.problem})" for aid, s in existing}
    if st.session_state.get("handouts__assignment") not in titles:  # a link's assignment that is not (or not yours)
        st.session_state.pop("handouts__assignment", None)
    assignment_id = st.selectbox("Assignment", list(titles), key="handouts__assignment", format_func=titles.get)
    settings = dict(existing)[assignment_id]
    link["assignment"] = str(assignment_id)
    if settings.problem not in BY_ID:
        st.error("This assignment's problem is no longer in the app.")
        return None
    problem = BY_ID[settings.problem]
    try:
        who = roster_variants(problem, assignment_id)
    except records.RecordingUnavailable as error:
        st.error(str(error))
        return None
    if len(who) > MAX_SHEETS:
        parts = -(-len(who) // MAX_SHEETS)
        if not 1 <= st.session_state.get("handouts__part_number", 1) <= parts:
            st.session_state.pop("handouts__part_number")
        part = int(st.number_input(f"Part (of {MAX_SHEETS} students each)", 1, parts, 1, key="handouts__part_number"))
        who = who[(part - 1) * MAX_SHEETS: part * MAX_SHEETS]
        link["part"] = str(part)
    return problem, who, settings.answers, f"{problem.id}-assignment-{assignment_id}"


def handouts_page() -> None:
    st.html(PRINT_CSS + SHEET_CSS)
    st.markdown("# Handouts\n:gray[Printable sheets for a class: each student's givens with room to work, and a "
                "separate answer key. Print with the browser (one student per sheet), or download LaTeX or "
                'Markdown.]<span class="dl-screen-only"></span>', unsafe_allow_html=True)
    course = lms_course()
    if course is not None and not is_instructor():  # from the LMS: that course's assignments, no key
        try:
            placed = course_assignments(course)
        except records.RecordingUnavailable as error:
            st.error(str(error))
            return
        st.info("From your course site: the handouts and answer keys of its Dynamics Lab assignments.",
                icon=":material/school:")
    elif not instructor_key_entry("handouts__instructor_key", "the handouts and their answer keys"):
        return
    else:
        placed = None
    st.query_params.pop("instructor", None)  # an instructor link's key leaves the address bar
    _from_link()
    link: dict[str, str] = {}
    chosen = _whose(placed, link)
    if chosen is None:
        _to_link(link)
        return
    problem, who, counted, stem = chosen
    part = st.radio("Print", (STATEMENTS, KEY), horizontal=True, key="handouts__what")
    key = part == KEY
    _to_link({**link, "what": "key" if key else "statements"})
    docs = sheets(problem, who, key, counted)
    name = f"{stem}-{'key' if key else 'statements'}"
    row = st.container(horizontal=True)
    row.download_button("One LaTeX file", lambda: documents.handout_latex(docs), file_name=f"{name}.tex",
                        mime="application/x-tex", on_click="ignore", icon=":material/download:", key="handouts__tex")
    row.download_button("Markdown", lambda: documents.handout_markdown(docs), file_name=f"{name}.md",
                        mime="text/markdown", on_click="ignore", icon=":material/download:", key="handouts__md")
    st.markdown(f"{len(docs)} {'answer keys' if key else 'statements'} below, each from a new sheet when printed."
                '<span class="dl-screen-only"></span>', unsafe_allow_html=True)
    for n, doc in enumerate(docs):
        st.markdown(documents.markdown(doc))
        if doc.work_space:
            st.html('<div class="dl-work"></div>')
        if n < len(docs) - 1:
            st.html('<div class="dl-sheet-break"></div>')
