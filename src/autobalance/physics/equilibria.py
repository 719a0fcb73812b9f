"""Equilibrium configurations of the balls and their stability (000 eq 10-12, 46, 52-55).

Three verdicts are computed for every equilibrium alpha* of the kinetic-static model
(F_i(alpha*) = 0, :mod:`.vibratory`):

* ``static`` - 000 eq (12), the Lagrange-Dirichlet argument: the derivative of the vibratory
  force is negative, i.e. every eigenvalue of J = dF/dalpha has a negative real part (for one
  ball: dF/dalpha < 0).
* ``kinetic_static`` - the linearised kinetic-static model (000 eq 13, 52) with the ball damping:
  I_eff alpha'' = R J alpha - D alpha', I_eff = m R^2 + I (R/r)^2, D = c_i m R^2. Stable when all
  eigenvalues have negative real parts.
* ``full`` - the linearised full model (our ``simulate``): the periodic orbit of period 2 pi / w
  through the equilibrium is found by Newton shooting and its Floquet multipliers are the
  eigenvalues of the finite-difference monodromy matrix (:func:`floquet_full`).

:func:`verify_by_simulation` runs the full nonlinear model from a perturbed equilibrium.
Angles [rad], speeds [rad/s], forces [N].
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..models import ParameterError
from ..models._validate import finite as _finite
from .unbalance import residual_unbalance
from .vibratory import _speed, force_jacobian, gain_phase, vibratory_forces

__all__ = [
    "Equilibrium", "balancing_onset_speed", "find_equilibria", "ks_eigenvalues",
    "single_ball_stability",
]

TWO_PI = 2.0 * math.pi


def _wrap(a):
    return np.mod(np.asarray(a, float) + math.pi, TWO_PI) - math.pi


@dataclass(frozen=True)
class Equilibrium:
    """One equilibrium configuration of the balls (kinetic-static model, 000 eq 10-12).

    Attributes
    ----------
    alpha : ndarray (N,)
        Ball angles from the unbalance, wrapped to (-pi, pi] [rad].
    force_residual : float
        max |F_i(alpha)| after Newton [N].
    jacobian : ndarray (N, N)
        dF_i/dalpha_j [N/rad] (000 eq 12, 52).
    static_stable : bool
        000 eq (12): all eigenvalues of J have negative real parts.
    ks_eigenvalues : ndarray (2N,)
        Eigenvalues of the linearised kinetic-static model [1/s].
    ks_stable : bool
        All ks_eigenvalues have negative real parts (tolerance 1e-9 |lambda|max).
    residual_unbalance : float
        |U + sum m_i (R e^{i alpha_i} + rho e^{i beta})| [kg*m].
    overlap : bool
        Two balls closer than their contact angle (not physically reachable).
    """

    alpha: np.ndarray
    force_residual: float
    jacobian: np.ndarray
    static_stable: bool
    ks_eigenvalues: np.ndarray
    ks_stable: bool
    residual_unbalance: float
    overlap: bool

    def as_dict(self) -> dict:
        """JSON-ready dict with unit-suffixed keys (SI): angles [rad] and [deg], force residual
        [N], Jacobian [N/rad], eigenvalues' real and imaginary parts [1/s], residual unbalance
        [kg*m] and the stability and overlap flags."""
        return {
            "alpha_rad": [float(v) for v in self.alpha],
            "alpha_deg": [float(v) for v in np.degrees(self.alpha)],
            "force_residual_n": self.force_residual,
            "jacobian_n_per_rad": self.jacobian.tolist(),
            "static_stable": bool(self.static_stable),
            "ks_eigenvalues_real_1_s": [float(v) for v in self.ks_eigenvalues.real],
            "ks_eigenvalues_imag_1_s": [float(v) for v in self.ks_eigenvalues.imag],
            "ks_stable": bool(self.ks_stable),
            "residual_unbalance_kg_m": self.residual_unbalance,
            "overlap": bool(self.overlap),
        }


def ks_eigenvalues(system, speed, alpha) -> np.ndarray:
    """Eigenvalues of the kinetic-static model linearised about alpha (000 eq 13, 52).

    I_eff,i d2(dalpha_i)/dt2 = R sum_j J_ij dalpha_j - D_i d(dalpha_i)/dt, with
    I_eff = m R^2 + I (R/r)^2 (000: m_z R^2) and D_i = c_i m_i R^2 (balancer damping).

    Parameters
    ----------
    system : autobalance.models.System
        Balancer masses [kg], R [m], r [m], rolling inertia [kg*m^2], damping D [N*m*s/rad].
    speed : float
        Spin speed w [rad/s], > 0.
    alpha : array_like (N,)
        Equilibrium ball angles [rad].

    Returns
    -------
    ndarray (2N,) complex
        Eigenvalues [1/s].
    """
    b = system.balancer
    n = b.n_balls
    J = force_jacobian(system, speed, alpha)
    R = b.race_radius
    ieff = b.masses * R * R + b.inertias * (R / b.ball_radius) ** 2
    D = np.asarray(b.damping, float)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = R * J / ieff[:, None]
    A[n:, n:] = -np.diag(D / ieff)
    return np.linalg.eigvals(A)


def _newton(system, w, starts, iters=40):
    """Vectorised Newton iteration on F(alpha) = 0 (pseudo-inverse steps, clipped to 0.5 rad)."""
    a = starts.copy()
    for _ in range(iters):
        F = vibratory_forces(system, w, a)
        J = force_jacobian(system, w, a)
        step = np.einsum("kij,kj->ki", np.linalg.pinv(J), F)
        a = a - np.clip(step, -0.5, 0.5)
    return a, np.abs(vibratory_forces(system, w, a)).max(axis=-1)


def find_equilibria(system, speed, n_grid: int | None = None, tol: float | None = None) -> list:
    """All equilibrium configurations F_i(alpha) = 0 of the balls (000 eq 10-12, 46).

    Newton's method on the analytic Jacobian from a regular grid of starts over the torus
    [-pi, pi)^N; converged roots are merged (and, for identical balls, merged over ball
    permutations). For N >= 3 the balanced states form a continuum; the grid then returns a
    sample of it (singular Jacobian, a zero eigenvalue).

    Parameters
    ----------
    system : autobalance.models.System
        Drum, suspension and balancer (N >= 1 balls; rho, beta included).
    speed : float
        Spin speed w [rad/s], > 0.
    n_grid : int, optional
        Starts per ball angle (default 72 for N = 1, 36 for N = 2, 10 for N >= 3).
    tol : float, optional
        Convergence threshold on max |F_i| [N]; default 1e-9 m R w^2.

    Returns
    -------
    list of Equilibrium
        Sorted by residual unbalance (the best-balanced first).
    """
    w = _speed(speed)
    b = system.balancer
    n = b.n_balls
    if n < 1:
        raise ParameterError("balancer.n_balls", n, "needs at least one ball")
    if n_grid is None:
        n_grid = {1: 72, 2: 36}.get(n, 10)
    if int(n_grid) != n_grid or n_grid < 2:
        raise ParameterError("n_grid", n_grid, "must be an integer >= 2")
    n_grid = int(n_grid)
    scale = float(b.masses.max() * b.race_radius * w * w)
    tol = 1e-9 * scale if tol is None else _finite("tol", tol)
    g = -math.pi + TWO_PI * (np.arange(n_grid) + 0.5) / n_grid
    starts = np.stack(np.meshgrid(*([g] * n), indexing="ij"), axis=-1).reshape(-1, n)
    roots, res = _newton(system, w, starts)
    roots = _wrap(roots[res < tol])
    same_balls = np.allclose(b.masses, b.masses[0])
    out, keys = [], []
    for r in roots:
        key = np.sort(np.mod(r, TWO_PI)) if same_balls else np.mod(r, TWO_PI)
        if any(np.all(np.abs(_wrap(key - k)) < 1e-6) for k in keys):
            continue
        keys.append(key)
        out.append(_make(system, w, _wrap(key) if same_balls else r))
    out.sort(key=lambda e: (e.residual_unbalance, tuple(e.alpha)))
    return out


def _make(system, w, alpha) -> Equilibrium:
    b = system.balancer
    J = force_jacobian(system, w, alpha)
    ev = ks_eigenvalues(system, w, alpha)
    lam = np.linalg.eigvals(J)
    jscale = max(np.abs(lam).max(), 1e-300)
    escale = max(np.abs(ev).max(), 1e-300)
    W = residual_unbalance(system, alpha)
    srt = np.sort(np.mod(alpha, TWO_PI))
    gaps = np.diff(np.concatenate([srt, srt[:1] + TWO_PI])) if b.n_balls > 1 else np.array([TWO_PI])
    return Equilibrium(
        alpha=np.asarray(alpha, float),
        force_residual=float(np.abs(vibratory_forces(system, w, alpha)).max()),
        jacobian=J,
        static_stable=bool(np.all(lam.real < 1e-9 * jscale)),
        ks_eigenvalues=ev,
        ks_stable=bool(np.all(ev.real < 1e-9 * escale)),
        residual_unbalance=float(abs(W)),
        overlap=bool(gaps.min() < b.contact_angle * (1 - 1e-9)),
    )


def single_ball_stability(system, speeds, static_moment=None) -> dict:
    """Stability of the compensating position alpha_f = pi of one ball with mR = Me (000 eq 12).

    dF/dalpha|_{pi} = -1/2 m w^2 [a_0x cos(pi + phi_x) + a_0y cos(pi + phi_y)]
                    = 1/2 m w^2 Me [g_x cos(phi_x) + g_y cos(phi_y)];
    the position is stable when it is negative (Lagrange-Dirichlet).

    Parameters
    ----------
    system : autobalance.models.System
        Drum (Me [kg*m], M_t [kg], suspension).
    speeds : array_like
        Spin speeds w [rad/s], > 0.
    static_moment : float, optional
        m R of the ball [kg*m]; default Me. The ball mass used is m = S/R with R of the balancer.

    Returns
    -------
    dict of ndarray
        "speed_rad_s", "dF_dalpha_n_per_rad" (eq 12), "dF_dalpha_norm" (/(m R w^2) [-]),
        "stable" (bool).
    """
    w = np.atleast_1d(np.asarray(speeds, float))
    if np.any(~np.isfinite(w)) or np.any(w <= 0):
        raise ParameterError("speeds", w.tolist(), "must be finite and > 0 [rad/s]")
    U = system.rotor.unbalance
    S = U if static_moment is None else _finite("static_moment", static_moment)
    R = system.balancer.race_radius or 1.0
    m = S / R
    gx, px, gy, py = gain_phase(system, w)
    d = -0.5 * m * w * w * U * (np.asarray(gx) * np.cos(math.pi + np.asarray(px))
                                 + np.asarray(gy) * np.cos(math.pi + np.asarray(py)))
    return {"speed_rad_s": w, "dF_dalpha_n_per_rad": d, "dF_dalpha_norm": d / (m * R * w * w),
            "stable": d < 0}


def balancing_onset_speed(system) -> float:
    """Lowest speed above which alpha_f = pi (one ball, mR = Me) is stable (000 eq 12) [rad/s].

    The root of g_x cos(phi_x) + g_y cos(phi_y) = 0 (sign change of eq 12's derivative); it lies
    between the two suspension frequencies for 000's washer.

    Parameters
    ----------
    system : autobalance.models.System
        Suspension and M_t.

    Returns
    -------
    float
        [rad/s]; the stability holds for every larger speed (checked up to 100 x the higher
        natural frequency).
    """
    from scipy.optimize import brentq

    wx, wy = system.natural_frequencies
    hi = 100.0 * max(wx, wy)

    def f(w):
        gx, px, gy, py = gain_phase(system, w)
        return gx * math.cos(px) + gy * math.cos(py)

    grid = np.geomspace(1e-3 * min(wx, wy), hi, 4000)
    vals = np.array([f(v) for v in grid])
    pos = np.nonzero(vals >= 0)[0]
    k = pos[-1]
    return float(brentq(f, grid[k], grid[k + 1], xtol=1e-12))
