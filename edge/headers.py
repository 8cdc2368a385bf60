"""The headers a course site expects on every answer, and Streamlit's metrics kept private.

One setting decides who may embed the app in a frame: ``DL_FRAME_ANCESTORS``, the origins
separated by spaces (an LMS such as ``https://canvas.example.edu``), ``'self'`` when unset. The
same value goes into the Content-Security-Policy's ``frame-ancestors`` here and in the nginx
templates (``deploy/``); the LTI platforms the admin registered (``DL_LTI_PLATFORMS``) are added
here, and only they, and their origins may receive the app's forms (a deep link's answer). The policy lets scripts come only from the app itself: its files, the
blob: modules Streamlit's components v2 make in the page from the app's own code (the figure, the
answers, the derivation), the hashes of the inline scripts (the one line in Streamlit's index.html,
read from the file at start-up, and the app's own, ``edge.inline_scripts.ALL`` and the line that
posts an LTI deep link's answer back to the LMS), and WebAssembly compiled by the app's own scripts ('wasm-unsafe-eval'; no
eval of strings). The page connects only to its own server. Styles allow inline ones (Streamlit and
plotly.js write style attributes). A browser test opens every page under it and finds no violation.

``/_stcore/metrics`` (Streamlit's per-session counters) answers 404 unless ``DL_PUBLIC_METRICS=1``.
An HTML page also names the modules it needs at once (``Link: rel=modulepreload``: edge/early_modules.py).
"""
from __future__ import annotations

import base64
import functools
import hashlib
import os
import re
from pathlib import Path

from edge import base_path, early_modules

FRAME_ENV, METRICS_ENV = "DL_FRAME_ANCESTORS", "DL_PUBLIC_METRICS"
METRICS_PATH = "/_stcore/metrics"
_ORIGIN = re.compile(r"^(https?://[A-Za-z0-9.-]+(:\d{1,5})?|https?://\*\.[A-Za-z0-9.-]+|'self'|'none')$")


class SettingError(ValueError):
    """A setting the admin gave cannot be used as it is."""


def _lms_origins() -> tuple[str, ...]:
    """The registered LTI platforms' origins (lti/platforms.py), where LTI is on."""
    from lti import platforms

    try:
        return platforms.frame_origins()
    except platforms.NotRegistered as error:
        raise SettingError(str(error)) from None


def frame_ancestors(value: str | None = None) -> str:
    """The origins that may embed the app, checked: each an http(s) origin, 'self' or 'none'; with
    the registered LTI platforms' origins added (only theirs: a platform not registered is not)."""
    raw = (os.environ.get(FRAME_ENV, "") if value is None else value).split()
    bad = [origin for origin in raw if not _ORIGIN.match(origin)]
    if bad:
        raise SettingError(f"{FRAME_ENV}: {bad[0]!r} is not an origin such as https://lms.example.edu, "
                           "'self' or 'none'")
    lms = [o for o in _lms_origins() if o not in raw] if value is None else []
    if lms and raw == ["'none'"]:
        raw = []
    return " ".join((raw or ["'self'"]) + lms)


def form_targets() -> str:
    """Where the app's forms may post: itself, and the registered LMSs (a deep link's answer)."""
    return " ".join(["'self'", *_lms_origins()])


def _inline_scripts(html: str) -> list[str]:
    return re.findall(r"<script(?![^>]*\bsrc=)[^>]*>(.*?)</script>", html, flags=re.S)


@functools.cache
def inline_script_hashes() -> tuple[str, ...]:
    """CSP hashes of the inline scripts the pages hold: the one line in Streamlit's index.html, and
    the app's own (``edge.inline_scripts.ALL``, put in the page by ``st.html``), each allowed by its
    exact text and nothing else."""
    import streamlit

    from lti.routes import AUTO_SUBMIT
    from edge.inline_scripts import ALL

    html = (Path(streamlit.__file__).parent / "static" / "index.html").read_text(encoding="utf-8")
    scripts = _inline_scripts(html) + [s for script in ALL for s in _inline_scripts(script)] + [AUTO_SUBMIT]
    return tuple("'sha256-" + base64.b64encode(hashlib.sha256(s.encode()).digest()).decode() + "'"
                 for s in scripts)


def content_security_policy(ancestors: str | None = None) -> str:
    return "; ".join([
        "default-src 'self'",
        "script-src 'self' blob: 'wasm-unsafe-eval' " + " ".join(inline_script_hashes()),
        "style-src 'self' 'unsafe-inline'",
        "img-src 'self' data: blob:",
        "font-src 'self' data:",
        "connect-src 'self'",
        "worker-src 'self' blob:",
        "frame-src 'self'",
        "object-src 'none'",
        "base-uri 'self'",
        f"form-action {form_targets()}",
        f"frame-ancestors {frame_ancestors() if ancestors is None else ancestors}",
    ])


def security_headers() -> list[tuple[bytes, bytes]]:
    return [(b"content-security-policy", content_security_policy().encode()),
            (b"x-content-type-options", b"nosniff"),
            (b"referrer-policy", b"same-origin")]


class SecurityHeaders:
    """ASGI middleware: the headers above on every HTTP answer, and on an HTML page the modules it needs at
    once (``early_modules``); the metrics route closed."""

    def __init__(self, app):
        self.app = app
        self.headers = security_headers()  # a bad setting fails here, at start-up, in plain words
        self.names = {name for name, _ in self.headers}
        link = early_modules.link_header()
        self.page_headers = [(b"link", link)] if link else []
        self.base = base_path()
        self.metrics_public = os.environ.get(METRICS_ENV, "") == "1"

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http":
            return await self.app(scope, receive, send)
        if scope["path"].endswith(METRICS_PATH) and not self.metrics_public:
            await send({"type": "http.response.start", "status": 404, "headers": self.headers + [
                (b"content-type", b"text/plain; charset=utf-8")]})
            return await send({"type": "http.response.body", "body": b"not found\n"})

        async def with_headers(message):
            if message["type"] == "http.response.start":
                kept = [(k, v) for k, v in message.get("headers", []) if k.lower() not in self.names]
                page = early_modules.is_page(scope["path"], self.base) and any(
                    k.lower() == b"content-type" and v.startswith(b"text/html") for k, v in kept)
                message = {**message, "headers": kept + self.headers + (self.page_headers if page else [])}
            await send(message)

        await self.app(scope, receive, with_headers)
