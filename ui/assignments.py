"""Assignments on screen: a student's signed link on a problem page (``student_link``, then
``recording`` and ``your_attempts``), and the instructor's page (``instructor_page``: create an
assignment from a roster, hand out the links, read the gradebook, download it as CSV).

Everything stored goes through ``assignments.records``; nothing a student typed is rendered as
Markdown: st.table renders its cells as Markdown, so a stored string in a cell (what was typed, a
slip's name, a label) passes through ``literal``, and text through ``plain``."""
from __future__ import annotations

import datetime as dt
import urllib.parse
from dataclasses import dataclass

import streamlit as st

from assignments import migrate, records, signing
from assignments.identity import LinkRefused, StudentIdentity, from_link, is_assignment_link, link_query
from practice.judge import RELATIVE_TOLERANCE
from ui.catalog import BY_ID, PROBLEMS, Problem
from ui.practice import Recording, answer_label, instructor_key_entry
from ui.results import literal, plain

UTC = dt.timezone.utc


@st.cache_resource(show_spinner=False)
def _schema_ready() -> bool:
    """Bring the schema to head once per process (serve.py does it before listening; this covers
    ``streamlit run app.py``). False when the database cannot be reached: tried again next run."""
    try:
        migrate.upgrade()
    except Exception:  # noqa: BLE001  (reported to the user as "cannot be reached" by the caller)
        _schema_ready.clear()
        return False
    return True


def _when(moment: dt.datetime) -> str:
    return moment.astimezone(UTC).strftime("%d %b %Y, %H:%M UTC")


# -- the student's side

@dataclass
class StudentLink:
    """What a problem page needs from an assignment link."""
    identity: StudentIdentity | None = None
    refused: str = ""  # the link is refused: say this, show nothing else
    settings: records.Settings | None = None  # None: practice unrecorded (see ``notice``)
    notice: str = ""


def student_link(problem: Problem) -> StudentLink | None:
    """None unless the page was opened with an assignment link; else the checked link."""
    query = {k: st.query_params.get(k) for k in st.query_params.keys()}
    if not is_assignment_link(query):
        return None
    try:
        identity = from_link(query)
    except LinkRefused as refusal:
        return StudentLink(refused=str(refusal))
    unrecorded = StudentLink(identity, notice=records.UNAVAILABLE)
    if not _schema_ready():
        return unrecorded
    try:
        settings = records.assignment(identity.assignment_id)
        enrolled = settings is not None and records.enrolled(identity)
    except records.RecordingUnavailable:
        return unrecorded
    if settings is None or not enrolled:
        return StudentLink(refused="This assignment link is not in the course's records (the assignment or "
                                   "your code is not on its roster). Ask your instructor for a new link.")
    if settings.problem != problem.id:
        right = BY_ID[settings.problem].title if settings.problem in BY_ID else settings.problem
        return StudentLink(refused=f"This assignment link belongs to the page “{right}”, not this one. Open the "
                                   "link exactly as you received it.")
    return StudentLink(identity, settings=settings)


def recording(link: StudentLink) -> Recording:
    """Record each checked answer and the solution being shown, under the assignment's rules."""
    identity, settings = link.identity, link.settings
    try:
        revealed = records.solution_shown(identity)
    except records.RecordingUnavailable:
        revealed = False
    blocked = ""
    if not settings.solution_before_due and records.now() < settings.due:
        blocked = f"The solution opens at the due time, {_when(settings.due)}."

    def on_verdict(answer, typed: str, verdict) -> None:
        if not typed.strip():
            return  # "Type an answer first." is not an attempt
        try:
            kept = records.record_attempt(identity, answer.name, typed, verdict.correct, verdict.message,
                                          verdict.mistake)
        except records.RecordingUnavailable as error:
            st.error(str(error), icon=":material/cloud_off:")
            return
        what = f"Recorded: attempt {kept.number} of {settings.attempts_allowed} at {answer_label(answer).lower()}"
        if kept.marks():
            st.warning(f"{what}, kept but it does not count ({', '.join(kept.marks())}).", icon=":material/schedule:")
        else:
            st.info(f"{what}{', and it counts' if kept.counts else ''}.", icon=":material/task_alt:")

    def on_reveal() -> bool:
        try:
            records.record_reveal(identity)
            return True
        except records.RecordingUnavailable as error:
            st.error(f"{error} The solution stays hidden until it can be recorded.")
            return False

    return Recording(settings.tolerance, on_verdict, on_reveal, revealed, blocked)


def assignment_heading(link: StudentLink) -> None:
    """Who and what: the assignment's rules, or why nothing is recorded."""
    if link.settings is None:
        st.warning(link.notice, icon=":material/cloud_off:")
        return
    s = link.settings
    late = " The due time has passed: attempts are still kept, marked late." if records.now() > s.due else ""
    st.info(f"**{plain(s.title)}**, for student {literal(link.identity.label)}: due {_when(s.due)}. An attempt counts "
            f"if it is right (numbers within ±{s.tolerance * 100:g} %), made before the due time, within "
            f"{s.attempts_allowed} attempts per answer, and before you open the solution.{late}",
            icon=":material/assignment:")


def your_attempts(link: StudentLink, answers) -> None:
    """The student's own attempts, and for each answer what counts so far."""
    if link.settings is None:
        return
    try:
        mine = records.attempts_of(link.identity)
    except records.RecordingUnavailable as error:
        st.warning(str(error))
        return
    st.markdown("### Your attempts")
    labels = {a.name: answer_label(a) for a in answers}
    lines = []
    for name in link.settings.answers:
        tried = [a for a in mine if a.answer == name]
        counted = next((a for a in tried if a.counts), None)
        left = max(link.settings.attempts_allowed - len(tried), 0)
        lines.append(f"- {plain(labels.get(name, name))}: " + (
            f"right at attempt {counted.number} (counts)" if counted else
            f"not yet right; {left} of {link.settings.attempts_allowed} attempts left"))
    st.markdown("\n".join(lines))
    if mine:
        st.table([{"#": a.number, "answer": labels.get(a.answer, a.answer), "you typed": literal(a.typed),
                   "verdict": "right" if a.correct else "not right", "slip": literal(records.slip_name(a.slip)),
                   "time": a.at.strftime("%d %b %H:%M:%S UTC"), "counts": "yes" if a.counts else
                   ("no: " + ", ".join(a.marks()) if a.marks() else "no")} for a in mine])


# -- the instructor's page

def _app_base() -> str:
    """The app's address as the instructor's browser reached it, without this page's path."""
    parts = urllib.parse.urlsplit(st.context.url or "http://localhost:8501/")
    path = parts.path.rstrip("/")
    if path.endswith("/gradebook") or path == "gradebook":  # this page's url_path (app.py)
        path = path[: -len("gradebook")].rstrip("/")
    return urllib.parse.urlunsplit((parts.scheme, parts.netloc, path, "", ""))


def student_url(base: str, problem: str, identity: StudentIdentity) -> str:
    return f"{base}/{problem}?{urllib.parse.urlencode(link_query(identity))}"


def _links_csv(base: str, problem: str, students: list[StudentIdentity]) -> str:
    return records.safe_csv(["label", "seed", "link"], ([s.label, s.seed, student_url(base, problem, s)] for s in students))


def _answers_of(problem: Problem):
    solver = problem.solver
    picker = getattr(solver, "answers_for", None)
    return picker(solver.solve().regime) if picker else solver.ANSWERS


def _new_assignment() -> None:
    st.markdown("### New assignment")
    problem = BY_ID[st.selectbox("Problem", [p.id for p in PROBLEMS], format_func=lambda i: BY_ID[i].title,
                                 key="assign__problem")]
    answers = {a.name: a for a in _answers_of(problem)}
    with st.form("assign__form"):
        title = st.text_input("Title", max_chars=120, key="assign__title", placeholder="Week 9: the bouncing pendulum")
        counted = st.multiselect("Answers that count", list(answers), default=list(answers),
                                 format_func=lambda name: answer_label(answers[name]), key=f"assign__answers_{problem.id}")
        c1, c2 = st.columns(2)
        tolerance = c1.number_input("Tolerance for numbers (%)", 0.01, 10.0, RELATIVE_TOLERANCE * 100, 0.1,
                                    key="assign__tolerance")
        attempts = c2.number_input("Attempts allowed per answer", 1, 100, 3, key="assign__attempts")
        c3, c4 = st.columns(2)
        in_a_week = records.now() + dt.timedelta(days=7)
        due_day = c3.date_input("Due date (UTC)", in_a_week.date(), key="assign__due_day")
        due_time = c4.time_input("Due time (UTC)", dt.time(23, 59), key="assign__due_time")
        before = st.checkbox("Students may open the solution before the due time", key="assign__before")
        roster_text = st.text_area("Roster: one student label per line (your own codes, no names)",
                                   key="assign__roster", placeholder="s001\ns002\ns003")
        roster_file = st.file_uploader("…or a roster CSV (labels in the first column)", type=["csv", "txt"],
                                       key="assign__roster_file")
        create = st.form_submit_button("Create the assignment and its links", type="primary")
    if not create:
        return
    try:
        text = roster_file.getvalue().decode("utf-8-sig") if roster_file else roster_text
        labels = records.parse_roster(text)
        settings = records.Settings(title, problem.id, tuple(counted), tolerance / 100,
                                    dt.datetime.combine(due_day, due_time, UTC), int(attempts), before)
        if settings.errors():
            raise ValueError(" ".join(settings.errors()))
        aid = records.create_assignment(settings)
        records.enrol(aid, labels)
    except UnicodeDecodeError:
        st.error("The roster file is not UTF-8 text.")
        return
    except (ValueError, records.RecordingUnavailable) as error:
        st.error(plain(str(error)))
        return
    st.session_state["assign__chosen"] = aid
    st.success(f"Assignment {aid} created for {len(labels)} students: its links are below.")


def _assignment_choice(existing) -> int | None:
    ids = [aid for aid, _ in existing]
    titles = {aid: f"{aid}: {s.title} ({BY_ID[s.problem].title if s.problem in BY_ID else s.problem})"
              for aid, s in existing}
    if st.session_state.get("assign__chosen") not in ids:
        st.session_state["assign__chosen"] = ids[0]
    return st.selectbox("Assignment", ids, format_func=titles.get, key="assign__chosen")


def _gradebook(aid: int) -> None:
    book = records.gradebook(aid)
    s = book.settings
    problem = BY_ID.get(s.problem)
    labels = {a.name: answer_label(a) for a in _answers_of(problem)} if problem else {}
    base = _app_base()
    st.markdown(f"Due {_when(s.due)} · {s.attempts_allowed} attempts per answer · numbers within "
                f"±{s.tolerance * 100:g} % · solution before the due time: {'yes' if s.solution_before_due else 'no'}")
    st.markdown("#### Links, one per student")
    st.markdown("Send each student their own link (by your course's messaging, not in a public place): it opens "
                "their variant, and a changed link is refused.")
    st.download_button("Download the links (CSV)", _links_csv(base, s.problem, book.students),
                       file_name=f"assignment-{aid}-links.csv", mime="text/csv", key="assign__links_csv")
    with st.expander(f"The links ({len(book.students)})"):
        st.table([{"label": literal(st_.label), "link": student_url(base, s.problem, st_)} for st_ in book.students])
    st.markdown("#### Gradebook")
    rows = []
    for student in book.students:
        row = {"student": literal(student.label), "score": f"{book.score(student.label)} / {len(s.answers)}"}
        for a in s.answers:
            c = book.cells.get((student.label, a), records.Cell())
            right = f"at {c.first_right}" if c.first_right else "—"
            slips = f"; slips: {', '.join(map(literal, c.slips))}" if c.slips else ""
            row[labels.get(a, a)] = f"{right}; {c.attempts} used{slips}"
        rows.append(row)
    st.table(rows)
    c1, c2 = st.columns(2)
    c1.download_button("Download the gradebook (CSV)", records.gradebook_csv(book),
                       file_name=f"assignment-{aid}-gradebook.csv", mime="text/csv", key="assign__book_csv")
    c2.download_button("Download every attempt (CSV)", records.attempts_csv(aid),
                       file_name=f"assignment-{aid}-attempts.csv", mime="text/csv", key="assign__attempts_csv")
    st.markdown("#### Per answer")
    st.markdown("\n".join(f"- **{plain(labels.get(a, a))}**: " + " ".join(plain(line) for line in lines)
                          for a, lines in book.statistics().items()))


def instructor_page() -> None:
    from ui.page import _leave_legacy_pages_mode  # (ui.page imports this module)

    _leave_legacy_pages_mode()  # a deep link to /gradebook on a fresh server: see ui/page.py
    st.markdown("# Assignments\n:gray[Signed per-student links, every attempt recorded, the gradebook.]")
    if not instructor_key_entry("assign__instructor_key", "assignments"):
        return
    if not signing.configured():
        st.warning(f"The course admin has not set a course secret (`{signing.SECRET_ENV}`, at least "
                   f"{signing.MIN_SECRET} characters), so assignment links cannot be signed.")
        return
    if not _schema_ready():
        st.error("The course's database cannot be reached, so assignments cannot be created or read now. "
                 "Practice pages still work. (Admin: check DL_DATABASE_URL and the database server.)")
        return
    try:
        _new_assignment()
        existing = records.assignments()
        if not existing:
            st.markdown("No assignments yet.")
            return
        st.markdown("### Assignments")
        _gradebook(_assignment_choice(existing))
    except records.RecordingUnavailable as error:
        st.error(str(error))
