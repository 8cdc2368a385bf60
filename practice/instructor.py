"""The instructor's key: one secret, set by the course admin in ``DL_INSTRUCTOR_KEY``, that opens
the answer keys (the variant export) and lets a variant link show Study and Lecture. Without it
set, nothing is open to anyone. Compared in constant time; never stored in a link the page writes.
This is the one place the key is checked (assignments will use it too)."""
from __future__ import annotations

import hmac
import os

KEY_ENV = "DL_INSTRUCTOR_KEY"
MIN_LENGTH = 8  # a shorter key is too easy to guess, and is treated as not set


def configured() -> bool:
    return len(os.environ.get(KEY_ENV, "")) >= MIN_LENGTH


def key_matches(candidate: object) -> bool:
    """True if ``candidate`` is the instructor key (False when no key is set)."""
    if not configured() or not isinstance(candidate, str) or not candidate:
        return False
    return hmac.compare_digest(candidate.encode(), os.environ[KEY_ENV].encode())
