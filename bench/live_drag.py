"""Live dragging (issue 27): from an input event to the next painted frame that shows the new values,
on each page's first lesson control, against a bare page whose drag updates one number.

For each problem, Chromium opens its page (Study, 1400×1000), installs a probe, and moves the first
number of ``ABOUT.primary`` across its range: a slider by the mouse held down (one move per step),
a number box by typing (each keystroke an input event). The probe takes each event's timeStamp and
the time of the first task after the next animation frame in which the answers table's text changed
(the frame that paints it). The baseline is a plain HTML page whose range input writes its value
into one element on the next animation frame, dragged the same way. Also counted: the server runs
while the control moves (they should be none) and after the release (at most one).

    flock /tmp/dl-browser.lock .venv/bin/python bench/live_drag.py [--moves 60] [--pages disk_wall ...]
"""
from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from playwright.sync_api import sync_playwright  # noqa: E402

from scripts.live_app import launch_browser, running_app, wait_until_idle  # noqa: E402
from bench.controls import lesson_control  # noqa: E402
from ui.catalog import PROBLEMS  # noqa: E402

# Each input event's time, and the first task after the next frame in which ``watched`` changed text.
PROBE = """(watched) => {
  window.__lat = []; window.__runs = 0;
  const app = document.querySelector("[data-testid='stApp']");
  if (app) new MutationObserver((ms) => { for (const m of ms) if (m.oldValue === 'running') window.__runs++; })
    .observe(app, {attributes: true, attributeOldValue: true, attributeFilter: ['data-test-script-state']});
  const text = () => (document.querySelector(watched) || {}).textContent;
  const seen = (t0, before, tries) => requestAnimationFrame(() => setTimeout(() => {
    if (text() !== before) window.__lat.push(performance.now() - t0);
    else if (tries < 10) seen(t0, before, tries + 1);
  }, 0));
  for (const type of ['pointermove', 'keydown'])
    window.addEventListener(type, (e) => { if (type === 'pointermove' && !e.buttons) return; seen(e.timeStamp, text(), 0); }, true);
}"""

DRAWS = "performance.getEntriesByName('dl-live-draw').map((e) => e.duration)"  # live.js's own time per frame
BARE = """<!doctype html><html><body style="font-family: sans-serif; padding: 40px">
<p>value: <strong id="out">50</strong></p>
<input id="slider" type="range" min="0" max="100" step="1" value="50" style="width: 600px">
<script>
const slider = document.getElementById('slider'), out = document.getElementById('out');
let frame = 0;
slider.addEventListener('input', () => { if (!frame) frame = requestAnimationFrame(() => { frame = 0; out.textContent = slider.value; }); });
</script></body></html>"""


def p90(values: list[float]) -> float:
    return statistics.quantiles(values, n=10)[-1] if len(values) >= 10 else float("nan")


def drag_slider(page, track: dict, moves: int) -> None:
    y = track["y"] + track["height"] / 2
    x = lambda f: track["x"] + f * track["width"]  # noqa: E731
    page.mouse.move(x(0.5), y)
    page.mouse.down()
    for i in range(moves):  # across the range and back
        f = 0.5 + 0.45 * (1 - abs(2 * i / moves - 1)) * (1 if i < moves / 2 else -1)
        page.mouse.move(x(f), y)
        page.wait_for_timeout(20)


def bare(browser, moves: int) -> list[float]:
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.set_content(BARE)
    page.evaluate(PROBE, "#out")
    drag_slider(page, page.locator("#slider").bounding_box(), moves)
    page.mouse.up()
    page.wait_for_timeout(300)
    lat = page.evaluate("window.__lat")
    page.close()
    return lat


def live_page(browser, url: str, problem, moves: int) -> dict:
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    page.goto(f"{url}/{problem.id}")
    wait_until_idle(page)
    page.locator(".dl-answers table").first.wait_for()
    key, _, kind, _ = lesson_control(problem.id)  # the control every benchmark moves
    control = page.locator(f".st-key-{key}")
    control.scroll_into_view_if_needed()
    page.evaluate(PROBE, ".dl-answers table")  # the answers (the headline may not depend on this control)
    if kind == "slider":
        track = control.locator("[data-orientation='horizontal'][style*='position: relative']").bounding_box()
        drag_slider(page, track, moves)
        during = page.evaluate("window.__runs")
        draws = page.evaluate(DRAWS)  # before the run after release clears them
        page.mouse.up()
    else:  # a number box: typed, digit by digit (each keystroke one input event), not committed
        box = control.locator("input")
        box.click()
        start = float(box.input_value())
        for i in range(moves // 4):
            box.press("Control+a")
            box.type(f"{start * (1 + 0.01 * (i + 1)):.4g}", delay=20)
        during = page.evaluate("window.__runs")
        draws = page.evaluate(DRAWS)
        box.press("Enter")
    page.wait_for_function("() => window.__runs >= 1", timeout=30_000)
    wait_until_idle(page)
    page.wait_for_timeout(500)
    result = {"draw_ms": statistics.median(draws) if draws else float("nan"), "control": key.rsplit("__", 1)[-1],
              "kind": "slider" if kind == "slider" else "box", "lat": page.evaluate("window.__lat"),
              "runs_while_moving": during, "runs_after_release": page.evaluate("window.__runs") - during}
    page.close()
    return result


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--moves", type=int, default=60)
    parser.add_argument("--pages", nargs="*", default=[p.id for p in PROBLEMS])
    args = parser.parse_args()
    rows = {}
    with running_app() as url, sync_playwright() as pw:
        browser = launch_browser(pw)
        base = bare(browser, args.moves)
        rows["bare page"] = {"p90": p90(base), "median": statistics.median(base), "n": len(base)}
        for problem in PROBLEMS:
            if problem.id not in args.pages:
                continue
            r = live_page(browser, url, problem, args.moves)
            rows[problem.id] = {"control": r["control"], "kind": r["kind"], "p90": p90(r["lat"]),
                                "median": statistics.median(r["lat"]) if r["lat"] else float("nan"), "n": len(r["lat"]),
                                "ratio_p90": p90(r["lat"]) / rows["bare page"]["p90"],
                                "draw_median": r["draw_ms"], "runs_while_moving": r["runs_while_moving"], "runs_after_release": r["runs_after_release"]}
        browser.close()
    print(json.dumps(rows, indent=1))
    print(f"\n| page | control | events | median (ms) | p90 (ms) | p90 / bare | live.js's draw, median (ms) | runs while moving | runs after release |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name, r in rows.items():
        print(f"| {name} | {r.get('control', '')} {r.get('kind', '')} | {r['n']} | {r['median']:.1f} | {r['p90']:.1f} | "
              f"{r.get('ratio_p90', 1.0):.2f} | {r.get('draw_median', float('nan')):.2f} | {r.get('runs_while_moving', '')} | {r.get('runs_after_release', '')} |")


if __name__ == "__main__":
    main()
