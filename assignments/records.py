"""Every read and write of assignments, rosters and attempts, and the gradebook made from them.

An attempt is an answer the judge could read (the page never records a typo, an unknown name or a
unit of another dimension), written in one transaction and reported recorded only once that
transaction has committed; the same text as the student's previous attempt at that answer is not
recorded again. Any database failure becomes ``RecordingUnavailable`` with a message for the
student (the page then judges the answer anyway and says it was not recorded).

What counts is decided when reading, from the attempts in the order they were recorded and the
assignment's rules as they are then (one source of truth, so an extension or an edit applies to
the past): an attempt earns credit if it is right, within the attempts allowed for its answer
(plus the student's extra ones), made before the student opened that problem's solution, and on
time (before the due time, or the student's extension); a right answer after it earns the late
credit the instructor set (none, a penalty per started day, or a fixed fraction). Late and
over-limit attempts are kept and marked. Every instructor change is logged with its time, what it
was before and after, and can be undone (the undo is a change too)."""
from __future__ import annotations

import csv
import datetime as dt
import functools
import hashlib
import io
import json
import logging
import math
import re
import zoneinfo
from collections import Counter
from dataclasses import dataclass, field, replace
from typing import Callable, Iterable, TypeVar

from sqlalchemy import exists, func, select
from sqlalchemy.engine import Engine
from sqlalchemy.exc import IntegrityError, SQLAlchemyError

from assignments import db, signing
from assignments.identity import StudentIdentity
from practice.variants import MAX_SEED
from solvers import registry

log = logging.getLogger("dynamics_lab.records")
MAX_TYPED = 400
MAX_ROSTER = 2000
MAX_ROSTER_TEXT = 200_000  # characters: 2000 labels of 40, with room for extra columns
T = TypeVar("T")


class RecordingUnavailable(RuntimeError):
    """The database could not be reached or refused the write; nothing was recorded."""


class NotAccepted(RecordingUnavailable):
    """The assignment takes no answers now (closed or archived by the instructor): nothing recorded."""


UNAVAILABLE = ("The course's gradebook database cannot be reached right now, so this was not recorded. "
               "Practice still works; try again in a few minutes for your attempts to count.")
CLOSED = ("Your instructor has closed this assignment, so answers are checked but no longer recorded. "
          "Ask your instructor if you think it should still be open.")


def guarded(fn: Callable[..., T]) -> Callable[..., T]:
    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        try:
            return fn(*args, **kwargs)
        except (SQLAlchemyError, OSError) as error:
            log.warning("database unavailable in %s: %s", fn.__name__, error)
            raise RecordingUnavailable(UNAVAILABLE) from error
    return wrapper


# Control characters but tab, newline and carriage return (kept, and neutralised in the CSV):
# PostgreSQL's text cannot hold NUL (SQLite can), and none belongs in an answer, a message, a slip's
# name or a title; stored as U+FFFD, the same on both backends.
CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f]")


def _storable(text: str, limit: int) -> str:
    return CONTROL.sub("\ufffd", text[:limit])


def now() -> dt.datetime:
    return dt.datetime.now(dt.timezone.utc)


# -- assignments and their rules

STATUSES = ("open", "closed", "archived")
LATE_POLICIES = ("none", "per_day", "fixed")
DAY = dt.timedelta(days=1)


@dataclass(frozen=True)
class Part:
    """One problem of an assignment: the answers that count, each with its weight (points)."""
    problem: str
    answers: tuple[str, ...]
    weights: tuple[float, ...] = ()  # one per answer; empty: 1 each

    def __post_init__(self):
        object.__setattr__(self, "answers", tuple(self.answers))
        object.__setattr__(self, "weights", tuple(float(w) for w in self.weights) or (1.0,) * len(self.answers))

    def weight(self, answer: str) -> float:
        return self.weights[self.answers.index(answer)]

    def as_json(self) -> dict:
        return {"problem": self.problem, "answers": list(self.answers), "weights": list(self.weights)}


Question = tuple[str, str]  # (problem, answer)

# The free-body diagram as a question of its own, beside a problem's answers: drawn and judged on the page
# (practice/diagram_judge.py), recorded like a typed answer (the drawing in words as what was "typed").
DIAGRAM = "free_body_diagram"
DIAGRAM_HEADING = "Free-body diagram"


def in_zone(moment: dt.datetime, zone: str) -> dt.datetime:
    try:
        return moment.astimezone(zoneinfo.ZoneInfo(zone))
    except (zoneinfo.ZoneInfoNotFoundError, ValueError):
        return moment.astimezone(dt.timezone.utc)


def when_text(moment: dt.datetime, zone: str = "UTC") -> str:
    """A time as a person reads it, in a zone: "Tue 1 Dec 2026, 13:00 CET"."""
    local = in_zone(moment, zone)
    return f"{local:%a} {local.day} {local:%b %Y, %H:%M} {local.tzname()}"


def duration_text(span: dt.timedelta) -> str:
    """'3 h 20 min', '2 days 1 h': how late, rounded down to the minute."""
    minutes = int(span.total_seconds() // 60)
    if minutes == 0:
        return "less than a minute"
    days, rest = divmod(minutes, 24 * 60)
    hours, minutes = divmod(rest, 60)
    parts = ([f"{days} day{'s' if days != 1 else ''}"] if days else []) + ([f"{hours} h"] if hours else [])
    if not days and (minutes or not hours):
        parts.append(f"{minutes} min")
    return " ".join(parts)


def _number(x: float) -> str:
    return f"{x:g}"


@dataclass(frozen=True)
class Settings:
    """What the instructor chooses for an assignment."""
    title: str
    parts: tuple[Part, ...]
    tolerance: float  # relative, for typed numbers
    due: dt.datetime  # aware
    attempts_allowed: int  # per answer
    solution_before_due: bool = False
    late_policy: str = "none"  # none | per_day (late_value lost per started day) | fixed (late_value kept)
    late_value: float = 0.0
    hints: bool = True  # a known slip's hint ("A sign: the normal component reverses …")
    slip_names: bool = True  # with hints off: the slip named ("a known slip: A sign"), no hint
    answer_after_last: bool = False  # the right value shown once an answer's attempts are used up
    timezone: str = "UTC"  # the instructor's, for the times the instructor's page shows and enters
    status: str = "open"

    def __post_init__(self):
        object.__setattr__(self, "parts", tuple(self.parts))

    @classmethod
    def of(cls, title: str, problem: str, answers: Iterable[str], tolerance: float, due: dt.datetime,
           attempts_allowed: int, solution_before_due: bool = False, **rest) -> "Settings":
        """One problem, every answer worth 1."""
        return cls(title, (Part(problem, tuple(answers)),), tolerance, due, attempts_allowed, solution_before_due,
                   **rest)

    # -- what the assignment asks
    @property
    def problem(self) -> str:
        """The first problem (where a student's link opens)."""
        return self.parts[0].problem

    @property
    def problems(self) -> tuple[str, ...]:
        return tuple(p.problem for p in self.parts)

    @property
    def answers(self) -> tuple[str, ...]:
        """The first problem's answers that count."""
        return self.parts[0].answers

    def part(self, problem: str) -> Part | None:
        return next((p for p in self.parts if p.problem == problem), None)

    @property
    def questions(self) -> tuple[Question, ...]:
        return tuple((p.problem, a) for p in self.parts for a in p.answers)

    def weight(self, question: Question) -> float:
        part = self.part(question[0])
        return part.weight(question[1]) if part and question[1] in part.answers else 0.0

    @property
    def out_of(self) -> float:
        return sum(w for p in self.parts for w in p.weights)

    @property
    def accepting(self) -> bool:
        return self.status == "open"

    # -- late credit
    def late_credit(self, late_by: dt.timedelta) -> float:
        """The fraction a right answer keeps when it is ``late_by`` past the student's due time."""
        if late_by <= dt.timedelta(0):
            return 1.0
        if self.late_policy == "fixed":
            return max(0.0, min(1.0, self.late_value))
        if self.late_policy == "per_day":
            days = math.ceil(late_by / DAY)
            return max(0.0, round(1.0 - self.late_value * days, 6))
        return 0.0

    def late_rule(self) -> str:
        """The late policy in plain words."""
        if self.late_policy == "fixed":
            return f"a right answer after the due time earns {self.late_value * 100:g} % of its points"
        if self.late_policy == "per_day":
            last = math.ceil(1 / self.late_value) if self.late_value > 0 else 0
            return (f"a right answer after the due time loses {self.late_value * 100:g} % of its points per "
                    f"started day late (nothing from day {last} on)")
        return "a right answer after the due time is kept and shown, but earns no points"

    def feedback_rule(self) -> str:
        if self.hints:
            return "a known slip is named, with a hint"
        if self.slip_names:
            return "a known slip is named, without a hint"
        return "right or not right only"

    def errors(self, *, creating: bool = False, when: dt.datetime | None = None) -> list[str]:
        """What is wrong with these settings, in plain words (empty when they are fine). Creating,
        a due time in the past is wrong too."""
        wrong = []
        if not self.title.strip() or len(self.title) > 120:
            wrong.append("The title needs 1 to 120 characters" + (f" (it has {len(self.title)})." if self.title.strip() else "."))
        if not self.parts:
            wrong.append("Choose at least one problem.")
        seen = set()
        for part in self.parts:
            if part.problem not in registry.PROBLEM_IDS:
                wrong.append(f"{part.problem!r} is not a problem of this app.")
            if part.problem in seen:
                wrong.append(f"The problem {part.problem} is chosen twice.")
            seen.add(part.problem)
            if not part.answers:
                wrong.append(f"Choose at least one answer that counts in {part.problem}.")
            if len(part.weights) != len(part.answers) or not all(
                    math.isfinite(w) and 0 < w <= 1000 for w in part.weights):
                wrong.append("Each answer's weight is a number of points above 0 and at most 1000.")
        if not (math.isfinite(self.tolerance) and 1e-4 <= self.tolerance <= 0.1):
            wrong.append("The tolerance is between 0.01 % and 10 %.")
        if not 1 <= self.attempts_allowed <= 100:
            wrong.append("Allow from 1 to 100 attempts per answer.")
        if self.due.tzinfo is None:
            wrong.append("The due time needs a time zone.")
        elif creating and self.due <= (when or now()):
            wrong.append(f"The due time, {when_text(self.due, self.timezone)}, is already past: choose a later one.")
        if self.late_policy not in LATE_POLICIES:
            wrong.append("The late policy is none, a penalty per day, or a fixed fraction.")
        elif self.late_policy == "per_day" and not (math.isfinite(self.late_value) and 0 < self.late_value <= 1):
            wrong.append("The late penalty per day is between 1 % and 100 %.")
        elif self.late_policy == "fixed" and not (math.isfinite(self.late_value) and 0 <= self.late_value <= 1):
            wrong.append("The fraction kept for late work is between 0 % and 100 %.")
        try:
            zoneinfo.ZoneInfo(self.timezone)
        except (zoneinfo.ZoneInfoNotFoundError, ValueError):
            wrong.append(f"{self.timezone!r} is not a time zone (e.g. Europe/Berlin, America/New_York, UTC).")
        if self.status not in STATUSES:
            wrong.append("An assignment is open, closed or archived.")
        return wrong


# The columns an instructor's edit may change, as stored in the change log (JSON).
EDITABLE = ("title", "parts", "tolerance", "due", "attempts_allowed", "solution_before_due", "late_policy",
            "late_value", "hints", "slip_names", "answer_after_last", "timezone", "status")


def _as_json(settings: Settings) -> dict:
    out = {}
    for name in EDITABLE:
        value = getattr(settings, name)
        out[name] = ([p.as_json() for p in value] if name == "parts" else value.isoformat() if name == "due"
                     else value)
    return out


def _from_json(values: dict, base: Settings) -> Settings:
    changes = {}
    for name, value in values.items():
        if name == "parts":
            value = tuple(Part(p["problem"], tuple(p["answers"]), tuple(p.get("weights") or ())) for p in value)
        elif name == "due":
            value = dt.datetime.fromisoformat(value)
        changes[name] = value
    return replace(base, **changes)


def _settings(row: db.Assignment) -> Settings:
    parts = tuple(Part(p["problem"], tuple(p["answers"]), tuple(p.get("weights") or ())) for p in row.parts)
    return Settings(row.title, parts, row.tolerance, row.due, row.attempts_allowed, row.solution_before_due,
                    row.late_policy, row.late_value, row.hints, row.slip_names, row.answer_after_last,
                    row.timezone, row.status)


def _store(row: db.Assignment, settings: Settings) -> None:
    for name in EDITABLE:
        value = getattr(settings, name)
        if name == "parts":
            value = [p.as_json() for p in value]
        elif name == "title":
            value = _storable(value.strip(), 120)
        setattr(row, name, value)


def fingerprint(settings: Settings) -> str:
    """What makes two "Create" clicks the same assignment: the title (case and spacing aside), the
    problems with their answers, and the due time."""
    key = [" ".join(settings.title.split()).casefold(), [p.as_json() for p in settings.parts],
           settings.due.astimezone(dt.timezone.utc).isoformat()]
    return hashlib.sha256(json.dumps(key, sort_keys=True).encode()).hexdigest()


@dataclass(frozen=True)
class Created:
    id: int
    new: bool  # False: the same assignment had been created already (a repeated click, a reload)
    created_at: dt.datetime
    students: int  # on its roster now


@guarded
def create(settings: Settings, labels: Iterable[str] = (), bound: Engine | None = None,
           when: dt.datetime | None = None) -> Created:
    """Create the assignment with its roster, in one transaction; or, if the same assignment (see
    ``fingerprint``) exists already, add nothing and return it. ValueError says what is wrong."""
    when = when or now()
    if settings.errors(creating=True, when=when):
        raise ValueError(" ".join(settings.errors(creating=True, when=when)))
    labels = list(dict.fromkeys(labels))
    key = fingerprint(settings)
    with db.session(bound) as s:
        try:
            with s.begin():
                row = db.Assignment(created=when, fingerprint=key)
                _store(row, settings)
                s.add(row)
                s.flush()
                for label in labels:
                    s.add(db.Student(assignment_id=row.id, label=label, seed=student_seed(row.id, label)))
                s.add(db.Change(assignment_id=row.id, at=when, action="created", label="",
                                summary=f"Created “{row.title}” for {len(labels)} students.",
                                before={}, after=_as_json(settings)))
            return Created(row.id, True, when, len(labels))
        except IntegrityError:  # a concurrent click made it first
            pass
    with db.session(bound) as s:
        row = s.scalar(select(db.Assignment).where(db.Assignment.fingerprint == key))
        count = s.scalar(select(func.count()).select_from(db.Student).where(db.Student.assignment_id == row.id))
        return Created(row.id, False, row.created, count)


@guarded
def find(settings: Settings, bound: Engine | None = None) -> Created | None:
    """The assignment these settings would create, if it exists already."""
    with db.session(bound) as s:
        row = s.scalar(select(db.Assignment).where(db.Assignment.fingerprint == fingerprint(settings)))
        if row is None:
            return None
        count = s.scalar(select(func.count()).select_from(db.Student).where(db.Student.assignment_id == row.id))
        return Created(row.id, False, row.created, count)


def create_assignment(settings: Settings, bound: Engine | None = None) -> int:
    """Create an assignment (no roster yet), or find the same one made already; its id."""
    return create(settings, (), bound).id


@guarded
def assignment(assignment_id: int, bound: Engine | None = None) -> Settings | None:
    with db.session(bound) as s:
        row = s.get(db.Assignment, assignment_id)
        return _settings(row) if row else None


@guarded
def assignments(bound: Engine | None = None, archived: bool = True) -> list[tuple[int, Settings]]:
    """Every assignment, newest first (without the archived ones if ``archived`` is False)."""
    with db.session(bound) as s:
        query = select(db.Assignment).order_by(db.Assignment.id.desc())
        if not archived:
            query = query.where(db.Assignment.status != "archived")
        return [(r.id, _settings(r)) for r in s.scalars(query)]


# -- changes, each logged and undoable

def _describe(name: str, before, after, zone: str) -> str:
    words = {"title": "title", "tolerance": "tolerance", "due": "due time", "attempts_allowed": "attempts per answer",
             "solution_before_due": "solution before the due time", "late_policy": "late policy",
             "late_value": "late value", "hints": "hints", "slip_names": "named slips",
             "answer_after_last": "answer after the last attempt", "timezone": "time zone", "status": "status",
             "parts": "problems, answers and weights", "extended_due": "extension", "extra_attempts": "extra attempts"}

    def show(v):
        if v is None:
            return "none"
        if isinstance(v, bool):
            return "on" if v else "off"
        if name in ("due", "extended_due"):
            return when_text(dt.datetime.fromisoformat(v), zone)
        if name == "tolerance":
            return f"±{v * 100:g} %"
        if name == "late_value":
            return f"{v * 100:g} %"
        return str(v)
    if name == "parts":
        return "; ".join(_parts_changed(before, after)) or "points unchanged"
    return f"{words.get(name, name)} {show(before)} → {show(after)}"


def _answer_named(problem: str, answer: str, in_a_set: bool) -> str:
    """An answer as the instructor's page calls it: its label (with its problem's title in a problem set)."""
    try:
        solver = registry.solver(problem)
    except KeyError:
        return f"{problem}/{answer}"
    headings = {a.name: a.heading for a in solver.ANSWERS} | {DIAGRAM: DIAGRAM_HEADING}
    label = f"“{headings.get(answer, answer)}”"
    return f"{solver.ABOUT.title}: {label}" if in_a_set else label


def _parts_changed(before: list[dict], after: list[dict]) -> list[str]:
    """What an edit of the problems, answers and points changed, answer by answer, in the page's words
    ("“Highest angle after the bounce” 1 → 2 points", "“Angle at impact” no longer counts")."""
    old = {p["problem"]: dict(zip(p["answers"], p["weights"])) for p in before}
    new = {p["problem"]: dict(zip(p["answers"], p["weights"])) for p in after}
    in_a_set = len(old) > 1 or len(new) > 1
    said = []
    for problem in list(old) + [p for p in new if p not in old]:
        if problem not in new or problem not in old:
            title = registry.solver(problem).ABOUT.title if problem in registry.PROBLEM_IDS else problem
            said.append(f"{title} {'removed' if problem not in new else 'added'}")
            continue
        for answer in list(old[problem]) + [a for a in new[problem] if a not in old[problem]]:
            name = _answer_named(problem, answer, in_a_set)
            was, now = old[problem].get(answer), new[problem].get(answer)
            if was is None:
                said.append(f"{name} counts ({_number(now)} point{'s' if now != 1 else ''})")
            elif now is None:
                said.append(f"{name} no longer counts")
            elif was != now:
                said.append(f"{name} {_number(was)} → {_number(now)} point{'s' if now != 1 else ''}")
    if not said and [p["problem"] for p in before] != [p["problem"] for p in after]:
        said.append("the problems' order changed")
    return said


@guarded
def edit(assignment_id: int, settings: Settings, bound: Engine | None = None,
         when: dt.datetime | None = None) -> list[str]:
    """Change an assignment's settings (a due time in the past is allowed: it closes the
    assignment early); log what changed. Return the changes in plain words (empty: nothing changed)."""
    if settings.errors():
        raise ValueError(" ".join(settings.errors()))
    with db.session(bound) as s, s.begin():
        row = s.get(db.Assignment, assignment_id)
        if row is None:
            raise ValueError("There is no such assignment.")
        return _apply(s, row, settings, when or now())


def _apply(s, row: db.Assignment, settings: Settings, when: dt.datetime, undoes: int | None = None) -> list[str]:
    old, new = _as_json(_settings(row)), _as_json(settings)
    changed = [k for k in EDITABLE if old[k] != new[k]]
    if not changed:
        return []
    said = [_describe(k, old[k], new[k], settings.timezone) for k in changed]
    action = ("undo" if undoes else {"closed": "closed", "archived": "archived"}.get(new["status"], "reopened")
              if changed == ["status"] else "edited")
    _store(row, settings)
    # Once changed (edited, closed, archived, undone) it is no longer what its first settings would
    # create: a later "Create" with those settings makes a new assignment, not a find of this one.
    row.fingerprint = None
    s.add(db.Change(assignment_id=row.id, at=when, action=action, label="",
                    summary=_storable("; ".join(said)[:1000], 1000), before={k: old[k] for k in changed},
                    after={k: new[k] for k in changed}, undoes=undoes))
    return said


def set_status(assignment_id: int, status: str, bound: Engine | None = None, when: dt.datetime | None = None) -> list[str]:
    """Close (answers checked, not recorded), reopen, or archive (hidden, closed) an assignment."""
    settings = assignment(assignment_id, bound)
    if settings is None:
        raise ValueError("There is no such assignment.")
    return edit(assignment_id, replace(settings, status=status), bound, when)


@guarded
def grant(assignment_id: int, label: str, *, extended_due: dt.datetime | None = None, extra_attempts: int = 0,
          bound: Engine | None = None, when: dt.datetime | None = None) -> str:
    """Give one student an extension (a later due time; None: none) and extra attempts per answer;
    logged. Returns what changed in plain words ("" for nothing)."""
    if extended_due is not None and extended_due.tzinfo is None:
        raise ValueError("The extension needs a time zone.")
    if not 0 <= extra_attempts <= 100:
        raise ValueError("Extra attempts are from 0 to 100 per answer.")
    with db.session(bound) as s, s.begin():
        student = s.scalar(select(db.Student).where(db.Student.assignment_id == assignment_id,
                                                    db.Student.label == label))
        if student is None:
            raise ValueError(f"{label!r} is not on this assignment's roster.")
        zone = s.scalar(select(db.Assignment.timezone).where(db.Assignment.id == assignment_id)) or "UTC"
        return _grant(s, student, extended_due.isoformat() if extended_due else None, extra_attempts,
                      when or now(), zone)


def _grant(s, student: db.Student, extended_due: str | None, extra: int, when: dt.datetime, zone: str,
           undoes: int | None = None) -> str:
    old = {"extended_due": student.extended_due.isoformat() if student.extended_due else None,
           "extra_attempts": student.extra_attempts}
    new = {"extended_due": extended_due, "extra_attempts": extra}
    changed = [k for k in old if old[k] != new[k]]
    if not changed:
        return ""
    student.extended_due = dt.datetime.fromisoformat(extended_due) if extended_due else None
    student.extra_attempts = extra
    said = f"{student.label}: " + "; ".join(_describe(k, old[k], new[k], zone) for k in changed)
    s.add(db.Change(assignment_id=student.assignment_id, at=when, action="undo" if undoes else "student",
                    label=student.label, summary=said, before={k: old[k] for k in changed},
                    after={k: new[k] for k in changed}, undoes=undoes))
    return said


@guarded
def undo(assignment_id: int, change_id: int, bound: Engine | None = None, when: dt.datetime | None = None) -> str:
    """Put back what a change replaced (itself a logged change). ValueError if it cannot be undone:
    the creation (archive the assignment instead), or a change whose fields have changed since."""
    when = when or now()
    with db.session(bound) as s, s.begin():
        change = s.get(db.Change, change_id)
        if change is None or change.assignment_id != assignment_id:
            raise ValueError("There is no such change.")
        if change.action == "created":
            raise ValueError("Creating cannot be undone: archive the assignment instead (that can be undone).")
        row = s.get(db.Assignment, assignment_id)
        if change.label:
            student = s.scalar(select(db.Student).where(db.Student.assignment_id == assignment_id,
                                                        db.Student.label == change.label))
            now_values = {"extended_due": student.extended_due.isoformat() if student.extended_due else None,
                          "extra_attempts": student.extra_attempts}
            if any(now_values[k] != v for k, v in change.after.items()):
                raise ValueError("That student's extension or attempts have changed since: undo the later change first.")
            values = now_values | change.before
            return _grant(s, student, values["extended_due"], values["extra_attempts"], when, row.timezone,
                          undoes=change.id)
        current = _as_json(_settings(row))
        if any(current[k] != v for k, v in change.after.items()):
            raise ValueError("Those settings have changed since: undo the later change first.")
        return "; ".join(_apply(s, row, _from_json(change.before, _settings(row)), when, undoes=change.id))


@dataclass(frozen=True)
class Logged:
    """One entry of an assignment's history."""
    id: int
    at: dt.datetime
    action: str
    label: str
    summary: str
    undoes: int | None
    undone: bool  # a later change undid it


@guarded
def history(assignment_id: int, bound: Engine | None = None) -> list[Logged]:
    """Every change to the assignment, newest first."""
    with db.session(bound) as s:
        rows = s.scalars(select(db.Change).where(db.Change.assignment_id == assignment_id)
                         .order_by(db.Change.id.desc())).all()
    undoers: dict[int, list[int]] = {}
    for r in rows:
        if r.undoes:
            undoers.setdefault(r.undoes, []).append(r.id)
    undone: dict[int, bool] = {}
    for r in rows:  # newest first: a change's undoers came after it, so are decided already
        undone[r.id] = any(not undone[u] for u in undoers.get(r.id, ()))  # an undone undo undoes nothing
    return [Logged(r.id, r.at, r.action, r.label, r.summary, r.undoes, undone[r.id]) for r in rows]


# -- rosters

def student_seed(assignment_id: int, label: str) -> int:
    """The student's variant number: fixed by the assignment, the label and the course secret. Its
    parameters come from the assignment stream (``identity.parameters``), not ``?seed=N``'s."""
    return signing.variant_key(assignment_id, label) % (MAX_SEED + 1)


def parse_roster(text: str) -> list[str]:
    """The labels of a roster CSV: one label per line, in the first column (a header cell "label"
    is skipped). ValueError names each bad line and each repeated label, in plain words."""
    if len(text) > MAX_ROSTER_TEXT:
        raise ValueError(f"The roster is too long ({len(text):,} characters; at most {MAX_ROSTER_TEXT:,}): "
                         "one short label per line.")
    labels, bad, first_line = [], [], {}
    repeated: list[str] = []
    reader = csv.reader(io.StringIO(text.replace("\x00", "")))
    n = 0
    while True:
        try:
            row = next(reader)
        except StopIteration:
            break
        except csv.Error:
            raise ValueError(f"Line {reader.line_num} cannot be read as CSV (a line far too long, or a quote "
                             "never closed): one label per line, in the first column.") from None
        n = reader.line_num
        cell = row[0].strip() if row else ""
        if not cell or (not labels and not bad and cell.lower() in ("label", "student", "code")):
            continue
        if not signing.valid_label(cell):
            bad.append(f"{n} (“{cell[:40]}{'…' if len(cell) > 40 else ''}”)")
        elif cell in first_line:
            repeated.append(f"{cell} (lines {first_line[cell]} and {n})")
        else:
            first_line[cell] = n
            labels.append(cell)
    problems = []
    if bad:
        lines = ", ".join(bad[:10]) + (" …" if len(bad) > 10 else "")
        problems.append(f"Line{'s' if len(bad) > 1 else ''} {lines}: a student label is {signing.LABEL_RULE}.")
    if repeated:
        problems.append(f"Repeated label{'s' if len(repeated) > 1 else ''}: {', '.join(repeated[:10])}"
                        f"{' …' if len(repeated) > 10 else ''}. Each student needs a label of their own.")
    if problems:
        raise ValueError(" ".join(problems))
    if not labels:
        raise ValueError("The roster has no labels: one label per line, in the first column.")
    if len(labels) > MAX_ROSTER:
        raise ValueError(f"At most {MAX_ROSTER} students per roster ({len(labels)} given).")
    return labels


@guarded
def enrol(assignment_id: int, labels: Iterable[str], bound: Engine | None = None) -> list[StudentIdentity]:
    """Add these labels to the roster (a label already there keeps its variant); return every
    student of the roster, in label order."""
    with db.session(bound) as s, s.begin():
        have = set(s.scalars(select(db.Student.label).where(db.Student.assignment_id == assignment_id)))
        added = []
        for label in labels:
            if label not in have:
                s.add(db.Student(assignment_id=assignment_id, label=label, seed=student_seed(assignment_id, label)))
                have.add(label)
                added.append(label)
        if added:
            s.add(db.Change(assignment_id=assignment_id, at=now(), action="roster", label="",
                            summary=_storable(f"Added {len(added)} student{'s' if len(added) != 1 else ''}: "
                                              + ", ".join(added[:20]) + (" …" if len(added) > 20 else ""), 1000),
                            before={}, after={"added": added}))
    return roster(assignment_id, bound)


@guarded
def roster(assignment_id: int, bound: Engine | None = None) -> list[StudentIdentity]:
    with db.session(bound) as s:
        rows = s.scalars(select(db.Student).where(db.Student.assignment_id == assignment_id).order_by(db.Student.label))
        return [StudentIdentity(assignment_id, r.label, r.seed) for r in rows]


@guarded
def enrolled(identity: StudentIdentity, bound: Engine | None = None) -> bool:
    """The identity's label is on the assignment's roster, with the identity's variant."""
    with db.session(bound) as s:
        return bool(s.scalar(select(exists().where(
            db.Student.assignment_id == identity.assignment_id, db.Student.label == identity.label,
            db.Student.seed == identity.seed))))


@dataclass(frozen=True)
class Grant:
    """What one student was given beyond the assignment's rules."""
    extended_due: dt.datetime | None = None
    extra_attempts: int = 0


def due_for(settings: Settings, grant: Grant) -> dt.datetime:
    return max(settings.due, grant.extended_due) if grant.extended_due else settings.due


def allowed_for(settings: Settings, grant: Grant) -> int:
    return settings.attempts_allowed + grant.extra_attempts


def _grants(s, assignment_id: int, label: str | None = None) -> dict[str, Grant]:
    query = select(db.Student).where(db.Student.assignment_id == assignment_id)
    if label is not None:
        query = query.where(db.Student.label == label)
    return {r.label: Grant(r.extended_due, r.extra_attempts) for r in s.scalars(query)}


# -- attempts

@dataclass(frozen=True)
class Recorded:
    """An attempt as the database holds it, with what follows from the ones before it and the rules."""
    id: int
    label: str
    number: int  # of this student's attempts at this answer, in the order recorded
    answer: str
    typed: str
    correct: bool
    slip: str
    at: dt.datetime
    late: bool  # after the student's due time (the assignment's, or their extension)
    solution_shown: bool
    over_limit: bool
    problem: str = ""
    late_by: dt.timedelta = dt.timedelta(0)
    credit: float = 0.0  # the fraction of the answer's points it earns (late credit included)
    message: str = ""
    repeated: bool = False  # the same text as the attempt before it: not recorded again
    after_right: bool = False  # an earlier attempt at this answer was right: this one earns nothing more

    @property
    def counts(self) -> bool:
        """It earns points (on time, or late with late credit)."""
        return self.credit > 0

    def marks(self) -> list[str]:
        return [m for m, on in (("late", self.late), ("over the limit", self.over_limit),
                                ("after the solution", self.solution_shown), ("already right", self.after_right)) if on]


def _numbered(rows: Iterable[db.Attempt], settings: Settings | None, grants: dict[str, Grant]) -> list[Recorded]:
    seen: Counter = Counter()
    right: set = set()  # the answers an earlier attempt got right: a later one earns nothing (no double credit)
    out = []
    default_problem = settings.problem if settings else ""
    for r in sorted(rows, key=lambda r: r.id):
        problem = r.problem or default_problem
        key = (r.label, problem, r.answer)
        seen[key] += 1
        n = seen[key]
        after_right = key in right
        if r.correct:
            right.add(key)
        grant = grants.get(r.label, Grant())
        if settings is None:
            out.append(Recorded(r.id, r.label, n, r.answer, r.typed, r.correct, r.slip, r.at, r.late,
                                r.solution_shown, False, problem, message=r.message))
            continue
        due = due_for(settings, grant)
        late_by = max(r.at - due, dt.timedelta(0))
        over = n > allowed_for(settings, grant)
        credit = (settings.late_credit(late_by) if r.correct and not over and not r.solution_shown and not after_right
                  else 0.0)
        out.append(Recorded(r.id, r.label, n, r.answer, r.typed, r.correct, r.slip, r.at, late_by > dt.timedelta(0),
                            r.solution_shown, over, problem, late_by, credit, r.message, after_right=after_right))
    return out


def _normal(typed: str) -> str:
    return " ".join(typed.split())


@guarded
def record_attempt(identity: StudentIdentity, answer: str, typed: str, correct: bool, message: str, slip: str = "",
                   bound: Engine | None = None, when: dt.datetime | None = None, problem: str | None = None,
                   reading: str = "") -> Recorded:
    """Write one attempt (an answer the judge could read) at ``answer`` of ``problem`` (the
    assignment's first problem by default); return it as recorded, once its transaction has
    committed. The same answer as the student's previous attempt at this answer is not recorded
    again: that attempt comes back, marked ``repeated``. The same answer: the same ``reading``
    (the judge's: the same value read, with the same verdict, however it was typed), or, where
    either has none, the same text. ``NotAccepted`` if the assignment is closed."""
    when = when or now()
    with db.session(bound) as s:
        with s.begin():
            row = s.get(db.Assignment, identity.assignment_id)
            if row is None:
                raise RecordingUnavailable("This assignment is not in the course's database, so nothing can be "
                                           "recorded for it. Ask your instructor.")
            # One student's attempts are written one at a time: on PostgreSQL two tabs sending the
            # same text at once would each miss the other's row (SQLite's BEGIN IMMEDIATE serialises).
            s.execute(select(db.Student.id).where(db.Student.assignment_id == identity.assignment_id,
                                                  db.Student.label == identity.label).with_for_update())
            settings = _settings(row)
            if not settings.accepting:
                raise NotAccepted(CLOSED)
            problem = problem or settings.problem
            part = settings.part(problem)
            if part is None or answer not in part.answers:
                raise ValueError(f"{problem}/{answer} is not an answer this assignment counts.")
            previous = s.scalar(select(db.Attempt).where(
                db.Attempt.assignment_id == identity.assignment_id, db.Attempt.label == identity.label,
                db.Attempt.problem == problem, db.Attempt.answer == answer).order_by(db.Attempt.id.desc()).limit(1))
            if previous is not None and (previous.reading == reading if previous.reading and reading else
                                         _normal(previous.typed) == _normal(_storable(typed, MAX_TYPED))):
                kept_id, repeated = previous.id, True
            else:
                grant = _grants(s, identity.assignment_id, identity.label).get(identity.label, Grant())
                shown = bool(s.scalar(select(exists().where(
                    db.Reveal.assignment_id == identity.assignment_id, db.Reveal.label == identity.label,
                    db.Reveal.problem == problem))))
                attempt = db.Attempt(assignment_id=identity.assignment_id, label=identity.label, problem=problem,
                                     answer=answer, typed=_storable(typed, MAX_TYPED), correct=bool(correct),
                                     message=_storable(message, 1000), slip=_storable(slip, 400), at=when,
                                     late=when > due_for(settings, grant), solution_shown=shown, reading=reading)
                s.add(attempt)
                s.flush()
                kept_id, repeated = attempt.id, False
            # Numbered in the same transaction: its commit alone decides "Recorded" (a read after it
            # could fail, and tell a student whose attempt was kept that it was not).
            mine = _attempts_in(s, identity)
        # committed: from here on the attempt is recorded
    kept = next(a for a in mine if a.id == kept_id)
    return replace(kept, repeated=repeated)


def record_checked(identity: StudentIdentity, problem: str, answer: str, typed: str, verdict,
                   bound: Engine | None = None, when: dt.datetime | None = None) -> Recorded | None:
    """Record a judged answer if it is an attempt: None, and nothing written, when the judge could
    not read it (``verdict.readable`` False: a syntax error, an unknown name, a unit of another
    dimension; the message explains it and it costs no attempt). What is stored as said is the
    message under the assignment's feedback policy."""
    if not getattr(verdict, "readable", True) or not typed.strip():
        return None
    return record_attempt(identity, answer, typed, verdict.correct, verdict.message, verdict.mistake, bound, when,
                          problem, getattr(verdict, "reading", ""))


@guarded
def record_reveal(identity: StudentIdentity, bound: Engine | None = None, when: dt.datetime | None = None,
                  problem: str | None = None) -> None:
    with db.session(bound) as s, s.begin():
        if problem is None:
            row = s.get(db.Assignment, identity.assignment_id)
            problem = _settings(row).problem if row else ""
        s.add(db.Reveal(assignment_id=identity.assignment_id, label=identity.label, problem=problem,
                        at=when or now()))


@guarded
def solution_shown(identity: StudentIdentity, bound: Engine | None = None, problem: str | None = None) -> bool:
    """The student opened the solution (of ``problem``; of any problem of the assignment if None)."""
    with db.session(bound) as s:
        where = [db.Reveal.assignment_id == identity.assignment_id, db.Reveal.label == identity.label]
        if problem is not None:
            where.append(db.Reveal.problem == problem)
        return bool(s.scalar(select(exists().where(*where))))


@guarded
def attempts_of(identity: StudentIdentity, bound: Engine | None = None) -> list[Recorded]:
    """One student's attempts at one assignment (every problem), in the order recorded."""
    with db.session(bound) as s:
        return _attempts_in(s, identity)


def _attempts_in(s, identity: StudentIdentity) -> list[Recorded]:
    row = s.get(db.Assignment, identity.assignment_id)
    settings = _settings(row) if row else None
    grants = _grants(s, identity.assignment_id, identity.label)
    rows = s.scalars(select(db.Attempt).where(db.Attempt.assignment_id == identity.assignment_id,
                                              db.Attempt.label == identity.label)).all()
    return _numbered(rows, settings, grants)


@guarded
def attempt_count(assignment_id: int, bound: Engine | None = None) -> int:
    with db.session(bound) as s:
        return s.scalar(select(func.count()).select_from(db.Attempt).where(db.Attempt.assignment_id == assignment_id))


# -- what a student is told

def slip_name(slip: str, telling: bool = False) -> str:
    """A slip's short name: its hint's first clause ("e where e² belongs", "A sign"), which gives no hint away.
    ``telling`` (the instructor's gradebook and statistics, where answers' slips are compared): a first clause of a
    word or two runs on to the next comma ("A sign: the rod reverses its direction of rotation at the bounce")."""
    generic = {"sign": "the sign", "rounded": "a rounded coefficient"}
    if slip in generic:
        return generic[slip]
    first, *rest = re.split(r"[:;.]", slip, maxsplit=1)
    if telling and rest and len(first.split()) <= 2 and (more := re.split(r"[,;.(]", rest[0], maxsplit=1)[0].strip()):
        return f"{first.strip()}: {more}"
    return first.strip()


def slip_shown(slip: str | None, settings: Settings) -> str:
    """A slip as a student's own list of attempts names it: as their feedback did (hints on, or slips named),
    else not at all."""
    return slip_name(slip) if slip and (settings.hints or settings.slip_names) else ""


def feedback(message: str, correct: bool, slip: str, settings: Settings | None) -> str:
    """What the student is told about a readable answer under the assignment's feedback policy
    (None: Practice, the whole message). Hints off: a slip's hint is not given, only its name (or,
    with named slips off too, only "Not right")."""
    if settings is None or correct or not slip or settings.hints:
        return message
    if settings.slip_names:
        return f"Not right: it looks like a known slip, “{slip_name(slip)}”. Check that step, then try again."
    return "Not right. Check each step, then try again."


# -- the gradebook

@dataclass
class Cell:
    """One student's record at one answer."""
    attempts: int = 0
    allowed: int = 0  # for this student (extra attempts included)
    first_right: int | None = None  # the number of the attempt that earns the credit
    first_right_at: dt.datetime | None = None
    credit: float = 0.0  # the fraction of the answer's points earned
    late_by: dt.timedelta = dt.timedelta(0)  # that attempt's lateness
    right_no_credit: int | None = None  # a right attempt that earns nothing (late, over the limit, after the solution)
    right_no_credit_at: dt.datetime | None = None
    no_credit_why: str = ""
    slips: list[str] = field(default_factory=list)  # short names, first seen first
    marked: int = 0  # attempts kept but marked (late, over the limit, after the solution)

    def right_at(self) -> int | None:
        """The number of the first attempt that was right (earning its points or not), or None."""
        return self.first_right if self.first_right is not None else self.right_no_credit

    def right_when(self) -> dt.datetime | None:
        """When that attempt was made."""
        return self.first_right_at if self.first_right is not None else self.right_no_credit_at

    def done(self) -> str:
        """The answer settled, in words for the student's banner ("done (right)", "done (right, 2 h
        late: no credit)"), or "" while no attempt has been right: after a right one, no later
        attempt can earn more (it is as late or later, as far over the limit, after the solution)."""
        if self.first_right is not None and self.credit >= 1:
            return "done (right)"
        if self.first_right is not None:
            return f"done (right, {duration_text(self.late_by)} late: {self.credit * 100:g} % credit)"
        if self.right_no_credit is not None:
            return f"done (right but {self.no_credit_why}: no credit)"
        return ""

    def status(self, settings: Settings) -> str:
        """The cell in words: "right at attempt 2", "right 1 day late (attempt 1): 80 %", "not right
        yet: 1 of 3 attempts used", "not right: 4 attempts, 3 allowed"."""
        if self.first_right is not None:
            if self.credit >= 1:
                return f"right at attempt {self.first_right}"
            return (f"right {duration_text(self.late_by)} late (attempt {self.first_right}): "
                    f"{self.credit * 100:g} % credit")
        if self.right_no_credit is not None:
            return f"right but {self.no_credit_why} (attempt {self.right_no_credit}): no credit"
        if not self.attempts:
            return "not tried"
        if self.attempts > self.allowed:  # (tries past the limit are kept, marked; or the limit was lowered)
            return f"not right: {self.attempts} attempts, {self.allowed} allowed"
        if self.attempts == self.allowed:
            return f"not right: all {self.allowed} attempts used"
        return f"not right yet: {self.attempts} of {self.allowed} attempts used"


def _cells(settings: Settings, grants: dict[str, Grant], labels: Iterable[str],
           attempts: Iterable[Recorded]) -> dict[tuple[str, str, str], Cell]:
    cells = {(label, p, a): Cell(allowed=allowed_for(settings, grants.get(label, Grant())))
             for label in labels for p, a in settings.questions}
    for attempt in attempts:
        key = (attempt.label, attempt.problem, attempt.answer)
        if key not in cells:
            if (attempt.problem, attempt.answer) not in settings.questions:
                continue  # an answer that no longer counts
            cells[key] = Cell(allowed=allowed_for(settings, grants.get(attempt.label, Grant())))
        cell = cells[key]
        cell.attempts += 1
        cell.marked += bool(attempt.marks())
        if attempt.slip and (name := slip_name(attempt.slip, telling=True)) not in cell.slips:
            cell.slips.append(name)
        if attempt.credit > cell.credit:
            cell.credit, cell.first_right, cell.first_right_at = attempt.credit, attempt.number, attempt.at
            cell.late_by = attempt.late_by
        elif attempt.correct and attempt.credit == 0 and cell.right_no_credit is None and not attempt.after_right:
            cell.right_no_credit, cell.right_no_credit_at = attempt.number, attempt.at
            cell.no_credit_why = ("over the limit" if attempt.over_limit else "after the solution"
                                  if attempt.solution_shown else f"{duration_text(attempt.late_by)} late")
    return cells


@dataclass
class Gradebook:
    settings: Settings
    students: list[StudentIdentity]
    cells: dict[tuple[str, str, str], Cell]  # (label, problem, answer) -> cell
    grants: dict[str, Grant] = field(default_factory=dict)
    assignment_id: int = 0

    def cell(self, label: str, question: Question) -> Cell:
        return self.cells.get((label, *question), Cell(allowed=allowed_for(self.settings, self.grants.get(label, Grant()))))

    def score(self, label: str) -> float:
        """Points earned: each answer's weight times the credit it earned."""
        total = sum(self.settings.weight(q) * self.cell(label, q).credit for q in self.settings.questions)
        return round(total, 4)

    def how(self, label: str, names: dict[Question, str] | None = None) -> str:
        """How the score was computed, in words: each answer that earned points (its points, times
        its late credit), summed; then the answers right but earning nothing, and why (late, over the
        limit, after the solution), so that a student who did the work is not read as one who did
        nothing. ``names``: how to call each answer (its name by default)."""
        terms, unpaid = [], []
        for q in self.settings.questions:
            c, w = self.cell(label, q), self.settings.weight(q)
            name = (names or {}).get(q, q[1])
            if c.credit <= 0:
                if c.right_no_credit is not None:
                    unpaid.append(f"{name} right but {c.no_credit_why}")
                continue
            term = f"{name} {_number(w)}" if c.credit >= 1 else f"{name} {_number(w)} × {c.credit * 100:g} % (late)"
            terms.append(term)
        earned = " + ".join(terms) if terms else "no points" if unpaid else "nothing yet"
        return (f"{earned} = {_number(self.score(label))} of {_number(self.settings.out_of)}"
                + (f" ({'; '.join(unpaid)}: no credit)" if unpaid else ""))

    def late_right(self, label: str) -> int:
        """Answers right only after the due time (with or without late credit)."""
        return sum((c := self.cell(label, q)).late_by > dt.timedelta(0) and c.first_right is not None
                   or "late" in c.no_credit_why for q in self.settings.questions)

    def statistics(self) -> dict[Question, list[str]]:
        """Per answer, lines such as "8 of 12 students who tried it (67 %) got it right in time",
        "2 more (17 %) right after the due time" and "42 % named the slip “e where e² belongs”"."""
        out = {}
        for q in self.settings.questions:
            tried = [s.label for s in self.students if self.cell(s.label, q).attempts]
            if not tried:
                out[q] = ["Nobody has tried it yet."]
                continue
            cells = [self.cell(label, q) for label in tried]
            on_time = sum(c.first_right is not None and c.credit >= 1 for c in cells)
            late = sum(c.first_right is not None and c.credit < 1 or "late" in c.no_credit_why for c in cells)
            other = sum(c.first_right is None and c.right_no_credit is not None and "late" not in c.no_credit_why
                        for c in cells)
            lines = [f"{on_time} of {len(tried)} student{'s' if len(tried) > 1 else ''} who tried it "
                     f"({_percent(on_time, len(tried))}) got it right in time."]
            if late:
                lines.append(f"{late} more ({_percent(late, len(tried))}) got it right after the due time "
                             f"({'late credit: ' + self.settings.late_rule() if self.settings.late_policy != 'none' else 'no late credit'}).")
            if other:
                lines.append(f"{other} got it right only over the attempt limit or after opening the solution (no credit).")
            named = Counter(slip for c in cells for slip in set(c.slips))
            for slip, n in named.most_common():
                lines.append(f"{_percent(n, len(tried))} named the slip “{slip}” ({n} of {len(tried)}).")
            out[q] = lines
        return out


@dataclass(frozen=True)
class PointsTaken:
    """A student whose share of the points an edit would lower: the points they have, and would have, each
    out of the assignment's points then."""
    label: str
    before: float
    out_of_before: float
    after: float
    out_of_after: float


def points_taken(assignment_id: int, settings: Settings | None = None, grants: dict[str, Grant] | None = None,
                 bound: Engine | None = None) -> list[PointsTaken]:
    """The students whose share of the points would drop under ``settings`` (an earlier due time, fewer
    attempts, a harsher late rule, an answer no longer counted…; a tolerance applies to answers checked after it) or ``grants`` (an extension taken back…), ordered by label. (Points
    doubled or halved everywhere lower no one.)"""
    now_, then = gradebook(assignment_id, bound), gradebook(assignment_id, bound, settings, grants)
    return lowered(now_, then) if now_ is not None and then is not None else []


def lowered(before: Gradebook, after: Gradebook) -> list[PointsTaken]:
    """The students whose share of the points is lower in ``after`` than in ``before``."""
    a, b = before.settings.out_of, after.settings.out_of
    return [PointsTaken(st.label, before.score(st.label), a, after.score(st.label), b) for st in before.students
            if after.score(st.label) * a < before.score(st.label) * b * (1 - 1e-9)]


def _percent(n: int, total: int) -> str:
    return f"{round(100 * n / total)} %"


@guarded
def gradebook(assignment_id: int, bound: Engine | None = None, settings: Settings | None = None,
              grants: dict[str, Grant] | None = None) -> Gradebook | None:
    """The assignment's gradebook; or, with ``settings`` or some students' ``grants``, what it would be under
    them (nothing stored: an edit's effect, asked before it is saved)."""
    with db.session(bound) as s:
        row = s.get(db.Assignment, assignment_id)
        if row is None:
            return None
        settings = settings or _settings(row)
        grants = {**_grants(s, assignment_id), **(grants or {})}
        students = [StudentIdentity(assignment_id, r.label, r.seed) for r in s.scalars(
            select(db.Student).where(db.Student.assignment_id == assignment_id).order_by(db.Student.label))]
        attempts = _numbered(s.scalars(select(db.Attempt).where(db.Attempt.assignment_id == assignment_id)).all(),
                             settings, grants)
    cells = _cells(settings, grants, [st.label for st in students], attempts)
    known = {st.label for st in students}
    students += [StudentIdentity(assignment_id, label, -1) for label in sorted({k[0] for k in cells} - known)]
    return Gradebook(settings, students, cells, grants, assignment_id)


@dataclass(frozen=True)
class Standing:
    """Where one student stands: the rules as they apply to them, and their cells."""
    settings: Settings
    grant: Grant
    attempts: list[Recorded]
    cells: dict[Question, Cell]

    @property
    def due(self) -> dt.datetime:
        return due_for(self.settings, self.grant)

    @property
    def allowed(self) -> int:
        return allowed_for(self.settings, self.grant)

    def left(self, question: Question) -> int:
        return max(self.allowed - self.cells[question].attempts, 0)

    def score(self) -> float:
        return round(sum(self.settings.weight(q) * c.credit for q, c in self.cells.items()), 4)


@guarded
def standing(identity: StudentIdentity, bound: Engine | None = None) -> Standing | None:
    with db.session(bound) as s:
        row = s.get(db.Assignment, identity.assignment_id)
        if row is None:
            return None
        settings = _settings(row)
        grants = _grants(s, identity.assignment_id, identity.label)
        rows = s.scalars(select(db.Attempt).where(db.Attempt.assignment_id == identity.assignment_id,
                                                  db.Attempt.label == identity.label)).all()
    attempts = _numbered(rows, settings, grants)
    cells = _cells(settings, grants, [identity.label], attempts)
    return Standing(settings, grants.get(identity.label, Grant()), attempts,
                    {(p, a): cells[(identity.label, p, a)] for p, a in settings.questions})


# -- CSV, safe to open in a spreadsheet

FORMULA_START = ("=", "+", "-", "@", "\t", "\r", "\n")
# A plain decimal number ("-1.2", "+3", "6.02e23"): a spreadsheet reads it as that number, never as
# a formula, so it needs no apostrophe (one would make a typed -1.2 text: '-1.2).
PLAIN_NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def safe_cell(value: object) -> object:
    """A cell a spreadsheet will not run as a formula: text starting with = + - @, a tab or a
    carriage return gets a leading apostrophe (OWASP's advice), unless it is a plain number;
    numbers stay numbers."""
    if isinstance(value, str) and value.startswith(FORMULA_START) and not PLAIN_NUMBER.fullmatch(value):
        return "'" + value
    return value


def safe_csv(header: list[str], rows: Iterable[list[object]]) -> str:
    out = io.StringIO()
    writer = csv.writer(out)
    writer.writerow([safe_cell(h) for h in header])
    for row in rows:
        writer.writerow([safe_cell(v) for v in row])
    return out.getvalue()


def _time(value: dt.datetime | None) -> str:
    """A time a spreadsheet reads as one (the column's name says UTC)."""
    return value.astimezone(dt.timezone.utc).strftime("%Y-%m-%d %H:%M:%S") if value else ""


def _points(x: float) -> float | int:
    x = round(x, 4)
    return int(x) if x == int(x) else x


def question_name(settings: Settings, question: Question) -> str:
    """An answer's column name: its name alone for one problem, problem/answer in a problem set."""
    return question[1] if len(settings.parts) == 1 else f"{question[0]}/{question[1]}"


def gradebook_csv(book: Gradebook, names: dict[Question, str] | None = None) -> str:
    """One row per student: label, variant, points, out of, percent, the answers right only after the
    due time, the extension, how the score was computed; then per answer (called by ``names``, as the
    page calls it, else by its id) the points earned and possible, the status in words, the first
    right attempt and its time (whether it earned points or not: a right-but-late answer's time is the
    student's evidence), the attempts used and allowed, and the slips named."""
    s = book.settings
    header = ["label", "seed", "score", "out_of", "percent", "right_but_late", "extension_until_utc", "how"]
    for q in s.questions:
        name = " ".join(names[q].split()) if names and q in names else question_name(s, q)
        header += [f"{name}:points", f"{name}:out_of", f"{name}:status", f"{name}:right_at_attempt", f"{name}:right_at_utc",
                   f"{name}:attempts_used", f"{name}:attempts_allowed", f"{name}:slips"]
    rows = []
    for student in book.students:
        grant = book.grants.get(student.label, Grant())
        score = book.score(student.label)
        row: list[object] = [student.label, student.seed if student.seed >= 0 else "", _points(score),
                             _points(s.out_of), _points(100 * score / s.out_of) if s.out_of else 0,
                             book.late_right(student.label), _time(grant.extended_due), book.how(student.label, names)]
        for q in s.questions:
            c = book.cell(student.label, q)
            row += [_points(s.weight(q) * c.credit), _points(s.weight(q)), c.status(s), c.right_at() or "",
                    _time(c.right_when()),
                    c.attempts, c.allowed, "; ".join(c.slips)]
        rows.append(row)
    return safe_csv(header, rows)


def lms_csv(book: Gradebook, lms: str = "canvas") -> str:
    """The score per student for an LMS's gradebook import. Canvas: its columns (Student, ID, SIS
    User ID, SIS Login ID, Section), the assignment as a column of points and a "Points Possible"
    row; the label goes in the SIS columns, so use your students' SIS ids (or login ids) as labels.
    Moodle: "ID number" (map it to the user's ID number) and the points."""
    title = " ".join(book.settings.title.split())
    scores = [(st.label, _points(book.score(st.label))) for st in book.students if st.seed >= 0]
    if lms == "moodle":
        return safe_csv(["ID number", title], ([label, score] for label, score in scores))
    header = ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", title]
    rows = [["Points Possible", "", "", "", "", _points(book.settings.out_of)]]
    rows += [[label, "", label, label, "", score] for label, score in scores]
    return safe_csv(header, rows)


@guarded
def attempts_csv(assignment_id: int, bound: Engine | None = None, names: dict[Question, str] | None = None) -> str:
    """Every attempt, as recorded (typed text included, neutralised), with what it earned; each answer by
    its ids and as the page names it (``names``)."""
    with db.session(bound) as s:
        row = s.get(db.Assignment, assignment_id)
        settings = _settings(row) if row else None
        grants = _grants(s, assignment_id)
        attempts = _numbered(s.scalars(select(db.Attempt).where(db.Attempt.assignment_id == assignment_id)).all(),
                             settings, grants)
    header = ["label", "problem", "answer", "answer_name", "attempt", "typed", "correct", "slip", "time_utc", "late",
              "late_hours", "over_limit", "solution_shown", "credit", "after_right"]  # (new columns last)
    named = names or {}
    return safe_csv(header, ([a.label, a.problem, a.answer, named.get((a.problem, a.answer), a.answer), a.number, a.typed, a.correct, a.slip, _time(a.at), a.late,
                              round(a.late_by.total_seconds() / 3600, 2), a.over_limit, a.solution_shown,
                              _points(a.credit), a.after_right] for a in attempts))


def history_csv(entries: list[Logged]) -> str:
    return safe_csv(["time_utc", "action", "student", "change", "undoes"],
                    ([_time(e.at), e.action, e.label, e.summary, e.undoes or ""] for e in reversed(entries)))
