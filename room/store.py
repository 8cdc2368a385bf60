"""The records of questions put to a lecture hall: each round of a question, and one answer per browser
session per round (changed in place until the round closes), in the app's database (assignments/db.py:
SQLite by default, PostgreSQL where several processes share one), so every process counts every answer
and a restart loses none.

Nothing that names a student is kept: not a name, an address, a device, or the text typed; only what an
answer counts as (right, a named slip, other, or a choice) and when, under a hash of the session's random
id. Questions are kept ``KEEP_DAYS`` days (``DL_ROOM_KEEP_DAYS``, 365 by default), then deleted with their
answers. Database failures become ``RecordingUnavailable`` (assignments/records.py), said on the page."""
from __future__ import annotations

import datetime as dt
import hashlib
import hmac
import json
import os
import secrets
import threading
import time
from collections import Counter
from dataclasses import dataclass

from sqlalchemy import delete, func, select
from sqlalchemy.engine import Engine

from assignments import db
from assignments.records import RecordingUnavailable, guarded, now, safe_csv
from practice.instructor import Rule, Throttle

CODE_ALPHABET = "ACDEFHJKMNPRTUVWXY3479"  # no 0/O, 1/I/L, 2/Z, 5/S, 8/B, 6/G: read off a projector
CODE_LENGTH = 5  # 22⁵ ≈ 5 million codes; a guess is throttled (ui/room.py)
STATUSES = ("open", "closed", "revealed", "ended")
KEEP_ENV, KEEP_DAYS = "DL_ROOM_KEEP_DAYS", 365
CATEGORY_LENGTH = 200


@dataclass(frozen=True)
class Round:
    id: int
    code: str
    round: int
    problem: str
    question: str
    params: dict
    system: str
    hide_motion: bool
    status: str
    opened: dt.datetime


def _round(row: db.RoomQuestion) -> Round:
    return Round(row.id, row.code, row.round, row.problem, row.question, json.loads(row.params), row.system,
                 row.hide_motion, row.status, row.opened)


def normal_code(typed: str) -> str:
    """A code as typed (any case, spaces or a dash in it) as it is stored; "" if it cannot be one."""
    code = "".join(typed.split()).replace("-", "").upper()[: CODE_LENGTH + 1]
    return code if len(code) == CODE_LENGTH and set(code) <= set(CODE_ALPHABET) else ""


def responder(session_id: str) -> str:
    """What the records keep of a browser session: a hash of its random token (never the token itself)."""
    return hashlib.sha256(f"room|{session_id}".encode()).hexdigest()[:32]


def keep_days() -> int:
    try:
        return max(1, int(os.environ.get(KEEP_ENV, KEEP_DAYS)))
    except ValueError:
        return KEEP_DAYS


# A code typed wrong: from one browser session, waits of 1, 2, 4, 8 s, and the tenth wrong code in a row
# locks joining for 5 minutes; from one address (a whole hall behind one NAT), no wait (a typo must not
# hold the room up) until 40 wrong codes in a row, then a minute's lock. A right code resets both.
CODE_THROTTLE = Throttle(session=Rule(waits=(1, 2, 4, 8), lock_after=10, lockout=5 * 60),
                         address=Rule(waits=(0,), lock_after=40, lockout=60), what="room code")


def join(typed: str, session: str, address: str, bound: Engine | None = None) -> tuple[Round | None, str]:
    """The question a typed code opens, or None and why not (a code never given, or too many wrong ones)."""
    found: list[Round | None] = []

    def known() -> bool:
        found.append(latest(normal_code(typed), bound))
        return found[0] is not None

    verdict = CODE_THROTTLE.attempt(known, session, address)
    if verdict.ok:
        return found[0], ""
    if verdict.locked:
        minutes = max(1, round(verdict.wait / 60))
        return None, f"Too many wrong codes: joining is locked for {minutes} minute{'s' * (minutes != 1)}."
    if not verdict.checked:
        return None, f"Too soon after a wrong code: wait {max(1, round(verdict.wait))} s, then try again."
    return None, ("No question has that code. Check it against the screen: five letters and digits "
                  f"from {CODE_ALPHABET}.")


@guarded
def ask(problem: str, question: str, params: dict, system: str, hide_motion: bool, course: str = "",
        bound: Engine | None = None, when: dt.datetime | None = None) -> Round:
    """A new question, open, under a code no question has had; questions past the keeping time go."""
    when = when or now()
    with db.session(bound) as s, s.begin():
        s.execute(delete(db.RoomQuestion).where(db.RoomQuestion.opened < when - dt.timedelta(days=keep_days())))
        while True:
            code = "".join(secrets.choice(CODE_ALPHABET) for _ in range(CODE_LENGTH))
            if s.scalar(select(func.count()).where(db.RoomQuestion.code == code)) == 0:
                break
        row = db.RoomQuestion(code=code, round=1, problem=problem, question=question, params=json.dumps(params),
                              system=system, hide_motion=hide_motion, status="open", opened=when, course=course[:600])
        s.add(row)
        s.flush()
        return _round(row)


@guarded
def ask_again(code: str, bound: Engine | None = None, when: dt.datetime | None = None) -> Round:
    """The same question again (after a discussion): the last round closed if open, the next one opened."""
    with db.session(bound) as s, s.begin():
        last = s.scalar(select(db.RoomQuestion).where(db.RoomQuestion.code == code)
                        .order_by(db.RoomQuestion.round.desc()).limit(1))
        if last is None:
            raise LookupError(code)
        if last.status == "open":
            last.status = "closed"
        row = db.RoomQuestion(code=code, round=last.round + 1, problem=last.problem, question=last.question,
                              params=last.params, system=last.system, hide_motion=last.hide_motion,
                              status="open", opened=when or now(), course=last.course)
        s.add(row)
        s.flush()
        return _round(row)


@guarded
def rounds(code: str, bound: Engine | None = None) -> list[Round]:
    with db.session(bound) as s:
        return [_round(r) for r in s.scalars(select(db.RoomQuestion).where(db.RoomQuestion.code == code)
                                             .order_by(db.RoomQuestion.round))]


def latest(code: str, bound: Engine | None = None) -> Round | None:
    """The code's last round (the one a phone answers), or None for a code never given."""
    found = rounds(code, bound) if code else []
    return found[-1] if found else None


@guarded
def set_status(round_id: int, status: str, bound: Engine | None = None) -> None:
    """Close, reveal or end one round (``ended``: the code's every round, so no phone answers any more)."""
    if status not in STATUSES:
        raise ValueError(status)
    with db.session(bound) as s, s.begin():
        row = s.get(db.RoomQuestion, round_id)
        if row is None:
            raise LookupError(round_id)
        if status == "ended":
            for r in s.scalars(select(db.RoomQuestion).where(db.RoomQuestion.code == row.code)):
                r.status = "ended"
        else:
            row.status = status


@guarded
def answer(round_id: int, who: str, category: str, bound: Engine | None = None, when: dt.datetime | None = None) -> str:
    """Record ``who``'s answer to the round: "counted" (a first answer), "changed", "same", or the round's
    status ("closed", "revealed", "ended") when it takes no answer any more; nothing is counted twice."""
    with db.session(bound) as s, s.begin():
        status = s.scalar(select(db.RoomQuestion.status).where(db.RoomQuestion.id == round_id))
        if status is None:
            raise LookupError(round_id)
        if status != "open":
            return status
        row = s.scalar(select(db.RoomResponse).where(db.RoomResponse.question_id == round_id,
                                                     db.RoomResponse.responder == who))
        category = category[:CATEGORY_LENGTH]
        if row is None:
            s.add(db.RoomResponse(question_id=round_id, responder=who, category=category, at=when or now()))
            return "counted"
        if row.category == category:
            return "same"
        row.category, row.at = category, when or now()
        return "changed"


@guarded
def answer_of(round_id: int, who: str, bound: Engine | None = None) -> str | None:
    """What ``who`` answered in the round (its category), or None."""
    with db.session(bound) as s:
        return s.scalar(select(db.RoomResponse.category).where(db.RoomResponse.question_id == round_id,
                                                                db.RoomResponse.responder == who))


@guarded
def counts(code: str, bound: Engine | None = None) -> dict[int, Counter]:
    """Each round's answers by category (every process's: read from the database)."""
    found: dict[int, Counter] = {}
    with db.session(bound) as s:
        rows = s.execute(select(db.RoomQuestion.round, db.RoomResponse.category, func.count())
                         .join(db.RoomResponse, db.RoomResponse.question_id == db.RoomQuestion.id)
                         .where(db.RoomQuestion.code == code)
                         .group_by(db.RoomQuestion.round, db.RoomResponse.category))
        for number, category, n in rows:
            found.setdefault(number, Counter())[category] = n
    return found


@guarded
def responses_csv(code: str, bound: Engine | None = None) -> str:
    """The code's answers for the instructor's spreadsheet: one row per answer, no one named."""
    with db.session(bound) as s:
        rows = s.execute(select(db.RoomQuestion.opened, db.RoomQuestion.problem, db.RoomQuestion.question,
                                db.RoomQuestion.round, db.RoomResponse.category, db.RoomResponse.at)
                         .join(db.RoomResponse, db.RoomResponse.question_id == db.RoomQuestion.id)
                         .where(db.RoomQuestion.code == code)
                         .order_by(db.RoomQuestion.round, db.RoomResponse.at)).all()
    stamp = "%Y-%m-%d %H:%M:%S"
    return safe_csv(["lecture (UTC)", "problem", "question", "round", "answer counted as", "answered at (UTC)"],
                    ([opened.strftime(stamp), problem, question, number, category, at.strftime(stamp)]
                     for opened, problem, question, number, category, at in rows))


# -- what a phone's watch asks (edge/room_status.py): a few bytes, not a run of the page

_PROCESS_KEY = secrets.token_bytes(32)  # where no course secret is set: a token holds on this process only
STATUS_FRESH = 1.0  # s: one database read per code per process at most this often, however many phones ask
_STATUS: dict[str, tuple[float, str | None]] = {}
_STATUS_LOCK = threading.Lock()
STATUS_KEPT = 1024  # codes remembered at most


def _status_key() -> bytes:
    secret = os.environ.get("DL_COURSE_SECRET", "")
    return hashlib.sha256(b"room-status|" + secret.encode()).digest() if len(secret) >= 16 else _PROCESS_KEY


def status_token(code: str) -> str:
    """What a phone that joined ``code`` shows the status route: only a page that let it join can make it
    (the route cannot be used to guess codes past the join throttle)."""
    return hmac.new(_status_key(), f"room|{code}".encode(), hashlib.sha256).hexdigest()[:32]


def status_token_valid(code: str, token: str) -> bool:
    return bool(code) and hmac.compare_digest(status_token(code).encode(), token.encode()[:64])


def version(found: Round | None) -> str | None:
    """A round's state as the phone compares it: the round and its status; None for a code gone."""
    return f"{found.id}:{found.status}" if found is not None else None


def status_version(code: str, bound: Engine | None = None, clock=time.monotonic) -> str | None:
    """``version`` of the code's last round, read at most every STATUS_FRESH s per process."""
    now = clock()
    with _STATUS_LOCK:
        kept = _STATUS.get(code)
        if kept is not None and now - kept[0] < STATUS_FRESH:
            return kept[1]
    said = version(latest(code, bound))
    with _STATUS_LOCK:
        if len(_STATUS) >= STATUS_KEPT:
            _STATUS.clear()
        _STATUS[code] = (now, said)
    return said


__all__ = ["CODE_ALPHABET", "Round", "RecordingUnavailable", "answer", "answer_of", "ask", "ask_again", "counts",
           "join", "latest", "normal_code", "responder", "responses_csv", "rounds", "set_status", "status_token",
           "status_token_valid", "status_version", "version"]
