"""Loopback servers for the scheduler tests: real sockets that are not Dask schedulers."""

from __future__ import annotations

import socket
import struct
import threading

import pytest

#: The server modes a gyroshell without Dask cannot tell from a scheduler: the probe
#: passes (a plausible message length), so only Dask's own handshake refuses them.
NEEDS_DASK = ("stall",)


def closed_port() -> int:
    """A loopback port nothing listens on (bound, then released)."""
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def dask_for(mode: str) -> None:
    """Skip the test if refusing a server of ``mode`` needs Dask and it is not importable
    (without Dask such a server is refused earlier, for want of Dask)."""
    if mode in NEEDS_DASK:
        pytest.importorskip("distributed", exc_type=ImportError)


class FakeServer:
    """A loopback TCP server that is not a Dask scheduler: on each connection it says
    nothing (``silent``), closes at once (``close``), answers like an HTTP server
    (``http``) or sends a plausible Dask message length and then nothing (``stall``)."""

    REPLIES = {"silent": None, "close": b"", "http": b"HTTP/1.1 400 Bad Request\r\n\r\n",
               "stall": struct.pack("<Q", 64)}

    def __init__(self, mode: str) -> None:
        self.mode, self.conns = mode, []
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.port = self.sock.getsockname()[1]
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()

    def _serve(self) -> None:
        while True:
            try:
                conn, _ = self.sock.accept()
            except OSError:  # closed by stop()
                return
            reply = self.REPLIES[self.mode]
            if reply == b"":
                conn.close()
                continue
            if reply is not None:
                conn.sendall(reply)
            self.conns.append(conn)

    def stop(self) -> None:
        self.sock.close()
        for conn in self.conns:
            conn.close()
