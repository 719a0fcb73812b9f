"""Ranges and lists of values on the command line: one grammar for every option that takes them.

The values of an option are of one physical kind (:data:`.units.KINDS`); each end or item is a
value ``"<number> <unit>"`` as in a configuration (:func:`.units.parse_quantity`: bare numbers
are SI, speeds follow :func:`.units.speed_si`). The forms:

``LO:HI:N``
    N values from LO to HI, evenly spaced (:func:`parse_range`). A unit written once applies to
    both ends: ``100:1500 rpm:30``, ``100 rpm:1500:30`` and ``100 rpm:1500 rpm:30`` are the same
    grid. Two ends with their own units are each converted (``600 rpm:25 Hz:30``); a unit that
    is not of the option's kind is refused. N is an integer (``1e3`` reads as 1000) of at least
    the option's minimum; the table it makes must fit the memory limit
    (:func:`autobalance.limits.check_memory`), checked before anything is allocated.
``LO:HI``
    An interval, the same without N, for an option that takes one (:func:`parse_interval`).
``a, b, c unit``
    A list (:func:`parse_list`): the unit on the last item applies to every item written
    without one (``0, 10, 28 rad/s``); items may carry their own (``4 g*cm, 8 g*cm``).

:data:`RANGE_GRAMMAR`, :data:`LIST_GRAMMAR` and :func:`grammar_help` give the help texts the
options share. Every refusal is a :class:`.units.ConfigError` of one line naming the option as
typed, the text and what is allowed: ``--speeds = '100:1500 rpm:0': N must be an integer >= 2``.
"""
from __future__ import annotations

import math

import numpy as np

from .units import KINDS, ConfigError, _Bad, _si, split_value

__all__ = ["LIST_GRAMMAR", "RANGE_GRAMMAR", "VALUES_METAVAR", "grammar_help", "is_range",
           "list_items", "parse_interval", "parse_list", "parse_range", "parse_values",
           "written_unit"]

#: The range grammar as the options' help texts state it.
RANGE_GRAMMAR = ("LO:HI:N, N values from LO to HI; a unit written once applies to both ends "
                 "(bare numbers SI)")
#: The list grammar as the options' help texts state it.
LIST_GRAMMAR = "or a list 'a, b, c unit' (the unit on the last applies to all)"
#: The metavar of an option taking a range or a list.
VALUES_METAVAR = "LO:HI:N|A,B,C"


def grammar_help(what: str, example: str, *, lists: bool = True, interval: bool = False,
                 tail: str = "") -> str:
    """The help text of an option taking a range (and a list), in the words every such option
    uses.

    Parameters
    ----------
    what : str
        What the values are, e.g. ``"Speeds"``.
    example : str
        An example of the option's value, e.g. ``"100:1500 rpm:30"``.
    lists : bool
        The option also takes a list ``a, b, c unit``.
    interval : bool
        The option takes ``LO:HI`` (an interval, no N) instead of ``LO:HI:N``.
    tail : str
        Text appended (the default, the bounds), e.g. ``"default 200 points ..."``.

    Returns
    -------
    str
    """
    form = (RANGE_GRAMMAR.replace("LO:HI:N, N values from LO to HI", "LO:HI, from LO to HI")
            if interval else RANGE_GRAMMAR)
    text = f"{what}: {form}" + (f", {LIST_GRAMMAR}" if lists else "") + f"; e.g. '{example}'"
    return text + (f"; {tail}" if tail else "") + "."


def _refuse(option: str, text: str, why: str) -> ConfigError:
    return ConfigError(f"{option} = {text!r}: {why}")


def _expect(kind: str) -> str:
    unit, desc, example = KINDS[kind]
    return f"{desc} [{unit or '-'}], e.g. {example}"


def _split(item: str, kind: str, option: str, text: str) -> tuple[str, str]:
    """One end or item -> (number, unit) as written; ConfigError if it is not a value."""
    parts = split_value(item.strip())
    if parts is None:
        raise _refuse(option, text, f"cannot read {item.strip()!r}; each value is "
                                    f"'<number> <unit>', {_expect(kind)}")
    return parts


def _convert(number: str, unit: str, kind: str, option: str, text: str) -> float:
    """``number`` in ``unit`` (``""``: SI) -> SI float of ``kind``; finite."""
    try:
        v = _si(f"{number} {unit}" if unit else number, kind)
    except _Bad as e:
        raise _refuse(option, text, f"{number} {unit}: {e}") from None
    if not math.isfinite(v):
        raise _refuse(option, text, f"{number} {unit}: must be finite")
    return v


def _count(text_n: str, option: str, text: str, min_points: int) -> int:
    """N of ``LO:HI:N``: an integer (or an integral float, ``1e3``) >= ``min_points``."""
    try:
        n = int(text_n.strip())
    except ValueError:
        try:
            v = float(text_n.strip())
        except ValueError:
            v = float("nan")
        n = int(v) if math.isfinite(v) and v == int(v) else min_points - 1
    if n < min_points:
        raise _refuse(option, text, f"N must be an integer >= {min_points}")
    return n


def _ends(lo: str, hi: str, kind: str, option: str, text: str) -> tuple[float, float]:
    """The two ends of a range, the unit written on one applying to both -> SI floats."""
    (a, ua), (b, ub) = _split(lo, kind, option, text), _split(hi, kind, option, text)
    ua, ub = ua or ub, ub or ua
    return _convert(a, ua, kind, option, text), _convert(b, ub, kind, option, text)


def is_range(text: str) -> bool:
    """Whether ``text`` is written as a range (``LO:HI:N`` or ``LO:HI``), not a list.

    Parameters
    ----------
    text : str
        An option's value.

    Returns
    -------
    bool
    """
    return ":" in text


def _check_order(lo: float, hi: float, option: str, text: str, increasing: bool,
                 low: float | None, above: bool) -> None:
    """Refuse LO >= HI (``increasing``) and LO below ``low`` [SI] (``above``: LO <= low too)."""
    if increasing and not lo < hi:
        raise _refuse(option, text, "LO must be below HI")
    if low is not None and (lo <= low if above else lo < low):
        raise _refuse(option, text, f"LO must be {'>' if above else '>='} {low:g}")


def parse_range(text: str, kind: str, option: str, *, min_points: int = 2,
                max_points: int | None = None, bytes_per_point: float = 0.0,
                what: str = "table", increasing: bool = True, low: float | None = None,
                above: bool = False) -> np.ndarray:
    """``LO:HI:N`` -> N values [SI unit of ``kind``] from LO to HI (the module's grammar).

    Parameters
    ----------
    text : str
        The option's value, e.g. ``"100:1500 rpm:30"``.
    kind : str
        A key of :data:`.units.KINDS` (``"speed"``: [rad/s]).
    option : str
        The option as the user typed it, for the messages (``"--speeds"``).
    min_points : int
        Least N [-].
    max_points : int, optional
        Most N [-] (a bound of the computation, beside the memory limit).
    bytes_per_point : float
        Memory of one value's results [B]: N times it must fit the memory limit
        (:func:`autobalance.limits.check_memory`); 0: not checked.
    what : str
        What the values make, for the memory message (``"response table"``).
    increasing : bool
        Require LO < HI.
    low : float, optional
        Least LO [SI unit of ``kind``] (e.g. 0).
    above : bool
        LO must exceed ``low`` (not equal it).

    Returns
    -------
    numpy.ndarray
        The values [SI unit of ``kind``], ``numpy.linspace(LO, HI, N)``.

    Raises
    ------
    ConfigError
        Not of the grammar, a unit not of ``kind``, N or the ends out of bounds (one line).
    ResourceError
        The table would not fit the memory limit.
    """
    parts = text.split(":")
    if len(parts) != 3:
        raise _refuse(option, text, f"expected {RANGE_GRAMMAR}, e.g. '{_example(kind)}'")
    lo, hi = _ends(parts[0], parts[1], kind, option, text)
    n = _count(parts[2], option, text, min_points)
    if max_points is not None and n > max_points:
        raise _refuse(option, text, f"N must be at most {max_points}")
    _check_order(lo, hi, option, text, increasing, low, above)
    if bytes_per_point:
        from ..limits import check_memory

        check_memory(option, text, float(n) * bytes_per_point, f"{what} of {n} values")
    return np.linspace(lo, hi, n)


def parse_interval(text: str, kind: str, option: str, *, low: float | None = None,
                   strict: bool = True) -> tuple[float, float]:
    """``LO:HI`` -> (LO, HI) [SI unit of ``kind``], a unit written once applying to both.

    Parameters
    ----------
    text : str
        The option's value, e.g. ``"3:9 g*cm"``.
    kind : str
        A key of :data:`.units.KINDS`.
    option : str
        The option as typed, for the messages (``"--unbalance"``).
    low : float, optional
        Least LO [SI unit of ``kind``].
    strict : bool
        Require LO < HI (else LO <= HI).

    Returns
    -------
    tuple of float
        (LO, HI) [SI unit of ``kind``].

    Raises
    ------
    ConfigError
        Not ``LO:HI``, a unit not of ``kind``, or the ends out of order (one line).
    """
    parts = text.split(":")
    if len(parts) != 2:
        raise _refuse(option, text, "expected LO:HI; a unit written once applies to both "
                                    f"ends (bare numbers SI), e.g. '{_example(kind, False)}'")
    lo, hi = _ends(parts[0], parts[1], kind, option, text)
    if (hi <= lo) if strict else (hi < lo):
        raise _refuse(option, text, f"LO must be {'below' if strict else 'at most'} HI")
    _check_order(lo, hi, option, text, False, low, False)
    return lo, hi


def _list_parts(text: str, kind: str, option: str) -> list[tuple[str, str]]:
    """``a, b, c unit`` -> [(number, unit)], the last item's unit given to every item
    written without one."""
    items = [x.strip() for x in text.split(",")]
    if not any(items) or not all(items):
        raise _refuse(option, text, f"expected a value or a list 'a, b, c unit', {_expect(kind)}")
    parts = [_split(x, kind, option, text) for x in items]
    unit = parts[-1][1]
    if not unit and any(u for _, u in parts):
        raise _refuse(option, text, "write the unit on the last item (it applies to all) or "
                                    "on each")
    return [(a, u or unit) for a, u in parts]


def list_items(text: str, kind: str, option: str) -> list[str]:
    """``a, b, c unit`` -> the items as values, each with its unit (the last item's unit
    given to every item written without one), e.g. ``["4 g*cm", "8 g*cm"]``.

    Parameters
    ----------
    text : str
        The option's value.
    kind : str
        A key of :data:`.units.KINDS` (for the messages).
    option : str
        The option as typed, for the messages.

    Returns
    -------
    list of str
        At least one item.

    Raises
    ------
    ConfigError
        Empty, or an item that is not ``<number> <unit>`` (one line).
    """
    return [f"{a} {u}".strip() for a, u in _list_parts(text, kind, option)]


def parse_list(text: str, kind: str, option: str, *, max_points: int | None = None
               ) -> np.ndarray:
    """``a, b, c unit`` -> the values [SI unit of ``kind``] (the module's grammar).

    Parameters
    ----------
    text : str
        The option's value, e.g. ``"0, 0.6, 28 rad/s"``.
    kind : str
        A key of :data:`.units.KINDS`.
    option : str
        The option as typed, for the messages.
    max_points : int, optional
        Most items [-].

    Returns
    -------
    numpy.ndarray
        The values [SI unit of ``kind``], in the order written.

    Raises
    ------
    ConfigError
        Empty, too many items, or an item that is not a value of ``kind`` (one line).
    """
    parts = _list_parts(text, kind, option)
    if max_points is not None and len(parts) > max_points:
        raise _refuse(option, text, f"at most {max_points} values")
    return np.array([_convert(a, u, kind, option, text) for a, u in parts], float)


def parse_values(text: str, kind: str, option: str, *, min_points: int = 1,
                 max_points: int | None = None, bytes_per_point: float = 0.0,
                 what: str = "table", increasing: bool = False) -> np.ndarray:
    """A range ``LO:HI:N`` (:func:`parse_range`) or a list ``a, b, c unit``
    (:func:`parse_list`), by its form.

    Parameters
    ----------
    text : str
        The option's value.
    kind : str
        A key of :data:`.units.KINDS`.
    option : str
        The option as typed, for the messages.
    min_points, max_points, bytes_per_point, what, increasing
        As for :func:`parse_range` (``max_points`` also bounds a list; ``increasing`` applies
        to a range only).

    Returns
    -------
    numpy.ndarray
        The values [SI unit of ``kind``].

    Raises
    ------
    ConfigError, ResourceError
        As :func:`parse_range` and :func:`parse_list`.
    """
    if is_range(text):
        return parse_range(text, kind, option, min_points=min_points, max_points=max_points,
                           bytes_per_point=bytes_per_point, what=what, increasing=increasing)
    return parse_list(text, kind, option, max_points=max_points)


def written_unit(text: str) -> str:
    """The unit written on a range or list (the first end's or item's that has one; ``/min``
    as ``1/min``), ``""`` for bare numbers or a text not of the grammar.

    Parameters
    ----------
    text : str
        The option's value, e.g. ``"400:900 rpm:6"`` -> ``"rpm"``.

    Returns
    -------
    str
    """
    pieces = text.split(":")[:2] if is_range(text) else text.split(",")
    units = [p[1] for p in (split_value(x.strip()) for x in pieces) if p is not None and p[1]]
    unit = units[0] if units else ""
    return "1" + unit if unit.startswith("/") else unit       # 1000/min: 1/min


def _example(kind: str, with_n: bool = True) -> str:
    """An example range of ``kind`` for the messages (``"100:1500 rpm:30"``)."""
    unit = KINDS.get(kind, ("",))[0]
    ex = {"speed": "100:1500 rpm", "volume": "50:350 ml", "unbalance": "3:9 g*cm",
          "length": "40:60 mm"}.get(kind, f"1:2 {unit}".strip())
    return ex + (":30" if with_n else "")
