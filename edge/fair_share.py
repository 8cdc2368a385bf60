"""A per-session budget for Streamlit's websocket: one session cannot stall the others.

Every message a browser sends on ``/_stcore/stream`` (a rerun with the widgets' values, mostly)
starts work on the server: a rerun of the page's script, which holds the interpreter while it
runs. A person changes a control a few times a second at most; a script can send a thousand
reruns a second, and every other session in the process then waits behind them (issue 25: a
change took 27 s). So each connection gets a token bucket: ``RATE`` messages a second, bursts of
``BURST``. A message beyond it is held until a token comes, and while it is held a newer rerun
replaces an older one (each rerun carries every widget's value, so the latest is the state the
person sees; a rerun that carries a button's click is never replaced). Every connection from one
client address also draws on that address's bucket (``ADDRESS_RATE``, a lecture hall's NAT), so a
script cannot multiply its share by opening many tabs. Nor can it by runs at once: the rate a
process can serve is far below what a burst lets through (ten tabs' first 300 reruns, all new values,
were six seconds of script for every other student to wait behind), so an address has at most
``ADDRESS_RUNS`` session running the page at once (from a rerun let through until Streamlit says the
run finished, for ``RUN_COUNTS`` seconds at most: a run that waits on a worker process holds no one); a
rerun of another of its sessions waits, merged, for it to finish. One at a time loses a lecture hall's
NAT nothing (one interpreter runs one script at a time anyway) and keeps a script's tabs to one
student's share. A wait for the address's turn is no flood of the session's own: only its own rate
counts towards ``DROP_AFTER``. A connection held back
continuously for ``DROP_AFTER`` seconds is closed (1008, policy violation), and so is one with
more than ``MAX_HELD`` messages, or ``MAX_HELD_BYTES``, waiting that cannot be merged. Nothing here touches another address's connections,
and a person at a person's pace never meets the limit.

The browser's own reconnect brings a dropped session back at the person's pace; the log says once
per connection that it was slowed, and when it was dropped.
"""
from __future__ import annotations

import asyncio
import collections
import logging
import time

from streamlit.proto.BackMsg_pb2 import BackMsg
from streamlit.proto.ForwardMsg_pb2 import ForwardMsg

RATE = 10.0        # messages a second, sustained: more than a person can send
BURST = 30         # a quick series of changes (a held arrow key) passes untouched
ADDRESS_RATE = 60.0  # every session of one client address together: a lecture hall's NAT (200
ADDRESS_BURST = 300  #   students changing a control every 5 s is 40 a second), not a script's 400 tabs
DROP_AFTER = 15.0  # seconds held back without a break: no person does that
MAX_HELD = 64      # messages waiting that cannot be merged (clicks): a bound on memory...
MAX_HELD_BYTES = 1 << 20  # ... and on their size (a rerun is a few hundred bytes)
MAX_ADDRESSES = 10_000  # addresses remembered at most (the least recently seen forgotten)
ADDRESS_RUNS = 1   # an address's sessions running at once: one interpreter serves every address
RUN_COUNTS = 1.0   # seconds a run holds its address's place at most (one waiting on a worker holds none)
FINISHED_MAX_BYTES = 256  # a script_finished message is a few bytes: larger messages are not read
STREAM_PATH = "/_stcore/stream"
ONE_SHOT = {"trigger_value", "string_trigger_value", "json_trigger_value", "chat_input_value"}

log = logging.getLogger("dynamics_lab.fair_share")


class TokenBucket:
    def __init__(self, rate: float = RATE, burst: int = BURST, clock=time.monotonic):
        self.rate, self.burst, self.clock = rate, burst, clock
        self.tokens, self.at = float(burst), clock()

    def _refill(self) -> None:
        now = self.clock()
        self.tokens = min(self.burst, self.tokens + (now - self.at) * self.rate)
        self.at = now

    def wait(self) -> float:
        """Seconds until a token is there (0 if one is there now)."""
        self._refill()
        return 0.0 if self.tokens >= 1 else (1 - self.tokens) / self.rate

    def take(self) -> None:
        self._refill()
        self.tokens -= 1


def _rerun(message: dict):
    """The rerun a message from the browser asks for (its RerunScript), or None (another message, or none
    Streamlit could read: it refuses and closes those itself)."""
    data = message.get("bytes")
    if not data:
        return None
    back = BackMsg()
    try:
        back.ParseFromString(data)
    except Exception:  # noqa: BLE001
        return None
    return back.rerun_script if back.WhichOneof("type") == "rerun_script" else None


def kind_of(message: dict) -> tuple[bool, bool]:
    """(whether the page's script runs for it: a rerun; whether a newer rerun stands for it: a rerun without
    a click), from one reading of the message."""
    rerun = _rerun(message)
    if rerun is None:
        return False, False
    return True, not any(w.WhichOneof("value") in ONE_SHOT for w in rerun.widget_states.widgets)


def finishes_run(message: dict) -> bool:
    """Streamlit's word that a session's run is over (not one stopped for the next rerun)."""
    data = message.get("bytes")
    if not data or len(data) > FINISHED_MAX_BYTES:
        return False
    forward = ForwardMsg()
    try:
        forward.ParseFromString(data)
    except Exception:  # noqa: BLE001 - not ours to judge
        return False
    return forward.WhichOneof("type") == "script_finished" and forward.script_finished != ForwardMsg.FINISHED_EARLY_FOR_RERUN


class AddressRuns:
    """One address's sessions running the page, each since when; ``freed`` resolves when one finishes."""

    def __init__(self, clock=time.monotonic):
        self.clock = clock
        self.running: dict[int, float] = {}
        self.freed: asyncio.Future | None = None

    def room_for(self, session: int) -> bool:
        now = self.clock()
        for other, since in list(self.running.items()):
            if now - since > RUN_COUNTS:
                del self.running[other]
        return session in self.running or len(self.running) < ADDRESS_RUNS

    def start(self, session: int) -> None:
        self.running[session] = self.clock()

    def finish(self, session: int) -> None:
        if self.running.pop(session, None) is not None and self.freed is not None and not self.freed.done():
            self.freed.set_result(None)

    def next_free(self) -> asyncio.Future:
        if self.freed is None or self.freed.done():
            self.freed = asyncio.get_running_loop().create_future()
        return self.freed

    def seconds_to_expiry(self) -> float:
        return max(0.0, min((RUN_COUNTS - (self.clock() - since) for since in self.running.values()), default=0.0))


class SessionBudget:
    """The receive side of one websocket connection, metered by its own bucket and its address's, and by
    its address's runs at once."""

    def __init__(self, receive, send, who: str, clock=time.monotonic, shared: TokenBucket | None = None,
                 runs: AddressRuns | None = None):
        self.inner, self.send, self.who, self.clock = receive, send, who, clock
        self.buckets = (TokenBucket(clock=clock), shared or TokenBucket(ADDRESS_RATE, ADDRESS_BURST, clock))
        self.runs = runs or AddressRuns(clock)
        self.held: collections.deque[tuple[dict, bool, bool]] = collections.deque()  # (message, kind_of it)
        self.held_bytes = 0
        self.reader: asyncio.Future | None = None
        self.over_since: float | None = None  # held back since, without a message passing at once
        self.slowed = self.closed = False

    async def send_to_client(self, message: dict) -> None:
        """The app's send, silent once this budget has closed the connection; a finished run frees its
        address's place."""
        if finishes_run(message):
            self.runs.finish(id(self))
        if not self.closed:
            await self.send(message)

    def _wait(self) -> float:
        return max(bucket.wait() for bucket in self.buckets)

    def _may_pass(self, runs: bool) -> bool:
        """Whether a message may go to Streamlit now: a token in both buckets, and for one the page's script
        ``runs`` for a place among its address's runs (taken as it passes)."""
        if self._wait() > 0:
            return False
        if runs:
            if not self.runs.room_for(id(self)):
                return False
            self.runs.start(id(self))
        for bucket in self.buckets:
            bucket.take()
        return True

    async def receive(self) -> dict:
        while True:
            if self.held and self._may_pass(self.held[0][1]):
                message, *_ = self.held.popleft()
                self.held_bytes -= len(message.get("bytes") or b"")
                if not self.held and self.buckets[0].wait() == 0:  # (it waited its address's turn, not its own)
                    self.over_since = None
                return message
            if self.held and self.clock() - self.over_since > DROP_AFTER:
                return await self._drop(f"held back for {DROP_AFTER:.0f} s")
            if self.reader is None:
                self.reader = asyncio.ensure_future(self.inner())
            waiting = {self.reader}
            timeout = None
            if self.held:  # a token, a place among the address's runs (one finishing, or one timing out)
                timeout = self._wait() or self.runs.seconds_to_expiry() or 0.05
                waiting.add(self.runs.next_free())
            done, _ = await asyncio.wait(waiting, timeout=timeout, return_when=asyncio.FIRST_COMPLETED)
            if self.reader not in done:
                continue
            message, self.reader = self.reader.result(), None
            if message["type"] != "websocket.receive":
                self.held.clear()  # a disconnect needs no rerun before it
                self.held_bytes = 0
                self.runs.finish(id(self))
                return message
            runs, merges = kind_of(message)
            if not self.held and self._may_pass(runs):  # the usual case: at a person's pace
                self.over_since = None
                return message
            self._hold(message, runs, merges)
            if len(self.held) > MAX_HELD or self.held_bytes > MAX_HELD_BYTES:
                return await self._drop("too many messages waiting")

    def _hold(self, message: dict, runs: bool, merges: bool) -> None:
        # Said once, and only of a session past its own budget: one that waits for its address's turn (a
        # hall behind one NAT, each phone sending a message in a while) is no flood of its own.
        if not self.slowed and self.buckets[0].wait() > 0:
            self.slowed = True
            log.warning("session from %s sends more than %g messages a second: slowed", self.who, RATE)
        if self.over_since is None:
            self.over_since = self.clock()
        if self.held and self.held[-1][2] and merges:
            self.held_bytes -= len(self.held.pop()[0].get("bytes") or b"")
        self.held.append((message, runs, merges))
        self.held_bytes += len(message.get("bytes") or b"")

    async def _drop(self, why: str) -> dict:
        log.warning("session from %s dropped (%s)", self.who, why)
        self.held.clear()
        self.held_bytes = 0
        self.runs.finish(id(self))
        if self.reader is not None:
            self.reader.cancel()
        self.closed = True
        try:
            await self.send({"type": "websocket.close", "code": 1008, "reason": "too many messages"})
        except Exception:  # noqa: BLE001 - already gone
            pass
        return {"type": "websocket.disconnect", "code": 1008}


class AddressBuckets:
    """A token bucket per client address (or what ``make`` makes), the ``MAX_ADDRESSES`` most recently seen
    remembered."""

    def __init__(self, rate: float = ADDRESS_RATE, burst: int = ADDRESS_BURST, make=None):
        self.make = make or (lambda: TokenBucket(rate, burst))
        self.addresses: collections.OrderedDict[str, object] = collections.OrderedDict()

    def __call__(self, address: str):
        bucket = self.addresses.pop(address, None) or self.make()
        while len(self.addresses) >= MAX_ADDRESSES:
            self.addresses.popitem(last=False)
        self.addresses[address] = bucket
        return bucket


def client_address(scope) -> str:
    """The client's address as uvicorn gives it (the proxy's X-Forwarded-For where DL_TRUSTED_PROXIES
    trusts it: serve.py)."""
    return (scope.get("client") or ("?", 0))[0]


class FairShare:
    """ASGI middleware: every connection to Streamlit's websocket gets its own SessionBudget."""

    def __init__(self, app):
        self.app = app
        self.address_bucket = AddressBuckets(ADDRESS_RATE, ADDRESS_BURST)
        self.address_runs = AddressBuckets(make=AddressRuns)

    async def __call__(self, scope, receive, send):
        if scope["type"] != "websocket" or not scope["path"].endswith(STREAM_PATH):
            return await self.app(scope, receive, send)
        address = client_address(scope)
        budget = SessionBudget(receive, send, address, shared=self.address_bucket(address),
                               runs=self.address_runs(address))
        try:
            await self.app(scope, budget.receive, budget.send_to_client)
        except Exception:  # noqa: BLE001
            # Streamlit's endpoint, told of the disconnect of a session this budget dropped, may try to
            # close it again and raise (WebSocketDisconnected: a close was sent): the drop is logged already.
            if not budget.closed:
                raise
        finally:
            budget.runs.finish(id(budget))
            if budget.reader is not None:
                budget.reader.cancel()
