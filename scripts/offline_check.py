"""Proof that the app needs no outside network: run it in a network namespace that has only
loopback, under strace, and list every connect() it makes to an address that is not loopback.

    python scripts/offline_check.py      (root; iproute2 and strace from Debian)

Run twice: with Streamlit's defaults, and with the settings the Dockerfile ships
(STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE, and STREAMLIT_BROWSER_SERVER_ADDRESS set to the public host
name). Each run starts the app and opens a websocket whose Origin (the course's host name) differs
from its Host, as behind a proxy that rewrites Host. Nothing leaves the machine: in the namespace
every non-loopback connect fails at once (no route), and strace records that it was attempted.
"""
from __future__ import annotations

import base64
import os
import re
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
PUBLIC_HOST = "course.example.edu"
NS = f"dl-offline-{os.getpid()}"


def in_ns(*cmd: str) -> list[str]:
    return ["ip", "netns", "exec", NS, *cmd]


def websocket_handshake(port: int) -> tuple[str, float]:
    """Open the app's websocket with a foreign Origin, from inside the namespace; (status, seconds)."""
    key = base64.b64encode(os.urandom(16)).decode()
    request = (f"GET /_stcore/stream HTTP/1.1\r\nHost: 127.0.0.1:{port}\r\nUpgrade: websocket\r\n"
               f"Connection: Upgrade\r\nSec-WebSocket-Key: {key}\r\nSec-WebSocket-Version: 13\r\n"
               f"Sec-WebSocket-Protocol: streamlit\r\nOrigin: https://{PUBLIC_HOST}\r\n\r\n")
    code = ("import socket,sys,time; s=socket.create_connection(('127.0.0.1',%d),timeout=30); t=time.time();"
            "s.sendall(sys.stdin.buffer.read()); r=s.recv(200).split(b'\\r\\n')[0].decode();"
            "print(r, time.time()-t)" % port)
    out = subprocess.run(in_ns(sys.executable, "-c", code), input=request.encode(), capture_output=True,
                         timeout=60).stdout.decode().strip()
    status, seconds = out.rsplit(" ", 1)
    return status, float(seconds)


def run(label: str, env_extra: dict[str, str]) -> list[str]:
    port = 8611
    trace = Path(tempfile.mkstemp(prefix="dl-strace-")[1])
    env = {**{k: v for k, v in os.environ.items() if not k.startswith("STREAMLIT_")}, **env_extra}
    proc = subprocess.Popen(in_ns("strace", "-f", "-qq", "-e", "trace=connect", "-o", str(trace),
                                  sys.executable, str(ROOT / "serve.py"), "--server.port", str(port),
                                  "--server.address", "0.0.0.0", "--server.headless", "true"),
                            cwd=ROOT, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL,
                            start_new_session=True)
    try:
        probe = "import urllib.request as u; print(u.urlopen('http://127.0.0.1:%d/_stcore/health', timeout=2).read().decode())" % port
        started = time.monotonic()
        while time.monotonic() - started < 120:
            out = subprocess.run(in_ns(sys.executable, "-c", probe), capture_output=True, text=True)
            if out.stdout.strip() == "ok":
                break
            time.sleep(0.5)
        else:
            raise TimeoutError("the app did not become healthy inside the namespace")
        time.sleep(3)  # let start-up finish (the banner is printed after the server starts)
        status, seconds = websocket_handshake(port)
        time.sleep(1)
    finally:
        os.killpg(proc.pid, signal.SIGTERM)
        try:
            proc.wait(20)
        except subprocess.TimeoutExpired:
            os.killpg(proc.pid, signal.SIGKILL)
            proc.wait(5)
    outside = sorted({m.group(1) for m in re.finditer(r'inet_addr\("([\d.]+)"\)', trace.read_text())
                      if not m.group(1).startswith("127.")} | {m.group(1) for m in re.finditer(
                          r'inet_pton\(AF_INET6, "([0-9a-f:]+)"', trace.read_text()) if m.group(1) != "::1"})
    trace.unlink()
    print(f"{label}: healthy; websocket with Origin https://{PUBLIC_HOST}: {status} in {seconds:.3f} s; "
          f"connect() to non-loopback addresses: {outside or 'none'}")
    return outside


def main() -> None:
    subprocess.run(["ip", "netns", "add", NS], check=True)
    try:
        subprocess.run(["ip", "-n", NS, "link", "set", "lo", "up"], check=True)
        defaults = run("Streamlit defaults", {})
        shipped = run("settings the image ships", {"STREAMLIT_LOGGER_HIDE_WELCOME_MESSAGE": "true",
                                                    "STREAMLIT_BROWSER_SERVER_ADDRESS": PUBLIC_HOST})
        assert not shipped, f"the shipped settings still reach out: {shipped}"
        print("offline check: OK" + (f" (the defaults tried {defaults})" if defaults else ""))
    finally:
        subprocess.run(["ip", "netns", "delete", NS])


if __name__ == "__main__":
    main()
