"""Units at the configuration boundary: the pint registry and SI conversion by physical kind.

A value is either a bare number, meaning SI, or a string with units that :mod:`pint` parses
(``"20 N/mm"``, ``"0.025 kg*m"``, ``"61 deg"``, ``"1000 rpm"``, ``"167 Hz"``). Rotational speeds
in ``Hz`` are cycles per second and become ``2*pi*f`` [rad/s]; ``rpm`` becomes ``2*pi/60``
[rad/s]; ``rad/s`` and ``1/s`` stay as they are. Radians are dimensionless.
"""
from __future__ import annotations

import functools
import math
from typing import Any


@functools.lru_cache(maxsize=None)
def registry():
    """The one unit registry of the package (pint defaults; radian is dimensionless), made on
    first use: importing pint (and the dask it imports) took 0.3 s of every sweep worker's
    start, which parses no units. ``ureg`` (module attribute) is the same object.

    Returns
    -------
    pint.UnitRegistry
    """
    import pint

    return pint.UnitRegistry()


def __getattr__(name: str):
    if name == "ureg":
        return registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

TWO_PI = 2.0 * math.pi


class ConfigError(ValueError):
    """Invalid configuration; the message is one line naming the field, value and what is allowed."""

    def __init__(self, message: str):
        super().__init__(" ".join(str(message).split()))


#: kind -> (SI unit for pint, description, example). Dimensionless kinds have unit "".
KINDS: dict[str, tuple[str, str, str]] = {
    "mass": ("kg", "a mass", "'37 kg'"),
    "unbalance": ("kg*m", "an unbalance", "'0.025 kg*m' or '3000 g*cm'"),
    "inertia": ("kg*m^2", "a moment of inertia", "'0.5 kg*m^2'"),
    "rot_damping": ("N*m*s/rad", "a rotational damping", "'2.7 N*mm*s/rad'"),
    "stiffness": ("N/m", "a stiffness", "'20 N/mm'"),
    "damping": ("N*s/m", "a damping coefficient", "'200 kg/s' or '1.51 kN*s/m'"),
    "force": ("N", "a force", "'70 N'"),
    "torque": ("N*m", "a torque", "'25 N*m'"),
    "length": ("m", "a length", "'35 mm'"),
    "velocity": ("m/s", "a velocity", "'1 mm/s'"),
    "acceleration": ("m/s^2", "an acceleration", "'9.81 m/s^2'"),
    "angle": ("rad", "an angle", "'61 deg'"),
    "speed": ("rad/s", "a rotational speed", "'1000 rpm' or '167 Hz'"),
    "time": ("s", "a time", "'90 s'"),
    "ratio": ("", "a dimensionless number", "'0.002'"),
    "volume": ("m^3", "a volume", "'150 ml'"),
    "density": ("kg/m^3", "a density", "'1000 kg/m^3'"),
    "kin_viscosity": ("m^2/s", "a kinematic viscosity", "'1.01e-6 m^2/s' or '1 cSt'"),
}
#: Display form of the SI unit of each kind, and the suffix used in :func:`describe` keys.
UNIT_LABEL = {k: v[0].replace("^", "") or "-" for k, v in KINDS.items()}
UNIT_LABEL["ratio"] = "-"


def _suffix(kind: str) -> str:
    unit = KINDS.get(kind, ("",))[0]
    return "_" + unit.replace("*", "_").replace("/", "_").replace("^", "") if unit else ""


class _Bad(Exception):
    """A value that does not fit its field (message: what is allowed)."""


def _expect(kind: str) -> str:
    unit, desc, example = KINDS[kind]
    return f"expected {desc} [{unit or '-'}], e.g. {example}"


def _si(value: Any, kind: str) -> float:
    """One value of a physical kind -> SI float; raises :class:`_Bad`."""
    if isinstance(value, bool):
        raise _Bad(_expect(kind))
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str) or not value.strip():
        raise _Bad(_expect(kind))
    return _si_text(value.strip(), kind)


@functools.lru_cache(maxsize=4096)
def _si_text(text: str, kind: str) -> float:
    """A string with units -> SI float (pint parses slowly: cached; errors are not)."""
    unit = KINDS[kind][0]
    if any(ch in text for ch in "[],;"):
        # pint would read "[1, 2] ml" as one product (2 ml): a list must carry its units inside
        raise _Bad("one value expected; in a list each value carries its own unit "
                   "(['1 ml', '2 ml'], not [1, 2] ml)")
    try:
        q = registry().Quantity(text)
    except Exception:  # pint raises several types (UndefinedUnitError, AssertionError, ...)
        raise _Bad(f"cannot parse; {_expect(kind)}") from None
    try:
        if not dict(q.unit_items()):  # a bare number: SI
            return float(q.magnitude)
        if kind == "speed" and "hertz" in str(q.units):
            return float(q.to("Hz").magnitude) * TWO_PI
        return float(q.to(unit).magnitude)
    except Exception:  # DimensionalityError, complex magnitudes, ...
        raise _Bad(_expect(kind)) from None


def parse_quantity(value: Any, kind: str, field: str = "value") -> float:
    """Parse a number (SI) or a string with units into an SI float.

    Parameters
    ----------
    value : float or str
        ``5800000.0`` or ``"5.8 kN/mm"``.
    kind : str
        A key of :data:`KINDS` (``"stiffness"``, ``"speed"``, ...).
    field : str
        Dotted field name used in the error message.

    Returns
    -------
    float
        The value in the SI unit of ``kind`` (speeds in [rad/s], angles in [rad]).

    Raises
    ------
    ConfigError
        ``"<field> = <value>: expected ..."`` (one line).
    """
    try:
        return _si(value, kind)
    except _Bad as e:
        raise ConfigError(f"{field} = {value!r}: {e}") from None
