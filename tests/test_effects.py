"""Each effect of the model against a closed form or an exact equilibrium condition."""
import numpy as np
import pytest
from scipy.optimize import brentq

import autobalance as ab
from autobalance.simulate import simulate

from conftest import RPM


def test_base_excitation_transmissibility():
    """No unbalance, no balls, base motion x_b = X cos(w t): |x|/X = sqrt(k^2 + (c w)^2) /
    sqrt((k - M w^2)^2 + (c w)^2) (textbook base excitation); y stays at rest."""
    X, wb = 1e-3, 30.0
    s = ab.System(ab.Rotor(37.0, 0.0),
                  ab.Suspension(kx=20e3, ky=6e3, cx=200.0, cy=110.0, base_amplitude_x=X,
                                base_frequency=wb))
    sim = simulate(s, ab.SpeedProfile.constant(100.0, 10.0), options=ab.SimOptions(save_dt=1e-3))
    late = sim.t > 9.0
    T = np.hypot(20e3, 200.0 * wb) / np.hypot(20e3 - 37.0 * wb**2, 200.0 * wb)
    assert np.abs(sim.x[late]).max() == pytest.approx(T * X, rel=2e-3)
    # y is not excited; what remains is integration error coupled through the rotor frame
    assert np.abs(sim.y[late]).max() < 1e-4 * X


def test_race_eccentricity_shifts_the_ball_000_eq_45():
    """One ball with mR = Me on an isotropic suspension well above resonance, race offset rho at
    beta = pi/2. Exact frictionless equilibrium (ball row of the model at steady state):
    Im(e^{-i a} w) = rho sin(a - beta), w = W^2 H(W) (U + m R e^{ia} + m rho e^{i beta});
    000 eq 45 approximates the shift from pi as -rho sin(beta) / (e + rho cos(beta))."""
    M, U, R, rho, beta = 37.0, 0.05, 0.28, 1e-4, np.pi / 2
    m = U / R
    W = 1000 * RPM
    s = ab.System(ab.Rotor(M, U), ab.Suspension.isotropic(20e3, 200.0),
                  ab.BallBalancer(1, m, R, 0.014, element="point", damping=7.0 * m * R * R,
                                  eccentricity=rho, eccentricity_angle=beta))
    sim = simulate(s, ab.SpeedProfile.constant(W, 30.0),
                   initial=ab.InitialState(ball_angles=(np.pi - 0.3,), steady_state=True),
                   options=ab.SimOptions(save_dt=-1))
    H = 1 / (20e3 - s.total_mass * W**2 + 1j * 200.0 * W)

    def g(a):
        w = W**2 * H * (U + m * R * np.exp(1j * a) + m * rho * np.exp(1j * beta))
        return np.imag(np.exp(-1j * a) * w) - rho * np.sin(a - beta)
    a_exact = brentq(g, np.pi - 0.5, np.pi + 0.5)
    a_sim = np.mod(sim.alpha[-1, 0], 2 * np.pi)
    assert a_sim == pytest.approx(a_exact, abs=1e-6)
    e = U / M
    eq45 = -rho * np.sin(beta) / (e + rho * np.cos(beta))
    assert a_sim - np.pi == pytest.approx(eq45, rel=0.1)   # eq 45 neglects damping and M_t


def test_balls_follow_a_time_varying_unbalance():
    """000 'variable unbalance': U drops by 30 % (water extraction); frictionless balls move from
    +-arccos(-U0/2mR) to +-arccos(-U1/2mR)."""
    m, R, U0 = 0.0076, 0.035, 3.19e-4
    U1 = 0.7 * U0
    s = ab.System(ab.Rotor(16.53, U0, unbalance_schedule=((0.0, U0), (2.0, U0), (4.0, U1))),
                  ab.Suspension.isotropic(5.8e6, 1510.0),
                  ab.BallBalancer(2, m, R, 0.00614, element="point", damping=2.7e-3))
    a0 = np.arccos(-U0 / (2 * m * R))
    sim = simulate(s, ab.SpeedProfile.constant(2 * np.pi * 130, 25.0),
                   initial=ab.InitialState(ball_angles=(a0, -a0), steady_state=True),
                   options=ab.SimOptions(save_dt=0.01))
    a1 = np.arccos(-U1 / (2 * m * R))
    k2 = np.argmin(np.abs(sim.t - 2.0))
    assert np.abs(np.abs(np.angle(np.exp(1j * sim.alpha[k2]))) - a0).max() < 1e-3   # balanced
    assert np.sort(np.angle(np.exp(1j * sim.alpha[-1]))) == pytest.approx([-a1, a1], abs=1e-4)
    assert sim.residual_unbalance[-1] < 1e-4 * U1


@pytest.mark.parametrize("U,stuck", [(0.003, True), (0.05, False)])
def test_suspension_dry_friction_000_eq_48(U, stuck):
    """000 eq 48: with two friction dampers (F = 70 N each at gamma = 61 deg, Fig. 18) the tub
    cannot move while the unbalance force U W^2 stays below 2 F cos(gamma) = 68 N (x) and
    2 F sin(gamma) = 122 N (y). At 1000 rpm: U = 0.003 kg m (33 N) -> held (regularised law:
    residual creep ~ v_s / W = 1 um); U = 0.05 kg m (548 N) -> moves nearly freely (above
    resonance the response is mass-controlled, e = U / M)."""
    s = ab.System(ab.Rotor(37.0, U),
                  ab.Suspension(kx=20e3, ky=6e3, cx=200.0, cy=110.0, dry_friction_force=70.0,
                                dry_friction_angle=np.radians(61)))
    W = 1000 * RPM
    sim = simulate(s, ab.SpeedProfile.constant(W, 6.0), options=ab.SimOptions(save_dt=2e-3))
    late = sim.t > 5.0
    free = U / s.total_mass
    amp = np.abs(sim.amplitude[late]).max()
    if stuck:
        assert amp < 0.05 * free
    else:
        assert amp == pytest.approx(free, rel=0.15)
