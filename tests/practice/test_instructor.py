"""The instructor key's throttle (practice/instructor.py): a guesser gets at most 10 tries in a
minute from one client, however many sessions it opens; a lockout is said in plain words; the right
key works after it; nothing typed reaches the log."""
from __future__ import annotations

import logging

import pytest
from hypothesis import given, settings, strategies as st

from practice import instructor
from practice.instructor import Throttle

KEY = "the-right-key-for-these-tests"


class Clock:
    def __init__(self):
        self.now = 1000.0

    def __call__(self):
        return self.now


@pytest.fixture(autouse=True)
def key(monkeypatch):
    monkeypatch.setenv(instructor.KEY_ENV, KEY)


def guesses_in(throttle: Throttle, clock: Clock, seconds: float, sessions: int, address="203.0.113.7") -> int:
    """A guesser trying as fast as it is let, from ``sessions`` sessions in turn: the keys looked at."""
    looked_at, end, turn = 0, clock.now + seconds, 0
    while clock.now < end:
        verdict = throttle.try_key(f"guess-{looked_at}", f"session-{turn % sessions}", address)
        looked_at += verdict.checked
        turn += 1
        clock.now += 0.01  # a hundred tries a second
    return looked_at


@pytest.mark.parametrize("sessions", [1, 2, 32])
def test_at_most_ten_guesses_a_minute_from_one_client(sessions):
    clock = Clock()
    throttle = Throttle(clock)
    assert guesses_in(throttle, clock, 60, sessions) <= 10
    # ... and in every later minute of an hour, at most one more each
    for _ in range(59):
        assert guesses_in(throttle, clock, 60, sessions) <= 1


def test_one_session_is_locked_after_five_then_told_in_minutes():
    clock = Clock()
    throttle = Throttle(clock)
    verdicts = []
    for i in range(5):
        clock.now += verdicts[-1].wait if verdicts else 0
        verdicts.append(throttle.try_key(f"wrong-{i}", "s", "198.51.100.1"))
    assert [v.wait for v in verdicts[:4]] == [1, 2, 4, 8]  # the delay doubles
    assert verdicts[4].locked and verdicts[4].wait == 300
    assert "locked for 5 minutes" in verdicts[4].message()
    # The right key during the lockout is refused without being looked at...
    refused = throttle.try_key(KEY, "s", "198.51.100.1")
    assert not refused.ok and not refused.checked and refused.locked
    # ... and works once the lockout is over.
    clock.now += 300
    assert throttle.try_key(KEY, "s", "198.51.100.1").ok


def test_other_clients_are_not_held_back():
    clock = Clock()
    throttle = Throttle(clock)
    guesses_in(throttle, clock, 60, 4, address="203.0.113.7")
    assert throttle.try_key(KEY, "instructor-session", "192.0.2.50").ok


def test_a_try_too_soon_is_refused_without_looking():
    clock = Clock()
    throttle = Throttle(clock)
    assert not throttle.try_key("wrong", "s", "a").ok
    clock.now += 0.5
    early = throttle.try_key(KEY, "s", "a")
    assert not early.ok and not early.checked and "wait 0 s" not in early.message()
    clock.now += 0.5
    assert throttle.try_key(KEY, "s", "a").ok


def test_quiet_for_an_hour_starts_the_count_again():
    clock = Clock()
    throttle = Throttle(clock)
    for _ in range(3):
        clock.now += throttle.try_key("wrong", "s", "a").wait
    clock.now += 3601
    assert throttle.try_key("wrong", "s", "a").wait == 1


def test_memory_is_bounded_and_a_full_table_still_throttles(monkeypatch):
    monkeypatch.setattr(instructor, "MAX_TRACKED", 50)
    clock = Clock()
    throttle = Throttle(clock)
    for i in range(200):  # many sessions and addresses fill the table
        throttle.try_key("wrong", f"s{i}", f"a{i}")
        clock.now += 0.001
    assert len(throttle.records) <= 50
    # ... and one client guessing as fast as it may still gets at most ten keys looked at in a minute
    assert guesses_in(throttle, clock, 60, sessions=32, address="203.0.113.99") <= 10


@settings(max_examples=50)
@given(st.text(max_size=40))
def test_a_wrong_key_is_logged_without_what_was_typed(text):
    typed = "zq#" + text  # a mark that nothing else in the log line contains
    clock = Clock()
    records = []
    handler = logging.Handler()
    handler.emit = records.append
    instructor.log.addHandler(handler)
    try:
        verdict = Throttle(clock).try_key(typed, "session-1234567890", "192.0.2.9")
    finally:
        instructor.log.removeHandler(handler)
    assert not verdict.ok
    assert len(records) == 1
    logged = records[0].getMessage()
    assert "192.0.2.9" in logged and "wrong instructor key" in logged
    assert "zq#" not in logged
