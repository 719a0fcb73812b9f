"""Equilibrium configurations of the balls and their stability (000 eq 10-12, 46, 52-55).

Every equilibrium of the kinetic-static model falls in one of two kinds. In complex form
(:mod:`.vibratory`) the force on ball i is F_i = -m_i w^2 Im(e^{i alpha_i} Q) with one common
phasor Q = 1/2 conj(W) H + rho e^{-i beta} [m] (:func:`force_phasor`), so F = 0 needs either

* Q = 0: the residual unbalance takes the balanced value W = W* = -2 rho e^{i beta} / conj(H)
  (:func:`balanced_unbalance`; W* = 0 without eccentricity, 000 eq 22). These are two real
  conditions on N angles: for N >= 3 balls a continuous family of dimension N - 2
  (:class:`EquilibriumFamily`), the classical result for multi-ball balancers (Green, Champneys,
  Friswell & Munoz 2008, Phil. Trans. R. Soc. A 366, 705-728; reference 12 of seed 000), two
  mirror points for N = 2;
* Q != 0: every ball lies on the line of Q, alpha_i = phi or phi + pi, with phi fixed by one
  scalar equation (isolated, found in closed form by :func:`aligned_equilibria`).

:func:`find_equilibrium_set` returns both kinds; :func:`find_equilibria` keeps the list of
isolated points (for N >= 3 with one representative per family). Along a family the Jacobian
J = dF/dalpha has N - 2 zero eigenvalues whose eigenvectors span the family's tangent; they are
neutral, not unstable, and are removed before a verdict (:func:`deflate`).

Three verdicts are computed for every equilibrium alpha* of the kinetic-static model
(F_i(alpha*) = 0, :mod:`.vibratory`):

* ``static`` - 000 eq (12), the Lagrange-Dirichlet argument: the derivative of the vibratory
  force is negative, i.e. every eigenvalue of J = dF/dalpha has a negative real part (for one
  ball: dF/dalpha < 0).
* ``kinetic_static`` - the linearised kinetic-static model (000 eq 13, 52) with the ball damping:
  I_eff alpha'' = R J alpha - D alpha', I_eff = m R^2 + I (R/r)^2, D = c_i m R^2. Stable when all
  eigenvalues have negative real parts.
* ``full`` - the linearised full model (our ``simulate``), in
  :mod:`autobalance.studies.equilibria`: eigenvalues at the fixed point of a steady rotor frame,
  or the Floquet multipliers of the periodic orbit of period 2 pi / w found by Newton shooting
  (``full_stability`` picks the route; ``floquet_full``); a family's neutral multipliers are
  removed there too (docs/speed-map.md).

``verify_by_simulation`` (same module) runs the full nonlinear model from a perturbed equilibrium.
Angles [rad], speeds [rad/s], forces [N].
"""
from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import numpy.typing as npt

from ..models import ParameterError, System
from ..models._validate import finite as _finite
from .unbalance import residual_unbalance
from .vibratory import _H, _speed, force_jacobian, gain_phase, vibratory_forces
from .equilibrium_families import (TWO_PI, _ball_target, _balanced_pair, _dedupe, _family_points,
                                   _wrap, aligned_equilibria, balanced_unbalance, deflate,
                                   family_tangent, force_phasor)

__all__ = [
    "Equilibrium", "EquilibriumFamily", "EquilibriumSet", "aligned_equilibria",
    "balanced_unbalance", "balancing_onset_speed", "deflate", "family_tangent",
    "find_equilibria", "find_equilibrium_set", "force_phasor", "ks_eigenvalues",
    "single_ball_stability",
]



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
    family_dimension : int
        0 for an isolated equilibrium; d = N - 2 for a point standing for a continuous family
        (:class:`EquilibriumFamily`): then ``static_stable`` and ``ks_stable`` leave out the d
        neutral directions along the family (:func:`deflate`).
    """

    alpha: np.ndarray
    force_residual: float
    jacobian: np.ndarray
    static_stable: bool
    ks_eigenvalues: np.ndarray
    ks_stable: bool
    residual_unbalance: float
    overlap: bool
    family_dimension: int = 0

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
            **({"family_dimension": int(self.family_dimension)} if self.family_dimension else {}),
        }


def ks_eigenvalues(system: System, speed: float, alpha: npt.ArrayLike) -> np.ndarray:
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
    return np.linalg.eigvals(_ks_matrix(system, speed, alpha))


def _ks_matrix(system, speed, alpha, J=None) -> np.ndarray:
    """State matrix (2N, 2N) of the linearised kinetic-static model of :func:`ks_eigenvalues`
    (J: the force Jacobian at alpha when already known)."""
    b = system.balancer
    n = b.n_balls
    J = force_jacobian(system, speed, alpha) if J is None else J
    R = b.race_radius
    ieff = b.masses * R * R + b.inertias * (R / b.ball_radius) ** 2
    D = np.asarray(b.damping, float)
    A = np.zeros((2 * n, 2 * n))
    A[:n, n:] = np.eye(n)
    A[n:, :n] = R * J / ieff[:, None]
    A[n:, n:] = -np.diag(D / ieff)
    return A


def _newton(system, w, starts, iters=40):
    """Vectorised Newton iteration on F(alpha) = 0 (pseudo-inverse steps, clipped to 0.5 rad)."""
    a = starts.copy()
    for _ in range(iters):
        F = vibratory_forces(system, w, a)
        J = force_jacobian(system, w, a)
        step = np.einsum("kij,kj->ki", np.linalg.pinv(J), F)
        a = a - np.clip(step, -0.5, 0.5)
    return a, np.abs(vibratory_forces(system, w, a)).max(axis=-1)


def find_equilibria(system: System, speed: float, n_grid: int | None = None,
                    tol: float | None = None) -> list:
    """All equilibrium configurations F_i(alpha) = 0 of the balls (000 eq 10-12, 46).

    N <= 2: Newton's method on the analytic Jacobian from a regular grid of starts over the
    torus [-pi, pi)^N; converged roots are merged (and, for identical balls, merged over ball
    permutations). N >= 3: the closed forms of :func:`find_equilibrium_set`; the balanced
    states form continuous families there, and each family is represented by one of its
    points (``family_dimension`` = N - 2; a stable, non-overlapping one when there is one).

    Parameters
    ----------
    system : autobalance.models.System
        Drum, suspension and balancer (N >= 1 balls; rho, beta included).
    speed : float
        Spin speed w [rad/s], > 0.
    n_grid : int, optional
        Starts per ball angle for N <= 2 (default 72 for N = 1, 36 for N = 2); checked but
        unused for N >= 3.
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
    if n >= 3:
        es = find_equilibrium_set(system, w, tol=tol)
        out = list(es.isolated) + [f.representative() for f in es.families]
        out.sort(key=lambda e: (e.residual_unbalance, tuple(e.alpha)))
        return out
    return _newton_equilibria(system, w, n_grid, tol)


def _newton_equilibria(system, w: float, n_grid: int, tol: float) -> list:
    """The Newton-from-a-grid search of :func:`find_equilibria` (N <= 2)."""
    b = system.balancer
    n = b.n_balls
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
    return Equilibrium(
        alpha=np.asarray(alpha, float),
        force_residual=float(np.abs(vibratory_forces(system, w, alpha)).max()),
        jacobian=J,
        static_stable=bool(np.all(lam.real < 1e-9 * jscale)),
        ks_eigenvalues=ev,
        ks_stable=bool(np.all(ev.real < 1e-9 * escale)),
        residual_unbalance=float(abs(W)),
        overlap=_overlap(b, alpha),
    )


def single_ball_stability(system: System, speeds: npt.ArrayLike,
                          static_moment: float | None = None) -> dict:
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


def balancing_onset_speed(system: System) -> float:
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


# -- the two kinds of equilibria in closed form ----------------------------------------------
#: |W - W*| below this fraction of the ball capacity sum(m_i) R: a balanced state [-].
BALANCED_RTOL = 1e-6


@dataclass(frozen=True)
class EquilibriumFamily:
    """A continuous family of balanced equilibria, W(alpha) = W* (N >= 3; Green et al. 2008).

    Attributes
    ----------
    speed : float
        Spin speed w [rad/s].
    dimension : int
        d = N - 2 (the tangent dimension; N - rank of d W / d alpha).
    points : tuple of Equilibrium
        Sample points (``family_dimension`` = d; their ``static_stable`` and ``ks_stable`` leave
        out the d neutral directions); for d = 1 in order along the traced curve.
    tangent : ndarray (K, N, d)
        Orthonormal tangent bases at the samples [rad/rad].
    ks_max_real : ndarray (K,)
        Largest real part of the transverse kinetic-static eigenvalues [1/s].
    target_unbalance : complex
        W* [kg*m] (:func:`balanced_unbalance`).
    traced : bool
        d = 1 and the curve was followed until it closed (then ``length`` is its length [rad]).
    length : float
        Length of the traced curve with the balls labelled (it visits every relabelling of
        identical balls) in angle space [rad], step x points; NaN when not traced.
    """

    speed: float
    dimension: int
    points: tuple
    tangent: np.ndarray
    ks_max_real: np.ndarray
    target_unbalance: complex
    traced: bool
    length: float

    @property
    def n_samples(self) -> int:
        """Number of sample points K [-]."""
        return len(self.points)

    @property
    def alpha(self) -> np.ndarray:
        """Sample angles (K, N) [rad]."""
        return np.array([p.alpha for p in self.points])

    @property
    def residual_unbalance(self) -> np.ndarray:
        """|W| at the samples (K,) [kg*m] (= |W*| up to the projection tolerance)."""
        return np.array([p.residual_unbalance for p in self.points])

    @property
    def residual_range(self) -> tuple[float, float]:
        """(min, max) of the samples' residual unbalance [kg*m]."""
        r = self.residual_unbalance
        return float(r.min()), float(r.max())

    @property
    def overlap(self) -> np.ndarray:
        """Samples where two balls are closer than their contact angle (K,) [bool]."""
        return np.array([p.overlap for p in self.points], bool)

    @property
    def static_stable(self) -> np.ndarray:
        """000 eq (12) on the transverse part at each sample (K,) [bool]."""
        return np.array([p.static_stable for p in self.points], bool)

    @property
    def ks_stable(self) -> np.ndarray:
        """Transverse kinetic-static verdict at each sample (K,) [bool]."""
        return np.array([p.ks_stable for p in self.points], bool)

    def representative(self) -> Equilibrium:
        """One point standing for the family: the first stable non-overlapping sample, else the
        first non-overlapping one, else the first."""
        order = np.lexsort((np.arange(self.n_samples), ~self.ks_stable, self.overlap))
        return self.points[int(order[0])]

    def as_dict(self) -> dict:
        """JSON-ready dict (SI, unit-suffixed keys): dimension, samples [rad] and [deg], residual
        range [kg*m], per-sample verdicts and the stable share of the reachable samples."""
        reach = ~self.overlap
        ok = self.ks_stable & reach
        lo, hi = self.residual_range
        return {
            "dimension": int(self.dimension), "n_samples": self.n_samples,
            "traced": bool(self.traced), "length_rad": float(self.length),
            "alpha_rad": self.alpha.tolist(), "alpha_deg": np.degrees(self.alpha).tolist(),
            "residual_unbalance_min_kg_m": lo, "residual_unbalance_max_kg_m": hi,
            "target_unbalance_kg_m": abs(self.target_unbalance),
            "force_residual_n": max(p.force_residual for p in self.points),
            "static_stable": [bool(v) for v in self.static_stable],
            "ks_stable": [bool(v) for v in self.ks_stable],
            "ks_max_real_1_s": [float(v) for v in self.ks_max_real],
            "overlap": [bool(v) for v in self.overlap],
            "ks_stable_share": float(ok.sum() / reach.sum()) if reach.any() else 0.0,
        }


def _overlap(b, alpha) -> bool:
    """Two balls closer than their contact angle."""
    srt = np.sort(np.mod(alpha, TWO_PI))
    gaps = np.diff(np.concatenate([srt, srt[:1] + TWO_PI])) if b.n_balls > 1 else np.array([TWO_PI])
    return bool(gaps.min() < b.contact_angle * (1 - 1e-9))


def _family_member(system, w: float, alpha, tangent, J, F) -> tuple:
    """A family sample as an Equilibrium with the neutral directions removed from its verdicts,
    and the largest transverse kinetic-static real part [1/s] (J, F: its Jacobian and forces)."""
    b = system.balancer
    n = b.n_balls
    d = tangent.shape[1]
    A = _ks_matrix(system, w, alpha, J)
    ev = np.linalg.eigvals(A)
    st = deflate(J, tangent)["transverse"]
    E = np.zeros((2 * n, d))
    E[:n] = tangent
    tr = deflate(A, E)["transverse"]
    jscale = max(np.abs(np.linalg.eigvals(J)).max(), 1e-300)
    escale = max(np.abs(ev).max(), 1e-300)
    e = Equilibrium(
        alpha=np.asarray(alpha, float),
        force_residual=float(np.abs(F).max()),
        jacobian=J,
        static_stable=bool(np.all(st.real < 1e-9 * jscale)),
        ks_eigenvalues=ev,
        ks_stable=bool(np.all(tr.real < 1e-9 * escale)),
        residual_unbalance=float(abs(residual_unbalance(system, alpha))),
        overlap=_overlap(b, alpha),
        family_dimension=d,
    )
    return e, float(tr.real.max())


def _family(system, w: float, pts, d: int, traced: bool, length: float) -> EquilibriumFamily:
    members, tangents, kmax = [], [], []
    Js = force_jacobian(system, w, pts)
    Fs = vibratory_forces(system, w, pts)
    for a, J, F in zip(pts, Js, Fs):
        t = family_tangent(system, a)
        e, km = _family_member(system, w, a, t, J, F)
        members.append(e)
        tangents.append(t)
        kmax.append(km)
    return EquilibriumFamily(speed=w, dimension=d, points=tuple(members), tangent=np.array(tangents),
                             ks_max_real=np.array(kmax), target_unbalance=balanced_unbalance(system, w),
                             traced=traced, length=length)


@dataclass(frozen=True)
class EquilibriumSet:
    """Every equilibrium of the balls at one speed: isolated points and continuous families.

    Attributes
    ----------
    speed : float
        Spin speed w [rad/s].
    isolated : tuple of Equilibrium
        Isolated equilibria, sorted by residual unbalance.
    balanced : tuple of bool
        For each isolated one: a balanced state, |W - W*| <= BALANCED_RTOL sum(m_i) R (the two
        mirror points of N = 2 balls).
    families : tuple of EquilibriumFamily
        Balanced families (N >= 3), one per connected piece found (d = 1) or one in all (d >= 2).
    target_unbalance : complex
        W* [kg*m] (:func:`balanced_unbalance`).
    method : str
        "newton" (grid search, N <= 2) or "closed_form".
    """

    speed: float
    isolated: tuple
    balanced: tuple
    families: tuple
    target_unbalance: complex
    method: str

    def as_dict(self) -> dict:
        """JSON-ready dict (SI, unit-suffixed keys)."""
        return {"speed_rad_s": self.speed, "method": self.method,
                "balanced_unbalance_kg_m": abs(self.target_unbalance),
                "balanced_unbalance_angle_rad": float(np.angle(self.target_unbalance)),
                "isolated": [dict(e.as_dict(), balanced=bool(b))
                             for e, b in zip(self.isolated, self.balanced)],
                "families": [f.as_dict() for f in self.families]}


def find_equilibrium_set(system: System, speed: float, *, method: str = "auto",
                         n_grid: int | None = None, tol: float | None = None, n_samples: int = 36,
                         step: float = 0.1) -> EquilibriumSet:
    """Every equilibrium of the balls at one speed: isolated ones and balanced families.

    ``closed_form``: the aligned equilibria of :func:`aligned_equilibria`, the two balanced
    points of N = 2 balls (a triangle of sides m_1 R, m_2 R, |T|) and, for N >= 3, the balanced
    set W(alpha) = W*, found by Gauss-Newton projection from fixed starts. A one-dimensional
    family (N = 3) is traced (predictor along the tangent, corrector back onto the set, step
    ``step``) until it closes, and ``n_samples`` points are kept; every start not on a traced
    curve starts another family. For d >= 2 the projected starts are subsampled (farthest
    point first) into one family. ``newton``: :func:`find_equilibria`'s grid search (N <= 2
    only). ``auto``: ``newton`` for N <= 2 (unchanged results), ``closed_form`` otherwise.
    Equilibria are merged modulo 2 pi and, for identical balls, modulo relabelling.

    Parameters
    ----------
    system : autobalance.models.System
        Drum, suspension and balancer (N >= 1).
    speed : float
        Spin speed w [rad/s], > 0.
    method : str
        "auto", "closed_form" or "newton".
    n_grid : int, optional
        Starts per ball angle of the Newton search [-].
    tol : float, optional
        Largest accepted max |F_i| [N]; default 1e-9 m R w^2.
    n_samples : int
        Sample points kept per family [-], >= 2.
    step : float
        Tracing step along a one-dimensional family [rad], in (0, 0.5].

    Returns
    -------
    EquilibriumSet
    """
    w = _speed(speed)
    b = system.balancer
    n = b.n_balls
    if method not in ("auto", "closed_form", "newton"):
        raise ParameterError("method", method, "must be 'auto', 'closed_form' or 'newton'")
    if int(n_samples) != n_samples or n_samples < 2:
        raise ParameterError("n_samples", n_samples, "must be an integer >= 2")
    stp = _finite("step", step)
    if not 0.0 < stp <= 0.5:
        raise ParameterError("step", step, "must be in (0, 0.5] [rad]")
    if n < 1:
        raise ParameterError("balancer.n_balls", n, "needs at least one ball")
    if method == "auto":
        method = "newton" if n <= 2 else "closed_form"
    if method == "newton" and n >= 3:
        raise ParameterError("method", method, "the grid search is for N <= 2 balls (families for N >= 3)")
    scale = float(b.masses.max() * b.race_radius * w * w)
    tol = 1e-9 * scale if tol is None else _finite("tol", tol)
    Wt = balanced_unbalance(system, w)
    cap = float(np.sum(b.masses)) * b.race_radius
    same = bool(np.allclose(b.masses, b.masses[0]))
    families = []
    if method == "newton":
        isolated = find_equilibria(system, w, n_grid=n_grid, tol=tol)
    else:
        rows = list(aligned_equilibria(system, w))
        Q = np.abs(force_phasor(system, w, np.array(rows).reshape(-1, n))) if rows else np.zeros(0)
        qscale = 0.5 * abs(_H(system, w)) * max(cap, system.rotor.unbalance) + b.eccentricity
        rows = [r for r, q in zip(rows, Q) if q > 1e-9 * qscale]
        if n == 2:
            rows += _balanced_pair(system, _ball_target(system, w))
        if rows:
            F = np.abs(vibratory_forces(system, w, np.array(rows))).max(axis=-1)
            rows = [r for r, f in zip(rows, F) if f < tol]
        isolated = [_make(system, w, r) for r in _dedupe(rows, same)]
        isolated.sort(key=lambda e: (e.residual_unbalance, tuple(e.alpha)))
        if n >= 3 or (n == 2 and abs(_ball_target(system, w)) < BALANCED_RTOL * cap):
            for pts, d, traced, length in _family_points(system, w, int(n_samples), stp):
                pts = pts[np.abs(vibratory_forces(system, w, pts)).max(axis=-1) < tol]
                if len(pts):
                    families.append(_family(system, w, pts, d, traced, length))
    bal = tuple(bool(abs(residual_unbalance(system, e.alpha) - Wt) <= BALANCED_RTOL * cap) for e in isolated)
    return EquilibriumSet(speed=w, isolated=tuple(isolated), balanced=bal, families=tuple(families),
                          target_unbalance=Wt, method=method)
