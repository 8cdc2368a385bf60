"""Symbolic simplification under a hard time limit, in a warm worker process.

sympy's simplify can take arbitrarily long on an adversarial expression, and a thread cannot be
stopped, so the work runs in a child process (``python -m practice.worker``) that is killed, and
later restarted, when it overruns. Starting one costs about 0.7 s (importing sympy), so one is kept
warm and reused; while it is busy or starting, callers do not wait: they get ``None``
(inconclusive) and the numeric check decides.

The pipe carries length-prefixed pickles of sympy expressions that the parser built (never user
text) and booleans back, between this process and its own child.
"""
from __future__ import annotations

import os
import pickle
import select
import struct
import subprocess
import sys
import threading
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
_HEADER = struct.Struct("!I")


def _write(stream, obj) -> None:
    data = pickle.dumps(obj)
    stream.write(_HEADER.pack(len(data)) + data)
    stream.flush()


def _read(stream):
    header = stream.read(_HEADER.size)
    if len(header) < _HEADER.size:
        raise EOFError
    (size,) = _HEADER.unpack(header)
    return pickle.loads(stream.read(size))


def _serve() -> None:  # the child
    import sympy as sp

    stdin, stdout = sys.stdin.buffer, sys.stdout.buffer
    _write(stdout, "ready")
    while True:
        try:
            expr = _read(stdin)
        except EOFError:
            return
        try:
            _write(stdout, bool(sp.simplify(expr) == 0))
        except Exception:  # noqa: BLE001 - any failure is simply inconclusive
            _write(stdout, None)


class SimplifyWorker:
    def __init__(self):
        self._lock = threading.Lock()
        self._proc: subprocess.Popen | None = None
        self._ready = False

    def _start(self) -> None:
        self._proc = subprocess.Popen([sys.executable, "-m", "practice.worker"], cwd=ROOT,
                                      stdin=subprocess.PIPE, stdout=subprocess.PIPE,
                                      stderr=subprocess.DEVNULL, env={**os.environ, "PYTHONPATH": str(ROOT)})
        self._ready = False

    def _stop(self) -> None:
        if self._proc is not None:
            self._proc.kill()
            self._proc.wait(2)
        self._proc, self._ready = None, False

    def _replace(self) -> None:
        self._stop()
        self._start()

    def _poll(self, timeout: float) -> bool:
        readable, _, _ = select.select([self._proc.stdout], [], [], max(0.0, timeout))
        return bool(readable)

    def warm(self, wait: float = 0.0) -> bool:
        """Start the worker if needed; optionally wait up to ``wait`` s for it to be ready."""
        with self._lock:
            return self._warm(wait)

    def _warm(self, wait: float) -> bool:
        if self._proc is None or self._proc.poll() is not None:
            self._start()
        if not self._ready and self._poll(wait):
            try:
                self._ready = _read(self._proc.stdout) == "ready"
            except (EOFError, pickle.UnpicklingError):
                self._stop()
        return self._ready

    def is_zero(self, expr, timeout: float = 1.0, queue_wait: float = 0.2) -> bool | None:
        """True if simplify(expr) == 0 within ``timeout`` s; False if it simplifies to something
        else; None if inconclusive (worker busy, starting, failed or too slow: then killed)."""
        if not self._lock.acquire(timeout=queue_wait):
            return None
        try:
            if not self._warm(0.0):
                return None
            started = time.monotonic()
            _write(self._proc.stdin, expr)
            if self._poll(timeout - (time.monotonic() - started)):
                return _read(self._proc.stdout)
            self._replace()  # overran: kill it and start a fresh one, warm for the next answer
            return None
        except (OSError, EOFError, pickle.PickleError, ValueError):
            self._replace()  # it died (killed, out of memory): a fresh one, warm for the next answer
            return None
        finally:
            self._lock.release()

    def close(self) -> None:
        with self._lock:
            self._stop()


_WORKER: SimplifyWorker | None = None
_WORKER_LOCK = threading.Lock()


def shared_worker() -> SimplifyWorker:
    """One warm worker per process."""
    global _WORKER
    with _WORKER_LOCK:
        if _WORKER is None:
            _WORKER = SimplifyWorker()
        return _WORKER


if __name__ == "__main__":
    _serve()
