"""The stage (issue 27): on every problem page the motion, its Play button and the lesson's controls
(the registry's ``primary``) are all in the first screen, the controls never cover the figure, and
the bodies fill the plot: the motion's extent over every frame, as drawn, spans at least half of the
plot area in width or in height, with equal axes.

``stage_faults`` measures one page as it is shown. This module measures every page at a laptop
(1400×1000, Study) in one browser context; tests/test_where_used.py measures the same on the pages
it already opens at a projector (1280×720 and 1024×768, Lecture) and a phone (390×844), so the
three sizes cost no extra page loads.
"""
from __future__ import annotations

import pytest

from scripts.live_app import wait_until_idle
from tests.test_browser import open_page  # which skips (or, in CI, fails) without Chromium and Playwright
from ui.catalog import PROBLEMS

pytestmark = pytest.mark.browser

STAGE, CONTROLS = ".st-key-dl_stage", ".st-key-dl_stage_controls"

# The motion's box as drawn: every frame's moving traces on the motion's axes (x, y), in pixels, beside
# the plot area; and how many pixels a unit is along each axis (equal axes: the same). A 3-D scene:
# the scene's box beside the graph's.
MEASURE = """(g) => {
  const full = g._fullLayout;
  if (full.scene) {
    const domain = full.scene.domain, graph = g.getBoundingClientRect();
    return {scene: true, domainW: domain.x[1] - domain.x[0], domainH: domain.y[1] - domain.y[0],
            plotW: full._size.w, graphW: graph.width};
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
  return {scene: false, frames: frames.length, width: Math.abs(xa.l2p(x1) - xa.l2p(x0)) / xa._length,
          height: Math.abs(ya.l2p(y1) - ya.l2p(y0)) / ya._length,
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
    m = figure.locator(".dl-graph").evaluate(MEASURE)
    if m["scene"]:  # Euler's disk: the 3-D scene takes the graph's room
        if not (m["domainW"] >= 0.9 and m["domainH"] >= 0.9 and m["plotW"] >= 0.8 * m["graphW"]):
            faults.append(f"scene {m}")
    elif m["frames"] <= 1:
        faults.append("no animation")
    else:
        if max(m["width"], m["height"]) < 0.5:
            faults.append(f"bodies fill {m['width']:.2f} × {m['height']:.2f} of the plot")
        if abs(m["unitX"] - m["unitY"]) > 0.01 * m["unitX"]:
            faults.append(f"unequal axes {m['unitX']:.1f} / {m['unitY']:.1f} px")
    return faults


def test_the_motion_its_play_and_the_lesson_s_controls_share_a_laptop_s_first_screen(browser, app_url):
    width, height = 1400, 1000
    context, page, errors = open_page(browser, f"{app_url}/", width, height)
    found = {}
    for problem in PROBLEMS:
        page.goto(f"{app_url}/{problem.id}")
        wait_until_idle(page)
        faults = stage_faults(page, problem, height)
        if faults:
            found[problem.id] = faults
        assert page.locator("[data-testid='stException']").count() == 0, problem.id
    assert found == {}
    assert not errors, errors
    context.close()
