"""The database: its tables, and the one engine per process.

SQLite by default, a file at ``DL_DATA_DIR/dynamics-lab.sqlite`` (``./data`` if unset; put it on a
volume), so ``make run`` needs nothing installed. ``DL_DATABASE_URL`` points elsewhere, e.g.
``postgresql+psycopg://user:password@db/dynamics_lab`` when replicas share one database. The
schema is created and upgraded by Alembic (``migrations/``, ``python -m assignments migrate``,
which serve.py runs before it listens), never by ``create_all`` in production.

Times are stored in UTC. On SQLite every transaction starts with ``BEGIN IMMEDIATE`` and waits up
to 15 s for the file's write lock, so concurrent submissions queue instead of failing."""
from __future__ import annotations

import datetime as dt
import functools
import os
import sqlite3
from pathlib import Path

from sqlalchemy import (JSON, Boolean, DateTime, Float, ForeignKey, Index, Integer, String, Text, UniqueConstraint,
                        create_engine, event, make_url)
from sqlalchemy.engine import Engine
from sqlalchemy.pool import QueuePool
from sqlalchemy.orm import DeclarativeBase, Mapped, mapped_column, sessionmaker
from sqlalchemy.types import TypeDecorator

ROOT = Path(__file__).resolve().parent.parent
URL_ENV, DATA_ENV = "DL_DATABASE_URL", "DL_DATA_DIR"


class UTCDateTime(TypeDecorator):
    """A timezone-aware UTC time on every backend (SQLite keeps no zone)."""
    impl = DateTime(timezone=True)
    cache_ok = True

    def process_bind_param(self, value, dialect):
        if value is not None and value.tzinfo is None:
            raise ValueError("store aware times only")
        return value.astimezone(dt.timezone.utc) if value is not None else None

    def process_result_value(self, value, dialect):
        if value is None:
            return None
        return value.replace(tzinfo=dt.timezone.utc) if value.tzinfo is None else value.astimezone(dt.timezone.utc)


class Base(DeclarativeBase):
    pass


class Assignment(Base):
    __tablename__ = "assignment"
    __table_args__ = (Index("uq_assignment_fingerprint", "fingerprint", unique=True),)
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    title: Mapped[str] = mapped_column(String(120))
    # The problems, in order: [{"problem": id, "answers": [name, ...], "weights": [number, ...]}]
    parts: Mapped[list] = mapped_column(JSON)
    tolerance: Mapped[float] = mapped_column(Float)  # relative, for numbers
    due: Mapped[dt.datetime] = mapped_column(UTCDateTime)
    attempts_allowed: Mapped[int] = mapped_column(Integer)  # per answer
    solution_before_due: Mapped[bool] = mapped_column(Boolean)
    created: Mapped[dt.datetime] = mapped_column(UTCDateTime)
    timezone: Mapped[str] = mapped_column(String(64), default="UTC")  # the instructor's, for times shown
    status: Mapped[str] = mapped_column(String(16), default="open")  # open, closed, archived
    late_policy: Mapped[str] = mapped_column(String(16), default="none")  # none, per_day, fixed
    late_value: Mapped[float] = mapped_column(Float, default=0.0)  # the penalty per day, or the fraction kept
    hints: Mapped[bool] = mapped_column(Boolean, default=True)  # a slip's hint shown to the student
    slip_names: Mapped[bool] = mapped_column(Boolean, default=True)  # a slip named (without its hint)
    answer_after_last: Mapped[bool] = mapped_column(Boolean, default=False)  # the value once attempts run out
    # What makes a repeated "Create" the same assignment (title, problems, due): unique.
    fingerprint: Mapped[str | None] = mapped_column(String(64), nullable=True)


class Student(Base):
    """One roster line: a label (the instructor's opaque code), its variant, and what the
    instructor granted this student alone."""
    __tablename__ = "student"
    __table_args__ = (UniqueConstraint("assignment_id", "label"),)
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignment.id", ondelete="CASCADE"), index=True)
    label: Mapped[str] = mapped_column(String(40))
    seed: Mapped[int] = mapped_column(Integer)
    extended_due: Mapped[dt.datetime | None] = mapped_column(UTCDateTime, nullable=True)  # an extension
    extra_attempts: Mapped[int] = mapped_column(Integer, default=0)  # per answer, on top of the rule


class Attempt(Base):
    """An answer the judge could read (a typo is never one), as the student gave it."""
    __tablename__ = "attempt"
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignment.id", ondelete="CASCADE"), index=True)
    label: Mapped[str] = mapped_column(String(40))
    problem: Mapped[str] = mapped_column(String(40))
    answer: Mapped[str] = mapped_column(String(40))
    typed: Mapped[str] = mapped_column(String(400))
    correct: Mapped[bool] = mapped_column(Boolean)
    message: Mapped[str] = mapped_column(String(1000))  # what the student was told
    slip: Mapped[str] = mapped_column(String(400), default="")  # the slip named, if any
    at: Mapped[dt.datetime] = mapped_column(UTCDateTime)
    # After the due time in force when it was made. What counts is decided when reading, against
    # the due time and the student's extension as they are then (an extension applies to the past).
    late: Mapped[bool] = mapped_column(Boolean)
    solution_shown: Mapped[bool] = mapped_column(Boolean)  # the student had seen this problem's solution
    # What the judge read (practice.judge.Verdict.reading): the same reading twice in a row is one attempt.
    reading: Mapped[str] = mapped_column(String(64), default="", server_default="")


class Reveal(Base):
    """A student asked for a problem's solution (their attempts at it after that are marked)."""
    __tablename__ = "reveal"
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignment.id", ondelete="CASCADE"), index=True)
    label: Mapped[str] = mapped_column(String(40))
    problem: Mapped[str] = mapped_column(String(40))
    at: Mapped[dt.datetime] = mapped_column(UTCDateTime)


class Change(Base):
    """Every change an instructor made to an assignment, with its time: what it was before and
    after (so it can be undone), kept for the gradebook's history."""
    __tablename__ = "assignment_change"
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignment.id", ondelete="CASCADE"), index=True)
    at: Mapped[dt.datetime] = mapped_column(UTCDateTime)
    action: Mapped[str] = mapped_column(String(40))  # created, edited, closed, reopened, archived, extension, ...
    label: Mapped[str] = mapped_column(String(40), default="")  # the student, for a per-student change
    summary: Mapped[str] = mapped_column(String(1000))  # in plain words
    before: Mapped[dict] = mapped_column(JSON)
    after: Mapped[dict] = mapped_column(JSON)
    undoes: Mapped[int | None] = mapped_column(Integer, nullable=True)  # the change this one undid


class LtiUsed(Base):
    """A one-time value already spent: an LTI launch's nonce, a hand-off into the page (replays refused)."""
    __tablename__ = "lti_used"
    key: Mapped[str] = mapped_column(String(200), primary_key=True)
    at: Mapped[dt.datetime] = mapped_column(UTCDateTime, index=True)


class LtiLink(Base):
    """An LMS resource link (one placement of an assignment in one course) and its grade column."""
    __tablename__ = "lti_link"
    __table_args__ = (UniqueConstraint("issuer", "deployment_id", "resource_link_id"),)
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignment.id", ondelete="CASCADE"), index=True)
    issuer: Mapped[str] = mapped_column(String(255))
    deployment_id: Mapped[str] = mapped_column(String(255))
    context_id: Mapped[str] = mapped_column(String(255), index=True)
    resource_link_id: Mapped[str] = mapped_column(String(255))
    lineitem: Mapped[str] = mapped_column(String(1000), default="")  # the AGS line item's URL, if any


class LtiMember(Base):
    """A student who arrived from an LMS: their label here, and the platform's opaque ``sub`` (needed to
    send their score back). A name only where the admin turned that on (DL_LTI_KEEP_NAMES=1)."""
    __tablename__ = "lti_member"
    __table_args__ = (UniqueConstraint("assignment_id", "label"),)
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignment.id", ondelete="CASCADE"), index=True)
    label: Mapped[str] = mapped_column(String(40))
    issuer: Mapped[str] = mapped_column(String(255))
    sub: Mapped[str] = mapped_column(String(255))
    name: Mapped[str] = mapped_column(String(200), default="")


class LtiScore(Base):
    """One student's score for the LMS: what was last sent, and what waits (retried with backoff)."""
    __tablename__ = "lti_score"
    __table_args__ = (UniqueConstraint("assignment_id", "label"),)
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    assignment_id: Mapped[int] = mapped_column(ForeignKey("assignment.id", ondelete="CASCADE"), index=True)
    label: Mapped[str] = mapped_column(String(40))
    status: Mapped[str] = mapped_column(String(16))  # waiting, sent, failed
    sent: Mapped[float | None] = mapped_column(Float, nullable=True)  # the best score the LMS has
    sent_progress: Mapped[str] = mapped_column(String(20), default="")
    tries: Mapped[int] = mapped_column(Integer, default=0)
    next_try: Mapped[dt.datetime] = mapped_column(UTCDateTime, index=True)
    error: Mapped[str] = mapped_column(String(1000), default="")


class RoomQuestion(Base):
    """One round of a question put to a lecture hall (room/): the problem, the question, the givens the
    room sees, and where it stands. Asking again after a discussion is the next round under the same code."""
    __tablename__ = "room_question"
    __table_args__ = (UniqueConstraint("code", "round"),)
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    code: Mapped[str] = mapped_column(String(8), index=True)  # what the room types (room.store.CODE_ALPHABET)
    round: Mapped[int] = mapped_column(Integer)  # 1, then 2 after a discussion, ...
    problem: Mapped[str] = mapped_column(String(40))
    question: Mapped[str] = mapped_column(String(60))  # room.questions.Question.key
    # Every given, in SI, as JSON text: μ = ∞ is a given (Infinity), which PostgreSQL's JSON type refuses.
    params: Mapped[str] = mapped_column(Text)
    system: Mapped[str] = mapped_column(String(4))  # the units the room reads: si or us
    hide_motion: Mapped[bool] = mapped_column(Boolean)  # the motion stays off the projector until the reveal
    status: Mapped[str] = mapped_column(String(12))  # open, closed, revealed, ended
    opened: Mapped[dt.datetime] = mapped_column(UTCDateTime, index=True)  # the lecture's date and time
    course: Mapped[str] = mapped_column(String(600), default="")  # an LMS course (issuer and context), if any


class RoomResponse(Base):
    """One browser session's answer to one round: only what it counts as (no name, address, device, or
    the text typed), and when it was last changed."""
    __tablename__ = "room_response"
    __table_args__ = (UniqueConstraint("question_id", "responder"),)
    id: Mapped[int] = mapped_column(Integer, primary_key=True)
    question_id: Mapped[int] = mapped_column(ForeignKey("room_question.id", ondelete="CASCADE"), index=True)
    responder: Mapped[str] = mapped_column(String(64))  # a hash of the browser session's random id
    category: Mapped[str] = mapped_column(String(200))  # right, a slip's name, other, or a choice's word
    at: Mapped[dt.datetime] = mapped_column(UTCDateTime)


def database_url() -> str:
    url = os.environ.get(URL_ENV, "").strip()
    if url:
        return url
    data = Path(os.environ.get(DATA_ENV) or ROOT / "data")
    return f"sqlite:///{data / 'dynamics-lab.sqlite'}"


class DatabaseGone(OSError):
    """The SQLite file this engine opened was removed or replaced: nothing is written in its place."""


def sqlite_path(url: str) -> Path | None:
    """The file of a SQLite URL (None for another backend or an in-memory database)."""
    if not url.startswith("sqlite"):
        return None
    path = url.split("///", 1)[1] if "///" in url else ""
    return Path(path) if path and path != ":memory:" else None


def make_engine(url: str, create: bool = True) -> Engine:
    """An engine with this project's settings (pool checks, SQLite's locking).

    A SQLite file is created only by an engine made with ``create`` (the migration's), and only
    before its first connection: from then on every connection and every commit checks that the file
    is still the one first opened. A file removed under a running server (its directory deleted, a
    volume gone) would otherwise take writes into an unlinked inode, committed and lost, while the
    student read "Recorded"; here the commit fails, and the student reads "not recorded"."""
    path = sqlite_path(url)
    if path is not None:
        return _sqlite_file_engine(path, create)
    if url.startswith("sqlite"):
        return create_engine(url)
    connect_args = {"connect_timeout": 5} if url.startswith("postgresql") else {}
    return create_engine(url, pool_pre_ping=True, pool_size=10, max_overflow=20, pool_timeout=60,
                         connect_args=connect_args)


def _sqlite_file_engine(path: Path, create: bool) -> Engine:
    if create:
        path.parent.mkdir(parents=True, exist_ok=True)
    first: list[tuple[int, int]] = []  # (device, inode) of the file at the first connection

    def still_there() -> None:
        try:
            stat = os.stat(path)
        except OSError as error:
            raise DatabaseGone(f"the database file {path} is gone") from error
        if first and (stat.st_dev, stat.st_ino) != first[0]:
            raise DatabaseGone(f"the database file {path} was replaced while the app ran")

    def connect():
        mode = "rwc" if create and not first else "rw"
        connection = sqlite3.connect(f"{path.resolve().as_uri()}?mode={mode}", uri=True, timeout=15,
                                     check_same_thread=False)
        try:
            still_there()
        except DatabaseGone:
            connection.close()
            raise
        if not first:
            stat = os.stat(path)
            first.append((stat.st_dev, stat.st_ino))
        return connection

    engine = create_engine("sqlite://", creator=connect, poolclass=QueuePool, pool_size=10, max_overflow=20,
                           pool_timeout=60)

    @event.listens_for(engine, "connect")
    def _sqlite_connect(dbapi_connection, _record):
        dbapi_connection.isolation_level = None  # SQLAlchemy's BEGIN below, not the driver's
        cursor = dbapi_connection.cursor()
        cursor.execute("PRAGMA journal_mode=WAL")  # readers never wait for a writer
        cursor.execute("PRAGMA foreign_keys=ON")
        cursor.execute("PRAGMA busy_timeout=15000")
        cursor.close()

    @event.listens_for(engine, "begin")
    def _sqlite_begin(connection):
        # Take the write lock at the start: a deferred transaction that reads, then writes, can
        # fail at once with "database is locked" when another writer got in between.
        connection.exec_driver_sql("BEGIN IMMEDIATE")

    @event.listens_for(engine, "commit")
    def _sqlite_commit(_connection):
        still_there()  # raised before COMMIT: the transaction is rolled back, nothing recorded
    return engine


def described() -> str:
    """The app's database for a log line: its URL without the password."""
    return make_url(database_url()).render_as_string(hide_password=True)


@functools.cache
def engine() -> Engine:
    """The process's engine (one pool per process), for ``database_url()``. It never creates a
    SQLite file: ``migrate.upgrade`` does, once, where the start-up checks allow it."""
    return make_engine(database_url(), create=False)


@functools.cache
def _sessions(bound: Engine) -> sessionmaker:
    return sessionmaker(bound, expire_on_commit=False)


def session(bound: Engine | None = None):
    return _sessions(bound or engine())()
