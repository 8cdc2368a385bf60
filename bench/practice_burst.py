"""Benchmark 5, a lecture's burst in Practice: every student submits an answer within ten seconds.

    python bench/practice_burst.py [--sessions 200] [--window 10] [--soak 2000]

Speaks Streamlit's websocket protocol, as bench/lecture_load.py does. One server (serve.py, as
shipped). Each session opens disk_wall?practice=1, then, inside the window, types an answer into
the Practice box and presses Check (the text input's and the form button's widget states); the time
runs from the submission to the end of the script run that shows the verdict. A third of the
sessions type expressions that make sympy work hard (they run into the simplification worker's
time limit, and numeric evaluation decides), the rest a mix of right, wrong, refused and numeric
answers. Halfway through the window the simplification worker is killed (SIGKILL); it must be
replaced. Then a soak: ``--soak`` submissions from 20 sessions, one after another, with the
server's memory (the process and its worker) sampled every 250. Loopback only, bounded in time.
"""
from __future__ import annotations

import argparse
import asyncio
import os
import random
import signal
import subprocess
import sys
import time
from pathlib import Path

import websockets
from streamlit.proto.BackMsg_pb2 import BackMsg
from streamlit.proto.ForwardMsg_pb2 import ForwardMsg
from streamlit.proto.WidgetStates_pb2 import WidgetState

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "bench"))
from lecture_load import percentile, rss_mb, start_servers  # noqa: E402

PAGE, QUERY = "disk_wall", "practice=1"
EASY = ["2/3*V*sin(theta) + R*omega/3", "0.8333", "833 mm/s", "V*sin(theta)", "v1x", "(R*omega + 2*V*sin(theta))/3",
        "2/3*V*sin(theta) - R*omega/3", "1/0", "0.5"]
HARD = [  # heavy for sympy; the last two are unclear to numbers (not real near these values), so the
    # simplification worker must settle them and is kept busy up to its time limit
    "(V + R*omega + sin(theta))^12/(V + R*omega + sin(theta))^11 - V - R*omega - sin(theta) + 2/3*V*sin(theta) + R*omega/3",
    "sin(theta)^12 + cos(theta)^12 + 2/3*V*sin(theta) + R*omega/3 - (sin(theta)^2+cos(theta)^2)^6"
    " + 3*sin(theta)^2*cos(theta)^2*(sin(theta)^2+cos(theta)^2)^2",
    "(sqrt(V) + sqrt(R*omega))^12/(V + R*omega)^5 + atan(tan(theta)) - theta",
    "(sin(theta)+cos(theta)+tan(theta))^10/(sin(theta)+cos(theta)+tan(theta))^9 - sin(theta) - cos(theta) - tan(theta)"
    " + 2/3*V*sin(theta) + R*omega/3",
    "(V + R*omega + sin(theta))^12/(V + R*omega + sin(theta))^11 + sqrt(-(theta - 1)^2)",
    "(sqrt(V) + sqrt(R*omega))^12/(V + R*omega)^5 + sqrt(-(theta - 1)^2) + cos(theta)^12 + sin(theta)^12",
]
TIMEOUT = 60.0


async def run(ws, widgets: list[WidgetState]) -> tuple[float, list[ForwardMsg]]:
    msg = BackMsg()
    msg.rerun_script.page_name = PAGE
    msg.rerun_script.query_string = QUERY
    msg.rerun_script.widget_states.widgets.extend(widgets)
    started = time.perf_counter()
    await ws.send(msg.SerializeToString())
    messages = []
    while True:
        forward = ForwardMsg()
        forward.ParseFromString(await asyncio.wait_for(ws.recv(), timeout=TIMEOUT))
        messages.append(forward)
        if forward.HasField("script_finished") and forward.script_finished != ForwardMsg.FINISHED_EARLY_FOR_RERUN:
            return time.perf_counter() - started, messages


def elements(messages):
    for m in messages:
        if m.HasField("delta") and m.delta.HasField("new_element"):
            yield m.delta.new_element


def ids(messages) -> tuple[str, str]:
    """The widget ids of the answer box and the Check button."""
    box = next(e.text_input.id for e in elements(messages) if e.WhichOneof("type") == "text_input"
               and e.text_input.id.endswith(f"{PAGE}__attempt"))
    button = next(e.button.id for e in elements(messages) if e.WhichOneof("type") == "button"
                  and e.button.id.endswith(f"{PAGE}__check"))
    return box, button


def submission(box: str, button: str, text: str) -> list[WidgetState]:
    typed, pressed = WidgetState(id=box), WidgetState(id=button)
    typed.string_value = text
    pressed.trigger_value = True
    return [typed, pressed]


def verdict(messages) -> str | None:
    for e in elements(messages):
        if e.WhichOneof("type") == "alert" and e.alert.format in (e.alert.SUCCESS, e.alert.ERROR):
            return e.alert.body
        if e.WhichOneof("type") == "exception":
            return None
    return None


async def connect(url: str):
    return await websockets.connect(url, subprotocols=["streamlit"], max_size=None, open_timeout=60,
                                    ping_interval=None)


async def burst(url: str, sessions: int, window: float, server_pid: int, hard_every: int) -> dict:
    rng = random.Random(15)
    texts = [HARD[i // hard_every % len(HARD)] if hard_every and i % hard_every == 0 else EASY[i % len(EASY)]
             for i in range(sessions)]
    sockets, targets = [], []
    for i in range(sessions):  # everyone has the page open before the burst
        ws = await connect(url)
        _, messages = await run(ws, [])
        sockets.append(ws)
        targets.append(ids(messages))
    results: list[tuple[str, float, bool]] = []  # (kind, seconds, verdict arrived)
    killed = {}

    async def student(i: int) -> None:
        await asyncio.sleep(rng.uniform(0, window))
        try:
            seconds, messages = await run(sockets[i], submission(*targets[i], texts[i]))
            results.append(("hard" if texts[i] in HARD else "easy", seconds, verdict(messages) is not None))
        except Exception:  # noqa: BLE001 - a lost verdict is counted, not fatal
            results.append(("hard" if texts[i] in HARD else "easy", float("inf"), False))

    async def kill_worker() -> None:
        await asyncio.sleep(window / 2)
        killed["before"] = workers(server_pid)
        for pid in killed["before"]:
            os.kill(pid, signal.SIGKILL)

    await asyncio.gather(*(student(i) for i in range(sessions)), kill_worker())
    await asyncio.sleep(3)  # a replacement starts with the first answer after the kill; give it time to load
    killed["after"] = workers(server_pid)
    seconds, messages = await run(sockets[0], submission(*targets[0], HARD[0]))
    killed["next verdict"] = f"{verdict(messages)!r} in {seconds * 1000:.0f} ms"
    for ws in sockets:
        await ws.close()
    return {"results": results, "killed": killed}


def workers(server_pid: int) -> list[int]:
    out = subprocess.run(["pgrep", "-P", str(server_pid), "-f", "practice.worker"], capture_output=True, text=True)
    return [int(p) for p in out.stdout.split()]


async def soak(url: str, total: int, server_pid: int) -> list[tuple[int, float]]:
    sockets = [await connect(url) for _ in range(20)]
    targets = []
    for ws in sockets:
        targets.append(ids((await run(ws, []))[1]))
    samples, done = [(0, rss_mb([server_pid, *workers(server_pid)]))], 0
    all_texts = EASY + HARD
    while done < total:
        batch = [run(ws, submission(*t, all_texts[(done + i) % len(all_texts)] + f" + 0*V*{done + i}"))
                 for i, (ws, t) in enumerate(zip(sockets, targets))]
        await asyncio.gather(*batch)
        done += len(batch)
        if done % 250 < len(batch):
            samples.append((done, rss_mb([server_pid, *workers(server_pid)])))
    for ws in sockets:
        await ws.close()
    samples.append((-1, float(len(workers(server_pid)))))  # workers alive at the end
    return samples


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sessions", type=int, default=200)
    parser.add_argument("--window", type=float, default=10.0)
    parser.add_argument("--soak", type=int, default=2000)
    parser.add_argument("--hard-every", type=int, default=3, help="every n-th session types a hard expression "
                        "(0: none, the baseline for the easy answers' times)")
    args = parser.parse_args()
    procs, url, _, _ = start_servers(ROOT / "app.py", 1)
    try:
        out = asyncio.run(burst(url, args.sessions, args.window, procs[0].pid, args.hard_every))
        samples = asyncio.run(soak(url, args.soak, procs[0].pid)) if args.soak else []
    finally:
        procs[0].terminate()
        try:
            procs[0].wait(15)
        except subprocess.TimeoutExpired:
            procs[0].kill()
    results = out["results"]
    arrived = sum(ok for _, _, ok in results)
    share = f"1 in {args.hard_every}" if args.hard_every else "none"
    print(f"\n{args.sessions} sessions submit within {args.window:g} s on {PAGE} ({share} hard for sympy), one process; "
          f"worker killed at {args.window / 2:g} s: pids {out['killed']['before']} -> {out['killed']['after']}; "
          f"a hard answer after the burst: {out['killed']['next verdict']}\n")
    print("| answers | count | verdicts arrived | p50 | p95 | max |")
    print("|---|---|---|---|---|---|")
    for kind in ("easy", "hard", "all"):
        times = [s for k, s, _ in results if kind in ("all", k)]
        if not times:
            continue
        ok = sum(a for k, _, a in results if kind in ("all", k))
        print(f"| {kind} | {len(times)} | {ok} | {percentile(times, 50) * 1000:.0f} ms | "
              f"{percentile(times, 95) * 1000:.0f} ms | {max(times) * 1000:.0f} ms |")
    print(f"\nverdicts: {arrived}/{len(results)}")
    if samples:
        *samples, (_, alive) = samples
        print(f"\nsoak: submissions -> server RSS (process + worker), MB; {alive:.0f} worker(s) alive after it")
        print(" ".join(f"{n}: {mb:.0f}" for n, mb in samples))


if __name__ == "__main__":
    main()
