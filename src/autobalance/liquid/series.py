"""Time series of a liquid run: the spin angle of a linear speed table, the revolution average
that separates the synchronous moment from gravity's standing part, and the film runs' output
density (:mod:`.simulate`, and balls beside a liquid: :mod:`autobalance.simulate.hybrid`)."""
from __future__ import annotations

import numpy as np
import numpy.typing as npt

__all__ = ["film_samples", "revolution_average", "spin_angle"]


def revolution_average(psi: npt.ArrayLike, values: npt.ArrayLike) -> np.ndarray:
    """The mean of ``values`` over one revolution of the spin angle around each sample,
    (1/2 pi) integral over [psi - pi, psi + pi] of values d(psi) (trapezoid rule); within half
    a revolution of either end of the run the window is the first or last whole revolution (the
    whole run if it is shorter). A component turning at -Omega in the rotor frame (gravity's)
    averages out exactly at constant speed.

    Parameters
    ----------
    psi : array_like
        Spin angle at the samples, increasing [rad].
    values : array_like
        Samples (real or complex) [any unit].

    Returns
    -------
    ndarray
        The averages, in the unit of ``values``.
    """
    p = np.asarray(psi, float)
    v = np.asarray(values)
    c = np.concatenate([[0.0], np.cumsum(0.5 * (v[1:] + v[:-1]) * np.diff(p))])
    span = min(2 * np.pi, p[-1] - p[0])
    lo = np.clip(p - 0.5 * span, p[0], p[-1] - span)
    hi = lo + span

    def cum(x):
        return np.interp(x, p, c.real) + (1j * np.interp(x, p, c.imag) if np.iscomplexobj(c)
                                          else 0.0)

    return (cum(hi) - cum(lo)) / max(span, 1e-300)


def spin_angle(t: npt.ArrayLike, tt: np.ndarray, ww: np.ndarray) -> np.ndarray:
    """The spin angle [rad] at the times t of a linear speed table, 0 at tt[0]: exact (the
    integral of the linear speed).

    Parameters
    ----------
    t : array_like
        Times [s].
    tt : ndarray
        The table's times, increasing [s].
    ww : ndarray
        Its speeds [rad/s].
    """
    t = np.asarray(t, float)
    psi_knots = np.concatenate([[0.0], np.cumsum(0.5 * (ww[1:] + ww[:-1]) * np.diff(tt))])
    i = np.clip(np.searchsorted(tt, t, side="right") - 1, 0, tt.size - 2)
    tau = t - tt[i]
    slope = (ww[i + 1] - ww[i]) / (tt[i + 1] - tt[i])
    return psi_knots[i] + ww[i] * tau + 0.5 * slope * tau * tau


def film_samples(tt: np.ndarray, ww: np.ndarray) -> int:
    """Output samples of a film run over a speed table [-]: 1001, or 8 per revolution if more
    (for :func:`revolution_average`), at most 200 001.

    Parameters
    ----------
    tt : ndarray
        The table's times, increasing [s].
    ww : ndarray
        Its speeds [rad/s].
    """
    psi_end = np.cumsum(0.5 * (ww[1:] + ww[:-1]) * np.diff(tt))[-1]
    return int(min(max(1001, 8 * psi_end / (2 * np.pi) + 1), 200001))
