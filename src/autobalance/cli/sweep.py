"""``autobalance sweep``: a grid / Monte-Carlo sweep into a durable, resumable store.

Exit codes: 2 for a bad description, store or option; 1 when the sweep was aborted (lost
scheduler, dead workers: the store keeps every finished task); 128 + the signal number when it
was interrupted (Ctrl-C, SIGTERM: finished tasks kept).
"""
from __future__ import annotations

import os
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated, Iterator

import typer

from .common import (ExecutorOpt, JsonOpt, PlotOpt, SchedulerOpt, WorkersOpt, check_executor,
                     check_grade, check_plot, check_workers, fail, guard, print_json,
                     quiet_dask_logs)

#: Figure formats of ``sweep --plot``.
PLOT_SUFFIXES = (".png", ".svg", ".pdf")


@contextmanager
def _sweep_errors() -> Iterator[None]:
    """The sweep's own errors -> one line on stderr and the exit code of the module docstring."""
    from ..sweep import SweepAborted, SweepError, SweepInterrupted

    try:
        yield
    except SweepError as e:
        fail(str(e))
    except SweepInterrupted as e:       # Ctrl-C / SIGTERM: finished tasks kept
        fail(str(e), 128 + int(e.signal))
    except SweepAborted as e:           # lost scheduler, dead workers: store intact
        fail(str(e), 1)
    except KeyboardInterrupt:           # before the sweep started: nothing was run
        fail("interrupted before the first task; nothing was changed", 130)


def sweep_cmd(spec: Annotated[Path, typer.Argument(metavar="SWEEP.toml",
                                                   help="Sweep description (TOML).")],
              store: Annotated[Path, typer.Option("--store", help="Store directory (durable, "
                                                  "resumable).")],
              scheduler: SchedulerOpt = None, workers: WorkersOpt = None,
              executor: ExecutorOpt = None,
              resume: Annotated[bool, typer.Option(
                  "--resume", help="Continue an interrupted sweep in STORE.")] = False,
              grade: Annotated[float, typer.Option(
                  "--grade", help="Grade limit G [mm/s] for the share in the summary.")] = 16.0,
              plot: PlotOpt = None, json_: JsonOpt = False) -> None:
    """Run a grid / Monte-Carlo sweep into a durable store; print its summary.\f

    Parameters
    ----------
    spec : Path
        The sweep description (TOML).
    store : Path
        Store directory (durable; ``--resume`` continues it).
    scheduler, workers, executor
        Where the sweep runs (the shared options of :mod:`autobalance.cli.common`).
    resume : bool
        Continue an interrupted sweep in ``store``.
    grade : float
        Grade limit G [mm/s] for the share below it in the summary.
    plot : str
        Summary figure (.png, .svg, .pdf).
    json_ : bool
        Print the summary as one JSON object instead of text.
    """
    from ..sweep import load_spec, summary_dict, sweep

    with guard():
        with _sweep_errors():
            check_plot(plot, PLOT_SUFFIXES, example="summary.png")
            check_grade(grade)
            check_workers(workers)      # >= 1, and their processes fit the memory limit
            check_executor(executor)
            sp = load_spec(spec)
            if scheduler or executor == "dask" or os.environ.get("DASK_SCHEDULER_ADDRESS"):
                quiet_dask_logs()
            t0 = time.perf_counter()
            ds = sweep(sp, store, executor=executor, workers=workers, scheduler=scheduler,
                       resume=resume, progress=True)
        wall = time.perf_counter() - t0
        summary = summary_dict(ds, grade)
        summary.update({"store": str(store), "result": str(Path(store) / "result.zarr"),
                        "wall_time_s": wall, "dims": {k: int(v) for k, v in ds.sizes.items()}})
        if plot is not None:
            from ..plotting import plot_sweep

            plot_sweep(ds, grade).savefig(plot, dpi=110)
            summary["plot"] = str(plot)
    if json_:
        print_json(summary)
        return
    typer.echo(f"sweep {summary['name']}: {summary['runs']} runs ({summary['failed_runs']} "
               f"failed) in {wall:.1f} s -> {summary['result']}")
    for c in summary["checkpoints"]:
        typer.echo(f"  t = {c['time_s']:g} s: G p5/p50/p95 = {c['grade_G_p5_mm_s']:.2f} / "
                   f"{c['grade_G_p50_mm_s']:.2f} / {c['grade_G_p95_mm_s']:.2f} mm/s, "
                   f"share <= G{grade:g}: {100 * c['share_below_limit']:.1f} %")
