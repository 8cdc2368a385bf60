"""The route a phone's watch asks while it waits on a question put to the room (ui/room.py, watch.js):
``GET <base>/room-status?c=CODE&t=TOKEN`` answers ``{"v": "<round>:<status>"}``, a few bytes, so that 200
phones learn of a close, a reveal or a new round without a run of the page each (a Streamlit fragment's
rerun cost the server some 9 ms; 200 phones every 2.5 s took 70 % of a process: BENCHMARKS.md §8). The
token is the one the page gave the phone that joined (room/store.status_token: a guessed code gets 403,
so the route is no way round the join throttle); a code gone is 404. The database is read at most once a
second per code per process (room/store.status_version), in a worker thread; each client address may ask
``STATUS_RATE`` a second (a whole hall behind one NAT, bursts of ``STATUS_BURST``)."""
from __future__ import annotations

import urllib.parse

import orjson

from edge import base_path
from edge.fair_share import AddressBuckets, client_address
from room import store

PATH = "/room-status"
STATUS_RATE, STATUS_BURST = 150.0, 300  # requests a second per client address


class RoomStatus:
    """ASGI middleware (installed by serve.py): the room's status route; everything else goes on."""

    def __init__(self, app):
        self.app = app
        self.path = base_path() + PATH
        self.budget = AddressBuckets(STATUS_RATE, STATUS_BURST)

    async def __call__(self, scope, receive, send):
        if scope["type"] != "http" or scope["path"] != self.path:
            return await self.app(scope, receive, send)
        status, body = await self.answer(scope)
        await send({"type": "http.response.start", "status": status,
                    "headers": [(b"content-type", b"application/json"), (b"content-length", str(len(body)).encode()),
                                (b"cache-control", b"no-store"), *([(b"retry-after", b"3")] if status == 429 else [])]})
        await send({"type": "http.response.body", "body": body})

    async def answer(self, scope) -> tuple[int, bytes]:
        if scope["method"] != "GET":
            return 405, b'{"error": "GET only"}'
        bucket = self.budget(client_address(scope))
        if bucket.wait() > 0:
            return 429, b'{"error": "too many requests"}'
        bucket.take()
        query = urllib.parse.parse_qs(scope.get("query_string", b"")[:200].decode("latin-1"))
        code, token = store.normal_code((query.get("c") or [""])[0]), (query.get("t") or [""])[0]
        if not store.status_token_valid(code, token):
            return 403, b'{"error": "not a joined code"}'
        from anyio import to_thread

        try:
            said = await to_thread.run_sync(store.status_version, code)
        except store.RecordingUnavailable:
            return 503, b'{"error": "the database cannot be reached"}'
        if said is None:
            return 404, b'{"error": "no such question"}'
        return 200, orjson.dumps({"v": said})
