"""Create or upgrade the schema with Alembic (``migrations/``): ``python -m assignments migrate``."""
from __future__ import annotations

from alembic import command
from alembic.config import Config
from sqlalchemy.engine import Engine

from assignments import db

SCRIPTS = db.ROOT / "migrations"
MIGRATION_LOCK = 18_0001  # a PostgreSQL advisory lock's key: replicas starting together migrate one at a time


def config() -> Config:
    cfg = Config()
    cfg.set_main_option("script_location", str(SCRIPTS))
    return cfg


def upgrade(bound: Engine | None = None, revision: str = "head") -> None:
    """Bring the database of ``bound`` (the process's engine by default) to ``revision``."""
    cfg = config()
    with (bound or db.engine()).begin() as connection:
        if connection.dialect.name == "postgresql":  # (SQLite's BEGIN IMMEDIATE already serialises)
            connection.exec_driver_sql(f"SELECT pg_advisory_xact_lock({MIGRATION_LOCK})")
        cfg.attributes["connection"] = connection
        command.upgrade(cfg, revision)
