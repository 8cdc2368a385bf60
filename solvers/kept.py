"""What the sympy work gives, kept on disk between processes.

Deriving each problem (sympy's solve and simplify) and generating its JavaScript (its live values, pose and
motion) is most of a server's warm-up (27 s of it here without this, 15 s with; in every process at every start)
and of every test process that solves or draws a problem. What it gives depends on nothing but the code
and the arguments, so it is kept under a key of both: a changed byte of the solvers, the viz modules that
draw the figures, or the two ui modules that name and generate the files, is a new key. The interpreter's,
sympy's and numpy's versions are in the key too.

DL_GENERATED_CACHE names the directory (unset: ``dynamics-lab/generated`` under $XDG_CACHE_HOME or
~/.cache; "off": none). A directory that cannot be written is no cache: the process works as before. The
files are this program's own (text, and pickles of its derivations): the directory is the user's, as
the code is.
"""
from __future__ import annotations

import functools
import hashlib
import os
import pickle
import sys
from pathlib import Path
from typing import Callable

import numpy as np
import sympy as sp

CODE = Path(__file__).resolve().parent.parent


def _code_files() -> list[Path]:
    # (ui/figure.py names the generated files a motion module imports; ui/live.py generates the modules)
    return sorted([*(CODE / "solvers").glob("*.py"), *(CODE / "viz").glob("*.py"), CODE / "ui" / "live.py",
                   CODE / "ui" / "figure.py"])


@functools.cache
def code_key() -> str:
    digest = hashlib.sha256(repr((sys.version, sp.__version__, np.__version__)).encode())
    for path in _code_files():
        digest.update(str(path.relative_to(CODE)).encode() + b"\0" + path.read_bytes() + b"\0")
    return digest.hexdigest()[:20]


def cache_dir() -> Path | None:
    where = os.environ.get("DL_GENERATED_CACHE", "")
    if where == "off":
        return None
    if where:
        return Path(where)
    try:
        base = Path(os.environ.get("XDG_CACHE_HOME") or Path.home() / ".cache")
    except RuntimeError:  # no home to be found (a uid without an account, no HOME): no cache
        return None
    return base / "dynamics-lab" / "generated"


def _on_disk(suffix: str, dump: Callable[[object], bytes], load: Callable[[bytes], object]):
    def decorator(make: Callable):
        """``make`` (a value from hashable arguments) read from the disk where an earlier process wrote it."""
        @functools.wraps(make)
        def kept(*args):
            where = cache_dir()
            if where is None:
                return make(*args)
            name = hashlib.sha256(repr((make.__module__, make.__qualname__, args)).encode()).hexdigest()[:32]
            path = where / code_key() / (name + suffix)
            try:
                return load(path.read_bytes())
            except Exception:  # (none yet, or unreadable: made again and written over)
                pass
            value = make(*args)
            if value is not None:
                try:
                    path.parent.mkdir(parents=True, exist_ok=True)
                    partial = path.with_name(f".{path.name}.{os.getpid()}")
                    partial.write_bytes(dump(value))
                    os.replace(partial, path)  # whole or not at all: another process may be reading
                except OSError:
                    pass
            return value
        return kept
    return decorator


def _unpickled(data: bytes):
    """A pickle's sympy expressions as they were: rebuilt from their arguments with evaluation on, sympy
    would rewrite some ((R ω + 2 V sin θ)/3 came back as R ω/3 + 2 V sin θ/3, and the numeric steps' LaTeX
    with it)."""
    with sp.evaluate(False):
        return pickle.loads(data)


kept_on_disk = _on_disk(".js", str.encode, bytes.decode)  # generated JavaScript
kept_pickled = _on_disk(".pickle", functools.partial(pickle.dumps, protocol=pickle.HIGHEST_PROTOCOL), _unpickled)
