"""Plots of the liquid balancer: free surface, amplitude vs speed, amplitude vs fill, and the
figures of the reproduction targets (:mod:`autobalance.papers.liquid.targets`).

The ``*_figure`` functions return a matplotlib ``Figure`` on an Agg canvas (no pyplot); the
``plot_*`` functions save the same figure to a file (the CLI's ``--plot``). Only the free-surface
figure evaluates the model (the surface of 003 eq 3-5); everything else draws what it is given.
"""
from __future__ import annotations

import matplotlib
import numpy as np
from matplotlib.figure import Figure

from ..plotting.timeplot import _new_figure
from .free_surface import MODE_NAMES, free_surface

__all__ = ["bars_figure", "curves_figure", "fill_figure", "fill_panels_figure", "plot_fill",
           "plot_response", "plot_surface", "response_figure", "save_figure", "surface_figure"]


def save_figure(fig: Figure, path, dpi: int = 120) -> None:
    """Write a figure to ``path`` (format from the suffix)."""
    fig.savefig(path, dpi=dpi)


def surface_figure(omegas, volume, radius, height, g=9.80665, title="") -> Figure:
    """Liquid depth vs radius at several speeds [rad/s]: whole radius and a zoom at the wall.

    Parameters
    ----------
    omegas : sequence of float
        Speeds [rad/s].
    volume : float
        V [m^3].
    radius, height : float
        Chamber R, h [m].
    g : float
        Gravity [m/s^2].
    title : str
        Figure title (default: the free-surface equation and the fixed quantities).
    """
    fig = _new_figure((10, 5.2 + 0.25 * ((len(omegas) + 1) // 2)))
    axes = fig.subplots(1, 2, gridspec_kw={"width_ratios": [3, 2]})
    cmap = matplotlib.colormaps["viridis"]
    zoom = 0.1 * radius
    labels = []
    for ax, (r0, r1) in zip(axes, ((0.0, radius), (radius - zoom, radius))):
        r = np.linspace(r0, r1, 1201)
        for i, w in enumerate(omegas):
            fs = free_surface(w, volume, radius, height, g)
            col = cmap(0.9 * i / max(len(omegas) - 1, 1))
            z = fs.depth(r)
            ax.fill_between(r * 1e3, 0, z * 1e3, color=col, alpha=0.12)
            ln, = ax.plot(r * 1e3, z * 1e3, color=col, lw=1.8)
            if ax is axes[0]:
                labels.append((ln, f"ω = {w:.3g} 1/s: mode {fs.mode} "
                                   f"({MODE_NAMES[fs.mode]}), regime {fs.regime}"))
        ax.plot([r0 * 1e3, radius * 1e3, radius * 1e3, r0 * 1e3],
                [0, 0, height * 1e3, height * 1e3], "k-", lw=2)
        ax.set_xlim(r0 * 1e3, radius * 1e3 + 0.02 * (r1 - r0) * 1e3)
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


def plot_surface(path, omegas, volume, radius, height, g=9.80665):
    """:func:`surface_figure` saved to ``path``."""
    save_figure(surface_figure(omegas, volume, radius, height, g), path)


def response_figure(steady: dict, omega0: float, omega_r: float, run=None, title="") -> Figure:
    """Amplitude [mm] vs speed, with and without liquid; efficiency below.

    Parameters
    ----------
    steady : dict
        :func:`autobalance.liquid.steady_response` output.
    omega0, omega_r : float
        Entrainment speed (003 eq 6) and natural frequency [rad/s], drawn as vertical lines.
    run : RunUp or None
        Run-up to draw under the steady curves.
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
    ax2.set_xlabel("rotor speed ω [1/s]")
    ax2.grid(alpha=0.3, which="both")
    return fig


def plot_response(path, steady: dict, omega0: float, omega_r: float, run=None, title=""):
    """:func:`response_figure` saved to ``path``."""
    save_figure(response_figure(steady, omega0, omega_r, run, title), path)


def fill_figure(sweeps: list[dict], labels: list[str], title="", ax=None) -> Figure:
    """Steady amplitude [mm] vs fill volume [ml] (003 Fig. 5), one curve per sweep.

    Parameters
    ----------
    sweeps : list of dict
        Each with ``volume_m3`` and ``amplitude_m`` arrays (:func:`autobalance.liquid.fill_sweep`).
    labels : list of str
        Curve labels.
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


def plot_fill(path, sweeps: list[dict], labels: list[str], title=""):
    """:func:`fill_figure` saved to ``path``."""
    save_figure(fill_figure(sweeps, labels, title), path)


def fill_panels_figure(panels: list[tuple], suptitle="") -> Figure:
    """Several :func:`fill_figure` panels side by side (003 Fig. 5 a-c).

    Parameters
    ----------
    panels : list of (sweeps, labels, title)
        Arguments of :func:`fill_figure` for each panel.
    """
    fig = _new_figure((5.0 * len(panels), 4.6))
    for ax, (sweeps, labels, title) in zip(np.atleast_1d(fig.subplots(1, len(panels),
                                                                       sharey=True)), panels):
        fill_figure(sweeps, labels, title, ax=ax)
    if suptitle:
        fig.suptitle(suptitle)
    return fig


def curves_figure(panels: list[dict], suptitle="", size=None) -> Figure:
    """Families of curves, one panel each.

    Parameters
    ----------
    panels : list of dict
        Each: ``x`` (array), ``curves`` (list of (label, y array, style str or "")), ``xlabel``,
        ``ylabel`` (with units), optional ``title``, ``logy`` (bool), ``points`` (list of
        (label, x list, y list): published values as markers), ``vlines`` (list of (x, label)).
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


def bars_figure(panels: list[dict], suptitle="") -> Figure:
    """Grouped bar charts, one panel each (003 Fig. 6 style).

    Parameters
    ----------
    panels : list of dict
        Each: ``groups`` (group labels), ``series`` (list of (label, values per group)),
        ``ylabel`` (with units), optional ``title``, ``xlabel``, ``logy``.
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
