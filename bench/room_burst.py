"""Benchmark 6, Ask the room: a lecture hall's phones answer the instructor's question within 30 s.

    python bench/room_burst.py [--sessions 200] [--join 20] [--window 30] [--tail 5] [--one-address]
                               [--no-polling] [--json OUT]

Speaks Streamlit's websocket protocol, as bench/lecture_load.py does. One server (serve.py, as shipped,
with its own data directory, DL_DATA_DIR, and an instructor key), and the empty one-slider page
(bench/empty_app.py) on its own server beside it, at the same time. Once the server is healthy, the
benchmark asks a question in that server's database itself (room.store.ask: disk_wall's v1x at the
textbook's numbers, as "Ask the room" does). Each session connects from its own loopback address
(127.0.0.2 …, as in §4; ``--one-address``: the whole hall from 127.0.0.1, one NAT) at a random moment of
the join window and opens /room?c=CODE (the first run joins and draws the answer box: first load); then,
at a random moment of the answer window that follows, it types an answer into the box and presses "Send
my answer" (the text input's and the form button's widget states): the answer's time runs from the
submission to the end of that script run (script_finished). The texts: right ones (0.8333, 0.8333 m/s,
the expression), slips and wrong ones (1.25, 0.5, 2) and unreadable ones (abc, 1.2 kg: said so, and never
counted). Every session also does what the page's ``_watch`` fragment makes a browser do: it reruns that
fragment (BackMsg rerun_script with its fragment_id, ``is_auto_rerun``) every 2.5 s, as the ForwardMsg
``auto_rerun`` of each full run asks, with the timers cleared at each full run's start (as Streamlit's
frontend does, App.handleNewSession and handleAutoRerun); those polls run all the time, from each
session's first load to the end, and the poll's time runs from its send to the end of its fragment run
(``--no-polling``: none, to see what the polls cost the answers). An answer whose run's end never comes
(60 s) is an error, reported with the runs that did end after it.

Meanwhile a projector reads ``room.store.counts(code)`` from the database every 0.25 s in this process
(as the instructor's page reads it, but not through a Streamlit run, and in a thread of this busy
process: a read's time includes waits for this process's interpreter): the histogram's lag of an answer is
the time from its script run's end at the phone to the end of the first read, begun after it, that
counts at least as many answers as the phones had been told were in. The instructor's page adds its
own polling on top (every 1.5 s, and its fragment's run under the same load). At the end: every answer
the phones were told is in is in the database exactly once, by the category the judge gives its text,
and no unreadable one; errors (exceptions, error alerts, lost connections, time-outs) and the server
log's tracebacks. Then ``--tail`` seconds of polls alone (no one answers), for the polls' own CPU cost.

The empty page: the same sessions (same addresses, same moments) open it and move its slider once in
the answer window. Reports first-load and answer (slider change) p50/p95/p99, the ratio of the p95s,
and server CPU seconds per script run (first loads, answers and fragment polls together), with what the
rest of the machine used meanwhile (it is shared). The servers' logs of the last run are kept in
$TMPDIR/room_burst-{room,empty}-server.log. Loopback only, bounded in time (every wait 60 s at most).
"""
from __future__ import annotations

import argparse
import asyncio
import collections
import json
import os
import random
import re
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

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
from scripts.live_app import Starting  # noqa: E402

PAGE, EMPTY = "room", ""
PROBLEM, QUESTION = "disk_wall", "answer:v1x"
RIGHT = ["0.8333", "0.8333 m/s", "(R*omega + 2*V*sin(theta))/3"]
WRONG = ["1.25", "0.5", "2"]  # 0.5 is a named slip (the spin term's sign), the others "other"
UNREADABLE = ["abc", "1.2 kg"]
TEXTS = RIGHT + WRONG + UNREADABLE  # session i types TEXTS[i % 8]: a quarter of the hall unreadable
TIMEOUT = 60.0  # seconds any one answer from the server is waited for
POLL_EVERY = 0.25  # s: the benchmark's projector reads the counts this often
INSTRUCTOR_KEY = "bench-room-burst-key"
LOGS = Path(tempfile.gettempdir())  # the servers' logs of the last run: $TMP/room_burst-*-server.log


@dataclass
class Stats:
    first_load: list[float] = field(default_factory=list)
    answers: list[tuple[str, str, float, float]] = field(default_factory=list)  # (text, verdict, seconds, when)
    polls: list[float] = field(default_factory=list)  # fragment reruns: from the first unanswered send to its end
    runs: collections.Counter = field(default_factory=collections.Counter)  # full / fragment / early
    errors: list[str] = field(default_factory=list)
    settled: int = 0  # sessions that have answered, or failed before they could


class Client:
    """One browser session on one websocket: a reader files each script run's messages; the fragment
    timers the server asks for (ForwardMsg.auto_rerun) send fragment reruns as the browser would."""

    def __init__(self, ws, page: str, query: str, stats: Stats, polling: bool):
        self.ws, self.page, self.query, self.stats, self.polling = ws, page, query, stats, polling
        self.committed: list[WidgetState] = []  # what the browser resends with every rerun (no clicks)
        self.current: list[ForwardMsg] = []
        self.finished: list[tuple[bool, int, float, list[ForwardMsg]]] = []  # (fragment?, status, when, messages)
        self.changed = asyncio.Event()
        self.timers: dict[str, asyncio.Task] = {}
        self.intervals: dict[str, float] = {}
        self.fragment_sent: collections.deque[float] = collections.deque()
        self.closed: str | None = None
        self.reader = asyncio.create_task(self._read())

    async def _read(self) -> None:
        try:
            async for data in self.ws:
                forward = ForwardMsg()
                forward.ParseFromString(data)
                kind = forward.WhichOneof("type")
                if kind == "new_session":
                    self.current = [forward]
                    if not forward.metadata.run.fragment_ids:  # a full run: the browser clears its timers,
                        self._stop_timers()  # and a poll sent before it is answered by it
                        self.fragment_sent.clear()
                elif kind == "auto_rerun":
                    self._start_timer(forward.auto_rerun.fragment_id, forward.auto_rerun.interval)
                elif kind == "stop_auto_rerun":
                    for fid in forward.stop_auto_rerun.fragment_ids:
                        if fid in self.timers:
                            self.timers.pop(fid).cancel()
                elif kind == "script_finished":
                    now = time.perf_counter()
                    fragment = bool(forward.metadata.run.fragment_ids) or \
                        forward.script_finished == ForwardMsg.FINISHED_FRAGMENT_RUN_SUCCESSFULLY
                    status = forward.script_finished
                    self.current.append(forward)
                    self.finished.append((fragment, status, now, self.current))
                    self.current = []
                    if status == ForwardMsg.FINISHED_EARLY_FOR_RERUN:
                        self.stats.runs["early"] += 1
                    elif fragment:
                        self.stats.runs["fragment"] += 1
                        if self.fragment_sent:
                            self.stats.polls.append(now - self.fragment_sent[0])
                            self.fragment_sent.clear()
                    else:
                        self.stats.runs["full"] += 1
                    if any(exception(m) for m in self.finished[-1][3]):
                        self.stats.errors.append(f"exception element in a {'fragment' if fragment else 'full'} run")
                    self.changed.set()
                else:
                    self.current.append(forward)
        except websockets.ConnectionClosed as error:
            self.closed = f"connection closed: {error}"[:200]
        except Exception as error:  # noqa: BLE001 - a broken reader is counted, not fatal
            self.closed = f"reader: {type(error).__name__}: {error}"[:200]
        finally:
            self._stop_timers()
            self.changed.set()

    def _start_timer(self, fragment_id: str, interval: float) -> None:
        if not self.polling or not fragment_id:
            return
        if fragment_id in self.timers and self.intervals.get(fragment_id) == interval:
            return  # as the frontend's handleAutoRerun: a timer of the same period runs on
        self.intervals[fragment_id] = interval
        if fragment_id in self.timers:
            self.timers.pop(fragment_id).cancel()
        self.timers[fragment_id] = asyncio.create_task(self._every(fragment_id, interval))

    def _stop_timers(self) -> None:
        for task in self.timers.values():
            task.cancel()
        self.timers.clear()

    async def _every(self, fragment_id: str, interval: float) -> None:
        while True:
            await asyncio.sleep(interval)
            self.fragment_sent.append(time.perf_counter())
            try:
                await self.send(list(self.committed), fragment_id)
            except websockets.ConnectionClosed:
                return

    async def send(self, widgets: list[WidgetState], fragment: str = "") -> None:
        msg = BackMsg()
        msg.rerun_script.page_name = self.page
        msg.rerun_script.query_string = self.query
        msg.rerun_script.widget_states.widgets.extend(widgets)
        if fragment:
            msg.rerun_script.fragment_id = fragment
            msg.rerun_script.is_auto_rerun = True
        await self.ws.send(msg.SerializeToString())

    async def full_run(self, widgets: list[WidgetState]) -> tuple[float, float, list[ForwardMsg]]:
        """Send a full rerun and wait for the next full run to end (fragment runs in between are the
        timers'): (seconds, when it ended, its messages)."""
        seen = first = len(self.finished)
        started = time.perf_counter()
        await self.send(widgets)
        deadline = started + TIMEOUT
        while True:
            for fragment, status, when, messages in self.finished[seen:]:
                if not fragment and status != ForwardMsg.FINISHED_EARLY_FOR_RERUN:
                    return when - started, when, messages
            seen = len(self.finished)
            if self.closed:
                raise ConnectionError(self.closed)
            self.changed.clear()
            remaining = deadline - time.perf_counter()
            if remaining <= 0:
                raise TimeoutError(f"no end of the run in {TIMEOUT:g} s; since the send: {self.story(first, started)}")
            try:
                await asyncio.wait_for(self.changed.wait(), remaining)
            except asyncio.TimeoutError:
                pass

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
        self._stop_timers()
        await self.ws.close()
        self.reader.cancel()


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


def elements(messages):
    for m in messages:
        if m.HasField("delta") and m.delta.HasField("new_element"):
            yield m.delta.new_element


def exception(message: ForwardMsg) -> bool:
    return (message.HasField("delta") and message.delta.HasField("new_element")
            and message.delta.new_element.WhichOneof("type") == "exception")


def answer_ids(messages) -> tuple[str, str]:
    """The widget ids of the answer box and the "Send my answer" button."""
    box = next(e.text_input.id for e in elements(messages) if e.WhichOneof("type") == "text_input"
               and re.search(r"room__typed_\d+$", e.text_input.id))
    button = next(e.button.id for e in elements(messages) if e.WhichOneof("type") == "button"
                  and re.search(r"room__send_\d+$", e.button.id))
    return box, button


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


async def connect(url: str, source: str):
    return await websockets.connect(url, subprotocols=["streamlit"], max_size=None, open_timeout=TIMEOUT,
                                    ping_interval=None, local_addr=(source, 0))


async def student(url: str, code: str, i: int, join_at: float, answer_at: float, start: float, stats: Stats,
                  done: asyncio.Event, polling: bool) -> None:
    await asyncio.sleep(max(0.0, start + join_at - time.perf_counter()))
    text = TEXTS[i % len(TEXTS)]
    client, answered = None, False
    try:
        client = Client(await connect(url, source_address(i)), PAGE, f"c={code}", stats, polling)
        seconds, _, messages = await client.full_run([])
        stats.first_load.append(seconds)
        box, button = answer_ids(messages)
        await asyncio.sleep(max(0.0, start + answer_at - time.perf_counter()))
        typed, pressed = WidgetState(id=box), WidgetState(id=button)
        typed.string_value = text
        pressed.trigger_value = True
        client.committed = [typed]  # the box's value stays in every later rerun; the click does not
        seconds, when, messages = await client.full_run([typed, pressed])
        said = verdict(messages)
        stats.answers.append((text, said, seconds, when))
        stats.settled, answered = stats.settled + 1, True
        expected = "unreadable" if text in UNREADABLE else "counted"
        if said != expected:
            stats.errors.append(f"{text!r} was told {said!r}, not {expected!r}")
        await done.wait()  # the page stays open (and polls) until the hall is done
        if client.closed:
            stats.errors.append(f"session {i}, after its answer: {client.closed}")
    except Exception as error:  # noqa: BLE001 - every failure is counted, none is fatal
        stats.errors.append(f"session {i}: {type(error).__name__}: {error}"[:700])
        stats.settled += not answered
    finally:
        if client is not None:
            try:
                await client.close()
            except Exception:  # noqa: BLE001
                pass


async def empty_session(url: str, i: int, join_at: float, answer_at: float, start: float, stats: Stats,
                        done: asyncio.Event) -> None:
    await asyncio.sleep(max(0.0, start + join_at - time.perf_counter()))
    client, answered = None, False
    try:
        client = Client(await connect(url, source_address(i)), EMPTY, "", stats, polling=False)
        seconds, _, messages = await client.full_run([])
        stats.first_load.append(seconds)
        found = widget_id(messages, "x")
        if found is None:
            raise LookupError("no slider on the empty page")
        wid, kind, _ = found
        await asyncio.sleep(max(0.0, start + answer_at - time.perf_counter()))
        state = widget_state(wid, kind, round(0.5 + 0.001 * (i % 400 + 1), 6))
        seconds, when, _ = await client.full_run([state])
        stats.answers.append(("slider", "moved", seconds, when))
        stats.settled, answered = stats.settled + 1, True
        await done.wait()
    except Exception as error:  # noqa: BLE001
        stats.errors.append(f"{type(error).__name__}: {error}"[:200])
        stats.settled += not answered
    finally:
        if client is not None:
            try:
                await client.close()
            except Exception:  # noqa: BLE001
                pass


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


async def scenario(room_url: str, empty_url: str, code: str, room_pids: list[int], empty_pids: list[int],
                   args) -> dict:
    rng = random.Random(2026)
    moments = [(rng.uniform(0, args.join), args.join + rng.uniform(0, args.window)) for _ in range(args.sessions)]
    room, empty = Stats(), Stats()
    room_done, empty_done, stop = asyncio.Event(), asyncio.Event(), asyncio.Event()
    room_pids, empty_pids = family(room_pids[0]), family(empty_pids[0])
    cpu_before = (cpu_seconds(room_pids), cpu_seconds(empty_pids))
    machine_before, own_before = machine_busy(), own_cpu()
    rss_before = rss_mb(room_pids)
    start = time.perf_counter()
    reads_task = asyncio.create_task(projector(code, stop))
    students = [asyncio.create_task(student(room_url, code, i, j, a, start, room, room_done, not args.no_polling))
                for i, (j, a) in enumerate(moments)]
    baseline = [asyncio.create_task(empty_session(empty_url, i, j, a, start, empty, empty_done))
                for i, (j, a) in enumerate(moments)]
    bound = args.join + args.window + 2 * TIMEOUT

    async def settled(stats: Stats) -> None:  # every session answered (or failed)
        while stats.settled < args.sessions and time.perf_counter() - start < bound:
            await asyncio.sleep(0.2)

    await asyncio.gather(settled(room), settled(empty))
    answered = time.perf_counter() - start
    cpu_burst = (cpu_seconds(room_pids) - cpu_before[0], cpu_seconds(empty_pids) - cpu_before[1])
    machine = {"seconds": answered, "busy": machine_busy() - machine_before, "room server": cpu_burst[0],
               "empty server": cpu_burst[1], "load generator": own_cpu() - own_before}
    machine["others"] = machine["busy"] - machine["room server"] - machine["empty server"] - machine["load generator"]
    runs_burst = (sum(room.runs.values()), sum(empty.runs.values()))
    rss_burst = rss_mb(room_pids) - rss_before
    empty_done.set()
    # The polls alone: the hall has answered and waits for the instructor, every phone still polling.
    tail_runs, tail_cpu = room.runs["fragment"], cpu_seconds(room_pids)
    tail_polls = len(room.polls)
    await asyncio.sleep(args.tail)
    tail_runs, tail_cpu = room.runs["fragment"] - tail_runs, cpu_seconds(room_pids) - tail_cpu
    tail_poll_times = room.polls[tail_polls:]
    await asyncio.sleep(1.0)  # the projector's last reads
    stop.set()
    room_done.set()
    await asyncio.wait_for(asyncio.gather(*students, *baseline), TIMEOUT)
    reads = await reads_task
    return {"room": room, "empty": empty, "reads": reads, "answered after": answered,
            "cpu burst": cpu_burst, "runs burst": runs_burst, "rss burst": rss_burst,
            "tail": (args.tail, tail_runs, tail_cpu, tail_poll_times), "start": start, "machine": machine}


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
                or "database unavailable" in line or "Exception" in line):
            keep.append(f"{n + 1}: {line[:240]}")
    return keep


def ms(seconds: float) -> str:
    return f"{seconds * 1000:.0f}"


def row(label: str, s: Stats, cpu: float, runs: int) -> dict:
    times = [t for _, _, t, _ in s.answers]
    return {"page": label, "sessions": len(s.first_load), "first p50": percentile(s.first_load, 50),
            "first p95": percentile(s.first_load, 95), "answer p50": percentile(times, 50),
            "answer p95": percentile(times, 95), "answer p99": percentile(times, 99),
            "answer max": max(times) if times else float("nan"), "answers": len(times), "errors": len(s.errors),
            "runs": runs, "cpu s": cpu, "cpu per run": cpu / max(1, runs),
            "poll p50": percentile(s.polls, 50), "poll p95": percentile(s.polls, 95),
            "runs by kind": dict(s.runs)}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sessions", type=int, default=200)
    parser.add_argument("--join", type=float, default=20.0, help="seconds over which the hall opens the page")
    parser.add_argument("--window", type=float, default=30.0, help="seconds, after the join, in which all answer")
    parser.add_argument("--tail", type=float, default=5.0, help="seconds of polls alone after the last answer")
    parser.add_argument("--one-address", action="store_true", help="every session from 127.0.0.1 (one NAT)")
    parser.add_argument("--no-polling", action="store_true", help="the phones' fragment polls not emulated")
    parser.add_argument("--json", type=Path, help="also write the results here")
    args = parser.parse_args()
    lecture_load.ONE_ADDRESS["on"] = args.one_address

    data = Path(tempfile.mkdtemp(prefix="dl-room-bench-"))
    os.environ.pop("DL_DATABASE_URL", None)  # the SQLite file in the data directory, as shipped
    os.environ["DL_DATA_DIR"] = str(data)  # before assignments.db makes its engine: the server's database
    os.environ["DL_INSTRUCTOR_KEY"] = INSTRUCTOR_KEY
    env = {"DL_DATA_DIR": str(data), "DL_INSTRUCTOR_KEY": INSTRUCTOR_KEY,
           "STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE": "true", "STREAMLIT_SERVER_COOKIE_SECRET": "bench"}
    began = time.perf_counter()
    servers = [Starting(env=env), Starting(entry=[str(ROOT / "bench" / "serve_empty.py")], env=env)]
    logs: dict[str, list[str]] = {}
    try:
        room_server, empty_server = (s.ready() for s in servers)
        print(f"  servers ready in {time.perf_counter() - began:.0f} s (data in {data})", file=sys.stderr)
        from room import store
        from solvers import registry

        asked = store.ask(PROBLEM, QUESTION, dict(registry.solver(PROBLEM).solve().params), "si", True)
        ws = lambda u: u.replace("http://", "ws://") + "/_stcore/stream"  # noqa: E731
        out = asyncio.run(scenario(ws(room_server.url), ws(empty_server.url), asked.code, [room_server.pid],
                                   [empty_server.pid], args))
        final = store.counts(asked.code).get(1, collections.Counter())
        timed = time.perf_counter()
        for _ in range(200):
            store.latest(asked.code)
        latest_ms = (time.perf_counter() - timed) / 200 * 1000
    finally:
        for label, server in zip(("room", "empty"), servers):
            kept = LOGS / f"room_burst-{label}-server.log"  # the last run's, kept for reading
            try:
                shutil.copyfile(server.proc.log, kept)
                logs[label] = log_problems(kept)
            except OSError:
                pass
            server.stop()
        shutil.rmtree(data, ignore_errors=True)
    took = time.perf_counter() - began

    room, empty = out["room"], out["empty"]
    (cpu_room, cpu_empty), (runs_room, runs_empty) = out["cpu burst"], out["runs burst"]
    rows = [row("empty page (slider)", empty, cpu_empty, runs_empty), row("room (answer)", room, cpu_room, runs_room)]
    rows[0]["p95 x empty"], rows[1]["p95 x empty"] = 1.0, rows[1]["answer p95"] / rows[0]["answer p95"]
    lags, unseen = histogram_lags(room.answers, out["reads"])
    read_times = [end - began for began, end, total in out["reads"] if total >= 0]
    told = collections.Counter(said for _, said, _, _ in room.answers)
    expected = expected_counts(room.answers)
    recorded_ok = dict(final) == dict(expected)
    tail_seconds, tail_runs, tail_cpu, tail_polls = out["tail"]

    addresses = "one address (127.0.0.1)" if args.one_address else \
        f"{min(args.sessions, len(lecture_load.SOURCE_ADDRESSES))} loopback addresses"
    print(f"\n{args.sessions} phones open /room?c={asked.code} over {args.join:g} s, then answer within "
          f"{args.window:g} s, one process, from {addresses}; "
          f"{'fragment polls every 2.5 s emulated' if not args.no_polling else 'fragment polls NOT emulated'}; "
          f"the empty page side by side. Last answer {out['answered after']:.1f} s after the start; "
          f"run took {took:.0f} s.\n")
    print("| page | first load p50 / p95 | answer p50 / p95 / p99 / max | p95 × empty | errors | script runs "
          "(full / fragment / stopped early) | server CPU | CPU per run |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        kinds = r["runs by kind"]
        print(f"| {r['page']} | {ms(r['first p50'])} / {ms(r['first p95'])} ms | {ms(r['answer p50'])} / "
              f"{ms(r['answer p95'])} / {ms(r['answer p99'])} / {ms(r['answer max'])} ms | {r['p95 x empty']:.1f} | "
              f"{r['errors']} ({r['answers']} answered) | {kinds.get('full', 0)} / {kinds.get('fragment', 0)} / "
              f"{kinds.get('early', 0)} | {r['cpu s']:.1f} s | {r['cpu per run'] * 1000:.1f} ms |")
    print(f"\nfragment polls (_watch, every 2.5 s a phone): p50 {ms(percentile(room.polls, 50))} ms, "
          f"p95 {ms(percentile(room.polls, 95))} ms, max {ms(max(room.polls, default=float('nan')))} ms "
          f"over the whole run; polls alone for {tail_seconds:g} s after the last answer: {tail_runs} runs, "
          f"{tail_cpu:.2f} s CPU ({tail_cpu / max(1, tail_runs) * 1000:.1f} ms a poll, "
          f"{tail_cpu / max(tail_seconds, 1e-9):.2f} s CPU a second), p95 {ms(percentile(tail_polls, 95))} ms")
    print(f"histogram (the counts read from the database every {POLL_EVERY:g} s): lag p50 {ms(percentile(lags, 50))} ms, "
          f"p95 {ms(percentile(lags, 95))} ms, max {ms(max(lags, default=float('nan')))} ms, never seen {unseen}; "
          f"a read took p95 {ms(percentile(read_times, 95))} ms, max {ms(max(read_times, default=float('nan')))} ms; "
          f"the instructor's page adds up to 1.5 s of its own polling and its fragment's run")
    print(f"phones were told: {dict(told)}")
    print(f"database: {sum(final.values())} answers counted {dict(final)}; expected from the phones "
          f"{sum(expected.values())} {dict(expected)}: {'the same' if recorded_ok else 'DIFFERENT'}")
    print(f"server memory growth during the burst: {out['rss burst']:.0f} MB")
    m = out["machine"]
    print(f"the machine ({os.cpu_count()} cores) over the {m['seconds']:.0f} s of the burst: {m['busy']:.0f} CPU s busy: "
          f"room server {m['room server']:.0f}, empty server {m['empty server']:.0f}, this load generator "
          f"{m['load generator']:.0f}, other processes {m['others']:.0f}; store.latest (a poll's database read) "
          f"in this process: {latest_ms:.2f} ms")
    for label, stats in (("room", room), ("empty", empty)):
        if stats.errors:
            kinds = collections.Counter(re.sub(r"^session \d+(, )?", "", e)[:160] for e in stats.errors)
            print(f"{label} errors ({len(stats.errors)}, by kind): {kinds.most_common(6)}")
            for e in stats.errors[:3]:
                print(f"    {e}")
    for label, found in logs.items():
        print(f"{label} server log ({LOGS / f'room_burst-{label}-server.log'}): {len(found)} problem lines" + "".join(f"\n    {line}" for line in found[:15]))
    if args.json:
        args.json.write_text(json.dumps({
            "args": vars(args) | {"json": str(args.json)}, "code": asked.code, "rows": rows, "took": took,
            "histogram lag": {"p50": percentile(lags, 50), "p95": percentile(lags, 95),
                              "max": max(lags, default=None), "unseen": unseen},
            "reads": {"p95": percentile(read_times, 95), "max": max(read_times, default=None)},
            "told": dict(told), "database": dict(final), "expected": dict(expected), "recorded ok": recorded_ok,
            "tail": {"seconds": tail_seconds, "runs": tail_runs, "cpu": tail_cpu}, "machine": out["machine"],
            "store.latest ms": latest_ms,
            "errors": {"room": room.errors, "empty": empty.errors}, "server log": logs,
        }, indent=1, default=str))


if __name__ == "__main__":
    main()
