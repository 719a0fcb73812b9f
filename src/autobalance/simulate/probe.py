"""Evaluations of the compiled right-hand side at a chosen state, to check closed forms against
the kernel (e.g. 004's immobility in :mod:`autobalance.physics.immobility`)."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = ["kernel_required_friction", "rotor_frame_derivative"]


def kernel_required_friction(system: System, speed: float, alpha: npt.ArrayLike,
                             phase: float = 0.0) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
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
    phase : float
        The spin angle psi [rad] (where in-plane gravity points in the rotor frame; the
        deflection is the kernel's, from the static equilibrium).

    Returns
    -------
    required : ndarray (N,)
        Friction torque each stuck ball needs [N*m], in the user's ball order.
    limit : ndarray (N,)
        Its static limit mu_s N R [N*m].
    accel : ndarray (2,)
        Rotor-frame accelerations (u'', v'') [m/s^2].
    """
    from ..core.layout import P_FLAW, alpha_slice, n_q, psi_index, speed_index
    from ..physics.response import steady_orbit_start
    from .pack import pack_params, spin_arrays
    from ..core.rhs import profile_segment, rhs
    from ..core.work import rhs_work
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
    st[alpha_slice(N)] = np.mod(a[order], 2 * np.pi)
    st[speed_index(N)] = speed
    st[psi_index(N)] = float(phase)
    prof_t, prof_w, _ = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    dy, rw = np.zeros(2 * nq), rhs_work(N)
    lam = rw[0]
    rhs(0.0, st, P, B, N, profile_segment(0.0, prof_t), (prof_t, prof_w, unb_t, unb_u),
        (np.ones(N, dtype=np.int64), np.ones(N), np.array([0.0, 0.0])), dy, rw)
    inv = np.argsort(order)
    return lam[:N][inv], lam[N:2 * N][inv], dy[nq:nq + 2]


def rotor_frame_derivative(system: System, speed: float, states: npt.ArrayLike,
                           liquid_moment: tuple[complex, complex] = (0j, 0j),
                           phase: float = 0.0) -> np.ndarray:
    """Time derivative of rotor-frame states at constant spin speed, from the compiled kernel
    (core/rhs.py, every ball free to roll): the right-hand side whose Jacobian is the linearised
    full model about a steady state (autobalance.studies.equilibria).

    A state is z = (u, v, alpha_1..N, u', v', alpha_1'..N') with psi = ``phase`` and psi' =
    speed held (the kernel's held-speed mode). The balls are passed to the kernel in angular order and the
    derivatives returned in the caller's order. Friction enters as the kernel computes it for
    sliding balls (sign +1 of sliding); pass a system without rolling resistance for a smooth
    right-hand side.

    Parameters
    ----------
    system : System
        The machine.
    speed : float
        Constant spin speed [rad/s].
    states : array_like (K, 2N + 4) or (2N + 4,)
        Rotor displacement [m], ball angles [rad], their rates [m/s], [rad/s].
    liquid_moment : (complex, complex)
        A liquid's moment U [kg*m] and its rate U' [kg*m/s] (rotor frame), held as the run of
        balls beside a liquid holds them over a coupling step (core/hybrid.py): the chamber
        feels W^2 U - 2 i W U'. The system itself has no ``[liquid]`` (its mass in the rotor's,
        :func:`autobalance.liquid.start.pool_machine`).
    phase : float
        The spin angle psi [rad] at which to evaluate: where in-plane gravity points in the
        rotor frame (0: the rotor frame is the inertial frame; no effect without gravity).

    Returns
    -------
    ndarray, the shape of ``states``
        dz/dt [m/s, rad/s, m/s^2, rad/s^2].
    """
    from ..core.layout import (P_LQDX, P_LQDY, P_LQX, P_LQY, alpha_dot_slice, alpha_slice, n_q,
                               psi_index, speed_index)
    from ..core.rhs import profile_segment, rhs
    from ..core.work import rhs_work
    from ..models import SimOptions, SpeedProfile
    from .pack import pack_params, spin_arrays

    w = float(speed)
    spin = SpeedProfile.constant(w, 1.0)
    P, B = pack_params(system, spin, SimOptions(friction_law="stick"))
    P[P_LQX], P[P_LQY] = complex(liquid_moment[0]).real, complex(liquid_moment[0]).imag
    P[P_LQDX], P[P_LQDY] = complex(liquid_moment[1]).real, complex(liquid_moment[1]).imag
    N = system.balancer.n_balls
    nq = n_q(N)
    Z = np.atleast_2d(np.asarray(states, float))
    prof_t, prof_w, _ = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    seg = profile_segment(0.0, prof_t)
    dy, rw = np.zeros(2 * nq), rhs_work(N)
    held = np.array([2.0, w])
    out = np.empty_like(Z)
    for k, z in enumerate(Z):
        a = np.mod(z[2:2 + N], 2 * np.pi)
        order = np.argsort(a)
        y = np.zeros(2 * nq)
        y[0], y[1] = z[0], z[1]
        y[alpha_slice(N)] = a[order]
        y[nq], y[nq + 1] = z[N + 2], z[N + 3]
        y[alpha_dot_slice(N)] = z[N + 4:][order]
        y[psi_index(N)] = float(phase)
        y[speed_index(N)] = w
        rhs(0.0, y, P, B, N, seg, (prof_t, prof_w, unb_t, unb_u),
            (np.zeros(N, dtype=np.int64), np.ones(N), held), dy, rw)
        inv = np.argsort(order)
        out[k, :2] = dy[:2]
        out[k, 2:2 + N] = dy[alpha_slice(N)][inv]
        out[k, N + 2:N + 4] = dy[nq:nq + 2]
        out[k, N + 4:] = dy[alpha_dot_slice(N)][inv]
    return out.reshape(np.shape(states))
