"""A static file's bytes as the browser takes them: brotli where it asks for br, else gzip, each made once.

Brotli at its best quality (11) is a sixth smaller than gzip's best on the app's JavaScript (plotly.js's bundle
355 → 293 KB, KaTeX's script 73 → 61 KB, the 3-D bundle 518 → 420 KB: a first visit's bytes, on a phone) but
takes one to two seconds a megabyte, too long to make while a student waits. So a file leaves gzipped until its
brotli is ready: made once, in one background thread at the lowest CPU priority (brotli lets go of the
interpreter lock, so a page's run is not held up by it), and kept on disk beside the generated code
(``solvers.kept.cache_dir``) under the hash of the file's bytes, where a later process or another replica of
the same image finds it. No cache directory: made again by each process, still in the background.
"""
from __future__ import annotations

import hashlib
import os
import threading
from concurrent.futures import Future, ThreadPoolExecutor

import brotli

BROTLI_QUALITY = 11


def accepts(scope, coding: str) -> bool:
    """The request's Accept-Encoding names ``coding`` (or *) without ``q=0``."""
    header = dict(scope["headers"]).get(b"accept-encoding", b"").decode("latin-1")
    for item in header.split(","):
        name, _, params = item.partition(";")
        quality = params.replace(" ", "").removeprefix("q=")
        if name.strip() in (coding, "*") and not (params and _is_zero(quality)):
            return True
    return False


def _is_zero(quality: str) -> bool:
    try:
        return float(quality) == 0
    except ValueError:
        return False


def _lowest_priority() -> None:
    try:  # Linux: a thread is a task of its own, with its own nice value
        os.setpriority(os.PRIO_PROCESS, threading.get_native_id(), 19)
    except (AttributeError, OSError):  # elsewhere the thread keeps the process's priority
        pass


_BACKGROUND = ThreadPoolExecutor(max_workers=1, thread_name_prefix="brotli", initializer=_lowest_priority)


def _kept_path(raw: bytes):
    from solvers.kept import cache_dir  # (here: serve.py imports this module before anything heavy)

    where = cache_dir()
    if where is None:
        return None
    digest = hashlib.sha256(raw).hexdigest()[:32]
    return where / "brotli" / f"{digest}.q{BROTLI_QUALITY}.{brotli.version}.br"


def _brotli(raw: bytes) -> bytes:
    """``raw`` in brotli: from the disk where a process made it before, else made and kept there."""
    path = _kept_path(raw)
    if path is not None:
        try:
            packed = path.read_bytes()
            if brotli.decompress(packed) == raw:  # (a torn or foreign file is made again)
                return packed
        except Exception:
            pass
    packed = brotli.compress(raw, quality=BROTLI_QUALITY)
    if path is not None:
        try:
            path.parent.mkdir(parents=True, exist_ok=True)
            partial = path.with_name(f".{path.name}.{os.getpid()}.{threading.get_native_id()}")
            partial.write_bytes(packed)
            os.replace(partial, path)  # whole or not at all: another process may be reading
        except OSError:
            pass
    return packed


class Compressed:
    """One file's bytes, gzipped (given) and in brotli (made in the background on first ask)."""

    def __init__(self, raw: bytes, gzipped: bytes):
        self.raw, self.gzipped = raw, gzipped
        self._brotli: Future | None = None
        self._lock = threading.Lock()

    def brotli(self) -> Future:
        """The brotli bytes to come (started at the first call)."""
        with self._lock:
            if self._brotli is None:
                self._brotli = _BACKGROUND.submit(_brotli, self.raw)
            return self._brotli

    def body(self, scope) -> tuple[bytes, bytes | None]:
        """What to send to this request and its Content-Encoding (None: the file as it is)."""
        if accepts(scope, "br"):
            made = self.brotli()
            if made.done() and made.exception() is None:
                return made.result(), b"br"
        if accepts(scope, "gzip"):
            return self.gzipped, b"gzip"
        return self.raw, None
