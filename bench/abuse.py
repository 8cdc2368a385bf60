"""Benchmark 7, fair share: one session floods reruns while a class works.

    python bench/abuse.py [--page disk_wall] [--students 20] [--rate 1000] [--flood 10] [--tabs 1] [--url WS_URL]

Speaks Streamlit's websocket protocol, as bench/lecture_load.py does. Two phases on one server
(serve.py on a free loopback port, or ``--url``): **calm**, where ``--students`` sessions each move
the page's lesson control every 1–2 s and a new visitor opens the page every second; then the same
with **flood**: one more session sends ``--rate`` reruns a second (each with a new value, never
reading an answer) for ``--flood`` seconds, as the hostile script of issue 25 did. Reports, per
phase, the students' change latency (p50/p95/max), the visitors' page loads (max), errors, and what
the flooder managed to send and whether it was dropped. The target: the students' p95 with the
flood within 2x their p95 without it, page loads within 2 s. Loopback only, bounded in time.

``--tabs N``: the flood comes from N sessions of one address (127.0.0.1), each sending ``--rate`` reruns a
second, while the students and visitors connect from addresses of their own (127.0.0.2 …), as a class on
a campus network meets a script that opened many tabs.
"""
from __future__ import annotations

import argparse
import asyncio
import os
import random
import subprocess
import sys
import time
from dataclasses import dataclass, field
from pathlib import Path

import websockets
from streamlit.proto.BackMsg_pb2 import BackMsg

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from bench.lecture_load import CONTROLS, percentile, rss_mb, run_script, widget_id, widget_state  # noqa: E402
from scripts.live_app import free_port, wait_healthy  # noqa: E402


@dataclass
class Phase:
    changes: list[float] = field(default_factory=list)
    loads: list[float] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)
    flood_sent: int = 0
    flood_dropped: str = ""


OWN_ADDRESSES = [f"127.0.0.{n}" for n in range(2, 255)]  # (with --tabs: each student and visitor one of these)
source = {"own": False}


def address(n: int) -> str:
    return OWN_ADDRESSES[n % len(OWN_ADDRESSES)] if source["own"] else "127.0.0.1"


async def connect(url, source_address: str = "127.0.0.1"):
    return await websockets.connect(url, subprotocols=["streamlit"], max_size=None, open_timeout=30,
                                    ping_interval=None, local_addr=(source_address, 0))


async def student(url: str, page: str, until: float, phase: Phase, rng: random.Random, n: int = 0) -> None:
    key, value, step = CONTROLS[page]
    try:
        async with await connect(url, address(n)) as ws:
            _, _, messages = await run_script(ws, page, [])
            wid, kind, fragment = widget_id(messages, key)
            while time.perf_counter() < until:
                await asyncio.sleep(rng.uniform(1.0, 2.0))
                value = round(value + step, 6)
                seconds, _, _ = await run_script(ws, page, [widget_state(wid, kind, value)], fragment)
                phase.changes.append(seconds)
    except Exception as error:  # noqa: BLE001 - counted, never fatal
        phase.errors.append(f"student: {type(error).__name__}: {error}"[:160])


async def visitors(url: str, page: str, until: float, phase: Phase) -> None:
    visits = [0]

    async def visit():
        visits[0] += 1
        try:
            async with await connect(url, address(1000 + visits[0])) as ws:
                started = time.perf_counter()
                await run_script(ws, page, [])
                phase.loads.append(time.perf_counter() - started)
        except Exception as error:  # noqa: BLE001
            phase.errors.append(f"visitor: {type(error).__name__}: {error}"[:160])
    tasks = []
    while time.perf_counter() < until:
        tasks.append(asyncio.create_task(visit()))
        await asyncio.sleep(1.0)
    await asyncio.gather(*tasks)


async def flooder(url: str, page: str, rate: float, seconds: float, phase: Phase) -> None:
    key, start, step = CONTROLS[page]
    try:
        ws = await connect(url)
        _, _, messages = await run_script(ws, page, [])
        wid, kind, fragment = widget_id(messages, key)
        end = time.perf_counter() + seconds
        batch = max(1, int(rate / 100))  # every 10 ms
        while time.perf_counter() < end:
            tick = time.perf_counter()
            for _ in range(batch):
                value = round(start + step * (phase.flood_sent % 50 + 1), 6)  # a new value each time
                msg = BackMsg()
                msg.rerun_script.page_name = page
                msg.rerun_script.widget_states.widgets.append(widget_state(wid, kind, value))
                msg.rerun_script.fragment_id = fragment
                # A send the server does not read yet waits here (TCP's back-pressure): bounded.
                await asyncio.wait_for(ws.send(msg.SerializeToString()), timeout=max(0.01, end - time.perf_counter()))
                phase.flood_sent += 1
            await asyncio.sleep(max(0.0, 0.01 - (time.perf_counter() - tick)))
    except asyncio.TimeoutError:
        phase.flood_dropped = phase.flood_dropped or "held back (send blocked)"
    except websockets.ConnectionClosed as closed:
        phase.flood_dropped = f"closed by the server ({closed.rcvd.code if closed.rcvd else '?'})"
    except Exception as error:  # noqa: BLE001
        phase.errors.append(f"flooder: {type(error).__name__}: {error}"[:160])
    finally:
        try:
            ws.transport.abort()  # leave without a handshake: the server must not wait on it
        except Exception:  # noqa: BLE001
            pass


async def run_phase(url: str, page: str, students: int, seconds: float, flood: tuple[float, float] | None,
                    tabs: int = 1) -> Phase:
    phase = Phase()
    until = time.perf_counter() + seconds
    tasks = [asyncio.create_task(student(url, page, until, phase, random.Random(i), i)) for i in range(students)]
    await asyncio.sleep(3.0)  # everyone has loaded before the clock that matters starts
    tasks.append(asyncio.create_task(visitors(url, page, until, phase)))
    if flood:
        tasks += [asyncio.create_task(flooder(url, page, flood[0], flood[1], phase)) for _ in range(tabs)]
    await asyncio.wait_for(asyncio.gather(*tasks), timeout=seconds + 120)
    return phase


def start_server() -> tuple[subprocess.Popen, str]:
    port = free_port()
    env = {**os.environ, "STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE": "true", "STREAMLIT_SERVER_COOKIE_SECRET": "bench"}
    proc = subprocess.Popen([sys.executable, str(ROOT / "serve.py"), "--server.port", str(port),
                             "--server.address", "127.0.0.1", "--server.headless", "true",
                             "--browser.gatherUsageStats", "false"],
                            cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    wait_healthy(f"http://127.0.0.1:{port}", timeout=180, proc=proc)
    return proc, f"ws://127.0.0.1:{port}/_stcore/stream"


def line(label: str, p: Phase) -> str:
    ms = lambda s: f"{s * 1000:.0f}"  # noqa: E731
    return (f"| {label} | {len(p.changes)} | {ms(percentile(p.changes, 50))} / {ms(percentile(p.changes, 95))} / "
            f"{ms(max(p.changes, default=float('nan')))} ms | {ms(max(p.loads, default=float('nan')))} ms | "
            f"{len(p.errors)} | {p.flood_sent or '—'} | {p.flood_dropped or '—'} |")


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--page", default="disk_wall", choices=[p for p in CONTROLS if p])
    parser.add_argument("--students", type=int, default=20)
    parser.add_argument("--rate", type=float, default=1000.0, help="the flood's reruns per second")
    parser.add_argument("--flood", type=float, default=10.0, help="the flood's length in seconds")
    parser.add_argument("--tabs", type=int, default=1, help="flooding sessions from one address (the class: "
                        "each from its own, with more than 1)")
    parser.add_argument("--url", help="a running server's websocket URL (default: start serve.py)")
    args = parser.parse_args()
    source["own"] = args.tabs > 1
    seconds = args.flood + 15.0  # the flood, and the time after it that a queue would hold everyone
    proc, url = (None, args.url) if args.url else start_server()
    warm_mb = rss_mb([proc.pid]) if proc else float("nan")
    try:
        calm = asyncio.run(run_phase(url, args.page, args.students, seconds, None))
        flood = asyncio.run(run_phase(url, args.page, args.students, seconds, (args.rate, args.flood), args.tabs))
    finally:
        if proc:
            proc.terminate()
            proc.wait(15)
    print(f"\nserver memory once warm (serve.py, before any session): {warm_mb:.0f} MB")
    print(f"\n{args.page}: {args.students} students changing every 1-2 s for {seconds:g} s, a visitor a second; "
          f"flood {args.rate:g}/s for {args.flood:g} s from {'one session' if args.tabs == 1 else f'each of {args.tabs} sessions of one address (the class from their own)'}\n")
    print("| phase | changes | change p50 / p95 / max | page load max | errors | flood sent | flooder |")
    print("|---|---|---|---|---|---|---|")
    print(line("calm", calm))
    print(line("flood", flood))
    ratio = percentile(flood.changes, 95) / percentile(calm.changes, 95)
    print(f"\nchange p95 with the flood / without: {ratio:.2f} (target <= 2); "
          f"page load max with the flood: {max(flood.loads, default=float('nan')):.2f} s (target <= 2)")
    for error in (calm.errors + flood.errors)[:5]:
        print("  error:", error, file=sys.stderr)


if __name__ == "__main__":
    main()
