"""Where the app is used (issue 14): a projector, a phone, a keyboard and a screen reader.

Measured in Debian's Chromium as a person meets the page: element boxes against the viewport,
computed font sizes inside the figure's frame, and axe-core's WCAG 2.1 A/AA rules (serious and
critical findings) on the project's own content, figure frames included. One server and one
browser serve the whole module.
"""
from __future__ import annotations

import pytest

from scripts.live_app import SETTLED, wait_until_idle
from tests.browser.test_browser import kept_context, open_page, tour, visit, wait_moved, watched_context
from tests.browser.test_stage import MOTION_SCALE, overlaps, stage_faults, stage_graph
from solvers.catalog import PROBLEMS
from ui.params import is_slider
from ui.figure import LECTURE

pytestmark = pytest.mark.browser

axe_playwright = pytest.importorskip("axe_playwright_python.sync_playwright")

IDS = [p.id for p in PROBLEMS]
PROJECTORS = [(1280, 720), (1024, 768)]
PHONES = [(390, 844), (360, 740)]
# The figure component's root (ui/plotly_component/figure.js): in the page itself, no frame.
FIGURE = ".dl-figure"
WCAG = {"runOnly": {"type": "tag", "values": ["wcag2a", "wcag2aa", "wcag21a", "wcag21aa"]},
        "resultTypes": ["violations"]}
# Streamlit's own page navigation fails two list rules even in an empty app: not the project's.
STREAMLIT_OWN = {"exclude": [["[data-testid='stSidebarNav']"]]}
# A moving trace's first coordinates: they change when the animation moves.
# A slider's thumb: Streamlit 1.67 gives it no role="slider", only focus and aria-valuetext.
SLIDER = "[data-testid='stSlider'] [aria-valuetext]"
SNAPSHOT = ("(el) => JSON.stringify(el._fullData.map(t => [t.x && Array.from(t.x).slice(0, 4), "
            "t.y && Array.from(t.y).slice(0, 4)]))")


def open_at(browser, url: str, size: tuple[int, int], phone: bool = False):
    return open_page(browser, url, *size, phone=phone)


def graph_of(page):
    """The first figure, once its graph is drawn."""
    figure = page.locator(FIGURE).first
    figure.locator(".dl-graph .main-svg").first.wait_for()
    page.wait_for_timeout(300)
    return figure


def serious_violations(page) -> list[str]:
    """axe-core's serious and critical WCAG 2.1 A/AA findings, in the page and in every frame, each audited
    once its transitions have ended (``SETTLED``)."""
    axe = axe_playwright.Axe()
    found = []
    for frame in page.frames:
        frame.evaluate(SETTLED, 50)  # (50 ms: a fade may begin a few frames late, once hover is looked at again)
        context = STREAMLIT_OWN if frame == page.main_frame else None
        for v in axe.run(frame, context=context, options=WCAG).response["violations"]:
            if v["impact"] in ("serious", "critical"):
                targets = [n["target"] for n in v["nodes"][:3]]
                found.append(f"{frame.url.rsplit('/', 1)[-1][:40]}: {v['id']} ({v['impact']}) {targets}")
    return found


def sidebar_collapsed(page) -> bool:
    return page.locator("[data-testid='stSidebar']").get_attribute("data-collapsed") == "true"


def answers_table(page):
    return page.locator("[data-testid='stMain'] table").first


# --- the projector ---------------------------------------------------------------------------

def test_lecture_view_on_a_projector_and_a_smaller_one(browser, app_url):
    """The lecture size (1280x720) on every page; the smaller projector (1024x768) on every other page (suite
    time). And on every page with a 2-D motion, the smaller projector draws it not much smaller: on a 1024x768
    projector the lecture's legend in a column beside the motion took 330 of its 520 px (the stick drawn at 46
    px a metre against 86 at 1280x720, the cart at 32); the legend stands beside the motion or in rows above
    it, whichever draws the motion larger: a projector 0.8 times as wide draws it at least 0.6 times as large
    (px per unit of its x axis)."""
    scales = {}
    for size in PROJECTORS:
        context = kept_context(browser, *size)
        checked = [p for p in PROBLEMS if size == PROJECTORS[0] or p in PROBLEMS[1::2]]
        visited = [p for p in PROBLEMS if p in checked or p.id != "eulers_disk"]
        # each a new page, as a fresh visit, in the same browser (the app's scripts from its cache)
        for problem, (page, errors) in zip(visited, tour(context, [f"{app_url}/{p.id}?lecture=1" for p in visited])):
            scales[problem.id, size] = stage_graph(page).evaluate(MOTION_SCALE)
            if problem in checked:
                _lecture_view_checks(page, problem, size)
            assert not errors, (problem.id, size, errors)
        context.close()
    smaller = {pid: (scales[pid, PROJECTORS[0]], scale) for (pid, size), scale in scales.items()
               if size == PROJECTORS[1] and scale is not None}
    assert len(smaller) == len(PROBLEMS) - 1  # every page but Euler's disk's 3-D scene
    assert {pid: pair for pid, pair in smaller.items() if pair[1] < 0.6 * pair[0]} == {}


def _lecture_view_checks(page, problem, size) -> None:
    """The lecture view's checks on one page (opened at ``size``, idle), for its stage, figure, type and audit."""
    width, height = size
    where = f"{problem.id} at {width}x{height}"
    assert sidebar_collapsed(page), where
    frame = graph_of(page)
    # The stage: the lesson's controls beside the motion, in the first screen; the bodies fill the plot.
    assert stage_faults(page, problem, height) == [], where
    frame_top = page.locator(FIGURE).first.bounding_box()["y"]
    graph = frame.locator(".dl-graph").bounding_box()
    play = frame.get_by_role("button", name="Play the animation").bounding_box()
    # The whole figure and its Play control within the first screen, with no scrolling (boxes
    # inside the frame are in the page's coordinates).
    assert 0 <= frame_top <= play["y"] and graph["y"] + graph["height"] <= height, where
    assert play["y"] + play["height"] <= height, where
    # Every text the figure draws (ticks, axis titles, legend, labels) at least 18 px.
    fonts = frame.locator(".dl-graph").evaluate(
        "g => [...g.querySelectorAll('text')].filter(t => t.textContent.trim())"
        ".map(t => parseFloat(getComputedStyle(t).fontSize))")
    assert fonts and min(fonts) >= LECTURE["min_font"], (where, sorted(fonts)[:5])
    # And every text of the lesson's controls beside it (labels, values, options), none over another.
    controls = page.locator(".st-key-dl_stage_controls").evaluate(
        "c => [...c.querySelectorAll('*')].filter(e => e.offsetParent !== null && ([...e.childNodes].some("
        "n => n.nodeType === 3 && n.textContent.trim()) || e.tagName === 'INPUT' && e.type !== 'range'))"
        ".map(e => { const r = e.getBoundingClientRect(); return [e.textContent.trim().slice(0, 30) || e.value,"
        " parseFloat(getComputedStyle(e).fontSize), {x: r.x, y: r.y, width: r.width, height: r.height}]; })")
    assert controls and min(size for _, size, _ in controls) >= LECTURE["min_font"], (where, sorted(controls, key=lambda c: c[1])[:3])
    texts = [(text, box) for text, _, box in controls if box["width"] and box["height"]]
    over = [(a, b) for n, (a, box) in enumerate(texts) for b, other in texts[n + 1:]
            if overlaps(box, other) and not (inside(box, other) or inside(other, box))]  # (nested: one text)
    assert over == [], (where, over)
    # Lines and markers as drawn: thicker than the study view's thinnest (1 px lines, 9 px markers).
    widths = frame.locator(".dl-graph").evaluate(
        # (a filled body's outline follows its drawn size instead: tests/browser/test_stage.py)
        "g => g._fullData.flatMap(t => [t.line && t.mode !== 'markers' && t.fill !== 'toself' ? t.line.width : null,"
        " t.marker && /markers/.test(t.mode || '') ? t.marker.size : null]).filter(v => v != null)")
    assert min(widths) >= 1.8, (where, widths)
    # The answers follow the figure, in large type.
    table = answers_table(page)
    assert table.bounding_box()["y"] > graph["y"] + graph["height"], where
    assert float(table.evaluate("t => getComputedStyle(t).fontSize").rstrip("px")) >= 20, where
    # And every paragraph and list item of the answers and the derivation (the checks, the notes,
    # the slips), which Streamlit's own 1rem for p, ul and ol would keep at 16 px.
    sizes = page.locator(".dl-text p, .dl-text li").evaluate_all(
        "els => els.map(e => parseFloat(getComputedStyle(e).fontSize))")
    assert sizes and min(sizes) >= 20, (where, sorted(sizes)[:3])
    assert serious_violations(page) == [], where
    if all(is_slider(p) for p in problem.solver.PARAMS if p.name in problem.primary and hasattr(p, "dimension")):
        _controls_beside_and_the_figure_stays(page, where)
    if problem == PROBLEMS[0] and size == PROJECTORS[0]:
        _the_figure_follows_the_sidebar(page, where)


def inside(a: dict, b: dict) -> bool:
    """Box ``a`` within box ``b``."""
    return (b["x"] - 1 <= a["x"] and a["x"] + a["width"] <= b["x"] + b["width"] + 1
            and b["y"] - 1 <= a["y"] and a["y"] + a["height"] <= b["y"] + b["height"] + 1)


def _controls_beside_and_the_figure_stays(page, where: str) -> None:
    """The lesson's controls stand beside the figure with the sidebar closed; changing a parameter
    does not move the figure."""
    slider = page.locator(".st-key-dl_stage_controls " + SLIDER).first
    slider.wait_for()
    assert sidebar_collapsed(page), where
    frame_top = page.locator(FIGURE).first.bounding_box()["y"]
    before = answers_table(page).inner_text()
    slider.focus()
    slider.press("ArrowLeft")
    # the run's answers, not the live values shown before it (live.js commits a key press once the key is up)
    page.wait_for_function("(before) => document.querySelector(\"[data-testid='stMain'] table\").innerText"
                           " !== before && !document.querySelector('.dl-live-value')", arg=before, timeout=30_000)
    wait_until_idle(page)
    assert page.locator(FIGURE).first.bounding_box()["y"] == pytest.approx(frame_top, abs=2), where
    assert page.evaluate("document.querySelector(\"[data-testid='stMain']\").scrollTop") == 0, where


def _the_figure_follows_the_sidebar(page, where: str) -> None:
    """Opening the sidebar (») narrows the figure, closing it widens it again: drawn, not clipped."""
    graph = page.locator(f"{FIGURE} .dl-graph").first
    drawn = graph.locator(".main-svg").first
    wide = graph.bounding_box()["width"]
    for button, narrower in (("[data-testid='stExpandSidebarButton']", True),
                             ("[data-testid='stSidebar'] [data-testid='stSidebarCollapseButton'] button", False)):
        page.locator(button).click()
        follows = (lambda w: w < wide - 100) if narrower else (lambda w: w == pytest.approx(wide, abs=2))
        for _ in range(50):  # (the sidebar slides, then the figure is redrawn: up to 10 s on a busy machine)
            page.wait_for_timeout(200)
            width = graph.bounding_box()["width"]
            if follows(width) and drawn.bounding_box()["width"] == pytest.approx(width, abs=2):
                break
        assert follows(width), (where, wide, width)
        assert drawn.bounding_box()["width"] == pytest.approx(width, abs=2), (where, "the drawing did not follow")


# --- the phone -------------------------------------------------------------------------------

@pytest.mark.parametrize("size", PHONES, ids=[f"{w}x{h}" for w, h in PHONES])
def test_on_a_phone(browser, app_url, size):
    width, _ = size
    # The phone size of the issues (390x844) on every page; the narrowest on every other page.
    pages = PROBLEMS if size == PHONES[0] else PROBLEMS[::2]
    context, page, errors = open_at(browser, f"{app_url}/{pages[0].id}", size, phone=True)
    for n, problem in enumerate(pages):
        if n:
            visit(page, app_url, problem.id)  # from the navigation, as a student goes from page to page
        where = f"{problem.id} at {width} px"
        frame = graph_of(page)  # measure the settled page, its figure drawn
        # The stage: the motion, Play and the lesson's controls (below it) in the first screen of a phone.
        assert stage_faults(page, problem, size[1]) == [], where
        # The page never scrolls sideways.
        assert page.evaluate("document.documentElement.scrollWidth") <= width, where
        main = page.locator("[data-testid='stMain']")
        assert main.evaluate("m => m.scrollWidth <= m.clientWidth"), where
        # No display equation is wider than its box (KaTeX draws each row as .base boxes).
        wide = page.evaluate(
            "() => [...document.querySelectorAll(\"[data-testid='stMain'] .katex-display\")].filter(d => {"
            " const box = d.getBoundingClientRect();"
            " return [...d.querySelectorAll('.katex-html .base')].some(b => b.getBoundingClientRect().right > box.right + 0.5);"
            "}).map(d => d.querySelector('annotation').textContent.slice(0, 80))")
        assert wide == [], (where, wide)
        assert page.locator("[data-testid='stMain'] .katex-error").count() == 0, where
        # The figure fits the width, and Play works by touch.
        iframe = page.locator(FIGURE).first.bounding_box()
        assert iframe["x"] >= 0 and iframe["x"] + iframe["width"] <= width, where
        svg_width = frame.locator(".dl-graph .main-svg").first.bounding_box()["width"]
        assert svg_width <= iframe["width"] + 0.5, where
        graph = frame.locator(".dl-graph")
        start = graph.evaluate(SNAPSHOT)
        frame.get_by_role("button", name="Play the animation").tap()
        assert wait_moved(graph, SNAPSHOT, start) != start, f"{where}: a tap on Play did not move the animation"
        frame.get_by_role("button", name="Pause the animation").tap()
        if width == 360:
            assert serious_violations(page) == [], where
        if n == 0:
            _controls_reachable_and_results_kept(page, where)
        assert not errors, (where, errors)
    context.close()


def _controls_reachable_and_results_kept(page, where: str) -> None:
    """The controls open over the page, a change follows, and closing them shows the new results."""
    before = answers_table(page).inner_text()
    page.locator("[data-testid='stExpandSidebarButton']").tap()
    box = page.locator("[data-testid='stSidebar'] [data-testid='stNumberInput'] input").first
    if not box.is_visible():
        page.locator("[data-testid='stSidebar']").get_by_text("More parameters", exact=True).tap()
    box.wait_for()
    box.tap()
    box.fill(f"{float(box.input_value()) * 1.1:.6g}")
    box.press("Enter")
    page.wait_for_function("(before) => { const t = document.querySelector(\"[data-testid='stMain'] table\");"
                           " return t && t.innerText !== before; }", arg=before, timeout=30_000)
    wait_until_idle(page)
    page.locator("[data-testid='stSidebar'] [data-testid='stSidebarCollapseButton'] button").tap()
    page.wait_for_timeout(500)
    assert answers_table(page).is_visible(), where
    assert answers_table(page).inner_text() != before, where


# --- the screen reader and the keyboard ------------------------------------------------------

VIEWS = [("", "home")] + [(f"{p.id}{q}", f"{p.id}{q or '-study'}") for p in PROBLEMS for q in ("", "?practice=1")]


def test_no_serious_accessibility_violations_in_study_and_practice_and_home(browser, app_url):
    """The lecture view is audited in the projector test, the study view again on a phone."""
    context = watched_context(browser, viewport={"width": 1280, "height": 720})
    page = context.new_page()
    found = {}
    for path, name in VIEWS:
        visit(page, app_url, path)  # from the navigation where it can be
        if page.locator(FIGURE).count():
            graph_of(page)  # audit the figure's frame drawn
        found[name] = serious_violations(page)
        if not path:  # the gallery's pictures are there, each with its text alternative
            alts = page.locator("[data-testid='stMain'] img").evaluate_all("imgs => imgs.map(i => i.alt)")
            assert len(alts) == len(PROBLEMS) and all(alts), alts
    assert {k: v for k, v in found.items() if v} == {}
    context.close()


def test_the_view_and_the_animation_answer_the_keyboard(browser, app_url):
    context, page, errors = open_at(browser, f"{app_url}/pendulum_rebound", (1400, 1000))
    lecture = page.locator("[data-testid='stSidebar']").get_by_role("radio", name="Lecture")
    lecture.focus()
    page.keyboard.press("Enter")
    page.wait_for_url("**lecture=1**", timeout=30_000)
    wait_until_idle(page)
    frame = graph_of(page)
    graph = frame.locator(".dl-graph")
    start = graph.evaluate(SNAPSHOT)
    frame.get_by_role("button", name="Play the animation").focus()
    page.keyboard.press("Enter")
    page.wait_for_timeout(1200)
    moved = graph.evaluate(SNAPSHOT)
    assert moved != start, "Enter on Play did not start the animation"
    page.keyboard.press(" ")  # Space pauses
    page.wait_for_timeout(300)
    paused = graph.evaluate(SNAPSHOT)
    page.wait_for_timeout(500)
    assert graph.evaluate(SNAPSHOT) == paused, "Space did not pause"
    frame.get_by_role("button", name="Step forward one frame").focus()
    page.keyboard.press("Enter")
    page.wait_for_timeout(300)
    assert graph.evaluate(SNAPSHOT) != paused, "the step button did not step"
    stepped = graph.evaluate(SNAPSHOT)
    page.keyboard.press("ArrowLeft")
    page.wait_for_timeout(300)
    assert graph.evaluate(SNAPSHOT) != stepped, "← did not step back"
    assert not errors, errors
    context.close()
