"""Evaluations of the compiled right-hand side at a chosen state, to check closed forms against
the kernel (e.g. 004's immobility in :mod:`autobalance.physics.immobility`)."""
from __future__ import annotations

import numpy as np

__all__ = ["kernel_required_friction"]


def kernel_required_friction(system, speed, alpha):
    """Friction torque [N m] each stuck ball needs and its static limit mu_s N R [N m], from the
    compiled kernel (core/rhs.py, exact stick-slip branch) with both balls stuck, the rotor on its
    steady orbit (physics/response.steady_orbit_start) at constant speed. Also returns the rotor-frame
    accelerations (u'', v'') [m/s^2], zero on the steady orbit. Used to check the closed form
    (:func:`autobalance.physics.immobility.immobile_mask`, 004 eq 1 against mu_s N).

    Parameters
    ----------
    system : System
        The machine (isotropic suspension for the steady orbit to be stationary).
    speed : float
        Constant spin speed [rad/s].
    alpha : array_like
        Ball angles from the unbalance [rad], one per ball.

    Returns
    -------
    required : ndarray (N,)
        Friction torque each stuck ball needs [N*m], in the user's ball order.
    limit : ndarray (N,)
        Its static limit mu_s N R [N*m].
    accel : ndarray (2,)
        Rotor-frame accelerations (u'', v'') [m/s^2].
    """
    from ..core.layout import P_FLAW, n_q, speed_index
    from ..physics.response import steady_orbit_start
    from .pack import pack_params, spin_arrays
    from ..core.rhs import profile_segment, rhs
    from ..models import SimOptions, SpeedProfile

    spin = SpeedProfile.constant(float(speed), 1.0)
    P, B = pack_params(system, spin, SimOptions(friction_law="stick"))
    P[P_FLAW] = 0.0
    N = system.balancer.n_balls
    nq = n_q(N)
    a = np.asarray(alpha, float)
    x, y, vx, vy = steady_orbit_start(system, float(speed), a)
    order = np.argsort(np.mod(a, 2 * np.pi))
    st = np.zeros(2 * nq)
    st[0], st[1] = x, y                         # psi = 0: rotor frame = inertial frame
    st[nq], st[nq + 1] = vx + speed * y, vy - speed * x
    st[2:2 + N] = np.mod(a[order], 2 * np.pi)
    st[speed_index(N)] = speed
    prof_t, prof_w, _ = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    dy, lam = np.zeros(2 * nq), np.zeros(3 * N + 1)
    Mm, A = np.zeros((nq, nq)), np.zeros((nq, nq))
    fv, bb, idx = np.zeros(nq), np.zeros(nq), np.zeros(nq, dtype=np.int64)
    rhs(0.0, st, P, B, N, profile_segment(0.0, prof_t), prof_t, prof_w, unb_t, unb_u,
        np.ones(N, dtype=np.int64), np.ones(N), np.array([0.0, 0.0]), dy, lam, Mm, fv, A, bb, idx)
    inv = np.argsort(order)
    return lam[:N][inv], lam[N:2 * N][inv], dy[nq:nq + 2]
