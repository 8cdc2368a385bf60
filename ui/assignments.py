"""Assignments on screen: a student's signed link on a problem page (``student_link``, then
``assignment_heading``, ``recording`` and ``your_attempts``), and the instructor's page
(``instructor_page``: create an assignment (one problem or a set) from a roster, hand out the
links, edit, close, reopen or archive it, give one student an extension or extra attempts, undo
any change, read the gradebook and download it).

Everything stored goes through ``assignments.records``; nothing a student typed is rendered as
Markdown: st.table renders its cells as Markdown, so a stored string in a cell (what was typed, a
slip's name, a label) passes through ``literal``, and text through ``plain``."""
from __future__ import annotations

import datetime as dt
import hashlib
import html
import re
import urllib.parse
import zoneinfo
from dataclasses import dataclass, replace
from types import SimpleNamespace

import streamlit as st

from assignments import records, signing
from assignments.identity import LinkRefused, StudentIdentity, from_link, is_assignment_link, link_query
from lti import passback, roster as lti_roster, store as lti_store
from practice import diagram_judge
from practice.judge import RELATIVE_TOLERANCE, Verdict
from solvers import units
from solvers.catalog import BY_ID, PROBLEMS, Problem
from edge.inline_scripts import COPY_LINKS, SCROLLABLE_TABLES
from ui.results import literal, plain
from ui.session import (Recording, course_assignments, instructor_key_entry, lms_course, lti_arrival,
                        schema_ready)

UTC = dt.timezone.utc


def _browser_zone() -> str | None:
    """The viewer's own time zone, as their browser reports it (None when it does not, or names
    one this server does not know)."""
    try:
        zone = st.context.timezone
        zoneinfo.ZoneInfo(zone)
        return zone
    except Exception:  # noqa: BLE001  (no browser, as in AppTest; an unknown name)
        return None


def _title(problem_id: str) -> str:
    return BY_ID[problem_id].title if problem_id in BY_ID else problem_id


def _answers_of(problem: Problem):
    solver = problem.solver
    picker = getattr(solver, "answers_for", None)
    return picker(solver.solve().regime) if picker else solver.ANSWERS


def _answer_labels(settings: records.Settings) -> dict[tuple[str, str], str]:
    """Each question's label as the pages write it ("Highest angle after the bounce"), with its
    problem's title in a problem set."""
    out = {}
    for part in settings.parts:
        problem = BY_ID.get(part.problem)
        every = {}
        if problem is not None:
            every = {a.name: a.heading for a in problem.solver.ANSWERS}
            every |= {a.name: a.heading for a in _answers_of(problem)} | {records.DIAGRAM: records.DIAGRAM_HEADING}
        for name in part.answers:
            label = every.get(name, name)
            out[(part.problem, name)] = label if len(settings.parts) == 1 else f"{_title(part.problem)}: {label}"
    return out


def _short_labels(settings: records.Settings) -> tuple[dict[tuple[str, str], str], str]:
    """Each question as the gradebook's table heads it, and the key to them: in a problem set "P1: Angle
    at impact" with "P1: Rod-and-sphere pendulum…" said once above (the title in every heading and
    every "how" made a row taller than a projector's screen); one problem's labels as they are."""
    if len(settings.parts) == 1:
        return _answer_labels(settings), ""
    short, key = {}, []
    for i, part in enumerate(settings.parts, 1):
        key.append(f"**P{i}**: {plain(_title(part.problem))}")
        one = _answer_labels(records.replace(settings, parts=(part,)))
        short |= {q: f"P{i}: {label}" for q, label in one.items()}
    return short, " · ".join(key)


# -- the student's side

@dataclass
class StudentLink:
    """What a problem page needs from an assignment link."""
    identity: StudentIdentity | None = None
    refused: str = ""  # the link is refused: say this, show nothing else
    settings: records.Settings | None = None  # None: practice unrecorded (see ``notice``)
    notice: str = ""
    problem: str = ""  # the page's problem


def student_link(problem: Problem) -> StudentLink | None:
    """None unless the page was opened with an assignment link or from an LMS launch; else the
    checked link (both identities meet here, and go on to the same records)."""
    query = {k: st.query_params.get(k) for k in st.query_params.keys()}
    arrival = lti_arrival() if not is_assignment_link(query) else None
    if arrival and arrival.get("refused"):
        return StudentLink(refused=arrival["refused"])
    if arrival and arrival.get("role") == "student":
        identity = lti_store.from_handoff(arrival)
    elif not is_assignment_link(query):
        return None
    else:
        try:
            identity = from_link(query)
        except LinkRefused as refusal:
            return StudentLink(refused=str(refusal))
    unrecorded = StudentLink(identity, notice=records.UNAVAILABLE, problem=problem.id)
    if not schema_ready():
        return unrecorded
    try:
        settings = records.assignment(identity.assignment_id)
        enrolled = settings is not None and records.enrolled(identity)
    except records.RecordingUnavailable:
        return unrecorded
    if settings is None or not enrolled:
        return StudentLink(refused="This assignment link is not in the course's records (the assignment or "
                                   "your code is not on its roster). Ask your instructor for a new link.")
    if problem.id not in settings.problems and identity.source == "lti":
        return None  # an LMS student on another page of the app: practice, as anyone
    if problem.id not in settings.problems:  # (its problems listed below the refusal: refused_links)
        return StudentLink(identity, refused="This page is not part of this assignment (your instructor may have "
                                             "changed its problems). Open one of its problems:",
                           settings=settings, problem=problem.id)
    return StudentLink(identity, settings=settings, problem=problem.id)


def refused_links(link: StudentLink) -> None:
    """Below a refusal of a page the assignment no longer has: its problems, each a link that opens in this
    tab (or LMS frame) with the same signed query."""
    if link.settings is not None and link.problem not in link.settings.problems:
        st.html(_problem_links(link))


def _standing(link: StudentLink) -> records.Standing | None:
    try:
        return records.standing(link.identity)
    except records.RecordingUnavailable:
        return None


def _zone(link: StudentLink) -> tuple[str, str]:
    """The zone to show the student's times in, and how it was chosen."""
    mine = _browser_zone()
    if mine:
        return mine, "your time zone"
    return link.settings.timezone, "the course's time zone"


def _solution_opens(settings: records.Settings, due: dt.datetime) -> dt.datetime | None:
    """When the student may open the solution (None: now)."""
    return None if settings.solution_before_due else due


def recording(link: StudentLink, solution=None, system: str = "si") -> Recording:
    """Record each readable answer and the solution being shown, under the assignment's rules;
    the verdict's message under its feedback policy."""
    identity, settings, problem = link.identity, link.settings, link.problem
    try:
        revealed = records.solution_shown(identity, problem=problem)
    except records.RecordingUnavailable:
        revealed = False
    standing = _standing(link)
    due = standing.due if standing else settings.due
    zone, _ = _zone(link)
    blocked = ""
    opens = _solution_opens(settings, due)
    if opens is not None and records.now() < opens:
        blocked = f"The solution opens at your due time, {records.when_text(opens, zone)}."
    labels = _answer_labels(settings)

    def say(verdict: Verdict) -> str:
        return records.feedback(verdict.message, verdict.correct, verdict.mistake, settings)

    def recorded(write, label: str, answer, shown_with) -> None:
        """An attempt written by ``write()``, then said; or why it could not be."""
        try:
            kept = write()
        except records.NotAccepted as error:
            st.warning(str(error), icon=":material/lock:")
            return
        except records.RecordingUnavailable as error:
            st.error(str(error), icon=":material/cloud_off:")
            return
        passback.queue(identity)  # an LMS student's score waits for the sender thread, not this page
        _said_recorded(kept, label, link, shown_with, answer, system)

    def on_verdict(answer, typed: str, verdict: Verdict) -> None:
        if not verdict.readable or not typed.strip():
            return  # explained above; not an attempt
        recorded(lambda: records.record_checked(identity, problem, answer.name, typed,
                                                replace(verdict, message=say(verdict))),
                 labels.get((problem, answer.name), answer.heading), answer, solution)

    part = settings.part(problem)
    counts_diagram = part is not None and records.DIAGRAM in part.answers

    def on_diagram(drawing, verdict) -> None:
        """A readable drawing checked: an attempt at the free-body diagram, where it counts."""
        if not counts_diagram:
            return
        if verdict.right:
            said = "Right."
        else:  # kept as the feedback policy lets the page say it
            said = "Not right: " + (" ".join(f.message for f in verdict.findings) if settings.hints else
                                    ", ".join(verdict.keys) if settings.slip_names else "")
        typed = diagram_judge.in_words(drawing, len({d.body for d in drawing}))
        recorded(lambda: records.record_attempt(identity, records.DIAGRAM, typed, verdict.right, said,
                                                ", ".join(verdict.keys), problem=problem,
                                                reading=diagram_judge.reading(drawing)),
                 records.DIAGRAM_HEADING, SimpleNamespace(name=records.DIAGRAM), None)

    diagram_done = bool(standing and counts_diagram and standing.cells[(problem, records.DIAGRAM)].right_at())

    def on_reveal() -> bool:
        try:
            records.record_reveal(identity, problem=problem)
            return True
        except records.RecordingUnavailable as error:
            st.error(f"{error} The solution stays hidden until it can be recorded.")
            return False

    costs = ("Opening the solution is recorded, and your instructor sees it. After it, no answer to this problem "
             "earns points: answers already right keep theirs.")
    return Recording(settings.tolerance, on_verdict, on_reveal, revealed, blocked, say, costs, on_diagram,
                     diagram_done, (settings.hints, settings.slip_names))


def _named(label: str) -> str:
    """An answer's label inside a sentence: quoted as the page writes it ("speed of G" kept, not "g")."""
    return f"“{label}”"


def _said_recorded(kept: records.Recorded, label: str, link: StudentLink, solution, answer, system: str) -> None:
    """The recorded attempt in words, under an icon that matches what it earned."""
    standing = _standing(link)
    allowed = standing.allowed if standing else link.settings.attempts_allowed
    what = (f"attempt {kept.number} of {allowed} at {_named(label)}" if kept.number <= allowed else
            f"answer {kept.number} at {_named(label)}, past your {allowed} graded attempts")  # never "4 of 3"
    if kept.repeated:
        st.info(f"The same answer as your last attempt at {_named(label)}: not counted again (it stays attempt "
                f"{kept.number}{f' of {allowed}' if kept.number <= allowed else ''}).",
                icon=":material/repeat:")
        return
    right_at = standing.cells[(link.problem, answer.name)].right_at() if standing else None
    if right_at is not None and right_at < kept.number:  # settled before: nothing after it can earn more
        st.info(f"Recorded: {what}. {'Right' if kept.correct else 'Not right'}; your attempt {right_at} at "
                f"{_named(label)} was already right, and it stands: this one changes nothing.",
                icon=":material/task_alt:")
        return
    if kept.over_limit:
        st.warning(f"Recorded: {what}: it is kept, but it cannot count.", icon=":material/block:")
    elif kept.correct and kept.credit >= 1:
        st.success(f"Recorded: {what}. Right, and it counts.", icon=":material/task_alt:")
    elif kept.correct and kept.credit > 0:
        st.warning(f"Recorded: {what}. Right, {records.duration_text(kept.late_by)} after your due time: it "
                   f"earns {kept.credit * 100:g} % of its points (late credit).", icon=":material/schedule:")
    elif kept.correct:
        why = ("you had opened the solution" if kept.solution_shown else
               f"it is {records.duration_text(kept.late_by)} after your due time, and this assignment gives no "
               "late credit")
        seen = "after the solution" if kept.solution_shown else "late"  # (as the gradebook calls it)
        st.warning(f"Recorded: {what}. Right, but it earns no points: {why}. It is kept, and your instructor "
                   f"sees it as right but {seen}.", icon=":material/schedule:")
    else:
        left = max(allowed - kept.number, 0)
        st.info(f"Recorded: {what}. Not right; {left} attempt{'s' if left != 1 else ''} left at this answer.",
                icon=":material/cancel:")
        if left == 0 and link.settings.answer_after_last and solution is not None:
            _show_answer(answer, solution, system, label)


def _show_answer(answer, solution, system: str, label: str) -> None:
    value = solution.answers.get(answer.name)
    if isinstance(value, (int, float)):
        st.info(f"You have used every attempt at {_named(label)}. The answer: "
                f"{units.format_quantity(value, answer.dimension, system)}.", icon=":material/lightbulb:")


def _problem_links(link: StudentLink) -> str:
    """The set's problems (HTML), each a link with the same signed query (the signature covers the
    assignment, variant and label, not the page), opened in the same tab or LMS frame: a Markdown
    link would open a new tab (Streamlit's default for every link it is not told otherwise of)."""
    query = html.escape(urllib.parse.urlencode(link_query(link.identity)))
    items = []
    for pid in link.settings.problems:
        name = html.escape(_title(pid))
        items.append(f"<li><strong>{name}</strong> (this page)</li>" if pid == link.problem else
                     f'<li><a href="{html.escape(pid)}?{query}" target="_self">{name}</a></li>')
    return "<ol>" + "".join(items) + "</ol>"


RULES = "The rules: what counts, your attempts left, the solution"


def assignment_heading(link: StudentLink) -> None:
    """The banner: that it is graded and the due time in the student's own time zone (or why nothing is
    recorded); under it, one tap away, what counts, the attempts left, the score and when the solution opens."""
    if link.settings is None:
        st.warning(link.notice, icon=":material/cloud_off:")
        return
    s = link.settings
    standing = _standing(link)
    due = standing.due if standing else s.due
    allowed = standing.allowed if standing else s.attempts_allowed
    zone, whose = _zone(link)
    now = records.now()
    lines = [f"**Graded assignment: {plain(s.title)}**, for student {literal(link.identity.label)}."]
    if not s.accepting:
        lines.append("**Closed by your instructor**: answers are checked but no longer recorded.")
    extended = " (your extension)" if standing and standing.grant.extended_due and due > s.due else ""
    if now > due:
        lines.append(f"**Due {records.when_text(due, zone)}**{extended}, {whose}: that has passed "
                     f"{records.duration_text(now - due)} ago. Answers are still recorded: "
                     f"{s.late_rule()}.")
    else:
        lines.append(f"**Due {records.when_text(due, zone)}**{extended}, {whose} ({records.duration_text(due - now)} "
                     f"from now).")
    # The banner says what and when; the rules are one tap away, so the problem comes first (on a phone
    # the whole banner was two screens before the givens).
    (st.info if s.accepting else st.warning)("\n\n".join(lines), icon=":material/assignment:")
    lines = [f"**After the due time**: {s.late_rule()}."] if now <= due else []
    lines.append(f"**What counts**: a right answer (numbers within ±{s.tolerance * 100:g} %), within {allowed} "
                 f"attempts per answer, before you open the solution. An answer the page cannot read (a typo, "
                 f"an unknown name, a unit of another kind) is explained and costs no attempt; the same answer "
                 f"twice in a row counts once. Feedback: {s.feedback_rule()}.")
    if standing:
        labels = _answer_labels(s)
        part = s.part(link.problem)
        left = [f"{plain(labels[(link.problem, a)].split(': ')[-1])} "
                + (standing.cells[(link.problem, a)].done() or f"{standing.left((link.problem, a))} of {allowed}")
                for a in part.answers]
        lines.append("**Attempts left**: " + " · ".join(left) + ".")
        lines.append(f"**Your score so far**: {records._number(standing.score())} of {records._number(s.out_of)} "
                     "points.")
    opens = _solution_opens(s, due)
    if opens is None:
        lines.append("**The solution**: you may open it now; answers you give after opening it do not count.")
    elif now < opens:
        lines.append(f"**The solution** opens at your due time, {records.when_text(opens, zone)}.")
    else:
        lines.append("**The solution** is open; answers you give after opening it do not count.")
    with st.expander(RULES, icon=":material/rule:"):
        st.markdown("\n\n".join(lines))
    if len(s.problems) > 1:
        st.markdown(f"**This assignment has {len(s.problems)} problems**, each with its own page:\n\n"
                    + _problem_links(link), unsafe_allow_html=True)  # (our titles and the signed query, escaped)


def your_attempts(link: StudentLink, answers, solution=None, system: str = "si") -> None:
    """The student's own attempts at this page's problem, and for each answer where it stands."""
    if link.settings is None:
        return
    try:
        standing = records.standing(link.identity)
    except records.RecordingUnavailable as error:
        st.warning(str(error))
        return
    if standing is None:
        return
    s = standing.settings
    zone, _ = _zone(link)
    st.markdown("### Your attempts")
    labels = {a.name: a.heading for a in answers} | {records.DIAGRAM: records.DIAGRAM_HEADING}
    by_name = {a.name: a for a in answers}
    lines = []
    part = s.part(link.problem)
    for name in part.answers:
        cell = standing.cells[(link.problem, name)]
        lines.append(f"- {plain(labels.get(name, name))}: {plain(cell.status(s))}"
                     f" ({records._number(part.weight(name) * cell.credit)} of {records._number(part.weight(name))} "
                     f"point{'s' if part.weight(name) != 1 else ''})")
        if (s.answer_after_last and cell.first_right is None and cell.attempts >= cell.allowed
                and solution is not None and name in by_name):
            value = solution.answers.get(name)
            if isinstance(value, (int, float)):
                lines.append(f"  - every attempt used; the answer: "
                             f"{plain(units.format_quantity(value, by_name[name].dimension, system))}")
    st.markdown("\n".join(lines))
    mine = [a for a in standing.attempts if a.problem == link.problem]
    if mine:
        def earned(a: records.Recorded) -> str:
            if a.credit >= 1:
                return "yes"
            if a.credit > 0:
                return f"{a.credit * 100:g} % (late)"
            return "no: " + ", ".join(a.marks()) if a.marks() else "no"

        # in time order; each attempt numbered at its answer, as "Recorded: attempt 2 of 3" said it
        # ("#" drew as a blank heading over numbers that restart per answer)
        st.table([{"answer": labels.get(a.answer, a.answer), "attempt": a.number, "you typed": literal(a.typed),
                   "verdict": "right" if a.correct else "not right", "slip": literal(records.slip_shown(a.slip, standing.settings)),
                   "time": records.when_text(a.at, zone), "counts": earned(a)} for a in mine])
        _tables_by_keyboard()


# -- the instructor's page

PAGE_PATHS = ("assignments", "gradebook")  # this page's url_path and its older alias (app.py)


def app_base(url: str) -> str:
    """The app's address in ``url`` (this page's, as the instructor's browser reached it), without this page's path."""
    parts = urllib.parse.urlsplit(url)
    path = parts.path.rstrip("/")
    head, _, last = path.rpartition("/")
    if last in PAGE_PATHS:
        path = head
    return urllib.parse.urlunsplit((parts.scheme, parts.netloc, path, "", ""))


def _app_base() -> str:
    return app_base(st.context.url or "http://localhost:8501/")


def student_url(base: str, problem: str, identity: StudentIdentity) -> str:
    return f"{base}/{problem}?{urllib.parse.urlencode(link_query(identity))}"


def _links_csv(base: str, problem: str, students: list[StudentIdentity]) -> str:
    return records.safe_csv(["label", "seed", "link"], ([s.label, s.seed, student_url(base, problem, s)] for s in students))


ZONES = sorted({z for z in zoneinfo.available_timezones() if "/" in z and not z.startswith(("posix/", "right/", "Etc/"))}
               | {"UTC"})


def _zone_picker(key: str, current: str | None = None) -> str:
    default = current or _browser_zone() or "UTC"
    if default not in ZONES:
        default = "UTC"
    if key not in st.session_state:
        st.session_state[key] = default
    return st.selectbox("Time zone for the due time", ZONES, key=key,
                        help="Due times are entered and shown in this zone (students see theirs in their own).")


def _late_inputs(prefix: str, policy: str = "none", value: float = 0.0) -> tuple[str, float]:
    names = {"none": "No late credit (late answers shown, worth nothing)", "per_day": "A penalty per day late",
             "fixed": "A fixed fraction of the points"}
    c1, c2 = st.columns([3, 2])
    chosen = c1.radio("Late work", list(names), index=list(names).index(policy), format_func=names.get,
                      key=f"{prefix}late_policy")
    if chosen == "per_day":
        pct = c2.number_input("Penalty per started day late (%)", 1.0, 100.0, value * 100 if value else 10.0, 1.0,
                              key=f"{prefix}late_per_day")
    elif chosen == "fixed":
        pct = c2.number_input("Fraction of the points a late right answer earns (%)", 0.0, 100.0,
                              value * 100 if policy == "fixed" else 50.0, 5.0, key=f"{prefix}late_fixed")
    else:
        pct = 0.0
    return chosen, pct / 100


NAMED_BY_HINTS = "Hints on already name the slip: untick Hints to choose."


def _feedback_inputs(prefix: str, s: records.Settings | None = None) -> tuple[bool, bool, bool, bool]:
    c1, c2 = st.columns(2)
    hints = c1.checkbox("Hints: a known slip is named with its hint (as in Practice)",
                        s.hints if s else True, key=f"{prefix}hints")
    named, kept = "Named slips (with hints off: the slip's name, no hint)", f"{prefix}slip_names"
    st.session_state.setdefault(kept, s.slip_names if s else True)
    if hints:  # the slip is named either way: the box shows so, and why it cannot be changed
        c1.checkbox(named, True, key=f"{prefix}slip_names_shown", disabled=True, help=NAMED_BY_HINTS)
        c1.caption(NAMED_BY_HINTS)
        st.session_state[kept] = st.session_state[kept]  # the instructor's own choice, kept for when hints go off
        names = True
    else:
        names = c1.checkbox(named, key=kept)
    after = c2.checkbox("Show the answer after an answer's last attempt",
                        s.answer_after_last if s else False, key=f"{prefix}answer_after_last")
    before = c2.checkbox("Students may open the solution before the due time",
                         s.solution_before_due if s else False, key=f"{prefix}before")
    return hints, names, after, before


def _due_inputs(prefix: str, zone: str, current: dt.datetime | None = None) -> dt.datetime:
    local = records.in_zone(current or records.now() + dt.timedelta(days=7), zone)
    c1, c2 = st.columns(2)
    day = c1.date_input(f"Due date ({zone})", local.date(), key=f"{prefix}due_day")
    time = c2.time_input(f"Due time ({zone})", local.time().replace(second=0, microsecond=0) if current
                         else dt.time(23, 59), key=f"{prefix}due_time", step=60)
    return dt.datetime.combine(day, time, zoneinfo.ZoneInfo(zone))


# Words that name a problem in a title (its id's words): "Week 13: ladder" with the disk chosen is flagged.
PROBLEM_WORDS = {p.id: set(re.split(r"[_\s]+", p.id.replace("eulers", "euler"))) for p in PROBLEMS}


def title_mismatch(title: str, chosen: list[str]) -> list[str]:
    """Words of the title that name a problem that is not chosen (and no chosen one)."""
    words = set(re.findall(r"[a-z]+", title.lower().replace("euler's", "euler")))
    mine = set().union(*(PROBLEM_WORDS.get(p, set()) for p in chosen)) if chosen else set()
    found = []
    for pid, named in PROBLEM_WORDS.items():
        if pid in chosen:
            continue
        for word in sorted((named & words) - mine):
            found.append(f"the title says “{word}”, but “{_title(pid)}” is not among the chosen problems")
    return found


def _roster_text(prefix: str) -> tuple[str, str]:
    """The roster as text (pasted, or the uploaded file's), and an error in plain words."""
    text = st.text_area("Roster: one student label per line (your own codes, no names)", key=f"{prefix}roster",
                        placeholder="s001\ns002\ns003")
    upload = st.file_uploader("…or a roster CSV (labels in the first column)", type=["csv", "txt"],
                              key=f"{prefix}roster_file")
    if upload is None:
        return text, ""
    data = upload.getvalue()
    if len(data) > records.MAX_ROSTER_TEXT * 4:
        return "", f"The roster file is too large ({len(data):,} bytes): one short label per line."
    try:
        return data.decode("utf-8-sig"), ""
    except UnicodeDecodeError:
        return "", "The roster file is not UTF-8 text: save it as CSV UTF-8 and upload it again."


NEW_FORM = "assign__new"  # the new assignment's inputs: keys f"{NEW_FORM}{n}_…", a fresh n once one is created


def _parts_inputs(p: str, chosen: list[str], s: records.Settings | None = None) -> list[records.Part]:
    """For each chosen problem, the answers that count and their points (as ``s`` has them, where it has
    the problem; every answer at 1 point otherwise)."""
    parts = []
    for pid in chosen:
        problem = BY_ID[pid]
        headings = {a.name: a.heading for a in _answers_of(problem)}
        typed = list(headings)
        headings[records.DIAGRAM] = f"{records.DIAGRAM_HEADING} (drawn on the page)"
        had = s.part(pid) if s is not None else None
        with st.container(border=True):
            st.markdown(f"**{plain(problem.title)}**")
            counted = st.multiselect("Answers that count", list(headings),
                                     default=[a for a in had.answers if a in headings] if had else typed,
                                     format_func=lambda name, headings=headings: headings[name],
                                     key=f"{p}answers_{pid}",
                                     help="The free-body diagram is a question too: the student draws it and checks "
                                          "it on the page, and each readable drawing is an attempt.")
            weights = [cell.number_input(f"Points: {headings[name]}", 0.1, 1000.0,
                                         float(had.weight(name)) if had and name in had.answers else 1.0, 0.5,
                                         key=f"{p}weight_{pid}_{name}") for cell, name in zip(_in_rows(len(counted)), counted)]
        parts.append(records.Part(pid, tuple(counted), tuple(weights)))
    return parts


def _new_assignment() -> None:
    st.markdown("Nothing is created until you press **Create**; the check above the button lists what "
                "would be wrong first.")
    p = f"{NEW_FORM}{st.session_state.get('assign__made', 0)}_"
    title = st.text_input("Title", key=f"{p}title", placeholder="Week 9: the bouncing pendulum")
    chosen = st.multiselect("Problems (one, or several for a problem set; in this order)", [q.id for q in PROBLEMS],
                            format_func=_title, key=f"{p}problems")
    parts = _parts_inputs(p, chosen)
    c1, c2 = st.columns(2)
    tolerance = c1.number_input("Tolerance for numbers (%)", 0.01, 10.0, RELATIVE_TOLERANCE * 100, 0.1,
                                key=f"{p}tolerance")
    attempts = c2.number_input("Attempts allowed per answer", 1, 100, 3, key=f"{p}attempts")
    zone = _zone_picker(f"{p}zone")
    due = _due_inputs(p, zone)
    policy, value = _late_inputs(p)
    hints, names, after, before = _feedback_inputs(p)
    text, file_error = _roster_text(p)

    settings = records.Settings(title, tuple(parts), tolerance / 100, due.astimezone(UTC), int(attempts), before,
                                policy, value, hints, names, after, zone)
    problems = list(settings.errors(creating=True))
    if file_error:
        problems.append(file_error)
    labels: list[str] = []
    if text.strip() and not file_error:
        try:
            labels = records.parse_roster(text)
        except ValueError as error:
            problems.append(str(error))
    elif not file_error:
        problems.append("Paste or upload a roster: one student label per line.")
    warnings = [w[0].upper() + w[1:] + "." for w in title_mismatch(title, chosen)]
    existing = None
    if not settings.errors():
        try:
            existing = records.find(settings)
        except records.RecordingUnavailable:
            pass

    st.markdown("#### Check before creating")
    if parts:
        summary = "; ".join(f"{_title(part.problem)} ({len(part.answers)} answers, "
                            f"{records._number(sum(part.weights))} points)" for part in parts)
        st.markdown(f"“{plain(title.strip() or '(no title)')}”: {plain(summary)}; due "
                    f"{records.when_text(due, zone)}; {int(attempts)} attempts per answer; "
                    f"{len(labels)} students; late: {plain(settings.late_rule())}; feedback: {settings.feedback_rule()}.")
    st.session_state["assign__drafting"] = bool(title.strip() or chosen or text.strip())
    if not (title.strip() or chosen or text.strip()):  # a fresh form: what it needs, not errors
        st.markdown("To create an assignment: a title, at least one problem, a due time in the future and a roster.")
        st.button("Create the assignment and its links", type="primary", key=f"{p}create", disabled=True)
        return
    for problem in problems:
        st.error(plain(problem), icon=":material/error:")
    for warning in warnings:
        st.warning(plain(warning), icon=":material/warning:")
    if existing is not None:
        st.info(f"This assignment exists already (number {existing.id}, created "
                f"{records.when_text(existing.created_at, zone)}): pressing Create again adds nothing.",
                icon=":material/content_copy:")
    confirmed = True
    if warnings and not problems:
        confirmed = st.checkbox("That is right: create it as it is", key=f"{p}confirm")
    if st.button("Create the assignment and its links", type="primary", key=f"{p}create",
                 disabled=bool(problems) or not confirmed):
        try:
            made = records.create(settings, labels)
        except ValueError as error:
            st.error(plain(str(error)))
            return
        # the form emptied and folded (its inputs under new keys), the assignment chosen below, where it says so
        st.session_state["assign__made"] = st.session_state.get("assign__made", 0) + 1
        st.session_state["assign__drafting"] = False
        st.session_state["assign__chosen"] = made.id
        st.session_state["assign__said"] = (
            f"Assignment {made.id} created for {made.students} students: its links are below." if made.new else
            f"Assignment {made.id} was already created ({records.when_text(made.created_at, zone)}), for "
            f"{made.students} students: nothing was added. Its links are below.")
        st.rerun()


def _assignment_choice(existing) -> int | None:
    ids = [aid for aid, _ in existing]
    status = {"open": "", "closed": " · closed", "archived": " · archived"}
    titles = {aid: f"{aid}: {s.title} ({', '.join(_title(p) for p in s.problems)}){status[s.status]}"
              for aid, s in existing}
    if st.session_state.get("assign__chosen") not in ids:
        st.session_state["assign__chosen"] = ids[0]
    return st.selectbox("Assignment", ids, format_func=titles.get, key="assign__chosen")


def _status_actions(aid: int, s: records.Settings) -> None:
    actions = {"open": [("Close (answers no longer recorded)", "closed"), ("Archive", "archived")],
               "closed": [("Reopen", "open"), ("Archive", "archived")],
               "archived": [("Unarchive (reopen)", "open")]}[s.status]
    columns = st.columns(len(actions) + 1)
    columns[0].markdown(f"Status: **{s.status}**")
    for column, (label, status) in zip(columns[1:], actions):
        if column.button(label, key=f"assign__status_{status}_{aid}"):
            said = records.set_status(aid, status)
            st.session_state["assign__said"] = f"Assignment {aid}: " + "; ".join(said) + "."
            st.rerun()


def _version(*values) -> str:
    """A short digest of what a form starts from: its widgets' keys carry it, so a form shown after
    a change (an undo, another tab's edit) starts from the stored values, not from stale inputs."""
    return hashlib.sha256(repr(values).encode()).hexdigest()[:8]


def _in_rows(count: int, across: int = 4) -> list:
    """``count`` cells in rows of ``across`` columns, in reading order: the Tab key goes along a row, then to
    the next (four columns of boxes took it down each column first)."""
    return [cell for start in range(0, count, across) for cell in st.columns(across)][:count]


def _edit(aid: int, s: records.Settings) -> None:
    p = f"assign__edit{aid}_{_version(s)}_"
    with st.expander("Edit: due time, attempts, tolerance, late work, feedback"):
        with st.form(f"{p}form"):
            title = st.text_input("Title", s.title, key=f"{p}title")
            c1, c2 = st.columns(2)
            tolerance = c1.number_input("Tolerance for numbers (%)", 0.01, 10.0, s.tolerance * 100, 0.1,
                                        key=f"{p}tolerance", help=f"A new tolerance {TOLERANCE_FROM_NOW}.")
            attempts = c2.number_input("Attempts allowed per answer", 1, 100, s.attempts_allowed, key=f"{p}attempts")
            zone = _zone_picker(f"{p}zone", s.timezone)
            # The date and time fields read in the zone their labels name, the assignment's own: a
            # new zone alone changes how times are shown, never the moment the work is due.
            due = _due_inputs(p, s.timezone, s.due)
            policy, value = _late_inputs(p, s.late_policy, s.late_value)
            hints, names, after, before = _feedback_inputs(p, s)
            save = st.form_submit_button("Save the changes")
        _check_and_save(aid, s, p, replace(s, title=title, tolerance=tolerance / 100, attempts_allowed=int(attempts),
                                           due=due.astimezone(UTC), late_policy=policy, late_value=value, hints=hints,
                                           slip_names=names, answer_after_last=after, solution_before_due=before,
                                           timezone=zone) if save else None)


def _check_and_save(aid: int, s: records.Settings, p: str, asked: records.Settings | None,
                    shown: records.Settings | None = None) -> None:
    """An edit asked for (``asked``, on a press of Save; None otherwise): its errors said, or kept while
    a warning that it lowers scores waits for an answer, and saved. ``shown``: what inputs outside a form
    show now; a waiting edit they no longer show is dropped (the warning goes: "Save it anyway" would
    have saved what the instructor had since corrected)."""
    if asked is not None:
        st.session_state.pop(f"{p}pending", None)
        if asked.errors():
            for problem in asked.errors():
                st.error(plain(problem))
            return
        st.session_state[f"{p}pending"] = asked
    if shown is not None and st.session_state.get(f"{p}pending") not in (None, shown):
        st.session_state.pop(f"{p}pending")
    new = st.session_state.get(f"{p}pending")
    if new is not None:
        _unless_it_takes_points(p, records.points_taken(aid, settings=new), lambda: _save_edit(aid, s, new))


def _edit_parts(aid: int, s: records.Settings) -> None:
    """The problems, the answers that count and their points: a problem added or taken out, an answer
    counted or not, its points (outside a form, so a problem chosen brings its answers at once)."""
    p = f"assign__parts{aid}_{_version(s)}_"
    with st.expander("Edit: problems, answers that count, points"):
        st.session_state.setdefault(f"{p}problems", list(s.problems))
        chosen = st.multiselect("Problems (in this order)", [q.id for q in PROBLEMS], format_func=_title,
                                key=f"{p}problems")
        parts = _parts_inputs(p, chosen, s)
        if chosen and chosen[0] != s.problem:
            st.info(f"Students' links open the first problem. The links already sent open “{_title(s.problem)}”"
                    + (", which still lists the assignment's problems." if s.problem in chosen else
                       ": that page will point them to this assignment's problems.")
                    + " “Download the links” gives the new ones.", icon=":material/link:")
        save = st.button("Save problems and points", key=f"{p}save")
        shown = replace(s, parts=tuple(parts))
        _check_and_save(aid, s, p, shown if save else None, shown)


# A verdict is the judge's when the answer was checked (what the student was told, and what the attempt counts
# as): a new tolerance is not applied to answers already recorded.
TOLERANCE_FROM_NOW = ("applies to answers checked from now on: those already recorded keep the verdict their "
                      "student was given")


def _save_edit(aid: int, s: records.Settings, new: records.Settings) -> None:
    passed = (" The new due time has passed: answers after it are late, those already recorded included."
              if new.due < records.now() <= s.due else "")
    passed += f" The new tolerance {TOLERANCE_FROM_NOW}." if new.tolerance != s.tolerance else ""
    said = records.edit(aid, new)
    st.session_state["assign__said"] = (f"Saved: {'; '.join(said)}.{passed}" if said else "Nothing changed.")
    st.rerun()


MAX_TAKEN_SHOWN = 12  # students named in the warning before an edit that lowers scores


def _whose(taken: list[records.PointsTaken]) -> str:
    """"2 students: s01 2 of 6 → 0 of 6, s02 …"."""
    named = ", ".join(f"{literal(t.label)} {records._number(t.before)} of {records._number(t.out_of_before)} → "
                      f"{records._number(t.after)} of {records._number(t.out_of_after)}" for t in taken[:MAX_TAKEN_SHOWN])
    more = f" and {len(taken) - MAX_TAKEN_SHOWN} more" if len(taken) > MAX_TAKEN_SHOWN else ""
    return f"{_students(len(taken))}: {named}{more}"


def _unless_it_takes_points(p: str, taken: list[records.PointsTaken], save) -> None:
    """``save()`` at once; or, where it would lower students' scores (an earlier due time turning answers
    already made late, an extension taken back…), say whose and by how much, and save only when asked
    again: an edit applies to the attempts already recorded."""
    if not taken:
        st.session_state.pop(f"{p}pending", None)
        save()
        return
    st.warning(f"**Nothing is saved yet.** This change applies to the answers already recorded too, and lowers "
               f"the share of the points earned by {_whose(taken)}.", icon=":material/warning:")
    save_anyway, keep = st.columns(2)
    if save_anyway.button("Save it anyway", key=f"{p}anyway"):
        st.session_state.pop(f"{p}pending", None)
        save()
    if keep.button("Do not save it", key=f"{p}cancel"):
        st.session_state.pop(f"{p}pending", None)
        st.rerun()


def _per_student(aid: int, book: records.Gradebook) -> None:
    s = book.settings
    labels = [st_.label for st_ in book.students if st_.seed >= 0]
    with st.expander("One student: an extension or extra attempts"):
        if not labels:
            st.markdown("No students yet.")
            return
        who = st.selectbox("Student", labels, key=f"assign__grant{aid}_who")
        grant = book.grants.get(who, records.Grant())
        p = f"assign__grant{aid}_{_version(grant, s.due)}_"  # (a new due time: a new suggested extension)
        with st.form(f"{p}form"):
            extend = st.checkbox("An extension: a later due time for this student", grant.extended_due is not None,
                                 key=f"{p}extend_{who}")
            due = _due_inputs(f"{p}{who}_", s.timezone, grant.extended_due or s.due + dt.timedelta(days=2))
            extra = st.number_input("Extra attempts per answer", 0, 100, grant.extra_attempts, key=f"{p}extra_{who}")
            save = st.form_submit_button("Save for this student")
        if save:
            if extend and due <= s.due:
                st.error(f"The extension must be after the assignment's due time, {records.when_text(s.due, s.timezone)}.")
                return
            st.session_state[f"{p}pending"] = (who, records.Grant(due.astimezone(UTC) if extend else None, int(extra)))
        pending = st.session_state.get(f"{p}pending")
        if pending is not None and pending[0] == who:
            _unless_it_takes_points(p, records.points_taken(aid, grants=dict([pending])),
                                    lambda: _save_grant(aid, *pending))


def _save_grant(aid: int, who: str, grant: records.Grant) -> None:
    try:
        said = records.grant(aid, who, extended_due=grant.extended_due, extra_attempts=grant.extra_attempts)
    except ValueError as error:
        st.error(plain(str(error)))
        return
    st.session_state["assign__said"] = f"Saved: {said}." if said else "Nothing changed."
    st.rerun()


def _add_students(aid: int, s: records.Settings) -> None:
    p = f"assign__more{aid}_"
    with st.expander("Add students to the roster"):
        text, problem = _roster_text(p)
        labels: list[str] = []
        if text.strip() and not problem:
            try:
                labels = records.parse_roster(text)
            except ValueError as error:
                problem = str(error)
        if problem:  # said as it is typed, as the new assignment's form does
            st.error(plain(problem), icon=":material/error:")
        if labels and s.due < records.now():
            st.warning(f"The due time has passed ({records.when_text(s.due, s.timezone)}): students added now start "
                       "late. Give each an extension under “One student” once added.", icon=":material/schedule:")
        if st.button("Add these students", key=f"{p}add", disabled=not labels or bool(problem)):
            before = {st_.label for st_ in records.roster(aid)}
            records.enrol(aid, labels)
            new = [label for label in labels if label not in before]
            had = len(labels) - len(new)
            st.session_state["assign__said"] = (
                f"Added {_students(len(new))}" + (f"; {_students(had)} {'was' if had == 1 else 'were'} on the roster "
                                                  "already (their links are unchanged)" if had else "") + ".")
            st.rerun()


def _students(n: int) -> str:
    return f"{n} student{'' if n == 1 else 's'}"


LEGEND = ("**Reading the gradebook.** Each answer's cell says where the student stands, in words: *right at "
          "attempt 2* (on time, full points); *right 3 h late (attempt 1): 80 % credit* (after the student's due "
          "time, with the late credit you set); *right but 1 day late: no credit* (no late credit set; kept so you "
          "can decide); *right but over the limit* or *after the solution* (no credit); *not right yet: 1 of 3 "
          "attempts used*; *not right: 4 attempts, 3 allowed* (tries past the limit are kept); *not tried*. **Score** is the points earned out of the points possible (each answer's "
          "points × the credit it earned); **how** shows the sum. An answer the page could not read (a typo) is "
          "never an attempt; the same answer twice in a row counts once. Slips are the known mistakes a student's "
          "wrong answers matched.")


# A student's link is that student: whoever opens it answers as them (no key is asked of a student).
OPENING_A_LINK = ("Opening a student's link answers as that student: every answer checked there is recorded as "
                  "theirs, and opening the solution there costs them the points of the answers not yet right. The links are shown to copy, not to "
                  "click; to try the assignment yourself, open its problems in Practice.")


LINKS_CSS = """<style>
  .dl-links ul { list-style: none; padding: 0; margin: 0; }
  .dl-links li { display: grid; grid-template-columns: minmax(3rem, auto) 1fr auto; gap: 0.25rem 0.75rem;
                 align-items: center; padding: 0.4rem 0; border-bottom: 1px solid rgba(128, 128, 128, 0.25); }
  .dl-links code { font-size: 0.85rem; overflow-wrap: anywhere; user-select: all; }
  .dl-links button { font: inherit; font-size: 0.875rem; padding: 0.25rem 0.75rem; min-height: 2.25rem; min-width: 5.5rem;
                     border: 1px solid rgba(128, 128, 128, 0.6); border-radius: 0.5rem; background: transparent;
                     color: inherit; cursor: pointer; position: relative; }
  .dl-links button:hover { border-color: currentColor; }
  .dl-links button:focus-visible { outline: 2px solid currentColor; outline-offset: 2px; }
  .dl-links button.dl-copied { border-color: #1c7c3c; color: #1c7c3c; }
  .dl-links .dl-sr { position: absolute; width: 1px; height: 1px; overflow: hidden; clip-path: inset(50%); white-space: nowrap; }
  .dl-links [role='status'] { min-height: 1.5rem; margin: 0.5rem 0 0; }
  @media (max-width: 640px) { .dl-links li { grid-template-columns: 1fr auto; } .dl-links code { grid-column: 1 / -1; grid-row: 2; } }
</style>"""


def link_list(links: list[tuple[str, str]]) -> str:
    """The students' links as HTML: each label, its link as text (whole, to select or copy) and a Copy
    button (inline_scripts.COPY_LINKS); a status line says what was copied."""
    rows = "".join(
        f'<li><span>{html.escape(label)}</span><code>{html.escape(url)}</code>'
        f'<button type="button" data-dl-copy="{html.escape(label)}"><span class="dl-copy-word">Copy</span>'
        f'<span class="dl-sr"> {html.escape(label)}\'s link</span></button></li>'
        for label, url in links)
    return (f'{LINKS_CSS}<div class="dl-links"><ul aria-label="Students\' links">{rows}</ul>'
            '<p role="status"></p></div>')


def _gradebook(aid: int, course: dict | None = None) -> None:
    book = records.gradebook(aid)
    s = book.settings
    labels = _answer_labels(s)
    base = _app_base()
    said = st.session_state.pop("assign__said", "")
    slot = st.empty()  # always there, so the expanders below keep their place (and stay open)
    if said:
        slot.success(plain(said))
        st.toast(plain(said)[:300], icon=":material/check:")  # seen where the button was pressed, below
    st.markdown(f"Due {records.when_text(s.due, s.timezone)} · {s.attempts_allowed} attempts per answer · numbers "
                f"within ±{s.tolerance * 100:g} % · late: {plain(s.late_rule())} · feedback: {s.feedback_rule()}"
                f"{'; the answer after the last attempt' if s.answer_after_last else ''} · solution before the due "
                f"time: {'yes' if s.solution_before_due else 'no'} · {records._number(s.out_of)} points")
    _status_actions(aid, s)
    _edit(aid, s)
    _edit_parts(aid, s)
    _per_student(aid, book)
    _add_students(aid, s)

    st.markdown("#### Links, one per student")
    st.markdown("Send each student their own link (by your course's messaging, not in a public place): it opens "
                "their variant, and a changed link is refused."
                + (" A link opens the first problem; the page lists the others." if len(s.parts) > 1 else ""))
    st.info(OPENING_A_LINK, icon=":material/person:")
    st.download_button("Download the links (CSV)", _links_csv(base, s.problem, book.students),
                       file_name=f"assignment-{aid}-links.csv", mime="text/csv", key="assign__links_csv")
    with st.expander(f"The links ({len(book.students)})"):  # as text to copy, not to click (OPENING_A_LINK)
        st.html(link_list([(st_.label, student_url(base, s.problem, st_)) for st_ in book.students]))
        st.html(COPY_LINKS, unsafe_allow_javascript=True)

    st.markdown("#### Gradebook")
    short, key = _short_labels(s)
    if key:
        st.markdown(key)
    rows = []
    for student in book.students:
        grant = book.grants.get(student.label, records.Grant())
        row = {"student": literal(student.label),
               "score": f"{records._number(book.score(student.label))} / {records._number(s.out_of)}"}
        for q in s.questions:
            c = book.cell(student.label, q)
            words = c.status(s)
            if c.slips:
                words += "; slips: " + ", ".join(map(literal, c.slips))
            row[short[q]] = words
        granted = []
        if grant.extended_due:
            granted.append(f"due {records.when_text(grant.extended_due, s.timezone)}")
        if grant.extra_attempts:
            granted.append(f"+{grant.extra_attempts} attempts")
        row["extension"] = ", ".join(granted) or "—"
        row["how"] = book.how(student.label, short)
        rows.append(row)
    st.table(rows, alt="Gradebook")
    st.markdown(LEGEND)
    c1, c2 = st.columns(2)
    c1.download_button("Download the gradebook (CSV)", records.gradebook_csv(book, labels),
                       file_name=f"assignment-{aid}-gradebook.csv", mime="text/csv", key="assign__book_csv")
    c2.download_button("Download every attempt (CSV)", records.attempts_csv(aid, names=labels),
                       file_name=f"assignment-{aid}-attempts.csv", mime="text/csv", key="assign__attempts_csv")
    c3, c4 = st.columns(2)
    c3.download_button("Grades for Canvas (CSV)", records.lms_csv(book, "canvas"),
                       file_name=f"assignment-{aid}-canvas.csv", mime="text/csv", key="assign__canvas_csv",
                       help="Canvas: Grades › Import. Your labels go in the SIS User ID and SIS Login ID columns, "
                            "so use your students' SIS ids as labels.")
    c4.download_button("Grades for Moodle (CSV)", records.lms_csv(book, "moodle"),
                       file_name=f"assignment-{aid}-moodle.csv", mime="text/csv", key="assign__moodle_csv",
                       help="Moodle: Grades › Import › CSV file; map “ID number” to the user's ID number.")
    _passback(aid)
    if course is not None and course.get("nrps"):
        _course_roster(aid, course)
    st.markdown("#### Per answer")
    st.markdown("\n".join(f"- **{plain(labels[q])}**: " + " ".join(plain(line) for line in lines)
                          for q, lines in book.statistics().items()))
    _history(aid, s)
    _tables_by_keyboard()


def _tables_by_keyboard() -> None:
    """A table wider than the page scrolls sideways: reachable by keyboard (inline_scripts.SCROLLABLE_TABLES)."""
    st.html(SCROLLABLE_TABLES, unsafe_allow_javascript=True)


def _passback(aid: int) -> None:
    """What reached the LMS's gradebook (students who came from an LMS only)."""
    sent = passback.summary(aid)
    if sent is None:
        return
    st.markdown("#### Grades sent to the LMS")
    st.markdown(f"{sent.sent} sent · {sent.waiting} waiting · {len(sent.failed)} not accepted by the LMS. "
                "The best score is sent after each recorded attempt; a busy LMS is tried again by itself.")
    if sent.failed:
        st.warning("The LMS did not accept these scores (they are tried again every hour):", icon=":material/sync_problem:")
        st.table([{"student": literal(label), "why": plain(why)} for label, why in sent.failed])
        if st.button("Send again now", key=f"assign__resend{aid}"):
            st.session_state["assign__said"] = f"{passback.send_again(aid)} scores will be sent again."
            st.rerun()


def _course_roster(aid: int, course: dict) -> None:
    """The LMS's roster (NRPS), asked for by the instructor: who has not started. Names are shown
    as the LMS gives them, not stored."""
    st.markdown("#### Your course's students")
    if not st.button("Read the roster from the LMS", key=f"assign__roster_lms{aid}",
                     help="Who in your course has not started this assignment. The names come from your LMS "
                          "and are not stored here."):
        return
    try:
        members = lti_roster.standing(course["iss"], course.get("aud", ""), course["nrps"], aid)
    except lti_roster.RosterUnavailable as error:
        st.warning(str(error), icon=":material/group_off:")
        return
    waiting = sum(m.attempts == 0 for m in members)
    st.markdown(f"{len(members)} students in the course; {waiting} {'has' if waiting == 1 else 'have'} not started.")
    st.table([{"student": literal(m.name) or "(no name shared)", "label here": literal(m.label),
               "attempts": str(m.attempts) if m.attempts else "not started"} for m in members])


def _history(aid: int, s: records.Settings) -> None:
    entries = records.history(aid)
    st.markdown("#### History")
    st.markdown("Every change to this assignment, newest first, with its time. Undoing a change is itself a "
                "change, kept here.")
    st.table([{"number": e.id, "time": records.when_text(e.at, s.timezone), "change": e.action,
               "what": plain(e.summary) + (" (undone)" if e.undone else "")} for e in entries])
    undoable = [e for e in entries if e.action not in ("created", "roster") and not e.undone]
    c1, c2, c3 = st.columns([3, 1, 2])
    if undoable:
        # keyed by the newest change: after another change the newest is chosen again, not the one picked before
        chosen = c1.selectbox("Undo a change", [e.id for e in undoable], key=f"assign__undo_pick{aid}_{undoable[0].id}",
                              format_func=lambda i: f"#{i}: " + next(e.summary for e in undoable if e.id == i)[:80])
        # (keyed by the newest change too: a change logged meanwhile, by another tab, drops this press rather
        # than undoing what is newest now instead of what was picked)
        if c2.button("Undo", key=f"assign__undo{aid}_{undoable[0].id}"):
            try:
                before = records.gradebook(aid)
                said = records.undo(aid, chosen)
            except ValueError as error:
                st.error(plain(str(error)))
                return
            taken = records.lowered(before, records.gradebook(aid)) if said else []
            st.session_state["assign__said"] = (f"Undone: {said}." + (f" It lowered the share of the points earned by {_whose(taken)}."
                                                if taken else "") if said else "Nothing to undo.")
            st.rerun()
    c3.download_button("Download the history (CSV)", records.history_csv(entries),
                       file_name=f"assignment-{aid}-history.csv", mime="text/csv", key="assign__history_csv")


def instructor_page() -> None:
    st.markdown("# Assignments\n:gray[Signed per-student links, every attempt recorded, the gradebook.]")
    arrival = lti_arrival()
    course = lms_course()
    if arrival and arrival.get("refused"):
        st.error(arrival["refused"])
    if course is None and not instructor_key_entry("assign__instructor_key", "assignments"):
        return
    if not signing.configured():
        st.warning(f"The course admin has not set a course secret (`{signing.SECRET_ENV}`, at least "
                   f"{signing.MIN_SECRET} characters), so assignment links cannot be signed.")
        return
    if not schema_ready():
        st.error("The course's database cannot be reached, so assignments cannot be created or read now. "
                 "Practice pages still work. (Admin: check DL_DATABASE_URL and the database server.)")
        return
    try:
        show_archived = st.session_state.get("assign__archived", False)
        if course is not None:  # an instructor from the LMS: this course's assignments, no others
            placed = course_assignments(course)
            existing = [(aid, s) for aid, s in records.assignments(archived=show_archived) if aid in placed]
            st.info(f"From your course site{': ' + plain(course['title']) if course.get('title') else ''}. These "
                    "are its Dynamics Lab assignments; add another with your LMS's “add external tool” dialog.",
                    icon=":material/school:")
            if course.get("a") in placed:
                st.session_state.setdefault("assign__chosen", course["a"])
        else:
            existing = records.assignments(archived=show_archived)
            with st.expander("New assignment", expanded=not existing or st.session_state.get("assign__drafting", False),
                             icon=":material/add:"):
                _new_assignment()
            existing = records.assignments(archived=show_archived)  # with the one just created
        st.markdown("### Your assignments")
        st.toggle("Show archived assignments", key="assign__archived")
        if not existing:
            st.markdown("No assignments yet." if not show_archived else "No assignments.")
            return
        _gradebook(_assignment_choice(existing), course)
    except records.RecordingUnavailable as error:
        st.error(str(error))
