"""Durable sweep store: one file per finished task, assembled into one xarray.Dataset.

Layout of a store directory::

    STORE/sweep.json                  description, identity digest and package version
    STORE/lock                        held (flock) by the one process working on the store
    STORE/tasks/r000000040-000000048.npz   results of runs 40..47, written to a temporary
                                      name and renamed (os.replace is atomic: a killed sweep
                                      leaves whole files only)
    STORE/result.zarr                 the assembled dataset (written when every run is done)

Task files are keyed by the runs they hold, not by their position in a task list, so a store
does not depend on ``batch_size`` or on how the runs were grouped: resuming with another batch
size runs exactly the runs that are missing.

A store is tied to its *identity*: a digest of the description and of every resolved value
that determines its results (each grid cell's system, profile, initial state and options, as
built from the base config's contents, the start angles, the package version and the digest of
the code that computes the runs, :func:`code_digest`). Opening it with anything else raises
StoreMismatch, never overwrites. One process at a time works on a
store (an exclusive ``flock`` on STORE/lock, released by the kernel when the process dies, so a
stale lock after ``kill -9`` is never an obstacle).
"""
from __future__ import annotations

import errno
import fcntl
import functools
import hashlib
import json
import os
import re
import shutil
import socket
import time
from pathlib import Path
from typing import TYPE_CHECKING, Callable

import numpy as np

from .. import __version__
from ..core.layout import RunStatus
from ..config import UNIT_LABEL
from .plan import Plan
from .spec import SweepError

if TYPE_CHECKING:
    import xarray as xr

STATUS_NAMES = ", ".join(f"{int(s)} {s.label}" for s in RunStatus
                         if s <= RunStatus.NON_FINITE or s is RunStatus.OUTSIDE_MODEL)
_TASK_RE = re.compile(r"r(\d{9})-(\d{9})\.npz")


class StoreMismatch(SweepError):
    """The store was made by another sweep description, base config or package version."""


class StoreBusy(SweepError):
    """Another process holds the store's lock."""


def task_path(store: Path, first: int, count: int) -> Path:
    """File of the runs first .. first + count - 1."""
    return Path(store) / "tasks" / f"r{first:09d}-{first + count:09d}.npz"


#: The subpackages whose code computes a run's stored results: a change to any of them is a
#: new store (the version alone stays 0.1.0 between commits, so a `git pull` that changed the
#: simulator would have resumed the old results). The CLI, figures, reports and the studies'
#: read-outs of the stored runs are not in it.
RESULT_CODE = ("config", "core", "liquid", "models", "physics", "simulate", "sweep")


@functools.cache
def code_digest() -> str:
    """Digest of the source of :data:`RESULT_CODE` (every .py file, by its path in the package
    and its bytes), once per process.

    Returns
    -------
    str
        16 hex digits.
    """
    root = Path(__file__).resolve().parent.parent
    h = hashlib.sha256()
    for sub in RESULT_CODE:
        for p in sorted((root / sub).rglob("*.py")):
            h.update(p.relative_to(root).as_posix().encode())
            h.update(p.read_bytes())
    return h.hexdigest()[:16]


def identity(plan: Plan) -> str:
    """Digest of everything that determines a store's results: the description's canonical
    JSON, every grid cell's resolved system, profile, initial state and options (so an edited
    base config or preset is a different sweep), the start angles, the package version and the
    code (:func:`code_digest`)."""
    cached = getattr(plan, "_identity", None)
    if cached is not None:
        return cached
    h = hashlib.sha256()
    h.update(plan.spec.canonical().encode())
    h.update(__version__.encode())
    h.update(code_digest().encode())
    for c in plan.cells:
        h.update(repr((c.system, c.spin, c.initial, c.options)).encode())
        if c.system.liquid is not None:      # not in System's repr (models/system.py)
            h.update(repr(c.system.liquid).encode())
    if len(plan.angles) == 1:
        h.update(np.ascontiguousarray(plan.start_angles, float).tobytes())
    else:                                   # a balancer.n_balls axis: the angles of every N
        for n in sorted(plan.angles):
            h.update(f"N={n}".encode())
            h.update(np.ascontiguousarray(plan.angles[n], float).tobytes())
    plan._identity = h.hexdigest()[:16]
    return plan._identity


def _meta(plan: Plan) -> dict:
    spec = plan.spec
    return {"digest": spec.digest(), "identity": identity(plan), "spec": json.loads(spec.canonical()),
            "name": spec.name, "n_runs": plan.n_runs, "autobalance_version": __version__,
            "code_digest": code_digest()}


def check_store_path(store: Path) -> None:
    """Refuse a --store that cannot be a store directory before anything is computed."""
    store = Path(store)
    if store.exists() and not store.is_dir():
        raise SweepError(f"--store {str(store)!r}: exists and is not a directory; give a new "
                         "directory or an existing sweep store")
    parent = store.parent if not store.exists() else store
    while not parent.exists():
        parent = parent.parent
    if not parent.is_dir():
        raise SweepError(f"--store {str(store)!r}: {str(parent)!r} is not a directory")


class StoreLock:
    """Exclusive lock of a store (``flock`` on STORE/lock, non-blocking). The lock file holds
    the owner's pid, host and start time for the refusal message."""

    def __init__(self, store: Path):
        self.path = Path(store) / "lock"
        self.fd = None

    def acquire(self) -> None:
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT, 0o644)
        except OSError as e:
            raise SweepError(f"--store {str(self.path.parent)!r}: cannot write to it "
                             f"({e.strerror or e}); nothing was run") from None
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as e:
            try:
                owner = os.pread(fd, 200, 0).decode(errors="replace").strip() or "another process"
            finally:
                os.close(fd)
            if e.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                raise StoreBusy(f"--store {str(self.path.parent)!r} is in use by {owner}; wait for "
                                "it to finish or stop it (nothing was changed)") from None
            raise SweepError(f"--store {str(self.path.parent)!r}: cannot lock it "
                             f"({e.strerror or e})") from None
        self.fd = fd
        self.stamped = False

    def stamp(self) -> None:
        """Record the owner in the lock file (after the store's checks passed)."""
        os.ftruncate(self.fd, 0)
        os.pwrite(self.fd, f"process {os.getpid()} on {socket.gethostname()} since "
                           f"{time.strftime('%Y-%m-%d %H:%M:%S')}".encode(), 0)
        self.stamped = True

    def release(self) -> None:
        if self.fd is not None:
            if self.stamped:
                try:
                    os.ftruncate(self.fd, 0)
                except OSError:
                    pass
            os.close(self.fd)   # closing the descriptor releases the flock
            self.fd = None

    def __enter__(self):
        self.acquire()
        return self

    def __exit__(self, *exc):
        self.release()


def _probe_writable(store: Path) -> None:
    """Write, sync and remove a file in STORE/tasks: a read-only or full store fails here,
    before any run is computed."""
    probe = Path(store) / "tasks" / f".probe-{os.getpid()}"
    try:
        with open(probe, "wb") as f:
            f.write(b"0" * 4096)
            f.flush()
            os.fsync(f.fileno())
        probe.unlink()
    except OSError as e:
        raise SweepError(f"--store {str(store)!r}: cannot write task files ({e.strerror or e}); "
                         "nothing was run") from None


def init_store(store: Path, plan: Plan, resume: bool, lock: StoreLock) -> None:
    """Create the store, or check that an existing one belongs to this plan; takes ``lock``.

    An existing store needs ``resume``, except a store of the same identity that holds no
    finished run yet (a sweep that failed before its first task: rerunning it loses nothing).
    """
    store = Path(store)
    meta = _meta(plan)
    mpath = store / "sweep.json"
    if store.exists() and not mpath.exists():
        extra = [p.name for p in store.iterdir() if p.name not in ("lock", "tasks")]
        tasks = store / "tasks"
        if extra or (tasks.is_dir() and any(tasks.iterdir())):
            raise SweepError(f"--store {str(store)!r} exists and is not a sweep store; choose an "
                             "empty or new directory")
    try:
        store.mkdir(parents=True, exist_ok=True)
    except OSError as e:
        raise SweepError(f"--store {str(store)!r}: cannot create it ({e.strerror or e})") from None
    lock.acquire()
    try:
        if mpath.exists():
            check_identity(store, plan)
            empty = not _task_files(store) and not (store / "result.zarr").exists()
            if not resume and not empty:
                raise SweepError(f"--store {str(store)!r} exists: pass --resume to continue it, "
                                 "or choose another --store path (nothing was overwritten)")
        (store / "tasks").mkdir(exist_ok=True)
        for tmp in [*(store / "tasks").glob("*.tmp"), *(store / "tasks").glob(".probe-*")]:
            tmp.unlink(missing_ok=True)     # half-written by a killed owner (we hold the lock)
        _probe_writable(store)
        lock.stamp()
        if not mpath.exists():
            tmp = mpath.with_suffix(".tmp")
            tmp.write_text(json.dumps(meta, indent=1, sort_keys=True))
            os.replace(tmp, mpath)
    except BaseException:
        lock.release()
        raise


def check_identity(store: Path, plan: Plan) -> None:
    """Refuse (StoreMismatch, one line) a store whose sweep.json is missing, unreadable, or
    records another package version, description, code or identity than ``plan``'s."""
    mpath = Path(store) / "sweep.json"
    if not mpath.exists():
        raise SweepError(f"store {str(store)!r}: no sweep.json; not a sweep store")
    try:
        old = json.loads(mpath.read_text())
    except (OSError, ValueError):
        raise StoreMismatch(f"--store {str(store)!r}: unreadable sweep.json; refusing to use "
                            "it") from None
    meta = _meta(plan)
    if old.get("autobalance_version") != __version__:
        raise StoreMismatch(f"--store {str(store)!r} was made by autobalance "
                            f"{old.get('autobalance_version')}, this is {__version__}; refusing "
                            "to mix results (start a new store)")
    if old.get("digest") != meta["digest"]:
        raise StoreMismatch(f"--store {str(store)!r} was made by a different sweep description "
                            f"(digest {old.get('digest')} != {meta['digest']}); refusing to "
                            "overwrite it (start a new store)")
    if old.get("code_digest") != meta["code_digest"] and "identity" in old:
        raise StoreMismatch(f"--store {str(store)!r} was made by other code of autobalance "
                            f"{__version__} (code digest {old.get('code_digest')} != "
                            f"{meta['code_digest']}: the simulator changed since); refusing to mix "
                            "results (start a new store)")
    if "identity" not in old:
        raise StoreMismatch(f"--store {str(store)!r} was made by an earlier store format (task "
                            "files by index, no identity); refusing to mix results (start a new "
                            "store)")
    if old.get("identity") != meta["identity"]:
        raise StoreMismatch(f"--store {str(store)!r} was made from different parameter values "
                            f"with the same description (the base config {meta['spec']['base']!r} "
                            f"or a preset changed; identity {old.get('identity')} != "
                            f"{meta['identity']}); refusing to mix machines (start a new store)")


def _task_files(store: Path) -> list:
    d = Path(store) / "tasks"
    return sorted(p for p in d.glob("r*.npz")) if d.is_dir() else []


def _check_task(path: Path, first: int, count: int, names, shapes: dict) -> None:
    """Raise ValueError if the file is not a complete task file of these runs."""
    with np.load(path) as z:
        if int(z["first"]) != first or int(z["count"]) != count:
            raise ValueError("its runs do not match its name")
        for name in names:
            a = z[name]
            if a.shape != (count,) + shapes[name]:
                raise ValueError(f"{name} has shape {a.shape}")


def scan_tasks(store: Path, plan: Plan, *,
               on_corrupt: Callable[[Path, str], object] | None = None) -> list:
    """The finished task files as (first, count, path), checked against the plan.

    A file whose name is not a range of this plan's runs, or overlaps another, is *corrupt*.
    With ``on_corrupt`` (resume, where the scan decides what to run) every file is also read and
    checked; a corrupt one is renamed to ``NAME.corrupt`` (kept for inspection, never deleted)
    and ``on_corrupt(path, reason)`` is called, so that its runs are computed again. Without it
    a SweepError names the file, and the contents are checked when :func:`assemble` reads
    them (each file is read once)."""
    names, shapes = _expected(plan)
    out = []
    covered = np.zeros(plan.n_runs, bool)
    for p in _task_files(store):
        m = _TASK_RE.fullmatch(p.name)
        reason = None
        if not m:
            reason = "unexpected file name"
        else:
            first, stop = int(m.group(1)), int(m.group(2))
            count = stop - first
            if not (0 <= first < stop <= plan.n_runs):
                reason = f"runs {first}..{stop - 1} are outside this sweep's {plan.n_runs} runs"
            elif covered[first:stop].any():
                reason = "its runs overlap another task file"
            elif on_corrupt is not None:
                try:
                    _check_task(p, first, count, names, shapes)
                except Exception as e:   # BadZipFile, EOFError, KeyError, ValueError, OSError
                    reason = f"{type(e).__name__}: {' '.join(str(e).split())[:120]}"
        if reason is not None:
            if on_corrupt is None:
                raise SweepError(f"task file {str(p)!r} is corrupt ({reason}); rerun the sweep "
                                 "with --resume to move it aside and recompute its runs")
            bad = p.with_name(p.name + ".corrupt")
            os.replace(p, bad)
            on_corrupt(bad, reason)
            continue
        covered[first:stop] = True
        out.append((first, count, p))
    return out


def covered_runs(scan: list, n_runs: int) -> np.ndarray:
    """Mask of the runs [-] that finished task files cover.

    Parameters
    ----------
    scan : list
        (first, count, path) of each finished task (:func:`scan_tasks`).
    n_runs : int
        Runs of the sweep.
    """
    mask = np.zeros(n_runs, bool)
    for first, count, _ in scan:
        mask[first:first + count] = True
    return mask


def write_task(store: Path, result: dict) -> None:
    """Atomically write one task's arrays (temporary file, fsync, rename)."""
    path = task_path(store, int(result["first"]), int(result["count"]))
    tmp = path.with_name(path.name + ".tmp")
    try:
        with open(tmp, "wb") as f:
            np.savez(f, **{k: np.asarray(v) for k, v in result.items()})
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError as e:
        raise SweepError(f"--store {str(store)!r}: cannot write task file {path.name} "
                         f"({e.strerror or e}); the finished tasks are kept") from None


VARIABLES = {
    # name: (dims after the run dims, units, long name)
    "grade_G": (("checkpoint",), "mm/s", "ISO 1940-1 balance grade at the checkpoint"),
    "residual_unbalance": (("checkpoint",), "kg*m", "residual unbalance at the checkpoint"),
    "ball_angle": (("checkpoint", "ball"), "rad", "ball angle from the unbalance, in (-pi, pi]; NaN for a ball the cell does not have"),
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


def history_times(plan: Plan) -> np.ndarray:
    """The decimated history times [s] of the sweep (empty without [outputs] history_dt)."""
    dt = plan.spec.history_dt
    return (np.arange(0.0, plan.cells[0].spin.duration + 1e-12, dt) if dt > 0 else np.zeros(0))


def _expected(plan: Plan) -> tuple[list, dict]:
    """Names of the per-run variables of a task file and their shapes after the run axis."""
    sizes = {"checkpoint": plan.checkpoints.size, "ball": plan.n_balls,
             "history_time": history_times(plan).size}
    names = [n for n, (dims, _, _) in VARIABLES.items()
             if not ("history_time" in dims and not sizes["history_time"])]
    return names, {n: tuple(sizes[d] for d in VARIABLES[n][0]) for n in names}


def _start_angle_coord(plan: Plan) -> tuple:
    """The ``start_angle`` coordinate: (sample, ball) for one ball count; with a
    ``balancer.n_balls`` grid axis (balancer__n_balls, sample, ball), NaN for the balls a
    count does not have."""
    attrs = {"units": "rad", "long_name": "ball start angle from the unbalance"}
    if len(plan.angles) == 1:
        return ("sample", "ball"), plan.start_angles, attrs
    axis = next(a for a in plan.spec.grid if a.path == "balancer.n_balls")
    out = np.full((len(axis.si), plan.n_samples, plan.n_balls), np.nan)
    for k, n in enumerate(axis.si):
        out[k, :, :int(n)] = plan.angles[int(n)]
    return (axis.dim, "sample", "ball"), out, attrs


def assemble(plan: Plan, store: Path, allow_partial: bool = True, scan: list | None = None):
    """The sweep as one xarray.Dataset (dims: grid axes..., sample[, checkpoint, ball,
    history_time]); runs of unfinished tasks are NaN (status -1) if allow_partial."""
    import xarray as xr

    spec = plan.spec
    n_s = plan.n_samples
    n_runs = plan.n_runs
    cps = plan.checkpoints
    hist_t = history_times(plan)
    names, shapes = _expected(plan)
    data = {}
    for name in names:
        fill = FILL.get(name, np.nan)
        data[name] = np.full((n_runs,) + shapes[name], fill,
                             dtype=np.int64 if name in FILL else float)
    if scan is None:
        scan = scan_tasks(store, plan)
    for first, count, p in scan:
        try:
            with np.load(p) as z:
                for name in data:
                    data[name][first:first + count] = z[name]
        except Exception as e:   # BadZipFile, EOFError, KeyError, a shape that does not fit
            raise SweepError(f"task file {str(p)!r} is corrupt ({type(e).__name__}); rerun the "
                             "sweep with --resume to recompute its runs") from None
    missing = int(n_runs - covered_runs(scan, n_runs).sum())
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
    coords["ball"] = ("ball", np.arange(plan.n_balls))
    coords["start_angle"] = _start_angle_coord(plan)
    if hist_t.size:
        coords["history_time"] = ("history_time", hist_t, {"units": "s"})
    dvars = {}
    for name, arr in data.items():
        dims, units, long = VARIABLES[name]
        dvars[name] = (tuple(grid_dims) + ("sample",) + dims,
                       arr.reshape(run_shape + arr.shape[1:]), {"units": units, "long_name": long})
    ds = xr.Dataset(dvars, coords=coords)
    ds.attrs.update({
        "sweep_name": spec.name, "sweep_digest": spec.digest(), "sweep_identity": identity(plan),
        "sweep_spec": spec.canonical(),
        "autobalance_version": __version__, "base": spec.base,
        "monte_carlo": spec.mc_kind, "n_runs": n_runs, "n_missing_runs": missing,
        "nominal_speed_rad_s": float(plan.cells[0].spin.nominal_speed),
    })
    return ds


def write_result(ds: xr.Dataset, store: Path) -> Path:
    """Write the assembled dataset as Zarr, replacing an older assembly: written to a
    temporary directory first, then swapped in (the old one is removed only after the swap)."""
    path = Path(store) / "result.zarr"
    tmp = Path(store) / "result.zarr.tmp"
    old = Path(store) / "result.zarr.old"
    for p in (tmp, old):
        if p.exists():
            shutil.rmtree(p)
    try:
        ds.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2)
        if path.exists():
            os.replace(path, old)
        os.replace(tmp, path)
    except OSError as e:
        raise SweepError(f"--store {str(store)!r}: cannot write result.zarr ({e.strerror or e}); "
                         "the task files are kept: rerun with --resume") from None
    if old.exists():
        shutil.rmtree(old, ignore_errors=True)
    return path
