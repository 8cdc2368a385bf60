"""Ask the room: the instructor puts a question to the lecture hall from a problem's Lecture view, the
room answers on its phones at /room with a code (no account), the projector counts the answers live,
then the instructor closes the question, reveals the answer and plays the motion; asked again after a
discussion, both votes stand side by side. A feature: the records are room/store.py, what an answer
counts as room/questions.py (the Practice judge), the histogram viz/room.py."""
from __future__ import annotations

import functools
import re
import secrets
import time
import urllib.parse

import orjson
import segno
import streamlit as st

from room import questions, store
from room.store import RecordingUnavailable
from solvers.catalog import BY_ID, Problem
from ui.exercise import read_in, statement
from edge import base_path
from edge.room_status import PATH as STATUS_PATH
from ui import figure
from ui.figure import show as show_figure
from practice.judge import Judge
from ui.results import plain
from ui.session import client, schema_ready
from viz.room import histogram, round_name

PATH = "room"  # the students' page (app.py), and the address the projector gives
CODE_FLAG = "c"  # /room?c=CODE: the QR code's link opens the question at once
PROJECTOR_EVERY = 1.5  # s: the projector's count follows the room at most this far behind
PHONE_EVERY = 3.0  # s: a phone learns the question closed, revealed or asked again (a few bytes a time)
SEND_EVERY = 1.0  # s: a phone's answers are taken at most this often (a flood changes nothing)
MAX_TYPED = 400  # characters of an answer read at most (the judge's own limit is lower, and says so)

STATUS_WORDS = {"open": "Answers are open", "closed": "Answers are closed", "revealed": "The answer is revealed",
                "ended": "This question has ended"}


def _asked_key(problem: Problem) -> str:
    return f"{problem.id}__room_code"


# -- the projector ------------------------------------------------------------------------------------

def projector(problem: Problem, system: str) -> bool:
    """The instructor's side, in a problem's Lecture view: "Ask the room" in the sidebar, and while a
    question is asked the join code, its QR code and the room's answers above the stage. True while the
    motion is to stay hidden (asked so, and not yet revealed): the page then leaves the stage out."""
    _ask_controls(problem, system)
    code = st.session_state.get(_asked_key(problem))
    if not code:
        return False
    schema_ready()  # (serve.py brought the schema up before listening; this covers `streamlit run`)
    try:
        last = store.latest(code)
    except RecordingUnavailable as error:
        st.error(str(error), icon=":material/cloud_off:")
        return False
    if last is None or last.status == "ended":
        st.session_state.pop(_asked_key(problem), None)
        return False
    _live(problem.id, code)
    # Below the projector's fragment, not in it: Streamlit registers a download button's file anew on each run
    # and drops the last, so a press while the fragment ran (every PROJECTOR_EVERY s) fetched nothing. The
    # file is made when pressed.
    st.download_button("The answers as CSV", functools.partial(_csv, code), file_name=f"room-{code}.csv",
                       mime="text/csv", key="room__csv", on_click="ignore", help="For a spreadsheet; no one is named")
    return last.hide_motion and last.status != "revealed"


def _stage_params(problem: Problem) -> dict:
    """The parameters the stage has now (the lesson's last run keeps them in SI), or the problem's own."""
    return st.session_state.get(f"{problem.id}__si") or dict(problem.solver.solve().params)


def _ask_controls(problem: Problem, system: str) -> None:
    params = _stage_params(problem)
    asked = questions.questions(problem.id, params)
    with st.sidebar:
        if st.session_state.get(f"{problem.id}__room_error"):
            st.error(st.session_state.pop(f"{problem.id}__room_error"), icon=":material/error:")
        st.markdown("### Ask the room", help="The room answers on its phones (no account); you close the "
                    "question, reveal the answer, then play the motion. The room sees the parameters the "
                    "stage has now.")
        if not asked:
            st.markdown("Nothing can be asked at these parameters.")
            return
        st.selectbox("Question", asked, format_func=lambda q: q.prompt, key=f"{problem.id}__room_question")
        st.toggle("Hide the motion until the reveal", value=True, key=f"{problem.id}__room_hide")
        st.button("Ask the room", key=f"{problem.id}__room_ask", on_click=_ask, args=(problem, system),
                  icon=":material/how_to_vote:")


def _ask(problem: Problem, system: str) -> None:
    """The button's press: the question and the switch as they are now (read here, not when the button was
    drawn), at the parameters the stage has."""
    params = _stage_params(problem)
    chosen = st.session_state.get(f"{problem.id}__room_question")
    key = chosen.key if isinstance(chosen, questions.Question) else ""
    hide = bool(st.session_state.get(f"{problem.id}__room_hide", True))
    if questions.question(problem.id, params, key) is None:  # (the list was drawn before the stage last changed)
        st.session_state[f"{problem.id}__room_error"] = ("That question cannot be asked at the stage's parameters "
                                                         "now: choose it again from the list.")
        return
    schema_ready()
    try:
        asked = store.ask(problem.id, key, params, system, hide)
    except RecordingUnavailable as error:
        st.session_state[f"{problem.id}__room_error"] = str(error)
        return
    st.session_state[_asked_key(problem)] = asked.code


def join_address(code: str = "") -> tuple[str, str]:
    """(the link the QR code holds, the short address the projector shows): the students' page on the
    server this browser reached, from its own address (st.context.url)."""
    here = urllib.parse.urlsplit(st.context.url or "")
    if here.scheme not in ("http", "https") or not here.netloc:
        return f"/{PATH}" + (f"?{CODE_FLAG}={code}" if code else ""), f"/{PATH}"
    base = here.path.rsplit("/", 1)[0]
    short = f"{here.netloc}{base}/{PATH}"
    return f"{here.scheme}://{short}" + (f"?{CODE_FLAG}={code}" if code else ""), short


def qr_image(link: str) -> str:
    """The link as a QR code (segno, drawn here: no outside service), a Markdown image with its words."""
    uri = segno.make(link, error="m").svg_data_uri(scale=8, border=3, dark="#000", light="#fff")
    return f"![A QR code that opens {plain(link)}]({uri})"


@st.fragment(run_every=PROJECTOR_EVERY)
def _live(problem_id: str, code: str) -> None:
    """The question on the projector, followed every PROJECTOR_EVERY s (reading every process's answers
    from the database): the join code, the count, the histogram, and the instructor's next step."""
    try:
        rounds = store.rounds(code)
        counts = store.counts(code)
    except RecordingUnavailable as error:
        st.error(str(error), icon=":material/cloud_off:")
        return
    last = rounds[-1]
    asked = questions.question(problem_id, last.params, last.question)
    if asked is None:
        st.error("This question cannot be asked at its parameters any more.", icon=":material/error:")
        return
    right = questions.right_category(problem_id, last.params, last.question) if last.status == "revealed" else None
    link, short = join_address(code)
    with st.container(key="dl_room", border=True):
        join, answers = st.columns([2, 3], gap="large")
        with join:
            st.markdown(f"**{plain(asked.prompt)}**" + (f" ({_unit_said(asked.answer, last.system)})" if asked.answer else "")
                        + (f"  \n{round_name(last.round)}" if last.round > 1 else ""))
            st.markdown(f"Answer at **{plain(short)}**")
            st.markdown(f"<p class='dl-room-code' aria-label='code {' '.join(code)}'>{code}</p>", unsafe_allow_html=True)
            if last.status == "open":
                st.markdown(qr_image(link))
        with answers:
            total = sum(counts.get(last.round, {}).values())
            st.markdown(f"**{total} answer{'s' * (total != 1)}** · {STATUS_WORDS[last.status]}")
            _next_steps(last)  # above the histogram: in a projector's first screen
            if right is not None:
                st.success(f"The answer: {plain(questions.right_answer(problem_id, last.params, last.system, last.question))}",
                           icon=":material/check_circle:")
            show_figure(histogram(questions.categories(problem_id, last.params, last.question), counts, right),
                        lecture=True)


def _unit_said(answer, system: str) -> str:
    unit = read_in(answer, system)
    return f"in {unit}" if unit else "a number"


def _next_steps(last: store.Round) -> None:
    """The instructor's buttons in one row: close the answers, reveal, ask again, end."""
    row = st.container(horizontal=True, gap="small")
    if last.status == "open":
        row.button("Close answers", key="room__close", type="primary", on_click=_step,
                   args=(store.set_status, last.id, "closed"))
    elif last.status == "closed":
        # the stage comes back with the reveal: the whole page runs again, not this fragment alone
        if row.button("Reveal", key="room__reveal", type="primary"):
            _step(store.set_status, last.id, "revealed")
            st.rerun()
    if last.status != "open":
        row.button("Ask again", key="room__again", on_click=_step, args=(store.ask_again, last.code),
                   help="The same question, a new vote (after a discussion): both votes are shown side by side.")
    if row.button("End", key="room__end", help="Back to the lesson; the answers stay in the records."):
        _step(store.set_status, last.id, "ended")
        st.rerun()


def _csv(code: str) -> str:
    try:
        return store.responses_csv(code)
    except RecordingUnavailable as error:
        return f"{error}\n"


def _step(do, *args) -> None:
    """One of the instructor's steps on the records (``store.set_status``, ``store.ask_again``); a failure is
    said in a toast, never a traceback."""
    try:
        do(*args)
    except (RecordingUnavailable, LookupError) as error:
        st.toast(str(error) or "That question is gone.")


# -- a student's phone --------------------------------------------------------------------------------

JOINED = "room__joined"  # session: the code this browser session answers
TRIED_LINK = "room__tried_link"  # session: the ?c= code already tried (a rerun does not try it again)
LAST_SEND = "room__last_send"


def student_page() -> None:
    """/room: the code (from the QR code's link, or typed), then the question with its givens, the answer
    box, and what the instructor has done since (followed every PHONE_EVERY s)."""
    schema_ready()
    linked = st.query_params.get(CODE_FLAG, "")[:20]
    if linked and st.session_state.get(TRIED_LINK) != linked:
        st.session_state[TRIED_LINK] = linked
        _join(linked)
    code = st.session_state.get(JOINED)
    if not code:
        _code_box(linked)
        return
    try:
        last = store.latest(code)
    except RecordingUnavailable as error:
        st.error(str(error), icon=":material/cloud_off:")
        return
    if last is None:  # (deleted after its keeping time)
        st.session_state.pop(JOINED, None)
        _code_box("")
        return
    _watch(last)
    _question(last)


ME_COOKIE = "dl_room"  # a random token the browser keeps for the room (watch.js sets it): no name, no fingerprint
ME_HOURS = 12  # a day's lectures: a reload, a reconnect or a restarted server is the same phone


def _me() -> str:
    """This browser, as the room's records know it: the random token its cookie keeps (a reload, a new tab or
    a restarted server is the same phone, so nothing is counted twice), else a new one (the watch sets it)."""
    if "room__me" not in st.session_state:
        kept = st.context.cookies.get(ME_COOKIE)
        st.session_state["room__me"] = (kept if isinstance(kept, str) and re.fullmatch(r"[0-9a-f]{32}", kept)
                                        else secrets.token_hex(16))
    return st.session_state["room__me"]


def _code_box(typed: str) -> None:
    st.markdown("# Your lecture's question")
    if st.session_state.get("room__join_error"):
        st.error(st.session_state["room__join_error"], icon=":material/pin:")
    with st.form("room__join"):
        st.text_input("The code on the screen", value=typed, key="room__code_typed", placeholder="e.g. K7QPX",
                      autocomplete="off")
        if st.form_submit_button("Join", type="primary", key="room__join_button"):
            _join(st.session_state.get("room__code_typed") or "")
            st.rerun()


def _join(typed: str) -> None:
    try:
        found, why = store.join(typed[:20], *client())
    except RecordingUnavailable as error:
        found, why = None, str(error)
    st.session_state.pop("room__join_error", None)
    if found is None:
        st.session_state["room__join_error"] = why
        return
    st.session_state[JOINED] = found.code
    st.query_params[CODE_FLAG] = found.code


def _watch(last: store.Round) -> None:
    """The phone's watch (plotly_component/watch.js): it asks the status route every PHONE_EVERY s and runs
    the page again once the instructor closes, reveals, asks again or ends; nothing drawn."""
    cookie = f"{ME_COOKIE}={_me()}; path={base_path() or '/'}; max-age={ME_HOURS * 3600}; samesite=lax"
    data = orjson.dumps({"url": f"{base_path()}{STATUS_PATH}?{CODE_FLAG}={last.code}&t={store.status_token(last.code)}",
                         "seen": store.version(last), "every": PHONE_EVERY, "cookie": cookie})
    figure.declared(figure.WATCH)(data=data, key="room_watch", on_changed_change=lambda: None)


def _question(last: store.Round) -> None:
    problem = BY_ID[last.problem]
    asked = questions.question(problem.id, last.params, last.question)
    if asked is None:
        st.error("This question cannot be answered any more.", icon=":material/error:")
        return
    solution = questions.solved(problem.id, last.params)  # (None past a physical limit: no names to type)
    judge = Judge(solution, problem.solver.derivation_of(solution), ()) if solution is not None else None
    st.markdown(f"## {plain(problem.title)}\n:gray[Your lecture's question"
                + (f", {round_name(last.round).lower()}" if last.round > 1 else "") + "]"
                + f"\n\n**{plain(asked.prompt)}**")  # what is asked first, then what is given
    st.markdown(statement(problem, last.params, (), last.system, judge, heading="**Given**"))
    who = store.responder(_me())
    if last.status == "open":
        _answer_box(last, asked, who)  # a fragment: a send runs the box alone, not the givens and the sketch
        return
    if st.session_state.get(f"room__send_{last.id}"):  # sent from a page drawn before the close
        st.warning("The answers are closed: this one was not counted.", icon=":material/block:")
    if last.status == "closed":
        st.info("The instructor has closed the answers. The answer comes next.", icon=":material/hourglass_top:")
    elif last.status == "revealed":
        _revealed(last, who)
    else:
        st.info("This question has ended. Thank you!", icon=":material/done_all:")


@st.fragment
def _answer_box(last: store.Round, asked, who: str) -> None:
    try:
        mine = store.answer_of(last.id, who)
    except RecordingUnavailable:
        mine = None
    with st.form(f"room__answer_{last.id}"):
        if asked.answer is None:
            words = [w for w, _ in asked.choices]
            picked = st.radio("Your answer", words, format_func=dict(asked.choices).get,
                              index=words.index(mine) if mine in words else None, key=f"room__pick_{last.id}")
        else:
            picked = st.text_input(f"Your answer ({_unit_said(asked.answer, last.system)}, or an expression)",
                                   key=f"room__typed_{last.id}", placeholder="e.g. 2.5, or 2/3*V")
        sent = st.form_submit_button("Send my answer", type="primary", key=f"room__send_{last.id}")
    if sent:
        _send(last, asked, who, picked)
    elif mine is not None:
        st.success("Your answer is in. You may change it until the instructor closes the answers.",
                   icon=":material/how_to_vote:")


def _send(last: store.Round, asked, who: str, picked) -> None:
    now = time.monotonic()
    if now - st.session_state.get(LAST_SEND, -SEND_EVERY) < SEND_EVERY:
        st.warning("Sent a moment ago: wait a second before sending again.", icon=":material/timer:")
        return
    st.session_state[LAST_SEND] = now
    response = questions.respond(last.problem, last.params, last.system, last.question, str(picked or "")[:MAX_TYPED])
    if response.understood:
        st.markdown("Read as:")
        st.latex(response.understood)
    if not response.counted:
        st.warning(plain(response.message) + " Nothing was counted: correct it and send again.",
                   icon=":material/edit_note:")
        return
    try:
        said = store.answer(last.id, who, response.category)
    except RecordingUnavailable as error:
        st.error(str(error), icon=":material/cloud_off:")
        return
    if said in ("counted", "changed", "same"):
        st.success({"counted": "Your answer is in.", "changed": "Your answer is changed.",
                    "same": "Your answer is in."}[said]  # (counted as the one before: nothing to change)
                   + " You may change it until the instructor closes the answers.", icon=":material/how_to_vote:")
    else:
        st.warning("The answers are closed: this one was not counted.", icon=":material/block:")


def _revealed(last: store.Round, who: str) -> None:
    right = questions.right_answer(last.problem, last.params, last.system, last.question)
    st.success(f"The answer: {plain(right)}", icon=":material/check_circle:")
    try:
        mine = store.answer_of(last.id, who)
    except RecordingUnavailable:
        return
    if mine is None:
        st.markdown("You did not answer this round.")
        return
    if mine == questions.right_category(last.problem, last.params, last.question):
        st.markdown("**You had it right.**")
        return
    hint = questions.feedback(last.problem, last.params, last.question, mine)
    st.markdown("**Yours was not right.**" + (f" {plain(hint)}" if hint else ""))
