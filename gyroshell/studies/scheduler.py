"""The address of a Dask scheduler: checked at once, then probed before Dask is handed it.

A study refuses a bad ``scheduler`` in well under a second and never waits longer than
``connect_timeout`` for one that does not answer:

1. :func:`check_address` reads the address (no import of Dask, no network): a scheme of
   :data:`SCHEMES`, a host name or IP address, a port in 1..65535.
2. :func:`probe` connects a plain socket to HOST:PORT within the timeout: "connection
   refused" (nothing listens there: immediate), an unknown host or an unreachable network
   are refused at once, naming the address. For ``tcp://`` it also reads the first bytes
   the other end sends: a Dask scheduler speaks first, its handshake starting with the
   message's length (8 bytes, little-endian); a server that says nothing, closes at once
   or sends text (an HTTP or SSH server on that port) is refused, quoting what it sent.
3. :func:`handshake` then lets Dask itself connect and exchange the handshake, with the
   whole exchange under the same deadline (Dask's own timeout covers only the TCP
   connect, not the handshake after it).
"""

from __future__ import annotations

import asyncio
import ipaddress
import logging
import re
import socket
import struct
import threading
import time
from contextlib import contextmanager
from dataclasses import dataclass

from ..core.errors import ParameterError

__all__ = ["DASK_LOGGERS", "MAX_HANDSHAKE_BYTES", "SCHEMES", "SchedulerAddress",
           "check_address", "handshake", "probe"]

#: Address schemes a study connects to (Dask's TCP-based transports; ``inproc://`` for a
#: cluster started in this Python process). ``ucx://`` needs ucx-py and is not offered.
SCHEMES: tuple[str, ...] = ("tcp", "tls", "ws", "wss", "inproc")
#: The schemes whose HOST:PORT a plain socket can probe.
SOCKET_SCHEMES: tuple[str, ...] = ("tcp", "tls", "ws", "wss")
#: Largest first message accepted from a scheduler, bytes: its handshake is a few hundred.
MAX_HANDSHAKE_BYTES = 1 << 20
#: Loggers of Dask that report a failed handshake with a traceback: quiet while probing.
DASK_LOGGERS: tuple[str, ...] = ("distributed", "distributed.protocol.core",
                                 "distributed.comm.tcp", "distributed.core")

_LABEL = re.compile(r"^(?!-)[A-Za-z0-9-]{1,63}(?<!-)$")
_FORM = ("an address like tcp://HOST:PORT (schemes: "
         + ", ".join(f"{s}://" for s in SCHEMES) + ")")


@dataclass(frozen=True)
class SchedulerAddress:
    """A checked scheduler address: ``scheme``, ``host`` (without brackets), ``port``
    (None for ``inproc://``) and the ``text`` given."""

    scheme: str
    host: str
    port: int | None
    text: str


def check_address(scheduler: object) -> SchedulerAddress:
    """The scheduler address read and checked, without the network.

    Raises
    ------
    ParameterError
        Naming what is wrong: not text, an unknown scheme (listing :data:`SCHEMES`), a
        malformed host, a missing port or one outside 1..65535.

    Examples
    --------
    >>> check_address("tcp://127.0.0.1:8786").port
    8786
    >>> check_address("http://127.0.0.1:8786")
    Traceback (most recent call last):
    ...
    gyroshell.ParameterError: scheduler 'http://127.0.0.1:8786': unknown scheme 'http://'; ...
    """
    if not isinstance(scheduler, str) or "://" not in scheduler:
        raise ParameterError(f"scheduler must be {_FORM}, got {scheduler!r}")
    scheme, _, location = scheduler.partition("://")
    if scheme.lower() not in SCHEMES:
        raise ParameterError(f"scheduler {scheduler!r}: unknown scheme '{scheme}://'; use "
                             + ", ".join(f"{s}://" for s in SCHEMES))
    scheme = scheme.lower()
    if scheme == "inproc":
        if not location.strip():
            raise ParameterError(f"scheduler {scheduler!r}: an inproc:// address names the "
                                 "in-process scheduler (cluster.scheduler_address)")
        return SchedulerAddress(scheme, location, None, scheduler)
    host, port = _host_port(scheduler, location.rstrip("/"))
    return SchedulerAddress(scheme, host, port, scheduler)


def _host_port(text: str, location: str) -> tuple[str, int]:
    """(host, port) of ``HOST:PORT`` or ``[IPv6]:PORT``, each checked."""
    if location.startswith("["):
        host, sep, rest = location[1:].partition("]")
        port_text = rest[1:] if rest.startswith(":") else None
        try:
            ipaddress.IPv6Address(host)
        except ValueError:
            raise ParameterError(f"scheduler {text!r}: [{host}] is not an IPv6 address"
                                 ) from None
        if not sep:
            raise ParameterError(f"scheduler {text!r}: missing ']' after the IPv6 address")
    else:
        host, sep, port_text = location.rpartition(":")
        if not sep:
            host, port_text = location, None
        _check_host(text, host)
    if port_text is None or not port_text:
        raise ParameterError(f"scheduler {text!r}: give the port, e.g. {text.rstrip('/')}"
                             ":8786 (Dask's default)")
    if not port_text.isdigit() or not 1 <= int(port_text) <= 65535:
        raise ParameterError(f"scheduler {text!r}: port must be an integer in [1, 65535], "
                             f"got {port_text!r}")
    return host, int(port_text)


def _check_host(text: str, host: str) -> None:
    """A host name (letters, digits, '-' in dot-separated labels) or an IPv4 address."""
    labels = host.split(".")
    if all(label.isdigit() for label in labels):
        try:
            ipaddress.IPv4Address(host)
            return
        except ValueError:
            raise ParameterError(f"scheduler {text!r}: {host!r} is not an IPv4 address"
                                 ) from None
    if not host or len(host) > 253 or not all(_LABEL.match(label) for label in labels):
        raise ParameterError(f"scheduler {text!r}: {host!r} is not a host name (letters, "
                             "digits and '-' in dot-separated labels) or an IP address")


def probe(address: SchedulerAddress, timeout: float) -> None:
    """Connect a plain socket to the scheduler's HOST:PORT within ``timeout`` (s) and, for
    ``tcp://``, read the start of its handshake; refuse at once what cannot be a Dask
    scheduler.

    Raises
    ------
    ParameterError
        Connection refused (nothing listens there), an unknown host, an unreachable
        network, no answer within ``timeout``, or an answer that is not Dask's.
    """
    if address.scheme not in SOCKET_SCHEMES:
        return
    where = f"the Dask scheduler at {address.text}"
    deadline = time.monotonic() + timeout
    try:
        sock = socket.create_connection((address.host, address.port), timeout=timeout)
    except ConnectionRefusedError:
        raise ParameterError(f"cannot reach {where}: connection refused (nothing listens "
                             f"on port {address.port} of {address.host}); start it with "
                             f"'dask scheduler --port {address.port}' or check the address"
                             ) from None
    except socket.gaierror as exc:
        raise ParameterError(f"cannot reach {where}: unknown host {address.host!r} "
                             f"({exc.strerror})") from None
    except TimeoutError:
        raise ParameterError(f"cannot reach {where}: no answer to the connection within "
                             f"{timeout:g} s (connect_timeout)") from None
    except OSError as exc:
        raise ParameterError(f"cannot reach {where}: {exc.strerror or exc}") from None
    with sock:
        if address.scheme == "tcp":
            _check_first_bytes(sock, where, deadline, timeout)


def _check_first_bytes(sock: socket.socket, where: str, deadline: float,
                       timeout: float) -> None:
    """The first 8 bytes from the other end: a Dask message length, or a refusal."""
    first = b""
    try:
        while len(first) < 8:
            sock.settimeout(max(deadline - time.monotonic(), 1e-3))
            chunk = sock.recv(8 - len(first))
            if not chunk:
                break
            first += chunk
    except TimeoutError:
        raise ParameterError(f"{where} did not answer: something accepts connections there "
                             f"but sent no Dask handshake within {timeout:g} s "
                             "(connect_timeout); check the port") from None
    except OSError as exc:
        raise ParameterError(f"{where} closed the connection ({exc.strerror or exc}) "
                             "without a Dask handshake; check the port") from None
    if len(first) < 8:
        raise ParameterError(f"{where} closed the connection without a Dask handshake "
                             f"(received {first[:40]!r}); check the port")
    (length,) = struct.unpack("<Q", first)
    if not 8 <= length <= MAX_HANDSHAKE_BYTES:
        raise ParameterError(f"{where} is not a Dask scheduler: it answered "
                             f"{_more(sock, first)!r}, not a Dask handshake; check the port")


def _more(sock: socket.socket, first: bytes) -> bytes:
    """``first`` and what else the other end has already sent (up to 40 bytes), to quote."""
    sock.settimeout(0.05)
    try:
        return first + sock.recv(32)
    except OSError:  # nothing more at once (a timeout is an OSError): quote what came
        return first


def handshake(address: SchedulerAddress, timeout: float, connection_args: dict) -> None:
    """Dask's own connection and handshake to the scheduler, all within ``timeout`` (s).

    Runs in a thread of its own with a fresh event loop (so that it also works where an
    event loop already runs, as in a notebook).

    Raises
    ------
    ParameterError
        No handshake within ``timeout``, a closed connection or an answer Dask cannot read.
    """
    outcome: list[BaseException | None] = []

    def run() -> None:
        try:
            asyncio.run(asyncio.wait_for(_connect_and_close(address.text, timeout,
                                                            connection_args), timeout))
            outcome.append(None)
        except BaseException as exc:  # noqa: BLE001 - handed to the calling thread below
            outcome.append(exc)

    with _quiet_dask_loggers():
        thread = threading.Thread(target=run, name="gyroshell-dask-handshake", daemon=True)
        thread.start()
        thread.join(timeout + 1.0)
    where = f"the Dask scheduler at {address.text}"
    if not outcome or isinstance(outcome[0], (TimeoutError, asyncio.TimeoutError)):
        raise ParameterError(f"{where} did not complete Dask's handshake within "
                             f"{timeout:g} s (connect_timeout): not a Dask scheduler, or "
                             "it is overloaded")
    if address.scheme == "inproc" and isinstance(outcome[0], ValueError):
        raise ParameterError(f"no Dask scheduler of this process listens at {address.text} "
                             "(inproc:// reaches only a cluster started in this process)")
    _raise_for(outcome[0], where)


def _raise_for(error: BaseException | None, where: str) -> None:
    """The handshake's outcome as a ParameterError (None: it succeeded)."""
    if error is None:
        return
    if isinstance(error, OSError):  # Dask's CommClosedError is an OSError
        raise ParameterError(f"cannot reach {where}: {error}") from None
    if isinstance(error, _websocket_errors()):  # ws://, wss:// to a server that is not Dask's
        raise ParameterError(f"{where} is not a Dask scheduler: {error}; check the port"
                             ) from None
    if isinstance(error, (MemoryError, struct.error, ValueError, TypeError, KeyError,
                          IndexError, EOFError)):  # what undecodable bytes raise in Dask
        raise ParameterError(f"{where} is not a Dask scheduler: its answer is not a Dask "
                             f"handshake ({type(error).__name__}); check the port") from None
    raise error


def _websocket_errors() -> tuple[type[BaseException], ...]:
    """What tornado (Dask's ws:// transport) raises for an answer that is not a websocket."""
    try:
        from tornado.httpclient import HTTPClientError
        from tornado.websocket import WebSocketError
    except ImportError:  # pragma: no cover - Dask installs tornado
        return ()
    return (WebSocketError, HTTPClientError)


async def _connect_and_close(text: str, timeout: float, connection_args: dict) -> None:
    from distributed.comm import connect

    comm = await connect(text, timeout=timeout, **connection_args)
    await comm.close()


@contextmanager
def _quiet_dask_loggers():
    """Dask's loggers silenced (they print a traceback for an undecodable handshake); the
    failure is reported as one ParameterError instead."""
    loggers = [logging.getLogger(name) for name in DASK_LOGGERS]
    levels = [lg.level for lg in loggers]
    for lg in loggers:
        lg.setLevel(logging.CRITICAL + 1)
    try:
        yield
    finally:
        for lg, level in zip(loggers, levels, strict=True):
            lg.setLevel(level)
