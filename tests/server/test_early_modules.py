"""edge/early_modules.py: the module st.html's element needs (the app's stylesheets), named to the browser on
the app's pages only, through the headers middleware (edge/headers.py) as serve.py installs it. (That a
page's answer carries it from the running server, and that Chromium fetches it while the page loads:
tests/server/test_edge_live.py, tests/browser/test_browser.py.)"""
from __future__ import annotations

import asyncio

import pytest
from starlette.applications import Starlette
from starlette.responses import HTMLResponse, PlainTextResponse
from starlette.routing import Route

from edge import early_modules
from edge.headers import SecurityHeaders


@pytest.mark.parametrize("path, base, page", [
    ("/", "", True), ("/disk_wall", "", True), ("/dl/", "/dl", True), ("/dl/disk_wall", "/dl", True),
    ("/lti/launch", "", False), ("/dl/lti/launch", "/dl", False), ("/disk_wall/", "", False),
    ("/_stcore/health", "", False), ("/dl", "/dl", False), ("/other/disk_wall", "/dl", False),
])
def test_only_the_app_s_pages_are_pages(path, base, page):
    """Where index.html's ./static/ names the server's static folder: the root or one page under the base."""
    assert early_modules.is_page(path, base) is page


def test_st_html_s_module_and_its_imports_are_named():
    found = early_modules.early_modules()
    assert found[0].startswith("static/js/Html.") and any(p.startswith("static/js/purify.") for p in found), found
    assert b"rel=modulepreload" in early_modules.link_header()


def headers_of(path: str, response) -> dict[bytes, bytes]:
    app = Starlette(routes=[Route(path, lambda request: response)])
    wrapped, sent = SecurityHeaders(app), []

    async def receive():
        return {"type": "http.request", "body": b"", "more_body": False}

    async def send(message):
        sent.append(message)
    scope = {"type": "http", "method": "GET", "path": path, "raw_path": path.encode(), "query_string": b"",
             "headers": [], "root_path": ""}
    asyncio.run(wrapped(scope, receive, send))
    return dict(sent[0]["headers"])


def test_the_header_goes_on_a_page_s_html_and_nowhere_else():
    assert headers_of("/disk_wall", HTMLResponse("<html></html>"))[b"link"] == early_modules.link_header()
    assert b"link" not in headers_of("/lti/launch", HTMLResponse("<html></html>"))  # the LTI tool's own page
    assert b"link" not in headers_of("/disk_wall", PlainTextResponse("ok"))  # not HTML


def test_under_a_base_path_the_header_goes_on_its_pages_only():
    """Streamlit's ``server.baseUrlPath`` (edge.base_path): its pages are under it, and a path outside it is not one."""
    from streamlit import config

    config.set_option("server.baseUrlPath", "dl")
    try:
        assert headers_of("/dl/disk_wall", HTMLResponse("<html></html>"))[b"link"] == early_modules.link_header()
        assert b"link" not in headers_of("/disk_wall", HTMLResponse("<html></html>"))
    finally:
        config.set_option("server.baseUrlPath", "")
