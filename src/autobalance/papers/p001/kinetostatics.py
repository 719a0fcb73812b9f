"""001's closed forms: the kinetostatic liquid angle alpha0 and residual lambda0 (eq 2-4) and the
laminar friction force and angle (eq 5-7), computed by :mod:`autobalance.liquid.kinetostatic`.
"""
from __future__ import annotations

import math

import numpy as np
import xarray as xr

from ...liquid import (alpha0, alpha0_residual, balancing_efficiency, friction_angle,
                       friction_force, friction_tan_bound, jeffcott_phase, laminar_pipe_force,
                       residual_lambda0)
from ...plotting import liquid as lp
from ...validation.target import Context, Outcome
from ..p003.bench import ML, bench, grid
from .liquids import liquids_001
from .published import rows as rows_of

__all__ = ["run_eq3_4", "run_eq5_7"]


def run_eq3_4(ctx: Context) -> Outcome:
    """001 eq 3: alpha0(delta, k) [rad], root of eq 2; 001 eq 4: lambda0 = k/sqrt(1 + 2k cos
    alpha0 + k^2) [-]; efficiency e/e_c [-] vs the rotor phase delta [rad].

    Parameters
    ----------
    ctx : Context
        Variant (quick: a coarser phase-angle grid).
    """
    rows = rows_of("001-eq3-4")
    d = np.radians(np.linspace(0.5, 89.5, grid(ctx, 179, 891)))
    ks = np.array([0.5, 0.9, 1.0, 1.2, 2.0])
    res, lo, hi = 0.0, math.pi, 0.0
    for k in ks:
        a = alpha0(d, k)
        m = k >= np.sin(d)
        res = max(res, float(np.abs(alpha0_residual(a[m], d[m], k)).max(initial=0.0)))
        lo, hi = min(lo, float(a[m].min(initial=math.pi))), max(hi, float(a[m].max(initial=0)))
    rows.add("eq3_solves_eq2", "|eq 2 residual| at alpha0 of eq 3 [-]", f"{res:.1e}", "1e-12",
             res < 1e-12, "delta 0.5-89.5 deg, k = 0.5-2 where k >= sin(delta) (a root exists)")
    rows.add("alpha0_range", "alpha0 over delta in (0, 90) deg [deg]",
             f"{math.degrees(lo):.2f}-{math.degrees(hi):.2f}", "(90, 180]",
             lo > math.pi / 2 and hi <= math.pi + 1e-12)
    a1 = alpha0(d, 1.0)
    lam = float(residual_lambda0(1.0, math.pi))
    rows.add("k1_complete_balance", "k = 1: max |cos(alpha0) + 1|; lambda0",
             f"{np.abs(np.cos(a1) + 1).max():.1e}; {lam}", "1e-12; inf",
             np.abs(np.cos(a1) + 1).max() < 1e-12 and math.isinf(lam))
    z = np.array([0.05, 0.1, 0.2])
    dz = jeffcott_phase(0.8, z)
    e12, e1 = balancing_efficiency(1.2, dz), balancing_efficiency(1.0, dz, 0.1)
    with np.errstate(divide="ignore"):  # k = 1, beta = 0: complete balance, e/e_c = inf
        ef = np.array([balancing_efficiency(k, d) for k in ks])
    rows.add("rises_with_phase_angle", "e/e_c at 0.8 omega_n, zeta = 0.05/0.1/0.2 (k = 1.2)",
             "/".join(f"{x:.3f}" for x in e12), "rising", bool(np.all(np.diff(e12) > 0)),
             "001's own eq 3 gives the opposite: for k != 1 alpha0 moves away from pi as delta "
             f"grows; at k = 1 (beta = 0.1 rad) independent of delta ({e1[0]:.3f}); 001's "
             "claim is experimental and not reproduced")
    a0 = np.array([alpha0(d, k) for k in ks])
    fig = lp.kinetostatic_figure(d, ks, a0, ef, "001 eq 3-4: kinetostatic liquid angle and "
                                                "residual eccentricity")
    ds = xr.Dataset({"alpha0_deg": (("k", "delta_deg"), np.degrees(a0)),
                     "efficiency": (("k", "delta_deg"), ef)},
                    coords={"k": ks, "delta_deg": np.degrees(d)}, attrs={"source": "001 eq 3-4"})
    vs, fig_vs, note = _against_physics(ctx)
    return Outcome(rows, {"eq3_4": fig, "vs-physics": fig_vs}, {"": ds, "vs-physics": vs},
                   f"closed forms on {d.size} phase angles. {note}")


def _against_physics(ctx: Context) -> tuple:
    """001's laws at the physical phase and ratio of 003's bench (150 ml of water), beside the
    quasi-static liquid and the settled coupled film (docs/liquid/kinetostatics.md sec. 2b):
    (Dataset, figure, note)."""
    from ...liquid.kinetostatic_check import kinetostatic_vs_physics
    from ...plotting.liquid_check import kinetostatic_check_figure

    b = bench()
    c, L = b.balancer.chamber, b.balancer.liquid
    ws = np.linspace(40.0, 100.0, grid(ctx, 7, 13))
    res = kinetostatic_vs_physics(b.rotor, (c.radius, c.height, c.inner_radius, b.balancer.volume),
                                  L.density, L.kinematic_viscosity, ws, arc=b.balancer.arc,
                                  settle_time=4.0)
    gap = np.abs(res["alpha_deg"]) - np.abs(res["alpha0_deg"])
    film = np.abs(res["alpha_film_deg"] - res["alpha_deg"])
    ok = np.isfinite(gap)
    eq3 = (f"puts it {gap[ok].min():.1f}-{gap[ok].max():.1f} deg short where eq 2 has a root "
           f"({int(ok.sum())} of {ws.size} speeds" if ok.any() else "has no root at any speed (")
    note = (f"Against the physics (003's bench, 150 ml of water, {ws[0]:g}-{ws[-1]:g} 1/s, not a "
            "published number): the quasi-static liquid sits on the deflection, the coupled film "
            f"settles within {np.nanmax(film):.2f} deg of it, and 001 eq 3 at the physical "
            f"phase and k {eq3}; docs/liquid/kinetostatics.md sec. 2b).")
    fig = kinetostatic_check_figure(res, "001's kinetostatics against the liquid from physics "
                                         "(003's bench, 150 ml water)")
    ds = xr.Dataset({k: ("omega_rad_s", np.asarray(v, float)) for k, v in res.items()
                     if k != "omega_rad_s"}, coords={"omega_rad_s": ws},
                    attrs={"source": "001 eq 1, 3, 6 against docs/liquid/kinetostatics.md sec. 2b's physics"})
    return ds, fig, note


def run_eq5_7(ctx: Context) -> Outcome:
    """001 eq 5: F_T = 8 pi^2 mu R xi omega |O1C|/180 [N] (xi [deg] as 001 writes it; ours
    takes xi [rad]); eq 6: sin beta = F_T/F [-]; eq 7: |tan beta| bound [-]; mu [Pa*s], R [m],
    omega [rad/s], m [kg].

    Parameters
    ----------
    ctx : Context
        Variant (quick: a coarser speed grid for the figure and data).
    """
    b = bench()
    rows = rows_of("001-eq5-7")
    rng = np.random.default_rng(1)
    mu, rho, v, ll, dd = (rng.uniform(lo, hi, 200) for lo, hi in
                          ((1e-4, 0.2), (600, 1700), (0.01, 5), (0.01, 1), (1e-3, 0.1)))
    e1 = float(np.abs(laminar_pipe_force(mu, rho, v, ll, dd) / (8 * math.pi * mu * ll * v)
                      - 1).max())
    R, xi_deg, w, off = 0.2, 180.0, 30.0, np.array([1e-3, 1e-2, 0.1])
    xi = math.radians(xi_deg)
    e2 = float(np.abs(friction_force(1e-3, R, xi, w, off)
                      / (8 * math.pi * 1e-3 * (math.pi * R * xi_deg / 180) * w * off) - 1).max())
    rows.add("eq5_laminar", "relative difference of pi/4 dP d^2 (lambda = 64/Re) and "
             "8 pi mu l v; eq 5 with l = pi R xi/180, v = omega |O1C|", f"{max(e1, e2):.1e}",
             "1e-12", max(e1, e2) < 1e-12,
             "200 random (mu, rho, v, l, d); 001 writes lambda for the length l in eq 5")
    m = 0.15
    sb = np.sin(friction_angle(1e-3, R, xi, m, w))
    e3 = float(np.abs(friction_force(1e-3, R, xi, w, off) / (m * w * w * off) / sb - 1).max())
    rows.add("eq6_offset_cancels", "relative spread of F_T/F over |O1C| = 1, 10, 100 mm",
             f"{e3:.1e}", "1e-12", e3 < 1e-12)
    liquids = liquids_001()
    ws = np.linspace(5.0, 100.0, grid(ctx, 96, 381))
    names = list(liquids)
    arc, V = b.balancer.arc, b.balancer.volume
    beta_rad = np.array([friction_angle(L.dynamic_viscosity, R, arc, L.density * V, ws)
                         for L in liquids.values()])
    beta = np.degrees(beta_rad)
    s = np.sin(np.radians(beta))
    tb = np.array([friction_tan_bound(L.dynamic_viscosity, R, arc, L.density * V, ws)
                   for L in liquids.values()])
    held = beta >= 90.0 - 1e-9  # sin(beta) of eq 6 >= 1: friction holds the liquid (our clip)
    e4 = float(np.abs(tb[~held] / (s[~held] / np.sqrt(1 - s[~held] ** 2)) - 1).max())
    rows.add("eq7_bound", "relative difference of the eq 7 bound and tan(beta) of eq 6",
             f"{e4:.1e}", "1e-12", e4 < 1e-12,
             f"{int((~held).sum())} (liquid, omega) points with sin(beta) < 1; at the other "
             f"{int(held.sum())} (viscous liquids at low speed) eq 6 gives sin(beta) >= 1 and "
             "eq 7 has no bound")
    fig = lp.friction_angle_figure(ws, names, beta_rad,
                                   f"R = {R:g} m, V = {V / ML:.0f} ml, "
                                   f"ξ = {math.degrees(arc):g}°",
                                   "001 eq 6: friction angle of the 001 liquids")
    ds = xr.Dataset({"beta_deg": (("liquid", "omega_rad_s"), beta)},
                    coords={"liquid": np.array(names, dtype="U"), "omega_rad_s": ws},
                    attrs={"source": "001 eq 6", "radius_m": R, "arc_deg": math.degrees(arc),
                           "volume_m3": V})
    return Outcome(rows, {"eq6": fig}, ds, "closed forms; random algebra check")
