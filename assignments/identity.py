"""Who is answering: the seam between how a student arrives and what is recorded.

A student arrives with a signed assignment link (``from_link``), or from an LMS's LTI 1.3 launch:
``lti.store.student`` turns the verified ID token into the same ``StudentIdentity`` with
``source="lti"`` (its label opaque, keyed from the platform and its ``sub``; its assignment from
the resource link). Everything downstream (the page, the records, the gradebook) sees only a
``StudentIdentity``; grade passback (``lti.passback``) reads ``records.standing``."""
from __future__ import annotations

import re
from dataclasses import dataclass
from types import ModuleType
from typing import Mapping

from assignments import signing
from practice.variants import ASSIGNMENT, MAX_SEED, variant

# The link's query keys. ``seed`` is the same key an ordinary variant link uses.
LINK_KEYS = ("assignment", "seed", "student", "sig")
# Each number has one spelling: ASCII digits, no leading zero ("01" and "٣" would read as 1 and 3).
ASSIGNMENT_NUMBER = re.compile(r"[1-9][0-9]{0,8}")
SEED_NUMBER = re.compile(r"0|[1-9][0-9]{0,9}")


@dataclass(frozen=True)
class StudentIdentity:
    assignment_id: int
    label: str  # the instructor's opaque code for the student (or an LTI platform's ``sub``)
    seed: int   # the student's variant
    source: str = "link"


class LinkRefused(ValueError):
    """A link that is not the one the instructor issued; the message says so in plain words."""


TAMPERED = ("This assignment link has been changed since your instructor issued it (its assignment, "
            "variant or student code does not match its signature), so it cannot be used. Open the link "
            "exactly as you received it, or ask your instructor for it again.")


def is_assignment_link(query: Mapping[str, str]) -> bool:
    return "assignment" in query or "sig" in query or "student" in query


def from_link(query: Mapping[str, str]) -> StudentIdentity:
    """The identity a signed link carries; ``LinkRefused`` if a part is missing, malformed or changed."""
    missing = [k for k in LINK_KEYS if not query.get(k)]
    if missing:
        raise LinkRefused(f"This assignment link is incomplete (it lacks {', '.join(missing)}). Open the "
                          "link exactly as you received it, or ask your instructor for it again.")
    assignment, seed, label, signature = (str(query[k]) for k in LINK_KEYS)
    if not (ASSIGNMENT_NUMBER.fullmatch(assignment) and SEED_NUMBER.fullmatch(seed) and int(seed) <= MAX_SEED
            and signing.valid_label(label) and re.fullmatch(r"[A-Za-z0-9_-]{1,64}", signature)):
        raise LinkRefused(TAMPERED)
    try:
        ok = signing.verify(int(assignment), int(seed), label, signature)
    except signing.NotConfigured as error:
        raise LinkRefused("Assignment links cannot be checked on this server: " + str(error)) from None
    if not ok:
        raise LinkRefused(TAMPERED)
    return StudentIdentity(int(assignment), label, int(seed), "link")


def parameters(identity: StudentIdentity, solver: ModuleType, problem: str) -> dict:
    """The student's givens (SI, radians): their variant number in the assignment stream, so the
    number in their link opened as a public ``?seed=N`` link gives other givens."""
    return variant(solver, problem, identity.seed, ASSIGNMENT)


def link_query(identity: StudentIdentity) -> dict[str, str]:
    """The query a student's link carries (signed here)."""
    return {"assignment": str(identity.assignment_id), "seed": str(identity.seed), "student": identity.label,
            "sig": signing.sign(identity.assignment_id, identity.seed, identity.label)}
