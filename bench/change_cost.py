"""Benchmark 1, as the browser asks for it: what one change of the lesson control costs the server,
on every page, against the empty one-slider page in the same run.

    python bench/change_cost.py [--changes 30] [--pages PAGE ...] [--json OUT] [--revisit]

One session per page speaks Streamlit's websocket protocol to a real server (``serve.py``, warmed as
it is shipped; the empty page on the same server code, ``bench/serve_empty.py``), as
``bench/lecture_load.py`` does: it loads the page, then moves the lesson control along its own grid
(``bench/controls.changes_of``, each value new) and sends each change as the browser does, with the
id of the fragment the control is drawn in when it is in one (the browser then reruns that fragment
alone; ``bench/interaction.py``'s AppTest always runs the whole script, so it cannot see this).
Each page change alternates with a change on the empty page, so drift on a shared machine hits both
alike. Per change: the wall time from sending the change to the server's "finished" (loopback), and
the server process's CPU time (user + system, read from /proc before and after; its mean, since
/proc counts in 10 ms ticks). Prints a Markdown table: the wall time's median, the CPU's mean, and the ratio to the empty page's in the same run.
``--revisit`` moves the control back and forth between two values instead (each seen once, untimed,
first), so every cache answers: what the page's elements and messages cost with no new numbers.
The page's session goes through a relay (``Wire``) that counts a change's bytes on the wire (the websocket's
compression on, as Chromium asks for it) beside the bytes decoded: the median of each.
"""
from __future__ import annotations

import argparse
import asyncio
import json
import statistics
import sys
import time
from pathlib import Path
from urllib.parse import urlparse

import websockets

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from bench.controls import changes_of, lesson_control  # noqa: E402
from edge.fair_share import BURST  # noqa: E402
from bench.lecture_load import (cpu_seconds, run_script, start_servers, stop_servers,  # noqa: E402
                                widget_id, widget_state)
from solvers import registry  # noqa: E402


# Changes sent back to back outrun a person; the server's per-session budget (edge/fair_share.py:
# BURST, then RATE a second) would hold them back and the wait would count as cost. So each tab
# sends fewer than a burst, and the next changes come from a new tab.
PER_SESSION = BURST - 5


class Wire:
    """A TCP relay in front of a server that counts the bytes it sends back: what a change costs on the wire,
    after the websocket's compression (``permessage-deflate``, which the client offers as a browser does),
    where ``run_script`` counts the messages as decoded."""

    def __init__(self, url: str):
        self.target = urlparse(url)
        self.sent = 0

    async def _pipe(self, reader, writer, counted: bool):
        try:
            while data := await reader.read(65536):
                if counted:
                    self.sent += len(data)
                writer.write(data)
                await writer.drain()
        except ConnectionError:
            pass
        finally:
            writer.close()

    async def _relay(self, reader, writer):
        upstream_reader, upstream_writer = await asyncio.open_connection(self.target.hostname, self.target.port)
        await asyncio.gather(self._pipe(reader, upstream_writer, False), self._pipe(upstream_reader, writer, True))

    async def __aenter__(self):
        self.server = await asyncio.start_server(self._relay, "127.0.0.1", 0)
        port = self.server.sockets[0].getsockname()[1]
        self.url = self.target._replace(netloc=f"127.0.0.1:{port}").geturl()
        return self

    async def __aexit__(self, *exc):
        self.server.close()


class Session:
    """One browser tab's worth of protocol: connect, load ``page``, find the control ``key``."""

    def __init__(self, url: str, page: str, key: str, pid: int):
        self.url, self.page, self.key, self.pid = url, page, key, pid

    async def __aenter__(self):
        self.ws = await websockets.connect(self.url, subprotocols=["streamlit"], max_size=None,
                                           open_timeout=60, ping_interval=None)
        _, _, messages = await run_script(self.ws, self.page, [])
        found = widget_id(messages, self.key)
        if found is None:
            raise SystemExit(f"no control {self.key} on {self.page or 'the empty page'}")
        self.wid, self.kind, self.fragment = found
        return self

    async def __aexit__(self, *exc):
        await self.ws.close()

    async def change(self, value: float, wire: Wire | None = None) -> tuple[float, float, int, int]:
        """(wall seconds, server CPU seconds, bytes decoded, bytes on the ``wire``) of one change to
        ``value``; an exception element (a traceback on the page) fails the run."""
        cpu = cpu_seconds([self.pid])
        on_wire = wire.sent if wire else 0
        began = time.perf_counter()
        _, decoded, messages = await run_script(self.ws, self.page, [widget_state(self.wid, self.kind, value)], self.fragment)
        wall = time.perf_counter() - began
        for m in messages:
            if m.HasField("delta") and m.delta.HasField("new_element") and m.delta.new_element.WhichOneof("type") == "exception":
                raise SystemExit(f"{self.page}: exception after a change to {value}")
        await asyncio.sleep(0.01)  # the relay's last write counted
        return wall, cpu_seconds([self.pid]) - cpu, decoded, (wire.sent if wire else 0) - on_wire


async def measure(page: str, changes: int, empty_url: str, empty_pid: int, page_url: str, page_pid: int,
                  revisit: bool = False) -> dict:
    key, _, _, _ = lesson_control(page)
    values = (changes_of(page, 2) * changes)[:changes] if revisit else changes_of(page, changes)
    rows = []
    async with Wire(page_url) as wire:
        for start in range(0, len(values), PER_SESSION):  # a new tab every PER_SESSION changes: see PER_SESSION
            async with Session(wire.url, page, key, page_pid) as p, Session(empty_url, "", "x", empty_pid) as e:
                if revisit and start == 0:  # both values seen once, untimed: every timed change is a cache's answer
                    for value in values[:2]:
                        await p.change(value)
                for i, value in enumerate(values[start:start + PER_SESSION], start=start + 1):
                    rows.append((*await p.change(value, wire), *await e.change(round(0.9 - 0.5 * i / len(values), 6))))
    walls, cpus, decoded, on_wire, ewalls, ecpus, _, _ = zip(*rows)
    # the wall time's median; the CPU's mean (/proc counts it in 10 ms ticks: one change's reading is
    # 0 or 10 ms, and only their sum over many changes has the resolution)
    wall, ewall, cpu, ecpu = statistics.median(walls), statistics.median(ewalls), statistics.mean(cpus), statistics.mean(ecpus)
    return {"page": page, "fragment": bool(p.fragment), "changes": len(rows),
            "wall ms": wall * 1e3, "empty wall ms": ewall * 1e3, "wall x empty": wall / ewall,
            "cpu ms": cpu * 1e3, "empty cpu ms": ecpu * 1e3, "cpu x empty": cpu / ecpu if ecpu else float("nan"),
            "KB decoded": statistics.median(decoded) / 1024, "KB on the wire": statistics.median(on_wire) / 1024}


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--changes", type=int, default=30)
    parser.add_argument("--pages", nargs="*", default=list(registry.PROBLEM_IDS))
    parser.add_argument("--json", type=Path)
    parser.add_argument("--revisit", action="store_true", help="two values back and forth: every cache answers")
    args = parser.parse_args()
    empty = start_servers(ROOT / "bench" / "empty_app.py", 1)
    app = start_servers(ROOT / "app.py", 1)
    rows = []
    try:
        for page in args.pages:
            rows.append(asyncio.run(measure(page, args.changes, empty[1], empty[0][0].pid, app[1], app[0][0].pid,
                                            args.revisit)))
            print(f"  done: {page}", file=sys.stderr)
    finally:
        stop_servers(*app[:1], app[2], app[3])
        stop_servers(*empty[:1], empty[2], empty[3])
    print(f"\nOne change of the lesson control, as the browser sends it; median of {args.changes} changes, "
          "each beside one on the empty page\n")
    print("| page | fragment rerun | wall per change (empty) | × empty | server CPU per change (empty) | × empty "
          "| KB on the wire (decoded) |")
    print("|---|---|---|---|---|---|---|")
    for r in rows:
        print(f"| {r['page']} | {'yes' if r['fragment'] else 'no'} | {r['wall ms']:.1f} ms ({r['empty wall ms']:.1f}) | "
              f"{r['wall x empty']:.2f} | {r['cpu ms']:.1f} ms ({r['empty cpu ms']:.1f}) | {r['cpu x empty']:.2f} | "
              f"{r['KB on the wire']:.1f} ({r['KB decoded']:.1f}) |")
    if args.json:
        args.json.write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
