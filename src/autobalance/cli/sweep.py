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

from .common import (DEFAULT_GRADE, ExecutorOpt, GradeOpt, JsonOpt, PlotOpt, SchedulerOpt,
                     UnitsOpt, WorkersOpt, check_distinct, check_executor, check_grade, check_plot,
                     check_workers, class_text, fail, grade_text, guard, print_json,
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
              grade: GradeOpt = DEFAULT_GRADE,
              plot: PlotOpt = None, json_: JsonOpt = False, units: UnitsOpt = None) -> None:
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
        Target grade G [mm/s] for the share below it in the summary.
    plot : str
        Summary figure (.png, .svg, .pdf).
    json_ : bool
        Print the summary as one JSON object instead of text (SI: per checkpoint over all runs
        and per grid cell, :func:`autobalance.sweep.summary_dict`).
    units : str
        Units of the text (default: as written in the base config and the grid).
    """
    from ..sweep import load_spec, summary_dict, sweep

    with guard():
        with _sweep_errors():
            check_plot(plot, PLOT_SUFFIXES, example="summary.png")
            grade = check_grade(grade)
            check_workers(workers)      # >= 1, and their processes fit the memory limit
            check_executor(executor, workers, scheduler)   # --workers only where it applies
            sp = load_spec(spec)
            check_distinct({"--plot": plot}, {"the sweep file": spec,
                                              "the sweep's base config file": sp.base_source})
            shown = _display(sp, units)
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
            from ..atomic import save_figure
            from ..plotting import plot_sweep

            save_figure(plot_sweep(ds, grade), plot, "--plot", dpi=110)
            summary["plot"] = str(plot)
    if json_:
        print_json(summary)
        return
    typer.echo(f"sweep {summary['name']}: {summary['runs']} runs ({summary['failed_runs']} "
               f"failed) in {wall:.1f} s -> {summary['result']}")
    typer.echo(f"  target grade: {grade_text(grade)}")
    cells = summary["cells"]
    if len(cells) > 1:
        typer.echo("  all runs:")
    for c in summary["checkpoints"]:
        typer.echo(("    " if len(cells) > 1 else "  ") + _checkpoint_line(c, grade, shown))
    if len(cells) > 1:
        typer.echo(f"  per grid cell ({len(cells)}):")
        for cell in cells[:MAX_CELL_LINES]:
            where = ", ".join(_coord_text(a, cell, shown, units) for a in summary["grid"])
            failed = f", {cell['failed_runs']} failed" if cell["failed_runs"] else ""
            runs = f"{cell['ok_runs']} run{'s' if cell['ok_runs'] != 1 else ''}"
            typer.echo(f"    {where} ({runs}{failed}):")
            for c in cell["checkpoints"]:
                typer.echo("      " + _checkpoint_line(c, grade, shown))
        if len(cells) > MAX_CELL_LINES:
            typer.echo(f"    ... {len(cells) - MAX_CELL_LINES} more cells (all in --json)")


#: Grid cells printed in the text summary (--json has every cell).
MAX_CELL_LINES = 50


def _display(sp, units):
    """The display units of a sweep: as written in its base config (with sweep.set), or as
    ``--units`` says; SI for a base that cannot be read (the sweep reports that itself)."""
    from ..config import ConfigError, _read, apply_overrides
    from ..config.display import display_units

    raw = None
    if sp.base_config is not None:
        raw = sp.base_config.raw
    else:
        try:
            raw = apply_overrides(_read(sp.base_source)[0], list(sp.overrides))
        except ConfigError:
            pass
    return display_units(raw if isinstance(raw, dict) else None, units)


def _checkpoint_line(c: dict, grade: float, shown) -> str:
    """One checkpoint of a summary: 5/50/95 % grades, class of the 95 % with its interval,
    share <= grade with its interval, and the verdict of the 95 % grade."""
    from ..confidence import interval_text

    p95 = interval_text(*c["grade_G_p95_mm_s_ci"], lambda g: f"{g:.2f} mm/s")
    share = interval_text(*c["share_below_limit_ci"], lambda v: f"{100 * v:.1f} %")
    return (f"t = {shown.fmt(c['time_s'], 'time')}: G p5/p50/p95 = {c['grade_G_p5_mm_s']:.2f} / "
            f"{c['grade_G_p50_mm_s']:.2f} / {c['grade_G_p95_mm_s']:.2f} mm/s (p95 "
            f"{class_text(c['grade_G_p95_mm_s'])}; {p95}), share <= G{grade:g}: "
            f"{100 * c['share_below_limit']:.1f} % ({share}); p95 <= G{grade:g}: "
            f"{c['p95_verdict']}")


#: Config kinds of grid axes that have a display unit (:mod:`autobalance.config.display`).
_DISPLAY_KINDS = ("speed", "unbalance", "length", "mass", "force", "time")


def _coord_text(axis: dict, cell: dict, shown, units) -> str:
    """``path = value`` of a cell's coordinate: as written in the description, or, with
    ``--units``, converted to the chosen unit of its kind."""
    from ..sweep.spec import field_kind

    value = cell["coords"][axis["key"]]
    given = cell["coords_as_given"][axis["path"]]
    kind = field_kind(axis["path"]) if "." in axis["path"] else ""
    if units is not None and kind in _DISPLAY_KINDS and isinstance(value, (int, float)):
        return f"{axis['path']} = {shown.fmt(value, kind)}"
    return f"{axis['path']} = {given}"
