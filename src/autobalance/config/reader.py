"""The one reader of TOML input: config files, sweep files (``sweep/spec.py``) and ``--set``
values (``overrides.py``).

What is not a small UTF-8 TOML text is refused in one line (ConfigError) naming the file,
before it can hang the process or exhaust its memory:

* a path that is not a regular file (a directory, a character or block device such as
  ``/dev/zero``, a FIFO, a socket) is refused from its ``stat``, without opening it; the file
  is then opened non-blocking and checked again on the open descriptor (a file replaced by a
  FIFO in between does not block either);
* a file larger than ``AUTOBALANCE_MAX_FILE_SIZE`` (:func:`autobalance.limits.max_file_bytes`,
  default 1 MiB) is refused from its size, and at most that many bytes are ever read (a file
  that grows while it is read, or a ``/proc`` file that reports size 0);
* the bytes are decoded as UTF-8: a NUL byte (a binary file) or an invalid sequence (a
  latin-1 file) is refused with its byte offset and line;
* arrays and tables nested deeper than ``AUTOBALANCE_MAX_NESTING``
  (:func:`autobalance.limits.max_nesting`, default 32) are refused: TOML nested thousands deep
  exhausts the parser's recursion (caught), and anything less deep is measured after parsing
  without recursion.
"""
from __future__ import annotations

import os
import stat
import tomllib
from pathlib import Path
from typing import Any

from ..limits import fmt_bytes, max_file_bytes, max_nesting
from .units import ConfigError

__all__ = ["bracket_depth", "check_nesting", "load_toml", "nesting_depth", "parse_toml",
           "read_text"]

_NOT_REGULAR = ((stat.S_ISDIR, "a directory"), (stat.S_ISCHR, "a character device"),
                (stat.S_ISBLK, "a block device"), (stat.S_ISFIFO, "a FIFO (named pipe)"),
                (stat.S_ISSOCK, "a socket"))


def _check_regular(mode: int, what: str, name: str) -> None:
    for test, kind in _NOT_REGULAR:
        if test(mode):
            raise ConfigError(f"{what} {name!r} is {kind}, not a regular file; give a TOML file")
    if not stat.S_ISREG(mode):
        raise ConfigError(f"{what} {name!r} is not a regular file; give a TOML file")


def _too_big(what: str, name: str, size: str, limit: int) -> ConfigError:
    return ConfigError(f"{what} {name!r} is {size}, more than the limit of {fmt_bytes(limit)} "
                       "for an input file (set AUTOBALANCE_MAX_FILE_SIZE to raise it)")


def read_text(path: str | Path, what: str = "config file") -> str:
    """The text of a small regular UTF-8 file, or a one-line refusal.

    Parameters
    ----------
    path : str or Path
        The file.
    what : str
        What it is, for the message (``"config file"``, ``"sweep file"``).

    Returns
    -------
    str
        Its text.

    Raises
    ------
    ConfigError
        Missing or unreadable, not a regular file, larger than the limit, a NUL byte or not
        UTF-8 (one line naming the file; the byte offset for the last two).
    """
    name = str(path)
    try:
        st = os.stat(path)
    except OSError as e:
        raise ConfigError(f"cannot read {what} {name!r}: {e.strerror or e}") from None
    _check_regular(st.st_mode, what, name)
    limit = max_file_bytes()
    if st.st_size > limit:
        raise _too_big(what, name, fmt_bytes(st.st_size), limit)
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOCTTY", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(path, flags)
    except OSError as e:
        raise ConfigError(f"cannot read {what} {name!r}: {e.strerror or e}") from None
    chunks, n = [], 0
    try:
        _check_regular(os.fstat(fd).st_mode, what, name)     # the file that was opened
        while n <= limit:
            b = os.read(fd, min(1 << 16, limit + 1 - n))
            if not b:
                break
            chunks.append(b)
            n += len(b)
    except OSError as e:
        raise ConfigError(f"cannot read {what} {name!r}: {e.strerror or e}") from None
    finally:
        os.close(fd)
    if n > limit:
        raise _too_big(what, name, f"more than {fmt_bytes(limit)} (it grew while read)", limit)
    data = b"".join(chunks)
    nul = data.find(b"\0")
    if nul >= 0:
        raise ConfigError(f"{what} {name!r}: a NUL byte at offset {nul} (line "
                          f"{_line(data, nul)}); a binary file, not TOML text")
    try:
        return data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise ConfigError(f"{what} {name!r}: not UTF-8 text (byte 0x{data[e.start]:02x} at "
                          f"offset {e.start}, line {_line(data, e.start)}); save it as "
                          "UTF-8") from None


def _line(data: bytes, offset: int) -> int:
    """Line number (from 1) of a byte offset."""
    return data.count(b"\n", 0, offset) + 1


def nesting_depth(obj: Any, stop: int | None = None) -> int:
    """Levels of nested lists and dicts in ``obj`` (0 for a scalar, 1 for a flat table),
    measured without recursion.

    Parameters
    ----------
    obj : object
        Parsed TOML (dicts, lists, scalars).
    stop : int, optional
        Return as soon as the depth exceeds this (a value > stop, not the full depth).

    Returns
    -------
    int
        The depth.
    """
    deepest = 0
    stack = [(obj, 1)] if isinstance(obj, (dict, list)) else []
    while stack:
        o, d = stack.pop()
        deepest = max(deepest, d)
        if stop is not None and deepest > stop:
            break
        children = o.values() if isinstance(o, dict) else o
        stack.extend((c, d + 1) for c in children if isinstance(c, (dict, list)))
    return deepest


def _too_deep(where: str, limit: int, depth: str | None = None) -> ConfigError:
    how = f"nested {depth} levels deep" if depth is not None else "nested too deeply to parse"
    return ConfigError(f"{where}: arrays or tables {how}; at most {limit} levels are allowed "
                       "(set AUTOBALANCE_MAX_NESTING to raise it)")


def check_nesting(obj: Any, where: str) -> None:
    """Refuse parsed TOML nested deeper than the limit (:func:`autobalance.limits.max_nesting`).

    Parameters
    ----------
    obj : object
        Parsed TOML.
    where : str
        The file or option, for the message.

    Raises
    ------
    ConfigError
        Nested deeper than the limit (one line).
    """
    limit = max_nesting()
    if nesting_depth(obj, stop=limit) > limit:
        raise _too_deep(where, limit, f"more than {limit}")


def bracket_depth(text: str) -> int:
    """Deepest nesting of ``[`` and ``{`` in a TOML value written on one line, outside its
    quoted strings (for a text that is not valid TOML).

    Parameters
    ----------
    text : str
        The value as written, e.g. ``[[0, 1], [2, 3]]``.

    Returns
    -------
    int
        The depth (0 without brackets).
    """
    depth = deepest = 0
    quote = None
    escaped = False
    for c in text:
        if quote is not None:
            if escaped:
                escaped = False
            elif c == "\\" and quote == '"':
                escaped = True
            elif c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif c in "[{":
            depth += 1
            deepest = max(deepest, depth)
        elif c in "]}":
            depth = max(depth - 1, 0)
    return deepest


def parse_toml(text: str, where: str) -> dict:
    """Parse a TOML text, refusing it in one line if it is invalid or nested too deeply.

    Parameters
    ----------
    text : str
        The TOML text.
    where : str
        The file, for the messages.

    Returns
    -------
    dict
        The parsed tables.

    Raises
    ------
    ConfigError
        ``WHERE: invalid TOML: ...`` or nested deeper than the limit (one line).
    """
    try:
        d = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"{where}: invalid TOML: {' '.join(str(e).split())}") from None
    except RecursionError:                  # thousands of nested arrays or inline tables
        raise _too_deep(where, max_nesting()) from None
    check_nesting(d, where)
    return d


def load_toml(path: str | Path, what: str = "config file") -> tuple[dict, str]:
    """(parsed tables, text) of a TOML input file (:func:`read_text`, :func:`parse_toml`).

    Parameters
    ----------
    path : str or Path
        The file.
    what : str
        What it is, for the messages (``"config file"``, ``"sweep file"``).

    Returns
    -------
    tuple
        (dict, str).

    Raises
    ------
    ConfigError
        Any refusal of :func:`read_text` or :func:`parse_toml` (one line naming the file).
    """
    text = read_text(path, what)
    return parse_toml(text, str(path)), text
