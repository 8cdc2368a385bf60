"""Start the app on a free loopback port for browser tests and screenshots, and stop it after.

    with running_app() as url: ...

Also: ``launch_browser(playwright)`` with Debian's Chromium and the flags this machine needs, and
``wait_until_idle(page)`` for a page whose script has finished running.
"""
from __future__ import annotations

import contextlib
import os
import socket
import subprocess
import sys
import tempfile
import time
import urllib.request
from pathlib import Path
from typing import NamedTuple
from edge.streamlit_dom import ATTRIBUTES, SCRIPT_IDLE, SELECTORS

ROOT = Path(__file__).resolve().parent.parent
CHROMIUM = os.environ.get("CHROMIUM", "/usr/bin/chromium")
CHROMIUM_ARGS = ["--no-sandbox", "--disable-gpu", "--disable-background-networking",
                 "--disable-component-update", "--disable-sync", "--no-first-run", "--disable-quic"]


def free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def start_app(port: int, extra: list[str] | None = None, env: dict | None = None,
              entry: list[str] | None = None, root: Path = ROOT) -> subprocess.Popen:
    """The production entry point (serve.py: warm, then Streamlit), so tests see what ships.
    ``entry`` replaces it, e.g. with a benchmark's baseline served by the same code. Its output
    goes to a new temporary file (``proc.log``), never to a pipe: a server that outlives many tests
    would fill a pipe nobody reads and stall on its next log line. ``root``: the code's directory (a copy
    of it: tests/house/test_read_only_code.py)."""
    cmd = [sys.executable, *(entry or [str(root / "serve.py")]), "--server.headless", "true",
           "--server.port", str(port), "--server.address", "127.0.0.1",
           "--browser.gatherUsageStats", "false", "--server.fileWatcherType", "none", *(extra or [])]
    handle, name = tempfile.mkstemp(prefix="dl-app-", suffix=".log")
    os.close(handle)
    log = Path(name)
    with open(log, "ab") as out:
        proc = subprocess.Popen(cmd, cwd=root, stdout=out, stderr=subprocess.STDOUT, env={**os.environ, **(env or {})})
    proc.log = log
    return proc


def wait_healthy(url: str, timeout: float = 120.0, proc: subprocess.Popen | None = None) -> None:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        if proc is not None and proc.poll() is not None:
            said = Path(proc.log).read_text(errors="replace") if hasattr(proc, "log") else proc.stderr.read().decode(errors="replace")
            raise RuntimeError(f"app exited early: {said[-2000:]}")
        try:
            with urllib.request.urlopen(f"{url}/_stcore/health", timeout=2) as r:
                if r.read().strip() == b"ok":
                    return
        except OSError:
            pass
        time.sleep(0.3)
    raise TimeoutError(f"{url} not healthy after {timeout} s")


class Server(NamedTuple):
    url: str
    log: Path  # everything the server wrote
    pid: int


class Starting:
    """A server started now and waited for later: its warm-up (some 20 s) runs beside other work."""

    def __init__(self, extra: list[str] | None = None, entry: list[str] | None = None, env: dict | None = None,
                 root: Path = ROOT):
        port = free_port()
        self.url = f"http://127.0.0.1:{port}"
        self.proc = start_app(port, extra, env=env, entry=entry, root=root)

    def ready(self) -> Server:
        wait_healthy(self.url, timeout=180, proc=self.proc)
        return Server(self.url, self.proc.log, self.proc.pid)

    def stop(self) -> None:
        self.proc.terminate()
        try:
            self.proc.wait(10)
        except subprocess.TimeoutExpired:
            self.proc.kill()
        self.proc.log.unlink(missing_ok=True)


@contextlib.contextmanager
def running_server(extra: list[str] | None = None, entry: list[str] | None = None, env: dict | None = None,
                   root: Path = ROOT):
    """A started, healthy server (``Server``) of the code in ``root``, stopped after."""
    starting = Starting(extra, entry, env, root)
    try:
        yield starting.ready()
    finally:
        starting.stop()


@contextlib.contextmanager
def running_app(extra: list[str] | None = None, entry: list[str] | None = None, env: dict | None = None):
    with running_server(extra, entry, env) as server:
        yield server.url


def launch_browser(playwright):
    return playwright.chromium.launch(executable_path=CHROMIUM, args=CHROMIUM_ARGS)


# A page's record of its script runs, installed before its own scripts (``context.add_init_script(IDLE_WATCH)``):
# how many runs have ended, when the run state last changed, when the page last sent on its websocket (a
# widget's change, a page link: each a run asked for) and when a person last touched it (a key, the pointer,
# typed text, the window's size: what may ask for a run a moment later). ``wait_until_idle`` then waits on
# what happened.
IDLE_WATCH = f"""window.__dlIdle = {{runs: 0, changed: 0, sent: 0, touched: 0}};
new MutationObserver((records) => {{ for (const r of records) {{
  window.__dlIdle.changed = performance.now();
  if (r.target.getAttribute(r.attributeName) === '{SCRIPT_IDLE}' && r.oldValue !== '{SCRIPT_IDLE}') window.__dlIdle.runs++;
}} }}).observe(document, {{subtree: true, attributes: true, attributeOldValue: true,
                          attributeFilter: ['{ATTRIBUTES["scriptState"]}']}});
const dlIdleSend = WebSocket.prototype.send;
WebSocket.prototype.send = function (data) {{ window.__dlIdle.sent = performance.now(); return dlIdleSend.call(this, data); }};
for (const type of ['keydown', 'keyup', 'pointerdown', 'pointermove', 'pointerup', 'click', 'input', 'change',
                    'wheel', 'touchend', 'resize']) {{
  window.addEventListener(type, () => {{ window.__dlIdle.touched = performance.now(); }}, {{capture: true, passive: true}});
}}"""
QUIET_MS = 300  # how long the page is left alone after a run ends, something is sent or a person touches it
IDLE_NOW = f"""(quiet) => {{ const s = window.__dlIdle, app = document.querySelector("{SELECTORS['app']}");
  return !!app && app.getAttribute('{ATTRIBUTES["scriptState"]}') === '{SCRIPT_IDLE}' && s.runs > 0
         && !document.querySelector("{SELECTORS['skeleton']}")
         && performance.now() - Math.max(s.changed, s.sent, s.touched) >= quiet; }}"""


# Resolves once no finite animation or CSS transition has run for ``calm`` ms (at most 3 s): what is still moving
# (the sidebar folding away as the lecture view opens, a slider's min and max fading out once the pointer leaves
# it) would be measured, or audited, as it stands at that instant. Not part of ``wait_until_idle``: a wait for
# every transition after every run cost the browser tests more than the checks that need it (docs/benchmarks-log.md).
SETTLED = """(calm) => new Promise((resolve) => {
  let since = null;
  const moving = () => document.getAnimations().some((a) => a.playState === 'running'
    && a.effect && a.effect.getComputedTiming().endTime !== Infinity);
  const tick = (now) => {
    since = moving() ? null : (since ?? now);
    if (since !== null && now - since >= calm) resolve(true); else requestAnimationFrame(tick);
  };
  requestAnimationFrame(tick);
  setTimeout(() => resolve(false), 3000);
})"""


def wait_until_idle(page, timeout: float = 30_000) -> None:
    """Wait for the script run to finish (and for Streamlit to have started one at all), then for the page
    to be quiet for ``QUIET_MS``: no run state changed, nothing sent, and no key, pointer or typing (a
    control's change may be sent a moment after the key or the pointer). A page left alone since its last run
    is idle at once: the quiet counts from what the page did, not from the call. (A check that measures
    what may still be moving waits for ``SETTLED`` too.) In a page with ``IDLE_WATCH``, a page's first run
    is waited for and a run's end is seen as it happens; elsewhere, fixed times before and after. Either way
    no element may still show Streamlit's placeholder: an element whose code loads on first use (``st.html``,
    which carries the app's stylesheets; Markdown's math) is drawn a moment after the run ends, up to two
    seconds later on a busy 2-core machine, and a page printed or tabbed through before then had none of
    the app's styles."""
    app = SELECTORS["app"]
    page.wait_for_selector(app, timeout=timeout)
    if page.evaluate("() => !!window.__dlIdle"):
        page.wait_for_function(IDLE_NOW, arg=QUIET_MS, timeout=timeout)
        return
    page.wait_for_timeout(QUIET_MS)
    page.wait_for_selector(f"{app}[{ATTRIBUTES['scriptState']}='{SCRIPT_IDLE}']", timeout=timeout)
    page.wait_for_function(f"() => !document.querySelector(\"{SELECTORS['skeleton']}\")", timeout=timeout)
    page.wait_for_timeout(QUIET_MS)
