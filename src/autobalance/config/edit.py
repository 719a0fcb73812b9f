"""Configurations built and changed in Python.

:func:`from_models` makes a :class:`Config` of model dataclasses built in Python (a
:class:`~autobalance.models.System`, its spin, initial state and options).

:func:`replace_values` sets dotted paths (``"balancer.rolling_resistance"``,
``"profile.plateau"``, ``"initial.ball_angles"``) on a built Config and returns a new one.
Each value is validated and converted by the same schema as a file or ``--set`` (a number is
SI, a string carries units), and the frozen models are changed with :func:`dataclasses.replace`,
so their own checks run again and every error is the same one line naming the field, the
value and what is allowed. This is how a sweep builds its grid cells.

A built model no longer shows which keys were given and which took a default that depends on
others: a balancer's ``stiction`` defaults to its ``rolling_resistance``, per-ball values given
as one number are expanded to ``n_balls`` values, and a std/tsr profile is stored as its speed
table. :attr:`Config.raw` keeps the keys as given; it is used where it still builds the same
model. Otherwise (a Config whose models were replaced in Python) the keys are read off the
model: per-ball values that are all equal count as one number, a stiction equal to the
rolling resistance as left out, and the profile is a ``table`` (or ``motor``) profile.
"""
from __future__ import annotations

import dataclasses
from collections.abc import Iterable, Mapping
from typing import Any

from ..models import (BallBalancer, InitialState, MotorDrive, ParameterError, SimOptions,
                      SpeedProfile, System)
from .load import Config, build_profile, profile_params
from .overrides import split_path
from .schema import _MODELS, PROFILE_KINDS, SECTION_MODELS, SECTIONS, _build, _section, check_value
from .units import ConfigError

_PER_BALL = ("ball_mass", "damping", "rolling_resistance", "stiction")
_UNSET = object()  # a key set to None: back to the model's default


def _plain(v: Any) -> Any:
    """A model value as in a TOML table (tuples -> lists)."""
    return [_plain(x) for x in v] if isinstance(v, tuple) else v


def _table(obj, skip: tuple = ()) -> dict:
    """The fields of a model as the keys of its TOML table (SI; None left out)."""
    return {f.name: _plain(getattr(obj, f.name)) for f in dataclasses.fields(obj)
            if f.name not in skip and getattr(obj, f.name) is not None}


def _balancer_table(b: BallBalancer) -> dict:
    """The keys of a built balancer as a file would give them (see the module notes)."""
    t = _table(b)
    for k in _PER_BALL:
        if not t[k]:
            del t[k]                       # a balancer without balls
        elif len(set(t[k])) == 1:
            t[k] = t[k][0]
    if "stiction" in t and t["stiction"] == t.get("rolling_resistance"):
        del t["stiction"]
    return t


def _spin_table(spin: SpeedProfile | MotorDrive) -> dict:
    """A built spin as a ``[profile]`` table of kind ``motor`` or ``table`` (SI)."""
    if isinstance(spin, MotorDrive):
        return {"kind": "motor", **_table(spin)}
    t = {"kind": "table", **_table(spin, skip=("name",))}
    if t["nominal_speed"] == max(spin.speeds):
        del t["nominal_speed"]
    if tuple(spin.checkpoints) == (spin.times[-1],):
        del t["checkpoints"]
    return t


def from_models(system: System, spin: SpeedProfile | MotorDrive | dict,
                initial: InitialState | None = None, options: SimOptions | None = None, *,
                source: str = "<python>") -> Config:
    """A :class:`Config` of models built in Python, e.g. to sweep them.

    Parameters
    ----------
    system : System
        Rotor, suspension, balancer and gravity.
    spin : SpeedProfile, MotorDrive or dict
        The spin; or a ``[profile]`` table such as ``{"kind": "tsr", "nominal": "167 Hz",
        ...}`` (validated like a file), whose keys can then be swept (``profile.plateau``).
        A SpeedProfile built in Python is a speed table: its ``times``, ``speeds``,
        ``nominal_speed`` and ``checkpoints`` can be changed, not the arguments it was made of.
    initial : InitialState, optional
        Default: balls equispaced from pi/4, at rest; rotor at rest.
    options : SimOptions, optional
        Default: ``SimOptions()``.
    source : str
        Label stored in :attr:`Config.source`.

    Returns
    -------
    Config
        With :attr:`Config.raw` made from the models (SI numbers), so that
        :func:`from_dict` of it builds the same models.

    Raises
    ------
    ConfigError
        A wrong type, or initial ball angles or speeds that do not fit the balancer (one line).
    """
    if not isinstance(system, System):
        raise ConfigError(f"system = {system!r}: expected an autobalance.System")
    if isinstance(spin, dict):
        kind, params = profile_params(spin)
        spin, prof = build_profile(kind, params), dict(spin)
    elif isinstance(spin, (SpeedProfile, MotorDrive)):
        prof = _spin_table(spin)
    else:
        raise ConfigError(f"profile = {spin!r}: expected a SpeedProfile, a MotorDrive or a "
                          "[profile] table (dict)")
    initial = InitialState() if initial is None else initial
    options = SimOptions() if options is None else options
    for name, obj, cls in (("initial", initial, InitialState), ("options", options, SimOptions)):
        if not isinstance(obj, cls):
            raise ConfigError(f"{name} = {obj!r}: expected an autobalance.{cls.__name__}")
    _build("initial", initial.angles_for, system.balancer)
    _build("initial", initial.speeds_for, system.balancer)
    raw = {k: getattr(system, k) for k in ("name", "description") if getattr(system, k)}
    raw.update({s: _table(getattr(system, s)) for s in ("rotor", "suspension", "gravity")})
    if system.liquid is not None:
        raw["liquid"] = _table(system.liquid)
    raw.update(balancer=_balancer_table(system.balancer), profile=prof,
               initial=_table(initial), options=_table(options))
    return Config(system, spin, initial, options, raw=raw, source=source,
                  profile_kind=prof["kind"])


# -- the keys as given -------------------------------------------------------------------------
def _raw(config: Config) -> dict:
    return config.raw if isinstance(config.raw, dict) else {}


def _given_balancer(config: Config) -> tuple[dict, dict]:
    """(table as written, its keys in SI) of the balancer: Config.raw's if it builds the same
    balancer, else read off the model."""
    b = config.system.balancer
    table = _raw(config).get("balancer")
    try:
        if table is None and b == BallBalancer(0):
            return {}, {}
        if isinstance(table, dict):
            p = _section("balancer", table, SECTIONS["balancer"], _MODELS["balancer"])
            if BallBalancer(**p) == b:
                return table, p
    except (ConfigError, ParameterError):
        pass
    t = _balancer_table(b)
    return t, t


def _given_profile(config: Config) -> tuple[str, dict, dict, bool]:
    """(kind, table as written without kind, its keys in SI, whether from Config.raw)."""
    table = _raw(config).get("profile")
    try:
        kind, p = profile_params(table)
        if kind == config.profile_kind and build_profile(kind, p) == config.spin:
            return kind, {k: v for k, v in table.items() if k != "kind"}, p, True
    except (ConfigError, ParameterError):
        pass
    t = _spin_table(config.spin)
    kind = t.pop("kind")
    return kind, t, t, False


# -- replace_values ----------------------------------------------------------------------------
def _check_keys(section: str, specs: dict, values: dict) -> dict:
    """Values of one section -> SI (in the order of its keys, as a file is checked)."""
    out = {}
    for key, spec in specs.items():
        if key not in values:
            continue
        if values[key] is None:
            if spec.required:
                raise ConfigError(f"{section}.{key}: missing; required {spec.need}")
            out[key] = _UNSET
        else:
            out[key] = check_value(f"{section}.{key}", spec, values[key])
    return out


def _default(cls, name: str) -> Any:
    f = next(f for f in dataclasses.fields(cls) if f.name == name)
    return f.default_factory() if f.default_factory is not dataclasses.MISSING else f.default


def _replace_model(config: Config, section: str, si: dict):
    """The section's model with the SI values; a balancer's per-ball values and stiction that
    follow n_balls and rolling_resistance by default follow them here too."""
    model = (config.initial if section == "initial" else config.options if section == "options"
             else getattr(config.system, section))
    if not si:
        return model, None
    cls = SECTION_MODELS[section]
    if model is None:                      # a [liquid] section added by these values
        si = {k: v for k, v in si.items() if v is not _UNSET}
        for key, spec in SECTIONS[section].items():
            if spec.required and key not in si:
                raise ConfigError(f"{section}.{key}: missing; required {spec.need} (the system "
                                  f"has no [{section}] section yet)")
        return _build(section, cls, **si), None
    table = None
    if section == "balancer":
        derived = set()
        if "n_balls" in si and si["n_balls"] != model.n_balls:
            derived.update(_PER_BALL)
        if "rolling_resistance" in si:
            derived.add("stiction")
        table, given = _given_balancer(config)
        si = {**{k: given.get(k, _UNSET) for k in derived - set(si)}, **si}
    si = {k: _default(cls, k) if v is _UNSET else v for k, v in si.items()}
    return _build(section, dataclasses.replace, model, **si), table


def _replace_profile(config: Config, values: dict):
    """(spin, kind, new [profile] table) with the profile values applied."""
    kind0, table, given, from_raw = _given_profile(config)
    kind = values.get("kind", kind0)
    if kind not in PROFILE_KINDS:
        raise ConfigError(f"profile.kind = {kind!r}: unknown profile kind; allowed: "
                          f"{', '.join(PROFILE_KINDS)}")
    specs = PROFILE_KINDS[kind]
    for key in values:
        if key != "kind" and key not in specs:
            how = "" if from_raw else " (a profile built in Python is a speed table)"
            raise ConfigError(f"profile.{key}: unknown key for kind {kind!r}{how}; allowed: "
                              f"{', '.join(specs)}")
    given = {k: v for k, v in given.items() if k in specs}
    si = _check_keys("profile", specs, {k: v for k, v in values.items() if k != "kind"})
    params = {k: v for k, v in {**given, **si}.items() if v is not _UNSET}
    for key, spec in specs.items():
        if spec.required and key not in params:
            raise ConfigError(f"profile.{key}: missing; required {spec.need}")
    if kind == kind0 == "table" and not from_raw:   # keep the name of a Python-built table
        defaults = {"nominal_speed": None, "checkpoints": ()}
        spin = _build("profile", dataclasses.replace, config.spin, **{**defaults, **params})
    else:
        spin = build_profile(kind, params)
    table = {"kind": kind, **{k: v for k, v in table.items() if k in specs}}
    return spin, kind, _written(table, values)


def _written(table: dict | None, values: dict) -> dict:
    """A copy of a TOML table with the values as given (None: the key removed)."""
    out = dict(table) if isinstance(table, dict) else {}
    for key, value in values.items():
        if value is None:
            out.pop(key, None)
        else:
            out[key] = value
    return out


def _group(values) -> dict:
    """{section: {key: value}} of path -> value items ("" holds name and description)."""
    items = values.items() if isinstance(values, Mapping) else values
    out: dict[str, dict] = {}
    for path, value in items:
        section, key = split_path(str(path))
        out.setdefault(section, {})[key] = value
    return out


def replace_values(config: Config,
                   values: Mapping[str, Any] | Iterable[tuple[str, Any]]) -> Config:
    """A new Config with dotted paths set to values, validated like ``--set``.

    Parameters
    ----------
    config : Config
        The configuration to start from (:func:`load_config`, :func:`from_dict`,
        :func:`from_models`); it is not changed.
    values : mapping or iterable of (path, value)
        ``{"balancer.rolling_resistance": 0.002, "rotor.unbalance": "0.2 g*m",
        "profile.plateau": "100 Hz", "initial.ball_angles": ["45 deg", "135 deg"],
        "options.rtol": 1e-7}``. A number is SI, a string carries units (as in a file);
        ``None`` puts a key back to its default. ``profile.kind`` switches the profile kind
        (keeping the keys the new kind accepts, as ``--set``); ``name`` and ``description``
        rename the system.

    Returns
    -------
    Config
        The models changed by :func:`dataclasses.replace` (their checks run again);
        :attr:`Config.raw` holds the values as given, :attr:`Config.sources` marks them.

    Raises
    ------
    ConfigError
        One line naming the field, the value and what is allowed: an unknown path, a value of
        the wrong kind or units, or a value a model rejects (checked in the order
        :func:`from_dict` checks a file).
    """
    groups = _group(values)
    top = groups.pop("", {})
    for key, value in top.items():
        if not isinstance(value, str):
            raise ConfigError(f"{key} = {value!r}: expected a string")
    si = {s: _check_keys(s, SECTIONS[s], groups[s]) for s in SECTIONS if s in groups}
    raw = {**_raw(config), **top}
    models = {}
    for section in ("rotor", "suspension", "balancer", "gravity", "liquid", "profile",
                    "initial", "options"):
        if section == "profile":
            spin, kind = config.spin, config.profile_kind
            if "profile" in groups:
                spin, kind, raw["profile"] = _replace_profile(config, groups["profile"])
            continue
        models[section], table = _replace_model(config, section, si.get(section))
        if section in groups:
            raw[section] = _written(raw.get(section) if table is None else table, groups[section])
        if section == "initial":
            _build("initial", models["initial"].angles_for, models["balancer"])
            _build("initial", models["initial"].speeds_for, models["balancer"])
    system = dataclasses.replace(config.system, **top, **{s: models[s] for s in
                                 ("rotor", "suspension", "balancer", "gravity", "liquid")})
    sources = {**config.sources, **{f"{s}.{k}" if s else k: f"set {v!r}"
                                    for s, g in {"": top, **groups}.items() for k, v in g.items()}}
    return dataclasses.replace(config, system=system, spin=spin, initial=models["initial"],
                               options=models["options"], raw=raw, sources=sources,
                               profile_kind=kind)
