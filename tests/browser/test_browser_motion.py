"""The lesson page's motion computed in the browser (issue 51: ui/live.py's generated module, live.js's
``motionOf``) is the figure the server draws frame by frame, as Chromium draws it: the same frames at the
same times, every body's every point to the figure's rounding, the same key frame; before and after a
lesson control is changed by keyboard (the release's figure is the same figure). The parameters come from
the page's own address, read as the app reads a link (ui.params.parameters_of_link), and the reference
is the viz module's figure as the server drew it before (``figures`` without ``in_browser``)."""
from __future__ import annotations

from urllib.parse import parse_qsl, urlparse

import numpy as np
import pytest

from bench.controls import lesson_control
from scripts.live_app import wait_until_idle
from solvers import registry
from solvers.catalog import BY_ID
from tests.browser.test_browser import open_page  # which skips (or, in CI, fails) without Chromium and Playwright
from ui.live import in_browser
from ui.params import parameters_of_link
from viz.catalog import drawings
from viz.common import DIGITS, expanded

pytestmark = pytest.mark.browser

IN_BROWSER = [pid for pid in registry.PROBLEM_IDS if in_browser(pid)]
# A state off the defaults where a page has regimes, options or events: the disk sliding along the wall, front
# drive, the bounced stick swinging round into the ball.
QUERIES = {"disk_wall": "?mu=0.05&omega=40", "driven_cart": "?drive=front&mu=0.3", "stick_ball": "?mode=bounce&s=0.25",
           "pendulum_rebound": "?surface=wall&e=0.6", "sliding_ladder": "?theta0=75&L=3",
           "eulers_disk": "?theta=30&r=0.05", "rod_disk_spring": "?k=10&theta1=20&disk=pinned"}
DRAWN = """() => { const f = document.querySelector('.dl-figure.dl-staged');
  return f && f.dlFigure && f.dlFigure.frames && f.dlFigure.frames.length ? f.dlFigure : null; }"""
FRAMES = ("() => { const f = (" + DRAWN + ")(); return {frames: f.frames.map((fr) => fr.data.map((d) => [d.x, d.y, d.z])),"
          " times: f.times, key: f.keyFrame, data: f.graph.data.map((d) => [d.x, d.y, d.z])}; }")
AXES = ("x", "y", "z")  # (z in a 3-D scene: Euler's disk)
ROUNDING = 10.0 ** -DIGITS


def assert_the_server_s_figure(page, pid: str) -> dict:
    """The stage's frames as drawn against the server's figure for the page's address; the address's query."""
    page.wait_for_function(DRAWN, timeout=30_000)
    query = dict(parse_qsl(urlparse(page.url).query))
    params, warnings = parameters_of_link(BY_ID[pid], query, "si", markdown=False)
    assert not warnings, warnings
    reference = drawings(pid).figures(registry.solver(pid).solve(**params))[0]
    want = expanded(reference.spec)
    drawn = page.evaluate(FRAMES)
    assert drawn["key"] == reference.key_frame
    assert np.allclose(drawn["times"], reference.spec["animation"]["times"], rtol=0, atol=1.001e-6)  # (a unit apart at a boundary)
    assert len(drawn["frames"]) == len(want["frames"])
    for n, (have, frame) in enumerate(zip(drawn["frames"], want["frames"])):
        for trace, drawn_rows in zip(frame["data"], have):
            for axis, h in zip(AXES, drawn_rows):
                if axis not in trace:
                    assert h is None, (pid, n, axis)
                    continue
                w = np.array([np.nan if v is None else v for v in np.ravel(np.asarray(trace[axis], dtype=object))], dtype=float)
                h = np.array([np.nan if v is None else v for v in h], dtype=float)
                # both rounded to DIGITS from values equal to ~1e-12: equal, or one unit apart at a boundary
                assert w.shape == h.shape and np.allclose(h, w, rtol=0, atol=1.001 * ROUNDING, equal_nan=True), (
                    pid, query, n, axis)
    # and every trace that does not move, as drawn: a plot against time the browser draws from the motion
    # it integrates (θ(t) below the pendulum) among them
    moving = set(reference.spec["animation"]["traces"])
    for j, trace in enumerate(reference.spec["data"]):
        if j in moving:
            continue
        for axis, h in zip(AXES, drawn["data"][j]):
            if axis not in trace:
                continue
            w = np.array([np.nan if v is None else v for v in np.ravel(np.asarray(trace[axis], dtype=object))], dtype=float)
            h = np.array([np.nan if v is None else v for v in np.ravel(np.asarray(h, dtype=object))], dtype=float)
            assert w.shape == h.shape and np.allclose(h, w, rtol=0, atol=1.001 * ROUNDING, equal_nan=True), (
                pid, query, trace.get("name"), axis)
    return query


@pytest.mark.parametrize("pid", IN_BROWSER)
def test_the_motion_the_browser_computes_is_the_server_s_figure(browser, app_url, pid):
    context, page, errors = open_page(browser, f"{app_url}/{pid}{QUERIES.get(pid, '')}")
    before = assert_the_server_s_figure(page, pid)
    key = lesson_control(pid)[0]
    page.locator(f".st-key-dl_stage_controls .st-key-{key} input[type='range']").focus()
    page.keyboard.press("ArrowLeft")
    name = key.rsplit("__", 1)[1]
    page.wait_for_function(f"(was) => new URL(location.href).searchParams.get({name!r}) !== was",
                           arg=before.get(name), timeout=30_000)
    wait_until_idle(page)
    after = assert_the_server_s_figure(page, pid)
    assert after != before
    assert not errors, errors
    context.close()


def test_chromium_s_websocket_is_compressed(browser, app_url):
    """A change's bytes on the wire (issue 51): Chromium and the server agree on permessage-deflate
    (.streamlit/config.toml; serve.compress_websocket_fast), so its JSON and LaTeX travel at about a third
    of their size."""
    from tests.browser.test_browser import watched_context

    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    agreed = []
    cdp = context.new_cdp_session(page)
    cdp.send("Network.enable")
    cdp.on("Network.webSocketHandshakeResponseReceived",
           lambda e: agreed.append({k.lower(): v for k, v in e["response"]["headers"].items()}.get("sec-websocket-extensions", "")))
    page.goto(f"{app_url}/disk_wall")
    page.wait_for_function(DRAWN, timeout=30_000)
    assert agreed and all(a.startswith("permessage-deflate") for a in agreed), agreed
    context.close()
