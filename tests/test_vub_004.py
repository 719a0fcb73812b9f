"""Tier 2: seed 004 (Van De Velde et al., temporary speed reduction) - Table 1 rig.

Published: resonance 94.2 Hz; initial unbalance eps = 19.3 um is G20 at 167 Hz; total ball
unbalance G34 (sec. 4.3, 4.6). Exact stick-slip vs 004's tanh law (v_sat = 1e-6 rad/s) solved by
scipy Radau on the same equations.
"""
import numpy as np
import pytest

import autobalance as ab
from autobalance.config import load_config
from autobalance.simulate.reference import solve_reference
from autobalance.physics.iso1940 import grade_value as grade_G
from autobalance.simulate import simulate

from conftest import vub_004


@pytest.fixture(scope="module")
def cfg():
    return load_config("vub_jeffcott_004")


def test_preset_resonance_94_2_hz(cfg):
    wx, wy = cfg.system.natural_frequencies
    assert wx / (2 * np.pi) == pytest.approx(94.2, abs=0.05)


def test_simulated_slow_sweep_peaks_at_the_damped_resonance(cfg):
    """Slow ramp 80 -> 110 Hz in 60 s without balls: the amplitude peak is at the damped peak
    w_n / sqrt(1 - 2 zeta^2) = 94.8 Hz (zeta = 0.0776), delayed by < 0.2 Hz by the sweep."""
    s = ab.System(cfg.system.rotor, cfg.system.suspension)
    prof = ab.SpeedProfile.ramp(2 * np.pi * 80, 2 * np.pi * 110, 60.0, 60.0)
    sim = simulate(s, prof, options=ab.SimOptions(save_dt=5e-3))
    f_peak = sim.speed[np.argmax(sim.amplitude)] / (2 * np.pi)
    zeta = 1510.0 / (2 * np.sqrt(5.8e6 * s.total_mass))
    f_damped = np.sqrt(5.8e6 / s.total_mass) / np.sqrt(1 - 2 * zeta**2) / (2 * np.pi)
    assert f_peak == pytest.approx(f_damped, abs=0.25)
    assert f_peak == pytest.approx(94.2, abs=1.0)


def test_initial_unbalance_is_g20_and_balls_are_g34(cfg):
    s, w = cfg.system, cfg.spin.nominal_speed
    assert w / (2 * np.pi) == pytest.approx(167.0)
    # grade of the rotor alone (balls cancelling each other: opposite positions)
    sim = simulate(s, cfg.spin, initial=ab.InitialState(ball_angles=(np.pi / 2, -np.pi / 2)),
                   options=ab.SimOptions(save_dt=-1, max_steps=1), throw=False)
    assert sim.grade_G[0] == pytest.approx(20.0, abs=0.5)
    assert grade_G(s.balancer.capacity, s.total_mass, w) == pytest.approx(34.0, abs=0.5)


@pytest.mark.slow
def test_exact_stick_agrees_with_tanh_law_radau():
    """100 Hz (just above resonance), balls released near the heavy side: ball 1 slides ~115 deg,
    ball 2 slips and sticks after 0.3 deg. Radau on 004's tanh law (v_sat = 1e-6 rad/s) and our
    exact switch model agree to 0.01 deg and 1e-4 relative amplitude over 0.5 s."""
    s = vub_004()
    prof = ab.SpeedProfile.constant(2 * np.pi * 100.0, 0.5)
    ini = ab.InitialState(ball_angles=(np.radians(20), np.radians(60)), steady_state=True)
    sim = simulate(s, prof, initial=ini, options=ab.SimOptions(save_dt=0.01, rtol=1e-9, atol_scale=1e-9))
    ref = solve_reference(s, prof, 0.5, initial=ini, t_eval=sim.t, rtol=1e-8, atol=1e-12)
    assert ref.status == 0
    assert np.abs(np.degrees(sim.alpha - ref.y[2:4].T)).max() < 0.01
    amp_ref = np.hypot(ref.y[0], ref.y[1])
    assert np.abs(sim.amplitude - amp_ref).max() < 1e-4 * amp_ref.max()
    assert np.degrees(sim.alpha[-1, 0] - sim.alpha[0, 0]) < -100    # ball 1 really moved
    assert sim.alpha_dot[-1, 1] == 0.0                              # ball 2 stuck (exact)


def test_tsr_run_reports_both_checkpoints(cfg):
    sim = simulate(cfg.system, cfg.spin, initial=cfg.initial)
    S = sim.summary()
    assert S["status"] == "ok"
    assert [c["time_s"] for c in S["checkpoints"]] == pytest.approx([18.0, 90.0])
    for c in S["checkpoints"]:
        assert 0.0 <= c["grade_G_mm_s"] <= 20.3 + 33.8 + 0.1     # within the operating bounds
    assert S["max_amplitude_m"] > 5 * S["final"]["amplitude_m"]   # resonance crossed


def test_kernel_equals_004_eq_8_10_transcription(rng):
    """Our general right-hand side reduces to 004 eq (8)-(10) (transcribed literally in NumPy in
    core/reference.py) for the Jeffcott rig: random states, run-up (psi'' != 0) and hold."""
    from autobalance.simulate.reference import make_rhs, paper_004_rhs
    s = vub_004()
    prof = ab.SpeedProfile((0.0, 10.0, 20.0), (0.0, 900.0, 900.0))
    fk = make_rhs(s, prof, v_sat=1e-3)
    fp = paper_004_rhs(s, prof, v_sat=1e-3)
    for _ in range(50):
        y = np.zeros(10)
        y[0:2] = rng.normal(0, 5e-5, 2)
        y[2:4] = np.sort(rng.uniform(0, 2 * np.pi, 2))
        y[5:7] = rng.normal(0, 0.05, 2)
        y[7:9] = rng.normal(0, 2.0, 2)
        t = rng.uniform(0, 19.9)
        y[9] = prof.speed(t)
        if abs(np.angle(np.exp(1j * (y[3] - y[2])))) < s.balancer.contact_angle:
            continue   # contact forces are ours, not 004's
        a, b = fk(t, y), fp(t, y)
        assert np.allclose(a, b, rtol=1e-9, atol=1e-12 * np.abs(b).max())
