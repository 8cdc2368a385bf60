"""Show a figure (viz.common.Figure) in the page, through a small Streamlit components-v2 module
instead of st.plotly_chart.

st.plotly_chart rebuilds and validates every figure through plotly's go.Figure on each call
(tens of milliseconds for an animation; see BENCHMARKS.md). The component (components v2, since
Streamlit 1.51: no iframe) takes the figure's JSON as it is and draws it in the page with a
partial plotly.js bundle served by this app (no network): plotly.js is loaded and compiled once
per page load, a rerun with a new figure updates the graph in place (``Plotly.react``), a rerun
with the same figure leaves it alone (a running animation goes on), and real Play/Pause/step
buttons work from the keyboard (Space, ← →) and by touch.

The bundles (ui/plotly_bundles: 2-D "basic", and "gl3d" for every figure of a page with a 3-D
scene) and the component's module (plotly_component/figure.js) are served under names that carry
their content's hash, so ``serve.py`` can let browsers keep them for a year (``BundleServer``): a
revisit downloads none of them again. Each run sends only a two-line module that imports it.
"""
from __future__ import annotations

import gzip
import hashlib
import os
import re
import tempfile
import threading
from functools import cache
from pathlib import Path

import orjson
import streamlit as st
import streamlit.components.v1 as components_v1

from edge import base_path, streamlit_dom
from edge.compressed import Compressed
from viz.common import DIGITS, Figure

NAME = "dynamics_lab_figure"
_HERE = Path(__file__).resolve().parent
_DIR = _HERE / "plotly_component"
_BUNDLES = _HERE / "plotly_bundles"
ASSETS_ENV = "DL_ASSET_DIR"


@cache
def assets() -> Path:
    """Where the served files keyed by their content are written (the modules, the bundles, KaTeX and the
    generated poses): ``DL_ASSET_DIR``, else a directory of this user's in the system's temporary directory;
    never the code's own directory, so the code can be read-only (a container's root file system)."""
    place = Path(os.environ.get(ASSETS_ENV) or Path(tempfile.gettempdir()) / f"dynamics-lab-assets-{os.getuid()}")
    place.mkdir(parents=True, exist_ok=True)
    return place
KINDS = ("basic", "gl3d")
YEAR = 365 * 24 * 3600


def _keyed(source: Path | bytes, stem: str, suffix: str) -> tuple[str, bytes]:
    """A file's content (or these bytes) under a name keyed by its hash, written to the asset directory
    (``assets``), which Streamlit's own component route serves (without serve.py too); written whole
    under another name first, so that another process serving the same directory never reads half of it."""
    data = source if isinstance(source, bytes) else source.read_bytes()
    name = f"{stem}.{hashlib.sha256(data).hexdigest()[:16]}{suffix}"
    target = assets() / name
    if not target.exists() or target.stat().st_size != len(data):
        partial = target.with_name(f".{name}.{os.getpid()}.{threading.get_ident()}")
        partial.write_bytes(data)
        os.replace(partial, target)
    return name, data


@cache
def bundles() -> dict[str, tuple[str, bytes]]:
    """kind -> (file name keyed by the content's hash, the script)."""
    return {kind: _keyed(_BUNDLES / f"plotly-{kind}.min.js", f"plotly-{kind}", ".min.js") for kind in KINDS}


DERIVATION = "dynamics_lab_derivation"
ANSWERS = "dynamics_lab_answers"
LESSON = "dynamics_lab_lesson"
DRAW = "dynamics_lab_draw"
WATCH = "dynamics_lab_watch"
# Each component's name and the module that draws it (plotly_component/<file>): this file's figure,
# the answers and the derivation that ui/results.py shows (one module, text.js, for both), and the
# lesson's parts below its stage together in one element (``together``), the drawing exercise's
# free-body diagram (ui/diagram_exercise.py), and a phone's watch on a question put to the room (ui/room.py).
COMPONENTS = {NAME: "figure.js", ANSWERS: "text.js", DERIVATION: "text.js", LESSON: "lesson.js", DRAW: "draw.js",
              WATCH: "watch.js"}
# Modules the components import: the live values while a lesson control is dragged (ui/live.py),
# which ride with the answers they follow (an element of their own cost every run two widgets' work).
IMPORTED = ("live.js",)


@cache
def module(file: str = "figure.js") -> tuple[str, bytes]:
    """A component's JavaScript module (plotly_component/<file>), keyed by its content; one that reads
    Streamlit's page gets its selectors first, as data (``DOM``: edge/streamlit_dom.py, the one seam)."""
    source = (_DIR / file).read_text()
    if "DOM." in source:
        source = streamlit_dom.js_prelude() + source
    return _keyed(source.encode(), file.removesuffix(".js"), ".js")


def kind_of(figure: Figure, page=()) -> str:
    """The bundle that draws this figure: gl3d for a 3-D scene, and for every figure on a page that
    has one (gl3d draws 2-D scatter too), so a page downloads one plotly.js, not two."""
    return "gl3d" if any("scene" in f.spec.get("layout", {}) for f in (figure, *page)) else "basic"


class BundleServer:
    """ASGI middleware (installed by serve.py): the plotly bundles and the component's module,
    gzipped once at start-up rather than on every request, and the generated modules (``generated_file``)
    gzipped once when first asked for, with a year's immutable cache lifetime (their names change with
    their content); in brotli to a browser that takes it, once made (``edge.compressed``). Everything else
    passes through to Streamlit."""

    def __init__(self, app):
        self.app = app
        # Streamlit names the component after its module too (ui.figure.dynamics_lab_figure), so a
        # file is known by the end of its path: /component/<component's name>/<file's name>.
        self.files = {f".{NAME}/{name}": Compressed(data, gzip.compress(data, 9))
                      for name, data in (*bundles().values(), *map(module, {*COMPONENTS.values(), *IMPORTED}), katex())}

    async def __call__(self, scope, receive, send):
        if scope["type"] == "http" and scope["method"] in ("GET", "HEAD"):
            for suffix, packed in self.files.items():
                if scope["path"].endswith(suffix) and "/component/" in scope["path"]:
                    return await self._send(scope, send, packed)
            generated = _GENERATED.search(scope["path"]) if "/component/" in scope["path"] else None
            if generated and (packed := self._generated(generated.group(1))):
                return await self._send(scope, send, packed)
        await self.app(scope, receive, send)

    def _generated(self, name: str) -> Compressed | None:
        """A generated module (``generated_file``: the live values, a pose, a motion), read from the asset
        directory the first time it is asked for and kept, gzipped: named by its content, it never changes."""
        key = f".{NAME}/{name}"
        if key not in self.files:
            try:
                data = (assets() / name).read_bytes()
            except OSError:
                return None
            self.files[key] = Compressed(data, gzip.compress(data, 9))
        return self.files[key]

    @staticmethod
    async def _send(scope, send, packed: Compressed):
        body, coding = packed.body(scope)
        headers = [(b"content-type", b"text/javascript; charset=utf-8"),
                   (b"cache-control", f"public, max-age={YEAR}, immutable".encode()),
                   (b"vary", b"Accept-Encoding"), (b"content-length", str(len(body)).encode())]
        if coding:
            headers.append((b"content-encoding", coding))
        await send({"type": "http.response.start", "status": 200, "headers": headers})
        await send({"type": "http.response.body", "body": b"" if scope["method"] == "HEAD" else body})


def url(name: str) -> str:
    """A served file's path on this server (Streamlit's component route, under the base path)."""
    return f"{base_path()}/component/{__name__}.{NAME}/{name}"


def module_url(file: str) -> str:
    """The served path of a component's module or one it imports (plotly_component/<file>)."""
    return url(module(file)[0])


# A generated module's name as ``generated_file`` makes it (the only names ``BundleServer`` reads from disk).
_GENERATED = re.compile(rf"/component/{re.escape(__name__)}\.{NAME}/((?:values|pose|motion)\.[0-9a-f]{{16}}\.js)$")


def generated_file(stem: str, text: str) -> str:
    """A generated JavaScript module (ui/live.py: a figure's pose) written to the asset directory beside
    the component's files, under a name keyed by its content (the browser imports it once, not with every run): its name
    (``url`` gives its path)."""
    return _keyed(text.encode(), stem, ".js")[0]


@cache
def katex() -> tuple[str, bytes]:
    """KaTeX for the answers and the derivation (plotly_component/text.js; ui/katex/: the version of
    Streamlit's own Markdown, whose stylesheet and fonts are already in the page), keyed by its
    content like the bundles."""
    return _keyed(_HERE / "katex" / "katex.min.js", "katex", ".min.js")


def katex_url() -> str:
    return url(katex()[0])


_lock = threading.Lock()
_components: dict[str, object] = {}


def declared(name: str = NAME):
    """The v2 component ``name`` (a key of ``COMPONENTS``), declared on first use inside a running
    app: a declaration made before the runtime exists (serve.py imports this module while warming
    up) would not be registered. The v1 declaration only gives the files their route."""
    with _lock:
        if not _components:
            bundles()
            components_v1.declare_component(NAME, path=str(assets()))
        if name not in _components:
            file = COMPONENTS[name]
            # The module a run carries: a dynamic import of <file>.<hash>.js, which the browser
            # fetches once and keeps (a blob URL cannot resolve a path: hence the page's URL).
            # (A newline tells Streamlit this is the module's text, not a file's path.)
            # The lesson's element also starts fetching the module its answers and derivation are drawn
            # with, beside its own (lesson.js would ask for it only once loaded: one round trip more).
            also = (f"  import(new URL({url(module('text.js')[0])!r}, location.href).href).catch(() => null);\n"
                    if name == LESSON else "")
            stub = (f"export default (c) => {{\n{also}  import(new URL({url(module(file)[0])!r}, location.href).href)"
                    ".then(m => m.render(c));\n};\n")
            # isolate_styles=False: in the page's own DOM, where plotly.js puts its stylesheet and
            # Streamlit its KaTeX styles.
            _components[name] = st.components.v2.component(name, js=stub, isolate_styles=False)
        return _components[name]


# The lecture view on a projector (issue 14): the component raises every text of the figure to at
# least ``min_font`` px and multiplies line widths and marker sizes. In every view the motion on the
# stage (``fit_screen``, ui/page.py) is sized to what is left of the first screen (below its top, and
# above the lesson's controls where a phone stacks them under it), so Play, the whole figure and the
# controls show without scrolling.
# The legend stands in a column at the right: a projector is wide, and a row of legend above a
# figure of equal axes would take the height the drawing needs.
LECTURE = {"min_font": 18, "title_font": 22, "line_scale": 1.8, "marker_scale": 1.6, "legend_right": True}


def payload(figure: Figure, bundle: str, style: dict | None, fit_screen: bool = False,
            forces: bool | None = None, motion: str | None = None) -> bytes:
    """What a run sends for one figure: one JSON object as bytes, the figure's cached JSON spliced
    in as it is (no second encoding of it). ``forces``: the stage's Forces switch, on or off (None: the
    figure has none); ``motion``: the generated module its frames are computed from, for an animation the
    browser computes (viz.common.animated_in_browser; ui.live.motion_module)."""
    head = orjson.dumps({"height": figure.height, "title": figure.title, "description": figure.description,
                         "bundle": bundle, "style": style, "fit_screen": fit_screen, "key_frame": figure.key_frame,
                         "key_caption": figure.key_caption, **({} if forces is None else {"forces": forces}),
                         **({} if motion is None else {"motion": {"module": motion, "live": module_url("live.js"),
                                                                  "digits": DIGITS}})})
    return head[:-1] + b',"spec":' + figure.json_bytes() + b"}"


def data(figure: Figure, page=(), lecture: bool = False, fit_screen: bool = False, forces: bool | None = None,
         motion: str | None = None) -> bytes:
    """What a figure's element is sent; ``page``: every figure of the page, so that all of them share
    one plotly.js bundle."""
    return payload(figure, url(bundles()[kind_of(figure, page)][0]), LECTURE if lecture else None, fit_screen, forces,
                   motion)


def show(figure: Figure, page=(), lecture: bool = False, fit_screen: bool = False, forces: bool | None = None,
         on_forces=None, motion: str | None = None) -> None:
    """The figure in an element of its own (``data``); with ``forces`` (on or off), its Forces switch,
    whose press calls ``on_forces(wanted: bool)`` before the rerun it starts."""
    if on_forces is None:
        declared()(data=data(figure, page, lecture, fit_screen, motion=motion), key=figure.key)
        return
    key = figure.key

    def pressed():
        on_forces(st.session_state[key]["forces"] is True)
    declared()(data=data(figure, page, lecture, fit_screen, forces, motion), key=key, on_forces_change=pressed)


LINKS = "links"


def part(name: str, key: str, sent: bytes) -> dict:
    """One element's worth inside ``together``: the component ``name`` would draw it (its module's
    path), under ``key``, from the data its own element would be ``sent``; or, ``name`` LINKS, the
    lesson's links (ui/takehome.lesson_links_data), which lesson.js draws itself. The data goes in as JSON,
    not as a string of it: a string escaped every quote and doubled every LaTeX backslash (a tenth more bytes)."""
    return {"component": name, "module": module_url(COMPONENTS[name]) if name != LINKS else None, "key": key,
            "data": orjson.Fragment(sent)}


def together(parts: list[dict], key: str) -> None:
    """Several parts (``part``: the answers, figures, the derivation) in one element, each drawn by its
    own module into a slot of its own (plotly_component/lesson.js): Streamlit's work per element on every
    run is done once, not once a part."""
    declared(LESSON)(data=orjson.dumps({"parts": parts}), key=key)
