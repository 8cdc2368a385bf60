"""Production entry point: warm every derivation, then start Streamlit in the same process.

Streamlit has no start-up hook, and its health endpoint answers as soon as the server listens.
Derivations are cached in module globals (functools.cache), so running each problem once here,
before the server starts, means /_stcore/health answers only when this replica is warm: the
first student on a new replica waits for nothing. It also turns Nagle's algorithm off on every
connection (see ``accept_without_nagle``). Arguments after the script name go to
``streamlit run app.py``, e.g. ``python serve.py --server.port 8501``.
"""
from __future__ import annotations

import gc
import itertools
import logging
import socket
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent


def warm() -> float:
    """Solve every problem for every option (deriving each sympy chain once) and build its figures."""
    import importlib

    from practice.worker import shared_worker
    from solvers.core import Choice
    from ui.catalog import PROBLEMS

    started = time.perf_counter()
    shared_worker().warm()
    for problem in PROBLEMS:
        solver = importlib.import_module(f"solvers.{problem.id}")
        viz = importlib.import_module(f"viz.{problem.id}")
        choices = [p for p in solver.PARAMS if isinstance(p, Choice)]
        for combination in itertools.product(*(c.options for c in choices)):
            solution = solver.solve(**dict(zip((c.name for c in choices), combination)))
            viz.figures(solution)
        if problem.id == "disk_wall":
            solver.solve(mu=0.01, omega=-40.0)  # the sliding regime's derivation
    # The one costly on-request figure, for the textbook's numbers (shared by every session).
    from ui.page import _requested

    default = importlib.import_module("solvers.eulers_disk").solve()
    _requested("eulers_disk", tuple(sorted(default.params.items())))
    return time.perf_counter() - started


def accept_without_nagle() -> None:
    """Let every accepted connection send at once (TCP_NODELAY), as asyncio means it to.

    Streamlit binds its listening socket itself (``_bind_socket``) and leaves its protocol number
    at 0. Accepted sockets inherit that, and asyncio turns TCP_NODELAY on only for sockets that
    say IPPROTO_TCP, so every connection kept Nagle's algorithm: a small message written while the
    previous one is unacknowledged waits for the browser's delayed ACK, 40 ms on Linux. That was a
    fixed 40 ms on every first load and on some 5–10 % of the interactions under load (the same
    bug as uvicorn #3149). Re-wrapping the bound socket with its true protocol is enough.
    """
    from streamlit.web.server.starlette import starlette_server

    bind = starlette_server._bind_socket  # fails loudly if a Streamlit upgrade renames it

    def bind_tcp(address: str, port: int, backlog: int) -> socket.socket:
        bound = bind(address, port, backlog)
        if bound.family not in (socket.AF_INET, socket.AF_INET6) or bound.proto == socket.IPPROTO_TCP:
            return bound
        tcp = socket.socket(bound.family, bound.type, socket.IPPROTO_TCP, fileno=bound.detach())
        tcp.setblocking(False)
        tcp.set_inheritable(True)
        return tcp

    starlette_server._bind_socket = bind_tcp


def serve_figure_bundles() -> None:
    """Serve the figure component's plotly bundles gzipped once and cached by browsers for a year
    (``ui.figure.BundleServer``). Streamlit's own component route would send them with a bare
    ``Cache-Control: public`` and no validator, so every visit downloaded plotly.js again, and
    gzip them anew on every request."""
    from starlette.middleware import Middleware
    from streamlit.web.server.starlette import starlette_app

    from ui.figure import BundleServer

    streamlit_middleware = starlette_app.create_streamlit_middleware  # fails loudly if renamed

    def with_bundles():
        stack = streamlit_middleware()
        stack.insert(1, Middleware(BundleServer))  # after the path-security check, before gzip
        return stack

    starlette_app.create_streamlit_middleware = with_bundles


def run(script: Path, argv: list[str]) -> None:
    """``streamlit run script *argv`` in this process, with Nagle off, the figure bundles cached by
    browsers and the warmed heap frozen."""
    accept_without_nagle()
    serve_figure_bundles()
    # The warmed derivations (sympy trees, lambdified code) live as long as the process: move them
    # out of the collector's sight, so a full collection under load scans only what requests make.
    gc.collect()
    gc.freeze()
    from streamlit.web import cli

    sys.argv = ["streamlit", "run", str(script), *argv]
    sys.exit(cli.main())


def main() -> None:
    sys.path.insert(0, str(ROOT))
    seconds = warm()
    logging.getLogger("dynamics_lab").warning("warmed in %.1f s", seconds)
    run(ROOT / "app.py", sys.argv[1:])


if __name__ == "__main__":
    main()
