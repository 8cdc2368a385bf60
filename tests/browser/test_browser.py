"""The app in a real browser: Playwright driving Debian's Chromium against a live server.

Each page is opened from the navigation, a control is changed from the keyboard as a person
would, the answers and the derivation must follow with no error box, and Play must move the
animation. A screenshot of each page goes to screenshots/browser/ (ignored by git).
Skipped when Chromium is missing on a workstation; in CI (CI set) a missing browser fails.
"""
from __future__ import annotations

import re
import time
from pathlib import Path

import pytest

from edge.streamlit_dom import SELECTORS
from scripts.live_app import IDLE_WATCH, wait_until_idle
from solvers.catalog import PROBLEMS

pytestmark = pytest.mark.browser
SHOTS = Path(__file__).resolve().parents[2] / "screenshots" / "browser"


def open_page(browser, url: str, width: int = 1400, height: int = 1000, phone: bool = False,
              zone: str | None = None):
    """A new page at this viewport (a phone: mobile, touch, 2× pixels) and time zone, opened and idle, its
    context (``context.close()`` when done) and the list its script errors go to. The page is new (a new
    session of the app); its context is the module's for that viewport (``Kept``)."""
    lease = kept_context(browser, width, height, phone, zone)
    return (lease, *open_in(lease, url))


def watched_context(browser, **options):
    """A new browser context (``browser.new_context``'s options) whose pages keep the records ``wait_until_idle``
    and ``csp_violations`` read (``IDLE_WATCH``, ``CSP_WATCH``), for a test that needs a context of its own."""
    context = browser.new_context(**options)
    context.add_init_script(CSP_WATCH)
    context.add_init_script(IDLE_WATCH)
    return context


def kept_context(browser, width: int = 1400, height: int = 1000, phone: bool = False, zone: str | None = None):
    """The module's context for this viewport (a phone: mobile, touch, 2× pixels) and time zone, as a ``Lease``
    (``close()`` when done)."""
    extra = {"is_mobile": True, "has_touch": True, "device_scale_factor": 2} if phone else {}
    if zone:
        extra["timezone_id"] = zone
    key = (width, height, phone, zone)
    kept = _KEPT.setdefault(browser, {})
    if key not in kept or kept[key].closed:
        kept[key] = Kept(watched_context(browser, viewport={"width": width, "height": height}, **extra))
    return Lease(kept[key])


class Kept:
    """A browser context kept for a module's tests at one viewport: a fresh context's first load costs a
    2-core machine about a second more than a load with the app's scripts in the cache."""

    def __init__(self, context):
        self.context, self.closed = context, False


class Lease:
    """A test's use of a kept context, as ``open_page`` returns it: ``close()`` closes the pages opened through
    it, and the context itself too if the test changed it (anything but opening pages: routes, handlers,
    permissions), so that the next test meets it as new."""

    def __init__(self, kept: Kept):
        self.kept, self.pages, self.changed = kept, [], False

    def new_page(self):
        page = self.kept.context.new_page()
        self.pages.append(page)
        return page

    def new_cdp_session(self, page):
        return self.kept.context.new_cdp_session(page)

    def __getattr__(self, name: str):
        self.changed = True
        return getattr(self.kept.context, name)

    def close(self) -> None:
        for page in self.pages:
            page.close()
        self.pages = []
        if self.changed and not self.kept.closed:
            self.kept.closed = True
            self.kept.context.close()


_KEPT: dict = {}  # browser -> {(width, height, phone, zone): Kept}


def open_in(context, url: str):
    """A new page in ``context`` (opened by ``open_page``: its viewport, its cache of the app's scripts), opened
    at ``url`` and idle, and the list its script errors go to."""
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(url)
    wait_until_idle(page)
    return page, errors


def tour(context, urls):
    """Each of ``urls`` in a new page of ``context`` (``kept_context``), handed over idle as (page, errors) and
    closed when the next is asked for; the next one's load starts before a page is handed over, so a second
    renderer works on the machine's second core while the caller measures this one (a tour of the seven pages
    in 0.7 of the time of one after another: docs/benchmarks-log.md)."""
    def start(url):
        page, errors = context.new_page(), []
        page.on("pageerror", lambda exc: errors.append(str(exc)))
        page.goto(url, wait_until="commit")
        return page, errors

    ahead = start(urls[0]) if urls else None
    for n in range(len(urls)):
        page, errors = ahead
        ahead = start(urls[n + 1]) if n + 1 < len(urls) else None
        wait_until_idle(page)
        yield page, errors
        page.close()


def visit(page, app_url: str, path: str) -> None:
    """Open ``path`` ("disk_wall", or "" for the home page) as a student going through the app does: by its
    link in the navigation, in the page already open, where Streamlit's frontend and plotly.js stay loaded (a
    third of a fresh load's work in the browser: docs/benchmarks-log.md, "A page visit in the browser tests");
    by its address where it carries a query or the page is not the app's yet. Idle after."""
    link = page.locator(f"{SELECTORS['sidebarNavLink']}[href='{app_url}/{path}']")
    if "?" in path or not page.url.startswith(app_url) or link.count() != 1:
        page.goto(f"{app_url}/{path}")
    else:
        link.evaluate("a => a.click()")  # (on a phone the navigation is in the closed sidebar: a script's click)
        page.wait_for_url(re.compile(rf"{re.escape(app_url)}/{re.escape(path)}(\?.*)?$"))
    wait_until_idle(page)


TRACK = "[data-orientation='horizontal'][style*='position: relative']"  # a Streamlit slider's track (within its control)


def hold_drag(page, track: dict, start: float, end: float, moves: int = 5) -> None:
    """The mouse pressed on ``track`` (a bounding box) at the fraction ``start`` of its width and moved to
    ``end`` in ``moves`` steps, 40 ms apart, and held there (the caller releases it)."""
    x, y = track["x"] + start * track["width"], track["y"] + track["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    for i in range(1, moves + 1):
        page.mouse.move(x + (end - start) * track["width"] * i / moves, y)
        page.wait_for_timeout(40)

# Every Content-Security-Policy violation a page meets, kept for csp_violations(page).
CSP_WATCH = ("window.__csp = []; document.addEventListener('securitypolicyviolation', "
             "e => window.__csp.push(e.violatedDirective + ' ' + e.blockedURI));"
             # every message the page sends on a websocket (after the load, each one a run asked for: RUN_COUNTER)
             " window.__sent = 0; const send = WebSocket.prototype.send;"
             " WebSocket.prototype.send = function (data) { window.__sent++; return send.call(this, data); };")


def wait_moved(graph, snapshot: str, start: str, timeout: float = 10) -> str:
    """``graph``'s ``snapshot`` (an expression of the element) once it differs from ``start`` (a Play has moved the
    animation), or as it is after ``timeout`` seconds (the caller asserts it moved)."""
    deadline = time.monotonic() + timeout
    now = graph.evaluate(snapshot)
    while now == start and time.monotonic() < deadline:
        graph.page.wait_for_timeout(50)
        now = graph.evaluate(snapshot)
    return now


def csp_violations(page) -> list[str]:
    return page.evaluate("window.__csp")


def main_text(page) -> str:
    return page.locator("[data-testid='stMain']").inner_text()


def derivation_text(page) -> str:
    """The derivation's element (ui/plotly_component/text.js) as the page shows it."""
    return page.locator("[data-testid='stMain'] .dl-derivation").inner_text()


def answers_table(page) -> str:
    return page.locator("[data-testid='stMain'] table").first.inner_text()


def test_a_deep_link_on_a_fresh_server_gets_the_app(browser, fresh_server):
    """The first visit of a server nobody has opened yet: a deep link with a parameter."""
    context, page, errors = open_page(browser, f"{fresh_server.url}/driven_cart?mu=0.5")
    nav = page.locator("[data-testid='stSidebarNav']").inner_text()
    assert "Euler's disk" in nav and "Home" in nav  # the app's navigation (app_pages/: no legacy pages mode)
    # (its heading may come a moment after the first idle state on a busy machine)
    page.locator("[data-testid='stMain'] h1", has_text="Cart with driven wheels").wait_for(timeout=30_000)
    assert page.locator("[data-testid='stException']").count() == 0
    assert not errors
    context.close()


def test_without_katex_the_answers_still_show_their_values(browser, app_url):
    """KaTeX's script lost on the way (a network dropping mid-visit): the answers' numbers, the
    ledger and the checks still show, the symbols and equations as their TeX."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    context.route("**/katex.*.min.js", lambda route: route.abort())
    page = context.new_page()
    errors: list[str] = []
    page.on("pageerror", lambda exc: errors.append(str(exc)))
    page.goto(f"{app_url}/disk_wall")
    page.locator(".dl-answers table").first.wait_for(timeout=30_000)
    wait_until_idle(page)
    table = page.locator(".dl-answers table").first.inner_text()
    assert "m/s" in table and "v_{1x}" in table, table  # the value, and the symbol as TeX
    assert page.locator(".dl-answers li").count() >= 3 and page.locator(".dl-derivation code").count() >= 6
    # The network back: the next change typesets every formula shown, the unchanged ones too.
    context.unroute("**/katex.*.min.js")
    page.locator(".st-key-disk_wall__si__V input[type='range']").press("ArrowRight")  # V, on the stage
    page.wait_for_function("() => !document.querySelector('.dl-text code')"
                           " && document.querySelectorAll('.dl-answers .katex').length >= 7", timeout=30_000)
    assert page.locator(".dl-derivation .katex-display").count() >= 6
    assert not errors, errors
    context.close()


def test_a_shared_link_to_a_heading_lands_on_it_and_each_check_says_it_agrees(browser, app_url):
    """The answers' and the derivation's headings keep the ids Streamlit's Markdown gave them, so a
    link to one scrolls there once the element is drawn; a passing check is said, not only shown."""
    context, page, errors = open_page(browser, f"{app_url}/stick_ball#checked-a-second-way")
    heading = page.locator("#checked-a-second-way")
    heading.wait_for(timeout=30_000)
    page.wait_for_function("() => { const r = document.getElementById('checked-a-second-way')"
                           ".getBoundingClientRect(); return r.top >= 40 && r.top < 200; }", timeout=10_000)  # below the header
    ids = page.locator(".dl-text h3, .dl-text h4").evaluate_all("hs => hs.map(h => h.id)")
    assert {"answers", "across-the-impact", "checked-a-second-way", "derivation-step-by-step"} <= set(ids), ids
    spoken = page.locator(".dl-answers ul").aria_snapshot()  # what a screen reader is given
    items = spoken.count("- listitem")
    assert items and spoken.count('text: "agrees:"') == items and "✓" not in spoken, spoken
    assert not errors, errors
    context.close()


def test_every_request_stays_on_the_app_s_own_server(browser, app_url):
    """A lecture hall's network, or a course site's policy, may reach nothing but the app: no font,
    icon or script from anywhere else (the tab's icon too: a Material icon there was fetched from
    fonts.gstatic.com)."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    elsewhere: list[str] = []
    context.on("request", lambda r: None if r.url.startswith((app_url, "data:", "blob:")) else elsewhere.append(r.url))
    page = context.new_page()
    for path in ("/", f"/{PROBLEMS[0].id}"):
        page.goto(app_url + path)
        wait_until_idle(page)
    page.locator("[data-testid='stMain'] .js-plotly-plot").first.wait_for(timeout=30_000)  # really drawn
    page.wait_for_timeout(500)  # and what it asks for after drawing
    assert not elsewhere, elsewhere
    context.close()


def test_each_page_from_the_navigation_follows_its_controls_and_animates(browser, app_url, subtests):
    """From the home page, each problem page in turn by its link in the navigation, in one tab as a student
    goes through them (each page's checks reported on their own: ``subtests``)."""
    context, page, errors = open_page(browser, app_url)
    for problem in PROBLEMS:
        with subtests.test(page=problem.id):
            _follows_its_controls_and_animates(page, errors, problem)
    context.close()


def _follows_its_controls_and_animates(page, errors, problem) -> None:
    """One problem's page opened from the navigation: a number box and a slider changed from the keyboard move
    the answers and the derivation, Play and the arrow keys move the animation."""
    page.locator("[data-testid='stSidebarNav']").get_by_text(problem.title, exact=True).click()
    page.wait_for_url(f"**/{problem.id}")
    wait_until_idle(page)
    page.get_by_role("heading", name=problem.title).wait_for()
    before_answers, before_derivation = answers_table(page), derivation_text(page)
    # The slips' Markdown (bold, emphasis, inline math) is rendered, not shown as marks.
    assert not re.search(r"\*\w|\w\*|\$", before_derivation), before_derivation

    # Change the first number box as a person does: select, type, Enter. A page whose lesson
    # parameters are all sliders has its number boxes under "More parameters": open it first.
    boxes = page.locator("[data-testid='stSidebar'] [data-testid='stNumberInput'] input")
    if boxes.count() == 0:
        page.locator("[data-testid='stSidebar']").get_by_text("More parameters", exact=True).click()
        boxes.first.wait_for(timeout=30_000)
        wait_until_idle(page)
    box = boxes.first
    box.click()
    value = float(box.input_value())
    box.press("Control+a")
    box.type(f"{value * 1.1:.6g}")
    box.press("Enter")
    page.wait_for_function("(before) => { const t = document.querySelector(\"[data-testid='stMain'] table\");"
                           " return t && t.innerText !== before; }", arg=before_answers, timeout=30_000)
    wait_until_idle(page)
    assert answers_table(page) != before_answers
    assert derivation_text(page) != before_derivation  # the derivation's numbers follow
    assert page.locator("[data-testid='stException']").count() == 0
    assert page.locator("[data-testid='stAlertContentError']").count() == 0

    # A slider (angles, restitution) answers the keyboard too: a lesson's, on the stage beside the figure.
    slider = page.locator(".st-key-dl_stage_controls [data-testid='stSlider'] input[type='range']").first
    if slider.count():
        before = answers_table(page)
        slider.focus()
        slider.press("ArrowLeft")
        # the run's answers, not the live values shown before it (live.js commits a key press once the key is up)
        page.wait_for_function("(before) => document.querySelector(\"[data-testid='stMain'] table\").innerText"
                               " !== before && !document.querySelector('.dl-live-value')", arg=before, timeout=30_000)
        wait_until_idle(page)

    # Play moves the animation: a moving trace's coordinates change; the keyboard steps it too.
    figure = page.locator(".dl-figure").first  # the figure component, in the page (no frame)
    graph = figure.locator(".dl-graph")
    graph.wait_for()
    snapshot = ("(el) => JSON.stringify(el._fullData.map(t => [t.x && Array.from(t.x).slice(0, 4), "
                "t.y && Array.from(t.y).slice(0, 4)]))")
    start = graph.evaluate(snapshot)
    figure.get_by_role("button", name="Play the animation").click()
    assert wait_moved(graph, snapshot, start) != start, "Play did not move the animation"
    figure.get_by_role("button", name="Pause the animation").click()
    page.wait_for_timeout(300)
    paused = graph.evaluate(snapshot)
    figure.press("ArrowRight")
    page.wait_for_timeout(300)
    assert graph.evaluate(snapshot) != paused, "the arrow key did not step the animation"
    assert not errors, errors
    assert csp_violations(page) == []  # the page works under the app's Content-Security-Policy

    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"{problem.id}.png"))


def test_a_bad_link_shows_a_warning_not_a_traceback(browser, app_url):
    context, page, errors = open_page(browser, f"{app_url}/stick_ball?v=NaN&mode=%3Cscript%3E")
    text = main_text(page)
    assert "using the default instead" in text
    assert "Traceback" not in text and page.locator("[data-testid='stException']").count() == 0
    context.close()


def test_practice_mode_in_the_browser(browser, app_url):
    context, page, errors = open_page(browser, f"{app_url}/disk_wall?practice=1&seed=5")
    assert "not a proctored assessment" in main_text(page)
    page.get_by_role("textbox", name="Your answer").fill("2/3*V*sin(theta) + R*omega/3")
    page.get_by_role("button", name="Check", exact=True).click()
    page.get_by_text("Right: that is the answer").wait_for(timeout=30_000)
    page.get_by_role("textbox", name="Your answer").fill("![x](http://example.invalid/x.png)")
    page.get_by_role("button", name="Check", exact=True).click()
    page.get_by_text("is not allowed").wait_for(timeout=30_000)
    assert page.locator("[data-testid='stMain'] img[src*='example.invalid']").count() == 0
    context.close()


def help_texts(page) -> list[str]:
    """The text of every help tooltip in the main area that a student can hover (not one inside a
    closed expander, such as the instructor key's), shown by hovering over its icon."""
    icons = page.locator("[data-testid='stMain'] [data-testid='stTooltipIcon']:visible")
    texts = []
    for i in range(icons.count()):
        icons.nth(i).hover()
        tip = page.locator("[data-testid='stTooltipContent']").last
        tip.wait_for(timeout=5_000)
        texts.append(tip.inner_text())
        page.mouse.move(0, 0)
    assert any("the givens:" in t for t in texts), texts  # the answer box's help was read
    return texts


@pytest.mark.parametrize("problem", PROBLEMS, ids=lambda p: p.id)
def test_the_whole_practice_page_gives_no_answer_away(browser, app_url, problem):
    """Everything the Practice view puts in the browser (the text of the main area and the sidebar,
    the TeX behind every equation, labels, titles, any figure's frame, and the URL) holds no
    answer's value or closed form, for the textbook's numbers, a student's variant and every option
    that changes the derivation (e.g. the cart's rear and all-wheel drives)."""
    from practice.variants import variant
    from urllib.parse import urlencode

    from tests.practice.test_practice import OPTIONS, leaks, setup

    options = [(f"practice=1&{urlencode(o)}", o) for pid, o in OPTIONS if pid == problem.id and o]
    context, page, errors = open_page(browser, f"{app_url}/{problem.id}?practice=1")
    for n, (query, params) in enumerate((("practice=1", {}), ("seed=7", variant(problem.solver, problem.id, 7)),
                                         *options)):
        if n:  # by its address, in the same browser: a new session, the app's scripts from the cache
            page.goto(f"{app_url}/{problem.id}?{query}")
            wait_until_idle(page)
        page.get_by_role("button", name="Show the solution").wait_for(timeout=30_000)
        wait_until_idle(page)
        texts = [page.locator("body").inner_text(), page.url]
        texts += page.locator("annotation[encoding='application/x-tex']").all_text_contents()
        texts += page.eval_on_selector_all("[aria-label], [title]", "els => els.map(e => "
                                           "(e.getAttribute('aria-label') || '') + ' ' + (e.getAttribute('title') || ''))")
        texts += [frame.locator("body").inner_text() for frame in page.frames[1:] if frame.url != "about:blank"]
        texts += help_texts(page)
        # kept apart by a mark the leak check's flattening keeps: the statement's inline givens $\mu$ and $g$, one
        # annotation each, read as the all-wheel drive's closed form μ g where they met
        text = "\n§\n".join(texts)
        assert "The problem" in text and "The method" in text and "Show the solution" in text, query
        _, solution, judge, answers = setup(problem.id, **params)
        assert leaks(text, solution, answers.values(), judge) == [], query
        assert not errors
        if query.startswith("seed"):
            SHOTS.mkdir(parents=True, exist_ok=True)
            page.screenshot(path=str(SHOTS / f"practice-{problem.id}.png"), full_page=True)
    context.close()


def test_a_revisit_downloads_no_plotly_again_and_a_page_compiles_one(browser, app_url):
    """What can be counted of issue 13: a second visit in the same browser moves ≤ 100 KB over
    HTTP (the figure's plotly.js bundle comes from the cache: serve.py gives it a year's lifetime),
    and a page with two figures loads one plotly.js, in the page itself (no frame per figure)."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    visits = []
    for _ in range(2):
        page = context.new_page()
        received: dict[str, list] = {}
        cdp = context.new_cdp_session(page)
        cdp.on("Network.requestWillBeSent",
               lambda e, got=received: got.setdefault(e["requestId"], [e["request"]["url"], 0]))
        cdp.on("Network.loadingFinished",
               lambda e, got=received: got.get(e["requestId"], [None, 0]).__setitem__(1, e["encodedDataLength"]))
        cdp.send("Network.enable")
        page.goto(f"{app_url}/driven_cart")  # two figures
        wait_until_idle(page)
        page.locator(".dl-figure").last.locator(".main-svg").first.wait_for()
        page.wait_for_timeout(500)
        assert page.locator(".dl-graph.js-plotly-plot").count() == 2 and page.locator("iframe").count() == 0
        assert page.evaluate("document.querySelectorAll('script[src*=\"/plotly-\"]').length") == 1
        visits.append(received)
    first, again = ({}, {})
    for visit, sizes in zip(visits, (first, again)):
        for url, size in visit.values():  # both figures ask for the bundle: one download, one wait
            sizes[url] = sizes.get(url, 0) + size
    bundle = [url for url in first if "/plotly-basic." in url]
    assert bundle and max(first[url] for url in bundle) > 300_000  # the first visit did fetch it
    assert all(again.get(url, 0) == 0 for url in bundle), "plotly.js downloaded again"
    assert sum(again.values()) <= 100 * 1024, sorted(again.items(), key=lambda kv: -kv[1])[:5]
    context.close()


def test_the_browser_rebuilds_the_frames_the_server_means(browser, app_url):
    """A change sends an animation compacted (viz.common.compacted: a map per frame for a rigid
    body, a trail once, a spring's turns); the component rebuilds the rows in JavaScript. Every
    frame plotly holds in the browser is the frame Python's own rebuilding (viz.common.expanded)
    gives, on every page whose frames the server sends, for a rigid body, a trail and a spring alike (the
    motions the browser computes: tests/browser/test_browser_motion.py)."""
    import importlib
    import json

    import numpy as np

    from ui.live import in_browser
    from viz.common import expanded

    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    for problem in (p for p in PROBLEMS if not in_browser(p.id)):
        figure = importlib.import_module(f"viz.{problem.id}").figures(problem.solver.solve(), "si")[0]
        meant = expanded(json.loads(figure.json()))["frames"]
        visit(page, app_url, problem.id)
        graph = page.locator(".dl-figure .dl-graph").first
        graph.locator(".main-svg").first.wait_for()
        got = graph.evaluate("(el) => el._transitionData._frames.map(f => f.data.map(d =>"
                             " Object.fromEntries(['x', 'y', 'z'].filter(k => d[k]).map(k => [k, d[k]]))))")
        assert len(got) == len(meant), problem.id
        for frame, want in zip(got, meant):
            for trace, expected in zip(frame, want["data"], strict=True):
                for k in ("x", "y", "z"):
                    if k in expected:
                        a = np.asarray(trace[k], dtype=float)
                        b = np.asarray(expected[k], dtype=float)
                        assert a.shape == b.shape and (np.isnan(a) == np.isnan(b)).all(), (problem.id, k)
                        assert np.nanmax(np.abs(a - b), initial=0.0) <= 1e-9, (problem.id, k)
    context.close()


def test_the_time_slider_scrubs_by_keyboard_and_follows_play(browser, app_url):
    """The animation's time slider is a range input above the graph (plotly's own slider redrew
    every step as SVG on each change): Home/End and the arrows move the motion and its time
    readout, and Play moves the slider with the frames."""
    context, page, errors = open_page(browser, f"{app_url}/disk_wall")
    figure = page.locator(".dl-figure").first
    figure.locator(".main-svg").first.wait_for()
    scrub, readout, graph = figure.locator("input.dl-scrub"), figure.locator(".dl-readout"), figure.locator(".dl-graph")
    first = readout.inner_text()  # the impact's animation starts a little before it: t < 0
    assert scrub.get_attribute("aria-label") and first.startswith("t = ") and first.endswith(" s")
    snapshot = "(el) => JSON.stringify(el._fullData.map(t => t.x && Array.from(t.x).slice(0, 4)))"
    start = graph.evaluate(snapshot)
    scrub.focus()
    scrub.press("End")
    page.wait_for_timeout(300)
    last = int(scrub.get_attribute("max"))
    assert last >= 29 and scrub.input_value() == str(last)
    assert readout.inner_text() != first and graph.evaluate(snapshot) != start
    scrub.press("Home")
    scrub.press("ArrowRight")
    page.wait_for_timeout(300)
    assert scrub.input_value() == "1"  # one step, not two (the figure's own arrow keys stay out)
    figure.get_by_role("button", name="Play the animation").click()
    page.wait_for_timeout(1200)
    assert int(scrub.input_value()) > 3, "the slider did not follow Play"
    assert not errors, errors
    context.close()


def test_the_time_readout_tells_the_frames_apart(browser, app_url):
    """Stick and ball bouncing with e = 0 meet again 1.3 ms after the impact: 36 of the animation's
    frames read "t = 0.00 s" at two decimals. The readout takes as many decimals (up to five) as tell
    the frames apart, and two where they already do (the pendulum)."""
    context, page, errors = open_page(browser, f"{app_url}/stick_ball?mode=bounce&e=0")
    figure = page.locator(".dl-figure").first
    figure.locator(".main-svg").first.wait_for()
    shown = figure.evaluate("""(el) => { const fig = el.dlFigure, out = [];
      for (let i = 0; i < fig.times.length; i++) { fig.showTime(i); out.push(el.querySelector('.dl-readout').textContent); }
      fig.showTime(0); return out; }""")
    assert len(shown) >= 30 and len(set(shown)) >= 0.9 * len(shown), shown
    page.goto(f"{app_url}/pendulum_rebound")
    wait_until_idle(page)
    readout = page.locator(".dl-figure .dl-readout").first
    readout.wait_for()
    assert re.fullmatch(r"t = -?\d+\.\d\d s", readout.inner_text()), readout.inner_text()
    assert not errors, errors
    context.close()


# The runs the page asks for from now on: its messages on the app's websocket (CSP_WATCH counts them).
# (Streamlit's script-state attribute can miss a fragment's run that starts and ends within one render.)
RUN_COUNTER = ("() => { const from = window.__sent;"
               " Object.defineProperty(window, '__runs', {configurable: true, get: () => window.__sent - from}); }")
LIVE_CELLS = ("() => [...document.querySelector('.dl-answers table').tBodies[0].rows].map((r) => r.cells[2].innerText)")
# The stage graph's traces as plotly holds them now (name -> [x, y]), its key frame's (from the frames
# the figure was drawn with), and whether the graph is dimmed.
STAGE_GRAPH = "document.querySelector('.st-key-dl_stage .dl-figure .dl-graph')"
POSED_NOW = (f"() => Object.fromEntries({STAGE_GRAPH}.data.map((t) => [t.name, [Array.from(t.x || []), Array.from(t.y || []),"
             " t.opacity ?? 1]]))")
KEY_FRAME = (f"() => {{ const g = {STAGE_GRAPH}, fig = g.closest('.dl-figure').dlFigure, f = fig.frames[fig.keyFrame];"
             " return Object.fromEntries(f.traces.map((t, n) => [g.data[t].name, [f.data[n].x, f.data[n].y]])); }")


def live_ready(page) -> None:
    """Wait until the stage's live view can pose the figure: live.js imports the pose module the page
    names (pose.<hash>.js) when the page mounts, and a move before it arrives shows the figure marked
    "updating" (right, but not what these tests look at). Awaiting the same import resolves after live.js's."""
    page.wait_for_function("() => performance.getEntriesByType('resource').some((r) => /\\/pose\\.[0-9a-f]+\\.js/.test(r.name))",
                           timeout=30_000)
    page.evaluate("async () => { for (const r of performance.getEntriesByType('resource'))"
                  " if (/\\/pose\\.[0-9a-f]+\\.js/.test(r.name)) await import(r.name); }")


def test_answers_follow_a_dragged_slider_before_release_and_practice_has_none(browser, app_url):
    """Issue 27: while θ₀ is dragged (the mouse held down) the answers, and the caption's headline, are the
    solver's for the value the slider shows, with no server run; past the impact angle every answer waits ("updating…") and the
    regime is said; on release one run replaces everything. Practice loads no live module; axe stays
    at zero."""
    import numpy as np

    from solvers.pendulum_rebound import solve
    from solvers import units
    from tests.browser.test_where_used import serious_violations
    from ui.results import answer_rows
    from solvers.catalog import BY_ID
    from viz.common import headline_text
    from viz.pendulum_rebound import figures, key_pose
    from solvers.live import leads as live_leads, options_of as live_options

    context, page, errors = open_page(browser, f"{app_url}/pendulum_rebound")
    loaded = []
    page.on("request", lambda r: loaded.append(r.url))
    page.locator(".dl-answers table").first.wait_for()
    page.evaluate(RUN_COUNTER)
    live_ready(page)
    control = page.locator(".st-key-pendulum_rebound__si__theta0")
    track = control.locator(TRACK).bounding_box()
    low, high = -89, 89
    x_of = lambda degrees: track["x"] + (degrees - low) / (high - low) * track["width"]  # noqa: E731
    y = track["y"] + track["height"] / 2
    shown = lambda: float(control.locator("[data-testid='stSliderThumbValue']").inner_text())  # noqa: E731  (the thumb's own)

    def expected(degrees: float) -> list[str]:
        solution = solve(theta0=units.to_si(degrees, "angle"))
        return [row[2] for row in answer_rows(solution, BY_ID["pendulum_rebound"].answers_of(solution), "si")]

    def caption_headline(degrees: float) -> str:
        solution = solve(theta0=units.to_si(degrees, "angle"))
        stage = figures(solution, "si")[0]
        return headline_text(stage.headline, {**solution.params, **solution.answers})

    before = page.evaluate(LIVE_CELLS)
    page.mouse.move(x_of(0), y)
    page.mouse.down()
    for degrees in range(0, -21, -4):
        page.mouse.move(x_of(degrees), y)
    page.wait_for_timeout(200)
    dragged_to = shown()
    assert dragged_to < -5, dragged_to
    during = page.evaluate(LIVE_CELLS)
    assert during != before and during == expected(dragged_to), (during, expected(dragged_to))
    assert page.evaluate("window.__runs") == 0  # all of it in the browser
    assert page.locator(".dl-figure .dl-live-stale").count() >= 1  # the motion is not redrawn: marked
    headline = page.locator(".dl-live-headline").inner_text()  # on the stage, by the figure: the answer θ₀ changes
    rows = BY_ID["pendulum_rebound"].answers_of(solve())
    lead = live_leads("pendulum_rebound", live_options("pendulum_rebound", solve().params), solve().regime,
                      tuple(a.name for a in rows))["theta0"]
    assert lead > 0 and headline.endswith(expected(dragged_to)[lead]), headline  # (not the angle at impact: it stays)
    # The caption's headline is the server's caption for the value shown; the rest of it dimmed.
    caption = page.locator(".st-key-dl_stage .dl-description")
    assert caption.locator(".dl-live-caption").inner_text() == caption_headline(dragged_to)
    assert caption.locator(".dl-live-caption.dl-live-stale").count() == 0
    assert caption.locator(".dl-live-stale").count() == 1 and caption.get_attribute("aria-live") == "off"
    # The figure at its key instant (the first impact) follows: its bodies where the server draws them for
    # the value shown (viz key_pose, rounded as the figure is), the graph itself not dimmed, the rest of it
    # (the sphere's path, the θ(t) plot, the floor) dimmed.
    def pose_is_the_servers(degrees: float) -> dict:
        solution = solve(theta0=units.to_si(degrees, "angle"))
        want, now = key_pose(solution.params, solution.answers), page.evaluate(POSED_NOW)
        for name, (x, y) in want.items():
            for axis, a, b in (("x", now[name][0], x), ("y", now[name][1], y)):
                a, b = np.asarray(a, dtype=float), np.asarray(b, dtype=float)
                assert a.shape == b.shape and np.allclose(a, b, rtol=1e-9, atol=1e-12, equal_nan=True), (degrees, name, axis, a, b)
            assert now[name][2] == 1, name
        assert {name for name, (_, _, opacity) in now.items() if opacity == 1} == set(want), now.keys()
        return {name: now[name][:2] for name in want}

    graph = page.locator(".st-key-dl_stage .dl-figure .dl-graph")
    pose_is_the_servers(dragged_to)
    assert "dl-live-stale" not in graph.get_attribute("class")
    assert "key instant live" in page.locator(".dl-live-note").inner_text()

    page.mouse.move(x_of(-70), y)  # below the impact angle (−35.7°): no impact, nothing to show
    page.wait_for_timeout(200)
    assert set(page.evaluate(LIVE_CELLS)) == {"updating…"}
    assert "no impact" in page.locator(".dl-live-status").inner_text()
    assert caption.locator(".dl-live-caption.dl-live-stale").count() == 1  # another regime: its words would be wrong
    assert "dl-live-stale" in graph.get_attribute("class")  # no impact: no pose to show, the figure waits

    page.mouse.move(x_of(-12), y)
    page.wait_for_timeout(200)
    released_at = shown()
    live_values = page.evaluate(LIVE_CELLS)
    assert "dl-live-stale" not in graph.get_attribute("class")  # back in the run's regime: the pose follows again
    live_pose = pose_is_the_servers(released_at)
    page.mouse.up()
    page.wait_for_function("() => window.__runs >= 1 && !document.querySelector('.dl-live-value')", timeout=30_000)
    wait_until_idle(page)
    page.wait_for_timeout(300)
    assert page.evaluate("window.__runs") == 1  # one server run for the whole drag
    assert page.evaluate(LIVE_CELLS) == live_values == expected(released_at)
    drawn = page.evaluate(KEY_FRAME)  # the server's new figure, its key frame (rows rebuilt from the compact form)
    for name, (x, y) in live_pose.items():
        for a, b in ((drawn[name][0], x), (drawn[name][1], y)):
            assert np.allclose(np.asarray(a, dtype=float), np.asarray(b, dtype=float), rtol=0, atol=2e-4, equal_nan=True), name
    assert page.locator(".dl-live-stale, .dl-live-badge, .dl-live-caption").count() == 0
    assert caption.inner_text().startswith(caption_headline(released_at)) and caption.get_attribute("aria-live") == "polite"
    assert page.locator("#dl-live-announce").inner_text().strip()  # the main answer, said once
    assert any("/live." in url for url in loaded + page.evaluate(
        "() => performance.getEntriesByType('resource').map((e) => e.name)"))  # so the check below can fail
    assert serious_violations(page) == []
    assert not errors, errors
    assert csp_violations(page) == []
    # Released below the impact angle: the solver refuses, the run draws no answers, no figure and no
    # live view, and nothing live is left on its page (its derivation not dimmed as if updating).
    middle = track["y"] + track["height"] / 2  # (y is a pose's coordinates by now)
    page.mouse.move(x_of(-12), middle)
    page.mouse.down()
    for degrees in (-30, -50, -70):
        page.mouse.move(x_of(degrees), middle)
    page.mouse.up()
    page.wait_for_function("() => window.__runs >= 2", timeout=30_000)
    wait_until_idle(page)
    page.wait_for_timeout(300)
    assert page.locator(".dl-answers table").count() == 0 and shown() < -35.7
    assert page.locator(".dl-derivation").count() >= 1  # (so the check below can fail)
    assert page.locator(".dl-live-stale, .dl-live-badge, .dl-live-value, .dl-live-caption").count() == 0
    assert page.evaluate("() => document.body.classList.contains('dl-live-dragging')") is False
    # Dragged back from there, the thumb follows the pointer (no live view to draw it: react-aria's own
    # drag), and the release runs the page with answers again.
    page.mouse.move(x_of(shown()), middle)
    page.mouse.down()
    for degrees in (-60, -45, -30, -15):
        page.mouse.move(x_of(degrees), middle)
        page.wait_for_timeout(60)
    page.wait_for_timeout(200)
    assert -20 < shown() < -10, shown()
    page.mouse.up()
    page.wait_for_function("() => window.__runs >= 3", timeout=30_000)
    page.locator(".dl-answers table").first.wait_for(timeout=30_000)
    assert not errors, errors
    context.close()

    context, page, errors = open_page(browser, f"{app_url}/pendulum_rebound?practice=1")
    page.get_by_role("heading", name=BY_ID["pendulum_rebound"].title).wait_for()
    sources = page.evaluate("() => performance.getEntriesByType('resource').map((e) => e.name)")
    assert not any("/live." in url for url in sources), sources
    assert page.locator("#dl-live-style").count() == 0
    context.close()


# Each pointer move's frame as painted (live.js draws in that frame's animation-frame callbacks; a
# user-blocking task after them runs once the frame is done): the answers, the thumb's value and place.
FRAME_DRAWN = ("(key) => { window.__frames = []; window.addEventListener('pointermove', (e) => { if (!e.buttons) return;"
               " requestAnimationFrame(() => scheduler.postTask(() => { const t = document.querySelector("
               "`.st-key-${key} [data-testid=stSliderThumbValue]`);"
               " window.__frames.push([[...document.querySelector('.dl-answers table').tBodies[0].rows].map((r) => r.cells[2].innerText),"
               " t.innerText, t.parentElement.style.left]); }, {priority: 'user-blocking'})); }, true); }")


@pytest.mark.parametrize("pid,query", [("pendulum_rebound", ""), ("sliding_ladder", ""),
                                       # a link's values between the sliders' steps: V dragged from 3.14159
                                       # (six figures), e = 0.53 on a slider of 0.05 steps kept while V moves
                                       ("disk_wall", "?V=3.14159&e=0.53")])
def test_a_drag_s_values_are_painted_in_the_frame_the_pointer_moved_in(browser, app_url, pid, query):
    """Issue 27: each move of a dragged stage slider is drawn in the frame that move came with: the
    thumb at its value, the value it shows, and the answers for it (live.js works the value out from
    the pointer as react-aria does and draws the thumb itself: React's render of the slider for each
    move came after that frame). On release react-aria commits exactly the value drawn last (its own
    computation, from the pointer's travel), the run's answers are the ones shown while dragging, and
    the thumb is React's again. Moves of random length, fractions of a pixel, past either end of the
    track, on sliders of other steps and formats (0.05 to two decimals, 0.1 m/s to six figures), from a
    link's value between two steps; several drags, each released somewhere else."""
    import random

    from bench.controls import lesson_control

    context, page, errors = open_page(browser, f"{app_url}/{pid}{query}")
    page.locator(".dl-answers table").first.wait_for()
    page.evaluate(RUN_COUNTER)
    live_ready(page)
    control = page.locator(f".st-key-{lesson_control(pid)[0]}")
    thumb = control.locator("input[type='range']")
    low, high = (float(thumb.get_attribute(a)) for a in ("min", "max"))
    track = control.locator(TRACK).bounding_box()
    y = track["y"] + track["height"] / 2
    rng = random.Random(pid)
    moved = 0
    page.evaluate(FRAME_DRAWN, lesson_control(pid)[0])
    for drag in range(4):
        page.evaluate("window.__frames = []")
        x = track["x"] + rng.uniform(0.2, 0.8) * track["width"]
        page.mouse.move(x, y)
        page.mouse.down()
        for _ in range(5):
            x = min(max(x + rng.uniform(-0.25, 0.25) * track["width"], track["x"] - 40), track["x"] + track["width"] + 40)
            page.mouse.move(round(x, 2), y)
            page.wait_for_timeout(60)
        frames = page.evaluate("window.__frames")
        assert page.evaluate("window.__runs") == drag  # none while moving
        page.mouse.up()
        page.wait_for_function("() => !document.querySelector('.dl-live-value')", timeout=30_000)
        wait_until_idle(page)
        assert len(frames) == 5, frames
        for cells, shown, left in frames:  # the thumb where its value is, in the frame of the move
            assert abs(float(left.rstrip("%")) - (float(shown) - low) / (high - low) * 100) < 1e-3, (shown, left)  # (CSS keeps 4 decimals)
            assert "updating…" in cells or len(set(cells)) > 1, cells
        moved += len({shown for _, shown, _ in frames}) > 1
        committed = float(thumb.input_value())  # react-aria's, from the pointer's whole travel
        last_cells, last_shown, _ = frames[-1]
        assert committed == float(last_shown), (drag, committed, last_shown)
        assert control.locator("[data-testid='stSliderThumbValue']").inner_text() == last_shown
        served = page.evaluate(LIVE_CELLS)  # the run's answers for that value: the last frame's where it computed them
        assert all(live in ("updating…", ran) for live, ran in zip(last_cells, served, strict=True)), (last_cells, served)
        assert page.evaluate(f"() => document.querySelector('.st-key-{lesson_control(pid)[0]} [data-orientation] > :first-child').style.backgroundImage") == ""
    assert moved >= 3  # the values changed within the drags, so a frame late would have shown
    assert page.evaluate("window.__runs") == 4  # one run a drag
    if "e=0.53" in query:  # the value between two steps stood through every run, as the answers used it
        assert control.page.locator(".st-key-disk_wall__si__e [data-testid='stSliderThumbValue']").inner_text() == "0.53"
        assert "e=0.53" in page.url
    assert not errors, errors
    context.close()


def test_a_posed_figure_is_drawn_as_plotly_draws_it(browser, app_url):
    """Issue 27: the pose a drag moves (ui/plotly_component/figure.js svgUpdate: the SVG of the posed
    traces set at once, instead of plotly's animate of every moving trace) draws what plotly draws for
    the same coordinates: on each 2-D stage, the frame on screen written again by svgUpdate leaves every
    line, fill and marker where plotly put it (plotly drops points of a line that lie on it within a
    pixel's fraction; the points it keeps are among the ones written, to a twentieth of a pixel)."""
    import numpy as np

    REDRAWN = """() => {
      const fig = document.querySelector('.st-key-dl_stage .dl-figure').dlFigure, gd = fig.graph;
      const frame = fig.frames[fig.frameIndex];  // its moving traces that are bodies (not a bar chart's)
      const posed = frame.traces.filter((t) => gd._fullData[t].type === 'scatter');
      const drawn = () => [...gd.querySelectorAll('.scatterlayer .trace')].filter((g) => posed.includes(g.__data__[0].trace.index))
        .map((g) => [...g.querySelectorAll('.js-line, .js-fill, .point')].map((e) => e.getAttribute('d') || e.getAttribute('transform')));
      const before = drawn();
      const written = fig.svgUpdate(posed, posed.map((t) => {
        const d = frame.data[frame.traces.indexOf(t)];
        return {x: d.x || gd.data[t].x, y: d.y || gd.data[t].y};
      }));
      return {written, before, after: drawn()};
    }"""
    points = lambda path: np.array([[float(v) for v in xy.split(",")] for xy in re.findall(r"-?[\d.]+,-?[\d.]+", path or "")]).reshape(-1, 2)  # noqa: E731
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    for problem in PROBLEMS:
        if problem.id == "eulers_disk":  # a 3-D scene: its pose is set on its WebGL objects (sceneUpdate)
            continue
        visit(page, app_url, problem.id)  # from the navigation, as a student goes from page to page
        page.locator(".st-key-dl_stage .dl-figure .main-svg").first.wait_for()
        got = page.evaluate(REDRAWN)
        assert got["written"], problem.id
        compared = 0
        for before, after in zip(got["before"], got["after"], strict=True):
            assert len(before) == len(after), problem.id
            for plotly_path, ours in zip(before, after):
                theirs, mine = points(plotly_path), points(ours)
                assert len(theirs) <= len(mine) and np.allclose(theirs[[0, -1]] if len(theirs) else theirs,
                                                                mine[[0, -1]] if len(mine) else mine, atol=0.05), problem.id
                for xy in theirs:
                    assert np.abs(mine - xy).max(axis=1).min() <= 0.05, (problem.id, xy)
                compared += len(theirs)
        assert compared > 20, problem.id
    context.close()


def test_a_held_3d_scene_s_pose_is_drawn_where_webgl_draws_it(browser, app_url):
    """Issue 27: while a lesson control is dragged, Euler's disk's bodies are drawn in an SVG over its
    3-D scene (figure.js sceneOverlay: each point projected by the scene's camera), not by redrawing
    the scene in WebGL for each pose. Held at the frame on screen, the overlay's rim, marked radius,
    contact point and G land on the pixels WebGL drew for them: each colour's pixels within 2 px of
    the other drawing's, both ways, nearly all of them (the SVG has no depth: where the contact's path
    passes in front of the rim, WebGL draws it over, the overlay under). While held, the scene's render
    loop is parked (the page idles, so a move's frame starts at once); released, it draws again."""
    import io

    import numpy as np
    from PIL import Image
    from scipy.ndimage import distance_transform_edt

    HOLD = """async () => {
      const fig = document.querySelector('.st-key-dl_stage .dl-figure').dlFigure, gd = fig.graph;
      const frame = fig.frames[fig.frameIndex];
      const posed = gd._fullData.map((t, i) => i);
      const data = posed.map((t) => {
        const n = frame.traces.indexOf(t), d = n < 0 ? {} : frame.data[n];
        return {x: d.x || gd.data[t].x, y: d.y || gd.data[t].y, z: d.z || gd.data[t].z};
      });
      fig.hold();
      await fig.showHeld([], 0.3, posed);
      return {drawn: fig.sceneOverlay(posed, data),
              colours: gd._fullData.map((t) => (t.mode.includes('lines') ? t.line.color : t.marker.color))};
    }"""
    context, page, errors = open_page(browser, f"{app_url}/eulers_disk")
    graph = page.locator(".st-key-dl_stage .dl-figure .dl-graph")
    page.locator(".st-key-dl_stage .dl-figure .gl-container canvas").first.wait_for()
    page.wait_for_timeout(500)
    webgl = np.asarray(Image.open(io.BytesIO(graph.screenshot())).convert("RGB"), dtype=int)
    held = page.evaluate(HOLD)
    assert held["drawn"]
    page.wait_for_timeout(300)
    assert page.locator(".dl-scene-pose path").count() >= 3
    overlay = np.asarray(Image.open(io.BytesIO(graph.screenshot())).convert("RGB"), dtype=int)
    assert webgl.shape == overlay.shape
    compared = 0
    for colour in set(held["colours"]):
        rgb = np.array([int(colour.lstrip("#")[i:i + 2], 16) for i in (0, 2, 4)])
        # (the colour itself: an edge blended with white would pass for a lighter colour)
        a, b = (np.abs(img - rgb).sum(axis=2) < 30 for img in (webgl, overlay))
        assert a.sum() > 20 and b.sum() > 20, colour
        for one, other in ((a, b), (b, a)):
            near = distance_transform_edt(~other)[one] <= 2.0  # each pixel's distance to the other drawing's nearest
            assert near.mean() >= 0.95, (colour, near.mean())
        compared += 1
    assert compared >= 3
    # While held the scene's render loop (plotly asks for every frame) is parked: the page idles.
    parked = ("async () => { for (const r of performance.getEntriesByType('resource'))"
              " if (/\\/figure\\.[0-9a-f]+\\.js/.test(r.name)) return (await import(r.name)).parkedSceneLoops(); }")
    assert page.evaluate(parked) == 1
    # released: the loop runs again, WebGL draws the bodies again (as before the hold), the overlay gone
    page.evaluate("() => document.querySelector('.st-key-dl_stage .dl-figure').dlFigure.release()")
    page.wait_for_timeout(300)
    assert page.locator(".dl-scene-pose").count() == 0 and page.evaluate(parked) == 0
    again = np.asarray(Image.open(io.BytesIO(graph.screenshot())).convert("RGB"), dtype=int)
    assert (np.abs(again - webgl).sum(axis=2) > 30).mean() < 0.002
    # and the scene still turns under the mouse (its loop draws the new camera)
    box = page.locator(".st-key-dl_stage .dl-figure .gl-container canvas").first.bounding_box()
    page.mouse.move(box["x"] + box["width"] * 0.5, box["y"] + box["height"] * 0.6)
    page.mouse.down()
    page.mouse.move(box["x"] + box["width"] * 0.65, box["y"] + box["height"] * 0.6, steps=5)
    page.mouse.up()
    page.wait_for_timeout(300)
    turned = np.asarray(Image.open(io.BytesIO(graph.screenshot())).convert("RGB"), dtype=int)
    assert (np.abs(turned - again).sum(axis=2) > 30).mean() > 0.01
    assert not errors, errors
    context.close()


@pytest.mark.parametrize("size,query", [((1280, 720), "lecture=1"), ((390, 844), "")], ids=["projector", "phone"])
def test_the_live_headline_covers_the_figure_s_title_and_keeps_its_unit(browser, app_url, size, query):
    """While Euler's disk's tilt is dragged, the live headline over the figure's title hides all of it
    (the lecture view's title is taller than the headline's line: its lower half showed through) and
    shows the whole headline, its unit included (a phone cut "… 36.57 rad…")."""
    width, height = size
    context, page, errors = open_page(browser, f"{app_url}/eulers_disk?{query}", width, height, phone=width < 640)
    page.locator(".st-key-dl_stage .dl-figure .gl-container canvas").first.wait_for()
    control = page.locator(".st-key-eulers_disk__si__theta")
    control.scroll_into_view_if_needed()
    hold_drag(page, control.locator(TRACK).bounding_box(), 0.3, 0.55)
    page.wait_for_timeout(200)
    badge, title, headline = page.evaluate("""() => {
      const box = (el) => { const r = el.getBoundingClientRect(); return {top: r.top, bottom: r.bottom}; };
      const badge = document.querySelector('.dl-live-badge');
      return [{...box(badge), cut: badge.scrollWidth > badge.clientWidth}, box(document.querySelector('.st-key-dl_stage .dl-title')),
              badge.querySelector('.dl-live-headline').textContent];
    }""")
    page.mouse.up()
    assert badge["top"] <= title["top"] + 0.5 and badge["bottom"] >= title["bottom"] - 0.5, (badge, title)
    assert not badge["cut"] and headline.endswith("rad/s"), (badge, headline)
    assert not errors, errors
    context.close()


def test_a_held_arrow_key_is_live_and_runs_the_page_once_after_release(browser, app_url):
    """Issue 27: ArrowRight held on a stage slider (rod_disk_spring's θ₂) for about a second
    moves the thumb and its value, and the answers follow the solver during the hold with no run; the
    release runs the page once. A single press (and Home/End) still moves and runs once. The thumb stays
    a slider whose value screen readers get; axe stays at zero."""
    from solvers.rod_disk_spring import solve
    from solvers import units
    from tests.browser.test_where_used import serious_violations
    from ui.results import answer_rows
    from solvers.catalog import BY_ID

    context, page, errors = open_page(browser, f"{app_url}/rod_disk_spring")
    page.locator(".dl-answers table").first.wait_for()
    page.evaluate(RUN_COUNTER)
    live_ready(page)
    thumb = page.locator(".st-key-dl_stage_controls .st-key-rod_disk_spring__si__theta2 input[type='range']")
    shown = lambda: float(thumb.input_value())  # noqa: E731

    def expected(degrees: float) -> list[str]:
        solution = solve(theta2=units.to_si(degrees, "angle"))
        return [row[2] for row in answer_rows(solution, BY_ID["rod_disk_spring"].answers_of(solution), "si")]

    def runs() -> int:
        return page.evaluate("window.__runs")

    def settled(count: int) -> None:
        page.wait_for_function(f"() => window.__runs >= {count} && !document.querySelector('.dl-live-value')",
                               timeout=30_000)
        wait_until_idle(page)

    start = shown()
    thumb.focus()
    page.keyboard.down("ArrowRight")
    seen = []
    for i in range(30):  # about a second of the key's repeats
        page.wait_for_timeout(33)
        page.keyboard.down("ArrowRight")  # held: an auto-repeat
        if i % 10 == 9:
            page.wait_for_timeout(50)
            seen.append((shown(), page.evaluate(LIVE_CELLS), thumb.get_attribute("aria-valuetext")))
    assert runs() == 0, "the page ran while the key was held"
    assert [s for s, _, _ in seen] == sorted({s for s, _, _ in seen}) and seen[-1][0] >= start + 25, seen
    for degrees, cells, said in seen:
        assert cells == expected(degrees), (degrees, cells, expected(degrees))
        assert said and said.startswith(str(int(degrees))), said  # the slider says the value it shows
    held_to = shown()
    page.keyboard.up("ArrowRight")
    settled(1)
    page.wait_for_timeout(400)
    assert runs() == 1 and shown() == held_to  # one run, for the value the thumb showed
    assert page.evaluate(LIVE_CELLS) == expected(held_to)
    assert thumb.get_attribute("role") in (None, "slider") and thumb.evaluate("(el) => el === document.activeElement")

    thumb.press("ArrowLeft")  # one press: one step, one run
    settled(2)
    assert shown() == held_to - 1 and runs() == 2 and page.evaluate(LIVE_CELLS) == expected(held_to - 1)
    thumb.press("Home")  # to the slider's end (committed by the key back from one step above it)
    settled(3)
    assert shown() == float(thumb.get_attribute("min")) and runs() == 3
    assert page.evaluate(LIVE_CELLS) == expected(shown())
    thumb.press("ArrowRight")  # and back at once: nothing to run, and the live view is gone, not left "updating…"
    thumb.press("ArrowLeft")
    page.wait_for_timeout(800)
    assert runs() == 3 and shown() == float(thumb.get_attribute("min"))
    assert page.locator(".dl-live-badge, .dl-live-value, .dl-live-stale").count() == 0
    assert serious_violations(page) == []
    assert not errors, errors
    assert csp_violations(page) == []
    context.close()


def test_a_phone_steps_a_stage_slider_one_step_a_tap(browser, app_url):
    """Issue 27: at 390×844 a finger cannot hit one step of θ₂ on a half-width slider; its + and −
    (44 px, named for screen readers) move exactly one step a tap, live; a burst of taps is one run,
    and a lone tap (or Enter on the focused button) one run each."""
    from solvers.rod_disk_spring import solve
    from solvers import units
    from ui.results import answer_rows
    from solvers.catalog import BY_ID

    context, page, errors = open_page(browser, f"{app_url}/rod_disk_spring", 390, 844, phone=True)
    page.locator(".dl-answers table").first.wait_for()
    page.evaluate(RUN_COUNTER)
    live_ready(page)
    slider = page.locator(".st-key-rod_disk_spring__si__theta2")
    shown = lambda: float(slider.locator("input[type='range']").input_value())  # noqa: E731
    higher = slider.get_by_role("button", name="θ₂ one step higher")
    lower = slider.get_by_role("button", name="θ₂ one step lower")

    def expected(degrees: float) -> list[str]:
        solution = solve(theta2=units.to_si(degrees, "angle"))
        return [row[2] for row in answer_rows(solution, BY_ID["rod_disk_spring"].answers_of(solution), "si")]

    def settled(count: int) -> None:
        page.wait_for_function(f"() => window.__runs >= {count} && !document.querySelector('.dl-live-value')",
                               timeout=30_000)
        wait_until_idle(page)

    start = shown()
    # The burst's three taps as a finger gives them: touches at the button's centre, 60 ms apart (Playwright's
    # tap() waits for the button to be stable before each, which on a loaded machine outlasted the 250 ms
    # that make a burst one run).
    box = higher.bounding_box()
    for _ in range(3):
        page.touchscreen.tap(box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        page.wait_for_timeout(60)
    page.wait_for_timeout(40)
    # (at once: the burst is committed 250 ms after the last tap) The live badge over the figure stays on one
    # line, clear of Play (it wrapped over it on a phone), and the figure at its key instant (θ₂) is live.
    badge, play, line, graph = page.evaluate(
        "() => { const box = (el) => { const r = el.getBoundingClientRect(); return {y: r.y, height: r.height}; };"
        " const badge = document.querySelector('.dl-live-badge'), fig = document.querySelector('.st-key-dl_stage .dl-figure');"
        " const css = getComputedStyle(badge); return [box(badge), box(fig.querySelector('.dl-play')),"
        " parseFloat(css.lineHeight) || 1.6 * parseFloat(css.fontSize), fig.querySelector('.dl-graph').className]; }")
    assert shown() == start + 3 and page.evaluate("window.__runs") == 0
    assert page.evaluate(LIVE_CELLS) == expected(start + 3)
    assert badge["height"] <= 1.6 * line and badge["y"] + badge["height"] <= play["y"] + 1, (badge, play, line)
    assert "dl-live-stale" not in graph
    settled(1)
    page.wait_for_timeout(400)
    assert page.evaluate("window.__runs") == 1 and shown() == start + 3
    assert page.evaluate(LIVE_CELLS) == expected(start + 3)
    lower.tap()
    settled(2)
    assert shown() == start + 2 and page.evaluate("window.__runs") == 2
    lower.focus()
    page.keyboard.press("Enter")
    settled(3)
    assert shown() == start + 1 and page.evaluate("window.__runs") == 3
    assert page.evaluate(LIVE_CELLS) == expected(start + 1)
    assert not errors, errors
    context.close()


FOCUS_SEEN = """() => { const e = document.activeElement, outlined = e.closest('label') || e, s = getComputedStyle(outlined);
  return {role: e.getAttribute('role'), tag: e.tagName, style: s.outlineStyle, width: parseFloat(s.outlineWidth)}; }"""


def test_a_first_visit_fetches_the_app_s_styles_element_while_the_page_loads(browser, app_url):
    """st.html's element (the app's stylesheets, the phone's type and the stage's layout among them) is
    Streamlit's code loaded on first use: asked for only when the first run's first st.html arrived, it
    drew the page without the app's styles for half a second more at 390 px on this machine (up to two
    seconds in a busy test run). The page's answer names it (edge/early_modules.py), so the browser fetches
    it while the document loads, before its DOMContentLoaded, in a context with nothing cached."""
    from edge.early_modules import early_modules

    context = watched_context(browser, viewport={"width": 390, "height": 844})
    page, errors = open_in(context, f"{app_url}/disk_wall")
    timing = page.evaluate("""(names) => {
      const loaded = performance.getEntriesByType('navigation')[0].domContentLoadedEventStart;
      const fetched = names.map((n) => performance.getEntriesByType('resource').find((e) => e.name.endsWith(n)));
      return {loaded, fetched: fetched.map((e) => e ? e.startTime : null)};
    }""", [path.rsplit("/", 1)[1] for path in early_modules()])
    assert early_modules() and all(t is not None and t < timing["loaded"] for t in timing["fetched"]), timing
    assert not errors, errors
    context.close()


def test_keyboard_focus_is_seen_on_a_switch_and_on_the_main_area(browser, app_url):
    """Tabbing onto "No slip at the contact" showed only a label background 1.1:1 against the page, and the main
    area (the skip link's target, a tab stop) showed nothing: both are outlined, 2 px, in the text's colour. In a
    context of its own: a page opened beside others in a kept one did not show the main area's :focus-visible."""
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page, errors = open_in(context, f"{app_url}/disk_wall")
    seen = {}
    for _ in range(60):
        page.keyboard.press("Tab")
        focus = page.evaluate(FOCUS_SEEN)
        key = "switch" if focus["role"] == "switch" else "main" if focus["tag"] == "MAIN" else None
        if key and key not in seen:
            seen[key] = focus
        if len(seen) == 2:
            break
    assert set(seen) == {"switch", "main"}, seen
    assert all(f["style"] == "solid" and f["width"] >= 2 for f in seen.values()), seen
    assert not errors, errors
    context.close()
