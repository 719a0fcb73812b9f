"""Tier 1: closed-form limits of the rotor/balancer model.

- Jeffcott rotor (textbook; 004 sec. 2.2): a = U w^2 / |k - M_t w^2 + i c w|, phase lag
  atan2(c w, k - M_t w^2); per axis for an anisotropic suspension (000 eq 6-7).
- Ideal balancer (no friction): above both natural frequencies two equal balls settle at
  +-arccos(-U / (2 m R)) and the vibration vanishes; below them they go to the heavy side; with
  U > N m R they sit opposite the unbalance (000 p.5, "Me < mR N"; 004 sec. 2.2).
"""
import numpy as np
import pytest

import autobalance as ab
from autobalance.physics.response import axis_response
from autobalance.simulate import simulate

from conftest import vub_004, washer_000


@pytest.mark.parametrize("f_hz", [40.0, 90.0, 94.2, 100.0, 167.0])
def test_jeffcott_amplitude_and_phase(f_hz):
    s = vub_004(n=0)
    W = 2 * np.pi * f_hz
    tight = ab.SimOptions(save_dt=-1, rtol=1e-10, atol_scale=1e-10)
    sim = simulate(s, ab.SpeedProfile.constant(W, 0.4), options=tight)
    amp, lag = axis_response(s.total_mass, 5.8e6, 1510.0, s.rotor.unbalance, W)
    # 0.4 s = 18 decay times 1/(zeta w_n): the start-up transient is below 1e-7 of the response
    assert sim.amplitude[-1] == pytest.approx(amp, rel=1e-6)
    assert np.angle(sim.u[-1] + 1j * sim.v[-1]) == pytest.approx(-lag, abs=1e-6)


def test_anisotropic_axes_follow_000_eq_6_7():
    """Washer without balls at 1000 rpm: x and y amplitudes and phases per axis."""
    s = washer_000(n=0, g=0.0)
    W = 1000 * 2 * np.pi / 60
    sim = simulate(s, ab.SpeedProfile.constant(W, 8.0), options=ab.SimOptions(save_dt=2e-4))
    late = sim.t > 7.0
    ax, _ = axis_response(s.total_mass, 20e3, 200.0, 0.025, W)
    ay, _ = axis_response(s.total_mass, 6e3, 110.0, 0.025, W)
    assert np.abs(sim.x[late]).max() == pytest.approx(ax, rel=2e-3)
    assert np.abs(sim.y[late]).max() == pytest.approx(ay, rel=2e-3)


def test_two_balls_settle_at_arccos_and_vibration_vanishes():
    s = vub_004(mu=0.0)
    W = 2 * np.pi * 130.0
    sim = simulate(s, ab.SpeedProfile.constant(W, 15.0),
                   initial=ab.InitialState(ball_angles=(0.3, 1.2), steady_state=True))
    target = np.arccos(-s.rotor.unbalance / (2 * 0.0076 * 0.035))
    a = np.sort(np.angle(np.exp(1j * sim.alpha[-1])))
    assert a == pytest.approx([-target, target], abs=1e-4)
    assert sim.amplitude[-1] < 1e-6 * s.rotor.unbalance / s.total_mass * 1e3
    assert sim.grade_G[-1] < 1e-3


def test_anisotropic_washer_balls_settle_at_120_deg():
    """000 eq 28: mR = Me per ball -> alpha_f = +-120 deg at 1000 rpm (above both resonances)."""
    s = washer_000(g=0.0, c_i=7.0)
    sim = simulate(s, ab.SpeedProfile.constant(1000 * 2 * np.pi / 60, 20.0),
                   initial=ab.InitialState(ball_angles=(np.radians(90), np.radians(150)),
                                           steady_state=True))
    a = np.sort(np.degrees(np.angle(np.exp(1j * sim.alpha[-1]))))
    assert a == pytest.approx([-120.0, 120.0], abs=0.05)
    assert sim.amplitude[-1] < 1e-4 * 0.025 / 37.0


def _pair_centre(s, W, guess):
    """Touching pair at gamma +- delta/2 is in equilibrium when the rotor deflection points at
    gamma (004 eq 1 summed over the pair: 2 m z W^2 sin(arg w - gamma) cos(delta/2) = 0), with
    w = W^2 (U + 2 m R cos(delta/2) e^{i gamma}) / (k - M_t W^2 + i c W) (Jeffcott)."""
    from scipy.optimize import brentq
    b = s.balancer
    mR = b.masses[0] * b.race_radius * np.cos(b.contact_angle / 2)
    H = 1.0 / (s.suspension.kx - s.total_mass * W**2 + 1j * s.suspension.cx * W)

    def f(g):
        w = W**2 * (s.rotor.unbalance + 2 * mR * np.exp(1j * g)) * H
        return np.sin(np.angle(w) - g)
    return brentq(f, guess - 0.5, guess + 0.5)


def test_below_resonance_balls_go_to_heavy_side():
    s = vub_004(mu=0.0)
    W = 2 * np.pi * 60.0          # below 94.2 Hz
    sim = simulate(s, ab.SpeedProfile.constant(W, 40.0),
                   initial=ab.InitialState(ball_angles=(1.0, -1.2), steady_state=True))
    a = np.angle(np.exp(1j * sim.alpha[-1]))
    gamma = _pair_centre(s, W, 0.0)
    assert abs(gamma) < 0.5                     # the heavy side, shifted by the phase lag
    assert a.mean() == pytest.approx(gamma, abs=1e-3)
    G0 = s.rotor.unbalance / s.total_mass * 1e3 * W
    assert sim.grade_G[-1] > 2.5 * G0           # the balancer adds to the unbalance


def test_unbalance_beyond_capacity_balls_opposite():
    s = vub_004(mu=0.0, unbalance=3 * 2 * 0.0076 * 0.035)   # U = 3 x N m R
    W = 2 * np.pi * 150.0
    sim = simulate(s, ab.SpeedProfile.constant(W, 20.0),
                   initial=ab.InitialState(ball_angles=(0.5, 1.5), steady_state=True))
    a = np.mod(sim.alpha[-1], 2 * np.pi)
    gamma = _pair_centre(s, W, np.pi)
    assert abs(gamma - np.pi) < 0.2             # opposite the unbalance, up to the phase lag
    assert a.mean() == pytest.approx(gamma, abs=1e-3)
    assert a[1] - a[0] == pytest.approx(s.balancer.contact_angle, abs=1e-3)   # touching
    res = abs(s.rotor.unbalance + 2 * 0.0076 * 0.035 * np.cos(s.balancer.contact_angle / 2)
              * np.exp(1j * gamma))
    assert sim.residual_unbalance[-1] == pytest.approx(res, rel=1e-3)


def test_steady_state_start_has_no_transient():
    s = washer_000(n=0, g=0.0)
    W = 1000 * 2 * np.pi / 60
    sim = simulate(s, ab.SpeedProfile.constant(W, 2.0),
                   initial=ab.InitialState(steady_state=True), options=ab.SimOptions(save_dt=2e-4))
    ax, _ = axis_response(s.total_mass, 20e3, 200.0, 0.025, W)
    assert np.abs(sim.x).max() == pytest.approx(ax, rel=2e-3)
