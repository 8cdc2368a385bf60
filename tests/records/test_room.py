"""Questions put to a lecture hall, as recorded (room/store.py), on SQLite and PostgreSQL: one answer per
browser session per round, changed in place until the round closes and never counted twice; every
process's answers counted (two engines on one database, as two replicas); a restart loses none; the
CSV names no one and runs no formula; old questions go after the keeping time; a guessed code is
throttled per session, while a hall's typos behind one address hold no one up."""
from __future__ import annotations

import csv
import datetime as dt
import io
import string
from collections import Counter

import pytest
from hypothesis import given, settings, strategies as st
from sqlalchemy import select

from assignments import db
from room import store
from solvers import registry

PARAMS = dict(registry.solver("disk_wall").solve().params)


def asked(database, **kw) -> store.Round:
    return store.ask("disk_wall", "answer:v1x", PARAMS, "si", True, bound=database, **kw)


def test_a_question_opens_under_a_new_code_of_the_projector_s_letters(database):
    codes = {asked(database).code for _ in range(30)}
    assert len(codes) == 30
    for code in codes:
        assert len(code) == store.CODE_LENGTH and set(code) <= set(store.CODE_ALPHABET)
        assert not set(code) & set("0O1IL2Z5S8B6G")  # none a projector's reader confuses
        assert store.latest(code, database).status == "open"


def test_one_answer_per_session_changed_in_place_until_closed(database):
    q = asked(database)
    assert store.answer(q.id, "ann", "right", database) == "counted"
    assert store.answer(q.id, "ann", "right", database) == "same"
    assert store.answer(q.id, "ann", "other", database) == "changed"
    assert store.answer(q.id, "bob", "right", database) == "counted"
    assert store.counts(q.code, database) == {1: Counter(other=1, right=1)}
    store.set_status(q.id, "closed", database)
    assert store.answer(q.id, "cat", "right", database) == "closed"  # late: not counted
    assert store.answer(q.id, "ann", "right", database) == "closed"  # nor changed
    store.set_status(q.id, "revealed", database)
    assert store.answer(q.id, "cat", "right", database) == "revealed"
    assert store.counts(q.code, database) == {1: Counter(other=1, right=1)}
    assert store.answer_of(q.id, "ann", database) == "other" and store.answer_of(q.id, "cat", database) is None


def test_asked_again_the_rounds_are_counted_apart_under_one_code(database):
    q = asked(database)
    store.answer(q.id, "ann", "other", database)
    again = store.ask_again(q.code, database)
    assert (again.code, again.round, again.question) == (q.code, 2, q.question)
    assert store.rounds(q.code, database)[0].status == "closed"  # the first vote ends with the second's start
    assert store.answer(q.id, "bob", "right", database) == "closed"
    assert store.answer(again.id, "ann", "right", database) == "counted"
    assert store.counts(q.code, database) == {1: Counter(other=1), 2: Counter(right=1)}
    assert store.latest(q.code, database).id == again.id


def test_ending_a_question_ends_every_round_of_its_code(database):
    q = asked(database)
    again = store.ask_again(q.code, database)
    store.set_status(again.id, "ended", database)
    assert [r.status for r in store.rounds(q.code, database)] == ["ended", "ended"]
    assert store.answer(again.id, "ann", "right", database) == "ended"


def test_every_process_counts_every_answer_and_a_restart_loses_none(database, tmp_path):
    """Two engines on one database are two replicas (or one process before and after a restart)."""
    q = asked(database)
    url = (f"sqlite:///{tmp_path / 'test.sqlite'}" if database.dialect.name == "sqlite"  # (the fixture's file)
           else database.url.render_as_string(hide_password=False))
    other = db.make_engine(url, create=False)
    try:
        store.answer(q.id, "ann", "right", database)
        store.answer(q.id, "bob", "other", other)
        store.answer(q.id, "ann", "other", other)  # changed on the other replica: still one answer
        assert store.counts(q.code, database) == store.counts(q.code, other) == {1: Counter(other=2)}
    finally:
        other.dispose()
    database.dispose()  # the process goes; its pool with it
    assert store.counts(q.code, database) == {1: Counter(other=2)}


def test_nothing_that_names_a_student_is_kept(database):
    q = asked(database)
    who = store.responder("a-streamlit-session-id-0123")
    store.answer(q.id, who, "right", database)
    with db.session(database) as s:
        row = s.scalar(select(db.RoomResponse))
    assert row.responder == who != "a-streamlit-session-id-0123" and len(who) == 32
    assert {c.name for c in db.RoomResponse.__table__.columns} == {"id", "question_id", "responder", "category", "at"}


def test_the_csv_names_no_one_and_runs_no_formula(database):
    q = asked(database)
    store.answer(q.id, store.responder("s1"), "right", database)
    store.answer(q.id, store.responder("s2"), "=HYPERLINK(\"http://x\")", database)  # (never a category: a control)
    rows = list(csv.reader(io.StringIO(store.responses_csv(q.code, database))))
    assert rows[0] == ["lecture (UTC)", "problem", "question", "round", "answer counted as", "answered at (UTC)"]
    assert sorted(r[4] for r in rows[1:]) == ["'=HYPERLINK(\"http://x\")", "right"]
    assert all(store.responder("s1") not in cell for r in rows for cell in r)


def test_questions_past_the_keeping_time_go_with_their_answers(database, monkeypatch):
    monkeypatch.setenv(store.KEEP_ENV, "30")
    long_ago = store.now() - dt.timedelta(days=31)
    old = asked(database, when=long_ago)
    store.answer(old.id, "ann", "right", database, when=long_ago)
    recent = asked(database, when=store.now() - dt.timedelta(days=29))
    asked(database)  # asking is when the old ones go
    assert store.latest(old.code, database) is None and store.latest(recent.code, database) is not None
    with db.session(database) as s:
        assert s.scalar(select(db.RoomResponse).where(db.RoomResponse.question_id == old.id)) is None


@given(st.text(alphabet=string.ascii_letters + string.digits + " -", max_size=12))
@settings(max_examples=200)
def test_a_typed_code_is_read_in_any_case_and_spacing_or_not_at_all(typed):
    code = store.normal_code(typed)
    squeezed = "".join(typed.split()).replace("-", "").upper()
    assert code == (squeezed if len(squeezed) == store.CODE_LENGTH and set(squeezed) <= set(store.CODE_ALPHABET) else "")


class Clock:
    def __init__(self):
        self.now = 1000.0

    def __call__(self):
        return self.now


@pytest.fixture
def clock(monkeypatch):
    clock = Clock()
    monkeypatch.setattr(store.CODE_THROTTLE, "clock", clock)
    store.CODE_THROTTLE.records.clear()
    yield clock
    store.CODE_THROTTLE.records.clear()


def test_a_guessed_code_waits_then_locks_the_session(database, clock):
    q = asked(database)
    found, why = store.join(q.code.lower(), "guesser", "192.0.2.1", database)
    assert found.code == q.code and why == ""
    tried = 0
    for _ in range(10):
        found, why = store.join("AAAAA", "guesser", "192.0.2.1", database)
        tried += "No question has that code" in why or "locked" in why
        clock.now += 30  # past every wait: each try is looked at
    assert found is None and "locked for 5 minutes" in why and tried == 10
    found, why = store.join(q.code, "guesser", "192.0.2.1", database)  # even the right code, while locked
    assert found is None and "locked" in why
    clock.now += 5 * 60
    assert store.join(q.code, "guesser", "192.0.2.1", database)[0].code == q.code


def test_a_hall_s_typos_behind_one_address_hold_no_one_up(database, clock):
    q = asked(database)
    for n in range(39):  # 39 students behind one NAT each mistype at once: each typo is looked at, none waits
        found, why = store.join("AAAAA", f"student-{n}", "192.0.2.7", database)
        assert found is None and why.startswith("No question has that code")
    clock.now += 1  # a second later (their own session's wait), each types it right
    for n in range(39):
        assert store.join(q.code, f"student-{n}", "192.0.2.7", database)[0] is not None
    # a guesser behind the same address, without a right code between: locked after 40 in a row
    for n in range(40):
        store.join("AAAAA", f"guess-{n}", "192.0.2.8", database)
    found, why = store.join(q.code, "late-student", "192.0.2.8", database)
    assert found is None and "locked for 1 minute" in why
