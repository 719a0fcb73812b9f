"""001 Fig. 3-6 (abstract): the trends of 001's experiments with liquids of several densities
and viscosities, from the steady whirl of 003's bench with the liquid from physics (the
quasi-static liquid in the displaced chamber, :func:`autobalance.liquid.steady.
physical_steady_response`, :func:`autobalance.liquid.steady.physical_fill_sweep`; nothing
calibrated). The steady synchronous whirl of a liquid turning rigidly with the chamber does not
depend on its viscosity: viscosity acts on the film's waves and on whether that whirl is
reached (docs/liquid/machine.md sec. 3f, the stability map).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
import xarray as xr

from ...liquid import Liquid, sufficient_volume
from ...liquid.steady import physical_fill_sweep, physical_steady_response
from ...plotting import liquid as lp
from ...validation.target import Context, Outcome, Rows
from ..p003.bench import ML, Bench, bench, grid
from ..p003.fig5_6 import TIE
from ..p003.published import BALANCING
from .liquids import liquids_001
from .published import rows as rows_of

if TYPE_CHECKING:
    from collections.abc import Sequence

__all__ = ["DENSITY_SERIES", "VISCOSITY_SERIES", "at_optimal_fill", "run_fig3_6"]

#: Liquids of liquids_001.toml in 001's density series (Fig. 3-5) and viscosity series (Fig. 6).
DENSITY_SERIES = ("light_670", "water", "dense_1230", "dense_1370", "heavy_1650")
VISCOSITY_SERIES = ("water", "viscous_14", "viscous_97")


def at_optimal_fill(b: Bench, liquid: Liquid, omegas: Sequence[float]) -> dict:
    """Steady response with ``liquid`` at its own sufficient fill rho V R = D (k = 1).

    Parameters
    ----------
    b : Bench
        The bench (rotor, chamber radius [m], model).
    liquid : Liquid
        Working liquid (density [kg/m^3], viscosity).
    omegas : sequence of float
        Speeds [rad/s].
    """
    V = sufficient_volume(b.rotor.unbalance, liquid.density, b.balancer.chamber.radius)
    return physical_steady_response(b.rotor, b.balancer_with(V, liquid=liquid), omegas)


def _regime_rows(rows: Rows, b: Bench, liquids: dict) -> None:
    """Rows all_regimes and rises_toward_critical (density series, k = 1)."""
    wr = b.omega_r
    zones = {"before": (0.6, 0.8), "at": (1.0,), "after": (1.2,)}
    best = {z: min(max(at_optimal_fill(b, liquids[n], [f * wr for f in fs])["efficiency"])
                   for n in DENSITY_SERIES) for z, fs in zones.items()}
    rows.add("all_regimes", "least (over 670-1650 kg/m^3) best efficiency before / at / after "
             "resonance, k = 1 [-]", " / ".join(f"{best[z]:.3g}" for z in zones),
             f"> {BALANCING} in each zone", min(best.values()) > BALANCING,
             "before: 0.6, 0.8 omega_r; at: omega_r; after: 1.2 omega_r (our zones)"
             + ("" if min(best.values()) > BALANCING else "; below resonance the liquid "
                "gathers on the deflection's side, the unbalance's (physics)"))
    ev = at_optimal_fill(b, liquids["viscous_97"], [35.0, 42.0, 50.0])["efficiency"]
    up = bool(np.all(np.diff(ev) > 0))
    rows.add("rises_toward_critical", "efficiency at 35/42/50 1/s, nu = 96.97e-6 m^2/s, k = 1",
             "/".join(f"{x:.2f}" for x in ev), "rising", up,
             "" if up else "below resonance the liquid raises the whirl more as the deflection "
             "grows toward resonance (physics)")


def _fill_rows(rows: Rows, b: Bench, liquids: dict) -> dict:
    """Row density_optimal_fill; returns the optimal fill [ml] by liquid of the density
    series."""
    vols = np.array(b.sweep_volumes)
    opt = {}
    for n in DENSITY_SERIES:        # the least fill within TIE of the least amplitude
        a = physical_fill_sweep(b.rotor, b.balancer_with(liquid=liquids[n]), vols,
                                b.omega_r)["amplitude_m"]
        opt[n] = round(float(vols[np.argmax(a <= (1 + TIE) * a.min())]) / ML)
    spread = max(opt.values()) - min(opt.values())
    rows.add("density_optimal_fill", f"least fill within {TIE:.0%} of the least amplitude at "
             "omega_r, 670-1650 kg/m^3 [ml]",
             "/".join(str(opt[n]) for n in DENSITY_SERIES), "within one 50 ml step",
             spread <= 50, "the liquid's moment follows from the deflection and the film's "
             "geometry, not from a capacity rho V R (docs/liquid/film.md sec. 3d)"
             + ("" if spread <= 50 else "; a denser liquid still needs less volume, by less "
                "than 1/rho"))
    return opt


def _viscosity_rows(rows: Rows, b: Bench, liquids: dict) -> None:
    """Rows viscosity_at_optimum and viscosity_over_density (50 1/s, k = 1)."""
    e50 = {n: at_optimal_fill(b, liquids[n], [50.0])
           for n in set(DENSITY_SERIES) | set(VISCOSITY_SERIES)}
    amp_ratio = e50["viscous_97"]["amplitude_m"][0] / e50["water"]["amplitude_m"][0]
    visc = ("the steady synchronous whirl of a liquid turning rigidly with the chamber does "
            "not depend on its viscosity (physics); viscosity damps the film's waves and decides "
            "whether that whirl is reached (study fill-map --dynamic)")
    rows.add("viscosity_at_optimum", "A(nu = 96.97e-6)/A(water) at 50 1/s, k = 1 [-]",
             round(float(amp_ratio), 1), f"> {BALANCING}", amp_ratio > BALANCING,
             "" if amp_ratio > BALANCING else visc)
    by_d = e50["light_670"]["efficiency"][0] / e50["heavy_1650"]["efficiency"][0]
    by_v = e50["water"]["efficiency"][0] / e50["viscous_97"]["efficiency"][0]
    rows.add("viscosity_over_density", "efficiency ratio over the viscosity range / over the "
             "density range at 50 1/s, k = 1", f"{by_v:.1f} / {by_d:.2f}", "ratio > 10",
             by_v > 10 * by_d, "" if by_v > 10 * by_d else visc)


def _overfill_row(rows: Rows, b: Bench) -> None:
    """Row overfill_worse: water at omega_r, fills beyond the optimum."""
    sw = physical_fill_sweep(b.rotor, b.balancer, np.array(b.sweep_volumes), b.omega_r)
    iopt = int(np.argmin(sw["amplitude_m"]))
    worse = iopt + 1 < len(sw["amplitude_m"]) and bool(
        np.all(sw["amplitude_m"][iopt + 1:] > sw["amplitude_m"][iopt]))
    rows.add("overfill_worse", "water at omega_r: A(200-350 ml) > A(optimum) ",
             f"optimum {sw['optimum_volume_m3'] / ML:.0f} ml; "
             + ("all larger fills worse" if worse else "not all worse"), "direction", worse,
             "" if worse else "at resonance the whirl falls with the fill while the film is "
             "broken (a crescent), then stays flat once it closes into an intact ring: "
             "over-filling does not hurt the steady whirl (physics); 001 explains its loss by "
             "surface waves, which the stability map shows as a whirl not reached")


def run_fig3_6(ctx: Context) -> Outcome:
    """001 Fig. 3-6 (abstract): efficiency [-], optimal fill [ml] and dynamic support force
    |u| |k + i c omega| [N] for the 001 liquids (rho [kg/m^3], nu [m^2/s]), the liquid from
    physics.

    Parameters
    ----------
    ctx : Context
        Variant (quick: a coarser speed grid for the figures and data).
    """
    b = bench()
    R, D, wr = b.balancer.chamber.radius, b.rotor.unbalance, b.omega_r
    rows = rows_of("001-fig3-6")
    liquids = liquids_001()
    _regime_rows(rows, b, liquids)
    opt = _fill_rows(rows, b, liquids)
    _viscosity_rows(rows, b, liquids)
    _overfill_row(rows, b)
    ws = np.linspace(10.0, 100.0, grid(ctx, 91, 361))
    names = list(dict.fromkeys(DENSITY_SERIES + VISCOSITY_SERIES))
    runs = {n: at_optimal_fill(b, liquids[n], ws) for n in names}
    force = {n: b.rotor.support_force(r["amplitude_m"], ws) for n, r in runs.items()}
    force_dry = b.rotor.support_force(runs["water"]["amplitude_dry_m"], ws)
    f35 = lp.speed_series_figure(
        ws, [(f"{n} ({liquids[n].density:g} kg/m³)", runs[n]["efficiency"], "")
             for n in DENSITY_SERIES], wr, "efficiency A_dry/A_wet [-]",
        "density series at k = 1, ν = 1.01e-6 m²/s",
        "001 Fig. 3-5 (physical model): balancing with liquids of different density", floor=(1e-2, 1e4))
    f6 = lp.speed_series_figure(
        ws, [("no liquid", force_dry, "k--")]
        + [(f"{n} (ν = {liquids[n].kinematic_viscosity:.3g} m²/s)", force[n], "")
           for n in VISCOSITY_SERIES], wr, "dynamic support force [N]",
        "viscosity series at k = 1",
        "001 Fig. 6 (physical model): dynamic force vs speed for several viscosities")
    ds = xr.Dataset({"efficiency": (("liquid", "omega_rad_s"),
                                    np.array([runs[n]["efficiency"] for n in names])),
                     "force_N": (("liquid", "omega_rad_s"), np.array([force[n] for n in names])),
                     "force_dry_N": ("omega_rad_s", force_dry),
                     "volume_ml": ("liquid", [sufficient_volume(D, liquids[n].density, R) / ML
                                              for n in names]),
                     "optimal_fill_ml": ("liquid", [float(opt.get(n, np.nan)) for n in names])},
                    coords={"liquid": np.array(names, dtype="U"), "omega_rad_s": ws},
                    attrs={"source": "001 Fig. 3-6 (the liquid from physics, leblanc_003)",
                           "unbalance_kg_m": D, "radius_m": R})
    return Outcome(rows, {"fig3_5": f35, "fig6": f6}, ds,
                   f"steady response of {len(names)} liquids on {ws.size} speeds")
