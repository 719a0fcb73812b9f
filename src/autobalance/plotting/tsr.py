"""Figures of the start-position, unbalance, plateau and immobility studies
(:mod:`autobalance.studies`; seed 004's figures and the same studies of any machine): read the
study datasets, compute no physics. Each function returns a matplotlib Figure on the Agg canvas.

* :func:`plot_single` - 004 Fig. 4: amplitude with/without balancer, ball positions, COG (grade);
* :func:`plot_monte_carlo` - Fig. 5-6: PDFs of G_STD and G_TSR, each run's TSR vs STD grade;
* :func:`plot_unbalance` - Fig. 7, 11-12: 5/95 % isolines against G_ini, operating boundaries;
* :func:`plot_profile` - Fig. 9: 95 % isolines of STD, TSR and a 3x slower run-up;
* :func:`plot_immobility` - Fig. 8, 10: immobility against speed for the mu_r x c_r sets;
* :func:`plot_plateau` - Fig. 14-16: 95 % residual grade over lower plateau x G_ini;
* :func:`plot_descent` - Fig. 13: residual grade percentiles along a gradual speed reduction;
* :func:`plot_speed_profile` - Fig. 3: the standardised speed profile;
* :func:`plot_start_positions` - any machine: the grade at each read-out over start positions.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    import xarray as xr

G_LIMIT = 16.0


def _fig(n, w=5.0, h=4.2, polar=()):
    fig = Figure(figsize=(w * n, h), constrained_layout=True)
    FigureCanvasAgg(fig)
    axes = [fig.add_subplot(1, n, i + 1, projection="polar" if i in polar else None)
            for i in range(n)]
    return fig, axes


def plot_single(ds: xr.Dataset) -> Figure:
    """004 Fig. 4 from :func:`compute_single`."""
    fig, (a1, a2, a3) = _fig(3, polar=(1, 2))
    t = ds["time"].values
    a1.plot(t, ds["amplitude"].values * 1e6, lw=0.8, label="with balancer")
    a1.plot(t, ds["amplitude_no_balancer"].values * 1e6, "--", lw=0.8, label="without balancer")
    a1.set_xlabel("time [s]")
    a1.set_ylabel("amplitude [um]")
    ax2 = a1.twinx()
    ax2.plot(t, ds["speed"].values / (2 * np.pi), "k:", lw=0.8)
    ax2.set_ylabel("speed [Hz]")
    a1.legend(fontsize=8)
    a1.set_title("amplitude")
    for b in range(ds.sizes["ball"]):
        a2.plot(ds["ball_angle"].values[:, b], t, lw=0.8, label=f"ball {b + 1}")
    a2.set_title("ball position (radius = time [s])", fontsize=9)
    a2.legend(fontsize=7, loc="lower left")
    G = ds["grade_G"].values
    a3.plot(ds["cog_angle"].values, G, lw=0.8)
    a3.plot(np.linspace(0, 2 * np.pi, 200), np.full(200, G_LIMIT), "r--", lw=0.8)
    k = int(np.argmin(np.abs(t - ds.attrs["t_std_s"])))
    a3.plot(ds["cog_angle"].values[0], G[0], "o", mfc="none", label=f"start G{G[0]:.1f}")
    a3.plot(ds["cog_angle"].values[k], G[k], "ko", label=f"STD G{G[k]:.1f}")
    a3.plot(ds["cog_angle"].values[-1], G[-1], "k*", ms=10, label=f"TSR G{G[-1]:.1f}")
    a3.set_title("COG location (radius = G [mm/s])", fontsize=9)
    a3.legend(fontsize=7, loc="lower left")
    fig.suptitle(f"004 Fig. 4: single TSR run, G_ini = G{ds.attrs['G_ini']:.1f}")
    return fig


def plot_monte_carlo(ds: xr.Dataset) -> Figure:
    """004 Fig. 5-6 from :func:`compute_monte_carlo`."""
    fig, (a1, a2) = _fig(2)
    ok = ds["status"].values == 0
    s, t = ds["G_STD"].values[ok], ds["G_TSR"].values[ok]
    gi = ds.attrs["G_ini"]
    top = max(s.max(), t.max(), gi) * 1.05
    bins = np.arange(0, top + 1, 1.0)
    a1.hist(s, bins, density=True, color="0.6", alpha=0.8,
            label=f"STD: {100 * np.mean(s <= G_LIMIT):.1f} % <= G16")
    a1.hist(t, bins, density=True, histtype="step", color="k", lw=1.5,
            label=f"TSR: {100 * np.mean(t <= G_LIMIT):.1f} % <= G16")
    if "G_TSR_ideal" in ds:
        ti = ds["G_TSR_ideal"].values[ok]
        a1.hist(ti, bins, density=True, histtype="step", color="b", lw=1.0, ls="--",
                label=f"TSR, plateau {ds.attrs['ideal_plateau_hz']:.1f} Hz: "
                      f"{100 * np.mean(ti <= G_LIMIT):.1f} % <= G16")
    a1.axvline(gi, color="k", ls="--", lw=1, label=f"G_ini = G{gi:.1f}")
    a1.axvline(G_LIMIT, color="r", ls=":", lw=1)
    if "G_stick_plateau" in ds.attrs:
        a1.axvline(ds.attrs["G_stick_plateau"], color="k", ls="-.", lw=0.8,
                   label=f"stick threshold G* at {ds.attrs['plateau_hz']:.0f} Hz: "
                         f"G{ds.attrs['G_stick_plateau']:.1f}")
    a1.set_xlabel("grade G [mm/s]")
    a1.set_ylabel("probability density [s/mm]")
    a1.legend(fontsize=7, loc="upper left")
    a1.set_title(f"PDF of G ({ok.sum()} runs)")
    a2.scatter(s, t, s=5, alpha=0.5)
    a2.plot([0, top], [0, top], "k:", lw=1)
    a2.axhline(gi, color="k", ls="--", lw=1)
    a2.axvline(gi, color="k", ls="--", lw=1)
    a2.set_xlim(0, top)
    a2.set_ylim(0, top)
    a2.set_xlabel("G_STD [mm/s]")
    a2.set_ylabel("G_TSR [mm/s]")
    regs = ", ".join(f"{k} {100 * ds.attrs[f'region_{k}']:.1f}%" for k in ("I.A", "I.B", "II", "III", "IV"))
    a2.set_title(regs, fontsize=8)
    fig.suptitle("004 Fig. 5-6: start-position Monte Carlo")
    return fig


def interval_band(ax: Axes, x: np.ndarray, est: np.ndarray, lo: np.ndarray, hi: np.ndarray,
                  color: str) -> None:
    """Draw the 95 % confidence interval of a sampled curve ``est`` as a band from ``lo`` to
    ``hi`` [units of the curve]; where the upper end is unbounded (too few runs) an upward
    arrow marks the estimate instead (:mod:`autobalance.confidence`)."""
    have = set(ax.get_legend_handles_labels()[1])
    band, arrow = "95 % confidence interval", "upper end unbounded (too few starts)"
    lo = np.where(np.isfinite(lo), lo, np.nan)
    top = np.isinf(hi) & np.isfinite(est)
    hi = np.where(np.isfinite(hi), hi, np.nan)
    ax.fill_between(x, lo, hi, color=color, alpha=0.18, lw=0,
                    label=None if band in have else band)
    if top.any():
        ax.plot(x[top], est[top], "^", color=color, ms=5, mfc="none",
                label=None if arrow in have else arrow)


def plot_unbalance(ds: xr.Dataset, grade: float = G_LIMIT, title: str | None = None) -> Figure:
    """004 Fig. 7 (and 11-12 per case) from :func:`compute_unbalance`: the 5 and 95 % isolines of
    the first and last read-outs (004: STD and TSR) against G_ini, the operating boundaries and
    the target ``grade`` [mm/s]."""
    cases = list(ds["case"].values)
    fig, axes = _fig(len(cases))
    G = ds["G_ini"].values
    lo, hi = ds["lower_boundary"].values, ds["upper_boundary"].values   # NaN beside a liquid
    procs = list(dict.fromkeys([ds["procedure"].values[0], ds["procedure"].values[-1]]))
    for ax, case in zip(axes, cases):
        for proc, col in zip(procs, ("0.5", "k")):
            d = ds["grade_G"].sel(case=case, procedure=proc)
            ax.plot(G, d.sel(percentile=95.0), color=col, lw=1.6, label=f"{proc} 95 %")
            if "grade_G_ci" in ds:
                ci = ds["grade_G_ci"].sel(case=case, procedure=proc, percentile=95.0)
                interval_band(ax, G, d.sel(percentile=95.0).values, ci.sel(bound="lo").values,
                              ci.sel(bound="hi").values, col)
            ax.plot(G, d.sel(percentile=5.0), color=col, lw=1.0, ls="--", label=f"{proc} 5 %")
        ax.plot(G, G, "k:", lw=0.8, label="G = G_ini")
        if np.isfinite(lo).any():
            ax.plot(G, lo, "k-.", lw=0.8, label="balls out/in of phase")
            ax.plot(G, hi, "k-.", lw=0.8)
        ax.axhline(grade, color="r", lw=0.8, label=f"target G{grade:g}")
        ax.set_xlabel("initial unbalance G_ini [mm/s]")
        ax.set_ylabel("residual G [mm/s]")
        mr, cr = float(ds["mu_r"].sel(case=case)), float(ds["c_r"].sel(case=case))
        ax.set_title(f"mu_r = {mr:g}, c_r = {cr:g}")
        ax.legend(fontsize=7)
    fig.suptitle(title or "004 Fig. 7: residual grade against initial unbalance")
    return fig


def plot_profile(ds: xr.Dataset) -> Figure:
    """004 Fig. 9 from :func:`compute_profile`."""
    fig, (ax,) = _fig(1, w=6.0)
    G = ds["G_ini"].values
    for proc, st in (("STD", "0.5"), ("TSR", "k"), ("slow", "C1")):
        ax.plot(G, ds["grade_G"].sel(procedure=proc, percentile=95.0), color=st, lw=1.6,
                label=f"{proc} 95 %")
    ax.plot(G, G, "k:", lw=0.8)
    ax.axhline(G_LIMIT, color="r", lw=0.8)
    ax.axvspan(10, 21, color="C1", alpha=0.1, label="004: slow worse in [G10, G21]")
    ax.set_xlabel("initial unbalance G_ini [mm/s]")
    ax.set_ylabel("residual G [mm/s]")
    ax.legend(fontsize=8)
    ax.set_title("004 Fig. 9: speed profile")
    return fig


def plot_immobility(ds: xr.Dataset, title: str | None = None, stick: bool = False,
                    speed_unit: str = "Hz") -> Figure:
    """004 Fig. 8/10 from :func:`compute_immobility`: bands over c_r, lines at c_r = 1 (or the
    first c_r), the profile's speeds dashed, the natural frequency dotted and, with ``stick``,
    the stick threshold G* [mm/s] on a second axis (004's figures have none); speeds in
    ``speed_unit`` (a pint speed unit, e.g. "rpm"; 004 uses Hz). Beside a liquid on a
    horizontal axis, the share of configurations whose rings hold (``ring_holds``) grey dashed."""
    from .speed_map import _per_unit

    fig, (ax,) = _fig(1, w=6.5)
    k_hz = 2 * np.pi / _per_unit(speed_unit)          # [speed_unit] per Hz
    f = k_hz * ds["speed"].values
    im = ds["immobility"]
    for k, mr in enumerate(ds["mu_r"].values):
        d = im.sel(mu_r=mr).values
        c_line = 1.0 if 1.0 in ds["c_r"].values else ds["c_r"].values[0]
        line, = ax.plot(f, im.sel(mu_r=mr, c_r=c_line), lw=1.4, label=f"mu_r = {mr:g}")
        ax.fill_between(f, d.min(axis=0), d.max(axis=0), alpha=0.2, color=line.get_color())
    for x in (ds.attrs["plateau_hz"], ds.attrs["nominal_hz"]):
        if np.isfinite(x):
            ax.axvline(k_hz * x, color="k", ls="--", lw=0.8)
    ax.axvline(k_hz * ds.attrs["f_n_hz"], color="r", ls=":", lw=0.8)
    if "ring_holds" in ds:          # beside a liquid on a horizontal axis
        c_line = 1.0 if 1.0 in ds["c_r"].values else ds["c_r"].values[0]
        ax.plot(f, ds["ring_holds"].sel(c_r=c_line).values, color="0.5", lw=1.0, ls="--",
                label="rings intact under gravity (share)")
    ax.set_xlabel(f"speed [{speed_unit}]")
    ax.set_ylabel("immobility [-]")
    ax.set_title(title or f"004 Fig. 8/10: immobility, G_ini = G{ds.attrs['G_ini']:g} "
                 f"(bands: c_r {', '.join(f'{c:g}' for c in ds['c_r'].values)})", fontsize=9)
    ax.legend(fontsize=8, loc="center right")
    if stick:
        bx = ax.twinx()
        bx.plot(f, ds["G_stick"].values, color="C3", lw=1.0, ls="-.")
        bx.set_ylabel("stick threshold G* [mm/s] (dash-dot)", color="C3")
        bx.set_ylim(0.0, 4.0 * max(ds.attrs["G_ini"], 1.0))
    return fig


def plot_plateau(ds: xr.Dataset, grade: float = G_LIMIT, title: str | None = None) -> Figure:
    """004 Fig. 14-16 from :func:`compute_plateau`: upper row the map (Fig. 14-15), lower row
    the 95 % residual grade against the plateau for each G_ini (Fig. 16 is such a slice), the
    target ``grade`` [mm/s] dotted."""
    cases = list(ds["case"].values)
    fig = Figure(figsize=(5.0 * len(cases), 8.0), constrained_layout=True)
    FigureCanvasAgg(fig)
    for i, (case, ideal) in enumerate(zip(cases, np.atleast_1d(ds.attrs["ideal"]))):
        ax = fig.add_subplot(2, len(cases), i + 1)
        d = ds["grade_G_p95"].sel(case=case)
        m = ax.pcolormesh(ds["G_ini"].values, ds["plateau_ratio"].values, d.values,
                          cmap="Greys", shading="nearest")
        fig.colorbar(m, ax=ax, label="95 % residual G [mm/s]")
        ax.axhline(ideal, color="r", ls="--", lw=1, label=f"ideal {ideal:g}")
        ax.set_xlabel("initial unbalance G_ini [mm/s]")
        ax.set_ylabel("lower plateau / Omega_n [-]")
        ax.set_title(f"case {case}")
        ax.legend(fontsize=8)
        bx = fig.add_subplot(2, len(cases), len(cases) + i + 1)
        r = ds["plateau_ratio"].values
        for g in ds["G_ini"].values:
            bx.plot(r, d.sel(G_ini=g).values, "o-", ms=3, lw=0.8, label=f"G_ini = {g:.3g}")
        mean = ds["mean_p95"].sel(case=case).values
        bx.plot(r, mean, "k-", lw=2.0, label="mean (picks the plateau)")
        if "mean_p95_ci" in ds:
            ci = ds["mean_p95_ci"].sel(case=case).values
            interval_band(bx, r, mean, ci[:, 0], ci[:, 1], "k")
        bx.axhline(grade, color="r", ls=":", lw=0.8)
        bx.axvline(ideal, color="r", ls="--", lw=1)
        bx.set_xlabel("lower plateau / Omega_n [-]")
        bx.set_ylabel("95 % residual G_TSR [mm/s]")
        bx.legend(fontsize=7, ncol=2)
    fig.suptitle(title or "004 Fig. 14-16: lower TSR plateau")
    return fig


def plot_descent(ds: xr.Dataset) -> Figure:
    """004 Fig. 13 from :func:`compute_descent`: percentiles of the residual grade against the
    speed ratio along the descent (read right to left), the stick threshold G*(Omega), the
    standard plateau and the balancer's operating boundary G_ini + G_balls."""
    fig, (ax,) = _fig(1, w=7.5, h=4.6)
    r = ds["ratio"].values
    a = ds.attrs
    for p, ls in zip(ds["percentile"].values, (":", "--", "-", "--", ":")):
        ax.plot(r, ds["grade_G"].sel(percentile=p).values, "k", ls=ls,
                lw=1.6 if p == 50 else 1.0, label=f"{p:g} %")
    ax.plot(r, ds["G_stick"].values, color="C0", lw=1.0, ls="-.", label="stick threshold G*")
    ax.axvline(a["standard_ratio"], color="0.4", ls=":", lw=1,
               label=f"standard plateau {a['standard_ratio']:.2f}")
    ax.axvline(1.0, color="r", lw=0.6)
    if np.isfinite(a["half_drop_median"]):
        ax.axvline(a["half_drop_median"], color="C1", lw=1,
                   label=f"half drop of the median {a['half_drop_median']:.3f}")
    top = a["G_ini"] + a["G_balls"]
    ax.axhline(top, color="k", ls="--", lw=0.8, label=f"G_ini + G_balls = G{top:.0f}")
    ax.axhline(G_LIMIT, color="r", ls=":", lw=0.8)
    ax.set_xlim(r.max(), r.min())
    ax.set_ylim(0, top * 1.15)
    ax.set_xlabel("Omega / Omega_n [-] (the speed decreases to the right)")
    ax.set_ylabel("residual G [mm/s]")
    ax.set_title(f"004 Fig. 13: gradual speed reduction, G_ini = G{a['G_ini']:g}, "
                 f"{a['runs']} starts")
    ax.legend(fontsize=7, ncol=2, loc="upper right")
    return fig


def plot_speed_profile(ds: xr.Dataset) -> Figure:
    """004 Fig. 3 from :func:`autobalance.papers.p004.tsr.compute_table1`: speed [Hz] against
    time [s] with the STD and TSR read-outs."""
    fig, (ax,) = _fig(1, w=7.0, h=3.6)
    ax.plot(ds["time"].values, ds["speed"].values / (2 * np.pi), "k", lw=1.2)
    f_n = ds.attrs["f_n_hz"]
    ax.axhline(f_n, color="r", ls="--", lw=0.8, label=f"resonance {f_n:.1f} Hz")
    for t, lab in zip(ds.attrs["checkpoints_s"], ("STD read-out", "TSR read-out")):
        ax.axvline(t, color="C0", ls=":", lw=0.8)
        ax.text(t, 5, f" {lab}", fontsize=8, rotation=90, va="bottom")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("speed [Hz]")
    ax.set_title("004 Fig. 3: standardised speed profile (our reading)")
    ax.legend(fontsize=8, loc="lower right")
    return fig


def plot_start_positions(ds: xr.Dataset, title: str | None = None) -> Figure:
    """The start-position study of any machine
    (:func:`autobalance.studies._start_positions.compute_start_positions`, no grid): the density
    of the grade at each read-out with its share at or below the target, and each run's last
    against its first read-out (004 Fig. 5-6 generalised); with a single read-out (a motor
    drive, a constant speed) each run's grade against its start angle instead."""
    fig, (a1, a2) = _fig(2)
    ok = ds["status"].values == 0
    g = ds["grade_G"].values[ok]                    # (run, checkpoint)
    lim, gi = ds.attrs["grade"], ds.attrs["G_ini"]
    top = max(float(np.nanmax(g)), gi, lim) * 1.05
    bins = np.linspace(0.0, top, 60)
    for j, lab in enumerate(ds["checkpoint_label"].values):
        share = 100 * float(ds["share_below_grade"].values[j])
        a1.hist(g[:, j], bins, density=True, histtype="step", lw=1.4,
                label=f"{lab}: {share:.1f} % <= G{lim:g}")
    a1.axvline(gi, color="k", ls="--", lw=1, label=f"G_ini = G{gi:.3g}")
    a1.axvline(lim, color="r", ls=":", lw=1)
    a1.set_xlabel("grade G [mm/s]")
    a1.set_ylabel("probability density [s/mm]")
    a1.legend(fontsize=7)
    a1.set_title(f"{int(ok.sum())} runs: {ds.attrs['starts']}", fontsize=9)
    labels = ds["checkpoint_label"].values
    if g.shape[1] < 2:                  # one read-out (a motor drive, a constant speed)
        _grade_against_start(a2, ds["start_angle"].values[ok], g[:, 0], lim, top, labels[0])
        fig.suptitle(title or "Start-position Monte Carlo")
        return fig
    a2.scatter(g[:, 0], g[:, -1], s=5, alpha=0.5)
    a2.plot([0, top], [0, top], "k:", lw=1)
    a2.axhline(lim, color="r", ls=":", lw=1)
    a2.axvline(lim, color="r", ls=":", lw=1)
    a2.set_xlim(0, top)
    a2.set_ylim(0, top)
    a2.set_xlabel(f"G at {labels[0]} [mm/s]")
    a2.set_ylabel(f"G at {labels[-1]} [mm/s]")
    if "region_share" in ds:
        a2.set_title(", ".join(f"{r} {100 * v:.1f}%" for r, v in
                               zip(ds["region"].values, ds["region_share"].values)), fontsize=8)
    fig.suptitle(title or "Start-position Monte Carlo")
    return fig


def _grade_against_start(ax, angles: np.ndarray, g: np.ndarray, lim: float, top: float,
                         label: str) -> None:
    """The second panel of :func:`plot_start_positions` with a single read-out: each run's
    grade g [mm/s] against its start, the angle of ball 2 from ball 1 (one ball: its angle)
    [deg] from ``angles`` (run, ball) [rad]; ``lim`` the target and ``top`` the axis end
    [mm/s]."""
    if angles.ndim < 2 or angles.shape[1] == 0:     # a liquid alone: no start positions
        ax.set_axis_off()
        return
    a = angles[:, 1] - angles[:, 0] if angles.shape[1] >= 2 else angles[:, 0]
    ax.scatter(np.degrees(np.mod(a, 2 * np.pi)), g, s=5, alpha=0.5)
    ax.axhline(lim, color="r", ls=":", lw=1)
    ax.set_xlim(0, 360)
    ax.set_ylim(0, top)
    ax.set_xlabel("start angle of ball 2 from ball 1 [deg]" if angles.shape[1] >= 2
                  else "start angle of the ball [deg]")
    ax.set_ylabel(f"G at {label} [mm/s]")


def plot_design(ds: xr.Dataset, title: str | None = None) -> Figure:
    """The design search (:func:`autobalance.studies._design.compute_design`): each design's worst
    quantile of the final grade against its total ball mass, by profile, with its interval (a
    bar; an end beyond the axes, or unbounded, an arrow at the top), filled where the design is
    decided to meet the target, the Pareto front joined and the target grade dotted; and each
    design's quantile against the initial grade."""
    fig, (a1, a2) = _fig(2, w=5.5)
    mass = 1e3 * ds["total_ball_mass"].values
    worst = ds["worst_quantile"].values
    prof = ds["profile"].values
    ci = ds["worst_quantile_ci"].values if "worst_quantile_ci" in ds else None
    meets = ds["meets"].values.astype(bool)
    top = max(float(np.nanmax(worst)), float(ds.attrs["grade"])) * 1.3
    span = float(np.ptp(mass)) or float(mass.max()) or 1.0
    for j, (p, mk) in enumerate(zip(dict.fromkeys(prof), "osd^v")):
        k = prof == p
        x = mass[k] + (j - 0.5) * 0.015 * span          # profiles side by side
        pts = a1.scatter(x, worst[k], marker=mk, label=p, zorder=3)
        if ci is not None:
            color = pts.get_facecolor()[0]
            lo, hi = ci[k, 0], np.minimum(np.where(np.isfinite(ci[k, 1]), ci[k, 1], top), top)
            a1.errorbar(x, worst[k], yerr=[worst[k] - lo, hi - worst[k]], fmt="none",
                        ecolor=color, lw=0.8, capsize=2)
            up = ~np.isfinite(ci[k, 1]) | (ci[k, 1] > top)
            a1.scatter(x[up], np.full(up.sum(), top), marker="^", color=color, s=18)
            open_ = ~meets[k]
            a1.scatter(x[open_], worst[k][open_], marker=mk, facecolor="white",
                       edgecolor=color, zorder=4)
    if ci is not None:
        a1.set_ylim(top=top * 1.02)
        a1.set_title("filled: decided to meet the target; bar: 95 % interval (arrow: unbounded)",
                     fontsize=7)
    par = np.flatnonzero(ds["pareto"].values)
    par = par[np.argsort(mass[par])]
    a1.plot(mass[par], worst[par], "k-", lw=0.8, label="Pareto front")
    a1.axhline(ds.attrs["grade"], color="r", ls=":", lw=1, label=f"target G{ds.attrs['grade']:g}")
    a1.set_xlabel("total ball mass [g]")
    a1.set_ylabel(f"worst {100 * ds.attrs['confidence']:g} % grade [mm/s]")
    a1.legend(fontsize=7)
    gi = ds["G_ini"].values
    for k in np.argsort(ds["rank"].values)[:6]:
        a2.plot(gi, ds["quantile"].values[k], "o-", ms=3, lw=1, label=str(ds["design"].values[k]))
    a2.axhline(ds.attrs["grade"], color="r", ls=":", lw=1)
    a2.set_xlabel("initial unbalance G_ini [mm/s]")
    a2.set_ylabel(f"{100 * ds.attrs['confidence']:g} % grade [mm/s]")
    a2.legend(fontsize=6)
    a2.set_title("the six best ranked designs", fontsize=9)
    fig.suptitle(title or "Design search")
    return fig
