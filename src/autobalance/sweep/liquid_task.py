"""The sweep task of a liquid-balancer machine (a ``[liquid]`` section): one wall-film run per
grid cell, stored in the variables of the ball runs (:data:`autobalance.sweep.store.VARIABLES`);
with balls beside the liquid one run of :func:`autobalance.simulate.hybrid.simulate_hybrid` per
run, read as a batch of ball runs."""
from __future__ import annotations

from types import SimpleNamespace

import numpy as np


def run_liquid_task(payload: dict, cps: np.ndarray, hist: np.ndarray) -> dict:
    """:func:`autobalance.sweep.task.run_task` for liquid balancers: one wall-film run per system
    (:func:`autobalance.simulate.simulate` of a liquid alone: a prescribed profile or a motor), read at
    the checkpoints and history times as the ball runs are; no balls (``ball_angle`` all NaN),
    no stick-slip events."""
    from ..core.layout import RunStatus
    from ..physics.iso1940 import grade_value
    from ..simulate import simulate

    spin, systems = payload["spin"], payload["systems"]
    n, n_cp = len(systems), cps.size
    out = {"first": payload["first"], "count": n,
           "grade_G": np.zeros((n, n_cp)), "residual_unbalance": np.zeros((n, n_cp)),
           "ball_angle": np.full((n, n_cp, payload.get("ball_slots", 0)), np.nan),
           "initial_grade_G": np.array([grade_value(abs(s.rotor.unbalance), s.total_mass,
                                                    spin.nominal_speed) for s in systems]),
           "max_amplitude": np.zeros(n), "status": np.zeros(n, np.int8),
           "steps": np.zeros(n, np.int64), "events": np.zeros(n, np.int64)}
    if hist.size:
        for name in ("grade_G_history", "amplitude_history", "speed_history"):
            out[name] = np.full((n, hist.size), np.nan)
    for i, s in enumerate(systems):
        sim = simulate(s, spin, throw=False)
        at = sim.at(cps)
        out["grade_G"][i], out["residual_unbalance"][i] = at["grade_G"], at["residual_unbalance"]
        out["max_amplitude"][i] = max(float(np.max(sim.amplitude)), sim.max_amplitude_before_film)
        out["steps"][i] = sim.steps
        out["status"][i] = int(RunStatus.from_label(sim.status))
        if hist.size:
            film = hist >= sim.film_start
            out["grade_G_history"][i] = sim.at(hist)["grade_G"]
            out["amplitude_history"][i, film] = np.interp(hist[film], sim.t, sim.amplitude)
            out["speed_history"][i] = [spin.speed(t) for t in hist]
    return out


def run_hybrid_task(payload: dict, out_t: np.ndarray) -> SimpleNamespace:
    """The runs of a task of balls beside a liquid (each with its own start, as a batch of ball
    runs), read at ``out_t`` [s] (checkpoints, then history times) from each run's history:
    its own samples where they fall on them (the checkpoints are on the run's output grid),
    linear between them. Returns what :func:`autobalance.sweep.task._task_outputs` reads of a
    :class:`autobalance.simulate.result.BatchResult` (spin, status, stats, grade_G,
    residual_unbalance, alpha, states)."""
    from ..simulate.hybrid import simulate_hybrid

    rows = {"grade_G": [], "residual_unbalance": [], "alpha": [], "states": [], "stats": [],
            "status": []}
    for s, init in zip(payload["systems"], payload["initials"]):
        sim = simulate_hybrid(s, payload["spin"], initial=init, options=payload["options"],
                              throw=False)

        def at(v):
            return np.stack([np.interp(out_t, sim.t, c) for c in np.asarray(v).T], axis=-1)

        rows["grade_G"].append(np.interp(out_t, sim.t, sim.grade_G))
        rows["residual_unbalance"].append(np.interp(out_t, sim.t, sim.residual_unbalance))
        rows["alpha"].append(at(sim.alpha))
        rows["states"].append(at(sim.states))
        rows["stats"].append(sim.stats)
        rows["status"].append(sim.status)
    res = {k: (v if k == "status" else np.array(v)) for k, v in rows.items()}
    return SimpleNamespace(spin=payload["spin"], **res)
