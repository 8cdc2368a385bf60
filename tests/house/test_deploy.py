"""The nginx template as Debian's nginx runs it on loopback, in front of a stand-in for the app: the
headers a course site expects come once (its own 429 and 503 answers included, with frame-ancestors
from the one setting), one browser's burst of requests is cut at its limit while another browser
is served, and the Compose file's config is the template rendered."""
from __future__ import annotations

import http.server
import os
import shutil
import tempfile
import threading
import urllib.error
import urllib.request
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from scripts.balancer_check import ROOT, compose_nginx, start_nginx
from scripts.live_app import free_port

NGINX = shutil.which("nginx") or "/usr/sbin/nginx"


def test_the_compose_config_is_the_template_rendered():
    assert (ROOT / "deploy" / "nginx-compose.conf").read_text() == compose_nginx()
    compose = (ROOT / "deploy" / "docker-compose.yml").read_text()
    assert "/etc/nginx/templates/default.conf.template" in compose  # the image fills ${DL_FRAME_ANCESTORS}
    assert "DL_FRAME_ANCESTORS" in compose


class App(http.server.BaseHTTPRequestHandler):
    """Stands in for a replica: answers with the app's own headers."""

    def do_GET(self):
        self.send_response(200)
        self.send_header("Content-Security-Policy", "default-src 'self'; frame-ancestors https://lms.example.edu")
        self.send_header("X-Content-Type-Options", "nosniff")
        self.send_header("Referrer-Policy", "same-origin")
        self.send_header("Content-Length", "2")
        self.end_headers()
        self.wfile.write(b"ok")

    def log_message(self, *args):
        pass


@pytest.fixture(scope="module")
def balancer(monkeypatch_module):
    if not Path(NGINX).exists():
        if os.environ.get("CI"):
            pytest.fail("CI must test the nginx template (.ci/run installs Debian's nginx)")
        pytest.skip("no nginx: apt-get install nginx")
    monkeypatch_module.setenv("DL_FRAME_ANCESTORS", "https://lms.example.edu")
    upstream = http.server.ThreadingHTTPServer(("127.0.0.1", 0), App)
    threading.Thread(target=upstream.serve_forever, daemon=True).start()
    workdir = Path(tempfile.mkdtemp(prefix="dl-nginx-"))
    listen = free_port()
    nginx = start_nginx([upstream.server_address[1]], listen, workdir)
    try:
        yield f"http://127.0.0.1:{listen}"
    finally:
        nginx.terminate()
        nginx.wait(10)
        upstream.shutdown()
        shutil.rmtree(workdir, ignore_errors=True)


@pytest.fixture(scope="module")
def monkeypatch_module():
    patch = pytest.MonkeyPatch()
    yield patch
    patch.undo()


def get(url: str, browser: str | None = None) -> tuple[int, list[tuple[str, str]], str]:
    request = urllib.request.Request(url, headers={"Cookie": f"dl_route={browser}"} if browser else {})
    try:
        with urllib.request.urlopen(request, timeout=10) as answer:
            return answer.status, answer.headers.items(), answer.read().decode()
    except urllib.error.HTTPError as refused:
        return refused.code, refused.headers.items(), refused.read().decode()


def named(headers, name: str) -> list[str]:
    return [v for k, v in headers if k.lower() == name]


def test_each_header_comes_once_and_the_apps_policy_passes(balancer):
    status, headers, _ = get(balancer + "/", browser="b-1")
    assert status == 200
    assert named(headers, "x-content-type-options") == ["nosniff"]
    assert named(headers, "referrer-policy") == ["same-origin"]
    assert named(headers, "content-security-policy") == ["default-src 'self'; frame-ancestors https://lms.example.edu"]


def test_one_browsers_burst_is_cut_and_another_browser_is_served(balancer):
    with ThreadPoolExecutor(16) as pool:
        statuses = list(pool.map(lambda _: get(balancer + "/", browser="flooder"), range(400)))
    refused = [s for s in statuses if s[0] == 429]
    assert refused and len(refused) < 400
    _, headers, body = refused[0]
    assert "Too many requests" in body and named(headers, "retry-after") == ["10"]
    assert named(headers, "content-security-policy") == ["default-src 'none'; frame-ancestors https://lms.example.edu"]
    assert named(headers, "x-content-type-options") == ["nosniff"]
    assert get(balancer + "/", browser="a-student")[0] == 200
