"""An attempt's reading: what the judge read in the typed text, so that the same answer typed
another way ("-14.54" where ° is shown, then "-14.54 °") counts once.

One column with a default: earlier attempts keep "" (compared by their text, as before).

Revision ID: 0004
Revises: 0003
Create Date: 2026-11-28
"""
import sqlalchemy as sa
from alembic import op

revision = "0004"
down_revision = "0003"
branch_labels = None
depends_on = None


def upgrade() -> None:
    with op.batch_alter_table("attempt") as batch:
        batch.add_column(sa.Column("reading", sa.String(64), nullable=False, server_default=""))


def downgrade() -> None:
    with op.batch_alter_table("attempt") as batch:
        batch.drop_column("reading")
