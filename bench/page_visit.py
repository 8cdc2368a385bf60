"""What a page visit costs the browser: a problem page opened by its address (a fresh context: Streamlit's
frontend, plotly.js and KaTeX loaded and compiled anew) against the same page reached by the navigation's
link in a page already open (tests.browser.test_browser.visit). Chromium's own counters (CDP
Performance.getMetrics: the main thread's task, script and other time) and the wall time to the drawn figure.

    .venv/bin/python bench/page_visit.py

Not a speed target: the reason the browser tests' tours go from page to page by the navigation
(docs/benchmarks-log.md, "A page visit in the browser tests"), and what loading two pages at a time gives a
2-core machine (``tour``: the same log, "third round")."""
from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from playwright.sync_api import sync_playwright  # noqa: E402

from scripts.live_app import IDLE_WATCH, launch_browser, running_server, wait_until_idle  # noqa: E402
from solvers import registry  # noqa: E402
from tests.browser.test_browser import tour, visit  # noqa: E402

KEYS = ("TaskDuration", "ScriptDuration", "TaskOtherDuration")


def metrics(cdp) -> dict:
    return {m["name"]: m["value"] for m in cdp.send("Performance.getMetrics")["metrics"] if m["name"] in KEYS}


def drawn(page, idle: bool = True) -> None:
    if idle:  # (visit waits for it itself)
        wait_until_idle(page)
    page.wait_for_function("() => document.querySelector('.dl-figure .main-svg')", timeout=60_000)


def main() -> None:
    pages = [p for p in registry.PROBLEM_IDS if p != "eulers_disk"]  # (the 3-D page loads its own bundle: apart)
    rows = {"by its address": [], "by the navigation": []}
    with running_server() as server, sync_playwright() as pw:
        browser = launch_browser(pw)
        for pid in pages:  # a fresh context each time: nothing cached
            context = browser.new_context(viewport={"width": 1400, "height": 1000})
            page = context.new_page()
            cdp = context.new_cdp_session(page)
            cdp.send("Performance.enable")
            started = time.perf_counter()
            page.goto(f"{server.url}/{pid}")
            drawn(page)
            rows["by its address"].append((time.perf_counter() - started, metrics(cdp)))
            context.close()
        context = browser.new_context(viewport={"width": 1400, "height": 1000})
        page = context.new_page()
        cdp = context.new_cdp_session(page)
        cdp.send("Performance.enable")
        page.goto(f"{server.url}/{pages[-1]}")
        drawn(page)
        for pid in pages:
            before, started = metrics(cdp), time.perf_counter()
            visit(page, server.url, pid)
            drawn(page, idle=False)
            after = metrics(cdp)
            rows["by the navigation"].append((time.perf_counter() - started, {k: after[k] - before[k] for k in KEYS}))
        # The pages by their addresses in one context (its cache warm), one after another and two at a time.
        context = browser.new_context(viewport={"width": 1400, "height": 1000})
        context.add_init_script(IDLE_WATCH)
        urls = [f"{server.url}/{pid}" for pid in pages]
        tours = {}
        for how in ("one after another", "two at a time (tour)", "one after another", "two at a time (tour)"):
            started = time.perf_counter()
            if how == "one after another":
                for url in urls:
                    page = context.new_page()
                    page.goto(url)
                    drawn(page)
                    page.close()
            else:
                for page, _ in tour(context, urls):
                    drawn(page, idle=False)
            tours.setdefault(how, []).append(time.perf_counter() - started)
    print(f"{len(pages)} problem pages at 1400x1000, medians")
    print("| opened | wall to the drawn figure (s) | main thread: tasks (s) | of it script (s) | other (s) |")
    print("|---|---|---|---|---|")
    for how, samples in rows.items():
        wall = statistics.median(w for w, _ in samples)
        cells = [statistics.median(m[k] for _, m in samples) for k in KEYS]
        print(f"| {how} | {wall:.2f} | " + " | ".join(f"{c:.2f}" for c in cells) + " |")
    print(f"\nThe {len(pages)} pages by their addresses in one context, each to its drawn figure (s, two runs):")
    for how, walls in tours.items():
        print(f"- {how}: " + ", ".join(f"{w:.1f}" for w in walls))


if __name__ == "__main__":
    main()
