"""Expand a SweepSpec into grid cells, Monte-Carlo samples and tasks; run one task.

Runs are numbered r = cell * n_samples + sample (C order over the grid axes, sample fastest).
A task is a run of consecutive runs sharing the spin profile and the ball count (so one
``simulate_batch`` call serves it), at most ``batch_size`` long. Everything here is
deterministic: the same description gives the same tasks and the same results.
"""
from __future__ import annotations

import copy
import itertools
from dataclasses import dataclass

import numpy as np

from ..config import ConfigError, _read, apply_overrides, from_dict
from ..models import InitialState, SimOptions
from .spec import SweepError, SweepSpec, _toml_literal


@dataclass
class Plan:
    """Grid cells (configs), sample start angles and tasks of a sweep."""

    spec: SweepSpec
    cells: list              # Config per grid cell (C order)
    start_angles: np.ndarray  # (n_samples, N) [rad]
    tasks: list              # (first_run, n_runs) pairs
    n_balls: int

    @property
    def n_samples(self) -> int:
        return self.start_angles.shape[0]

    @property
    def n_runs(self) -> int:
        return len(self.cells) * self.n_samples

    @property
    def checkpoints(self) -> np.ndarray:
        return np.asarray(self.cells[0].spin.checkpoints, float)


def start_grid(n: int, n_balls: int, identical: bool) -> np.ndarray:
    """004 sec. 4.2: n equispaced start positions per ball. For identical balls the
    configurations that differ only by swapping balls are removed (combinations with
    repetition: n (n + 1) / 2 = 1275 for n = 50 and two balls); otherwise the full product."""
    pos = 2 * np.pi * np.arange(n) / n
    combos = (itertools.combinations_with_replacement(range(n), n_balls) if identical
              else itertools.product(range(n), repeat=n_balls))
    return np.array([[pos[i] for i in c] for c in combos], float).reshape(-1, n_balls)


def separate(angles: np.ndarray, delta: float) -> np.ndarray:
    """Move balls that start closer than the contact angle delta [rad] symmetrically apart to
    exactly delta (004's point masses may coincide; ours touch). Keeps the centroid of each pair."""
    a = np.array(angles, float)
    n = a.size
    if n < 2 or delta <= 0:
        return a
    for _ in range(200):
        order = np.argsort(np.mod(a, 2 * np.pi), kind="stable")
        moved = False
        for k in range(n):
            i, j = order[k], order[(k + 1) % n]
            gap = np.mod(a[j] - a[i], 2 * np.pi)
            if gap < delta * (1 - 1e-12):
                push = 0.5 * (delta - gap) * (1 + 1e-9)
                a[i] -= push
                a[j] += push
                moved = True
        if not moved:
            return a
    raise SweepError("monte_carlo: too many balls to place them without overlap")


def make_plan(spec: SweepSpec) -> Plan:
    """Build the configs of every grid cell (validated like --set) and the samples."""
    try:
        raw, label, _ = _read(spec.base)
    except SweepError:
        raise
    except ConfigError as e:
        raise SweepError(f"sweep.base: {e}") from None
    try:
        base_raw = apply_overrides(raw, list(spec.overrides))
    except SweepError:
        raise
    except ConfigError as e:
        raise SweepError(f"sweep.set: {e}") from None
    cells = []
    for combo in itertools.product(*[range(len(a.values)) for a in spec.grid]):
        sets = [f"{a.path}={_toml_literal(a.values[i])}" for a, i in zip(spec.grid, combo)]
        where = ", ".join(f"{a.path}={a.values[i]!r}" for a, i in zip(spec.grid, combo))
        try:
            cfg = from_dict(apply_overrides(copy.deepcopy(base_raw), sets), source=label)
        except Exception as e:   # ConfigError / ParameterError: name the grid point
            raise SweepError(f"grid point {where or '(base)'}: {e}") from None
        cells.append(cfg)
    nb = {c.system.balancer.n_balls for c in cells}
    if len(nb) != 1:
        raise SweepError(f"grid: balancer.n_balls must be the same in every cell (got {sorted(nb)})")
    N = nb.pop()
    b0 = cells[0].system.balancer
    if spec.mc_kind == "start_grid":
        identical = all(len(set(map(float, np.atleast_1d(getattr(b0, f))))) <= 1
                        for f in ("ball_mass", "damping", "rolling_resistance", "stiction"))
        angles = start_grid(spec.mc_n, N, identical)
    elif spec.mc_kind == "random":
        rng = np.random.default_rng(spec.seed)
        angles = rng.uniform(0.0, 2 * np.pi, size=(spec.mc_samples, N))
    else:
        angles = np.asarray(cells[0].initial.angles_for(b0), float).reshape(1, N)
    delta = b0.contact_angle
    angles = np.array([separate(a, delta) for a in angles]).reshape(-1, N)
    # tasks: consecutive runs with the same spin, at most batch_size long
    n_s = angles.shape[0]
    tasks = []
    start = 0
    n_runs = len(cells) * n_s
    while start < n_runs:
        spin = cells[start // n_s].spin
        stop = start + 1
        while (stop < n_runs and stop - start < spec.batch_size
               and cells[stop // n_s].spin == spin):
            stop += 1
        tasks.append((start, stop - start))
        start = stop
    return Plan(spec, cells, angles, tasks, N)


def task_payload(plan: Plan, k: int, options: SimOptions | None = None) -> dict:
    """Everything a worker needs to run task k (picklable)."""
    first, count = plan.tasks[k]
    n_s = plan.n_samples
    runs = range(first, first + count)
    systems = [plan.cells[r // n_s].system for r in runs]
    base_init = [plan.cells[r // n_s].initial for r in runs]
    inits = [InitialState(ball_angles=tuple(plan.start_angles[r % n_s]), x=i.x, y=i.y,
                          vx=i.vx, vy=i.vy, steady_state=i.steady_state)
             for r, i in zip(runs, base_init)]
    opts = options or plan.cells[first // n_s].options
    spin = plan.cells[first // n_s].spin
    hist = ()
    if plan.spec.history_dt > 0:
        hist = tuple(np.arange(0.0, spin.duration + 1e-12, plan.spec.history_dt))
    return {"task": k, "first": first, "systems": systems, "initials": inits, "spin": spin,
            "options": opts, "history_times": hist}


def run_task(payload: dict) -> dict:
    """Run one task (in any process): numpy arrays per run, see store.VARIABLES."""
    from ..core.layout import S_AMAX, S_EVENTS, S_STEPS
    from ..result import grade_G, residual_unbalance
    from ..simulate import simulate_batch

    spin = payload["spin"]
    cps = np.asarray(spin.checkpoints, float)
    hist = np.asarray(payload["history_times"], float)
    out_t = np.concatenate([cps, hist])
    res = simulate_batch(payload["systems"], spin, payload["initials"],
                         options=payload["options"], out_times=out_t)
    n_cp = cps.size
    systems = payload["systems"]
    mt = np.array([s.total_mass for s in systems])
    a0 = np.array([i.ball_angles for i in payload["initials"]], float).reshape(len(systems), -1)
    u0 = np.array([abs(residual_unbalance(s, a, np.array(0.0))) for s, a in zip(systems, a0)])
    status = np.array([{"ok": 0, "max_steps": 1, "step_size_underflow": 2,
                        "non_finite": 3}.get(s, 9) for s in res.status], np.int8)
    out = {
        "task": payload["task"], "first": payload["first"],
        "grade_G": res.grade_G[:, :n_cp],
        "residual_unbalance": res.residual_unbalance[:, :n_cp],
        "ball_angle": np.angle(np.exp(1j * res.alpha[:, :n_cp, :])),
        "initial_grade_G": grade_G(u0, mt, spin.nominal_speed),
        "max_amplitude": res.stats[:, S_AMAX],
        "status": status,
        "steps": res.stats[:, S_STEPS].astype(np.int64),
        "events": res.stats[:, S_EVENTS].astype(np.int64),
    }
    if hist.size:
        nq = res.states.shape[2] // 2
        st = res.states[:, n_cp:, :]
        out["grade_G_history"] = res.grade_G[:, n_cp:]
        out["amplitude_history"] = np.hypot(st[:, :, 0], st[:, :, 1])
        out["speed_history"] = st[:, :, 2 * nq - 1]
    return out
