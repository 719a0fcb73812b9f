"""Run a sweep's tasks: serially, on local processes (default), or on a Dask cluster.

Every executor runs the same pure function ``plan.run_task`` on the same payloads, and the
parent process alone writes the results (one atomic file per task, store.py). Results are
therefore bit-identical across executors, and a lost worker only costs the tasks it held
(Dask reschedules them; an interrupted sweep resumes from the files on disk).
"""
from __future__ import annotations

import os
import sys
import time
from pathlib import Path

from ..models import SimOptions
from .plan import Plan, make_plan, run_task, task_payload
from .spec import SweepError, SweepSpec, load_spec
from .store import assemble, done_tasks, init_store, write_result, write_task

EXECUTORS = ("serial", "local", "dask")


class Progress:
    """A one-line progress bar with rate and ETA on stderr (a line per 10 % when not a tty)."""

    def __init__(self, total_runs: int, done_runs: int = 0, enabled: bool = True, stream=None):
        self.total = total_runs
        self.start_done = done_runs
        self.done = done_runs
        self.t0 = time.perf_counter()
        self.stream = stream or sys.stderr
        self.enabled = enabled
        self.tty = hasattr(self.stream, "isatty") and self.stream.isatty()
        self._last_decile = -1

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
        elif int(frac * 10) != self._last_decile:
            self._last_decile = int(frac * 10)
            self.stream.write(line + "\n")
            self.stream.flush()


def _init_worker() -> None:
    """One numba thread per worker process (the processes already use every core)."""
    import numba

    numba.set_num_threads(1)


def _run_serial(payloads, on_result):
    for p in payloads:
        on_result(run_task(p))


def _run_local(payloads, on_result, workers: int):
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor, as_completed

    ctx = mp.get_context("spawn")
    with ProcessPoolExecutor(max_workers=workers, mp_context=ctx,
                             initializer=_init_worker) as ex:
        futs = [ex.submit(run_task, p) for p in payloads]
        for f in as_completed(futs):
            on_result(f.result())


def _run_dask(payloads, on_result, address: str):
    from distributed import Client, as_completed

    with Client(address, set_as_default=False) as client:
        client.run(_init_worker)
        futs = [client.submit(run_task, p, pure=False, retries=3) for p in payloads]
        # the client is not the default one: as_completed needs its loop explicitly
        for f in as_completed(futs, loop=client.loop):
            on_result(f.result())
            f.release()


def sweep(spec: SweepSpec | str | Path, store: str | Path, *, executor: str | None = None,
          workers: int | None = None, scheduler: str | None = None, resume: bool = False,
          progress: bool = True, options: SimOptions | None = None, assemble_result: bool = True):
    """Run a sweep into a durable store and return the assembled xarray.Dataset.

    Parameters
    ----------
    spec : SweepSpec or path
        The sweep description (or a TOML file).
    store : path
        Store directory; refused if it holds another sweep or exists without ``resume``.
    executor : str
        "serial", "local" (processes on this machine, the default) or "dask" (the default when
        ``scheduler`` or DASK_SCHEDULER_ADDRESS is given).
    workers : int
        Local processes (default: all cores).
    scheduler : str
        Dask scheduler address, e.g. "tcp://127.0.0.1:8786".
    resume : bool
        Continue an interrupted sweep: finished tasks are kept, the others are run.
    options : SimOptions
        Override the numerical options of the base config.
    """
    if not isinstance(spec, SweepSpec):
        spec = load_spec(spec)
    scheduler = scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS") or None
    executor = executor or ("dask" if scheduler else "local")
    if executor not in EXECUTORS:
        raise SweepError(f"executor = {executor!r}: must be one of {list(EXECUTORS)}")
    if executor == "dask" and not scheduler:
        raise SweepError("executor = 'dask' needs --scheduler ADDRESS (or DASK_SCHEDULER_ADDRESS)")
    if workers is not None and (isinstance(workers, bool) or int(workers) != workers or workers < 1):
        raise SweepError(f"workers = {workers!r}: must be an integer >= 1")
    store = Path(store)
    plan = make_plan(spec)
    init_store(store, spec, resume)
    done = done_tasks(store, len(plan.tasks))
    todo = [k for k in range(len(plan.tasks)) if k not in done]
    done_runs = sum(plan.tasks[k][1] for k in done)
    bar = Progress(plan.n_runs, done_runs, enabled=progress)
    payloads = (task_payload(plan, k, options) for k in todo)

    def on_result(res):
        write_task(store, res)
        bar.update(len(res["status"]))

    if todo:
        if executor == "serial":
            _run_serial(payloads, on_result)
        elif executor == "local":
            _run_local(list(payloads), on_result, workers or os.cpu_count() or 1)
        else:
            _run_dask(list(payloads), on_result, scheduler)
    ds = assemble(plan, store)
    if assemble_result:
        write_result(ds, store)
    return ds


def open_sweep(store: str | Path, spec: SweepSpec | str | Path | None = None):
    """The dataset of a (possibly unfinished) store: result.zarr if complete, else assembled
    from the task files (unfinished runs NaN, attrs['n_missing_runs'] > 0)."""
    import json

    import xarray as xr

    store = Path(store)
    res = store / "result.zarr"
    if res.exists() and spec is None:
        return xr.open_zarr(res).load()
    if spec is None:
        meta = json.loads((store / "sweep.json").read_text())
        raise SweepError(f"store {str(store)!r} is not assembled yet; pass the description "
                         f"{meta.get('name')!r} to open_sweep or run it with --resume")
    if not isinstance(spec, SweepSpec):
        spec = load_spec(spec)
    plan: Plan = make_plan(spec)
    return assemble(plan, store)
