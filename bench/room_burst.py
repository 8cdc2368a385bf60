"""Benchmark 6, Ask the room: a lecture hall's phones answer the instructor's question within 30 s.

    python bench/room_burst.py [--sessions 200] [--join 20] [--window 30] [--tail 5] [--one-address]
                               [--no-polling] [--restart-at SECONDS] [--processes 1|2]
                               [--database sqlite|postgres] [--json OUT]

Speaks Streamlit's websocket protocol, as bench/lecture_load.py does. The room's server (serve.py, as
shipped, with an instructor key and a course secret, DL_COURSE_SECRET, as a course runs it) and the empty
one-slider page (bench/serve_empty.py) on servers of their own beside it, at the same time. Once the
servers are healthy, the benchmark asks a question in the room's database itself (room.store.ask:
disk_wall's v1x at the textbook's numbers, as "Ask the room" does). Each phone connects from its own
loopback address (127.0.0.2 …, as in §4; ``--one-address``: the whole hall from 127.0.0.1, one NAT) at a
random moment of the join window and opens /room?c=CODE (the first run joins and draws the question and
the answer box: first load); then, at a random moment of the answer window that follows, it types an
answer and presses "Send my answer". The answer box is a fragment (ui/room.py ``_answer_box``), so the
send is what Streamlit's frontend sends for a widget inside a fragment: a rerun with the text input's and
the form button's widget states and the fragment's id (``rerun_script.fragment_id``, the ``fragment_id``
of the box's delta in the first run; not an auto-rerun). The answer's time runs from the send to the end
of that fragment's run, which must say "Your answer is in" (a confirmation that does not come is a lost
confirmation). The texts: right ones (0.8333, 0.8333 m/s, the expression), slips and wrong ones (1.25,
0.5, 2) and unreadable ones (abc, 1.2 kg: said so, and never counted).

Every phone also does what the page's watch (ui/plotly_component/watch.js, a components-v2 element drawing
nothing) makes a browser do, from its first load to the end: ``GET <base>/room-status?c=CODE&t=TOKEN`` (the
URL from the element's data in the run, with the phone's cookies, over HTTP keep-alive; one httpx client per
source address, its connections bound to that address as the websocket is, so the route's budget per address
sees what a hall's phones would be; with ``--one-address`` one shared client), the first after ``every`` ×
U(0.5, 1.5) s, then every ``every`` × U(0.8, 1.2) s (``every`` = ui/room.py PHONE_EVERY, 3 s; after a 429, 2
×; after a failed request, 2 ×). When the answer's ``v`` differs from the ``seen`` of the data, or on 403/404,
the watch asks for ONE full run of the page (the element's trigger, a ``json_trigger_value``) and stops until
a run draws it with new data. The requests' latencies and status codes are counted (``--no-polling``: none). A
ForwardMsg ``auto_rerun`` (a polling fragment) is counted too: the phone's page has none now. Like the
browser's ``document.cookie`` in watch.js, each drawing of the element keeps the ``cookie`` of its data
(``dl_room=<token>``, ui/room.py ME_COOKIE) as the phone's cookie, which every later websocket handshake (a
reconnect) and status request sends (``Cookie: dl_room=…``, with nginx's dl_route).

Meanwhile a projector reads ``room.store.counts(code)`` from the database every 0.25 s in this process
(as the instructor's page reads it, but not through a Streamlit run, and in a thread of this busy
process: a read's time includes waits for this process's interpreter): the histogram's lag of an answer is
the time from its run's end at the phone to the end of the first read, begun after it, that counts at
least as many answers as the phones had been told were in. The instructor's page adds its own polling
(every 1.5 s, and its fragment's run under the same load). At the end: every answer the phones were told is
in is in the database exactly once, by the category the judge gives its text, and no unreadable one;
errors (exceptions, error alerts, lost connections, time-outs, lost confirmations) and the server logs'
tracebacks. Then ``--tail`` seconds of status polls alone (no one answers), for their own CPU cost.

``--restart-at S``: S seconds after the start, the room's server is stopped (SIGTERM; SIGKILL after 15 s) and
started again on the same port with the same database (it warms before it listens). A phone whose websocket
dropped reconnects (after 0.5–1 s, then backing off to every 5 s, for 180 s at most, roughly as a browser's
Streamlit does), runs the page again with the widget states it had (its typed text once sent) and, if its
answer had not been confirmed, sends it again (at once, or at its moment if that is still to come). The new
server has no sessions: a phone whose answer was in comes back as a new session, so the report says how many
reopened pages said "Your answer is in" (all should: the reconnect's handshake carries the phone's dl_room
cookie, so the page is the same responder; a page that sets another token is an error) and how many sends were
cut by the restart (their answer may be in the database without the phone knowing: the re-send from the new
session, the same responder, changes it rather than adding one, which the database check at the end sees).
Drops and refused connections while the server is down are counted, not errors. With ``--processes 2``, the
first replica is the one restarted.

``--processes 2``: two room processes behind Debian's nginx with deploy/nginx.conf.template (as
bench/lecture_load.py's ``start_servers``: DL_TRUSTED_PROXIES=*, sticky per browser by its dl_route cookie,
which a phone keeps from its websocket's answer and sends with its status requests and reconnects, as a
browser does), the empty page likewise on two processes behind its own nginx. Both room processes share
one PostgreSQL database (``--database postgres``, the default with more than one process: a throw-away
cluster from tests/databases.py, migrated here before the servers start); the projector reads it too, so
its count includes every process's answers.

The empty page: the same sessions (same addresses, same moments) open it and move its slider once in
the answer window. Reports first-load and answer (slider change) p50/p95/p99, the ratio of the p95s,
server CPU seconds per second of the burst (room and empty, and the status polls alone in the tail), with
what the rest of the machine used meanwhile (it is shared) and the load generator's event-loop lag. The
servers' logs of the last run are kept in $TMPDIR/room_burst-{room,empty}-server.log (a restart's
processes one after the other). Loopback only, bounded in time (every wait 60 s at most, a reconnect 180 s).
"""
from __future__ import annotations

import argparse
import asyncio
import collections
import contextlib
import itertools
import json
import os
import random
import re
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import httpx
import websockets
from streamlit.proto.Alert_pb2 import Alert
from streamlit.proto.BackMsg_pb2 import BackMsg
from streamlit.proto.ForwardMsg_pb2 import ForwardMsg
from streamlit.proto.WidgetStates_pb2 import WidgetState

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
sys.path.insert(0, str(ROOT))
import lecture_load  # noqa: E402
from lecture_load import cpu_seconds, percentile, rss_mb, source_address, widget_id, widget_state  # noqa: E402
from scripts.live_app import free_port, start_app, wait_healthy  # noqa: E402

PAGE, EMPTY = "room", ""
PROBLEM, QUESTION = "disk_wall", "answer:v1x"
RIGHT = ["0.8333", "0.8333 m/s", "(R*omega + 2*V*sin(theta))/3"]
WRONG = ["1.25", "0.5", "2"]  # 0.5 is a named slip (the spin term's sign), the others "other"
UNREADABLE = ["abc", "1.2 kg"]
TEXTS = RIGHT + WRONG + UNREADABLE  # session i types TEXTS[i % 8]: a quarter of the hall unreadable
TIMEOUT = 60.0  # seconds any one answer from the server is waited for
RECONNECT_FOR = 180.0  # seconds a phone keeps trying to reconnect (a restarted server warms before it listens)
POLL_EVERY = 0.25  # s: the benchmark's projector reads the counts this often
WATCH = "dynamics_lab_watch"  # ui/figure.py WATCH: the phone's watch element
INSTRUCTOR_KEY = "bench-room-burst-key"
COURSE_SECRET = "bench-room-burst-course-secret-0123456789"  # the same in every server and here
LOGS = Path(tempfile.gettempdir())  # the servers' logs of the last run: $TMP/room_burst-*-server.log


@dataclass
class Outage:
    """The restart's moments (perf_counter): SIGTERM sent, the process gone, the new one healthy."""
    began: float | None = None
    down: float | None = None
    up: float | None = None
    warm_cpu: float = 0.0  # the new process's CPU seconds until healthy (its warm-up)

    def during(self, when: float, after: float = 5.0) -> bool:
        """``when`` falls in the outage (or the ``after`` seconds of reconnects that follow it)."""
        return self.began is not None and self.began <= when <= (self.up or float("inf")) + after


@dataclass
class Stats:
    first_load: list[float] = field(default_factory=list)
    reloads: list[float] = field(default_factory=list)  # a reconnected page's full run
    reconnects: list[float] = field(default_factory=list)  # from the drop to the reconnected page's run end
    answers: list[tuple[str, str, float, float]] = field(default_factory=list)  # (text, verdict, seconds, when)
    late: list[float] = field(default_factory=list)  # a verdict's end past the phone's planned moment (s)
    runs: collections.Counter = field(default_factory=collections.Counter)  # full / fragment / early / trigger
    status: list[tuple[float, float, str]] = field(default_factory=list)  # status requests: (sent, seconds, code)
    fires: collections.Counter = field(default_factory=collections.Counter)  # the watch's triggers, by cause
    errors: list[str] = field(default_factory=list)
    expected: collections.Counter = field(default_factory=collections.Counter)  # drops, refusals of a restart
    interrupted: int = 0  # sends whose connection dropped before their run's end
    remembered: int = 0  # confirmed phones whose reconnected page said "Your answer is in"
    forgotten: int = 0  # ... and those whose page did not
    cut_found: int = 0  # phones whose send was cut and whose reconnected page said "Your answer is in"
    kept: int = 0  # reconnect handshakes that carried the phone's dl_room cookie
    new_token: int = 0  # ... after which the page's watch set another token (the cookie not used)
    auto_reruns: int = 0  # ForwardMsg.auto_rerun seen (a polling fragment)
    counted_by: collections.Counter = field(default_factory=collections.Counter)  # confirmed answers per replica
    elsewhere: int = 0  # status requests nginx sent to another replica than the phone's websocket
    settled: int = 0  # sessions that have answered, or failed before they could


class Client:
    """One browser session on one websocket: a reader files each script run's messages."""

    def __init__(self, ws, page: str, query: str, stats: Stats):
        self.ws, self.page, self.query, self.stats = ws, page, query, stats
        self.committed: list[WidgetState] = []  # what the browser resends with every rerun (no clicks)
        self.current: list[ForwardMsg] = []
        self.finished: list[tuple[bool, int, float, list[ForwardMsg]]] = []  # (fragment?, status, when, messages)
        self.changed = asyncio.Event()
        self.ended = asyncio.Event()  # the connection is gone
        self.closed: str | None = None
        self.closing = False  # closed by this side (the end of the run)
        self.reader = asyncio.create_task(self._read())

    async def _read(self) -> None:
        try:
            async for data in self.ws:
                forward = ForwardMsg()
                forward.ParseFromString(data)
                kind = forward.WhichOneof("type")
                if kind == "new_session":
                    self.current = [forward]
                elif kind == "auto_rerun":
                    self.stats.auto_reruns += 1
                elif kind == "script_finished":
                    now = time.perf_counter()
                    status = forward.script_finished
                    fragment = bool(forward.metadata.run.fragment_ids) or \
                        status == ForwardMsg.FINISHED_FRAGMENT_RUN_SUCCESSFULLY
                    self.current.append(forward)
                    self.finished.append((fragment, status, now, self.current))
                    self.current = []
                    if status == ForwardMsg.FINISHED_EARLY_FOR_RERUN:
                        self.stats.runs["early"] += 1
                    else:
                        self.stats.runs["fragment" if fragment else "full"] += 1
                    if any(exception(m) for m in self.finished[-1][3]):
                        self.stats.errors.append(f"exception element in a {'fragment' if fragment else 'full'} run")
                    self.changed.set()
                else:
                    self.current.append(forward)
            self.closed = "connection closed by the server"
        except websockets.ConnectionClosed as error:
            self.closed = f"connection closed: {error}"[:200]
        except Exception as error:  # noqa: BLE001 - a broken reader is counted, not fatal
            self.closed = f"reader: {type(error).__name__}: {error}"[:200]
        finally:
            self.closed = self.closed or "connection closed"
            self.ended.set()
            self.changed.set()

    async def send(self, widgets: list[WidgetState], fragment: str = "") -> None:
        msg = BackMsg()
        msg.rerun_script.page_name = self.page
        msg.rerun_script.query_string = self.query
        msg.rerun_script.widget_states.widgets.extend(widgets)
        if fragment:  # a widget drawn in a fragment: the browser reruns that fragment alone
            msg.rerun_script.fragment_id = fragment
        await self.ws.send(msg.SerializeToString())

    async def run(self, widgets: list[WidgetState], fragment: str = "") -> tuple[float, float, list[ForwardMsg]]:
        """Send a rerun (of ``fragment`` alone, if given) and wait for the first run to end after it that
        was not stopped early (a full run too, for a fragment's: a full run asked for meanwhile takes the
        click): (seconds, when it ended, its messages). ConnectionError if the connection drops first."""
        seen = first = len(self.finished)
        started = time.perf_counter()
        try:
            await self.send(widgets, fragment)
        except websockets.ConnectionClosed as error:
            raise ConnectionError(f"connection closed: {error}"[:200]) from None
        deadline = started + TIMEOUT
        while True:
            for was_fragment, status, when, messages in self.finished[seen:]:
                if status != ForwardMsg.FINISHED_EARLY_FOR_RERUN and (fragment or not was_fragment):
                    return when - started, when, messages
            seen = len(self.finished)
            if self.closed:
                raise ConnectionError(self.closed)
            self.changed.clear()
            remaining = deadline - time.perf_counter()
            if remaining <= 0:
                raise TimeoutError(f"no end of the run in {TIMEOUT:g} s; since the send: {self.story(first, started)}")
            with contextlib.suppress(asyncio.TimeoutError):
                await asyncio.wait_for(self.changed.wait(), remaining)

    def story(self, first: int, started: float) -> str:
        """The runs that ended since ``first`` (for a report of a run that did not end)."""
        names = {ForwardMsg.FINISHED_SUCCESSFULLY: "full", ForwardMsg.FINISHED_FRAGMENT_RUN_SUCCESSFULLY: "fragment",
                 ForwardMsg.FINISHED_EARLY_FOR_RERUN: "stopped early", ForwardMsg.FINISHED_WITH_COMPILE_ERROR: "compile error"}
        runs = [f"{'fragment ' if fragment else ''}{names.get(status, status)} at +{when - started:.1f} s"
                for fragment, status, when, _ in self.finished[first:]]
        pending = collections.Counter(m.WhichOneof("type") for m in self.current)
        told = [verdict(messages) for *_, messages in self.finished[first:]] + [verdict(self.current)]
        return (f"{runs[:6]}{' …' if len(runs) > 6 else ''}, {len(runs)} in all; unfinished: {dict(pending)}; "
                f"verdicts seen: {[t for t in told if t != 'none']}")

    async def close(self) -> None:
        self.closing = True
        with contextlib.suppress(Exception):
            await asyncio.wait_for(self.ws.close(), 5)
        self.reader.cancel()


def cookie_header(jar: dict[str, str]) -> str:
    """A phone's cookies as its browser sends them: ``Cookie: dl_room=…; dl_route=…`` ("" when none)."""
    return "; ".join(f"{name}={value}" for name, value in jar.items())


class Watch:
    """A phone's watch.js: one per phone, for the whole run (its timer outlives a dropped websocket, as the
    page in the browser does). ``render`` is the element drawn with data it did not have; every drawing sets
    the phone's dl_room cookie (``document.cookie``) in ``jar``, the phone's cookies (its dl_route too)."""

    def __init__(self, base: str, http: httpx.AsyncClient | None, stats: Stats, done: asyncio.Event,
                 jar: dict[str, str]):
        self.base, self.http, self.stats, self.done, self.jar = base, http, stats, done, jar
        self.data: dict | None = None
        self.trigger = ""  # the element's trigger widget id
        self.client: Client | None = None
        self.replica = ""
        self.rendered = asyncio.Event()
        self.task = asyncio.create_task(self._loop()) if http is not None else None

    def render(self, element, client: Client, replica: str) -> str:
        """Take the drawn element; return the dl_room token its data sets ("" if none)."""
        self.client, self.replica = client, replica
        if element is None:
            return ""
        raw = element.bytes or element.json.encode()
        data = json.loads(raw)
        name, _, value = str(data.get("cookie") or "").split(";", 1)[0].strip().partition("=")
        if name and value:  # watch.js: document.cookie = data.cookie (a first-party cookie, path=/, 12 h)
            self.jar[name] = value
        if data != self.data:
            from streamlit.components.v2.bidi_component.main import _make_trigger_id
            self.data, self.trigger = data, _make_trigger_id(element.id, "events")
            self.rendered.set()
        return value if name == "dl_room" else ""

    async def _loop(self) -> None:
        rng = random.Random()
        while not self.done.is_set():
            await self.rendered.wait()
            self.rendered.clear()
            data = self.data
            every = float(data.get("every", 3.0))
            delay = every * (0.5 + rng.random())  # spread a hall's phones over the period
            while not self.done.is_set():
                await asyncio.sleep(delay)
                if self.rendered.is_set():  # drawn anew meanwhile: that drawing's timer takes over
                    break
                code, said = await self._ask(data["url"])
                fire = code in ("403", "404") or (code == "200" and said != data.get("seen"))
                if fire:
                    await self._fire(code if code != "200" else "changed")
                    break  # stopped until a run draws it with new data
                delay = every * (2 if code in ("429",) or not code.isdigit() else 0.8 + 0.4 * rng.random())

    async def _ask(self, url: str) -> tuple[str, str | None]:
        sent = time.perf_counter()
        said = None
        try:
            cookie = cookie_header(self.jar)  # credentials: "same-origin": the browser sends its cookies
            answer = await self.http.get(self.base + url, headers={"Cookie": cookie} if cookie else None)
            code = str(answer.status_code)
            if self.replica and answer.headers.get("x-replica", self.replica) != self.replica:
                self.stats.elsewhere += 1
            if answer.status_code == 200:
                said = answer.json().get("v")
            self.http.cookies.clear()  # a cookie is this phone's: none kept in the shared client's jar
        except httpx.HTTPError as error:
            code = type(error).__name__
        except Exception as error:  # noqa: BLE001 - a broken answer is counted, not fatal
            code = f"bad answer: {type(error).__name__}"
        self.stats.status.append((sent, time.perf_counter() - sent, code))
        return code, said

    async def _fire(self, why: str) -> None:
        """One run of the whole page (the element's trigger), as ``setTriggerValue("changed", true)``."""
        self.stats.fires[why] += 1
        client = self.client
        if client is None or client.closed:
            return  # the page's reconnect runs it anyway
        trigger = WidgetState(id=self.trigger)
        trigger.json_trigger_value = json.dumps([{"event": "changed", "value": True}])
        self.stats.runs["trigger"] += 1
        with contextlib.suppress(Exception):
            await client.send([*client.committed, trigger])

    def stop(self) -> None:
        if self.task is not None:
            self.task.cancel()


def family(pid: int) -> list[int]:
    """A server's process and its descendants (the practice judge's worker, the figure worker)."""
    found, todo = [], [pid]
    while todo:
        current = todo.pop()
        found.append(current)
        for task in Path(f"/proc/{current}/task").glob("*/children"):
            try:
                todo += [int(c) for c in task.read_text().split()]
            except OSError:
                pass
    return found


def machine_busy() -> float:
    """CPU seconds all cores have been busy (not idle, not waiting on I/O) since boot."""
    fields = [int(v) for v in Path("/proc/stat").read_text().split("\n", 1)[0].split()[1:]]
    return (sum(fields[:8]) - fields[3] - fields[4]) / os.sysconf("SC_CLK_TCK")


def own_cpu() -> float:
    times = os.times()
    return times.user + times.system


class Servers:
    """One page's servers: ``processes`` of them (bench/serve_empty.py or serve.py), behind nginx when more
    than one (as bench/lecture_load.py's start_servers); each with its own log file (live_app.start_app)."""

    def __init__(self, label: str, processes: int, env: dict, entry: list[str] | None = None):
        self.label, self.env, self.entry = label, dict(env), entry
        if processes > 1:  # behind nginx, as Compose runs it: the client is the one nginx's X-Forwarded-For names
            self.env["DL_TRUSTED_PROXIES"] = "*"
        self.ports = [free_port() for _ in range(processes)]
        self.procs = [start_app(port, env=self.env, entry=entry) for port in self.ports]
        self.every_proc = list(self.procs)  # a restart's processes too: their logs are read at the end
        self.retired_cpu = 0.0  # CPU seconds of processes stopped by a restart
        self.nginx: subprocess.Popen | None = None
        self.workdir: Path | None = None
        self.listen: int | None = None

    def ready(self) -> None:
        for port, proc in zip(self.ports, self.procs):
            wait_healthy(f"http://127.0.0.1:{port}", timeout=180, proc=proc)
        if len(self.procs) > 1:
            from scripts.balancer_check import start_nginx

            self.workdir = Path(tempfile.mkdtemp(prefix="dl-bench-nginx-"))
            self.listen = free_port()
            self.nginx = start_nginx(self.ports, self.listen, self.workdir)

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.listen or self.ports[0]}"

    def pids(self) -> list[int]:
        return [p for proc in self.procs for p in family(proc.pid)]

    def cpu(self) -> float:
        return cpu_seconds(self.pids()) + self.retired_cpu

    def nginx_cpu(self) -> float:
        return cpu_seconds(family(self.nginx.pid)) if self.nginx else 0.0

    def restart(self, outage: Outage, n: int = 0) -> None:
        """Stop process ``n`` (SIGTERM, SIGKILL after 15 s) and start it again on its port (blocking)."""
        old = self.procs[n]
        members = family(old.pid)
        self.retired_cpu += cpu_seconds(members)  # (its last moments' CPU are not seen)
        outage.began = time.perf_counter()
        old.send_signal(signal.SIGTERM)
        try:
            old.wait(15)
        except subprocess.TimeoutExpired:
            old.kill()
            old.wait(10)
        for pid in members[1:]:  # a worker the server started and left behind
            with contextlib.suppress(OSError):
                os.kill(pid, signal.SIGKILL)
        outage.down = time.perf_counter()
        new = start_app(self.ports[n], env=self.env, entry=self.entry)
        self.procs[n] = new
        self.every_proc.append(new)
        wait_healthy(f"http://127.0.0.1:{self.ports[n]}", timeout=180, proc=new)
        outage.up = time.perf_counter()
        outage.warm_cpu = cpu_seconds(family(new.pid))

    def stop(self) -> list[str]:
        """Stop everything; keep the logs (one after the other) in $TMP/room_burst-<label>-server.log and
        return their problem lines."""
        if self.nginx:
            self.nginx.terminate()
            with contextlib.suppress(subprocess.TimeoutExpired):
                self.nginx.wait(10)
        for proc in self.procs:
            if proc.poll() is None:
                proc.terminate()
        for proc in self.procs:
            try:
                proc.wait(15)
            except subprocess.TimeoutExpired:
                proc.kill()
        kept = LOGS / f"room_burst-{self.label}-server.log"
        with open(kept, "w") as out:
            for n, proc in enumerate(self.every_proc):
                out.write(f"===== process {n} (pid {proc.pid}) =====\n")
                with contextlib.suppress(OSError):
                    out.write(Path(proc.log).read_text(errors="replace"))
                Path(proc.log).unlink(missing_ok=True)
        if self.workdir:
            shutil.rmtree(self.workdir, ignore_errors=True)
        return log_problems(kept)


def elements(messages):
    for m in messages:
        if m.HasField("delta") and m.delta.HasField("new_element"):
            yield m.delta.new_element


def exception(message: ForwardMsg) -> bool:
    return (message.HasField("delta") and message.delta.HasField("new_element")
            and message.delta.new_element.WhichOneof("type") == "exception")


def page_parts(messages) -> tuple[str, str, str, object]:
    """The answer box's widget id, the "Send my answer" button's, the fragment they are drawn in (the
    delta's fragment_id, which the browser's rerun of a widget in a fragment carries) and the watch
    element (None if not drawn)."""
    box = button = fragment = ""
    watch = None
    for m in messages:
        if not (m.HasField("delta") and m.delta.HasField("new_element")):
            continue
        e = m.delta.new_element
        kind = e.WhichOneof("type")
        if kind == "text_input" and re.search(r"room__typed_\d+$", e.text_input.id):
            box, fragment = e.text_input.id, m.delta.fragment_id
        elif kind == "button" and re.search(r"room__send_\d+$", e.button.id):
            button = e.button.id
        elif kind == "bidi_component" and e.bidi_component.component_name.endswith(WATCH):
            watch = e.bidi_component
    if not (box and button):
        raise LookupError(f"no answer box on the page (verdict: {verdict(messages)})")
    return box, button, fragment, watch


def verdict(messages) -> str:
    """What the phone was told of its answer: counted / changed / same / unreadable / refused / closed /
    error: … / exception / none."""
    for e in elements(messages):
        kind = e.WhichOneof("type")
        if kind == "exception":
            return "exception"
        if kind != "alert":
            continue
        body = e.alert.body
        if e.alert.format == Alert.SUCCESS:
            for start, said in (("Your answer is in", "counted"), ("Your answer is changed", "changed"),
                                ("That is your answer already", "same")):
                if body.startswith(start):
                    return said
        elif e.alert.format == Alert.WARNING:
            for part, said in (("Nothing was counted", "unreadable"), ("Sent a moment ago", "refused"),
                               ("answers are closed", "closed")):
                if part in body:
                    return said
        elif e.alert.format == Alert.ERROR:
            return f"error: {body[:120]}"
    return "none"


async def connect(url: str, source: str, jar: dict[str, str]) -> tuple[object, str]:
    """A websocket from ``source`` with the browser's cookies in its handshake (``jar``: the room's dl_room once
    the watch has set it, nginx's dl_route behind nginx; websockets >= 14's ``additional_headers``); keeps
    the dl_route nginx sets in ``jar``: (it, the replica nginx chose: its X-Replica header, "" without nginx)."""
    cookie = cookie_header(jar)
    ws = await websockets.connect(url, subprotocols=["streamlit"], max_size=None, open_timeout=TIMEOUT,
                                  ping_interval=None, local_addr=(source, 0),
                                  additional_headers={"Cookie": cookie} if cookie else None)
    for said in ws.response.headers.get_all("Set-Cookie"):
        if said.startswith("dl_route="):
            jar["dl_route"] = said.split(";", 1)[0].partition("=")[2]
    return ws, ws.response.headers.get("X-Replica", "")


async def connect_retrying(url: str, source: str, jar: dict[str, str], stats: Stats, outage: Outage, who: str):
    """``connect``, again and again (0.5 s, backing off to 5 s) for RECONNECT_FOR s, as the browser does."""
    began, wait = time.perf_counter(), 0.5
    while True:
        try:
            return await connect(url, source, jar)
        except (OSError, websockets.InvalidHandshake, asyncio.TimeoutError) as error:
            now = time.perf_counter()
            said = f"connect failed: {type(error).__name__}: {error}"[:160]
            if outage.during(now):
                stats.expected["connect refused during the restart"] += 1
            else:
                stats.errors.append(f"{who}: {said}")
            if now - began > RECONNECT_FOR:
                raise ConnectionError(f"no connection in {RECONNECT_FOR:g} s: {said}") from None
            await asyncio.sleep(wait * random.uniform(0.8, 1.2))
            wait = min(5.0, wait * 1.5)


async def until(moment: float, event: asyncio.Event) -> None:
    """Sleep until ``moment`` (perf_counter) or until ``event`` is set, whichever first."""
    with contextlib.suppress(asyncio.TimeoutError):
        await asyncio.wait_for(event.wait(), max(0.0, moment - time.perf_counter()))


async def student(base: str, code: str, i: int, join_at: float, answer_at: float, start: float, stats: Stats,
                  done: asyncio.Event, http: httpx.AsyncClient | None, outage: Outage) -> None:
    await asyncio.sleep(max(0.0, start + join_at - time.perf_counter()))
    ws_url = base.replace("http://", "ws://") + "/_stcore/stream"
    text, who = TEXTS[i % len(TEXTS)], f"session {i}"
    expected = "unreadable" if text in UNREADABLE else "counted"
    source = source_address(i)
    jar: dict[str, str] = {}  # the phone's cookies: dl_room (the watch sets it), dl_route (nginx's)
    watch = Watch(base, http, stats, done, jar)
    client: Client | None = None
    told, dropped_at, settled, cut = None, None, False, False
    try:
        while not done.is_set():
            token = jar.get("dl_room", "")  # the handshake carries it: the page is this phone again
            ws, replica = await connect_retrying(ws_url, source, jar, stats, outage, who)
            stats.kept += bool(token and dropped_at is not None)
            client = Client(ws, PAGE, f"c={code}", stats)
            try:
                seconds, when, messages = await client.run(list(client.committed))
                box, button, fragment, element = page_parts(messages)
                if dropped_at is None:
                    stats.first_load.append(seconds)
                else:
                    stats.reloads.append(seconds)
                    stats.reconnects.append(when - dropped_at)
                drawn = watch.render(element, client, replica)
                if token and drawn and drawn != token:
                    stats.new_token += 1
                    stats.errors.append(f"{who}: the page set a new dl_room token despite the cookie it was sent")
                if not fragment:
                    stats.errors.append(f"{who}: the answer box is not in a fragment")
                if told == "counted":  # the page this new session draws: does it know the answer is in?
                    if verdict(messages) == "counted":
                        stats.remembered += 1
                    else:
                        stats.forgotten += 1
                elif told is None and cut and verdict(messages) == "counted":
                    stats.cut_found += 1  # the cut send had landed: the re-send below is told "in" again, once
                if told is None:
                    await until(start + answer_at, client.ended)
                    if client.closed:
                        raise ConnectionError(client.closed)
                    typed, pressed = WidgetState(id=box), WidgetState(id=button)
                    typed.string_value = text
                    pressed.trigger_value = True
                    client.committed = [typed]  # the box's value stays in every later rerun; the click does not
                    try:
                        seconds, when, messages = await client.run([typed, pressed], fragment)
                    except ConnectionError:
                        stats.interrupted, cut = stats.interrupted + 1, True
                        raise
                    told = verdict(messages)
                    stats.answers.append((text, told, seconds, when))
                    stats.late.append(when - (start + answer_at))
                    stats.settled, settled = stats.settled + 1, True
                    if told == "counted":
                        stats.counted_by[replica or "the one process"] += 1
                    if told != expected:
                        stats.errors.append(f"{who}: {text!r} was told {told!r}, not {expected!r}"
                                            + (" (a lost confirmation)" if told == "none" else ""))
                await wait_done(client, done)  # the page stays open (and polls) until the hall is done
            except ConnectionError as error:
                reason = str(error)
            else:
                reason = client.closed or ""
            if client.closed and not done.is_set():
                dropped_at = time.perf_counter()
                if outage.during(dropped_at):
                    stats.expected["websocket dropped by the restart"] += 1
                else:
                    stats.errors.append(f"{who}: {reason or client.closed}")
                await client.close()
                client = None
                await asyncio.sleep(random.uniform(0.5, 1.0))  # the browser's first reconnect attempt
                continue
            break
    except Exception as error:  # noqa: BLE001 - every failure is counted, none is fatal
        stats.errors.append(f"{who}: {type(error).__name__}: {error}"[:700])
    finally:
        if not settled:
            stats.settled += 1
        watch.stop()
        if client is not None:
            await client.close()


async def wait_done(client: Client, done: asyncio.Event) -> None:
    """Until the hall is done or the connection is gone."""
    waits = [asyncio.ensure_future(done.wait()), asyncio.ensure_future(client.ended.wait())]
    try:
        await asyncio.wait(waits, return_when=asyncio.FIRST_COMPLETED)
    finally:
        for w in waits:
            w.cancel()


async def empty_session(base: str, i: int, join_at: float, answer_at: float, start: float, stats: Stats,
                        done: asyncio.Event) -> None:
    await asyncio.sleep(max(0.0, start + join_at - time.perf_counter()))
    client, answered = None, False
    try:
        ws, _ = await connect(base.replace("http://", "ws://") + "/_stcore/stream", source_address(i), {})
        client = Client(ws, EMPTY, "", stats)
        seconds, _, messages = await client.run([])
        stats.first_load.append(seconds)
        found = widget_id(messages, "x")
        if found is None:
            raise LookupError("no slider on the empty page")
        wid, kind, _ = found
        await asyncio.sleep(max(0.0, start + answer_at - time.perf_counter()))
        state = widget_state(wid, kind, round(0.5 + 0.001 * (i % 400 + 1), 6))
        seconds, when, _ = await client.run([state])
        stats.answers.append(("slider", "moved", seconds, when))
        stats.settled, answered = stats.settled + 1, True
        await wait_done(client, done)
        if client.closed and not client.closing:
            stats.errors.append(client.closed)
    except Exception as error:  # noqa: BLE001
        stats.errors.append(f"{type(error).__name__}: {error}"[:200])
        stats.settled += not answered
    finally:
        if client is not None:
            await client.close()


async def projector(code: str, stop: asyncio.Event) -> list[tuple[float, float, int]]:
    """The counts read from the database every POLL_EVERY s: (read began, read ended, answers counted)."""
    from room import store

    reads = []
    while not stop.is_set():
        began = time.perf_counter()
        try:
            counts = await asyncio.to_thread(store.counts, code)
            reads.append((began, time.perf_counter(), sum(counts.get(1, {}).values())))
        except Exception as error:  # noqa: BLE001 - a failed read is a gap in the projector's view
            reads.append((began, time.perf_counter(), -1))
            print(f"  projector read failed: {error}", file=sys.stderr)
        await asyncio.sleep(max(0.0, began + POLL_EVERY - time.perf_counter()))
    return reads


async def loop_lag(stop: asyncio.Event) -> list[float]:
    """How late this process's event loop wakes from a 0.1 s sleep (its own load delays every time taken)."""
    lags = []
    while not stop.is_set():
        began = time.perf_counter()
        await asyncio.sleep(0.1)
        lags.append(time.perf_counter() - began - 0.1)
    return lags


def database_pids() -> list[int]:
    """The PostgreSQL cluster's processes (tests/databases.py: its data directory beside the socket), if any."""
    url = os.environ.get("DL_DATABASE_URL", "")
    found = re.search(r"host=([^&]+)", url)
    if not found:
        return []
    try:
        pid = int((Path(found.group(1)) / "data" / "postmaster.pid").read_text().split()[0])
    except (OSError, ValueError, IndexError):
        return []
    return family(pid)


def http_clients(sessions: int, polling: bool) -> dict[str, httpx.AsyncClient]:
    """One client per source address, its connections bound to it (a phone's own keep-alive connection)."""
    if not polling:
        return {}
    addresses = sorted({source_address(i) for i in range(sessions)})
    per = max(1, -(-sessions // len(addresses)))
    return {a: httpx.AsyncClient(transport=httpx.AsyncHTTPTransport(
        local_address=a, limits=httpx.Limits(max_connections=None, max_keepalive_connections=per)),
        timeout=TIMEOUT) for a in addresses}


async def scenario(room: Servers, empty: Servers, code: str, args) -> dict:
    rng = random.Random(2026)
    moments = [(rng.uniform(0, args.join), args.join + rng.uniform(0, args.window)) for _ in range(args.sessions)]
    phones, baseline_stats, outage = Stats(), Stats(), Outage()
    room_done, empty_done, stop = asyncio.Event(), asyncio.Event(), asyncio.Event()
    clients = http_clients(args.sessions, not args.no_polling)
    database_cpu = lambda: cpu_seconds(database_pids())  # noqa: E731
    cpu_before = (room.cpu(), empty.cpu(), room.nginx_cpu() + empty.nginx_cpu(), database_cpu())
    machine_before, own_before = machine_busy(), own_cpu()
    rss_before = rss_mb(room.pids())
    start = time.perf_counter()
    reads_task = asyncio.create_task(projector(code, stop))
    lag_task = asyncio.create_task(loop_lag(stop))
    students = [asyncio.create_task(student(room.base, code, i, j, a, start, phones, room_done,
                                            clients.get(source_address(i)), outage))
                for i, (j, a) in enumerate(moments)]
    baseline = [asyncio.create_task(empty_session(empty.base, i, j, a, start, baseline_stats, empty_done))
                for i, (j, a) in enumerate(moments)]
    restart = None
    if args.restart_at is not None:
        async def restart_at() -> None:
            await asyncio.sleep(max(0.0, start + args.restart_at - time.perf_counter()))
            print(f"  restarting the room's server at +{time.perf_counter() - start:.1f} s", file=sys.stderr)
            await asyncio.to_thread(room.restart, outage)
            print(f"  restarted: down at +{outage.down - start:.1f} s, healthy at +{outage.up - start:.1f} s",
                  file=sys.stderr)
        restart = asyncio.create_task(restart_at())
    bound = args.join + args.window + RECONNECT_FOR + 2 * TIMEOUT

    async def settled(stats: Stats) -> None:  # every session answered (or failed)
        while stats.settled < args.sessions and time.perf_counter() - start < bound:
            await asyncio.sleep(0.2)

    await asyncio.gather(settled(phones), settled(baseline_stats))
    if restart is not None:
        await restart  # (a restart later than every answer still happens: the burst ends after it)
    answered = time.perf_counter() - start
    cpu_burst = (room.cpu() - cpu_before[0], empty.cpu() - cpu_before[1],
                 room.nginx_cpu() + empty.nginx_cpu() - cpu_before[2])
    machine = {"seconds": answered, "busy": machine_busy() - machine_before, "room server": cpu_burst[0],
               "empty server": cpu_burst[1], "nginx": cpu_burst[2], "postgres": database_cpu() - cpu_before[3],
               "load generator": own_cpu() - own_before}
    machine["others"] = machine["busy"] - sum(machine[k] for k in ("room server", "empty server", "nginx",
                                                                    "postgres", "load generator"))
    status_burst = len(phones.status)
    rss_burst = rss_mb(room.pids()) - rss_before
    empty_done.set()
    # The polls alone: the hall has answered and waits for the instructor, every phone still polling.
    tail_began, tail_cpu, tail_status = time.perf_counter(), room.cpu(), len(phones.status)
    tail_own = own_cpu()
    await asyncio.sleep(args.tail)
    tail = {"seconds": time.perf_counter() - tail_began, "cpu": room.cpu() - tail_cpu,
            "requests": phones.status[tail_status:], "load generator": own_cpu() - tail_own}
    await asyncio.sleep(1.0)  # the projector's last reads
    stop.set()
    room_done.set()
    await asyncio.wait_for(asyncio.gather(*students, *baseline), TIMEOUT)
    for http in clients.values():
        await http.aclose()
    reads, lags = await reads_task, await lag_task
    return {"room": phones, "empty": baseline_stats, "reads": reads, "answered after": answered,
            "cpu burst": cpu_burst, "rss burst": rss_burst, "status burst": phones.status[:status_burst],
            "tail": tail, "start": start, "machine": machine, "outage": outage, "loop lag": lags}


def histogram_lags(answers, reads) -> tuple[list[float], int]:
    """For the k-th answer the phones were told is in (in the order they were told): from that moment to
    the end of the first read begun after it that counts at least k. (lags, answers never seen)."""
    told = sorted(when for _, said, _, when in answers if said in ("counted",))
    lags, unseen = [], 0
    for k, when in enumerate(told, 1):
        seen = next((end for began, end, total in reads if began >= when and total >= k), None)
        if seen is None:
            unseen += 1
        else:
            lags.append(seen - when)
    return lags, unseen


def expected_counts(answers) -> collections.Counter:
    """The categories the judge gives the texts the phones were told are in (the same judge, here)."""
    from room import questions
    from solvers import registry

    params = dict(registry.solver(PROBLEM).solve().params)
    expected = collections.Counter()
    for text, said, _, _ in answers:
        if said == "counted":
            expected[questions.respond(PROBLEM, params, "si", QUESTION, text).category] += 1
    return expected


def log_problems(path: Path) -> list[str]:
    """The server log's tracebacks and error lines (and the fair share's slowed/dropped sessions)."""
    try:
        lines = path.read_text(errors="replace").splitlines()
    except OSError:
        return []
    keep = []
    for n, line in enumerate(lines):
        if ("Traceback" in line or " ERROR " in line or "Error:" in line or "dropped" in line
                or "database unavailable" in line or "Exception" in line or "slowed" in line):
            keep.append(f"{n + 1}: {line[:240]}")
    return keep


def ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f}"


def row(label: str, s: Stats, cpu: float, seconds: float) -> dict:
    times = [t for _, _, t, _ in s.answers]
    return {"page": label, "sessions": len(s.first_load), "first p50": percentile(s.first_load, 50),
            "first p95": percentile(s.first_load, 95), "first p99": percentile(s.first_load, 99),
            "answer p50": percentile(times, 50), "answer p95": percentile(times, 95),
            "answer p99": percentile(times, 99), "answer max": max(times) if times else float("nan"),
            "answers": len(times), "errors": len(s.errors), "cpu s": cpu, "cpu per s": cpu / max(seconds, 1e-9),
            "runs by kind": dict(s.runs)}


def status_summary(requests: list[tuple[float, float, str]], seconds: float) -> dict:
    times = [t for _, t, _ in requests]
    return {"requests": len(requests), "per s": len(requests) / max(seconds, 1e-9),
            "p50": percentile(times, 50), "p95": percentile(times, 95), "p99": percentile(times, 99),
            "max": max(times, default=float("nan")), "codes": dict(collections.Counter(c for *_, c in requests))}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sessions", type=int, default=200)
    parser.add_argument("--join", type=float, default=20.0, help="seconds over which the hall opens the page")
    parser.add_argument("--window", type=float, default=30.0, help="seconds, after the join, in which all answer")
    parser.add_argument("--tail", type=float, default=5.0, help="seconds of status polls alone after the last answer")
    parser.add_argument("--one-address", action="store_true", help="every session from 127.0.0.1 (one NAT)")
    parser.add_argument("--no-polling", action="store_true", help="the phones' status polls not emulated")
    parser.add_argument("--restart-at", type=float, metavar="SECONDS",
                        help="stop the room's server this long after the start and start it again")
    parser.add_argument("--processes", type=int, default=1, help="room (and empty) processes; > 1: behind nginx")
    parser.add_argument("--database", choices=("sqlite", "postgres"),
                        help="the room's database (default: sqlite for one process, postgres for more)")
    parser.add_argument("--json", type=Path, help="also write the results here")
    args = parser.parse_args()
    lecture_load.ONE_ADDRESS["on"] = args.one_address
    args.database = args.database or ("postgres" if args.processes > 1 else "sqlite")

    with contextlib.ExitStack() as stack:
        if args.database == "postgres":
            from tests.databases import postgres_cluster, postgres_missing

            if postgres_missing():
                sys.exit(f"no PostgreSQL: {postgres_missing()}")
            url = stack.enter_context(postgres_cluster())
        else:
            url = None
        run(args, url)


def run(args, database_url: str | None) -> None:
    data = Path(tempfile.mkdtemp(prefix="dl-room-bench-"))
    if database_url:
        os.environ["DL_DATABASE_URL"] = database_url  # every room process and the projector: one database
    else:
        os.environ.pop("DL_DATABASE_URL", None)  # the SQLite file in the data directory, as shipped
    os.environ["DL_DATA_DIR"] = str(data)  # before assignments.db makes its engine: the server's database
    os.environ["DL_INSTRUCTOR_KEY"] = INSTRUCTOR_KEY
    os.environ["DL_COURSE_SECRET"] = COURSE_SECRET  # the status token: the same in every process and here
    env = {"DL_DATA_DIR": str(data), "DL_INSTRUCTOR_KEY": INSTRUCTOR_KEY, "DL_COURSE_SECRET": COURSE_SECRET,
           "STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE": "true", "STREAMLIT_SERVER_COOKIE_SECRET": "bench"}
    if database_url:
        env["DL_DATABASE_URL"] = database_url
        from assignments import migrate

        migrate.upgrade()  # once, here, before two processes would race to create the schema
    began = time.perf_counter()
    servers = [Servers("room", args.processes, env),
               Servers("empty", args.processes, env, entry=[str(ROOT / "bench" / "serve_empty.py")])]
    logs: dict[str, list[str]] = {}
    try:
        for s in servers:
            s.ready()
        room_servers, empty_servers = servers
        print(f"  servers ready in {time.perf_counter() - began:.0f} s (data in {data}; "
              f"{args.database}{', behind nginx' if args.processes > 1 else ''})", file=sys.stderr)
        from assignments import db
        from room import store
        from solvers import registry

        asked = store.ask(PROBLEM, QUESTION, dict(registry.solver(PROBLEM).solve().params), "si", True)
        out = asyncio.run(scenario(room_servers, empty_servers, asked.code, args))
        final = store.counts(asked.code).get(1, collections.Counter())
        timed, ticks = time.perf_counter(), itertools.count(0.0, 10.0)  # a clock that never finds it fresh
        for _ in range(200):
            store.status_version(asked.code, clock=lambda: next(ticks))
        status_read_ms = (time.perf_counter() - timed) / 200 * 1000
        described = db.described()
    finally:
        for s in servers:
            logs[s.label] = s.stop()
        shutil.rmtree(data, ignore_errors=True)
    took = time.perf_counter() - began
    report(args, asked.code, out, final, logs, took, status_read_ms, described)


def report(args, code: str, out: dict, final, logs: dict, took: float, status_read_ms: float,
           described: str) -> None:
    room, empty = out["room"], out["empty"]
    cpu_room, cpu_empty, cpu_nginx = out["cpu burst"]
    seconds = out["answered after"]
    outage: Outage = out["outage"]
    rows = [row("empty page (slider)", empty, cpu_empty, seconds), row("room (answer)", room, cpu_room, seconds)]
    rows[0]["p95 x empty"], rows[1]["p95 x empty"] = 1.0, rows[1]["answer p95"] / rows[0]["answer p95"]
    lags, unseen = histogram_lags(room.answers, out["reads"])
    read_times = [end - began for began, end, total in out["reads"] if total >= 0]
    told = collections.Counter(said for _, said, _, _ in room.answers)
    expected = expected_counts(room.answers)
    recorded_ok = dict(final) == dict(expected)
    extra = collections.Counter(final) - expected
    missing = expected - collections.Counter(final)
    lost = sum(1 for text, said, _, _ in room.answers if text not in UNREADABLE and said != "counted")
    burst = status_summary(out["status burst"], seconds)
    tail = out["tail"]
    tail_status = status_summary(tail["requests"], tail["seconds"])
    lag = out["loop lag"]

    addresses = "one address (127.0.0.1)" if args.one_address else \
        f"{min(args.sessions, len(lecture_load.SOURCE_ADDRESSES))} loopback addresses"
    print(f"\n{args.sessions} phones open /room?c={code} over {args.join:g} s, then answer within "
          f"{args.window:g} s, {args.processes} process(es){' behind nginx' if args.processes > 1 else ''}, "
          f"{described}, from {addresses}; status polls "
          f"{'NOT emulated' if args.no_polling else 'every 3 s × U(0.8, 1.2) a phone'}"
          + (f"; the room's server restarted at +{args.restart_at:g} s" if args.restart_at is not None else "")
          + f"; the empty page side by side. Last answer {seconds:.1f} s after the start; run took {took:.0f} s.\n")
    print("| page | first load p50 / p95 / p99 | answer p50 / p95 / p99 / max | p95 × empty | errors | script runs "
          "| server CPU in the burst | CPU per s |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        kinds = r["runs by kind"]
        runs = " / ".join(f"{k} {v}" for k, v in sorted(kinds.items()))
        print(f"| {r['page']} | {ms(r['first p50'])} / {ms(r['first p95'])} / {ms(r['first p99'])} ms | "
              f"{ms(r['answer p50'])} / {ms(r['answer p95'])} / {ms(r['answer p99'])} / {ms(r['answer max'])} ms | "
              f"{r['p95 x empty']:.1f} | {r['errors']} ({r['answers']} answered) | {runs} | {r['cpu s']:.1f} s | "
              f"{r['cpu per s']:.2f} |")
    print(f"\nstatus route (the phones' watch) during the burst: {burst['requests']} requests, "
          f"{burst['per s']:.1f}/s, p50 {ms(burst['p50'])} / p95 {ms(burst['p95'])} / p99 {ms(burst['p99'])} / "
          f"max {ms(burst['max'])} ms, codes {burst['codes']}; the watch's triggers {dict(room.fires)}; "
          f"auto_rerun messages seen: {room.auto_reruns}")
    print(f"status polls alone for {tail['seconds']:.1f} s after the last answer: {tail_status['requests']} requests "
          f"({tail_status['per s']:.1f}/s), p95 {ms(tail_status['p95'])} ms, codes {tail_status['codes']}; room server "
          f"{tail['cpu']:.2f} s CPU ({tail['cpu'] / tail['seconds']:.3f} s CPU a second, "
          f"{tail['cpu'] / max(1, tail_status['requests']) * 1000:.2f} ms a request); this load generator "
          f"{tail['load generator'] / tail['seconds']:.3f} s CPU a second; "
          f"store.status_version's database read here: {status_read_ms:.2f} ms")
    print(f"histogram (the counts read from the database every {POLL_EVERY:g} s): lag p50 {ms(percentile(lags, 50))} ms, "
          f"p95 {ms(percentile(lags, 95))} ms, max {ms(max(lags, default=float('nan')))} ms, never seen {unseen}; "
          f"a read took p95 {ms(percentile(read_times, 95))} ms, max {ms(max(read_times, default=float('nan')))} ms; "
          f"the instructor's page adds up to 1.5 s of its own polling and its fragment's run")
    print(f"phones were told: {dict(told)}; lost confirmations (a readable answer not told 'in'): {lost}; "
          f"confirmed answers by the process that took them: {dict(room.counted_by)}"
          + (f"; status requests nginx sent to another process than the phone's websocket: {room.elsewhere}"
             if args.processes > 1 else ""))
    print(f"database: {sum(final.values())} answers counted {dict(final)}; expected from the phones "
          f"{sum(expected.values())} {dict(expected)}: {'the same' if recorded_ok else 'DIFFERENT'}"
          + (f"; in the database but never confirmed: {dict(extra)}" if extra else "")
          + (f"; confirmed but NOT in the database: {dict(missing)}" if missing else ""))
    if outage.began is not None:
        start = out["start"]
        print(f"restart: SIGTERM at +{outage.began - start:.1f} s, process gone {outage.down - outage.began:.1f} s "
              f"later, healthy again at +{outage.up - start:.1f} s ({outage.up - outage.began:.1f} s without a "
              f"server; the new one's warm-up {outage.warm_cpu:.1f} s CPU, in the room's CPU above: without it "
              f"{cpu_room - outage.warm_cpu:.1f} s, {(cpu_room - outage.warm_cpu) / seconds:.2f} s CPU a second); "
              f"expected: {dict(room.expected)}; sends cut by it {room.interrupted}; reconnected pages "
              f"{len(room.reloads)}: reload p50 {ms(percentile(room.reloads, 50))} / p95 {ms(percentile(room.reloads, 95))} ms, "
              f"drop to page p50 {percentile(room.reconnects, 50):.1f} / p95 {percentile(room.reconnects, 95):.1f} / "
              f"max {max(room.reconnects, default=float('nan')):.1f} s; reconnects with the phone's dl_room cookie "
              f"{room.kept} (a new token set after one: {room.new_token}); confirmed phones whose reopened page said "
              f"'Your answer is in': {room.remembered}, did not: {room.forgotten}; cut sends whose reopened page "
              f"said it: {room.cut_found}; verdicts past their planned "
              f"moment: p95 {percentile(room.late, 95):.1f} s, max {max(room.late, default=float('nan')):.1f} s")
    print(f"server memory growth during the burst: {out['rss burst']:.0f} MB")
    m = out["machine"]
    print(f"the machine ({os.cpu_count()} cores) over the {m['seconds']:.0f} s of the burst: {m['busy']:.0f} CPU s busy "
          f"({m['busy'] / m['seconds']:.2f} cores): room server {m['room server']:.0f}, empty server "
          f"{m['empty server']:.0f}, nginx {m['nginx']:.1f}, postgres {m['postgres']:.1f}, this load generator {m['load generator']:.0f}, other "
          f"processes {m['others']:.0f} ({m['others'] / m['seconds']:.2f} cores); this process's event loop late "
          f"p50 {ms(percentile(lag, 50))} / p95 {ms(percentile(lag, 95))} / max {ms(max(lag, default=float('nan')))} ms")
    for label, stats in (("room", room), ("empty", empty)):
        if stats.errors:
            kinds = collections.Counter(re.sub(r"^session \d+(: )?", "", e)[:160] for e in stats.errors)
            print(f"{label} errors ({len(stats.errors)}, by kind): {kinds.most_common(6)}")
            for e in stats.errors[:3]:
                print(f"    {e}")
    for label, found in logs.items():
        print(f"{label} server log ({LOGS / f'room_burst-{label}-server.log'}): {len(found)} problem lines"
              + "".join(f"\n    {line}" for line in found[:15]))
    if args.json:
        args.json.write_text(json.dumps({
            "args": vars(args) | {"json": str(args.json)}, "code": code, "rows": rows, "took": took,
            "database url": described, "status burst": burst, "status tail": tail_status | {"cpu": tail["cpu"]},
            "fires": dict(room.fires), "auto reruns": room.auto_reruns,
            "histogram lag": {"p50": percentile(lags, 50), "p95": percentile(lags, 95),
                              "max": max(lags, default=None), "unseen": unseen},
            "reads": {"p95": percentile(read_times, 95), "max": max(read_times, default=None)},
            "told": dict(told), "lost confirmations": lost, "counted by": dict(room.counted_by),
            "status elsewhere": room.elsewhere, "database": dict(final), "expected": dict(expected),
            "recorded ok": recorded_ok, "machine": out["machine"], "status read ms": status_read_ms,
            "restart": None if outage.began is None else {
                "down s": outage.up - outage.began, "warm cpu": outage.warm_cpu, "expected": dict(room.expected),
                "interrupted": room.interrupted, "remembered": room.remembered, "forgotten": room.forgotten,
                "cut found": room.cut_found, "cookie reconnects": room.kept, "new token": room.new_token,
                "reconnect p95": percentile(room.reconnects, 95), "late p95": percentile(room.late, 95)},
            "errors": {"room": room.errors, "empty": empty.errors}, "server log": logs,
        }, indent=1, default=str))


if __name__ == "__main__":
    main()
