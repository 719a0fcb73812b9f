"""The figure of the tolerance study (:func:`autobalance.studies.tolerances`): where the target
residual's budget goes, cause by cause. Reads the study's dataset
(:func:`autobalance.studies._tolerances.tolerances_dataset`), computes no physics; returns a
matplotlib Figure on the Agg canvas."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    import xarray as xr

#: The bars of each cause: the dataset's variable and its legend.
BARS = (("budget", "budget (share of the target)"),
        ("at_limit", "worst case at the allowed tolerance"),
        ("own", "worst case of this machine's own"))


def plot_tolerances(ds: xr.Dataset, unbalance_unit: str = "kg*m", factor: float = 1.0,
                    title: str | None = None) -> Figure:
    """Per cause of the residual (eccentricity, rolling, friction, other) three bars on a log
    axis: its budget, the worst-case residual at the allowed tolerance and with the machine's
    own; a dashed line at the target residual and a dotted one at the machine's own worst case
    (all causes at once). A zero or missing value draws no bar; the simulated runs, when the
    study ran them, are a strip of points at the right.

    Parameters
    ----------
    ds : xarray.Dataset
        A tolerance study's dataset (``budget``, ``at_limit``, ``own`` over ``cause`` [kg m];
        attrs ``target_unbalance_kg_m``, ``worst_residual_kg_m`` [kg m]).
    unbalance_unit : str
        The axis's unit of unbalance (the config's; a pint unit string).
    factor : float
        Display value per kg m [unbalance_unit / (kg m)].
    title : str or None
        The figure's title (None: the machine's name and the target grade).
    """
    causes = [str(c) for c in ds["cause"].values]
    fig = Figure(figsize=(7.0, 4.2), constrained_layout=True)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    x = np.arange(len(causes), dtype=float)
    width = 0.26
    shown = []
    for k, (name, label) in enumerate(BARS):
        v = factor * ds[name].values
        ok = np.isfinite(v) & (v > 0)
        shown.append(v[ok])
        ax.bar(x[ok] + (k - 1) * width, v[ok], width, label=label, color=f"C{k}")
    target = factor * float(ds.attrs["target_unbalance_kg_m"])
    worst = factor * float(ds.attrs.get("worst_residual_kg_m", np.nan))
    ax.axhline(target, color="k", ls="--", lw=1.2, label="target residual")
    if np.isfinite(worst) and worst > 0:
        ax.axhline(worst, color="C3", ls=":", lw=1.2, label="this machine's worst case")
    ticks, labels = list(x), causes
    if "simulated_residual" in ds:
        r = factor * ds["simulated_residual"].values
        r = r[np.isfinite(r) & (r > 0)]
        xs = np.full(r.size, x[-1] + 1.0)
        ax.plot(xs, r, "o", ms=3, color="0.3", alpha=0.6, label="simulated runs")
        shown.append(r)
        ticks, labels = ticks + [x[-1] + 1.0], causes + ["simulated"]
    values = np.concatenate([*shown, [target]])
    ax.set_yscale("log")
    ax.set_ylim(0.3 * values.min(), 3.0 * max(values.max(), worst if np.isfinite(worst) else 0))
    ax.set_xticks(ticks, labels)
    ax.set_ylabel(f"residual unbalance [{unbalance_unit}]")
    if title is None:
        grade = ds.attrs.get("target_grade_G_mm_s")
        title = ("tolerances" if grade is None else
                 f"{ds.attrs.get('name', '')}: tolerances for G{grade:.3g}")
    ax.set_title(title)
    ax.legend(fontsize=7, loc="best")
    ax.grid(True, axis="y", which="both", alpha=0.3)
    return fig
