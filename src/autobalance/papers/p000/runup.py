"""Seed 000 washer: balancing at constant speed (Fig. 5) and the run-up to 1000 rpm (Tables 1-2,
Fig. 10-11), against the paper.

Each ``compute_*`` returns plain data (SI); :data:`PUBLISHED` holds the paper's numbers (one
leaf per number, units in the key); ``compare_*`` return keyed rows
(:class:`autobalance.validation.target.Rows`).

Choices (the paper omits them; docs/model.md sec. 7, docs/VALIDATION.md):

* machine: the ``washer_000`` preset with two balls of m R = Me and gravity (000 eq 50); ball
  damping c_i = 2 1/s (D = c_i m R^2), calibrated on the ball revolutions of Table 1; drum
  inertia B_z = 0.532 kg m^2 from t_f = B_z w_f / T0 = 2.23 s (Table 1, constant torque);
* Fig. 5: balls at rest at 90 and 150 deg with the drum on its harmonic orbit; also with
  c_i = 7.1 1/s, the ball damping at which the same start settles in the published 1.5 s;
* run-ups: the balls start together at the bottom of the drum, opposite the unbalance (000:
  "during the washing cycle the balls stay at the lowest position"); the speed controller takes
  over at n_f (constant torque) or at 0.99 n_f (the linear and harmonic laws approach n_f only
  asymptotically); 25 s simulated.

Tolerances (justified in docs/VALIDATION.md): +-30 % on the run-up amplitudes and +-2.5 ball
revolutions (what varying the omitted c_i from 2 to 3 1/s moves them by); +-5 % on t_f (the load
of the unbalance and the balls on the drum, ~3 %); +-0.5 deg on the final ball angles (gravity
wobble ~0.13 deg); the balancing time against the paper's own bound t < 250/w.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ...models import MotorDrive
from ...physics.runup import runup_fraction_closed_form, runup_time_closed_form
from ...studies._runup import balancing_time as _balancing_time
from ...validation.target import Rows
from .washer import W1000, washer

if TYPE_CHECKING:
    from ...models import System
    from ...simulate.result import Simulation

__all__ = ["B_Z", "LAWS", "PUBLISHED", "T0", "balancing_time", "compare_fig10_11", "compare_fig5",
           "compare_tables", "compute_fig10_11", "compute_fig5", "compute_tables", "runup",
           "runup_fraction_closed_form", "runup_time_closed_form", "settle"]

#: Motor torque T0 [N*m] of 000 Tables 1-2.
T0 = 25.0
#: Drum inertia B_z [kg*m^2] (the washer_000 preset's calibration on Table 1).
B_Z = 0.532
#: Torque laws of 000 Tables 1-2.
LAWS = MotorDrive.LAWS
#: Static unbalance Me [kg*m] of Table 1 and Table 2.
TABLE_ME = {1: 0.025, 2: 0.05}
#: Ball damping c_i [1/s] of the two Fig. 5 runs: the preset, and the one that settles in 1.5 s.
FIG5_C_I = {"c_i_2": 2.0, "c_i_7.1": 7.1}


def _table(values) -> dict:
    """Rows (t_f [s], x_max [mm], y_max [mm], revolutions [-]) in the order of LAWS."""
    cols = ("t_f_s", "x_max_mm", "y_max_mm", "revolutions")
    return {law: dict(zip(cols, v)) for law, v in zip(LAWS, values)}


PUBLISHED = {
    "fig5": {"alpha1_deg": 120.0, "alpha2_deg": -120.0,
             "balancing_time_s": {"c_i_2": 1.5, "c_i_7.1": 1.5},
             "settle_time_conclusions_wt": 150.0,
             "source": "000 Fig. 5: two balls, Me = mR = 0.025 kg m, 1000 rpm; balanced 'in just 1.5 "
                       "seconds (t < 250/w)'; Conclusions: final position 'very quickly t < 150/w'"},
    "table1": {"_Me_kg_m": 0.025, "source": "000 Table 1: T0 = 25 N m, n_f = 1000 rpm, Me = mR = 0.025 kg m",
               **_table([(2.23, 4.6, 4.1, 8.0), (8.2, 4.9, 4.9, 7.6), (8.6, 5.1, 5.2, 6.0)])},
    "table2": {"_Me_kg_m": 0.05, "source": "000 Table 2: T0 = 25 N m, n_f = 1000 rpm, Me = mR = 0.05 kg m",
               **_table([(1.7, 8.5, 8.7, 7.0), (7.2, 9.2, 8.6, 8.0), (8.3, 9.9, 9.7, 5.5)])},
    "fig10": {"ball_direction": "opposite to the drum rotation",
              "amplitude_with_vs_without_balls": "very small difference",
              "source": "000 Fig. 10 and 'Variable spin velocity': constant torque; the balls move "
                        "opposite to the drum as it accelerates; at the resonances the amplitudes "
                        "are almost the same with and without the balls"},
    "fig11": {"revolutions": 8.0, "amplitude_with_vs_without_balls": "very small difference",
              "source": "000 Fig. 11: linear torque; 'the balls turn with the drum about 8 times'; "
                        "'a very small difference between the maximum amplitude of vibrations "
                        "with and without the balls'"},
}


# -- closed forms ------------------------------------------------------------------------------


# -- simulations -------------------------------------------------------------------------------
def balancing_time(sim: Simulation, fraction: float = 0.05) -> float:
    """Last time [s] at which the whirl amplitude exceeds ``fraction`` of the unbalanced drum's
    amplitude far above resonance, e = Me/M_t [m] (000 eq 6-7 with a = e); the run-up study's
    :func:`autobalance.studies._runup.balancing_time` on a Simulation.

    Parameters
    ----------
    sim : Simulation
        A run of :func:`autobalance.simulate.simulate` (time [s], amplitude [m]).
    fraction : float
        Threshold as a fraction of e [-].
    """
    s = sim.system
    return _balancing_time(sim.t, sim.amplitude, s.rotor.unbalance / s.total_mass, fraction)


def settle(c_i: float = 2.0, duration: float = 10.0) -> tuple[System, Simulation, float]:
    """000 Fig. 5: two balls with mR = Me = 0.025 kg m at 1000 rpm from (90, 150) deg, gravity on.

    Parameters
    ----------
    c_i : float
        Ball damping c_i [1/s] (D = c_i m R^2).
    duration : float
        Simulated time [s].

    Returns
    -------
    tuple
        (system, Simulation, balancing time [s]).
    """
    from ...models import InitialState, SimOptions, SpeedProfile
    from ...simulate import simulate

    s = washer(Me=0.025, c_i=c_i, g=9.81)
    sim = simulate(s, SpeedProfile.constant(W1000, duration),
                   initial=InitialState(ball_angles=(math.radians(90), math.radians(150)),
                                        steady_state=True),
                   options=SimOptions(save_dt=2e-3))
    return s, sim, balancing_time(sim)


def runup(Me: float, law: str, balls: bool = True, duration: float = 25.0) -> Simulation:
    """000 Tables 1-2 run-up: T0 = 25 N m to n_f = 1000 rpm under ``law`` (000 eq 15-18), two balls
    of mR = Me starting together at the bottom (or without balls).

    Parameters
    ----------
    Me : float
        Static unbalance Me = m R of each ball [kg*m].
    law : str
        Torque law, one of :data:`LAWS`.
    balls : bool
        With the two balls (False: the drum alone).
    duration : float
        Simulated time [s].

    Returns
    -------
    Simulation
    """
    import dataclasses

    from ...models import InitialState, MotorDrive, SimOptions
    from ...simulate import simulate

    s = washer(Me=Me, g=9.81)
    if balls:
        d = s.balancer.contact_angle
        start = (math.pi - d / 2 - 1e-3, math.pi + d / 2 + 1e-3)
    else:
        s = dataclasses.replace(s, balancer=dataclasses.replace(s.balancer, n_balls=0))
        start = ()
    drive = MotorDrive(law, T0, W1000, duration, hold_fraction=1.0 if law == "constant" else 0.99)
    return simulate(s, drive, initial=InitialState(ball_angles=start), options=SimOptions(save_dt=2e-3))


def _history(sim) -> dict:
    return {"t_s": sim.t, "x_m": sim.x, "y_m": sim.y, "alpha_rad": sim.alpha,
            "speed_rad_s": sim.speed, "amplitude_m": sim.amplitude}


def compute_fig5(duration: float = 10.0) -> dict:
    """000 Fig. 5 with the preset c_i = 2 1/s and with c_i = 7.1 1/s: {case: run dict}.

    Parameters
    ----------
    duration : float
        Simulated time of each run [s].
    """
    out = {}
    for case, c_i in FIG5_C_I.items():
        s, sim, tb = settle(c_i, duration)
        out[case] = {**_history(sim), "c_i": c_i, "balancing_time_s": tb,
                     "final_alpha_deg": np.sort(np.degrees(np.angle(np.exp(1j * sim.alpha[-1])))),
                     "final_amplitude_m": float(sim.amplitude[-1])}
    return out


def _summary(sim) -> dict:
    S = sim.summary()
    return {"status": S["status"], "t_f_s": S.get("time_to_final_speed_s"),
            "x_max_m": S["x_max_m"], "y_max_m": S["y_max_m"],
            "revolutions": float(np.mean(np.abs(S["ball_revolutions"]))) if sim.n_balls else 0.0,
            "signed_revolutions": [float(v) for v in S["ball_revolutions"]],
            "final_grade_G_mm_s": S["final"]["grade_G_mm_s"]}


def compute_tables(histories: bool = False) -> dict:
    """000 Tables 1-2: {(table, law): summary dict} for the six run-ups.

    Parameters
    ----------
    histories : bool
        Also keep the time histories (t [s], x, y [m], ball angles [rad], speed [rad/s]).
    """
    out = {}
    for tab, Me in TABLE_ME.items():
        for law in LAWS:
            sim = runup(Me, law)
            out[(tab, law)] = {**_summary(sim), **(_history(sim) if histories else {})}
    return out


def compute_fig10_11() -> dict:
    """000 Fig. 10 (constant torque) and Fig. 11 (linear torque) for Table 1's Me = 0.025 kg m
    (the figures do not state Me), with and without the balls: {(law, balls): summary + history}."""
    return {(law, balls): {**_summary(sim), **_history(sim)}
            for law in ("constant", "linear") for balls in (True, False)
            for sim in [runup(TABLE_ME[1], law, balls=balls)]}


# -- comparisons -------------------------------------------------------------------------------
def compare_fig5(data: dict | None = None, prefix: str = "000-fig5") -> list:
    """Rows of 000 Fig. 5: final ball angles [deg], balancing times [s], settling [w t].

    Parameters
    ----------
    data : dict or None
        :func:`compute_fig5` output (computed when None).
    prefix : str
        Key prefix of the rows (the target id).
    """
    d = data or compute_fig5()
    rows = Rows(prefix, PUBLISHED["fig5"])
    bound = 250 / W1000
    a = d["c_i_2"]["final_alpha_deg"]
    for i, (key, ours) in enumerate((("alpha1_deg", a[1]), ("alpha2_deg", a[0]))):
        rows.add(key, f"000 Fig. 5 final angle of ball {i + 1} [deg]", round(float(ours), 2),
                 "+-0.5", abs(ours - rows.published(key)) <= 0.5,
                 "c_i = 2 1/s, gravity on (wobble ~0.13 deg)")
    notes = {"c_i_2": "amplitude < 5 % of unbalanced; c_i = 2 1/s chosen for Tables 1-2; the "
                      "paper's c_i is unknown",
             "c_i_7.1": "same start, stiffer ball damping (settles in the published time but makes "
                        "only ~2.5 run-up revolutions)"}
    for case, note in notes.items():
        t = d[case]["balancing_time_s"]
        rows.add(f"balancing_time_s/{case}",
                 f"000 Fig. 5 balancing time [s] (c_i = {d[case]['c_i']:g} 1/s)", round(t, 2),
                 f"< {bound:.2f} (250/w)", t < bound, note)
    t = d["c_i_7.1"]["balancing_time_s"] * W1000
    rows.add("settle_time_conclusions_wt", "000 Conclusions: balls settled [w t]", round(t, 1),
             "< 150", t < 150.0, f"c_i = 7.1 1/s (the Fig. 5 settling); with the preset c_i = 2 "
             f"1/s w t = {d['c_i_2']['balancing_time_s'] * W1000:.0f}")
    return rows


def compare_tables(data: dict | None = None, prefix: str = "000-table1-2") -> list:
    """Rows of 000 Tables 1-2: t_f [s], x_max and y_max [mm], ball revolutions [-] per table and law.

    Parameters
    ----------
    data : dict or None
        :func:`compute_tables` output (computed when None).
    prefix : str
        Key prefix of the rows (the target id).
    """
    d = data or compute_tables()
    tau = B_Z * W1000 / T0
    rows = Rows(prefix, {f"table{tab}": PUBLISHED[f"table{tab}"] for tab in TABLE_ME})
    for tab in TABLE_ME:
        for law in LAWS:
            key = f"table{tab}/{law}"
            p, S = rows.published(key), d[(tab, law)]
            lab = f"000 Table {tab} {law}"
            if law == "constant":
                note = ("B_z calibrated on this row" if tab == 1 else
                        "a larger unbalance can only slow the run-up with the same B_z; 1.7 s implies "
                        "another B_z or T0, which the paper does not give")
            elif law == "linear":
                note = (f"t to 0.99 n_f; the printed law reaches "
                        f"{runup_fraction_closed_form(law, p['t_f_s'], tau):.3f} n_f at {p['t_f_s']:g} s "
                        "(closed form, B_z of the constant row)")
            else:
                note = (f"the printed law needs {runup_time_closed_form(law, 0.95, tau):.1f} s to reach "
                        f"0.95 n_f and reaches {runup_fraction_closed_form(law, p['t_f_s'], tau):.2f} n_f "
                        f"at {p['t_f_s']:g} s (closed form): not reachable")
            t = S["t_f_s"]
            rows.add(f"{key}/t_f_s", f"{lab} t_f [s]",
                     "not reached in 25 s" if t is None else round(t, 2), "+-5 %",
                     t is not None and abs(t - p["t_f_s"]) <= 0.05 * p["t_f_s"], note)
            for ax in ("x", "y"):
                v = S[f"{ax}_max_m"] * 1e3
                q = p[f"{ax}_max_mm"]
                rows.add(f"{key}/{ax}_max_mm", f"{lab} {ax}_max [mm]", round(v, 2), "+-30 %",
                         abs(v - q) <= 0.3 * q, "tolerance = sensitivity to the unknown c_i")
            r = S["revolutions"]
            rows.add(f"{key}/revolutions", f"{lab} ball revolutions", round(r, 1), "+-2.5",
                     abs(r - p["revolutions"]) <= 2.5, "mean of the two balls, relative to the drum")
    return rows


def compare_fig10_11(data: dict | None = None, prefix: str = "000-fig10-11") -> list:
    """Rows of 000 Fig. 10-11: ball direction, revolutions [-], amplitude with vs without balls [%].

    Parameters
    ----------
    data : dict or None
        :func:`compute_fig10_11` output (computed when None).
    prefix : str
        Key prefix of the rows (the target id).
    """
    d = data or compute_fig10_11()
    rows = Rows(prefix, {"fig10": PUBLISHED["fig10"], "fig11": PUBLISHED["fig11"]})
    rev = d[("constant", True)]["signed_revolutions"]
    opposite = all(v < 0 for v in rev)
    rows.add("fig10/ball_direction", "000 Fig. 10 ball motion during the run-up",
             "opposite to the drum rotation" if opposite else "with the drum", "sign",
             opposite, "net revolutions relative to the drum: " + ", ".join(f"{v:.1f}" for v in rev))
    r = d[("linear", True)]["revolutions"]
    p = rows.published("fig11/revolutions")
    rows.add("fig11/revolutions", "000 Fig. 11 ball revolutions (linear torque)", round(r, 1),
             "+-2.5", abs(r - p) <= 2.5,
             "mean of the two balls relative to the drum, Me = 0.025 kg m (Table 1)")
    for fig, law in (("fig10", "constant"), ("fig11", "linear")):
        w, wo = d[(law, True)], d[(law, False)]
        aw = max(w["x_max_m"], w["y_max_m"])
        awo = max(wo["x_max_m"], wo["y_max_m"])
        diff = 100 * (aw / awo - 1)
        rows.add(f"{fig}/amplitude_with_vs_without_balls",
                 f"000 {fig.replace('fig', 'Fig. ')} max amplitude with vs without balls [%]",
                 round(diff, 1), "+-30 % (the x_max sensitivity to c_i)", abs(diff) <= 30.0,
                 f"max(x_max, y_max) {aw * 1e3:.2f} mm with, {awo * 1e3:.2f} mm without the "
                 "balls; the balls start together opposite the unbalance and are dragged "
                 "round with the drum through the resonances")
    return rows
