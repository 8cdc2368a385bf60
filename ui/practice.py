"""“Try it yourself”: the problem with every given, the method's first steps without their results,
a box per answer (a number or an expression in the givens), feedback on the common slips, then the
solution on request. The instructor's side (the variant export, and Study or Lecture for a variant
link) needs the instructor key. Nothing a student types is evaluated or rendered as Markdown."""
from __future__ import annotations

import html
import re

import streamlit as st

from practice.judge import RELATIVE_TOLERANCE, Judge, tolerance_text
from practice.method import exercise_steps
from practice.variants import MAX_SEED
from solvers.core import Derivation, Solution
from solvers.solution import PARTS
from solvers.catalog import Problem
from ui.diagram_exercise import diagram_right, draw_exercise
from ui.exercise import answer_choice, statement
from ui.equations import PHONE_WIDTH_EM, broken
from edge.inline_scripts import TAKE_FOCUS
from ui.results import literal, plain, plain_with_math
from ui.session import Recording

def seed_from_url() -> tuple[int | None, str | None]:
    raw = st.query_params.get("seed")
    if raw is None:
        return None, None
    if re.fullmatch(r"\d{1,10}", raw) and int(raw) <= MAX_SEED:
        return int(raw), None
    return None, f"The link's variant number “{literal(raw[:20])}” is not a whole number from 0 to {MAX_SEED}; " \
                 "showing the textbook's numbers."


def method(steps, derivation: Derivation, parts=(1, 2, 3, 4)) -> str:
    """The method (``exercise_steps``) under the course's four headings: those of ``parts`` (numbered as
    in the whole method), under "The method" when the first part is among them."""
    blocks, last = [], None
    for i, (part, title, tex) in enumerate(exercise_steps(steps, derivation), start=1):
        if part not in parts:
            continue
        if part != last:
            blocks.append(f"#### {PARTS[part]}")
            last = part
        blocks.append(f"**{i}.** {plain_with_math(title)}")
        if tex:  # broken over rows where wide (a display equation that scrolls sideways is a region a keyboard cannot reach)
            blocks.append(f"$$\n{broken(tex, PHONE_WIDTH_EM)}\n$$")
    if 1 not in parts:
        return "\n\n".join(blocks)
    return "\n\n".join(["### The method", ":gray[The steps to take. Equations that lead to a result appear "
                        "with the solution.]", *blocks])


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
        st.markdown(statement(problem, solution.params, answers, system, judge))
        # the course's order: the diagram first, then the balance laws written from it and the analysis (whose
        # steps name its loads: they appear once the diagram is right, or with the solution)
        steps = solution.steps[: solution.symbolic_steps]
        st.markdown(method(steps, judge.derivation, parts=(1, 2)))
        draw_exercise(problem, solution, recording.on_diagram if recording is not None else None,
                      recording.diagram_feedback if recording is not None else (True, True))
        if diagram_right(problem, solution) or (recording is not None and recording.diagram_right):
            st.markdown(method(steps, judge.derivation, parts=(3, 4)))
        else:
            st.markdown(":gray[The balance laws written from the diagram, and the analysis, follow once your "
                        "diagram is right (or with the solution).]")
        st.markdown("### The answers")
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
    right = [a.heading for a in answers if a.name in found]
    left = [a.heading for a in answers if a.name not in found]
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
