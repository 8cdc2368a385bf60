"""Nothing lost in silence: while submissions run, the data is removed, replaced, made read-only or
cut off; every attempt a student was told is "Recorded" is in the database afterwards, and none
that was not (the two counts are equal), on SQLite and PostgreSQL. And at start-up, an empty
database where an earlier one is expected stops the app with a reason, while a fresh machine's
first start still just works."""
from __future__ import annotations

import datetime as dt
import os
import shutil
import subprocess
import sys
import threading
import time
from pathlib import Path

import pytest
from sqlalchemy import create_engine, text

from assignments import db, migrate, records, signing

UTC = dt.timezone.utc
DUE = dt.datetime(2030, 1, 1, tzinfo=UTC)
SUBMISSIONS, SABOTAGE_AFTER = 60, 20


@pytest.fixture(autouse=True)
def course_secret(monkeypatch):
    monkeypatch.setenv(signing.SECRET_ENV, "course-secret-for-the-tests-0018")
    monkeypatch.delenv(migrate.EXPECT_ENV, raising=False)


def submit_while(engine, sabotage) -> tuple[int, int, list]:
    """Four students submit SUBMISSIONS attempts between them; after SABOTAGE_AFTER are recorded,
    ``sabotage()`` runs. Returns (told "Recorded", the assignment's id, what the others were told)."""
    settings = records.Settings.of(title="Gone", problem="pendulum_rebound", answers=("theta_rebound",), tolerance=5e-3,
                                due=DUE, attempts_allowed=100, solution_before_due=False)
    aid = records.create_assignment(settings, engine)
    students = records.enrol(aid, ["s1", "s2", "s3", "s4"], engine)
    told_recorded, refusals, lock = [], [], threading.Lock()
    done_sabotage = threading.Event()
    remaining = iter(range(SUBMISSIONS))

    def student(who):
        for n in remaining:
            try:
                kept = records.record_attempt(who, "theta_rebound", str(n), False, "m", bound=engine)
                with lock:
                    told_recorded.append(kept.id)
                    if len(told_recorded) == SABOTAGE_AFTER and not done_sabotage.is_set():
                        sabotage()
                        done_sabotage.set()
            except records.RecordingUnavailable as refused:
                with lock:
                    refusals.append(str(refused))
            time.sleep(0.002)

    threads = [threading.Thread(target=student, args=(who,)) for who in students]
    for t in threads:
        t.start()
    for t in threads:
        t.join(120)
    assert done_sabotage.is_set()
    return len(told_recorded), aid, refusals


def rows_in_sqlite(path: Path, aid: int) -> int:
    with create_engine(f"sqlite:///{path}").connect() as c:
        return c.execute(text("SELECT count(*) FROM attempt WHERE assignment_id = :a"), {"a": aid}).scalar()


def immutable(path: Path, on: bool) -> bool:
    return subprocess.run(["chattr", "+i" if on else "-i", str(path)], capture_output=True).returncode == 0


SQLITE_SABOTAGE = ["remove the file", "remove the directory", "replace the file", "make it read-only"]


@pytest.mark.parametrize("how", SQLITE_SABOTAGE)
def test_sqlite_recorded_means_recorded(tmp_path, how):
    data = tmp_path / "data"
    path = data / "dynamics-lab.sqlite"
    engine = db.make_engine(f"sqlite:///{path}")
    migrate.upgrade(engine)
    # A second name for the same file, so that what it holds can be counted after it is gone.
    kept = tmp_path / "kept"
    kept.mkdir()
    files = [path] + [path.with_name(path.name + suffix) for suffix in ("-wal", "-shm")]
    made_immutable: list[Path] = []

    def sabotage():
        for f in files:
            if f.exists():
                os.link(f, kept / f.name)
        if how == "remove the file":
            for f in files:
                f.unlink(missing_ok=True)
        elif how == "remove the directory":
            shutil.rmtree(data)
        elif how == "replace the file":
            path.rename(data / "moved-away.sqlite")
            path.write_bytes(b"")
        elif how == "make it read-only":
            # The database and its write-ahead log; not the -shm index, which SQLite maps into
            # memory (writing to a mapped page of an immutable file is a SIGBUS, not an error).
            for f in files[:2]:
                if f.exists() and immutable(f, True):
                    made_immutable.append(f)
            if not made_immutable:
                pytest.skip("chattr +i is not available here")

    try:
        told, aid, refusals = submit_while(engine, sabotage)
    finally:
        for f in made_immutable:
            immutable(f, False)
    engine.dispose()
    assert told >= SABOTAGE_AFTER and refusals, "the sabotage must have refused some submissions"
    assert all("not recorded" in r for r in refusals)
    counted = rows_in_sqlite(path if how == "make it read-only" else kept / path.name, aid)
    assert counted == told
    if how in ("remove the file", "remove the directory"):
        assert not path.exists(), "nothing is created in place of the removed database"
    if how == "replace the file":
        assert path.read_bytes() == b"", "nothing is written into the file put in its place"


@pytest.mark.parametrize("how", ["cut off and renamed", "made read-only"])
def test_postgresql_recorded_means_recorded(postgres_server, how):
    admin = create_engine(postgres_server, isolation_level="AUTOCOMMIT")
    name = f"dl_lost_{os.getpid()}_{how.split()[0]}"
    moved = name + "_moved"
    with admin.connect() as c:
        c.execute(text(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)"))
        c.execute(text(f"DROP DATABASE IF EXISTS {moved} WITH (FORCE)"))
        c.execute(text(f"CREATE DATABASE {name}"))
    engine = db.make_engine(postgres_server.replace("/postgres?", f"/{name}?"))
    migrate.upgrade(engine)

    def sabotage():
        with admin.connect() as c:
            if how == "cut off and renamed":
                # Shut the door before emptying the room: a student reconnecting between the two
                # would hold the database open and the rename would be refused.
                c.execute(text(f"ALTER DATABASE {name} ALLOW_CONNECTIONS false"))
                c.execute(text(f"SELECT pg_terminate_backend(pid, 5000) FROM pg_stat_activity WHERE datname = '{name}'"))
                c.execute(text(f"ALTER DATABASE {name} RENAME TO {moved}"))
                c.execute(text(f"ALTER DATABASE {moved} ALLOW_CONNECTIONS true"))
            else:
                c.execute(text(f"ALTER DATABASE {name} SET default_transaction_read_only = on"))
                c.execute(text(f"SELECT pg_terminate_backend(pid, 5000) FROM pg_stat_activity WHERE datname = '{name}'"))

    try:
        told, aid, refusals = submit_while(engine, sabotage)
        engine.dispose()
        assert told >= SABOTAGE_AFTER and refusals and all("not recorded" in r for r in refusals)
        where = moved if how == "cut off and renamed" else name
        with create_engine(postgres_server.replace("/postgres?", f"/{where}?")).connect() as c:
            counted = c.execute(text("SELECT count(*) FROM attempt WHERE assignment_id = :a"), {"a": aid}).scalar()
        assert counted == told
    finally:
        engine.dispose()
        with admin.connect() as c:
            c.execute(text(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)"))
            c.execute(text(f"DROP DATABASE IF EXISTS {moved} WITH (FORCE)"))
        admin.dispose()


# -- at start-up

def migrate_command(env: dict) -> subprocess.CompletedProcess:
    base = {k: v for k, v in os.environ.items() if k not in (db.URL_ENV, db.DATA_ENV, migrate.EXPECT_ENV)}
    return subprocess.run([sys.executable, "-m", "assignments", "migrate"], cwd=db.ROOT, env=base | env,
                          capture_output=True, text=True, timeout=60)


def test_a_fresh_machine_just_starts_and_a_deleted_file_then_stops_it(tmp_path):
    data = tmp_path / "data"
    first = migrate_command({db.DATA_ENV: str(data)})
    assert first.returncode == 0, first.stderr
    assert (data / migrate.MARKER).exists()
    (data / "dynamics-lab.sqlite").unlink()
    again = migrate_command({db.DATA_ENV: str(data)})
    assert again.returncode != 0
    assert "is missing" in again.stderr and "Restore it from a backup" in again.stderr
    assert not (data / "dynamics-lab.sqlite").exists(), "nothing created in its place"
    assert "Traceback" not in again.stderr


def test_an_expected_database_that_is_not_there_stops_the_start(tmp_path):
    volume = tmp_path / "new-empty-volume"
    refused = migrate_command({db.DATA_ENV: str(volume), migrate.EXPECT_ENV: "1"})
    assert refused.returncode != 0 and "Is the data volume mounted" in refused.stderr
    assert not (volume / "dynamics-lab.sqlite").exists() and "Traceback" not in refused.stderr


def test_an_expected_postgresql_database_that_is_empty_stops_the_start(postgres_server):
    admin = create_engine(postgres_server, isolation_level="AUTOCOMMIT")
    name = f"dl_empty_{os.getpid()}"
    with admin.connect() as c:
        c.execute(text(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)"))
        c.execute(text(f"CREATE DATABASE {name}"))
    url = postgres_server.replace("/postgres?", f"/{name}?")
    try:
        refused = migrate_command({db.URL_ENV: url, migrate.EXPECT_ENV: "1"})
        assert refused.returncode != 0 and "is empty" in refused.stderr
        assert "Traceback" not in refused.stderr
        fresh = migrate_command({db.URL_ENV: url})  # the first start of a new course
        assert fresh.returncode == 0, fresh.stderr
        expected_now = migrate_command({db.URL_ENV: url, migrate.EXPECT_ENV: "1"})
        assert expected_now.returncode == 0, expected_now.stderr
    finally:
        with admin.connect() as c:
            c.execute(text(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)"))
        admin.dispose()


def test_serve_refuses_to_start_and_says_why(tmp_path, monkeypatch):
    import serve

    monkeypatch.delenv(db.URL_ENV, raising=False)
    monkeypatch.setenv(db.DATA_ENV, str(tmp_path / "missing-volume"))
    monkeypatch.setenv(migrate.EXPECT_ENV, "1")
    db.engine.cache_clear()
    try:
        with pytest.raises(SystemExit) as stopped:
            serve.migrate()
    finally:
        db.engine.cache_clear()
    assert "did not start" in str(stopped.value.code) and "Is the data volume mounted" in str(stopped.value.code)


@pytest.mark.parametrize("env, said", [
    ({"DL_INSTRUCTOR_KEY": "short", "DL_COURSE_SECRET": "c" * 32}, "DL_INSTRUCTOR_KEY has 5 characters"),
    ({"DL_COURSE_SECRET": "c" * 32}, "DL_INSTRUCTOR_KEY is not: nobody could create"),
    ({"DL_COURSE_SECRET": "tooshort", "DL_INSTRUCTOR_KEY": "k" * 24}, "DL_COURSE_SECRET has 8 characters"),
    ({"DL_FRAME_ANCESTORS": "javascript:alert(1)"}, "is not an origin"),
    ({"DL_EXPECT_DATABASE": "yes"}, "DL_EXPECT_DATABASE is 1"),
])
def test_settings_that_cannot_work_stop_the_start_in_plain_words(tmp_path, env, said):
    clean = {k: v for k, v in os.environ.items()
             if k not in ("DL_INSTRUCTOR_KEY", "DL_COURSE_SECRET", "DL_FRAME_ANCESTORS", migrate.EXPECT_ENV)}
    started = subprocess.run([sys.executable, str(db.ROOT / "serve.py"), "--server.port", "1"], cwd=db.ROOT,
                             env=clean | {db.DATA_ENV: str(tmp_path)} | env, capture_output=True, text=True,
                             timeout=60)
    assert started.returncode != 0 and said in started.stderr and "did not start" in started.stderr
    assert "Traceback" not in started.stderr


def test_settings_that_work_pass():
    import serve

    fine = {"DL_INSTRUCTOR_KEY": "k" * 24, "DL_COURSE_SECRET": "c" * 32,
            "DL_FRAME_ANCESTORS": "'self' https://canvas.example.edu", migrate.EXPECT_ENV: "1"}
    with pytest.MonkeyPatch.context() as patch:
        for name, value in fine.items():
            patch.setenv(name, value)
        assert serve.settings_problems() == []
        for name in fine:
            patch.delenv(name)
        assert serve.settings_problems() == []  # a fresh machine's make run
        patch.setenv("DL_INSTRUCTOR_KEY", "k" * 24)
        assert serve.settings_problems() == []  # a practice site with answer keys and handouts


def test_a_running_server_never_makes_its_database_anew(tmp_path, monkeypatch):
    """The data directory removed under a running process: the next page's migration (the
    Assignments page runs one) refuses, where it had made an empty gradebook in its place."""
    data = tmp_path / "data"
    monkeypatch.delenv(db.URL_ENV, raising=False)
    monkeypatch.setenv(db.DATA_ENV, str(data))
    migrate.upgrade()  # serve.py at start-up
    shutil.rmtree(data)
    with pytest.raises(migrate.DatabaseMissing):
        migrate.upgrade()
    assert not data.exists()


def test_an_empty_file_in_place_of_the_database_stops_the_start(tmp_path):
    data = tmp_path / "data"
    assert migrate_command({db.DATA_ENV: str(data)}).returncode == 0
    (data / "dynamics-lab.sqlite").write_bytes(b"")  # a restore gone wrong, a volume swapped
    refused = migrate_command({db.DATA_ENV: str(data)})
    assert refused.returncode != 0 and "has no tables" in refused.stderr
