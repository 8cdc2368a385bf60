"""Costly figures drawn on request (Euler's disk running down: some 250,000 steps of its full
equations), in a worker process of their own.

In a server's thread such an integration holds the interpreter for seconds, and every other session
in the process waited for it: a 2 ms run took 370 ms while one run-down was computed beside it. In
the worker the server's threads only wait for the answer, which holds nothing. Requests queue for
the one worker (two would take the second core a replica's other sessions need); each figure is
kept in the server by its parameters, shared by every session.
"""
from __future__ import annotations

import functools
import multiprocessing
import threading
from concurrent.futures import ProcessPoolExecutor
from concurrent.futures.process import BrokenProcessPool

_lock = threading.Lock()
_pool: ProcessPoolExecutor | None = None
_asked = 0  # requests in the worker or queued for it: what a new one waits behind


def _worker() -> ProcessPoolExecutor:
    global _pool
    with _lock:
        if _pool is None:  # a fresh interpreter (spawn): the server's threads and locks stay behind
            _pool = ProcessPoolExecutor(max_workers=1, mp_context=multiprocessing.get_context("spawn"))
        return _pool


def _replace(broken: ProcessPoolExecutor) -> None:
    global _pool
    with _lock:
        if _pool is broken:
            _pool = None


def in_worker(function, *args):
    """``function(*args)`` computed in the worker process (after the requests queued before it); a
    worker that died (killed, out of memory) is replaced once."""
    global _asked
    with _lock:
        _asked += 1
    try:
        for attempt in (1, 2):
            pool = _worker()
            try:
                return pool.submit(function, *args).result()
            except BrokenProcessPool:
                _replace(pool)
                if attempt == 2:
                    raise
    finally:
        with _lock:
            _asked -= 1


def waiting() -> int:
    """How many requests are in the worker or queued for it now."""
    return _asked


def drawn(problem_id: str, params: tuple):
    """The problem's on-request figure for these parameters (``(name, value)`` pairs), drawn here."""
    from solvers import registry
    from viz.catalog import drawings

    solution = registry.solver(problem_id).solve(**dict(params))
    return drawings(problem_id).on_request.draw(solution)


@functools.lru_cache(maxsize=64)
def figure(problem_id: str, params: tuple):
    """The problem's on-request figure, drawn in the worker once per parameters and kept."""
    return in_worker(drawn, problem_id, params)
