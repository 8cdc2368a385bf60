"""Widget values from the browser that cannot be read: refused, said once, logged once.

A browser sends each widget's value as one of the protobuf's typed fields. Streamlit trusts the
field: a string sent for a slider, or a list of three numbers for one, made its deserializer raise
before the page's script began, so the student saw Streamlit's generic error and the log got a full
traceback on every rerun (issue 25: about 143 KB a second from one session). ``install()`` puts a
check in front of that deserializer: a value sent in a field of another kind than the widget's
(text for a number, a list for a box), one the deserializer refuses, or a number that is not finite, is treated as not sent (Streamlit then keeps
the widget's last value, as for a widget it has no state for), the page says so in plain words
(``take_refusals`` for app.py), and the log says it once per session and kind.
"""
from __future__ import annotations

import logging
import math
import threading

log = logging.getLogger("dynamics_lab.widgets")
_lock = threading.Lock()
_refused: dict[str, set[str]] = {}   # session id -> kinds refused since the page last said so
_logged: set[tuple[str, str]] = set()  # (session id, kind) already in the log
MAX_SESSIONS = 10_000  # bounds both: a session's entries go when its page has said so


def _session_id() -> str:
    from streamlit.runtime.scriptrunner import get_script_run_ctx

    ctx = get_script_run_ctx(suppress_warning=True)
    return ctx.session_id if ctx else "?"


# Fields a browser may rightly send for a widget whose metadata names another of the same kind: a
# number box sends int_value for whole numbers and double_value otherwise (Streamlit's metadata
# follows whichever came last).
SAME_KIND = [{"double_value", "int_value"}]


def _compatible(sent: str | None, expected: str) -> bool:
    return sent == expected or any(sent in kind and expected in kind for kind in SAME_KIND)


def _not_finite(value) -> bool:
    values = value if isinstance(value, (list, tuple)) else [value]
    return any(isinstance(v, float) and not math.isfinite(v) for v in values)


def refuse(kind: str) -> None:
    session = _session_id()
    with _lock:
        if len(_refused) < MAX_SESSIONS:
            _refused.setdefault(session, set()).add(kind)
        first = (session, kind) not in _logged
        if first:
            if len(_logged) > MAX_SESSIONS:
                _logged.clear()
            _logged.add((session, kind))
    if first:
        log.warning("session %s sent a widget value that cannot be read (%s): ignored (said once per session and kind)",
                    session[:8], kind)


def take_refusals() -> set[str]:
    """What this session's browser sent that was refused since the last call (then forgotten)."""
    with _lock:
        return _refused.pop(_session_id(), set())


def install() -> None:
    """Check every serialized widget value before Streamlit deserializes it (idempotent)."""
    from streamlit.runtime.state import session_state

    states = session_state.WStates
    if getattr(states.__getitem__, "dl_checked", False):
        return
    original = states.__getitem__  # fails loudly if a Streamlit upgrade renames it

    def checked_getitem(self, k):
        wstate = self.states.get(k)
        metadata = self.widget_metadata.get(k)
        if not isinstance(wstate, session_state.Serialized) or metadata is None:
            return original(self, k)
        sent = wstate.value.WhichOneof("value")
        if sent is None:  # no field: Streamlit's way of saying a widget was cleared
            return original(self, k)
        if metadata.value_type and not _compatible(sent, metadata.value_type):
            refuse(f"{sent or 'nothing'} where {metadata.value_type} belongs")
            raise KeyError(k)  # as for a widget with no state: Streamlit keeps its last value
        try:
            value = original(self, k)
        except Exception as error:  # noqa: BLE001 - whatever the deserializer refuses
            refuse(f"{sent} refused: {type(error).__name__}")
            raise KeyError(k) from None
        if _not_finite(value):
            self.states[k] = wstate  # (the deserializer kept its result: put the sent value back)
            refuse(f"{sent} not finite")
            raise KeyError(k)
        return value

    checked_getitem.dl_checked = True
    states.__getitem__ = checked_getitem
