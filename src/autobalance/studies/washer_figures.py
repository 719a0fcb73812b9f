"""Figures of the washer analysis (000) for any machine: evaluate the closed forms of
:mod:`autobalance.physics` and draw them with :mod:`autobalance.plotting.washer` (which only
draws). ``autobalance analyze`` draws its ``--plot`` figures with these; the seed-000 targets
compute their data in :mod:`autobalance.papers.p000` and call the same ``*_figure`` functions."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from matplotlib.figure import Figure

from ..plotting.washer import (ball_forces_figure, eccentricity_deviation_figure, force_extreme_ratio_figure,
                               residual_bound_figure, rolling_deviation_figure, speed_title,
                               vibratory_force_damping_figure, vibratory_force_figure)

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from ..models import System

__all__ = ["plot_ball_forces", "plot_residual_bound", "plot_vibratory_force",
           "plot_vibratory_force_damping", "plot_rolling_deviation", "plot_eccentricity_deviation",
           "plot_force_extreme_ratio"]

_ALPHA = np.linspace(0, 2 * math.pi, 361)


def _titles(system, speeds) -> list:
    from ..physics.vibratory import speed_regime

    return [speed_title(w, speed_regime(system, w)) for w in speeds]


def plot_vibratory_force(system: System, speeds: npt.ArrayLike,
                         labels: Sequence[str] | None = None) -> Figure:
    """:func:`~autobalance.plotting.washer.vibratory_force_figure`: the normalised vibratory
    force on one ball (mR = Me) against its angle, 000 eq (11), Fig. 6.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (its drum, suspension and race radius).
    speeds : float or array_like
        Spin speeds w [rad/s], > 0: one panel each.
    labels : sequence of str, optional
        Panel titles (default the speed and its regime).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..physics.vibratory import single_ball_force

    speeds = list(np.atleast_1d(speeds))
    return vibratory_force_figure(_ALPHA, [single_ball_force(system, w, _ALPHA) for w in speeds],
                                  labels or _titles(system, speeds))


def plot_ball_forces(system: System, speeds: npt.ArrayLike, angles: npt.ArrayLike) -> Figure:
    """:func:`~autobalance.plotting.washer.ball_forces_figure` of the machine's own balancer:
    each ball's vibratory force (000 eq 8, 39-42: its masses, R, rho, beta) against its own
    angle with the others held, and its rest band +-f/r (its stiction; eq 21).

    Parameters
    ----------
    system : autobalance.models.System
        The machine (N >= 1 balls).
    speeds : float or array_like
        Spin speeds w [rad/s], > 0: one panel each.
    angles : array_like (N,)
        The balls' angles [rad] at which the others are held.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..physics.vibratory import vibratory_forces

    b = system.balancer
    a0 = np.asarray(angles, float)
    speeds = list(np.atleast_1d(speeds))
    panels = []
    for w in speeds:
        balls = []
        for i in range(b.n_balls):
            grid = np.repeat(a0[None, :], _ALPHA.size, axis=0)
            grid[:, i] = _ALPHA
            F = vibratory_forces(system, w, grid)[:, i]
            balls.append({"F_norm": F / (b.masses[i] * b.race_radius * w * w),
                          "f_r": float(b.stiction[i]), "at": float(a0[i])})
        panels.append(balls)
    return ball_forces_figure(_ALPHA, panels, _titles(system, speeds), system.name)


def plot_residual_bound(system: System, speeds: npt.ArrayLike,
                        f_r: float | npt.ArrayLike | None = None) -> Figure:
    """:func:`~autobalance.plotting.washer.residual_bound_figure` of the machine's own
    balancer: the true worst-case residual of its balls at rest
    (:func:`autobalance.physics.worst_case.residual_bound`; 000 eq 20-22, 46-49) with its rho,
    beta and damper friction against speed, and each cause alone; blank below the balancing
    onset (000 eq 12).

    Parameters
    ----------
    system : autobalance.models.System
        The machine (N >= 1 balls).
    speeds : array_like
        Spin speeds w [rad/s], > 0.
    f_r : float or array_like, optional
        Rolling-resistance coefficient f/r [-], one or one per ball (default its stiction).

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..physics.worst_case import residual_bound

    w = np.asarray(speeds, float)
    mu = system.balancer.stiction if f_r is None else f_r
    keys = {"all causes (true bound)": {},
            "rolling resistance alone": {"eccentricity": 0.0, "friction_force": 0.0},
            "eccentricity alone": {"rolling_resistance": 0.0, "friction_force": 0.0},
            "suspension friction alone": {"rolling_resistance": 0.0, "eccentricity": 0.0}}
    curves = {k: np.full(w.shape, np.nan) for k in keys}
    for j, wj in enumerate(w):
        for label, kw in keys.items():
            r = residual_bound(system, wj, **{"rolling_resistance": mu, **kw})
            if r["balancing"]:
                curves[label][j] = r["worst_residual_kg_m"]
    b = system.balancer
    levels = {"rotor unbalance U": system.rotor.unbalance,
              "capacity sum m_i R": float(np.sum(b.masses) * b.race_radius)}
    mu_txt = ", ".join(f"{v:g}" for v in sorted(set(np.atleast_1d(mu).tolist())))
    return residual_bound_figure(w, curves, system.natural_frequencies, levels,
                                 f"{system.name or 'machine'}: worst-case residual at rest, "
                                 f"{b.n_balls} balls, f/r = {mu_txt}")


def plot_vibratory_force_damping(system: System, speeds: npt.ArrayLike,
                                 damping_scales: Sequence[float] = (0.5, 1.0, 2.0)) -> Figure:
    """:func:`~autobalance.plotting.washer.vibratory_force_damping_figure`: the one-ball
    vibratory force (000 eq 11) for scaled suspension damping, 000 Fig. 7.

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speeds : float or array_like
        Spin speeds w [rad/s], > 0: one panel each.
    damping_scales : sequence of float
        Factors on the suspension damping c_x, c_y [-].

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..physics.vibratory import single_ball_force

    speeds = list(np.atleast_1d(speeds))
    return vibratory_force_damping_figure(
        _ALPHA, [[(c, single_ball_force(system, w, _ALPHA, damping_scale=c)["F_norm"])
                  for c in damping_scales] for w in speeds],
        _titles(system, speeds))


def plot_rolling_deviation(system: System, speeds: npt.ArrayLike,
                           f_r_values: Sequence[float] = (1e-3, 2e-3)) -> Figure:
    """:func:`~autobalance.plotting.washer.rolling_deviation_figure`: the largest position
    error of one ball from rolling resistance against speed, 000 eq (24), Fig. 12.

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speeds : array_like
        Spin speeds w [rad/s], > 0.
    f_r_values : sequence of float
        Rolling-resistance coefficients f/r [-]: one curve each.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..physics.error_bounds import rolling_deadband_single

    w = np.asarray(speeds, float)
    return rolling_deviation_figure(w, {fr: rolling_deadband_single(system, w, fr)
                                        for fr in f_r_values}, system.natural_frequencies)


def plot_eccentricity_deviation(eccentricity: float, rhos: Sequence[float],
                                betas: npt.ArrayLike | None = None, system: System | None = None,
                                speed: float | None = None) -> Figure:
    """:func:`~autobalance.plotting.washer.eccentricity_deviation_figure`: the one-ball error
    from a race eccentricity, 000 eq (45), and with ``system`` and ``speed`` also the exact
    root of eq (44) on every tenth beta.

    Parameters
    ----------
    eccentricity : float
        Rotor eccentricity e = Me/M [m], > 0.
    rhos : sequence of float
        Race eccentricities rho [m]: one curve each.
    betas : array_like, optional
        Race eccentricity angles beta [rad] (default 0 to 2 pi, 181 points).
    system : autobalance.models.System, optional
        The machine of the exact root.
    speed : float, optional
        Spin speed w [rad/s] of the exact root, > 0.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..physics.error_bounds import eccentricity_deviation_exact, eccentricity_deviation_single

    b = np.linspace(0, 2 * math.pi, 181) if betas is None else np.asarray(betas, float)
    exact = None
    if system is not None and speed is not None:
        exact = {rho: (b[::10], eccentricity_deviation_exact(system, speed, rho, b[::10]))
                 for rho in rhos}
    return eccentricity_deviation_figure(
        b, {rho: eccentricity_deviation_single(eccentricity, rho, b) for rho in rhos}, exact)


def plot_force_extreme_ratio(system: System, speeds: npt.ArrayLike,
                             published: float | None = None) -> Figure:
    """:func:`~autobalance.plotting.washer.force_extreme_ratio_figure`: the ratio of the
    negative to the positive extreme of the one-ball vibratory force, 000 eq (11), Fig. 6.

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speeds : array_like
        Spin speeds w [rad/s], > 0.
    published : float, optional
        The published ratio [-], drawn as a line.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..physics.vibratory import force_extreme_ratio

    w = np.asarray(speeds, float)
    return force_extreme_ratio_figure(w, force_extreme_ratio(system, w), system.natural_frequencies,
                                      published)
