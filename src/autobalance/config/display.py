"""Units for showing results: the units the user wrote, or a ``--units`` choice.

Everything inside the package is SI, and so is every JSON object (unit-suffixed keys). Terminal
text and figures instead show each quantity in the unit the user wrote for its kind in the
configuration: a centrifuge whose profile says ``nominal = "4000 rpm"`` and whose rotor says
``unbalance = "0.573 g*m"`` sees speeds in rpm and unbalances in g*m. A kind the configuration
gives only as bare numbers (SI) or not at all is shown in SI.

:func:`display_units` reads those units from :attr:`Config.raw` (the keys as written, after
``--set``): for each kind, the first key of :data:`WRITTEN_KEYS` given as a string with a unit,
then any other key of that kind in the schema. ``choice`` (the CLI's ``--units``) is ``"si"``
or a comma list ``"speed=rpm,unbalance=g*mm"`` that replaces the units of the kinds it names.

Rotational speeds follow the configuration's convention (:func:`.units.speed_si`, the same
function for reading and showing): a unit carrying an angle (``rad/s``, ``deg/s``, ``rpm``,
``rev/min``) is an angle per time; a pure inverse time (``Hz``, ``1/s``, ``min^-1``, ``1/min``)
counts revolutions, so ``2 pi`` rad/s show as 1 Hz or 1 1/s and 1000 rpm as 1000 1/min (pint
alone would show 1 rad/s as 1 Hz).
"""
from __future__ import annotations

import functools
import math
import re
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from .schema import PROFILE_KINDS, SECTIONS
from .units import (KINDS, NUMBER, ConfigError, check_unit_expression, registry, speed_si,
                    split_value)

if TYPE_CHECKING:
    from .load import Config

__all__ = ["DISPLAY_KINDS", "WRITTEN_KEYS", "DisplayUnits", "as_written", "display_units",
           "written_unit"]

#: The kinds shown in display units, and their SI unit (grade: ISO 1940's mm/s, always).
DISPLAY_KINDS: dict[str, str] = {"speed": "rad/s", "unbalance": "kg*m", "length": "m",
                                 "mass": "kg", "force": "N", "time": "s", "volume": "m^3",
                                 "grade": "mm/s"}

#: The keys whose written unit sets a kind's display unit, first match wins; then any other key
#: of that kind (schema order).
WRITTEN_KEYS: dict[str, tuple[str, ...]] = {
    "speed": ("profile.nominal", "profile.speed", "profile.end_speed", "profile.final_speed",
              "profile.nominal_speed", "profile.speeds", "profile.plateau"),
    "unbalance": ("rotor.unbalance", "rotor.unbalance_schedule"),
    "length": ("balancer.race_radius", "balancer.eccentricity", "balancer.ball_radius"),
    "mass": ("rotor.mass", "balancer.ball_mass"),
    "force": ("suspension.dry_friction_force",),
    "time": ("profile.duration", "profile.ramp_time", "profile.times"),
    "volume": ("liquid.volume",),
}

@functools.lru_cache(maxsize=256)
def _factor(unit: str, kind: str) -> float:
    """Display value per SI value of ``kind`` in ``unit`` (pint parses slowly: cached); a
    speed by :func:`.units.speed_si`, as the configuration reads it."""
    if kind == "speed":
        return 1.0 / speed_si(registry().Quantity(1.0, unit))
    return float(registry().Quantity(1.0, DISPLAY_KINDS[kind]).to(unit).magnitude)


def _check_unit(text: Any, kind: str) -> str | None:
    """``text`` as a unit of ``kind`` (converts from its SI unit), or None if it is not one
    (or not a unit expression of :func:`.units.check_unit_expression`)."""
    if not isinstance(text, str) or not text.strip():
        return None
    text = text.strip()
    if check_unit_expression(text) is not None:
        return None
    try:
        unit = registry().parse_units(text)
        registry().Quantity(1.0, DISPLAY_KINDS[kind]).to(unit)
        if kind == "speed":
            speed_si(registry().Quantity(1.0, unit))
    except Exception:   # pint raises several types (UndefinedUnitError, DimensionalityError...)
        return None
    return text if str(unit) != "dimensionless" else None


def written_unit(value: Any, kind: str) -> str | None:
    """The unit written in one configuration value of ``kind``, as written.

    Parameters
    ----------
    value : str, number or list
        A value as in a TOML file: ``"4000 rpm"`` -> ``"rpm"``, ``"0.573 g*m"`` -> ``"g*m"``;
        a list gives the unit of its first value that has one (pairs: their second item for
        an unbalance schedule, their first for a time).
    kind : str
        A key of :data:`DISPLAY_KINDS` other than ``"grade"``.

    Returns
    -------
    str or None
        A pint unit string, or None for a bare number (SI), a missing value or a unit that does
        not fit ``kind``.
    """
    if isinstance(value, (list, tuple)):
        for item in value:
            if isinstance(item, (list, tuple)) and len(item) == 2:
                item = item[1] if kind == "unbalance" else item[0]
            unit = written_unit(item, kind)
            if unit is not None:
                return unit
        return None
    if not isinstance(value, str):
        return None
    parts = split_value(value.strip())
    if parts is None or not parts[1]:
        return None
    unit = parts[1]
    return _check_unit("1" + unit if unit.startswith("/") else unit, kind)   # 1000/min


def _keys_of_kind(kind: str) -> list[str]:
    """Every config key of ``kind``: WRITTEN_KEYS first, then the schema's other keys."""
    keys = list(WRITTEN_KEYS.get(kind, ()))
    for section, specs in SECTIONS.items():
        keys += [f"{section}.{k}" for k, s in specs.items()
                 if (s.kind == kind or kind in s.pair_kinds) and f"{section}.{k}" not in keys]
    for specs in PROFILE_KINDS.values():
        keys += [f"profile.{k}" for k, s in specs.items()
                 if s.kind == kind and f"profile.{k}" not in keys]
    return keys


def _written_units(raw: dict) -> dict[str, str]:
    """Kind -> the unit the configuration ``raw`` writes for it (kinds it writes none for are
    left out)."""
    out = {}
    for kind in DISPLAY_KINDS:
        if kind == "grade":
            continue
        for path in _keys_of_kind(kind):
            section, key = path.split(".", 1)
            table = raw.get(section) if isinstance(raw, dict) else None
            unit = written_unit(table.get(key), kind) if isinstance(table, dict) else None
            if unit is not None:
                out[kind] = unit
                break
    return out


def _bad_choice(choice: str, why: str) -> ConfigError:
    kinds = ", ".join(DISPLAY_KINDS)
    return ConfigError(f"--units = {choice!r}: {why}; allowed: 'si' or a comma list of "
                       f"kind=unit with kind in {kinds}, e.g. 'speed=rpm,unbalance=g*mm'")


def _parse_choice(choice: str) -> dict[str, str]:
    """``"speed=rpm,unbalance=g*mm"`` -> {kind: unit}, each unit checked against its kind."""
    out: dict[str, str] = {}
    for item in choice.split(","):
        if not item.strip():
            continue
        if "=" not in item:
            raise _bad_choice(choice, f"{item.strip()!r} is not kind=unit")
        kind, unit = (s.strip() for s in item.split("=", 1))
        if kind not in DISPLAY_KINDS:
            raise _bad_choice(choice, f"unknown kind {kind!r}")
        if kind in out:
            raise _bad_choice(choice, f"kind {kind!r} given twice")
        if kind == "grade":
            if _check_unit(unit, "grade") is None or not math.isclose(
                    registry().Quantity(1.0, unit).to("mm/s").magnitude, 1.0):
                raise _bad_choice(choice, f"grade = {unit!r}: the ISO 1940 grade G is always "
                                          "shown in mm/s")
        elif _check_unit(unit, kind) is None:
            raise _bad_choice(choice, f"{kind} = {unit!r} is not {KINDS[kind][1]} unit "
                                      f"(SI: {DISPLAY_KINDS[kind]})")
        out[kind] = unit
    if not out:
        raise _bad_choice(choice, "no kind=unit given")
    return out


@dataclass(frozen=True)
class DisplayUnits:
    """The unit each kind of quantity is shown in (terminal text, figures).

    Attributes
    ----------
    units : dict
        Kind -> pint unit string, for every kind of :data:`DISPLAY_KINDS`.
    written : dict
        Kind -> the unit the configuration wrote (the kinds it wrote a unit for).
    """

    units: dict = field(default_factory=lambda: dict(DISPLAY_KINDS))
    written: dict = field(default_factory=dict)

    def _kind(self, kind: str) -> str:
        if kind not in self.units:
            raise ValueError(f"kind = {kind!r}: must be one of {', '.join(self.units)}")
        return kind

    def unit(self, kind: str) -> str:
        """The unit of ``kind`` (a pint unit string, e.g. ``"rpm"``).

        Parameters
        ----------
        kind : str
            speed, unbalance, length, mass, force, time or grade.

        Returns
        -------
        str
        """
        return self.units[self._kind(kind)]

    def factor(self, kind: str) -> float:
        """Display value per SI value of ``kind`` [display unit / SI unit] (linear: every
        display kind is a ratio scale).

        Parameters
        ----------
        kind : str
            speed, unbalance, length, mass, force, time or grade.

        Returns
        -------
        float
            E.g. 60 / (2 pi) for speed in rpm, 1000 for unbalance in g*m.
        """
        return _factor(self.unit(kind), kind)

    def to(self, value_si: float, kind: str) -> float:
        """``value_si`` in the SI unit of ``kind`` (speeds [rad/s], grades [mm/s]) converted to
        its display unit.

        Parameters
        ----------
        value_si : float
            The value [SI unit of ``kind``]; NaN stays NaN.
        kind : str
            speed, unbalance, length, mass, force, time or grade.

        Returns
        -------
        float
            The value [display unit].
        """
        return float(value_si) * self.factor(kind)

    def fmt(self, value_si: float, kind: str, digits: int = 4) -> str:
        """``value_si`` [SI unit of ``kind``] as text in its display unit, e.g. ``"4000 rpm"``.

        Parameters
        ----------
        value_si : float
            The value [SI unit of ``kind``].
        kind : str
            speed, unbalance, length, mass, force, time or grade.
        digits : int
            Significant digits.

        Returns
        -------
        str
            ``"<value> <unit>"`` (``"nan <unit>"`` for NaN, ``"- <unit>"`` for None).
        """
        if value_si is None:
            return f"- {self.unit(kind)}"
        return f"{number_text(self.to(value_si, kind), digits)} {self.unit(kind)}"


def number_text(x: float, digits: int = 4) -> str:
    """``x`` with ``digits`` significant digits, without an exponent between 1e-4 and 1e7
    (``11000``, not ``1.1e+04``; ``0.00012``); outside that range, or NaN and inf, as ``g``.

    Parameters
    ----------
    x : float
        The number [any unit].
    digits : int
        Significant digits (>= 1).
    """
    x = float(x)
    if not math.isfinite(x) or x == 0.0 or not 1e-4 <= abs(x) < 1e7:
        return f"{x:.{digits}g}"
    x = float(f"{x:.{digits}g}")                 # round to the digits first
    d = max(0, digits - 1 - math.floor(math.log10(abs(x))))
    text = f"{x:.{d}f}"
    return text.rstrip("0").rstrip(".") if "." in text else text


def display_units(cfg: Config | dict | None, choice: str | None = None) -> DisplayUnits:
    """The display units of a configuration: as written, or as ``choice`` says.

    Parameters
    ----------
    cfg : Config or dict or None
        The configuration (its :attr:`Config.raw`, the keys as written after ``--set``), or
        such a raw dict; None: no configuration (SI, or ``choice``).
    choice : str, optional
        ``None`` (the units written in ``cfg``; SI for the kinds it gives no unit for),
        ``"si"`` (every kind in SI), or a comma list ``"speed=rpm,unbalance=g*mm"`` (these
        kinds in these units, the others as written).

    Returns
    -------
    DisplayUnits

    Raises
    ------
    ConfigError
        A bad ``choice``: one line naming ``--units``, the value and what is allowed.
    """
    raw = cfg if isinstance(cfg, dict) or cfg is None else getattr(cfg, "raw", None)
    written = _written_units(raw) if isinstance(raw, dict) else {}
    if choice is not None and not isinstance(choice, str):
        raise _bad_choice(str(choice), "expected a string")
    units = dict(DISPLAY_KINDS)
    if choice is None:
        units.update(written)
    elif choice.strip().lower() != "si":
        units.update(written)
        units.update(_parse_choice(choice))
    return DisplayUnits(units=units, written=written)


#: A refusal's one-line message: ``<section>.<key> = <value>: <what is allowed>``.
_REFUSAL = re.compile(r"^([a-z_]+\.[a-z_]+) = ([^:]+): (.*)$", re.S)


@functools.lru_cache(maxsize=1)
def _kind_of_key() -> dict[str, str]:
    """Config key -> its display kind (the first kind that lists it)."""
    out: dict[str, str] = {}
    for kind in DISPLAY_KINDS:
        if kind != "grade":
            for path in _keys_of_kind(kind):
                out.setdefault(path, kind)
    return out


def as_written(message: str, raw: dict | None) -> str:
    """A refusal's one-line message with the refused value as the configuration wrote it.

    The models refuse values in SI (``profile.initial_speed = 3.14159: must be >= ... 19.06
    rad/s``). When ``raw`` (:attr:`Config.raw`, the keys as written after ``--set``) wrote that
    key as a string with a unit, and the refused number is that string in SI, the message
    shows the written value with its SI value in brackets, and every "<number> <SI unit>" of
    the key's kind in the rest of the message also in the written unit:
    ``profile.initial_speed = 30 rpm (3.142 rad/s): must be >= ... 19.06 rad/s (182 rpm)``.
    Any other message is returned unchanged.

    Parameters
    ----------
    message : str
        The one-line message (``<section>.<key> = <value>: <allowed>``).
    raw : dict or None
        The configuration as written; None leaves the message as it is.

    Returns
    -------
    str
    """
    from .units import parse_quantity

    m = _REFUSAL.match(message)
    if m is None or not isinstance(raw, dict):
        return message
    path, value, allowed = m.groups()
    kind = _kind_of_key().get(path)
    section, key = path.split(".", 1)
    table = raw.get(section)
    written = table.get(key) if isinstance(table, dict) else None
    unit = written_unit(written, kind) if kind is not None and isinstance(written, str) else None
    if unit is None:
        return message
    try:
        v = float(value)
        same = math.isclose(parse_quantity(written, kind, path), v, rel_tol=1e-9, abs_tol=0.0)
    except (ValueError, ConfigError):
        return message
    if not same:
        return message
    si, f = DISPLAY_KINDS[kind], _factor(unit, kind)
    if unit.replace(" ", "") == si.replace(" ", ""):
        return f"{path} = {written.strip()}: {allowed}"      # written in SI: nothing to add
    also = re.sub(rf"({NUMBER}) {re.escape(si)}(?![\w*/^])",
                  lambda x: f"{x.group(0)} ({number_text(float(x.group(1)) * f)} {unit})",
                  allowed)
    return f"{path} = {written.strip()} ({v:.6g} {si}): {also}"
