"""Run reproduction targets and write the report: ``report.json``, ``report.html``,
``VALIDATION.md``, figures (PNG + SVG) under ``figures/`` and data (NetCDF) under ``data/``; each
file is written atomically (:mod:`autobalance.atomic`: a run killed while writing leaves the
previous file, never a part of one).

A target that raises is recorded with status ``error`` and its message; the others still run
and the report is still written. A published number a target claims but does not report is
listed as *unreported* (and counted): nothing is skipped silently. Sweep stores live under
``<out>/stores/<name>/<identity>`` and are reused on a rerun, so an interrupted ``--full`` run
resumes; a changed package or option gets new stores beside the old ones.
"""
from __future__ import annotations

import json
import time
import traceback
from collections.abc import Sequence
from pathlib import Path
from typing import Callable, Optional

from ..atomic import atomic_output, save_figure, write_atomic
from ..jsonable import netcdf_safe
from ..validation.target import Context, Target, claims, status
from .summary import counts as _counts  # noqa: F401  (re-exported for the CLI)
from .summary import summarize, summary_lines

__all__ = ["run_targets", "summary_lines", "summarize", "write_report"]

STATUSES = ("pass", "miss", "not computed")


def _save_data(data, out: Path, tid: str) -> list:
    if data is None:
        return []
    items = data.items() if isinstance(data, dict) else [("", data)]
    paths = []
    for name, ds in items:
        rel = Path("data") / f"{tid}{'-' + name if name else ''}.nc"
        (out / rel).parent.mkdir(parents=True, exist_ok=True)
        with atomic_output(out / rel) as tmp:
            netcdf_safe(ds).to_netcdf(tmp)
        paths.append(rel.as_posix())
    return paths


def _save_figures(figures: dict, out: Path, tid: str) -> list:
    paths = []
    for name, fig in figures.items():
        stem = Path("figures") / f"{tid}-{name}"
        (out / stem).parent.mkdir(parents=True, exist_ok=True)
        save_figure(fig, out / stem.with_suffix(".png"), dpi=100)
        save_figure(fig, out / stem.with_suffix(".svg"))
        paths.append(stem.with_suffix(".png").as_posix())
    return paths


def _run_one(target, ctx: Context) -> dict:
    from ..jsonable import to_jsonable as _clean

    rec = {"id": target.id, "paper": target.paper, "items": list(target.items),
           "title": target.title, "notes": target.notes, "quick": target.quick,
           "claims": claims(target), "rows": [], "figures": [], "data": [], "run_notes": "",
           "error": None, "unreported": [], "unclaimed": [], "wall_time_s": 0.0}
    if target.run is None:
        rec["status"] = "nothing to compute"
        return rec
    t0 = time.perf_counter()
    try:
        outcome = target.run(ctx)
        rows = _clean(outcome.rows)
        for r in rows:
            r["status"] = status(r)
        rec.update(rows=rows, run_notes=outcome.notes)
        if ctx.out is not None:
            rec["figures"] = _save_figures(outcome.figures, Path(ctx.out), target.id)
            rec["data"] = _save_data(outcome.data, Path(ctx.out), target.id)
        keys = [r.get("key") for r in rows]
        rec["unreported"] = [k for k in rec["claims"] if k not in keys]
        rec["unclaimed"] = [k for k in keys if k not in rec["claims"]]
        rec["status"] = "ran"
        if rec["unclaimed"]:
            rec["status"] = "error"
            rec["error"] = f"rows without a published claim: {', '.join(map(str, rec['unclaimed']))}"
    except Exception as exc:                      # recorded in the report; the run goes on
        rec["status"] = "error"
        rec["error"] = f"{type(exc).__name__}: {' '.join(str(exc).split())}"
        rec["traceback"] = traceback.format_exc(limit=6)
        rec["unreported"] = list(rec["claims"])
    rec["wall_time_s"] = round(time.perf_counter() - t0, 2)
    return rec


def run_targets(targets: Sequence[Target], ctx: Context,
                progress: Optional[Callable[[int, int, dict], None]] = None) -> dict:
    """Run ``targets`` in order and return the report dict (nothing written)."""
    from .. import __version__

    t0 = time.perf_counter()
    recs = []
    for i, target in enumerate(targets):
        rec = _run_one(target, ctx)
        recs.append(rec)
        if progress is not None:
            progress(i + 1, len(targets), rec)
    return {"autobalance_version": __version__, "variant": "quick" if ctx.quick else "full",
            "wall_time_s": round(time.perf_counter() - t0, 1),
            "out": None if ctx.out is None else str(ctx.out),
            "summary": summarize(recs), "targets": recs}


def write_report(report: dict, out: Path, option: Optional[str] = None) -> dict:
    """Write report.json, report.html and VALIDATION.md into ``out``, each atomically (a failed
    write leaves the previous file: :mod:`autobalance.atomic`); returns their paths.

    Parameters
    ----------
    report : dict
        The report (:func:`run_targets`).
    out : Path
        The report directory (created).
    option : str, optional
        The option that named ``out`` (``"--out"``), for the one-line error.

    Returns
    -------
    dict
        ``{"json": path, "html": path, "markdown": path}``.

    Raises
    ------
    autobalance.atomic.OutputError
        A file could not be written (one line; the previous file unchanged).
    """
    from ..jsonable import to_jsonable as _clean
    from .html import render_html
    from .markdown import render_markdown

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    paths = {"json": out / "report.json", "html": out / "report.html",
             "markdown": out / "VALIDATION.md"}
    write_atomic(paths["json"], json.dumps(_clean(report), indent=1, allow_nan=False), option)
    write_atomic(paths["html"], render_html(report), option)
    write_atomic(paths["markdown"], render_markdown(report), option)
    return {k: str(v) for k, v in paths.items()}
