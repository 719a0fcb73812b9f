"""Speed benchmark (make bench): ours vs scipy.integrate.solve_ivp(Radau) on the same equations.

Prints, from one run on this machine:
  1. wall time per simulated second at 167 Hz for the 004 preset (Table 1 rig), ours (exact
     stick-slip, compiled) vs scipy Radau on 004's tanh law (v_sat = 1e-6 rad/s) using the same
     compiled right-hand side, and their ratio;
  2. the wall time of one full 90 s TSR run (004 profile) after compilation.
Results are also written to out/bench.json.
"""
from __future__ import annotations

import json
import os
import statistics
import sys
import time

import numpy as np

import autobalance as ab
from autobalance.config import load_config
from autobalance.core.reference import solve_reference
from autobalance.simulate import simulate


def timed(fn, repeat=5):
    times = []
    out = None
    for _ in range(repeat):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return statistics.median(times), out


def main(radau_window: float = 0.1) -> dict:
    cfg = load_config("vub_jeffcott_004")
    s = cfg.system
    w = 2 * np.pi * 167.0
    ini = ab.InitialState(ball_angles=(np.radians(100), np.radians(200)), steady_state=True)
    T = 5.0
    prof = ab.SpeedProfile.constant(w, T)
    opts = ab.SimOptions(save_dt=-1)
    simulate(s, prof, initial=ini, options=opts)                      # compile
    t_ours, sim = timed(lambda: simulate(s, prof, initial=ini, options=opts))
    ours_per_s = t_ours / T
    prof_r = ab.SpeedProfile.constant(w, radau_window)
    t0 = time.perf_counter()
    ref = solve_reference(s, prof_r, radau_window, initial=ini, v_sat=1e-6, method="Radau",
                          rtol=1e-6, atol=1e-9)
    t_radau = time.perf_counter() - t0
    radau_per_s = t_radau / radau_window
    # same window with ours, to compare the end states
    sim_w = simulate(s, prof_r, initial=ini, options=opts)
    d_alpha = float(np.degrees(np.abs(sim_w.alpha[-1] - ref.y[2:4, -1])).max())

    simulate(cfg.system, cfg.spin, initial=cfg.initial, options=opts)
    t_tsr, sim_tsr = timed(lambda: simulate(cfg.system, cfg.spin, initial=cfg.initial, options=opts))
    st = sim_tsr.summary()["solver"]
    res = {
        "ours_wall_per_simulated_s_at_167Hz_s": ours_per_s,
        "radau_tanh_wall_per_simulated_s_at_167Hz_s": radau_per_s,
        "radau_window_s": radau_window,
        "radau_rhs_evaluations": int(ref.nfev),
        "ratio_radau_over_ours": radau_per_s / ours_per_s,
        "end_state_difference_deg": d_alpha,
        "tsr_90s_wall_s": t_tsr,
        "tsr_90s_steps": st["steps"],
        "tsr_90s_rhs_evaluations": st["rhs_evaluations"],
        "tsr_90s_events": st["events"],
        "cpu": os.cpu_count(),
    }
    print("autobalance benchmark (004 preset, Table 1 rig)")
    print(f"  per simulated second at 167 Hz: ours {ours_per_s*1e3:9.3f} ms | scipy Radau+tanh "
          f"{radau_per_s*1e3:9.1f} ms | ratio {res['ratio_radau_over_ours']:8.0f}x  "
          f"(Radau window {radau_window} s, {ref.nfev} RHS calls; end states differ by {d_alpha:.2e} deg)")
    print(f"  one full 90 s TSR run: {t_tsr*1e3:.1f} ms wall (median of 5; {st['steps']} steps, "
          f"{st['events']} stick-slip events, {st['rhs_evaluations']} RHS evaluations)")
    print(f"  targets: 90 s TSR <= 100 ms, ratio >= 1000x")
    os.makedirs("out", exist_ok=True)
    with open("out/bench.json", "w") as f:
        json.dump(res, f, indent=2)
    return res


if __name__ == "__main__":
    main(float(sys.argv[1]) if len(sys.argv) > 1 else 0.1)
