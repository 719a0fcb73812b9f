"""Figures of the washer analysis (000) for any machine: evaluate the closed forms of
:mod:`autobalance.physics` and draw them with :mod:`autobalance.plotting.washer` (which only
draws). Used by ``autobalance analyze``; the seed-000 targets compute their data in
:mod:`autobalance.papers.p000` and call the same ``*_figure`` functions."""
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
    """:func:`vibratory_force_figure` of ``system`` at ``speeds`` [rad/s] (one ball, mR = Me);
    ``labels`` replace the panel titles."""
    from ..physics.vibratory import single_ball_force

    speeds = list(np.atleast_1d(speeds))
    return vibratory_force_figure(_ALPHA, [single_ball_force(system, w, _ALPHA) for w in speeds],
                                  labels or _titles(system, speeds))



def plot_ball_forces(system: System, speeds: npt.ArrayLike, angles: npt.ArrayLike) -> Figure:
    """:func:`ball_forces_figure` of the machine's own balancer at ``speeds`` [rad/s]: each
    ball's vibratory force (000 eq 8, 39-42: its masses, R, rho, beta) against its own angle
    with the others at ``angles`` [rad], and its rest band +-f/r (its stiction)."""
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
    """:func:`residual_bound_figure` of the machine's own balancer: the true worst-case residual
    of its balls at rest (:func:`autobalance.physics.worst_case.residual_bound`, with its
    f/r or ``f_r`` [-], its rho, beta and damper friction) against ``speeds`` [rad/s], and each
    cause alone; blank below the balancing onset."""
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
    """:func:`vibratory_force_damping_figure` of ``system`` at ``speeds`` [rad/s] for the
    suspension damping factors ``damping_scales`` [-]."""
    from ..physics.vibratory import single_ball_force

    speeds = list(np.atleast_1d(speeds))
    return vibratory_force_damping_figure(
        _ALPHA, [[(c, single_ball_force(system, w, _ALPHA, damping_scale=c)["F_norm"])
                  for c in damping_scales] for w in speeds],
        _titles(system, speeds))



def plot_rolling_deviation(system: System, speeds: npt.ArrayLike,
                           f_r_values: Sequence[float] = (1e-3, 2e-3)) -> Figure:
    """:func:`rolling_deviation_figure` of ``system`` (eq 24) at ``speeds`` [rad/s] for the
    rolling resistances ``f_r_values`` [-]."""
    from ..physics.error_bounds import rolling_deadband_single

    w = np.asarray(speeds, float)
    return rolling_deviation_figure(w, {fr: rolling_deadband_single(system, w, fr)
                                        for fr in f_r_values}, system.natural_frequencies)



def plot_eccentricity_deviation(eccentricity: float, rhos: Sequence[float],
                                betas: npt.ArrayLike | None = None, system: System | None = None,
                                speed: float | None = None) -> Figure:
    """:func:`eccentricity_deviation_figure` of eq 45 for the eccentricity e [m] and ring
    eccentricities ``rhos`` [m] over ``betas`` [rad]; with ``system`` and ``speed`` [rad/s] also
    the exact root of eq 44 on every tenth beta."""
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
    """:func:`force_extreme_ratio_figure` of ``system`` at ``speeds`` [rad/s]."""
    from ..physics.vibratory import force_extreme_ratio

    w = np.asarray(speeds, float)
    return force_extreme_ratio_figure(w, force_extreme_ratio(system, w), system.natural_frequencies,
                                      published)
