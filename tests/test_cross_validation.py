"""Independent implementations that must agree.

000's vibratory force (eq 8, 10-11, 39-43; physics/vibratory.py, from the harmonic response)
is the revolution average of the tangential force the full equations of motion put on a fixed
ball (our Lagrangian kernel, core/rhs.py). With the balls held by friction, the friction each
ball needs is lambda_i(t) = -R F_i*(t), so <lambda_i> over one revolution at steady state must
be -R F_i: for an anisotropic suspension (the 2 Omega content averages out) and with race
eccentricity.
"""
import numpy as np
from scipy.integrate import trapezoid
import pytest

import autobalance as ab
from autobalance.physics.vibratory import vibratory_forces
from autobalance.simulate.pack import pack_params, spin_arrays
from autobalance.core.rhs import rhs
from autobalance.core.work import rhs_work

from conftest import RPM, washer_000


@pytest.mark.parametrize("angles", [(1.0, 4.0), (2.5, -2.0), (0.3, 2.0)])
def test_vibratory_force_is_the_revolution_average_of_the_kernel_force(angles):
    W = 1000 * RPM
    s = washer_000(Me=0.025, g=0.0, f_r=1.0, rho=2e-4, beta=0.7)   # f/r = 1 (the largest allowed): balls stay put
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
    dy, rw = np.zeros(2 * nq), rhs_work(N)
    lam = rw[0]
    k = sim.t >= 6.0 - 2 * np.pi / W - 1e-12          # the last revolution (transient < 1e-9)
    lams = []
    for y, t in zip(sim.states[k], sim.t[k]):
        rhs(t, y.copy(), P, B, N, 0, (pt, pw, ut, uu), (stuck, sgn, spin), dy, rw)
        lams.append(lam[:N].copy())
    avg = trapezoid(np.array(lams), sim.t[k], axis=0) / (sim.t[k][-1] - sim.t[k][0])
    F = vibratory_forces(s, W, np.array(sim.alpha[-1]))
    assert avg == pytest.approx(-s.balancer.race_radius * F, rel=1e-6)


@pytest.mark.parametrize("law", ["stick", "tanh"])
@pytest.mark.parametrize("n, rho, g", [(2, 0.0, 0.0), (3, 2e-4, 9.81)])
def test_prescribed_spin_solve_equals_dense_solve_of_the_mass_matrix(law, n, rho, g):
    """With a prescribed spin, rhs eliminates the slipping balls through a 2x2 Schur complement
    (the balls couple only to the rotor). Its accelerations and the stuck balls' friction must be
    those of a dense solve of the kernel's own mass-matrix rows (left in the work arrays Mm, fv),
    for random states and stick/slip modes, on a ramp (psi'' != 0), anisotropic, with race
    eccentricity and gravity."""
    rng = np.random.default_rng(7)
    s = washer_000(n=n, rho=rho, beta=0.7, g=g, f_r=0.05)
    opts = ab.SimOptions(friction_law=law)
    prof = ab.SpeedProfile((0.0, 10.0), (0.0, 150.0))
    P, B = pack_params(s, prof, opts)
    pt, pw, _ = spin_arrays(prof)
    ut, uu = s.rotor.unbalance_table()
    nq = n + 3
    ip = nq - 1
    spin = np.zeros(2)
    dy, rw = np.zeros(2 * nq), rhs_work(n)
    lam, Mm, fv = rw[:3]
    for _ in range(50):
        t = rng.uniform(0.5, 9.5)
        y = np.concatenate([rng.normal(0, 1e-3, 2), np.sort(rng.uniform(0, 6.0, n)),
                            [rng.uniform(0, 50)], rng.normal(0, 0.1, 2), rng.normal(0, 2.0, n),
                            [15.0 * t]])
        stuck = rng.integers(0, 2, n).astype(np.int64)
        sgn = rng.choice([-1.0, 1.0], n)
        assert rhs(t, y, P, B, n, 0, (pt, pw, ut, uu), (stuck, sgn, spin), dy, rw)
        psidd = dy[nq + ip]
        assert psidd == pytest.approx(15.0)
        free = [0, 1] + [2 + i for i in range(n) if law == "tanh" or stuck[i] == 0]
        M = np.zeros((nq, nq))
        M[:2, :] = Mm[:2, :]
        M[2:ip, :] = Mm[2:ip, :]
        for i in range(n):          # ball-ball entries are zero, M is symmetric
            M[2 + i, 2:ip] = 0.0
            M[2 + i, 2 + i] = Mm[2 + i, 2 + i]
        M[:2, 2:ip] = M[2:ip, :2].T
        M[0, 1] = M[1, 0] = 0.0
        x = np.linalg.solve(M[np.ix_(free, free)], fv[free] - M[free, ip] * psidd)
        qdd = np.zeros(nq)
        qdd[free] = x
        qdd[ip] = psidd
        assert dy[nq:] == pytest.approx(qdd, rel=1e-10, abs=1e-12 * np.abs(qdd).max())
        for i in range(n):
            if law == "stick" and stuck[i] == 1:
                k = 2 + i
                assert lam[i] == pytest.approx(M[k] @ qdd - fv[k], rel=1e-9,
                                               abs=1e-12 * np.abs(fv).max())
                assert dy[k] == 0.0 and dy[nq + k] == 0.0
