"""003's closed forms: the bottom-touch and entrainment speeds (eq 4, eq 6) and the free surface
in the four motion modes (eq 1-5, Fig. 4). Compute with :mod:`autobalance.liquid`, compare with
:mod:`.published`, draw with :mod:`autobalance.plotting.liquid`.
"""
from __future__ import annotations

import math

import numpy as np
import xarray as xr

from ...liquid import (G_STANDARD, bottom_touch_speed, entrainment_speed, free_surface,
                       liquid_volume, mode_speeds, motion_mode, surface_profiles)
from ...plotting import liquid as lp
from ...validation.target import Context, Outcome, Rows
from .bench import G10, ML, bench, grid
from .published import printed_tolerance, rows as rows_of

__all__ = ["run_eq4_6", "run_fig4"]


# -- 003 eq 4 and eq 6: speeds ------------------------------------------------------------------
def _speed_rows(rows: Rows, R: float, h: float) -> None:
    """Rows of 003's printed speeds (eq 4 at V = 100 ml, eq 6 at 100/200/300 ml), each with
    g = 10 m/s^2 and with standard gravity."""
    for gk, g in (("g10", G10), ("g_standard", G_STANDARD)):
        cases = [("bottom_touch_rad_s", "0.89", bottom_touch_speed(100 * ML, R, g),
                  "omega at z* = 0, V = 100 ml [1/s] (003 eq 4)")]
        cases += [(f"omega0_rad_s/V{v}ml", p, entrainment_speed(v * ML, R, h, g),
                   f"omega_0, V = {v} ml [1/s] (003 eq 6)")
                  for v, p in ((100, "28"), (200, "19.8"), (300, "16.2"))]
        for path, printed, w, q in cases:
            pub = rows.published(f"{path}/{gk}")
            ok = abs(w - pub) <= printed_tolerance(printed)
            dev = 100.0 * (w / pub - 1.0)
            note = ("003's printed speeds follow from g = 10 m/s^2" if gk == "g10" else
                    f"{dev:+.1f} % with standard gravity" +
                    ("" if ok else "; 003 evidently used g = 10 m/s^2 (row g10)"))
            rows.add(f"{path}/{gk}", f"{q}, g = {g:g} m/s^2", round(w, 4),
                     f"+-{printed_tolerance(printed):g}", ok, note)


def run_eq4_6(ctx: Context) -> Outcome:
    """003 eq 4: omega_b = (2/R^2) sqrt(g V/pi) [rad/s] (z* = 0); 003 eq 6: omega_0 =
    sqrt(pi g h^2/V) [rad/s]; V [m^3], R, h [m], g [m/s^2] = 10 and 9.80665.

    Parameters
    ----------
    ctx : Context
        Variant (quick: a coarser volume grid for the figure).
    """
    b = bench()
    R, h = b.balancer.chamber.radius, b.balancer.chamber.height
    rows = rows_of("003-eq4-6")
    _speed_rows(rows, R, h)
    vols = np.linspace(25.0, 350.0, grid(ctx, 66, 326))
    gs = np.array([G10, G_STANDARD])
    wb = np.array([[bottom_touch_speed(v * ML, R, g) for v in vols] for g in gs])
    w0 = np.array([[entrainment_speed(v * ML, R, h, g) for v in vols] for g in gs])
    ds = xr.Dataset({"omega_b_rad_s": (("g_m_s2", "volume_ml"), wb),
                     "omega_0_rad_s": (("g_m_s2", "volume_ml"), w0)},
                    coords={"g_m_s2": gs, "volume_ml": vols},
                    attrs={"source": "003 eq 4 (omega_b), eq 6 (omega_0)", "radius_m": R,
                           "height_m": h})
    printed_0 = [rows.published(f"omega0_rad_s/V{v}ml/g10") for v in (100, 200, 300)]
    fig = lp.mode_speeds_figure(vols * ML, gs, wb, w0,
                                ([100 * ML], [rows.published("bottom_touch_rad_s/g10")]),
                                ([100 * ML, 200 * ML, 300 * ML], printed_0),
                                f"003 eq 4 and eq 6: R = {R:g} m, h = {h:g} m")
    return Outcome(rows, {"eq4_6": fig}, ds,
                   f"closed forms of 003 eq 4 and 6 at g = 10 and 9.80665 m/s^2; figure on "
                   f"{vols.size} volumes")


# -- 003 Fig. 4: free surface in the four modes ------------------------------------------------
def _mode_rows(rows: Rows, vols, R: float, h: float, g: float) -> None:
    """Rows four_modes, mode2_end and mode3_end: the order of the modes with speed and the
    speeds that end modes 2 and 3 (003 sec. 5.1-5.2)."""
    grid_w = np.linspace(0.0, 60.0, 601)
    seqs = {round(V / ML): [motion_mode(w, V, R, h, g) for w in grid_w] for V in vols}
    ok = all(s == sorted(s) and set(s) == {1, 2, 3, 4} for s in seqs.values())
    rows.add("four_modes", "motion modes over 0-60 1/s (003 sec. 5.1)",
             "1 -> 2 -> 3 -> 4 for " + ", ".join(f"{v} ml" for v in seqs), "all four, in order",
             ok, "mode 1 -> 2 is our criterion (centre sunk by 0.25 h0): 003 gives none")
    z_b, reg_b, wall0, reg_0 = [], [], [], []
    for V in vols:
        s = mode_speeds(V, R, h, g)
        wb, w0 = s["bottom_touch_rad_s"], s["omega_0_rad_s"]
        z_b.append(abs(free_surface(wb, V, R, h, g).z_star))
        reg_b.append(free_surface(wb * (1 - 1e-6), V, R, h, g).regime
                     + free_surface(wb * (1 + 1e-6), V, R, h, g).regime)
        wall0.append(abs(free_surface(w0, V, R, h, g).wall_height / h - 1.0))
        reg_0.append(free_surface(w0 * (1 - 1e-6), V, R, h, g).regime
                     + free_surface(w0 * (1 + 1e-6), V, R, h, g).regime)
    rows.add("mode2_end", "z* at the mode 2 -> 3 speed [m], regime across it",
             f"|z*| <= {max(z_b):.1e} m; regimes {'/'.join(sorted(set(reg_b)))}",
             "|z*| < 1e-12 m, A -> B", max(z_b) < 1e-12 and set(reg_b) == {"AB"},
             "100, 200, 300 ml (all below half filling, V_c/2 = 3.14 l)")
    rows.add("mode3_end", "wall height at omega_0 of eq 6 vs h [-], regime across it",
             f"|z(R)/h - 1| <= {max(wall0):.1e}; regimes {'/'.join(sorted(set(reg_0)))}",
             "1e-9, B -> D", max(wall0) < 1e-9 and set(reg_0) == {"BD"})


def _volume_rows(rows: Rows, vols, R: float, h: float, g: float) -> int:
    """Rows volume_balance, shape_above_omega0 and density_free; returns the number of volume
    checks."""
    errs, regimes = [], set()
    for fill in np.linspace(0.01, 0.99, 25):
        V = fill * math.pi * R * R * h
        for w in np.linspace(0.0, 200.0, 41):
            fs = free_surface(w, V, R, h, g)
            regimes.add(fs.regime)
            errs.append(abs(liquid_volume(fs.z_star, w, R, h, g) / V - 1.0))
    rows.add("volume_balance", "relative volume error of the clipped paraboloid [-]",
             f"{max(errs):.1e} over {len(errs)} cases, regimes {''.join(sorted(regimes))}",
             "1e-9", max(errs) < 1e-9 and regimes == set("ABCD"),
             "fills 1-99 % of the chamber, 0-200 1/s (regimes C, D: our closed forms)")
    dr = [(free_surface(1e4, V, R, h, g).mean_radius()
           - free_surface(entrainment_speed(V, R, h, g), V, R, h, g).mean_radius()) / R
          for V in vols]
    rows.add("shape_above_omega0", "change of the liquid's mean radius from omega_0 to "
             "omega -> inf, / R [-]", round(max(dr), 5), "< 0.01", max(dr) < 0.01,
             f"R/h = {R / h:g}; 100/200/300 ml: " + ", ".join(f"{x:.2%}" for x in dr)
             + "; the mean radius sets the unbalance the liquid can create")
    rows.add("density_free", "density in the free-surface balance (003 eq 3-5)",
             "none: z*, H and the modes are functions of V, R, h, omega, g only", "-", True,
             "the material balance is geometric; the density enters only the dynamics")
    return len(errs)


def run_fig4(ctx: Context) -> Outcome:
    """003 eq 3-5, Fig. 4: free surface z(r) = z* + omega^2 r^2/(2g) [m] clipped to the chamber,
    its motion modes (003 sec. 5.1) and volume balance; V [m^3], R, h [m], omega [rad/s].

    Parameters
    ----------
    ctx : Context
        Variant (quick: a coarser radial grid for the data).
    """
    b = bench()
    R, h = b.balancer.chamber.radius, b.balancer.chamber.height
    g = b.g
    rows = rows_of("003-fig4")
    vols = (100 * ML, 200 * ML, 300 * ML)
    _mode_rows(rows, vols, R, h, g)
    n_checks = _volume_rows(rows, vols, R, h, g)
    V = b.video_volume
    s = mode_speeds(V, R, h, g)
    w1, w2, w0 = s["omega_1_rad_s"], s["omega_2_rad_s"], s["omega_0_rad_s"]
    speeds = [0.0, 0.5 * (w1 + w2), math.sqrt(w2 * w0), w0, 2.0 * w0]
    fig = lp.surface_figure(surface_profiles(speeds, V, R, h, g),
                            title=f"003 Fig. 4 (ours): free surface in the four modes, "
                                  f"V = {V / ML:.0f} ml, R = {R:g} m, h = {h:g} m")
    r = np.linspace(0.0, R, grid(ctx, 401, 2001))
    fss = [free_surface(w, V, R, h, g) for w in speeds]
    ds = xr.Dataset({"depth_m": (("omega_rad_s", "r_m"), np.array([f.depth(r) for f in fss])),
                     "z_star_m": ("omega_rad_s", [f.z_star for f in fss]),
                     "mode": ("omega_rad_s", np.array([f.mode for f in fss], dtype=np.int32)),
                     "regime": ("omega_rad_s", np.array(["ABCD".index(f.regime) for f in fss],
                                                        dtype=np.int32))},
                    coords={"omega_rad_s": speeds, "r_m": r},
                    attrs={"source": "003 eq 3-5", "volume_m3": V, "radius_m": R,
                           "height_m": h, "g_m_s2": g, "regime_codes": "0=A 1=B 2=C 3=D"})
    return Outcome(rows, {"fig4": fig}, ds,
                   f"closed-form free surface; volume check on {n_checks} cases")
