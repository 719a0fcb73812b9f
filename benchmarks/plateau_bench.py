"""Plateau-map benchmark (make bench): 004 sec. 4.6's map of the TSR plateau, paper size.

1. Side by side in one run, on the paper's grid (17 plateau speeds 0.96-1.12 Omega_n x 9
   initial grades) with 21 starts per cell (n = 6): the sweep with branching (each start's 18 s
   run-up integrated once per cell family, ``simulate_branches``) against the same sweep with
   every cell alone (``branch=False``); wall time, runs/s, and
   that the two stores hold the same bytes.
2. The paper-size map itself (``studies._plateau.compute_plateau``: 153 cells x 210 starts =
   32 130 runs, nominal case): wall time, runs/s and its ideal plateau.
"""
from __future__ import annotations

import json
import os
import sys
import tempfile
import time

import numpy as np

from autobalance.config import load_config
from autobalance.physics.iso1940 import grade_value, unbalance_value
from autobalance.studies._plateau import compute_plateau, default_grid
from autobalance.sweep import spec_from_dict, sweep

PRESET = "vub_jeffcott_004"


def _spec(n: int) -> dict:
    cfg = load_config(PRESET)
    s, spin = cfg.system, cfg.spin
    fn = s.natural_frequencies[0]
    G_b = float(grade_value(s.balancer.capacity, s.total_mass, spin.nominal_speed))
    ratios, G = default_grid(G_b, quick=False)
    U = unbalance_value(G, s.total_mass, spin.nominal_speed)
    return {"sweep": {"name": "plateau-bench", "base": PRESET, "batch_size": 64},
            "grid": {"profile.plateau": [float(r * fn) for r in ratios],
                     "rotor.unbalance": [float(u) for u in U]},
            "monte_carlo": {"kind": "start_grid", "n": n}}


def side_by_side(n: int, work: str) -> dict:
    spec = spec_from_dict(_spec(n), "bench")
    # untimed: a stale kernel cache (after a change to core/) is compiled in the workers by the
    # first sweep of each kind, which would put tens of seconds into the first timed sweep
    for branch in (True, False):
        sweep(spec_from_dict(_spec(1), "warm"), os.path.join(work, f"warm{branch}"),
              executor="local", progress=False, branch=branch)
    out = {}
    for branch in (True, False):
        t0 = time.perf_counter()
        ds = sweep(spec, os.path.join(work, f"b{branch}"), executor="local", progress=False,
                   branch=branch)
        out[branch] = (time.perf_counter() - t0, ds)
    (wb, a), (ws, b) = out[True], out[False]
    same = all(a[v].values.tobytes() == b[v].values.tobytes() for v in a.data_vars)
    return {"runs": int(a.sizes["sample"] * a["grade_G"].size // a.sizes["sample"]
                        // a.sizes["checkpoint"]),
            "wall_branched_s": wb, "wall_separate_s": ws, "bit_identical": bool(same),
            "mean_steps": float(a["steps"].mean()), "mean_events": float(a["events"].mean())}


def main() -> dict:
    with tempfile.TemporaryDirectory(prefix="ab-plateau-bench-") as work:
        sbs = side_by_side(6, work)
        t0 = time.perf_counter()
        ds = compute_plateau(PRESET, store_dir=os.path.join(work, "paper"))
        wall = time.perf_counter() - t0
    runs = int(ds.sizes["plateau_ratio"] * ds.sizes["G_ini"] * 210)
    lines = [
        f"004 plateau map (17 plateau speeds x 9 initial grades), {os.cpu_count()} cores, local processes",
        f"  21 starts per cell ({sbs['runs']} runs), side by side: branched {sbs['wall_branched_s']:.1f} s, "
        f"every cell alone {sbs['wall_separate_s']:.1f} s: {sbs['wall_separate_s'] / sbs['wall_branched_s']:.2f}x; "
        f"stores bit-identical: {sbs['bit_identical']}; {sbs['mean_steps']:.0f} steps and "
        f"{sbs['mean_events']:.0f} events per run",
        f"  paper size, 210 starts per cell ({runs} runs, nominal case): {wall:.1f} s wall, "
        f"{runs / wall:.1f} runs/s; ideal plateau {ds.attrs['ideal'][0]:.2f} Omega_n",
    ]
    print("\n".join(lines))
    res = {"side_by_side": sbs, "paper_runs": runs, "paper_wall_s": wall,
           "ideal_ratio": float(ds.attrs["ideal"][0]),
           "mean_p95": np.asarray(ds["mean_p95"].values).tolist()}
    os.makedirs("out", exist_ok=True)
    with open("out/bench_plateau.json", "w") as f:
        json.dump(res, f, indent=1)
    return res


if __name__ == "__main__":
    main()
    sys.exit(0)
