"""Benchmark 2: the first render of each page in a fresh process (imports, the page's sympy
derivation, solve, figures), with AppTest; and the same page's second render in that process.

    python bench/cold_start.py
"""
from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from solvers import registry  # noqa: E402

PAGES = list(registry.PROBLEM_IDS)
CODE = """
import json, time
t0 = time.perf_counter()
from streamlit.testing.v1 import AppTest
t1 = time.perf_counter()
at = AppTest.from_file({path!r}, default_timeout=300).run()
t2 = time.perf_counter()
at.run()
t3 = time.perf_counter()
assert not at.exception
print(json.dumps({{"imports": t1 - t0, "first": t2 - t1, "second": t3 - t2}}))
"""


def main() -> None:
    print("| page | process start to first render | first render | second render |\n|---|---|---|---|")
    for page in PAGES:
        out = subprocess.run([sys.executable, "-c", CODE.format(path=str(ROOT / "app_pages" / f"{page}.py"))],
                             cwd=ROOT, capture_output=True, text=True, check=True, timeout=300)
        t = json.loads(out.stdout.strip().splitlines()[-1])
        print(f"| {page} | {(t['imports'] + t['first']):.2f} s | {t['first']:.2f} s | {t['second'] * 1000:.0f} ms |")


if __name__ == "__main__":
    main()
