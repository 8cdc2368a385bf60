"""A new state's own work, outside Streamlit: the lesson control moved to values not seen before, and for each
the solve, the figures (the stage's frames left to the browser, as on the lesson page), their JSON, the live
view's data, the derivation's data (its diagrams drawn) and the answers' data, each timed alone.

    python bench/new_state.py [PAGE ...] [--changes 25]

Prints the median of each part and their sum per page: what a change costs the server before Streamlit
runs its elements (bench/change_cost.py measures the whole change; bench/profile_run.py splits it under cProfile).
"""
from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))


def measure(pid: str, changes: int) -> dict[str, float]:
    from bench.controls import changes_of, first_number
    from solvers import units
    from solvers.catalog import BY_ID
    from ui import live, page, results
    from viz.catalog import drawings

    problem = BY_ID[pid]
    solver = problem.solver
    control = first_number(pid)  # the lesson control bench/change_cost.py moves
    name = control.name
    base = solver.solve().params
    spent: dict[str, list[float]] = {}

    def timed(part, work):
        start = time.perf_counter()
        out = work()
        spent.setdefault(part, []).append(time.perf_counter() - start)
        return out

    for shown in changes_of(pid, changes):
        value = units.to_si(shown, control.dimension)
        value += 1e-9 * (base[name] - value)  # off the slider's grid (no state warmed at start), inside its range
        solution = timed("solve", lambda: solver.solve(**{**base, name: value}))
        figures = timed("figures", lambda: drawings(pid).figures(solution, "si", in_browser=True))
        timed("figures' JSON", lambda: [f.json_bytes() for f in figures])
        answers = problem.answers_of(solution)
        timed("live view", lambda: live.payload(problem, solution, answers, "si", figures[0]))
        timed("derivation and diagrams", lambda: page._derivation_data(solver, solution))
        timed("answers", lambda: results.answers_data(solution, answers, "si", None))
    return {part: statistics.median(times) * 1000 for part, times in spent.items()}


def main() -> None:
    from solvers import registry
    parser = argparse.ArgumentParser()
    parser.add_argument("pages", nargs="*", default=list(registry.PROBLEM_IDS))
    parser.add_argument("--changes", type=int, default=25)
    args = parser.parse_args()
    from serve import warm
    warm()
    for pid in args.pages:
        parts = measure(pid, args.changes)
        print(f"{pid}: {sum(parts.values()):.2f} ms  (" + ", ".join(f"{k} {v:.2f}" for k, v in parts.items()) + ")")


if __name__ == "__main__":
    main()
