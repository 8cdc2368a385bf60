"""Benchmark 1 and 3: server time per control change on every page, against an empty page with one
slider measured in the same run; and each figure's JSON size.

    python bench/interaction.py [--changes 30] [--pages PAGE ...] [--json OUT] [--no-figures] [--revisit]

Server time is AppTest's run after a widget change (the script run plus Streamlit's own work),
median of distinct values: each change moves the page's lesson control one step of its own
(``bench/controls.changes_of``: a slider along its grid within its range, the only values a drag
gives, a box by half its step), so no value repeats within a run (a slider with fewer positions
than ``--changes``, the pendulum's e with 21, gives all it has). The process is warmed first as ``serve.py`` warms a replica
before it listens (every derivation, and what ``WARM`` lists, e.g. the ladder's every slider
angle), so the numbers are a warm server's. Prints a Markdown table. ``--revisit`` moves the
control back and forth between two values instead, so every cache answers: the page's elements'
own cost, the floor that no caching goes below.
"""
from __future__ import annotations

import argparse
import importlib
import json
import math
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from streamlit.runtime.scriptrunner import script_runner  # noqa: E402
from streamlit.testing.v1 import AppTest  # noqa: E402

from bench.controls import changes_of, lesson_control  # noqa: E402
from solvers import registry  # noqa: E402

CONTROLS = {pid: lesson_control(pid) for pid in registry.PROBLEM_IDS}  # page -> (widget key, start, kind, step)


SCRIPT_CPU: list[float] = []  # thread CPU time of each script run, taken in the script's own thread
_run_script = script_runner.ScriptRunner._run_script


def _timed_run_script(self, *args, **kwargs):
    began = time.thread_time()
    try:
        return _run_script(self, *args, **kwargs)
    finally:
        SCRIPT_CPU.append(time.thread_time() - began)


def widget(at, key, kind):
    return at.slider(key=key) if kind == "slider" else at.number_input(key=key)


def paired_changes(path: Path, key: str, kind: str, values: list[float]) -> tuple[float, float, float, float, float]:
    """Alternate a change on the page with a change on the empty page, so that drift on a shared
    machine hits both alike; returns (page median, empty median, median of the paired ratios,
    page's and empty page's median script CPU). The script's CPU time (its thread's, so waiting
    for a core or for the interpreter's lock is not in it) is what the page itself costs; the wall
    time also carries the machine's queueing. It is NaN unless ``main`` installed the timer."""
    page = AppTest.from_file(str(path), default_timeout=120).run()
    empty = AppTest.from_file(str(ROOT / "bench" / "empty_page.py"), default_timeout=120).run()
    page_times, empty_times, page_cpu, empty_cpu = [], [], [], []
    changes = len(values)
    for i, value in enumerate(values, start=1):
        w = widget(page, key, kind)
        SCRIPT_CPU.clear()
        began = time.perf_counter()
        w.set_value(value).run()
        page_times.append(time.perf_counter() - began)
        page_cpu.append(sum(SCRIPT_CPU) if SCRIPT_CPU else math.nan)
        assert not page.exception, page.exception
        assert not page.error, f"{path.stem} refused {value}: {page.error[0].value}"  # a refusal is not a change
        e = empty.slider(key="x")
        SCRIPT_CPU.clear()
        began = time.perf_counter()
        e.set_value(round(0.9 - 0.5 * i / changes, 6)).run()
        empty_times.append(time.perf_counter() - began)
        empty_cpu.append(sum(SCRIPT_CPU) if SCRIPT_CPU else math.nan)
    ratios = [p / e for p, e in zip(page_times, empty_times)]
    return (statistics.median(page_times), statistics.median(empty_times), statistics.median(ratios),
            statistics.median(page_cpu), statistics.median(empty_cpu))


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--changes", type=int, default=30)
    parser.add_argument("--json", type=Path, help="also write {page: ratio} here")
    parser.add_argument("--no-figures", action="store_true", help="leave out the figures' sizes")
    parser.add_argument("--pages", nargs="*", default=list(CONTROLS), help="these pages only (default: all)")
    parser.add_argument("--revisit", action="store_true",
                        help="alternate between two values of the control, so that after the first two changes every "
                             "cache answers: what the page's elements cost a run with nothing to compute")
    args = parser.parse_args()
    from serve import warm
    print(f"warmed as serve.py does in {warm():.1f} s\n")
    script_runner.ScriptRunner._run_script = _timed_run_script
    print("| page | median server time per change | empty page, same run | × empty page (median of pairs) "
          "| script CPU per change: page / empty (×) |")
    print("|---|---|---|---|---|")
    ratios = {}
    for pid in args.pages:
        key, _, kind, _ = CONTROLS[pid]
        values = (changes_of(pid, 2) * args.changes)[2:args.changes + 2] if args.revisit else changes_of(pid, args.changes)
        if args.revisit:  # both values seen once, untimed, so every timed change is a cache's answer
            paired_changes(ROOT / "app_pages" / f"{pid}.py", key, kind, changes_of(pid, 2))
        page, empty, ratio, page_cpu, empty_cpu = paired_changes(ROOT / "app_pages" / f"{pid}.py", key, kind, values)
        ratios[pid] = ratio
        print(f"| {pid} | {page * 1000:.1f} ms | {empty * 1000:.1f} ms | {ratio:.2f} "
              f"| {page_cpu * 1000:.1f} / {empty_cpu * 1000:.1f} ms ({page_cpu / empty_cpu:.1f}) |", flush=True)
    print(f"\nworst ratio: {max(ratios.values()):.2f}")
    if args.json:
        args.json.write_text(json.dumps(ratios, indent=1))
    if args.no_figures:
        return
    print("\n| figure | frames | JSON size |\n|---|---|---|")
    for pid in args.pages:
        solution = importlib.import_module(f"solvers.{pid}").solve()
        for fig in importlib.import_module(f"viz.{pid}").figures(solution):
            print(f"| {pid}: {fig.key} | {len(fig.spec['animation']['times']) if 'animation' in fig.spec else 0} | {len(fig.json_bytes()) / 1024:.0f} KB |")


if __name__ == "__main__":
    main()
