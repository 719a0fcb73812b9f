"""One task of a sweep, in any process: its payload (everything a worker needs, picklable) and
``run_task``, the one pure function every executor runs (``execute.py``)."""
from __future__ import annotations

import sys

import numpy as np

from ..core.layout import RunStatus
from ..models import InitialState, SimOptions
from .plan import BranchTask, Plan

__all__ = ["run_task", "task_payload"]


def task_payload(plan: Plan, task: tuple | BranchTask, options: SimOptions | None = None) -> dict:
    """Everything a worker needs to run the task (first run, count) or :class:`BranchTask`
    (picklable)."""
    n_s = plan.n_samples
    if isinstance(task, BranchTask):
        payload = task_payload(plan, task.ranges(n_s)[0], options)
        payload["branches"] = [(first, plan.cells[first // n_s].spin)
                               for first, _ in task.ranges(n_s)]
        return payload
    first, count = task
    runs = range(first, first + count)
    systems = [plan.cells[r // n_s].system for r in runs]
    base_init = [plan.cells[r // n_s].initial for r in runs]
    inits = [InitialState(ball_angles=tuple(plan.cell_angles(r // n_s)[r % n_s]),
                          ball_speeds=i.ball_speeds, x=i.x, y=i.y, vx=i.vx, vy=i.vy,
                          steady_state=i.steady_state)
             for r, i in zip(runs, base_init)]
    opts = options or plan.cells[first // n_s].options
    spin = plan.cells[first // n_s].spin
    hist = ()
    if plan.spec.history_dt > 0:
        hist = tuple(np.arange(0.0, spin.duration + 1e-12, plan.spec.history_dt))
    return {"first": first, "count": count, "systems": systems, "initials": inits, "spin": spin,
            "options": opts, "history_times": hist, "ball_slots": plan.n_balls}


def _pad_balls(a: np.ndarray, slots: int) -> np.ndarray:
    """(runs, checkpoints, N) -> (runs, checkpoints, slots), NaN for the balls N..slots-1."""
    if a.shape[2] >= slots:
        return a
    out = np.full(a.shape[:2] + (slots,), np.nan)
    out[:, :, :a.shape[2]] = a
    return out


def one_thread_on_dask() -> None:
    """On a Dask worker, one numba thread in this task's thread. ``numba.set_num_threads`` is
    thread-local, so the workers' set-up (``execute._init_worker``, run once through
    ``client.run``) reaches one thread only, and a worker with several task threads would run
    every batch on all cores again (core/batch.py). Nothing elsewhere: the local process pool
    sets its one thread at start, and a serial sweep keeps the caller's count."""
    dd = sys.modules.get("distributed")          # a Dask worker has imported it
    if dd is None:
        return
    try:
        dd.get_worker()
    except ValueError:                             # not inside a Dask task
        return
    import numba

    numba.set_num_threads(1)


def run_task(payload: dict) -> dict | list:
    """Run one task (in any process): numpy arrays per run, see store.VARIABLES. The runs of a
    task share their ball count N; ``ball_angle`` has ``payload["ball_slots"]`` (>= N) balls,
    NaN beyond N. A branch task (``payload["branches"]``: (first run, profile) per cell) returns
    one such dict per cell."""
    from ..simulate import simulate_batch, simulate_branches

    one_thread_on_dask()
    spin = payload["spin"]
    cps = np.asarray(spin.checkpoints, float)
    hist = np.asarray(payload["history_times"], float)
    if payload["systems"][0].liquid is not None:
        from .liquid_task import run_hybrid_task, run_liquid_task
        if payload["systems"][0].balancer.n_balls:
            return _task_outputs(payload, run_hybrid_task(payload, np.concatenate([cps, hist])),
                                 payload["first"], cps.size, hist.size)
        return run_liquid_task(payload, cps, hist)
    out_t = np.concatenate([cps, hist])
    if "branches" in payload:
        res = simulate_branches(payload["systems"], [sp for _, sp in payload["branches"]],
                                payload["initials"], options=payload["options"], out_times=out_t)
        return [_task_outputs(payload, r, first, cps.size, hist.size)
                for (first, _), r in zip(payload["branches"], res)]
    res = simulate_batch(payload["systems"], spin, payload["initials"],
                         options=payload["options"], out_times=out_t)
    return _task_outputs(payload, res, payload["first"], cps.size, hist.size)


def _task_outputs(payload: dict, res, first: int, n_cp: int, n_hist: int) -> dict:
    """The stored variables of a task's runs (store.VARIABLES) from their BatchResult."""
    from ..core.layout import S_AMAX, S_EVENTS, S_STEPS, speed_index
    from ..physics.iso1940 import grade_value
    from ..simulate.result import residual_unbalance_history

    spin = res.spin
    systems = payload["systems"]
    mt = np.array([s.total_mass for s in systems])
    n_balls = systems[0].balancer.n_balls
    a0 = np.array([i.ball_angles for i in payload["initials"]], float).reshape(len(systems),
                                                                               n_balls)
    u0 = np.array([abs(residual_unbalance_history(s, a, np.array(0.0))) for s, a in zip(systems, a0)])
    status = np.array([int(RunStatus.from_label(s)) for s in res.status], np.int8)
    out = {
        "first": first, "count": len(systems),
        "grade_G": res.grade_G[:, :n_cp],
        "residual_unbalance": res.residual_unbalance[:, :n_cp],
        "ball_angle": _pad_balls(np.angle(np.exp(1j * res.alpha[:, :n_cp, :])),
                                 payload.get("ball_slots", n_balls)),
        "initial_grade_G": grade_value(u0, mt, spin.nominal_speed),
        "max_amplitude": res.stats[:, S_AMAX],
        "status": status,
        "steps": res.stats[:, S_STEPS].astype(np.int64),
        "events": res.stats[:, S_EVENTS].astype(np.int64),
    }
    if n_hist:
        st = res.states[:, n_cp:, :]
        out["grade_G_history"] = res.grade_G[:, n_cp:]
        out["amplitude_history"] = np.hypot(st[:, :, 0], st[:, :, 1])
        out["speed_history"] = st[:, :, speed_index(systems[0].balancer.n_balls)]
    # a failed run (max_steps, step-size underflow, non-finite state) has no outcome: NaN, with
    # its status, steps and events kept (its start, initial_grade_G, is still known)
    failed = status != 0
    if failed.any():
        for name in ("grade_G", "residual_unbalance", "ball_angle", "max_amplitude",
                     "grade_G_history", "amplitude_history", "speed_history"):
            if name in out:
                out[name] = np.array(out[name], float)
                out[name][failed] = np.nan
    return out

