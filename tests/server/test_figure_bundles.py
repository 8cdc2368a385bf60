"""The figure component's plotly.js: the smallest bundle that draws each figure, the same plotly.js
version as the pinned plotly package, and served so that a browser downloads it once a year
(serve.py installs ui.figure.BundleServer in front of Streamlit)."""
from __future__ import annotations

import asyncio
import gzip
import importlib
import re
from pathlib import Path

import plotly
import pytest

from solvers import registry
from ui import figure as component
from viz.catalog import drawings

IDS = registry.PROBLEM_IDS


def registered(kind: str, module_type: str) -> set[str]:
    """The trace types (or layout components) a bundle registers, read from the bundle itself."""
    text = component.bundles()[kind][1].decode("utf-8", "replace")
    return set(re.findall(rf'moduleType:"{module_type}",name:"(\w+)"', text))


def test_the_bundles_say_what_they_register():
    """What the next test relies on: the reading above finds plotly.js's lib/index-*.js lists, and
    gl3d draws every 2-D layout basic draws (the same components), so it can draw a whole page."""
    assert registered("basic", "trace") == {"scatter", "bar", "pie"}
    assert {"scatter", "scatter3d"} <= registered("gl3d", "trace")
    assert registered("gl3d", "component") == registered("basic", "component") >= {"annotations", "shapes", "legend"}


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


@pytest.mark.parametrize("pid", IDS)
def test_a_page_gets_one_bundle_that_has_all_its_traces(pid):
    solution = importlib.import_module(f"solvers.{pid}").solve()
    page = drawings(pid).figures(solution)  # as ui/page.py shows them, the on-request figure with the page's
    asked = drawings(pid).on_request
    shown = [*page, asked.draw(solution)] if asked else page
    kinds = {component.kind_of(fig, page) for fig in shown}
    types = {trace.get("type", "scatter") for fig in shown for trace in fig.spec["data"]}
    assert len(kinds) == 1, kinds  # one plotly.js per page
    assert types <= registered(kinds.pop(), "trace"), types
    # The 1.6 MB gl3d bundle only on a page with a 3-D scene.
    assert (component.kind_of(page[0], page) == "gl3d") == ("scatter3d" in types)


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
