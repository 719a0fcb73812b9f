"""Equilibria of the balls checked on the full model (000 sec. 3 / Fig. 10-11): the Floquet
multipliers of the linearised full model and a perturbed simulation from an equilibrium. The
closed-form equilibria and their kinetic-static stability are :mod:`autobalance.physics.equilibria`."""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..core.layout import psi_index, rate_index
from ..models import ParameterError
from ..models._validate import finite as _finite
from ..physics.equilibria import TWO_PI, _wrap
from ..physics.vibratory import _speed

__all__ = ["floquet_full", "verify_by_simulation"]


# -- linearised full model ---------------------------------------------------------------------
def _period_map(system, w, z, options):
    """One revolution of the full model from state z = (x, y, vx, vy, alpha, alpha_dot) at psi = 0."""
    from ..models import InitialState, SpeedProfile
    from ..simulate import simulate

    n = system.balancer.n_balls
    T = TWO_PI / w
    init = InitialState(ball_angles=tuple(z[4:4 + n]), ball_speeds=tuple(z[4 + n:]),
                        x=z[0], y=z[1], vx=z[2], vy=z[3])
    sim = simulate(system, SpeedProfile.constant(w, T), initial=init, options=options)
    st = sim.states[-1]
    u, v, ud, vd = st[0], st[1], st[rate_index(0, n)], st[rate_index(1, n)]
    psi = st[psi_index(n)]
    c, s = math.cos(psi), math.sin(psi)
    x, y = u * c - v * s, u * s + v * c
    gx, gy = ud - w * v, vd + w * u          # inertial velocity in the rotor frame
    vx, vy = gx * c - gy * s, gx * s + gy * c
    a = sim.alpha[-1]
    a = z[4:4 + n] + _wrap(a - z[4:4 + n])
    return np.concatenate([[x, y, vx, vy], a, sim.alpha_dot[-1]])


def floquet_full(system, speed, alpha, iters: int = 6, rtol: float = 1e-11) -> dict:
    """Floquet multipliers of the full model about an equilibrium (linearised full model).

    The full model (our ``simulate``: 000 eq 2-4 with ball inertia, gravity, eccentricity) at
    constant speed w is periodic with T = 2 pi / w in the inertial frame. Newton shooting finds
    the periodic orbit z* = P(z*) of the one-revolution map P from the kinetic-static equilibrium
    (drum on its harmonic orbit, balls at rest); the multipliers are the eigenvalues of dP/dz
    (central finite differences). Rolling resistance and suspension dry friction are switched
    off (they make P non-smooth; stability of the ideal model). |mu| < 1 for all multipliers:
    asymptotically stable.

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speed : float
        Spin speed w [rad/s], > 0.
    alpha : array_like (N,)
        Starting ball angles [rad] (an equilibrium of :func:`find_equilibria`).
    iters : int
        Newton iterations (>= 1).
    rtol : float
        Integrator tolerance of each revolution [-].

    Returns
    -------
    dict
        "multipliers" (complex ndarray), "max_modulus" [-], "stable" (bool: max |mu| < 1 - 1e-7),
        "orbit_alpha_rad" (ball angles on the periodic orbit at psi = 0), "shooting_residual".
    """
    from ..physics.response import steady_orbit_start
    from ..models import SimOptions

    w = _speed(speed)
    b = system.balancer
    n = b.n_balls
    bal = dataclasses.replace(b, rolling_resistance=0.0, stiction=None)
    sus = dataclasses.replace(system.suspension, dry_friction_force=0.0)
    sysl = dataclasses.replace(system, balancer=bal, suspension=sus)
    opts = SimOptions(save_dt=-1.0, rtol=rtol, atol_scale=1e-9, exact_holds=False)

    a0 = np.asarray(alpha, float)
    z = np.concatenate([steady_orbit_start(sysl, w, a0), a0, np.zeros(n)])
    L = max(system.rotor.unbalance, b.capacity) / system.total_mass
    h = np.concatenate([[1e-4 * L] * 2, [1e-4 * L * w] * 2, [1e-5] * n, [1e-5 * w * 1e-2] * n])
    res = np.inf
    for _ in range(int(iters)):
        P0 = _period_map(sysl, w, z, opts)
        G = P0 - z
        res = float(np.max(np.abs(G / np.maximum(h * 1e4, 1e-300))))
        M = np.empty((z.size, z.size))
        for k in range(z.size):
            dz = np.zeros_like(z)
            dz[k] = h[k]
            M[:, k] = (_period_map(sysl, w, z + dz, opts) - _period_map(sysl, w, z - dz, opts)) / (2 * h[k])
        A = M - np.eye(z.size)
        try:
            step = np.linalg.lstsq(A, -G, rcond=1e-10)[0]
        except np.linalg.LinAlgError:   # pragma: no cover
            break
        z = z + step
        if res < 1e-9:
            break
    mu = np.linalg.eigvals(M)
    mx = float(np.abs(mu).max())
    return {"multipliers": mu, "max_modulus": mx, "stable": mx < 1.0 - 1e-7,
            "orbit_alpha_rad": _wrap(z[4:4 + n]), "shooting_residual": res}


def verify_by_simulation(system, speed, alpha, perturbation: float = 0.05, duration: float = 20.0,
                         options=None) -> dict:
    """Run the full nonlinear model from a perturbed equilibrium and report where the balls go.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (gravity, friction etc. as given).
    speed : float
        Constant spin speed w [rad/s], > 0.
    alpha : array_like (N,)
        Equilibrium ball angles [rad].
    perturbation : float
        Initial offset added to ball i: +perturbation * (-1)^i [rad], > 0.
    duration : float
        Simulated time [s], > 0.
    options : SimOptions, optional
        Default: save_dt = 2 pi / w * 4.

    Returns
    -------
    dict
        "final_alpha_rad" (mean over the last revolution), "drift_rad" (max |final - alpha|,
        wrapped), "stays" (drift < 2 x perturbation and the balls stopped moving; a
        stable-looking outcome), "final_amplitude_m".
    """
    from ..models import InitialState, SimOptions, SpeedProfile
    from ..simulate import simulate

    w = _speed(speed)
    p = _finite("perturbation", perturbation)
    dur = _finite("duration", duration)
    if p <= 0 or dur <= 0:
        raise ParameterError("perturbation" if p <= 0 else "duration",
                             perturbation if p <= 0 else duration, "must be > 0")
    a = np.asarray(alpha, float)
    n = a.size
    a0 = a + p * (-1.0) ** np.arange(n)
    opts = options or SimOptions(save_dt=TWO_PI / w / 8)
    sim = simulate(system, SpeedProfile.constant(w, dur),
                   initial=InitialState(ball_angles=tuple(a0), steady_state=True), options=opts)
    k = sim.t >= sim.t[-1] - TWO_PI / w
    fin = np.angle(np.exp(1j * sim.alpha[k]).mean(axis=0))
    drift = float(np.abs(_wrap(fin - a)).max())
    moving = float(np.abs(sim.alpha_dot[k]).mean(axis=0).max())
    return {"final_alpha_rad": fin, "drift_rad": drift,
            "stays": bool(drift < 2 * p and moving < 1e-2 * w),
            "final_amplitude_m": float(sim.amplitude[-1]), "duration_s": dur}
