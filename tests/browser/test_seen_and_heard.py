"""What a student sees and hears, as a second trial found it (issue 29): in Debian's Chromium, the
names a screen reader reads from the accessibility tree, numbers and words never broken inside on a
phone, the figures' width, titles and axis titles kept whole, and an animation that keeps its
stated duration without a GPU. One server and one browser serve the whole module.
"""
from __future__ import annotations

import re
import time

import pytest

from scripts.live_app import wait_until_idle
from tests.browser.test_browser import open_page, visit, watched_context
from solvers.catalog import PROBLEMS

pytestmark = pytest.mark.browser

SIZES = [(1400, 1000), (1280, 720), (390, 844)]
PHONES = [(390, 844), (360, 740)]
CONTROL_ROLES = {"slider", "spinbutton", "button", "combobox", "switch", "checkbox", "radio", "textbox",
                 "listbox", "option", "tab", "link", "menuitem", "searchbox"}
VALUE_ROLES = ("slider", "spinbutton", "textbox")


def is_phone(size) -> bool:
    return size[0] < 500


def open_sized(browser, url: str, size):
    return open_page(browser, url, *size, phone=is_phone(size))


def show_sidebar(page) -> None:
    """The sidebar's controls are the page's too: open it where it starts collapsed (a phone, the
    lecture view)."""
    expand = page.locator("[data-testid='stExpandSidebarButton']")
    if expand.count() and expand.is_visible():
        expand.click()
        page.wait_for_function("() => document.querySelector(\"[data-testid='stSidebar']\")"
                               ".getAttribute('data-collapsed') !== 'true'", timeout=10_000)
        page.wait_for_timeout(500)


def control_names(page) -> list[tuple[str, str]]:
    """(role, accessible name) of every control in Chromium's accessibility tree: what a screen
    reader announces for it."""
    cdp = page.context.new_cdp_session(page)
    try:
        nodes = cdp.send("Accessibility.getFullAXTree")["nodes"]
    finally:
        cdp.detach()
    found = []
    for node in nodes:
        role = (node.get("role") or {}).get("value")
        if node.get("ignored") or role not in CONTROL_ROLES:
            continue
        found.append((role, str((node.get("name") or {}).get("value", ""))))
    return found


def doubled(name: str) -> bool:
    """"A A": the same words said twice in a row."""
    words = name.split()
    half = len(words) // 2
    return len(words) >= 2 and len(words) % 2 == 0 and words[:half] == words[half:]


NAMED_PATHS = ["", "gradebook", *(p.id for p in PROBLEMS), *(f"{p.id}?seed=7" for p in PROBLEMS),
               "pendulum_rebound?units=us&practice=1"]


@pytest.mark.parametrize("size", SIZES, ids=[f"{w}x{h}" for w, h in SIZES])
def test_every_control_is_announced_in_words_once(browser, app_url, size):
    """Every control's accessible name (sliders, number boxes, help buttons, selects, toggles), on
    every page: no TeX ($, \\) and never the same words twice (a slider was announced as
    "$\\theta_0$ — release angle … $\\theta_0$ — release angle …")."""
    bad = {}
    context, page, errors = open_sized(browser, f"{app_url}/", size)
    # Each path at one of the sizes, in turn (names do not change with the width; every size and
    # every path is still read, at a third of the time of each path at each size).
    for path in NAMED_PATHS[SIZES.index(size)::len(SIZES)]:
        visit(page, app_url, path)  # from the navigation where it can be, as a student goes from page to page
        show_sidebar(page)
        names = control_names(page)
        if path not in ("", "gradebook"):
            # A problem's value controls (a slider, a number or an answer box) are drawn before the
            # tree is read: wait for them in the tree itself (the units switch is an input too, and
            # is drawn first, so waiting for any input read a tree without the sliders).
            deadline = time.monotonic() + 30
            while not any(role in VALUE_ROLES for role, _ in names) and time.monotonic() < deadline:
                page.wait_for_timeout(250)
                names = control_names(page)
            assert any(role in VALUE_ROLES for role, _ in names), (path, names)
        wrong = [(role, name) for role, name in names if "$" in name or "\\" in name or doubled(name)]
        if wrong:
            bad[path] = wrong
    assert bad == {}
    assert not errors, errors
    context.close()


# --- a phone: no value, unit or word broken inside ---------------------------------------------

# Every run of characters between spaces (a number with its grouping, a unit, a word) that the page
# lays out over more than one line; a hyphenated word may break after its hyphen.
BROKEN = """() => {
  const root = document.querySelector("[data-testid='stMain']");
  const walker = document.createTreeWalker(root, NodeFilter.SHOW_TEXT);
  const range = document.createRange(), broken = [];
  for (let node = walker.nextNode(); node; node = walker.nextNode()) {
    const el = node.parentElement;
    if (!el || el.closest(".katex, .dl-graph, svg, style, script, .dl-sr") || !el.getClientRects().length) continue;
    for (const m of node.textContent.matchAll(/[^ \\n\\t-]+-?/g)) {
      range.setStart(node, m.index);
      range.setEnd(node, m.index + m[0].length);
      const lines = new Set([...range.getClientRects()].filter(r => r.width > 0).map(r => Math.round(r.bottom)));
      if (lines.size > 1) broken.push(m[0]);
    }
  }
  return broken;
}"""

PHONE_PATHS = ["", *(p.id for p in PROBLEMS), *(f"{p.id}?practice=1" for p in PROBLEMS),
               "pendulum_rebound?units=us", "disk_wall?seed=7"]


@pytest.mark.parametrize("size", PHONES, ids=[f"{w}px" for w, _ in PHONES])
def test_on_a_phone_no_value_unit_or_word_breaks_inside(browser, app_url, size):
    """At 390 or 360 px: the answers, the ledger, the checks, the notes, the problem's givens and
    the captions break only between words (a ledger's "0.943 / 2 N·s", "befor / e" and "kg·m²/ / s"
    were broken inside), and the page still never scrolls sideways."""
    width = size[0]
    context, page, errors = open_sized(browser, f"{app_url}/", size)
    found = {}
    for path in PHONE_PATHS[PHONES.index(size)::len(PHONES)]:  # each path at one width, in turn
        visit(page, app_url, path)  # from the navigation where it can be, as a student goes from page to page
        if path:
            page.locator(".dl-answers table, [data-testid='stMain'] table").first.wait_for(timeout=30_000)
        page.wait_for_timeout(500)
        broken = page.evaluate(BROKEN)
        if broken:
            found[path] = broken
        assert page.evaluate("document.documentElement.scrollWidth") <= width, path
        main = page.locator("[data-testid='stMain']")
        assert main.evaluate("m => m.scrollWidth <= m.clientWidth"), path
    assert found == {}
    assert not errors, errors
    context.close()


# --- the figures ------------------------------------------------------------------------------

def first_figure(page):
    figure = page.locator(".dl-figure").first
    figure.locator(".dl-graph .main-svg").first.wait_for(timeout=30_000)
    page.wait_for_timeout(500)
    return figure


# The shown frames of a Play, by the time readout the component writes for each one it draws.
RECORD_PLAY = """(figure) => {
  window.dlShown = [];
  const readout = figure.querySelector('.dl-readout'), scrub = figure.querySelector('.dl-scrub');
  new MutationObserver(() => window.dlShown.push([performance.now(), Number(scrub.value)]))
    .observe(readout, {childList: true, characterData: true, subtree: true});
  window.dlStart = performance.now();
}"""


def test_play_keeps_the_stated_duration_without_a_gpu(browser, app_url, subtests):
    """Chromium with --disable-gpu, as on many school laptops: Play lasts the frames × frame time the
    figure states (Euler's disk's caption says 4 s; it took 6.5), dropping frames rather than time,
    and shows most of its frames (the 3-D scene is redrawn in place, not replotted). Every page in turn,
    from the navigation, in one tab (each page reported on its own: ``subtests``)."""
    context, page, errors = open_page(browser, f"{app_url}/", 1400, 1000)
    for problem in PROBLEMS:
        with subtests.test(page=problem.id):
            visit(page, app_url, problem.id)
            _play_keeps_its_duration(page, errors, problem)
    context.close()


def _play_keeps_its_duration(page, errors, problem) -> None:
    import importlib
    import json

    spec = json.loads(importlib.import_module(f"viz.{problem.id}").figures(problem.solver.solve(), "si")[0].json())
    frames, frame_ms = len(spec["animation"]["times"]), spec["animation"]["frame_ms"]
    stated = (frames - 1) * frame_ms
    figure = first_figure(page)
    page.wait_for_timeout(1000)
    figure.evaluate(RECORD_PLAY)
    figure.get_by_role("button", name="Play the animation").click()
    page.wait_for_function(f"() => window.dlShown.length && window.dlShown.at(-1)[1] === {frames - 1}",
                           timeout=stated * 4 + 10_000)
    shown = page.evaluate("window.dlShown")
    took = shown[-1][0] - shown[0][0]
    assert stated * 0.9 <= took <= stated * 1.1 + 150, (problem.id, round(took), stated)
    distinct = len({index for _, index in shown})
    assert distinct >= 0.6 * frames, (problem.id, distinct, frames)
    if problem.id == "eulers_disk":
        caption = figure.locator(".dl-description").inner_text()
        assert f"{stated / 1000:.0f} s on screen" in caption and abs(stated / 1000 - round(stated / 1000)) < 0.05, caption
    assert not errors, errors


def test_figures_widen_when_the_sidebar_is_collapsed(browser, app_url):
    context, page, errors = open_page(browser, f"{app_url}/pendulum_rebound", 1400, 1000)
    figure = first_figure(page)
    before = figure.locator(".main-svg").first.bounding_box()["width"]
    page.locator("[data-testid='stSidebar']").hover()  # the collapse button shows on hover
    page.locator("[data-testid='stSidebar'] [data-testid='stSidebarCollapseButton'] button").click()
    page.wait_for_function("() => document.querySelector(\"[data-testid='stSidebar']\")"
                           ".getAttribute('data-collapsed') === 'true'", timeout=10_000)
    page.wait_for_timeout(1000)
    room = figure.bounding_box()["width"]
    after = figure.locator(".main-svg").first.bounding_box()["width"]
    assert room > before + 100 and after >= room - 2, (before, after, room)
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("size", [(1400, 1000), *PHONES], ids=["1400", "390", "360"])
def test_euler_s_disk_s_axis_titles_are_inside_its_figure(browser, app_url, size):
    """The 3-D scene's axis titles were drawn by WebGL, where a phone cut the z-axis's off ("z (mm)"
    absent, "y (mm" cut): they are the scene's own annotations, kept inside the graph."""
    context, page, errors = open_sized(browser, f"{app_url}/eulers_disk", size)
    figure = first_figure(page)
    page.wait_for_timeout(1000)
    graph = figure.locator(".dl-graph").bounding_box()
    titles = {}
    for text in figure.locator(".dl-graph svg text").all():
        if text.text_content() in ("x (mm)", "y (mm)", "z (mm)"):
            titles[text.text_content()] = text.bounding_box()
    assert set(titles) == {"x (mm)", "y (mm)", "z (mm)"}, titles
    for title, box in titles.items():
        assert graph["x"] <= box["x"] and box["x"] + box["width"] <= graph["x"] + graph["width"], (title, box, graph)
    assert not errors, errors
    context.close()


# --- titles are never cut ----------------------------------------------------------------------

CUT = """() => [...document.querySelectorAll("[data-testid='stPageLink'] span, [data-testid='stSidebarNav'] span")]
  .filter(e => e.offsetParent !== null && e.textContent.trim() && e.scrollWidth > e.clientWidth + 1)
  .map(e => e.textContent.trim())"""


@pytest.mark.parametrize("size", [*SIZES, (1024, 768), (360, 740)], ids=["1400", "1280", "390", "1024", "360"])
def test_no_page_title_is_cut_on_the_home_page_or_in_the_navigation(browser, app_url, size):
    """A home card's title read "…off the floo" and the navigation's "Rod-and-sphere pendulum
    bou…": titles wrap instead."""
    context, page, errors = open_sized(browser, f"{app_url}/", size)
    page.locator("[data-testid='stPageLink']").first.wait_for()
    show_sidebar(page)
    assert page.evaluate(CUT) == []
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("theme", ["light", "dark"])
def test_a_navigation_link_reached_by_the_keyboard_shows_its_focus(browser, app_url, theme):
    """Tab onto the navigation's links (the current page's among them): each shows a solid outline in
    a colour that stands out from the sidebar (Streamlit tinted it a faint grey, rgba(…, 0.15), the same
    as the current page's background: there focus could not be seen)."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000}, color_scheme=theme)  # the OS's theme
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(f"{app_url}/pendulum_rebound")
    wait_until_idle(page)
    seen = {}
    for _ in range(40):  # from the page's top: the skip link, then the navigation
        page.keyboard.press("Tab")
        focus = page.evaluate("""() => { const a = document.activeElement;
            if (!a || a.getAttribute('data-testid') !== 'stSidebarNavLink') return null;
            const s = getComputedStyle(a), bar = getComputedStyle(a.closest("[data-testid='stSidebar']"));
            return {text: a.innerText.trim().split('\\n').pop().trim(), style: s.outlineStyle, width: parseFloat(s.outlineWidth),
                    colour: s.outlineColor, sidebar: bar.backgroundColor}; }""")
        if focus:
            seen[focus["text"]] = focus
    assert "Rod-and-sphere pendulum bounces off the floor" in seen and len(seen) >= 8, list(seen)
    for text, focus in seen.items():
        assert focus["style"] == "solid" and focus["width"] >= 2, (text, focus)
        assert contrast(focus["colour"], focus["sidebar"]) >= 3, (text, focus)  # WCAG 1.4.11, non-text contrast
    assert not errors, errors
    context.close()


def contrast(colour: str, background: str) -> float:
    """WCAG's contrast ratio of a CSS rgb()/rgba() colour, drawn over an opaque ``background``."""
    def channels(css: str) -> list[float]:
        numbers = [float(c) for c in re.findall(r"[\d.]+", css)]
        return [c / 255 for c in numbers[:3]] + [numbers[3] if len(numbers) > 3 else 1.0]

    *under, _ = channels(background)
    *over, alpha = channels(colour)
    drawn = [alpha * c + (1 - alpha) * b for c, b in zip(over, under)]

    def luminance(rgb: list[float]) -> float:
        lin = [c / 12.92 if c <= 0.04045 else ((c + 0.055) / 1.055) ** 2.4 for c in rgb]
        return 0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2]
    hi, lo = sorted((luminance(drawn), luminance(under)), reverse=True)
    return (hi + 0.05) / (lo + 0.05)
