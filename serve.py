"""Production entry point: warm every derivation, then start Streamlit in the same process.

Streamlit has no start-up hook, and its health endpoint answers as soon as the server listens.
Derivations are cached in module globals (functools.cache), so running each problem once here,
before the server starts, means /_stcore/health answers only when this replica is warm: the
first student on a new replica waits for nothing. It also turns Nagle's algorithm off on every
connection (see ``accept_without_nagle``). Arguments after the script name go to
``streamlit run app.py``, e.g. ``python serve.py --server.port 8501``.
"""
from __future__ import annotations

import asyncio
import gc
import gzip
import itertools
import logging
import os
import socket
import sys
import threading
import time
from pathlib import Path

from edge.compressed import Compressed, accepts

ROOT = Path(__file__).resolve().parent


def warm() -> float:
    """Solve every problem for every option (deriving each sympy chain once), build its figures and
    generate its live view's function and pose module (for each unit system it is offered in)."""
    from practice.worker import shared_worker
    from solvers import registry
    from solvers.core import Choice
    from ui import live
    from solvers.catalog import BY_ID
    from viz import on_request
    from viz.catalog import drawings

    started = time.perf_counter()
    shared_worker().warm()
    # A costly figure on request, for the textbook's numbers: drawn in its worker process (the other
    # core) while this one warms the rest, and waited for at the end (it took ~10 s on its own here).
    requested = [threading.Thread(target=on_request.figure, args=(pid, tuple(sorted(solver.solve().params.items()))),
                                  name=f"warm {pid}'s on-request figure")
                 for pid, solver in zip(registry.PROBLEM_IDS, registry.solvers())
                 if drawings(pid).on_request]
    for thread in requested:
        thread.start()
    for pid, solver in zip(registry.PROBLEM_IDS, registry.solvers()):
        figures = drawings(pid).figures
        choices = [p for p in solver.PARAMS if isinstance(p, Choice)]
        for combination in itertools.product(*(c.options for c in choices)):
            solution = solver.solve(**dict(zip((c.name for c in choices), combination)))
            figures(solution)
            for system in ("si", "us") if BY_ID[pid].us_units else ("si",):
                live.warm(pid, solution.params, system)  # the live view's function and pose module
        for params in solver.WARM:  # the states no option combination reaches, or a slider's every position
            figures(solver.solve(**params))
    for thread in requested:
        thread.join()
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


# What Streamlit sends uncompressed that compresses well: its JS bundles (KaTeX among them) and CSS.
# Not HTML: every unknown path gets index.html (2 KB), and caching per path would let any URL grow
# the cache; a JS or CSS response is always a real file, so the cache is bounded by the package.
COMPRESSIBLE = (b"text/javascript", b"application/javascript", b"text/css", b"image/svg+xml")


WEBSOCKET_WINDOW_BITS = 15  # the compressor's window, 2**15 bytes: zlib's largest


def compress_websocket_fast() -> None:
    """The websocket's permessage-deflate (server.enableWebsocketCompression, .streamlit/config.toml) at
    zlib's level 1 instead of its default 6, over a window of the last 32 KB sent instead of uvicorn's 4 KB.
    Level 6 spent about 1 ms on a change's 36 KB, a tenth of the whole run, for 12.6 KB; level 1 takes
    0.2 ms for 14 KB (BENCHMARKS.md §4). The window: most of what a change sends (the derivation's symbolic
    steps, the answers' labels, the figure's layout, a companion's grid) was in the change before it, which
    a 4 KB window cannot reach back to; 32 KB, zlib's largest, does (BENCHMARKS.md §1). It costs each
    connection 144 KB of the compressor's memory where 4 KB cost 32 KB (zlib: 4 × window + 512 × 2^memLevel),
    about 22 MB more for 200 students on a process (docs/deploying.md)."""
    from uvicorn.protocols.websockets import websockets_sansio_impl

    factory = websockets_sansio_impl.ServerPerMessageDeflateFactory  # fails loudly if uvicorn renames it

    class FastDeflate(factory):
        def __init__(self, **options):
            super().__init__(**{**options, "server_max_window_bits": WEBSOCKET_WINDOW_BITS,
                                "compress_settings": {**(options.get("compress_settings") or {}), "level": 1}})

    websockets_sansio_impl.ServerPerMessageDeflateFactory = FastDeflate


class StaticGzip:
    """ASGI middleware (installed by serve.py): Streamlit's own static files compressed, each once.

    Streamlit keeps ``/static/`` and the root document out of its gzip middleware, because that
    middleware would compress them again on every request; so a first visit downloaded its JS
    bundles and KaTeX's 265 KB script uncompressed (BENCHMARKS.md section 6). Here a compressible
    file's answer to a GET (a 200 with an ETag, not already encoded, no Range) is gzipped once per
    (path, ETag) and kept in memory. Streamlit's own headers stay (Cache-Control, Last-Modified);
    the ETag becomes weak, as nginx makes it (other bytes, same file: revalidation still gets its
    304); Content-Length, Content-Encoding and Vary are set for the gzipped body. A browser that takes brotli
    gets it once it is made (``edge.compressed``: in the background, gzip until then). HEAD, Range and
    clients that take neither get Streamlit's answer as it is."""

    def __init__(self, app):
        self.app = app
        self.packed: dict[tuple[str, bytes], Compressed | asyncio.Task] = {}

    async def __call__(self, scope, receive, send):
        if (scope["type"] != "http" or scope["method"] != "GET" or not accepts(scope, "gzip")
                or any(name == b"range" for name, _ in scope["headers"])):
            return await self.app(scope, receive, send)
        # Streamlit's FileResponse may stream the file by path (ASGI pathsend) where the server
        # offers it; the body is needed here, so it is not offered.
        scope = {**scope, "extensions": {k: v for k, v in scope.get("extensions", {}).items()
                                         if k != "http.response.pathsend"}}
        start, chunks = None, []

        async def capture(message):
            nonlocal start
            if start is None and message["type"] == "http.response.start":
                headers = dict(message["headers"])
                if (message["status"] == 200 and b"etag" in headers and b"content-encoding" not in headers
                        and headers.get(b"content-type", b"").startswith(COMPRESSIBLE)):
                    start = message
                    return
                start = False  # not this one's: pass everything through untouched
            if not start or message["type"] != "http.response.body":
                return await send(message)
            chunks.append(message.get("body", b""))
            if not message.get("more_body", False):
                await self._send_packed(scope, send, start, b"".join(chunks))

        await self.app(scope, receive, capture)

    async def _send_packed(self, scope, send, start, raw: bytes):
        headers = dict(start["headers"])
        key = (scope["path"], headers[b"etag"])
        packed = self.packed.get(key)
        if packed is None:
            # Compressed off the event loop, once even when many first visits ask at the same time.
            packed = self.packed[key] = asyncio.ensure_future(asyncio.to_thread(_gzipped, raw))
        if isinstance(packed, asyncio.Task):
            packed = self.packed[key] = await packed
        body, coding = packed.body(scope)
        etag = headers[b"etag"]
        kept = [(k, v) for k, v in start["headers"] if k not in (b"etag", b"content-length", b"vary")]
        vary = b", ".join(v for v in (headers.get(b"vary"), b"Accept-Encoding") if v)
        kept += [(b"etag", etag if etag.startswith(b"W/") else b"W/" + etag), (b"vary", vary),
                 (b"content-encoding", coding), (b"content-length", str(len(body)).encode())]
        await send({**start, "headers": kept})
        await send({"type": "http.response.body", "body": body})


def _gzipped(raw: bytes) -> Compressed:
    return Compressed(raw, gzip.compress(raw, 9))


TRUSTED_PROXIES_ENV = "DL_TRUSTED_PROXIES"


def trust_only_named_proxies() -> None:
    """uvicorn takes a client's address from X-Forwarded-For when the connection comes from one of
    FORWARDED_ALLOW_IPS, by default 127.0.0.1 and ::1: anyone on this machine (or any proxy there)
    could then name any address, and walk round the instructor key's throttle per address. Here it
    trusts exactly the proxies the admin names in DL_TRUSTED_PROXIES (addresses or networks, comma-
    separated; '*' where only the proxy can reach the app, as in Compose and Kubernetes), none when
    unset (``make run``, a one-machine ``docker run``)."""
    os.environ["FORWARDED_ALLOW_IPS"] = os.environ.get(TRUSTED_PROXIES_ENV, "").strip()


def install_middleware() -> None:
    """Put our middlewares in front of Streamlit, after its path-security check and before its gzip:
    ``SecurityHeaders`` (the headers a course site expects, metrics closed: edge/headers.py),
    ``LtiRoutes`` (the LTI 1.3 tool's ``/lti/…`` routes when platforms are registered: lti/routes.py),
    ``FairShare`` (each websocket session's message budget: edge/fair_share.py), ``StaticGzip``
    (Streamlit's static files gzipped once) and ``ui.figure.BundleServer`` (the figure component's
    plotly bundles gzipped once and cached by browsers for a year; Streamlit's own component route
    would send them with a bare ``Cache-Control: public`` and no validator, so every visit
    downloaded plotly.js again, gzipped anew on every request), and ``ui.takehome.DownloadServer``
    (the lesson page's download links: /download/<problem>/<file>?<the page's query>), and
    ``edge.room_status.RoomStatus`` (what a phone waiting on a question put to the room asks: /room-status)."""
    from starlette.middleware import Middleware
    from streamlit.web.server.starlette import starlette_app

    from edge.fair_share import FairShare
    from edge.headers import SecurityHeaders
    from edge.room_status import RoomStatus
    from lti.routes import LtiRoutes
    from ui.figure import BundleServer
    from ui.takehome import DownloadServer

    streamlit_middleware = starlette_app.create_streamlit_middleware  # fails loudly if renamed

    def with_ours():
        stack = streamlit_middleware()
        stack[1:1] = [Middleware(SecurityHeaders), Middleware(LtiRoutes), Middleware(FairShare), Middleware(StaticGzip),
                      Middleware(BundleServer), Middleware(DownloadServer), Middleware(RoomStatus)]
        return stack

    starlette_app.create_streamlit_middleware = with_ours


def run(script: Path, argv: list[str]) -> None:
    """``streamlit run script *argv`` in this process, with Nagle off, static files gzipped once, the
    figure bundles cached by browsers, our middlewares and the warmed heap frozen."""
    accept_without_nagle()
    compress_websocket_fast()
    trust_only_named_proxies()
    install_middleware()
    from edge import widget_values

    widget_values.install()
    # The warmed derivations (sympy trees, lambdified code) live as long as the process: move them
    # out of the collector's sight, so a full collection under load scans only what requests make.
    gc.collect()
    gc.freeze()
    from streamlit.web import cli

    sys.argv = ["streamlit", "run", str(script), *argv]
    sys.exit(cli.main())


def settings_problems() -> list[str]:
    """What in the admin's settings cannot work, in words that say how to mend it. Assignments are
    on when the course secret is set, and then the instructor key must be too (the key alone opens
    the answer keys and handouts of a practice site); a key or secret too short to resist guessing
    is refused, not ignored (it used to be treated as unset, closing everything in silence)."""
    from assignments import migrate as schema, signing
    from edge.headers import SettingError, frame_ancestors
    from lti import platforms
    from practice import instructor

    problems = []
    try:
        frame_ancestors()
    except SettingError as error:
        problems.append(str(error))
    key, secret = os.environ.get(instructor.KEY_ENV, ""), os.environ.get(signing.SECRET_ENV, "")
    for name, value, least, make in ((instructor.KEY_ENV, key, instructor.MIN_LENGTH, "openssl rand -base64 18"),
                                     (signing.SECRET_ENV, secret, signing.MIN_SECRET, "openssl rand -hex 32")):
        if value and len(value) < least:
            problems.append(f"{name} has {len(value)} characters; it needs at least {least} (make one with: {make}).")
    if secret and not key:
        problems.append(f"{signing.SECRET_ENV} is set (assignments are on) but {instructor.KEY_ENV} is not: "
                        "nobody could create or read an assignment (README: Deploy).")
    if platforms.enabled() and not secret:
        problems.append(f"{platforms.PLATFORMS_ENV} is set (LTI is on) but {signing.SECRET_ENV} is not: launches "
                        "are sealed and students' variants keyed with it (README: Inside the LMS).")
    problems += platforms.problems()
    if os.environ.get(schema.EXPECT_ENV, "") not in ("", "0", "1"):
        problems.append(f"{schema.EXPECT_ENV} is 1 (the database must exist) or unset.")
    return list(dict.fromkeys(problems))


def migrate() -> None:
    """Create or upgrade the assignments' schema (Alembic) before listening. A database that cannot
    be reached is logged, not fatal: practice works without it, and the pages say so. An empty
    database where an earlier one is expected (assignments/migrate.py) is fatal: the app refuses to
    start, and says why, rather than record a course's attempts into a fresh, empty gradebook."""
    from assignments import db, migrate as schema

    log = logging.getLogger("dynamics_lab")
    try:
        schema.upgrade()
        log.warning("database ready: %s", db.described())
    except schema.DatabaseMissing as error:
        log.error("not starting: %s", error)
        sys.exit(f"Dynamics Lab did not start: {error}")
    except Exception as error:  # noqa: BLE001
        log.error("database not ready (assignments will not be recorded until it is): %s", error)


def main() -> None:
    sys.path.insert(0, str(ROOT))
    problems = settings_problems()
    if problems:
        for problem in problems:
            logging.getLogger("dynamics_lab").error("setting: %s", problem)
        sys.exit("Dynamics Lab did not start: " + " ".join(problems))
    migrate()
    from lti import passback, platforms

    if platforms.enabled():
        passback.start()  # scores left waiting by the last run are sent without waiting for a new attempt
    seconds = warm()
    logging.getLogger("dynamics_lab").warning("warmed in %.1f s", seconds)
    run(ROOT / "app.py", sys.argv[1:])


if __name__ == "__main__":
    main()
