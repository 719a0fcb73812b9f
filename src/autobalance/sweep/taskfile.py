"""Task files of a sweep store: one ``.npz`` per finished range of runs, written atomically, and
verified whenever it is read.

A task file ``STORE/tasks/rFIRST-STOP.npz`` holds the variables of :data:`VARIABLES` for the
runs FIRST .. STOP - 1, their range (``first``, ``count``), and ``integrity``: two strings,

* the identity of the store that computed it (:func:`autobalance.sweep.store.identity`, the
  digest of everything that determines the results): a file copied from another store (the
  same run range of another base config or machine) carries another identity;
* the SHA-256 of its contents (:func:`content_digest`): the run range of its name, that
  identity, and every variable's name, dtype, shape and bytes. An array edited and saved
  again, or a file renamed to another range, no longer matches it.

A file that fails a check (unreadable, wrong runs or shapes, another identity, a content that
does not match its digest) is *corrupt*: a resume moves it aside to ``NAME.corrupt`` and
computes its runs again; anything else that reads it refuses it in one line. The digests catch
damage, mix-ups and edits made without this code; they are not a signature (anyone who can
run this code can write a file that passes).
"""
from __future__ import annotations

import hashlib
import os
import re
from pathlib import Path
from typing import TYPE_CHECKING, Callable

import numpy as np

from ..core.layout import RunStatus
from .spec import SweepError

if TYPE_CHECKING:
    from .plan import Plan

__all__ = ["FILL", "VARIABLES", "content_digest", "covered_runs", "expected", "history_times",
           "load_tasks", "read_task", "scan_tasks", "task_path", "write_task"]

STATUS_NAMES = ", ".join(f"{int(s)} {s.label}" for s in RunStatus
                         if s <= RunStatus.NON_FINITE or s is RunStatus.OUTSIDE_MODEL)
_TASK_RE = re.compile(r"r(\d{9})-(\d{9})\.npz")

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
#: The member of a task file holding (store identity, content digest), and those of its range.
INTEGRITY = "integrity"
_RANGE = ("first", "count")


def task_path(store: Path, first: int, count: int) -> Path:
    """File of the runs first .. first + count - 1.

    Parameters
    ----------
    store : Path
        The store directory.
    first : int
        First run.
    count : int
        Number of runs.
    """
    return Path(store) / "tasks" / f"r{first:09d}-{first + count:09d}.npz"


def history_times(plan: Plan) -> np.ndarray:
    """The decimated history times [s] of the sweep (empty without [outputs] history_dt).

    Parameters
    ----------
    plan : Plan
        The sweep's plan.
    """
    dt = plan.spec.history_dt
    return (np.arange(0.0, plan.cells[0].spin.duration + 1e-12, dt) if dt > 0 else np.zeros(0))


def expected(plan: Plan) -> tuple[list, dict]:
    """Names of the per-run variables of a task file and their shapes after the run axis.

    Parameters
    ----------
    plan : Plan
        The sweep's plan.
    """
    sizes = {"checkpoint": plan.checkpoints.size, "ball": plan.n_balls,
             "history_time": history_times(plan).size}
    names = [n for n, (dims, _, _) in VARIABLES.items()
             if not ("history_time" in dims and not sizes["history_time"])]
    return names, {n: tuple(sizes[d] for d in VARIABLES[n][0]) for n in names}


def content_digest(first: int, count: int, identity: str, arrays: dict) -> str:
    """SHA-256 (hex) of a task's contents: its run range, its store's identity and each
    variable's name, dtype, shape and bytes, by name.

    Parameters
    ----------
    first : int
        First run.
    count : int
        Number of runs.
    identity : str
        The identity of the store that computed it.
    arrays : dict
        Name -> array of its variables (``first``, ``count`` and ``integrity`` are left out).
    """
    h = hashlib.sha256(f"r{first:09d}-{first + count:09d}\0{identity}\0".encode())
    for name in sorted(arrays):
        if name in _RANGE or name == INTEGRITY:
            continue
        a = np.ascontiguousarray(arrays[name])
        h.update(f"{name}\0{a.dtype.str}\0{a.shape}\0".encode())
        h.update(a.tobytes())
    return h.hexdigest()


def write_task(store: Path, result: dict, identity: str) -> None:
    """Atomically write one task's arrays with their integrity record (temporary file, fsync,
    rename).

    Parameters
    ----------
    store : Path
        The store directory.
    result : dict
        The task's arrays (``first``, ``count`` and :data:`VARIABLES`).
    identity : str
        The store's identity (:func:`autobalance.sweep.store.identity`).
    """
    first, count = int(result["first"]), int(result["count"])
    arrays = {k: np.asarray(v) for k, v in result.items()}
    arrays[INTEGRITY] = np.array([identity, content_digest(first, count, identity, arrays)])
    path = task_path(store, first, count)
    tmp = path.with_name(path.name + ".tmp")
    try:
        with open(tmp, "wb") as f:
            np.savez(f, **arrays)
            f.flush()
            os.fsync(f.fileno())
        os.replace(tmp, path)
    except OSError as e:
        raise SweepError(f"--store {str(store)!r}: cannot write task file {path.name} "
                         f"({e.strerror or e}); the finished tasks are kept") from None


def read_task(path: Path, first: int, count: int, plan: Plan, identity: str) -> dict:
    """The variables of a task file, verified: its content digest (which binds them to the
    run range of its name), its store's identity, their shapes.

    Parameters
    ----------
    path : Path
        The task file.
    first : int
        First run its name says it holds.
    count : int
        Number of runs its name says it holds.
    plan : Plan
        The sweep's plan (the variables and their shapes).
    identity : str
        The identity of the store reading it.

    Returns
    -------
    dict
        Name -> array of the variables of :func:`expected`.

    Raises
    ------
    ValueError
        A check failed (the message says which); unreadable files raise what ``np.load``
        raises (BadZipFile, EOFError, KeyError, OSError).
    """
    names, shapes = expected(plan)
    with np.load(path, allow_pickle=False) as z:
        if INTEGRITY not in z.files:
            raise ValueError("it has no content digest or store identity")
        record = z[INTEGRITY]
        arrays = {k: z[k] for k in z.files if k not in _RANGE and k != INTEGRITY}
    if record.shape != (2,) or record.dtype.kind != "U":
        raise ValueError(f"its integrity record has shape {record.shape}")
    theirs, digest = str(record[0]), str(record[1])
    if content_digest(first, count, theirs, arrays) != digest:
        raise ValueError("its contents do not match its content digest (edited, damaged or "
                         "renamed)")
    if theirs != identity:
        raise ValueError(f"it was made by another store (identity {theirs[:16]} != {identity})")
    for name in names:
        if name not in arrays:
            raise KeyError(f"{name} is not in it")
        a = arrays[name]
        if a.shape != (count,) + shapes[name]:
            raise ValueError(f"{name} has shape {a.shape}")
    return {name: arrays[name] for name in names}


def _task_files(store: Path) -> list:
    d = Path(store) / "tasks"
    return sorted(p for p in d.glob("r*.npz")) if d.is_dir() else []


def _reason(e: Exception) -> str:
    """One short line of why a task file was rejected."""
    text = " ".join(str(e).split())[:120]
    return text if isinstance(e, ValueError) and text else f"{type(e).__name__}: {text}".rstrip(": ")


def scan_tasks(store: Path, plan: Plan, identity: str | None = None, *,
               on_corrupt: Callable[[Path, str], object] | None = None) -> list:
    """The finished task files as (first, count, path), checked against the plan.

    A file whose name is not a range of this plan's runs, or overlaps another, is *corrupt*.
    With ``on_corrupt`` (resume, where the scan decides what to run) every file is also read and
    verified (:func:`read_task`); a corrupt one is renamed to ``NAME.corrupt`` (kept for
    inspection, never deleted) and ``on_corrupt(path, reason)`` is called, so that its runs are
    computed again. Without it a SweepError names the file, and the contents are verified when
    :func:`autobalance.sweep.store.assemble` reads them (each file is read once).

    Parameters
    ----------
    store : Path
        The store directory.
    plan : Plan
        The sweep's plan.
    identity : str, optional
        The store's identity (required with ``on_corrupt``).
    on_corrupt : callable, optional
        Called with (new path, reason) for each file moved aside.
    """
    out = []
    covered = np.zeros(plan.n_runs, bool)
    for p in _task_files(store):
        m = _TASK_RE.fullmatch(p.name)
        reason = None
        if not m:
            reason = "unexpected file name"
        else:
            first, stop = int(m.group(1)), int(m.group(2))
            if not (0 <= first < stop <= plan.n_runs):
                reason = f"runs {first}..{stop - 1} are outside this sweep's {plan.n_runs} runs"
            elif covered[first:stop].any():
                reason = "its runs overlap another task file"
            elif on_corrupt is not None:
                try:
                    read_task(p, first, stop - first, plan, identity)
                except Exception as e:   # BadZipFile, EOFError, KeyError, ValueError, OSError
                    reason = _reason(e)
        if reason is not None:
            if on_corrupt is None:
                raise SweepError(f"task file {str(p)!r} is corrupt ({reason}); rerun the sweep "
                                 "with --resume to move it aside and recompute its runs")
            bad = p.with_name(p.name + ".corrupt")
            os.replace(p, bad)
            on_corrupt(bad, reason)
            continue
        covered[first:stop] = True
        out.append((first, stop - first, p))
    return out


def load_tasks(scan: list, plan: Plan, identity: str, data: dict) -> None:
    """Read every scanned task file into ``data`` (name -> (n_runs, ...) array), verified.

    Parameters
    ----------
    scan : list
        (first, count, path) of each task (:func:`scan_tasks`).
    plan : Plan
        The sweep's plan.
    identity : str
        The store's identity.
    data : dict
        The arrays to fill, run-major.

    Raises
    ------
    SweepError
        A corrupt task file (one line naming it and why).
    """
    for first, count, p in scan:
        try:
            arrays = read_task(p, first, count, plan, identity)
        except Exception as e:   # BadZipFile, EOFError, KeyError, ValueError, OSError
            raise SweepError(f"task file {str(p)!r} is corrupt ({_reason(e)}); rerun the sweep "
                             "with --resume to move it aside and recompute its runs") from None
        for name in data:
            data[name][first:first + count] = arrays[name]


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
