"""LTI 1.3: spent nonces and hand-offs, resource links, LMS students and their scores for the LMS.

New tables only: an existing SQLite or PostgreSQL database gains them in place, nothing copied.

Revision ID: 0003
Revises: 0002
Create Date: 2026-11-24
"""
import sqlalchemy as sa
from alembic import op

revision = "0003"
down_revision = "0002"
branch_labels = None
depends_on = None

UTC_TIME = sa.DateTime(timezone=True)


def _assignment():
    return sa.Column("assignment_id", sa.Integer(), sa.ForeignKey("assignment.id", ondelete="CASCADE"),
                     nullable=False)


def upgrade() -> None:
    op.create_table("lti_used", sa.Column("key", sa.String(200), primary_key=True),
                    sa.Column("at", UTC_TIME, nullable=False))
    op.create_index("ix_lti_used_at", "lti_used", ["at"])
    op.create_table(
        "lti_link", sa.Column("id", sa.Integer(), primary_key=True), _assignment(),
        sa.Column("issuer", sa.String(255), nullable=False), sa.Column("deployment_id", sa.String(255), nullable=False),
        sa.Column("context_id", sa.String(255), nullable=False),
        sa.Column("resource_link_id", sa.String(255), nullable=False),
        sa.Column("lineitem", sa.String(1000), nullable=False),
        sa.UniqueConstraint("issuer", "deployment_id", "resource_link_id"))
    op.create_table(
        "lti_member", sa.Column("id", sa.Integer(), primary_key=True), _assignment(),
        sa.Column("label", sa.String(40), nullable=False), sa.Column("issuer", sa.String(255), nullable=False),
        sa.Column("sub", sa.String(255), nullable=False), sa.Column("name", sa.String(200), nullable=False),
        sa.UniqueConstraint("assignment_id", "label"))
    op.create_table(
        "lti_score", sa.Column("id", sa.Integer(), primary_key=True), _assignment(),
        sa.Column("label", sa.String(40), nullable=False), sa.Column("status", sa.String(16), nullable=False),
        sa.Column("sent", sa.Float(), nullable=True), sa.Column("sent_progress", sa.String(20), nullable=False),
        sa.Column("tries", sa.Integer(), nullable=False), sa.Column("next_try", UTC_TIME, nullable=False),
        sa.Column("error", sa.String(1000), nullable=False), sa.UniqueConstraint("assignment_id", "label"))
    for table in ("lti_link", "lti_member", "lti_score"):
        op.create_index(f"ix_{table}_assignment_id", table, ["assignment_id"])
    op.create_index("ix_lti_link_context_id", "lti_link", ["context_id"])
    op.create_index("ix_lti_score_next_try", "lti_score", ["next_try"])


def downgrade() -> None:
    for table in ("lti_score", "lti_member", "lti_link", "lti_used"):
        op.drop_table(table)
