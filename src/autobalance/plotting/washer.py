"""Figures of the washer analysis in the style of 000 Fig. 6, 7, 9, 12 and 15.

Matplotlib ``Figure`` objects on an Agg canvas (no pyplot). The physics is computed by
:mod:`autobalance.analysis` functions called here; this module only converts units and draws.
"""
from __future__ import annotations

import math

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["plot_eccentricity_deviation", "plot_ks_comparison", "plot_rolling_deviation",
           "plot_vibratory_force", "plot_vibratory_force_damping"]


def _fig(size=(7.0, 4.5)) -> Figure:
    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def plot_vibratory_force(system, speeds, labels=None) -> Figure:
    """000 Fig. 6: F_x, F_y and F = F_x + F_y over m R w^2 versus the ball angle, one ball with
    mR = Me, one panel per speed [rad/s] (e.g. above both natural frequencies and between them)."""
    from ..analysis.vibratory import single_ball_force, speed_regime

    speeds = list(np.atleast_1d(speeds))
    fig = _fig((4.2 * len(speeds), 4.0))
    axes = fig.subplots(1, len(speeds), squeeze=False)[0]
    al = np.linspace(0, 2 * math.pi, 361)
    for k, (ax, w) in enumerate(zip(axes, speeds)):
        c = single_ball_force(system, w, al)
        ax.plot(np.degrees(al), c["Fx_norm"], "--", label="F_x")
        ax.plot(np.degrees(al), c["Fy_norm"], ":", label="F_y")
        ax.plot(np.degrees(al), c["F_norm"], "k-", label="F = F_x + F_y")
        ax.axhline(0, color="0.6", lw=0.8)
        lab = labels[k] if labels else f"w = {w:.3g} rad/s ({speed_regime(system, w)})"
        ax.set_title(f"{chr(97 + k)}) {lab}", fontsize=9)
        ax.set_xlabel("ball angle alpha [deg]")
        ax.set_xticks(range(0, 361, 90))
    axes[0].set_ylabel("F / (m R w^2) [-]")
    axes[0].legend(fontsize=8)
    fig.suptitle("Vibratory force on one ball, mR = Me (000 eq 11, Fig. 6)", fontsize=10)
    return fig


def plot_vibratory_force_damping(system, speeds, damping_scales=(0.5, 1.0, 2.0)) -> Figure:
    """000 Fig. 7: F/(m R w^2) of one ball for several suspension damping factors, per speed."""
    from ..analysis.vibratory import single_ball_force, speed_regime

    speeds = list(np.atleast_1d(speeds))
    fig = _fig((4.2 * len(speeds), 4.0))
    axes = fig.subplots(1, len(speeds), squeeze=False)[0]
    al = np.linspace(0, 2 * math.pi, 361)
    for ax, w in zip(axes, speeds):
        for ds in damping_scales:
            c = single_ball_force(system, w, al, damping_scale=ds)
            ax.plot(np.degrees(al), c["F_norm"], label=f"c x {ds:g}")
        ax.axhline(0, color="0.6", lw=0.8)
        ax.set_title(f"w = {w:.3g} rad/s ({speed_regime(system, w)})", fontsize=9)
        ax.set_xlabel("ball angle alpha [deg]")
        ax.set_xticks(range(0, 361, 90))
    axes[0].set_ylabel("F / (m R w^2) [-]")
    axes[0].legend(fontsize=8)
    fig.suptitle("Vibratory force vs suspension damping (000 Fig. 7)", fontsize=10)
    return fig


def plot_rolling_deviation(system, speeds, f_r_values=(1e-3, 2e-3)) -> Figure:
    """000 Fig. 12: largest position error of one ball (eq 24) versus spin speed [rad/s]."""
    from ..analysis.error_bounds import rolling_deadband_single

    w = np.asarray(speeds, float)
    fig = _fig()
    ax = fig.subplots()
    for fr in f_r_values:
        d = rolling_deadband_single(system, w, fr)
        ax.plot(w, np.degrees(np.where(np.isfinite(d), d, np.nan)), label=f"f/r = {fr:g}")
    for wn, name in zip(system.natural_frequencies, ("w_x", "w_y")):
        ax.axvline(wn, color="0.6", ls="--", lw=0.8)
        ax.text(wn, 0.95, name, transform=ax.get_xaxis_transform(), fontsize=8)
    ax.set_xlabel("spin speed w [rad/s]")
    ax.set_ylabel("max deviation [deg]")
    ax.set_yscale("log")
    ax.legend()
    ax.set_title("Position error from rolling resistance, one ball mR = Me (000 eq 24, Fig. 12)",
                 fontsize=10)
    return fig


def plot_eccentricity_deviation(eccentricity, rhos, betas=None, system=None, speed=None) -> Figure:
    """000 Fig. 15: deviation of one ball from alpha = pi versus beta (eq 45) for several rho [m];
    with ``system`` and ``speed`` also the exact kinetic-static root of eq 44 (dots)."""
    import dataclasses

    from ..analysis.equilibria import find_equilibria
    from ..analysis.error_bounds import eccentricity_deviation_single

    b = np.linspace(0, 2 * math.pi, 181) if betas is None else np.asarray(betas, float)
    fig = _fig()
    ax = fig.subplots()
    for rho in rhos:
        d = np.degrees(eccentricity_deviation_single(eccentricity, rho, b))
        d = np.where(np.abs(d) > 90.0, np.nan, d)        # eq 45 diverges where e + rho cos(beta) = 0
        line, = ax.plot(np.degrees(b), d,
                        label=f"rho = {rho * 1e3:g} mm (eq 45)")
        if system is not None and speed is not None:
            bb = b[::10]
            ex = []
            for beta in bb:
                bal = dataclasses.replace(system.balancer, eccentricity=rho, eccentricity_angle=beta)
                s1 = dataclasses.replace(system, balancer=bal)
                st = [e for e in find_equilibria(s1, speed) if e.ks_stable]
                dev = [np.angle(np.exp(1j * (e.alpha[0] - math.pi))) for e in st]
                ex.append(min(dev, key=abs) if dev else np.nan)
            ax.plot(np.degrees(bb), np.degrees(ex), "o", color=line.get_color(), ms=3)
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_xlabel("beta [deg]")
    ax.set_ylabel("Delta alpha_rho [deg]")
    ax.set_xticks(range(0, 361, 60))
    ax.legend(fontsize=8)
    ax.set_title("Ball deviation from the race eccentricity (000 eq 45, Fig. 15)", fontsize=10)
    return fig


def plot_ks_comparison(comparison: dict) -> Figure:
    """000 Fig. 9: D_x, D_y [um] and D_alpha [rad] between the full and the kinetic-static model,
    from :func:`autobalance.analysis.kinetic_static.compare_with_full`."""
    t = np.asarray(comparison["t_s"])
    fig = _fig((7.0, 6.0))
    ax = fig.subplots(3, 1, sharex=True)
    ax[0].plot(t, np.asarray(comparison["D_x_m"]) * 1e6, lw=0.6)
    ax[0].set_ylabel("D_x [um]")
    ax[1].plot(t, np.asarray(comparison["D_y_m"]) * 1e6, lw=0.6, color="tab:orange")
    ax[1].set_ylabel("D_y [um]")
    da = np.asarray(comparison["D_alpha_rad"])
    for i in range(da.shape[1]):
        ax[2].plot(t, da[:, i], lw=0.8, label=f"ball {i + 1}")
    ax[2].set_ylabel("D_alpha [rad]")
    ax[2].set_xlabel("t [s]")
    ax[2].legend(fontsize=8)
    fig.suptitle("Full model minus kinetic-static model (000 Fig. 9)", fontsize=10)
    return fig
