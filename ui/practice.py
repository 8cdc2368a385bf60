"""“Try it yourself”: the problem with every given, the method's first steps without their results,
a box per answer (a number or an expression in the givens), feedback on the common slips, then the
solution on request. The instructor's side (the variant export, and Study or Lecture for a variant
link) needs the instructor key. Nothing a student types is evaluated or rendered as Markdown."""
from __future__ import annotations

import html
import ipaddress
import re
from dataclasses import dataclass
from typing import Callable

import sympy as sp
import streamlit as st
from streamlit.runtime.scriptrunner import get_script_run_ctx

from practice import instructor
from practice.judge import RELATIVE_TOLERANCE, Judge, Verdict, tolerance_text
from practice.variants import MAX_SEED, variants_csv
from solvers.core import Choice, Derivation, Solution
from solvers.solution import PARTS
from solvers import units
from ui.catalog import Problem
from ui.equations import PHONE_WIDTH_EM, broken
from ui.inline_scripts import TAKE_FOCUS
from ui.results import literal, plain, plain_with_math

INSTRUCTOR = "dl_instructor"  # session flag: the key was entered (once per session, for every page)
KEY_MESSAGE = "dl_instructor_message"  # what the last try of the key was told


def seed_from_url() -> tuple[int | None, str | None]:
    raw = st.query_params.get("seed")
    if raw is None:
        return None, None
    if re.fullmatch(r"\d{1,10}", raw) and int(raw) <= MAX_SEED:
        return int(raw), None
    return None, f"The link's variant number “{literal(raw[:20])}” is not a whole number from 0 to {MAX_SEED}; " \
                 "showing the textbook's numbers."


def client() -> tuple[str, str]:
    """(this browser session's id, the client's address as the server knows it). The server takes
    X-Forwarded-For only from the proxies the admin names in DL_TRUSTED_PROXIES (serve.py hands
    them to uvicorn), so a client cannot name another address for itself; an IPv6 client counts by
    its /64 network (one host holds a whole /64). Streamlit says None for loopback."""
    ctx = get_script_run_ctx()
    peer = st.context.ip_address
    address = peer if isinstance(peer, str) and peer else "127.0.0.1"
    try:
        ip = ipaddress.ip_address(address)
        if ip.version == 6:
            address = str(ipaddress.ip_network(f"{ip}/64", strict=False))
    except ValueError:
        pass
    return (ctx.session_id if ctx else "?"), address[:64]


def try_instructor_key(typed: str) -> None:
    """One try of the key (throttled: practice/instructor.py); the verdict's words kept for the page."""
    verdict = instructor.try_key(typed, *client())
    if verdict.ok:
        st.session_state[INSTRUCTOR] = True
    st.session_state[KEY_MESSAGE] = verdict.message()


def take_instructor_link() -> None:
    """?instructor=KEY, on any page: tried once and dropped from the address bar at once (it still
    reaches the browser's history and the proxy's log: typing the key is safer)."""
    if "instructor" in st.query_params:
        typed = st.query_params.get("instructor")
        del st.query_params["instructor"]
        if not st.session_state.get(INSTRUCTOR):
            try_instructor_key(typed)


def is_instructor() -> bool:
    """True once this session gave the instructor key, in a key box or as ?instructor=KEY."""
    take_instructor_link()
    return bool(st.session_state.get(INSTRUCTOR))


def answer_label(answer) -> str:
    """The label with its first letter capitalised and the rest as written (cm, v_cm, I_O)."""
    return answer.heading


def read_in(answer, system: str) -> str:
    """The unit a number typed alone is read in, in words for degrees; "" for a number without one."""
    unit = units.unit(answer.dimension, system) if answer.dimension in units.DIMENSIONS else ""
    return "degrees" if unit == "°" else unit


def answer_choice(answer, system: str) -> str:
    """An answer as the answer box offers it: its label and the unit a number typed alone is read in
    ("Angular velocity just after impact, in rad/s")."""
    return answer_label(answer) + (f", in {unit}" if (unit := read_in(answer, system)) else "")


def statement(problem: Problem, solution: Solution, answers, system: str, judge: Judge) -> str:
    """The problem as an exercise: every given with its value, then what to find."""
    rows = ["| given | symbol, typed as | value |", "|---|---|---|"]
    for p in problem.solver.PARAMS:
        value = solution.params[p.name]
        if isinstance(p, Choice):
            rows.append(f"| {plain(p.label)} | | {plain(p.label_of(value))} |")
        else:
            sym = judge.givens.get(p.name)
            typed = f"`{judge.typed_name(sym)}`" if sym is not None else ""
            rows.append(f"| {plain(p.label)} | ${p.symbol}$ {typed} | {units.format_quantity(value, p.dimension, system)} |")
    find = "\n".join(f"- {plain(answer_label(a))}, ${a.symbol}$" + (f", in {plain(u)}" if (u := read_in(a, system)) else "")
                     for a in answers)
    return "\n\n".join(["### The problem", "\n".join(rows),
                        "**Find**", find])


def flat_latex(latex: str) -> str:
    """LaTeX with its braces, spaces and \\left/\\right sizing taken out, so that P_{t} and P_t, or
    sympy's and a step's spacing of the same formula, compare alike. The page's method filter and
    the tests' leak check share it, so they cannot disagree about what counts as showing a result."""
    return re.sub(r"\\(?:left|right)(?![A-Za-z])|[{}\s]", "", latex)


def result_forms(derivation: Derivation) -> list[str]:
    """Every way a step can show a result (flattened): its symbol, and its closed form in the givens
    (a step may state N_front's expression without naming N_front). A closed form without givens
    (a bare number) is left to the value check: it would match any step with that number."""
    forms = []
    for link in derivation.chain:
        forms.append(flat_latex(sp.latex(link.symbol)))
        closed = derivation.expression_of(link.name)
        if closed.free_symbols:
            forms.append(flat_latex(sp.latex(closed)))
    return forms


DRAW_IT = ("Draw the free-body diagram: isolate the body, and put on it every force, impulse and couple, each "
           "at the point where it acts (the diagram comes with the solution).")


def exercise_steps(steps, derivation: Derivation) -> list[tuple[int, str, str]]:
    """The method as an exercise shows it, (part, title, equation or ""): every step's title, and the
    equation only of the steps that show no result (no unknown, answer or intermediate value, by
    symbol or by closed form); the free-body diagram (Step 2) is the student's to draw, so its steps
    are one instruction and the balance laws written from it (Step 3) keep their titles alone."""
    forms = result_forms(derivation)
    out = []
    for step in steps:
        if step.part == 2:
            if not out or out[-1][0] != 2:
                out.append((2, DRAW_IT, ""))
            continue
        flat = flat_latex(step.latex)
        shows = step.part == 3 or any(form in flat for form in forms)
        out.append((step.part, step.title, "" if shows else step.latex))
    return out


def method(steps, derivation: Derivation) -> str:
    """The method (``exercise_steps``) under the course's four headings."""
    blocks, last = [], None
    for i, (part, title, tex) in enumerate(exercise_steps(steps, derivation), start=1):
        if part != last:
            blocks.append(f"#### {PARTS[part]}")
            last = part
        blocks.append(f"**{i}.** {plain_with_math(title)}")
        if tex:  # broken over rows where wide (a display equation that scrolls sideways is a region a keyboard cannot reach)
            blocks.append(f"$$\n{broken(tex, PHONE_WIDTH_EM)}\n$$")
    return "\n\n".join(["### The method", ":gray[The steps to take. Equations that lead to a result appear "
                        "with the solution.]", *blocks])


@dataclass(frozen=True)
class Recording:
    """An assignment's rules and the calls that record what the student does (ui/assignments.py)."""
    tolerance: float
    on_verdict: Callable[[object, str, Verdict], None]  # (answer, typed text, verdict), after it is shown
    on_reveal: Callable[[], bool]  # record "solution shown"; False if it could not be recorded
    revealed: bool = False  # the student has already seen the solution (recorded earlier)
    reveal_blocked: str = ""  # why "Show the solution" is not offered yet ("" when it is)
    say: Callable[[Verdict], str] | None = None  # the verdict's message under the feedback policy
    reveal_costs: str = ""  # what opening the solution costs, asked to confirm first ("": opened at once)


def practice_panel(problem: Problem, solution: Solution, answers, system: str,
                   recording: Recording | None = None) -> bool:
    """The exercise and its answer box; return True once the student asked to see the solution."""
    signature = repr(sorted(solution.params.items()))
    revealed_key = f"{problem.id}__revealed"
    if recording is not None and recording.revealed:
        st.session_state[revealed_key] = signature
    if st.session_state.get(revealed_key) != signature:
        st.session_state.pop(revealed_key, None)
    tolerance_value = recording.tolerance if recording else RELATIVE_TOLERANCE
    found_key = f"{problem.id}__found"  # the answers checked right for these numbers: the tally, and symbols to use
    if st.session_state.get(found_key, (None,))[0] != signature:
        st.session_state[found_key] = (signature, ())
    found = st.session_state[found_key][1]
    judge = Judge(solution, problem.solver.derivation_of(solution), answers, tolerance_value, found=found)
    revealed = st.session_state.get(revealed_key) == signature
    if not revealed:
        if recording is None:  # an assignment's banner says what holds for it instead
            st.info("Practice, not a proctored assessment: work the problem with these numbers, then check "
                    "your answers. The solution stays hidden until you ask for it.", icon=":material/school:")
        st.markdown(statement(problem, solution, answers, system, judge))
        st.markdown(method(solution.steps[: solution.symbolic_steps], judge.derivation))
    tally = st.empty()  # filled once this run's check is judged
    with st.form(key=f"{problem.id}__practice"):
        # How to type an answer is the chooser's help: its "?" comes before the choice, so Tab goes from the
        # choice straight into the box (a "?" in the box's label took the first Tab, and the typing went nowhere)
        answer = st.selectbox("Answer to check", answers, format_func=lambda a: answer_choice(a, system),
                              key=f"{problem.id}__attempt_answer",
                              help="Type a number, with a unit (mm, kN, ft/s, slug·ft² …; units are case-sensitive) "
                                   "or alone: read in the unit named with the answer (degrees for angles); or an "
                                   f"expression in the givens: {judge.givens_text()}, written as by hand (2V sinθ/3 "
                                   "is 2·V·sin θ/3), with a unit after it if you like. Write powers as ^ or **, "
                                   "e.g. (a + b)^2/3, sqrt(x), sin(θ), or 30° inside sin.")
        box, tolerance = st.columns([5, 1], vertical_alignment="bottom")
        # No max_chars: Streamlit drops a paste longer than it without a word; the judge says the limit
        text = box.text_input("Your answer", key=f"{problem.id}__attempt",
                              placeholder="a number (unit optional), or an expression")  # (whole in a phone's box)
        tolerance.markdown(f"within {tolerance_text(tolerance_value)}", help="A number counts as right within this relative "
                           "tolerance, unless it is nearer a known slip's value. An expression must equal "
                           "the answer.")
        submitted = st.form_submit_button("Check", type="primary", key=f"{problem.id}__check")
    if submitted:
        verdict = judge.check(answer, text or "", system)
        if verdict.understood:
            st.markdown("Read as:")  # not st.caption: its grey fails AA contrast
            st.latex(verdict.understood)
        # (an answer not read is explained whatever the feedback: it is a typo, or a unit left out, never judged)
        message = recording.say(verdict) if recording is not None and recording.say and verdict.readable else verdict.message
        if not verdict.readable:  # a typo, an unknown name, a unit of another kind: explained, not judged
            st.warning(plain(message) + (" This is not counted as an attempt." if recording is not None else ""),
                       icon=":material/edit_note:")
        elif verdict.correct:
            st.success(plain(message), icon=":material/check_circle:")
        else:
            st.error(plain(message), icon=":material/cancel:")
        if recording is not None:
            recording.on_verdict(answer, text or "", verdict)
        if verdict.correct and answer.name not in found:
            found = (*found, answer.name)
            st.session_state[found_key] = (signature, found)
    if found and not revealed:
        tally.markdown(_tally(answers, found, system))
    if not revealed and recording is not None and recording.reveal_blocked:
        st.markdown(plain(recording.reveal_blocked))
    elif not revealed:
        _reveal(problem, recording, revealed_key, signature)
    return revealed


def _tally(answers, found, system: str) -> str:
    """The answers checked right so far for these numbers, and those left (each may then be written in
    an answer that follows from it)."""
    right = [answer_label(a) for a in answers if a.name in found]
    left = [answer_label(a) for a in answers if a.name not in found]
    said = f"**Right so far ({len(right)} of {len(answers)}):** " + "; ".join(f"✓ {plain(r)}" for r in right)
    if left:
        said += "  \n**Still to check:** " + "; ".join(plain(x) for x in left)
    return said + ("  \nYou may use a right answer's symbol in the answers that follow from it." if left else "")


def _take_focus(key: str | None) -> None:
    """The button keyed ``key`` takes the keyboard's focus once this run is drawn (inline_scripts.TAKE_FOCUS)."""
    if key:
        st.html(f'<span data-dl-focus="{html.escape(key)}" hidden></span>{TAKE_FOCUS}', unsafe_allow_javascript=True)


def _reveal(problem: Problem, recording: Recording | None, revealed_key: str, signature: str) -> None:
    """"Show the solution"; where opening it costs something (an assignment's points), said first and
    opened only on a second, deliberate press (on a phone it sits under Check)."""
    asking, costs = f"{problem.id}__reveal_asked", recording.reveal_costs if recording is not None else ""
    focus = f"{problem.id}__reveal_focus"  # the button to take the keyboard's focus on the run after a press
    asked = st.session_state.get(asking) == signature and costs
    if asked:
        st.warning(costs, icon=":material/visibility:")
        open_it, keep = st.columns(2)
        if keep.button("Keep it hidden", key=f"{problem.id}__reveal_keep"):
            st.session_state.pop(asking, None)
            st.session_state[focus] = f"{problem.id}__reveal"
            st.rerun()
        pressed = open_it.button("Open the solution", key=f"{problem.id}__reveal_sure")
    else:
        pressed = st.button("Show the solution", key=f"{problem.id}__reveal")
    _take_focus(st.session_state.pop(focus, None))
    if not pressed:
        return
    if costs and not asked:
        st.session_state[asking] = signature
        st.session_state[focus] = f"{problem.id}__reveal_sure"
        st.rerun()
    st.session_state.pop(asking, None)
    if recording is None or recording.on_reveal():
        st.session_state[revealed_key] = signature
        st.rerun()


def instructor_key_entry(key: str, what: str = "the answer keys") -> bool:
    """True for an instructor (the key given once this session); else ask for it and return False."""
    if not instructor.configured():
        st.markdown(f"The course admin has not set an instructor key (`{instructor.KEY_ENV}`, at least "
                    f"{instructor.MIN_LENGTH} characters), so {what} stay closed.")
        return False
    if is_instructor():
        return True
    st.text_input("Instructor key", type="password", key=key, on_change=_key_typed, args=(key,),
                  help="Set by the course admin. Kept by this tab only, never in a cookie (a shared "
                       "lecture-hall computer keeps no instructor behind): a reload or a new tab asks again. "
                       "An instructor link (?instructor=KEY) does the same.")
    if st.session_state.get(KEY_MESSAGE):
        st.error(st.session_state[KEY_MESSAGE])
    return False


def _course_keys(problem: Problem) -> None:
    """An LMS instructor's session (no key given): its course's assignments on this problem, whose
    answer keys the Handouts page gives it; the ``?seed=N`` variants below are every course's, so
    they stay behind the key."""
    from ui.assignments import course_assignments, lms_course  # (ui.assignments imports this module)
    from assignments import records

    course = lms_course()
    if course is None:
        return
    try:
        placed = course_assignments(course)
        mine = [s.title for aid, s in records.assignments() if aid in placed and problem.id in s.problems]
    except records.RecordingUnavailable as error:
        st.error(str(error))
        return
    said = ", ".join(f"“{plain(t)}”" for t in mine) if mine else "none on this problem yet"
    st.markdown(f"From your course site. Your course's assignments here: {said}. Each student's givens and "
                "answers are on the **Handouts** page (in the menu, For instructors; choose **Answer key**), "
                "with no key to type. The numbered variants of `?seed=N` links below are shared by every "
                "course: they need the instructor key.")


def _key_typed(key: str) -> None:
    """The key box changed: one try, and the box emptied (a rerun does not try the same text again)."""
    typed = st.session_state.get(key) or ""
    st.session_state[key] = ""
    if typed:
        try_instructor_key(typed)


def instructor_export(problem: Problem) -> None:
    with st.expander("For instructors: per-student variants"):
        if not is_instructor():
            _course_keys(problem)
        if not instructor_key_entry(f"{problem.id}__instructor_key"):
            return
        st.markdown(f"Hand out `?seed=N` links (N from 0 to {MAX_SEED:,}); each gives its own numbers, the "
                    "same in every session, and opens in Practice. Export the parameters and answers (SI units, "
                    "radians) to check students' work. Put no names or student ids in links: they end up in "
                    "access logs.")
        c1, c2 = st.columns(2)
        first = c1.number_input("First seed", 0, MAX_SEED, 1, key=f"{problem.id}__seed_first")
        last = c2.number_input("Last seed", 0, MAX_SEED, 30, key=f"{problem.id}__seed_last")
        if st.button("Prepare the CSV", key=f"{problem.id}__prepare"):
            try:
                st.session_state[f"{problem.id}__csv"] = variants_csv(problem.solver, problem.id, int(first), int(last))
            except ValueError as error:
                st.error(plain(str(error)))
        data = st.session_state.get(f"{problem.id}__csv")
        if data:
            st.download_button("Download variants (CSV)", data, file_name=f"{problem.id}-variants.csv",
                               mime="text/csv", key=f"{problem.id}__download")
