"""Statistics of a sweep dataset: percentiles over the samples, shares below a grade, per grid
cell and pooled.

004 uses percentiles rather than mean and variance because the outcomes are far from normal
(sec. 4.3): the 5/50/95 % isolines and the share of runs qualifying a grade (e.g. G16).
"""
from __future__ import annotations

from collections.abc import Sequence
from typing import TYPE_CHECKING

import numpy as np

from ..confidence import LEVEL, quantile_interval, share_interval, verdict

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


def _over(da: xr.DataArray, dim: str | tuple) -> xr.DataArray:
    """``da`` with the dimensions ``dim`` stacked into one last dimension ``_s``."""
    dims = (dim,) if isinstance(dim, str) else tuple(dim)
    da = da.stack(_s=dims) if len(dims) > 1 else da.rename({dims[0]: "_s"})
    return da.transpose(..., "_s")


def _bounds(values: np.ndarray, like: xr.DataArray, lead: dict | None = None) -> xr.DataArray:
    """(lead..., like's dims but ``_s``, 2) values as a DataArray with a ``bound`` (lo, hi)
    dimension and the coordinates of ``like``."""
    import xarray as xr

    rest = [d for d in like.dims if d != "_s"]
    coords = {c: like[c] for c in like.coords if set(like[c].dims) <= set(rest)}
    coords["bound"] = ["lo", "hi"]
    dims = (*(lead or {}), *rest, "bound")
    if lead:
        coords.update(lead)
    return xr.DataArray(values, dims=dims, coords=coords)


def percentile_intervals(ds: xr.Dataset, var: str = "grade_G", q: Sequence[float] = (5, 50, 95),
                         dim: str | tuple = "sample", level: float = LEVEL) -> xr.DataArray:
    """The distribution-free intervals of the percentiles of :func:`percentiles`
    (:func:`autobalance.confidence.quantile_interval`, order statistics; failed runs left
    out).

    Parameters
    ----------
    ds : xarray.Dataset
        An assembled sweep.
    var : str
        The variable [its units].
    q : sequence of float
        Percentiles [%].
    dim : str or tuple of str
        The dimensions sampled over.
    level : float
        Confidence level [-].

    Returns
    -------
    xarray.DataArray
        (percentile, the other dimensions..., bound) with bound = lo, hi [units of ``var``];
        an end the sample cannot bound is -inf / inf.
    """
    x = _over(ds[var].where(ds["status"] == 0), dim)
    out = []
    for qq in q:
        _, lo, hi = quantile_interval(x.values, float(qq) / 100.0, level)
        out.append(np.stack([lo, hi], axis=-1))
    da = _bounds(np.stack(out), x, {"percentile": list(q)})
    da.attrs.update(ds[var].attrs)
    da.attrs["confidence_level"] = level
    return da


def share_intervals(ds: xr.Dataset, grade: float, var: str = "grade_G",
                    dim: str | tuple = "sample", level: float = LEVEL) -> xr.DataArray:
    """The Clopper-Pearson intervals of the shares of :func:`share_below`
    (:func:`autobalance.confidence.share_interval`; failed runs left out).

    Parameters
    ----------
    ds : xarray.Dataset
        An assembled sweep.
    grade : float
        The limit [units of ``var``].
    var : str
        The variable.
    dim : str or tuple of str
        The dimensions sampled over.
    level : float
        Confidence level [-].

    Returns
    -------
    xarray.DataArray
        (the other dimensions..., bound) with bound = lo, hi [-].
    """
    hit = _over((ds[var] <= grade) & (ds["status"] == 0), dim)
    ok = _over(ds["status"] == 0, dim).broadcast_like(hit).transpose(*hit.dims)  # + checkpoint
    _, lo, hi = share_interval(hit.sum("_s").values, ok.sum("_s").values, level)
    da = _bounds(np.stack([lo, hi], axis=-1), hit)
    da.attrs.update({"units": "-", "confidence_level": level})
    return da


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
    """(percentiles (..., checkpoint, percentile), share (..., checkpoint), ok-run counts (...),
    failed-run counts (...), percentile intervals (..., checkpoint, percentile, bound), share
    intervals (..., checkpoint, bound)) over ``dims``, the grid dimensions kept first in their
    order."""
    p = percentiles(ds, "grade_G", q, dim=dims)
    share = share_below(ds, grade, dim=dims)
    grid = [d for d in ds["grade_G"].dims if d not in dims and d != "checkpoint"]
    p = p.transpose(*grid, "checkpoint", "percentile")
    share = share.transpose(*grid, "checkpoint")
    p_ci = percentile_intervals(ds, "grade_G", q, dim=dims).transpose(*grid, "checkpoint",
                                                                      "percentile", "bound")
    s_ci = share_intervals(ds, grade, dim=dims).transpose(*grid, "checkpoint", "bound")
    status = ds["status"]
    ok = (status == 0).sum(dims).transpose(*grid)
    failed = ((status != 0) & (status >= 0)).sum(dims).transpose(*grid)
    return p.values, share.values, ok.values, failed.values, p_ci.values, s_ci.values


def _checkpoint_rows(cps, p: np.ndarray, share: np.ndarray, p_ci: np.ndarray,
                     s_ci: np.ndarray, grade: float) -> list:
    """One dict per checkpoint: time, 5/50/95 % grades with their intervals, ISO class of the
    95 % grade, share with its interval, and the verdict of the 95 % grade against
    ``grade``."""
    from ..physics.iso1940 import grade_class

    rows = []
    for i, t in enumerate(cps):
        p95 = float(p[i, 2])
        rows.append({
            "time_s": float(t),
            "grade_G_p5_mm_s": float(p[i, 0]),
            "grade_G_p5_mm_s_ci": [float(v) for v in p_ci[i, 0]],
            "grade_G_p50_mm_s": float(p[i, 1]),
            "grade_G_p50_mm_s_ci": [float(v) for v in p_ci[i, 1]],
            "grade_G_p95_mm_s": p95,
            "grade_G_p95_mm_s_ci": [float(v) for v in p_ci[i, 2]],
            "iso_class_p95_G_mm_s": float(grade_class(p95)) if np.isfinite(p95) else float("nan"),
            "share_below_limit": float(share[i]),
            "share_below_limit_ci": [float(v) for v in s_ci[i]],
            "p95_verdict": verdict(float(p_ci[i, 2, 0]), float(p_ci[i, 2, 1]), grade),
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
        ``confidence_level``, ``checkpoints`` (pooled; each percentile and share with its
        interval ``..._ci`` = [lo, hi], null where the runs cannot bound it, and
        ``p95_verdict``: "meets", "fails" or "undecided" for p95 <= ``grade``), ``grid`` (:func:`grid_axes`), ``cells`` (per cell:
        ``coords`` {path_with_unit_suffix: SI value}, ``coords_as_given`` {path: value as
        written}, ``ok_runs``, ``failed_runs``, ``checkpoints``) and
        ``initial_grade_G_p50_mm_s``. Failed runs (status != 0) are left out of the statistics.
    """
    cps = ds["checkpoint"].values
    dims = tuple(d for d in ds["grade_G"].dims if d != "checkpoint")
    p, share, _, _, p_ci, s_ci = _quantiles(ds, grade, dims)
    out = {
        "name": ds.attrs.get("sweep_name"),
        "runs": int(ds.attrs.get("n_runs", 0)),
        "missing_runs": int(ds.attrs.get("n_missing_runs", 0)),
        "failed_runs": int(((ds["status"] != 0) & (ds["status"] >= 0)).sum()),
        "grade_limit_mm_s": grade,
        "confidence_level": LEVEL,
        "checkpoints": _checkpoint_rows(cps, p, share, p_ci, s_ci, grade),
    }
    axes = grid_axes(ds)
    pc, sc, okc, failc, pc_ci, sc_ci = _quantiles(ds, grade, ("sample",))
    cells = []
    for idx in np.ndindex(*[len(a["values"]) for a in axes]):
        cells.append({
            "coords": {a["key"]: a["values"][i] for a, i in zip(axes, idx)},
            "coords_as_given": {a["path"]: a["values_as_given"][i] for a, i in zip(axes, idx)},
            "ok_runs": int(okc[idx]), "failed_runs": int(failc[idx]),
            "checkpoints": _checkpoint_rows(cps, pc[idx], sc[idx], pc_ci[idx], sc_ci[idx],
                                            grade),
        })
    out["grid"] = axes
    out["cells"] = cells
    ig = ds["initial_grade_G"].where(ds["status"] == 0)
    out["initial_grade_G_p50_mm_s"] = float(ig.median())
    return out
