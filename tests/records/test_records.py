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
from concurrent.futures import ThreadPoolExecutor

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
DUE = (dt.datetime.now(UTC) + dt.timedelta(days=30)).replace(hour=12, minute=0, second=0, microsecond=0)
BEFORE, AFTER = DUE - dt.timedelta(days=1), DUE + dt.timedelta(minutes=1)
THETA = ("pendulum_rebound", "theta_rebound")
E_FOR_E2 = next(m.feedback for m in registry.solver("pendulum_rebound").MISTAKES if m.answer == "theta_rebound")


SECRET = "course-secret-for-the-tests-0018"


@pytest.fixture(autouse=True)
def course_secret(monkeypatch):
    monkeypatch.setenv(signing.SECRET_ENV, SECRET)  # it keys the students' variants


def settings(**changes) -> records.Settings:
    base = records.Settings.of("Bounce", "pendulum_rebound", ("theta_rebound", "I_O"), 5e-3, DUE, 3, False)
    return records.replace(base, **changes)


def new_assignment(database, labels=("s01", "s02"), **changes) -> tuple[int, list[StudentIdentity]]:
    aid = records.create(settings(**changes), labels, database).id
    return aid, records.roster(aid, database)


_typed = iter(range(10**6))


def attempt(database, who, answer="theta_rebound", correct=False, slip="", when=BEFORE, typed=None):
    """One readable attempt; a different text each time unless ``typed`` is given."""
    typed = f"{next(_typed)}.5" if typed is None else typed
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
    cell = book.cell("s01", THETA)
    assert (cell.first_right, cell.attempts, cell.marked, cell.slips) == (2, 3, 1, ["e where e² belongs"])
    assert book.score("s01") == 1 and book.score("s02") == 0
    assert book.cell("s02", THETA).first_right is None


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
    assert lines[THETA] == ["3 of 5 students who tried it (60 %) got it right in time.",
                            "40 % named the slip “e where e² belongs” (2 of 5).",
                            "20 % named the slip “the sign” (1 of 5)."]
    assert lines[("pendulum_rebound", "I_O")] == ["Nobody has tried it yet."]


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
    assert sorted(r["typed"] for r in rows) == labels and sum(r["credit"] == "1" for r in rows) == 20


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
    if text[:1] in FORMULA_PREFIXES and not records.PLAIN_NUMBER.fullmatch(text):
        assert safe == "'" + text
    else:
        assert safe == text
    assert records.safe_cell(-1.5) == -1.5  # numbers stay numbers
    for number in ("-1.2", "+3", "-.5e-3"):  # typed numbers open as numbers, not as the text '-1.2
        assert records.safe_cell(number) == number


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
    assert records.parse_roster("label\ns01\ns02\n\ns03\n") == ["s01", "s02", "s03"]
    with pytest.raises(ValueError, match=r"Repeated label: s01 \(lines 2 and 5\)"):  # was dropped silently
        records.parse_roster("label\ns01\ns02\n\ns01\n")
    with pytest.raises(ValueError, match=r"Lines 2 \(“Jane Doe”\), 3 \(“=cmd\(\)”\): .*no names"):
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
        records.create_assignment(settings(parts=(records.Part("pendulum_rebound", ()),)), database)
    with pytest.raises(ValueError, match="already past"):  # was accepted silently
        records.create_assignment(settings(due=dt.datetime.now(UTC) - dt.timedelta(minutes=5)), database)
    with pytest.raises(ValueError, match="not a time zone"):
        records.create_assignment(settings(timezone="Mars/Olympus"), database)
    with pytest.raises(ValueError, match="penalty per day"):
        records.create_assignment(settings(late_policy="per_day", late_value=0), database)
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


# -- issue 26: typos cost nothing, late work is visible, every slip is undoable

def test_an_unreadable_answer_is_never_an_attempt(database):
    """The judge's unreadable verdicts (a syntax error, an unknown name, a unit of another
    dimension) are explained and never recorded or counted; two typos then the right answer is
    attempt 1, and counts."""
    from practice.judge import Judge
    from solvers import pendulum_rebound
    from assignments.identity import parameters

    aid, (ann, _) = new_assignment(database, attempts_allowed=1)
    solution = pendulum_rebound.solve(**parameters(ann, pendulum_rebound, "pendulum_rebound"))
    answer = next(a for a in pendulum_rebound.ANSWERS if a.name == "theta_rebound")
    judge = Judge(solution, pendulum_rebound.derivation_of(solution), [answer])
    for typo in ("hello", "w", "(1 + 2", "3 kg", "sqrt(-1)"):
        verdict = judge.check(answer, typo)
        assert not verdict.readable and not verdict.correct and verdict.message, typo
        assert records.record_checked(ann, "pendulum_rebound", "theta_rebound", typo, verdict, database, BEFORE) is None
    assert records.attempt_count(aid, database) == 0
    right = f"{solution.answers['theta_rebound'] * 180 / 3.141592653589793:.4f}"
    verdict = judge.check(answer, right)
    assert verdict.readable and verdict.correct
    kept = records.record_checked(ann, "pendulum_rebound", "theta_rebound", right, verdict, database, BEFORE)
    assert kept.number == 1 and kept.counts and records.gradebook(aid, database).score("s01") == 1
    wrong = judge.check(answer, "1")
    assert wrong.readable and not wrong.correct  # a readable wrong answer is an attempt


def test_the_same_answer_twice_in_a_row_counts_once(database):
    aid, (ann, _) = new_assignment(database)
    first = attempt(database, ann, typed="12.5")
    again = attempt(database, ann, typed=" 12.5 ")  # a second click, or the same text re-sent
    assert again.repeated and again.id == first.id and again.number == 1
    other = attempt(database, ann, typed="13")
    back = attempt(database, ann, typed="12.5")  # not in a row: a new attempt
    assert (other.number, back.number, back.repeated) == (2, 3, False)
    elsewhere = attempt(database, ann, answer="I_O", typed="13")  # another answer: its own count
    assert elsewhere.number == 1 and not elsewhere.repeated
    assert records.attempt_count(aid, database) == 4


def test_the_same_answer_from_many_tabs_at_once_counts_once(database):
    """Eight tabs sending one text at the same moment: one attempt (PostgreSQL's READ COMMITTED let
    each transaction miss the others' rows before the student's row was locked)."""
    aid, (ann, _) = new_assignment(database)
    with ThreadPoolExecutor(8) as pool:
        kept = list(pool.map(lambda _: attempt(database, ann, typed="12.5"), range(8)))
    assert records.attempt_count(aid, database) == 1
    assert len({k.id for k in kept}) == 1 and sum(not k.repeated for k in kept) == 1


def test_a_changed_assignment_is_not_found_by_its_first_settings(database):
    """Created, then edited (or archived): the same Create again makes a new assignment, rather than
    pointing at one that no longer has those settings."""
    first = records.create(settings(), ["s01"], database)
    records.edit(first.id, records.replace(records.assignment(first.id, database), attempts_allowed=5), database)
    again = records.create(settings(), ["s01"], database)
    assert again.new and again.id != first.id
    records.set_status(again.id, "archived", database)
    third = records.create(settings(), ["s01"], database)
    assert third.new and third.id not in (first.id, again.id)
    assert records.create(settings(), ["s01"], database).id == third.id  # a repeated click still finds it


def test_a_right_answer_given_again_earns_nothing_more(database):
    """Right at attempt 1, then right again (another value within the tolerance): the page said "this one changes
    nothing", but the student's table said "counts: yes" twice and the attempts CSV gave each a credit of 1 (a
    sum per answer counted it twice). The second earns nothing, marked "already right"; the gradebook is as before."""
    aid, (ann, _) = new_assignment(database)
    attempt(database, ann, correct=True)
    again = attempt(database, ann, correct=True)
    assert again.after_right and again.credit == 0 and "already right" in again.marks()
    mine = records.attempts_of(ann, database)
    assert [(a.number, a.credit, a.after_right) for a in mine] == [(1, 1.0, False), (2, 0.0, True)]
    rows = list(csv.DictReader(io.StringIO(records.attempts_csv(aid, database))))
    assert [(r["attempt"], r["after_right"], r["credit"]) for r in rows] == [("1", "False", "1"), ("2", "True", "0")]
    book = records.gradebook(aid, database)
    assert book.cell("s01", THETA).status(book.settings) == "right at attempt 1" and book.score("s01") == 1


def test_a_cell_past_its_limit_says_how_many_of_how_many():
    """A student who went on past the limit (kept, marked) or whose limit was lowered: "4 attempts, 3
    allowed", one short phrase (was "all 3 attempts used (1 more over the limit)")."""
    words = {n: records.Cell(attempts=n, allowed=3).status(settings()) for n in (0, 2, 3, 4)}
    assert words == {0: "not tried", 2: "not right yet: 2 of 3 attempts used", 3: "not right: all 3 attempts used",
                     4: "not right: 4 attempts, 3 allowed"}


def test_right_but_late_is_visible_everywhere(database):
    """A right answer after the due time: the student's attempt, the gradebook's cell, its
    statistics and the CSVs all say right-but-late (no late credit by default)."""
    aid, (ann, bob) = new_assignment(database)
    late = attempt(database, ann, correct=True, when=DUE + dt.timedelta(hours=3, minutes=5))
    assert late.late and late.correct and not late.counts and late.credit == 0
    attempt(database, bob, correct=True)
    book = records.gradebook(aid, database)
    assert book.cell("s01", THETA).status(book.settings) == "right but 3 h 5 min late (attempt 1): no credit"
    assert book.cell("s02", THETA).status(book.settings) == "right at attempt 1"
    assert book.statistics()[THETA][:2] == ["1 of 2 students who tried it (50 %) got it right in time.",
                                            "1 more (50 %) got it right after the due time (no late credit)."]
    assert book.late_right("s01") == 1 and book.late_right("s02") == 0
    # how the score was made: the late answer named, not "nothing yet" (the student did the work)
    assert book.how("s01") == "no points = 0 of 2 (theta_rebound right but 3 h 5 min late: no credit)"
    assert book.how("s02") == "theta_rebound 1 = 1 of 2"
    row = next(csv.DictReader(io.StringIO(records.gradebook_csv(book, {THETA: "Highest angle"}))))
    assert row["Highest angle:status"].startswith("right but 3 h 5 min late") and row["right_but_late"] == "1"
    # the late answer's attempt and time are in the gradebook too (the student's evidence), and the
    # score's words call the answer as the page does
    assert (row["Highest angle:points"], row["Highest angle:out_of"], row["Highest angle:right_at_attempt"]) == \
        ("0", "1", "1")
    assert row["Highest angle:right_at_utc"] == (DUE + dt.timedelta(hours=3, minutes=5)).strftime("%Y-%m-%d %H:%M:%S")
    assert row["how"] == "no points = 0 of 2 (Highest angle right but 3 h 5 min late: no credit)"


@pytest.mark.parametrize("policy, value, late_by, credit", [
    ("per_day", 0.2, dt.timedelta(hours=1), 0.8),  # a started day
    ("per_day", 0.2, dt.timedelta(days=1, hours=1), 0.6),
    ("per_day", 0.3, dt.timedelta(days=5), 0.0),
    ("fixed", 0.5, dt.timedelta(days=9), 0.5),
    ("none", 0.0, dt.timedelta(minutes=1), 0.0),
])
def test_late_credit_and_how_the_score_was_computed(database, policy, value, late_by, credit):
    aid, (ann, _) = new_assignment(database, late_policy=policy, late_value=value)
    attempt(database, ann, answer="I_O", correct=True)
    kept = attempt(database, ann, correct=True, when=DUE + late_by)
    assert kept.credit == pytest.approx(credit)
    book = records.gradebook(aid, database)
    assert book.score("s01") == pytest.approx(1 + credit)
    how = book.how("s01")
    if credit > 0:
        assert how == f"theta_rebound 1 × {credit * 100:g} % (late) + I_O 1 = {1 + credit:g} of 2"
    else:  # right, but earning nothing: said, and why
        assert how == f"I_O 1 = 1 of 2 (theta_rebound right but {records.duration_text(late_by)} late: no credit)"


def test_an_extension_and_extra_attempts_apply_to_one_student(database):
    aid, (ann, bob) = new_assignment(database, attempts_allowed=1)
    attempt(database, ann)  # wrong: her one attempt is used
    over = attempt(database, ann, correct=True)
    assert over.over_limit and not over.counts
    late = attempt(database, bob, correct=True, when=DUE + dt.timedelta(days=1))
    assert late.late and not late.counts
    said = records.grant(aid, "s01", extra_attempts=1, bound=database)
    assert "extra attempts 0 → 1" in said
    records.grant(aid, "s02", extended_due=DUE + dt.timedelta(days=2), bound=database)
    book = records.gradebook(aid, database)  # the past is read under the new grants
    assert book.score("s01") == 1 and book.score("s02") == 1
    assert book.cell("s01", THETA).allowed == 2 and book.cell("s02", ("pendulum_rebound", "I_O")).allowed == 1
    standing = records.standing(bob, database)
    assert standing.due == DUE + dt.timedelta(days=2) and standing.allowed == 1
    with pytest.raises(ValueError, match="not on this assignment's roster"):
        records.grant(aid, "s99", extra_attempts=1, bound=database)


def test_creating_twice_makes_one_assignment(database):
    """A repeated click or a reload: the same title, problems and due time find the one created."""
    first = records.create(settings(), ["s01", "s02"], database)
    again = records.create(settings(title="  bounce "), ["s01", "s02"], database)
    assert first.new and not again.new and again.id == first.id and again.students == 2
    assert records.find(settings(), database).id == first.id
    assert len(records.assignments(database)) == 1
    other = records.create(settings(due=DUE + dt.timedelta(days=7)), ["s01"], database)
    assert other.new and other.id != first.id
    with ThreadPoolExecutor(4) as pool:  # four clicks at once
        made = list(pool.map(lambda _: records.create(settings(title="Race"), ["s01"], database), range(4)))
    assert len({m.id for m in made}) == 1 and sum(m.new for m in made) == 1


def test_edits_close_reopen_archive_are_logged_and_undone(database):
    aid, (ann, _) = new_assignment(database)
    base = records.assignment(aid, database)
    later = DUE + dt.timedelta(days=3)
    said = records.edit(aid, records.replace(base, due=later, attempts_allowed=5, tolerance=0.01, hints=False),
                        database)
    assert len(said) == 4 and any(s.startswith("attempts per answer 3 → 5") for s in said)
    assert records.edit(aid, records.assignment(aid, database), database) == []  # nothing changed, nothing logged
    records.set_status(aid, "closed", database)
    with pytest.raises(records.NotAccepted, match="closed"):
        attempt(database, ann, correct=True)
    assert records.attempt_count(aid, database) == 0
    records.set_status(aid, "open", database)
    attempt(database, ann, correct=True)
    records.set_status(aid, "archived", database)
    assert records.assignments(database, archived=False) == []
    log = records.history(aid, database)
    assert [e.action for e in log] == ["archived", "reopened", "closed", "edited", "created"]
    assert all(e.at.tzinfo for e in log)

    records.undo(aid, log[0].id, database)  # unarchive
    assert records.assignment(aid, database).status == "open"
    edited = next(e for e in log if e.action == "edited")
    records.undo(aid, edited.id, database)
    back = records.assignment(aid, database)
    assert (back.due, back.attempts_allowed, back.tolerance, back.hints) == (DUE, 3, 5e-3, True)
    log = records.history(aid, database)
    assert log[0].action == "undo" and log[0].undoes == edited.id and next(e for e in log if e.id == edited.id).undone
    with pytest.raises(ValueError, match="archive the assignment instead"):
        records.undo(aid, log[-1].id, database)
    records.undo(aid, log[0].id, database)  # undo the undo: the edit is back, and so not "undone"
    assert records.assignment(aid, database).attempts_allowed == 5
    log = records.history(aid, database)
    marks = {e.id: e.undone for e in log}
    assert marks[edited.id] is False and marks[log[1].id] is True and marks[log[0].id] is False
    records.undo(aid, edited.id, database)  # and the edit can be undone again
    assert records.assignment(aid, database).attempts_allowed == 3
    csv_rows = list(csv.DictReader(io.StringIO(records.history_csv(log))))
    assert csv_rows[0]["action"] == "created" and len(csv_rows) == len(log)


def test_a_student_grant_is_logged_and_undone(database):
    aid, _ = new_assignment(database)
    records.grant(aid, "s02", extended_due=DUE + dt.timedelta(days=1), extra_attempts=2, bound=database)
    change = records.history(aid, database)[0]
    assert change.label == "s02" and "extension" in change.summary and "extra attempts 0 → 2" in change.summary
    records.undo(aid, change.id, database)
    standing = records.standing(StudentIdentity(aid, "s02", 0), database)
    assert standing.grant == records.Grant() and standing.due == DUE


def test_a_problem_set_with_weights_gives_one_score(database):
    parts = (records.Part("pendulum_rebound", ("theta_rebound", "I_O"), (2, 1)),
             records.Part("disk_wall", ("v1x",), (3,)))
    aid, (ann, bob) = new_assignment(database, parts=parts, late_policy="fixed", late_value=0.5)
    attempt(database, ann, correct=True)
    records.record_attempt(ann, "v1x", "2.5", True, "m", "", database, DUE + dt.timedelta(hours=1), "disk_wall")
    records.record_attempt(bob, "v1x", "2.5", False, "m", "", database, BEFORE, "disk_wall")
    with pytest.raises(ValueError, match="not an answer this assignment counts"):
        records.record_attempt(bob, "v1y", "2.5", False, "m", "", database, BEFORE, "disk_wall")
    book = records.gradebook(aid, database)
    assert book.settings.out_of == 6 and book.score("s01") == 2 + 1.5 and book.score("s02") == 0
    assert book.how("s01") == "theta_rebound 2 + v1x 3 × 50 % (late) = 3.5 of 6"
    rows = list(csv.DictReader(io.StringIO(records.gradebook_csv(book))))
    assert rows[0]["disk_wall/v1x:points"] == "1.5" and rows[0]["score"] == "3.5" and rows[0]["out_of"] == "6"
    # a reveal on one problem marks only that problem's later attempts
    records.record_reveal(bob, database, BEFORE, problem="disk_wall")
    shown = records.record_attempt(bob, "v1x", "3", True, "m", "", database, BEFORE, "disk_wall")
    fine = attempt(database, bob, correct=True)
    assert shown.solution_shown and not fine.solution_shown and fine.counts
    assert records.solution_shown(bob, database, "disk_wall") and not records.solution_shown(bob, database, "pendulum_rebound")


def test_the_csvs_open_as_numbers_and_import_into_an_lms(database):
    aid, (ann, bob) = new_assignment(database, title="Week 9, the bounce")
    attempt(database, ann, typed="-1.2")
    attempt(database, ann, correct=True)
    book = records.gradebook(aid, database)
    attempts = list(csv.DictReader(io.StringIO(records.attempts_csv(aid, database, {THETA: "Highest angle"}))))
    assert attempts[0]["typed"] == "-1.2"  # a typed number stays a number (it was '-1.2)
    assert (attempts[0]["answer"], attempts[0]["answer_name"]) == ("theta_rebound", "Highest angle")
    canvas = list(csv.reader(io.StringIO(records.lms_csv(book, "canvas"))))
    assert canvas[0] == ["Student", "ID", "SIS User ID", "SIS Login ID", "Section", "Week 9, the bounce"]
    assert canvas[1] == ["Points Possible", "", "", "", "", "2"]
    assert canvas[2] == ["s01", "", "s01", "s01", "", "1"] and canvas[3][-1] == "0"
    moodle = list(csv.reader(io.StringIO(records.lms_csv(book, "moodle"))))
    assert moodle == [["ID number", "Week 9, the bounce"], ["s01", "1"], ["s02", "0"]]
    row = next(csv.DictReader(io.StringIO(records.gradebook_csv(book))))
    assert (row["score"], row["percent"], row["theta_rebound:points"], row["theta_rebound:attempts_used"]) == \
        ("1", "50", "1", "2")


@pytest.mark.parametrize("text, message", [
    ("s01\n" + "x" * 200_000 + "\n", "too long"),
    ('s01\n"' + "x" * 140_000 + "\n", "too long"),
    ('s01\n"' + "y" * 10 + '\n' + "z" * 140_000 + "\n", "cannot be read as CSV|too long"),
    ("s01\ns02\ns01\ns02\n", r"Repeated labels: s01 \(lines 1 and 3\), s02 \(lines 2 and 4\)"),
    ("s01\x00\ns02\n", None),
])
def test_a_bad_roster_gets_a_plain_message(text, message):
    """A CSV with one very long line raised an uncaught csv.Error (field larger than field limit)."""
    if message is None:
        assert records.parse_roster(text) == ["s01", "s02"]
        return
    with pytest.raises(ValueError, match=message):
        records.parse_roster(text)


def test_feedback_follows_the_assignments_policy():
    hint = E_FOR_E2
    said = f"Not quite. {hint}"
    assert records.feedback(said, False, hint, None) == said  # Practice: every hint
    assert records.feedback(said, False, hint, settings()) == said  # hints on
    named = records.feedback(said, False, hint, settings(hints=False))
    assert "e where e² belongs" in named and hint not in named
    bare = records.feedback(said, False, hint, settings(hints=False, slip_names=False))
    assert bare == "Not right. Check each step, then try again."
    assert records.feedback("Right: 3 m/s.", True, "", settings(hints=False)) == "Right: 3 m/s."


SIGN_SLIPS = [m.feedback for m in registry.solver("pendulum_rebound").MISTAKES if m.feedback.startswith("A sign")]


def test_a_slip_s_name_tells_the_instructor_which_and_the_student_no_more_than_their_feedback():
    """Two of the pendulum's slips are "A sign…": the gradebook named both “A sign”. The instructor's name runs
    on to what the sign is; a student's own list of attempts names a slip only as their feedback did."""
    telling = [records.slip_name(slip, telling=True) for slip in SIGN_SLIPS]
    assert len(SIGN_SLIPS) == 2 and len(set(telling)) == 2 and all(t.startswith("A sign: ") for t in telling)
    assert all(t.split(": ", 1)[1] in slip for t, slip in zip(telling, SIGN_SLIPS))
    assert records.slip_name(E_FOR_E2, telling=True) == records.slip_name(E_FOR_E2) == "e where e² belongs"
    hint = SIGN_SLIPS[0]
    assert records.slip_shown(hint, settings()) == records.slip_shown(hint, settings(hints=False)) == "A sign"
    assert records.slip_shown(hint, settings(hints=False, slip_names=False)) == ""
    assert records.slip_shown(None, settings()) == ""


def test_the_statistics_of_one_student_say_one_student(database):
    aid, students = new_assignment(database, ["s01"])
    attempt(database, students[0], slip=SIGN_SLIPS[0])
    assert records.gradebook(aid, database).statistics()[THETA][0] == (
        "0 of 1 student who tried it (0 %) got it right in time.")


def test_the_upgrade_keeps_an_assignment_made_before_problem_sets(database):
    """Revision 0001's assignment (one problem, its answers) and its attempts survive 0002."""
    from alembic import command
    from sqlalchemy import text

    cfg = migrate.config()
    with database.begin() as connection:
        cfg.attributes["connection"] = connection
        command.downgrade(cfg, "0001")
    with database.begin() as c:
        c.execute(text("INSERT INTO assignment (id, title, problem, answers, tolerance, due, attempts_allowed, "
                       "solution_before_due, created) VALUES (7, 'Old', 'disk_wall', :answers, 0.005, :due, 2, "
                       "false, :due)"), {"answers": '["v1x", "v1y"]', "due": DUE})
        c.execute(text("INSERT INTO student (assignment_id, label, seed) VALUES (7, 's01', 5)"))
        c.execute(text("INSERT INTO attempt (assignment_id, label, answer, typed, correct, message, slip, at, late, "
                       "solution_shown) VALUES (7, 's01', 'v1x', '2', true, 'Right', '', :at, false, false)"),
                  {"at": BEFORE})
    migrate.upgrade(database)
    old = records.assignment(7, database)
    assert old.parts == (records.Part("disk_wall", ("v1x", "v1y")),) and old.status == "open" and old.hints
    assert records.gradebook(7, database).score("s01") == 1
    assert records.attempts_of(StudentIdentity(7, "s01", 5), database)[0].problem == "disk_wall"


def test_an_edit_of_the_points_is_said_answer_by_answer_in_the_pages_words(database):
    """"Saved: problems, answers and weights pendulum_rebound: theta_impact ×1, …" named the answers by
    their ids and listed everything before and after; the instructor's page calls them by their labels."""
    aid, _ = new_assignment(database)
    before = records.assignment(aid, database)
    changed = records.Part("pendulum_rebound", ("theta_rebound", "omega_after"), (2, 1))
    said = records.edit(aid, records.replace(before, parts=(changed,)), database)
    assert said == ["“Highest angle after the bounce” 1 → 2 points; “Moment of inertia about the pivot” no longer "
                    "counts; “Angular velocity just after impact” counts (1 point)"]
    assert records.history(aid, database)[0].summary == "; ".join(said)
    with_disk = (changed, records.Part("disk_wall", ("v1x",), (3,)))
    assert records.edit(aid, records.replace(before, parts=with_disk), database) == [
        "Spinning disk hits a rough wall added"]


def test_the_free_body_diagram_is_a_question_scored_like_an_answer(database):
    """The diagram counted beside an answer, with its points: a drawing (in words, with its reading) is an
    attempt; the same drawing again is one; late and attempt rules apply; the gradebook and its CSV have it."""
    from practice.diagram_judge import DrawnLoad, in_words, reading

    parts = (records.Part("sliding_ladder", ("N_A0", records.DIAGRAM), (1, 2)),)
    aid, (ann, bob) = new_assignment(database, parts=parts, late_policy="fixed", late_value=0.5)
    wrong = (DrawnLoad("force", "the ladder", "G", 270.0, "W"),)
    right = wrong + (DrawnLoad("force", "the ladder", "B", 90.0, "N_B"), DrawnLoad("force", "the ladder", "A", 0.0, "N_A"))
    renamed = (DrawnLoad("force", "the ladder", "G", 270.0, "weight"),)  # the same drawing, named otherwise
    first = records.record_attempt(ann, records.DIAGRAM, in_words(wrong), False, "Not right", "missing", database,
                                   BEFORE, "sliding_ladder", reading(wrong))
    again = records.record_attempt(ann, records.DIAGRAM, in_words(renamed), False, "Not right", "missing", database,
                                   BEFORE, "sliding_ladder", reading(renamed))
    assert first.number == 1 and again.repeated and in_words(wrong) == "force “W” at G, 270°"
    records.record_attempt(ann, records.DIAGRAM, in_words(right), True, "Right.", "", database, BEFORE,
                           "sliding_ladder", reading(right))
    records.record_attempt(bob, records.DIAGRAM, in_words(right), True, "Right.", "", database,
                           DUE + dt.timedelta(hours=2), "sliding_ladder", reading(right))
    book = records.gradebook(aid, database)
    assert book.settings.out_of == 3 and book.score("s01") == 2 and book.score("s02") == 1
    assert records.Settings.errors(book.settings) == []
    row = list(csv.DictReader(io.StringIO(records.gradebook_csv(book))))[0]
    assert row[f"{records.DIAGRAM}:points"] == "2" and row[f"{records.DIAGRAM}:status"] == "right at attempt 2"
    assert records._answer_named("sliding_ladder", records.DIAGRAM, False) == "“Free-body diagram”"
