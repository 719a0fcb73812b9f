"""``autobalance reproduce [TARGET ...]``: every table and figure of the four seeds, published vs
computed, as an HTML report (the main job: ``make run``).

TARGET is ``all`` (default), a paper (``000``, ``001``, ``003``, ``004``), ``liquid`` (001 + 003),
``balls`` (000 + 004) or a target id or alias (``--list`` shows them; e.g. ``tsr-mc`` =
``004-fig5-6-table2``). ``--quick`` (default) finishes in a
few minutes on 2 cores with coarser Monte-Carlo grids (each target states what changes);
``--full`` runs the paper-size studies (hours), resumable: the sweep stores under ``OUT/stores``
are reused by a rerun. Progress: one line per target on stderr. Output: ``OUT/report.html`` (figures in ``OUT/figures``, data in
``OUT/data``), ``OUT/report.json``, ``OUT/VALIDATION.md``; a summary per paper on the terminal,
or one JSON object with ``--json``. Input errors: one line on stderr, exit code 2; a target that
fails is reported in the page and the command exits with code 1.
"""
from __future__ import annotations

import sys
from pathlib import Path
from typing import Annotated, Optional

import typer

from .cli_common import _guard, _print_json, check_executor, check_workers
from .config import ConfigError

TargetsArg = Annotated[Optional[list[str]], typer.Argument(
    metavar="[TARGET]...", help="all (default), 000, 001, 003, 004, liquid, balls or target ids.")]


def _check_out(out: Path) -> Path:
    if out.exists() and not out.is_dir():
        raise ConfigError(f"--out = {str(out)!r}: exists and is not a directory")
    return out


def _progress(i: int, n: int, rec: dict) -> None:
    from .report.runner import _counts

    c = _counts([rec])
    what = ("nothing to compute" if rec["status"] == "nothing to compute" else
            f"{c['pass']}/{c['published']} pass" + (f", {c['miss']} miss" if c["miss"] else "")
            + (f", {c['not computed']} not computed" if c["not computed"] else "")
            + (f", ERROR {rec['error']}" if rec["error"] else ""))
    typer.echo(f"[{i}/{n}] {rec['id']:<26} {what} ({rec['wall_time_s']:.1f} s)", err=True)


def reproduce(targets: TargetsArg = None,
              quick: Annotated[bool, typer.Option("--quick/--full", help="Coarse grids (minutes) "
                                                  "or the papers' grids (hours, resumable).")] = True,
              out: Annotated[Path, typer.Option("--out", metavar="DIR",
                                                help="Report directory.")] = Path("out"),
              as_json: Annotated[bool, typer.Option("--json", help="Print the report (rows and "
                                                    "summary) as one JSON object.")] = False,
              executor: Annotated[str, typer.Option("--executor", help="Sweeps: local | serial | "
                                                    "dask.")] = "local",
              workers: Annotated[Optional[int], typer.Option("--workers", help="Local processes "
                                                             "(default: all cores).")] = None,
              scheduler: Annotated[Optional[str], typer.Option(
                  "--scheduler", help="Dask scheduler address (implies --executor dask).")] = None,
              list_: Annotated[bool, typer.Option("--list", help="List the targets and exit.")] = False,
              ) -> None:
    """Reproduce the seeds' tables and figures: published vs computed, as an HTML report."""
    import os

    from .report.registry import select
    from .report.runner import run_targets, summary_lines, write_report
    from .validation.target import Context, claims

    with _guard():
        chosen = select(targets)
        if list_:
            for t in chosen:
                also = f" (also: {', '.join(t.aliases)})" if t.aliases else ""
                typer.echo(f"{t.id:<26} {t.paper}  {', '.join(t.items):<34} "
                           f"{len(claims(t)):>3} numbers  {t.title}{also}")
            return
        check_executor(executor)
        check_workers(workers)      # >= 1, and their processes fit the memory limit
        if scheduler:
            executor = "dask"
        if executor == "dask" and not (scheduler or os.environ.get("DASK_SCHEDULER_ADDRESS")):
            raise ConfigError("--executor = 'dask': needs --scheduler ADDRESS (or "
                              "DASK_SCHEDULER_ADDRESS)")
        out = _check_out(out)
        ctx = Context(quick=quick, out=out, executor=executor, workers=workers,
                      scheduler=scheduler)
        saved = os.environ.get("DASK_SCHEDULER_ADDRESS")
        if scheduler:                   # the studies' sweeps read the address from here
            os.environ["DASK_SCHEDULER_ADDRESS"] = scheduler
        try:
            report = run_targets(chosen, ctx, progress=_progress)   # on stderr
        finally:
            if saved is None:
                os.environ.pop("DASK_SCHEDULER_ADDRESS", None)
            else:
                os.environ["DASK_SCHEDULER_ADDRESS"] = saved
        paths = write_report(report, out)
    if as_json:
        _print_json({**report, "files": paths})
    else:
        s = report["summary"]
        for paper, c in summary_lines(s):
            typer.echo(f"{paper:>5}: {c['pass']:>3} of {c['published']:>3} published quantities "
                       f"reproduced, {c['miss']} miss, {c['not computed']} not computed, "
                       f"{c['unreported']} unreported ({c['targets']} targets, {c['errors']} errors)")
        typer.echo(f"report: {paths['html']}")
    if report["summary"]["total"]["errors"]:
        sys.exit(1)


__all__ = ["reproduce"]
