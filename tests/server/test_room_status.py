"""The route a phone's watch asks (edge/room_status.py): a joined phone's token gets the question's round
and status, and sees them change with the instructor's step; a guessed code, a forged token, a code gone,
another method and a flood from one address each get their status, never a page run; the database is
read once a second per code however many phones ask."""
from __future__ import annotations

import pytest
from starlette.responses import PlainTextResponse
from starlette.testclient import TestClient

from assignments import db, migrate
from edge import room_status
from edge.room_status import RoomStatus
from room import store
from solvers import registry

PARAMS = dict(registry.solver("disk_wall").solve().params)


@pytest.fixture
def hall(monkeypatch, tmp_path):
    monkeypatch.setenv(db.URL_ENV, f"sqlite:///{tmp_path / 'room.sqlite'}")
    db.engine.cache_clear()
    migrate.upgrade()
    store._STATUS.clear()
    yield TestClient(RoomStatus(PlainTextResponse("streamlit")))
    store._STATUS.clear()
    db.engine.cache_clear()


def asked() -> store.Round:
    return store.ask("disk_wall", "answer:v1x", PARAMS, "si", True)


def test_a_joined_phone_sees_the_question_s_steps(hall, monkeypatch):
    q = asked()
    url = f"/room-status?c={q.code}&t={store.status_token(q.code)}"
    answer = hall.get(url)
    assert answer.status_code == 200 and answer.json() == {"v": f"{q.id}:open"}
    assert answer.headers["cache-control"] == "no-store"
    store.set_status(q.id, "closed")
    monkeypatch.setattr(store, "STATUS_FRESH", 0.0)  # (a second later)
    assert hall.get(url).json() == {"v": f"{q.id}:closed"}
    again = store.ask_again(q.code)
    assert hall.get(url).json() == {"v": f"{again.id}:open"}
    assert hall.get(url.replace(q.code, q.code.lower())).status_code == 200  # (the code as typed)


def test_the_database_is_read_once_per_code_while_fresh(hall, monkeypatch):
    q = asked()
    monkeypatch.setattr(store, "STATUS_FRESH", 60.0)  # (however slowly a loaded machine asks fifty times)
    reads = []
    real = store.latest
    monkeypatch.setattr(store, "latest", lambda *a, **k: reads.append(1) or real(*a, **k))
    for _ in range(50):
        assert hall.get(f"/room-status?c={q.code}&t={store.status_token(q.code)}").status_code == 200
    assert len(reads) == 1


@pytest.mark.parametrize("query", ["c=AAAAA&t=0", "c={code}&t=forged", "c={code}", "t={token}", "c=<script>&t={token}",
                                   "c={code}&t={token}" + "x" * 5000])
def test_a_guessed_code_or_a_forged_token_is_refused(hall, query):
    q = asked()
    answer = hall.get("/room-status?" + query.format(code=q.code, token=store.status_token(q.code)))
    assert answer.status_code == 403 and answer.json() == {"error": "not a joined code"}


def test_a_code_gone_another_method_and_other_paths(hall, monkeypatch):
    gone = "ACDEF"
    assert hall.get(f"/room-status?c={gone}&t={store.status_token(gone)}").status_code == 404
    assert hall.post(f"/room-status?c={gone}&t={store.status_token(gone)}").status_code == 405
    assert hall.get("/room").text == "streamlit" and hall.get("/room-status/x").text == "streamlit"


def test_a_flood_from_one_address_is_told_to_wait(hall, monkeypatch):
    monkeypatch.setattr(room_status, "STATUS_RATE", 1.0)
    monkeypatch.setattr(room_status, "STATUS_BURST", 5)
    flooded = TestClient(RoomStatus(PlainTextResponse("streamlit")))
    q = asked()
    url = f"/room-status?c={q.code}&t={store.status_token(q.code)}"
    said = [flooded.get(url) for _ in range(8)]
    assert [a.status_code for a in said] == [200] * 5 + [429] * 3
    assert said[-1].headers["retry-after"] == "3"


def test_a_token_holds_for_its_code_only_and_follows_the_course_secret(monkeypatch):
    assert store.status_token_valid("ACDEF", store.status_token("ACDEF"))
    assert not store.status_token_valid("ACDEH", store.status_token("ACDEF"))
    before = store.status_token("ACDEF")
    monkeypatch.setenv("DL_COURSE_SECRET", "a-course-secret-of-32-characters")
    assert store.status_token("ACDEF") != before  # replicas with one course secret accept each other's tokens
