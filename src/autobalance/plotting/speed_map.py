"""Figure of a speed map (:func:`autobalance.studies._speed_map.compute_speed_map`): reads the
dataset and draws; no physics here.

Top panel: ISO 1940 grade of the best stable state against speed, the speed ranges where the
balanced state is stable shaded green and the grid speeds where it has no verdict hatched, the
natural frequencies marked. Bottom panel: the balanced state's verdict over suspension-damping
factor x speed in four categories (VERDICT_STYLE): stable, unstable, no verdict (its own colour
and hatch, never the unstable one) and none (no reachable balanced state).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.colors import ListedColormap
from matplotlib.figure import Figure
from matplotlib.patches import Patch

from ..config.units import parse_quantity

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["VERDICT_STYLE", "plot_speed_map"]

#: The balanced state's verdicts in code order (the dataset's ``flag_meanings``), each with its
#: colour, hatch and legend label.
VERDICT_STYLE = (("none", "0.85", "", "no balanced state"), ("unstable", "tab:red", "", "unstable"),
                 ("stable", "tab:green", "", "stable"), ("no_verdict", "khaki", "xx", "no verdict"))
NO_VERDICT = 3


def _codes(ds: xr.Dataset, damping: bool) -> np.ndarray:
    """Verdict codes of the balanced state (VERDICT_STYLE order) over speed or (damping factor,
    speed); from the exists/stable flags for a map without ``balanced_verdict``."""
    tail = "_damping" if damping else ""
    if f"balanced_verdict{tail}" in ds:
        v = ds[f"balanced_verdict{tail}"]
        names = str(v.attrs.get("flag_meanings", "")).split()
        order = [m[0] for m in VERDICT_STYLE]
        if names and names != order:
            raise ValueError(f"balanced_verdict{tail}: flag_meanings {names}, expected {order}")
        return v.values.astype(int)
    stable = ds[f"balanced_stable{tail}"].values > 0
    exists = ds[f"balanced_exists{tail}"].values > 0
    return np.where(stable, 2, np.where(exists, 1, 0))


def _per_unit(speed_unit: str) -> float:
    """[rad/s] in one ``speed_unit`` (pint registry; Hz and rpm are revolutions, as in config)."""
    return parse_quantity(f"1 {speed_unit}", "speed", field="speed_unit")


def plot_speed_map(ds: xr.Dataset, speed_unit: str = "rad/s") -> Figure:
    """The speed map's two panels (module docstring).

    Parameters
    ----------
    ds : xarray.Dataset
        A speed map (coordinate ``speed`` [rad/s]; attrs ``stable_ranges_rad_s``,
        ``natural_frequencies_rad_s``).
    speed_unit : str
        Unit of the speed axis, any rotational speed pint knows: "rad/s", "rpm", "Hz", ...

    Returns
    -------
    matplotlib.figure.Figure
    """
    k = _per_unit(speed_unit)
    w = ds["speed"].values / k
    fig = Figure(figsize=(7.5, 6.5), constrained_layout=True)
    FigureCanvasAgg(fig)
    a1, a2 = fig.add_subplot(2, 1, 1), fig.add_subplot(2, 1, 2)
    flat = np.asarray(ds.attrs.get("stable_ranges_rad_s", []), float).ravel()
    for i in range(0, flat.size - 1, 2):
        a1.axvspan(flat[i] / k, flat[i + 1] / k, color="tab:green", alpha=0.15,
                   label="balanced state stable" if i == 0 else None)
    xe = _edges(w)
    _, colour, hatch, _ = VERDICT_STYLE[NO_VERDICT]
    for j, c in enumerate(np.nonzero(_codes(ds, False) == NO_VERDICT)[0]):
        a1.axvspan(xe[c], xe[c + 1], facecolor=colour, alpha=0.35, hatch=hatch, edgecolor="0.3",
                   lw=0.0, label="balanced state: no verdict" if j == 0 else None)
    g = ds["grade"].values
    kind = ds["best_kind"].values if "best_kind" in ds else np.zeros(w.size)
    a1.plot(w, g, "-", color="0.4", lw=0.8)
    for code, mk, lab in ((1, "o", "isolated equilibrium"), (2, "s", "balanced family"),
                          (3, "x", "balls in contact (kinetic-static)")):
        sel = kind == code
        if sel.any():
            a1.plot(w[sel], g[sel], mk, ms=3, label=f"best stable: {lab}")
    pos = g[np.isfinite(g) & (g > 0)]
    if pos.size:
        a1.set_yscale("log")
    a1.set_ylabel("grade of the best stable state [mm/s]")
    for ax in (a1, a2):
        for j, wn in enumerate(np.unique(np.atleast_1d(ds.attrs.get("natural_frequencies_rad_s", [])))):
            ax.axvline(wn / k, color="k", ls="--", lw=0.8, label="natural frequency" if j == 0 and ax is a1 else None)
        if "film_from_rad_s" in ds.attrs:           # beside a liquid: the films from here on
            ax.axvline(float(ds.attrs["film_from_rad_s"]) / k, color="tab:blue", ls=":", lw=1.0,
                       label="liquid a film (balanced states only, with the films)"
                       if ax is a1 else None)
        if w.size > 1:
            ax.set_xlim(w[0], w[-1])
    a1.legend(fontsize=7, loc="best")
    a1.set_title(f"{ds.attrs.get('machine', '')}: equilibria and stability ({ds.attrs.get('method', '')})",
                 fontsize=9)
    f = ds["damping_factor"].values
    z = _codes(ds, True).astype(float)
    cmap = ListedColormap([m[1] for m in VERDICT_STYLE])
    yy = np.arange(f.size + 1) - 0.5
    a2.pcolormesh(xe, yy, z, cmap=cmap, vmin=-0.5, vmax=len(VERDICT_STYLE) - 0.5, shading="flat")
    for i in range(f.size):                     # hatch the no-verdict cells
        for c in np.nonzero(z[i] == NO_VERDICT)[0]:
            a2.add_patch(_cell(xe[c], xe[c + 1], yy[i], yy[i + 1], hatch))
    a2.set_yticks(np.arange(f.size), [f"{v:g}" for v in f])
    a2.set_ylabel("suspension damping factor [-]")
    a2.set_xlabel(f"speed [{speed_unit}]")
    a2.legend(handles=[Patch(facecolor=c, hatch=h, edgecolor="0.3", label=lab)
                       for _, c, h, lab in VERDICT_STYLE],
              fontsize=7, loc="upper center", bbox_to_anchor=(0.5, -0.2), ncol=4, frameon=False)
    a2.set_title("balanced state over damping x speed", fontsize=9)
    return fig


def _cell(x0: float, x1: float, y0: float, y1: float, hatch: str):
    """A hatched, unfilled rectangle over one map cell (x [speed unit], y [row index])."""
    from matplotlib.patches import Rectangle

    return Rectangle((x0, y0), x1 - x0, y1 - y0, fill=False, hatch=hatch, edgecolor="0.3", lw=0.0)


def _edges(x: np.ndarray) -> np.ndarray:
    """Cell edges around the points x (geometric midpoints; half a step beyond the ends)."""
    x = np.asarray(x, float)
    if x.size == 1:
        return np.array([0.9 * x[0], 1.1 * x[0]])
    mid = np.sqrt(x[1:] * x[:-1])
    return np.concatenate([[x[0] ** 2 / mid[0]], mid, [x[-1] ** 2 / mid[-1]]])
