"""Sweep benchmark (make bench): the 004 start-position Monte Carlo, 1275 runs of 90 s TSR.

Prints wall time and runs/s on this machine with the default executor (local processes, all
cores), side by side in one run: the kernel and the kernel with its steps capped at 0.75 ms
(half DOPRI5's mean step; the exponential jumps' 10-50 ms steps are cut far more; the kernel
without its slip jumps is timed per run in benchmarks/run.py, case C, and
benchmarks/slip_etd_bench.py); the 5/50/95 % of G after STD
(20 %) and after TSR (100 %) for each; and a profile of where the time goes (planning, the
kernel, process start-up and writing, and the kernel's time by kind of run), from timed phases.
"""
from __future__ import annotations

import json
import os
import shutil
import sys
import tempfile
import time

import numpy as np

from autobalance.models import SimOptions
from autobalance.sweep import make_plan, spec_from_dict, summary_dict, sweep
from autobalance.sweep.task import run_task, task_payload

SPEC = {
    "sweep": {"name": "004-start-positions", "base": "vub_jeffcott_004", "batch_size": 32},
    "monte_carlo": {"kind": "start_grid", "n": 50},
}


def run(options: SimOptions | None, label: str, workdir: str):
    spec = spec_from_dict(SPEC, "bench")
    store = os.path.join(workdir, label)
    t0 = time.perf_counter()
    ds = sweep(spec, store, executor="local", options=options, progress=False)
    wall = time.perf_counter() - t0
    s = summary_dict(ds)
    extra = {"mean_steps": float(ds["steps"].mean()), "mean_events": float(ds["events"].mean())}
    return s, wall, extra, ds


def profile(n_tasks: int = 4) -> dict:
    """Time the phases of a few tasks in this process (one thread)."""
    import numba

    numba.set_num_threads(1)
    spec = spec_from_dict(SPEC, "bench")
    t0 = time.perf_counter()
    plan = make_plan(spec)
    t_plan = time.perf_counter() - t0
    run_task(task_payload(plan, plan.tasks[0]))   # compile / load the cache
    t_pay = t_run = 0.0
    runs = 0
    for k in range(1, n_tasks + 1):
        t0 = time.perf_counter()
        p = task_payload(plan, plan.tasks[k])
        t1 = time.perf_counter()
        r = run_task(p)
        t2 = time.perf_counter()
        t_pay += t1 - t0
        t_run += t2 - t1
        runs += len(r["status"])
    return {"plan_s": t_plan, "payload_s_per_run": t_pay / runs, "task_s_per_run": t_run / runs}


def run_kinds(stride: int = 16) -> dict:
    """Kernel time of every stride-th run of the grid, one at a time in this process, by kind:
    runs whose balls stay stuck at the plateau and runs where a ball slips there (a stick-slip
    ratchet at the rotor's backward whirl frequency, hundreds of events per second)."""
    import autobalance as ab
    from autobalance.config import load_config
    from autobalance.sweep.plan import separate, start_grid

    cfg = load_config("vub_jeffcott_004")
    angles = start_grid(50, 2, True)[::stride]
    o = SimOptions(save_dt=-1.0)
    ab.simulate(cfg.system, cfg.spin, initial=cfg.initial, options=o)      # load the cache
    rows = []
    for a in angles:
        ini = ab.InitialState(ball_angles=tuple(separate(a, cfg.system.balancer.contact_angle)))
        t0 = time.perf_counter()
        sim = ab.simulate(cfg.system, cfg.spin, initial=ini, options=o)
        dt = time.perf_counter() - t0
        sv = sim.summary()["solver"]
        rows.append((dt, sv["steps"], sv["events"]))
    r = np.array(rows)
    moving = r[:, 2] > 500
    total = r[:, 0].sum()
    kinds = []
    for mask, label in ((~moving, "balls stuck at the plateau"), (moving, "a ball slips at the plateau")):
        if mask.any():
            kinds.append({"label": label, "share_runs": float(mask.mean()),
                          "ms_per_run": float(1e3 * r[mask, 0].mean()),
                          "steps": float(r[mask, 1].mean()), "events": float(r[mask, 2].mean()),
                          "share_time": float(r[mask, 0].sum() / total)})
    return {"sampled": len(rows), "kinds": kinds}


def main() -> dict:
    work = tempfile.mkdtemp(prefix="ab-sweep-bench-")
    run_task(task_payload(make_plan(spec_from_dict(SPEC, "bench")), make_plan(
        spec_from_dict(SPEC, "bench")).tasks[0]))   # compile here: the workers load the cache
    try:
        s1, w1, e1, ds1 = run(None, "default", work)
        # DOPRI5's phases run at ~1.5 ms steps (stability-bound, docs/numerics/index.md): capping the
        # step at 0.75 ms halves them, and cuts the slip jumps' steps (10-50 ms) far more
        h = 0.75e-3
        s2, w2, e2, ds2 = run(SimOptions(max_step=h), "half", work)
        dG = np.abs(ds1["grade_G"].values - ds2["grade_G"].values)
        prof = profile()
        kinds = run_kinds()
    finally:
        shutil.rmtree(work, ignore_errors=True)
    n = s1["runs"]
    cores = os.cpu_count()
    kernel_share = prof["task_s_per_run"] * n / cores / w1
    lines = [
        f"004 start-position Monte Carlo: {n} runs x 90 s TSR, {cores} cores, local processes",
        f"  default      : {w1:6.1f} s wall, {n / w1:6.1f} runs/s, {e1['mean_steps']:.0f} DOPRI5 "
        f"steps and {e1['mean_events']:.0f} stick-slip events per run, {s1['failed_runs']} failed",
        f"  steps <= {h * 1e3:.2f} ms: {w2:6.1f} s wall, {n / w2:6.1f} runs/s (max_step = {h * 1e3:.3f} ms, "
        f"{e2['mean_steps']:.0f} steps per run), {s2['failed_runs']} failed",
        "  G [mm/s]         p5      p50      p95   share <= G16",
    ]
    for lab, s in (("default", s1), ("<= 0.75 ms", s2)):
        for c in s["checkpoints"]:
            tag = "STD (20 %)" if c["time_s"] < 89 else "TSR (100 %)"
            lines.append(f"  {lab:9s} {tag:11s} {c['grade_G_p5_mm_s']:6.2f} {c['grade_G_p50_mm_s']:8.2f} "
                         f"{c['grade_G_p95_mm_s']:8.2f}   {100 * c['share_below_limit']:5.1f} %")
    lines.append(f"  per run, default vs steps <= {h * 1e3:.2f} ms: max |dG| = {np.nanmax(dG):.3g} mm/s; runs with |dG| "
                 f"> 0.1 mm/s at 100 %: {int((dG[..., -1] > 0.1).sum())} of {n}")
    lines.append(f"  profile: plan {prof['plan_s']:.2f} s; per run {prof['task_s_per_run'] * 1e3:.1f} ms in the "
                 f"kernel task, {prof['payload_s_per_run'] * 1e3:.2f} ms building its input; the kernel "
                 f"accounts for ~{100 * min(kernel_share, 1):.0f} % of the wall time")
    for k in kinds["kinds"]:
        lines.append(f"  kernel time by run ({kinds['sampled']} runs sampled, one thread): {k['label']}: "
                     f"{100 * k['share_runs']:.0f} % of runs, {k['ms_per_run']:.1f} ms per run "
                     f"({k['steps']:.0f} steps, {k['events']:.0f} events), "
                     f"{100 * k['share_time']:.0f} % of the time")
    lines.append("  targets: <= 60 s for the 1275 runs; <= 10 s with the default kernel")
    print("\n".join(lines))
    res = {"runs": n, "max_abs_dG_mm_s": float(np.nanmax(dG)), "run_kinds": kinds,
           "runs_dG_gt_0.1": int((dG[..., -1] > 0.1).sum()), "wall_default_s": w1, "wall_half_step_s": w2, "summary_default": s1,
           "summary_half_step": s2, "per_run_default": e1, "per_run_half": e2, "profile": prof}
    os.makedirs("out", exist_ok=True)
    with open("out/bench_sweep.json", "w") as f:
        json.dump(res, f, indent=1)
    return res


if __name__ == "__main__":
    main()
    sys.exit(0)
