"""Figure of a run-up study (:func:`autobalance.studies._runup.compute_runup`): reads the dataset
and draws; no physics here. Top: spin speed against time per case. Bottom: whirl amplitude with
the balls (solid) and without (dashed), the balancing threshold dotted."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

from .speed_map import _per_unit

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["plot_runup"]


def plot_runup(ds: xr.Dataset, speed_unit: str = "rad/s", title: str = "") -> Figure:
    """Speed and whirl amplitude against time, per case (module docstring).

    Parameters
    ----------
    ds : xarray.Dataset
        A run-up study (``speed`` [rad/s], ``amplitude`` and ``amplitude_bare`` [m] over
        (case, time [s]); attrs ``eccentricity_m``, ``balancing_fraction``).
    speed_unit : str
        Unit of the speed axis, any rotational speed pint knows: "rad/s", "rpm", "Hz", ...
    title : str
        Figure title.

    Returns
    -------
    matplotlib.figure.Figure
    """
    k = _per_unit(speed_unit)
    fig = Figure(figsize=(8, 6.5))
    FigureCanvasAgg(fig)
    ax1, ax2 = fig.subplots(2, 1, sharex=True)
    t = ds["time"].values
    for i, case in enumerate(ds["case"].values):
        c = f"C{i}"
        d = ds.sel(case=case)
        ax1.plot(t, d["speed"].values / k, color=c, label=str(case))
        ax2.plot(t, 1e3 * d["amplitude"].values, color=c, label=f"{case}, with {ds.attrs.get('balancer', 'balls')}")
        if "amplitude_bare" in d:
            ax2.plot(t, 1e3 * d["amplitude_bare"].values, color=c, ls="--", lw=0.9,
                     label=f"{case}, without")
    thr = ds.attrs["balancing_fraction"] * ds.attrs["eccentricity_m"]
    ax2.axhline(1e3 * thr, color="0.4", ls=":", lw=0.9,
                label=f"{100 * ds.attrs['balancing_fraction']:g} % of e = U/M_t")
    ax1.set_ylabel(f"speed [{speed_unit}]")
    ax2.set_ylabel("whirl amplitude [mm]")
    ax2.set_xlabel("time [s]")
    ax2.set_yscale("log")
    lo = np.nanmin(1e3 * ds["amplitude"].values[ds["amplitude"].values > 0], initial=1e-4)
    ax2.set_ylim(bottom=max(lo, 1e-3 * thr * 1e3))
    ax1.legend(fontsize=8)
    ax2.legend(fontsize=7, ncol=2)
    for ax in (ax1, ax2):
        ax.grid(alpha=0.3)
    if title:
        ax1.set_title(title)
    fig.tight_layout()
    return fig
