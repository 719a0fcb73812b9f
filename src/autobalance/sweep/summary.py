"""Statistics of a sweep dataset: percentiles over the samples, shares below a grade, per grid
cell and pooled.

004 uses percentiles rather than mean and variance because the outcomes are far from normal
(sec. 4.3): the 5/50/95 % isolines and the share of runs qualifying a grade (e.g. G16).
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray as xr


def percentiles(ds: xr.Dataset, var: str = "grade_G", q: Sequence[float] = (5, 50, 95),
                dim: str | tuple = "sample") -> xr.DataArray:
    """Percentiles of ``var`` over ``dim`` (default the Monte-Carlo samples) as a DataArray
    with a leading ``percentile`` dimension; failed runs (status != 0) are excluded."""
    da = ds[var].where(ds["status"] == 0)
    out = da.quantile(np.asarray(q) / 100.0, dim=dim, skipna=True)
    out = out.rename({"quantile": "percentile"}).assign_coords(percentile=list(q))
    out.attrs.update(ds[var].attrs)
    return out


def share_below(ds: xr.Dataset, grade: float, var: str = "grade_G",
                dim: str | tuple = "sample") -> xr.DataArray:
    """Share [-] of the runs with ``var`` <= ``grade`` (004: share qualifying G16)."""
    ok = ds["status"] == 0
    hit = (ds[var] <= grade) & ok
    return hit.sum(dim) / ok.sum(dim)


def reduce_over(ds: xr.Dataset, keep: str, var: str = "grade_G",
                q: Sequence[float] = (5, 50, 95)) -> xr.DataArray:
    """Percentiles of ``var`` over every dimension except ``keep`` (and checkpoint/ball)."""
    dims = [d for d in ds[var].dims if d not in (keep, "checkpoint", "ball", "history_time")]
    return percentiles(ds, var, q, dim=tuple(dims))


def _suffix(units: str) -> str:
    """JSON key suffix of a coordinate's units attribute: "kg*m" -> "_kg_m", "-" -> ""."""
    u = (units or "").strip()
    if u in ("", "-", "1"):
        return ""
    return "_" + u.replace("*", "_").replace("/", "_").replace("^", "")


def _quantiles(ds, grade: float, dims: tuple, q=(5, 50, 95)):
    """(percentiles (..., checkpoint, percentile), share (..., checkpoint), ok-run counts (...))
    over ``dims``, the grid dimensions kept first in their order."""
    p = percentiles(ds, "grade_G", q, dim=dims)
    share = share_below(ds, grade, dim=dims)
    grid = [d for d in ds["grade_G"].dims if d not in dims and d != "checkpoint"]
    p = p.transpose(*grid, "checkpoint", "percentile")
    share = share.transpose(*grid, "checkpoint")
    status = ds["status"]
    ok = (status == 0).sum(dims).transpose(*grid)
    failed = ((status != 0) & (status >= 0)).sum(dims).transpose(*grid)
    return p.values, share.values, ok.values, failed.values


def _checkpoint_rows(cps, p: np.ndarray, share: np.ndarray) -> list:
    """One dict per checkpoint: time, 5/50/95 % grades, ISO class of the 95 % grade, share."""
    from ..physics.iso1940 import grade_class

    rows = []
    for i, t in enumerate(cps):
        p95 = float(p[i, 2])
        rows.append({
            "time_s": float(t),
            "grade_G_p5_mm_s": float(p[i, 0]),
            "grade_G_p50_mm_s": float(p[i, 1]),
            "grade_G_p95_mm_s": p95,
            "iso_class_p95_G_mm_s": float(grade_class(p95)) if np.isfinite(p95) else float("nan"),
            "share_below_limit": float(share[i]),
        })
    return rows


def grid_axes(ds: xr.Dataset) -> list:
    """The sweep's grid axes as JSON-able dicts: path, dimension, units, SI values and the
    values as written in the description.

    Parameters
    ----------
    ds : xarray.Dataset
        An assembled sweep (:func:`autobalance.sweep.sweep`).

    Returns
    -------
    list of dict
        ``{"path", "dim", "units", "key", "values", "values_as_given"}`` per axis, in the
        dimension order; ``key`` is the path with its JSON unit suffix
        (``"rotor.unbalance_kg_m"``).
    """
    import json

    out = []
    for d in ds["grade_G"].dims:
        if d in ("sample", "checkpoint"):
            continue
        c = ds[d]
        units = c.attrs.get("units", "")
        path = c.attrs.get("long_name", d.replace("__", "."))
        given = c.attrs.get("values_as_given")
        out.append({"path": path, "dim": d, "units": units, "key": path + _suffix(units),
                    "values": [v.item() for v in c.values],
                    "values_as_given": json.loads(given) if given else
                    [v.item() for v in c.values]})
    return out


def summary_dict(ds: xr.Dataset, grade: float = 16.0) -> dict:
    """JSON-able summary: per checkpoint, the 5/50/95 % grades, the ISO 1940 class of the 95 %
    grade and the share below ``grade`` over all runs (``checkpoints``, the pooled line), the
    same per grid cell (``cells``, C order over the grid axes, each with its coordinates);
    plus counts and failures.

    Parameters
    ----------
    ds : xarray.Dataset
        An assembled sweep (:func:`autobalance.sweep.sweep`).
    grade : float
        Grade limit G [mm/s] of the shares (004: G16).

    Returns
    -------
    dict
        ``name``, ``runs``, ``missing_runs``, ``failed_runs``, ``grade_limit_mm_s``,
        ``checkpoints`` (pooled), ``grid`` (:func:`grid_axes`), ``cells`` (per cell:
        ``coords`` {path_with_unit_suffix: SI value}, ``coords_as_given`` {path: value as
        written}, ``ok_runs``, ``failed_runs``, ``checkpoints``) and
        ``initial_grade_G_p50_mm_s``. Failed runs (status != 0) are left out of the statistics.
    """
    cps = ds["checkpoint"].values
    dims = tuple(d for d in ds["grade_G"].dims if d != "checkpoint")
    p, share, _, _ = _quantiles(ds, grade, dims)
    out = {
        "name": ds.attrs.get("sweep_name"),
        "runs": int(ds.attrs.get("n_runs", 0)),
        "missing_runs": int(ds.attrs.get("n_missing_runs", 0)),
        "failed_runs": int(((ds["status"] != 0) & (ds["status"] >= 0)).sum()),
        "grade_limit_mm_s": grade,
        "checkpoints": _checkpoint_rows(cps, p, share),
    }
    axes = grid_axes(ds)
    pc, sc, okc, failc = _quantiles(ds, grade, ("sample",))
    cells = []
    for idx in np.ndindex(*[len(a["values"]) for a in axes]):
        cells.append({
            "coords": {a["key"]: a["values"][i] for a, i in zip(axes, idx)},
            "coords_as_given": {a["path"]: a["values_as_given"][i] for a, i in zip(axes, idx)},
            "ok_runs": int(okc[idx]), "failed_runs": int(failc[idx]),
            "checkpoints": _checkpoint_rows(cps, pc[idx], sc[idx]),
        })
    out["grid"] = axes
    out["cells"] = cells
    ig = ds["initial_grade_G"].where(ds["status"] == 0)
    out["initial_grade_G_p50_mm_s"] = float(ig.median())
    return out
