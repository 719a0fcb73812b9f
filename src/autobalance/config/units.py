"""Units at the configuration boundary: the pint registry and SI conversion by physical kind.

A value is either a bare number, meaning SI, or a string ``"<number> <unit expression>"`` that
:mod:`pint` parses (``"20 N/mm"``, ``"0.025 kg*m"``, ``"61 deg"``, ``"1000 rpm"``, ``"167 Hz"``).
The number is a plain decimal or scientific literal; the unit expression is made of unit names
(pint's, with prefixes, ``%``, ``deg``, ``µ``), ``*`` (or ``·``), ``/``, ``^`` or ``**`` with an
integer exponent of at most :data:`MAX_EXPONENT` in magnitude (or a superscript one, ``min⁻¹``),
parentheses and ``1/`` (:func:`check_unit_expression`). Anything else (operators between
numbers, a power of the number, large exponents, function calls) is refused before pint sees
it. Radians are dimensionless.

Rotational speeds (kind ``"speed"``) follow the convention of drawings and motor plates
(:func:`speed_si`): a unit that carries an angle (``rad/s``, ``deg/s``, ``rpm``, ``rev/min``,
``rps``, ``rev/s``, ``turn/s``) is an angle per time and is converted to [rad/s]; a pure inverse
time (``min^-1``, ``1/min``, ``/min``, ``Hz``, ``kHz``, ``1/s``, ``s^-1``) counts revolutions per
time: one revolution (``2 pi`` rad) per that time [rad/s]. So ``1000 min^-1`` = ``1000 rpm`` =
104.72 rad/s and ``50 1/s`` = ``50 Hz`` = 314.16 rad/s; an angular frequency in rad/s is
written ``rad/s`` (or as a bare number). ``rev`` is defined as pint's ``revolution``.
"""
from __future__ import annotations

import functools
import math
import re
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import pint


@functools.lru_cache(maxsize=None)
def registry():
    """The one unit registry of the package (pint defaults plus ``rev = revolution``; radian
    is dimensionless), made on first use: importing pint (and the dask it imports) took 0.3 s
    of every sweep worker's start, which parses no units. ``ureg`` (module attribute) is the
    same object.

    Returns
    -------
    pint.UnitRegistry
    """
    import pint

    ureg = pint.UnitRegistry()
    ureg.define("rev = revolution")
    return ureg


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

#: Largest magnitude of an exponent in a unit expression (``m^3``, ``min^-1``, ``s**-2``).
MAX_EXPONENT = 4
#: Longest value text read [characters] (a number and its unit expression).
MAX_TEXT = 200
#: A plain decimal or scientific number (no operators, no names).
NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?"
_VALUE = re.compile(rf"\s*({NUMBER})(?![\d.eE])\s*(.*?)\s*", re.S)
_TOKEN = re.compile(r"\s*(?:(?P<sup>[⁻⁺]?[⁰¹²³⁴](?![⁰¹²³⁴⁵⁶⁷⁸⁹]))"
                    r"|(?P<name>(?:[^\W\d_]|°)(?:[^\W⁰¹²³⁴⁵⁶⁷⁸⁹]|°)*)|(?P<pct>%)"
                    r"|(?P<pow>\*\*|\^)|(?P<op>[*/·])|(?P<one>1)(?![\w.])|(?P<open>\()"
                    r"|(?P<close>\)))")
_EXPONENT = re.compile(r"\s*([-+]?\d+)(?![\w.])")


def _suffix(kind: str) -> str:
    unit = KINDS.get(kind, ("",))[0]
    return "_" + unit.replace("*", "_").replace("/", "_").replace("^", "") if unit else ""


class _Bad(Exception):
    """A value that does not fit its field (message: what is allowed)."""


def _expect(kind: str) -> str:
    unit, desc, example = KINDS[kind]
    return f"expected {desc} [{unit or '-'}], e.g. {example}"


@functools.lru_cache(maxsize=1024)
def _known_unit(name: str) -> bool:
    """Whether ``name`` is a unit of the registry (with or without a prefix; ``°``: degree)."""
    if name == "°":
        return True
    try:
        return bool(registry().parse_unit_name(name))
    except Exception:   # pint raises several types for odd names
        return False


def check_unit_expression(text: str) -> str | None:
    """Why ``text`` is not a unit expression this package reads, or None if it is one.

    A unit expression is a sequence of unit names (known to the registry, prefixes included,
    ``%``), ``*`` (or ``·``) and ``/``, powers ``^`` or ``**`` of a name or a parenthesis with
    an integer exponent of magnitude at most :data:`MAX_EXPONENT` (or a superscript one,
    ``min⁻¹``, ``m²``), balanced parentheses, and ``1`` just before ``/`` (``1/min``); it may
    start with ``/`` (``1000/min``). Nothing is evaluated.

    Parameters
    ----------
    text : str
        The unit part of a value, e.g. ``"N*mm*s/rad"`` or ``"min^-1"``.

    Returns
    -------
    str or None
        A short reason (``"exponent 1000 is larger than 4"``), or None.
    """
    if len(text) > MAX_TEXT:
        return f"longer than {MAX_TEXT} characters"
    pos, depth, prev = 0, 0, "start"
    text = text.rstrip()
    while pos < len(text):
        m = _TOKEN.match(text, pos)
        if m is None:
            return f"unexpected {text[pos:].strip()[:10]!r}"
        kind, tok = m.lastgroup, m.group(m.lastgroup)
        pos = m.end()
        if kind == "name":
            if tok.startswith("_") or not _known_unit(tok):
                return f"unknown unit {tok!r}"
            if text[pos:].lstrip().startswith("("):
                return f"{tok}(...) is not a unit"
        elif kind == "sup":                     # min⁻¹, m²: a power, as written on drawings
            if prev not in ("name", "close", "pct"):
                return "a power applies to a unit only"
            kind = "close"
        elif kind == "pow":
            if prev not in ("name", "close", "pct"):
                return "a power applies to a unit only"
            e = _EXPONENT.match(text, pos)
            if e is None:
                return "an exponent must be an integer"
            if abs(int(e.group(1))) > MAX_EXPONENT:
                return f"exponent {e.group(1)} is larger than {MAX_EXPONENT}"
            pos, kind = e.end(), "close"
        elif kind == "one":
            if not text[pos:].lstrip().startswith("/"):
                return "a number inside the unit"
        elif kind == "op" and prev == "op":
            return f"two operators in a row before {text[pos:].strip()[:10]!r}"
        elif kind == "op" and prev == "start" and tok == "*":
            return "the unit starts with '*'"
        elif kind == "open":
            depth += 1
        elif kind == "close":
            depth -= 1
            if depth < 0:
                return "unbalanced parentheses"
        prev = kind
    if depth:
        return "unbalanced parentheses"
    if prev in ("op", "open", "one"):
        return "the unit ends with an operator"
    return None


def split_value(text: str) -> tuple[str, str] | None:
    """``"<number> <unit expression>"`` -> (number, unit) as written, or None if ``text`` is
    not of that form (the unit checked by :func:`check_unit_expression`; ``""``: none).

    Parameters
    ----------
    text : str
        One value, e.g. ``"1000 min^-1"`` or ``"42"``.

    Returns
    -------
    tuple of str, or None
    """
    if len(text) > MAX_TEXT:
        return None
    m = _VALUE.fullmatch(text)
    if m is None or (m.group(2) and check_unit_expression(m.group(2)) is not None):
        return None
    return m.group(1), m.group(2)


def speed_si(q: pint.Quantity) -> float:
    """A rotational speed as a pint Quantity -> [rad/s], by the convention of the module
    docstring: an angle per time (its root units carry ``radian``) converted to rad/s; a pure
    inverse time (Hz, 1/s, 1/min) counts revolutions, 2 pi times its value in 1/s.

    Parameters
    ----------
    q : pint.Quantity
        E.g. ``Quantity(1000, "rpm")`` or ``Quantity(1000, "1/min")``.

    Returns
    -------
    float
        The speed [rad/s].

    Raises
    ------
    pint.DimensionalityError, ValueError
        Not an angle per time or an inverse time.
    """
    angle = dict(q.to_root_units().unit_items()).get("radian", 0)
    if angle == 1:
        return float(q.to("rad/s").magnitude)
    if angle:
        raise ValueError(f"radian^{angle} in a speed")
    return float(q.magnitude) * _revolutions(str(q.units))


@functools.lru_cache(maxsize=256)
def _revolutions(unit: str) -> float:
    """[rad/s] per 1 ``unit``, a pure inverse time counting revolutions: one revolution per
    that time (so 1000 min^-1 gives the same float as 1000 rpm, and 1 Hz is 2 pi rad/s)."""
    ureg = registry()
    return float((ureg.Quantity(1.0, unit) * ureg.revolution).to("rad/s").magnitude)


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
    """A string ``"<number> <unit>"`` -> SI float (pint parses slowly: cached; errors are
    not). The form is checked first (:func:`split_value`): pint never evaluates anything else."""
    unit = KINDS[kind][0]
    if any(ch in text for ch in "[],;"):
        # pint would read "[1, 2] ml" as one product (2 ml): a list must carry its units inside
        raise _Bad("one value expected; in a list each value carries its own unit "
                   "(['1 ml', '2 ml'], not [1, 2] ml)")
    parts = split_value(text)
    if parts is None:
        raise _Bad(f"cannot parse; {_expect(kind)}")
    if not parts[1]:                    # a bare number: SI
        return float(parts[0])
    try:
        q = registry().Quantity(text)
    except Exception:  # pint raises several types (UndefinedUnitError, AssertionError, ...)
        raise _Bad(f"cannot parse; {_expect(kind)}") from None
    try:
        if not dict(q.unit_items()):
            return float(q.magnitude)
        if kind == "speed":
            return speed_si(q)
        return float(q.to(unit).magnitude)
    except Exception:  # DimensionalityError, complex magnitudes, ...
        raise _Bad(_expect(kind)) from None


def parse_quantity(value: Any, kind: str, field: str = "value") -> float:
    """Parse a number (SI) or a string ``"<number> <unit>"`` into an SI float.

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
        The value in the SI unit of ``kind`` (speeds in [rad/s], by :func:`speed_si`; angles
        in [rad]).

    Raises
    ------
    ConfigError
        ``"<field> = <value>: expected ..."`` (one line).
    """
    try:
        return _si(value, kind)
    except _Bad as e:
        raise ConfigError(f"{field} = {value!r}: {e}") from None
