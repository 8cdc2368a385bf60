"""A derivation as a person meets it, in Debian's Chromium: every page at a laptop's, a projector's (the
lecture view: labels in projector type) and a phone's size, visited once per size for both of its pictures:
- Step 2's free-body diagrams: no label on another or outside its picture, the picture inside the column, a
  text alternative for a screen reader, nothing serious for axe-core; two diagrams side by side where the
  column holds both (the ladder's), none on another;
- every display equation whole (none cut above or below), and none set smaller or scrolling sideways where
  the width gives room.
One server and one browser serve the module (tests/conftest.py)."""
from __future__ import annotations

import pytest

from solvers import registry
from tests.browser.test_browser import open_page, visit

pytestmark = pytest.mark.browser

SIZES = {"laptop": (1400, 1000, ""), "projector": (1280, 720, "?lecture=1"), "phone": (390, 844, "")}

# Every diagram's labels, as drawn: each text's box, and its picture's.
MEASURE = """() => [...document.querySelectorAll('svg.dl-fbd')].map((svg) => {
  const r = (el) => { const b = el.getBoundingClientRect(); return [b.left, b.top, b.right, b.bottom]; };
  return {svg: r(svg), column: r(svg.closest('.dl-text')), label: svg.getAttribute('aria-label'),
          texts: [...svg.querySelectorAll('text')].map((t) => [t.textContent, ...r(t)])};
})"""


EQUATIONS_DRAWN = """() => [...document.querySelectorAll('.dl-math .katex-display')].map((d) => {
  const box = d.getBoundingClientRect(), tex = (d.querySelector('annotation') || {}).textContent || '';
  let top = Infinity, bottom = -Infinity;
  for (const e of d.querySelectorAll('.katex-html *')) {
    const r = e.getBoundingClientRect();
    if (r.width && r.height) { top = Math.min(top, r.top); bottom = Math.max(bottom, r.bottom); }
  }
  return {tex: tex.slice(0, 80), above: box.top - top, below: bottom - box.bottom,
          smaller: /\\\\(small|footnotesize|scriptsize)\\b/.test(tex), scrolls: d.scrollWidth > d.clientWidth + 1};
})"""




def _overlap(a, b) -> bool:
    return not (a[2] <= b[0] + 0.5 or b[2] <= a[0] + 0.5 or a[3] <= b[1] + 0.5 or b[3] <= a[1] + 0.5)


@pytest.mark.parametrize("size", list(SIZES))
def test_every_page_draws_its_diagrams_legibly_and_its_equations_whole(browser, app_url, size):
    """The diagrams: as the module says. The equations: the stick's x_rev = 2·π·0.5000 / 1.200 had its
    numerator's top cut off (a display equation scrolls sideways, which clips it above and below), and the
    ladder's |θ̇_f| was set at 60 % of the others' size on a laptop with room to spare (its rows broken for a
    phone); a wide column's rows, taken on an estimate, ran past a projector's column in lecture type. Every
    equation of every page is whole; on a laptop none is set smaller, and on a laptop or a projector none
    scrolls sideways (where the wide rows would, the phone's are drawn)."""
    from tests.browser.test_where_used import serious_violations

    width, height, query = SIZES[size]
    context, page, errors = open_page(browser, f"{app_url}/{registry.PROBLEM_IDS[0]}{query}", width, height,
                                      phone=size == "phone")
    try:
        for n, pid in enumerate(registry.PROBLEM_IDS):
            if n:
                visit(page, app_url, f"{pid}{query}")
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
            # a page's diagrams (the ladder's two) apart, and side by side where the column holds them
            boxes = [d["svg"] for d in drawn]
            assert not [(i, j) for i, a in enumerate(boxes) for j, b in enumerate(boxes[:i]) if _overlap(a, b)], (pid, size)
            column = drawn[0]["column"]
            if size == "laptop" and sum(b[2] - b[0] + 40 for b in boxes) <= column[2] - column[0]:
                assert len({round(b[1]) for b in boxes}) == 1, (pid, size, "stacked with room beside", boxes)
            if n == 0 or size == "phone" and pid == "stick_ball":
                assert serious_violations(page) == [], (pid, size)
            _equations_whole(page, pid, size)
        assert not errors, errors
    finally:
        context.close()


def _equations_whole(page, pid: str, size: str) -> None:
    page.locator(".dl-math .katex-display").first.wait_for(timeout=30_000)
    page.evaluate("document.fonts.ready.then(() => new Promise(requestAnimationFrame))")  # KaTeX's own widths
    page.wait_for_timeout(300)
    drawn = page.evaluate(EQUATIONS_DRAWN)
    assert drawn, (pid, size)
    cut = [e for e in drawn if e["above"] > 0.5 or e["below"] > 0.5]
    assert not cut, (pid, size, cut)
    if size != "phone":  # (nor, taking a wide column's rows, one wider than the column: it scrolled sideways)
        assert not [e["tex"] for e in drawn if e["scrolls"] or (e["smaller"] and size == "laptop")], (pid, size)


# The stage's overlay as drawn: each Forces trace's points (non-null) and opacity, and the switch.
OVERLAY = """() => {
  const g = document.querySelector('.st-key-dl_stage .dl-graph'), b = document.querySelector('.st-key-dl_stage .dl-forces');
  const full = g._fullData || [];
  return {pressed: b && !b.hidden ? b.getAttribute('aria-pressed') : null,
          traces: (g.data || []).map((t, i) => [t.name, t.legendgroup === 'forces', (t.x || []).filter((v) => v !== null).length,
                                                  full[i] ? full[i].opacity : 1])};
}"""


@pytest.mark.parametrize("pid", ["disk_wall", "sliding_ladder"])
def test_the_stage_s_forces_switch_is_pressed_by_keyboard_and_its_arrows_follow_a_drag(browser, app_url, pid):
    """The Forces switch is a button in the motion's own row: pressed from the keyboard it lays the
    diagram's arrows on the motion and the link keeps it; while a lesson control is dragged the arrows at
    the key instant follow it (posed, not dimmed), as the bodies do; pressed again, they are gone."""
    from bench.controls import lesson_control
    from tests.browser.test_browser import TRACK, hold_drag
    from scripts.live_app import wait_until_idle

    context, page, errors = open_page(browser, f"{app_url}/{pid}", 1400, 1000)
    try:
        switch = page.locator(".st-key-dl_stage .dl-forces")
        switch.wait_for(timeout=30_000)
        assert page.evaluate(OVERLAY)["pressed"] == "false"
        assert not any(forces for _, forces, _, _ in page.evaluate(OVERLAY)["traces"])
        switch.focus()
        page.keyboard.press("Enter")
        page.wait_for_function("() => document.querySelector('.st-key-dl_stage .dl-forces').getAttribute('aria-pressed') === 'true'",
                               timeout=30_000)
        wait_until_idle(page)
        assert "forces=1" in page.url
        drawn = page.evaluate(OVERLAY)
        assert sum(forces for _, forces, _, _ in drawn["traces"]) >= 2, drawn
        # the pose modules: the page's first, then the one with the arrows (after the press)
        page.wait_for_function("() => performance.getEntriesByType('resource').filter((r) => /\\/pose\\.[0-9a-f]+\\.js/.test(r.name)).length >= 2",
                               timeout=30_000)
        page.evaluate("async () => { for (const r of performance.getEntriesByType('resource'))"
                      " if (/\\/pose\\.[0-9a-f]+\\.js/.test(r.name)) await import(r.name); }")
        control = page.locator(f".st-key-{lesson_control(pid)[0]}")
        hold_drag(page, control.locator(TRACK).bounding_box(), 0.45, 0.6)
        page.wait_for_function("() => document.querySelector('.st-key-dl_stage .dl-graph.dl-live-stale') === null"
                               " && !!document.querySelector('.dl-live-value')", timeout=10_000)
        page.wait_for_timeout(300)
        held = page.evaluate(OVERLAY)["traces"]
        arrows = [(name, points, opacity) for name, forces, points, opacity in held if forces]
        assert any(points for _, points, _ in arrows), arrows  # drawn at the key instant
        assert all(opacity == 1 for _, points, opacity in arrows if points), arrows  # posed, not dimmed
        page.mouse.up()
        wait_until_idle(page)
        switch.focus()
        page.keyboard.press("Space")
        page.wait_for_function("() => document.querySelector('.st-key-dl_stage .dl-forces').getAttribute('aria-pressed') === 'false'",
                               timeout=30_000)
        wait_until_idle(page)
        assert not any(forces for _, forces, _, _ in page.evaluate(OVERLAY)["traces"])
        assert "forces=1" not in page.url
        assert not errors, errors
    finally:
        context.close()
