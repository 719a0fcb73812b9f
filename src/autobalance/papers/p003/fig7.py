"""003 Fig. 7 a-d (video frames of 300 ml at 18, 30, 54, 80 1/s) and the speed range of the
balancing mode (sec. 5.4, 7): entrainment speed (eq 6), liquid angle and efficiency of the
bench with the liquid from physics (the quasi-static liquid in the displaced chamber,
:func:`autobalance.liquid.steady.physical_steady_response`; the wall film coupled with the
rotor for the run-up, :func:`autobalance.liquid.film.physical_run_up`), surface shape (eq 5),
onset of balancing.
"""
from __future__ import annotations

import math
from dataclasses import replace

import numpy as np
import xarray as xr

from ...liquid import entrainment_speed, free_surface, motion_mode
from ...liquid.film import physical_run_up
from ...liquid.quasistatic import quasi_static
from ...liquid.stability import ring_stability
from ...liquid.steady import physical_steady_response, pool_response
from ...plotting import liquid as lp
from ...validation.target import Context, Outcome, Rows
from .bench import G10, GCM, ML, Bench, bench, grid
from .published import BALANCING, OPPOSITE_DEG, rows as rows_of

__all__ = ["FRAMES_RAD_S", "run_fig7"]

#: Speeds of 003's video frames Fig. 7 a-d [rad/s].
FRAMES_RAD_S = (18.0, 30.0, 54.0, 80.0)


def _frame_rows(rows: Rows, b: Bench, st: dict) -> None:
    """Rows of the frames a-d and of the surface shape at 80 1/s (300 ml)."""
    R, h, g, V = b.balancer.chamber.radius, b.balancer.chamber.height, b.g, b.video_volume
    ang, eff = np.abs(st["liquid_angle_deg"]), st["efficiency"]
    w0 = entrainment_speed(V, R, h, g)
    rows.add("a_entrained_rad_s", "omega_0 of eq 6 (300 ml) [1/s]; mode at 18 1/s",
             f"{w0:.2f} ({entrainment_speed(V, R, h, G10):.2f} at g = 10); mode "
             f"{motion_mode(18.0, V, R, h, g)}", "omega_0 <= 18", w0 <= 18.0,
             "003: eq 6 gives 16.2, 'fully consistent' with the observed 18 1/s")
    below = ("below resonance the liquid gathers on the deflection's side, which is the "
             "unbalance's side there (physics: the classical result, not 003's observation)")
    rows.add("b_opposite_at_30", "|liquid angle| at 30 1/s [deg]", round(float(ang[1]), 1),
             f"> {OPPOSITE_DEG:g}", ang[1] > OPPOSITE_DEG,
             f"efficiency there {eff[1]:.2f}" + ("" if ang[1] > OPPOSITE_DEG else "; " + below))
    rows.add("c_against_at_54", "|liquid angle| at 54 1/s [deg]", round(float(ang[2]), 1),
             f"> {OPPOSITE_DEG:g}", ang[2] > OPPOSITE_DEG,
             "at resonance the deflection lags the unbalance by about 90 deg and the liquid "
             "follows the deflection")
    lam = ring_stability(b.rotor, R, h, V, 80.0, density=b.balancer.liquid.density,
                         viscosity=b.balancer.liquid.kinematic_viscosity, n_cells=256)
    rows.add("d_effective_at_80", "steady efficiency at 80 1/s [-]", round(float(eff[3]), 2),
             f"> {BALANCING}", eff[3] > BALANCING,
             "the steady state; its stability is not part of this row. The coupled film run-up "
             "whirls asynchronously there with 300 ml of water (docs/liquid/film.md sec. 3d), and "
             f"the balanced state is linearly {'stable' if lam.stable else 'unstable'} there "
             f"(growth rate {lam.growth_rate:+.2f} 1/s on 256 cells, sec. 3j), while 003 "
             "observes balancing")
    fs, cyl = free_surface(80.0, V, R, h, g), math.sqrt(R * R - V / (math.pi * h))
    dev = max(cyl - fs.r_dry, fs.r_lid - cyl) / R
    rows.add("surface_cylindrical", "largest radial distance of the surface from the limiting "
             "cylinder at 80 1/s, / R [-]", round(dev, 5), "< 0.01", dev < 0.01,
             f"at omega_0 = {w0:.1f} 1/s: {(R - cyl) / R:.4f}")
    w80 = st["deflection_m"][3]
    q = quasi_static(R, h, V, b.balancer.liquid.density, 80.0, w80, g=g)
    rows.add("ring_shifted_centre", "horizontal section of the liquid at 80 1/s",
             f"{q.regime} about the rotation axis, offset {abs(w80) * 1e3:.2f} mm from the "
             "chamber centre", "a ring, shifted", q.regime == "ring" and abs(w80) > 0,
             "the quasi-static liquid turns about the rotation axis while the chamber is "
             "displaced by the whirl (docs/liquid/models.md sec. 3b)")


def _entrainment_rows(rows: Rows, b: Bench) -> dict:
    """Rows of the entrainment speed vs fill and unbalance (003 eq 6); returns omega_0 [rad/s]
    by fill [ml]."""
    R, h, g = b.balancer.chamber.radius, b.balancer.chamber.height, b.g
    w0s = {v: entrainment_speed(v * ML, R, h, g) for v in (100, 150, 200, 300, 350)}
    ok = all(15.0 <= w0s[v] <= 21.0 for v in (200, 300))
    rows.add("entrainment_observed_rad_s", "omega_0 of eq 6 at 200 and 300 ml [1/s]",
             f"{w0s[200]:.1f}, {w0s[300]:.1f}", "inside 15-21", ok,
             "the volumes of 003's eq 6 estimates other than 100 ml; outside: "
             + ", ".join(f"{v} ml {w0s[v]:.1f}" for v in (100, 150, 350))
             + " (003 does not say which fills the 15-21 range covers)")
    vals = list(w0s.values())
    rows.add("entrainment_falls_with_fill", "omega_0 at 100-350 ml [1/s]",
             " > ".join(f"{x:.1f}" for x in vals), "decreasing", all(np.diff(vals) < 0),
             "eq 6: omega_0 ~ V^-1/2")
    # how much the largest unbalance shakes the pool at its entrainment speed: the whirl of the
    # rotor carrying the pool (Jeffcott) and its wall acceleration against gravity
    rho = b.balancer.liquid.density
    shake = max(abs(complex(pool_response(replace(b.rotor, unbalance=3000.0 * GCM), v * ML, rho,
                                          w0s[v]))) for v in (200, 300))
    acc = shake * max(w0s[200], w0s[300]) ** 2 / g
    rows.add("entrainment_depends_on_unbalance", "omega_0 vs D", "independent of D", "-", False,
             "eq 6 contains no D, nor does the spin-up from rest (axisymmetric: the rotor's "
             "whirl is not in it, docs/liquid/spin-up.md sec. 3h); 003's dependence is experimental. "
             f"At omega_0 (200, 300 ml) the whirl of D = 3000 g*cm is at most "
             f"{shake * 1e3:.3f} mm, a wall acceleration of {100 * acc:.2f} % of g: the rotor "
             "barely shakes the pool there")
    return w0s


def _onset_rows(rows: Rows, b: Bench, w0s: dict) -> None:
    """Rows of the lower limit of the balancing range (150 ml): omega_0/omega_r, no balancing
    below it, onset near omega_r/2."""
    R, h, g, wr = b.balancer.chamber.radius, b.balancer.chamber.height, b.g, b.omega_r
    q = entrainment_speed(b.video_volume, R, h, g) / wr
    rows.add("omega0_over_omega_r", "omega_0(300 ml)/omega_r [-]", round(q, 3),
             "15/54-21/54 (003's observed spread)", 15 / 54 <= q <= 21 / 54)
    st150 = physical_steady_response(b.rotor, b.balancer, [wr / 3, wr / 2])["efficiency"]
    rows.add("no_balancing_before_entrainment", "efficiency at omega_r/3, 150 ml [-]",
             round(float(st150[0]), 3), "1 +- 0.02", abs(st150[0] - 1) <= 0.02,
             f"omega_0(150 ml) = {w0s[150]:.1f} 1/s > omega_r/3: a centred pool, its mass only")
    wg = np.linspace(0.2 * wr, 1.5 * wr, 131)
    e = physical_steady_response(b.rotor, b.balancer, wg)["efficiency"]
    onset = wg[np.argmax(e > BALANCING)] / wr if (e > BALANCING).any() else float("nan")
    rows.add("balancing_onset_over_omega_r", f"first speed with efficiency > {BALANCING}, 150 "
             "ml, / omega_r [-]", round(float(onset), 3), f"efficiency > {BALANCING} at "
             f"omega_r/2 ({st150[1]:.2f})", st150[1] > BALANCING,
             "" if st150[1] > BALANCING else "the liquid balances only past resonance, where the "
             "deflection turns away from the unbalance (physics, nothing calibrated)")


def run_fig7(ctx: Context) -> Outcome:
    """003 Fig. 7 a-d: 300 ml at 18, 30, 54, 80 rad/s: mode (003 eq 6), liquid angle [deg] and
    efficiency [-] (the liquid from physics), surface shape (003 eq 5); onset of balancing.

    Parameters
    ----------
    ctx : Context
        Variant (quick: coarser speed grid and run-up output for the figure and data).
    """
    b = bench()
    R, h, g = b.balancer.chamber.radius, b.balancer.chamber.height, b.g
    rows = rows_of("003-fig7")
    V = b.video_volume
    bal = b.balancer_with(V)
    k = bal.capacity / b.rotor.unbalance
    st = physical_steady_response(b.rotor, bal, FRAMES_RAD_S)
    _frame_rows(rows, b, st)
    _onset_rows(rows, b, _entrainment_rows(rows, b))
    w0 = entrainment_speed(V, R, h, g)
    ws = np.linspace(5.0, 100.0, grid(ctx, 96, 381))
    s300 = physical_steady_response(b.rotor, bal, ws)
    s150 = physical_steady_response(b.rotor, b.balancer, ws)
    ru = physical_run_up(b.rotor, bal, b.omega_end, b.duration, g, n_out=grid(ctx, 800, 4000))
    fig = lp.liquid_states_figure(s300, w0, b.rotor.natural_frequency(bal.mass), ru,
                                  FRAMES_RAD_S, np.radians(np.abs(st["liquid_angle_deg"])),
                                  ("steady, 150 ml", ws, s150["amplitude_m"]),
                                  f"003 Fig. 7 (physical model): R = {R:g} m, V = {V / ML:.0f} ml water, "
                                  f"D = {b.rotor.unbalance / GCM:.0f} g·cm")
    ds = xr.Dataset({"amplitude_m": (("volume_ml", "omega_rad_s"),
                                     np.array([s150["amplitude_m"], s300["amplitude_m"]])),
                     "liquid_angle_deg": (("volume_ml", "omega_rad_s"),
                                          np.array([s150["liquid_angle_deg"],
                                                    s300["liquid_angle_deg"]])),
                     "amplitude_dry_m": ("omega_rad_s", s300["amplitude_dry_m"]),
                     "run_up_omega_rad_s": ("t_s", ru.omega),
                     "run_up_amplitude_m": ("t_s", ru.amplitude),
                     "run_up_amplitude_dry_m": ("t_s", ru.amplitude_dry),
                     "run_up_liquid_angle_rad": ("t_s", ru.liquid_angle)},
                    coords={"volume_ml": [150.0, V / ML], "omega_rad_s": ws, "t_s": ru.t},
                    attrs={"source": "003 Fig. 7 (the liquid from physics; run-up: wall film "
                                     "coupled with the rotor from omega_0)",
                           "omega_0_rad_s": w0, "capacity_over_unbalance": k})
    return Outcome(rows, {"fig7": fig}, ds,
                   f"steady whirl on {ws.size} speeds (150 and 300 ml), film run-up "
                   f"{w0:.1f}-{b.omega_end:g} 1/s at {b.omega_end / b.duration:g} 1/s^2 "
                   f"({ru.t.size} samples)")
