"""Alembic's environment: migrate the engine ``assignments.migrate.upgrade`` hands in (the app's
own, with its SQLite settings), or the database of ``sqlalchemy.url`` / ``DL_DATABASE_URL``."""
from alembic import context

from assignments import db

config = context.config
connection = config.attributes.get("connection")


def run(conn) -> None:
    context.configure(connection=conn, target_metadata=db.Base.metadata,
                      render_as_batch=conn.dialect.name == "sqlite")  # SQLite alters tables by copying
    with context.begin_transaction():
        context.run_migrations()


if connection is not None:
    run(connection)
else:
    engine = db.make_engine(config.get_main_option("sqlalchemy.url") or db.database_url())
    with engine.connect() as conn:
        run(conn)
    engine.dispose()
