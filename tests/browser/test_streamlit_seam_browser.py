"""Every name in the seam to Streamlit's DOM (edge/streamlit_dom.py) still matches on the pinned Streamlit:
each is looked for in a page where the app draws it, one test per name. After an upgrade of Streamlit, the
names that no longer match are this module's failures, and nothing else has to be searched."""
from __future__ import annotations

import json

import pytest
from playwright.sync_api import TimeoutError as PlaywrightTimeout

from edge import streamlit_dom
from tests.browser.test_assignments_browser import choose, seeded_assignment, wait_for_text
from tests.browser.test_browser import open_in, open_page, watched_context
from tests.conftest import INSTRUCTOR_KEY

pytestmark = pytest.mark.browser

# Where each element is drawn: a place's address and viewport.
PLACES = {
    "a lesson": ("/pendulum_rebound", 1400, 1000),
    "a refusal on the projector": ("/rod_disk_spring?lecture=1&k=51", 1280, 720),
    "Practice": ("/driven_cart?practice=1", 1400, 1000),
    "the home page": ("/", 1400, 1000),
    "Handouts": (f"/handouts?instructor={INSTRUCTOR_KEY}", 1400, 1000),
    "a gradebook": (f"/gradebook?instructor={INSTRUCTOR_KEY}", 1400, 1000),
    "a first visit": ("/disk_wall", 1400, 1000),
}
# What is drawn only for a moment (a placeholder while an element's code loads on a first visit): counted as
# it appears, by an observer installed before the page's own scripts, in a context of its own (nothing cached).
SEEN = """window.__dlSeen = {}; new MutationObserver(() => { for (const [k, v] of Object.entries(window.__dlLook || {}))
  if (document.querySelector(v)) window.__dlSeen[k] = (window.__dlSeen[k] || 0) + 1; })
  .observe(document, {subtree: true, childList: true});"""
TRANSIENT = {"a first visit"}
LESSON = ("app", "appView", "main", "header", "sidebar", "sidebarNavLink", "layoutWrapper", "verticalBlock",
          "elementContainer", "markdown", "heading", "checkbox", "buttonGroup", "widgetLabel", "slider",
          "sliderTickBar", "sliderThumbValue", "appClass", "mainBlock", "stage", "motion", "stageControls",
          "stale", "scriptState")
WHERE = {**dict.fromkeys(LESSON, "a lesson"), "pageLink": "the home page", "metricLabel": "a refusal on the projector",
         "alert": "a refusal on the projector", "radio": "a refusal on the projector", "form": "Practice", "button": "Practice", "expander": "Practice",
         "textInput": "Practice", "selectbox": "Practice", "downloadButton": "Handouts", "numberInput": "Handouts",
         "table": "a gradebook", "skeleton": "a first visit"}
TITLE = "The seam's gradebook"


def test_every_name_in_the_seam_has_a_place_to_be_found():
    assert set(WHERE) == set(streamlit_dom.SELECTORS) and set(WHERE.values()) == set(PLACES)


@pytest.fixture(scope="module")
def matches(browser, app_url, request):
    """place -> (name -> how many elements its selector matches there), each place opened once."""
    monkeypatch = pytest.MonkeyPatch()
    request.addfinalizer(monkeypatch.undo)
    found, assignment = {}, seeded_assignment(monkeypatch, TITLE, {"disk_wall": 1}, ["s01"])
    for place, (path, width, height) in PLACES.items():
        if place in TRANSIENT:
            context = watched_context(browser, viewport={"width": width, "height": height})
            looked_for = {name: streamlit_dom.SELECTORS[name] for name, where in WHERE.items() if where == place}
            context.add_init_script(f"window.__dlLook = {json.dumps(looked_for)};\n{SEEN}")
            page, errors = open_in(context, app_url + path)
            found[place] = {**page.evaluate("() => window.__dlSeen"), "(script errors)": errors,
                            "(idle state)": None}
            context.close()
            continue
        context, page, errors = open_page(browser, app_url + path, width, height)
        if place == "a gradebook":
            choose(page, "Assignment", assignment)
            wait_for_text(page, "Reading the gradebook")
        expected = [streamlit_dom.SELECTORS[name] for name, where in WHERE.items() if where == place]
        try:  # the page drawn whole (an instructor's link reruns it; the figures come after the first run)
            page.wait_for_function("(all) => all.every((s) => document.querySelector(s))", arg=expected,
                                   timeout=20_000)
        except PlaywrightTimeout:
            pass  # each missing name is its own test's failure
        found[place] = page.evaluate(
            "(s) => Object.fromEntries(Object.entries(s).map(([k, v]) => [k, document.querySelectorAll(v).length]))",
            dict(streamlit_dom.SELECTORS))
        found[place]["(idle state)"] = page.get_attribute(streamlit_dom.SELECTORS["app"],
                                                          streamlit_dom.ATTRIBUTES["scriptState"])
        found[place]["(script errors)"] = errors
        context.close()
    return found


@pytest.mark.parametrize("name", sorted(WHERE))
def test_the_seam_s_selector_matches_on_the_pinned_streamlit(matches, name):
    place = WHERE[name]
    assert matches[place].get(name, 0) > 0, f"{name} ({streamlit_dom.SELECTORS[name]}) is not in {place}'s page"
    if name == "scriptState":  # the app's JavaScript knows a run is done by its value (live.js, the tests' waits)
        assert matches[place]["(idle state)"] == streamlit_dom.SCRIPT_IDLE
    assert matches[place]["(script errors)"] == []
