"""What LTI keeps in the course's database: spent one-time values, resource links, LMS students."""
from __future__ import annotations

import datetime as dt
import hashlib
import hmac

from sqlalchemy import delete, select
from sqlalchemy.engine import Engine
from sqlalchemy.exc import IntegrityError

from assignments import db, records, signing
from assignments.identity import StudentIdentity
from lti import platforms
from lti.launch import AGS_CLAIM, Launch, label_of, refuse

KEEP_USED = dt.timedelta(days=2)  # a nonce older than an id_token can live is no longer needed


def spender(bound: Engine | None = None):
    """``spend(key)``: True the first time a key is spent, False after (a replay)."""
    def spend(key: str) -> bool:
        try:
            with db.session(bound) as s, s.begin():
                s.execute(delete(db.LtiUsed).where(db.LtiUsed.at < records.now() - KEEP_USED))
                s.add(db.LtiUsed(key=key[:200], at=records.now()))
            return True
        except IntegrityError:
            return False
    return spend


def _placement(issuer: str, deployment: str, context: str, assignment_id: int) -> str:
    message = f"dynamics-lab/lti-placement/v1\x1f{issuer}\x1f{deployment}\x1f{context}\x1f{assignment_id}"
    return hmac.new(signing._secret(), message.encode(), hashlib.sha256).hexdigest()[:32]


def placement(launch: Launch, assignment_id: int) -> str:
    """The custom parameter a deep link gives its resource link: the assignment, sealed to this course."""
    return f"{assignment_id}.{_placement(launch.platform.issuer, launch.deployment, launch.context.get('id', ''), assignment_id)}"


def assignment_of(launch: Launch, bound: Engine | None = None) -> int | None:
    """The assignment a resource link launch opens: known from an earlier launch, or from the custom
    parameter its deep link set (checked against this course). Records the link and its line item."""
    link_id = launch.claim("resource_link")["id"]
    lineitem = (launch.claims.get(AGS_CLAIM) or {}).get("lineitem", "")
    with db.session(bound) as s, s.begin():
        row = s.scalar(select(db.LtiLink).where(db.LtiLink.issuer == launch.platform.issuer,
                                                db.LtiLink.deployment_id == launch.deployment,
                                                db.LtiLink.resource_link_id == link_id))
        if row is not None:
            if lineitem and row.lineitem != lineitem:
                row.lineitem = lineitem[:1000]
            return row.assignment_id
        custom = str((launch.claim("custom") or {}).get("dl_assignment", ""))
        number, _, mac = custom.partition(".")
        context = launch.context.get("id", "")
        if not (number.isdigit() and hmac.compare_digest(
                mac, _placement(launch.platform.issuer, launch.deployment, context, int(number)))):
            return None
        if s.get(db.Assignment, int(number)) is None:
            return None
        s.add(db.LtiLink(assignment_id=int(number), issuer=launch.platform.issuer, deployment_id=launch.deployment,
                         context_id=context[:255], resource_link_id=link_id[:255], lineitem=lineitem[:1000]))
        return int(number)


def link(assignment_id: int, launch: Launch, resource_link_id: str, bound: Engine | None = None) -> None:
    """Record a resource link made here (deep linking) for an assignment of this course."""
    with db.session(bound) as s, s.begin():
        s.add(db.LtiLink(assignment_id=assignment_id, issuer=launch.platform.issuer, deployment_id=launch.deployment,
                         context_id=launch.context.get("id", "")[:255], resource_link_id=resource_link_id[:255],
                         lineitem=""))


def student(launch: Launch, assignment_id: int, bound: Engine | None = None) -> StudentIdentity:
    """The learner as a student of the assignment: enrolled under their opaque label (their variant
    fixed by the assignment, that label and the course secret), with the ``sub`` kept for passback."""
    sub, issuer = launch.claims["sub"], launch.platform.issuer
    label = label_of(issuer, sub)
    records.enrol(assignment_id, [label], bound)
    name = str(launch.claims.get("name", ""))[:200] if platforms.keep_names() else ""
    with db.session(bound) as s, s.begin():
        row = s.scalar(select(db.LtiMember).where(db.LtiMember.assignment_id == assignment_id,
                                                  db.LtiMember.label == label))
        if row is None:
            s.add(db.LtiMember(assignment_id=assignment_id, label=label, issuer=issuer, sub=sub[:255], name=name))
        elif name and row.name != name:
            row.name = name
    return StudentIdentity(assignment_id, label, records.student_seed(assignment_id, label), "lti")


def contexts_assignments(issuer: str, context: str, bound: Engine | None = None) -> list[int]:
    """The assignments placed in one LMS course (what its instructor sees)."""
    with db.session(bound) as s:
        return sorted(set(s.scalars(select(db.LtiLink.assignment_id).where(db.LtiLink.issuer == issuer,
                                                                           db.LtiLink.context_id == context))))


def from_handoff(payload: dict) -> StudentIdentity | None:
    if payload.get("role") != "student":
        return None
    return StudentIdentity(int(payload["a"]), str(payload["l"]), int(payload["s"]), "lti")


def refuse_unplaced(launch: Launch):
    return refuse(f"resource link {launch.claim('resource_link')['id']!r} of {launch.platform.issuer} has no assignment",
                  "This link in your course has no Dynamics Lab assignment yet (your instructor adds one with "
                  "the LMS's “add external tool” dialog).")


def contexts_of(assignment_id: int, bound: Engine | None = None) -> set[tuple[str, str]]:
    """The LMS courses (issuer, context id) an assignment is placed in."""
    with db.session(bound) as s:
        return {(issuer, context) for issuer, context in s.execute(
            select(db.LtiLink.issuer, db.LtiLink.context_id).where(db.LtiLink.assignment_id == assignment_id))}
