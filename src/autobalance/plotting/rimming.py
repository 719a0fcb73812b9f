"""Figure of the liquid on a horizontal axis in time (:func:`autobalance.liquid.rimming.
rimming_run`): data in, a matplotlib Figure out; the caller saves."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from .timeplot import _new_figure

if TYPE_CHECKING:
    from collections.abc import Sequence

    from matplotlib.figure import Figure

__all__ = ["rimming_figure"]


def rimming_figure(runs: Sequence, labels: Sequence[str], film_start: float,
                   title: str = "") -> Figure:
    """Left: the chamber's speed and the liquid's mean speed over time, the film model's start
    speed dotted, each run's end marked (its status in the legend). Right: the thinnest and
    thickest cell over the mean thickness, and the share of the liquid held by nothing (on a
    log axis, zeros drawn at 1e-4).

    Parameters
    ----------
    runs : sequence of RimSpinUp
        One run per chamber.
    labels : sequence of str
        Their legend labels.
    film_start : float
        The film model's start speed [rad/s] (dotted).
    title : str
        Figure title.
    """
    fig = _new_figure((11, 4.5))
    a, b = fig.subplots(1, 2)
    for r, lab in zip(runs, labels):
        line, = a.plot(r.t, r.speed, color="0.5", lw=0.9)
        line, = a.plot(r.t, r.liquid_speed, label=f"{lab}: liquid ({r.status} at "
                       f"{r.stop_time:.3g} s)")
        a.plot(r.t[-1], r.liquid_speed[-1], "o", color=line.get_color())
        mean = np.mean(r.depth[0])
        floor = 1e-4                                     # zeros, on the log axis
        b.plot(r.t, np.maximum(r.depth.min(axis=1) / mean, floor), color=line.get_color(),
               label=f"{lab}: thinnest")
        b.plot(r.t, r.depth.max(axis=1) / mean, color=line.get_color(), ls="--",
               label="thickest")
        b.plot(r.t, np.maximum(r.loose, floor), color=line.get_color(), ls=":",
               label="share held by nothing")
    a.axhline(film_start, color="0.3", ls=":", lw=1.0)
    a.set(xlabel="time [s]", ylabel="speed [rad/s]",
          title="chamber (grey) and liquid (dotted: the film model's start)")
    b.set(xlabel="time [s]", ylabel="over the mean thickness [-]", yscale="log",
          title="the layer")
    a.legend(fontsize=8)
    b.legend(fontsize=8)
    a.grid(alpha=0.3)
    b.grid(alpha=0.3, which="both")
    if title:
        fig.suptitle(title)
    return fig
