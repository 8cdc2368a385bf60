"""The instructor's key: one secret, set by the course admin in ``DL_INSTRUCTOR_KEY``, that opens
the answer keys (the variant export), assignments and the gradebook, and lets a variant link show
Study and Lecture. Without it set, nothing is open to anyone. Compared in constant time; never
stored in a link the page writes. This is the one place the key is checked.

Every try goes through ``THROTTLE``: after a wrong key, the next try from the same browser session
waits 1, 2, 4 then 8 s, and the fifth wrong key in a row locks key entry for that session for 5
minutes; from one client address (every session of it together) the waits go on doubling and the
tenth wrong key locks it for 10 minutes. So one client gets at most 10 tries in its first minute
and one every 10 minutes after that (tests/practice/test_instructor.py counts them); a try while locked is
refused without looking at the key, and the right key works again once the time is up. Each wrong
key is logged, without what was typed. The throttle lives in the process: each replica keeps its
own (README: Security).
"""
from __future__ import annotations

import collections
import dataclasses
import hmac
import logging
import math
import os
import threading
import time
from typing import Callable

KEY_ENV = "DL_INSTRUCTOR_KEY"
MIN_LENGTH = 8  # a shorter key is too easy to guess, and is treated as not set
RECOMMENDED_LENGTH = 24  # what the README's `openssl rand -base64 18` gives

log = logging.getLogger("dynamics_lab.instructor")


def configured() -> bool:
    return len(os.environ.get(KEY_ENV, "")) >= MIN_LENGTH


def key_matches(candidate: object) -> bool:
    """True if ``candidate`` is the instructor key (False when no key is set). Unthrottled: for a
    caller that has already gone through ``try_key``, or for tests."""
    if not configured() or not isinstance(candidate, str) or not candidate:
        return False
    return hmac.compare_digest(candidate.encode(), os.environ[KEY_ENV].encode())


@dataclasses.dataclass(frozen=True)
class Rule:
    """Waits after the 1st, 2nd... wrong key in a row, then a lockout from ``lock_after`` on."""
    waits: tuple[float, ...]
    lock_after: int
    lockout: float


SESSION = Rule(waits=(1, 2, 4, 8), lock_after=5, lockout=5 * 60)
ADDRESS = Rule(waits=(1, 2, 4, 8, 16, 32, 64, 128, 256), lock_after=10, lockout=10 * 60)
FORGET_AFTER = 3600.0  # an hour without a wrong key starts the count again
MAX_TRACKED = 20_000   # who is remembered at most (the oldest forgotten first): a bound on memory


@dataclasses.dataclass
class Record:
    failures: int = 0
    last: float = 0.0
    next_try: float = 0.0


@dataclasses.dataclass(frozen=True)
class Verdict:
    ok: bool
    wait: float = 0.0       # seconds before the next try is looked at
    locked: bool = False    # the wait is a lockout, not a step of the delay
    checked: bool = True    # False: refused without looking at the key (a try while waiting)

    def message(self) -> str:
        if self.ok:
            return ""
        if self.locked:
            minutes = max(1, round(self.wait / 60))
            return (f"Too many wrong keys: key entry is locked for {minutes} minute{'s' * (minutes != 1)}. "
                    "The right key works again after that.")
        if not self.checked:
            return f"Too soon after a wrong key: wait {math.ceil(self.wait)} s, then try again."
        return f"That is not the instructor key. The next try is possible in {math.ceil(self.wait)} s."


class Throttle:
    """Wrong tries of a secret, counted per browser session and per client address (``session`` and
    ``address``: the two rules); ``what`` names the secret in the log. One instance per secret."""
    def __init__(self, clock=time.monotonic, session: Rule = SESSION, address: Rule = ADDRESS, what: str = "instructor key"):
        self.clock = clock
        self.rules = (session, address)
        self.what = what
        self.records: collections.OrderedDict[tuple[str, str], Record] = collections.OrderedDict()
        self.lock = threading.Lock()

    def _record(self, kind: str, who: str, now: float) -> Record:
        """The record of ``who``, most recently used last; the least recently used other one is
        forgotten when the table is full (never the one asked for, so a full table still throttles)."""
        key = (kind, who)
        record = self.records.pop(key, None)
        if record is None or (now - record.last > FORGET_AFTER and now >= record.next_try):
            record = Record(last=now)
            while len(self.records) >= MAX_TRACKED:
                self.records.popitem(last=False)
        self.records[key] = record
        return record

    def try_key(self, candidate: object, session: str, address: str) -> Verdict:
        return self.attempt(lambda: key_matches(candidate), session, address)

    def attempt(self, right: Callable[[], bool], session: str, address: str) -> Verdict:
        """One try: refused without calling ``right`` while this session or address must wait; else
        ``right()`` decides, and a wrong try lengthens the wait."""
        now = self.clock()
        with self.lock:
            mine = [(self.rules[0], self._record("session", session, now)), (self.rules[1], self._record("address", address, now))]
            wait = max(record.next_try - now for _, record in mine)
            if wait > 0:
                locked = any(r.failures >= rule.lock_after and r.next_try - now > 0 for rule, r in mine)
                return Verdict(ok=False, wait=wait, locked=locked, checked=False)
            if right():
                for _, record in mine:
                    record.failures, record.next_try = 0, 0.0
                log.info("%s accepted from %s (session %s)", self.what, address, session[:8])
                return Verdict(ok=True)
            for rule, record in mine:
                record.failures += 1
                record.last = now
                step = record.failures - 1
                record.next_try = now + (rule.lockout if record.failures >= rule.lock_after
                                         else rule.waits[min(step, len(rule.waits) - 1)])
            wait = max(record.next_try - now for _, record in mine)
            locked = any(r.failures >= rule.lock_after for rule, r in mine)
        log.warning("wrong %s from %s (session %s): %d in a row from the address, next try in %.0f s%s",
                    self.what, address, session[:8], mine[1][1].failures, wait, " (locked)" if locked else "")
        return Verdict(ok=False, wait=wait, locked=locked)


THROTTLE = Throttle()


def try_key(candidate: object, session: str, address: str) -> Verdict:
    """The one door to the key: throttled per browser session and per client address."""
    return THROTTLE.try_key(candidate, session, address)
