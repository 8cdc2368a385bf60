"""Assignments, their rosters, every attempt, and the solutions shown.

Revision ID: 0001
Revises:
Create Date: 2026-11-23
"""
import sqlalchemy as sa
from alembic import op

revision = "0001"
down_revision = None
branch_labels = None
depends_on = None

UTC_TIME = sa.DateTime(timezone=True)  # assignments.db.UTCDateTime stores through this


def upgrade() -> None:
    op.create_table(
        "assignment",
        sa.Column("id", sa.Integer(), primary_key=True),
        sa.Column("title", sa.String(120), nullable=False),
        sa.Column("problem", sa.String(40), nullable=False),
        sa.Column("answers", sa.JSON(), nullable=False),
        sa.Column("tolerance", sa.Float(), nullable=False),
        sa.Column("due", UTC_TIME, nullable=False),
        sa.Column("attempts_allowed", sa.Integer(), nullable=False),
        sa.Column("solution_before_due", sa.Boolean(), nullable=False),
        sa.Column("created", UTC_TIME, nullable=False),
    )
    for table, columns in (
        ("student", [sa.Column("seed", sa.Integer(), nullable=False)]),
        ("attempt", [sa.Column("answer", sa.String(40), nullable=False),
                     sa.Column("typed", sa.String(400), nullable=False),
                     sa.Column("correct", sa.Boolean(), nullable=False),
                     sa.Column("message", sa.String(1000), nullable=False),
                     sa.Column("slip", sa.String(400), nullable=False),
                     sa.Column("at", UTC_TIME, nullable=False),
                     sa.Column("late", sa.Boolean(), nullable=False),
                     sa.Column("solution_shown", sa.Boolean(), nullable=False)]),
        ("reveal", [sa.Column("at", UTC_TIME, nullable=False)]),
    ):
        op.create_table(
            table,
            sa.Column("id", sa.Integer(), primary_key=True),
            sa.Column("assignment_id", sa.Integer(), sa.ForeignKey("assignment.id", ondelete="CASCADE"),
                      nullable=False),
            sa.Column("label", sa.String(40), nullable=False),
            *columns,
            *([sa.UniqueConstraint("assignment_id", "label")] if table == "student" else []),
        )
        op.create_index(f"ix_{table}_assignment_id", table, ["assignment_id"])


def downgrade() -> None:
    for table in ("reveal", "attempt", "student", "assignment"):
        op.drop_table(table)
