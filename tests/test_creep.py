"""``options.friction_law = "creep"``: the exact stick-slip kernel with stuck balls
creeping along the slow manifold of 004's tanh law, -v_sat atanh(lambda / mu N R)
(physics/friction.py). Checked against scipy Radau on the stiff tanh law itself (the kernel's
right-hand side with F = mu N R tanh(alpha_dot / v_sat)), on a hold (closed-form jumps, cut
into creep chunks) and on a ramp (stepped), with both balls stuck and needing 55 % and 83 % of
their friction limit (004 Table 1 rig at 120 Hz, balls at 0 and 145 deg)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import autobalance as ab
from autobalance.core.rhs import CREEP_RATIO_MAX
from autobalance.core.rhs import creep_speed as creep_twin
from autobalance.models import ParameterError
from autobalance.physics.friction import creep_speed
from autobalance.simulate import simulate
from autobalance.simulate.reference import solve_reference

from conftest import vub_004
from oracles import stepped

W120 = 2 * math.pi * 120.0
START = ab.InitialState(ball_angles=(0.0, math.radians(145.0)), steady_state=True)
PROFILES = {"hold": ab.SpeedProfile.constant(W120, 2.0),
            "ramp": ab.SpeedProfile.ramp(W120, 2 * math.pi * 126.0, 2.0, 2.0)}


def _end_angles(law: str, profile, v_sat: float, holds: bool = True) -> np.ndarray:
    o = ab.SimOptions(friction_law=law, v_sat=v_sat, save_dt=0.1, rtol=1e-9, atol_scale=1e-9)
    r = stepped(vub_004(), profile, initial=START, options=o, holds=holds)
    assert r.status == "ok"
    return r.alpha[-1]


@settings(max_examples=80, deadline=None)
@given(lam=st.floats(-2.0, 2.0), lim=st.floats(0.0, 1.5), v=st.floats(1e-9, 1e-2))
def test_kernel_twin_of_the_creep_speed(lam, lim, v):
    home = float(creep_speed(lam, lim, v))
    assert creep_twin(lam, lim, v) == pytest.approx(home, rel=1e-14, abs=1e-300)


def test_creep_speed_limits():
    assert creep_speed(0.0, 1.0, 1e-6) == 0.0                  # no load, no creep
    assert creep_speed(0.5, 0.0, 1e-6) == 0.0                  # no normal force, no friction
    # friction opposes the creep: a ball needing +lambda creeps towards -alpha, odd in lambda
    assert creep_speed(0.5, 1.0, 1e-6) == pytest.approx(-1e-6 * math.atanh(0.5))
    assert creep_speed(-0.5, 1.0, 1e-6) == -creep_speed(0.5, 1.0, 1e-6)
    assert creep_speed(3.0, 1.0, 1.0) == pytest.approx(-math.atanh(CREEP_RATIO_MAX))
    # on the manifold the tanh law's friction equals the torque the ball needs
    lam, lim, v = 0.37, 0.9, 2e-6
    assert -lim * math.tanh(creep_speed(lam, lim, v) / v) == pytest.approx(lam, rel=1e-12)


@pytest.mark.parametrize("case", sorted(PROFILES))
def test_creep_follows_the_stiff_tanh_law(case):
    """Radau on the tanh law moves the stuck balls by 1.1e-4-2.3e-4 rad in 2 s at v_sat =
    1e-4 rad/s; exact stick does not move them, creep reproduces the motion to 9e-5 of it
    (measured). The tolerance, 1 % of the motion, leaves a factor 100 over the measured error
    and fails if the creep is missing, or its speed off by more than 1 %."""
    prof, v = PROFILES[case], 1e-4
    ref = solve_reference(vub_004(), prof, 2.0, initial=START, v_sat=v, t_eval=[2.0],
                          rtol=1e-9, atol=1e-12)
    assert ref.status == 0
    tanh_end = ref.y[2:4, -1]
    stick, creep = _end_angles("stick", prof, v), _end_angles("creep", prof, v)
    moved = np.abs(tanh_end - stick)
    assert moved.min() > 5e-5                                   # the tanh law really creeps
    assert np.all(np.abs(creep - tanh_end) <= 1e-2 * moved)


def test_creep_vanishes_linearly_with_v_sat_and_holds_jump_as_they_integrate():
    prof = PROFILES["hold"]
    stick = _end_angles("stick", prof, 1e-6)
    d5 = _end_angles("creep", prof, 1e-5) - stick
    d6 = _end_angles("creep", prof, 1e-6) - stick
    assert np.all(np.abs(d6) > 0) and d5 / d6 == pytest.approx([10.0, 10.0], rel=1e-3)
    # the closed-form hold, cut into creep chunks, against the same hold integrated step by step
    jumped = _end_angles("creep", prof, 1e-4)
    integ = _end_angles("creep", prof, 1e-4, holds=False)
    assert np.abs(jumped - integ).max() <= 1e-3 * np.abs(jumped - stick).min()


def test_creep_needs_stiction_equal_to_rolling_resistance():
    s = vub_004()
    b = s.balancer
    other = dataclasses.replace(s, balancer=dataclasses.replace(
        b, stiction=2 * float(b.rolling_resistance[0])))
    with pytest.raises(ParameterError) as e:
        simulate(other, PROFILES["hold"], initial=START,
                 options=ab.SimOptions(friction_law="creep"))
    assert e.value.field == "options.friction_law" and "stiction" in str(e.value)
    assert "\n" not in str(e.value)
