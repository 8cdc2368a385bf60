"""Where a page's run goes: cProfile over the script thread of AppTest's runs after a control change
(the same changes as bench/interaction.py), warmed as serve.py warms a replica.

    python bench/profile_run.py PAGE [--changes 30] [--sort tottime|cumtime] [--limit 40] [--empty]

``--empty``: profile the empty one-slider page instead, for comparison. Prints pstats' table.
"""
from __future__ import annotations

import argparse
import cProfile
import pstats
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from streamlit.runtime.scriptrunner import script_runner  # noqa: E402
from streamlit.testing.v1 import AppTest  # noqa: E402

from bench.controls import changes_of, lesson_control  # noqa: E402
from bench.interaction import widget  # noqa: E402

PROFILE = cProfile.Profile()
_ACTIVE = [False]
_run_script = script_runner.ScriptRunner._run_script


def _profiled(self, *args, **kwargs):
    """The script run, profiled in its own thread while a measured change is under way."""
    if not _ACTIVE[0]:
        return _run_script(self, *args, **kwargs)
    PROFILE.enable()
    try:
        return _run_script(self, *args, **kwargs)
    finally:
        PROFILE.disable()


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("page")
    parser.add_argument("--changes", type=int, default=30)
    parser.add_argument("--sort", default="tottime")
    parser.add_argument("--limit", type=int, default=40)
    parser.add_argument("--empty", action="store_true")
    parser.add_argument("--callers", nargs="*", help="also print who calls these functions (pstats patterns)")
    args = parser.parse_args()
    from serve import warm
    warm()
    script_runner.ScriptRunner._run_script = _profiled
    if args.empty:
        at = AppTest.from_file(str(ROOT / "bench" / "empty_page.py"), default_timeout=120).run()
        values = [round(0.9 - 0.5 * i / args.changes, 6) for i in range(1, args.changes + 1)]
        key, kind = "x", "slider"
    else:
        at = AppTest.from_file(str(ROOT / "app_pages" / f"{args.page}.py"), default_timeout=120).run()
        values = changes_of(args.page, args.changes)
        key, _, kind, _ = lesson_control(args.page)
    for value in values:
        _ACTIVE[0] = True
        widget(at, key, kind).set_value(value).run()
        _ACTIVE[0] = False
        assert not at.exception, at.exception
    stats = pstats.Stats(PROFILE)
    stats.sort_stats(args.sort).print_stats(args.limit)
    for name in args.callers or ():
        stats.print_callers(name)


if __name__ == "__main__":
    main()
