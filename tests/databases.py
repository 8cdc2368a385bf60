"""Throw-away databases for the tests: a SQLite file, and a PostgreSQL cluster from Debian's
package (initdb + pg_ctl into a temporary directory, a Unix socket only, stopped at the end).
Never a database the tests did not start."""
from __future__ import annotations

import contextlib
import os
import pwd
import shutil
import subprocess
import tempfile
from pathlib import Path

def _newest_postgres() -> Path:
    """Debian's newest installed server (15 on bookworm), or DL_PG_BIN."""
    if os.environ.get("DL_PG_BIN"):
        return Path(os.environ["DL_PG_BIN"])
    found = sorted(Path("/usr/lib/postgresql").glob("*/bin/initdb"), key=lambda p: int(p.parent.parent.name)
                   if p.parent.parent.name.isdigit() else 0)
    return found[-1].parent if found else Path("/usr/lib/postgresql/15/bin")


PG_BIN = _newest_postgres()


def postgres_missing() -> str | None:
    """Why PostgreSQL cannot run here (None when it can)."""
    if not (PG_BIN / "initdb").exists():
        return f"no PostgreSQL at {PG_BIN} (apt-get install postgresql)"
    if os.geteuid() == 0:
        try:
            pwd.getpwnam("postgres")
        except KeyError:
            return "running as root, and no 'postgres' user to run the server as"
    return None


@contextlib.contextmanager
def postgres_cluster():
    """A running cluster; yields the URL of its ``postgres`` database (trust auth, socket in a temp dir)."""
    tmp = Path(tempfile.mkdtemp(prefix="dl-pg-"))
    as_server = []
    if os.geteuid() == 0:  # initdb refuses root: run the server as Debian's postgres user
        user = pwd.getpwnam("postgres")
        os.chown(tmp, user.pw_uid, user.pw_gid)
        as_server = ["runuser", "-u", "postgres", "--"]
    data = tmp / "data"
    quiet = {"stdout": subprocess.DEVNULL, "stderr": subprocess.PIPE, "check": True}
    try:
        subprocess.run([*as_server, str(PG_BIN / "initdb"), "-D", str(data), "-U", "postgres", "--auth=trust",
                        "-E", "UTF8", "--no-sync"], **quiet)
        options = f"-c listen_addresses='' -c unix_socket_directories={tmp} -c fsync=off -c max_connections=200"
        subprocess.run([*as_server, str(PG_BIN / "pg_ctl"), "-D", str(data), "-o", options, "-l",
                        str(tmp / "server.log"), "-w", "-t", "60", "start"], **quiet)
        yield f"postgresql+psycopg://postgres@/postgres?host={tmp}"
    finally:
        if (data / "postmaster.pid").exists():
            subprocess.run([*as_server, str(PG_BIN / "pg_ctl"), "-D", str(data), "-m", "immediate", "stop"],
                           stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        shutil.rmtree(tmp, ignore_errors=True)
