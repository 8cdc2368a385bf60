"""Questions put to a lecture hall and the room's answers (room/, ui/room.py).

Revision ID: 0005
Revises: 0004
Create Date: 2026-11-29
"""
import sqlalchemy as sa
from alembic import op

UTC_TIME = sa.DateTime(timezone=True)

revision = "0005"
down_revision = "0004"
branch_labels = None
depends_on = None


def upgrade() -> None:
    op.create_table(
        "room_question",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("code", sa.String(8), nullable=False),
        sa.Column("round", sa.Integer, nullable=False),
        sa.Column("problem", sa.String(40), nullable=False),
        sa.Column("question", sa.String(60), nullable=False),
        sa.Column("params", sa.Text, nullable=False),
        sa.Column("system", sa.String(4), nullable=False),
        sa.Column("hide_motion", sa.Boolean, nullable=False),
        sa.Column("status", sa.String(12), nullable=False),
        sa.Column("opened", UTC_TIME, nullable=False),
        sa.Column("course", sa.String(600), nullable=False),
        sa.UniqueConstraint("code", "round"),
    )
    op.create_index("ix_room_question_code", "room_question", ["code"])
    op.create_index("ix_room_question_opened", "room_question", ["opened"])
    op.create_table(
        "room_response",
        sa.Column("id", sa.Integer, primary_key=True),
        sa.Column("question_id", sa.Integer, sa.ForeignKey("room_question.id", ondelete="CASCADE"), nullable=False),
        sa.Column("responder", sa.String(64), nullable=False),
        sa.Column("category", sa.String(200), nullable=False),
        sa.Column("at", UTC_TIME, nullable=False),
        sa.UniqueConstraint("question_id", "responder"),
    )
    op.create_index("ix_room_response_question_id", "room_response", ["question_id"])


def downgrade() -> None:
    op.drop_table("room_response")
    op.drop_table("room_question")
