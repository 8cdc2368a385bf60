"""The free-body diagrams as a person meets them, in Debian's Chromium: every page's Step 2 shows its
diagrams at a laptop's, a projector's (the lecture view: labels in projector type) and a phone's
size, no label on another or outside its picture, the picture inside the column; a screen reader
gets each diagram's text alternative; axe-core finds nothing serious. One server and one browser
serve the module (tests/conftest.py)."""
from __future__ import annotations

import os
from pathlib import Path

import pytest

from scripts.live_app import CHROMIUM
from solvers import registry
from tests.test_browser import open_page

pytestmark = pytest.mark.browser

if not Path(CHROMIUM).exists():
    if os.environ.get("CI"):
        raise RuntimeError(f"CI needs Chromium at {CHROMIUM} (.ci/run installs Debian's chromium)")
    pytest.skip(f"no Chromium at {CHROMIUM}: apt-get install chromium", allow_module_level=True)

pytest.importorskip("playwright.sync_api")

SIZES = {"laptop": (1400, 1000, ""), "projector": (1280, 720, "?lecture=1"), "phone": (390, 844, "")}

# Every diagram's labels, as drawn: each text's box, and its picture's.
MEASURE = """() => [...document.querySelectorAll('svg.dl-fbd')].map((svg) => {
  const r = (el) => { const b = el.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom]; };
  return {svg: r(svg), column: r(svg.closest('.dl-text')), label: svg.getAttribute('aria-label'),
          texts: [...svg.querySelectorAll('text')].map((t) => [t.textContent, ...r(t)])};
})"""


def _overlap(a, b) -> bool:
    return not (a[2] <= b[0] + 0.5 or b[2] <= a[0] + 0.5 or a[3] <= b[1] + 0.5 or b[3] <= a[1] + 0.5)


@pytest.mark.parametrize("size", list(SIZES))
def test_every_page_draws_its_diagrams_legibly(browser, app_url, size):
    from tests.test_where_used import serious_violations

    width, height, query = SIZES[size]
    context, page, errors = open_page(browser, f"{app_url}/{registry.PROBLEM_IDS[0]}{query}", width, height,
                                      phone=size == "phone")
    try:
        for n, pid in enumerate(registry.PROBLEM_IDS):
            if n:
                page.goto(f"{app_url}/{pid}{query}")
            page.locator("svg.dl-fbd").first.wait_for(timeout=60_000)
            solver = registry.solver(pid)
            expected = len(solver.free_body_diagrams(solver.solve().params))
            drawn = page.evaluate(MEASURE)
            assert len(drawn) == expected, (pid, size, len(drawn))
            for d in drawn:
                assert d["label"].startswith("Free-body diagram"), (pid, d["label"])
                svg = d["svg"]
                assert svg[0] >= d["column"][0] - 1 and svg[2] <= d["column"][2] + 1, (pid, size, "wider than its column")
                texts = d["texts"]
                for i, (text, *box) in enumerate(texts):
                    assert box[0] >= svg[0] - 0.5 and box[2] <= svg[2] + 0.5 and box[1] >= svg[1] - 0.5 \
                        and box[3] <= svg[3] + 0.5, (pid, size, text, "leaves the figure")
                    for other, *obox in texts[:i]:
                        assert not _overlap(box, obox), (pid, size, text, other)
                if size == "projector":  # the back row: load labels in projector type
                    heights = [t[4] - t[2] for t in texts]
                    assert max(heights) >= 18, (pid, heights)
            if n == 0 or size == "phone" and pid == "stick_ball":
                assert serious_violations(page) == [], (pid, size)
        assert not errors, errors
    finally:
        context.close()
