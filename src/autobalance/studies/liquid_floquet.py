"""The balanced state of balls beside a liquid on a horizontal axis and its linear stability at a
constant speed (docs/liquid/horizontal-axis.md sec. 3m): Floquet's theory about the periodic state
that in-plane gravity, turning at -Omega in the rotor frame, makes of the balanced state.

Method (our choice): sec. 3k's step map of the coupling the run of balls beside a liquid uses
(core/hybrid.py), over one revolution T = 2 pi / Omega in m equal steps dt = T / m:

1. every film takes one step of :func:`autobalance.core.shallow_water.films_step` forced by the
   chamber about the rotation axis, w + sag e^{-i psi} (the kernel's deflection is from the
   static equilibrium; sag = M_t g / k, inertial), its rate and the last step's w'', with
   gravity's offset of the potential at the spin angle psi;
2. the rotor and the balls advance over dt with the films' moment held, by the exact
   propagator of the kernel's right-hand side linearised about the balanced state at the
   step's middle angle (A, B and gravity's pull c on the balls: the exponential midpoint rule;
   :func:`autobalance.studies.ball_propagator.ball_propagator`);
3. the films' new moment is taken up by the chamber, Z and Z' kept (as sec. 3k).

The balls are linear about the balanced angles of the machine without gravity, so gravity's
effect on them is kept to first order in g / (Omega^2 R), as the films' wall height is first
order in the chamber's offset (core/shallow_water.py). The periodic state x* = P(x*) of the
revolution map by :func:`autobalance.liquid.maps.periodic_state`; the multipliers of its
monodromy give lambda = ln(mu) / T (a compartment's volume neutral and dropped).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..liquid.film import FilmsState
    from ..liquid.stability import RingStability
    from ..models import System

__all__ = ["balanced_floquet"]


def _period_map(system, pool, st, W: float, alpha, m: int):
    """The revolution map P of the balanced state's coupling under gravity on m steps (module
    docstring) on the state (z, w'', eta, q), z = (u, v, alpha, u', v', alpha') rotor frame from
    the static equilibrium; also the thinnest film [m] of its last evaluation. A state whose
    CFL step is shorter than T / m: ValueError."""
    from ..core.shallow_water import films_dt, films_moment, films_step, gravity_offset
    from .ball_propagator import ball_propagator

    N = alpha.size
    T = 2.0 * math.pi / W
    dt = T / m
    gp, gdir = system.gravity.g, system.gravity.direction
    Mt = pool.total_mass
    sag = Mt * gp / pool.suspension.kx * complex(math.cos(gdir), math.sin(gdir))
    L = max(pool.rotor.unbalance, pool.balancer.capacity) / Mt
    props = [ball_propagator(pool, W, alpha, dt, L, phase=(k + 0.5) * W * dt)[:3]
             for k in range(m)]
    z_ref = np.concatenate([[0.0, 0.0], alpha, np.zeros(N + 2)])
    mz, r, nc = z_ref.size, N + 2, st.h.size
    work = [np.zeros(nc) for _ in range(9)]
    thinnest = [math.inf]

    def P(x):
        z = x[:mz].copy()
        wdd = complex(x[mz], x[mz + 1])
        h, q = x[mz + 2:mz + 2 + nc].copy(), x[mz + 2 + nc:].copy()
        thin = math.inf
        for k in range(m):
            psi = k * W * dt
            rot = complex(math.cos(psi), -math.sin(psi))
            w = complex(z[0], z[1]) + sag * rot            # the chamber about the axis
            wd = complex(z[r], z[r + 1]) - 1j * W * sag * rot
            if films_dt(h, q, st.starts, st.Rs, W, dt) < dt * (1.0 - 1e-9):
                raise ValueError(k)
            films_step(h, q, st.theta, st.starts, st.Rs, st.nus, st.wall, W, 0.0, w,
                       gravity_offset(gp, gdir, psi, W), wd, wdd, dt, *work)
            U, Ud = films_moment(h, q, st.theta, st.starts, st.Rs, st.Hs, st.rhos)
            U1, Ud1 = films_moment(work[0], work[1], st.theta, st.starts, st.Rs, st.Hs, st.rhos)
            Phi, Gam, c = props[k]
            z = z_ref + Phi @ (z - z_ref) + Gam @ np.array([U.real, U.imag, Ud.real, Ud.imag]) + c
            dU, dUd = (U1 - U - dt * Ud) / Mt, (Ud1 - Ud) / Mt
            z[0] -= dU.real
            z[1] -= dU.imag
            z[r] -= dUd.real
            z[r + 1] -= dUd.imag
            psi1 = psi + W * dt
            wd1 = complex(z[r], z[r + 1]) - 1j * W * sag * complex(math.cos(psi1),
                                                                   -math.sin(psi1))
            wdd = (wd1 - wd) / dt
            h, q = work[0].copy(), work[1].copy()
            thin = min(thin, float(h.min()))
        thinnest[0] = thin
        return np.concatenate([z, [wdd.real, wdd.imag], h, q])

    return P, thinnest, sag


def balanced_floquet(system: System, pool: System, speed: float, alpha: np.ndarray,
                     st: FilmsState) -> RingStability:
    """The linear stability of the balanced state of balls beside a liquid on a horizontal axis
    at the constant spin ``speed``: the Floquet exponents about its periodic state under
    gravity (module docstring). Called by
    :func:`autobalance.studies.liquid_balanced.balanced_stability`, which checks the machine.

    Parameters
    ----------
    system : autobalance.models.System
        Balls beside a ``[liquid]`` section on a horizontal axis; [gravity] g [m/s^2] and
        direction [rad].
    pool : autobalance.models.System
        Its ideal pool machine (:func:`autobalance.studies.liquid_balanced.
        require_balanced_liquid`): M_t [kg], k [N/m], the balls' m [kg], R [m].
    speed : float
        Omega [rad/s], > 0, where every film is a ring.
    alpha : ndarray (N,)
        The balanced angles of the machine without gravity [rad].
    st : autobalance.liquid.film.FilmsState
        The uniform films (:func:`autobalance.studies.liquid_balanced.uniform_films`).

    Returns
    -------
    autobalance.liquid.stability.RingStability
        Exponents [1/s], ``dt`` the period [s], ``state`` the periodic state at psi = 0,
        ``steps`` the period's grid; no periodic state with an intact film:
        :class:`autobalance.liquid.stability.NoPeriodicFilm` on ``speed``.
    """
    from ..core.shallow_water import films_dt
    from ..liquid.maps import SHOOT_TOL, FinerGrid, compartments, multiplier_modes, periodic_state
    from ..liquid.stability import DT_FRACTION, WET_FRACTION, NoPeriodicFilm, RingStability

    W = float(speed)
    T = 2.0 * math.pi / W
    N = alpha.size
    nc = st.h.size
    hs = float(np.max(st.h))
    scale = np.concatenate([[hs] * 2, [1.0] * N, [hs * W] * 2, [W] * N, [hs * W * W] * 2,
                            np.full(nc, hs), np.full(nc, hs * W * float(np.max(st.Rs)))])
    mz = 2 * N + 4
    groups = [mz + 2 + c for c in compartments(st)]
    m = int(math.ceil(1.2 * T / (DT_FRACTION * films_dt(st.h, st.q, st.starts, st.Rs, W,
                                                            math.inf))))
    x = None
    for _ in range(6):
        P, thinnest, sag = _period_map(system, pool, st, W, alpha, m)
        if x is None:       # the balanced state, the chamber at its sag, the films uniform
            a0 = -W * W * sag
            x = np.concatenate([[0.0, 0.0], alpha, np.zeros(N + 2), [a0.real, a0.imag],
                                st.h, st.q])
        try:
            x, J, res = periodic_state(P, x, scale, groups, "balanced_stability")
            P(x)
            break
        except FinerGrid as e:      # a state needed a shorter step than the period's grid
            x, m = e.x, int(math.ceil(1.25 * m))
    else:
        raise NoPeriodicFilm("speed", round(W, 6), "has no periodic state of the balls beside "
                             f"the films under gravity on a grid of up to {m} steps a revolution")
    if res > SHOOT_TOL:
        raise NoPeriodicFilm("speed", round(W, 6), "has no periodic state of the balls beside "
                             f"the films under gravity: the shooting ended at {res:.3g}")
    if thinnest[0] < WET_FRACTION * float(np.min(st.h)):
        raise NoPeriodicFilm("speed", round(W, 6), "has no intact film under gravity there: "
                             f"it thins to {thinnest[0]:.3g} m (a crescent)")
    lam = multiplier_modes(J, T, len(groups), "balanced_stability")
    return RingStability(W, lam, T, x, m)
