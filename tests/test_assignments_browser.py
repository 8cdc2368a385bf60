"""Assignments in Chromium, as an instructor and two students meet them: the instructor enters the
key, creates an assignment from a roster and downloads the links; two students open their links
(one on a phone), answer and see each attempt recorded; a tampered link is refused; the gradebook
shows both and downloads as CSV. axe-core finds no serious or critical WCAG 2.1 A/AA issue on
either page, and each is shot at 1400×1000, 1280×720 and 390×844 into screenshots/assignments/."""
from __future__ import annotations

import csv
import io
import os
from pathlib import Path

import pytest

from scripts.live_app import CHROMIUM, running_app, wait_until_idle
from solvers import disk_wall
from practice.variants import ASSIGNMENT, variant
from solvers import units

pytestmark = pytest.mark.browser
SHOTS = Path(__file__).resolve().parent.parent / "screenshots" / "assignments"
KEY, SECRET = "instructor-key-0018", "course-secret-for-the-tests-0018"
SIZES = {"laptop": (1400, 1000), "projector": (1280, 720), "phone": (390, 844)}

if not Path(CHROMIUM).exists():
    if os.environ.get("CI"):
        raise RuntimeError(f"CI needs Chromium at {CHROMIUM} (.ci/run installs Debian's chromium)")
    pytest.skip(f"no Chromium at {CHROMIUM}: apt-get install chromium", allow_module_level=True)

playwright = pytest.importorskip("playwright.sync_api")

from tests.test_browser import csp_violations, open_page  # noqa: E402
from tests.test_where_used import serious_violations  # noqa: E402


@pytest.fixture(scope="module")
def course_url(tmp_path_factory):
    data = tmp_path_factory.mktemp("course-data")
    env = {"DL_INSTRUCTOR_KEY": KEY, "DL_COURSE_SECRET": SECRET, "DL_DATA_DIR": str(data), "DL_DATABASE_URL": ""}
    with running_app(env=env) as url:
        yield url


def shoot(page, name: str) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"{name}.png"), full_page=True)


def no_sideways_scroll(page) -> bool:
    return page.evaluate("document.documentElement.scrollWidth <= window.innerWidth + 1")


def at_size(browser, url: str, size: str):
    return open_page(browser, url, *SIZES[size], phone=size == "phone")


def wait_for_text(page, text: str) -> None:
    page.get_by_text(text, exact=False).first.wait_for(timeout=60_000)
    wait_until_idle(page)


def check(page, typed: str) -> None:
    page.get_by_label("Your answer", exact=True).fill(typed)
    page.get_by_role("button", name="Check").click()
    wait_for_text(page, "Recorded: attempt")


def test_an_assignment_in_the_browser(browser, course_url):
    # The instructor: key, new assignment (the disk and the wall, two students), the links as CSV.
    context, page, errors = at_size(browser, f"{course_url}/gradebook", "laptop")
    page.get_by_label("Instructor key", exact=True).fill(KEY)
    page.get_by_label("Instructor key", exact=True).press("Enter")
    wait_for_text(page, "New assignment")
    page.get_by_label("Title", exact=True).fill("Week 6: the disk and the wall")
    page.get_by_label("Roster: one student label per line").fill("s01\ns02")
    page.get_by_role("button", name="Create the assignment and its links").click()
    wait_for_text(page, "created for 2 students")
    with page.expect_download() as download:
        page.get_by_role("button", name="Download the links (CSV)").click()
    links = list(csv.DictReader(io.StringIO(Path(download.value.path()).read_text())))
    assert [row["label"] for row in links] == ["s01", "s02"]
    assert all(row["link"].startswith(f"{course_url}/disk_wall?assignment=") for row in links)

    # Two students: the first on a phone (right), the second on a laptop (a slip).
    for row, size, right in ((links[0], "phone", True), (links[1], "laptop", False)):
        sctx, spage, serrors = at_size(browser, row["link"], size)
        wait_for_text(spage, "Week 6: the disk and the wall")
        value = disk_wall.solve(**variant(disk_wall, "disk_wall", int(row["seed"]), ASSIGNMENT)).answers["v1x"]
        typed = f"{units.to_display(value, 'speed'):.5g}" if right else f"{-units.to_display(value, 'speed'):.5g}"
        check(spage, typed)
        assert ("and it counts" in spage.inner_text("body")) == right
        wait_for_text(spage, "Your attempts")
        assert no_sideways_scroll(spage), size
        if right:
            for name in SIZES:
                spage.set_viewport_size(dict(zip(("width", "height"), SIZES[name])))
                spage.wait_for_timeout(400)
                spage.get_by_text("Recorded: attempt").first.scroll_into_view_if_needed()
                shoot(spage, f"student-{name}")
            spage.set_viewport_size(dict(zip(("width", "height"), SIZES[size])))
        assert serious_violations(spage) == [], size
        assert not serrors
        sctx.close()

    # A tampered link (another variant): refused, in plain words.
    tampered = links[1]["link"].replace(f"seed={links[1]['seed']}", f"seed={links[0]['seed']}")
    tctx, tpage, _ = at_size(browser, tampered, "laptop")
    wait_for_text(tpage, "changed since your instructor issued it")
    assert tpage.get_by_role("button", name="Check").count() == 0
    tctx.close()

    # The gradebook, then its CSV.
    page.reload()  # a new session: the key is asked again
    page.get_by_label("Instructor key", exact=True).fill(KEY)
    page.get_by_label("Instructor key", exact=True).press("Enter")
    wait_until_idle(page)
    page.get_by_role("button", name="Download the gradebook (CSV)").wait_for(timeout=60_000)
    body = page.inner_text("body")
    assert "1 / 7" in body and "0 / 7" in body and "named the slip" in body
    with page.expect_download() as download:
        page.get_by_role("button", name="Download the gradebook (CSV)").click()
    book = list(csv.DictReader(io.StringIO(Path(download.value.path()).read_text())))
    assert [(r["label"], r["score"]) for r in book] == [("s01", "1"), ("s02", "0")]
    assert serious_violations(page) == []
    for name in SIZES:
        page.set_viewport_size(dict(zip(("width", "height"), SIZES[name])))
        page.wait_for_timeout(400)
        assert no_sideways_scroll(page), name
        shoot(page, f"instructor-{name}")
    assert not errors
    context.close()


def test_an_instructor_link_leaves_the_address_bar_on_every_page(browser, course_url):
    """?instructor=KEY opens the instructor's side and is gone from the address bar at once, on
    the home page, every problem and the Assignments page; no page meets a CSP violation."""
    from solvers import registry

    for path in ["", *registry.PROBLEM_IDS, "gradebook"]:
        context, page, errors = open_page(browser, f"{course_url}/{path}?instructor={KEY}")
        page.wait_for_function("() => !location.search.includes('instructor')", timeout=15_000)
        assert KEY not in page.url and KEY not in page.evaluate("document.body.innerText"), path
        assert csp_violations(page) == [] and not errors, path
        if path == "gradebook":
            page.get_by_text("Create the assignment", exact=False).first.wait_for(timeout=30_000)
        context.close()
