"""Grade passback (LTI Assignment and Grade Services): each LMS student's score, sent to the line item
of the resource link they launched, off the student's request.

A recorded attempt of a student who arrived from an LMS (``queue``) marks their score as waiting:
one database write on the page, nothing else. A worker thread per process (``start``) sends what
waits: the score that counts, as the gradebook computes it (``records.standing``), with
``activityProgress`` (Submitted, or Completed when every answer is right or out of attempts) and
``gradingProgress`` FullyGraded. The best score wins: a lower score than the one the LMS has is not
sent (a late attempt, a changed rule). Sending the same score twice changes nothing (idempotent).
A 429, a 5xx or no answer is tried again with exponential backoff (at least the platform's
Retry-After); any other refusal is kept as "failed", shown to the instructor with its reason, and
tried again an hour later (or at once from the gradebook's "Send again"). Staff are never sent:
only students have an ``lti_member`` row. Rows are claimed before sending, so replicas sharing a
database do not send one score twice at the same time.
"""
from __future__ import annotations

import datetime as dt
import logging
import random
import threading
import time
import uuid
from dataclasses import dataclass

import jwt
import requests
from sqlalchemy import select, update
from sqlalchemy.engine import Engine

from assignments import db, records
from assignments.identity import StudentIdentity
from lti import platforms

log = logging.getLogger("dynamics_lab.lti")
SCORE_SCOPE = "https://purl.imsglobal.org/spec/lti-ags/scope/score"
MEMBERSHIP_SCOPE = "https://purl.imsglobal.org/spec/lti-nrps/scope/contextmembership.readonly"
CLAIM_SECONDS = 120  # a claimed row is left alone this long by other workers
FAILED_AGAIN = dt.timedelta(hours=1)
MAX_BACKOFF = 3600.0
TIMEOUT = 10


def queue(identity: StudentIdentity, bound: Engine | None = None) -> bool:
    """Mark this student's score as waiting to be sent, if they came from an LMS. Never raises: the
    student's page goes on whatever the database or the LMS does."""
    try:
        with db.session(bound) as s, s.begin():
            member = s.scalar(select(db.LtiMember.id).where(db.LtiMember.assignment_id == identity.assignment_id,
                                                            db.LtiMember.label == identity.label))
            if member is None:
                return False
            row = s.scalar(select(db.LtiScore).where(db.LtiScore.assignment_id == identity.assignment_id,
                                                     db.LtiScore.label == identity.label))
            if row is None:
                s.add(db.LtiScore(assignment_id=identity.assignment_id, label=identity.label, status="waiting",
                                  sent=None, sent_progress="", tries=0, next_try=records.now(), error=""))
            else:
                row.status, row.tries, row.next_try = "waiting", 0, records.now()
    except Exception as error:  # noqa: BLE001 - the page never fails for the LMS's sake
        log.warning("grade passback not queued for assignment %s: %s", identity.assignment_id, error)
        return False
    if bound is None:  # the app's own database: its sender thread (tests run ``run_due`` themselves)
        start()
        _wake.set()
    return True


@dataclass(frozen=True)
class Score:
    given: float
    maximum: float
    progress: str  # activityProgress


def score_of(identity: StudentIdentity, bound: Engine | None = None) -> Score | None:
    standing = records.standing(identity, bound)
    if standing is None:
        return None
    done = all(c.first_right is not None or c.attempts >= c.allowed for c in standing.cells.values())
    tried = any(c.attempts for c in standing.cells.values())
    progress = "Completed" if done else "Submitted" if tried else "Initialized"
    return Score(standing.score(), standing.settings.out_of, progress)


# -- the platform's access token (client credentials with the tool's signed assertion)

_tokens: dict[tuple[str, str, str], tuple[str, float]] = {}


class SendFailed(RuntimeError):
    def __init__(self, message: str, retry: bool, after: float = 0.0):
        super().__init__(message)
        self.retry, self.after = retry, after


def _check(answer: requests.Response, what: str) -> None:
    if answer.status_code < 300:
        return
    retry = answer.status_code == 429 or answer.status_code >= 500
    after = answer.headers.get("Retry-After", "")
    raise SendFailed(f"{what}: the LMS answered {answer.status_code} {answer.text[:200]}", retry,
                     float(after) if after.isdigit() else 0.0)


def access_token(platform: platforms.Platform, scope: str, post=requests.post) -> str:
    key = (platform.auth_token_url, platform.client_id, scope)
    held = _tokens.get(key)
    if held and held[1] > time.time() + 60:
        return held[0]
    now = int(time.time())
    assertion = jwt.encode({"iss": platform.client_id, "sub": platform.client_id, "aud": platform.auth_token_url,
                            "iat": now, "exp": now + 300, "jti": uuid.uuid4().hex}, platforms.tool_key(),
                           algorithm="RS256", headers={"kid": platforms.tool_jwk()["kid"]})
    try:
        answer = post(platform.auth_token_url, data={
            "grant_type": "client_credentials", "client_assertion": assertion, "scope": scope,
            "client_assertion_type": "urn:ietf:params:oauth:client-assertion-type:jwt-bearer"}, timeout=TIMEOUT)
    except requests.RequestException as error:
        raise SendFailed(f"access token: no answer from the LMS ({type(error).__name__})", True) from None
    _check(answer, "access token")
    try:
        body = answer.json()
        token, lifetime = str(body["access_token"]), float(body.get("expires_in", 3600))
    except (ValueError, KeyError, TypeError, AttributeError):  # an answer that is not a token: try again later
        raise SendFailed("access token: the LMS's answer held no access token", True) from None
    _tokens[key] = (token, time.time() + lifetime)
    return token


def _scores_url(lineitem: str) -> str:
    path, _, query = lineitem.partition("?")
    return path.rstrip("/") + "/scores" + ("?" + query if query else "")


def send(row_id: int, bound: Engine | None = None, post=requests.post) -> str:
    """Send one waiting score (already claimed); returns its new status."""
    with db.session(bound) as s:
        row = s.get(db.LtiScore, row_id)
        member = s.scalar(select(db.LtiMember).where(db.LtiMember.assignment_id == row.assignment_id,
                                                     db.LtiMember.label == row.label))
        link = s.execute(select(db.LtiLink.lineitem, db.LtiLink.deployment_id).where(
            db.LtiLink.assignment_id == row.assignment_id, db.LtiLink.issuer == member.issuer,
            db.LtiLink.lineitem != "").order_by(db.LtiLink.id)).first()
    identity = StudentIdentity(row.assignment_id, row.label, records.student_seed(row.assignment_id, row.label), "lti")
    lineitem, platform = (link[0], platforms.serving(member.issuer, link[1])) if link else ("", None)
    try:
        if platform is None or not lineitem:
            raise SendFailed("the LMS gave this link no grade column (line item), or is no longer registered", False)
        if not platforms.owns(platform, lineitem):
            raise SendFailed(f"the grade column's address {lineitem[:200]} is not on the LMS's registered "
                             "addresses (its issuer, token, key set or frame origins)", False)
        score = score_of(identity, bound)
        if score is None:
            raise SendFailed("the assignment no longer exists", False)
        if row.sent is not None and (score.given, score.progress) == (row.sent, row.sent_progress) \
                or row.sent is not None and score.given < row.sent:
            return _done(row_id, bound, "sent", row.sent, row.sent_progress)  # the LMS has this, or better
        body = {"userId": member.sub, "scoreGiven": score.given, "scoreMaximum": score.maximum,
                "activityProgress": score.progress, "gradingProgress": "FullyGraded",
                "timestamp": records.now().isoformat(timespec="milliseconds")}
        token = access_token(platform, SCORE_SCOPE, post)
        try:
            answer = post(_scores_url(lineitem), json=body, timeout=TIMEOUT, headers={
                "Authorization": f"Bearer {token}", "Content-Type": "application/vnd.ims.lis.v1.score+json"})
        except requests.RequestException as error:
            raise SendFailed(f"score: no answer from the LMS ({type(error).__name__})", True) from None
        if answer.status_code == 401:
            _tokens.clear()  # an expired or revoked token: a new one next time
        _check(answer, "score")
        log.info("grade passback: assignment %s, %s: %s of %s sent", row.assignment_id, row.label, score.given,
                 score.maximum)
        return _done(row_id, bound, "sent", score.given, score.progress)
    except SendFailed as error:
        return _failed(row_id, bound, error)


def _done(row_id: int, bound, status: str, sent: float | None, progress: str) -> str:
    with db.session(bound) as s, s.begin():
        row = s.get(db.LtiScore, row_id)
        row.sent, row.sent_progress, row.error, row.tries = sent, progress, "", 0
        if row.status == "sending":  # else queued again while this was sent: it waits (the newer may count more)
            row.status = status
        return row.status


def _failed(row_id: int, bound, error: SendFailed) -> str:
    with db.session(bound) as s, s.begin():
        row = s.get(db.LtiScore, row_id)
        row.tries += 1
        row.error = str(error)[:1000]
        if error.retry:
            wait = max(error.after, min(MAX_BACKOFF, 2.0 * 2 ** row.tries) * random.uniform(0.8, 1.2))
            row.status, row.next_try = "waiting", records.now() + dt.timedelta(seconds=wait)
        else:
            row.status, row.next_try = "failed", records.now() + FAILED_AGAIN
        log.warning("grade passback for assignment %s, %s not sent (%s): %s", row.assignment_id, row.label,
                    row.status, error)
        return row.status


def run_due(bound: Engine | None = None, post=requests.post) -> int:
    """Send every score due now, each claimed first (status "sending", left alone by other workers
    for CLAIM_SECONDS); returns how many were tried."""
    now = records.now()
    with db.session(bound) as s:
        due = s.execute(select(db.LtiScore.id, db.LtiScore.next_try).where(
            db.LtiScore.status.in_(("waiting", "failed", "sending")), db.LtiScore.next_try <= now)
            .order_by(db.LtiScore.next_try).limit(200)).all()
    tried = 0
    for row_id, when in due:
        with db.session(bound) as s, s.begin():
            claimed = s.execute(update(db.LtiScore).where(db.LtiScore.id == row_id, db.LtiScore.next_try == when)
                                .values(status="sending", next_try=now + dt.timedelta(seconds=CLAIM_SECONDS))).rowcount
        if claimed:
            send(row_id, bound, post)
            tried += 1
    return tried


@dataclass(frozen=True)
class Passback:
    sent: int
    waiting: int
    failed: list[tuple[str, str]]  # (label, reason)


def summary(assignment_id: int, bound: Engine | None = None) -> Passback | None:
    """What the instructor sees: None when no student of this assignment came from an LMS."""
    with db.session(bound) as s:
        rows = s.execute(select(db.LtiScore.label, db.LtiScore.status, db.LtiScore.error)
                         .where(db.LtiScore.assignment_id == assignment_id)).all()
        members = s.scalar(select(db.LtiMember.id).where(db.LtiMember.assignment_id == assignment_id).limit(1))
    if members is None:
        return None
    return Passback(sum(r.status == "sent" for r in rows), sum(r.status in ("waiting", "sending") for r in rows),
                    [(r.label, r.error) for r in rows if r.status == "failed"])


def send_again(assignment_id: int, bound: Engine | None = None) -> int:
    """The instructor's "Send again": every failed score of the assignment waits again, now."""
    with db.session(bound) as s, s.begin():
        count = s.execute(update(db.LtiScore).where(db.LtiScore.assignment_id == assignment_id,
                                                    db.LtiScore.status == "failed")
                          .values(status="waiting", tries=0, next_try=records.now())).rowcount
    _wake.set()
    return count


_wake = threading.Event()
_started = threading.Lock()
_worker: list[threading.Thread] = []


def start() -> None:
    """The process's sender thread (once): wakes on a queued score, and every 30 s for retries."""
    with _started:
        if _worker and _worker[0].is_alive():
            return

        def loop() -> None:
            while True:
                _wake.wait(30)
                _wake.clear()
                try:
                    run_due()
                except Exception as error:  # noqa: BLE001 - a database away: the next round tries again
                    log.warning("grade passback round failed: %s", error)

        thread = threading.Thread(target=loop, name="lti-passback", daemon=True)
        thread.start()
        _worker[:] = [thread]
