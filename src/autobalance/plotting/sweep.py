"""Figures of a sweep dataset (autobalance.sweep): reads results, computes no physics.

* PDF of the grade G at every checkpoint, over all runs (like 004 Fig. 5);
* with two checkpoints, each run's second grade against its first (004 Fig. 6: STD vs TSR);
* for every swept parameter, the 5/50/95 % grade over the other dimensions against it
  (004 Fig. 7 for the initial unbalance).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    import xarray as xr


def plot_sweep(ds: xr.Dataset, grade: float = 16.0) -> Figure:
    """Figure summarising a sweep; ``grade`` [mm/s] is drawn as the acceptance limit."""
    ok = (ds["status"] == 0).values
    G = ds["grade_G"]
    cps = ds["checkpoint"].values
    grid_dims = [d for d in G.dims if d not in ("sample", "checkpoint")]
    n_panels = 1 + (1 if cps.size == 2 else 0) + len(grid_dims)
    fig = Figure(figsize=(5.2 * n_panels, 4.2), constrained_layout=True)
    FigureCanvasAgg(fig)
    axes = fig.subplots(1, n_panels, squeeze=False)[0]
    title = f"sweep {ds.attrs.get('sweep_name', '')}: {int(ok.sum())} runs"
    n_bad = int((~ok).sum())
    if n_bad:
        title += f" ({n_bad} failed, not shown)"
    fig.suptitle(title)

    ax = axes[0]
    vals = G.values
    top = np.nanmax(np.where(ok[..., None], vals, np.nan)) if ok.any() else 1.0
    bins = np.linspace(0.0, max(top, grade) * 1.05, 40)
    for i, t in enumerate(cps):
        g = vals[..., i][ok]
        share = np.mean(g <= grade) if g.size else np.nan
        ax.hist(g, bins=bins, density=True, histtype="step", lw=1.6,
                label=f"t = {t:g} s: {100 * share:.1f} % <= G{grade:g}")
    ax.axvline(grade, color="r", ls="--", lw=1)
    ax.set_xlabel("grade G [mm/s]")
    ax.set_ylabel("probability density [s/mm]")
    ax.set_title("distribution of the balancing grade")
    ax.legend(fontsize=8)
    k = 1
    if cps.size == 2:
        ax = axes[k]
        k += 1
        g1 = vals[..., 0][ok]
        g2 = vals[..., 1][ok]
        ax.scatter(g1, g2, s=6, alpha=0.5)
        lim = max(np.nanmax(g1) if g1.size else 1, np.nanmax(g2) if g2.size else 1, grade) * 1.05
        ax.plot([0, lim], [0, lim], "k:", lw=1, label="equal")
        ax.axhline(grade, color="r", ls="--", lw=1)
        ax.axvline(grade, color="r", ls="--", lw=1)
        ax.set_xlim(0, lim)
        ax.set_ylim(0, lim)
        ax.set_xlabel(f"G at t = {cps[0]:g} s [mm/s]")
        ax.set_ylabel(f"G at t = {cps[1]:g} s [mm/s]")
        ax.set_title("each run: later vs earlier checkpoint")
        ax.legend(fontsize=8)
    for dim in grid_dims:
        ax = axes[k]
        k += 1
        x = ds[dim].values
        other = [d for d in G.dims if d not in (dim, "checkpoint")]
        Gm = G.where(ds["status"] == 0)
        for i, t in enumerate(cps):
            q = Gm.isel(checkpoint=i).quantile([0.05, 0.5, 0.95], dim=other, skipna=True).values
            line, = ax.plot(x, q[1], lw=1.8, label=f"t = {t:g} s: median")
            ax.fill_between(x, q[0], q[2], color=line.get_color(), alpha=0.2,
                            label=f"t = {t:g} s: 5-95 %")
        ax.axhline(grade, color="r", ls="--", lw=1)
        unit = ds[dim].attrs.get("units", "")
        ax.set_xlabel(f"{ds[dim].attrs.get('long_name', dim)} [{unit}]")
        ax.set_ylabel("grade G [mm/s]")
        ax.set_title(f"grade vs {ds[dim].attrs.get('long_name', dim)}")
        ax.legend(fontsize=8)
    return fig
