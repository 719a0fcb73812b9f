"""Statistics of a sweep dataset: percentiles over the samples, shares below a grade.

004 uses percentiles rather than mean and variance because the outcomes are far from normal
(sec. 4.3): the 5/50/95 % isolines and the share of runs qualifying a grade (e.g. G16).
"""
from __future__ import annotations

import numpy as np


def percentiles(ds, var: str = "grade_G", q=(5, 50, 95), dim: str | tuple = "sample"):
    """Percentiles of ``var`` over ``dim`` (default the Monte-Carlo samples) as a DataArray
    with a leading ``percentile`` dimension; failed runs (status != 0) are excluded."""
    da = ds[var].where(ds["status"] == 0)
    out = da.quantile(np.asarray(q) / 100.0, dim=dim, skipna=True)
    out = out.rename({"quantile": "percentile"}).assign_coords(percentile=list(q))
    out.attrs.update(ds[var].attrs)
    return out


def share_below(ds, grade: float, var: str = "grade_G", dim: str | tuple = "sample"):
    """Share [-] of the runs with ``var`` <= ``grade`` (004: share qualifying G16)."""
    ok = ds["status"] == 0
    hit = (ds[var] <= grade) & ok
    return hit.sum(dim) / ok.sum(dim)


def reduce_over(ds, keep: str, var: str = "grade_G", q=(5, 50, 95)):
    """Percentiles of ``var`` over every dimension except ``keep`` (and checkpoint/ball)."""
    dims = [d for d in ds[var].dims if d not in (keep, "checkpoint", "ball", "history_time")]
    return percentiles(ds, var, q, dim=tuple(dims))


def summary_dict(ds, grade: float = 16.0) -> dict:
    """JSON-able summary: per checkpoint, the 5/50/95 % grades and the share below ``grade``
    over all runs; plus counts and failures."""
    cps = ds["checkpoint"].values
    dims = tuple(d for d in ds["grade_G"].dims if d != "checkpoint")
    p = percentiles(ds, "grade_G", dim=dims)
    share = share_below(ds, grade, dim=dims)
    out = {
        "name": ds.attrs.get("sweep_name"),
        "runs": int(ds.attrs.get("n_runs", 0)),
        "missing_runs": int(ds.attrs.get("n_missing_runs", 0)),
        "failed_runs": int(((ds["status"] != 0) & (ds["status"] >= 0)).sum()),
        "grade_limit_mm_s": grade,
        "checkpoints": [],
    }
    for i, t in enumerate(cps):
        out["checkpoints"].append({
            "time_s": float(t),
            "grade_G_p5_mm_s": float(p.sel(percentile=5).isel(checkpoint=i)),
            "grade_G_p50_mm_s": float(p.sel(percentile=50).isel(checkpoint=i)),
            "grade_G_p95_mm_s": float(p.sel(percentile=95).isel(checkpoint=i)),
            "share_below_limit": float(share.isel(checkpoint=i)),
        })
    ig = ds["initial_grade_G"].where(ds["status"] == 0)
    out["initial_grade_G_p50_mm_s"] = float(ig.median())
    return out
