"""Every read and write of assignments, rosters and attempts, and the gradebook made from them.

An attempt is written in one transaction and reported recorded only once that transaction has
committed; any database failure becomes ``RecordingUnavailable`` with a message for the student
(the page then judges the answer anyway and says it was not recorded). What counts is decided when
reading, from the attempts in the order they were recorded (one source of truth): an attempt counts
if it is right, on time, within the attempts allowed for its answer, and made before the student
asked for the solution. Late and over-limit attempts are kept, and marked."""
from __future__ import annotations

import csv
import datetime as dt
import functools
import io
import logging
import re
from collections import Counter
from dataclasses import dataclass, field
from typing import Callable, Iterable, TypeVar

from sqlalchemy import exists, func, select
from sqlalchemy.engine import Engine
from sqlalchemy.exc import SQLAlchemyError

from assignments import db, signing
from assignments.identity import StudentIdentity
from practice.variants import MAX_SEED

log = logging.getLogger("dynamics_lab.records")
MAX_TYPED = 400
MAX_ROSTER = 2000
T = TypeVar("T")


class RecordingUnavailable(RuntimeError):
    """The database could not be reached or refused the write; nothing was recorded."""


UNAVAILABLE = ("The course's gradebook database cannot be reached right now, so this was not recorded. "
               "Practice still works; try again in a few minutes for your attempts to count.")


def _guarded(fn: Callable[..., T]) -> Callable[..., T]:
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


# -- assignments and rosters

@dataclass(frozen=True)
class Settings:
    """What the instructor chooses for an assignment."""
    title: str
    problem: str
    answers: tuple[str, ...]  # the answers that count
    tolerance: float  # relative, for typed numbers
    due: dt.datetime  # aware
    attempts_allowed: int  # per answer
    solution_before_due: bool

    def errors(self) -> list[str]:
        """What is wrong with these settings, in plain words (empty when they are fine)."""
        wrong = []
        if not self.title.strip() or len(self.title) > 120:
            wrong.append("The title needs 1 to 120 characters.")
        if not self.answers:
            wrong.append("Choose at least one answer that counts.")
        if not 1e-4 <= self.tolerance <= 0.1:
            wrong.append("The tolerance is between 0.01 % and 10 %.")
        if not 1 <= self.attempts_allowed <= 100:
            wrong.append("Allow from 1 to 100 attempts per answer.")
        if self.due.tzinfo is None:
            wrong.append("The due time needs a time zone.")
        return wrong


@_guarded
def create_assignment(settings: Settings, bound: Engine | None = None) -> int:
    if settings.errors():
        raise ValueError(" ".join(settings.errors()))
    with db.session(bound) as s, s.begin():
        row = db.Assignment(title=_storable(settings.title.strip(), 120), problem=settings.problem,
                            answers=list(settings.answers),
                            tolerance=settings.tolerance, due=settings.due, attempts_allowed=settings.attempts_allowed,
                            solution_before_due=settings.solution_before_due, created=now())
        s.add(row)
        s.flush()
        return row.id


def _settings(row: db.Assignment) -> Settings:
    return Settings(row.title, row.problem, tuple(row.answers), row.tolerance, row.due, row.attempts_allowed,
                    row.solution_before_due)


@_guarded
def assignment(assignment_id: int, bound: Engine | None = None) -> Settings | None:
    with db.session(bound) as s:
        row = s.get(db.Assignment, assignment_id)
        return _settings(row) if row else None


@_guarded
def assignments(bound: Engine | None = None) -> list[tuple[int, Settings]]:
    """Every assignment, newest first."""
    with db.session(bound) as s:
        return [(r.id, _settings(r)) for r in s.scalars(select(db.Assignment).order_by(db.Assignment.id.desc()))]


def student_seed(assignment_id: int, label: str) -> int:
    """The student's variant number: fixed by the assignment, the label and the course secret. Its
    parameters come from the assignment stream (``identity.parameters``), not ``?seed=N``'s."""
    return signing.variant_key(assignment_id, label) % (MAX_SEED + 1)


def parse_roster(text: str) -> list[str]:
    """The labels of a roster CSV: one label per line, in the first column (a header cell "label"
    is skipped); ValueError names each bad line. Duplicates are kept once."""
    labels, bad = [], []
    for n, row in enumerate(csv.reader(io.StringIO(text)), start=1):
        cell = row[0].strip() if row else ""
        if not cell or (n == 1 and cell.lower() in ("label", "student", "code")):
            continue
        if signing.valid_label(cell):
            labels.append(cell)
        else:
            bad.append(n)
    if bad:
        lines = ", ".join(map(str, bad[:10])) + (" …" if len(bad) > 10 else "")
        raise ValueError(f"Line{'s' if len(bad) > 1 else ''} {lines}: a student label is {signing.LABEL_RULE}.")
    labels = list(dict.fromkeys(labels))
    if not labels:
        raise ValueError("The roster has no labels: one label per line, in the first column.")
    if len(labels) > MAX_ROSTER:
        raise ValueError(f"At most {MAX_ROSTER} students per roster.")
    return labels


@_guarded
def enrol(assignment_id: int, labels: Iterable[str], bound: Engine | None = None) -> list[StudentIdentity]:
    """Add these labels to the roster (a label already there keeps its variant); return every
    student of the roster, in label order."""
    with db.session(bound) as s, s.begin():
        have = set(s.scalars(select(db.Student.label).where(db.Student.assignment_id == assignment_id)))
        for label in labels:
            if label not in have:
                s.add(db.Student(assignment_id=assignment_id, label=label, seed=student_seed(assignment_id, label)))
                have.add(label)
    return roster(assignment_id, bound)


@_guarded
def roster(assignment_id: int, bound: Engine | None = None) -> list[StudentIdentity]:
    with db.session(bound) as s:
        rows = s.scalars(select(db.Student).where(db.Student.assignment_id == assignment_id).order_by(db.Student.label))
        return [StudentIdentity(assignment_id, r.label, r.seed) for r in rows]


@_guarded
def enrolled(identity: StudentIdentity, bound: Engine | None = None) -> bool:
    """The identity's label is on the assignment's roster, with the identity's variant."""
    with db.session(bound) as s:
        return bool(s.scalar(select(exists().where(
            db.Student.assignment_id == identity.assignment_id, db.Student.label == identity.label,
            db.Student.seed == identity.seed))))


# -- attempts

@dataclass(frozen=True)
class Recorded:
    """An attempt as the database holds it, with what follows from the ones before it."""
    id: int
    label: str
    number: int  # of this student's attempts at this answer, in the order recorded
    answer: str
    typed: str
    correct: bool
    slip: str
    at: dt.datetime
    late: bool
    solution_shown: bool
    over_limit: bool

    @property
    def counts(self) -> bool:
        return self.correct and not (self.late or self.over_limit or self.solution_shown)

    def marks(self) -> list[str]:
        return [m for m, on in (("late", self.late), ("over the limit", self.over_limit),
                                ("after the solution", self.solution_shown)) if on]


def _numbered(rows: Iterable[db.Attempt], allowed: int) -> list[Recorded]:
    seen: Counter = Counter()
    out = []
    for r in sorted(rows, key=lambda r: r.id):
        seen[(r.label, r.answer)] += 1
        n = seen[(r.label, r.answer)]
        out.append(Recorded(r.id, r.label, n, r.answer, r.typed, r.correct, r.slip, r.at, r.late, r.solution_shown, n > allowed))
    return out


@_guarded
def record_attempt(identity: StudentIdentity, answer: str, typed: str, correct: bool, message: str, slip: str = "",
                   bound: Engine | None = None, when: dt.datetime | None = None) -> Recorded:
    """Write one attempt; return it as recorded, once its transaction has committed."""
    when = when or now()
    with db.session(bound) as s:
        with s.begin():
            due = s.scalar(select(db.Assignment.due).where(db.Assignment.id == identity.assignment_id))
            if due is None:
                raise RecordingUnavailable("This assignment is not in the course's database, so nothing can be "
                                           "recorded for it. Ask your instructor.")
            shown = bool(s.scalar(select(exists().where(db.Reveal.assignment_id == identity.assignment_id,
                                                        db.Reveal.label == identity.label))))
            row = db.Attempt(assignment_id=identity.assignment_id, label=identity.label, answer=answer,
                             typed=_storable(typed, MAX_TYPED), correct=bool(correct), message=_storable(message, 1000),
                             slip=_storable(slip, 400),
                             at=when, late=when > due, solution_shown=shown)
            s.add(row)
            s.flush()
            # Numbered in the same transaction: its commit alone decides "Recorded" (a read after it
            # could fail, and tell a student whose attempt was kept that it was not).
            mine = _attempts_in(s, identity)
        # committed: from here on the attempt is recorded
    return next(a for a in mine if a.id == row.id)


@_guarded
def record_reveal(identity: StudentIdentity, bound: Engine | None = None, when: dt.datetime | None = None) -> None:
    with db.session(bound) as s, s.begin():
        s.add(db.Reveal(assignment_id=identity.assignment_id, label=identity.label, at=when or now()))


@_guarded
def solution_shown(identity: StudentIdentity, bound: Engine | None = None) -> bool:
    with db.session(bound) as s:
        return bool(s.scalar(select(exists().where(db.Reveal.assignment_id == identity.assignment_id,
                                                   db.Reveal.label == identity.label))))


@_guarded
def attempts_of(identity: StudentIdentity, bound: Engine | None = None) -> list[Recorded]:
    """One student's attempts at one assignment, in the order recorded."""
    with db.session(bound) as s:
        return _attempts_in(s, identity)


def _attempts_in(s, identity: StudentIdentity) -> list[Recorded]:
    allowed = s.scalar(select(db.Assignment.attempts_allowed).where(db.Assignment.id == identity.assignment_id))
    rows = s.scalars(select(db.Attempt).where(db.Attempt.assignment_id == identity.assignment_id,
                                              db.Attempt.label == identity.label)).all()
    return _numbered(rows, allowed or 0)


@_guarded
def attempt_count(assignment_id: int, bound: Engine | None = None) -> int:
    with db.session(bound) as s:
        return s.scalar(select(func.count()).select_from(db.Attempt).where(db.Attempt.assignment_id == assignment_id))


# -- the gradebook

def slip_name(slip: str) -> str:
    """A slip's short name: its hint's first clause ("e where e² belongs", "A sign")."""
    generic = {"sign": "the sign", "rounded": "a rounded coefficient"}
    if slip in generic:
        return generic[slip]
    return re.split(r"[:;.]", slip, maxsplit=1)[0].strip()


@dataclass
class Cell:
    """One student's record at one answer."""
    attempts: int = 0
    first_right: int | None = None  # the number of the first attempt that counts
    first_right_at: dt.datetime | None = None
    slips: list[str] = field(default_factory=list)  # short names, first seen first
    marked: int = 0  # attempts kept but marked (late, over the limit, after the solution)


@dataclass
class Gradebook:
    settings: Settings
    students: list[StudentIdentity]
    cells: dict[tuple[str, str], Cell]  # (label, answer) -> cell

    def score(self, label: str) -> int:
        return sum(self.cells.get((label, a), Cell()).first_right is not None for a in self.settings.answers)

    def statistics(self) -> dict[str, list[str]]:
        """Per answer, lines such as "8 of 12 students who tried it (67 %) got it right in time" and
        "42 % named the slip “e where e² belongs”"."""
        out = {}
        for answer in self.settings.answers:
            tried = [s.label for s in self.students if self.cells.get((s.label, answer), Cell()).attempts]
            lines = []
            if not tried:
                out[answer] = ["Nobody has tried it yet."]
                continue
            right = sum(self.cells[(label, answer)].first_right is not None for label in tried)
            lines.append(f"{right} of {len(tried)} students who tried it ({_percent(right, len(tried))}) "
                         "got it right within the rules.")
            named = Counter(slip for label in tried for slip in set(self.cells[(label, answer)].slips))
            for slip, n in named.most_common():
                lines.append(f"{_percent(n, len(tried))} named the slip “{slip}” ({n} of {len(tried)}).")
            out[answer] = lines
        return out


def _percent(n: int, total: int) -> str:
    return f"{round(100 * n / total)} %"


@_guarded
def gradebook(assignment_id: int, bound: Engine | None = None) -> Gradebook | None:
    with db.session(bound) as s:
        row = s.get(db.Assignment, assignment_id)
        if row is None:
            return None
        settings = _settings(row)
        students = [StudentIdentity(assignment_id, r.label, r.seed) for r in s.scalars(
            select(db.Student).where(db.Student.assignment_id == assignment_id).order_by(db.Student.label))]
        attempts = _numbered(s.scalars(select(db.Attempt).where(db.Attempt.assignment_id == assignment_id)).all(),
                             settings.attempts_allowed)
    cells = {(st.label, a): Cell() for st in students for a in settings.answers}
    for attempt in attempts:
        cell = cells.setdefault((attempt.label, attempt.answer), Cell())
        cell.attempts += 1
        cell.marked += bool(attempt.marks())
        if attempt.slip and (name := slip_name(attempt.slip)) not in cell.slips:
            cell.slips.append(name)
        if attempt.counts and cell.first_right is None:
            cell.first_right, cell.first_right_at = attempt.number, attempt.at
    known = {st.label for st in students}
    students += [StudentIdentity(assignment_id, label, -1) for label in sorted({l for l, _ in cells} - known)]
    return Gradebook(settings, students, cells)


# -- CSV, safe to open in a spreadsheet

FORMULA_START = ("=", "+", "-", "@", "\t", "\r", "\n")


def safe_cell(value: object) -> object:
    """A cell a spreadsheet will not run as a formula: text starting with = + - @, a tab or a
    carriage return gets a leading apostrophe (OWASP's advice); numbers stay numbers."""
    if isinstance(value, str) and value.startswith(FORMULA_START):
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
    return value.strftime("%Y-%m-%d %H:%M:%S UTC") if value else ""


def gradebook_csv(book: Gradebook) -> str:
    """One row per student: label, variant, score, then per answer the first attempt that counts,
    its time, the attempts used, the marked ones and the slips named."""
    header = ["label", "seed", "score", "out_of"]
    for a in book.settings.answers:
        header += [f"{a}:first_right_attempt", f"{a}:first_right_at", f"{a}:attempts", f"{a}:marked", f"{a}:slips"]
    rows = []
    for student in book.students:
        row: list[object] = [student.label, student.seed if student.seed >= 0 else "", book.score(student.label),
                             len(book.settings.answers)]
        for a in book.settings.answers:
            c = book.cells.get((student.label, a), Cell())
            row += [c.first_right or "", _time(c.first_right_at), c.attempts, c.marked, "; ".join(c.slips)]
        rows.append(row)
    return safe_csv(header, rows)


@_guarded
def attempts_csv(assignment_id: int, bound: Engine | None = None) -> str:
    """Every attempt, as recorded (typed text included, neutralised)."""
    with db.session(bound) as s:
        allowed = s.scalar(select(db.Assignment.attempts_allowed).where(db.Assignment.id == assignment_id)) or 0
        attempts = _numbered(s.scalars(select(db.Attempt).where(db.Attempt.assignment_id == assignment_id)).all(),
                             allowed)
    header = ["label", "answer", "attempt", "typed", "correct", "slip", "time", "late", "over_limit",
              "solution_shown", "counts"]
    return safe_csv(header, ([a.label, a.answer, a.number, a.typed, a.correct, a.slip, _time(a.at), a.late, a.over_limit,
                          a.solution_shown, a.counts] for a in attempts))
