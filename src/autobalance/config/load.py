"""Reading configurations: TOML files and presets -> :class:`Config` of model dataclasses."""
from __future__ import annotations

from collections.abc import Iterable
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..models import (BallBalancer, Gravity, InitialState, LiquidDevice, MotorDrive,
                      ParameterError, Rotor, SimOptions, SpeedProfile, Suspension, System)
from .overrides import apply_overrides
from .presets import _preset_dir, preset_path
from .reader import parse_toml, read_text
from .schema import (_MODELS, _PROFILE_MODELS, PROFILE_KINDS, REQUIRED_SECTIONS, SECTIONS,
                     TOP_LEVEL, _build, _section)
from ..models.profile import PROFILE_KINDS as PROFILE_KINDS_REGISTRY
from .units import ConfigError

#: The constructor of each ``[profile]`` kind (the models' registry), called with its keys in SI.
PROFILE_BUILDERS = PROFILE_KINDS_REGISTRY


def build_profile(kind: str, params: dict) -> SpeedProfile | MotorDrive:
    """The spin of a ``[profile]`` kind from its keys in SI (validated by :data:`PROFILE_KINDS`).

    Parameters
    ----------
    kind : str
        A key of :data:`PROFILE_KINDS`.
    params : dict
        The kind's keys in SI (missing optional keys take the constructor defaults).

    Returns
    -------
    SpeedProfile or MotorDrive

    Raises
    ------
    ConfigError
        A value the model rejects (``profile.<key> = ...``, one line).
    """
    return _build("profile", PROFILE_BUILDERS[kind], **params)


def profile_params(data: Any) -> tuple[str, dict]:
    """Validate a ``[profile]`` table: its kind and its given keys in SI.

    Parameters
    ----------
    data : dict
        The table: ``{"kind": "tsr", "nominal": "167 Hz", ...}`` (see :data:`PROFILE_KINDS`).

    Returns
    -------
    tuple
        (kind, {key: SI value}) of the keys given.

    Raises
    ------
    ConfigError
        Not a table, missing or unknown kind, unknown key or bad value (one line).
    """
    if not isinstance(data, dict):
        raise ConfigError(f"profile = {data!r}: expected a table [profile]")
    kinds = ", ".join(PROFILE_KINDS)
    if "kind" not in data:
        raise ConfigError(f"profile.kind: missing; required, one of {kinds}")
    kind = data["kind"]
    if kind not in PROFILE_KINDS:
        raise ConfigError(f"profile.kind = {kind!r}: unknown profile kind; allowed: {kinds}")
    rest = {k: v for k, v in data.items() if k != "kind"}
    return kind, _section("profile", rest, PROFILE_KINDS[kind], _PROFILE_MODELS[kind],
                          extra=f" for kind {kind!r}")


def _profile(data: Any) -> tuple[SpeedProfile | MotorDrive, str, dict]:
    """(spin, kind, given keys in SI) of a ``[profile]`` table."""
    kind, p = profile_params(data)
    return build_profile(kind, p), kind, p


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

    Returns
    -------
    Config
        The models; :attr:`Config.raw` is ``raw`` itself (not copied).

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
    liquid = _build("liquid", LiquidDevice, **p["liquid"]) if "liquid" in p else None
    spin, kind, _ = _profile(raw["profile"])
    initial = _build("initial", InitialState, **p.get("initial", {}))
    _build("initial", initial.angles_for, balancer)
    _build("initial", initial.speeds_for, balancer)
    options = _build("options", SimOptions, **p.get("options", {}))
    name = raw.get("name") or Path(str(source)).stem
    system = System(rotor, suspension, balancer, gravity, name=name,
                    description=raw.get("description", ""), liquid=liquid)
    return Config(system, spin, initial, options, raw=raw, source=str(source),
                  sources=dict(sources or {}), profile_kind=kind)


# -- files ------------------------------------------------------------------------------------
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

    Parameters
    ----------
    text : str
        A TOML text. Only single-line values are annotated (the presets keep every value on
        one line).

    Returns
    -------
    dict
        Dotted key (``"suspension.kx"``) -> comment (``"004 Table 1: k = 5.8 kN/mm"``).
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
    """(raw dict, source label, source comments) of a preset name or a .toml path, read by
    :func:`autobalance.config.reader.read_text` (one-line ConfigError for what is not a small
    regular UTF-8 TOML file)."""
    src = str(source)
    is_path = isinstance(source, Path) or src.endswith(".toml") or "/" in src or "\\" in src
    if not is_path and not (_preset_dir() / f"{src}.toml").is_file() and Path(src).exists():
        is_path = True  # an existing file without .toml suffix (or a FIFO, refused below)
    path = Path(src) if is_path else preset_path(src)
    # the one reader of input files (reader.py): regular files only, size, UTF-8, nesting
    text = read_text(path if not is_path else src, "config file")
    raw = parse_toml(text, src)
    return raw, (src if is_path else path.stem), source_comments(text)


def load_config(source: str | Path, overrides: Iterable[str] = ()) -> Config:
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
        Its ``sources`` hold the file's comments and ``--set ...`` for each override.

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
    try:
        return from_dict(merged, source=label, sources=comments)
    except (ConfigError, ParameterError) as e:
        e.written = merged        # the keys as written, for the CLI's message (display.as_written)
        raise
