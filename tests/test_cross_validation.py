"""Independent implementations that must agree.

000's vibratory force (eq 8, 10-11, 39-43; analysis/vibratory.py, from the harmonic response)
is the revolution average of the tangential force the full equations of motion put on a fixed
ball (our Lagrangian kernel, core/rhs.py). With the balls held by friction, the friction each
ball needs is lambda_i(t) = -R F_i*(t), so <lambda_i> over one revolution at steady state must
be -R F_i: for an anisotropic suspension (the 2 Omega content averages out) and with race
eccentricity.
"""
import numpy as np
import pytest

import autobalance as ab
from autobalance.analysis.vibratory import vibratory_forces
from autobalance.core.pack import pack_params, spin_arrays
from autobalance.core.rhs import rhs

from conftest import RPM, washer_000


@pytest.mark.parametrize("angles", [(1.0, 4.0), (2.5, -2.0), (0.3, 2.0)])
def test_vibratory_force_is_the_revolution_average_of_the_kernel_force(angles):
    W = 1000 * RPM
    s = washer_000(Me=0.025, g=0.0, f_r=5.0, rho=2e-4, beta=0.7)   # f/r = 5: balls stay put
    opts = ab.SimOptions(save_dt=1e-4, normal_force="drum", rtol=1e-10, atol_scale=1e-10)
    prof = ab.SpeedProfile.constant(W, 6.0)
    sim = ab.simulate(s, prof, initial=ab.InitialState(ball_angles=angles, steady_state=True),
                      options=opts)
    assert np.all(sim.alpha_dot[-1] == 0.0)
    P, B = pack_params(s, prof, opts)
    pt, pw, _ = spin_arrays(prof)
    ut, uu = s.rotor.unbalance_table()
    N, nq = 2, 5
    stuck, sgn, spin = np.ones(N, np.int64), np.ones(N), np.zeros(2)
    dy, lam = np.zeros(2 * nq), np.zeros(3 * N + 1)
    Mm, A = np.zeros((nq, nq)), np.zeros((nq, nq))
    fv, bb, idx = np.zeros(nq), np.zeros(nq), np.zeros(nq, np.int64)
    k = sim.t >= 6.0 - 2 * np.pi / W - 1e-12          # the last revolution (transient < 1e-9)
    lams = []
    for y, t in zip(sim.states[k], sim.t[k]):
        rhs(t, y.copy(), P, B, N, 0, pt, pw, ut, uu, stuck, sgn, spin, dy, lam, Mm, fv, A, bb, idx)
        lams.append(lam[:N].copy())
    avg = np.trapezoid(np.array(lams), sim.t[k], axis=0) / (sim.t[k][-1] - sim.t[k][0])
    F = vibratory_forces(s, W, np.array(sim.alpha[-1]))
    assert avg == pytest.approx(-s.balancer.race_radius * F, rel=1e-6)
