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

import dataclasses
import math
from dataclasses import dataclass

import numpy as np

from ..models import ParameterError
from ..models._validate import finite as _finite
from .unbalance import residual_unbalance
from .vibratory import _speed, force_jacobian, gain_phase, vibratory_forces

__all__ = [
    "Equilibrium", "balancing_onset_speed", "find_equilibria", "floquet_full",
    "ks_eigenvalues", "single_ball_stability", "verify_by_simulation",
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
    nq = n + 3
    st = sim.states[-1]
    u, v, ud, vd = st[0], st[1], st[nq], st[nq + 1]
    psi = st[nq - 1]
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
    from ..simulate.pack import steady_orbit_start
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
