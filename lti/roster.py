"""The course roster from the LMS (Names and Role Provisioning Services), for its instructor only:
who has started an assignment and who has not. The members' names are read from the LMS when the
instructor asks and shown, never stored here."""
from __future__ import annotations

from dataclasses import dataclass

import requests
from sqlalchemy import func, select
from sqlalchemy.engine import Engine

from assignments import db
from lti import platforms
from lti.launch import label_of
from lti.passback import MEMBERSHIP_SCOPE, TIMEOUT, SendFailed, _check, _tokens, access_token

MEDIA = "application/vnd.ims.lti-nrps.v2.membershipcontainer+json"
MAX_PAGES = 50


@dataclass(frozen=True)
class Member:
    name: str  # as the LMS gives it (empty when the LMS shares no names)
    label: str  # this student's label here
    attempts: int  # in the assignment


class RosterUnavailable(RuntimeError):
    """The LMS did not give its roster; the message says why, in plain words."""


def learners(issuer: str, client_id: str, url: str, get=requests.get, post=requests.post) -> list[dict]:
    """The context's active learners, every page (the Link header's rel="next")."""
    platform = platforms.find(issuer, client_id)
    if platform is None or not url:
        raise RosterUnavailable("This course site does not offer its roster to Dynamics Lab.")
    try:
        token, members, pages = "", [], 0
        while url and pages < MAX_PAGES:
            if not platforms.owns(platform, url):  # the launch's, or a next page's: the LMS's own address only
                raise RosterUnavailable(f"The roster's address {str(url)[:200]} is not the LMS's registered address.")
            token = token or access_token(platform, MEMBERSHIP_SCOPE, post)
            answer = get(url, headers={"Authorization": f"Bearer {token}", "Accept": MEDIA}, timeout=TIMEOUT)
            if answer.status_code == 401:
                _tokens.clear()  # an expired or revoked token: a new one next time
            _check(answer, "roster")
            members += answer.json().get("members", [])
            url, pages = answer.links.get("next", {}).get("url"), pages + 1
    except (SendFailed, requests.RequestException, ValueError) as error:
        raise RosterUnavailable(f"The LMS did not give the course roster ({error}).") from None
    return [m for m in members if isinstance(m, dict) and m.get("user_id") and m.get("status", "Active") == "Active"
            and any(str(r).endswith("#Learner") or r == "Learner" for r in m.get("roles", []))]


def standing(issuer: str, client_id: str, url: str, assignment_id: int, bound: Engine | None = None,
             **http) -> list[Member]:
    """Each learner of the course with their attempts at the assignment: those not started first."""
    people = [(str(m.get("name", "")), label_of(issuer, str(m["user_id"])))
              for m in learners(issuer, client_id, url, **http)]
    with db.session(bound) as s:
        counts = dict(s.execute(select(db.Attempt.label, func.count()).where(
            db.Attempt.assignment_id == assignment_id).group_by(db.Attempt.label)).all())
    return sorted((Member(name, label, counts.get(label, 0)) for name, label in people),
                  key=lambda m: (m.attempts > 0, m.name, m.label))
