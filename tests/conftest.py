"""Test-wide settings: Hypothesis runs derandomized in CI (reproducible, no flaky deadlines)."""
import contextlib
import os
import shutil
import tempfile

import pytest

from hypothesis import HealthCheck, settings

settings.register_profile("dev", deadline=None)
settings.register_profile("ci", deadline=None, derandomize=True, print_blob=True,
                          suppress_health_check=[HealthCheck.too_slow])
settings.load_profile("ci" if os.environ.get("CI") else "dev")


@pytest.fixture(autouse=True)
def fresh_key_throttle():
    """Each test starts with no wrong instructor keys on record (the throttle is process-wide)."""
    from practice import instructor

    instructor.THROTTLE.records.clear()
    yield


# The browser tests' shared fixtures (test_browser, test_where_used, test_stage, test_seen_and_heard, ...):
# one server for the whole session (each start costs 10-30 s of a 2-core CI machine; a module that
# needs a server of its own, with other settings, defines its own fixture), and one Chromium per
# module: Playwright's sync API holds an event loop while it runs, which would refuse every other
# test's asyncio.run() if it lived for the whole session.
@pytest.fixture(scope="module")
def browser():
    from playwright.sync_api import sync_playwright

    from scripts.live_app import launch_browser

    with sync_playwright() as pw:
        b = launch_browser(pw)
        yield b
        b.close()


# The shared server's instructor key and course secret (handouts, assignments: test_print.py,
# test_assignments_browser.py).
INSTRUCTOR_KEY, COURSE_SECRET = "instructor-key-0018", "course-secret-for-the-tests-0018"


def reset_database_caches() -> None:
    """The process's database engine and schema check forgotten (AppTest: after a test points the app at
    another database)."""
    from assignments import db
    from ui.session import schema_ready

    db.engine.cache_clear()
    schema_ready.clear()


@pytest.fixture
def course_database(monkeypatch, tmp_path):
    """The record pages' setting (AppTest): the instructor key and a SQLite file of the test's own, the
    process's engine and schema check forgotten before and after."""
    from assignments import db

    monkeypatch.setenv("DL_INSTRUCTOR_KEY", INSTRUCTOR_KEY)
    monkeypatch.setenv(db.URL_ENV, f"sqlite:///{tmp_path / 'course.sqlite'}")
    reset_database_caches()
    yield
    reset_database_caches()


@pytest.fixture
def course(course_database, monkeypatch):
    """``course_database`` and the course secret that signs the students' links (assignments, handouts, LTI,
    take-home)."""
    from assignments import signing

    monkeypatch.setenv(signing.SECRET_ENV, COURSE_SECRET)


_DATA_DIRS: list[str] = []  # the servers' data directories, removed when the session ends


def _data_dir() -> str:
    _DATA_DIRS.append(tempfile.mkdtemp(prefix="dl-app-data-"))
    return _DATA_DIRS[-1]


def _shipped_env() -> dict:
    return {"DL_INSTRUCTOR_KEY": INSTRUCTOR_KEY, "DL_COURSE_SECRET": COURSE_SECRET,
            "DL_DATA_DIR": _data_dir(), "DL_DATABASE_URL": ""}


def _fresh_env() -> dict:
    """A server as shipped: no instructor key or course secret, its data in a temp directory (never the checkout's)."""
    return {"DL_DATA_DIR": _data_dir(), "DL_DATABASE_URL": ""}


# Servers the collected tests will need, started as soon as they are collected: each warms for some
# 20 s on the second core while the first tests (AppTest's, without a server) run. By name, the
# settings each starts with (made when it starts: the shared one's data directory).
_EARLY: dict = {}
_USES: dict[str, int] = {}  # how many collected tests still need a server of that name (each its own: "fresh")
_AFTER_SHIPPED: list[str] = []  # servers to start once the shared one is ready
_SETTINGS = {"shipped": _shipped_env, "fresh": _fresh_env}
SERVED = {"shipped_server", "app_url", "fresh_server", "browser"}


@pytest.hookimpl(tryfirst=True)  # before ``-m`` selects by the mark
def pytest_collection_modifyitems(session, config, items):
    """The modules that need a live server or a browser are marked ``served`` and run after the
    others (each module's tests kept together and in order), so the servers started below warm
    while AppTest's tests run."""
    served = {item.module.__name__ for item in items if SERVED & set(getattr(item, "fixturenames", ()))}
    for item in items:
        if item.module.__name__ in served:
            item.add_marker("served")
    items.sort(key=lambda item: item.module.__name__ in served)


def pytest_collection_finish(session):
    from scripts.live_app import Starting

    used = {name for item in session.items for name in getattr(item, "fixturenames", ())}
    if "shipped_server" in used or ("app_url" in used and not os.environ.get("APP_URL")):
        _EARLY["shipped"] = Starting(env=_SETTINGS["shipped"]())
    if "fresh_server" in used:
        # (started once the shared server is warm, not beside it: two warming at once doubled the first test's wait)
        if "shipped" in _EARLY:
            _AFTER_SHIPPED.append("fresh")
        else:
            _EARLY["fresh"] = Starting(env=_SETTINGS["fresh"]())
        _USES["fresh"] = sum("fresh_server" in getattr(item, "fixturenames", ()) for item in session.items)


def pytest_unconfigure(config):
    for starting in _EARLY.values():  # started for tests that did not run (-x, a keyboard interrupt)
        starting.stop()
    for path in _DATA_DIRS:
        shutil.rmtree(path, ignore_errors=True)


@contextlib.contextmanager
def _early(name: str):
    from scripts.live_app import Starting

    starting = _EARLY.pop(name, None) or Starting(env=_SETTINGS[name]())
    _USES[name] = _USES.get(name, 1) - 1
    if _USES[name] > 0:  # a fresh server for the next test that needs one, warming while this one runs
        _EARLY[name] = Starting(env=_SETTINGS[name]())
    try:
        server = starting.ready()
        if name == "shipped":
            while _AFTER_SHIPPED:
                later = _AFTER_SHIPPED.pop()
                if later not in _EARLY and _USES.get(later, 0) > 0:  # (still to be used)
                    _EARLY[later] = Starting(env=_SETTINGS[later]())
        yield server
    finally:
        starting.stop()


@pytest.fixture(scope="session")
def shipped_server():
    """The app as shipped (serve.py) on a free loopback port, started once for the whole session
    (a start is some 20 s of warming): ``scripts.live_app.Server`` (its URL, its log, its pid), with
    an instructor key, a course secret and a data directory of its own (its records in SQLite there).
    A test that needs other settings starts its own."""
    with _early("shipped") as server:
        yield server


@pytest.fixture
def fresh_server():
    """A server as shipped that nobody has visited (its first visit is the test's), stopped after the test."""
    with _early("fresh") as server:
        yield server


@pytest.fixture(scope="session")
def app_url(request):
    """The shared server's URL, or APP_URL: the container, the balancer."""
    if os.environ.get("APP_URL"):
        return os.environ["APP_URL"].rstrip("/")
    return request.getfixturevalue("shipped_server").url


# The database tests run the same suite on both backends (tests/records/test_records.py): a SQLite file
# per test, and a database per test in one PostgreSQL cluster per session. PostgreSQL is skipped
# where it is not installed, except in CI (.ci/run installs it), where its absence is a failure.
@pytest.fixture(scope="session")
def postgres_server():
    from tests.databases import postgres_cluster, postgres_missing

    why = postgres_missing()
    if why:
        if os.environ.get("CI"):
            pytest.fail(f"CI must test PostgreSQL: {why}")
        pytest.skip(why)
    with postgres_cluster() as url:
        yield url


_database_count = iter(range(10**6))


@pytest.fixture(params=["sqlite", "postgresql"])
def database(request, tmp_path):
    """A fresh, migrated database (an engine) on each backend."""
    from sqlalchemy import create_engine, text

    from assignments import db, migrate

    if request.param == "sqlite":
        engine = db.make_engine(f"sqlite:///{tmp_path / 'test.sqlite'}")
        migrate.upgrade(engine)
        yield engine
        engine.dispose()
        return
    server = request.getfixturevalue("postgres_server")
    name = f"dl_test_{os.getpid()}_{next(_database_count)}"
    admin = create_engine(server, isolation_level="AUTOCOMMIT")
    with admin.connect() as c:
        c.execute(text(f"CREATE DATABASE {name}"))
    engine = db.make_engine(server.replace("/postgres?", f"/{name}?"))
    try:
        migrate.upgrade(engine)
        yield engine
    finally:
        engine.dispose()
        with admin.connect() as c:
            c.execute(text(f"DROP DATABASE IF EXISTS {name} WITH (FORCE)"))
        admin.dispose()
