"""The figure component's plotly.js: the smallest bundle that draws each figure, the same plotly.js
version as the pinned plotly package, and served so that a browser downloads it once a year
(serve.py installs ui.figure.BundleServer in front of Streamlit)."""
from __future__ import annotations

import asyncio
import gzip
import importlib
import os
import re
import shutil
from pathlib import Path

import brotli
import plotly
import pytest

from edge import compressed
from scripts import build_plotly_bundles
from solvers import registry
from ui import figure as component
from viz.catalog import drawings

IDS = registry.PROBLEM_IDS


def registered(kind: str, module_type: str) -> set[str]:
    """The trace types (or layout components) a bundle holds, read from the bundle itself."""
    text = component.bundles()[kind][1].decode("utf-8", "replace")
    return set(re.findall(rf'moduleType:"{module_type}",name:"(\w+)"', text))


def registered_components(kind: str) -> set[str]:
    """The layout components a bundle registers, read from its entry (build/core.js and build/<kind>.js):
    a component the bundle merely holds (selections, which the cartesian axes import) draws nothing
    unless registered. The bundle is built from these entries (the next test)."""
    sources = [build_plotly_bundles.PINS / "core.js", build_plotly_bundles.PINS / f"{kind}.js"]
    return {name for source in sources
            for name in re.findall(r"require\('plotly\.js/src/components/(\w+)'\)", source.read_text())}


@pytest.mark.skipif(not shutil.which("npm") and not os.environ.get("CI"), reason="npm is not on this machine")
def test_the_bundles_are_built_from_the_npm_package_by_the_script(tmp_path):
    """The served plotly.js is what scripts/build_plotly_bundles.py builds from the pinned npm tree, byte
    for byte: neither the pins nor the entries can change without the bundles (in CI, npm must be there)."""
    for built in build_plotly_bundles.build(tmp_path):
        assert built.read_bytes() == (build_plotly_bundles.BUNDLES / built.name).read_bytes(), built.name


def test_the_bundles_hold_only_what_the_figures_use():
    """What the tests below rely on: the bundles hold the traces of their entries and nothing else
    (basic: scatter and bar, no pie), and gl3d draws every 2-D layout basic draws, so it can draw a
    whole page."""
    assert registered("basic", "trace") == {"scatter", "bar"}
    assert registered("gl3d", "trace") == {"scatter", "bar", "scatter3d"}
    assert registered_components("basic") == {"annotations", "shapes", "colorscale", "legend", "fx", "modebar"}
    assert registered_components("gl3d") == registered_components("basic") | {"annotations3d"}
    assert registered_components("basic") <= registered("basic", "component")
    assert registered_components("gl3d") <= registered("gl3d", "component")


# Where a figure asks for a layout component (a key anywhere in its data, layout or frames).
COMPONENT_OF_KEY = {"annotations": "annotations", "shapes": "shapes", "images": "images", "updatemenus": "updatemenus",
                    "selections": "selections", "grid": "grid", "rangeslider": "rangeslider",
                    "rangeselector": "rangeselector", "error_x": "errorbars", "error_y": "errorbars",
                    "error_z": "errorbars", "colorbar": "colorbar"}


def components_asked(spec, within: str = "") -> set[str]:
    """The layout components a figure's spec asks plotly for. ``sliders`` is not one: the figure
    component draws the time slider in HTML and removes plotly's (figure.js); a scene's annotations
    are annotations3d."""
    asked = set()
    if isinstance(spec, dict):
        for key, value in spec.items():
            if key in COMPONENT_OF_KEY and value:
                asked.add("annotations3d" if (key, within) == ("annotations", "scene") else COMPONENT_OF_KEY[key])
            if key.endswith("calendar"):
                asked.add("calendars")
            asked |= components_asked(value, key if key in ("scene",) else within)
    elif isinstance(spec, list):
        for value in spec:
            asked |= components_asked(value, within)
    return asked


def test_the_reading_of_a_figure_s_components_finds_them():
    assert components_asked({"layout": {"scene": {"annotations": [{"text": "x"}]}, "annotations": [{}]}}) \
        == {"annotations3d", "annotations"}
    assert components_asked({"data": [{"error_y": {"array": [1]}, "marker": {"colorbar": {"x": 1}}}]}) \
        == {"errorbars", "colorbar"}
    assert components_asked({"layout": {"xaxis": {"rangeslider": {"visible": True}}, "sliders": [{}]}}) == {"rangeslider"}


def shown_on(pid: str) -> tuple[list, list]:
    """(the page's figures, every figure the page can show: those and the on-request one)."""
    solution = importlib.import_module(f"solvers.{pid}").solve()
    page = drawings(pid).figures(solution)  # as ui/page.py shows them, the on-request figure with the page's
    asked = drawings(pid).on_request
    return page, ([*page, asked.draw(solution)] if asked else page)


@pytest.mark.parametrize("pid", IDS)
def test_a_page_gets_one_bundle_that_has_all_its_traces_and_components(pid):
    page, shown = shown_on(pid)
    kinds = {component.kind_of(fig, page) for fig in shown}
    types = {trace.get("type", "scatter") for fig in shown for trace in fig.spec["data"]}
    assert len(kinds) == 1, kinds  # one plotly.js per page
    kind = kinds.pop()
    assert types <= registered(kind, "trace"), types
    for fig in shown:
        assert components_asked(fig.spec) <= registered_components(kind), fig.name
    # The 1.6 MB gl3d bundle only on a page with a 3-D scene.
    assert (component.kind_of(page[0], page) == "gl3d") == ("scatter3d" in types)


def test_the_room_s_votes_are_drawn_by_the_2d_bundle():
    from collections import Counter

    from viz.room import histogram

    figure = histogram((("a", "A"), ("b", "B"), ("other", "other")), {1: Counter(a=3, b=1), 2: Counter(a=1, c=2)}, "a")
    assert component.kind_of(figure) == "basic"
    assert {trace.get("type", "scatter") for trace in figure.spec["data"]} <= registered("basic", "trace")
    assert components_asked(figure.spec) <= registered_components("basic")


def version(text: str) -> str:
    return re.search(r"plotly\.js (?:\(\w+ - minified\) )?v(\d+\.\d+\.\d+)", text[:400]).group(1)


def test_the_derivation_s_katex_is_the_version_of_streamlit_s_markdown():
    """Streamlit puts the stylesheet and fonts of its Markdown's KaTeX in every page; the derivation
    component lays out its equations with ui/katex, so the two must be one version (a 0.18 layout
    under the 0.16 stylesheet overflowed a phone)."""
    import streamlit

    static = Path(streamlit.__file__).parent / "static" / "static" / "js"
    chunks = list(static.glob("rehype-katex.*.js"))
    assert len(chunks) == 1, chunks
    streamlit_katex = re.search(r"version:`(\d+\.\d+\.\d+)`", chunks[0].read_text()).group(1)
    ours = re.search(r'version:"(\d+\.\d+\.\d+)"', component.katex()[1].decode()).group(1)
    assert ours == streamlit_katex


def test_the_bundles_are_the_plotly_js_of_the_pinned_plotly_package():
    full = Path(plotly.__file__).parent / "package_data" / "plotly.min.js"
    for kind, (name, data) in component.bundles().items():
        assert version(data.decode("utf-8", "replace")) == version(full.read_text(errors="replace")), kind
        assert name.startswith(f"plotly-{kind}.") and name.endswith(".min.js")


def request(path: str, accept: str = "gzip, deflate") -> tuple[dict, bytes, bool]:
    """One GET through the middleware; also says whether Streamlit's app behind it was reached."""
    reached = []

    async def streamlit(scope, receive, send):
        reached.append(scope["path"])

    sent = []

    async def send(message):
        sent.append(message)

    scope = {"type": "http", "method": "GET", "path": path,
             "headers": [(b"accept-encoding", accept.encode())]}
    asyncio.run(component.BundleServer(streamlit)(scope, None, send))
    if reached:
        return {}, b"", True
    headers = {k.decode(): v.decode() for k, v in sent[0]["headers"]}
    return headers, sent[1]["body"], False


def test_a_bundle_is_served_gzipped_and_immutable_under_its_content_name():
    name, data = component.bundles()["basic"]
    headers, body, passed = request(f"/dynamics-lab/component/ui.figure.{component.NAME}/{name}")
    assert not passed
    assert headers["cache-control"] == "public, max-age=31536000, immutable"
    assert headers["content-encoding"] == "gzip" and gzip.decompress(body) == data
    assert int(headers["content-length"]) == len(body) < len(data) / 2
    plain_headers, plain, _ = request(f"/component/ui.figure.{component.NAME}/{name}", accept="identity")
    assert "content-encoding" not in plain_headers and plain == data


def test_a_bundle_leaves_in_brotli_to_a_browser_that_takes_it_once_made(tmp_path, monkeypatch):
    monkeypatch.setenv("DL_GENERATED_CACHE", str(tmp_path))
    name, data = component.bundles()["basic"]
    path, accept = f"/component/ui.figure.{component.NAME}/{name}", "gzip, deflate, br, zstd"  # as Chromium asks
    server = component.BundleServer(None)
    for _ in range(2):  # the first ask starts it (gzip meanwhile), the second finds it made
        sent = []

        async def send(message):
            sent.append(message)

        asyncio.run(server({"type": "http", "method": "GET", "path": path,
                            "headers": [(b"accept-encoding", accept.encode())]}, None, send))
        compressed._BACKGROUND.submit(lambda: None).result(timeout=120)
    headers = {k.decode(): v.decode() for k, v in sent[0]["headers"]}
    assert headers["content-encoding"] == "br" and brotli.decompress(sent[1]["body"]) == data
    assert int(headers["content-length"]) == len(sent[1]["body"]) < 0.9 * len(gzip.compress(data, 9))
    assert headers["cache-control"] == "public, max-age=31536000, immutable" and headers["vary"] == "Accept-Encoding"


def test_anything_else_goes_to_streamlit():
    name, _ = component.bundles()["basic"]
    for path in ("/component/ui.figure.dynamics_lab_figure/index.html", f"/static/{name}",
                 "/component/ui.figure.dynamics_lab_figure/plotly-basic.0000000000000000.min.js"):
        assert request(path)[2], path


def test_a_generated_module_is_served_gzipped_and_immutable_and_nothing_else_from_its_directory():
    """The live values', the poses' and the motions' modules (ui/live.py), named by their content, are
    served like the bundles (a year's cache, gzipped once), read from the asset directory on first asking;
    a name of another form, or one never generated, goes to Streamlit (which answers 404)."""
    from ui import live

    name = live._values_file("disk_wall", ())
    data = (component.assets() / name).read_bytes()
    headers, body, passed = request(f"/dynamics-lab/component/ui.figure.{component.NAME}/{name}")
    assert not passed and headers["cache-control"] == "public, max-age=31536000, immutable"
    assert gzip.decompress(body) == data and len(body) < len(data) / 2
    for path in (f"/component/ui.figure.{component.NAME}/values.0000000000000000.js",
                 f"/component/ui.figure.{component.NAME}/../{name}", f"/component/ui.figure.{component.NAME}/x{name}",
                 f"/static/{name}"):
        assert request(path)[2], path
