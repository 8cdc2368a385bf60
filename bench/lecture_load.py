"""Benchmark 4, the lecture: hundreds of students open the same link, then each moves a control.

    python bench/lecture_load.py [--sessions 200] [--join 20] [--changes 5] [--pause 4 6]
                                 [--processes 1 2] [--spread] [--pages PAGE ...] [--json OUT]

A load generator that speaks Streamlit's own websocket protocol (the protobuf messages in
streamlit.proto): each session connects to /_stcore/stream, sends BackMsg.rerun_script for its
page and reads ForwardMsgs until script_finished (first load), then moves one control ``changes``
times, sending the widget's new state (interaction), each change ``--pause`` seconds after the
last one's answer (uniform; 4–6 s by default, the issue's "about every 5 s"; tables before the
seventh session used 2–4 s, a lecture 1.7 times as busy: ``--pause 2 4``). Hundreds of sessions run from
one asyncio process. The same scenario runs against an empty one-slider app in the same run.
Reports first-load and interaction latency (p50/p95/p99), errors, bytes per interaction, the server's
CPU time per run (first loads and interactions together; one process, holding one interpreter lock,
has about a second of it per second) and server memory per session. Loopback only, bounded in count and time.

Each session connects from its own loopback address (127.0.0.2 … 127.0.0.254, the socket bound to
it; Linux's loopback answers all of 127/8), as the students of a lecture come from their own
phones and laptops: the server's fair share (edge/fair_share.py) budgets messages per client
address, and 200 sessions from one address would be throttled as one NAT'd room flooding. By
default the scenario runs twice, on one process (``--processes 1``: a replica of the shipped image)
and on two behind the nginx of ``deploy/`` (``--processes 2``: the shipped Compose topology, with
``DL_TRUSTED_PROXIES=*`` as Compose sets it, so the app reads each client's address from nginx's
X-Forwarded-For). Each page's lecture runs side by side with the same lecture on the empty page
(its own servers of the same topology, at the same time): the machine is shared, and what else runs
on it then weighs on the page and on its baseline alike; the ratio is the page's interaction p95
over that of the empty page beside it.
"""
from __future__ import annotations

import argparse
import asyncio
import json
import os
import random
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

import websockets
from streamlit.proto.BackMsg_pb2 import BackMsg
from streamlit.proto.ForwardMsg_pb2 import ForwardMsg
from streamlit.proto.WidgetStates_pb2 import WidgetState

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from scripts.balancer_check import start_nginx  # noqa: E402
from scripts.live_app import free_port, wait_healthy  # noqa: E402

from bench.controls import lesson_control  # noqa: E402
from solvers import registry  # noqa: E402

CONTROLS = {  # page -> (widget key suffix, start value, step per change)
    "": ("x", 0.5, 0.01),  # the empty app's slider
} | {pid: (key, start, step) for pid in registry.PROBLEM_IDS for key, start, _, step in [lesson_control(pid)]}
SESSION_TIMEOUT = 120.0
SOURCE_ADDRESSES = [f"127.0.0.{n}" for n in range(2, 255)]


ONE_ADDRESS = {"on": False}  # --one-address: the whole hall behind one NAT


def source_address(n: int) -> str:
    """The loopback address session ``n`` connects from (253 of them, reused round the list; with
    ``--one-address``, 127.0.0.1 for all: a lecture hall behind one NAT, which the fair share serves as one
    address, one run at a time)."""
    return "127.0.0.1" if ONE_ADDRESS["on"] else SOURCE_ADDRESSES[n % len(SOURCE_ADDRESSES)]


@dataclass
class Results:
    first_load: list[float] = field(default_factory=list)
    interaction: list[float] = field(default_factory=list)
    interaction_bytes: list[int] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)


async def run_script(ws, page: str, widgets: list[WidgetState],
                     fragment: str = "") -> tuple[float, int, list[ForwardMsg]]:
    """Send a rerun as the browser does (``fragment``: the id of the fragment the changed widget is
    drawn in, whose rerun is the fragment's alone) and read the server's answer to its end."""
    msg = BackMsg()
    msg.rerun_script.page_name = page
    msg.rerun_script.query_string = ""
    msg.rerun_script.widget_states.widgets.extend(widgets)
    if fragment:
        msg.rerun_script.fragment_id = fragment
    started = time.perf_counter()
    await ws.send(msg.SerializeToString())
    received, messages = 0, []
    while True:
        data = await asyncio.wait_for(ws.recv(), timeout=SESSION_TIMEOUT)
        received += len(data)
        forward = ForwardMsg()
        forward.ParseFromString(data)
        messages.append(forward)
        if forward.HasField("script_finished") and forward.script_finished != ForwardMsg.FINISHED_EARLY_FOR_RERUN:
            return time.perf_counter() - started, received, messages


def widget_id(messages: list[ForwardMsg], key: str) -> tuple[str, str, str] | None:
    """(id, kind, fragment id or "") of the slider or number box whose key is ``key``: the browser
    reruns only the fragment a changed widget is drawn in."""
    for forward in messages:
        if forward.HasField("delta") and forward.delta.HasField("new_element"):
            element = forward.delta.new_element
            kind = element.WhichOneof("type")
            if kind in ("slider", "number_input"):
                wid = getattr(element, kind).id
                if wid.endswith(key):
                    return wid, kind, forward.delta.fragment_id
    return None


def widget_state(wid: str, kind: str, value: float) -> WidgetState:
    state = WidgetState(id=wid)
    if kind == "slider":  # a slider's value is an array (it may be a range)
        state.double_array_value.data.append(value)
    else:
        state.double_value = value
    return state


async def session(url: str, page: str, delay: float, changes: int, results: Results, rng: random.Random,
                  spread: bool, pause: tuple[float, float], source: str = "127.0.0.1") -> None:
    await asyncio.sleep(delay)
    key, value, step = CONTROLS[page]
    if spread:  # every student her own values: no two sessions ask for the same state
        step = step * rng.uniform(0.05, 0.95)
    try:
        async with websockets.connect(url, subprotocols=["streamlit"], max_size=None, open_timeout=60,
                                      ping_interval=None, local_addr=(source, 0)) as ws:
            seconds, _, messages = await run_script(ws, page, [])
            results.first_load.append(seconds)
            found = widget_id(messages, key)
            if found is None:
                results.errors.append(f"no widget {key} on {page or 'empty'}")
                return
            wid, kind, fragment = found
            for _ in range(changes):
                await asyncio.sleep(rng.uniform(*pause))
                value = round(value + step, 6)
                seconds, size, messages = await run_script(ws, page, [widget_state(wid, kind, value)], fragment)
                if any(m.HasField("delta") and m.delta.HasField("new_element")
                       and m.delta.new_element.WhichOneof("type") == "exception" for m in messages):
                    results.errors.append("exception element")
                results.interaction.append(seconds)
                results.interaction_bytes.append(size)
    except Exception as error:  # noqa: BLE001 - every failure is counted, none is fatal
        results.errors.append(f"{type(error).__name__}: {error}"[:200])


def rss_mb(pids: list[int]) -> float:
    total = 0
    for pid in pids:
        try:
            for line in Path(f"/proc/{pid}/status").read_text().splitlines():
                if line.startswith("VmRSS:"):
                    total += int(line.split()[1])
        except OSError:
            pass
    return total / 1024


def cpu_seconds(pids: list[int]) -> float:
    """User + system CPU time the server processes have used so far."""
    total = 0
    for pid in pids:
        try:
            fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
            total += int(fields[11]) + int(fields[12])  # utime, stime (fields 14 and 15 of stat)
        except OSError:
            pass
    return total / os.sysconf("SC_CLK_TCK")


def percentile(values: list[float], q: float) -> float:
    if not values:
        return float("nan")
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, int(round(q / 100 * (len(ordered) - 1))))]


def start_servers(app: Path, processes: int) -> tuple[list[subprocess.Popen], str, Path | None, subprocess.Popen | None]:
    env = {**os.environ, "STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE": "true", "STREAMLIT_SERVER_COOKIE_SECRET": "bench"}
    if processes > 1:  # behind nginx, as Compose runs it: the client is the one nginx's X-Forwarded-For names
        env["DL_TRUSTED_PROXIES"] = "*"
    ports = [free_port() for _ in range(processes)]
    procs = []
    for port in ports:
        # The empty baseline runs on the same server as the app (serve.run), without the warm-up.
        cmd = [sys.executable, str(ROOT / ("serve.py" if app.name == "app.py" else "bench/serve_empty.py"))]
        procs.append(subprocess.Popen(cmd + ["--server.port", str(port), "--server.address", "127.0.0.1",
                                             "--server.headless", "true", "--browser.gatherUsageStats", "false"],
                                      cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
    for port, proc in zip(ports, procs):
        wait_healthy(f"http://127.0.0.1:{port}", timeout=180, proc=proc)
    if processes == 1:
        return procs, f"ws://127.0.0.1:{ports[0]}/_stcore/stream", None, None
    workdir = Path(tempfile.mkdtemp(prefix="dl-bench-nginx-"))
    listen = free_port()
    nginx = start_nginx(ports, listen, workdir)
    return procs, f"ws://127.0.0.1:{listen}/_stcore/stream", workdir, nginx


async def scenario(url: str, page: str, sessions: int, join: float, changes: int, pids: list[int],
                   spread: bool, pause: tuple[float, float] = (4.0, 6.0)) -> tuple[Results, float, float]:
    results = Results()
    rng = random.Random(1234)
    before = rss_mb(pids)
    cpu_before = cpu_seconds(pids)
    samples = [before]
    tasks = [asyncio.create_task(session(url, page, rng.uniform(0, join), changes, results, random.Random(i),
                                         spread, pause, source_address(i))) for i in range(sessions)]

    async def sample_memory():
        while not all(t.done() for t in tasks):
            samples.append(rss_mb(pids))
            await asyncio.sleep(0.5)

    sampler = asyncio.create_task(sample_memory())
    await asyncio.wait_for(asyncio.gather(*tasks), timeout=join + changes * pause[1] + 2 * SESSION_TIMEOUT)
    await sampler
    runs = len(results.first_load) + len(results.interaction)
    cpu_per_run = (cpu_seconds(pids) - cpu_before) / max(1, runs)
    return results, max(0.0, max(samples) - before) / sessions, cpu_per_run


def report(label: str, r: Results, mb_per_session: float, cpu_per_run: float) -> dict:
    row = {
        "page": label,
        "first p50": percentile(r.first_load, 50), "first p95": percentile(r.first_load, 95),
        "int p50": percentile(r.interaction, 50), "int p95": percentile(r.interaction, 95),
        "int p99": percentile(r.interaction, 99), "errors": len(r.errors),
        "interactions": len(r.interaction),
        "KB/interaction": statistics.mean(r.interaction_bytes) / 1024 if r.interaction_bytes else float("nan"),
        "MB/session": mb_per_session, "CPU/run": cpu_per_run,
    }
    if r.errors:
        print(f"  {label}: first errors: {r.errors[:3]}", file=sys.stderr)
    return row


def stop_servers(procs: list[subprocess.Popen], workdir: Path | None, nginx: subprocess.Popen | None) -> None:
    if nginx:
        nginx.terminate()
    for proc in procs:
        proc.terminate()
    for proc in procs:
        try:
            proc.wait(15)
        except subprocess.TimeoutExpired:
            proc.kill()
    if workdir:
        shutil.rmtree(workdir, ignore_errors=True)


async def side_by_side(empty_url: str, page_url: str, page: str, empty_pids: list[int], page_pids: list[int], args):
    return await asyncio.gather(
        scenario(empty_url, "", args.sessions, args.join, args.changes, empty_pids, args.spread, tuple(args.pause)),
        scenario(page_url, page, args.sessions, args.join, args.changes, page_pids, args.spread, tuple(args.pause)))


def run_topology(processes: int, pages: list[str], args) -> list[dict]:
    """Each page's lecture side by side with the same lecture on the empty page: both on fresh
    servers of this topology, at the same time, so that whatever else the machine is doing (it is
    shared) weighs on both alike. The rows: the empty page beside each page, then the page."""
    rows = []
    for page in pages:
        empty = start_servers(ROOT / "bench" / "empty_app.py", processes)
        try:
            app = start_servers(ROOT / "app.py", processes)
            try:
                (er, emb, ecpu), (pr, pmb, pcpu) = asyncio.run(side_by_side(
                    empty[1], app[1], page, [p.pid for p in empty[0]], [p.pid for p in app[0]], args))
            finally:
                stop_servers(app[0], app[2], app[3])
        finally:
            stop_servers(empty[0], empty[2], empty[3])
        beside, row = report(f"empty page beside {page}", er, emb, ecpu), report(page, pr, pmb, pcpu)
        beside["p95 x empty"], row["p95 x empty"] = 1.0, row["int p95"] / beside["int p95"]
        rows += [beside, row]
        print(f"  done: {page} ({processes} process(es)): p95 {row['int p95'] * 1000:.0f} ms, "
              f"the empty page's beside it {beside['int p95'] * 1000:.0f} ms", file=sys.stderr)
    return rows


def print_table(rows: list[dict], processes: int, args) -> None:
    print(f"\n{args.sessions} sessions joining over {args.join:g} s, {args.changes} changes each "
          f"{args.pause[0]:g}–{args.pause[1]:g} s apart, "
          f"{processes} process(es){' behind nginx' if processes > 1 else ''}, "
          f"{'each session its own values' if args.spread else 'the same values in every session'}, "
          + ("from one address (one NAT)\n" if ONE_ADDRESS["on"] else
             f"from {min(args.sessions, len(SOURCE_ADDRESSES))} loopback addresses\n"))
    print("| page | first load p50 / p95 | interaction p50 / p95 / p99 | p95 × empty | errors | KB per interaction "
          "| server MB per session | server CPU per run |")
    print("|---|---|---|---|---|---|---|---|")
    for row in rows:
        print(f"| {row['page']} | {row['first p50'] * 1000:.0f} / {row['first p95'] * 1000:.0f} ms | "
              f"{row['int p50'] * 1000:.0f} / {row['int p95'] * 1000:.0f} / {row['int p99'] * 1000:.0f} ms | "
              f"{row['p95 x empty']:.1f} | {row['errors']} ({row['interactions']} done) | "
              f"{row['KB/interaction']:.0f} | {row['MB/session']:.2f} | {row['CPU/run'] * 1000:.1f} ms |")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sessions", type=int, default=200)
    parser.add_argument("--join", type=float, default=20.0)
    parser.add_argument("--changes", type=int, default=5)
    parser.add_argument("--pause", type=float, nargs=2, default=(4.0, 6.0), metavar=("LOW", "HIGH"),
                        help="seconds between a session's changes, drawn uniformly (default 4 6)")
    parser.add_argument("--processes", type=int, nargs="+", default=[1, 2],
                        help="the topologies: 1 = one process, n > 1 = n processes behind nginx (default 1 2)")
    parser.add_argument("--pages", nargs="*", default=[p for p in CONTROLS if p])
    parser.add_argument("--spread", action="store_true",
                        help="each session moves its control by its own random steps (no shared states)")
    parser.add_argument("--json", type=Path, help="also write {processes: {page: row}} here")
    parser.add_argument("--one-address", action="store_true", help="every session from 127.0.0.1 (one NAT)")
    args = parser.parse_args()
    ONE_ADDRESS["on"] = args.one_address
    results = {}
    for processes in args.processes:
        rows = run_topology(processes, args.pages, args)
        print_table(rows, processes, args)
        results[str(processes)] = {row["page"]: row for row in rows}
        sys.stdout.flush()
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))


if __name__ == "__main__":
    main()
