"""serve.py's server fixes: every connection Streamlit accepts sends at once (TCP_NODELAY); the websocket
compressed cheaply.

Without the first, each small message written behind an unacknowledged one waits for the browser's
delayed ACK (40 ms on Linux): see serve.accept_without_nagle and BENCHMARKS.md.
"""
from __future__ import annotations

import asyncio
import socket
import sys

import pytest
from streamlit.web.server.starlette import starlette_server

import serve

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="asyncio's TCP_NODELAY rule, on Linux")


def nodelay_of_accepted(bind) -> int:
    """Bind a listener with ``bind``, serve it with asyncio as uvicorn does, connect once, and
    read TCP_NODELAY on the server's side of the connection."""
    async def accept_one() -> int:
        seen: asyncio.Future[int] = asyncio.get_running_loop().create_future()

        class Report(asyncio.Protocol):
            def connection_made(self, transport):
                sock = transport.get_extra_info("socket")
                seen.set_result(sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY))
                transport.close()

        listener = bind("127.0.0.1", 0, 8)
        server = await asyncio.get_running_loop().create_server(Report, sock=listener)
        async with server:
            _, writer = await asyncio.open_connection("127.0.0.1", listener.getsockname()[1])
            value = await asyncio.wait_for(seen, 5)
            writer.close()
        return value

    return asyncio.run(accept_one())


@pytest.fixture
def patched(monkeypatch):
    monkeypatch.setattr(starlette_server, "_bind_socket", starlette_server._bind_socket)  # restored after
    serve.accept_without_nagle()
    return starlette_server._bind_socket


def test_streamlits_own_listener_leaves_nagle_on():
    """The bug, shown on the pinned Streamlit: if this starts failing, upstream fixed it and
    accept_without_nagle can go."""
    assert nodelay_of_accepted(starlette_server._bind_socket) == 0


def test_served_connections_send_without_nagle(patched):
    assert nodelay_of_accepted(patched) != 0


def test_listener_stays_a_usable_server_socket(patched):
    listener = patched("127.0.0.1", 0, 8)
    try:
        assert listener.proto == socket.IPPROTO_TCP
        assert listener.getblocking() is False and listener.get_inheritable()
        assert listener.getsockopt(socket.SOL_SOCKET, socket.SO_ACCEPTCONN)
    finally:
        listener.close()


def test_the_websocket_is_compressed_at_zlib_s_fastest_level_over_a_window_reaching_the_change_before(monkeypatch):
    """serve.compress_websocket_fast: uvicorn's permessage-deflate (on in .streamlit/config.toml) compresses at
    level 1 (level 6 spent five times the CPU for a little less), a stage figure's JSON to under 40 % of its
    size; and over zlib's largest window, 32 KB, not uvicorn's 4 KB, which it tells the browser in the
    handshake: the next change's derivation (another release angle), most of it the symbolic steps the last
    one sent, then costs a small part of what it costs with the 4 KB window."""
    import tomllib
    import zlib
    from pathlib import Path

    from uvicorn.protocols.websockets import websockets_sansio_impl
    from websockets.frames import Frame, Opcode

    from solvers.pendulum_rebound import solve
    from ui.results import derivation_data
    from viz.pendulum_rebound import figures

    config = tomllib.loads((Path(serve.__file__).parent / ".streamlit" / "config.toml").read_text())
    assert config["server"]["enableWebsocketCompression"] is True
    uvicorn_s = websockets_sansio_impl.ServerPerMessageDeflateFactory
    monkeypatch.setattr(websockets_sansio_impl, "ServerPerMessageDeflateFactory", uvicorn_s)  # restored after
    serve.compress_websocket_fast()
    asked = dict(server_max_window_bits=12, client_max_window_bits=12, compress_settings={"memLevel": 5})  # uvicorn's
    factory = websockets_sansio_impl.ServerPerMessageDeflateFactory(**asked)
    assert factory.compress_settings == {"memLevel": 5, "level": 1}
    answer, extension = factory.process_request_params([], [])
    assert ("server_max_window_bits", "15") in answer
    figure = figures(solve())[0].json_bytes()
    assert len(factory.process_request_params([], [])[1].encode(Frame(Opcode.BINARY, figure)).data) < 0.4 * len(figure)
    first, second = (derivation_data(solve(theta0=theta0)) for theta0 in (0.6, 0.61))
    sent = [extension.encode(Frame(Opcode.BINARY, payload)).data for payload in (first, second)]
    reader = zlib.decompressobj(-15)  # the browser's, one for the connection
    assert [reader.decompress(bytes(data) + b"\x00\x00\xff\xff") for data in sent] == [first, second]
    _, narrow = uvicorn_s(**asked).process_request_params([], [])
    narrow_sent = [narrow.encode(Frame(Opcode.BINARY, payload)).data for payload in (first, second)]
    assert len(sent[1]) < 0.5 * len(narrow_sent[1]), (len(sent[1]), len(narrow_sent[1]))
