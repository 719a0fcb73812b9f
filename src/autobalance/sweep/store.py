"""Durable sweep store: one file per finished task, assembled into one xarray.Dataset.

Layout of a store directory::

    STORE/sweep.json        description (canonical JSON + digest) and package version
    STORE/tasks/t000042.npz results of task 42, written to a temporary name and renamed
                            (os.replace is atomic: a killed sweep leaves whole files only)
    STORE/result.zarr       the assembled dataset (written when every task is done)

A store is tied to its description: opening it with another description or package version
raises StoreMismatch. Resuming skips the tasks whose file exists.
"""
from __future__ import annotations

import json
import os
from pathlib import Path

import numpy as np

from .. import __version__
from ..config import UNIT_LABEL
from .plan import Plan
from .spec import SweepError, SweepSpec

STATUS_NAMES = "0 ok, 1 max_steps, 2 step_size_underflow, 3 non_finite"


class StoreMismatch(SweepError):
    """The store was made by another sweep description or package version."""


def task_path(store: Path, k: int) -> Path:
    return Path(store) / "tasks" / f"t{k:06d}.npz"


def init_store(store: Path, spec: SweepSpec, resume: bool) -> None:
    """Create the store, or check that an existing one belongs to this description."""
    store = Path(store)
    meta = {"digest": spec.digest(), "spec": json.loads(spec.canonical()),
            "name": spec.name, "autobalance_version": __version__}
    mpath = store / "sweep.json"
    if mpath.exists():
        if not resume:
            raise SweepError(f"store {str(store)!r} exists: pass --resume to continue it, or "
                             "choose another --store path (nothing was overwritten)")
        try:
            old = json.loads(mpath.read_text())
        except (OSError, ValueError):
            raise StoreMismatch(f"store {str(store)!r}: unreadable sweep.json; refusing to use it") from None
        if old.get("autobalance_version") != __version__:
            raise StoreMismatch(f"store {str(store)!r} was made by autobalance "
                                f"{old.get('autobalance_version')}, this is {__version__}; "
                                "refusing to mix results (start a new store)")
        if old.get("digest") != meta["digest"]:
            raise StoreMismatch(f"store {str(store)!r} was made by a different sweep description "
                                f"(digest {old.get('digest')} != {meta['digest']}); refusing to "
                                "overwrite it (start a new store)")
        return
    if store.exists() and any(store.iterdir()):
        raise SweepError(f"store {str(store)!r} exists and is not a sweep store; choose an "
                         "empty or new directory")
    (store / "tasks").mkdir(parents=True, exist_ok=True)
    tmp = mpath.with_suffix(".tmp")
    tmp.write_text(json.dumps(meta, indent=1, sort_keys=True))
    os.replace(tmp, mpath)


def write_task(store: Path, result: dict) -> None:
    """Atomically write one task's arrays."""
    path = task_path(store, int(result["task"]))
    tmp = path.with_name(path.name + ".tmp")
    with open(tmp, "wb") as f:
        np.savez(f, **{k: np.asarray(v) for k, v in result.items()})
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, path)


def done_tasks(store: Path, n_tasks: int) -> set:
    return {k for k in range(n_tasks) if task_path(store, k).exists()}


VARIABLES = {
    # name: (dims after the run dims, units, long name)
    "grade_G": (("checkpoint",), "mm/s", "ISO 1940-1 balance grade at the checkpoint"),
    "residual_unbalance": (("checkpoint",), "kg*m", "residual unbalance at the checkpoint"),
    "ball_angle": (("checkpoint", "ball"), "rad", "ball angle from the unbalance, in (-pi, pi]"),
    "initial_grade_G": ((), "mm/s", "grade of the rotor with the balls at their start positions"),
    "max_amplitude": ((), "m", "largest whirl amplitude during the run"),
    "status": ((), "1", f"solver status ({STATUS_NAMES})"),
    "steps": ((), "1", "integration steps"),
    "events": ((), "1", "stick-slip events"),
    "grade_G_history": (("history_time",), "mm/s", "grade over time (decimated)"),
    "amplitude_history": (("history_time",), "m", "whirl amplitude over time (decimated)"),
    "speed_history": (("history_time",), "rad/s", "spin speed over time (decimated)"),
}
FILL = {"status": -1, "steps": -1, "events": -1}


def assemble(plan: Plan, store: Path, allow_partial: bool = True):
    """The sweep as one xarray.Dataset (dims: grid axes..., sample[, checkpoint, ball,
    history_time]); runs of unfinished tasks are NaN (status -1) if allow_partial."""
    import xarray as xr

    spec = plan.spec
    n_s, N = plan.n_samples, plan.n_balls
    n_runs = plan.n_runs
    cps = plan.checkpoints
    hist_t = (np.arange(0.0, plan.cells[0].spin.duration + 1e-12, spec.history_dt)
              if spec.history_dt > 0 else np.zeros(0))
    sizes = {"checkpoint": cps.size, "ball": N, "history_time": hist_t.size}
    data = {}
    for name, (dims, _, _) in VARIABLES.items():
        if "history_time" in dims and not hist_t.size:
            continue
        shape = (n_runs,) + tuple(sizes[d] for d in dims)
        fill = FILL.get(name, np.nan)
        data[name] = np.full(shape, fill, dtype=np.int64 if name in FILL else float)
    missing = 0
    for k, (first, count) in enumerate(plan.tasks):
        p = task_path(store, k)
        if not p.exists():
            missing += count
            continue
        with np.load(p) as z:
            for name in data:
                data[name][first:first + count] = z[name]
    if missing and not allow_partial:
        raise SweepError(f"store {str(store)!r}: {missing} of {n_runs} runs not finished")
    grid_dims = [a.dim for a in spec.grid]
    run_shape = spec.shape + (n_s,)
    coords = {}
    for a in spec.grid:
        unit = UNIT_LABEL.get(a.unit_kind, "")
        coords[a.dim] = (a.dim, np.asarray(a.si), {"units": unit, "long_name": a.path,
                                                    "values_as_given": json.dumps(list(a.values))})
    coords["sample"] = ("sample", np.arange(n_s))
    coords["checkpoint"] = ("checkpoint", cps, {"units": "s", "long_name": "checkpoint time"})
    coords["ball"] = ("ball", np.arange(N))
    coords["start_angle"] = (("sample", "ball"), plan.start_angles,
                             {"units": "rad", "long_name": "ball start angle from the unbalance"})
    if hist_t.size:
        coords["history_time"] = ("history_time", hist_t, {"units": "s"})
    dvars = {}
    for name, arr in data.items():
        dims, units, long = VARIABLES[name]
        dvars[name] = (tuple(grid_dims) + ("sample",) + dims,
                       arr.reshape(run_shape + arr.shape[1:]), {"units": units, "long_name": long})
    ds = xr.Dataset(dvars, coords=coords)
    ds.attrs.update({
        "sweep_name": spec.name, "sweep_digest": spec.digest(), "sweep_spec": spec.canonical(),
        "autobalance_version": __version__, "base": spec.base,
        "monte_carlo": spec.mc_kind, "n_runs": n_runs, "n_missing_runs": missing,
        "nominal_speed_rad_s": float(plan.cells[0].spin.nominal_speed),
    })
    return ds


def write_result(ds, store: Path) -> Path:
    """Write the assembled dataset as Zarr (replacing an older assembly)."""
    import shutil

    path = Path(store) / "result.zarr"
    tmp = Path(store) / "result.zarr.tmp"
    if tmp.exists():
        shutil.rmtree(tmp)
    ds.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2)
    if path.exists():
        shutil.rmtree(path)
    os.replace(tmp, path)
    return path
