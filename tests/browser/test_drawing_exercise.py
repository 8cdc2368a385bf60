"""“Draw the free-body diagram” as a student meets it in Debian's Chromium (issue 50): drawn right with
the keyboard alone at a laptop's size, every change announced, judged right; drawn wrong on purpose
by touch on a phone (a finger turns an arrow by its handle, which leaves the arrow in sight) and by the
mouse on the projector, each slip named; axe-core finds nothing serious; and nothing of the expected
diagram reaches the browser before the solution is shown (every websocket frame the page receives is
read). One server and one browser serve the module."""
from __future__ import annotations

import math

import pytest

from practice.diagram_judge import exercise_diagram
from solvers import registry
from tests.browser.test_browser import open_page, watched_context

pytestmark = pytest.mark.browser

DRAW = ".dl-draw"


def _add(page, kind: str, name: str, at: str) -> None:
    """A load added from the palette by the keyboard: the kind chosen, the name typed, the point chosen, Add."""
    d = page.locator(DRAW)
    d.locator("[data-dl=kind]").focus()
    d.locator("[data-dl=kind]").select_option(label=kind)  # (a native select: the keys pick its option)
    page.keyboard.press("Tab")
    page.keyboard.type(name)
    page.keyboard.press("Tab")
    d.locator("[data-dl=point]").select_option(label=at)
    page.keyboard.press("Tab")
    page.keyboard.press("Enter")


def _announced(page) -> str:
    page.wait_for_timeout(120)
    return page.locator(f"{DRAW} [role=status]").inner_text()


def _verdict(page) -> str:
    alert = page.locator("[data-testid='stAlert']").filter(has_text="thing").or_(
        page.locator("[data-testid='stAlert']").filter(has_text="Right: every load"))
    alert.first.wait_for(timeout=30_000)
    return alert.first.inner_text()


def test_drawn_right_with_the_keyboard_alone(browser, app_url):
    from tests.browser.test_where_used import serious_violations

    context, page, errors = open_page(browser, f"{app_url}/sliding_ladder?practice=1")
    try:
        page.locator(DRAW).wait_for(timeout=60_000)
        _add(page, "Force", "W", "G")  # a new force points down
        assert "Added: Force “W” at G, along −E_y" in _announced(page)
        _add(page, "Force", "N_B", "B")
        page.keyboard.press("Tab")  # from Add to the drawing, where the new load is selected
        for _ in range(12):  # 12 × 15° = 180°: up
            page.keyboard.press("ArrowUp")
        assert "Force “N_B” at B, along +E_y" in _announced(page)
        _add(page, "Force", "N_A", "G")
        page.keyboard.press("Tab")
        page.keyboard.press("ArrowRight")  # G -> A (the points in order G, A, B)
        assert "Moved: Force “N_A” at A" in _announced(page)
        for _ in range(6):
            page.keyboard.press("ArrowUp")
        assert "Force “N_A” at A, along +E_x" in _announced(page)
        # a fourth, taken away again by the Delete key
        _add(page, "Impulse", "extra", "B")
        page.keyboard.press("Tab")
        page.keyboard.press("Delete")
        assert "Removed: Impulse “extra”" in _announced(page)
        assert page.locator(f"{DRAW} ol > li").count() == 3
        page.locator(f"{DRAW} [data-dl=check]").focus()
        page.keyboard.press("Enter")
        assert "Right: every load is there" in _verdict(page)
        # the drawing outlives the run the Check started, and the list reads it to a screen reader
        rows = page.locator(f"{DRAW} ol > li").all_inner_texts()
        assert len(rows) == 3 and "along +E_x" in rows[2]
        assert serious_violations(page) == []
        assert not errors, errors
    finally:
        context.close()


def test_drawn_wrong_by_touch_on_a_phone(browser, app_url):
    context, page, errors = open_page(browser, f"{app_url}/disk_wall?practice=1", 390, 844, phone=True)
    try:
        d = page.locator(DRAW)
        d.wait_for(timeout=60_000)
        d.locator("[data-dl=name]").fill("F")
        d.locator("[data-dl=add]").tap()  # an impulse at C, the centre: nothing touches the disk there
        handle = d.locator(".dl-draw-handle").first
        handle.scroll_into_view_if_needed()
        box = handle.bounding_box()
        assert box["width"] >= 44, box  # a fingertip's size
        tip = page.evaluate("""() => { const p = document.querySelector('.dl-draw g[data-load] polygon');
            const r = p.getBoundingClientRect(); return [r.left + r.width / 2, r.top + r.height / 2]; }""")
        centre = (box["x"] + box["width"] / 2, box["y"] + box["height"] / 2)
        assert math.dist(tip, centre) > box["width"] / 2, "the arrow's head is under the finger"
        cdp = context.new_cdp_session(page)
        cdp.send("Input.dispatchTouchEvent", {"type": "touchStart", "touchPoints": [{"x": centre[0], "y": centre[1]}]})
        for k in range(1, 9):  # the finger goes round to the right of C: the impulse turns toward +E_x
            cdp.send("Input.dispatchTouchEvent", {"type": "touchMove", "touchPoints": [
                {"x": centre[0] + 9 * k, "y": centre[1] - 7 * k}]})
        cdp.send("Input.dispatchTouchEvent", {"type": "touchEnd", "touchPoints": []})
        page.wait_for_timeout(600)  # (a finger lifts and comes back: a tap at once would be taken for the drag's double tap)
        row = d.locator("ol > li").first.inner_text()
        assert "Impulse “F” at" in row and "along −E_y" not in row, row
        d.locator("[data-dl=check]").tap()
        said = _verdict(page)
        assert "“F” is drawn at C: does anything touch the disk there?" in said
        assert page.evaluate("document.documentElement.scrollWidth") <= 390
        from tests.browser.test_where_used import serious_violations
        assert serious_violations(page) == []
        page.get_by_role("heading", name="The problem").scroll_into_view_if_needed()
        sketch = page.locator("img[alt^='The disk slides toward a rough wall']")
        assert sketch.count() == 1 and sketch.bounding_box()["width"] <= 390
        assert not errors, errors
    finally:
        context.close()


def test_drawn_wrong_with_the_mouse_on_the_projector(browser, app_url):
    """The ladder with a normal force pulling into the floor and friction on the smooth wall."""
    context, page, errors = open_page(browser, f"{app_url}/sliding_ladder?practice=1", 1280, 720)
    try:
        d = page.locator(DRAW)
        d.wait_for(timeout=60_000)
        for name, at in (("W", "G"), ("N", "B"), ("f", "A")):
            d.locator("[data-dl=point]").select_option(label=at)
            d.locator("[data-dl=name]").fill(name)
            d.locator("[data-dl=add]").click()
        # the last (f at A, pointing down) dragged by its handle to point up along the wall
        handle = d.locator(".dl-draw-handle").nth(2)
        handle.scroll_into_view_if_needed()
        box = handle.bounding_box()
        x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
        page.mouse.move(x, y)
        page.mouse.down()
        page.mouse.move(x, y - 150, steps=6)
        page.mouse.up()
        assert "along +E_y" in d.locator("ol > li").nth(2).inner_text()
        d.locator("[data-dl=check]").click()
        said = _verdict(page)
        assert "“N” pulls the ladder toward the floor: the floor can only push on it" in said
        assert "“f”: the wall is smooth: it pushes along its normal only" in said
        assert "Something else touches the ladder" in said
        assert not errors, errors
    finally:
        context.close()


@pytest.mark.parametrize("pid", ["sliding_ladder", "pendulum_rebound"])
def test_nothing_of_the_diagram_reaches_the_browser_before_the_solution(browser, app_url, pid):
    """Every websocket frame the Practice page receives, read for what only the diagram would say: a
    load's name ("the wall's normal force"), the diagram's own drawing (svg.dl-fbd) and its Step 2."""
    solver = registry.solver(pid)
    diagram = exercise_diagram(solver, solver.solve())
    bodies = {b.name for b in diagram.bodies}
    telling = [load.name for load in diagram.loads if load.name not in bodies] + ['class="dl-fbd"', "isolated. "]
    context = watched_context(browser, viewport={"width": 1400, "height": 1000})
    page = context.new_page()
    received: list[bytes] = []
    page.on("websocket", lambda ws: ws.on("framereceived", lambda f: received.append(
        f if isinstance(f, bytes) else f.encode())))
    try:
        page.goto(f"{app_url}/{pid}?practice=1")
        page.locator(DRAW).wait_for(timeout=60_000)
        page.get_by_role("button", name="Show the solution").wait_for(timeout=30_000)
        sent = b"".join(received).decode("utf-8", "replace")
        assert "dl-draw-body" in sent  # the blank arrived, by this way
        assert [word for word in telling if word in sent] == []
        page.get_by_role("button", name="Show the solution").click()
        page.locator("svg.dl-fbd").first.wait_for(timeout=30_000)  # and with the solution, the diagram
    finally:
        context.close()


def test_in_an_assignment_the_diagram_is_a_question_recorded_like_an_answer(browser, app_url, monkeypatch):
    """The ladder's diagram counted beside one answer: nothing drawn costs no attempt; a wrong drawing is
    attempt 1, the same drawing again is not counted again, the right one counts; the method's later
    steps open; the student's table and the gradebook's CSV have it."""
    import csv
    import io

    from assignments import records
    from assignments.identity import StudentIdentity, link_query
    from tests.browser.test_assignments_browser import choose, download, enter_key, seeded_assignment, wait_for_text
    from urllib.parse import urlencode

    ids: list[int] = []
    choice = seeded_assignment(monkeypatch, "Draw the ladder", {"sliding_ladder": 1}, ["s01"], (records.DIAGRAM,), ids)
    identity = StudentIdentity(ids[0], "s01", records.student_seed(ids[0], "s01"))
    context, page, errors = open_page(browser, f"{app_url}/sliding_ladder?{urlencode(link_query(identity))}")
    try:
        wait_for_text(page, "Graded assignment")
        d = page.locator(DRAW)
        d.wait_for(timeout=60_000)
        assert "follow once your diagram is right" in page.locator("[data-testid='stMain']").inner_text()
        d.locator("[data-dl=check]").click()
        assert "Nothing is drawn yet" in page.get_by_text("This is not counted as an attempt").first.inner_text()
        for name, at in (("W", "G"), ("N", "B")):
            d.locator("[data-dl=point]").select_option(label=at)
            d.locator("[data-dl=name]").fill(name)
            d.locator("[data-dl=add]").click()
        d.locator("[data-dl=check]").click()
        page.get_by_text("Recorded: attempt 1 of 3 at “Free-body diagram”").wait_for(timeout=30_000)
        d.locator("[data-dl=check]").click()  # the same drawing again
        page.get_by_text("not counted again").first.wait_for(timeout=30_000)
        svg = d.locator(".dl-draw-canvas > svg")
        svg.focus()
        for _ in range(12):  # N (selected, the last added) turned up
            page.keyboard.press("ArrowUp")
        d.locator("[data-dl=point]").select_option(label="A")
        d.locator("[data-dl=name]").fill("N_A")
        d.locator("[data-dl=add]").click()
        svg.focus()
        for _ in range(6):
            page.keyboard.press("ArrowUp")
        d.locator("[data-dl=check]").click()
        page.get_by_text("Right, and it counts").first.wait_for(timeout=30_000)
        main = page.locator("[data-testid='stMain']").inner_text()
        assert "follow once your diagram is right" not in main and "Newton–Euler" in main
        assert "Free-body diagram: right at attempt 2" in main, main[-1500:]
        assert not errors, errors
    finally:
        context.close()
    context, page, errors = open_page(browser, f"{app_url}/gradebook")
    try:
        enter_key(page)
        choose(page, "Assignment", choice)
        page.get_by_role("button", name="Download the gradebook (CSV)").wait_for(timeout=60_000)
        book = list(csv.DictReader(io.StringIO(download(page, "Download the gradebook (CSV)"))))
        assert [(r["label"], r["Free-body diagram:points"], r["Free-body diagram:out_of"]) for r in book] == [
            ("s01", "1", "1")]
        attempts = list(csv.DictReader(io.StringIO(download(page, "Download every attempt (CSV)"))))
        drawn = [a for a in attempts if a["answer"] == records.DIAGRAM]
        assert len(drawn) == 2 and drawn[0]["typed"].startswith("force “W” at G, 270°")
    finally:
        context.close()
