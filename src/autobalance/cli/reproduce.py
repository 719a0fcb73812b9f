"""``autobalance reproduce [TARGET ...]``: every table and figure of the four seeds, published vs
computed, as an HTML report (the main job: ``make run``).

TARGET is ``all`` (default), a paper (``000``, ``001``, ``003``, ``004``), ``liquid`` (001 + 003),
``balls`` (000 + 004) or a target id or alias (``--list`` shows them; e.g. ``tsr-mc`` =
``004-fig5-6-table2``). ``--quick`` (default) finishes in a few minutes on 2 cores with coarser
Monte-Carlo grids (each target states what changes); ``--full`` runs the paper-size studies
(hours), resumable: the sweep stores under ``OUT/stores`` are reused by a rerun. Progress: one
line per target on stderr. Output: ``OUT/report.html`` (figures in ``OUT/figures``, data in
``OUT/data``), ``OUT/report.json``, ``OUT/VALIDATION.md``; a summary per paper on the terminal,
or one JSON object with ``--json``. Input errors: one line on stderr, exit code 2; a target that
fails is reported in the page and the command exits with code 1.

The sweeps of the targets run where ``--executor`` / ``--workers`` / ``--scheduler`` say: they
travel in the :class:`~autobalance.validation.target.Context` given to every target (the
environment is not touched; ``$DASK_SCHEDULER_ADDRESS`` stays the sweeps' default scheduler).
"""
from __future__ import annotations

import os
import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from ..config import ConfigError
from .common import (ExecutorOpt, JsonOpt, SchedulerOpt, WorkersOpt, check_executor,
                     check_workers, guard, print_json)

TargetsArg = Annotated[Optional[list[str]], typer.Argument(
    metavar="[TARGET]...", help="all (default), 000, 001, 003, 004, liquid, balls or target ids.")]


def _check_out(out: Path) -> Path:
    """``--out-dir DIR``: a directory (made if missing) this process can write the report's files
    into (each is written beside its final name, then renamed: :mod:`autobalance.atomic`)."""
    if out.exists() and not out.is_dir():
        raise ConfigError(f"--out-dir = {str(out)!r}: exists and is not a directory")
    if out.is_dir() and not os.access(out, os.W_OK | os.X_OK):
        raise ConfigError(f"--out-dir = {str(out)!r}: the directory is not writable")
    return out


def _progress(i: int, n: int, rec: dict) -> None:
    """One line per finished target on stderr: ``[i/n] id  counts (wall time)``."""
    from ..report.runner import _counts

    c = _counts([rec])
    what = ("nothing to compute" if rec["status"] == "nothing to compute" else
            f"{c['pass']}/{c['published']} pass" + (f", {c['miss']} miss" if c["miss"] else "")
            + (f", {c['not computed']} not computed" if c["not computed"] else "")
            + (f", ERROR {rec['error']}" if rec["error"] else ""))
    typer.echo(f"[{i}/{n}] {rec['id']:<26} {what} ({rec['wall_time_s']:.1f} s)", err=True)


def _echo_list(chosen) -> None:
    """``--list``: one line per target (id, paper, items, number of claims, title, aliases)."""
    from ..validation.target import claims

    for t in chosen:
        also = f" (also: {', '.join(t.aliases)})" if t.aliases else ""
        typer.echo(f"{t.id:<26} {t.paper}  {', '.join(t.items):<34} "
                   f"{len(claims(t)):>3} numbers  {t.title}{also}")


def _context(quick: bool, out: Path, executor: str, workers: Optional[int],
             scheduler: Optional[str]):
    """The checked run options as a Context; a scheduler implies the dask executor."""
    from ..validation.target import Context

    if scheduler:
        executor = "dask"
    check_executor(executor, workers, scheduler)    # dask needs an address, ...
    check_workers(workers)      # >= 1, and their processes fit the memory limit
    out = _check_out(out)
    return Context(quick=quick, out=out, executor=executor, workers=workers, scheduler=scheduler)


def reproduce(targets: TargetsArg = None,
              quick: Annotated[bool, typer.Option("--quick", help="Coarse grids (minutes; the "
                                                  "default).")] = False,
              full: Annotated[bool, typer.Option("--full", help="The papers' grids (hours, "
                                                 "resumable).")] = False,
              out: Annotated[Path, typer.Option("--out-dir", metavar="DIR",
                                                help="Report directory.")] = Path("out"),
              as_json: JsonOpt = False, executor: ExecutorOpt = "local",
              workers: WorkersOpt = None, scheduler: SchedulerOpt = None,
              list_: Annotated[bool, typer.Option("--list", help="List the targets and exit.")] = False,
              ) -> None:
    """Reproduce the seeds' tables and figures: published vs computed, as an HTML report.\f

    Parameters
    ----------
    targets : list of str
        all (default), a paper, liquid, balls or target ids / aliases.
    quick : bool
        Coarse grids (minutes); the default unless ``full``.
    full : bool
        The papers' grids (hours, resumable); not with ``quick``.
    out : Path
        Report directory.
    as_json : bool
        Print the report (rows and summary) as one JSON object.
    executor, workers, scheduler
        Where the targets' sweeps run (the shared options of :mod:`autobalance.cli.common`);
        they travel in the Context; a scheduler implies the dask executor.
    list_ : bool
        List the targets and exit.

    Exits with code 1 if a target failed, 2 on an input error.
    """
    from ..report.registry import select
    from ..report.runner import run_targets, summary_lines, write_report

    with guard():
        chosen = select(targets)
        if list_:
            _echo_list(chosen)
            return
        if quick and full:
            raise ConfigError("--quick and --full: give one of them (--quick: coarse grids, the "
                              "default; --full: the papers' grids)")
        ctx = _context(not full, out, executor, workers, scheduler)
        report = run_targets(chosen, ctx, progress=_progress)   # on stderr
        paths = write_report(report, ctx.out, "--out-dir")
    if as_json:
        print_json({**report, "files": paths})
    else:
        s = report["summary"]
        for paper, c in summary_lines(s):
            typer.echo(f"{paper:>5}: {c['pass']:>3} of {c['published']:>3} published quantities "
                       f"reproduced, {c['miss']} miss, {c['not computed']} not computed, "
                       f"{c['unreported']} unreported ({c['targets']} targets, {c['errors']} errors)")
        typer.echo(f"report: {paths['html']}")
    if report["summary"]["total"]["errors"]:
        sys.exit(1)
