"""Figures of the liquid (Leblanc) balancer: free surface, amplitude vs speed and vs fill, and the
figures of the 003 and 001 reproduction targets (:mod:`autobalance.papers.p003`,
:mod:`autobalance.papers.p001`).

Every function takes computed data (SI units, angles in radians) and returns a matplotlib
``Figure`` on an Agg canvas (no pyplot); units are converted only for the axes and labels
(mm, ml, deg, g*cm). Nothing here evaluates the model or writes a file: the caller computes
(:mod:`autobalance.liquid`) and saves (``fig.savefig``).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import matplotlib
import numpy as np
from matplotlib.figure import Figure

from ..liquid.free_surface import MODE_NAMES
from .timeplot import _new_figure

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt
    import xarray as xr
    from matplotlib.axes import Axes

    from ..liquid.dynamics import RunUp
    from ..liquid.simulate import LiquidSimulation

__all__ = ["bars_figure", "curves_figure", "efficiency_bars_figure", "fill_figure",
           "fill_panels_figure", "fill_vs_radius_figure", "friction_angle_figure",
           "fill_map_figure", "kinetostatic_figure", "liquid_run_figure", "liquid_states_figure", "mode_speeds_figure",
           "response_figure", "speed_series_figure", "spinup_figure", "stability_figure",
           "surface_figure"]

ML = 1e-6   # [m^3] per ml
GCM = 1e-5  # [kg*m] per g*cm


def surface_figure(profiles: dict, title: str = "") -> Figure:
    """Liquid depth vs radius at several speeds: whole radius and a zoom at the wall.

    Parameters
    ----------
    profiles : dict
        :func:`autobalance.liquid.surface_profiles` output: ``omega_rad_s`` [rad/s], ``r_m``
        [m], ``depth_m`` [m] (speeds x radii), ``mode``, ``regime``, ``volume_m3`` [m^3],
        ``radius_m`` [m], ``height_m`` [m], ``wall_zoom`` [-] (the zoomed fraction of R).
    title : str
        Figure title (default: the free-surface equation and the fixed quantities).
    """
    omegas, r, depth = profiles["omega_rad_s"], profiles["r_m"], profiles["depth_m"]
    radius, height, volume = profiles["radius_m"], profiles["height_m"], profiles["volume_m3"]
    fig = _new_figure((10, 5.2 + 0.25 * ((len(omegas) + 1) // 2)))
    axes = fig.subplots(1, 2, gridspec_kw={"width_ratios": [3, 2]})
    cmap = matplotlib.colormaps["viridis"]
    zoom = profiles["wall_zoom"] * radius
    labels = []
    for ax, r0 in zip(axes, (0.0, radius - zoom)):
        part = r >= r0
        for i, w in enumerate(omegas):
            col = cmap(0.9 * i / max(len(omegas) - 1, 1))
            x, z = r[part] * 1e3, depth[i][part] * 1e3
            ax.fill_between(x, 0, z, color=col, alpha=0.12)
            ln, = ax.plot(x, z, color=col, lw=1.8)
            if ax is axes[0]:
                mode = profiles["mode"][i]
                labels.append((ln, f"ω = {w:.3g} rad/s: mode {mode} ({MODE_NAMES[mode]}), "
                                   f"regime {profiles['regime'][i]}"))
        ax.plot([r0 * 1e3, radius * 1e3, radius * 1e3, r0 * 1e3],
                [0, 0, height * 1e3, height * 1e3], "k-", lw=2)
        ax.set_xlim(r0 * 1e3, radius * 1e3 + 0.02 * (radius - r0) * 1e3)
        ax.set_ylim(-0.03 * height * 1e3, 1.05 * height * 1e3)
        ax.set_xlabel("radius r [mm]")
        ax.grid(alpha=0.3)
    axes[0].set_ylabel("liquid depth z [mm] (bottom 0, lid h)")
    axes[0].set_title("axis (left) to wall (right)", fontsize=10)
    axes[1].set_title(f"zoom: last {zoom * 1e3:.3g} mm at the wall", fontsize=10)
    fig.suptitle(title or f"Free surface z = z* + ω²r²/2g, V = {volume * 1e6:.4g} ml, "
                          f"R = {radius * 1e3:.4g} mm, h = {height * 1e3:.4g} mm (003 eq 3-5)")
    fig.legend([ln for ln, _ in labels], [t for _, t in labels], loc="outside lower center",
               ncol=2, fontsize=8, frameon=False)
    return fig


def response_figure(steady: dict, omega0: float, omega_r: float, run: RunUp | None = None,
                    title: str = "") -> Figure:
    """Amplitude [mm] vs speed, with and without liquid; efficiency below.

    Parameters
    ----------
    steady : dict
        :func:`autobalance.liquid.steady_response` output.
    omega0, omega_r : float
        Entrainment speed (003 eq 6) and natural frequency [rad/s], drawn as vertical lines.
    run : RunUp or None
        Run-up to draw under the steady curves.
    title : str
        Axes title.
    """
    fig = _new_figure((8, 6.5))
    ax, ax2 = fig.subplots(2, 1, sharex=True, gridspec_kw={"height_ratios": [2, 1]})
    w = steady["omega_rad_s"]
    if run is not None:
        ax.plot(run.omega, run.amplitude_dry * 1e3, color="0.6", lw=0.8, label="run-up, no liquid")
        ax.plot(run.omega, run.amplitude * 1e3, color="C1", lw=0.8, label="run-up, with liquid")
    ax.plot(w, steady["amplitude_dry_m"] * 1e3, "k--", lw=1.5, label="steady, no liquid")
    ax.plot(w, steady["amplitude_m"] * 1e3, "C0-", lw=1.8, label="steady, with liquid")
    for a in (ax, ax2):
        a.axvline(omega0, color="C2", ls=":", lw=1.2)
        a.axvline(omega_r, color="C3", ls=":", lw=1.2)
    ax.text(omega0, ax.get_ylim()[1] * 0.5, " ω0 (003 eq 6)", color="C2", fontsize=8)
    ax.text(omega_r, ax.get_ylim()[1] * 0.5, " ω_n with liquid", color="C3", fontsize=8)
    ax.set_ylabel("whirl amplitude [mm]")
    ax.set_title(title or "Rotor with a liquid balancer")
    ax.legend(fontsize=8, loc="upper left")
    ax.grid(alpha=0.3)
    eff = np.clip(steady["efficiency"], 1e-2, 1e3)
    ax2.semilogy(w, eff, "C0-")
    ax2.axhline(1.0, color="k", lw=0.8)
    ax2.set_ylabel("efficiency A_dry/A_wet [-]")
    ax2.set_xlabel("rotor speed ω [rad/s]")
    ax2.grid(alpha=0.3, which="both")
    return fig


def fill_figure(sweeps: list[dict], labels: list[str], title: str = "",
                ax: Axes | None = None) -> Figure:
    """Steady amplitude [mm] vs fill volume [ml] (003 Fig. 5), one curve per sweep.

    Parameters
    ----------
    sweeps : list of dict
        Each with ``volume_m3`` and ``amplitude_m`` arrays (:func:`autobalance.liquid.fill_sweep`).
    labels : list of str
        Curve labels.
    title : str
        Panel title.
    ax : matplotlib Axes or None
        Draw into this panel (of a larger figure) instead of a new figure.
    """
    fig = _new_figure((7.5, 4.6)) if ax is None else ax.figure
    ax = fig.subplots() if ax is None else ax
    for s, lab in zip(sweeps, labels):
        ax.plot(s["volume_m3"] * 1e6, s["amplitude_m"] * 1e3, "o-", label=lab)
    ax.set_xlabel("liquid volume V [ml]")
    ax.set_ylabel("whirl amplitude [mm]")
    ax.set_yscale("log")
    ax.set_title(title or "Amplitude vs fill", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    return fig


def fill_panels_figure(panels: list[tuple], suptitle: str = "") -> Figure:
    """Several :func:`fill_figure` panels side by side (003 Fig. 5 a-c).

    Parameters
    ----------
    panels : list of (sweeps, labels, title)
        Arguments of :func:`fill_figure` for each panel.
    suptitle : str
        Figure title.
    """
    fig = _new_figure((5.0 * len(panels), 4.6))
    for ax, (sweeps, labels, title) in zip(np.atleast_1d(fig.subplots(1, len(panels),
                                                                       sharey=True)), panels):
        fill_figure(sweeps, labels, title, ax=ax)
    if suptitle:
        fig.suptitle(suptitle)
    return fig


def curves_figure(panels: list[dict], suptitle: str = "",
                  size: tuple[float, float] | None = None) -> Figure:
    """Families of curves, one panel each.

    Parameters
    ----------
    panels : list of dict
        Each: ``x`` (array), ``curves`` (list of (label, y array, style str or "")), ``xlabel``,
        ``ylabel`` (with units), optional ``title``, ``logy`` (bool), ``points`` (list of
        (label, x list, y list): published values as markers), ``vlines`` (list of (x, label)).
    suptitle : str
        Figure title.
    size : (float, float) or None
        Figure size [in]; default 5.4 per panel x 4.4.
    """
    fig = _new_figure(size or (5.4 * len(panels), 4.4))
    axes = np.atleast_1d(fig.subplots(1, len(panels)))
    for ax, p in zip(axes, panels):
        for lab, y, style in p["curves"]:
            ax.plot(p["x"], y, style or "-", label=lab)
        for lab, xs, ys in p.get("points", ()):
            ax.plot(xs, ys, "kx", ms=8, mew=2, label=lab)
        for x, lab in p.get("vlines", ()):
            ax.axvline(x, color="0.5", ls=":", lw=1.0)
            ax.annotate(lab, (x, 0.98), xycoords=("data", "axes fraction"), rotation=90,
                        va="top", ha="right", fontsize=7, color="0.3")
        if p.get("logy"):
            ax.set_yscale("log")
        ax.set_xlabel(p["xlabel"])
        ax.set_ylabel(p["ylabel"])
        ax.set_title(p.get("title", ""), fontsize=10)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=7)
    if suptitle:
        fig.suptitle(suptitle)
    return fig


def bars_figure(panels: list[dict], suptitle: str = "") -> Figure:
    """Grouped bar charts, one panel each (003 Fig. 6 style).

    Parameters
    ----------
    panels : list of dict
        Each: ``groups`` (group labels), ``series`` (list of (label, values per group)),
        ``ylabel`` (with units), optional ``title``, ``xlabel``, ``logy``.
    suptitle : str
        Figure title.
    """
    fig = _new_figure((5.0 * len(panels), 4.4))
    axes = np.atleast_1d(fig.subplots(1, len(panels), sharey=True))
    for ax, p in zip(axes, panels):
        n = len(p["series"])
        x = np.arange(len(p["groups"]))
        width = 0.8 / max(n, 1)
        for i, (lab, vals) in enumerate(p["series"]):
            ax.bar(x + (i - 0.5 * (n - 1)) * width, vals, width, label=lab)
        ax.set_xticks(x, p["groups"])
        ax.axhline(1.0, color="k", lw=0.8)
        if p.get("logy"):
            ax.set_yscale("log")
        ax.set_xlabel(p.get("xlabel", ""))
        ax.set_title(p.get("title", ""), fontsize=10)
        ax.grid(alpha=0.3, axis="y", which="both")
    axes[0].set_ylabel(panels[0]["ylabel"])
    axes[0].legend(fontsize=7)
    if suptitle:
        fig.suptitle(suptitle)
    return fig


# -- figures of the 003 and 001 targets ----------------------------------------------------------
def mode_speeds_figure(volumes: npt.ArrayLike, g_values: Sequence[float], omega_b: np.ndarray,
                       omega_0: np.ndarray, printed_b: tuple[npt.ArrayLike, npt.ArrayLike],
                       printed_0: tuple[npt.ArrayLike, npt.ArrayLike],
                       suptitle: str = "") -> Figure:
    """Bottom-touch and entrainment speeds vs fill (003 eq 4, eq 6), with the printed values.

    Parameters
    ----------
    volumes : array
        Liquid volumes V [m^3].
    g_values : sequence of float
        Gravities [m/s^2], one curve each.
    omega_b, omega_0 : array (gravities x volumes)
        Bottom-touch speed (003 eq 4) and entrainment speed (003 eq 6) [rad/s].
    printed_b, printed_0 : (volumes [m^3], speeds [rad/s])
        The seed's printed values, drawn as markers.
    suptitle : str
        Figure title.
    """
    v = np.asarray(volumes) / ML
    panels = [{"x": v, "xlabel": "liquid volume V [ml]", "ylabel": "speed [rad/s]", "title": t,
               "curves": [(f"g = {g:g} m/s²", y[i], "-") for i, g in enumerate(g_values)],
               "points": [("003 printed", list(np.asarray(pv) / ML), list(pw))]}
              for t, y, (pv, pw) in (("bottom touch ω_b (003 eq 4)", omega_b, printed_b),
                                     ("entrainment ω0 (003 eq 6)", omega_0, printed_0))]
    return curves_figure(panels, suptitle)


def fill_vs_radius_figure(volumes: np.ndarray, amplitude: np.ndarray, radii: Sequence[float],
                          ratios: Sequence[float], suptitle: str = "") -> Figure:
    """Amplitude vs fill, one panel per chamber radius, one curve per relative speed (003 Fig. 5).

    Parameters
    ----------
    volumes : array
        Fill volumes V [m^3] (0 = no liquid).
    amplitude : array (radii x ratios x volumes)
        Steady whirl amplitude [m].
    radii : sequence of float
        Chamber radii R [m].
    ratios : sequence of float
        Speeds omega/omega_r [-].
    suptitle : str
        Figure title.
    """
    return fill_panels_figure(
        [([{"volume_m3": volumes, "amplitude_m": amplitude[i, j]} for j in range(len(ratios))],
          [f"{f} ω_r" for f in ratios], f"{tag}: R = {R:g} m")
         for i, (R, tag) in enumerate(zip(radii, "abc"))], suptitle)


def efficiency_bars_figure(efficiency: npt.ArrayLike, unbalances: Sequence[float],
                           fills: Sequence[float], radii: Sequence[float],
                           ratios: Sequence[float], suptitle: str = "") -> Figure:
    """Efficiency A(no liquid)/A(liquid) vs chamber radius, one panel per unbalance (003 Fig. 6).

    Parameters
    ----------
    efficiency : array (unbalances x radii x ratios)
        Efficiency [-] (drawn clipped to 1e-2..1e4 on a log axis).
    unbalances : sequence of float
        Rotor unbalance D [kg*m] of each panel.
    fills : sequence of float
        Fill volume V [m^3] of each panel.
    radii : sequence of float
        Chamber radii R [m] (bar groups).
    ratios : sequence of float
        Speeds omega/omega_r [-] (bars of a group).
    suptitle : str
        Figure title.
    """
    eff = np.clip(efficiency, 1e-2, 1e4)
    return bars_figure([{"groups": [f"{R:g}" for R in radii], "logy": True,
                         "xlabel": "chamber radius R [m]",
                         "title": f"{tag}: D = {D / GCM:.0f} g·cm, V = {V / ML:.0f} ml",
                         "ylabel": "efficiency A(no liquid)/A(liquid) [-]",
                         "series": [(f"{f} ω_r", eff[i, :, k]) for k, f in enumerate(ratios)]}
                        for i, (D, V, tag) in enumerate(zip(unbalances, fills, "abc"))],
                       suptitle)


def liquid_states_figure(steady: dict, omega0: float, omega_r: float, run: RunUp | None,
                         frames: Sequence[float], frame_angles: Sequence[float],
                         reference: tuple[str, npt.ArrayLike, npt.ArrayLike] | None = None,
                         title: str = "") -> Figure:
    """:func:`response_figure` with the speeds of video frames marked (003 Fig. 7 a-d).

    Parameters
    ----------
    steady, omega0, omega_r, run, title
        As in :func:`response_figure` (speeds [rad/s]).
    frames : sequence of float
        Speeds of the frames [rad/s], tagged a, b, c, ...
    frame_angles : sequence of float
        |liquid angle| at each frame [rad] (labelled in degrees).
    reference : (label, omegas [rad/s], amplitude [m]) or None
        A further steady curve (e.g. another fill).
    """
    fig = response_figure(steady, omega0, omega_r, run, title)
    ax, ax2 = fig.axes[:2]
    if reference is not None:
        label, w, amp = reference
        ax.plot(w, np.asarray(amp) * 1e3, "C4-", lw=1.0, label=label)
        ax.legend(fontsize=8, loc="upper left")
    for tag, w, a in zip("abcdefgh", frames, np.degrees(frame_angles)):
        ax2.annotate(f"Fig. 7{tag}: |θ| = {a:.0f}°", (w, 0.97), rotation=90, fontsize=7,
                     xycoords=("data", "axes fraction"), va="top", ha="right", color="C5")
        for x in (ax, ax2):
            x.axvline(w, color="C5", lw=0.6, ls="--")
    return fig


def kinetostatic_figure(delta: npt.ArrayLike, ks: Sequence[float], alpha0: npt.ArrayLike,
                        efficiency: np.ndarray, suptitle: str = "") -> Figure:
    """Liquid angle alpha0 and efficiency e/e_c vs the rotor phase angle, one curve per k
    (001 eq 3-4).

    Parameters
    ----------
    delta : array
        Rotor phase angles [rad] (drawn in degrees).
    ks : sequence of float
        k = D0/D [-], one curve each.
    alpha0 : array (ks x delta)
        Liquid equilibrium angle [rad] (drawn in degrees).
    efficiency : array (ks x delta)
        e/e_c [-] (drawn clipped to 1e-2..1e3 on a log axis).
    suptitle : str
        Figure title.
    """
    dd, ad = np.degrees(delta), np.degrees(alpha0)
    return curves_figure(
        [{"x": dd, "xlabel": "rotor phase angle δ [deg]", "ylabel": "liquid angle α0 [deg]",
          "title": "001 eq 3", "curves": [(f"k = {k:g}", ad[i], "") for i, k in enumerate(ks)]},
         {"x": dd, "xlabel": "rotor phase angle δ [deg]", "logy": True,
          "ylabel": "efficiency e/e_c [-]", "title": "001 eq 4 (β = 0)",
          "curves": [(f"k = {k:g}", np.clip(efficiency[i], 1e-2, 1e3), "")
                     for i, k in enumerate(ks)]}], suptitle)


def friction_angle_figure(omegas: npt.ArrayLike, names: Sequence[str], beta: npt.ArrayLike,
                          title: str = "", suptitle: str = "") -> Figure:
    """Friction angle beta vs speed, one curve per liquid (001 eq 6).

    Parameters
    ----------
    omegas : array
        Rotor speeds [rad/s].
    names : sequence of str
        Liquid names.
    beta : array (liquids x speeds)
        Friction angle [rad] (drawn in degrees, log axis).
    title, suptitle : str
        Panel and figure titles.
    """
    bd = np.degrees(beta)
    return curves_figure([{"x": omegas, "xlabel": "rotor speed ω [rad/s]",
                           "ylabel": "friction angle β [deg]", "logy": True, "title": title,
                           "curves": [(n, bd[i], "") for i, n in enumerate(names)]}],
                         suptitle, size=(7.5, 4.6))


def speed_series_figure(omegas: npt.ArrayLike, curves: list[tuple[str, npt.ArrayLike, str]],
                        omega_r: float, ylabel: str, title: str = "", suptitle: str = "",
                        floor: tuple[float, float] | None = None) -> Figure:
    """A family of curves vs rotor speed with the resonance marked, log axis (001 Fig. 3-6).

    Parameters
    ----------
    omegas : array
        Rotor speeds [rad/s].
    curves : list of (label, values, style)
        One curve each (style "" for the default).
    omega_r : float
        Resonance speed [rad/s], drawn as a vertical line.
    ylabel : str
        Label of the values, with units.
    title, suptitle : str
        Panel and figure titles.
    floor : (lo, hi) or None
        Clip the values to this range before drawing (e.g. an infinite efficiency).
    """
    cs = [(lab, y if floor is None else np.clip(y, *floor), st) for lab, y, st in curves]
    return curves_figure([{"x": omegas, "xlabel": "rotor speed ω [rad/s]", "ylabel": ylabel,
                           "logy": True, "title": title, "vlines": [(omega_r, "ω_r")],
                           "curves": cs}], suptitle, size=(7.5, 4.6))


def liquid_run_figure(sim: LiquidSimulation, grade_limit: float = 16.0,
                      grade_label: str | None = None, time_unit: str = "s") -> Figure:
    """One liquid-balancer run over time: the whirl amplitude with and without the liquid, the
    liquid's moment and angle from the unbalance (and each chamber's, for several), and the ISO
    grade.

    Parameters
    ----------
    sim : autobalance.liquid.simulate.LiquidSimulation
        The run (t [s], amplitude [m], liquid_unbalance [kg*m], grade [mm/s]).
    grade_limit : float
        Grade drawn as a dashed line [mm/s].
    grade_label : str or None
        Its legend text (default ``"G<grade_limit>"``).
    time_unit : str
        Label of the time axis (the values are [s]).
    """
    U = sim.synchronous_unbalance
    cap = sim.system.liquid.capacity
    x, xl = sim.t, f"time [{time_unit}]"
    per = [] if sim.chamber_unbalance is None else [     # several chambers: each one's film
        (f"chamber R = {c.chamber_radius:g} m: |U_j| / ρV_jR_j", np.abs(u) / c.capacity, "-.")
        for c, u in zip(sim.system.liquid.chambers, sim.chamber_unbalance.T)]
    fig = curves_figure([
        {"x": x, "xlabel": xl, "ylabel": "whirl amplitude [mm]", "title": "rotor",
         "curves": [("with liquid", 1e3 * sim.amplitude, ""),
                    ("without liquid", 1e3 * sim.amplitude_without_liquid, "--")]},
        {"x": x, "xlabel": xl, "ylabel": "liquid moment / capacity ρVR [-], angle / 180° [-]",
         "title": "liquid (synchronous part)",
         "curves": [("|U| / ρVR", np.abs(U) / cap, ""),
                    ("angle from the unbalance in [0, 360°) / 180°",
                     np.mod(np.degrees(np.angle(U)), 360.0) / 180.0, ":"), *per]},
        {"x": x, "xlabel": xl, "ylabel": "grade G [mm/s]", "title": "ISO 1940 grade",
         "curves": [("G of |D + U_sync|", sim.grade, ""),
                    (grade_label or f"G{grade_limit:g}", np.full(x.size, grade_limit), "k--")]},
    ], suptitle=f"{sim.system.name}: liquid balancer (film from t = {sim.film_start:.3g} s)",
        size=(15.0, 4.4))
    return fig


def fill_map_figure(ds: xr.Dataset, speed_unit: str = "rad/s", speed_factor: float = 1.0,
                    title: str = "") -> Figure:
    """The fill map (:func:`autobalance.studies._fill_map.compute_fill_map`): the steady whirl
    vs speed for each fill beside the rotor without liquid, and the efficiency A(no liquid) /
    A(liquid) (above 1: the liquid balances).

    Parameters
    ----------
    ds : xarray.Dataset
        amplitude [m] (fill, speed), amplitude_without_liquid [m], efficiency [-]; fill [m^3],
        speed [rad/s]; optionally spread [-] (fill, dynamic_speed [rad/s]) of the stability map
        and growth_rate [1/s] (fill, linear_speed [rad/s]) of the linear one.
    speed_unit : str
        Label of the speed axis.
    speed_factor : float
        Displayed speed per rad/s [speed_unit / (rad/s)].
    title : str
        Figure title.
    """
    x = ds["speed"].values * speed_factor
    xl = f"speed [{speed_unit}]"
    fills = ds["fill"].values / ML
    amp = [(f"{v:.0f} ml", 1e3 * a, "") for v, a in zip(fills, ds["amplitude"].values)]
    amp.append(("no liquid", 1e3 * ds["amplitude_without_liquid"].values, "k--"))
    eff = [(f"{v:.0f} ml", e, "") for v, e in zip(fills, ds["efficiency"].values)]
    eff.append(("1: no effect", np.ones(x.size), "k:"))
    panels = [
        {"x": x, "xlabel": xl, "ylabel": "steady whirl [mm]", "title": "whirl", "logy": True,
         "curves": amp},
        {"x": x, "xlabel": xl, "ylabel": "efficiency A(no liquid) / A(liquid) [-]",
         "title": "efficiency", "curves": eff},
    ]
    if "growth_rate" in ds:     # the balanced state's linear stability (sec. 3j)
        cur = [(f"{v:.0f} ml", g, "") for v, g in zip(fills, ds["growth_rate"].values)]
        cur.append(("0: unstable above", np.zeros(x.size), "k:"))
        panels.append({"x": ds["linear_speed"].values * speed_factor, "xlabel": xl,
                       "ylabel": "growth rate [1/s]", "title": "balanced state: linear",
                       "curves": cur})
    if "spread" in ds:          # the stability map of the coupled film
        xd = ds["dynamic_speed"].values * speed_factor
        cur = [(f"{v:.0f} ml", sp, "o-") for v, sp in zip(fills, ds["spread"].values)]
        cur.append((f"{ds.attrs.get('spread_max', 0.05):g}: steady below",
                    np.full(xd.size, ds.attrs.get("spread_max", 0.05)), "k--"))
        panels.append({"x": xd, "xlabel": xl, "ylabel": "whirl spread, last quarter [-]",
                       "title": "coupled film: steady?", "logy": True, "curves": cur})
    return curves_figure(panels, suptitle=title, size=(6.5 * len(panels), 4.8))


def spinup_figure(runs: Sequence, labels: Sequence[str], omega0: Sequence[float],
                  title: str = "") -> Figure:
    """The liquid's spin-up from rest (:func:`autobalance.liquid.spinup.spinup_run`): left, the
    liquid's mean angular speed against the chamber's, with 003 eq 6's entrainment speed of each
    chamber (dotted) and the model's (the lid reached, a dot); right, the depth profile when each
    chamber's liquid reaches the lid.

    Parameters
    ----------
    runs : sequence of SpinUp
        One run per chamber.
    labels : sequence of str
        Their legend labels.
    omega0 : sequence of float
        003 eq 6's entrainment speed of each chamber [rad/s].
    title : str
        Figure title.
    """
    fig = _new_figure((11, 4.5))
    a, b = fig.subplots(1, 2)
    top = max(float(r.speed[-1]) for r in runs)
    a.plot([0, top], [0, top], color="0.7", lw=0.8, label="with the chamber")
    for r, lab, w0 in zip(runs, labels, omega0):
        line, = a.plot(r.speed, r.liquid_speed, label=lab)
        a.axvline(w0, color=line.get_color(), ls=":", lw=1.0)
        if r.lid_time is not None:
            a.plot(r.speed[-1], r.liquid_speed[-1], "o", color=line.get_color())
        b.fill_between(r.r * 1e3, 0.0, r.depth[-1] * 1e3, alpha=0.35, color=line.get_color())
        b.plot(r.r * 1e3, r.depth[-1] * 1e3, color=line.get_color(), label=lab)
    a.set(xlabel="chamber speed Ω [1/s]", ylabel="liquid's mean speed [1/s]",
          title="spin-up (dotted: 003 eq 6; dot: lid reached)")
    b.set(xlabel="radius r [mm]", ylabel="depth h [mm]", title="liquid at the lid (mode 4)")
    a.legend(fontsize=8)
    a.grid(alpha=0.3)
    b.grid(alpha=0.3)
    if title:
        fig.suptitle(title)
    return fig


def stability_figure(res: dict, title: str = "") -> Figure:
    """The growth rate of the least stable perturbation of the centred state against speed
    (:func:`autobalance.liquid.stability.machine_stability`), the unstable ranges shaded and
    the natural frequency with the liquid as a rigid mass dotted.

    Parameters
    ----------
    res : dict
        ``machine_stability``'s result (speeds [rad/s], growth rates [1/s]); with balls beside
        the liquid ``balanced_machine_stability``'s (its ``ball_angles_rad``: the balanced
        state).
    title : str
        Figure title.
    """
    state = "balanced state of the balls" if "ball_angles_rad" in res else "centred state"
    fig = _new_figure((8, 4.5))
    ax = fig.subplots()
    ax.plot(res["omega_rad_s"], res["growth_rate_1_s"], "o-", ms=3)
    ax.axhline(0.0, color="k", lw=0.8)
    for lo, hi in res["unstable_ranges_rad_s"]:
        ax.axvspan(lo, hi, color="tab:red", alpha=0.15)
    ax.axvline(res["omega_n_rad_s"], color="0.5", ls=":", lw=1.0, label="ω_n (liquid rigid)")
    ax.axvline(res["film_from_rad_s"], color="tab:green", ls=":", lw=1.0,
               label="film from (003 eq 6; a pool below)")
    ax.set(xlabel="speed Ω [1/s]", ylabel="growth rate [1/s]",
           title=f"{state}, {res['cells']} cells per wall (shaded: unstable)")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    if title:
        fig.suptitle(title)
    return fig
