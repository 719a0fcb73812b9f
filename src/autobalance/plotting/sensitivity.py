"""The figure of the sensitivity study (:func:`autobalance.studies.sensitivity`): which variant
moves which result beyond its noise. Reads the study's dataset, computes no physics; returns a
matplotlib Figure on the Agg canvas."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    import xarray as xr

#: The colour scale's end: effects beyond this many standard errors get the full colour [-].
Z_CLIP = 4.0


def effect_text(unit: str, effect: float) -> str:
    """A variant's effect on one quantity of the given unit (the dataset's ``unit``
    coordinate) as the cell's text: grades ("mm/s") in mm/s, shares ("-") in percentage
    points."""
    if unit == "mm/s":
        return f"{effect:+.2f}"
    return f"{100 * effect:+.0f}"


def plot_sensitivity(ds: xr.Dataset, z: float = 2.0, title: str | None = None) -> Figure:
    """Each variant's effect (rows) on each quantity (columns) of
    :func:`autobalance.studies._sensitivity.compute_sensitivity`: the colour is effect / SE
    (red up, blue down, clipped at :data:`Z_CLIP`), the text the effect (grades [mm/s], shares
    and regions [percentage points]); an effect within ``z`` [-] standard errors is grey, in
    the noise.

    Parameters
    ----------
    ds : xarray.Dataset
        A sensitivity study's dataset (variant "base" first).
    z : float
        Significance threshold [-] (effect / SE).
    title : str or None
        The figure's title (None: the study's own).
    """
    variants = [str(v) for v in ds["variant"].values[1:]]
    qs = [str(q) for q in ds["quantity"].values]
    units = [str(u) for u in ds["unit"].values]
    eff = ds["effect"].values[1:]
    se = ds["effect_se"].values[1:]
    with np.errstate(divide="ignore", invalid="ignore"):
        zs = np.where(se > 0, eff / se, np.where(eff != 0, np.sign(eff) * np.inf, 0.0))
    fig = Figure(figsize=(1.0 + 0.75 * len(qs), 1.6 + 0.45 * len(variants)),
                 constrained_layout=True)
    FigureCanvasAgg(fig)
    ax = fig.add_subplot(1, 1, 1)
    im = ax.imshow(np.clip(zs, -Z_CLIP, Z_CLIP), cmap="RdBu_r", vmin=-Z_CLIP, vmax=Z_CLIP,
                   aspect="auto")
    for i in range(len(variants)):
        for j, unit in enumerate(units):
            ax.text(j, i, effect_text(unit, eff[i, j]), ha="center", va="center", fontsize=7,
                    color="k" if abs(zs[i, j]) > z else "0.6")
    ax.set_xticks(range(len(qs)), qs, rotation=45, ha="right", fontsize=8)
    ax.set_yticks(range(len(variants)), variants, fontsize=8)
    bar = fig.colorbar(im, ax=ax, shrink=0.9)
    bar.set_label("effect / standard error [-]", fontsize=8)
    starts = ds.attrs.get("starts")
    ax.set_title((title or "effect of each variant against the base")
                 + (f"; the same starts ({starts})" if starts else "")
                 + f"; grey: within {z:g} SE", fontsize=9)
    return fig
