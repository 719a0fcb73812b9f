"""Validation helpers shared by the parameter dataclasses.

Every check raises :class:`ParameterError` whose message is one line naming the field, the value
and what is allowed, so the CLI can print it verbatim (exit code 2, no traceback).
"""
from __future__ import annotations

import math

import numpy as np


class ParameterError(ValueError):
    """A physical parameter is out of its allowed range (one-line message)."""

    def __init__(self, field: str, value, allowed: str):
        self.field = field
        self.value = value
        self.allowed = allowed
        super().__init__(f"{field} = {value!r}: {allowed}")


def finite(field: str, value) -> float:
    """``value`` as a finite float, or ParameterError naming ``field``.

    Parameters
    ----------
    field : str
        Dotted name of the field, for the message.
    value : float
        The value [its field's unit].
    """
    try:
        v = float(value)
    except (TypeError, ValueError):
        raise ParameterError(field, value, "must be a real number") from None
    if not math.isfinite(v):
        raise ParameterError(field, value, "must be a finite number (not NaN or inf)")
    return v


def positive(field: str, value) -> float:
    """``value`` as a float > 0, or ParameterError naming ``field``.

    Parameters
    ----------
    field : str
        Dotted name of the field, for the message.
    value : float
        The value [its field's unit].
    """
    v = finite(field, value)
    if v <= 0.0:
        raise ParameterError(field, value, "must be > 0")
    return v


def nonneg(field: str, value) -> float:
    """``value`` as a float >= 0, or ParameterError naming ``field``.

    Parameters
    ----------
    field : str
        Dotted name of the field, for the message.
    value : float
        The value [its field's unit].
    """
    v = finite(field, value)
    if v < 0.0:
        raise ParameterError(field, value, "must be >= 0")
    return v


def in_range(field: str, value, lo: float, hi: float) -> float:
    """``value`` as a float within [lo, hi], or ParameterError naming ``field``.

    Parameters
    ----------
    field : str
        Dotted name of the field, for the message.
    value : float
        The value [its field's unit].
    lo, hi : float
        Bounds [the field's unit], inclusive.
    """
    v = finite(field, value)
    if not (lo <= v <= hi):
        raise ParameterError(field, value, f"must be within [{lo:g}, {hi:g}]")
    return v


def count(field: str, value, lo: int = 0) -> int:
    """An integer count >= lo [-] (an integral float such as 2.0 is accepted)."""
    if isinstance(value, bool) or not isinstance(value, (int, float)) \
            or (isinstance(value, float) and not math.isfinite(value)) or int(value) != value:
        raise ParameterError(field, value, f"must be an integer >= {lo}")
    v = int(value)
    if v < lo:
        raise ParameterError(field, value, f"must be an integer >= {lo}")
    return v


def per_ball(field: str, value, n: int, check) -> tuple[float, ...]:
    """A scalar (same for all balls) or a sequence of length n, each element checked."""
    if isinstance(value, (list, tuple)):
        if len(value) != n:
            raise ParameterError(field, list(value), f"needs {n} values (one per ball) or one scalar")
        return tuple(check(f"{field}[{i}]", v) for i, v in enumerate(value))
    return tuple(check(field, value) for _ in range(n))


def array(field: str, value, *, strict: bool) -> np.ndarray:
    """Float array, finite, > 0 (strict) or >= 0; ParameterError naming ``field`` otherwise."""
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError(field, value, "must be a real number or an array of them") from None
    if not np.all(np.isfinite(a)):
        raise ParameterError(field, value, "must be finite (not NaN or inf)")
    bad = a <= 0.0 if strict else a < 0.0
    if np.any(bad):
        worst = float(a[bad].flat[0]) if a.ndim else float(a)
        raise ParameterError(field, worst, "must be > 0" if strict else "must be >= 0")
    return a
