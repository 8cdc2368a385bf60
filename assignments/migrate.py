"""Create or upgrade the schema with Alembic (``migrations/``): ``python -m assignments migrate``.

This is the one place a database is created, and it refuses to create one where an earlier one is
expected: an empty database in place of a course's gradebook is an error, not a fresh start. The
evidence it reads: ``DL_EXPECT_DATABASE=1`` (the admin's word that this deployment already has
its data; README, the admin's checklist), and, for SQLite, the marker file it leaves beside the
database it created (so a database file deleted from its directory, or replaced by an empty one,
is not silently taken for a new course), and, within a running process, the database it has
already brought up (a data directory removed under the server is not made anew by the next page).
A directory removed with its marker and the server restarted is found only by DL_EXPECT_DATABASE.
With neither, as on a fresh machine's ``make run``, it creates the database as before."""
from __future__ import annotations

import datetime as dt
import os

from alembic import command
from alembic.config import Config
from sqlalchemy import inspect
from sqlalchemy.engine import Engine

from assignments import db

SCRIPTS = db.ROOT / "migrations"
MIGRATION_LOCK = 18_0001  # a PostgreSQL advisory lock's key: replicas starting together migrate one at a time
EXPECT_ENV = "DL_EXPECT_DATABASE"
MARKER = ".dynamics-lab-database"  # beside a SQLite file this module created


_created_here: dict[str, bool] = {}  # the databases this process has brought up: never created again


class DatabaseMissing(RuntimeError):
    """An earlier database is expected here and an empty one (or none) was found."""


def config() -> Config:
    cfg = Config()
    cfg.set_main_option("script_location", str(SCRIPTS))
    return cfg


def expected() -> bool:
    return os.environ.get(EXPECT_ENV, "").strip() == "1"


def _has_schema(engine: Engine) -> bool:
    with engine.connect() as connection:
        return inspect(connection).has_table("alembic_version")


def check_expected(url: str) -> None:
    """Raise DatabaseMissing, in words an admin can act on, where an earlier database should be."""
    path = db.sqlite_path(url)
    if path is not None and path.exists() and (path.parent / MARKER).exists():
        engine = db.make_engine(url, create=False)
        try:
            empty = not _has_schema(engine)
        finally:
            engine.dispose()
        if empty:
            raise DatabaseMissing(
                f"The database file {path} has no tables, but this directory held a database (the marker "
                f"{MARKER} is there): it was replaced by an empty one. Restore it from a backup.")
    if path is not None and not path.exists():
        if _created_here.get(url) or (path.parent / MARKER).exists():
            raise DatabaseMissing(
                f"The database file {path} is missing, but this directory held one (the marker {MARKER} "
                "is there). Restore it from a backup (README: Backing up); to start an empty gradebook on "
                f"purpose, delete {path.parent / MARKER}.")
        if expected():
            raise DatabaseMissing(
                f"{EXPECT_ENV}=1 says this deployment has its data, but there is no database file at {path}. "
                "Is the data volume mounted (docker run -v dynamics-lab-data:/data)? Restore it, or unset "
                f"{EXPECT_ENV} for the very first start of a new course.")
        return
    if expected():
        engine = db.make_engine(url, create=False)
        shown = engine.url.render_as_string(hide_password=True) if path is None else str(path)
        try:
            if not _has_schema(engine):
                raise DatabaseMissing(
                    f"{EXPECT_ENV}=1 says this deployment has its data, but the database {shown} is empty. "
                    "Is it the right database, with its volume? Restore it, or unset "
                    f"{EXPECT_ENV} for the very first start of a new course.")
        finally:
            engine.dispose()


def upgrade(bound: Engine | None = None, revision: str = "head") -> None:
    """Bring the database of ``bound`` to ``revision``; without ``bound``, the app's database
    (``DL_DATABASE_URL`` or the SQLite file), created here if the checks above allow it."""
    if bound is not None:
        return _upgrade(bound, revision)
    url = db.database_url()
    check_expected(url)
    path = db.sqlite_path(url)
    created = path is not None and not path.exists()
    engine = db.make_engine(url, create=True)
    try:
        _upgrade(engine, revision)
    finally:
        engine.dispose()
    _created_here[url] = True
    if created:
        (path.parent / MARKER).write_text(
            f"Dynamics Lab created {path.name} here at {dt.datetime.now(dt.timezone.utc):%Y-%m-%d %H:%M} UTC.\n"
            "While this file is here, the app will not start with that database missing.\n")


def _upgrade(bound: Engine, revision: str) -> None:
    cfg = config()
    with bound.begin() as connection:
        if connection.dialect.name == "postgresql":  # (SQLite's BEGIN IMMEDIATE already serialises)
            connection.exec_driver_sql(f"SELECT pg_advisory_xact_lock({MIGRATION_LOCK})")
        cfg.attributes["connection"] = connection
        command.upgrade(cfg, revision)
