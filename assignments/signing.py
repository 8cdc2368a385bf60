"""Signed assignment links: HMAC-SHA256 with the course secret (``DL_COURSE_SECRET``).

A link carries the assignment, the variant (seed) and the student's label in the clear, and a
signature over all three; a changed character in any of them, or in the signature, is refused.
The label is the instructor's own opaque code (no names, no e-mail addresses: links reach access
logs and browser histories), so the signature proves only "the instructor issued this link", not
who holds it. Compared in constant time. The same secret keys each student's variant number
(``variant_key``), so nobody without it can work out a classmate's."""
from __future__ import annotations

import base64
import hashlib
import hmac
import json
import os
import re
import time

SECRET_ENV = "DL_COURSE_SECRET"
MIN_SECRET = 16  # characters; a shorter secret is treated as not set
LABEL = re.compile(r"[A-Za-z0-9][A-Za-z0-9_.-]{0,39}")
LABEL_RULE = ("1 to 40 letters, digits, '.', '_' or '-', starting with a letter or digit "
              "(an opaque code of yours: no names or e-mail addresses)")
SIGNATURE_BYTES = 16  # 128 bits, 22 characters in the link


class NotConfigured(RuntimeError):
    pass


def configured() -> bool:
    return len(os.environ.get(SECRET_ENV, "")) >= MIN_SECRET


def _secret() -> bytes:
    if not configured():
        raise NotConfigured(f"The course admin has not set a course secret ({SECRET_ENV}, at least "
                            f"{MIN_SECRET} characters), so assignment links cannot be signed or checked.")
    return os.environ[SECRET_ENV].encode()


def valid_label(label: object) -> bool:
    return isinstance(label, str) and LABEL.fullmatch(label) is not None


def _message(assignment: int, seed: int, label: str) -> bytes:
    # A field separator no label or number can contain: ("1", "23") and ("12", "3") differ.
    return f"dynamics-lab/assignment/v1\x1f{assignment}\x1f{seed}\x1f{label}".encode()


def _mac(message: bytes) -> bytes:
    return hmac.new(_secret(), message, hashlib.sha256).digest()


def variant_key(assignment: int, label: str) -> int:
    """A 64-bit number fixed by the assignment, the label and the course secret."""
    return int.from_bytes(_mac(f"dynamics-lab/variant/v1\x1f{assignment}\x1f{label}".encode())[:8], "big")


def sign(assignment: int, seed: int, label: str) -> str:
    """The link's signature (URL-safe base64, no padding)."""
    if not valid_label(label):
        raise ValueError(f"A student label is {LABEL_RULE}.")
    digest = _mac(_message(assignment, seed, label))
    return base64.urlsafe_b64encode(digest[:SIGNATURE_BYTES]).decode().rstrip("=")


def verify(assignment: int, seed: int, label: str, signature: str) -> bool:
    """True only for the signature this secret gives these three values."""
    if not valid_label(label) or not isinstance(signature, str):
        return False
    return hmac.compare_digest(sign(assignment, seed, label).encode(), signature.encode())


def seal(purpose: str, payload: dict, seconds: int) -> str:
    """A short-lived token (URL-safe, no padding): ``payload`` as JSON with its expiry, signed with
    the course secret for one ``purpose`` (an LTI login's state, a launch's hand-off into the page).
    Readable by whoever holds it: put no secret in it."""
    body = json.dumps({**payload, "exp": int(time.time()) + seconds}, separators=(",", ":"), sort_keys=True)
    packed = base64.urlsafe_b64encode(body.encode()).decode().rstrip("=")
    mac = _mac(f"dynamics-lab/{purpose}/v1\x1f{packed}".encode())
    return packed + "." + base64.urlsafe_b64encode(mac).decode().rstrip("=")


def unseal(purpose: str, token: object) -> dict | None:
    """The payload of a token ``seal`` made for this purpose and not expired; None for anything else."""
    if not isinstance(token, str) or len(token) > 8000 or token.count(".") != 1:
        return None
    packed, mac = token.split(".")
    want = base64.urlsafe_b64encode(_mac(f"dynamics-lab/{purpose}/v1\x1f{packed}".encode())).decode().rstrip("=")
    if not hmac.compare_digest(want.encode(), mac.encode()):
        return None
    try:
        payload = json.loads(base64.urlsafe_b64decode(packed + "=" * (-len(packed) % 4)))
    except ValueError:
        return None
    if not isinstance(payload, dict) or not isinstance(payload.get("exp"), int) or payload["exp"] < time.time():
        return None
    return payload
