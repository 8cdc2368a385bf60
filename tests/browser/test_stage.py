"""The stage (issue 27): on every problem page the motion, its Play button and the lesson's controls
(the registry's ``primary``) are all in the first screen, the controls never cover the figure, and
the bodies fill the plot: the motion's extent over every frame, as drawn, spans at least half of the
plot area in width or in height, with equal axes.

``stage_faults`` measures one page as it is shown. This module measures every page at a laptop
(1400×1000, Study) in one browser context; tests/browser/test_where_used.py measures the same on the pages
it already opens at a projector (1280×720 and 1024×768, Lecture) and a phone (390×844), so the
three sizes cost no extra page loads.
"""
from __future__ import annotations

import pytest

from scripts.live_app import SETTLED, wait_until_idle
from tests.browser.test_browser import hold_drag, open_page, visit  # which skips (or, in CI, fails) without Chromium and Playwright
from solvers.catalog import PROBLEMS

pytestmark = pytest.mark.browser

STAGE, CONTROLS = ".st-key-dl_stage", ".st-key-dl_stage_controls"


# The stage's graph drawn: plotly's full data and layout made (a 3-D scene's too). A page idle has sent its
# figure; plotly draws it a moment later (Euler's disk: its 3-D bundle loaded first).
DRAWN = """(selector) => { const g = document.querySelector(selector);
  return !!(g && g._fullData && g._fullData.length && g._fullLayout && (!g.layout.scene || g._fullLayout.scene)); }"""


def stage_graph(page):
    """The stage's graph, once plotly has drawn it."""
    page.wait_for_function(DRAWN, arg=f"{STAGE} .dl-graph", timeout=30_000)
    return page.locator(f"{STAGE} .dl-graph").first


# The motion's box as drawn: every frame's moving traces on the motion's axes (x, y), in pixels, beside
# the plot area; and how many pixels a unit is along each axis (equal axes: the same). A 3-D scene:
# the scene's box beside the graph's.
MEASURE = """(g) => {
  const full = g._fullLayout;
  if (full.scene) {
    // The moving body (the disk's rim, the body colour) as drawn: the scene redrawn and its pixels read at
    // once, before the browser composites the frame; its box beside the plot area's.
    const scene = full.scene._scene, canvas = scene.glplot.canvas;
    scene.glplot.redraw();
    const copy = document.createElement("canvas");
    copy.width = canvas.width; copy.height = canvas.height;
    const ctx = copy.getContext("2d");
    ctx.drawImage(canvas, 0, 0);
    const px = ctx.getImageData(0, 0, copy.width, copy.height).data, body = [0x00, 0x72, 0xB2];
    let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
    for (let i = 0; i < px.length; i += 4) {
      if (px[i + 3] < 200 || Math.abs(px[i] - body[0]) + Math.abs(px[i + 1] - body[1]) + Math.abs(px[i + 2] - body[2]) > 40) continue;
      const x = (i / 4) % copy.width, y = Math.floor(i / 4 / copy.width);
      x0 = Math.min(x0, x); x1 = Math.max(x1, x); y0 = Math.min(y0, y); y1 = Math.max(y1, y);
    }
    const scale = canvas.width / canvas.getBoundingClientRect().width;
    return {scene: true, width: (x1 - x0) / scale / full._size.w, height: (y1 - y0) / scale / full._size.h};
  }
  const xa = full.xaxis, ya = full.yaxis;
  let x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
  const frames = (g._transitionData && g._transitionData._frames) || [];
  for (const frame of frames) {
    frame.data.forEach((d, n) => {
      const trace = g._fullData[frame.traces[n]];
      if (!trace || (trace.xaxis || 'x') !== 'x' || (trace.yaxis || 'y') !== 'y' || !d.x || !d.y) return;
      for (const v of d.x) if (v !== null && isFinite(v)) { x0 = Math.min(x0, v); x1 = Math.max(x1, v); }
      for (const v of d.y) if (v !== null && isFinite(v)) { y0 = Math.min(y0, v); y1 = Math.max(y1, v); }
    });
  }
  // Each filled body's outline (a sphere, a disk) beside its drawn size: thick outlines turn a small sphere into a ring.
  const rings = [];
  g._fullData.forEach((t, n) => {
    if (t.fill !== "toself" || !t.line || t.xaxis !== "x" || t.yaxis !== "y") return;
    const f = frames[0] && frames[0].traces.indexOf(n) >= 0 ? frames[0].data[frames[0].traces.indexOf(n)] : t;
    const span = (v, a) => { v = Array.from(v).filter(u => u !== null && isFinite(u));
                             return Math.abs(a.l2p(Math.max(...v)) - a.l2p(Math.min(...v))); };
    const size = Math.min(span(f.x, xa), span(f.y, ya));
    // (at most 1/14 of its size, 1.5 px at least; figure.js redraws an outline a quarter off)
    if (t.line.width > 1.3 * Math.max(1.5, size / 14)) rings.push(`${t.name}: ${t.line.width} px on ${size.toFixed(0)} px`);
  });
  // Every axis label (ticks and titles) clear of the others and of every other subplot's plot area.
  const labels = [...g.querySelectorAll(".xaxislayer-above text, .yaxislayer-above text, .g-xtitle text, .g-ytitle text,"
                                        + " .g-x2title text, .g-y2title text")].filter(t => t.textContent.trim());
  const boxes = labels.map(t => [t.textContent, t.getBoundingClientRect()]);
  const areas = [...g.querySelectorAll(".draglayer .nsewdrag")].map(r => [r.closest("g[class]").getAttribute("class"), r.getBoundingClientRect()]);
  const cross = (a, b) => a.left < b.right - 1 && b.left < a.right - 1 && a.top < b.bottom - 1 && b.top < a.bottom - 1;
  const clashes = [];
  boxes.forEach(([text, box], i) => {
    boxes.slice(i + 1).forEach(([other, b]) => { if (cross(box, b)) clashes.push(`${text} / ${other}`); });
    areas.forEach(([name, area]) => {
      if (cross(box, area)) clashes.push(`${text} in ${name}`);
    });
  });
  // Stacked plots: the upper x axis's title reads as its own, nearer its tick labels than the plot below.
  const title = g.querySelector(".g-xtitle text"), below = g.querySelector(".draglayer .x2y2 .nsewdrag");
  const ticks = [...g.querySelectorAll(".xaxislayer-above .xtick text")].map(t => t.getBoundingClientRect().bottom);
  const under = below && below.getBoundingClientRect().top >= g.querySelector(".draglayer .xy .nsewdrag").getBoundingClientRect().bottom - 1;
  if (title && under && ticks.length) {  // (a plot beside the motion, on a wide stage: nothing below it)
    const t = title.getBoundingClientRect(), own = t.top - Math.max(...ticks), other = below.getBoundingClientRect().top - t.bottom;
    if (own > other) clashes.push(`${title.textContent} ${own.toFixed(0)} px below its ticks, ${other.toFixed(0)} px above the plot below`);
  }
  return {scene: false, frames: frames.length, width: Math.abs(xa.l2p(x1) - xa.l2p(x0)) / xa._length,
          height: Math.abs(ya.l2p(y1) - ya.l2p(y0)) / ya._length, rings: rings, clashes: clashes,
          unitX: Math.abs(xa.l2p(1) - xa.l2p(0)), unitY: Math.abs(ya.l2p(1) - ya.l2p(0))};
}"""


def box(locator) -> dict:
    b = locator.bounding_box()
    assert b is not None, locator
    return b


def overlaps(a: dict, b: dict) -> bool:
    return (a["x"] < b["x"] + b["width"] - 1 and b["x"] < a["x"] + a["width"] - 1
            and a["y"] < b["y"] + b["height"] - 1 and b["y"] < a["y"] + a["height"] - 1)


def stage_faults(page, problem, height: int) -> list[str]:
    """What is wrong with ``problem``'s stage as the page (idle, ``height`` px tall) shows it."""
    figure = page.locator(f"{STAGE} .dl-figure").first
    figure.locator(".dl-graph .main-svg").first.wait_for(timeout=30_000)
    page.wait_for_timeout(300)  # the figure fits the screen again once the controls beside it are drawn
    page.evaluate(SETTLED, 0)  # and the sidebar has folded away (the lecture view, a phone)
    graph, play = box(figure.locator(".dl-graph")), box(figure.get_by_role("button", name="Play the animation"))
    controls = box(page.locator(CONTROLS))
    faults = []
    # Every lesson parameter has its control on the stage (a label each).
    labels = page.locator(f"{CONTROLS} [data-testid='stWidgetLabel']").all_inner_texts()
    if len(labels) < len(problem.primary):
        faults.append(f"{len(labels)} controls on the stage for {len(problem.primary)} lesson parameters")
    if not (0 <= graph["y"] and graph["y"] + graph["height"] <= height + 1):
        faults.append(f"figure {graph['y']:.0f}–{graph['y'] + graph['height']:.0f}")
    if not play["y"] + play["height"] <= height:
        faults.append(f"Play at {play['y']:.0f}")
    if not (0 <= controls["y"] and controls["y"] + controls["height"] <= height + 1):
        faults.append(f"controls {controls['y']:.0f}–{controls['y'] + controls['height']:.0f}")
    if overlaps(graph, controls):
        faults.append("controls over the figure")
    caption = figure.locator(".dl-description").evaluate(
        "e => ({y: e.getBoundingClientRect().top, line: parseFloat(getComputedStyle(e).lineHeight), text: e.textContent})")
    if caption["text"] and caption["y"] < height < caption["y"] + caption["line"]:  # (a projector cut it in half)
        faults.append(f"the caption's first line {caption['y']:.0f}–{caption['y'] + caption['line']:.0f} cut at the foot")
    faults += stepper_faults(page, height)
    m = figure.locator(".dl-graph").evaluate(MEASURE)
    if m["scene"]:  # Euler's disk: its disk as drawn fills the 3-D scene's plot area as a 2-D stage's bodies do
        if max(m["width"], m["height"]) < 0.5:
            faults.append(f"the disk fills {m['width']:.2f} × {m['height']:.2f} of the scene")
    elif m["frames"] <= 1:
        faults.append("no animation")
    else:
        if max(m["width"], m["height"]) < 0.5:
            faults.append(f"bodies fill {m['width']:.2f} × {m['height']:.2f} of the plot")
        if abs(m["unitX"] - m["unitY"]) > 0.01 * m["unitX"]:
            faults.append(f"unequal axes {m['unitX']:.1f} / {m['unitY']:.1f} px")
        faults += [f"ring: {ring}" for ring in m["rings"]] + [f"label over: {clash}" for clash in m["clashes"]]
    return faults


def stepper_faults(page, height: int) -> list[str]:
    """Each stage slider's −/+ (ui/plotly_component/live.js) on a narrow screen: two, named, at least
    44×32 px, in the first screen, clear of the thumb at either end of the track and of the track's whole
    box (the 40 px a finger drags in: 44 px tall, they reached 12 px into it, and a drag begun a little low
    on the thumb at an end pressed − or +), under a track of the slider's width on a phone taller than
    800 px; none on a wide one."""
    narrow = page.evaluate("innerWidth") <= 640
    faults = []
    for slider in page.locator(f"{CONTROLS} [data-testid='stSlider']").all():
        name = slider.locator("input[type='range']").get_attribute("aria-label").split(" — ")[0]
        steps = [s for s in slider.locator(".dl-step").all() if s.is_visible()]
        if not narrow:
            if steps:
                faults.append(f"{name}: −/+ on a wide screen")
            continue
        names = sorted(s.get_attribute("aria-label") for s in steps)
        if names != [f"{name} one step higher", f"{name} one step lower"]:
            faults.append(f"{name}: steppers {names}")
            continue
        track = box(slider.locator("[role='group'] > [data-orientation]").first)
        # Under the track, the −/+ leave it the slider's width, long enough to drag to a value; a short phone
        # keeps them at its ends, where it had a third of it (some 55 px of a 390 px phone's half).
        if height > 800 and track["width"] < 0.85 * box(slider)["width"]:
            faults.append(f"{name}: a track of {track['width']:.0f} px in a slider {box(slider)['width']:.0f} px wide")
        thumb = box(slider.locator("[data-testid='stSliderThumbValue']").locator("xpath=..").first)
        half = thumb["width"] / 2
        for step in steps:
            b = box(step)
            if b["width"] < 44 or b["height"] < 32 or b["y"] < 0 or b["y"] + b["height"] > height + 1:
                faults.append(f"{step.get_attribute('aria-label')}: {b['width']:.0f}×{b['height']:.0f} at {b['y']:.0f}")
            if overlaps(b, track):
                faults.append(f"{step.get_attribute('aria-label')}: {track['y'] + track['height'] - b['y']:.0f} px into the "
                              "track's box")
            for end in (track["x"], track["x"] + track["width"]):  # the thumb at either end of its track
                if overlaps(b, {**thumb, "x": end - half}):
                    faults.append(f"{step.get_attribute('aria-label')}: under the thumb at the track's end")
        # The track's end values (shown while it is touched) clear of each other and of the −/+ (their text's
        # own box, with a gap): a half-width track at 360 px ran "0.00" into "1.00" and the +.
        ends = slider.locator("[data-testid='stSliderTickBar'] p").evaluate_all(INK)
        if len(ends) != 2:
            faults.append(f"{name}: {len(ends)} end values")
        for n, end in enumerate(ends):
            near = {**end, "x": end["x"] - 2, "width": end["width"] + 4}
            for other in [box(s) for s in steps] + ends[n + 1:]:
                if overlaps(near, other):
                    faults.append(f"{name}: the end value {end['text']!r} touches its neighbour")
    if narrow:  # two sliders side by side: their tracks level, whichever label wraps (θ₀'s sat 16 px lower than L's)
        tracks = [(box(s), box(s.locator("[role='group'] > [data-orientation]").first))
                  for s in page.locator(f"{CONTROLS} [data-testid='stSlider']").all()]
        for n, (a, ta) in enumerate(tracks):
            for b, tb in tracks[n + 1:]:
                side_by_side = a["y"] < b["y"] + b["height"] - 1 and b["y"] < a["y"] + a["height"] - 1  # one row
                if side_by_side and abs(ta["y"] - tb["y"]) > 1:
                    faults.append(f"tracks side by side {abs(ta['y'] - tb['y']):.0f} px apart in height")
    return faults


INK = ("(ps) => ps.map((p) => { const r = document.createRange(); r.selectNodeContents(p);"
       " const b = r.getBoundingClientRect(); return {x: b.x, y: b.y, width: b.width, height: b.height, text: p.textContent}; })")


def test_the_motion_its_play_and_the_lesson_s_controls_share_a_laptop_s_first_screen(browser, app_url):
    width, height = 1400, 1000
    context, page, errors = open_page(browser, f"{app_url}/", width, height)
    found = {}
    for problem in PROBLEMS:
        visit(page, app_url, problem.id)  # from the navigation, as a student goes from page to page
        faults = stage_faults(page, problem, height)
        if faults:
            found[problem.id] = faults
        assert page.locator("[data-testid='stException']").count() == 0, problem.id
    assert found == {}
    assert not errors, errors
    context.close()


# The motion's plot and the second plot below or beside it (energy bars, θ(t)), as drawn: each plot's box
# in px, and the motion's scale (px a metre).
PLOTS = """(g) => { const f = g._fullLayout, box = (xa, ya) => ({x: xa._offset, y: ya._offset, width: xa._length,
                                                                   height: ya._length});
  return {motion: box(f.xaxis, f.yaxis), second: box(f.xaxis2, f.yaxis2), area: f._size.h,
          scale: f.yaxis._length / Math.abs(f.yaxis.range[1] - f.yaxis.range[0])}; }"""


# A filled body's size across as drawn at the first frame (px): the trace named ``name``.
BODY_PX = """(g, name) => { const f = g._fullLayout, t = g.data.find((d) => d.name === name);
  const xs = (t.x || []).filter((v) => v !== null);
  return (Math.max(...xs) - Math.min(...xs)) * f.xaxis._length / Math.abs(f.xaxis.range[1] - f.xaxis.range[0]); }"""


@pytest.mark.parametrize("pid, body, across_at_least", [("rod_disk_spring", "disk", 36), ("pendulum_rebound", "sphere", 55)])
def test_on_a_projector_a_tall_motion_stands_beside_its_second_plot(browser, app_url, pid, body, across_at_least):
    """The rod and disk on the projector (1280×720, lecture view) were drawn some 85 px long: the motion,
    taller than wide, had the upper 60 % of a short, wide graph, its energy bars the rest, and equal axes
    left most of its width empty. Beside the bars at the graph's whole height it is drawn larger. The
    pendulum's sphere was 35 px across above its θ(t) beside a legend a third of the width, the rod's disk
    30 px under the figure's heading and a line of keys (issue 54): without the legend (the caption names
    the bodies, as on a phone), the heading (a screen reader's) and the keys (the buttons' titles), they
    stand beside their second plot, larger; on a 1024×768 projector too (the rod's disk was 25 px)."""
    problem = next(p for p in PROBLEMS if p.id == pid)
    for (width, height), least in (((1280, 720), across_at_least), ((1024, 768), 0.8 * across_at_least)):
        context, page, errors = open_page(browser, f"{app_url}/{pid}?lecture=1", width, height)
        wait_until_idle(page)
        assert stage_faults(page, problem, height) == []
        drawn = page.locator(f"{STAGE} .dl-figure .dl-graph").first.evaluate(PLOTS)
        motion, second = drawn["motion"], drawn["second"]
        assert not overlaps(motion, second), drawn
        if width == 1280:
            assert motion["x"] + motion["width"] < second["x"] and motion["height"] >= 0.95 * drawn["area"], drawn
        across = page.locator(f"{STAGE} .dl-figure .dl-graph").first.evaluate(BODY_PX, body)
        assert across >= least, (width, body, across)
        if not page.locator(f"{STAGE} .dl-graph .legend").count():  # the caption names the bodies instead
            assert body in page.locator(f"{STAGE} .dl-figure .dl-description").inner_text()
        assert not errors, errors
        context.close()


def test_a_refusal_on_the_projector_is_in_projector_type(browser, app_url):
    """Past the model's limit on the projector (the spring stops the rod before θ₂), the refusal and the
    limit beside it are read from the back of the room: 18 px at least (the limit's label was 14 px)."""
    context, page, errors = open_page(browser, f"{app_url}/rod_disk_spring?lecture=1&k=51", 1280, 720)
    wait_until_idle(page)
    sizes = page.evaluate("""() => [...document.querySelectorAll(`.st-key-dl_motion [data-testid='stAlert'] p,
        .st-key-dl_motion [data-testid='stMetricLabel'] p, .st-key-dl_motion [data-testid='stMetricValue']`)]
        .map(e => [e.textContent.trim(), parseFloat(getComputedStyle(e).fontSize)])""")
    assert len(sizes) >= 3 and any("largest angle" in text for text, _ in sizes), sizes
    assert all(size >= 18 for _, size in sizes), sizes
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("query", ["theta=68", "theta=89.5&r=0.5"])
def test_a_disk_tilted_near_upright_stands_whole_in_the_projector_s_first_screen(browser, app_url, query):
    """Euler's disk tilted near upright stands up to 2r tall: its box grows to hold it (the rim's top
    was cut off at a lid r high), drawn smaller so the box, its tick labels and its axis titles stay
    inside the graph in the lecture view's first screen (1280×720), as the laptop's and phone's do."""
    width, height = 1280, 720
    problem = next(p for p in PROBLEMS if p.id == "eulers_disk")
    context, page, errors = open_page(browser, f"{app_url}/eulers_disk?lecture=1&{query}", width, height)
    wait_until_idle(page)
    assert stage_faults(page, problem, height) == []
    graph = box(page.locator(f"{STAGE} .dl-figure .dl-graph"))
    titles = page.locator(f"{STAGE} .dl-figure .infolayer .annotation-text")
    assert titles.count() == 3
    for title in titles.all():  # x (mm), y (mm) below the box, z (mm) above it
        b = box(title)
        assert graph["y"] <= b["y"] and b["y"] + b["height"] <= min(height, graph["y"] + graph["height"]) + 1, (title.text_content(), b, graph)
    assert not errors, errors
    context.close()


def test_the_motion_refits_when_what_is_above_the_stage_grows(browser, app_url):
    """The stage is fitted to the first screen when drawn; what is above it may grow after (the title set in
    its web font, a notice): the stage then moves down without changing size, and the figure must fit again,
    not run past the screen's bottom (seen once at 1280×720: "figure 289–778")."""
    width, height = 1280, 720
    problem = next(p for p in PROBLEMS if p.id == "disk_wall")
    context, page, errors = open_page(browser, f"{app_url}/disk_wall?lecture=1", width, height)
    wait_until_idle(page)
    assert stage_faults(page, problem, height) == []
    page.evaluate("""() => { const h = document.querySelector("[data-testid='stMain'] h1");
                            h.style.paddingBottom = '90px'; }""")
    page.wait_for_timeout(600)
    assert stage_faults(page, problem, height) == []
    assert not errors, errors
    context.close()


def settled_box(page, locator) -> dict:
    """``locator``'s box once it has stayed put for 100 ms (a finger put down where it was a moment before
    missed a thumb that the stage's refit had moved: the drag moved nothing, on a busy machine)."""
    last = box(locator)
    for _ in range(50):
        page.wait_for_timeout(100)
        now = box(locator)
        if now == last:
            break
        last = now
    return last


def thumb_centre(page, slider) -> tuple[float, float]:
    """Where a finger goes down on ``slider``'s thumb: its centre once the stage is drawn and fitted to the
    screen (the controls below it may still move until then) and the thumb has settled."""
    stage_graph(page)
    thumb = settled_box(page, slider.locator("[role='group'] > [data-orientation] > div[style*='absolute']").first)
    return thumb["x"] + thumb["width"] / 2, thumb["y"] + thumb["height"] / 2


def finger_drag(page, touch, slider, travel: float, moves: int, said: list | None = None,
                ending: str = "touchEnd") -> list[str]:
    """A finger on ``slider``'s thumb moved ``travel`` px along its track in ``moves`` equal moves (CDP touch
    events, ``touch`` a CDP session), then lifted (``ending``; "touchCancel": the browser took the touch
    back): the thumb's value after each move, and in ``said`` what a screen reader gets of it (``heard``)."""
    x, y = thumb_centre(page, slider)
    touch.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": x, "y": y}]})
    shown = []
    for n in range(1, moves + 1):
        touch.send("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [{"x": x + travel * n / moves, "y": y}]})
        page.wait_for_timeout(40)
        shown.append(slider.locator("[data-testid='stSliderThumbValue']").inner_text())
        if said is not None:
            said.append(heard(touch, slider))
    page.evaluate("window.__sentBeforeLift = window.__sent")
    touch.send("Input.dispatchTouchEvent", {"type": ending, "touchPoints": []})
    page.wait_for_timeout(800)
    wait_until_idle(page)
    return shown


def test_a_finger_drags_a_stage_slider_along_its_track_on_a_phone(browser, app_url):
    """On a phone (390×844, touch) a finger moved along V's track (the −/+ under it, the track the slider's
    width): the thumb follows while the finger moves, one run after it lifts, and the link keeps the value."""
    context, page, errors = open_page(browser, f"{app_url}/disk_wall", 390, 844, phone=True)
    page.wait_for_timeout(300)
    slider = page.locator(f"{CONTROLS} [data-testid='stSlider']").first
    sent = page.evaluate("window.__sent")
    shown = [float(v) for v in finger_drag(page, context.new_cdp_session(page), slider, 75, 15)]
    assert shown == sorted(shown) and len(set(shown)) >= 10 and shown[0] > 2, shown  # V starts at 2 m/s
    assert page.evaluate("window.__sentBeforeLift") == sent  # no run while moving
    assert page.evaluate("window.__sent") - sent == 1
    assert f"V={shown[-1]:g}" in page.url, (page.url, shown[-1])
    assert not errors, errors
    context.close()


def heard(cdp, slider) -> str | None:
    """What a screen reader gets of ``slider``'s value: Chromium's accessibility tree (CDP, ``cdp`` a session
    of the page) for its range input, the node named as the slider's label is. Chromium gives a range
    input's value there, whatever its aria-valuetext says."""
    label = slider.locator("[data-testid='stWidgetLabel']").inner_text().strip()
    for node in cdp.send("Accessibility.getFullAXTree")["nodes"]:
        if node.get("role", {}).get("value") == "slider" and node.get("name", {}).get("value", "").strip() == label:
            props = {p["name"]: p["value"].get("value") for p in node.get("properties", [])}
            return props.get("valuetext")
    return None


def test_a_screen_reader_hears_the_value_a_dragged_thumb_shows(browser, app_url):
    """live.js draws a dragged stage slider's thumb itself (react-aria sees none of the moves): what a screen
    reader gets of the slider (Chromium's accessibility tree) is the value the thumb shows on every move,
    not the value before the drag; a drag the browser cancels puts it back, a finished one says where it
    landed."""
    context, page, errors = open_page(browser, f"{app_url}/disk_wall", 390, 844, phone=True)
    page.wait_for_timeout(300)
    slider = page.locator(f"{CONTROLS} [data-testid='stSlider']").first
    touch = context.new_cdp_session(page)
    touch.send("Accessibility.enable")
    before = heard(touch, slider)
    assert before == slider.locator("[data-testid='stSliderThumbValue']").inner_text(), before
    said: list = []
    shown = finger_drag(page, touch, slider, 60, 6, said, ending="touchCancel")
    assert len(set(shown)) >= 4 and said == shown, (shown, said)
    assert slider.locator("[data-testid='stSliderThumbValue']").inner_text() == before
    assert heard(touch, slider) == before
    said.clear()
    shown = finger_drag(page, touch, slider, -40, 4, said)
    assert said == shown and float(shown[-1]) < float(before), (shown, said)
    assert heard(touch, slider) == shown[-1]
    assert not errors, errors
    context.close()


def test_a_drag_lands_on_the_value_its_thumb_showed(browser, app_url):
    """The value a finger lets go on is the one its thumb showed: live.js draws the thumb during a drag, and
    react-aria commits the release from its own arithmetic, which at half a step could round the other way
    (the ladder's θ₀ showed 28° and became 29°: 60 px left of 60° on a 160 px track of 84 steps is 28.5°)."""
    context, page, errors = open_page(browser, f"{app_url}/sliding_ladder", 390, 844, phone=True)
    page.wait_for_timeout(300)
    slider = page.locator(f"{CONTROLS} [data-testid='stSlider']").nth(1)  # θ₀
    touch = context.new_cdp_session(page)
    landed = []
    for travel in (-60, 47, -33, 21, -13, 26, -40):
        shown = finger_drag(page, touch, slider, travel, 5)[-1]
        landed.append((travel, shown, slider.locator("input[type='range']").get_attribute("aria-valuetext"),
                       page.url.split("theta0=")[-1]))
    assert all(shown == kept == linked for _, shown, kept, linked in landed), landed
    assert not errors, errors
    context.close()


# The posed traces' reach on the motion's axes beside the axes' ranges as drawn: [[x lo, x hi], [y lo, y hi]] each.
# ``posed``: those traces (by default the ones not dimmed: while a control is held, the posed ones).
POSED_REACH = """(g, posed) => {
  const full = g._fullLayout, reach = [[Infinity, -Infinity], [Infinity, -Infinity]];
  posed = posed || g.data.map((t, n) => n).filter((n) => (g._fullData[n].opacity ?? 1) === 1
    && (g.data[n].xaxis || 'x') === 'x' && (g.data[n].yaxis || 'y') === 'y');
  for (const n of posed) [g.data[n].x, g.data[n].y].forEach((vs, a) => { for (const v of vs || []) if (v !== null && isFinite(v)) {
    reach[a][0] = Math.min(reach[a][0], v); reach[a][1] = Math.max(reach[a][1], v); } });
  return {reach, posed, ranges: [full.xaxis.range.slice(), full.yaxis.range.slice()]};
}"""


@pytest.mark.parametrize("pid, key", [("sliding_ladder", "L"), ("driven_cart", "a")])
def test_a_body_dragged_larger_stays_inside_the_axes(browser, app_url, pid, key):
    """A size dragged to its top (the ladder's L, 4 → 12 m; the cart's CM height a): the posed body at its key
    instant stays inside the plot while the mouse is held (the axes widen to hold it; they ran past them), and
    after the release the run's own figure is drawn with its own ranges."""
    context, page, errors = open_page(browser, f"{app_url}/{pid}", 1400, 1000)
    graph = stage_graph(page)
    before = graph.evaluate(POSED_REACH, None)["ranges"]
    control = page.locator(f".st-key-{pid}__si__{key}")
    thumb = control.locator("input[type='range']")
    low, high, value = (float(thumb.get_attribute(a)) for a in ("min", "max", "value"))
    hold_drag(page, control.locator("[role='group'] > [data-orientation]").first.bounding_box(), (value - low) / (high - low), 1.0, 15)
    page.wait_for_timeout(800)  # the last pose drawn
    held = graph.evaluate(POSED_REACH, None)
    for (lo, hi), (a, b) in zip(held["reach"], held["ranges"]):
        assert a <= lo and hi <= b, held  # the body whole inside the axes
    assert held["ranges"] != before, (held, before)  # (widened: at the top the body reaches past the start's)
    page.mouse.up()
    page.wait_for_function(f"() => new URL(location.href).searchParams.get('{key}') === '{high:g}'", timeout=30_000)
    wait_until_idle(page)
    page.wait_for_timeout(800)
    after = graph.evaluate(POSED_REACH, held["posed"])  # the same bodies, at their first frame
    for (lo, hi), (a, b) in zip(after["reach"], after["ranges"]):
        assert a <= lo and hi <= b, after
    assert not errors, errors
    context.close()


SCENE_REACH = """(g) => {
  const full = g._fullLayout.scene, axes = ['xaxis', 'yaxis', 'zaxis'];
  const posed = g.data.map((t, n) => n).filter((n) => g._fullData[n].visible === 'legendonly');
  let outside = 0;
  for (const n of posed) ['x', 'y', 'z'].forEach((c, k) => { const [lo, hi] = full[axes[k]].range;
    for (const v of g.data[n][c] || []) if (v !== null && isFinite(v) && (v < lo - 1e-9 || v > hi + 1e-9)) outside++; });
  return {posed: posed.length, outside, ranges: axes.map((a) => full[a].range.slice()),
          given: axes.map((a) => g.layout.scene[a].range.slice())};
}"""


def test_a_3d_body_dragged_larger_stays_inside_its_scene(browser, app_url):
    """Euler's disk's r dragged from 37.5 mm to its top on a projector: the disk grew out of its ±40 mm box, the
    rim drawn off the scene and over the page above it, until release. The box grows with it (one scale on all
    three axes) while the mouse is held, and after release the run's own figure is drawn."""
    context, page, errors = open_page(browser, f"{app_url}/eulers_disk?lecture=1", 1280, 720)
    graph = stage_graph(page)
    before = graph.evaluate(SCENE_REACH)
    control = page.locator(".st-key-eulers_disk__si__r")
    thumb = control.locator("input[type='range']")
    low, high, value = (float(thumb.get_attribute(a)) for a in ("min", "max", "value"))
    hold_drag(page, control.locator("[role='group'] > [data-orientation]").first.bounding_box(), (value - low) / (high - low), 1.0, 15)
    page.wait_for_timeout(1500)  # the last pose drawn (a 3-D redraw in software)
    held = graph.evaluate(SCENE_REACH)
    assert held["posed"] >= 2 and held["outside"] == 0, held  # the rim and the radius, whole inside the box
    assert held["ranges"][0][1] > 5 * before["ranges"][0][1], (held, before)  # (0.5 m against 37.5 mm: widened)
    page.mouse.up()
    page.wait_for_function(f"() => new URL(location.href).searchParams.get('r') === '{high:g}'", timeout=30_000)
    wait_until_idle(page)
    page.wait_for_timeout(1500)
    after = graph.evaluate(SCENE_REACH)
    assert after["posed"] == 0 and after["ranges"] == after["given"], after  # the run's figure, its own box
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("pid", ["driven_cart", "sliding_ladder"])
def test_the_companion_figures_keep_their_size_when_the_view_puts_them_first(browser, app_url, pid):
    """Study to Lecture in one visit puts the companion figures before the answers, in the element they
    share with them (ui/figure.together): each is drawn at its full height, and above the answers, never
    over them (a moved plot measured itself while out of the page: its box 0 px, drawn over the table)."""
    context, page, errors = open_page(browser, f"{app_url}/{pid}")
    page.locator(".dl-part .dl-figure .main-svg").first.wait_for(timeout=30_000)
    study = page.evaluate("() => [...document.querySelectorAll('.dl-part .dl-figure .dl-graph')].map(g => g.getBoundingClientRect().height)")
    page.locator("[data-testid='stSidebar']").get_by_role("radio", name="Lecture").click()
    page.wait_for_url("**lecture=1**", timeout=30_000)
    wait_until_idle(page)
    page.wait_for_timeout(1000)
    drawn = page.evaluate("""() => {
      const answers = document.querySelector('.dl-text.dl-answers').getBoundingClientRect();
      return [...document.querySelectorAll('.dl-part .dl-figure')].map((f) => {
        const graph = f.querySelector('.dl-graph').getBoundingClientRect(), plot = f.querySelector('.main-svg').getBoundingClientRect();
        const slot = f.closest('.dl-part').getBoundingClientRect();
        return {graph: graph.height, plot: plot.height, slot: slot.height, bottom: Math.max(slot.bottom, plot.bottom), answersTop: answers.top};
      });
    }""")
    assert drawn and len(drawn) == len(study), (drawn, study)
    for figure, before in zip(drawn, study):
        assert figure["graph"] >= 0.9 * before and figure["slot"] >= figure["plot"], (pid, figure, before)
        assert figure["bottom"] <= figure["answersTop"] + 1, (pid, figure)
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("pid, phone", [("disk_wall", False), ("stick_ball", False), ("driven_cart", True)])
def test_practice_s_solution_draws_the_motion_at_its_own_height(browser, app_url, pid, phone):
    """Practice's figures come with "Show the solution", below the answer boxes: no first screen is left
    there to fit the motion to, and a fitted figure was squashed to a 200 px strip (the disk 30 px
    across). Each figure is drawn at its own height, as the figures further down a lesson are."""
    import importlib

    own = [f.height for f in importlib.import_module(f"viz.{pid}").figures(importlib.import_module(f"solvers.{pid}").solve())]
    size = {"width": 390, "height": 844, "phone": True} if phone else {}
    context, page, errors = open_page(browser, f"{app_url}/{pid}?practice=1", **size)
    page.get_by_role("button", name="Show the solution").click()
    page.locator(".dl-figure .main-svg").first.wait_for(timeout=30_000)
    wait_until_idle(page)
    page.wait_for_timeout(500)
    heights = page.evaluate("() => [...document.querySelectorAll('.dl-figure .dl-graph')].map(g => g.getBoundingClientRect().height)")
    assert len(heights) == len(own), (heights, own)
    for height, expected in zip(heights, own):
        assert height >= 0.9 * expected, (pid, heights, own)
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("query", ["theta=10", "theta=80", "r=0.2"])
def test_euler_s_disk_on_a_phone_has_no_empty_bands_round_its_scene(browser, app_url, query):
    """On a phone the 3-D scene's graph is as tall as its box needs (figure.js: sceneHeight): WebGL draws the
    box to the graph's width, and a taller graph left bands above and below it (z's label 128 px below the
    graph's top, x's and y's 83 px above its foot, at the textbook's 10°). The box keeps its size (its x and
    y labels as far apart), and every label stays inside the graph, the disk stood up too, or 20 cm across
    (where plotly.js's round-off once hid two of the three labels)."""
    context, page, errors = open_page(browser, f"{app_url}/eulers_disk?{query}", 390, 844, phone=True)
    wait_until_idle(page)
    page.wait_for_timeout(1000)
    graph, labels = page.evaluate("""() => {
      const g = document.querySelector('.st-key-dl_stage .dl-graph'), box = g.getBoundingClientRect();
      const labels = Object.fromEntries([...g.querySelectorAll('text')].filter(t => /^[xyz] \\(mm\\)$/.test(t.textContent))
        .map(t => { const r = t.getBoundingClientRect(); return [t.textContent[0], [r.left, r.top, r.right, r.bottom]]; }));
      return [[box.left, box.top, box.right, box.bottom], labels];
    }""")
    left, top, right, bottom = graph
    assert set(labels) == {"x", "y", "z"}, labels
    assert labels["z"][1] - top <= 80, (graph, labels)  # the box's top edges above z's label, no more
    for axis in "xy":
        assert 0 <= bottom - labels[axis][3] <= 50, (graph, labels)
        assert labels[axis][0] >= left and labels[axis][2] <= right, (graph, labels)
    assert labels["y"][2] - labels["x"][0] >= 0.6 * (right - left), (graph, labels)
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("size", [(390, 844), (1400, 1000)])
def test_a_still_picture_to_scale_has_no_empty_band_round_it(browser, app_url, size):
    """Beside the pendulum's refusal (θ₀ below the impact angle) a still picture drawn to one scale on both
    axes keeps no empty band above or below its plot (with an animation's 140 px margin for the time
    slider, 85 px were left empty under its x axis's title)."""
    context, page, errors = open_page(browser, f"{app_url}/pendulum_rebound?theta0=-40", *size, phone=size[0] < 500)
    wait_until_idle(page)
    page.wait_for_timeout(800)
    graph, plot, title, legend = page.evaluate("""() => {
      const g = document.querySelector('.st-key-dl_stage .dl-graph'), box = (el) => el ? el.getBoundingClientRect().toJSON() : null;
      return [box(g), box(g.querySelector('.nsewdrag')), box(g.querySelector('.xtitle')), box(g.querySelector('.legend'))];
    }""")
    above = plot["top"] - (legend["bottom"] if legend else graph["top"])
    below = graph["bottom"] - title["bottom"]
    assert 0 <= above <= 40 and 0 <= below <= 40, (above, below)
    assert not errors, errors
    context.close()


def test_a_plot_on_a_phone_s_stage_keeps_its_legend(browser, app_url):
    """Beside the cart's wheelie the ẍ–μ curves stand on the stage: on a phone they keep their legend (a
    motion there drops its legend, its caption naming the bodies; the three drives' curves had no names)."""
    context, page, errors = open_page(browser, f"{app_url}/driven_cart?drive=rear&mu=3", 390, 844, phone=True)
    wait_until_idle(page)
    page.wait_for_timeout(800)
    names = page.evaluate(f"() => [...document.querySelectorAll(\"{STAGE} .dl-graph .legend .legendtext\")].map(t => t.textContent)")
    assert {"front-wheel drive", "rear-wheel drive", "all-wheel drive"} <= set(names), names
    assert not errors, errors
    context.close()


def test_past_a_limit_the_badge_over_a_phone_s_stage_says_the_whole_note(browser, app_url):
    """Dragging the pendulum's θ₀ below the impact angle on a phone: every answer waits, and the badge over the
    figure says why, whole ("Now: released below the angle where the sphere touches the floor: no impact."),
    on as many lines as it takes; it was one line cut short ("Now: relea…") after a headline saying only
    "updating…"."""
    context, page, errors = open_page(browser, f"{app_url}/pendulum_rebound", 390, 844, phone=True)
    page.wait_for_timeout(300)
    slider = page.locator(f"{CONTROLS} [data-testid='stSlider']").nth(1)  # θ₀
    touch = context.new_cdp_session(page)
    x, y = thumb_centre(page, slider)
    touch.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": x, "y": y}]})
    for n in range(1, 9):
        touch.send("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [{"x": max(2, x - 25 * n), "y": y}]})
        page.wait_for_timeout(40)
    page.wait_for_timeout(200)
    badge = page.evaluate("""() => { const b = document.querySelector('.dl-live-badge');
      return {text: b.innerText.trim(), cut: b.scrollWidth > b.clientWidth + 1 || b.scrollHeight > b.clientHeight + 1}; }""")
    touch.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
    assert badge["text"] == "Now: released below the angle where the sphere touches the floor: no impact.", badge
    assert not badge["cut"], badge
    wait_until_idle(page)
    assert not errors, errors
    context.close()


def test_the_live_headline_over_a_phone_s_stage_is_whole_on_every_page(phone_tour):
    """A stage slider dragged on a phone (390 px): the live headline over the figure (the answer the control
    changes and its unit) is whole, on at most two lines, on every page; the ladder's cut its angle: "… the
    wall: 35.26° (0.…" (an angle is given in degrees alone there)."""
    badges = {pid: seen["badge"] for pid, seen in phone_tour.items()}
    assert len(badges) == len(PROBLEMS)
    assert {pid: b["text"] for pid, b in badges.items() if b["cut"] and not b["noteOnly"]} == {}  # (past a limit the note wraps, by design)


MOTION_SCALE = """(g) => { const l = g._fullLayout;
  return l.scene || !l.xaxis ? null : l.xaxis._length / Math.abs(l.xaxis.range[1] - l.xaxis.range[0]); }"""


@pytest.mark.parametrize("size", [(1400, 1000), (390, 844)], ids=["laptop", "phone"])
def test_the_live_headline_shows_what_the_dragged_control_changes(browser, app_url, size):
    """On the pendulum's stage (issue 54: "angle at impact" stood still whatever was dragged): dragging e
    heads the stage with the angular velocity after the impact, dragging θ₀ with the one before it, and
    the number in view moves with the drag."""
    from solvers import live
    from tests.browser.test_browser import TRACK, live_ready
    from solvers.catalog import BY_ID

    problem = BY_ID["pendulum_rebound"]
    solution = problem.solver.solve()
    answers = problem.answers_of(solution)
    names = tuple(a.name for a in answers)
    lead = live.leads(problem.id, live.options_of(problem.id, solution.params), solution.regime, names)
    context, page, errors = open_page(browser, f"{app_url}/pendulum_rebound", *size, phone=size[0] < 500)
    try:
        page.locator(".dl-answers table").first.wait_for(timeout=60_000)
        live_ready(page)
        seen = {}
        for name in ("e", "theta0"):
            key = f"{problem.id}__si__{name}"
            track = page.locator(f".st-key-{key} {TRACK}")
            track.scroll_into_view_if_needed()
            box = track.bounding_box()
            hold_drag(page, box, 0.6, 0.75, moves=2)  # (θ₀ low on its range releases it below the impact angle: no impact)
            first = page.locator(".dl-live-headline").inner_text()
            page.mouse.move(box["x"] + 0.9 * box["width"], box["y"] + box["height"] / 2)
            page.wait_for_timeout(200)
            second = page.locator(".dl-live-headline").inner_text()
            page.mouse.up()
            wait_until_idle(page)
            label = answers[lead[name]].label
            assert first.startswith(label) and second.startswith(label), (name, label, first, second)
            assert first != second, (name, first)  # the number in view follows the drag
            seen[name] = label
        assert seen["e"] != seen["theta0"], seen
        assert not errors, errors
    finally:
        context.close()


@pytest.mark.parametrize("pid, name", [("rod_disk_spring", "k"), ("pendulum_rebound", "theta0")])
def test_a_control_released_past_a_limit_stays_where_it_was_on_a_phone(browser, app_url, pid, name):
    """A phone (390×844): a stage slider dragged past the model's limit and released (the rod's k to its top,
    the pendulum's θ₀ below the impact angle) stays where it was on the screen when the refusal is drawn
    above it (it was pushed to y ≈ 1049 of 844): the student can drag it back at once, and the refusal's
    words are the drag's (the same regime)."""
    from tests.browser.test_browser import TRACK, live_ready

    context, page, errors = open_page(browser, f"{app_url}/{pid}", 390, 844, phone=True)
    try:
        page.locator(".dl-answers table").first.wait_for(timeout=60_000)
        live_ready(page)
        control = page.locator(f".st-key-{pid}__si__{name}")
        control.scroll_into_view_if_needed()
        box = control.locator(TRACK).bounding_box()
        end = 1.05 if name == "k" else 0.02
        hold_drag(page, box, 0.5, end)
        page.wait_for_function("() => (document.querySelector('.dl-live-status') || {}).textContent", timeout=10_000)
        said = page.locator(".dl-live-status").inner_text().removeprefix("Now: ").rstrip(".")
        before = control.bounding_box()["y"]
        page.mouse.up()
        wait_until_idle(page)
        page.locator("[data-testid='stAlert']").first.wait_for(timeout=30_000)
        page.wait_for_timeout(800)
        after = control.bounding_box()
        assert abs(after["y"] - before) < 4 and 0 <= after["y"] and after["y"] + after["height"] <= 844, (before, after)
        refusal = page.locator("[data-testid='stAlert']").first.inner_text()
        assert said and said.casefold() in refusal.casefold(), (said, refusal)
        assert not errors, errors
    finally:
        context.close()




def test_on_a_phone_each_slider_s_end_values_stand_at_its_ends(phone_tour):
    """A phone's stage sliders, two to a row: the ends' values (min and max) under each track stood
    bunched mid-track ("0 100" in 64 px of a 172 px track, issue 54); each stands at its end."""
    ends = {pid: seen["ends"] for pid, seen in phone_tour.items()}
    assert len(ends) == len(PROBLEMS) and all(ends.values()), ends
    assert {pid: [e for e in each if max(e) > 16] for pid, each in ends.items() if any(max(e) > 16 for e in each)} == {}


# Each stage slider's ends' values beside its track's ends (px: the first's left, the last's right).
SLIDER_ENDS = """() => [...document.querySelectorAll(".st-key-dl_stage_controls [data-testid='stSlider']")].map((s) => {
  const track = s.querySelector("[data-orientation='horizontal']").getBoundingClientRect();
  const ticks = [...s.querySelector("[data-testid='stSliderTickBar']").children].map((c) => c.getBoundingClientRect());
  return [ticks[0].left - track.left, track.right - ticks[ticks.length - 1].right]; })"""

# The live badge over the stage as drawn: its text, whether it is cut (or on more than two lines), and
# whether it holds the note alone (past a limit).
BADGE = """() => { const b = document.querySelector('.dl-live-badge');
  const line = parseFloat(getComputedStyle(b).lineHeight);
  return {text: b.textContent, cut: b.scrollWidth > b.clientWidth || b.scrollHeight > b.clientHeight + 1
          || b.querySelector('.dl-live-headline').getClientRects().length > 2 || b.clientHeight > 2.3 * line + 8,
          noteOnly: b.classList.contains('dl-live-note-only')}; }"""


@pytest.fixture(scope="module")
def phone_tour(browser, app_url):
    """Every problem page at 390×844, reached from the navigation as a student goes from page to page, seen
    once for the tests above: its sliders' ends (as opened), then its live badge while the first stage slider
    is held mid-drag (released after: the page runs once more). problem id -> what was seen."""
    context, page, errors = open_page(browser, f"{app_url}/", 390, 844, phone=True)
    seen = {}
    try:
        for problem in PROBLEMS:
            visit(page, app_url, problem.id)
            page.locator(f"{CONTROLS} [data-testid='stSliderTickBar']").first.wait_for(timeout=30_000)
            ends = page.evaluate(SLIDER_ENDS)
            page.locator(f"{STAGE} .dl-figure .dl-graph").first.wait_for()
            hold_drag(page, page.locator(f"{CONTROLS} [data-testid='stSlider'] [role='group'] > [data-orientation]")
                      .first.bounding_box(), 0.3, 0.5)
            page.wait_for_function("() => (document.querySelector('.dl-live-badge') || {}).textContent", timeout=10_000)
            page.wait_for_timeout(200)
            badge = page.evaluate(BADGE)
            page.mouse.up()
            wait_until_idle(page)
            seen[problem.id] = {"ends": ends, "badge": badge}
        assert not errors, errors
    finally:
        context.close()
    return seen
