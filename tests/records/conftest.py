"""The record pages' shared setting (AppTest): the instructor key and a SQLite file of the test's own, the
process's engine and schema check forgotten before and after (``reset_database_caches``, also after a test
points the app at another database)."""
from __future__ import annotations

import pytest

from assignments import db
from tests.conftest import INSTRUCTOR_KEY


def reset_database_caches() -> None:
    from ui.session import schema_ready

    db.engine.cache_clear()
    schema_ready.clear()


@pytest.fixture
def course_database(monkeypatch, tmp_path):
    monkeypatch.setenv("DL_INSTRUCTOR_KEY", INSTRUCTOR_KEY)
    monkeypatch.setenv(db.URL_ENV, f"sqlite:///{tmp_path / 'course.sqlite'}")
    reset_database_caches()
    yield
    reset_database_caches()
