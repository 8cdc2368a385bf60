"""Who this browser session is, for every page: an instructor (the key typed once, or an
``?instructor=KEY`` link), an LMS instructor of one course (an LTI launch's hand-off), or a student;
and the contract by which an assignment records what the answer box (ui/practice.py) is told. A kit
piece: the features (practice, assignments, handouts, the variants' export) import it, it imports none
of them."""
from __future__ import annotations

import ipaddress
from dataclasses import dataclass
from typing import Callable

import streamlit as st
from sqlalchemy.exc import SQLAlchemyError
from streamlit.runtime.scriptrunner import get_script_run_ctx

from assignments import migrate, records
from lti import launch as lti_launch, store as lti_store
from practice import instructor
from practice.judge import Verdict

INSTRUCTOR = "dl_instructor"  # session flag: the key was entered (once per session, for every page)
KEY_MESSAGE = "dl_instructor_message"  # what the last try of the key was told


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


def _key_typed(key: str) -> None:
    """The key box changed: one try, and the box emptied (a rerun does not try the same text again)."""
    typed = st.session_state.get(key) or ""
    st.session_state[key] = ""
    if typed:
        try_instructor_key(typed)


@st.cache_resource(show_spinner=False)
def schema_ready() -> bool:
    """Bring the schema to head once per process (serve.py does it before listening; this covers
    ``streamlit run app.py``). False when the database cannot be reached: tried again next run."""
    try:
        migrate.upgrade()
    except Exception:  # noqa: BLE001  (reported to the user as "cannot be reached" by the caller)
        schema_ready.clear()
        return False
    return True


LAUNCH_SPENT = ("This launch from your course site has expired or was already used (it works once, for two "
                "minutes). Open the activity again from your course's page in the LMS.")


def lti_arrival() -> dict | None:
    """What an LTI launch handed this session (lti/launch.py): the ``?lti=`` hand-off in the URL is
    redeemed once and taken out of the URL, and the session keeps it (no cookie is needed in the
    LMS's iframe). ``{"refused": …}`` when the hand-off is spent, expired or altered."""
    token = st.query_params.get("lti")
    if token:
        del st.query_params["lti"]
        payload = lti_launch.redeem(token, lti_store.spender()) if schema_ready() else None
        st.session_state["lti__arrival"] = payload or {"refused": LAUNCH_SPENT}
    return st.session_state.get("lti__arrival")


def lms_course() -> dict | None:
    """The LMS course whose instructor (or TA) launched this session (issuer, context), or None. It
    opens that course's assignments, their gradebook and their answer keys without the instructor
    key, and nothing else the key opens (the ``?seed=N`` variants shared by every course, other
    courses' assignments, creating assignments here)."""
    arrival = lti_arrival()
    return arrival if arrival and arrival.get("role") == "instructor" and arrival.get("ctx") else None


def course_assignments(course: dict) -> set[int]:
    """The assignments placed in the LMS course ``course`` (``lms_course()``'s); RecordingUnavailable
    when the database cannot be reached (said on the page, never a traceback)."""
    try:
        return set(lti_store.contexts_assignments(course["iss"], course["ctx"]))
    except (SQLAlchemyError, OSError) as error:
        raise records.RecordingUnavailable("The course's database cannot be reached right now, so its "
                                           "assignments cannot be read. Try again in a few minutes.") from error


@dataclass(frozen=True)
class Recording:
    """An assignment's rules and the calls that record what the student does (made by ui/assignments.py)."""
    tolerance: float
    on_verdict: Callable[[object, str, Verdict], None]  # (answer, typed text, verdict), after it is shown
    on_reveal: Callable[[], bool]  # record "solution shown"; False if it could not be recorded
    revealed: bool = False  # the student has already seen the solution (recorded earlier)
    reveal_blocked: str = ""  # why "Show the solution" is not offered yet ("" when it is)
    say: Callable[[Verdict], str] | None = None  # the verdict's message under the feedback policy
    reveal_costs: str = ""  # what opening the solution costs, asked to confirm first ("": opened at once)
    on_diagram: Callable | None = None  # (drawing, diagram verdict), a readable Check of the free-body diagram
    diagram_right: bool = False  # the free-body diagram was recorded right already (the method's later steps open)
    diagram_feedback: tuple[bool, bool] = (True, True)  # the assignment's hints, and slip names without them
