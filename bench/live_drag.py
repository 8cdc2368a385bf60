"""Live dragging (issue 27): from an input event to the next painted frame that shows the new values,
on each page's first lesson control, against a bare page whose control updates one number.

For each problem, Chromium opens its page (Study, 1400×1000), installs a probe, and moves the first
number of ``ABOUT.primary`` across its range: a slider by the mouse held down (each move a whole
number of steps, so each gives a new value), a number box by typing (each keystroke an input event;
those that leave a new number in the box are counted). The probe takes each such event's timeStamp
and the time of the first task after the next animation frame in which the answers table's text
changed (the frame that paints it). The baseline is a plain HTML page whose range input (and text
box) writes its value into one element on the next animation frame, dragged (typed in) the same
way: a slider is compared with the dragged one, a box with the typed one. Also counted: the server
runs the page asks for (its messages on the app's websocket) while the control moves (they should
be none) and after the release (one).

    flock /tmp/dl-browser.lock .venv/bin/python bench/live_drag.py [--moves 60] [--pages disk_wall ...]
"""
from __future__ import annotations

import argparse
import json
import math
import statistics
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from playwright.sync_api import sync_playwright  # noqa: E402

from scripts.live_app import launch_browser, running_app, wait_until_idle  # noqa: E402
from edge.streamlit_dom import keyed  # noqa: E402
from bench.controls import lesson_control  # noqa: E402
from solvers.catalog import PROBLEMS  # noqa: E402

# Each input event that gives the control a new value: its time, and the first task after the next
# animation frame in which ``watched`` changed text. A pointer move of the drag always does (the drag
# moves a whole number of steps at a time); a typed character does when the box's number is a new one
# ("2.0" after "2." after "2" is the same number, nothing to redraw: not counted, else its wait would
# run on to the next number's frame).
PROBE = """(watched) => {
  window.__lat = [];
  const text = () => (document.querySelector(watched) || {}).textContent;
  // the first task after the frame: a user-blocking one (a plain task would wait behind the page's
  // own tasks queued before it, e.g. React's render of the slider after the frame that showed the values)
  const after = (task) => window.scheduler && scheduler.postTask ? scheduler.postTask(task, {priority: 'user-blocking'}) : setTimeout(task, 0);
  const seen = (t0, before, tries) => requestAnimationFrame(() => after(() => {
    if (text() !== before) window.__lat.push(performance.now() - t0);
    else if (tries < 10) seen(t0, before, tries + 1);
  }));
  let typed = NaN;  // the number in the box being typed in
  const number = (box) => box.value.trim() === '' ? NaN : Number(box.value);
  window.addEventListener('focusin', (e) => { if (e.target.value !== undefined) typed = number(e.target); }, true);
  window.addEventListener('pointermove', (e) => { if (e.buttons && e.isTrusted) seen(e.timeStamp, text(), 0); }, true);
  window.addEventListener('input', (e) => {
    if (e.target.type === 'range') return;  // (the bare page's slider: its pointer moves are counted)
    const x = number(e.target);
    if (Number.isFinite(x) && x !== typed) { typed = x; seen(e.timeStamp, text(), 0); }
  }, true);
}"""

DRAWS = "performance.getEntriesByName('dl-live-draw').map((e) => e.duration)"  # live.js's own time per frame
BARE = """<!doctype html><html><body style="font-family: sans-serif; padding: 40px">
<p>value: <strong id="out">50</strong></p>
<input id="slider" type="range" min="0" max="100" step="1" value="50" style="width: 600px">
<p>number: <strong id="typed">2</strong></p>
<input id="box" type="text" value="2">
<script>
const slider = document.getElementById('slider'), out = document.getElementById('out');
const box = document.getElementById('box'), typed = document.getElementById('typed');
let frame = 0;
slider.addEventListener('input', () => { if (!frame) frame = requestAnimationFrame(() => { frame = 0; out.textContent = slider.value; }); });
box.addEventListener('input', () => { if (!frame) frame = requestAnimationFrame(() => { frame = 0; typed.textContent = String(Number(box.value)); }); });
</script></body></html>"""


def p90(values: list[float]) -> float:
    return statistics.quantiles(values, n=10)[-1] if len(values) >= 10 else float("nan")


def drag_slider(page, track: dict, moves: int, steps: int = 100, at: int | None = None) -> None:
    """Held down on ``track`` (a slider of ``steps`` steps) at step ``at`` (the thumb's place; the
    middle if None), then ``moves`` moves that each change the value: a whole number of steps at a
    time (at least one, and 2.25 % of the track, the pace of a quick drag), to and fro within a
    quarter of the range either side of where it started (a student exploring around the textbook's
    value), inside the middle 90 % of the range; released off its start."""
    y = track["y"] + track["height"] / 2
    per_move = max(1, math.ceil(0.0225 * steps))
    at = round(steps / 2) if at is None else at
    low, high, way = max(math.ceil(0.05 * steps), at - steps // 4), min(math.floor(0.95 * steps), at + steps // 4), 1
    at = start = min(max(at, low), high)
    page.mouse.move(track["x"] + at / steps * track["width"], y)
    page.mouse.down()
    for _ in range(moves):
        if not low <= at + way * per_move <= high:
            way = -way
        at += way * per_move
        page.mouse.move(track["x"] + at / steps * track["width"], y)
        page.wait_for_timeout(20)
    if at == start:  # released elsewhere, so the release has a new value to run (counted)
        page.mouse.move(track["x"] + (at + (per_move if at + per_move <= high else -per_move)) / steps * track["width"], y)
        page.wait_for_timeout(20)


def type_box(box, keystrokes: int) -> None:
    """Values 1 %, 2 %, … above the box's own typed into it digit by digit (each keystroke an input
    event), about ``keystrokes`` keystrokes in all, not committed."""
    box.click()
    start = float(box.input_value())
    for i in range(keystrokes // 4):
        box.press("Control+a")
        box.type(f"{start * (1 + 0.01 * (i + 1)):.4g}", delay=20)


def slider_steps(control) -> tuple[int, int]:
    """How many steps a Streamlit slider's range holds, and the step its thumb is at (its range
    input's min, max, step and value)."""
    thumb = control.locator("input[type='range']")
    low, high, step = (float(thumb.get_attribute(a)) for a in ("min", "max", "step"))
    return round((high - low) / step), round((float(thumb.input_value()) - low) / step)


def bare(browser, moves: int) -> dict[str, list[float]]:
    """The bare page's latencies: its slider dragged, its box typed in, as the app's controls are."""
    lat = {}
    for kind, watched in (("slider", "#out"), ("box", "#typed")):
        page = browser.new_page(viewport={"width": 1400, "height": 1000})
        page.set_content(BARE)
        page.evaluate(PROBE, watched)
        if kind == "slider":
            drag_slider(page, page.locator("#slider").bounding_box(), moves)
            page.mouse.up()
        else:
            type_box(page.locator("#box"), moves)
        page.wait_for_timeout(300)
        lat[kind] = page.evaluate("window.__lat")
        page.close()
    return lat


def live_page(browser, url: str, problem, moves: int) -> dict:
    page = browser.new_page(viewport={"width": 1400, "height": 1000})
    # The runs the page asks for: each message it sends on the app's websocket after it has loaded
    # is a rerun request (a control committed). Streamlit's script-state attribute, watched in the page,
    # can miss a fragment's run that starts and ends within one render.
    sent = []
    page.on("websocket", lambda ws: ws.on("framesent", lambda payload: sent.append(payload)))
    page.goto(f"{url}/{problem.id}")
    wait_until_idle(page)
    page.locator(".dl-answers table").first.wait_for()
    key, _, kind, _ = lesson_control(problem.id)  # the control every benchmark moves
    control = page.locator(keyed(key))
    control.scroll_into_view_if_needed()
    page.evaluate(PROBE, ".dl-answers table")  # the answers (the headline may not depend on this control)
    loaded = len(sent)
    if kind == "slider":
        track = control.locator("[data-orientation='horizontal'][style*='position: relative']").bounding_box()
        drag_slider(page, track, moves, *slider_steps(control))
        during = len(sent) - loaded
        draws = page.evaluate(DRAWS)  # before the run after release clears them
        page.mouse.up()
    else:  # a number box: typed, digit by digit (each keystroke one input event), not committed
        box = control.locator("input")
        type_box(box, moves)
        during = len(sent) - loaded
        draws = page.evaluate(DRAWS)
        box.press("Enter")
    page.wait_for_function("() => !document.querySelector('.dl-live-value')", timeout=30_000)  # the run's values
    wait_until_idle(page)
    page.wait_for_timeout(500)
    result = {"draw_ms": statistics.median(draws) if draws else float("nan"), "control": key.rsplit("__", 1)[-1],
              "kind": kind if kind == "slider" else "box", "lat": page.evaluate("window.__lat"),
              "runs_while_moving": during, "runs_after_release": len(sent) - loaded - during}
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
        for kind, lat in base.items():
            rows[f"bare page ({kind})"] = {"control": "range input" if kind == "slider" else "text box", "kind": kind,
                                           "p90": p90(lat), "median": statistics.median(lat), "n": len(lat)}
        for problem in PROBLEMS:
            if problem.id not in args.pages:
                continue
            print(problem.id, file=sys.stderr, flush=True)  # (where a run that never ends stopped)
            r = live_page(browser, url, problem, args.moves)
            bare_p90 = rows[f"bare page ({r['kind']})"]["p90"]  # a slider against a dragged one, a box against a typed one
            rows[problem.id] = {"control": r["control"], "kind": r["kind"], "p90": p90(r["lat"]),
                                "median": statistics.median(r["lat"]) if r["lat"] else float("nan"), "n": len(r["lat"]),
                                "ratio_p90": p90(r["lat"]) / bare_p90,
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
