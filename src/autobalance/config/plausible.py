"""Bare numbers that look like a forgotten unit: a configuration value written without a unit
is SI (:mod:`.units`), so ``race_radius = 15`` meant as 15 mm is a race of 15 m. Such a machine
is legal and is not refused; :func:`bare_number_warnings` names each bare number beyond the
plausible range of its kind (:data:`PLAUSIBLE_SI`), one line each, for ``show`` and the studies
(:func:`autobalance.physics.sanity.config_warnings`).

Only values written as numbers (int or float in :attr:`Config.raw`, the keys as written after
``--set``) are checked; a string carries its unit and is taken as meant.
"""
from __future__ import annotations

from typing import Any

from .schema import PROFILE_KINDS, SECTIONS, F

__all__ = ["PLAUSIBLE_SI", "bare_number_warnings"]

#: kind -> (largest plausible SI value, its unit, a likely meant unit): a bare number above it
#: is more likely a value in a smaller unit than SI. A race of 2 m is a large washer drum's
#: diameter; 1e5 rad/s is 955 000 rpm, beyond any balanced rotor; 10 t is a large turbine
#: rotor; an unbalance of 10 kg*m is 1 t at 10 mm; 1 m^3 of liquid fills no balance ring.
PLAUSIBLE_SI: dict[str, tuple[float, str, str]] = {
    "length": (2.0, "m", "mm"),
    "speed": (1e5, "rad/s", "rpm"),
    "mass": (1e4, "kg", "g"),
    "unbalance": (10.0, "kg*m", "g*mm"),
    "volume": (1.0, "m^3", "ml"),
}


def _bare(value: Any) -> bool:
    """A number as written (int or float, not a bool or a string with its unit)."""
    return isinstance(value, (int, float)) and not isinstance(value, bool)


def _items(spec: F, value: Any) -> list[tuple[str, str, Any]]:
    """(index suffix, kind, value) of every number of one key's value: a scalar, the items
    of a list (per ball, per chamber, list keys) or the items of [time, unbalance] pairs."""
    if spec.shape == "pairs":
        out = []
        if isinstance(value, (list, tuple)):
            for i, pair in enumerate(value):
                if isinstance(pair, (list, tuple)) and len(pair) == len(spec.pair_kinds):
                    out += [(f"[{i}][{j}]", k, v) for j, (k, v) in
                            enumerate(zip(spec.pair_kinds, pair))]
        return out
    if isinstance(value, (list, tuple)):
        return [(f"[{i}]", spec.kind, v) for i, v in enumerate(value)]
    return [("", spec.kind, value)]


def _specs(raw: dict) -> list[tuple[str, dict, dict]]:
    """(section, its specs, its raw table) of every section of ``raw`` the schema knows; the
    profile's keys are those of its kind."""
    out = []
    for section, specs in SECTIONS.items():
        if isinstance(raw.get(section), dict):
            out.append((section, specs, raw[section]))
    prof = raw.get("profile")
    if isinstance(prof, dict) and isinstance(prof.get("kind"), str):
        out.append(("profile", PROFILE_KINDS.get(prof["kind"].strip(), {}), prof))
    return out


def bare_number_warnings(raw: dict) -> list[str]:
    """One line per value written as a bare number (SI) beyond the plausible range of its kind
    (:data:`PLAUSIBLE_SI`), e.g. ``balancer.race_radius = 15``: "a length of 15 m".

    Parameters
    ----------
    raw : dict
        The configuration as written (:attr:`autobalance.config.Config.raw`, after ``--set``).

    Returns
    -------
    list of str
        The warnings (empty when every bare number is plausible).
    """
    out = []
    if not isinstance(raw, dict):
        return out
    for section, specs, table in _specs(raw):
        for key, value in table.items():
            spec = specs.get(key)
            if spec is None:
                continue
            for sub, kind, v in _items(spec, value):
                if kind not in PLAUSIBLE_SI or not _bare(v):
                    continue
                top, unit, meant = PLAUSIBLE_SI[kind]
                if abs(float(v)) > top:
                    out.append(f"{section}.{key}{sub} = {v!r} has no unit, so it is SI: "
                               f"{float(v):g} {unit}, above the plausible {top:g} {unit}; a "
                               f"forgotten unit? (write e.g. '{v!r} {meant}')")
    return out
