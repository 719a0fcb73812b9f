"""Plots of the liquid balancer: free surface, amplitude vs speed, amplitude vs fill."""
from __future__ import annotations

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from .free_surface import MODE_NAMES, free_surface  # noqa: E402

__all__ = ["plot_fill", "plot_response", "plot_surface"]


def plot_surface(path, omegas, volume, radius, height, g=9.80665):
    """Liquid depth vs radius at several speeds [rad/s]: whole radius and a zoom at the wall."""
    fig, axes = plt.subplots(1, 2, figsize=(10, 5.2), gridspec_kw={"width_ratios": [3, 2]})
    cmap = plt.get_cmap("viridis")
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
    fig.suptitle(f"Free surface z = z* + ω²r²/2g, V = {volume * 1e6:.4g} ml, "
                 f"R = {radius * 1e3:.4g} mm, h = {height * 1e3:.4g} mm (003 eq 3-5)")
    fig.legend([l for l, _ in labels], [t for _, t in labels], loc="lower center", ncol=2,
               fontsize=8, frameon=False)
    fig.tight_layout(rect=(0, 0.06 + 0.035 * ((len(labels) + 1) // 2), 1, 1))
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_response(path, steady: dict, omega0: float, omega_r: float, run=None, title=""):
    """Amplitude [mm] vs speed, with and without liquid; efficiency below."""
    fig, (ax, ax2) = plt.subplots(2, 1, figsize=(8, 6.5), sharex=True,
                                  gridspec_kw={"height_ratios": [2, 1]})
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
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)


def plot_fill(path, sweeps: list[dict], labels: list[str], title=""):
    """Steady amplitude [mm] vs fill volume [ml] (003 Fig. 5)."""
    fig, ax = plt.subplots(figsize=(7.5, 4.6))
    for s, lab in zip(sweeps, labels):
        ax.plot(s["volume_m3"] * 1e6, s["amplitude_m"] * 1e3, "o-", label=lab)
    ax.set_xlabel("liquid volume V [ml]")
    ax.set_ylabel("whirl amplitude [mm]")
    ax.set_yscale("log")
    ax.set_title(title or "Amplitude vs fill", fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)
    plt.close(fig)
