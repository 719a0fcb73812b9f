"""Run a sweep's tasks: serially, on local processes (default), or on a Dask cluster.

Every executor runs the same pure function ``task.run_task`` on the same payloads, and the
parent process alone writes the results (one atomic file per task, store.py). Results are
therefore bit-identical across executors, and a lost worker only costs the tasks it held
(Dask reschedules them; an interrupted sweep resumes from the files on disk).
"""
from __future__ import annotations

import dataclasses

import os
import signal
import sys
import threading
import time
from pathlib import Path
from typing import TYPE_CHECKING, TextIO

from ..models import InitialState, MotorDrive, SimOptions, SpeedProfile, System
from .plan import Plan, make_plan
from .scheduler import connect, parse_address
from .task import run_task, task_payload
from .spec import SweepError, SweepSpec, as_spec, load_spec
from .store import (StoreLock, _read_meta, assemble, check_identity, check_store_path,
                    covered_runs, identity, init_store, read_result, scan_tasks, write_result,
                    write_task)

if TYPE_CHECKING:
    from ..config import Config

EXECUTORS = ("serial", "local", "dask")


class Progress:
    """A one-line progress bar with rate and ETA on stderr; when the stream is not a terminal
    (a log, a pipe), one line per :attr:`STEPS`-th of the runs (every 5 %) and the last."""

    #: Lines of a non-terminal stream over the whole sweep (a line per 100 / STEPS %).
    STEPS = 20

    def __init__(self, total_runs: int, done_runs: int = 0, enabled: bool = True,
                 stream: TextIO | None = None):
        self.total = total_runs
        self.start_done = done_runs
        self.done = done_runs
        self.t0 = time.perf_counter()
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self._last_step = -1

    def update(self, n: int) -> None:
        self.done += n
        if not self.enabled:
            return
        el = time.perf_counter() - self.t0
        new = self.done - self.start_done
        rate = new / el if el > 0 else 0.0
        eta = (self.total - self.done) / rate if rate > 0 else float("nan")
        frac = self.done / self.total if self.total else 1.0
        bar = "#" * int(30 * frac)
        line = (f"[{bar:<30}] {self.done}/{self.total} runs  {rate:7.1f} runs/s  "
                f"ETA {eta:6.1f} s")
        if self.tty:
            self.stream.write("\r" + line)
            if self.done >= self.total:
                self.stream.write("\n")
            self.stream.flush()
        elif (k := self.done * self.STEPS // max(self.total, 1)) != self._last_step:
            self._last_step = k
            self.stream.write(line + "\n")
            self.stream.flush()


class SweepAborted(RuntimeError):
    """A sweep stopped before its end (lost scheduler, dead workers); the store keeps every
    finished task. One-line message; the CLI exits with code 1."""

    def __init__(self, message: str):
        super().__init__(" ".join(str(message).split()))


class SweepInterrupted(KeyboardInterrupt):
    """Ctrl-C (SIGINT) or SIGTERM: the workers were stopped, the finished tasks are kept.
    ``signal`` is the signal number; the CLI exits with 128 + signal. ``resumable`` is False
    when the store was temporary (a study without ``--store``): nothing was kept, and the
    message says so instead of offering a resume. A KeyboardInterrupt, so that no ``except
    Exception`` on the way up (a report that records failed targets and goes on) swallows
    it."""

    def __init__(self, message: str, sig: int = signal.SIGINT, resumable: bool = True):
        super().__init__(" ".join(str(message).split()))
        self.signal = sig
        self.resumable = resumable


def _die_with_parent() -> None:
    """Linux: have the kernel SIGKILL this process when its parent dies (prctl
    PR_SET_PDEATHSIG), so a ``kill -9`` of the sweep leaves no worker behind."""
    try:
        import ctypes

        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(1, signal.SIGKILL, 0, 0, 0)    # PR_SET_PDEATHSIG = 1
    except (OSError, AttributeError):
        pass


def _init_worker(parent: int | None = None) -> None:
    """Worker set-up: one numba thread per process (the processes already use every core);
    Ctrl-C is the parent's to handle (it stops the workers), and a worker dies with its
    parent."""
    import numba

    numba.set_num_threads(1)
    if parent is not None:
        signal.signal(signal.SIGINT, signal.SIG_IGN)
        _die_with_parent()
        if os.getppid() != parent:          # the parent died before the prctl took effect
            os._exit(1)


def _run_serial(payloads, on_result):
    for p in payloads:
        on_result(run_task(p))


def _stop_pool(ex) -> None:
    """Kill the pool's processes now (Ctrl-C, a write error): finished tasks are already on
    disk, the ones running are lost and rerun on --resume."""
    procs = list(getattr(ex, "_processes", {}).values())
    manager = getattr(ex, "_executor_manager_thread", None)    # shutdown() forgets it
    _quiet_exit_wakeup(getattr(ex, "_executor_manager_thread_wakeup", None))
    for p in procs:
        try:
            p.kill()
        except (OSError, AttributeError, ValueError):
            pass
    ex.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        try:
            p.join(timeout=5)
        except (OSError, AttributeError, ValueError, AssertionError):
            pass
    # let the pool's manager thread finish closing its wake-up pipe (prompt exit in the common
    # case; _quiet_exit_wakeup covers a manager still closing when the interpreter exits). The
    # thread is taken before shutdown(), which sets the pool's reference to None: read after
    # it, the join never ran, and a loaded machine failed test_sweep_faults' check of the pipe
    if manager is not None:
        manager.join(timeout=5)


def _quiet_exit_wakeup(wakeup) -> None:
    """Make a stopped pool's wake-up pipe safe to poke at interpreter exit.

    concurrent.futures' exit hook (Python 3.11, ``_python_exit``) calls ``wakeup()`` on every
    pool's pipe without the pool's lock: it checks ``_closed`` and then writes, while the pool's
    manager thread may close the pipe in between. After a Ctrl-C or a write error the manager is
    often still closing, and the write failed with "Exception ignored ... OSError: [Errno 9] Bad
    file descriptor" after our one-line error (seen under load and on a quiet machine). A closed
    pipe needs no wake-up, so this pool's ``wakeup`` ignores a pipe closed under it."""
    if wakeup is None:
        return
    method = type(wakeup).wakeup

    def wakeup_unless_closed(w=wakeup):
        try:
            method(w)
        except (OSError, ValueError):
            pass

    wakeup.wakeup = wakeup_unless_closed


_GUARD_HINT = ("a script that calls autobalance.sweep() must do so under "
               "`if __name__ == \"__main__\":` (workers start with 'spawn' and import the "
               "script), or use executor='serial'")


def _run_local(payloads, on_result, workers: int, kept):
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed
    from concurrent.futures.process import BrokenProcessPool

    ctx = mp.get_context("spawn")
    ex = ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_init_worker,
                             initargs=(os.getpid(),))
    try:
        # workers are spawned during submit: with SIGINT ignored meanwhile they inherit that
        # disposition, so a Ctrl-C from the terminal (sent to the whole process group) reaches
        # only this process, which stops them
        main = threading.current_thread() is threading.main_thread()
        old = signal.signal(signal.SIGINT, signal.SIG_IGN) if main else None
        try:
            futs = [ex.submit(run_task, p) for p in payloads]
        finally:
            if old is not None:
                signal.signal(signal.SIGINT, old)
        for f in as_completed(futs):
            on_result(f.result())
    except BrokenProcessPool:
        _stop_pool(ex)
        raise SweepAborted(f"the local worker processes died ({kept()}); if this ran from a "
                           f"script, {_GUARD_HINT}; rerun with --resume to continue") from None
    except BaseException:
        _stop_pool(ex)
        raise
    ex.shutdown(wait=True)


class _WriteFailed(Exception):
    """Wraps an error of on_result so it is not mistaken for a lost scheduler."""


def _run_dask(payloads, on_result, client, kept):
    from distributed import as_completed

    futs = []
    try:
        client.run(_init_worker)
        futs = [client.submit(run_task, p, pure=False, retries=3) for p in payloads]
        # the client is not the default one: as_completed needs its loop explicitly
        for f in as_completed(futs, loop=client.loop):
            res = f.result()
            try:
                on_result(res)
            except BaseException as e:
                raise _WriteFailed() from e
            f.release()
    except _WriteFailed as w:
        _cancel(client, futs)
        raise w.__cause__ from None
    except (KeyboardInterrupt, SweepInterrupted):
        _cancel(client, futs)
        raise
    except Exception as e:
        _cancel(client, futs)
        msg = " ".join(str(e).split())[:120] or type(e).__name__
        raise SweepAborted(f"lost the Dask scheduler {client.scheduler.address if client.scheduler else ''}"
                           f" ({type(e).__name__}: {msg}); the store is intact ({kept()}): rerun "
                           "with --resume when the cluster is back") from None


def _cancel(client, futs) -> None:
    try:
        client.cancel(futs, force=True)
    except Exception:
        pass


def _start_line(plan: Plan, n_todo: int, workers: int) -> str:
    """The sweep's start line: what it will compute and where. No time is promised here: the
    progress bar's rate and ETA are measured (a step-count estimate before the first run can be
    off by 100x on stick-slip runs)."""
    return (f"{plan.spec.name}: {n_todo} of {plan.n_runs} runs to compute on {workers} "
            f"worker(s)")


def sweep(spec: SweepSpec | dict | str | Path, store: str | Path, *,
          base: Config | System | None = None,
          spin: SpeedProfile | MotorDrive | dict | None = None,
          initial: InitialState | None = None, executor: str | None = None,
          workers: int | None = None, scheduler: str | None = None, resume: bool = False,
          progress: bool = True, options: SimOptions | None = None, assemble_result: bool = True,
          branch: bool = True, keyed: bool = False):
    """Run a sweep into a durable store and return the assembled xarray.Dataset.

    Parameters
    ----------
    spec : SweepSpec, dict or path
        The sweep description: validated, parsed (``{"sweep": ..., "grid": ...,
        "monte_carlo": ...}``) or a TOML file.
    store : path
        Store directory; refused if it holds another sweep (description, base config contents
        or package version), is in use by another process, or exists without ``resume``.
    base : Config or System, optional
        A base built in Python, for a description (dict or file) without ``sweep.base``:
        a :class:`autobalance.config.Config` (e.g. ``from_models(...)``, or a loaded config
        changed with ``replace_values``), or a :class:`autobalance.System` with ``spin``
        (and ``initial``, ``options``). ``sweep.set`` and every grid value are set on it
        as on a preset; the same models give the same results and the same store identity
        whatever they were built from.
    spin : SpeedProfile, MotorDrive or dict, optional
        The spin of a System base; a dict is a ``[profile]`` table (``{"kind": "tsr",
        "nominal": "167 Hz", ...}``), whose keys can then be grid axes.
    initial : InitialState, optional
        The initial state of a System base.
    executor : str
        "serial", "local" (processes on this machine, the default) or "dask" (the default when
        ``scheduler`` or DASK_SCHEDULER_ADDRESS is given).
    workers : int
        Local processes (default: all cores); only with the local executor (serial: 1).
    scheduler : str
        Dask scheduler address, e.g. "tcp://127.0.0.1:8786": a malformed one is refused at
        once, an unreachable one within seconds (:func:`autobalance.sweep.scheduler.connect`).
    resume : bool
        Continue an interrupted sweep: finished runs are kept, the others are run (whatever
        batch size made them); task files that fail their checks (unreadable, from another
        store, edited) are moved aside and rerun, and a result.zarr that does not match its
        digest is assembled again. A store that does not exist is refused (with ``keyed``, a
        new identity's store is started).
    options : SimOptions
        Override the numerical options of the base config (with a System base: its options).
    assemble_result : bool
        Assemble (and return) the result; False only writes the task files.
    branch : bool
        Run grid cells whose speed profiles agree up to a knot as branches of one history
        (:class:`autobalance.sweep.plan.BranchTask`); False runs every cell on its own. The
        results are the same bit for bit; False is the reference of ``make bench``.
    keyed : bool
        ``store`` is a directory of stores, one per identity (``store / identity``, the digest
        of everything that determines the results): a rerun of the same sweep resumes its own
        store, and one whose machine, options or package version changed starts a new one
        beside it instead of being refused (the studies' stores, e.g. ``make run``'s
        ``out/stores``).

    Raises
    ------
    SweepError
        Bad description, bad store (one line); nothing is computed.
    SweepInterrupted
        Ctrl-C or SIGTERM: the workers are stopped at once, every finished task is kept.
    SweepAborted
        Lost Dask scheduler or dead worker processes; every finished task is kept.
    """
    import multiprocessing as mp

    if getattr(mp.current_process(), "_inheriting", False):
        # a spawned worker importing a script that calls sweep() without a __main__ guard:
        # end this child quietly, the parent reports it in one line
        raise SystemExit(3)
    spec = as_spec(spec, base, spin, initial, options if isinstance(base, System) else None)
    executor, scheduler, where = check_executor(executor, workers, scheduler)
    store = Path(store)
    check_store_path(store)
    if resume and not keyed and not (store / "sweep.json").is_file():
        raise SweepError(f"--resume: there is no sweep store at --store {str(store)!r} to "
                         "continue (no sweep.json); leave out --resume to start it")
    plan = make_plan(spec)
    if options is not None:
        # the override is part of every cell, hence of the store's identity: a resume with
        # other options is refused instead of mixing runs of both in one store
        plan.cells = [dataclasses.replace(c, options=options) for c in plan.cells]
    if keyed:
        store = store / identity(plan)
        check_store_path(store)
    lock = StoreLock(store)
    client = None
    try:
        client = connect(scheduler, where) if executor == "dask" else None
        with _signals_raise():
            return _sweep_locked(plan, store, lock, executor, workers, client, resume,
                                 progress, assemble_result, branch)
    finally:
        lock.release()
        if client is not None:
            try:
                client.close(timeout=5)
            except Exception:
                pass


def check_executor(executor: str | None, workers: int | None = None,
                   scheduler: str | None = None) -> tuple[str, str | None, str]:
    """(executor, scheduler address, where the address came from) of :func:`sweep`'s
    arguments, checked before anything is built (the command line checks its options with
    it before loading the machine): a known executor, a well-formed address for dask
    (:func:`scheduler.parse_address`), and workers only where they apply (local processes; a
    serial sweep has one, a Dask cluster its own).

    Parameters
    ----------
    executor : str or None
        "serial", "local", "dask" or None (dask with a scheduler address, else local).
    workers : int or None
        Local worker processes as given (None: not given).
    scheduler : str or None
        The Dask scheduler address (None: ``DASK_SCHEDULER_ADDRESS`` if set).

    Raises
    ------
    SweepError
        An unknown executor, dask without an address, a malformed address, workers that are
        not an integer >= 1 or given where they do not apply (one line).
    """
    where = "--scheduler" if scheduler else "DASK_SCHEDULER_ADDRESS"
    scheduler = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS") or None
    given = f"--executor {executor}" if executor is not None else f"{where} {scheduler!r}"
    if executor is None:
        executor = "dask" if scheduler else "local"
    if executor not in EXECUTORS:
        raise SweepError(f"--executor = {executor!r}: must be one of {', '.join(EXECUTORS)}")
    if executor == "dask" and not scheduler:
        raise SweepError("--executor = 'dask': needs --scheduler ADDRESS (or "
                         "DASK_SCHEDULER_ADDRESS)")
    if workers is not None and (isinstance(workers, bool) or int(workers) != workers or workers < 1):
        raise SweepError(f"workers = {workers!r}: must be an integer >= 1")
    if workers is not None and executor == "serial" and workers > 1:
        raise SweepError(f"--executor serial with --workers {workers}: conflicting; a serial "
                         "sweep runs in this process, one run after another (leave out "
                         "--workers, or use --executor local)")
    if workers is not None and executor == "dask":
        raise SweepError(f"--workers {workers} with {given}: conflicting; a Dask sweep runs on "
                         "the cluster's own workers (leave out --workers)")
    if executor == "dask":
        parse_address(scheduler, where)
    return executor, scheduler, where


class _signals_raise:
    """While a sweep runs in the main thread, SIGTERM raises SweepInterrupted like Ctrl-C."""

    def __enter__(self):
        self.old = None
        if threading.current_thread() is threading.main_thread():
            def on_term(signum, frame):
                raise SweepInterrupted("terminated", signal.SIGTERM)
            self.old = signal.signal(signal.SIGTERM, on_term)
        return self

    def __exit__(self, *exc):
        if self.old is not None:
            signal.signal(signal.SIGTERM, self.old)


def _sweep_locked(plan, store, lock, executor, workers, client, resume, progress,
                  assemble_result, branch=True):
    init_store(store, plan, resume, lock)
    ident = identity(plan)
    warn = (lambda msg: print(f"warning: {msg}", file=sys.stderr, flush=True))

    def on_corrupt(path, reason):
        warn(f"task file {str(path)!r} was rejected ({reason}): moved aside, its runs are "
             "computed again")

    scan = scan_tasks(store, plan, ident, on_corrupt=on_corrupt)
    covered = covered_runs(scan, plan.n_runs)
    todo_tasks = plan.tasks_for(~covered, branch)
    done_runs = int(covered.sum())
    n_workers = 1 if executor == "serial" else (workers or os.cpu_count() or 1)
    if executor == "dask":
        n_workers = max(len(client.scheduler_info().get("workers", {})), 1)
    if todo_tasks and progress:
        print(_start_line(plan, plan.n_runs - done_runs, n_workers), file=sys.stderr,
              flush=True)
    bar = Progress(plan.n_runs, done_runs, enabled=progress)
    payloads = (task_payload(plan, t) for t in todo_tasks)
    finished = [done_runs]

    def on_result(res):
        for r in res if isinstance(res, list) else [res]:     # a branch task: one per cell
            write_task(store, r, ident)
            finished[0] += len(r["status"])
            bar.update(len(r["status"]))

    def kept():
        return f"{finished[0]} of {plan.n_runs} runs kept in {str(store)!r}"

    try:
        if todo_tasks:
            if executor == "serial":
                _run_serial(payloads, on_result)
            elif executor == "local":
                _run_local(list(payloads), on_result, n_workers, kept)
            else:
                _run_dask(list(payloads), on_result, client, kept)
    except (KeyboardInterrupt, SweepInterrupted) as e:
        sig = getattr(e, "signal", signal.SIGINT)
        what = "terminated (SIGTERM)" if sig == signal.SIGTERM else "interrupted"
        if bar.tty:
            sys.stderr.write("\n")
        raise SweepInterrupted(f"{what}: {kept()}; continue with --resume", sig) from None
    result = Path(store) / "result.zarr"
    if not todo_tasks and result.exists() and assemble_result:
        try:
            return read_result(store)         # checked against its digest in sweep.json
        except SweepError as e:   # edited, damaged or unrecorded: rebuilt from the task files
            warn(f"{str(e).split('; ')[0]}: assembled again from the verified task files")
    ds = assemble(plan, store)
    if assemble_result:
        write_result(ds, store)
    return ds


def open_sweep(store: str | Path, spec: SweepSpec | str | Path | None = None):
    """The dataset of a (possibly unfinished) store.

    Parameters
    ----------
    store : str or Path
        The store directory.
    spec : SweepSpec or path, optional
        Its description. Without it, the finished store's result.zarr, checked against the
        digest recorded in sweep.json (:func:`autobalance.sweep.store.read_result`). With it,
        assembled from the task files, each one verified (unfinished runs NaN,
        ``attrs['n_missing_runs']`` > 0); a store of another identity is refused.

    Raises
    ------
    SweepError
        Not a store, not assembled yet (without ``spec``), a result.zarr or a task file that
        does not match its digest, a store of another format or identity (one line).
    """
    store = Path(store)
    if spec is None:
        if not (store / "result.zarr").exists():
            name = _read_meta(store).get("name")
            raise SweepError(f"store {str(store)!r} is not assembled yet; pass the description "
                             f"{name!r} to open_sweep or run it with --resume")
        return read_result(store)
    if not isinstance(spec, SweepSpec):
        spec = load_spec(spec)
    plan: Plan = make_plan(spec)
    check_identity(store, plan)
    return assemble(plan, store)
