"""Where a dragged lesson slider's frames go in the browser: one drag (40 moves, as
bench/live_drag.py drags; a number box typed in, about 40 keystrokes) traced in Chromium, the renderer main thread's time by event, and the
script's by function and file.

    python bench/trace_drag.py [PAGE]      (default pendulum_rebound)
"""
import collections
import json
import sys
import tempfile
from pathlib import Path
sys.path.insert(0, str(Path(__file__).resolve().parent.parent))
from playwright.sync_api import sync_playwright
from scripts.live_app import running_app, launch_browser, wait_until_idle
from edge.streamlit_dom import keyed
from bench.controls import lesson_control
from bench.live_drag import drag_slider, slider_steps, type_box
pid = sys.argv[1] if len(sys.argv) > 1 else "pendulum_rebound"
TRACE = Path(tempfile.gettempdir()) / f"dl-drag-{pid}.trace.json"
with running_app() as url, sync_playwright() as pw:
    b = launch_browser(pw)
    page = b.new_page(viewport={"width": 1400, "height": 1000})
    page.goto(f"{url}/{pid}"); wait_until_idle(page); page.locator(".dl-answers table").first.wait_for()
    page.wait_for_timeout(1000)
    key, _, kind, _ = lesson_control(pid)
    control = page.locator(keyed(key))
    b.start_tracing(page=page, path=str(TRACE), categories=["devtools.timeline", "disabled-by-default-devtools.timeline", "v8.execute", "blink.user_timing"])
    if kind == "slider":
        drag_slider(page, control.locator("[data-orientation='horizontal'][style*='position: relative']").bounding_box(), 40, *slider_steps(control))
    else:  # a number box, typed in as bench/live_drag.py types
        type_box(control.locator("input"), 40)
    b.stop_tracing()
    page.mouse.up()
    b.close()
events = json.load(open(str(TRACE)))
events = events["traceEvents"] if isinstance(events, dict) else events
# the renderer's main thread: the thread named CrRendererMain in the busiest renderer
names = {(e["pid"], e["tid"]): e["args"]["name"] for e in events if e.get("ph") == "M" and e.get("name") == "thread_name"}
main = [k for k, v in names.items() if v == "CrRendererMain"]
by = collections.Counter(); span = [1e30, 0]
for e in events:
    if (e.get("pid"), e.get("tid")) in main and e.get("ph") == "X" and "dur" in e:
        by[e["name"]] += e["dur"] / 1000
        span[0] = min(span[0], e["ts"]); span[1] = max(span[1], e["ts"] + e["dur"])
print(f"{pid}: traced {(span[1]-span[0])/1000:.0f} ms of the main thread's timeline")
for k, v in by.most_common(18):
    print(f"  {v:8.1f} ms  {k}")
by_script = collections.Counter()
for e in events:
    if (e.get("pid"), e.get("tid")) in main and e.get("ph") == "X" and e.get("name") == "FunctionCall":
        d = e.get("args", {}).get("data", {})
        by_script[f"{(d.get('url') or '').split('/')[-1][:40]} {d.get('functionName') or ''}"] += e["dur"] / 1000
print("script (FunctionCall) by file and function:")
for k, v in by_script.most_common(8):
    print(f"  {v:8.1f} ms  {k}")
print(f"(trace: {TRACE})")
