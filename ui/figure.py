"""Show a figure (viz.common.Figure) through a small custom component instead of st.plotly_chart.

st.plotly_chart rebuilds and validates every figure through plotly's go.Figure on each call
(tens of milliseconds for an animation; see BENCHMARKS.md). This component takes the figure's
JSON as it is and draws it with a partial plotly.js bundle served by this app (no network),
keeps an animation running across reruns when the figure is unchanged, and adds real Play/Pause
buttons that work from the keyboard (Space, ← →).

The bundles (ui/plotly_bundles: 2-D "basic", and "gl3d" for every figure of a page with a 3-D
scene) are served under names that carry their content's hash, so ``serve.py`` can let browsers
keep them for a year (``BundleServer``): a revisit downloads none of plotly.js again.
"""
from __future__ import annotations

import gzip
import hashlib
import threading
from functools import cache
from pathlib import Path

import streamlit.components.v1 as components

from viz.common import Figure

NAME = "dynamics_lab_figure"
_DIR = Path(__file__).resolve().parent / "plotly_component"
_BUNDLES = Path(__file__).resolve().parent / "plotly_bundles"
KINDS = ("basic", "gl3d")
YEAR = 365 * 24 * 3600


@cache
def bundles() -> dict[str, tuple[str, bytes]]:
    """kind -> (file name keyed by the content's hash, the script), written beside the component's
    page so that Streamlit's own component route can serve it too (without serve.py)."""
    out = {}
    for kind in KINDS:
        data = (_BUNDLES / f"plotly-{kind}.min.js").read_bytes()
        name = f"plotly-{kind}.{hashlib.sha256(data).hexdigest()[:16]}.min.js"
        target = _DIR / name
        if not target.exists() or target.stat().st_size != len(data):
            target.write_bytes(data)
        out[kind] = (name, data)
    return out


def kind_of(figure: Figure, page=()) -> str:
    """The bundle that draws this figure: gl3d for a 3-D scene, and for every figure on a page that
    has one (gl3d draws 2-D scatter too), so a page downloads one plotly.js, not two."""
    return "gl3d" if any("scene" in f.spec.get("layout", {}) for f in (figure, *page)) else "basic"


class BundleServer:
    """ASGI middleware (installed by serve.py): the plotly bundles, gzipped once at start-up rather
    than on every request, with a year's immutable cache lifetime (their names change with their
    content). Everything else passes through to Streamlit."""

    def __init__(self, app):
        self.app = app
        # Streamlit names the component after its module too (ui.figure.dynamics_lab_figure), so a
        # bundle is known by the end of its path: /component/<component's name>/<bundle's name>.
        self.files = {f".{NAME}/{name}": (data, gzip.compress(data, 9)) for name, data in bundles().values()}

    async def __call__(self, scope, receive, send):
        if scope["type"] == "http" and scope["method"] in ("GET", "HEAD"):
            for suffix, (raw, packed) in self.files.items():
                if scope["path"].endswith(suffix) and "/component/" in scope["path"]:
                    return await self._send(scope, send, raw, packed)
        await self.app(scope, receive, send)

    @staticmethod
    async def _send(scope, send, raw: bytes, packed: bytes):
        accepts = b"gzip" in dict(scope["headers"]).get(b"accept-encoding", b"")
        body = packed if accepts else raw
        headers = [(b"content-type", b"text/javascript; charset=utf-8"),
                   (b"cache-control", f"public, max-age={YEAR}, immutable".encode()),
                   (b"vary", b"Accept-Encoding"), (b"content-length", str(len(body)).encode())]
        if accepts:
            headers.append((b"content-encoding", b"gzip"))
        await send({"type": "http.response.start", "status": 200, "headers": headers})
        await send({"type": "http.response.body", "body": b"" if scope["method"] == "HEAD" else body})


_lock = threading.Lock()
_component = None


def _declared():
    """Declare the component on first use, inside a running app: a declaration made before the
    runtime exists (serve.py imports this module while warming up) would not be registered."""
    global _component
    with _lock:
        if _component is None:
            bundles()
            _component = components.declare_component(NAME, path=str(_DIR))
        return _component


# The lecture view on a projector (issue 14): the component raises every text of the figure to at
# least ``min_font`` px, multiplies line widths and marker sizes, and (``fit_screen``, the first
# figure) sizes the graph to what is left of the first screen, so Play and the whole figure show.
# The legend stands in a column at the right: a projector is wide, and a row of legend above a
# figure of equal axes would take the height the drawing needs.
LECTURE = {"min_font": 18, "title_font": 22, "line_scale": 1.8, "marker_scale": 1.6, "legend_right": True}


def show(figure: Figure, page=(), lecture: bool = False, fit_screen: bool = False) -> None:
    """``page``: every figure of the page, so that all of them share one plotly.js bundle."""
    style = {**LECTURE, "fit_screen": fit_screen} if lecture else None
    # Bytes travel as a binary argument: no second JSON encoding of the figure by Streamlit.
    _declared()(spec=figure.json_bytes(), height=figure.height, title=figure.title,
                description=figure.description, bundle=bundles()[kind_of(figure, page)][0], style=style,
                key=figure.key, default=None)
