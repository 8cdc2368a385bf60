"""`make bench`: the quick benchmarks of the server's share, beside the last recorded numbers.

    python bench/quick.py [--record]

Runs, in about ten minutes (most of it warming a fresh server per page), the quick versions of BENCHMARKS.md §1 and §4:
- the interaction ratios (``bench/interaction.py --changes 15``: AppTest's run after a change of each
  page's lesson control, against the empty one-slider page interleaved in the same process);
- one change as the browser sends it (``bench/change_cost.py --changes 25``: a real server, each change
  of the lesson control with its fragment's id, against the empty page's on the same server code;
  the wall time per change);
- one change's bytes on the wire (the same run of ``change_cost.py``: the median, the websocket compressed);
- a 50-session lecture on one process (``bench/lecture_load.py --sessions 50 --join 10 --changes 3
  --pause 2 3 --processes 1``: interaction p95 against the empty page's, run beside it), and the same
  lecture with each session at its own values (``--spread``: no cache answers for another session);
and prints each ratio beside the one recorded in ``bench/recorded.json`` (which BENCHMARKS.md quotes),
so a regression shows in the next commit's numbers. ``--record`` writes this run's ratios there.
Not part of ``make test``.
"""
from __future__ import annotations

import argparse
import json
import subprocess
import sys
import tempfile
from datetime import datetime, timezone
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
RECORDED = ROOT / "bench" / "recorded.json"
INTERACTION = ["--changes", "15", "--no-figures"]
CHANGE = ["--changes", "25"]
LECTURE = ["--sessions", "50", "--join", "10", "--changes", "3", "--pause", "2", "3", "--processes", "1"]


def run(script: str, args: list[str], out: Path) -> dict:
    subprocess.run([sys.executable, str(ROOT / "bench" / script), *args, "--json", str(out)], cwd=ROOT, check=True,
                   stdout=sys.stderr)
    return json.loads(out.read_text())


def measure() -> dict:
    with tempfile.TemporaryDirectory() as tmp:
        interaction = run("interaction.py", INTERACTION, Path(tmp) / "interaction.json")
        change = run("change_cost.py", CHANGE, Path(tmp) / "change.json")
        lecture = run("lecture_load.py", LECTURE, Path(tmp) / "lecture.json")["1"]
        spread = run("lecture_load.py", [*LECTURE, "--spread"], Path(tmp) / "spread.json")["1"]
    return {"interaction": {page: round(ratio, 2) for page, ratio in interaction.items()},
            "change": {row["page"]: round(row["wall x empty"], 2) for row in change},
            "change_kb": {row["page"]: round(row["KB on the wire"], 1) for row in change},
            "lecture": {page: round(row["p95 x empty"], 2) for page, row in lecture.items()
                        if not page.startswith("empty page")},
            "lecture_spread": {page: round(row["p95 x empty"], 2) for page, row in spread.items()
                               if not page.startswith("empty page")},
            "lecture_errors": sum(row["errors"] for row in (*lecture.values(), *spread.values()))}


def cell(value: float | None) -> str:
    return "–" if value is None else f"{value:.2f}"


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--record", action="store_true", help=f"write this run's ratios to {RECORDED.name}")
    args = parser.parse_args()
    recorded = json.loads(RECORDED.read_text()) if RECORDED.exists() else {}
    now = measure()
    print(f"\nRatios to the empty page in the same run, and a change's KB on the wire (recorded: "
          f"{recorded.get('date', 'none')}, {recorded.get('commit', '')}). Targets: a run ≤ 3, lecture p95 ≤ 4, "
          "a change ≤ 8 KB.\n")
    columns = (("interaction", "AppTest run × empty"), ("change", "change as sent × empty"),
               ("change_kb", "change KB on the wire"), ("lecture", "50-session lecture p95 × empty"),
               ("lecture_spread", "the same, each its own values"))
    print("| page | " + " | ".join(f"{title} | recorded" for _, title in columns) + " |")
    print("|---|" + "---|---|" * len(columns))
    for page in now["interaction"]:
        print(f"| {page} | " + " | ".join(f"{cell(now[key].get(page))} | {cell(recorded.get(key, {}).get(page))}"
                                         for key, _ in columns) + " |")
    print(f"\nlecture errors: {now['lecture_errors']} (recorded: {recorded.get('lecture_errors', '–')})")
    if args.record:
        commit = subprocess.run(["git", "rev-parse", "--short", "HEAD"], cwd=ROOT, capture_output=True,
                                text=True).stdout.strip()
        RECORDED.write_text(json.dumps({"date": datetime.now(timezone.utc).strftime("%Y-%m-%d %H:%M UTC"),
                                        "commit": commit, **now}, indent=1) + "\n")
        print(f"recorded in {RECORDED.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
