"""Sweep benchmark (make bench): the 004 start-position Monte Carlo, 1275 runs of 90 s TSR.

Prints wall time and runs/s on this machine with the default executor (local processes, all
cores), the 5/50/95 % of G after STD (20 %) and after TSR (100 %) at the default step and at half
the effective step (max_step = half the mean step of the default runs), and a profile of where
the time goes (planning, the kernel, process start-up and writing), from timed phases.
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
from autobalance.sweep.plan import run_task, task_payload

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


def main() -> dict:
    work = tempfile.mkdtemp(prefix="ab-sweep-bench-")
    try:
        s1, w1, e1, ds1 = run(None, "default", work)
        # the integrated phases run at ~1.5 ms steps (stability-bound, docs/numerics.md):
        # capping the step at 0.75 ms halves it everywhere the integrator steps
        h = 0.75e-3
        s2, w2, e2, ds2 = run(SimOptions(max_step=h), "half", work)
        dG = np.abs(ds1["grade_G"].values - ds2["grade_G"].values)
        prof = profile()
    finally:
        shutil.rmtree(work, ignore_errors=True)
    n = s1["runs"]
    cores = os.cpu_count()
    kernel_share = prof["task_s_per_run"] * n / cores / w1
    lines = [
        f"004 start-position Monte Carlo: {n} runs x 90 s TSR, {cores} cores, local processes",
        f"  default step : {w1:6.1f} s wall, {n / w1:6.1f} runs/s, {e1['mean_steps']:.0f} steps "
        f"and {e1['mean_events']:.0f} stick-slip events per run, {s1['failed_runs']} failed",
        f"  half step    : {w2:6.1f} s wall, {n / w2:6.1f} runs/s (max_step = {h * 1e3:.3f} ms, "
        f"{e2['mean_steps']:.0f} steps per run), {s2['failed_runs']} failed",
        "  G [mm/s]         p5      p50      p95   share <= G16",
    ]
    for lab, s in (("default", s1), ("half step", s2)):
        for c in s["checkpoints"]:
            tag = "STD (20 %)" if c["time_s"] < 89 else "TSR (100 %)"
            lines.append(f"  {lab:9s} {tag:11s} {c['grade_G_p5_mm_s']:6.2f} {c['grade_G_p50_mm_s']:8.2f} "
                         f"{c['grade_G_p95_mm_s']:8.2f}   {100 * c['share_below_limit']:5.1f} %")
    lines.append(f"  per run, default vs half step: max |dG| = {np.nanmax(dG):.3g} mm/s; runs with |dG| "
                 f"> 0.1 mm/s at 100 %: {int((dG[..., -1] > 0.1).sum())} of {n}")
    lines.append(f"  profile: plan {prof['plan_s']:.2f} s; per run {prof['task_s_per_run'] * 1e3:.1f} ms in the "
                 f"kernel task, {prof['payload_s_per_run'] * 1e3:.2f} ms building its input; the kernel "
                 f"accounts for ~{100 * min(kernel_share, 1):.0f} % of the wall time")
    lines.append("  targets (issue 3): <= 60 s for the 1275 runs; moonshot 10 s")
    print("\n".join(lines))
    res = {"runs": n, "max_abs_dG_mm_s": float(np.nanmax(dG)),
           "runs_dG_gt_0.1": int((dG[..., -1] > 0.1).sum()), "wall_default_s": w1, "wall_half_step_s": w2, "summary_default": s1,
           "summary_half_step": s2, "per_run_default": e1, "per_run_half": e2, "profile": prof}
    os.makedirs("out", exist_ok=True)
    with open("out/bench_sweep.json", "w") as f:
        json.dump(res, f, indent=1)
    return res


if __name__ == "__main__":
    main()
    sys.exit(0)
