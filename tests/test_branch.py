"""Branching runs: a run paused on arriving at a profile knot continues bit for bit as
the run that did not pause (core/integrate.integrate_span), under its own profile or any other
that agrees up to the knot; simulate_branches equals separate simulate_batch calls; a sweep over
profile keys runs its families as BranchTasks and stores exactly what the unbranched sweep
stores, also when resumed."""
from __future__ import annotations

import numpy as np
import pytest

from autobalance.config import load_config
from autobalance.core.integrate import integrate, integrate_span
from autobalance.core.layout import C_EVI, C_WHERE, N_S, S_STATUS, RunStatus, carry_size
from autobalance.models import InitialState, MotorDrive
from autobalance.simulate import simulate_batch, simulate_branches
from autobalance.simulate.pack import atol_vector, initial_vector, pack_params, spin_arrays
from autobalance.simulate.pack import _h_max
from autobalance.simulate.run import branch_knot
from autobalance.sweep import make_plan, sweep
from autobalance.sweep.plan import BranchTask

from conftest import assert_bit_identical, spec_of
from oracles import paths_off

#: 004's machine on a 12 s profile: run-up to 167 Hz in 6 s, down in 1 s, plateau 2 s, up 1 s
SHORT = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s",
         "profile.plateau_time=2 s", "profile.up_time=1 s"]


def _starts(n: int, seed: int = 1) -> list:
    rng = np.random.default_rng(seed)
    return [(a, a + rng.uniform(0.5, 5.7)) for a in rng.uniform(0.0, 2 * np.pi, n)]


def _kernel_args(cfg, angles, off=None):
    s, spin, o = cfg.system, cfg.spin, cfg.options
    P, B = pack_params(s, spin, o)
    paths_off(P, **(off or {}))
    y0, _ = initial_vector(s, spin, InitialState(ball_angles=angles))
    unb_t, unb_u = s.rotor.unbalance_table()
    return P, B, s.balancer.n_balls, unb_t, unb_u, y0, atol_vector(s, spin, o), _h_max(spin, o)


def _pause_and_continue(cfg, angles, t_pause, prof_w_after=None, off=None):
    """(whole run, paused then continued) of one start: (y, out_y, stats) each, and where the
    run paused (layout.C_WHERE; 5: at the end of a hold with its breakaway). ``prof_w_after``:
    the speeds the continuation uses (any after the knot); ``off``: the fast paths stepped
    instead (oracles.paths_off)."""
    P, B, N, unb_t, unb_u, y0, atol, h_max = _kernel_args(cfg, angles, off)
    prof_t, prof_w, t_end = spin_arrays(cfg.spin)
    w_after = prof_w if prof_w_after is None else prof_w_after
    o = cfg.options
    out_t = np.linspace(0.0, t_end, 25)
    whole = (np.zeros((out_t.size, y0.size)), np.zeros(N_S))
    y_whole = integrate(P, B, N, prof_t, w_after, unb_t, unb_u, y0, t_end, o.rtol, atol, h_max,
                        int(o.max_steps), out_t, whole[0], whole[1])
    y = y0.copy()
    carry = np.zeros(carry_size(N))
    out_y, stats = np.zeros_like(whole[0]), np.zeros(N_S)
    integrate_span(P, B, N, prof_t, prof_w, unb_t, unb_u, y, t_end, o.rtol, atol, h_max,
                   int(o.max_steps), out_t, out_y, stats, t_pause, carry)
    assert stats[S_STATUS] == RunStatus.RUNNING
    where = int(carry[C_WHERE]) if carry[C_EVI] < 0 or carry[C_WHERE] != 3 else 5
    integrate_span(P, B, N, prof_t, w_after, unb_t, unb_u, y, t_end, o.rtol, atol, h_max,
                   int(o.max_steps), out_t, out_y, stats, np.inf, carry)
    return (y_whole, *whole), (y, out_y, stats), where


def _same(a, b) -> bool:
    return all(np.array_equal(x, y) for x, y in zip(a, b))


def test_pause_at_every_knot_continues_bit_for_bit():
    cfg = load_config("vub_jeffcott_004", SHORT)
    knots = spin_arrays(cfg.spin)[0][1:-1]
    for angles in _starts(3):
        for t_pause in knots:
            whole, cont, where = _pause_and_continue(cfg, angles, t_pause)
            assert 1 <= where <= 4
            assert _same(whole, cont), (angles, t_pause, where)


def test_continuation_under_another_profile_is_that_profile_s_run():
    """Paused after the run-up under one plateau, continued under another: the run of the
    other plateau, bit for bit (the arrival at the knot reads the next segment's slope)."""
    cfg = load_config("vub_jeffcott_004", SHORT)
    prof_t, prof_w, _ = spin_arrays(cfg.spin)
    other = prof_w.copy()
    other[2:4] *= 1.04
    for angles in _starts(3, seed=2):
        whole, cont, _ = _pause_and_continue(cfg, angles, prof_t[1], other)
        assert _same(whole, cont)


@pytest.mark.slow
@pytest.mark.parametrize("off, arrivals", [({}, {1, 2, 3, 4}),
                                           ({"ramps": False}, {2, 4}),
                                           ({"holds": False}, {4})],
                         ids=["jumps", "stepped-ramps", "stepped-holds"])
def test_pause_on_every_kind_of_arrival(off, arrivals):
    """004's 90 s profile, 12 starts, every interior knot: the knot is reached by a ramp jump
    (1), a closed-form hold (2), a hold until its breakaway (3) or a step (4); each continues
    bit for bit, also under another plateau."""
    cfg = load_config("vub_jeffcott_004")
    prof_t, prof_w, _ = spin_arrays(cfg.spin)
    other = prof_w.copy()
    other[2:4] *= 1.03
    seen = set()
    for angles in _starts(12):
        for t_pause in prof_t[1:-1]:
            whole, cont, where = _pause_and_continue(cfg, angles, t_pause, off=off)
            seen.add(where)
            assert _same(whole, cont), (angles, t_pause, where)
        assert _same(*_pause_and_continue(cfg, angles, prof_t[1], other, off=off)[:2])
    assert seen == arrivals


@pytest.mark.slow
def test_pause_anywhere_continues_bit_for_bit():
    """A pause time inside a segment stops the run at its next arrival after it (a jump's end,
    a slip jump's end, a hold's end with its breakaway on 004's plateau): the same profile
    continues bit for bit, with the slip jumps and without (DOPRI5 alone reaches the hold's
    end with a breakaway, kind 5, in these starts)."""
    seen = set()
    cfg = load_config("vub_jeffcott_004")
    for slip in (False, True):
        for angles in _starts(6, seed=5):
            for t_pause in (12.3, 20.7, 28.9, 33.1, 41.2, 52.5):
                whole, cont, where = _pause_and_continue(cfg, angles, t_pause,
                                                         off={"slip_jumps": slip})
                seen.add(where)
                assert _same(whole, cont), (slip, angles, t_pause, where)
    assert 5 in seen


def _spins(ratios, sets=SHORT):
    cfg = load_config("vub_jeffcott_004", sets)
    fn = cfg.system.natural_frequencies[0]
    return cfg, [load_config("vub_jeffcott_004", [*sets, f"profile.plateau={float(r * fn)!r}"]).spin
                 for r in ratios]


def test_branches_equal_separate_batches():
    cfg, spins = _spins((0.98, 1.02, 1.08))
    inits = [InitialState(ball_angles=a) for a in _starts(4, seed=3)]
    systems = [cfg.system] * len(inits)
    out_t = np.array([6.0, 12.0, 3.0, 9.5])               # any order, before and after the knot
    got = simulate_branches(systems, spins, inits, options=cfg.options, out_times=out_t)
    for sp, b in zip(spins, got):
        a = simulate_batch(systems, sp, inits, options=cfg.options, out_times=out_t)
        assert a.status == b.status == ["ok"] * len(inits)
        for name in ("states", "stats", "grade_G", "alpha", "max_amplitude"):
            assert np.array_equal(getattr(a, name), getattr(b, name)), name


def test_a_run_that_fails_before_the_knot_fails_in_every_branch():
    cfg, spins = _spins((0.98, 1.06))
    o = cfg.options.__class__(**{**cfg.options.__dict__, "max_steps": 300})
    inits = [InitialState(ball_angles=a) for a in _starts(2, seed=4)]
    systems = [cfg.system] * 2
    got = simulate_branches(systems, spins, inits, options=o)
    for sp, b in zip(spins, got):
        a = simulate_batch(systems, sp, inits, options=o)
        assert a.status == b.status == ["max_steps"] * 2
        assert np.array_equal(a.stats, b.stats)


def test_branch_knot():
    cfg, (a, b) = _spins((0.98, 1.02))
    assert branch_knot([a, b]) == 6.0                     # the end of the shared run-up
    assert branch_knot([a, a]) == 0.0 and branch_knot([a]) == 0.0
    _, (c,) = _spins((1.02,), [*SHORT[:-1], "profile.up_time=2 s"])
    assert branch_knot([a, b, c]) == 6.0
    longer = load_config("vub_jeffcott_004", [*SHORT[1:], "profile.duration=13 s"]).spin
    assert branch_knot([a, longer]) == 0.0                # another duration: another step bound
    motor = MotorDrive(law="constant", torque=1.0, final_speed=1000.0, duration=12.0)
    assert branch_knot([a, motor]) == 0.0
    with pytest.raises(ValueError, match="share no knot"):
        simulate_branches([cfg.system], [a, a])


PLATEAU_SWEEP = """
[sweep]
name = "plateau-branches"
base = "vub_jeffcott_004"
set = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s", "profile.plateau_time=2 s", "profile.up_time=1 s"]
batch_size = 9

[grid]
"profile.plateau" = ["98 Hz", "104 Hz", "110 Hz"]
"rotor.unbalance" = [2e-5, 6e-5]

[monte_carlo]
kind = "start_grid"
n = 4
"""


@pytest.mark.slow
def test_plateau_sweep_branches_and_stores_the_unbranched_result(tmp_path):
    spec = spec_of(PLATEAU_SWEEP)
    plan = make_plan(spec)
    assert plan.families == ((0, 2, 4), (1, 3, 5))           # one per unbalance
    branched = [t for t in plan.tasks if isinstance(t, BranchTask)]
    assert len(branched) == 8 and sum(len(t.cells) * t.count for t in branched) == plan.n_runs
    a = sweep(spec, tmp_path / "branched", executor="serial", progress=False)
    b = sweep(spec, tmp_path / "separate", executor="serial", progress=False, branch=False)
    assert_bit_identical(a, b)
    # resume with some cells' runs missing: the rest branch again (or run alone) to the same
    files = sorted((tmp_path / "branched" / "tasks").glob("*.npz"))
    for p in files[::3]:
        p.unlink()
    (tmp_path / "branched" / "result.zarr").rename(tmp_path / "old.zarr")
    c = sweep(spec, tmp_path / "branched", executor="serial", progress=False, resume=True)
    assert_bit_identical(c, b)
