"""Figures of the washer analysis and studies in the style of 000 Fig. 3, 5-7, 9-13, 15, 16, 18, 19
and Tables 1-4.

Matplotlib ``Figure`` objects on an Agg canvas (no pyplot). The ``*_figure`` functions and the
time-history / comparison plots take computed data (SI, angles in radians) and only convert units
and draw. The ``plot_*`` functions that take a ``system`` are adapters that first evaluate
:mod:`autobalance.physics` on a grid (kept for ``autobalance analyze``; the reproduction targets
compute their data in :mod:`autobalance.papers.p000` and call the ``*_figure`` functions).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from collections.abc import Iterable, Mapping, Sequence

    from numpy.typing import ArrayLike

__all__ = ["ball_forces_figure", "residual_bound_figure", "eccentricity_deviation_figure", "force_extreme_ratio_figure", "plot_ks_comparison", "plot_measured_vibration", "plot_published_vs_computed", "plot_runups", "plot_time_histories", "rolling_deviation_figure", "speed_title", "vibratory_force_damping_figure", "vibratory_force_figure"]


def _fig(size=(7.0, 4.5)) -> Figure:
    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _natural_lines(ax, natural_frequencies) -> None:
    """Vertical lines at w_x, w_y [rad/s] and the speed axis label."""
    for wn, name in zip(natural_frequencies, ("w_x", "w_y")):
        ax.axvline(wn, color="0.6", ls="--", lw=0.8)
        ax.text(wn, 0.95, name, transform=ax.get_xaxis_transform(), fontsize=8)
    ax.set_xlabel("spin speed w [rad/s]")


def _angle_panel(ax, title: str, xlabel: str) -> None:
    """Zero line, title, x label and 90-degree ticks of a force-vs-angle panel."""
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_title(title, fontsize=9)
    ax.set_xlabel(xlabel)
    ax.set_xticks(range(0, 361, 90))


def vibratory_force_figure(alpha: ArrayLike, forces: Sequence[Mapping[str, Any]],
                           titles: Sequence[str]) -> Figure:
    """000 Fig. 6: F_x, F_y and F = F_x + F_y over m R w^2 versus the ball angle, one panel per
    speed.

    Parameters
    ----------
    alpha : array
        Ball angles [rad] (drawn in degrees).
    forces : list of dict
        One per panel: ``Fx_norm``, ``Fy_norm``, ``F_norm`` [-] on ``alpha``
        (:func:`autobalance.physics.vibratory.single_ball_force`).
    titles : list of str
        Panel titles (e.g. the speed and its regime); prefixed a), b), ...
    """
    fig = _fig((4.2 * len(forces), 4.0))
    axes = fig.subplots(1, len(forces), squeeze=False)[0]
    a = np.degrees(alpha)
    for k, (ax, c, title) in enumerate(zip(axes, forces, titles)):
        ax.plot(a, c["Fx_norm"], "--", label="F_x")
        ax.plot(a, c["Fy_norm"], ":", label="F_y")
        ax.plot(a, c["F_norm"], "k-", label="F = F_x + F_y")
        _angle_panel(ax, f"{chr(97 + k)}) {title}", "ball angle alpha [deg]")
    axes[0].set_ylabel("F / (m R w^2) [-]")
    axes[0].legend(fontsize=8)
    fig.suptitle("Vibratory force on one ball, mR = Me (000 eq 11, Fig. 6)", fontsize=10)
    return fig


def ball_forces_figure(alpha: ArrayLike, panels: Sequence[Sequence[Mapping[str, Any]]],
                       titles: Sequence[str], name: str = "") -> Figure:
    """Vibratory force on each ball of a balancer versus its own angle, the other balls held at
    theirs, over m_i R w^2, with each ball's rest band +-f/r (000 eq 8, 20-21), one panel per
    speed.

    Parameters
    ----------
    alpha : array
        Ball angles [rad] (drawn in degrees).
    panels : list of list of dict
        One list per panel, one dict per ball: ``F_norm`` [-] on ``alpha``, ``f_r`` [-] (the
        band), ``at`` [rad] (the ball's own angle, marked).
    titles : list of str
        Panel titles (e.g. the speed and its regime); prefixed a), b), ...
    name : str
        The machine's name for the figure title.
    """
    fig = _fig((4.2 * len(panels), 4.0))
    axes = fig.subplots(1, len(panels), squeeze=False)[0]
    a = np.degrees(alpha)
    for k, (ax, balls, title) in enumerate(zip(axes, panels, titles)):
        for i, c in enumerate(balls):
            line, = ax.plot(a, c["F_norm"], label=f"ball {i + 1}")
            col = line.get_color()
            ax.axvline(np.degrees(np.mod(c["at"], 2 * math.pi)), color=col, ls=":", lw=0.8)
            if c["f_r"] > 0:
                ax.axhspan(-c["f_r"], c["f_r"], color=col, alpha=0.12)
        _angle_panel(ax, f"{chr(97 + k)}) {title}", "ball angle alpha_i [deg]")
    axes[0].set_ylabel("F_i / (m_i R w^2) [-]")
    axes[0].legend(fontsize=8)
    fig.suptitle(f"Vibratory force on each ball of {name or 'the balancer'}, others fixed; "
                 "shaded: rest band +-f/r (000 eq 8, 21)", fontsize=10)
    return fig


def residual_bound_figure(speeds: ArrayLike, curves: Mapping[str, ArrayLike],
                          natural_frequencies: tuple[float, float],
                          levels: Mapping[str, float] | None = None,
                          title: str = "") -> Figure:
    """Worst-case residual unbalance of balls at rest versus spin speed, by cause, with
    horizontal reference levels (e.g. the rotor's unbalance and the balls' capacity).

    Parameters
    ----------
    speeds : array
        Spin speeds w [rad/s].
    curves : dict
        label -> residual unbalance [kg*m] on ``speeds`` (NaN where not defined).
    natural_frequencies : (float, float)
        w_x, w_y [rad/s], drawn as vertical lines.
    levels : dict or None
        label -> unbalance [kg*m], drawn as horizontal dashed lines.
    title : str
        Figure title.
    """
    w = np.asarray(speeds, float)
    fig = _fig()
    ax = fig.subplots()
    for label, y in curves.items():
        y = np.asarray(y, float)
        ax.plot(w, np.where(y > 0, y, np.nan), label=label)
    for label, v in (levels or {}).items():
        ax.axhline(v, color="0.4", ls="--", lw=0.8)
        ax.text(w[0], v, f" {label}", fontsize=8, va="bottom")
    _natural_lines(ax, natural_frequencies)
    ax.set_ylabel("residual unbalance [kg m]")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.legend(fontsize=8)
    ax.set_title(title or "Worst-case residual unbalance of balls at rest", fontsize=10)
    return fig


def vibratory_force_damping_figure(alpha: ArrayLike,
                                   panels: Sequence[Sequence[tuple[float, ArrayLike]]],
                                   titles: Sequence[str]) -> Figure:
    """000 Fig. 7: F/(m R w^2) of one ball for several suspension damping factors, per speed.

    Parameters
    ----------
    alpha : array
        Ball angles [rad] (drawn in degrees).
    panels : list of list of (float, array)
        One list per panel of (damping factor [-], F/(m R w^2) [-] on ``alpha``).
    titles : list of str
        Panel titles.
    """
    fig = _fig((4.2 * len(panels), 4.0))
    axes = fig.subplots(1, len(panels), squeeze=False)[0]
    for ax, curves, title in zip(axes, panels, titles):
        for scale, F in curves:
            ax.plot(np.degrees(alpha), F, label=f"c x {scale:g}")
        ax.axhline(0, color="0.6", lw=0.8)
        ax.set_title(title, fontsize=9)
        ax.set_xlabel("ball angle alpha [deg]")
        ax.set_xticks(range(0, 361, 90))
    axes[0].set_ylabel("F / (m R w^2) [-]")
    axes[0].legend(fontsize=8)
    fig.suptitle("Vibratory force vs suspension damping (000 Fig. 7)", fontsize=10)
    return fig


def rolling_deviation_figure(speeds: ArrayLike, deviations: Mapping[float, ArrayLike],
                             natural_frequencies: tuple[float, float]) -> Figure:
    """000 Fig. 12: largest position error of one ball (eq 24) versus spin speed.

    Parameters
    ----------
    speeds : array
        Spin speeds w [rad/s].
    deviations : dict
        f/r [-] -> largest deviation [rad] on ``speeds`` (inf/nan where unbounded; drawn in
        degrees).
    natural_frequencies : (float, float)
        w_x, w_y [rad/s], drawn as vertical lines.
    """
    w = np.asarray(speeds, float)
    fig = _fig()
    ax = fig.subplots()
    for fr, d in deviations.items():
        ax.plot(w, np.degrees(np.where(np.isfinite(d), d, np.nan)), label=f"f/r = {fr:g}")
    _natural_lines(ax, natural_frequencies)
    ax.set_ylabel("max deviation [deg]")
    ax.set_yscale("log")
    ax.legend()
    ax.set_title("Position error from rolling resistance, one ball mR = Me (000 eq 24, Fig. 12)",
                 fontsize=10)
    return fig


def eccentricity_deviation_figure(
        betas: ArrayLike, eq45: Mapping[float, ArrayLike],
        exact: Mapping[float, tuple[ArrayLike, ArrayLike]] | None = None) -> Figure:
    """000 Fig. 15: deviation of one ball from alpha = pi versus beta (eq 45) for several rho,
    optionally with the exact kinetic-static root of eq 44 (dots).

    Parameters
    ----------
    betas : array
        Eccentricity angles beta [rad] (drawn in degrees).
    eq45 : dict
        rho [m] -> deviation of eq 45 [rad] on ``betas``; drawn in degrees, blank beyond 90 deg
        (eq 45 diverges where e + rho cos(beta) = 0).
    exact : dict or None
        rho [m] -> (betas [rad], deviation [rad]) of the exact root.
    """
    b = np.asarray(betas, float)
    fig = _fig()
    ax = fig.subplots()
    for rho, dev in eq45.items():
        d = np.degrees(dev)
        d = np.where(np.abs(d) > 90.0, np.nan, d)
        line, = ax.plot(np.degrees(b), d, label=f"rho = {rho * 1e3:g} mm (eq 45)")
        if exact is not None and rho in exact:
            bb, ex = exact[rho]
            ax.plot(np.degrees(bb), np.degrees(ex), "o", color=line.get_color(), ms=3)
    ax.axhline(0, color="0.6", lw=0.8)
    ax.set_xlabel("beta [deg]")
    ax.set_ylabel("Delta alpha_rho [deg]")
    ax.set_xticks(range(0, 361, 60))
    ax.legend(fontsize=8)
    ax.set_title("Ball deviation from the race eccentricity (000 eq 45, Fig. 15)", fontsize=10)
    return fig


def force_extreme_ratio_figure(speeds: ArrayLike, ratio: ArrayLike,
                               natural_frequencies: tuple[float, float],
                               published: float | None = None) -> Figure:
    """000 Fig. 6: -min F / max F of the one-ball vibratory force versus the spin speed, the
    range between the natural frequencies shaded and the published ratio as a dashed line.

    Parameters
    ----------
    speeds : array
        Spin speeds w [rad/s].
    ratio : array
        -min F / max F [-] on ``speeds``
        (:func:`autobalance.physics.vibratory.force_extreme_ratio`).
    natural_frequencies : (float, float)
        w_x, w_y [rad/s].
    published : float or None
        The published ratio [-].
    """
    fig = _fig()
    ax = fig.subplots()
    ax.plot(np.asarray(speeds, float), ratio, "k-", label="ours (eq 11)")
    wx, wy = natural_frequencies
    ax.axvspan(min(wx, wy), max(wx, wy), color="0.9", label="between w_y and w_x")
    if published is not None:
        ax.axhline(published, color="tab:red", ls="--", label=f"000 Fig. 6b: {published:g}")
    ax.set_yscale("log")
    ax.set_xlabel("spin speed w [rad/s]")
    ax.set_ylabel("-min F / max F [-]")
    ax.legend(fontsize=8)
    ax.set_title("Negative vs positive extreme of the vibratory force, one ball (000 Fig. 6)",
                 fontsize=10)
    return fig


# -- figures of data computed elsewhere (the closed-form curves of any machine are evaluated in
# -- autobalance.studies.washer_figures and drawn by the *_figure functions above)


def speed_title(speed: float, regime: str) -> str:
    """Panel title of a speed: "w = ... rad/s (regime)".

    Parameters
    ----------
    speed : float
        Spin speed w [rad/s].
    regime : str
        Its regime (:func:`autobalance.physics.vibratory.speed_regime`).
    """
    return f"w = {speed:.3g} rad/s ({regime})"


def plot_ks_comparison(comparison: dict) -> Figure:
    """000 Fig. 9: D_x, D_y [um] and D_alpha [rad] between the full and the kinetic-static model,
    from :func:`autobalance.simulate.kinetic_static.compare_with_full`."""
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


def _ideal_lines(ax, alpha_deg, ideal_deg):
    """Dashed lines at the ideal angles, shifted by whole turns next to where the balls end."""
    for a_end, ideal in zip(alpha_deg[-1], ideal_deg):
        ax.axhline(ideal + 360.0 * round((a_end - ideal) / 360.0), color="0.5", ls="--", lw=0.8)


def plot_time_histories(runs: Sequence[Mapping[str, Any]], title: str) -> Figure:
    """Constant-speed runs in the style of 000 Fig. 5, 13, 16, 18, 19: drum displacement x, y [mm]
    and ball angles alpha [deg] versus w t [rad], one column per run.

    ``runs``: dicts with "label", "t_s", "x_m", "y_m", "alpha_rad" (n_t, N), "speed_rad_s" (float)
    and optionally "ideal_deg" (dashed lines at the ideal ball angles)."""
    fig = _fig((4.6 * len(runs), 5.5))
    axes = fig.subplots(2, len(runs), squeeze=False, sharex="col")
    for k, r in enumerate(runs):
        wt = np.asarray(r["t_s"]) * r["speed_rad_s"]
        ax = axes[0, k]
        ax.plot(wt, np.asarray(r["x_m"]) * 1e3, lw=0.5, label="x")
        ax.plot(wt, np.asarray(r["y_m"]) * 1e3, lw=0.5, label="y", alpha=0.8)
        ax.set_ylabel("drum x, y [mm]")
        ax.set_title(r["label"], fontsize=9)
        ax.legend(fontsize=8, loc="upper right")
        ax = axes[1, k]
        a = np.degrees(np.asarray(r["alpha_rad"]))
        for i in range(a.shape[1]):
            ax.plot(wt, a[:, i], lw=0.9, label=f"ball {i + 1}")
        if r.get("ideal_deg") is not None:
            _ideal_lines(ax, a, r["ideal_deg"])
        ax.set_ylabel("alpha [deg]")
        ax.set_xlabel("w t [rad]")
        ax.legend(fontsize=8, loc="upper right")
    fig.suptitle(title, fontsize=10)
    return fig


def plot_runups(panels: Sequence[tuple[str, Sequence[Mapping[str, Any]]]], title: str,
                envelope: bool = False) -> Figure:
    """Run-ups in the style of 000 Fig. 10-11 (and the runs of Tables 1-2): spin speed n [rpm],
    drum x and y [mm] (or, with ``envelope``, the whirl amplitude |x + i y| [mm]) and the ball
    angles relative to the drum [rev] versus t [s], one column per panel and one line style per run.

    ``panels``: (panel title, runs); a run is a dict with "label", "t_s", "speed_rad_s", "x_m",
    "y_m", "amplitude_m", "alpha_rad" (n_t, N; N may be 0) and optionally "style" (matplotlib
    kwargs)."""
    drum = (("amplitude_m", "whirl amplitude [mm]"),) if envelope else (("x_m", "drum x [mm]"),
                                                                        ("y_m", "drum y [mm]"))
    nrow = 2 + len(drum)
    fig = _fig((5.0 * len(panels), 2.0 * nrow))
    axes = fig.subplots(nrow, len(panels), squeeze=False, sharex="col")
    for k, (name, runs) in enumerate(panels):
        for r in runs:
            t = np.asarray(r["t_s"])
            st = {"lw": 0.7, **r.get("style", {})}
            line, = axes[0, k].plot(t, np.asarray(r["speed_rad_s"]) * 30 / math.pi, label=r["label"], **st)
            st.setdefault("color", line.get_color())
            for j, (key, _) in enumerate(drum):
                axes[1 + j, k].plot(t, np.asarray(r[key]) * 1e3, **{**st, "lw": 0.4})
            a = np.asarray(r["alpha_rad"])
            for i in range(a.shape[1] if a.ndim == 2 else 0):
                axes[-1, k].plot(t, (a[:, i] - a[0, i]) / (2 * math.pi), **st)
        axes[0, k].set_title(name, fontsize=9)
        axes[0, k].legend(fontsize=7)
        axes[-1, k].set_xlabel("t [s]")
    labels = ("n [rpm]",) + tuple(lab for _, lab in drum) + ("ball angle - start [rev]",)
    for ax, lab in zip(axes[:, 0], labels):
        ax.set_ylabel(lab)
    fig.suptitle(title, fontsize=10)
    return fig


def plot_published_vs_computed(panels: Sequence[Mapping[str, Any]], title: str,
                               ncols: int | None = None) -> Figure:
    """Published numbers (black circles) against ours (red crosses), with each row's acceptance
    interval as a grey bar; one axes per panel (000 Tables 1-4).

    ``panels``: dicts with "title", "ylabel", "labels" (one per row), "published", "computed"
    (NaN where not computed) and optionally "xlabel" and "lo", "hi" (the interval in the units
    of the axis)."""
    n = len(panels)
    nc = ncols or min(n, 4)
    nr = int(math.ceil(n / nc))
    fig = _fig((3.6 * nc, 3.2 * nr))
    axes = np.atleast_1d(fig.subplots(nr, nc, squeeze=False)).ravel()
    for ax, p in zip(axes, panels):
        x = np.arange(len(p["labels"]))
        if p.get("lo") is not None:
            lo, hi = np.asarray(p["lo"], float), np.asarray(p["hi"], float)
            ax.vlines(x, lo, hi, color="0.75", lw=6, label="tolerance")
        ax.plot(x, p["published"], "ko", ms=5, mfc="none", label="published")
        ax.plot(x, np.asarray(p["computed"], float), "rx", ms=6, label="ours")
        ax.set_xticks(x, p["labels"], fontsize=7, rotation=30 if max(map(len, p["labels"])) > 4 else 0)
        ax.set_ylabel(p["ylabel"])
        if p.get("xlabel"):
            ax.set_xlabel(p["xlabel"])
        ax.set_title(p["title"], fontsize=9)
    for ax in axes[n:]:
        ax.set_visible(False)
    axes[0].legend(fontsize=7)
    fig.suptitle(title, fontsize=10)
    return fig


def plot_measured_vibration(points: Iterable[tuple[float, float, str]], speeds_rpm: ArrayLike,
                            model_amplitude_m: ArrayLike, model_label: str) -> Figure:
    """000 Fig. 3: tub vibration amplitudes converted from the measured accelerations (points)
    and a model curve, amplitude [mm] versus the spin speed n [rpm].

    ``points``: (n [rpm], amplitude [m], label) of the published measurements."""
    fig = _fig()
    ax = fig.subplots()
    ax.plot(speeds_rpm, np.asarray(model_amplitude_m) * 1e3, "k-", lw=1, label=model_label)
    for n, a, lab in points:
        ax.plot(n, a * 1e3, "o", ms=6, label=lab)
    ax.set_xlabel("spin speed n [rpm]")
    ax.set_ylabel("tub amplitude [mm]")
    ax.legend(fontsize=8)
    ax.set_title("Tub vibration: measured accelerations / w^2 (000 Fig. 3) and the drum model",
                 fontsize=10)
    return fig
