"""``python -m assignments migrate``: create or upgrade the database's schema (DL_DATABASE_URL, or
the SQLite file under DL_DATA_DIR)."""
import sys

from assignments import db, migrate

if __name__ == "__main__":
    if sys.argv[1:] != ["migrate"]:
        sys.exit("usage: python -m assignments migrate")
    try:
        migrate.upgrade()
    except migrate.DatabaseMissing as error:
        sys.exit(str(error))
    print(f"schema at head: {db.described()}")
