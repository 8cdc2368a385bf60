"""serve.py's StaticGzip: Streamlit's own static files (its JS bundles, KaTeX) leave gzipped, or in brotli
once it is made (edge/compressed.py), each compressed once, with Streamlit's cache headers kept. Requests go through Streamlit's real static
route and its real middleware stack, as serve.py patches it (install_middleware)."""
from __future__ import annotations

import asyncio
import gzip
from pathlib import Path

import brotli
import pytest
from starlette.applications import Starlette
from streamlit import file_util
from streamlit.web.server.starlette import starlette_app
from streamlit.web.server.starlette.starlette_static_routes import create_streamlit_static_assets_routes

import serve
from edge import compressed

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
    assert get(app, KATEX_PATH, accept_encoding="gzip, deflate")[2] == first


def test_a_browser_that_takes_brotli_gets_gzip_until_it_is_made_then_brotli(app, tmp_path, monkeypatch):
    monkeypatch.setenv("DL_GENERATED_CACHE", str(tmp_path))  # (made here, not taken from an earlier run's disk)
    path = "/static/js/" + next(KATEX.parent.glob("index.[!e]*.js")).name  # (a file no other test here asked for)
    raw = get(app, path, accept_encoding="identity")[2]
    status, headers, body = get(app, path, accept_encoding="gzip, deflate, br, zstd")  # as Chromium asks
    assert status == 200 and headers["content-encoding"] == "gzip" and gzip.decompress(body) == raw
    compressed._BACKGROUND.submit(lambda: None).result(timeout=120)  # the one background thread has made it
    status, headers, body = get(app, path, accept_encoding="gzip, deflate, br, zstd")
    assert status == 200 and headers["content-encoding"] == "br" and brotli.decompress(body) == raw
    assert int(headers["content-length"]) == len(body) < 0.9 * len(gzip.compress(raw, 9))
    assert "Accept-Encoding" in headers["vary"] and headers["etag"].startswith("W/")
    assert list(tmp_path.glob("brotli/*.br"))  # kept for the next process
    assert get(app, path, accept_encoding="gzip, br;q=0")[1]["content-encoding"] == "gzip"


@pytest.mark.parametrize("accept, coding, takes", [
    ("gzip", "gzip", True), ("deflate, gzip;q=0.5", "gzip", True), ("*", "gzip", True), ("identity", "gzip", False),
    ("gzip;q=0", "gzip", False), ("br", "gzip", False), ("", "gzip", False), ("gzip, deflate, br, zstd", "br", True),
    ("br;q=0, gzip", "br", False), ("gzip", "br", False)])
def test_accept_encoding_is_read_with_its_quality(accept, coding, takes):
    assert compressed.accepts({"headers": [(b"accept-encoding", accept.encode())]}, coding) is takes


def test_brotli_is_taken_from_the_disk_where_an_earlier_process_kept_it(tmp_path, monkeypatch):
    monkeypatch.setenv("DL_GENERATED_CACHE", str(tmp_path))
    raw = KATEX.read_bytes()
    made = compressed._brotli(raw)
    kept = compressed._kept_path(raw)
    assert kept.read_bytes() == made and brotli.decompress(made) == raw
    kept.write_bytes(brotli.compress(b"another file"))  # torn or foreign: made again, not sent
    assert brotli.decompress(compressed._brotli(raw)) == raw
    monkeypatch.setenv("DL_GENERATED_CACHE", "off")
    assert compressed._kept_path(raw) is None and brotli.decompress(compressed._brotli(raw)) == raw


def test_a_missing_file_and_the_page_pass_through(app):
    status, headers, body = get(app, "/static/js/no-such-file.js", accept_encoding="gzip")
    assert "content-encoding" not in headers and b"<html" in body.lower()  # Streamlit's SPA fallback
    status, headers, body = get(app, "/", accept_encoding="gzip")
    assert status == 200 and "content-encoding" not in headers and b"<html" in body.lower()
