"""Liquid-balancer benchmark (make bench): its figures on 003's
bench (preset leblanc_003: R = 0.2 m, h = 0.05 m, water, D = 3000 g*cm, omega_r = 54 1/s).

E. A run-up from rest through resonance, 0 -> 80 1/s in 16 s (the preset's rate): the liquid's
   spin-up from rest to the lid (liquid/spinup.py, 100 cells), then the wall film coupled to the
   rotor (simulate_liquid, 256 cells), timed whole and the spin-up alone; beside it the lumped
   model's run-up over the same ramp (liquid.dynamics.run_up, scipy LSODA), the model the
   physical one replaces. Target: <= 1 s of wall time.
F. The fill x speed map of the steady whirl with the quasi-static liquid (0-350 ml in 50 ml x
   25-90 1/s in 1 1/s steps), the map behind 003 Fig. 5.
G. The same fills x 12 constant speeds 40-84 1/s (above every fill's omega_0) with the dynamic film, each run 4 s, as one sweep on
   all cores (autobalance.sweep, local processes): the map that also shows where the steady
   whirl is not reached (asynchronous whirl). Target: minutes.
H. Four runs of two 80 g balls beside the liquid (0 -> 150 1/s in 20 s, held to 30 s), one
   after another and on two threads (the hybrid kernel releases the GIL; the tolerances'
   simulation check runs them so), side by side, with the results compared bit for bit.
I. The liquid on a horizontal axis (preset leblanc_washer: R = 0.26 m, 1 l of water, 256 cells;
   liquid/rimming.py): the preset's run-up from a puddle at rest until it leaves the model, and
   a run-down 300 -> 1 rpm in 20 s from a ring until it breaks; beside them the wall film's run
   of the same machine (simulate_liquid, from its start at 185 rpm to 1000 rpm).
Results are written to out/liquid_bench.json.
"""
from __future__ import annotations

import os
import tempfile
import time

import numpy as np

from autobalance.config import load_config
from autobalance.liquid import LiquidModel, run_up
from autobalance.liquid.simulate import liquid_parts, simulate_liquid
from autobalance.liquid.spinup import spinup_of
from autobalance.liquid.steady import physical_fill_sweep
from autobalance.sweep import spec_from_dict, sweep

from run import report, timed       # benchmarks/run.py: the shared timing and output

FILLS_ML = [50, 100, 150, 200, 250, 300, 350]


def main() -> dict:
    res, lines = {}, []
    cfg = load_config("leblanc_003", ["profile.end_speed=80 1/s", "profile.ramp_time=16 s",
                                      "profile.duration=16 s"])
    simulate_liquid(cfg.system, cfg.spin)                                  # compile
    t_e, sim = timed(lambda: simulate_liquid(cfg.system, cfg.spin), repeat=3)
    rotor, bal = liquid_parts(cfg.system)
    t_l, ru = timed(lambda: run_up(rotor, bal, LiquidModel(), 80.0, 16.0), repeat=3)
    t_s, _ = timed(lambda: spinup_of(cfg.system, cfg.spin), repeat=3)
    s = sim.summary()
    res["E_runup_0_80"] = {"total_s": t_e, "spinup_s": t_s, "lumped_s": t_l,
                           "film_steps": s["film_steps"], "film_start_rad_s": sim.film_start_speed,
                           "peak_mm": 1e3 * s["max_amplitude_m"],
                           "peak_without_liquid_mm": 1e3 * s["max_amplitude_without_liquid_m"]}
    lines.append(f"E. 003 run-up 0 -> 80 1/s in 16 s from rest: {t_e:.2f} s (target <= 1 s): "
                 f"the spin-up to the lid at {sim.film_start_speed:.1f} 1/s {t_s:.2f} s, then the "
                 f"film coupled with the rotor ({s['film_steps']} steps, 256 cells); the lumped "
                 f"model's run-up {t_l:.2f} s (ratio {t_e / t_l:.2f}); peak "
                 f"{1e3 * s['max_amplitude_m']:.2f} mm (without liquid "
                 f"{1e3 * s['max_amplitude_without_liquid_m']:.2f} mm)")

    speeds = np.arange(25.0, 90.5, 1.0)
    vols = np.array(FILLS_ML) * 1e-6

    def qs_map():
        return np.array([physical_fill_sweep(rotor, bal, vols, w)["amplitude_m"]
                         for w in speeds])

    t_f, amap = timed(qs_map, repeat=1)
    res["F_quasi_static_map"] = {"s": t_f, "points": int(amap.size)}
    lines.append(f"F. fill x speed map, quasi-static liquid: {len(FILLS_ML)} fills x "
                 f"{speeds.size} speeds = {amap.size} steady whirls in {t_f:.1f} s")

    spec = {"sweep": {"name": "leblanc-map", "base": "leblanc_003", "batch_size": 4,
                      "set": ["profile.kind=constant", "profile.duration=4 s",
                              "profile.speed=40 1/s"]},
            "grid": {"liquid.volume": [f"{v} ml" for v in FILLS_ML],
                     "profile.speed": [f"{w:g} 1/s" for w in np.linspace(40.0, 84.0, 12)]}}
    with tempfile.TemporaryDirectory() as d:
        t0 = time.perf_counter()
        ds = sweep(spec_from_dict(spec), os.path.join(d, "map"), executor="local",
                   progress=False)
        t_g = time.perf_counter() - t0
        n = int(ds["status"].size)
    res["G_dynamic_map"] = {"s": t_g, "runs": n}
    lines.append(f"G. fill x speed map, dynamic film (4 s per run, one sweep, local processes): "
                 f"{n} runs in {t_g:.1f} s ({n / t_g:.2f} runs/s; target: minutes)")

    from concurrent.futures import ThreadPoolExecutor

    from autobalance.models import InitialState
    from autobalance.simulate import simulate

    hb = load_config("leblanc_003", [
        "balancer.n_balls=2", "balancer.ball_mass=0.08 kg", "balancer.race_radius=0.25 m",
        "balancer.ball_radius=10 mm", "balancer.damping=20 N*mm*s/rad",
        "profile.end_speed=150 1/s", "profile.duration=30 s"])
    inits = [InitialState(ball_angles=(a, a + 2.0)) for a in (0.3, 1.1, 2.2, 3.3)]

    def one(i):
        return simulate(hb.system, hb.spin, initial=i, options=hb.options, throw=False)

    def threads():
        with ThreadPoolExecutor(2) as ex:
            return list(ex.map(one, inits))

    one(inits[0])                                                           # compile
    t_ser, a = timed(lambda: [one(i) for i in inits], repeat=2)
    t_thr, b = timed(threads, repeat=2)
    same = all(np.array_equal(x.states, y.states)
               and np.array_equal(x.liquid.unbalance, y.liquid.unbalance) for x, y in zip(a, b))
    res["H_hybrid_threads"] = {"serial_s": t_ser, "threads_s": t_thr, "identical": same}
    lines.append(f"H. 4 runs of balls beside the liquid (30 s each): one after another "
                 f"{t_ser:.2f} s, on 2 threads {t_thr:.2f} s ({t_ser / t_thr:.2f}x); "
                 f"identical: {same}")

    from autobalance.liquid.rimming import horizontal_spinup

    wash = load_config("leblanc_washer")
    down = load_config("leblanc_washer", ["profile.start_speed=300 rpm",
                                          "profile.end_speed=1 rpm", "profile.ramp_time=20 s",
                                          "profile.duration=20 s"])
    horizontal_spinup(wash.system, wash.spin, n_cells=64)                    # compile
    simulate_liquid(wash.system, wash.spin, n_cells=64)
    t_up, (up,) = timed(lambda: horizontal_spinup(wash.system, wash.spin), repeat=2)
    t_dn, (dn,) = timed(lambda: horizontal_spinup(down.system, down.spin), repeat=2)
    t_fw, _ = timed(lambda: simulate_liquid(wash.system, wash.spin), repeat=2)
    rpm = 30 / np.pi
    res["I_horizontal"] = {"run_up_s": t_up, "run_up_status": up.status,
                           "run_up_stop_rpm": up.stop_speed * rpm, "run_down_s": t_dn,
                           "run_down_status": dn.status, "run_down_stop_rpm": dn.stop_speed * rpm,
                           "film_run_s": t_fw}
    lines.append(f"I. washer ring on a horizontal axis, 256 cells: run-up from the puddle "
                 f"{t_up:.2f} s ({up.status} at {up.stop_speed * rpm:.1f} rpm), run-down from "
                 f"the ring {t_dn:.2f} s ({dn.status} at {dn.stop_speed * rpm:.1f} rpm); the "
                 f"film's run 185 -> 1000 rpm {t_fw:.2f} s (ratios {t_up / t_fw:.2f}, "
                 f"{t_dn / t_fw:.2f})")
    return report(lines, res, "liquid_bench.json")


if __name__ == "__main__":
    main()
