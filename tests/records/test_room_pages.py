"""A question put to the room, as the instructor's projector and the students' phones meet it (AppTest, a
SQLite file per test): asked from the Lecture view with the key only; joined by the code's link in any
case; answered, changed, refused once closed; the motion kept off the projector until the reveal; asked
again, two votes; the phone given no answer before the reveal; hostile text, forged codes, a flood of
sends and a database that is down each told in words, never a traceback."""
from __future__ import annotations

import time
from pathlib import Path

import pytest
from streamlit.testing.v1 import AppTest

from assignments import db
from room import store
from solvers import units
from solvers.catalog import BY_ID
from tests.conftest import INSTRUCTOR_KEY, reset_database_caches

ROOT = Path(__file__).resolve().parents[2]
KEY = INSTRUCTOR_KEY
PID = "disk_wall"


@pytest.fixture
def course(course, monkeypatch):
    """The course (tests/conftest.py), with the room's pace and its code throttle fresh."""
    monkeypatch.setattr("ui.room.SEND_EVERY", 0.0)  # (a test's sends come faster than a thumb's)
    store.CODE_THROTTLE.records.clear()
    yield
    store.CODE_THROTTLE.records.clear()


def projector(key: str = KEY) -> AppTest:
    at = AppTest.from_file(str(ROOT / "app_pages" / f"{PID}.py"), default_timeout=60)
    at.query_params.update({"lecture": "1", "instructor": key})
    return at.run()


def ask(at: AppTest, question: str, hide: bool = True) -> str:
    box = at.sidebar.selectbox(key=f"{PID}__room_question")
    box.select_index(box.options.index(question))
    at.sidebar.toggle(key=f"{PID}__room_hide").set_value(hide)
    at.sidebar.button(key=f"{PID}__room_ask").click().run()
    assert not at.exception
    return at.session_state[f"{PID}__room_code"]


def phone(code: str) -> AppTest:
    at = AppTest.from_file(str(ROOT / "app_pages" / "lecture_question.py"), default_timeout=60)
    at.query_params.update({"c": code})
    return at.run()


def send(at: AppTest, text: str) -> AppTest:
    box = next(w for w in at.text_input if w.key.startswith("room__typed_"))
    box.input(text)
    return next(b for b in at.button if b.key.startswith("room__send_")).click().run()


def count_said(at: AppTest) -> str:
    return next(m.value for m in at.markdown if " answer" in m.value and "·" in m.value)


def everything_shown(at: AppTest) -> str:
    return "\n".join(str(getattr(e, "value", "")) for e in at.main)


V1X = "Velocity after, along the wall"


def test_asked_answered_closed_revealed_asked_again(course):
    at = projector()
    code = ask(at, V1X)
    assert "0 answers" in count_said(at) and any(code in m.value for m in at.markdown)
    assert any(m.value.startswith("![A QR code that opens /room?c=") for m in at.markdown)
    stage_controls = [s for s in at.slider if s.key.startswith(PID)]
    assert stage_controls == []  # the motion (and its controls) off the projector until the reveal

    right = BY_ID[PID].solver.solve().answers["v1x"]
    ann, bob = phone(code.lower()), phone(f" {code[:2]}-{code[2:]} ")  # a code typed in any case and spacing
    assert not ann.exception and not bob.exception
    before = everything_shown(ann)
    assert f"{right:.4g}" not in before and units.format_quantity(right, BY_ID[PID].solver.ANSWERS[0].dimension, "si") not in before
    send(ann, f"{right:.4g}")
    assert ann.success and "Your answer is in" in ann.success[0].value
    send(bob, "1.25")
    send(bob, "2 +* 3")  # a typo: explained, and bob's answer stays what it was
    assert "Nothing was counted" in bob.warning[0].value
    at.run()
    assert "2 answers" in count_said(at)

    at.button(key="room__close").click().run()
    cat = phone(code)
    assert not any(w.key.startswith("room__typed_") for w in cat.text_input)  # closed: no box
    assert any("closed the answers" in i.value for i in cat.info)
    send(ann, "1.25")  # the page she had open, sent after the close
    assert "was not counted" in ann.warning[0].value
    at.run()
    assert "2 answers" in count_said(at)

    at.button(key="room__reveal").click().run()
    assert f"{right:.4g}" in at.success[0].value
    assert [s for s in at.slider if s.key.startswith(PID)]  # the stage is back, its controls with it
    ann.run()
    assert f"{right:.4g}" in ann.success[0].value and any("You had it right" in m.value for m in ann.markdown)
    bob.run()
    assert any("Yours was not right" in m.value for m in bob.markdown)

    at.button(key="room__again").click().run()
    assert "0 answers" in count_said(at)
    bob.run()
    send(bob, f"{right:.4g}")
    assert store.counts(code) == {1: {"right": 1, "other": 1}, 2: {"right": 1}}
    at.button(key="room__end").click().run()
    assert f"{PID}__room_code" not in at.session_state and not at.exception
    ann.run()
    assert any("has ended" in i.value for i in ann.info)


def test_a_regime_question_is_a_choice_and_asked_without_hiding_the_stage_stays(course):
    at = projector()
    code = ask(at, "During the impact, does the disk's rim stick to the wall or slide along it?", hide=False)
    assert [s for s in at.slider if s.key.startswith(PID)]  # asked without hiding: the stage stays
    ann = phone(code)
    ann.radio[0].set_value("slip")
    next(b for b in ann.button if b.key.startswith("room__send_")).click().run()
    assert "Your answer is in" in ann.success[0].value
    assert store.counts(code) == {1: {"slip": 1}}


def test_only_the_instructor_asks(course):
    at = projector(key="not-the-instructor-key")
    assert not any(b.key == f"{PID}__room_ask" for b in at.sidebar.button)


@pytest.mark.parametrize("forged", ["<script>alert(1)</script>", "AAAAA", "' OR 1=1 --", "x" * 5000, "%00"])
def test_a_forged_or_guessed_code_is_told_and_tried_no_faster(course, forged):
    at = phone(forged)
    assert not at.exception and "No question has that code" in at.error[0].value
    assert all("<script>" not in m.value for m in at.markdown)
    at.text_input(key="room__code_typed").input("BBBBB")
    at.button(key="room__join_button").click().run()
    assert "Too soon after a wrong code" in at.error[0].value  # the session's wait, before a second look


def test_hostile_text_in_the_answer_box_is_explained_never_rendered(course):
    code = ask(projector(), V1X)
    ann = phone(code)
    for text in ("<img src=x onerror=alert(1)>", "[link](javascript:alert(1))", "$\\href{x}{y}$", "__import__('os')", "9" * 100_000):
        send(ann, text)
        assert not ann.exception and ann.warning and "Nothing was counted" in ann.warning[0].value
        assert all("<img" not in m.value and "](javascript" not in m.value for m in ann.markdown)
    assert store.counts(code) == {}


def test_a_flood_of_sends_is_slowed_and_counted_once(course, monkeypatch):
    monkeypatch.setattr("ui.room.SEND_EVERY", 1.0)
    code = ask(projector(), V1X)
    ann = phone(code)
    send(ann, "1.25")
    send(ann, "1.5")
    assert "Sent a moment ago" in ann.warning[0].value
    time.sleep(1.05)
    send(ann, f"{BY_ID[PID].solver.solve().answers['v1x']:.4g}")
    assert "changed" in ann.success[0].value
    assert store.counts(code) == {1: {"right": 1}}


def test_with_the_database_down_each_side_says_so(course, monkeypatch):
    code = ask(projector(), V1X)
    monkeypatch.setenv(db.URL_ENV, "sqlite:////dev/null/down/course.sqlite")
    reset_database_caches()
    ann = phone(code)
    assert not ann.exception and "cannot be reached" in ann.error[0].value
    at = projector()
    assert not at.exception
    at.sidebar.button(key=f"{PID}__room_ask").click().run()
    assert not at.exception and any("cannot be reached" in e.value for e in at.sidebar.error)


def test_a_question_the_stage_has_moved_past_is_said_not_asked(course):
    """The sidebar's list is drawn on the page's run; a lesson control reruns the stage alone. An answer asked
    after the cart was driven past its wheelie (the model refuses: no answers) is said, and nothing asked."""
    at = AppTest.from_file(str(ROOT / "app_pages" / "driven_cart.py"), default_timeout=60)
    at.query_params.update({"lecture": "1", "instructor": KEY})
    at.run()
    at.sidebar.selectbox(key="driven_cart__room_question").select_index(0)  # the acceleration
    at.session_state["driven_cart__si"] = {**BY_ID["driven_cart"].solver.solve().params, "drive": "rear", "mu": 3.0}
    at.sidebar.button(key="driven_cart__room_ask").click().run()
    assert not at.exception and "driven_cart__room_code" not in at.session_state
    assert any("cannot be asked at the stage's parameters now" in e.value for e in at.sidebar.error)
