"""What an exponential integrator would save on the slipping phases of 004's runs.

For event-free windows of a few runs of 004's rig (no stick-slip event, no profile knot, the balls
slipping or one of them stuck), side by side in one process:
* the kernel (DOPRI5, rtol 1e-6): its steps in the window, and its error at the window's end
  against the same run at rtol 1e-11 (in units of the error tolerance: 1 = the tolerance);
* ETDRK4-B (core/expo.py) with L, the Jacobian at the window's start, refreshed every 10 steps,
  and constant steps: the fewest steps (of 5, 10, 20, 40, 80, 160, 320) whose error, from the
  kernel's state at the window's start, is within the tolerance and within the kernel's own;
* their times: the kernel's window as the difference of the runs to its end and to its start,
  best of 7; ETDRK4-B's window, best of 7.

Then whole runs of 004's profile with and without the slip jumps in the kernel (without: the
tests' oracle, tests/oracles.py, DOPRI5 stepping every slipping phase), side by side:
``whole_runs``.

Part of ``make bench`` (about 4 minutes; docs/numerics/index.md).
"""
from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from oracles import stepped  # noqa: E402  (the kernel with fast paths stepped: tests' oracle)


def _setup(mu_r: float, grade: float, k: int):
    from autobalance.models import InitialState
    from autobalance.physics.iso1940 import unbalance_value
    from autobalance.simulate.pack import run_inputs
    from autobalance.studies.common import case_sets, load
    base = load("vub_jeffcott_004")
    sets = case_sets(base, mu_r, 1.0)
    if grade >= 0:
        U = unbalance_value(grade, base.system.total_mass, base.spin.nominal_speed)
        sets = sets + [f"rotor.unbalance={float(U)!r}"]
    cfg = load("vub_jeffcott_004", sets)
    rng = np.random.default_rng(100 + k)
    x = rng.uniform(0, 2 * np.pi)
    a0 = (x, x + rng.uniform(0.6, 2 * np.pi - 0.6))
    return cfg, run_inputs(cfg.system, cfg.spin, InitialState(ball_angles=a0), cfg.options)


def _run_to(cfg, r, te, rtol=None, atol_factor=1.0):
    from autobalance.core.integrate import integrate
    from autobalance.core.layout import P_ETD
    n = r.y0.shape[0]
    out_t = np.array([te])
    out_y = np.zeros((1, n))
    st = r.stats.copy()
    P = r.P.copy()
    P[P_ETD] = 0.0               # the kernel's own stepping: DOPRI5 throughout (no slip jumps)
    y = integrate(P, r.B, r.B.shape[0], r.prof_t, r.prof_w, r.unb_t, r.unb_u, r.y0, te,
                  rtol or cfg.options.rtol, r.atol * atol_factor, r.h_max, 10 ** 9, out_t,
                  out_y, st)
    return y, st


def _best(fn, k=7):
    best = np.inf
    for _ in range(k):
        t0 = time.perf_counter()
        fn()
        best = min(best, time.perf_counter() - t0)
    return best


def window(cfg, r, t0, t1):
    """One window's row, or None when the kernel has an event or a knot in it."""
    from autobalance.core.expo import etd_window
    from autobalance.core.layout import S_EVENTS, S_STEPS
    N = r.B.shape[0]
    n = r.y0.shape[0]
    nq = n // 2
    if np.any((r.prof_t > t0) & (r.prof_t < t1)):
        return None
    y0, s0 = _run_to(cfg, r, t0)
    y1, s1 = _run_to(cfg, r, t1)
    if s1[S_EVENTS] != s0[S_EVENTS] or s1[S_STEPS] - s0[S_STEPS] < 20:
        return None
    mask = np.ones(n, bool)
    mask[nq - 1] = False          # the spin angle, outside the kernel's error norm too

    def err(y, ref):
        sc = r.atol + cfg.options.rtol * np.maximum(abs(y), abs(ref))
        return float(np.sqrt(np.mean(((y - ref) / sc)[mask] ** 2)))

    ref, _ = _run_to(cfg, r, t1, rtol=1e-11, atol_factor=1e-5)
    e_kernel = err(y1, ref)
    v = y0[nq + 2:2 * nq - 1]                     # the balls' speeds
    stuck = (v == 0.0).astype(np.int64)
    sgn = np.where(v >= 0.0, 1.0, -1.0)
    scale = np.r_[r.atol / cfg.options.atol_scale, 1.0]   # typical magnitudes
    for ns in (5, 10, 20, 40, 80, 160, 320):
        y = etd_window(r.P, r.B, N, r.prof_t, r.prof_w, r.unb_t, r.unb_u, stuck, sgn, y0,
                       t0, t1, ns, 10, scale)
        e = err(y, ref)
        if e <= min(1.0, max(e_kernel, 0.05)):
            break
    t_kernel = _best(lambda: _run_to(cfg, r, t1)) - _best(lambda: _run_to(cfg, r, t0))
    t_etd = _best(lambda: etd_window(r.P, r.B, N, r.prof_t, r.prof_w, r.unb_t, r.unb_u, stuck,
                                     sgn, y0, t0, t1, ns, 10, scale))
    return (t0, t1, int(s1[S_STEPS] - s0[S_STEPS]), e_kernel, t_kernel, ns, e, t_etd,
            int(stuck.sum()))


WINDOWS = np.arange(0.5, 17.5, 1.0)

#: Whole runs: (mu_r, G_ini (-1: 004's nominal), starts)
RUN_CASES = [(1.0, -1.0, 30), (0.5, 20.0, 30), (0.25, 30.0, 30), (0.25, 50.0, 15)]


def whole_runs() -> None:
    """004's 90 s profile, one start at a time, with and without the slip jumps in the
    kernel, alternated start by start: wall time of simulate (checkpoints
    only, best of 3), DOPRI5 steps, right-hand-side evaluations, and the largest change of the
    STD and TSR grades (18 s, 90 s) against the bound of 0.02 mm/s."""
    import dataclasses

    from autobalance.core.layout import S_RHS, S_STEPS
    from autobalance.models import InitialState
    print("\nwhole runs, 004's 90 s profile, with the slip jumps against without")
    print("case                  starts | time: off      on    ratio | steps: off    on    | "
          "RHS ratio | max |dG| [mm/s]")
    for mu_r, grade, n in RUN_CASES:
        cfg, _ = _setup(mu_r, grade, 0)
        rng = np.random.default_rng(11)
        starts = [(x, x + rng.uniform(0.6, 2 * np.pi - 0.6)) for x in rng.uniform(0, 2 * np.pi, n)]
        tot = {False: [0.0, 0, 0], True: [0.0, 0, 0]}
        grades = {False: [], True: []}
        for a in starts:
            for slip in (False, True):
                o = dataclasses.replace(cfg.options, save_dt=-1.0)
                ini = InitialState(ball_angles=a)
                sim = stepped(cfg.system, cfg.spin, initial=ini, options=o, slip_jumps=slip)
                tot[slip][0] += _best(lambda: stepped(cfg.system, cfg.spin, initial=ini,
                                                      options=o, slip_jumps=slip), 3)
                tot[slip][1] += int(sim.stats[S_STEPS])
                tot[slip][2] += int(sim.stats[S_RHS])
                grades[slip].append(sim.grade_G[1:3])
        dG = np.abs(np.array(grades[True]) - np.array(grades[False])).max()
        g = "G_ini nominal" if grade < 0 else f"G_ini {grade:g}"
        print(f"mu_r {mu_r:<4g} {g:<13} {n:5d} | {tot[False][0]:6.2f} s {tot[True][0]:6.2f} s "
              f"{tot[False][0] / tot[True][0]:5.2f} | {tot[False][1]:7d} {tot[True][1]:7d} | "
              f"{tot[False][2] / tot[True][2]:8.2f}  | {dG:.4f}", flush=True)


def main() -> None:
    cases = [(0.25, 30.0, 0), (1.0, -1.0, 1)]
    print("case             window [s]     stuck | kernel: steps  error  time   | ETDRK4-B: "
          "steps  error  time   | steps ratio  time ratio")
    tot_k = tot_e = 0.0
    for mu_r, grade, k in cases:
        cfg, r = _setup(mu_r, grade, k)
        for t0 in WINDOWS:
            row = window(cfg, r, float(t0), float(t0) + 0.5)
            if row is None:
                continue
            a, b, ks, ek, tk, es, ee, te, nst = row
            tot_k += tk
            tot_e += te
            g = "G_ini nominal" if grade < 0 else f"G_ini {grade:g}"
            print(f"mu_r {mu_r:<4g} {g:<13} [{a:5.2f}, {b:5.2f}]  {nst}   | {ks:6d}  {ek:6.2f} "
                  f"{tk * 1e3:6.2f} ms | {es:6d}  {ee:6.2f} {te * 1e3:6.2f} ms | {ks / es:8.1f}"
                  f"  {tk / te:8.2f}", flush=True)
    print(f"all windows: kernel {tot_k * 1e3:.1f} ms, ETDRK4-B {tot_e * 1e3:.1f} ms "
          f"(ratio {tot_k / tot_e:.2f})")
    whole_runs()


if __name__ == "__main__":
    main()
