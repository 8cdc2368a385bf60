"""Create or upgrade the schema with Alembic (``migrations/``): ``python -m assignments migrate``."""
from __future__ import annotations

from alembic import command
from alembic.config import Config
from sqlalchemy.engine import Engine

from assignments import db

SCRIPTS = db.ROOT / "migrations"


def config() -> Config:
    cfg = Config()
    cfg.set_main_option("script_location", str(SCRIPTS))
    return cfg


def upgrade(bound: Engine | None = None, revision: str = "head") -> None:
    """Bring the database of ``bound`` (the process's engine by default) to ``revision``."""
    cfg = config()
    with (bound or db.engine()).begin() as connection:
        cfg.attributes["connection"] = connection
        command.upgrade(cfg, revision)
