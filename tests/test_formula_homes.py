"""One home per formula: the compiled twins agree with their Python homes, the
kernels' fast paths come from one derivation, and one status describes every run."""
import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import autobalance as ab
from autobalance.core.hold import ball_unbalance
from autobalance.core.layout import (B_M, RunStatus, alpha_dot_slice, alpha_slice, n_q, psi_index,
                                     speed_index, state_size)
from autobalance.physics import (grade, grade_value, residual_unbalance, steady_deflection,
                                 synchronous_orbit, unbalance_for_grade)
from autobalance.simulate.pack import fast_paths, initial_vector, pack_params

from conftest import vub_004, washer_000

angles = st.lists(st.floats(-10.0, 10.0, allow_nan=False), min_size=2, max_size=2)


@settings(max_examples=60, deadline=None)
@given(a=angles, rho=st.floats(0.0, 2e-3), beta=st.floats(-np.pi, np.pi))
def test_kernel_twin_of_the_residual_unbalance(a, rho, beta):
    s = washer_000(rho=rho, beta=beta)
    b = s.balancer
    B = np.zeros((2, 8))
    B[:, B_M] = b.masses
    y = np.zeros(state_size(2))
    y[alpha_slice(2)] = a
    twin = ball_unbalance(y, B, 2, b.race_radius, rho, beta, s.rotor.unbalance)
    home = residual_unbalance(s, np.array(a))
    assert abs(twin - home) <= 1e-15 * (abs(home) + b.capacity)


def test_residual_unbalance_limits():
    s = vub_004()
    m, R, U = s.balancer.masses[0], s.balancer.race_radius, s.rotor.unbalance
    assert residual_unbalance(s, [0.0, 0.0]) == pytest.approx(U + 2 * m * R)
    assert residual_unbalance(s, [np.pi, np.pi]) == pytest.approx(U - 2 * m * R)
    # broadcast over configurations and a time-varying U
    W = residual_unbalance(s, np.zeros((4, 3, 2)), unbalance=np.full(3, 0.0))
    assert W.shape == (4, 3) and np.allclose(W, 2 * m * R)
    bare = dataclasses.replace(s, balancer=dataclasses.replace(s.balancer, n_balls=0))
    assert residual_unbalance(bare, np.zeros((5, 0))).shape == (5,)


def test_grade_homes_agree_and_invert():
    u = np.array([0.0, 1e-4, 3.19e-4])
    assert np.array_equal(grade_value(u, 16.55, 1049.3), grade(u, 16.55, 1049.3))
    assert unbalance_for_grade(grade(3.19e-4, 16.55, 1049.3), 16.55, 1049.3) == pytest.approx(3.19e-4)
    assert np.isnan(grade_value(np.nan, 1.0, 1.0))      # unchecked form: a failed run stays NaN
    with pytest.raises(ab.ParameterError, match="residual_unbalance"):
        grade(np.nan, 1.0, 1.0)


def test_steady_deflection_is_the_synchronous_orbit():
    s = vub_004()
    a = np.array([0.3, 2.0])
    W = residual_unbalance(s, a)
    for w in (100.0, 600.0, 1049.0):
        X, Y = synchronous_orbit(s, w, W)
        assert steady_deflection(s, w, a) == X
        assert Y == pytest.approx(-1j * X)                # isotropic: a circular orbit


@pytest.mark.parametrize("change, expected", [
    (lambda s, o: (s, o), (True, True, True, True, True)),
    (lambda s, o: (dataclasses.replace(s, gravity=ab.Gravity(9.81, 0.0)), o),
     (False, False, False, True, False)),
    (lambda s, o: (dataclasses.replace(s, suspension=dataclasses.replace(s.suspension, ky=6e6)), o),
     (False, False, False, False, False)),
    (lambda s, o: (dataclasses.replace(s, suspension=dataclasses.replace(s.suspension, dry_friction_force=1.0)), o),
     (False, False, False, False, False)),
    (lambda s, o: (s, dataclasses.replace(o, friction_law="tanh")),
     (False, False, False, True, True)),
    (lambda s, o: (s, dataclasses.replace(o, friction_law="creep")),
     (True, False, False, True, True)),
    (lambda s, o: (dataclasses.replace(s, rotor=dataclasses.replace(
        s.rotor, unbalance_schedule=((0.0, 3e-4), (1.0, 2e-4)))), o),
     (False, False, False, True, True)),
])
def test_fast_paths_derived_once(change, expected):
    """holds / ramps / slip jumps / isotropic / symmetric from the model; the kernels only read
    P."""
    from autobalance.core.layout import P_ETD, P_HOLDS, P_ISO, P_RAMPS, P_SYM

    s, o = change(vub_004(), ab.SimOptions())
    spin = ab.SpeedProfile.constant(600.0, 1.0)
    assert fast_paths(s, spin, o) == expected
    P, _ = pack_params(s, spin, o)
    assert tuple(bool(P[i]) for i in (P_HOLDS, P_RAMPS, P_ETD, P_ISO, P_SYM)) == expected


def test_fast_paths_motor_drive_never_holds():
    s = dataclasses.replace(vub_004(), rotor=dataclasses.replace(vub_004().rotor, polar_inertia=0.1))
    motor = ab.MotorDrive(law="constant", torque=1.0, final_speed=600.0, duration=1.0)
    assert fast_paths(s, motor, ab.SimOptions())[:2] == (False, False)


def test_state_layout_helpers_match_the_packed_state():
    s = vub_004()
    spin = ab.SpeedProfile.constant(600.0, 1.0)
    init = ab.InitialState(ball_angles=(0.5, 2.0), ball_speeds=(0.1, -0.2))
    y, order = initial_vector(s, spin, init)
    assert y.size == state_size(2) == 2 * n_q(2) == 10
    assert y[speed_index(2)] == 600.0 and y[psi_index(2)] == 0.0
    assert np.allclose(np.sort(y[alpha_slice(2)]), [0.5, 2.0])
    assert np.allclose(np.sort(y[alpha_dot_slice(2)]), [-0.2, 0.1])


def test_one_status():
    assert [RunStatus.of(c).label for c in (0, 1, 2, 3, 4, 7)] == \
        ["ok", "max_steps", "step_size_underflow", "non_finite", "running", "unknown"]
    assert RunStatus.from_label("max_steps") is RunStatus.MAX_STEPS
    assert "max_steps" in RunStatus.MAX_STEPS.message
    sim = ab.simulate(vub_004(), ab.SpeedProfile.constant(600.0, 0.2), options=ab.SimOptions(max_steps=5), throw=False)
    assert sim.status == "max_steps" and sim.message.startswith(RunStatus.MAX_STEPS.message)


@pytest.mark.parametrize("w", [100.0, 592.0, 1049.3])
def test_kernel_twin_of_the_dynamic_stiffness(w):
    """core/hold.hold_roots' static factor is 1 / dynamic_stiffness, and its roots solve
    M s^2 + (c + 2 i W M) s + (k - M W^2 + i c W) = 0 (the rotor-frame Jeffcott equation)."""
    from autobalance.core.hold import hold_roots
    from autobalance.physics import dynamic_stiffness

    s = vub_004()
    P, _ = pack_params(s, ab.SpeedProfile.constant(w, 1.0), ab.SimOptions())
    s1, s2, h = hold_roots(P, w)
    d = dynamic_stiffness(s.total_mass, s.suspension.kx, s.suspension.cx, w)
    assert h == pytest.approx(1.0 / d, rel=1e-14)
    for r in (s1, s2):
        res = s.total_mass * r * r + (s.suspension.cx + 2j * w * s.total_mass) * r + d
        assert abs(res) <= 1e-9 * abs(d)


def test_profile_kinds_registry_and_schema_agree():
    """One registry of profile kinds (models) and the config schema's keys for each kind."""
    import inspect

    from autobalance.config import PROFILE_KINDS as SCHEMA
    from autobalance.models import PROFILE_KINDS

    assert set(PROFILE_KINDS) == set(SCHEMA)
    for kind, ctor in PROFILE_KINDS.items():
        params = set(inspect.signature(ctor).parameters) - {"self"}
        assert set(SCHEMA[kind]) <= params, (kind, set(SCHEMA[kind]) - params)


@settings(max_examples=60, deadline=None)
@given(n=st.sampled_from([1, 2]), c1=st.floats(0.1, 2.0), c2=st.floats(0.1, 2.0),
       s1=st.floats(0.0, 1.6), s2=st.floats(0.0, 1.6), seed=st.integers(0, 2 ** 16))
def test_compiled_twin_of_the_circle_test(n, c1, c2, s1, s2, seed):
    """core/worst_case.row_min_distance against physics/reachable_set._arcs_distance (the home) on
    random required moments: the same row minima (identical operations, scalar order)."""
    from autobalance.core.worst_case import N_ARCS, row_min_distance
    from autobalance.physics.reachable_set import _arcs_distance

    rng = np.random.default_rng(seed)
    t0 = (rng.normal(size=(3, 64)) + 1j * rng.normal(size=(3, 64))) * (c1 + c2)
    shift = complex(rng.normal(), rng.normal())
    c = np.array([c1, c2][:n])
    s = np.array([s1, s2][:n])
    home = _arcs_distance((t0 + shift).ravel(), c, s).reshape(t0.shape).min(axis=1)
    twin = np.empty(3)
    row_min_distance(t0, shift, n, c1, c2 if n == 2 else 0.0, s1, s2 if n == 2 else 0.0,
                     np.empty((N_ARCS, 11)), twin)
    assert np.allclose(twin, home, rtol=1e-12, atol=1e-14 * (c1 + c2))


def test_residual_bound_is_the_same_with_the_twin():
    """The whole bound (scan and bisection) with the twin and with the home: the same figures."""
    import autobalance.physics.reachable_set as rs
    from autobalance.physics.worst_case import residual_bound

    s = washer_000(rho=1e-4, beta=0.3)
    try:
        rs.COMPILED_GAP = False
        home = residual_bound(s, 104.7, rolling_resistance=2e-3, n_theta=256, n_beta=6)
        rs.COMPILED_GAP = True
        twin = residual_bound(s, 104.7, rolling_resistance=2e-3, n_theta=256, n_beta=6)
    finally:
        rs.COMPILED_GAP = True
    assert twin["worst_residual_kg_m"] == pytest.approx(home["worst_residual_kg_m"], rel=1e-9)
    assert twin["separated"] == home["separated"]
