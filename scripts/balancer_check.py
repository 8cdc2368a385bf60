"""Scale-out, checked for real on loopback: two app replicas behind nginx (the same config as the
compose file), browsers sticky per browser, and a replica killed mid-session.

    python scripts/balancer_check.py [--replicas 2]

1. Starts the replicas (serve.py: warm before healthy) and Debian's nginx on 127.0.0.1.
2. Opens browser contexts until two land on different replicas (each browser has its own cookie).
3. Runs the browser test of two pages through the balancer.
4. Kills the replica serving a live page (SIGKILL) and waits for the page to reconnect to another
   replica and show the same problem and parameters (the URL carries the state).
Loopback only, bounded in time; exits non-zero on any failure.
"""
from __future__ import annotations

import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from playwright.sync_api import sync_playwright

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
from scripts.live_app import free_port, launch_browser, wait_healthy, wait_until_idle  # noqa: E402
from edge.streamlit_dom import SELECTORS  # noqa: E402

DEADLINE = time.monotonic() + 600  # the whole check stops by itself


def start_replica(port: int, secret: str) -> subprocess.Popen:
    env = {**os.environ, "STREAMLIT_SERVER_COOKIE_SECRET": secret, "STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE": "true",
           "DL_TRUSTED_PROXIES": "127.0.0.1"}  # nginx on this machine names the client
    return subprocess.Popen([sys.executable, str(ROOT / "serve.py"), "--server.port", str(port),
                             "--server.address", "127.0.0.1", "--server.headless", "true"],
                            cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


COMPOSE_SERVERS = "    server app:8501 max_fails=1 fail_timeout=10s;  # every replica of the service"


def render_nginx(servers: str, listen: str, frame_ancestors: str | None = None) -> str:
    """deploy/nginx.conf.template with its upstream servers and listen address; ``frame_ancestors``
    fills ${DL_FRAME_ANCESTORS} as the nginx image does from its environment (None leaves it, as
    deploy/nginx-compose.conf does)."""
    text = (ROOT / "deploy" / "nginx.conf.template").read_text()
    text = text.replace("@UPSTREAM_SERVERS@", servers).replace("@LISTEN@", listen)
    if frame_ancestors is not None:
        text = text.replace("${DL_FRAME_ANCESTORS}", frame_ancestors)
    return text


def compose_nginx() -> str:
    """What deploy/nginx-compose.conf holds (a test keeps the two equal)."""
    return "# Generated from nginx.conf.template for docker-compose.yml.\n" + render_nginx(COMPOSE_SERVERS, "80")


def start_nginx(ports: list[int], listen: int, workdir: Path) -> subprocess.Popen:
    from edge.headers import frame_ancestors

    servers = "\n".join(f"    server 127.0.0.1:{p} max_fails=1 fail_timeout=10s;" for p in ports)
    http = render_nginx(servers, f"127.0.0.1:{listen}", frame_ancestors())
    for sub in ("client_body", "proxy", "fastcgi", "uwsgi", "scgi"):
        (workdir / sub).mkdir(exist_ok=True)
    conf = workdir / "nginx.conf"
    conf.write_text(
        f"pid {workdir}/nginx.pid;\nerror_log {workdir}/error.log warn;\nevents {{}}\nhttp {{\n"
        f"  access_log off;\n  client_body_temp_path {workdir}/client_body;\n  proxy_temp_path {workdir}/proxy;\n"
        f"  fastcgi_temp_path {workdir}/fastcgi;\n  uwsgi_temp_path {workdir}/uwsgi;\n  scgi_temp_path {workdir}/scgi;\n"
        f"{http}\n}}\n")
    nginx = shutil.which("nginx") or "/usr/sbin/nginx"
    proc = subprocess.Popen([nginx, "-p", str(workdir), "-c", str(conf), "-g", "daemon off;"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE)
    time.sleep(0.5)
    if proc.poll() is not None:
        raise RuntimeError(proc.stderr.read().decode())
    return proc


def replica_of(page) -> str:
    return page.evaluate("fetch('/_stcore/health').then(r => r.headers.get('x-replica'))")


def answers(page) -> str:
    return page.locator(f"{SELECTORS['main']} table").first.inner_text()


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--replicas", type=int, default=2)
    args = parser.parse_args()
    secret = os.urandom(16).hex()  # the same on every replica
    ports = [free_port() for _ in range(args.replicas)]
    listen = free_port()
    workdir = Path(tempfile.mkdtemp(prefix="dl-nginx-"))
    replicas = {p: start_replica(p, secret) for p in ports}
    nginx = None
    try:
        for p in ports:
            wait_healthy(f"http://127.0.0.1:{p}", timeout=120, proc=replicas[p])
        nginx = start_nginx(ports, listen, workdir)
        url = f"http://127.0.0.1:{listen}"
        wait_healthy(url, timeout=30)
        print(f"replicas {ports} behind nginx on {url}")

        with sync_playwright() as pw:
            browser = launch_browser(pw)
            placed: dict[str, tuple] = {}
            for attempt in range(16):
                context = browser.new_context(viewport={"width": 1400, "height": 1000})
                page = context.new_page()
                page.goto(f"{url}/pendulum_rebound?e=0.3&theta0=20")
                wait_until_idle(page)
                where = replica_of(page)
                if where not in placed:
                    placed[where] = (context, page)
                else:
                    context.close()
                if len(placed) >= 2:
                    break
            assert len(placed) >= 2, f"every browser landed on one replica: {list(placed)}"
            print("two browsers, two replicas:", ", ".join(placed))
            for where, (_, page) in placed.items():  # sticky: a browser keeps its replica
                for _ in range(3):
                    assert replica_of(page) == where

            env = {**os.environ, "APP_URL": url}
            test = subprocess.run([sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider",
                                   str(ROOT / "tests" / "test_browser.py"), "-k",
                                   "each_page and (stick_ball or driven_cart) or bad_link"],
                                  cwd=ROOT, env=env, timeout=max(30, DEADLINE - time.monotonic()))
            assert test.returncode == 0, "browser test through the balancer failed"
            print("browser test through the balancer: passed")

            victim_addr, (context, page) = next(iter(placed.items()))
            before = answers(page)
            victim_port = int(victim_addr.rsplit(":", 1)[1])
            replicas[victim_port].send_signal(signal.SIGKILL)
            replicas[victim_port].wait(10)
            print(f"killed the replica at {victim_addr} under a live page")
            started = time.monotonic()
            deadline = started + 90
            while time.monotonic() < deadline:
                try:
                    now = replica_of(page)
                    if now and now != victim_addr and answers(page) == before:
                        break
                except Exception:  # noqa: BLE001 - the page is reconnecting
                    pass
                page.wait_for_timeout(1000)
            else:
                raise AssertionError("the page did not come back on another replica")
            wait_until_idle(page)
            assert "pendulum_rebound" in page.url and "e=0.3" in page.url and "theta0=20" in page.url
            assert answers(page) == before
            assert "Traceback" not in page.inner_text("body")  # (no error drawn in place of the page)
            print(f"the page reconnected to {replica_of(page)} in {time.monotonic() - started:.1f} s "
                  "with the same problem, parameters and answers")
            browser.close()
        print("balancer check: OK")
    finally:
        if nginx:
            nginx.terminate()
        for proc in replicas.values():
            if proc.poll() is None:
                proc.terminate()
        for proc in replicas.values():
            try:
                proc.wait(10)
            except subprocess.TimeoutExpired:
                proc.kill()
        shutil.rmtree(workdir, ignore_errors=True)


if __name__ == "__main__":
    main()
