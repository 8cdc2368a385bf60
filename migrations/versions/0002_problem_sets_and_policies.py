"""Problem sets, late credit, feedback policy, per-student extensions, and the change history.

An assignment's one problem and its answers become its parts (a list of problems, each with its
answers and weights); attempts and reveals name their problem; an assignment gains its time zone,
status (open, closed, archived), late policy, feedback policy and a fingerprint that makes a
repeated "Create" find the assignment already made; a student gains an extension and extra
attempts; every instructor change is kept in ``assignment_change``.

No table is copied (SQLite's batch mode): copying ``assignment`` drops the old table, and its
ON DELETE CASCADE would take every student and attempt with it. Columns are added and dropped in
place (SQLite 3.35 and later), with constant defaults, and the fingerprint is a unique index.

Revision ID: 0002
Revises: 0001
Create Date: 2026-11-24
"""
import sqlalchemy as sa
from alembic import op

revision = "0002"
down_revision = "0001"
branch_labels = None
depends_on = None

UTC_TIME = sa.DateTime(timezone=True)
TRUE, FALSE = "1", "0"  # constant defaults (a SQL expression would make SQLite copy the table)


def upgrade() -> None:
    bind = op.get_bind()
    for table in ("attempt", "reveal"):
        op.add_column(table, sa.Column("problem", sa.String(40), nullable=False, server_default=""))
        bind.execute(sa.text(f"UPDATE {table} SET problem = (SELECT assignment.problem FROM assignment "
                             f"WHERE assignment.id = {table}.assignment_id)"))
    op.add_column("assignment", sa.Column("parts", sa.JSON(), nullable=False, server_default="[]"))
    old = sa.table("assignment", sa.column("id", sa.Integer()), sa.column("problem", sa.String()),
                   sa.column("answers", sa.JSON()), sa.column("parts", sa.JSON()))
    for aid, problem, answers in bind.execute(sa.select(old.c.id, old.c.problem, old.c.answers)).all():
        part = {"problem": problem, "answers": list(answers), "weights": [1.0] * len(answers)}
        bind.execute(old.update().where(old.c.id == aid).values(parts=[part]))
    op.drop_column("assignment", "problem")
    op.drop_column("assignment", "answers")
    for column in (sa.Column("timezone", sa.String(64), nullable=False, server_default="UTC"),
                   sa.Column("status", sa.String(16), nullable=False, server_default="open"),
                   sa.Column("late_policy", sa.String(16), nullable=False, server_default="none"),
                   sa.Column("late_value", sa.Float(), nullable=False, server_default="0"),
                   sa.Column("hints", sa.Boolean(), nullable=False, server_default=TRUE),
                   sa.Column("slip_names", sa.Boolean(), nullable=False, server_default=TRUE),
                   sa.Column("answer_after_last", sa.Boolean(), nullable=False, server_default=FALSE),
                   sa.Column("fingerprint", sa.String(64), nullable=True)):
        op.add_column("assignment", column)
    op.create_index("uq_assignment_fingerprint", "assignment", ["fingerprint"], unique=True)
    op.add_column("student", sa.Column("extended_due", UTC_TIME, nullable=True))
    op.add_column("student", sa.Column("extra_attempts", sa.Integer(), nullable=False, server_default="0"))
    op.create_table(
        "assignment_change",
        sa.Column("id", sa.Integer(), primary_key=True),
        sa.Column("assignment_id", sa.Integer(), sa.ForeignKey("assignment.id", ondelete="CASCADE"), nullable=False),
        sa.Column("at", UTC_TIME, nullable=False),
        sa.Column("action", sa.String(40), nullable=False),
        sa.Column("label", sa.String(40), nullable=False),
        sa.Column("summary", sa.String(1000), nullable=False),
        sa.Column("before", sa.JSON(), nullable=False),
        sa.Column("after", sa.JSON(), nullable=False),
        sa.Column("undoes", sa.Integer(), nullable=True),
    )
    op.create_index("ix_assignment_change_assignment_id", "assignment_change", ["assignment_id"])


def downgrade() -> None:
    bind = op.get_bind()
    op.drop_table("assignment_change")
    op.drop_column("student", "extra_attempts")
    op.drop_column("student", "extended_due")
    op.drop_index("uq_assignment_fingerprint", table_name="assignment")
    for column in ("fingerprint", "answer_after_last", "slip_names", "hints", "late_value", "late_policy",
                   "status", "timezone"):
        op.drop_column("assignment", column)
    op.add_column("assignment", sa.Column("problem", sa.String(40), nullable=False, server_default=""))
    op.add_column("assignment", sa.Column("answers", sa.JSON(), nullable=False, server_default="[]"))
    new = sa.table("assignment", sa.column("id", sa.Integer()), sa.column("problem", sa.String()),
                   sa.column("answers", sa.JSON()), sa.column("parts", sa.JSON()))
    for aid, parts in bind.execute(sa.select(new.c.id, new.c.parts)).all():  # the first problem only
        first = parts[0]["problem"]
        bind.execute(new.update().where(new.c.id == aid).values(problem=first, answers=list(parts[0]["answers"])))
        for table in ("attempt", "reveal"):  # the old schema has no room for the other problems' records
            bind.execute(sa.text(f"DELETE FROM {table} WHERE assignment_id = :aid AND problem != :first"),
                         {"aid": aid, "first": first})
    op.drop_column("assignment", "parts")
    op.drop_column("reveal", "problem")
    op.drop_column("attempt", "problem")
