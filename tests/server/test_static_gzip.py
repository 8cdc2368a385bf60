"""serve.py's StaticGzip: Streamlit's own static files (its JS bundles, KaTeX) leave gzipped, each
compressed once, with Streamlit's cache headers kept. Requests go through Streamlit's real static
route and its real middleware stack, as serve.py patches it (install_middleware)."""
from __future__ import annotations

import asyncio
import gzip
from pathlib import Path

import pytest
from starlette.applications import Starlette
from streamlit import file_util
from streamlit.web.server.starlette import starlette_app
from streamlit.web.server.starlette.starlette_static_routes import create_streamlit_static_assets_routes

import serve

KATEX = next((Path(file_util.get_static_dir()) / "static" / "js").glob("rehype-katex.*.js"))
KATEX_PATH = f"/static/js/{KATEX.name}"


@pytest.fixture(scope="module")
def app():
    patch = pytest.MonkeyPatch()
    patch.setattr(starlette_app, "create_streamlit_middleware", starlette_app.create_streamlit_middleware)
    serve.install_middleware()  # restored after the module's tests
    yield Starlette(routes=create_streamlit_static_assets_routes(None),
                    middleware=starlette_app.create_streamlit_middleware())
    patch.undo()


def get(app, path: str, **headers: str) -> tuple[int, dict[str, str], bytes]:
    """One GET through the ASGI app; header names with _ for -."""
    sent, requested = [], []

    async def receive():  # the request once, then no disconnect (Starlette listens for one while sending)
        if requested:
            await asyncio.Event().wait()
        requested.append(True)
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message):
        sent.append(message)

    scope = {"type": "http", "method": "GET", "path": path, "raw_path": path.encode(), "root_path": "",
             "query_string": b"", "scheme": "http", "server": ("127.0.0.1", 80), "http_version": "1.1",
             "headers": [(k.replace("_", "-").encode(), v.encode()) for k, v in headers.items()]}
    asyncio.run(app(scope, receive, send))
    start = next(m for m in sent if m["type"] == "http.response.start")
    body = b"".join(m.get("body", b"") for m in sent if m["type"] == "http.response.body")
    return start["status"], {k.decode(): v.decode() for k, v in start["headers"]}, body


def test_katex_leaves_gzipped_and_decodes_to_the_file(app):
    status, headers, body = get(app, KATEX_PATH, accept_encoding="gzip, deflate")
    assert status == 200 and headers["content-encoding"] == "gzip"
    assert gzip.decompress(body) == KATEX.read_bytes()
    assert int(headers["content-length"]) == len(body) < KATEX.stat().st_size / 2
    assert "Accept-Encoding" in headers["vary"]


def test_streamlits_own_headers_stay(app):
    _, plain, raw = get(app, KATEX_PATH, accept_encoding="identity")
    _, packed, _ = get(app, KATEX_PATH, accept_encoding="gzip")
    assert "content-encoding" not in plain and raw == KATEX.read_bytes()
    assert packed["cache-control"] == plain["cache-control"] and "immutable" in plain["cache-control"]
    assert packed["last-modified"] == plain["last-modified"]
    assert packed["etag"] == "W/" + plain["etag"]  # other bytes, same file


def test_a_revisit_revalidates_with_the_weak_etag(app):
    _, headers, _ = get(app, KATEX_PATH, accept_encoding="gzip")
    status, _, body = get(app, KATEX_PATH, accept_encoding="gzip", if_none_match=headers["etag"])
    assert status == 304 and body == b""


def test_the_same_gzipped_bytes_every_time(app):
    first = get(app, KATEX_PATH, accept_encoding="gzip")[2]
    assert get(app, KATEX_PATH, accept_encoding="br, gzip")[2] == first


@pytest.mark.parametrize("accept, takes", [("gzip", True), ("deflate, gzip;q=0.5", True), ("*", True),
                                           ("identity", False), ("gzip;q=0", False), ("br", False), ("", False)])
def test_accept_encoding_is_read_with_its_quality(accept, takes):
    assert serve.accepts_gzip({"headers": [(b"accept-encoding", accept.encode())]}) is takes


def test_a_missing_file_and_the_page_pass_through(app):
    status, headers, body = get(app, "/static/js/no-such-file.js", accept_encoding="gzip")
    assert "content-encoding" not in headers and b"<html" in body.lower()  # Streamlit's SPA fallback
    status, headers, body = get(app, "/", accept_encoding="gzip")
    assert status == 200 and "content-encoding" not in headers and b"<html" in body.lower()
