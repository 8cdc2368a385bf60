"""Assignments in a real database, the same tests on SQLite and on PostgreSQL (tests/conftest.py's
``database`` fixture): the schema Alembic builds is the models', every attempt is kept and marked
(late, over the limit, after the solution), the gradebook counts by the rules, nothing is lost
under 200 concurrent submissions, a failed commit is never reported recorded, and the exports are
safe to open in a spreadsheet."""
from __future__ import annotations

import csv
import datetime as dt
import io
import threading

import pytest
from hypothesis import given
from hypothesis import strategies as hst
from sqlalchemy import event, select
from sqlalchemy.exc import OperationalError
from sqlalchemy.orm import Session

from assignments import db, migrate, records, signing
from assignments.identity import StudentIdentity
from solvers import registry
from scripts.live_app import free_port

UTC = dt.timezone.utc
DUE = dt.datetime(2026, 12, 1, 12, 0, tzinfo=UTC)
BEFORE, AFTER = DUE - dt.timedelta(days=1), DUE + dt.timedelta(minutes=1)
E_FOR_E2 = next(m.feedback for m in registry.solver("pendulum_rebound").MISTAKES if m.answer == "theta_rebound")


SECRET = "course-secret-for-the-tests-0018"


@pytest.fixture(autouse=True)
def course_secret(monkeypatch):
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)  # it keys the students' variants


def settings(**changes) -> records.Settings:
    base = records.Settings("Bounce", "pendulum_rebound", ("theta_rebound", "I_O"), 5e-3, DUE, 3, False)
    return records.Settings(**{**base.__dict__, **changes})


def new_assignment(database, labels=("s01", "s02"), **changes) -> tuple[int, list[StudentIdentity]]:
    aid = records.create_assignment(settings(**changes), database)
    return aid, records.enrol(aid, labels, database)


def attempt(database, who, answer="theta_rebound", correct=False, slip="", when=BEFORE, typed="1"):
    return records.record_attempt(who, answer, typed, correct, "message", slip, database, when)


def test_alembic_builds_the_models_schema_and_takes_it_down(database):
    from alembic.autogenerate import compare_metadata
    from alembic.migration import MigrationContext

    with database.connect() as connection:
        assert compare_metadata(MigrationContext.configure(connection, opts={"compare_type": True}),
                                db.Base.metadata) == []
    from alembic import command

    cfg = migrate.config()
    with database.begin() as connection:
        cfg.attributes["connection"] = connection
        command.downgrade(cfg, "base")
    with database.connect() as connection:
        assert set(database.dialect.get_table_names(connection)) <= {"alembic_version"}
    migrate.upgrade(database)
    assert records.assignments(database) == []


def test_attempts_are_kept_numbered_and_marked(database):
    aid, (ann, bob) = new_assignment(database, attempts_allowed=2)
    first = attempt(database, ann, slip=E_FOR_E2)
    second = attempt(database, ann, correct=True)
    third = attempt(database, ann, correct=True)
    assert (first.number, second.number, third.number) == (1, 2, 3)
    assert not first.counts and second.counts and third.over_limit and not third.counts
    late = attempt(database, bob, correct=True, when=AFTER)
    assert late.late and not late.counts  # kept, marked, not counted
    records.record_reveal(bob, database, BEFORE)
    shown = attempt(database, bob, answer="I_O", correct=True)
    assert shown.solution_shown and not shown.counts and shown.marks() == ["after the solution"]
    mine = records.attempts_of(ann, database)
    assert [a.number for a in mine] == [1, 2, 3] and [a.slip for a in mine] == [E_FOR_E2, "", ""]
    assert records.attempt_count(aid, database) == 5

    book = records.gradebook(aid, database)
    cell = book.cells[("s01", "theta_rebound")]
    assert (cell.first_right, cell.attempts, cell.marked, cell.slips) == (2, 3, 1, ["e where e² belongs"])
    assert book.score("s01") == 1 and book.score("s02") == 0
    assert book.cells[("s02", "theta_rebound")].first_right is None


def test_the_gradebooks_statistics_name_the_slips(database):
    labels = [f"s{n:02}" for n in range(5)]
    aid, students = new_assignment(database, labels)
    for who in students[:2]:  # two of five name the e-for-e² slip (one of them twice), then get it right
        attempt(database, who, slip=E_FOR_E2)
        attempt(database, who, slip=E_FOR_E2)
        attempt(database, who, correct=True)
    attempt(database, students[2], slip="sign")
    attempt(database, students[3], correct=True)
    attempt(database, students[4])
    lines = records.gradebook(aid, database).statistics()
    assert lines["theta_rebound"] == ["3 of 5 students who tried it (60 %) got it right within the rules.",
                                      "40 % named the slip “e where e² belongs” (2 of 5).",
                                      "20 % named the slip “the sign” (1 of 5)."]
    assert lines["I_O"] == ["Nobody has tried it yet."]


def test_two_hundred_concurrent_submissions_are_all_recorded(database):
    labels = [f"s{n:03}" for n in range(200)]
    aid, students = new_assignment(database, labels)
    start = threading.Barrier(len(students))
    outcomes: list = []

    def submit(who):
        start.wait()  # all 200 at once
        try:
            outcomes.append(attempt(database, who, correct=who.label.endswith("7"), typed=who.label))
        except Exception as error:  # noqa: BLE001 (counted below: the test says which failed and why)
            outcomes.append(error)

    threads = [threading.Thread(target=submit, args=(who,)) for who in students]
    for t in threads:
        t.start()
    for t in threads:
        t.join(120)
    failures = [o for o in outcomes if not isinstance(o, records.Recorded)]
    assert not failures and len(outcomes) == 200
    assert records.attempt_count(aid, database) == 200
    rows = list(csv.DictReader(io.StringIO(records.attempts_csv(aid, database))))
    assert sorted(r["typed"] for r in rows) == labels and sum(r["counts"] == "True" for r in rows) == 20


def test_a_failed_commit_is_never_reported_recorded(database):
    aid, (ann, _) = new_assignment(database)

    def connection_lost(session):
        raise OperationalError("COMMIT", {}, ConnectionError("server closed the connection unexpectedly"))

    event.listen(Session, "before_commit", connection_lost)
    try:
        with pytest.raises(records.RecordingUnavailable, match="not recorded"):
            attempt(database, ann, correct=True)
    finally:
        event.remove(Session, "before_commit", connection_lost)
    assert records.attempt_count(aid, database) == 0 and records.attempts_of(ann, database) == []


@pytest.mark.parametrize("url", ["sqlite:////dev/null/no-such-dir/db.sqlite", "postgresql"])
def test_a_database_that_is_down_says_so_in_plain_words(url, monkeypatch):
    if url == "postgresql":  # a port nothing listens on
        url = f"postgresql+psycopg://dl@127.0.0.1:{free_port()}/dl"
    monkeypatch.setenv(db.URL_ENV, url)
    db.engine.cache_clear()  # the process's engine, as the app gets it
    try:
        who = StudentIdentity(1, "s01", 1)
        with pytest.raises(records.RecordingUnavailable, match="cannot be reached.*Practice still works"):
            records.record_attempt(who, "theta_rebound", "1", True, "m")
        with pytest.raises(records.RecordingUnavailable):
            records.gradebook(1)
    finally:
        db.engine.cache_clear()


FORMULA_PREFIXES = ["=", "+", "-", "@", "\t", "\r", "\n"]  # typed here, not read from records


@pytest.mark.parametrize("prefix", FORMULA_PREFIXES)
def test_the_exports_neutralise_formula_cells(database, prefix):
    aid, (ann, _) = new_assignment(database)
    typed = f"{prefix}HYPERLINK(\"http://x\",\"y\")"
    attempt(database, ann, typed=typed, slip=f"{prefix}1+1")
    for text in (records.attempts_csv(aid, database), records.gradebook_csv(records.gradebook(aid, database))):
        cells = [c for row in csv.reader(io.StringIO(text)) for c in row]
        assert not [c for c in cells if c[:1] in FORMULA_PREFIXES]
    rows = list(csv.DictReader(io.StringIO(records.attempts_csv(aid, database))))
    assert rows[0]["typed"] == "'" + typed  # kept, readable, inert


@given(text=(hst.sampled_from(FORMULA_PREFIXES) | hst.characters()).flatmap(
    lambda first: hst.text(max_size=30).map(lambda rest: first + rest)) | hst.just(""))
def test_safe_cell_neutralises_exactly_the_formula_starts(text):
    safe = records.safe_cell(text)
    if text[:1] in FORMULA_PREFIXES:
        assert safe == "'" + text
    else:
        assert safe == text
    assert records.safe_cell(-1.5) == -1.5  # numbers stay numbers


def test_control_characters_are_stored_the_same_on_both_backends(database):
    """PostgreSQL's text cannot hold NUL (the insert failed and the student read "cannot be reached");
    SQLite can. Both store a control character (but tab, CR, LF) as U+FFFD, in what was typed, said and named."""
    aid, (ann, _) = new_assignment(database)
    kept = records.record_attempt(ann, "theta_rebound", "1\x00 m\x1b/s", False, "said\x00", "slip\x07", database, BEFORE)
    assert kept.typed == "1\ufffd m\ufffd/s" and kept.slip == "slip\ufffd"
    with Session(database) as s:
        assert s.scalars(select(db.Attempt.message)).one() == "said\ufffd"
    spaced = attempt(database, ann, typed="\t2\r\n")  # kept (and neutralised in the CSV)
    assert spaced.typed == "\t2\r\n"


def test_rosters_are_opaque_labels_with_bad_lines_named():
    assert records.parse_roster("label\ns01\ns02\n\ns01\n") == ["s01", "s02"]
    with pytest.raises(ValueError, match="Lines 2, 3: .*no names"):
        records.parse_roster("s01\nJane Doe\n=cmd()\n")
    with pytest.raises(ValueError, match="no labels"):
        records.parse_roster("label\n")


def test_each_student_gets_a_fixed_variant_of_their_own(database):
    aid, students = new_assignment(database, [f"s{n:02}" for n in range(30)])
    seeds = [s.seed for s in students]
    assert len(set(seeds)) == 30 and seeds == [records.student_seed(aid, s.label) for s in students]
    again = records.enrol(aid, ["s00", "s99"], database)  # re-enrolling keeps a student's variant
    assert {s.label: s.seed for s in again}["s00"] == seeds[0] and len(again) == 31
    assert records.enrolled(students[0], database)
    assert not records.enrolled(StudentIdentity(aid, "s00", seeds[0] + 1), database)


def test_a_variant_number_needs_the_course_secret(monkeypatch):
    """Keyed with the secret: another course's secret gives other numbers, so a classmate's cannot be
    worked out from their label; and without a secret there is none."""
    ours = [records.student_seed(1, f"s{n:02}") for n in range(20)]
    monkeypatch.setenv(signing.SECRET_ENV, SECRET + "-other")
    theirs = [records.student_seed(1, f"s{n:02}") for n in range(20)]
    assert len(set(ours)) == 20 and not set(ours) & set(theirs)
    monkeypatch.delenv(signing.SECRET_ENV)
    with pytest.raises(signing.NotConfigured):
        records.student_seed(1, "s00")


def test_settings_are_checked_in_plain_words(database):
    with pytest.raises(ValueError, match="at least one answer"):
        records.create_assignment(settings(answers=()), database)
    with pytest.raises(ValueError, match="1 to 100 attempts"):
        records.create_assignment(settings(attempts_allowed=0), database)


def test_the_migrate_command_makes_the_default_sqlite_file(tmp_path):
    import os
    import subprocess
    import sys

    from sqlalchemy import create_engine, inspect

    env = {k: v for k, v in os.environ.items() if k != db.URL_ENV} | {db.DATA_ENV: str(tmp_path / "volume")}
    done = subprocess.run([sys.executable, "-m", "assignments", "migrate"], cwd=db.ROOT, env=env,
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    engine = create_engine(f"sqlite:///{tmp_path / 'volume' / 'dynamics-lab.sqlite'}")
    assert {"assignment", "student", "attempt", "reveal"} <= set(inspect(engine).get_table_names())
    engine.dispose()


def test_replicas_starting_together_migrate_one_at_a_time(database):
    from alembic import command
    from concurrent.futures import ThreadPoolExecutor

    cfg = migrate.config()
    with database.begin() as connection:  # back to an empty database
        cfg.attributes["connection"] = connection
        command.downgrade(cfg, "base")
    with ThreadPoolExecutor(4) as pool:
        list(pool.map(lambda _: migrate.upgrade(database), range(4)))  # raises if any replica failed
    assert records.create_assignment(settings(), database) == 1
