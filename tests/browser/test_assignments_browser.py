"""Assignments in Chromium, end to end, as an instructor and three students meet them (issue 26).

The instructor enters the key, creates an assignment for three students (the disk and the wall,
a penalty of 20 % per day late), presses Create a second time (nothing is added), downloads the
links. Ann (a phone, in Tokyo) makes two typos, which cost nothing, then answers right, on time.
Bea (Berlin) answers wrong, then the same wrong answer again (counted once). The instructor then
moves the due time to a minute ago and gives Cem an extension; Bea answers right, late (80 %);
Cem (New York) makes a typo and answers right within his extension (full points). Each student's
banner shows the due time in their own time zone; the gradebook, its CSV, the Canvas CSV, the
attempts CSV and each student's own page agree. A tampered link is refused. axe-core finds no
serious or critical WCAG 2.1 A/AA issue on either page, and each is shot at 1400×1000, 1280×720
and 390×844 into screenshots/assignments/."""
from __future__ import annotations

import csv
import datetime as dt
import io
import re
from pathlib import Path

import pytest
from playwright.sync_api import expect

from assignments import records, signing
from scripts.live_app import wait_until_idle
from solvers import disk_wall
from tests.conftest import INSTRUCTOR_KEY as KEY
from practice.variants import ASSIGNMENT, variant
from solvers import units

pytestmark = pytest.mark.browser
SHOTS = Path(__file__).resolve().parents[2] / "screenshots" / "assignments"
SIZES = {"laptop": (1400, 1000), "projector": (1280, 720), "phone": (390, 844)}
TITLE = "Week 6: the disk and the wall"

from tests.browser.test_browser import csp_violations, open_page  # noqa: E402
from tests.browser.test_where_used import serious_violations  # noqa: E402


@pytest.fixture(scope="module")
def course_url(shipped_server):
    """The session's shared server: an instructor key, a course secret, its records in SQLite."""
    return shipped_server.url


def shoot(page, name: str) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"{name}.png"), full_page=True)


def no_sideways_scroll(page) -> bool:
    return page.evaluate("document.documentElement.scrollWidth <= window.innerWidth + 1")


def open_at(browser, url: str, size: str, zone: str):
    """A fresh context at this viewport and time zone, the page opened and idle, and its script errors."""
    return open_page(browser, url, *SIZES[size], phone=size == "phone", zone=zone)


def wait_for_text(page, text: str) -> None:
    page.get_by_text(text, exact=False).first.wait_for(timeout=60_000)
    wait_until_idle(page)


def main_text(page) -> str:
    return page.locator("[data-testid='stMain']").inner_text()


def check(page, typed: str, expect: str) -> str:
    """Type an answer, press Check, wait for ``expect``; the page's main text."""
    page.get_by_label("Your answer", exact=True).fill(typed)
    page.get_by_role("button", name="Check", exact=True).click()
    wait_for_text(page, expect)
    return main_text(page)


def v1x(row: dict, sign: float = 1.0) -> str:
    value = disk_wall.solve(**variant(disk_wall, "disk_wall", int(row["seed"]), ASSIGNMENT)).answers["v1x"]
    return f"{sign * units.to_display(value, 'speed'):.5g}"


def enter_key(page) -> None:
    page.get_by_label("Instructor key", exact=True).fill(KEY)
    page.get_by_label("Instructor key", exact=True).press("Enter")
    wait_until_idle(page)


def choose(page, label: str, option: str, tries: int = 3) -> None:
    """Pick an option of a Streamlit selectbox or multiselect by typing it, as a person would by keyboard: a
    click on the list can wait on an option that the typed filter keeps redrawing (CI timed out on "element is
    not stable"). On a busy machine the list may still be redrawing when the keys come (the option never took
    the focus, or a run redrew the list under them): the list is closed and the choice typed again, up to
    ``tries`` times."""
    box = page.get_by_role("combobox", name=label).first
    target = page.get_by_role("option", name=option, exact=True).first
    for _ in range(tries):
        box.click()
        page.keyboard.press("Control+a")  # (a try before may have left its text)
        page.keyboard.type(option)
        target.wait_for()
        for _ in range(40):
            if target.get_attribute("data-focused") == "true":
                page.keyboard.press("Enter")
                page.keyboard.press("Escape")
                wait_until_idle(page)
                return
            page.keyboard.press("ArrowDown")
            page.wait_for_timeout(25)
        page.keyboard.press("Escape")
        wait_until_idle(page)
    raise AssertionError(f"the option {option!r} of {label!r} never took the keyboard's focus ({tries} tries)")


def segment(scope, label: str, digits: str) -> None:
    """Type into one segment of a date or time field (year, month, day; hour, minute)."""
    box = scope.get_by_role("spinbutton", name=label, exact=True)
    box.click()
    box.page.keyboard.type(digits)


def until(page, condition: str, timeout: float = 30) -> None:
    """Wait until ``condition`` (JavaScript) holds, asked from outside the page: Playwright's wait_for_function
    polls by evaluating a string in the page, which the app's CSP (no 'unsafe-eval') refuses."""
    for _ in range(int(timeout * 10)):
        if page.evaluate(condition):
            return
        page.wait_for_timeout(100)
    raise AssertionError(f"never true: {condition}")


def download(page, button: str) -> str:
    with page.expect_download() as done:
        page.get_by_role("button", name=button).click()
    return Path(done.value.path()).read_text()


def banner(page) -> str:
    """The assignment's banner, and the rules in the expander under it (read closed, as a screen reader may)."""
    from ui.assignments import RULES

    rules = page.locator("[data-testid='stExpander']").filter(has_text=RULES).first.text_content()
    return page.locator("[data-testid='stAlert']").filter(has_text="Graded assignment").first.inner_text() + "\n" + rules


def test_an_assignment_end_to_end(browser, course_url):
    # The instructor (New York): the key, a new assignment in UTC, 20 % per day late, three students.
    context, page, errors = open_at(browser, f"{course_url}/gradebook", "laptop", "America/New_York")
    enter_key(page)
    wait_for_text(page, "New assignment")
    page.get_by_label("Title", exact=True).fill(TITLE)
    page.get_by_label("Title", exact=True).press("Enter")
    wait_until_idle(page)
    choose(page, "Problems (one, or several", "Spinning disk hits a rough wall")
    choose(page, "Time zone for the due time", "UTC")
    page.get_by_text("A penalty per day late").click()
    wait_until_idle(page)
    page.get_by_label("Penalty per started day late (%)").fill("20")
    page.get_by_label("Penalty per started day late (%)").press("Enter")
    page.get_by_label("Roster: one student label per line").fill("s01\ns02\ns03\ns02")
    page.get_by_label("Roster: one student label per line").press("Control+Enter")
    wait_for_text(page, "Repeated label: s02 (lines 2 and 4)")  # flagged before creating
    assert page.get_by_role("button", name="Create the assignment and its links").is_disabled()
    page.get_by_label("Roster: one student label per line").fill("s01\ns02\ns03")
    page.get_by_label("Roster: one student label per line").press("Control+Enter")
    wait_for_text(page, "3 students")
    page.get_by_role("button", name="Create the assignment and its links").click()
    wait_for_text(page, "created for 3 students")
    # the form emptied and folded away: nothing to press twice, the new assignment's links in view (the fold may
    # come a run after the words: waited for, not read at once)
    page.get_by_role("button", name="Create the assignment and its links").wait_for(state="hidden", timeout=30_000)
    assert not page.get_by_placeholder("Week 9: the bouncing pendulum").is_visible()  # the new form's title
    assert len(records_of(page)) == 1
    links = list(csv.DictReader(io.StringIO(download(page, "Download the links (CSV)"))))
    assert [row["label"] for row in links] == ["s01", "s02", "s03"]
    assert all(row["link"].startswith(f"{course_url}/disk_wall?assignment=") for row in links)
    ann, bea, cem = links
    due_text = re.search(r"Due (\w{3} \d+ \w{3} \d{4}, \d\d:\d\d UTC)", main_text(page)).group(1)
    due = dt.datetime.strptime(due_text, "%a %d %b %Y, %H:%M UTC").replace(tzinfo=dt.timezone.utc)

    # Ann, on a phone in Tokyo: two typos cost nothing, then right, on time.
    actx, apage, aerrors = open_at(browser, ann["link"], "phone", "Asia/Tokyo")
    wait_for_text(apage, "Graded assignment")
    assert f"Due {records.when_text(due, 'Asia/Tokyo')}" in banner(apage) and "your time zone" in banner(apage)
    assert "not a proctored assessment" not in main_text(apage)
    for typo in ("hello", "w"):
        text = check(apage, typo, "This is not counted as an attempt")
        assert "Recorded" not in text
    text = check(apage, v1x(ann), "Right, and it counts")
    # The due time moves (below) to the first whole minute after Ann's answer: the editor sets minutes.
    moment = (dt.datetime.now(dt.timezone.utc) + dt.timedelta(minutes=1)).replace(second=0, microsecond=0)
    assert "attempt 1 of 3" in text and "Velocity after, along the wall done (right)" in banner(apage)
    for name in SIZES:
        apage.set_viewport_size(dict(zip(("width", "height"), SIZES[name])))
        apage.wait_for_timeout(400)
        apage.get_by_text("Right, and it counts").first.scroll_into_view_if_needed()
        shoot(apage, f"student-{name}")
    apage.set_viewport_size(dict(zip(("width", "height"), SIZES["phone"])))
    assert no_sideways_scroll(apage)
    assert serious_violations(apage) == []

    # Bea, in Berlin: wrong (the sign), the same again (counted once).
    bctx, bpage, berrors = open_at(browser, bea["link"], "laptop", "Europe/Berlin")
    wait_for_text(bpage, "Graded assignment")
    assert f"Due {records.when_text(due, 'Europe/Berlin')}" in banner(bpage)
    check(bpage, v1x(bea, -1), "Recorded: attempt 1 of 3")
    check(bpage, v1x(bea, -1), "not counted again")

    # A tampered link (another variant): refused, in plain words (while the minute runs out).
    tampered = bea["link"].replace(f"seed={bea['seed']}", f"seed={ann['seed']}")
    tctx, tpage, _ = open_at(browser, tampered, "laptop", "UTC")
    wait_for_text(tpage, "changed since your instructor issued it")
    assert tpage.get_by_role("button", name="Check", exact=True).count() == 0
    tctx.close()

    # The instructor moves the due time to that minute (after Ann's answer, before Bea's right one), and gives
    # Cem an extension of two days; then the minute begins.
    page.get_by_text("Edit: due time, attempts").click()
    edit = page.locator("[data-testid='stExpander']").filter(has_text="Save the changes")
    for part, value in (("year", "%Y"), ("month", "%m"), ("day", "%d")):
        segment(edit, f"{part}, Due date (UTC)", moment.strftime(value))
    for part, value in (("hour", "%H"), ("minute", "%M")):
        segment(edit, f"{part}, Due time (UTC)", moment.strftime(value))
    page.get_by_role("button", name="Save the changes").click()
    wait_for_text(page, "Saved: due time")
    page.get_by_text("One student: an extension or extra attempts").click()
    choose(page, "Student", "s03")
    page.get_by_text("An extension: a later due time for this student").click()
    page.get_by_role("button", name="Save for this student").click()
    wait_for_text(page, "Saved: s03")
    page.wait_for_timeout(max(0, (moment - dt.datetime.now(dt.timezone.utc)).total_seconds() + 1) * 1000)

    # Bea: right, late: 80 % (one started day, 20 %).
    bpage.reload()
    wait_for_text(bpage, "Graded assignment")
    assert "has passed" in banner(bpage)
    text = check(bpage, v1x(bea), "late credit")
    assert "earns 80 % of its points" in text
    assert "Your score so far: 0.8 of 7 points" in banner(bpage)
    # By keyboard, "Show the solution" asks first; the next button takes the focus each time (it was left on the
    # page's body, and Tab started again from the top); kept hidden, so the grades below stand.
    bpage.get_by_role("button", name="Show the solution").focus()
    bpage.keyboard.press("Enter")
    wait_for_text(bpage, "Opening the solution is recorded")
    until(bpage, "document.activeElement && document.activeElement.innerText.includes('Open the solution')")
    bpage.keyboard.press("Tab")
    assert bpage.evaluate("document.activeElement.innerText").strip() == "Keep it hidden"
    bpage.keyboard.press("Enter")
    bpage.get_by_role("button", name="Show the solution").wait_for()
    until(bpage, "document.activeElement && document.activeElement.innerText.includes('Show the solution')")
    assert "Opening the solution is recorded" not in main_text(bpage)

    # Cem, in New York: a typo, then right within his extension.
    cctx, cpage, cerrors = open_at(browser, cem["link"], "laptop", "America/New_York")
    wait_for_text(cpage, "Graded assignment")
    assert "(your extension)" in banner(cpage) and "has passed" not in banner(cpage)
    check(cpage, "(1 + 2", "This is not counted as an attempt")
    text = check(cpage, v1x(cem), "Right, and it counts")
    assert "attempt 1 of 3" in text

    # The gradebook, its CSVs and each student's page agree.
    page.reload()
    enter_key(page)
    page.get_by_role("button", name="Download the gradebook (CSV)").wait_for(timeout=60_000)
    body = main_text(page)
    assert "right at attempt 1" in body and "late (attempt 1): 80 % credit" in body
    assert "Velocity after, along the wall 1 × 80 % (late) = 0.8 of 7" in body  # how the score was computed
    assert "Reading the gradebook" in body and "History" in body
    book = list(csv.DictReader(io.StringIO(download(page, "Download the gradebook (CSV)"))))
    named = "Velocity after, along the wall"  # the columns call each answer as the page does
    assert [(r["label"], r["score"], r[f"{named}:points"], r[f"{named}:out_of"]) for r in book] == [
        ("s01", "1", "1", "1"), ("s02", "0.8", "0.8", "1"), ("s03", "1", "1", "1")]
    assert book[1]["right_but_late"] == "1" and book[2]["extension_until_utc"]
    canvas = list(csv.reader(io.StringIO(download(page, "Grades for Canvas (CSV)"))))
    assert canvas[1][0] == "Points Possible" and canvas[1][-1] == "7"
    assert [(r[2], r[-1]) for r in canvas[2:]] == [("s01", "1"), ("s02", "0.8"), ("s03", "1")]
    attempts = list(csv.DictReader(io.StringIO(download(page, "Download every attempt (CSV)"))))
    assert len(attempts) == 4  # no typo, no repeat: Ann 1, Bea 2, Cem 1
    assert float(attempts[1]["typed"]) < 0  # a typed number opens as a number (it was '-1.2)
    for student_page, score in ((apage, "1 of 7"), (bpage, "0.8 of 7"), (cpage, "1 of 7")):
        student_page.reload()
        wait_for_text(student_page, "Graded assignment")
        assert f"Your score so far: {score} points" in banner(student_page)
    assert serious_violations(page) == []
    for name in SIZES:
        page.set_viewport_size(dict(zip(("width", "height"), SIZES[name])))
        page.wait_for_timeout(400)
        assert no_sideways_scroll(page), name
        page.get_by_text("Reading the gradebook").first.scroll_into_view_if_needed()
        shoot(page, f"instructor-{name}")
    assert not errors and not aerrors and not berrors and not cerrors
    for c in (context, actx, bctx, cctx):
        c.close()


def seeded_assignment(monkeypatch, title: str, answers: dict[str, int], roster: list[str], also: tuple[str, ...] = (),
                      ids: list | None = None) -> str:
    """An assignment written straight into the shared server's records (the first ``answers[pid]`` answers of
    each problem, and the questions ``also`` names, the free-body diagram, due in two days): its choice in the
    gradebook's selectbox (its id appended to ``ids``)."""
    import importlib

    from sqlalchemy import create_engine

    from tests.conftest import _DATA_DIRS, COURSE_SECRET
    from solvers.catalog import BY_ID

    monkeypatch.setenv(signing.SECRET_ENV, COURSE_SECRET)  # the shared server's, which signs the roster's links
    bound = create_engine(f"sqlite:///{Path(_DATA_DIRS[0]) / 'dynamics-lab.sqlite'}")  # the shared server's records
    parts = tuple(records.Part(pid, tuple(a.name for a in importlib.import_module(f"solvers.{pid}").ANSWERS)[:n] + also)
                  for pid, n in answers.items())
    due = dt.datetime.now(dt.timezone.utc) + dt.timedelta(days=2)
    aid = records.create(records.Settings(title, parts, 5e-3, due, 3), roster, bound).id
    if ids is not None:
        ids.append(aid)
    return f"{aid}: {title} ({', '.join(BY_ID[p.problem].title for p in parts)})"


def test_a_wide_gradebook_scrolls_by_keyboard(browser, course_url, monkeypatch):
    """Three problems' answers on a 1280×720 projector: the gradebook is wider than the page and scrolled
    sideways only with a mouse (axe-core: scrollable-region-focusable, serious). Its box is a named region
    that Tab reaches and the arrow keys scroll."""
    assignment = seeded_assignment(monkeypatch, "Three problems, twelve answers",
                                   dict.fromkeys(("pendulum_rebound", "disk_wall", "sliding_ladder"), 4), ["s01", "s02"])
    context, page, errors = open_at(browser, f"{course_url}/gradebook", "projector", "UTC")
    enter_key(page)
    choose(page, "Assignment", assignment)
    wait_for_text(page, "Reading the gradebook")
    box = page.locator("[data-testid='stTable'] > div").filter(has=page.locator("table[aria-label='Gradebook']"))
    assert box.evaluate("b => b.scrollWidth > b.clientWidth")  # wider than the page: the case at hand
    assert (box.get_attribute("tabindex"), box.get_attribute("role")) == ("0", "region")
    assert box.get_attribute("aria-label") == "Gradebook, scrolls sideways"
    box.focus()
    page.keyboard.press("ArrowRight")
    until(page, "document.activeElement.scrollLeft > 0")
    assert serious_violations(page) == []
    assert not errors
    context.close()


def records_of(page) -> list[str]:
    """The assignments the page lists (its selectbox's current choice and the 'created' notes)."""
    text = main_text(page)
    return sorted(set(re.findall(r"Assignment (\d+) (?:created|was already created)", text)))


def test_an_instructor_link_leaves_the_address_bar_on_every_page(browser, course_url):
    """?instructor=KEY opens the instructor's side and is gone from the address bar at once, on
    the home page, every problem, the Assignments and the Handouts page; no page meets a CSP violation."""
    from solvers import registry

    for path in ["", *registry.PROBLEM_IDS, "gradebook", "handouts"]:
        context, page, errors = open_page(browser, f"{course_url}/{path}?instructor={KEY}")
        page.wait_for_function("() => !location.search.includes('instructor')", timeout=15_000)
        assert KEY not in page.url and KEY not in page.evaluate("document.body.innerText"), path
        assert csp_violations(page) == [] and not errors, path
        if path == "gradebook":  # opened: the instructor's page, no key box
            page.get_by_text("Create the assignment", exact=False).first.wait_for(state="attached", timeout=30_000)
            assert page.locator("input[type='password']").count() == 0
        context.close()


def test_the_assignments_page_is_at_the_address_its_title_names(browser, course_url, fresh_server):
    """The page is titled Assignments: /assignments opens it (it was "Page not found"), also as a server's
    very first visit, the navigation links there, and /gradebook, where it lived, still opens it for the
    links already given out."""
    for url in (f"{fresh_server.url}/assignments", f"{course_url}/assignments", f"{course_url}/gradebook"):
        context, page, errors = open_page(browser, url)
        page.locator("[data-testid='stMain'] h1", has_text="Assignments").wait_for(timeout=30_000)
        wait_until_idle(page)
        assert "Page not found" not in page.locator("body").inner_text(), url
        assert page.get_by_role("dialog").count() == 0, url
        path = url.rsplit("/", 1)[1]
        if url.startswith(course_url):  # (the fresh server has no instructor key set)
            page.get_by_label("Instructor key", exact=True).wait_for()
        link = page.locator("[data-testid='stSidebarNav'] a", has_text="Assignments")
        assert link.count() == 1 and link.get_attribute("href").endswith("/assignments"), path
        assert not errors, path
        context.close()


def test_named_slips_says_why_it_cannot_be_changed_while_hints_are_on(browser, course_url):
    """Issue 54: the box was greyed out with no reason. It is ticked (the hint names the slip), cannot be
    changed, and says why, in words on the page; unticking Hints gives it back."""
    context, page, errors = open_at(browser, f"{course_url}/assignments", "laptop", "UTC")
    enter_key(page)
    # (the New assignment form's: an assignment made by an earlier test has its own, in its Edit expander)
    new = page.locator("[data-testid='stExpander']").filter(has=page.locator("summary", has_text="New assignment"))
    if new.locator("details").get_attribute("open") is None:
        new.locator("summary").click()
    names = new.get_by_role("checkbox", name=re.compile("^Named slips"))
    names.wait_for(state="attached", timeout=30_000)
    assert names.is_checked() and names.is_disabled()
    reason = new.get_by_text("Hints on already name the slip", exact=False)
    reason.scroll_into_view_if_needed()
    assert reason.is_visible()
    new.get_by_text("Hints: a known slip is named", exact=False).click()
    # (waited for, not read at once: the run the click starts may not have begun when the page is idle again)
    expect(new.get_by_role("checkbox", name=re.compile("^Named slips"))).to_be_enabled(timeout=30_000)
    expect(new.get_by_text("Hints on already name the slip", exact=False)).to_have_count(0)
    assert not errors
    context.close()


def test_each_students_link_has_a_copy_button(browser, course_url, monkeypatch):
    """Issue 54: the links wrapped over three lines of small monospace with no way to copy one whole (a
    partial selection made a link refused as changed). Each stays as text and has a Copy button: a real
    button named for its student, pressed by keyboard, that copies the whole link and says "Copied" on
    the button and in a status line a screen reader reads; on a laptop and on a phone, under the CSP."""
    from sqlalchemy import create_engine

    from tests.conftest import _DATA_DIRS, COURSE_SECRET
    from solvers.catalog import BY_ID

    monkeypatch.setenv(signing.SECRET_ENV, COURSE_SECRET)
    bound = create_engine(f"sqlite:///{Path(_DATA_DIRS[0]) / 'dynamics-lab.sqlite'}")
    due = dt.datetime.now(dt.timezone.utc) + dt.timedelta(days=2)
    title = "Links to copy"
    aid = records.create(records.Settings.of(title, "pendulum_rebound", ("theta_rebound",), 5e-3, due, 3),
                         ["c01", "c02"], bound).id
    for size in ("laptop", "phone"):
        context, page, errors = open_at(browser, f"{course_url}/assignments", size, "UTC")
        context.grant_permissions(["clipboard-read", "clipboard-write"], origin=course_url)
        enter_key(page)
        choose(page, "Assignment", f"{aid}: {title} ({BY_ID['pendulum_rebound'].title})")
        page.get_by_text("The links (2)").click()
        wait_until_idle(page)
        links = page.locator(".dl-links code")
        assert links.count() == 2
        link = links.first.inner_text()
        assert link.startswith(f"{course_url}/pendulum_rebound?"), link
        button = page.get_by_role("button", name="Copy c01's link", exact=True)
        button.scroll_into_view_if_needed()
        assert button.is_visible() and no_sideways_scroll(page), size
        button.focus()
        page.keyboard.press("Enter")
        until(page, "document.querySelector('.dl-links [role=status]').textContent.includes('Copied')")
        assert page.evaluate("() => navigator.clipboard.readText()") == link
        assert page.get_by_role("status").filter(has_text="Copied c01's link.").count() == 1
        assert page.get_by_role("button", name="Copied c01's link", exact=True).is_visible()
        shoot(page, f"links-to-copy-{size}")
        assert csp_violations(page) == [] and not errors, size
        context.close()


def test_on_a_phone_an_assignment_opens_on_its_problem(browser, course_url, monkeypatch):
    """Issue 54: on a phone a student's assignment opened on two screens of rules and attempts left before
    the givens. The banner says what and when; the problem starts on the first screen (its sketch, issue 50,
    then its givens straight after it); the rules are one tap away, in an expander after the banner (at
    every size)."""
    from sqlalchemy import create_engine

    from tests.conftest import _DATA_DIRS, COURSE_SECRET
    from ui.assignments import RULES, student_url

    monkeypatch.setenv(signing.SECRET_ENV, COURSE_SECRET)
    bound = create_engine(f"sqlite:///{Path(_DATA_DIRS[0]) / 'dynamics-lab.sqlite'}")
    due = dt.datetime.now(dt.timezone.utc) + dt.timedelta(days=2)
    settings = records.Settings.of("Problem first", "pendulum_rebound", ("theta_rebound", "theta_impact"), 5e-3, due, 3)
    (who,) = records.roster(records.create(settings, ["f01"], bound).id, bound)
    for size in ("phone", "laptop"):
        context, page, errors = open_at(browser, student_url(course_url, "pendulum_rebound", who), size, "Asia/Tokyo")
        givens = page.locator("[data-testid='stMarkdownContainer'] table").filter(has_text="coefficient of restitution")
        givens.first.wait_for(timeout=60_000)
        wait_until_idle(page)
        sketch = page.locator("[data-testid='stMarkdownContainer'] img[alt^='The rod and sphere']").first.bounding_box()
        table = givens.first.bounding_box()
        top = page.evaluate("() => scrollY") + sketch["y"]
        assert top < SIZES[size][1] * 0.8, (size, top)  # the problem starts on the first screen
        assert 0 <= table["y"] - (sketch["y"] + sketch["height"]) < 60, (size, table, sketch)  # its givens next
        assert "Graded assignment: Problem first" in banner(page) and "Due" in banner(page)
        expander = page.locator("[data-testid='stExpander']").filter(has_text=RULES)
        assert expander.count() == 1 and expander.locator("details").get_attribute("open") is None  # closed
        shoot(page, f"problem-first-{size}")
        expander.locator("summary").click()
        expander.get_by_text("Attempts left", exact=True).wait_for()
        assert "What counts" in expander.inner_text()
        assert not errors
        context.close()
