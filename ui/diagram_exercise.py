"""“Draw the free-body diagram”, in Practice (and an assignment's problem) before the numeric answers:
the bodies isolated with their named points and basis (viz.diagram.blank: no load of the answer), the
student's drawing in the browser (plotly_component/draw.js) until Check, then the judge's verdict
(practice/diagram_judge.py) in a tutor's words. The diagram itself comes with the solution."""
from __future__ import annotations

import orjson
import streamlit as st

from practice.diagram_judge import DrawnLoad, Unreadable, Verdict, exercise_diagram, judge, read_drawing
from solvers.catalog import Problem
from solvers.core import Solution
from ui.figure import DRAW, declared
from ui.results import plain
from viz.diagram import blank

MAX_SENT = 16_000  # bytes of a drawing read from the page (24 loads with long names fit in 5 KB)


_CANVASES: dict[tuple[str, str], bytes] = {}  # (problem, its numbers) -> the blank as sent


def _canvas(pid: str, signature: str, diagram, solution: Solution) -> bytes:
    kept = _CANVASES.get((pid, signature))
    if kept is None:
        if len(_CANVASES) > 512:
            _CANVASES.clear()
        kept = _CANVASES[(pid, signature)] = orjson.dumps(blank(diagram, diagram.values(solution)))
    return kept


def read_sent(sent, diagram):
    """The drawing the page sent (its JSON text), read; Unreadable with the reason."""
    if not isinstance(sent, str) or len(sent) > MAX_SENT:
        raise Unreadable("The drawing did not arrive whole; draw it again and press Check.")
    try:
        raw = orjson.loads(sent)
    except orjson.JSONDecodeError:
        raise Unreadable("The drawing did not arrive whole; draw it again and press Check.") from None
    return read_drawing(raw, diagram)


def _signature(solution: Solution) -> str:
    return repr(sorted(solution.params.items()))


def diagram_right(problem: Problem, solution: Solution) -> bool:
    """Whether this session's diagram for these numbers was last checked right."""
    signature, _, verdict = st.session_state.get(f"{problem.id}__fbd_kept", (None, None, None))
    return signature == _signature(solution) and verdict is not None and verdict.right


def draw_exercise(problem: Problem, solution: Solution, on_verdict=None, feedback=(True, True)) -> Verdict | None:
    """The exercise, for these numbers; the verdict of the last Check (None before one).
    ``on_verdict(drawing, verdict)``: an assignment records a readable one; ``feedback``: its policy,
    (the tutor's words, the slips' names without them)."""
    signature = _signature(solution)
    key = f"fbd-{problem.id}"  # (a component's key may not hold "__")
    kept = f"{problem.id}__fbd_kept"  # (signature, the drawing as last checked, its verdict)
    fresh = f"{problem.id}__fbd_fresh"  # a Check this run: an assignment records it
    if st.session_state.get(kept, (None,))[0] != signature:
        st.session_state[kept] = (signature, [], None)
    diagram = exercise_diagram(problem.solver, solution)

    def checked():  # (a callback: it runs before the script, so what it says is said below, where Check was)
        sent = (st.session_state.get(key) or {}).get("check")
        try:
            drawing = read_sent(sent, diagram)
        except Unreadable as why:
            st.session_state[kept] = (signature, st.session_state[kept][1], Verdict(False, readable=False, message=str(why)))
            return
        verdict = judge(diagram, diagram.values(solution), drawing, getattr(problem.solver, "DIAGRAM_SLIPS", ()))
        st.session_state[kept] = (signature, [d.__dict__ for d in drawing], verdict)
        st.session_state[fresh] = True

    st.markdown("### Draw the free-body diagram")
    st.markdown(plain(f"Isolate {' and '.join(b.name for b in diagram.bodies)} ({diagram.title.lower()}): put on "
                      "it every force, impulse and couple, each at the point where it acts, then check."))
    canvas = _canvas(problem.id, signature, diagram, solution)
    _, drawn, verdict = st.session_state[kept]
    data = canvas[:-1] + b',"canvas_key":' + orjson.dumps(signature) + b',"drawn":' + orjson.dumps(drawn) + b"}"
    declared(DRAW)(data=data, key=key, on_check_change=checked)
    if verdict is not None:
        show_verdict(verdict, *feedback, counted=on_verdict is not None)
    if st.session_state.pop(fresh, False) and on_verdict is not None and verdict is not None and verdict.readable:
        on_verdict(tuple(DrawnLoad(**d) for d in drawn), verdict)
    return verdict


def show_verdict(verdict: Verdict, hints: bool = True, slip_names: bool = True, counted: bool = False) -> None:
    """The verdict as the feedback policy lets it be said: the tutor's words, or only what kind of thing
    is wrong (the slips' names), or only right or not."""
    if not verdict.readable:
        st.warning(plain(verdict.message) + (" This is not counted as an attempt." if counted else ""),
                   icon=":material/edit_note:")
    elif verdict.right:
        st.success("Right: every load is there, at its point, the way the physics sets it. Now write the balance "
                   "laws from it.", icon=":material/check_circle:")
    else:
        n = len(verdict.findings)
        said = f"Not yet: {n} thing{'s' if n > 1 else ''} to look at."
        if hints:
            said += "\n\n" + "\n".join(f"- {plain(f.message)}" for f in verdict.findings)
        elif slip_names:
            said += " " + plain("; ".join(dict.fromkeys(verdict.keys))) + "."
        st.error(said, icon=":material/cancel:")
