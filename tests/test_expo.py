"""core/expo.py: the phi functions and the exponential Runge-Kutta step for slipping phases
(docs/numerics/index.md, "An exponential integrator for the slipping phases").

Tiers: the phi functions against scipy's matrix exponential of the augmented matrix and against
their scalar closed forms (fast); the method on 004's rig against the kernel's closed-form hold
and its order on a slipping window of the run-up (slow: each compiles and runs the kernel).
"""
from __future__ import annotations

import math

import numpy as np
import pytest
from scipy.linalg import expm

from autobalance.core.expo import etd_window
from autobalance.core.phi import phi_functions


def _phis_scipy(A, k=3):
    """phi_0..phi_k of A from one exponential of the block matrix [[A, I, 0..], [0, 0, I..], ..]
    (Saad 1992, SIAM J. Numer. Anal. 29, 209, Prop. 2.1): an independent reference."""
    m = A.shape[0]
    aug = np.zeros((m * (k + 1), m * (k + 1)))
    aug[:m, :m] = A
    for j in range(k):
        aug[j * m:(j + 1) * m, (j + 1) * m:(j + 2) * m] = np.eye(m)
    E = expm(aug)
    return [E[:m, j * m:(j + 1) * m] for j in range(k + 1)]


def _ours(A):
    m = A.shape[0]
    half, full, work = np.zeros((4, m, m)), np.zeros((4, m, m)), np.zeros((6, m, m))
    s = phi_functions(A, m, half, full, work)
    return s, half, full


@pytest.mark.parametrize("m, norm", [(3, 0.05), (11, 1.0), (11, 40.0), (11, 300.0)])
def test_phi_functions_equal_the_augmented_exponential(m, norm):
    A = np.random.default_rng(m + int(norm)).normal(size=(m, m)) * norm / np.sqrt(m)
    s, half, full = _ours(A)
    assert s >= 1 and np.abs(A).sum(0).max() / 2.0 ** s <= 0.5
    for ours, ref in ((full, _phis_scipy(A)), (half, _phis_scipy(A / 2))):
        for k in range(4):
            # measured 6e-14 at norm 300 (11 doublings); round-off grows with the doublings
            assert np.abs(ours[k] - ref[k]).max() <= 1e-12 * np.abs(ref[k]).max()


@pytest.mark.parametrize("z", [-40.0, -2.5, 0.7, 3.0])
def test_phi_functions_of_a_scalar_are_their_closed_forms(z):
    s, half, full = _ours(np.array([[z]]))
    e = math.exp(z)
    closed = [e, (e - 1) / z, (e - 1 - z) / z ** 2, (e - 1 - z - z * z / 2) / z ** 3]
    for k in range(4):
        assert full[k, 0, 0] == pytest.approx(closed[k], rel=1e-12)


def test_phi_functions_of_zero_are_the_inverse_factorials():
    s, half, full = _ours(np.zeros((4, 4)))
    for k in range(4):
        assert np.array_equal(full[k], np.eye(4) / math.factorial(k))


def _rig(mu_r, grade, seed):
    from autobalance.models import InitialState
    from autobalance.physics.iso1940 import unbalance_value
    from autobalance.simulate.pack import run_inputs
    from autobalance.studies.common import case_sets, load
    base = load("vub_jeffcott_004")
    U = unbalance_value(grade, base.system.total_mass, base.spin.nominal_speed)
    cfg = load("vub_jeffcott_004", case_sets(base, mu_r, 1.0) + [f"rotor.unbalance={float(U)!r}"])
    rng = np.random.default_rng(seed)
    x = rng.uniform(0, 2 * np.pi)
    a0 = (x, x + rng.uniform(0.6, 2 * np.pi - 0.6))
    return cfg, run_inputs(cfg.system, cfg.spin, InitialState(ball_angles=a0), cfg.options)


def _run_to(cfg, r, te, rtol=None, atol_factor=1.0):
    from autobalance.core.integrate import integrate
    from autobalance.core.layout import P_ETD, S_EVENTS, S_STEPS
    st = r.stats.copy()
    P = r.P.copy()
    P[P_ETD] = 0.0                            # the kernel's own stepping: DOPRI5 throughout
    y = integrate(P, r.B, 2, r.prof_t, r.prof_w, r.unb_t, r.unb_u, r.y0, te,
                  rtol or cfg.options.rtol, r.atol * atol_factor, r.h_max, 10 ** 9,
                  np.array([te]), np.zeros((1, r.y0.shape[0])), st)
    return y, int(st[S_STEPS]), int(st[S_EVENTS])


def _modes(y):
    nq = y.shape[0] // 2
    v = y[nq + 2:2 * nq - 1]                  # the balls' speeds
    return (v == 0.0).astype(np.int64), np.where(v >= 0.0, 1.0, -1.0)


@pytest.mark.slow
def test_etd_on_a_stuck_hold_equals_the_closed_form_hold():
    """Balls held by 20 times the rolling resistance on 004's 100 Hz plateau: the rotor is linear
    with constant forcing, which the kernel jumps in closed form (core/hold.py). Two ETDRK4-B
    steps of 0.25 s land on it (measured 6.8e-13 relative; one step of 0.5 s too): the method
    integrates the linear part exactly, and only the finite-difference error of L enters the
    remainder."""
    cfg, r = _rig(20.0, 20.0, 3)
    y0, _, _ = _run_to(cfg, r, 30.0)
    y1, steps, events = _run_to(cfg, r, 30.5)
    stuck, sgn = _modes(y0)
    assert stuck.all() and events == _run_to(cfg, r, 30.0)[2]
    scale = np.r_[r.atol / cfg.options.atol_scale, 1.0]
    y = etd_window(r.P, r.B, 2, r.prof_t, r.prof_w, r.unb_t, r.unb_u, stuck, sgn, y0, 30.0, 30.5,
                   2, 10, scale)
    w, w_ref = complex(y[0], y[1]), complex(y1[0], y1[1])
    assert abs(w - w_ref) <= 1e-11 * abs(w_ref)
    assert np.array_equal(y[2:4], y1[2:4])          # the stuck balls do not move


@pytest.mark.slow
def test_etd_converges_at_fourth_order_on_a_slipping_window_the_kernel_steps_finely():
    """004's run-up at a quarter of the rolling resistance, G30, both balls slipping from 1.5 to
    2 s (no event, no knot). Against the kernel at rtol 1e-12, the balls' speed error of
    ETDRK4-B with L refreshed every 4 steps falls by 10.8 and 22 from 8 to 16 to 32 steps
    (measured 4.1e-7, 3.8e-8, 1.7e-9 rad/s; a second-order method would give ratios of 4). The
    kernel (DOPRI5, rtol 1e-6) takes 139 steps there and ends 3.7e-6 rad/s off: 8 exponential
    steps are closer."""
    cfg, r = _rig(0.25, 30.0, 100)
    y0, s0, e0 = _run_to(cfg, r, 1.5)
    y1, s1, e1 = _run_to(cfg, r, 2.0)
    assert e1 == e0 and s1 - s0 > 100
    ref, _, _ = _run_to(cfg, r, 2.0, rtol=1e-12, atol_factor=1e-7)
    stuck, sgn = _modes(y0)
    assert not stuck.any()
    scale = np.r_[r.atol / cfg.options.atol_scale, 1.0]
    errs = []
    for ns in (8, 16, 32):
        y = etd_window(r.P, r.B, 2, r.prof_t, r.prof_w, r.unb_t, r.unb_u, stuck, sgn, y0, 1.5,
                       2.0, ns, 4, scale)
        errs.append(np.abs(y[7:9] - ref[7:9]).max())
    assert errs[0] / errs[1] >= 6.0 and errs[1] / errs[2] >= 6.0
    assert errs[0] < np.abs(y1[7:9] - ref[7:9]).max()


# -- the slip jumps in the kernel (P[P_ETD], pack.fast_paths) ----------------------------------
def _grades(cfg, starts, slip, max_step=0.0):
    import dataclasses

    from autobalance.core.layout import S_RHS, S_STEPS
    from autobalance.models import InitialState
    from oracles import stepped
    o = dataclasses.replace(cfg.options, save_dt=-1.0, max_step=max_step)
    out = []
    for a in starts:
        s = stepped(cfg.system, cfg.spin, initial=InitialState(ball_angles=a), options=o,
                    slip_jumps=slip)
        out.append((s.grade_G[1], s.grade_G[2], s.stats[S_STEPS], s.stats[S_RHS]))
    return np.array(out)


@pytest.mark.slow
@pytest.mark.parametrize("mu_r, grade", [(1.0, 20.0), (0.25, 30.0)])
def test_slip_jumps_keep_the_grades_within_0_02_mm_s_and_save_steps(mu_r, grade):
    """12 starts of 004's 90 s profile, STD and TSR grades (18 s, 90 s) with and without the
    slip jumps. The bound is every G within 0.02 mm/s of the run without jumps;
    benchmarks/slip_etd_bench.py measured at most 0.0052 mm/s over 105 starts of four cases,
    and halving DOPRI5's largest step moves G by as much (0.0062 mm/s at mu_r 0.5, G20, 40
    starts). Through resting contacts and with a failed window retried up to the step that
    failed, these 12 starts take 14-31 times fewer DOPRI5 steps and 3.7-5.4 times fewer
    right-hand-side evaluations with the jumps than without (measured); here at least four
    fifths of the steps and half of the evaluations must go."""
    cfg, _ = _rig(mu_r, grade, 0)
    rng = np.random.default_rng(11)
    starts = [(x, x + rng.uniform(0.6, 2 * np.pi - 0.6)) for x in rng.uniform(0, 2 * np.pi, 12)]
    off, on = _grades(cfg, starts, False), _grades(cfg, starts, True)
    assert np.abs(on[:, :2] - off[:, :2]).max() <= 0.02
    assert on[:, 2].sum() < 0.2 * off[:, 2].sum()
    assert on[:, 3].sum() < 0.5 * off[:, 3].sum()


@pytest.mark.slow
def test_slip_jumps_pause_at_a_knot_and_continue_bit_for_bit():
    """With the jumps on, a run paused at the end of the run-up (18 s) and continued equals the
    run that did not pause, to the last bit: the jump's step and retry time are carried."""
    from autobalance.core.integrate import integrate, integrate_span
    from autobalance.core.layout import N_S, P_ETD, S_STATUS, RunStatus, carry_size
    cfg, r = _rig(0.25, 30.0, 4)
    P = r.P.copy()
    P[P_ETD] = 1.0
    out_t = np.linspace(0.0, r.t_end, 19)
    whole_y, whole_s = np.zeros((out_t.size, r.y0.size)), np.zeros(N_S)
    args = (P, r.B, 2, r.prof_t, r.prof_w, r.unb_t, r.unb_u)
    yw = integrate(*args, r.y0, r.t_end, cfg.options.rtol, r.atol, r.h_max, 10 ** 8, out_t,
                   whole_y, whole_s)
    y, carry = r.y0.copy(), np.zeros(carry_size(2))
    cont_y, cont_s = np.zeros_like(whole_y), np.zeros(N_S)
    integrate_span(*args, y, r.t_end, cfg.options.rtol, r.atol, r.h_max, 10 ** 8, out_t, cont_y,
                   cont_s, 18.0, carry)
    assert cont_s[S_STATUS] == RunStatus.RUNNING
    integrate_span(*args, y, r.t_end, cfg.options.rtol, r.atol, r.h_max, 10 ** 8, out_t, cont_y,
                   cont_s, np.inf, carry)
    assert np.array_equal(y, yw) and np.array_equal(cont_y, whole_y)
    assert np.array_equal(cont_s, whole_s)


def test_slip_jumps_only_where_the_ramp_jumps_apply():
    """The jumps are taken under the conditions of the stuck ramps' jumps only
    (pack.fast_paths): not under gravity, nor with the creep law."""
    import dataclasses

    import autobalance as ab
    from autobalance.core.layout import P_ETD
    from autobalance.simulate.pack import pack_params
    cfg, _ = _rig(1.0, 20.0, 0)
    s, spin, o = cfg.system, cfg.spin, cfg.options
    assert pack_params(s, spin, o)[0][P_ETD] == 1.0
    grav = dataclasses.replace(s, gravity=ab.Gravity(9.81, 0.0))
    assert pack_params(grav, spin, o)[0][P_ETD] == 0.0
    creep = dataclasses.replace(o, friction_law="creep")
    assert pack_params(s, spin, creep)[0][P_ETD] == 0.0
