"""The Dask scheduler of a sweep: its address checked at once, then reached within seconds.

:func:`connect` refuses, in one line and before anything is created on disk:

* a malformed address (``'not a url'``, no port, an unknown scheme) at once, without
  contacting anything (:func:`parse_address`);
* a well-formed address where nothing answers: its host is resolved and its TCP port tried
  within :data:`CONNECT_TIMEOUT_S` each (a refused port fails at once, a silent host after the
  timeout), then, for ``tcp://``, the scheduler is asked who it is (Dask's ``identity`` call)
  within the same time, so that a port held by another service (that accepts the connection
  and never answers Dask's handshake) is refused too.

Only then is a :class:`distributed.Client` made: its own failure paths wait for its timeout at
exit, twice, and print an ignored exception.
"""
from __future__ import annotations

import asyncio
import re
import socket
import threading

from .spec import SweepError

__all__ = ["CONNECT_TIMEOUT_S", "SCHEMES", "connect", "parse_address"]

#: Address schemes of distributed's comms that a sweep can use.
SCHEMES = ("tcp", "tls", "ws", "wss", "ucx")
#: Seconds [s] for each of: resolving the host, opening its port, the scheduler's reply.
CONNECT_TIMEOUT_S = 3.0
_ADDRESS = re.compile(r"(?:(?P<scheme>[A-Za-z]+)://)?"
                      r"(?P<host>\[[0-9A-Fa-f:.]+\]|[A-Za-z0-9](?:[A-Za-z0-9._-]*[A-Za-z0-9])?)"
                      r":(?P<port>[0-9]{1,5})/?")


def parse_address(address: str, where: str = "--scheduler") -> tuple[str, str, int]:
    """(scheme, host, port) of a scheduler address such as ``tcp://127.0.0.1:8786``.

    Parameters
    ----------
    address : str
        The address; without a scheme it is tcp (as distributed takes it).
    where : str
        The option or setting it came from, for the message.

    Returns
    -------
    tuple
        (scheme, host without brackets, port).

    Raises
    ------
    SweepError
        Not SCHEME://HOST:PORT with a known scheme and a port 1..65535 (one line).
    """
    m = _ADDRESS.fullmatch(str(address).strip())
    scheme = (m.group("scheme") or "tcp").lower() if m else ""
    port = int(m.group("port")) if m else 0
    if not m or scheme not in SCHEMES or not 1 <= port <= 65535:
        raise SweepError(f"{where} {address!r}: not a scheduler address; expected "
                         f"SCHEME://HOST:PORT with SCHEME one of {', '.join(SCHEMES)}, e.g. "
                         "tcp://127.0.0.1:8786")
    return scheme, m.group("host").strip("[]"), port


def _resolve(host: str, port: int) -> list:
    """getaddrinfo within CONNECT_TIMEOUT_S (a thread: the resolver has no timeout of its own)."""
    out: dict = {}

    def run():
        try:
            out["r"] = socket.getaddrinfo(host, port, type=socket.SOCK_STREAM)
        except OSError as e:
            out["e"] = e

    t = threading.Thread(target=run, daemon=True)
    t.start()
    t.join(CONNECT_TIMEOUT_S)
    if "e" in out:
        raise out["e"]
    if "r" not in out:
        raise TimeoutError(f"the host name did not resolve within {CONNECT_TIMEOUT_S:g} s")
    return out["r"]


def _open_port(host: str, port: int) -> None:
    """Open and close a TCP connection to the host's port (OSError if nothing answers)."""
    err: OSError = OSError(f"no address for {host}")
    for family, kind, proto, _, addr in _resolve(host, port):
        s = socket.socket(family, kind, proto)
        s.settimeout(CONNECT_TIMEOUT_S)
        try:
            s.connect(addr)
            return
        except OSError as e:
            err = e
        finally:
            s.close()
    raise err


async def _identity(address: str) -> dict:
    """The scheduler's answer to Dask's ``identity`` call."""
    from distributed.comm import connect as comm_connect

    comm = await comm_connect(address, timeout=CONNECT_TIMEOUT_S)
    try:
        await comm.write({"op": "identity", "reply": True})
        return await comm.read()
    finally:
        comm.abort()


def _why(e: BaseException) -> str:
    if isinstance(e, (TimeoutError, socket.timeout, asyncio.TimeoutError)):
        return str(e) or f"no answer within {CONNECT_TIMEOUT_S:g} s"
    text = getattr(e, "strerror", None) or " ".join(str(e).split())[:120]
    return text or type(e).__name__


def connect(address: str, where: str = "--scheduler"):
    """A :class:`distributed.Client` of the scheduler at ``address``, or a one-line refusal
    within a few seconds (see the module docstring).

    Parameters
    ----------
    address : str
        The scheduler's address, e.g. ``tcp://127.0.0.1:8786``.
    where : str
        The option or setting it came from (``--scheduler``, ``DASK_SCHEDULER_ADDRESS``).

    Returns
    -------
    distributed.Client
        Not the default client; the caller closes it.

    Raises
    ------
    SweepError
        A malformed address, or no Dask scheduler answers there (one line; nothing created).
    """
    scheme, host, port = parse_address(address, where)

    def refuse(e: BaseException):
        return SweepError(f"{where} {address!r}: no Dask scheduler answers ({_why(e)}); "
                          "nothing was created")

    try:
        _open_port(host, port)
    except OSError as e:      # refused, unreachable, silent (TimeoutError), unknown host
        raise refuse(e) from None
    if scheme == "tcp":
        try:
            who = asyncio.run(asyncio.wait_for(_identity(address), CONNECT_TIMEOUT_S))
        except (TimeoutError, asyncio.TimeoutError):
            raise refuse(TimeoutError(f"the service at that port gave no Dask reply within "
                                      f"{CONNECT_TIMEOUT_S:g} s")) from None
        except Exception as e:   # CommClosedError, a garbled frame (MemoryError, ValueError)
            raise refuse(OSError(f"the service at that port does not speak Dask's protocol "
                                 f"({type(e).__name__})")) from None
        if not isinstance(who, dict) or who.get("type") != "Scheduler":
            kind = who.get("type") if isinstance(who, dict) else type(who).__name__
            raise refuse(OSError(f"it is a {kind}, not a scheduler"))
    from distributed import Client

    try:
        return Client(address, set_as_default=False, timeout=f"{4 * CONNECT_TIMEOUT_S:g}s")
    except Exception as e:   # it answered a moment ago: it went away, or a tls/ws handshake
        raise refuse(e) from None
