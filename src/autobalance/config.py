"""TOML configuration files and presets -> the :mod:`autobalance.models` dataclasses.

Units live only at this boundary. Every physical value in a TOML file (or a ``--set`` override)
is either a bare number, meaning SI, or a string with units that :mod:`pint` parses
(``"20 N/mm"``, ``"0.025 kg*m"``, ``"3000 g*cm"``, ``"61 deg"``, ``"1000 rpm"``, ``"167 Hz"``).
Rotational speeds in ``Hz`` are cycles per second and become ``2*pi*f`` [rad/s]; ``rpm``
becomes ``2*pi/60`` [rad/s]; ``rad/s`` and ``1/s`` stay as they are. Radians are dimensionless.

Every problem raises :class:`ConfigError` with one line naming the dotted field, the value and
what is allowed, e.g. ``suspension.kx = '5 kg': expected a stiffness [N/m], e.g. '20 N/mm'``.

File layout (sections and their keys: :data:`SECTIONS` and :data:`PROFILE_KINDS`)::

    name = "..."            description = "..."
    [rotor]       mass, unbalance, polar_inertia, spin_damping, unbalance_schedule
    [suspension]  kx, ky, cx, cy, dry_friction_*, base_*
    [balancer]    n_balls, ball_mass, race_radius, ball_radius, element, damping, ...
    [gravity]     g, direction
    [profile]     kind = constant | ramp | table | std | tsr | motor, and the kind's keys
    [initial]     ball_angles, ball_speeds, x, y, vx, vy, steady_state
    [options]     friction_law, v_sat, normal_force, rtol, atol_scale, max_step, save_dt, max_steps

Keys left out take the defaults of the model dataclasses.
"""
from __future__ import annotations

import copy
import dataclasses
import importlib.resources
import inspect
import math
import tomllib
from dataclasses import dataclass, field
from functools import partial
from pathlib import Path
from typing import Annotated, Any

import pint
from pydantic import BeforeValidator, ConfigDict, ValidationError, create_model
from pydantic_core import PydanticCustomError

from .models import (FRICTION_LAWS, INERTIA_FACTOR, NORMAL_FORCES, BallBalancer, Gravity,
                     InitialState, MotorDrive, ParameterError, Rotor, SimOptions, SpeedProfile,
                     Suspension, System)

__all__ = ["Config", "ConfigError", "PROFILE_KINDS", "SECTIONS", "apply_overrides", "describe",
           "from_dict", "list_presets", "load_config", "parse_quantity", "preset_path",
           "source_comments", "ureg"]

#: The one unit registry of the package (pint defaults; radian is dimensionless).
ureg = pint.UnitRegistry()

TWO_PI = 2.0 * math.pi


class ConfigError(ValueError):
    """Invalid configuration; the message is one line naming the field, value and what is allowed."""

    def __init__(self, message: str):
        super().__init__(" ".join(str(message).split()))


# -- physical kinds ---------------------------------------------------------------------------
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
    unit = KINDS[kind][0]
    if isinstance(value, bool):
        raise _Bad(_expect(kind))
    if isinstance(value, (int, float)):
        return float(value)
    if not isinstance(value, str) or not value.strip():
        raise _Bad(_expect(kind))
    try:
        q = ureg.Quantity(value.strip())
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
    """
    try:
        return _si(value, kind)
    except _Bad as e:
        raise ConfigError(f"{field} = {value!r}: {e}") from None


# -- field specifications ---------------------------------------------------------------------
@dataclass(frozen=True)
class F:
    """Specification of one TOML key: kind, shape and whether it is required."""

    kind: str  # a KINDS key, or "int", "text"
    shape: str = "scalar"  # scalar | per_ball (scalar or list) | list | pairs
    required: bool = False
    pair_kinds: tuple = ()
    choices: tuple = ()  # for text fields; the models check membership

    @property
    def need(self) -> str:
        if self.kind == "int":
            return "(an integer)"
        if self.kind == "bool":
            return "(true or false)"
        if self.kind == "text":
            return f"(one of {', '.join(self.choices)})" if self.choices else "(a string)"
        unit = UNIT_LABEL[self.kind] if self.shape != "pairs" else \
            ", ".join(UNIT_LABEL[k] for k in self.pair_kinds)
        return f"[{unit}]" + (" list" if self.shape == "list" else "")


SECTIONS: dict[str, dict[str, F]] = {
    "rotor": {
        "mass": F("mass", required=True), "unbalance": F("unbalance"),
        "polar_inertia": F("inertia"), "spin_damping": F("rot_damping"),
        "unbalance_schedule": F("pairs", "pairs", pair_kinds=("time", "unbalance")),
    },
    "suspension": {
        "kx": F("stiffness", required=True), "ky": F("stiffness", required=True),
        "cx": F("damping"), "cy": F("damping"), "dry_friction_force": F("force"),
        "dry_friction_angle": F("angle"), "dry_friction_velocity": F("velocity"),
        "base_amplitude_x": F("length"), "base_amplitude_y": F("length"),
        "base_frequency": F("speed"), "base_phase_x": F("angle"), "base_phase_y": F("angle"),
    },
    "balancer": {
        "n_balls": F("int", required=True), "ball_mass": F("mass", "per_ball"),
        "race_radius": F("length"), "ball_radius": F("length"), "element": F("text", choices=tuple(INERTIA_FACTOR)),
        "damping": F("rot_damping", "per_ball"), "rolling_resistance": F("ratio", "per_ball"),
        "stiction": F("ratio", "per_ball"), "eccentricity": F("length"),
        "eccentricity_angle": F("angle"), "restitution": F("ratio"),
        "contact_frequency": F("speed"),
    },
    "gravity": {"g": F("acceleration"), "direction": F("angle")},
    "initial": {
        "ball_angles": F("angle", "list"), "ball_speeds": F("speed", "list"),
        "x": F("length"), "y": F("length"), "vx": F("velocity"), "vy": F("velocity"),
        "steady_state": F("bool"),
    },
    "options": {
        "friction_law": F("text", choices=FRICTION_LAWS), "v_sat": F("speed"),
        "normal_force": F("text", choices=NORMAL_FORCES),
        "rtol": F("ratio"), "atol_scale": F("ratio"), "max_step": F("time"),
        "save_dt": F("time"), "max_steps": F("int"), "exact_holds": F("bool"),
    },
}

# nominal is required in a file: without it a std/tsr profile would silently run at 004's
# 167 Hz (the Python constructors keep that default for callers who mean 004)
_STD = {"nominal": F("speed", required=True), "duration": F("time"), "runup_fraction": F("ratio"),
        "runup_time": F("time")}
#: Keys of each ``[profile]`` kind (besides ``kind``).
PROFILE_KINDS: dict[str, dict[str, F]] = {
    "constant": {"speed": F("speed", required=True), "duration": F("time", required=True)},
    "ramp": {"start_speed": F("speed", required=True), "end_speed": F("speed", required=True),
             "ramp_time": F("time", required=True), "duration": F("time", required=True)},
    "table": {"times": F("time", "list", required=True), "speeds": F("speed", "list", required=True),
              "nominal_speed": F("speed"), "checkpoints": F("time", "list")},
    "std": dict(_STD),
    "tsr": {**_STD, "plateau": F("speed"), "down_time": F("time"), "plateau_time": F("time"),
            "up_time": F("time")},
    "motor": {"law": F("text", required=True, choices=MotorDrive.LAWS), "torque": F("torque", required=True),
              "final_speed": F("speed", required=True), "duration": F("time", required=True),
              "hold_fraction": F("ratio"), "initial_speed": F("speed")},
}
TOP_LEVEL = ("name", "description", "rotor", "suspension", "balancer", "gravity", "profile",
             "initial", "options")
REQUIRED_SECTIONS = ("rotor", "suspension", "profile")


def _fail(msg: str, value: Any, sub: str = ""):
    return PydanticCustomError("autobalance", "{msg}", {"msg": msg, "value": value, "sub": sub})


def _one(spec: F, value: Any, sub: str = "") -> Any:
    if spec.kind == "int":
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise _fail("expected an integer", value, sub)
        if isinstance(value, str):
            try:
                return int(value.strip())
            except ValueError:
                raise _fail("expected an integer", value, sub) from None
        return value  # the models check integrality and range
    if spec.kind == "bool":
        if not isinstance(value, bool):
            raise _fail("expected true or false", value, sub)
        return value
    if spec.kind == "text":
        if not isinstance(value, str):
            raise _fail("expected a string", value, sub)
        return value.strip()
    try:
        return _si(value, spec.kind)
    except _Bad as e:
        raise _fail(str(e), value, sub) from None


def _check(spec: F, value: Any) -> Any:
    """pydantic before-validator: TOML value -> SI float / int / str / tuple."""
    if spec.shape == "scalar":
        return _one(spec, value)
    if spec.shape == "per_ball" and not isinstance(value, list):
        return _one(spec, value)
    if spec.shape == "pairs":
        if not isinstance(value, list):
            raise _fail("expected a list of [time, unbalance] pairs, e.g. [['0 s', '0.025 kg*m']]",
                        value)
        out = []
        for i, pair in enumerate(value):
            if not isinstance(pair, list) or len(pair) != 2:
                raise _fail("expected a [time, unbalance] pair", pair, f"[{i}]")
            out.append(tuple(_one(F(k), v, f"[{i}][{j}]")
                             for j, (k, v) in enumerate(zip(spec.pair_kinds, pair))))
        return tuple(out)
    if not isinstance(value, list):
        raise _fail(f"expected a list; each {_expect(spec.kind)}", value)
    return tuple(_one(spec, v, f"[{i}]") for i, v in enumerate(value))


def _model(name: str, fields: dict[str, F]):
    defs = {k: (Annotated[Any, BeforeValidator(partial(_check, s))], ... if s.required else None)
            for k, s in fields.items()}
    return create_model(name, __config__=ConfigDict(extra="forbid"), **defs)


_MODELS = {name: _model(f"{name.title()}Section", f) for name, f in SECTIONS.items()}
_PROFILE_MODELS = {k: _model(f"{k.title()}Profile", f) for k, f in PROFILE_KINDS.items()}


def _section(section: str, data: Any, fields: dict[str, F], model, extra: str = "") -> dict:
    """Validate one TOML table with its pydantic model; return the given keys in SI."""
    if not isinstance(data, dict):
        raise ConfigError(f"{section} = {data!r}: expected a table [{section}]")
    try:
        parsed = model.model_validate(data)
    except ValidationError as exc:
        errs = exc.errors()
        # an unknown key first: it is often the misspelt name of the missing one
        err = next((e for e in errs if e["type"] == "extra_forbidden"), errs[0])
        path = ".".join([section, *map(str, err["loc"])])
        key = str(err["loc"][0]) if err["loc"] else ""
        if err["type"] == "extra_forbidden":
            raise ConfigError(f"{path}: unknown key{extra}; allowed: {', '.join(fields)}") from None
        if err["type"] == "missing":
            raise ConfigError(f"{path}: missing; required {fields[key].need}") from None
        ctx = err.get("ctx") or {}
        if err["type"] == "autobalance":
            raise ConfigError(f"{path}{ctx['sub']} = {ctx['value']!r}: {ctx['msg']}") from None
        raise ConfigError(f"{path} = {err.get('input')!r}: {err['msg']}") from None
    return {k: v for k, v in parsed.model_dump().items() if v is not None}


def _build(what: str, fn, *args, **kw):
    """Call a model constructor; ParameterError -> ConfigError with the same one-line text."""
    try:
        return fn(*args, **kw)
    except ParameterError as e:
        msg = str(e)
        if what == "profile" and msg.startswith("drive."):
            msg = "profile." + msg[len("drive."):]  # MotorDrive names its fields drive.*
        raise ConfigError(msg) from None


def _profile(data: Any) -> tuple[SpeedProfile | MotorDrive, str, dict]:
    if not isinstance(data, dict):
        raise ConfigError(f"profile = {data!r}: expected a table [profile]")
    kinds = ", ".join(PROFILE_KINDS)
    if "kind" not in data:
        raise ConfigError(f"profile.kind: missing; required, one of {kinds}")
    kind = data["kind"]
    if kind not in PROFILE_KINDS:
        raise ConfigError(f"profile.kind = {kind!r}: unknown profile kind; allowed: {kinds}")
    fields = PROFILE_KINDS[kind]
    rest = {k: v for k, v in data.items() if k != "kind"}
    p = _section("profile", rest, fields, _PROFILE_MODELS[kind], extra=f" for kind {kind!r}")
    if kind == "constant":
        spin = _build("profile", SpeedProfile.constant, p["speed"], p["duration"])
    elif kind == "ramp":
        spin = _build("profile", SpeedProfile.ramp, **p)
    elif kind == "table":
        spin = _build("profile", SpeedProfile, p["times"], p["speeds"],
                      nominal_speed=p.get("nominal_speed"), checkpoints=p.get("checkpoints", ()))
    elif kind == "std":
        spin = _build("profile", SpeedProfile.standard_runup, **p)
    elif kind == "tsr":
        spin = _build("profile", SpeedProfile.tsr, **p)
    else:
        spin = _build("profile", MotorDrive, **p)
    return spin, kind, p


# -- Config -----------------------------------------------------------------------------------
@dataclass(frozen=True)
class Config:
    """A validated configuration, ready for :func:`autobalance.simulate.simulate`.

    Attributes
    ----------
    system : System
        Rotor, suspension, balancer and gravity [SI].
    spin : SpeedProfile or MotorDrive
        Prescribed speed profile or motor drive.
    initial : InitialState
        Initial ball angles [rad] and rotor state [m, m/s].
    options : SimOptions
        Numerical options.
    raw : dict
        The merged TOML dict after overrides (values as written, with units).
    source : str
        Preset name or path of the TOML file.
    sources : dict
        Dotted key -> source comment of that key in the TOML file (``"--set"`` for overrides).
    profile_kind : str
        The ``[profile] kind`` the spin was built from.
    """

    system: System
    spin: SpeedProfile | MotorDrive
    initial: InitialState
    options: SimOptions
    raw: dict
    source: str
    sources: dict = field(default_factory=dict)
    profile_kind: str = ""

    @property
    def name(self) -> str:
        return self.system.name


def from_dict(raw: dict, source: str = "<dict>", sources: dict | None = None) -> Config:
    """Validate a TOML-like dict and build the model dataclasses.

    Parameters
    ----------
    raw : dict
        Parsed TOML (values as numbers in SI or strings with units).
    source : str
        Label stored in :attr:`Config.source`; its stem is the default ``name``.
    sources : dict, optional
        Dotted key -> source comment (see :func:`source_comments`).

    Raises
    ------
    ConfigError
        One line naming the first bad field.
    """
    if not isinstance(raw, dict):
        raise ConfigError(f"{source}: expected a TOML table at the top level")
    for key in raw:
        if key not in TOP_LEVEL:
            raise ConfigError(f"{key}: unknown key; allowed: {', '.join(TOP_LEVEL)}")
    for key in REQUIRED_SECTIONS:
        if key not in raw:
            need = "kind" if key == "profile" else ", ".join(
                k for k, s in SECTIONS[key].items() if s.required)
            raise ConfigError(f"{key}: missing; required section [{key}] with {need}")
    for key in ("name", "description"):
        if key in raw and not isinstance(raw[key], str):
            raise ConfigError(f"{key} = {raw[key]!r}: expected a string")
    p = {s: _section(s, raw[s], SECTIONS[s], _MODELS[s]) for s in SECTIONS if s in raw}
    rotor = _build("rotor", Rotor, **p["rotor"])
    suspension = _build("suspension", Suspension, **p["suspension"])
    balancer = _build("balancer", BallBalancer, **p["balancer"]) if "balancer" in p \
        else BallBalancer(0)
    gravity = _build("gravity", Gravity, **p.get("gravity", {}))
    spin, kind, _ = _profile(raw["profile"])
    initial = _build("initial", InitialState, **p.get("initial", {}))
    _build("initial", initial.angles_for, balancer)
    _build("initial", initial.speeds_for, balancer)
    options = _build("options", SimOptions, **p.get("options", {}))
    name = raw.get("name") or Path(str(source)).stem
    system = System(rotor, suspension, balancer, gravity, name=name,
                    description=raw.get("description", ""))
    return Config(system, spin, initial, options, raw=raw, source=str(source),
                  sources=dict(sources or {}), profile_kind=kind)


# -- presets, files and overrides -------------------------------------------------------------
def _preset_dir() -> Path:
    return Path(str(importlib.resources.files("autobalance") / "presets"))


def preset_path(name: str) -> Path:
    """Path of the preset ``name`` (file ``presets/<name>.toml`` in the package).

    Raises
    ------
    ConfigError
        If there is no such preset.
    """
    path = _preset_dir() / f"{name}.toml"
    if not path.is_file():
        names = ", ".join(p["name"] for p in list_presets())
        raise ConfigError(f"unknown preset {name!r}; available: {names} "
                          "(or give the path of a .toml file)")
    return path


def list_presets() -> list[dict]:
    """The presets shipped with the package: ``[{"name", "description", "path"}, ...]``."""
    out = []
    for path in sorted(_preset_dir().glob("*.toml")):
        try:
            desc = tomllib.loads(path.read_text(encoding="utf-8")).get("description", "")
        except (OSError, ValueError):
            desc = "(unreadable preset)"
        out.append({"name": path.stem, "description": desc, "path": str(path)})
    return out


def _comment(line: str) -> tuple[str, str] | None:
    """Split ``key = value  # comment`` into (code, comment); None without a comment."""
    quote = None
    i = 0
    while i < len(line):
        c = line[i]
        if quote:
            if c == "\\" and quote == '"':
                i += 1
            elif c == quote:
                quote = None
        elif c in "\"'":
            quote = c
        elif c == "#":
            return line[:i], line[i + 1:].strip()
        i += 1
    return None


def source_comments(text: str) -> dict[str, str]:
    """Trailing ``# comment`` of each ``key = value`` line of a TOML text, by dotted key.

    Only single-line values are annotated (the presets keep every value on one line).
    """
    out: dict[str, str] = {}
    section = ""
    for line in text.splitlines():
        split = _comment(line)
        code = (split[0] if split else line).strip()
        if code.startswith("[") and code.endswith("]"):
            section = code.strip("[]").strip()
            continue
        if split is None or not split[1] or "=" not in code:
            continue
        key = code.split("=", 1)[0].strip().strip("\"'")
        out[f"{section}.{key}" if section else key] = split[1]
    return out


def _read(source: str | Path) -> tuple[dict, str, dict]:
    """(raw dict, source label, source comments) of a preset name or a .toml path."""
    src = str(source)
    is_path = isinstance(source, Path) or src.endswith(".toml") or "/" in src or "\\" in src
    if not is_path and not (_preset_dir() / f"{src}.toml").is_file() and Path(src).is_file():
        is_path = True  # an existing file without .toml suffix
    path = Path(src) if is_path else preset_path(src)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as e:
        reason = e.strerror if isinstance(e, OSError) and e.strerror else str(e)
        raise ConfigError(f"cannot read config file {src!r}: {reason}") from None
    try:
        raw = tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"{src}: invalid TOML: {e}") from None
    return raw, (src if is_path else path.stem), source_comments(text)


def _parse_value(text: str) -> Any:
    """An override value: a TOML scalar/array, else a bare string such as ``100 Hz``."""
    text = text.strip()
    try:
        return tomllib.loads(f"v = {text}")["v"]
    except tomllib.TOMLDecodeError:
        pass
    if text.startswith("[") and text.endswith("]"):
        items = [t.strip() for t in text[1:-1].split(",") if t.strip()]
        return [_parse_value(t) for t in items]
    if len(text) >= 2 and text[0] == text[-1] and text[0] in "\"'":
        return text[1:-1]
    return text


def apply_overrides(raw: dict, overrides=()) -> dict:
    """Apply ``path=value`` overrides to a copy of a TOML dict.

    Parameters
    ----------
    raw : dict
        Parsed TOML (not modified).
    overrides : iterable of str
        ``"suspension.kx=25 N/mm"``, ``'rotor.unbalance="0.05 kg*m"'``,
        ``"initial.ball_angles=[0, 3.1]"``, ``"profile.kind=tsr"``. The value is read as a TOML
        scalar or array if it is one, else as a bare string (a number with units).

    Returns
    -------
    dict
        The merged dict.

    Notes
    -----
    Switching the profile kind (``profile.kind=NAME``; the CLI's ``--profile NAME``) keeps the
    ``[profile]`` keys that the new kind accepts and silently drops the others **if they came
    from the file or preset**; a key given with ``--set`` that the new kind does not accept is
    an error. The new kind's missing optional keys take the constructor defaults (std/tsr:
    004 values); its missing required keys (e.g. std/tsr ``nominal``) are reported missing.

    Raises
    ------
    ConfigError
        Malformed override or unknown path (one line).
    """
    out = copy.deepcopy(raw)
    base_kind = out.get("profile", {}).get("kind") if isinstance(out.get("profile"), dict) else None
    set_in_profile = set()
    profile_keys = {"kind"}.union(*PROFILE_KINDS.values())
    for item in overrides or ():
        if "=" not in item:
            raise ConfigError(f"--set {item!r}: expected path=value, e.g. suspension.kx='20 N/mm'")
        path, text = (s.strip() for s in item.split("=", 1))
        parts = path.split(".")
        value = _parse_value(text)
        if len(parts) == 1:
            if path not in ("name", "description"):
                raise ConfigError(f"--set {path}: unknown path; use section.key with a section "
                                  f"in {', '.join(TOP_LEVEL[2:])} (or name, description)")
            out[path] = value
            continue
        if len(parts) != 2 or parts[0] not in TOP_LEVEL[2:]:
            raise ConfigError(f"--set {path}: unknown path; sections: {', '.join(TOP_LEVEL[2:])}")
        section, key = parts
        allowed = sorted(profile_keys) if section == "profile" else list(SECTIONS[section])
        if key not in allowed:
            raise ConfigError(f"--set {path}: unknown key; allowed: {', '.join(allowed)}")
        if not isinstance(out.get(section, {}), dict):
            out[section] = {}
        out.setdefault(section, {})[key] = value
        if section == "profile":
            set_in_profile.add(key)
    prof = out.get("profile")
    if isinstance(prof, dict) and prof.get("kind") != base_kind and prof.get("kind") in PROFILE_KINDS:
        keep = set(PROFILE_KINDS[prof["kind"]]) | {"kind"} | set_in_profile
        out["profile"] = {k: v for k, v in prof.items() if k in keep}
    return out


def load_config(source: str | Path, overrides=()) -> Config:
    """Load a preset (by name) or a TOML file, apply overrides and validate.

    Parameters
    ----------
    source : str or Path
        Preset name (see :func:`list_presets`) or path of a ``.toml`` file.
    overrides : iterable of str
        ``path=value`` strings (see :func:`apply_overrides`).

    Returns
    -------
    Config

    Raises
    ------
    ConfigError
        Unknown preset, unreadable file, invalid TOML or any invalid value (one line).
    """
    raw, label, comments = _read(source)
    overrides = list(overrides or ())
    merged = apply_overrides(raw, overrides)
    for item in overrides:
        comments[item.split("=", 1)[0].strip()] = f"--set {item}"
    return from_dict(merged, source=label, sources=comments)


# -- describe ---------------------------------------------------------------------------------
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


def describe(config: Config) -> dict:
    """Every parameter of a configuration in SI, with the unit as key suffix.

    Returns
    -------
    dict
        ``{"name", "description", "source", "rotor": {"mass_kg": 37.0, ...}, "suspension":
        {"kx_N_m": 20000.0, ...}, "balancer", "gravity", "profile", "initial", "options",
        "derived": {...}, "sources": {"rotor.mass": "000 p.3: ...", ...}}``. Speeds are
        [rad/s], angles [rad]; ``sources`` holds the trailing comment of each TOML key.
    """
    s = config.system
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
    initial = _fields(config.initial, SECTIONS["initial"])
    initial["ball_angles_rad"] = _jsonable(config.initial.angles_for(s.balancer))
    initial["ball_speeds_rad_s"] = _jsonable(config.initial.speeds_for(s.balancer))
    wx, wy = s.natural_frequencies
    return {
        "name": s.name, "description": s.description, "source": config.source,
        "rotor": _fields(s.rotor, SECTIONS["rotor"]),
        "suspension": _fields(s.suspension, SECTIONS["suspension"]),
        "balancer": _fields(s.balancer, SECTIONS["balancer"]),
        "gravity": _fields(s.gravity, SECTIONS["gravity"]),
        "profile": prof,
        "initial": initial,
        "options": _fields(config.options, SECTIONS["options"]),
        "derived": {
            "total_mass_kg": s.total_mass,
            "eccentricity_m": s.rotor.eccentricity,
            "ball_capacity_kg_m": s.balancer.capacity,
            "natural_frequencies_rad_s": [wx, wy],
            "natural_frequencies_hz": [wx / TWO_PI, wy / TWO_PI],
        },
        "sources": dict(config.sources),
    }
