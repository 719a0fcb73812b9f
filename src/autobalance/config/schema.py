"""The keys of a configuration: one :class:`F` (kind, shape, required) per key and section.

The sections ``[rotor]``, ``[suspension]``, ``[balancer]``, ``[gravity]``, ``[initial]`` and
``[options]`` have one key per field of their model dataclass, in its order; a key is required
when the field has no default. Only the physical kind of each field is written here. The
``[profile]`` kinds are constructor arguments (``table`` and ``motor`` are dataclass fields).
Each section is validated by a pydantic model built from its specs (unknown keys forbidden).
"""
from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from functools import partial
from typing import Annotated, Any

from pydantic import BeforeValidator, ConfigDict, ValidationError, create_model
from pydantic_core import PydanticCustomError

from ..models import (AXES, CONTACT_MODELS, FRICTION_LAWS, INERTIA_FACTOR, NORMAL_FORCES, BallBalancer, Gravity,
                      InitialState, LiquidDevice, MotorDrive, ParameterError, Rotor, SimOptions, SpeedProfile,
                      Suspension)
from .units import UNIT_LABEL, ConfigError, _Bad, _expect, _si


@dataclass(frozen=True)
class F:
    """Specification of one TOML key: kind, shape and whether it is required."""

    kind: str  # a KINDS key, or "int", "text", "bool"
    shape: str = "scalar"  # scalar | per_ball, per_chamber (scalar or list) | list | pairs
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


def _fields_of(cls, skip: tuple = (), **specs: F) -> dict[str, F]:
    """The keys of a section: every field of the dataclass ``cls`` (but ``skip``) in its order,
    with its spec; required when the field has no default. A field without a spec, or a spec
    without a field, is a programming error caught at import."""
    out = {}
    for f in dataclasses.fields(cls):
        if f.name in skip:
            continue
        if f.name not in specs:
            raise TypeError(f"config schema: {cls.__name__}.{f.name} has no spec")
        required = f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING
        out[f.name] = dataclasses.replace(specs.pop(f.name), required=required)
    if specs:
        raise TypeError(f"config schema: {cls.__name__} has no field {sorted(specs)}")
    return out


#: The model dataclass of each section.
SECTION_MODELS = {"rotor": Rotor, "suspension": Suspension, "balancer": BallBalancer,
                  "gravity": Gravity, "liquid": LiquidDevice, "initial": InitialState,
                  "options": SimOptions}

SECTIONS: dict[str, dict[str, F]] = {
    "rotor": _fields_of(
        Rotor, mass=F("mass"), unbalance=F("unbalance"), polar_inertia=F("inertia"),
        spin_damping=F("rot_damping"),
        unbalance_schedule=F("pairs", "pairs", pair_kinds=("time", "unbalance"))),
    "suspension": _fields_of(
        Suspension, kx=F("stiffness"), ky=F("stiffness"), cx=F("damping"), cy=F("damping"),
        dry_friction_force=F("force"), dry_friction_angle=F("angle"),
        dry_friction_velocity=F("velocity"), base_amplitude_x=F("length"),
        base_amplitude_y=F("length"), base_frequency=F("speed"), base_phase_x=F("angle"),
        base_phase_y=F("angle")),
    "balancer": _fields_of(
        BallBalancer, n_balls=F("int"), ball_mass=F("mass", "per_ball"), race_radius=F("length"),
        ball_radius=F("length"), element=F("text", choices=tuple(INERTIA_FACTOR)),
        damping=F("rot_damping", "per_ball"), rolling_resistance=F("ratio", "per_ball"),
        stiction=F("ratio", "per_ball"), eccentricity=F("length"),
        eccentricity_angle=F("angle"), restitution=F("ratio"), contact_frequency=F("speed"),
        contact=F("text", choices=CONTACT_MODELS)),
    "gravity": _fields_of(Gravity, g=F("acceleration"), direction=F("angle")),
    "liquid": _fields_of(
        LiquidDevice, chamber_radius=F("length", "per_chamber"),
        chamber_height=F("length", "per_chamber"), volume=F("volume", "per_chamber"),
        density=F("density"), kinematic_viscosity=F("kin_viscosity"),
        partitions=F("int", "per_chamber"), friction_arc=F("angle"),
        axis=F("text", choices=AXES), inner_radius=F("length", "per_chamber")),
    "initial": _fields_of(
        InitialState, ball_angles=F("angle", "list"), ball_speeds=F("speed", "list"),
        x=F("length"), y=F("length"), vx=F("velocity"), vy=F("velocity"),
        steady_state=F("bool")),
    "options": _fields_of(
        SimOptions, friction_law=F("text", choices=FRICTION_LAWS), v_sat=F("speed"),
        normal_force=F("text", choices=NORMAL_FORCES), rtol=F("ratio"), atol_scale=F("ratio"),
        max_step=F("time"), save_dt=F("time"), max_steps=F("int")),
}

# Keys a section no longer has, with what to do instead (one line, the key as written).
RETIRED = {
    ("options", k): "retired: the kernel takes its closed forms (holds, stuck ramps, slip "
                    "jumps) and its continuous extension at events wherever they apply; "
                    "remove the key"
    for k in ("exact_holds", "exact_ramps", "dense_events", "exponential_slip")}

# nominal is required in a file: without it a std/tsr profile would silently run at 004's
# 167 Hz (the Python constructors keep that default for callers who mean 004)
_STD = {"nominal": F("speed", required=True), "duration": F("time"), "runup_fraction": F("ratio"),
        "runup_time": F("time")}
#: Keys of each ``[profile]`` kind (besides ``kind``).
PROFILE_KINDS: dict[str, dict[str, F]] = {
    "constant": {"speed": F("speed", required=True), "duration": F("time", required=True)},
    "ramp": {"start_speed": F("speed", required=True), "end_speed": F("speed", required=True),
             "ramp_time": F("time", required=True), "duration": F("time", required=True)},
    "table": _fields_of(SpeedProfile, skip=("name",), times=F("time", "list"),
                        speeds=F("speed", "list"), nominal_speed=F("speed"),
                        checkpoints=F("time", "list")),
    "std": dict(_STD),
    "tsr": {**_STD, "plateau": F("speed"), "down_time": F("time"), "plateau_time": F("time"),
            "up_time": F("time")},
    "motor": _fields_of(MotorDrive, law=F("text", choices=MotorDrive.LAWS), torque=F("torque"),
                        final_speed=F("speed"), duration=F("time"), hold_fraction=F("ratio"),
                        initial_speed=F("speed")),
}
TOP_LEVEL = ("name", "description", "rotor", "suspension", "balancer", "gravity", "liquid",
             "profile", "initial", "options")
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
    if spec.shape in ("per_ball", "per_chamber") and not isinstance(value, (list, tuple)):
        return _one(spec, value)
    if spec.shape == "pairs":
        if not isinstance(value, (list, tuple)):
            raise _fail("expected a list of [time, unbalance] pairs, e.g. [['0 s', '0.025 kg*m']]",
                        value)
        out = []
        for i, pair in enumerate(value):
            if not isinstance(pair, (list, tuple)) or len(pair) != 2:
                raise _fail("expected a [time, unbalance] pair", pair, f"[{i}]")
            out.append(tuple(_one(F(k), v, f"[{i}][{j}]")
                             for j, (k, v) in enumerate(zip(spec.pair_kinds, pair))))
        return tuple(out)
    if not isinstance(value, (list, tuple)):
        raise _fail(f"expected a list; each {_expect(spec.kind)}", value)
    return tuple(_one(spec, v, f"[{i}]") for i, v in enumerate(value))


def _invalid(path: str, ctx: dict) -> ConfigError:
    """The one-line error of a value that does not fit its spec (context of :func:`_fail`)."""
    return ConfigError(f"{path}{ctx['sub']} = {ctx['value']!r}: {ctx['msg']}")


def check_value(path: str, spec: F, value: Any) -> Any:
    """Validate one value of the key ``path`` against its spec and convert it to SI.

    Parameters
    ----------
    path : str
        Dotted key (``"balancer.rolling_resistance"``), named in the error message.
    spec : F
        The key's spec (:data:`SECTIONS`, :data:`PROFILE_KINDS`).
    value : float, int, str, bool or list
        As in a TOML file: a number (SI) or a string with units; lists for list keys.

    Returns
    -------
    float, int, str, bool or tuple
        The value in SI (lists become tuples).

    Raises
    ------
    ConfigError
        The same one line as for that value in a file or ``--set``.
    """
    try:
        return _check(spec, value)
    except PydanticCustomError as e:
        raise _invalid(path, e.context) from None


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
        if err["type"] == "extra_forbidden" and (section, key) in RETIRED:
            raise ConfigError(f"{path}: {RETIRED[section, key]}") from None
        if err["type"] == "extra_forbidden":
            raise ConfigError(f"{path}: unknown key{extra}; allowed: {', '.join(fields)}") from None
        if err["type"] == "missing":
            raise ConfigError(f"{path}: missing; required {fields[key].need}") from None
        ctx = err.get("ctx") or {}
        if err["type"] == "autobalance":
            raise _invalid(path, ctx) from None
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
