"""Speed benchmark (make bench): ours vs scipy.integrate.solve_ivp(Radau), measured side by side.

Cases, all on the 004 preset (Table 1 rig, mu = 0.002, 2 balls):
  A. 167 Hz hold with the balls stuck (time per simulated second);
  B. the standard run-up 0 -> 111 Hz in 12 s, through the 94.2 Hz resonance, where the balls move;
  C. one full 90 s TSR run (004 profile), ours only: the kernel (the slip jumps of
     core/expo.py on); the same run with DOPRI5 stepping every slipping phase (no slip jumps);
     also stepping the stuck ramps (no ramp jumps); and 004's tanh law emulated on its slow
     manifold (friction_law "creep"). The stepped runs are the tests' oracles
     (tests/oracles.py: the fast paths' flags cleared in the packed parameters).
Ours: exact stick-slip, compiled, default tolerances, with and without the closed-form hold.
Baselines: scipy Radau (rtol 1e-6, atol 1e-9) on 004's tanh law (v_sat = 1e-6 rad/s), with
  (1) our compiled right-hand side called from Python, and
  (2) a NumPy transcription of 004 eq (8)-(10) (core/reference.paper_004_rhs).
The ratios printed are Radau time / our time for the same simulated interval.
Results are written to out/bench.json.
"""
from __future__ import annotations

import json
import os
import sys
import warnings
import statistics
from pathlib import Path
import time

import numpy as np

import autobalance as ab
from autobalance.config import load_config
from autobalance.simulate.reference import solve_reference
from autobalance.simulate import simulate

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from oracles import stepped  # noqa: E402  (the kernel with fast paths stepped: tests' oracle)


def timed(fn, repeat=5):
    times, out = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def report(lines: list, res: dict, name: str) -> dict:
    """Print a benchmark's lines and write its results to out/<name> (JSON)."""
    print("\n".join(lines))
    os.makedirs("out", exist_ok=True)
    with open(os.path.join("out", name), "w") as f:
        json.dump(res, f, indent=2)
    return res


def radau(s, prof, T, ini, equations):
    t0 = time.perf_counter()
    sol = solve_reference(s, prof, T, initial=ini, v_sat=1e-6, method="Radau", rtol=1e-6,
                          atol=1e-9, equations=equations)
    return time.perf_counter() - t0, sol


def main() -> dict:
    warnings.filterwarnings("ignore", category=RuntimeWarning, module="scipy")
    cfg = load_config("vub_jeffcott_004")
    s = cfg.system
    res: dict = {"cpu_count": os.cpu_count()}
    lines = ["autobalance benchmark - 004 preset (Table 1 rig), wall times on this machine"]

    # --- A: 167 Hz hold, balls stuck -------------------------------------------------------
    W = 2 * np.pi * 167.0
    ini = ab.InitialState(ball_angles=(np.radians(100), np.radians(200)), steady_state=True)
    T = 5.0
    prof = ab.SpeedProfile.constant(W, T)
    o_exact = ab.SimOptions(save_dt=-1)
    simulate(s, prof, initial=ini, options=o_exact)
    stepped(s, prof, initial=ini, options=o_exact, holds=False)
    t_ex, _ = timed(lambda: simulate(s, prof, initial=ini, options=o_exact))
    t_in, sim_in = timed(lambda: stepped(s, prof, initial=ini, options=o_exact, holds=False))
    Tr = 0.2
    prof_r = ab.SpeedProfile.constant(W, Tr)
    radau(s, ab.SpeedProfile.constant(W, 1e-3), 1e-3, ini, "kernel")   # compile the RHS first
    t_rk, sol_k = radau(s, prof_r, Tr, ini, "kernel")
    t_rp, sol_p = radau(s, prof_r, Tr, ini, "paper")
    a = {
        "ours_exact_hold_s_per_s": t_ex / T, "ours_integrated_s_per_s": t_in / T,
        "radau_compiled_rhs_s_per_s": t_rk / Tr, "radau_numpy_004_rhs_s_per_s": t_rp / Tr,
        "radau_window_s": Tr, "radau_rhs_calls": [int(sol_k.nfev), int(sol_p.nfev)],
    }
    res["A_167Hz_hold"] = a
    lines.append("A. 167 Hz hold, balls stuck: wall time per simulated second")
    lines.append(f"   ours, closed-form hold      {a['ours_exact_hold_s_per_s']*1e3:10.4f} ms")
    lines.append(f"   ours, integrated (DOPRI5)   {a['ours_integrated_s_per_s']*1e3:10.4f} ms")
    lines.append(f"   Radau, our compiled RHS     {a['radau_compiled_rhs_s_per_s']*1e3:10.1f} ms"
                 f"   ratio {a['radau_compiled_rhs_s_per_s']/a['ours_exact_hold_s_per_s']:9.0f}x"
                 f" / {a['radau_compiled_rhs_s_per_s']/a['ours_integrated_s_per_s']:6.0f}x")
    lines.append(f"   Radau, NumPy 004 eq 8-10    {a['radau_numpy_004_rhs_s_per_s']*1e3:10.1f} ms"
                 f"   ratio {a['radau_numpy_004_rhs_s_per_s']/a['ours_exact_hold_s_per_s']:9.0f}x"
                 f" / {a['radau_numpy_004_rhs_s_per_s']/a['ours_integrated_s_per_s']:6.0f}x"
                 "   (ratios: vs closed-form / vs integrated)")

    # --- B: run-up through resonance, balls move ---------------------------------------------
    Tb = 12.0
    prof_b = ab.SpeedProfile((0.0, Tb), (0.0, W * Tb / 18.0), nominal_speed=W)
    o = ab.SimOptions(save_dt=-1)
    simulate(s, prof_b, initial=cfg.initial, options=o)
    t_ob, sim_b = timed(lambda: simulate(s, prof_b, initial=cfg.initial, options=o))
    t_bk, sol_bk = radau(s, prof_b, Tb, cfg.initial, "kernel")
    t_bp, sol_bp = radau(s, prof_b, Tb, cfg.initial, "paper")
    d_k = float(np.degrees(np.abs(sim_b.states[-1, 2:4] - sol_bk.y[2:4, -1])).max())
    d_p = float(np.degrees(np.abs(sim_b.states[-1, 2:4] - sol_bp.y[2:4, -1])).max())
    b = {"ours_s": t_ob, "radau_compiled_rhs_s": t_bk, "radau_numpy_004_rhs_s": t_bp,
         "end_angle_difference_deg": [d_k, d_p], "ball_travel_deg":
         float(np.degrees(np.abs(sim_b.states[-1, 2:4] - sim_b.states[0, 2:4])).max())}
    res["B_runup_12s"] = b
    lines.append(f"B. run-up 0 -> 111 Hz in 12 s through resonance (balls travel {b['ball_travel_deg']:.0f} deg)")
    lines.append(f"   ours {t_ob*1e3:8.1f} ms | Radau compiled RHS {t_bk:7.2f} s ({t_bk/t_ob:5.0f}x) | "
                 f"Radau NumPy 004 {t_bp:7.2f} s ({t_bp/t_ob:6.0f}x) | end angles differ {d_k:.1e} / {d_p:.1e} deg")
    lines.append("   (004 eq 8-10 have no ball-ball contact: its balls pass through each other, ours collide)")

    # --- C: full 90 s TSR run ------------------------------------------------------------------
    def tsr(**off):
        return stepped(cfg.system, cfg.spin, initial=cfg.initial, options=o, **off)

    for off in ({}, {"slip_jumps": False}, {"ramps": False}):
        tsr(**off)
    t_tsr, sim_tsr = timed(lambda: simulate(cfg.system, cfg.spin, initial=cfg.initial, options=o))
    t_pv, sim_pv = timed(lambda: tsr(slip_jumps=False))
    t_st, sim_st = timed(lambda: tsr(ramps=False))
    st = sim_tsr.summary()["solver"]
    st_p = sim_pv.summary()["solver"]
    st_s = sim_st.summary()["solver"]
    dG_p = float(np.abs(sim_pv.grade_G - sim_tsr.grade_G).max())
    dG_r = float(np.abs(sim_st.grade_G - sim_tsr.grade_G).max())
    res["C_tsr_90s"] = {"ours_s": t_tsr, **st, "no_slip_jumps_s": t_pv,
                        "no_slip_jumps_steps": st_p["steps"], "no_slip_jumps_events": st_p["events"],
                        "jumps_vs_none_max_dG_mm_s": dG_p, "stepped_ramps_s": t_st,
                        "stepped_ramps_steps": st_s["steps"], "ramps_vs_stepped_max_dG_mm_s": dG_r}
    lines.append(f"C. one full 90 s TSR run: {t_tsr*1e3:.1f} ms (median of 5; {st['steps']} steps, "
                 f"{st['events']} stick-slip events, {st['exact_holds']} closed-form holds, "
                 f"{st['exact_ramps']} ramps without stepping)")
    lines.append(f"   no slip jumps (DOPRI5 steps every slipping phase): "
                 f"{t_pv*1e3:.1f} ms, {st_p['steps']} steps, {st_p['events']} events; ratio "
                 f"{t_pv / t_tsr:.2f}x; checkpoint grades differ by {dG_p:.1e} mm/s")
    lines.append(f"   also the stuck ramps stepped: "
                 f"{t_st*1e3:.1f} ms, "
                 f"{st_s['steps']} steps; ratio {t_st / t_tsr:.2f}x; checkpoint grades differ by "
                 f"{dG_r:.1e} mm/s")
    lines.append("   targets: 90 s TSR <= 100 ms; ratio >= 1000x")
    # the same run under 004's own tanh law, emulated by the creep law (physics/friction.py)
    o_cr = ab.SimOptions(save_dt=-1, friction_law="creep", v_sat=1e-6)
    simulate(cfg.system, cfg.spin, initial=cfg.initial, options=o_cr)
    t_cr, sim_cr = timed(lambda: simulate(cfg.system, cfg.spin, initial=cfg.initial, options=o_cr))
    dG = float(np.abs(sim_cr.grade_G - sim_tsr.grade_G).max())
    res["C_tsr_90s"].update({"creep_s": t_cr, "creep_vs_stick_max_dG_mm_s": dG,
                             "creep_steps": sim_cr.summary()["solver"]["steps"]})
    lines.append(f"   004's tanh law (creep emulation, v_sat 1e-6 rad/s): {t_cr*1e3:.1f} ms "
                 f"({t_cr/t_tsr:.2f}x stick); checkpoint grades differ by {dG:.1e} mm/s")
    # --- D: the worst-case residual bound behind `study tolerances` (physics/worst_case.py) -----
    import autobalance.physics.reachable_set as wc
    from autobalance.studies._tolerances import compute_tolerances

    compute_tolerances("examples/centrifuge.toml", grade=16.0)          # compile
    tol = {}
    for flag in (False, True):
        wc.COMPILED_GAP = flag
        t0 = time.perf_counter()
        d = compute_tolerances("examples/centrifuge.toml", grade=16.0)
        tol[flag] = (time.perf_counter() - t0, d)
    wc.COMPILED_GAP = True
    same = all(tol[True][1][k] == tol[False][1][k] for k in
               ("max_eccentricity_m", "max_rolling_resistance", "max_suspension_friction_N",
                "worst_residual_kg_m"))
    res["D_tolerances_centrifuge"] = {"numpy_s": tol[False][0], "compiled_s": tol[True][0],
                                      "same_figures": same}
    lines.append(f"D. study tolerances of examples/centrifuge.toml (the circle test of the worst-case bound): "
                 f"NumPy home {tol[False][0]:.2f} s, compiled twin {tol[True][0]:.2f} s "
                 f"({tol[False][0] / tol[True][0]:.1f}x), same tolerances: {same}")
    return report(lines, res, "bench.json")


if __name__ == "__main__":
    main()
