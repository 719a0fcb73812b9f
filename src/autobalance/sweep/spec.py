"""Sweep description: base system, swept grid, Monte-Carlo dimension, outputs.

TOML form (every value with units where it has them)::

    [sweep]
    name = "tsr-start-positions"
    base = "vub_jeffcott_004"            # preset name or path of a config .toml
    set = ["balancer.rolling_resistance=0.002"]   # overrides applied to the base
    batch_size = 64                      # runs per task (amortises scheduling)

    [grid]                               # swept parameters, dims in this order
    "rotor.unbalance" = ["0.1 g*m", "0.2 g*m"]
    "balancer.rolling_resistance" = { start = 0.001, stop = 0.004, num = 4 }

    [monte_carlo]                        # the "sample" dimension
    kind = "start_grid"                  # 004 sec. 4.2: n equispaced start positions per ball,
    n = 50                               #   symmetric duplicates removed (50 -> 1275 for 2 balls)
    # kind = "random"; samples = 200; seed = 1   (uniform independent start angles)

    [outputs]
    history_dt = "0.5 s"                 # optional decimated time histories (0 = none)

The same description is a :class:`SweepSpec` in Python. Its canonical JSON (``spec.canonical()``)
identifies a sweep: a durable store made from another description is refused.

In Python the base may instead be a Config or System built there: ``spec_from_dict(d,
base=config)`` or ``autobalance.sweep(d, store, base=system, spin=profile)`` (:func:`as_spec`),
with ``d`` naming no ``sweep.base``.
"""
from __future__ import annotations

import dataclasses
import hashlib
import json
import math
import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

import numpy as np

from ..config import (PROFILE_KINDS, SECTIONS, Config, ConfigError, from_models,
                      parse_quantity)
from ..config.reader import load_toml
from ..models import InitialState, MotorDrive, SimOptions, SpeedProfile, System

MC_KINDS = ("start_grid", "random", "none")
_TOP = ("sweep", "grid", "monte_carlo", "outputs")
_SWEEP_KEYS = ("name", "base", "set", "batch_size", "description")
_MC_KEYS = {"start_grid": ("kind", "n"), "random": ("kind", "samples", "seed"), "none": ("kind",)}
_OUT_KEYS = ("history_dt",)


class SweepError(ConfigError):
    """A bad sweep description (one-line message naming the field)."""


def _quantity(value: Any, kind: str, where: str) -> float:
    """parse_quantity, raising SweepError (a bad sweep description) instead of ConfigError."""
    try:
        return parse_quantity(value, kind, where)
    except SweepError:
        raise
    except ConfigError as e:
        raise SweepError(str(e)) from None


def field_kind(path: str) -> str:
    """The quantity kind (config.SECTIONS) of a dotted config path, for SI coordinates."""
    parts = path.split(".")
    if len(parts) != 2:
        raise SweepError(f"grid.{path}: unknown path; use section.key, e.g. rotor.unbalance")
    section, key = parts
    if section == "profile":
        for kinds in PROFILE_KINDS.values():
            if key in kinds:
                return kinds[key].kind
        raise SweepError(f"grid.{path}: unknown profile key")
    if section not in SECTIONS or key not in SECTIONS[section]:
        raise SweepError(f"grid.{path}: unknown path; sections: {', '.join(SECTIONS)}")
    return SECTIONS[section][key].kind


@dataclass(frozen=True)
class GridAxis:
    """One swept parameter: dotted config path, raw values (as in TOML), SI values."""

    path: str
    values: tuple
    si: tuple
    unit_kind: str

    @property
    def dim(self) -> str:
        return self.path.replace(".", "__")


@dataclass(frozen=True)
class SweepSpec:
    """A sweep: ``base`` config with ``overrides``, a grid, a Monte-Carlo dimension, outputs.

    ``base`` names a preset or a config file; for a base built in Python (``base_config``, see
    :func:`spec_from_dict`) it is a label, ``"<python: NAME>"``. The store's identity digests
    every cell's resolved models, so the label is not what tells two bases apart. A sweep file's
    base config (:func:`load_spec`) is ``base`` relative to the sweep file's directory, and
    ``base_file`` is the file read; only ``base`` is in :meth:`canonical`.
    """

    name: str
    base: str
    overrides: tuple = ()
    grid: tuple = ()                 # of GridAxis
    mc_kind: str = "none"
    mc_n: int = 0                    # start_grid: positions per ball
    mc_samples: int = 1              # random: number of samples
    seed: int = 0
    batch_size: int = 64
    history_dt: float = 0.0          # [s], 0 = no histories
    description: str = ""
    extra: dict = field(default_factory=dict)
    base_config: Config | None = None   # a base built in Python (then ``base`` is its label)
    base_file: str = ""              # the base config file read (load_spec), else ``base``

    @property
    def base_source(self) -> str:
        """The preset name or config file to read the base from."""
        return self.base_file or self.base

    def canonical(self) -> str:
        """Deterministic JSON of everything that determines the results."""
        d = {
            "base": self.base, "overrides": list(self.overrides),
            "grid": [[a.path, list(a.values)] for a in self.grid],
            "mc_kind": self.mc_kind, "mc_n": self.mc_n, "mc_samples": self.mc_samples,
            "seed": self.seed, "history_dt": self.history_dt,
        }
        return json.dumps(d, sort_keys=True)

    def digest(self) -> str:
        return hashlib.sha256(self.canonical().encode()).hexdigest()[:16]

    @property
    def shape(self) -> tuple:
        return tuple(len(a.values) for a in self.grid)


def grid_axis(path: str, spec: Any) -> GridAxis:
    """One grid axis of a sweep description: ``grid.<path> = [values]`` or ``{start, stop,
    num}`` (values with units as strings, bare numbers SI), validated and converted to SI.

    Parameters
    ----------
    path : str
        Config path, e.g. ``"rotor.unbalance"``.
    spec : list or dict
        The values, or ``{"start", "stop", "num"}``.

    Returns
    -------
    GridAxis
        Its ``si`` values are SI.

    Raises
    ------
    SweepError
        One line naming ``grid.<path>`` and what is allowed.
    """
    kind = field_kind(path)
    if isinstance(spec, dict):
        unknown = set(spec) - {"start", "stop", "num"}
        if unknown:
            raise SweepError(f"grid.{path}: unknown key {sorted(unknown)[0]!r}; allowed: start, stop, num")
        for k in ("start", "stop", "num"):
            if k not in spec:
                raise SweepError(f"grid.{path}.{k}: missing; a range needs start, stop, num")
        num = spec["num"]
        if isinstance(num, bool) or not isinstance(num, int) or num < 1:
            raise SweepError(f"grid.{path}.num = {num!r}: must be an integer >= 1")
        check_grid_size([(f'grid."{path}".num', num, num)])    # before np.linspace allocates
        lo = _quantity(spec["start"], kind, f"grid.{path}.start")
        hi = _quantity(spec["stop"], kind, f"grid.{path}.stop")
        si = tuple(float(v) for v in np.linspace(lo, hi, num))
        return GridAxis(path, si, si, kind)
    if not isinstance(spec, list):
        raise SweepError(f"grid.{path} = {spec!r}: expected a list of values or {{start, stop, num}}")
    if not spec:
        raise SweepError(f"grid.{path} = []: empty grid; give at least one value")
    si = []
    for i, v in enumerate(spec):
        if isinstance(v, list):
            raise SweepError(f"grid.{path}[{i}] = {v!r}: grid values must be scalars")
        if kind in ("int", "text", "bool"):
            si.append(v)
        else:
            si.append(_quantity(v, kind, f"grid.{path}[{i}]"))
    if len(set(map(str, spec))) != len(spec):
        raise SweepError(f"grid.{path} = {spec!r}: values must be distinct")
    return GridAxis(path, tuple(spec), tuple(si), kind)


#: Bytes per grid cell (its validated Config and models; conservative) [B].
CELL_BYTES = 20e3


def check_grid_size(axes: list) -> None:
    """Refuse a grid whose cells would not fit the memory limit
    (:func:`autobalance.limits.check_memory`, :data:`CELL_BYTES` per cell), from the axes'
    lengths alone: nothing of the grid is built yet.

    Parameters
    ----------
    axes : list
        (field as written, value as written, number of values) of each axis, e.g.
        ``('grid."rotor.unbalance".num', 1000000000, 1000000000)``.

    Raises
    ------
    ResourceError
        One line naming the axis that alone exceeds the limit, or ``grid`` with the product.
    """
    from ..limits import check_memory, max_memory

    n_cells = math.prod(n for _, _, n in axes)
    if not axes or n_cells * CELL_BYTES <= max_memory():
        return
    field, value, n = max(axes, key=lambda a: a[2])
    if n * CELL_BYTES > max_memory() or len(axes) == 1:
        check_memory(field, value, n * CELL_BYTES, "sweep's grid")
    check_memory("grid", " x ".join(str(a[2]) for a in axes) + f" = {n_cells} cells",
                 min(n_cells, 10**300) * CELL_BYTES, "sweep's grid")


def _grid_sizes(grid_d: dict) -> list:
    """(field, value, length) of the grid axes whose length is known before they are built."""
    out = []
    for path, v in grid_d.items():
        if isinstance(v, dict) and isinstance(v.get("num"), int) and not isinstance(v["num"], bool):
            out.append((f'grid."{path}".num', v["num"], max(v["num"], 1)))
        elif isinstance(v, list):
            out.append((f'grid."{path}"', f"[{len(v)} values]", max(len(v), 1)))
    return out


def spec_from_dict(d: dict, label: str = "<dict>", *, base: Config | None = None) -> SweepSpec:
    """Validate a parsed sweep description (the TOML form of the module docstring).

    Parameters
    ----------
    d : dict
        ``{"sweep": {...}, "grid": {...}, "monte_carlo": {...}, "outputs": {...}}``.
    label : str
        The file it came from; its stem is the default ``sweep.name``.
    base : Config, optional
        A base built in Python (:func:`autobalance.config.from_models`, or a loaded config
        changed with :func:`autobalance.config.replace_values`). Then ``[sweep]`` is optional
        and must not name a ``base``; ``sweep.set`` applies to this base as to a preset.

    Returns
    -------
    SweepSpec
        Its ``base`` is ``sweep.base``, or ``"<python: NAME>"`` with ``base_config``.

    Raises
    ------
    SweepError
        One line naming the bad field.
    """
    for k in d:
        if k not in _TOP:
            raise SweepError(f"{k}: unknown section; allowed: {', '.join(_TOP)}")
    sw = d.get("sweep", {} if base is not None else None)
    if not isinstance(sw, dict):
        raise SweepError("sweep: missing; required table [sweep] with base = PRESET|CONFIG")
    for k in sw:
        if k not in _SWEEP_KEYS:
            raise SweepError(f"sweep.{k}: unknown key; allowed: {', '.join(_SWEEP_KEYS)}")
    if base is not None:
        if "base" in sw:
            raise SweepError(f"sweep.base = {sw['base']!r}: given twice, in the description "
                             "and as a Config built in Python (base=); give one of them")
        if not isinstance(base, Config):
            raise SweepError(f"base = {base!r}: expected an autobalance.config.Config")
        label_base = f"<python: {base.name}>" if base.name else "<python>"
    elif "base" not in sw or not isinstance(sw["base"], str):
        raise SweepError("sweep.base: missing; required, a preset name or a config .toml path")
    else:
        label_base = sw["base"]
    sets = sw.get("set", [])
    if not isinstance(sets, list) or not all(isinstance(s, str) for s in sets):
        raise SweepError(f"sweep.set = {sets!r}: expected a list of 'path=value' strings")
    bs = sw.get("batch_size", 64)
    if isinstance(bs, bool) or not isinstance(bs, int) or bs < 1:
        raise SweepError(f"sweep.batch_size = {bs!r}: must be an integer >= 1")
    grid_d = d.get("grid", {})
    if not isinstance(grid_d, dict):
        raise SweepError(f"grid = {grid_d!r}: expected a table of path = values")
    check_grid_size(_grid_sizes(grid_d))
    grid = tuple(grid_axis(p, v) for p, v in grid_d.items())
    mc = d.get("monte_carlo", {"kind": "none"})
    if not isinstance(mc, dict):
        raise SweepError(f"monte_carlo = {mc!r}: expected a table")
    kind = mc.get("kind", "none")
    if kind not in MC_KINDS:
        raise SweepError(f"monte_carlo.kind = {kind!r}: must be one of {list(MC_KINDS)}")
    for k in mc:
        if k not in _MC_KEYS[kind]:
            raise SweepError(f"monte_carlo.{k}: unknown key for kind {kind!r}; allowed: "
                             f"{', '.join(_MC_KEYS[kind])}")
    n = mc.get("n", 0)
    samples = mc.get("samples", 1)
    seed = mc.get("seed", 0)
    if kind == "start_grid" and (isinstance(n, bool) or not isinstance(n, int) or n < 1):
        raise SweepError(f"monte_carlo.n = {n!r}: must be an integer >= 1 (positions per ball)")
    if kind == "random":
        if isinstance(samples, bool) or not isinstance(samples, int) or samples < 1:
            raise SweepError(f"monte_carlo.samples = {samples!r}: must be an integer >= 1")
        if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
            raise SweepError(f"monte_carlo.seed = {seed!r}: must be an integer >= 0")
    out = d.get("outputs", {})
    if not isinstance(out, dict):
        raise SweepError(f"outputs = {out!r}: expected a table")
    for k in out:
        if k not in _OUT_KEYS:
            raise SweepError(f"outputs.{k}: unknown key; allowed: {', '.join(_OUT_KEYS)}")
    hdt = _quantity(out.get("history_dt", 0.0), "time", "outputs.history_dt")
    if hdt < 0 or not math.isfinite(hdt):
        raise SweepError(f"outputs.history_dt = {out.get('history_dt')!r}: must be >= 0")
    return SweepSpec(name=str(sw.get("name", Path(label).stem)), base=label_base,
                     overrides=tuple(sets), grid=grid, mc_kind=kind, mc_n=n,
                     mc_samples=samples if kind == "random" else 1, seed=seed, batch_size=bs,
                     history_dt=hdt, description=str(sw.get("description", "")),
                     base_config=base)


def load_spec(path: str | Path, *, base: Config | None = None) -> SweepSpec:
    """Read and validate a sweep TOML file.

    Parameters
    ----------
    path : str or Path
        The sweep description. A relative ``sweep.base`` path is taken relative to it.
    base : Config, optional
        A base built in Python instead of ``sweep.base`` (see :func:`spec_from_dict`).

    Returns
    -------
    SweepSpec
        Named after the file unless ``sweep.name`` is given. A base config file is its
        ``base`` as written (normalised) and its ``base_file`` as read.

    Raises
    ------
    SweepError
        Unreadable, not a regular file, larger than the input limit, not UTF-8, invalid or
        too deeply nested TOML (:mod:`autobalance.config.reader`), or a bad field (one line).
    ResourceError
        A grid too large for the memory limit (:func:`check_grid_size`).
    """
    p = Path(path)
    try:
        d, _ = load_toml(p, "sweep file")      # the config files' reader (config/reader.py)
    except SweepError:
        raise
    except ConfigError as e:
        raise SweepError(str(e)) from None
    spec = spec_from_dict(d, str(p), base=base)
    written = spec.base
    if spec.base_config is None and _is_path(written):
        # read from the sweep file's directory, identified by the path as written (relative to
        # that directory, normalised): the sweep file moved together with its base config is
        # the same sweep, and an absolute path names the same file wherever the sweep file is
        file = Path(written) if Path(written).is_absolute() else (p.parent / written).resolve()
        spec = dataclasses.replace(spec, base=Path(os.path.normpath(written)).as_posix(),
                                   base_file=str(file))
    return spec


def _is_path(base: str) -> bool:
    """Whether ``sweep.base`` names a config file rather than a preset (as config._read)."""
    return base.endswith(".toml") or "/" in base or "\\" in base


def as_spec(spec: SweepSpec | dict | str | Path, base: Config | System | None = None,
            spin: SpeedProfile | MotorDrive | dict | None = None,
            initial: InitialState | None = None,
            options: SimOptions | None = None) -> SweepSpec:
    """The SweepSpec of what :func:`autobalance.sweep` was given.

    Parameters
    ----------
    spec : SweepSpec, dict or path
        A description: validated, parsed (see :func:`spec_from_dict`) or a TOML file.
    base : Config or System, optional
        A base built in Python, for a description without ``sweep.base``. A System is made a
        Config with ``spin``, ``initial`` and ``options``
        (:func:`autobalance.config.from_models`).
    spin : SpeedProfile, MotorDrive or dict, optional
        The spin of a System base (required with it); a dict is a ``[profile]`` table.
    initial : InitialState, optional
        The initial state of a System base.
    options : SimOptions, optional
        The numerical options of a System base.

    Returns
    -------
    SweepSpec

    Raises
    ------
    SweepError
        A bad description or base (one line).
    """
    if isinstance(base, System):
        if spin is None:
            raise SweepError("spin: missing; a System base needs its speed profile or motor "
                             "drive (spin=), or pass a Config as base")
        try:
            base = from_models(base, spin, initial, options)
        except ConfigError as e:
            raise SweepError(f"base: {e}") from None
    elif spin is not None or initial is not None:
        raise SweepError("spin, initial: only with a System base (a Config has its own; change "
                         "it with autobalance.config.replace_values)")
    if isinstance(spec, SweepSpec):
        if base is not None:
            raise SweepError(f"base: the description has its base already ({spec.base!r}); "
                             "give it as a dict or TOML file without sweep.base")
        return spec
    if isinstance(spec, dict):
        return spec_from_dict(spec, base=base)
    return load_spec(spec, base=base)


__all__ = ["CELL_BYTES", "GridAxis", "MC_KINDS", "SweepError", "SweepSpec", "as_spec",
           "check_grid_size", "field_kind", "grid_axis", "load_spec", "spec_from_dict"]
