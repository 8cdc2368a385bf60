"""Benchmark 5, what a student feels: the app in Debian's Chromium against an empty page, same run.

    flock /tmp/dl-browser.lock python bench/browser.py [--changes 15] [--visits 3] [--pages ...] [--frame] [--stage]

Two servers on loopback, both started by ``serve.run`` (the same settings, Nagle off): the app
(serve.py, warmed) and an empty page with one number box and one slider (bench/empty_controls.py).
For every page, alternating with the empty page so drift on the shared machine hits both alike:

- **change → redrawn**: a new value typed into the first number box of the sidebar and Enter, until
  ``plotly_afterplot`` fires on a figure (the empty page, or a value no figure depends on: until the
  first frame after the run's last message). Each change is a value not seen before, so no cache
  answers. Median and p90; the ratio is the median of the per-pair ratios.
  With ``--stage``, a change is one arrow key's step of the lesson's first stage slider (on the empty page,
  its slider; towards the end with room for every change), released: the lesson's fragment reruns, as when
  a student lets go of a slider. It is timed from the slider's commit (the page's message asking for the run: the stage's keys commit 250 ms after
  the last key is up, a pointer's release at once) to the last redraw once the run is over (the live
  pose is drawn by plotly.js too).
- **first visit / revisit**: a fresh browser context (empty cache) opens the page, then a second
  tab in the same context opens it again; time from navigation to every figure drawn (the empty
  page: its controls drawn and the script idle), and bytes over the wire (CDP Network
  ``encodedDataLength`` of every finished request; the websocket's bytes are listed apart).
- **the figures' redraw alone**: the page's figures for the same values, redrawn by Plotly.react in
  a bare page (the same plotly.js bundle, the component's unfolding of the frames): what plotly.js
  alone costs a change, as a ratio to the empty page's change; and, opened again from the cache, how
  long after navigation plotly.js has run and how long its first drawing takes.
- with ``--frame``, a third tab: the page's frame alone (bench/page_frame.py: the navigation, the
  same sidebar controls and title, no answers, figure or derivation), changed the same way, so the
  table shows what Streamlit itself costs for a page with these controls.
- **where one change goes**: one more change under a Chromium performance trace (CPU samples and
  the renderer's main thread), split into server run (websocket BackMsg sent → last ForwardMsg of
  the run received), websocket bytes, JavaScript by source (plotly.js, KaTeX, Streamlit's React
  bundle, the figure component; a built-in such as JSON.parse or a DOM call counts as the script
  that called it), style/layout and paint.
"""
from __future__ import annotations

import argparse
import base64
import http.server
import json
import statistics
import sys
import threading
from collections import defaultdict
from contextlib import ExitStack
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from scripts.live_app import launch_browser, running_app, wait_until_idle  # noqa: E402
from edge.streamlit_dom import SELECTORS, js_prelude  # noqa: E402
from solvers import registry  # noqa: E402

PAGES = list(registry.PROBLEM_IDS)
EMPTY = "empty"
FRAME = "frame"
VIEWPORT = {"width": 1400, "height": 1000}

# Installed in every document; only the top one uses it. Graphs are looked for in the page and in
# every same-origin iframe, so the benchmark does not depend on how the figure is embedded.
HELPERS = js_prelude() + """
if (window === window.top) {
  // Every websocket message the page receives, with the start of the first frame after it is handled.
  const Native = window.WebSocket;
  window.__dlMessages = [];
  window.__dlSent = [];  // when the page sent each message (a slider's commit: its run asked for)
  window.WebSocket = class extends Native {
    send(data) { window.__dlSent.push(performance.now()); return super.send(data); }
    constructor(...args) {
      super(...args);
      this.addEventListener('message', () => {
        const entry = [performance.now(), null];
        window.__dlMessages.push(entry);
        setTimeout(() => requestAnimationFrame(() => { entry[1] = performance.now(); }), 0);
      });
    }
  };
  window.__dl = {
    graphs() {
      const out = [...document.querySelectorAll('.js-plotly-plot')];
      for (const f of document.querySelectorAll('iframe')) {
        try { out.push(...f.contentDocument.querySelectorAll('.js-plotly-plot')); } catch (e) {}
      }
      return out;
    },
    idle() {
      const app = document.querySelector(DOM.app);
      return !!app && app.getAttribute(DOM.attributes.scriptState) === DOM.scriptIdle;
    },
    drawn(figures) {
      if (figures === 0) return this.idle() && document.querySelectorAll(`${DOM.app} input`).length >= 2;
      const g = this.graphs();
      return g.length >= figures && g.every(d => d._fullLayout && d.querySelector('.main-svg'));
    },
    // Resolve with ms from the next Enter key to a figure's plotly_afterplot, or, when no figure
    // redraws (the empty page, or a value the figures do not depend on: their data are unchanged
    // and the component leaves them), to the first frame after the run's last message (none for
    // 300 ms after it). The DOM's script-state attribute cannot time a fast run: React may batch
    // its start and end.
    arm(figures, key = 'Enter') {
      let t0 = null;
      this.pending = new Promise((resolve, reject) => {
        const timer = setTimeout(() => reject(new Error('no redraw within 10 s')), 10000);
        const graphs = figures > 0 ? this.graphs() : [];
        let poll = null;
        const done = (t, redrawn) => {
          clearTimeout(timer); clearInterval(poll);
          for (const g of graphs) g.removeListener('plotly_afterplot', onPlot);
          // a slider's step is timed from its commit, the run asked for (the stage's keys commit a burst
          // 250 ms after the last key is up, live.js; a pointer's release commits at once)
          const from = key === 'Enter' ? t0 : (window.__dlSent.find(s => s >= t0) ?? t0);
          performance.mark('dl-drawn'); resolve({ms: t - from, redrawn: redrawn});
        };
        // a slider's step (not Enter): the live pose is drawn by plotly too, so the change ends at the last
        // redraw once the run is over (its last message, then quiet), not at the first
        let lastPlot = null;
        const onPlot = () => {
          if (t0 === null) return;
          if (key === 'Enter') done(performance.now(), true); else lastPlot = performance.now();
        };
        window.addEventListener('keydown', function onKey(e) {
          if (e.key !== key) return;
          t0 = performance.now(); performance.mark('dl-change');
          window.removeEventListener('keydown', onKey, true);
        }, true);
        for (const g of graphs) g.on('plotly_afterplot', onPlot);
        poll = setInterval(() => {
          if (t0 === null) return;
          const after = window.__dlMessages.filter(m => m[0] > t0);
          const last = after[after.length - 1];
          if (last && last[1] !== null && performance.now() - last[0] > 300 && this.idle())
            done(Math.max(last[1], lastPlot || 0), lastPlot !== null);
        }, 20);
      });
    },
  };
}
"""


def figure_count(page_id: str) -> int:
    if page_id == EMPTY:
        return 0
    import importlib

    solver = importlib.import_module(f"solvers.{page_id}")
    return len(importlib.import_module(f"viz.{page_id}").figures(solver.solve()))


class Wire:
    """Bytes over the wire for one tab, from CDP's Network domain."""

    def __init__(self, page):
        self.http = 0
        self.ws_frames: list[tuple[str, float, int]] = []  # (direction, timestamp s, bytes)
        cdp = page.context.new_cdp_session(page)
        cdp.on("Network.loadingFinished", self._finished)
        cdp.on("Network.webSocketFrameReceived", lambda e: self._frame("in", e))
        cdp.on("Network.webSocketFrameSent", lambda e: self._frame("out", e))
        cdp.send("Network.enable")

    def _finished(self, event):
        self.http += int(event.get("encodedDataLength", 0))

    def _frame(self, direction, event):
        r = event["response"]
        size = len(base64.b64decode(r["payloadData"])) if r.get("opcode") == 2 else len(r["payloadData"])
        self.ws_frames.append((direction, event["timestamp"], size))

    @property
    def ws_in(self) -> int:
        return sum(n for d, _, n in self.ws_frames if d == "in")


def visit(page, url: str, figures: int) -> tuple[float, Wire]:
    wire = Wire(page)
    page.goto(url, wait_until="commit")
    drawn_at = page.wait_for_function(f"() => __dl.drawn({figures}) ? performance.now() : false",
                                      polling="raf", timeout=60_000).json_value()
    page.wait_for_timeout(500)  # late requests (fonts, the second figure's assets) still count
    return drawn_at, wire


def first_box(page):
    boxes = page.locator(f"{SELECTORS['sidebar']} {SELECTORS['numberInput']} input, "
                         f"{SELECTORS['main']} {SELECTORS['numberInput']} input")
    if boxes.count() == 0:
        page.locator(SELECTORS["sidebar"]).get_by_text("More parameters", exact=True).click()
        boxes.first.wait_for(timeout=30_000)
        wait_until_idle(page)
    return boxes.first


def first_slider(page):
    """The lesson's first slider on the stage (the empty page: its slider)."""
    sliders = page.locator(f"{SELECTORS['stageControls']} input[type='range']")
    return sliders.first if sliders.count() else page.locator("input[type='range']").first


def way_with_room(slider, steps: int) -> str:
    """ArrowRight where the slider has ``steps`` steps of room above its value, else ArrowLeft (each step a new
    value: none stops at an end)."""
    value, top, step = slider.evaluate("(s) => [Number(s.value), Number(s.max), Number(s.step) || 1]")
    return "ArrowRight" if (top - value) / step >= steps else "ArrowLeft"


def change(page, box, value: float | str, figures: int) -> dict:
    """``box`` given ``value`` and Enter; a slider (``value`` its key, ArrowRight or ArrowLeft): one step,
    released (a new value each time)."""
    page.bring_to_front()  # a background tab's frames are throttled
    key = value if isinstance(value, str) else "Enter"
    page.evaluate("([figures, key]) => __dl.arm(figures, key)", [figures, key])
    if isinstance(value, str):
        box.focus()
        page.wait_for_timeout(50)
        box.press(key)
    else:
        box.fill(f"{value:.6g}")
        page.wait_for_timeout(50)
        box.press("Enter")
    try:
        ms = page.evaluate("__dl.pending")
    except Exception:
        print(f"no redraw on {page.url} for {value if isinstance(value, str) else f'{value:.6g}'}", flush=True)
        raise
    wait_until_quiet(page)
    return ms


def wait_until_quiet(page):
    page.wait_for_function("() => __dl.idle()", timeout=30_000)
    page.wait_for_timeout(150)


def percentile(values, q):
    ordered = sorted(values)
    return ordered[min(len(ordered) - 1, round(q * (len(ordered) - 1)))]


# ---------------------------------------------------------------- where one change goes (a trace)
CATEGORIES = ["devtools.timeline", "disabled-by-default-devtools.timeline", "blink.user_timing",
              "v8.execute", "disabled-by-default-v8.cpu_profiler"]


def js_source(frame: dict) -> str:
    url, name = frame.get("url", ""), frame.get("functionName", "")
    if name == "(garbage collector)":
        return "garbage collection"
    if name in ("(idle)", "(root)"):
        return ""
    if name == "(program)":
        return "browser internals"
    if "plotly" in url:
        return "plotly.js"
    if "katex" in url:
        return "KaTeX"
    if "/component/" in url or "/bidi-components/" in url or "dynamics_lab" in url:
        return "figure component"
    if "/static/js/" in url:
        return "Streamlit (React)"
    return "other script"


def attributed(key: tuple, node: int, nodes: dict, parents: dict) -> str:
    """A sample's source: its own script's, or for a built-in (JSON.parse, a DOM call; no URL) the
    script that called it, so plotly.js's or React's DOM work counts as theirs."""
    source = js_source(nodes.get((key, node), {}))
    seen = 0
    while source == "other script" and (key, node) in parents and seen < 200:
        node, seen = parents[(key, node)], seen + 1
        caller = js_source(nodes.get((key, node), {}))
        if caller not in ("other script", ""):
            return caller
    return source


def breakdown(trace: dict, frames: list[tuple[str, float, int]], ms: float) -> dict:
    events = trace["traceEvents"] if isinstance(trace, dict) else trace
    t0 = next(e["ts"] for e in events if e.get("name") == "dl-change")
    t1 = t0 + ms * 1000
    out: dict[str, float] = defaultdict(float)
    out["total"] = (t1 - t0) / 1000
    # CPU samples, attributed by the script they are in.
    nodes: dict[tuple, dict] = {}
    parents: dict[tuple, int] = {}
    clock: dict[tuple, float] = {}
    for e in events:
        if e.get("name") == "Profile":
            clock[(e["pid"], e.get("id"))] = e["args"]["data"]["startTime"]
        if e.get("name") != "ProfileChunk":
            continue
        key = (e["pid"], e.get("id"))
        data = e["args"]["data"]
        profile = data.get("cpuProfile", {})
        for node in profile.get("nodes", []):
            nodes[(key, node["id"])] = node["callFrame"]
            if "parent" in node:
                parents[(key, node["id"])] = node["parent"]
        ts = clock.get(key, 0.0)
        for sample, delta in zip(profile.get("samples", []), data.get("timeDeltas", [])):
            ts += delta
            if t0 <= ts <= t1:
                source = attributed(key, sample, nodes, parents)
                if source:
                    out["js: " + source] += delta / 1000
        clock[key] = ts
    # The renderer's own work outside script.
    for e in events:
        if e.get("ph") == "X" and t0 <= e["ts"] <= t1 and e.get("name") in (
                "UpdateLayoutTree", "Layout", "Paint", "PrePaint", "Layerize", "UpdateLayer"):
            group = "style and layout" if e["name"] in ("UpdateLayoutTree", "Layout") else "paint"
            out[group] += e.get("dur", 0) / 1000
    # The server's run, seen from the browser: the BackMsg out to the last message of the run.
    sent = [t for d, t, _ in frames if d == "out"]
    if sent:
        start = sent[-1]
        received = [(t, n) for d, t, n in frames if d == "in" and t >= start]
        if received:
            out["server run (BackMsg → last message)"] = (received[-1][0] - start) * 1000
            out["websocket KB received"] = sum(n for _, n in received) / 1024
    return dict(out)


FIGURE_ALONE = """<!doctype html><html><body style="width:1000px">%s<script src="plotly.js"></script><script>
const plotlyReady = performance.now();  // plotly.js loaded and run: the time a page pays before any drawing
%s
const specs = %s;  // per value, the page's figures
function shaped(spec) {
  const layout = Object.assign({}, spec.layout);
  delete layout.sliders;  // drawn in HTML by the component
  return {data: spec.data, layout: layout, frames: unfold(spec.animation, spec.data), config: {displayModeBar: false}};
}
async function firstDraw() {
  const graphs = specs[0].map((_, i) => document.getElementById("g" + i));
  const t0 = performance.now();
  await Promise.all(graphs.map((g, i) => Plotly.newPlot(g, shaped(specs[0][i]))));
  return [plotlyReady, performance.now() - t0];
}
async function run() {
  await firstDraw();
  const graphs = specs[0].map((_, i) => document.getElementById("g" + i));
  const times = [];
  for (const figures of specs.slice(1)) {
    const shaped_ = figures.map(shaped);
    await new Promise(r => setTimeout(r, 30));
    const t0 = performance.now();
    await Promise.all(graphs.map((g, i) => Plotly.react(g, shaped_[i])));
    times.push(performance.now() - t0);
  }
  return times;
}
</script></body></html>"""


def figure_alone(browser, page_id: str, changes: int) -> tuple[list[float], float, float]:
    """The page's figures with nothing else around them, in a bare page with the same plotly.js
    bundle and the figure component's own unfolding of the frames: Plotly.react from one value of
    the first control to the next (the values a change uses), what plotly.js alone costs a change
    whatever Streamlit and the rest of the page do; and on a revisit (plotly.js in the browser's
    cache), the time from navigation until plotly.js has run and the first drawing's time."""
    import importlib

    from ui import figure as component
    from solvers.catalog import BY_ID

    solver, viz = (importlib.import_module(f"{m}.{page_id}") for m in ("solvers", "viz"))
    name = BY_ID[page_id].primary[0]
    start = solver.solve().params[name]
    shown = [viz.figures(solver.solve(**{name: start * (1 + 0.004 * i)})) for i in range(changes + 1)]
    bundle = component.bundles()[component.kind_of(shown[0][0], shown[0])][1]
    module = (ROOT / "ui" / "plotly_component" / "figure.js").read_text()
    unfold = module[module.index("function unfold"):module.index("// Lecture sizing")]
    specs = "[" + ",".join("[" + ",".join(f.json_bytes().decode() for f in figures) + "]" for figures in shown) + "]"
    html = FIGURE_ALONE % ("".join(f'<div id="g{i}"></div>' for i in range(len(shown[0]))), unfold, specs)
    files = {"/figure-alone.html": (html.encode(), "text/html"), "/plotly.js": (bundle, "text/javascript")}

    class Files(http.server.BaseHTTPRequestHandler):
        def do_GET(self):  # noqa: N802 (the standard library's name)
            if self.path not in files:
                return self.send_error(404)
            body, kind = files[self.path]
            self.send_response(200)
            self.send_header("Content-Type", kind)
            self.send_header("Content-Length", str(len(body)))
            self.send_header("Cache-Control", "public, max-age=31536000, immutable")  # as BundleServer
            self.end_headers()
            self.wfile.write(body)

        def log_message(self, *args):
            pass

    server = http.server.ThreadingHTTPServer(("127.0.0.1", 0), Files)
    threading.Thread(target=server.serve_forever, daemon=True).start()
    url = f"http://127.0.0.1:{server.server_address[1]}/figure-alone.html"
    context = browser.new_context(viewport=VIEWPORT)
    page = context.new_page()
    page.goto(url)
    page.wait_for_function("() => !!window.Plotly")
    times = page.evaluate("run()")
    again = context.new_page()  # a revisit: the bundle comes from the browser's cache
    again.goto(url)
    again.wait_for_function("() => !!window.Plotly")
    ready, first_draw = again.evaluate("firstDraw()")
    context.close()
    server.shutdown()
    return times, ready, first_draw


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--changes", type=int, default=15)
    parser.add_argument("--visits", type=int, default=3)
    parser.add_argument("--pages", nargs="*", default=PAGES)
    parser.add_argument("--json", type=Path, help="write the raw numbers here")
    parser.add_argument("--frame", action="store_true",
                        help="also the page's frame alone (bench/page_frame.py), changed the same way")
    parser.add_argument("--stage", action="store_true",
                        help="each change a step of the lesson's first stage slider by the keyboard (an arrow key, "
                             "released: the lesson's fragment reruns), and of the empty page's slider, instead of "
                             "a value typed into the first number box (the sidebar's: the whole page reruns)")
    args = parser.parse_args()
    from playwright.sync_api import sync_playwright

    results: dict = {}
    with ExitStack() as stack:
        app = stack.enter_context(running_app())
        empty = stack.enter_context(running_app(entry=[str(ROOT / "bench" / "serve_empty.py"),
                                                       "--script", "empty_controls.py"]))
        frame = stack.enter_context(running_app(entry=[str(ROOT / "bench" / "serve_empty.py"),
                                                       "--script", "page_frame.py"])) if args.frame else None
        pw = stack.enter_context(sync_playwright())
        browser = launch_browser(pw)
        for page_id in args.pages:
            pair = {EMPTY: (f"{empty}/", 0), page_id: (f"{app}/{page_id}", figure_count(page_id))}
            if frame:
                pair[FRAME] = (f"{frame}/?problem={page_id}", 0)
            r = {k: defaultdict(list) for k in pair}
            # First visits and revisits, alternating.
            for _ in range(args.visits):
                for key, (url, figures) in pair.items():
                    context = browser.new_context(viewport=VIEWPORT)
                    context.add_init_script(HELPERS)
                    ms, wire = visit(context.new_page(), url, figures)
                    r[key]["first_ms"].append(ms)
                    r[key]["first_bytes"].append(wire.http)
                    r[key]["first_ws"].append(wire.ws_in)
                    ms, wire = visit(context.new_page(), url, figures)
                    r[key]["revisit_ms"].append(ms)
                    r[key]["revisit_bytes"].append(wire.http)
                    r[key]["revisit_ws"].append(wire.ws_in)
                    context.close()
            # Changes, alternating between the two tabs.
            tabs = {}
            for key, (url, figures) in pair.items():
                context = browser.new_context(viewport=VIEWPORT)
                context.add_init_script(HELPERS)
                page = context.new_page()
                wire = Wire(page)
                page.goto(url)
                page.wait_for_function(f"() => __dl.drawn({figures})", timeout=60_000)
                wait_until_idle(page)
                box = first_slider(page) if args.stage else first_box(page)
                start = way_with_room(box, args.changes + 2) if args.stage else float(box.input_value())
                tabs[key] = (context, page, box, start, figures, wire)
            for i in range(args.changes):
                for key, (_, page, box, start, figures, _) in tabs.items():
                    result = change(page, box, start if args.stage else start * (1 + 0.004 * (i + 1)), figures)
                    r[key]["change_ms"].append(result["ms"])
                    r[key]["redrawn"].append(result["redrawn"])
            # One more change of each under a performance trace.
            for key, (_, page, box, start, figures, wire) in tabs.items():
                browser.start_tracing(page=page, categories=CATEGORIES)
                ms = change(page, box, start if args.stage else start * 0.97, figures)["ms"]
                trace = json.loads(browser.stop_tracing())
                r[key]["breakdown"] = breakdown(trace, wire.ws_frames, ms)
            for context, *_ in tabs.values():
                context.close()
            alone, ready, first_draw = figure_alone(browser, page_id, args.changes)
            r[page_id].update(figure_alone_ms=alone, plotly_ready_ms=ready, first_draw_ms=first_draw)
            results[page_id] = {k: dict(v) for k, v in r.items()}
            report(page_id, results[page_id])
        browser.close()
    if args.json:
        args.json.write_text(json.dumps(results, indent=1))


def report(page_id: str, r: dict) -> None:
    e, p = r[EMPTY], r[page_id]
    med = statistics.median
    ratios = [a / b for a, b in zip(p["change_ms"], e["change_ms"])]
    print(f"\n## {page_id}  (empty page in brackets)")
    print(f"change → redrawn: median {med(p['change_ms']):.0f} ms [{med(e['change_ms']):.0f}], "
          f"p90 {percentile(p['change_ms'], 0.9):.0f} ms [{percentile(e['change_ms'], 0.9):.0f}], "
          f"× empty {med(ratios):.2f} (median of {len(ratios)} pairs; "
          f"{sum(p['redrawn'])} of them redrew a figure, the others left it unchanged)")
    alone = p.get("figure_alone_ms")
    if alone:
        print(f"the figures' redraw alone (plotly.js in a bare page): median {med(alone):.0f} ms, "
              f"p90 {percentile(alone, 0.9):.0f} ms, {med(alone) / med(e['change_ms']):.2f}× the empty page's change; "
              f"on a revisit plotly.js has run {p['plotly_ready_ms']:.0f} ms after navigation and draws the "
              f"figures in {p['first_draw_ms']:.0f} ms")
    for visit_kind in [k for k in ("first", "revisit") if p.get(f"{k}_ms")]:  # none with --visits 0
        ms, kb = med(p[f"{visit_kind}_ms"]), med(p[f"{visit_kind}_bytes"]) / 1024
        ems, ekb = med(e[f"{visit_kind}_ms"]), med(e[f"{visit_kind}_bytes"]) / 1024
        print(f"{visit_kind:8s}: drawn {ms:.0f} ms [{ems:.0f}] × {ms / ems:.2f}; "
              f"{kb:.0f} KB over HTTP [{ekb:.0f}], +{kb - ekb:.0f} KB; websocket "
              f"{med(p[f'{visit_kind}_ws']) / 1024:.0f} KB [{med(e[f'{visit_kind}_ws']) / 1024:.0f}]")
    if FRAME in r:
        f = r[FRAME]
        frame_ratios = [a / b for a, b in zip(f["change_ms"], e["change_ms"])]
        print(f"the frame alone: change median {med(f['change_ms']):.0f} ms, p90 {percentile(f['change_ms'], 0.9):.0f} ms, "
              f"× empty {med(frame_ratios):.2f}" + (f"; first visit {med(f['first_ms']):.0f} ms "
              f"(× {med(f['first_ms']) / med(e['first_ms']):.2f}), +{(med(f['first_bytes']) - med(e['first_bytes'])) / 1024:.0f} KB; "
              f"revisit {med(f['revisit_ms']):.0f} ms (× {med(f['revisit_ms']) / med(e['revisit_ms']):.2f})"
              if f.get("first_ms") else ""))
    for key in [k for k in (page_id, FRAME, EMPTY) if k in r]:
        parts = r[key]["breakdown"]
        print(f"one change, {key}: " + ", ".join(f"{k} {v:.1f}" for k, v in
                                                   sorted(parts.items(), key=lambda kv: -kv[1])))
    sys.stdout.flush()


if __name__ == "__main__":
    main()
