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

from ui import figure as component

IDS = ["disk_wall", "pendulum_rebound", "driven_cart", "eulers_disk", "stick_ball", "rod_disk_spring"]
# Trace types each partial bundle registers (plotly.js's lib/index-basic.js and lib/index-gl3d.js).
TRACES = {"basic": {"scatter", "bar", "pie"}, "gl3d": {"scatter", "scatter3d", "surface", "mesh3d",
                                                       "isosurface", "volume", "cone", "streamtube"}}


def version(text: str) -> str:
    return re.search(r"plotly\.js (?:\(\w+ - minified\) )?v(\d+\.\d+\.\d+)", text[:400]).group(1)


def test_the_bundles_are_the_plotly_js_of_the_pinned_plotly_package():
    full = Path(plotly.__file__).parent / "package_data" / "plotly.min.js"
    for kind, (name, data) in component.bundles().items():
        assert version(data.decode("utf-8", "replace")) == version(full.read_text(errors="replace")), kind
        assert name.startswith(f"plotly-{kind}.") and name.endswith(".min.js")


@pytest.mark.parametrize("pid", IDS)
def test_each_figure_gets_a_bundle_that_has_its_traces(pid):
    solution = importlib.import_module(f"solvers.{pid}").solve()
    figures = importlib.import_module(f"viz.{pid}").figures(solution)
    viz = importlib.import_module(f"viz.{pid}")
    if hasattr(viz, "on_request"):
        figures = [*figures, viz.on_request(solution)]
    for fig in figures:
        kind = component.kind_of(fig)
        types = {trace.get("type", "scatter") for trace in fig.spec["data"]}
        assert types <= TRACES[kind], (fig.key, types, kind)
        assert (kind == "gl3d") == ("scatter3d" in types)  # the 1.6 MB bundle only where needed


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
