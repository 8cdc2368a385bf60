"""The server's edge as a hostile client meets it, on one live server (serve.py on loopback):
forged widget values get a plain message and one log line per kind, never a traceback; a flood
of reruns from one session reaches the page's script at a person's pace; every answer carries the
headers a course site expects, and Streamlit's metrics are not public."""
from __future__ import annotations

import asyncio
import re
import time
import urllib.error
import urllib.request

import pytest
import websockets
from streamlit.proto.BackMsg_pb2 import BackMsg
from streamlit.proto.ForwardMsg_pb2 import ForwardMsg
from streamlit.proto.WidgetStates_pb2 import WidgetState

from bench.lecture_load import CONTROLS, cpu_seconds, run_script, widget_id, widget_state
from edge.fair_share import BURST, RATE
from solvers import registry


@pytest.fixture(scope="module")
def server(shipped_server):
    """(base URL, the server's log file, its pid): the session's server as shipped (each test reads
    only what the log gained while it ran)."""
    return shipped_server


def stream(url: str) -> str:
    return url.replace("http://", "ws://") + "/_stcore/stream"


def elements(messages: list[ForwardMsg], kind: str) -> list:
    return [getattr(m.delta.new_element, kind) for m in messages
            if m.HasField("delta") and m.delta.HasField("new_element") and m.delta.new_element.WhichOneof("type") == kind]


def forged(wid: str, how: str) -> WidgetState:
    state = WidgetState(id=wid)
    if how == "text":
        state.string_value = "1; DROP TABLE attempt"
    elif how == "list":
        state.int_array_value.data.extend([1, 2, 3])
    elif how == "nan":
        state.double_value = float("nan")
        state.double_array_value.data.append(float("nan"))  # (a oneof: the last one set is sent)
    elif how == "true":
        state.bool_value = True
    return state


FORGERIES = ["text", "list", "nan", "true"]


@pytest.mark.parametrize("page", registry.PROBLEM_IDS)
def test_forged_widget_values_get_a_message_and_one_log_line_per_kind(server, page):
    url, log, _ = server

    async def visit() -> dict[str, list[ForwardMsg]]:
        seen = {}
        async with websockets.connect(stream(url), subprotocols=["streamlit"], max_size=None) as ws:
            _, _, first = await run_script(ws, page, [])
            wid, _, _ = widget_id(first, CONTROLS[page][0])
            for how in FORGERIES:
                for _ in range(3):  # the same forgery, rerun after rerun
                    _, _, seen[how] = await run_script(ws, page, [forged(wid, how)])
        return seen

    before = log.read_text()
    seen = asyncio.run(visit())
    for how, messages in seen.items():
        assert not elements(messages, "exception"), (page, how)
        assert elements(messages, "markdown") or elements(messages, "alert"), (page, how)  # the page is drawn
    told = [a.body for m in seen.values() for a in elements(m, "alert") if "could not be read" in a.body]
    assert told, "the page says a value was not read"
    new = log.read_text()[len(before):]
    assert "Traceback" not in new
    lines = [line for line in new.splitlines() if "widget value that cannot be read" in line]
    kinds = [line.split("(", 1)[1] for line in lines]
    assert lines and len(kinds) == len(set(kinds)), "once per session and kind, not once per rerun"
    assert len(lines) <= len(FORGERIES)


def test_a_flood_reaches_the_script_at_a_persons_pace(server):
    url, log, pid = server
    page, rate, seconds = "disk_wall", 200, 3.0

    async def flood_and_count() -> tuple[int, float]:
        """Send ``rate`` reruns a second for ``seconds``; count the runs the server began and ended
        (finished, or stopped early for the next rerun) while it went on, and a second after."""
        # It also names another address for itself: the server must not take it (DL_TRUSTED_PROXIES unset).
        async with websockets.connect(stream(url), subprotocols=["streamlit"], max_size=None,
                                      additional_headers={"X-Forwarded-For": "203.0.113.77"}) as ws:
            _, _, first = await run_script(ws, page, [])
            wid, kind, _ = widget_id(first, CONTROLS[page][0])
            runs = 0

            async def count():
                nonlocal runs
                while True:
                    forward = ForwardMsg()
                    forward.ParseFromString(await ws.recv())
                    runs += forward.HasField("script_finished")

            counter = asyncio.create_task(count())
            started = time.monotonic()
            for n in range(int(rate * seconds)):
                msg = BackMsg()
                msg.rerun_script.page_name = page
                msg.rerun_script.widget_states.widgets.append(widget_state(wid, kind, 1.0 + 0.001 * n))
                await ws.send(msg.SerializeToString())
                await asyncio.sleep(1 / rate)
            elapsed = time.monotonic() - started
            await asyncio.sleep(1.0)
            counter.cancel()
            return runs, elapsed + 1.0

    cpu_before = cpu_seconds([pid])
    runs, elapsed = asyncio.run(flood_and_count())
    cpu = cpu_seconds([pid]) - cpu_before
    assert 1 <= runs <= BURST + RATE * elapsed + 2, runs
    # Without the budget the server's interpreter was busy with this one session the whole time
    # (about a core's worth of CPU); with it, about RATE runs a second of some 20 ms each.
    assert cpu < 0.5 * elapsed, f"{cpu:.2f} s of CPU in {elapsed:.1f} s"
    slowed = [line for line in log.read_text().splitlines() if "sends more than" in line]
    assert slowed and all("from 127.0.0.1 " in line for line in slowed), slowed  # not 203.0.113.77


def get(url: str) -> tuple[int, dict[str, str]]:
    try:
        with urllib.request.urlopen(url, timeout=10) as answer:
            return answer.status, {k.lower(): v for k, v in answer.headers.items()}
    except urllib.error.HTTPError as refused:
        return refused.code, {k.lower(): v for k, v in refused.headers.items()}


@pytest.mark.parametrize("path", ["/", "/disk_wall", "/_stcore/health", "/favicon.png"])
def test_every_answer_carries_the_security_headers(server, path):
    status, headers = get(server[0] + path)
    assert status == 200
    csp = headers["content-security-policy"]
    assert "frame-ancestors 'self'" in csp and "script-src 'self'" in csp and "object-src 'none'" in csp
    assert "http:" not in csp.replace("'self'", "") and "*" not in csp  # no other origin's script
    assert headers["x-content-type-options"] == "nosniff"
    assert headers["referrer-policy"] == "same-origin"


@pytest.mark.parametrize("path", ["/", "/disk_wall", "/handouts"])
def test_a_page_names_the_modules_it_needs_at_once_and_each_is_there(server, path):
    """st.html's element (the app's stylesheets) is Streamlit's code loaded on first use: a page's answer
    names it and its imports for preloading (edge/early_modules.py), each a module the server has, none that
    index.html preloads already; what is not a page names none."""
    status, headers = get(server[0] + path)
    assert status == 200
    linked = re.findall(r"<\./([^>]+)>; rel=modulepreload; crossorigin", headers["link"])
    assert any(re.fullmatch(r"static/js/Html\.[\w-]+\.js", p) for p in linked) and len(linked) >= 2, headers["link"]
    index = urllib.request.urlopen(server[0] + "/", timeout=10).read().decode()
    for module in linked:
        status, headers_of = get(f"{server[0]}/{module}")
        assert status == 200 and "javascript" in headers_of["content-type"], module
        assert f'href="./{module}"' not in index, module
    assert "link" not in get(server[0] + "/favicon.png")[1]


def test_metrics_are_not_public(server):
    status, headers = get(server[0] + "/_stcore/metrics")
    assert status == 404 and "content-security-policy" in headers
