"""Where the browser tests' wall time goes: a pytest plugin that times each Playwright call made by a test
(the outermost only: a wait inside ``wait_until_idle`` counts once, as ``wait_until_idle``) and axe-core's
audits, and writes the totals by call, with counts, to ``browser-time.json`` beside the summary it prints, with the
test lines that spent the most.

    CI=true .venv/bin/python -m pytest -m served -p bench.browser_time

docs/benchmarks-log.md, "Where the browser tests' time goes", has a round of it.
"""
from __future__ import annotations

import collections
import functools
import json
import sys
import threading
import time

TOTAL: collections.Counter = collections.Counter()
CALLS: collections.Counter = collections.Counter()
SITES: collections.Counter = collections.Counter()  # (label, the test's line that made the call) -> seconds
_depth = threading.local()


def _timed(function, label: str):
    @functools.wraps(function)
    def timed(*args, **kwargs):
        depth = getattr(_depth, "n", 0)
        _depth.n = depth + 1
        started = time.monotonic()
        try:
            return function(*args, **kwargs)
        finally:
            _depth.n = depth
            if depth == 0:
                took = time.monotonic() - started
                TOTAL[label] += took
                CALLS[label] += 1
                SITES[label, _test_line()] += took
    return timed


def _test_line() -> str:
    """The innermost line of a test module (or of its helpers under tests/) on the stack."""
    frame = sys._getframe(2)
    while frame is not None:
        name = frame.f_code.co_filename
        if "/tests/" in name:
            return f"{name.rsplit('/tests/', 1)[1]}:{frame.f_lineno}"
        frame = frame.f_back
    return "?"


def _time_methods(owner, names, prefix: str) -> None:
    for name in names:
        if hasattr(owner, name):
            setattr(owner, name, _timed(getattr(owner, name), f"{prefix}.{name}"))


def pytest_configure(config):
    from playwright.sync_api._generated import Browser, BrowserContext, Keyboard, Locator, Mouse, Page

    _time_methods(Page, ("goto", "wait_for_timeout", "wait_for_function", "wait_for_selector", "wait_for_url",
                         "evaluate", "eval_on_selector_all", "screenshot", "pdf"), "page")
    _time_methods(Locator, ("click", "tap", "fill", "press", "type", "hover", "focus", "wait_for", "evaluate",
                            "evaluate_all", "inner_text", "bounding_box", "screenshot", "count"), "locator")
    _time_methods(Browser, ("new_context",), "browser")
    _time_methods(BrowserContext, ("new_page", "close"), "context")
    _time_methods(Keyboard, ("press", "type"), "keyboard")
    _time_methods(Mouse, ("move", "down", "up", "click"), "mouse")


def pytest_collection_finish(session):
    """The helpers the test modules imported by name, timed where they were imported."""
    from scripts import live_app

    helpers = {"wait_until_idle": live_app.wait_until_idle}
    where_used = sys.modules.get("tests.browser.test_where_used")
    if where_used:
        helpers["serious_violations"] = where_used.serious_violations  # axe-core
    timed = {name: _timed(function, name) for name, function in helpers.items()}
    for module in [live_app, *(m for n, m in list(sys.modules.items()) if n.startswith("tests."))]:
        for name, function in helpers.items():
            if getattr(module, name, None) is function:
                setattr(module, name, timed[name])


def pytest_terminal_summary(terminalreporter):
    rows = sorted(TOTAL.items(), key=lambda kv: -kv[1])
    with open("browser-time.json", "w") as out:
        json.dump({label: {"seconds": round(s, 2), "calls": CALLS[label]} for label, s in rows}, out, indent=1)
    terminalreporter.write_sep("=", "wall time by browser call (outermost; bench/browser_time.py)")
    for label, seconds in rows[:15]:
        terminalreporter.write_line(f"{seconds:8.1f} s {CALLS[label]:6d} calls {seconds / CALLS[label] * 1000:7.0f} ms  {label}")
    terminalreporter.write_sep("-", "where in the tests (the 15 lines that spent the most)")
    for (label, line), seconds in SITES.most_common(15):
        terminalreporter.write_line(f"{seconds:8.1f} s  {label:24s} {line}")
