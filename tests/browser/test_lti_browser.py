"""Inside an LMS, in Chromium, end to end: ``lti1p3platform``'s platform (tests/lti_platform.py) on
``localhost`` embeds the app, served by serve.py on ``127.0.0.1`` (another site: the tool's frame
is third-party, and the flow uses no cookie). The instructor adds an assignment through deep
linking (the LMS's "add external tool" dialog): the LMS receives a resource link with its line
item. A learner launches it, lands on their own variant, answers right; their score reaches the
platform's AGS endpoint by itself. The instructor launches and sees that course's gradebook, with
the grade sent, and no key asked, and reads the course roster from the LMS (NRPS): who has not started; then, in the same session, Handouts
gives that course's answer keys with no key (SQLite's run). The journey runs on SQLite and on
PostgreSQL, in one Chromium; each frame's page is shot (SQLite's run) into screenshots/lti/."""
from __future__ import annotations

import json
import time
from pathlib import Path

import pytest
from sqlalchemy import text

from assignments import db, records, signing
from lti import launch as lti
from practice.variants import ASSIGNMENT, variant
from scripts.live_app import free_port, launch_browser, start_app, wait_healthy, wait_until_idle
from solvers import disk_wall, units
from tests.browser.test_browser import watched_context
from tests.lti_platform import INSTRUCTOR, ISSUER, LEARNER, LmsEmulator

pytestmark = pytest.mark.browser
SHOTS = Path(__file__).resolve().parents[2] / "screenshots" / "lti"
KEY, SECRET = "instructor-key-0030", "course-secret-for-the-lti-tests-30"

sync_api = pytest.importorskip("playwright.sync_api")


def in_lms(page, lms, start: str):
    """Open the LMS's course page with the tool's frame started at ``start``; the frame."""
    page.goto(f"{lms.url}/course?start={start.replace('&', '%26').replace('?', '%3F')}")
    frame = page.frame_locator("iframe[name=tool]")
    return frame, page.frame(name="tool")


SIZES = {"laptop": (1400, 1000), "projector": (1280, 720), "phone": (390, 844)}


def shoot(page, name: str, tool=None, shots: bool = True) -> None:
    """The LMS page with the tool's frame, at each size (the frame's page idle again after each)."""
    if not shots:
        return
    SHOTS.mkdir(parents=True, exist_ok=True)
    for size, (width, height) in SIZES.items():
        page.set_viewport_size({"width": width, "height": height})
        if tool is not None:
            wait_until_idle(tool)
        page.screenshot(path=str(SHOTS / f"{name}-{size}.png"))
    page.set_viewport_size({"width": 1400, "height": 1000})


@pytest.fixture(scope="module")
def browser():
    """One Chromium for both databases' journeys (its start is not what either tests)."""
    with sync_api.sync_playwright() as p:
        started = launch_browser(p)
        yield started
        started.close()


def test_deep_link_learner_launch_and_grade_passback_in_an_lms_frame(browser, database, tmp_path, monkeypatch):
    """The same journey on SQLite and on PostgreSQL (``database``: a fresh, migrated database on
    each); the app's own process records and sends, so the backend is the one it was started on."""
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)  # this process works out the learner's right answer
    sqlite = database.dialect.name == "sqlite"  # SQLite: the app's own file in its data directory, as shipped
    port = free_port()
    tool_url = f"http://127.0.0.1:{port}"
    with LmsEmulator(tool_url, host="localhost") as lms:
        platforms_file = tmp_path / "platforms.json"
        platforms_file.write_text(json.dumps([lms.registration_entry()]))
        env = {"DL_INSTRUCTOR_KEY": KEY, "DL_COURSE_SECRET": SECRET, "DL_DATA_DIR": str(tmp_path / "data"),
               "DL_DATABASE_URL": "" if sqlite else database.url.render_as_string(hide_password=False),
               "DL_LTI_PLATFORMS": str(platforms_file), "DL_PUBLIC_URL": tool_url}
        proc = start_app(port, env=env)
        try:
            wait_healthy(tool_url, proc=proc)
            context = watched_context(browser, viewport={"width": 1400, "height": 1000})
            page = context.new_page()
            errors: list[str] = []
            page.on("pageerror", lambda exc: errors.append(str(exc)))
            run_journey(page, lms, shots=sqlite)  # the pages look alike on both
            assert not errors, errors
            context.close()
        finally:
            proc.terminate()
            proc.wait(10)
        kept = db.make_engine(f"sqlite:///{tmp_path / 'data' / 'dynamics-lab.sqlite'}") if sqlite else database
        with kept.connect() as c:  # what the journey left is in this backend, not elsewhere
            assert c.execute(text("SELECT count(*) FROM lti_score WHERE status = 'sent'")).scalar() == 1
            assert c.execute(text("SELECT count(*) FROM attempt")).scalar() == 1


def run_journey(page, lms, shots: bool = True) -> None:
    # The instructor adds the activity from the LMS's dialog (deep linking).
    frame, _ = in_lms(page, lms, lms.login_url("teacher-1", INSTRUCTOR, deep_link=True))
    frame.get_by_label("Problem").select_option("disk_wall")
    frame.get_by_role("button", name="Next").click()
    frame.get_by_label("Title").fill("Week 6: the disk and the wall")
    boxes = frame.locator("input[name=answer]")
    for i in range(boxes.count()):  # only the velocity along the wall counts
        if boxes.nth(i).get_attribute("value") != "v1x":
            boxes.nth(i).uncheck()
    frame.get_by_label("Attempts per answer").fill("3")
    shoot(page, "deep-link-picker", shots=shots)
    frame.get_by_role("button", name="Add to the course").click()
    frame.get_by_text("The LMS received: Week 6: the disk and the wall").wait_for(timeout=30_000)
    (item,) = lms.deep_links[-1]
    assert item["lineItem"]["label"] == "Week 6: the disk and the wall"
    aid = int(item["custom"]["dl_assignment"].split(".")[0])

    # A learner opens it: their own variant, inside the LMS's frame.
    frame, tool = in_lms(page, lms, lms.login_url("learner-42", LEARNER, resource_link="rl-week6",
                                                  custom=item["custom"]))
    frame.get_by_text("Graded assignment: Week 6").wait_for(timeout=60_000)
    wait_until_idle(tool)
    assert "lti=" not in tool.url  # the hand-off has left the address
    label = lti.label_of(ISSUER, "learner-42")
    seed = records.student_seed(aid, label)
    v1x = disk_wall.solve(**variant(disk_wall, "disk_wall", seed, ASSIGNMENT)).answers["v1x"]
    frame.get_by_label("Your answer", exact=True).fill(f"{units.to_display(v1x, 'speed'):.5g}")
    frame.get_by_role("button", name="Check", exact=True).click()
    frame.get_by_text("Recorded: attempt 1 of 3").first.wait_for(timeout=60_000)
    wait_until_idle(tool)
    shoot(page, "learner-in-lms", tool, shots)

    # The score reaches the LMS by itself (the app's sender thread, the platform's AGS endpoint).
    deadline = time.monotonic() + 30
    while not lms.scores and time.monotonic() < deadline:
        time.sleep(0.2)
    (score,) = lms.scores
    assert (score["userId"], score["scoreGiven"], score["scoreMaximum"]) == ("learner-42", 1, 1)
    assert (score["lineitem"], score["activityProgress"], score["gradingProgress"]) == ("rl-week6", "Completed",
                                                                                       "FullyGraded")

    # The instructor opens the link: that course's gradebook, no key, the grade said sent.
    frame, tool = in_lms(page, lms, lms.login_url("teacher-1", INSTRUCTOR, resource_link="rl-week6"))
    frame.get_by_text("Grades sent to the LMS").wait_for(timeout=60_000)
    wait_until_idle(tool)
    body = frame.locator("[data-testid='stMain']").inner_text()
    assert "1 sent · 0 waiting · 0 not accepted" in body and "Instructor key" not in body

    # The course roster from the LMS (NRPS): who has not started.
    lms.members[:] = [{"user_id": "learner-42", "name": "Ann Ito", "roles": LEARNER},
                      {"user_id": "learner-43", "name": "Bea Roth", "roles": LEARNER}]
    frame.get_by_role("button", name="Read the roster from the LMS").click()
    frame.get_by_text("2 students in the course; 1 has not started.").wait_for(timeout=60_000)
    wait_until_idle(tool)
    roster = frame.locator("[data-testid='stMain']").inner_text()
    assert roster.index("Bea Roth") < roster.index("Ann Ito")  # not started first
    shoot(page, "instructor-gradebook-in-lms", tool, shots)
    if not shots:
        return  # the pages below read what the database gave above, the same on both

    # The same session, another page of the app: that course's answer keys, no key to type.
    frame.locator("[data-testid='stSidebarNav']").get_by_text("Handouts").click()
    frame.get_by_text("From your course site: the handouts").wait_for(timeout=60_000)
    frame.get_by_text("Answer key", exact=True).click()
    frame.get_by_text(f"Student {label}").first.wait_for(timeout=60_000)
    wait_until_idle(tool)
    sheets = frame.locator("[data-testid='stMain']").inner_text()
    assert "Instructor key" not in sheets and "A range of variants" not in sheets
    shoot(page, "instructor-handouts-in-lms", tool, shots)
