"""Every parameter of a configuration in SI, with the unit as key suffix (``autobalance show``)."""
from __future__ import annotations

import dataclasses
import inspect
from typing import Any

from ..models import MotorDrive, SpeedProfile
from .load import Config, _profile
from .schema import PROFILE_KINDS, SECTIONS, F
from .units import TWO_PI, _suffix


def _jsonable(v: Any) -> Any:
    if isinstance(v, (tuple, list)):
        return [_jsonable(x) for x in v]
    if hasattr(v, "tolist"):
        return v.tolist()
    return v


def _fields(obj, specs: dict[str, F], skip=()) -> dict:
    out = {}
    for f in dataclasses.fields(obj):
        if f.name in skip or f.name not in specs:
            continue
        spec = specs[f.name]
        key = f.name if spec.kind in ("int", "text") else f.name + _suffix(spec.kind)
        if spec.shape == "pairs":
            key = f.name + "".join(_suffix(k) for k in spec.pair_kinds)
        out[key] = _jsonable(getattr(obj, f.name))
    return out


def _describe_profile(config: Config) -> dict:
    spin = config.spin
    kind = config.profile_kind
    prof: dict[str, Any] = {"kind": kind}
    specs = PROFILE_KINDS.get(kind, {})
    if isinstance(spin, MotorDrive):
        prof.update(_fields(spin, specs))
    else:
        given = _profile(config.raw["profile"])[2]
        if kind in ("std", "tsr"):
            ctor = SpeedProfile.standard_runup if kind == "std" else SpeedProfile.tsr
            for name, par in inspect.signature(ctor).parameters.items():
                if par.default is not inspect.Parameter.empty and name in specs:
                    given.setdefault(name, par.default)
        for name, spec in specs.items():
            if name in given and given[name] is not None:
                prof[name + _suffix(spec.kind)] = _jsonable(given[name])
        prof.update({"times_s": list(spin.times), "speeds_rad_s": list(spin.speeds)})
    prof.update({"nominal_speed_rad_s": spin.nominal_speed,
                 "checkpoints_s": list(spin.checkpoints)})
    return prof


def describe(config: Config) -> dict:
    """Every parameter of a configuration in SI, with the unit as key suffix.

    Parameters
    ----------
    config : Config
        A validated configuration (:func:`load_config`, :func:`from_dict`, :func:`from_models`).

    Returns
    -------
    dict
        ``{"name", "description", "source", "rotor": {"mass_kg": 37.0, ...}, "suspension":
        {"kx_N_m": 20000.0, ...}, "balancer", "gravity", "profile", "initial", "options",
        "derived": {...}, "sources": {"rotor.mass": "000 p.3: ...", ...}}``. Speeds are
        [rad/s], angles [rad]; ``sources`` holds the trailing comment of each TOML key.
    """
    s = config.system
    initial = _fields(config.initial, SECTIONS["initial"])
    initial["ball_angles_rad"] = _jsonable(config.initial.angles_for(s.balancer))
    initial["ball_speeds_rad_s"] = _jsonable(config.initial.speeds_for(s.balancer))
    wx, wy = s.natural_frequencies
    liquid = {} if s.liquid is None else {"liquid": _fields(s.liquid, SECTIONS["liquid"])}
    derived_liquid = {} if s.liquid is None else {"liquid_chambers": s.liquid.n_chambers,
                                                  "liquid_mass_kg": s.liquid.mass,
                                                  "liquid_capacity_kg_m": s.liquid.capacity}
    return {
        "name": s.name, "description": s.description, "source": config.source,
        "rotor": _fields(s.rotor, SECTIONS["rotor"]),
        "suspension": _fields(s.suspension, SECTIONS["suspension"]),
        "balancer": _fields(s.balancer, SECTIONS["balancer"]),
        "gravity": _fields(s.gravity, SECTIONS["gravity"]),
        **liquid,
        "profile": _describe_profile(config),
        "initial": initial,
        "options": _fields(config.options, SECTIONS["options"]),
        "derived": {
            "total_mass_kg": s.total_mass,
            # the eccentricity of every grade: ISO 1940 on the total mass M_t (rotor, balls
            # and liquid, System.total_mass; 004 sec. 4)
            "eccentricity_m": s.rotor.unbalance / s.total_mass,
            "eccentricity_definition": "e = U/M_t",
            "ball_capacity_kg_m": s.balancer.capacity,
            **derived_liquid,
            "natural_frequencies_rad_s": [wx, wy],
            "natural_frequencies_hz": [wx / TWO_PI, wy / TWO_PI],
        },
        "sources": dict(config.sources),
    }
