"""Durable sweep store: one file per finished task, assembled into one xarray.Dataset.

Layout of a store directory::

    STORE/sweep.json                  description, identity, store format, package version and
                                      the content digest of result.zarr (replaced atomically)
    STORE/lock                        held (flock) by the one process working on the store
    STORE/tasks/r000000040-000000048.npz   results of runs 40..47 with the store's identity and
                                      their content digest (taskfile.py), written to a
                                      temporary name and renamed (os.replace is atomic: a
                                      killed sweep leaves whole files only)
    STORE/result.zarr                 the assembled dataset (written when every run is done)

Task files are keyed by the runs they hold, not by their position in a task list, so a store
does not depend on ``batch_size`` or on how the runs were grouped: resuming with another batch
size runs exactly the runs that are missing.

A store is tied to its *identity*: a digest of the description and of every resolved value
that determines its results (each grid cell's system, profile, initial state and options, as
built from the base config's contents, the start angles, the package version and the digest of
the code that computes the runs, :func:`code_digest`). A base config file enters the
description by its path relative to the sweep file (``spec.load_spec``), so a sweep file moved
together with its base is the same sweep, while an edited base is another (its values are in
the identity). Opening a store with anything else raises StoreMismatch, never overwrites. One
process at a time works on a store (an exclusive ``flock`` on STORE/lock, released by the
kernel when the process dies, so a stale lock after ``kill -9`` is never an obstacle).

Every read is verified: each task file against its content digest and the store's identity
(taskfile.py), result.zarr against the digest of its files recorded in sweep.json
(:func:`result_digest`). A resume reassembles a result that does not match from the task files;
:func:`read_result` refuses it in one line.
"""
from __future__ import annotations

import errno
import fcntl
import functools
import hashlib
import json
import os
import shutil
import socket
import time
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

from .. import __version__
from ..config import UNIT_LABEL
from .plan import Plan
from .spec import SweepError
from .taskfile import (FILL, VARIABLES, _task_files, covered_runs, expected, history_times,
                       load_tasks, scan_tasks, task_path, write_task)

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["FILL", "STORE_FORMAT", "VARIABLES", "StoreBusy", "StoreLock", "StoreMismatch",
           "assemble", "check_identity", "check_store_path", "code_digest", "covered_runs",
           "history_times", "identity", "init_store", "read_result", "result_digest",
           "scan_tasks", "task_path", "write_result", "write_task"]

#: The layout of the files of a store: 2 = task files with the store's identity and a content
#: digest, result.zarr with its digest in sweep.json. A store of another format is refused.
STORE_FORMAT = 2


class StoreMismatch(SweepError):
    """The store was made by another sweep description, base config or package version."""


class StoreBusy(SweepError):
    """Another process holds the store's lock."""


#: The subpackages whose code computes a run's stored results: a change to any of them is a
#: new store (the version alone stays the same between commits, so a `git pull` that changed the
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
            "code_digest": code_digest(), "store_format": STORE_FORMAT}


def _write_meta(store: Path, meta: dict) -> None:
    """Replace sweep.json atomically (temporary file, fsync, rename)."""
    mpath = Path(store) / "sweep.json"
    tmp = mpath.with_suffix(".tmp")
    with open(tmp, "w") as f:
        f.write(json.dumps(meta, indent=1, sort_keys=True))
        f.flush()
        os.fsync(f.fileno())
    os.replace(tmp, mpath)


def _read_meta(store: Path) -> dict:
    """sweep.json of a store (StoreMismatch, one line, if missing or unreadable)."""
    mpath = Path(store) / "sweep.json"
    if not mpath.exists():
        raise StoreMismatch(f"store {str(store)!r}: no sweep.json; not a sweep store")
    try:
        meta = json.loads(mpath.read_text())
    except (OSError, ValueError):
        raise StoreMismatch(f"--store {str(store)!r}: unreadable sweep.json; refusing to use "
                            "it") from None
    if not isinstance(meta, dict):
        raise StoreMismatch(f"--store {str(store)!r}: unreadable sweep.json; refusing to use it")
    return meta


def _check_format(store: Path, old: dict) -> None:
    """Refuse a store of another :data:`STORE_FORMAT` (one line)."""
    fmt = old.get("store_format", 1 if "identity" in old else 0)
    if fmt == STORE_FORMAT:
        return
    what = ("an earlier store format (task files without content digests or store identity)"
            if not isinstance(fmt, int) or fmt < STORE_FORMAT else f"a later store format ({fmt})")
    raise StoreMismatch(f"--store {str(store)!r} was made by {what}; refusing to mix results "
                        "(start a new store)")


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
            _write_meta(store, meta)
    except BaseException:
        lock.release()
        raise


def check_identity(store: Path, plan: Plan) -> None:
    """Refuse (StoreMismatch, one line) a store whose sweep.json is missing, unreadable, or
    records another package version, store format, description, code or identity than
    ``plan``'s.

    Parameters
    ----------
    store : Path
        The store directory.
    plan : Plan
        The sweep's plan.
    """
    old = _read_meta(store)
    meta = _meta(plan)
    if old.get("autobalance_version") != __version__:
        raise StoreMismatch(f"--store {str(store)!r} was made by autobalance "
                            f"{old.get('autobalance_version')}, this is {__version__}; refusing "
                            "to mix results (start a new store)")
    _check_format(store, old)
    if old.get("digest") != meta["digest"]:
        raise StoreMismatch(f"--store {str(store)!r} was made by a different sweep description "
                            f"(digest {old.get('digest')} != {meta['digest']}); refusing to "
                            "overwrite it (start a new store)")
    if old.get("code_digest") != meta["code_digest"]:
        raise StoreMismatch(f"--store {str(store)!r} was made by other code of autobalance "
                            f"{__version__} (code digest {old.get('code_digest')} != "
                            f"{meta['code_digest']}: the simulator changed since); refusing to mix "
                            "results (start a new store)")
    if old.get("identity") != meta["identity"]:
        raise StoreMismatch(f"--store {str(store)!r} was made from different parameter values "
                            f"with the same description (the base config {meta['spec']['base']!r} "
                            f"or a preset changed; identity {old.get('identity')} != "
                            f"{meta['identity']}); refusing to mix machines (start a new store)")


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
    history_time]) from its task files, each one verified (:func:`taskfile.read_task`).

    Parameters
    ----------
    plan : Plan
        The sweep's plan.
    store : Path
        The store directory.
    allow_partial : bool
        Runs of unfinished tasks are NaN (status -1); False refuses them.
    scan : list, optional
        The task files (:func:`scan_tasks`); scanned here if not given.

    Raises
    ------
    SweepError
        A corrupt task file, or unfinished runs without ``allow_partial`` (one line).
    """
    import xarray as xr

    spec = plan.spec
    n_s = plan.n_samples
    n_runs = plan.n_runs
    cps = plan.checkpoints
    hist_t = history_times(plan)
    names, shapes = expected(plan)
    data = {}
    for name in names:
        fill = FILL.get(name, np.nan)
        data[name] = np.full((n_runs,) + shapes[name], fill,
                             dtype=np.int64 if name in FILL else float)
    if scan is None:
        scan = scan_tasks(store, plan)
    load_tasks(scan, plan, identity(plan), data)       # each file verified (taskfile.py)
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


def result_digest(path: Path) -> str:
    """SHA-256 (hex) of an assembled result: every file below ``path`` (a Zarr directory), by
    its relative path, length and bytes.

    Parameters
    ----------
    path : Path
        The result.zarr directory.
    """
    h = hashlib.sha256()
    root = Path(path)
    for p in sorted(root.rglob("*")):
        if p.is_file():
            data = p.read_bytes()
            h.update(f"{p.relative_to(root).as_posix()}\0{len(data)}\0".encode())
            h.update(data)
    return h.hexdigest()


def write_result(ds: xr.Dataset, store: Path) -> Path:
    """Write the assembled dataset as Zarr, replacing an older assembly, and record its digest
    in sweep.json: written to a temporary directory first, its digest taken, then swapped in
    (the old one is removed only after the swap) and sweep.json replaced atomically. A kill in
    between leaves a result that does not match the digest: the next resume reassembles it.

    Parameters
    ----------
    ds : xarray.Dataset
        The assembled sweep (:func:`assemble`).
    store : Path
        The store directory (its lock held).
    """
    path = Path(store) / "result.zarr"
    tmp = Path(store) / "result.zarr.tmp"
    old = Path(store) / "result.zarr.old"
    for p in (tmp, old):
        if p.exists():
            shutil.rmtree(p)
    try:
        ds.to_zarr(tmp, mode="w", consolidated=True, zarr_format=2)
        digest = result_digest(tmp)
        if path.exists():
            os.replace(path, old)
        os.replace(tmp, path)
        meta = _read_meta(store)
        meta["result_digest"] = digest
        _write_meta(store, meta)
    except OSError as e:
        raise SweepError(f"--store {str(store)!r}: cannot write result.zarr ({e.strerror or e}); "
                         "the task files are kept: rerun with --resume") from None
    if old.exists():
        shutil.rmtree(old, ignore_errors=True)
    return path


def read_result(store: Path):
    """The assembled result of a finished store, verified against the digest in sweep.json.

    Parameters
    ----------
    store : Path
        The store directory.

    Returns
    -------
    xarray.Dataset
        Loaded into memory.

    Raises
    ------
    StoreMismatch
        A store of an earlier format (one line).
    SweepError
        No result.zarr, or one that does not match its recorded digest (edited, damaged, or
        written by a process killed before it recorded the digest) or cannot be read (one
        line; ``--resume`` assembles it again from the task files).
    """
    import xarray as xr

    store = Path(store)
    meta = _read_meta(store)
    _check_format(store, meta)
    path = store / "result.zarr"
    if not path.is_dir():
        raise SweepError(f"store {str(store)!r} is not assembled yet (no result.zarr); run it "
                         "with --resume")
    recorded = meta.get("result_digest")
    if recorded is None or result_digest(path) != recorded:
        raise SweepError(f"{str(path)!r} does not match the digest recorded in sweep.json "
                         "(edited or damaged); rerun the sweep with --resume to assemble it "
                         "again from the task files")
    try:
        return xr.open_zarr(path).load()
    except Exception as e:   # the files are those written, so the environment (memory, I/O)
        raise SweepError(f"{str(path)!r} is unreadable ({type(e).__name__}); rerun the sweep "
                         "with --resume to assemble it again from the task files") from None
