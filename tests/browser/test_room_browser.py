"""Ask the room, end to end in Chromium: an instructor's projector at 1280×720 (and 1024×768) asks from the
Lecture view; its code and QR code stand in the first screen, large, and the QR code read back from the
screen opens the question; phones at 390×844 answer, and the projector's count follows within 2 s; the
phone's page passes axe-core; the reveal reaches the phones. Screenshots of the join screen, a phone and
the histogram go to screenshots/room/ (opened and looked at when the feature changes)."""
from __future__ import annotations

import io
import time
from pathlib import Path

import pytest

from scripts.live_app import wait_until_idle
from tests.browser.test_browser import kept_context, open_in, watched_context
from tests.conftest import INSTRUCTOR_KEY

pytestmark = pytest.mark.served
zxingcpp = pytest.importorskip("zxingcpp")
SHOTS = Path(__file__).resolve().parents[2] / "screenshots" / "room"
COUNT = "[data-testid='stMain'] p:has-text(' answer')"


def shot(page, name: str) -> None:
    SHOTS.mkdir(parents=True, exist_ok=True)
    page.screenshot(path=str(SHOTS / f"{name}.png"))


def in_first_screen(page, locator) -> bool:
    box, size = locator.bounding_box(), page.viewport_size
    return box is not None and box["y"] >= 0 and box["y"] + box["height"] <= size["height"] and box["x"] + box["width"] <= size["width"]


def own_phone(browser, opened: list):
    """A phone of its own (its own cookies: a browser the room counts once), 390×844."""
    context = watched_context(browser, viewport={"width": 390, "height": 844}, is_mobile=True, has_touch=True,
                              device_scale_factor=2)
    opened.append(context)
    return context


def answers_shown(page) -> int:
    """The projector's count ("3 answers · Answers are open")."""
    return page.evaluate("() => parseInt([...document.querySelectorAll('.st-key-dl_room p')]"
                         ".find(p => /^\\d+ answers? /.test(p.innerText)).innerText)")


def test_the_room_answers_on_phones_and_the_projector_counts_within_two_seconds(browser, app_url):
    from PIL import Image
    from tests.browser.test_where_used import serious_violations

    lease = kept_context(browser, 1280, 720)
    phones_opened = []
    try:
        projector, errors = open_in(lease, f"{app_url}/disk_wall?lecture=1&instructor={INSTRUCTOR_KEY}")
        projector.get_by_test_id("stExpandSidebarButton").click()
        ask = projector.get_by_role("button", name="Ask the room")
        ask.wait_for()
        ask.click()
        code_shown = projector.locator("p.dl-room-code")
        code_shown.wait_for()
        projector.get_by_test_id("stSidebarCollapseButton").click()
        wait_until_idle(projector)
        code = code_shown.inner_text().strip()
        qr = projector.locator("img[alt^='A QR code']")
        qr.wait_for()
        for width, height in ((1280, 720), (1024, 768)):  # a projector's first screen, the back row's reach
            projector.set_viewport_size({"width": width, "height": height})
            projector.wait_for_timeout(300)
            assert in_first_screen(projector, code_shown) and in_first_screen(projector, qr), (width, height)
            assert float(code_shown.evaluate("e => parseFloat(getComputedStyle(e).fontSize)")) >= 56
            assert qr.bounding_box()["width"] >= 200
            shot(projector, f"join-{width}x{height}")
        projector.set_viewport_size({"width": 1280, "height": 720})
        read = zxingcpp.read_barcodes(Image.open(io.BytesIO(qr.screenshot())))
        link = read[0].text if read else ""
        assert link == f"{app_url}/room?c={code}"  # what the phone's camera reads, from the screen

        answered = []
        for n, text in enumerate(("0.8333", "1.25", "(R*omega + 2*V*sin(theta))/3")):
            phone, phone_errors = open_in(own_phone(browser, phones_opened), link)  # each its own browser
            if n == 0:
                assert serious_violations(phone) == []
            phone.get_by_label("Your answer").fill(text)
            phone.get_by_role("button", name="Send my answer").click()
            phone.get_by_text("Your answer is in").wait_for()
            sent = time.monotonic()
            projector.wait_for_function(
                "n => [...document.querySelectorAll('.st-key-dl_room p')].some(p => p.innerText.startsWith(n + ' answer'))",
                arg=n + 1, timeout=5000)
            answered.append((phone, time.monotonic() - sent))
            assert phone_errors == []
        assert max(lag for _, lag in answered) <= 2.0, [lag for _, lag in answered]
        again, _ = open_in(answered[0][0].context, link)  # the same phone, a new tab (or a reload): one answer still
        again.get_by_text("Your answer is in").wait_for()
        assert answers_shown(projector) == 3
        shot(answered[0][0], "phone-answered")
        shot(projector, "histogram")
        with projector.expect_download() as download:
            projector.get_by_role("button", name="CSV").click()
        rows = Path(download.value.path()).read_text().splitlines()
        assert rows[0].startswith("lecture (UTC),problem,question,round,answer counted as") and len(rows) == 4
        assert sorted(r.split(",")[4] for r in rows[1:]) == ["other", "right", "right"]

        projector.get_by_role("button", name="Close answers").click()
        projector.get_by_role("button", name="Reveal").click()
        projector.get_by_text("The answer: Velocity after, along the wall").wait_for()
        phone = answered[1][0]
        phone.get_by_text("The answer: Velocity after").wait_for(timeout=6000)  # its watch: every 2.5 s
        assert phone.get_by_text("Yours was not right").count() == 1
        shot(phone, "phone-revealed")
        assert errors == []
    finally:
        for context in phones_opened:
            context.close()
        lease.close()
