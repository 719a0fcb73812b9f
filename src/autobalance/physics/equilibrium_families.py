"""The geometry of the balls' equilibria (000 eq 10-12, 46; Green, Champneys, Friswell & Munoz
2008, Phil. Trans. R. Soc. A 366, 705-728): the common force phasor Q, the balanced unbalance W*,
the aligned equilibria in closed form, the balanced families of N >= 3 balls (tangent, tracing,
projection, sampling) and the deflation of their neutral directions.

:mod:`.equilibria` builds the equilibria and their verdicts from these (and re-exports the
public names). Angles [rad], speeds [rad/s], unbalances [kg*m].
"""
from __future__ import annotations

import itertools
import math
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from .unbalance import residual_unbalance
from .vibratory import _H, _angles, _speed

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = ["TWO_PI", "aligned_equilibria", "balanced_unbalance", "deflate", "family_tangent",
           "force_phasor"]

TWO_PI = 2.0 * math.pi


def _wrap(a):
    return np.mod(np.asarray(a, float) + math.pi, TWO_PI) - math.pi


def force_phasor(system: System, speed: float, alpha: npt.ArrayLike) -> np.ndarray:
    """Common phasor Q of the vibratory forces, F_i = -m_i w^2 Im(e^{i alpha_i} Q) [m].

    Q = 1/2 conj(W) H + rho e^{-i beta}: 000 eq (40)-(43) in the complex form of
    :func:`.vibratory.vibratory_forces` (W the residual unbalance, H = g_x e^{i phi_x} +
    g_y e^{i phi_y}). F = 0 needs Q = 0 (balanced) or every ball on the line of Q (aligned).

    Parameters
    ----------
    system : autobalance.models.System
        Drum, suspension and balancer (masses [kg], R [m], rho [m], beta [rad]).
    speed : float
        Spin speed w [rad/s], > 0.
    alpha : array_like (..., N)
        Ball angles from the unbalance [rad].

    Returns
    -------
    complex ndarray (...)
        Q [m].
    """
    w = _speed(speed)
    a = _angles(system, alpha)
    b = system.balancer
    W = residual_unbalance(system, a)
    return 0.5 * np.conj(W) * _H(system, w) + b.eccentricity * np.exp(-1j * b.eccentricity_angle)


def balanced_unbalance(system: System, speed: float) -> complex:
    """Residual unbalance W* on the balanced states, where the force on every ball vanishes [kg*m].

    Q = 0 in :func:`force_phasor` gives W* = -2 rho e^{i beta} / conj(H). Without race
    eccentricity W* = 0 (full compensation, 000 eq 22 with no deviation). Far above the natural
    frequencies H -> -2/M_t and W* -> M_t rho e^{i beta}: the mass centre sits on the race
    centre, the limit of 000 eq (46)-(47).

    Parameters
    ----------
    system : autobalance.models.System
        Suspension (kx, ky [N/m], cx, cy [N*s/m]), M_t [kg], rho [m], beta [rad].
    speed : float
        Spin speed w [rad/s], > 0.

    Returns
    -------
    complex
        W* [kg*m] (modulus: the residual unbalance of every balanced state at this speed).
    """
    w = _speed(speed)
    b = system.balancer
    if b.eccentricity == 0.0:
        return 0j
    H = _H(system, w)
    if H == 0:                                      # pragma: no cover - no finite suspension gives it
        return complex(math.nan, math.nan)
    return complex(-2.0 * b.eccentricity * np.exp(1j * b.eccentricity_angle) / np.conj(H))


def _ball_target(system, w: float) -> complex:
    """T = W* - U - sum(m_i) rho e^{i beta}: the sum sum_i m_i R e^{i alpha_i} of a balanced state [kg*m]."""
    b = system.balancer
    n = b.n_balls
    fixed = complex(residual_unbalance(system, np.zeros(n))) - float(np.sum(b.masses * b.race_radius))
    return balanced_unbalance(system, w) - fixed


def _mass_groups(b) -> list:
    """Indices of balls of equal mass (permuting them leaves the physics unchanged)."""
    m = b.masses
    out = []
    for i in range(b.n_balls):
        for g in out:
            if m[i] == m[g[0]]:
                g.append(i)
                break
        else:
            out.append([i])
    return out


def aligned_equilibria(system: System, speed: float, max_patterns: int = 65536) -> np.ndarray:
    """The isolated equilibria with Q != 0 in closed form: every ball on the line of Q.

    With alpha_i = phi (sigma_i = +1) or phi + pi (sigma_i = -1), s = sum sigma_i m_i R and
    P = 1/2 conj(U + sum m_i rho e^{i beta}) H + rho e^{-i beta}, the equilibrium condition
    Im(e^{i phi} Q) = 0 of 000 eq (40)-(43) becomes |P| sin(phi + arg P) = -1/2 s Im(H): zero or two
    solutions phi per sign pattern. Patterns differing by a permutation of equal balls are
    enumerated once. Points with Q = 0 (balanced) are left to :func:`find_equilibrium_set`.

    Parameters
    ----------
    system : autobalance.models.System
        Drum, suspension and balancer (N >= 1).
    speed : float
        Spin speed w [rad/s], > 0.
    max_patterns : int
        Most sign patterns to enumerate, prod over groups of equal balls of (size + 1) [-].

    Returns
    -------
    ndarray (K, N)
        Ball angles [rad], wrapped to (-pi, pi], one row per pattern and root (not deduplicated).
    """
    w = _speed(speed)
    b = system.balancer
    n = b.n_balls
    if n < 1:
        raise ParameterError("balancer.n_balls", n, "needs at least one ball")
    groups = _mass_groups(b)
    count = math.prod(len(g) + 1 for g in groups)
    if count > max_patterns:
        raise ParameterError("balancer.ball_mass", [float(v) for v in b.masses],
                             f"{count} sign patterns of distinct masses; at most {max_patterns}")
    mR = b.masses * b.race_radius
    H = _H(system, w)
    W0 = complex(residual_unbalance(system, np.zeros(n))) - float(mR.sum())
    P = 0.5 * np.conj(W0) * H + b.eccentricity * np.exp(-1j * b.eccentricity_angle)
    out = []
    if P == 0:
        return np.zeros((0, n))
    for ks in itertools.product(*[range(len(g) + 1) for g in groups]):
        sig = np.ones(n)
        for g, k in zip(groups, ks):
            sig[g[:k]] = -1.0
        r = -0.5 * float((sig * mR).sum()) * H.imag / abs(P)
        if abs(r) > 1.0:
            continue
        shift = np.where(sig < 0, math.pi, 0.0)
        for phi in {math.asin(r), math.pi - math.asin(r)}:
            out.append(_wrap(phi - np.angle(P) + shift))
    return np.array(out).reshape(-1, n)


def _balanced_pair(system, target: complex) -> list:
    """The two balanced states of two balls, m_1 R e^{i a_1} + m_2 R e^{i a_2} = T (a triangle)."""
    s1, s2 = system.balancer.masses * system.balancer.race_radius
    t = abs(target)
    if t == 0.0:
        return []
    c = (s1 * s1 + t * t - s2 * s2) / (2.0 * s1 * t)
    if abs(c) > 1.0:
        return []
    out = []
    for sgn in (1.0, -1.0):
        a1 = np.angle(target) + sgn * math.acos(c)
        a2 = np.angle(target - s1 * np.exp(1j * a1))
        out.append(_wrap(np.array([a1, a2])))
    return out


# -- the balanced families -----------------------------------------------------------------------
def _constraint_jacobian(system, alpha) -> np.ndarray:
    """d(Re W, Im W)/d alpha_j = (-m_j R sin alpha_j, m_j R cos alpha_j) [kg*m/rad], shape (..., 2, N)."""
    b = system.balancer
    a = np.asarray(alpha, float)
    mR = b.masses * b.race_radius
    return np.stack([-mR * np.sin(a), mR * np.cos(a)], axis=-2)


def family_tangent(system: System, alpha: npt.ArrayLike, rtol: float = 1e-8) -> np.ndarray:
    """Orthonormal basis of the tangent space of the balanced family through alpha [-].

    The family is W(alpha) = W* (two real conditions, :func:`balanced_unbalance`); its tangent
    is the null space of the 2 x N Jacobian d(Re W, Im W)/d alpha, of dimension N - 2 where
    the balls are not all on one line (Green et al. 2008; the module docstring).

    Parameters
    ----------
    system : autobalance.models.System
        Balancer masses [kg] and R [m].
    alpha : array_like (N,)
        A point of the family [rad].
    rtol : float
        Singular values below rtol x the largest count as zero [-].

    Returns
    -------
    ndarray (N, d)
        Columns: unit tangent vectors in angle space [rad/rad]; d = N - rank.
    """
    C = _constraint_jacobian(system, alpha)
    _, sv, vh = np.linalg.svd(C)
    rank = int(np.sum(sv > rtol * max(sv.max(), 1e-300)))
    return vh[rank:].T.copy()


def _project(system, target: complex, a, iters: int = 30, atol: float = 0.0):
    """Gauss-Newton projection onto sum m_i R e^{i alpha_i} = T (least-norm steps, vectorised;
    stops early once every residual is below atol [kg*m])."""
    b = system.balancer
    mR = b.masses * b.race_radius
    a = np.array(a, float)
    for _ in range(iters):
        r = (mR * np.exp(1j * a)).sum(axis=-1) - target
        if np.all(np.abs(r) < atol):
            break
        C = _constraint_jacobian(system, a)
        rv = np.stack([r.real, r.imag], axis=-1)
        G = C @ np.swapaxes(C, -1, -2)
        try:
            y = np.linalg.solve(G, rv[..., None])[..., 0]
        except np.linalg.LinAlgError:
            y = np.einsum("...ij,...j->...i", np.linalg.pinv(G), rv)
        step = np.einsum("...ji,...j->...i", C, y)
        a = a - np.clip(step, -0.5, 0.5)
    r = (mR * np.exp(1j * a)).sum(axis=-1) - target
    return a, np.abs(r)


def _cross_dist(A, B, same_balls: bool) -> np.ndarray:
    """max_i |a_i - b_i| (wrapped) [rad] between every row of A (K, N) and of B (L, N), modulo
    relabelling identical balls (sorted angles compared under every cyclic shift): (K, L)."""
    A = np.mod(np.atleast_2d(A), TWO_PI)
    B = np.mod(np.atleast_2d(B), TWO_PI)
    if not same_balls:
        d = np.abs(A[:, None, :] - B[None, :, :])
        return np.minimum(d, TWO_PI - d).max(axis=-1)
    A = np.sort(A, axis=-1)
    B = np.sort(B, axis=-1)
    out = None
    for k in range(A.shape[1]):
        d = np.abs(A[:, None, :] - np.roll(B, k, axis=-1)[None, :, :])
        d = np.minimum(d, TWO_PI - d).max(axis=-1)
        out = d if out is None else np.minimum(out, d)
    return out


def _trace(system, target: complex, a0, step: float, atol: float, max_steps: int = 20000):
    """Follow a one-dimensional balanced family from a0 (predictor along the tangent, Gauss-Newton
    corrector) until it closes on a0 (modulo 2 pi; balls labelled: modulo relabelling the curve
    folds back where two identical balls coincide, so closure is tested on the labelled curve)."""
    mR = system.balancer.masses * system.balancer.race_radius
    n = mR.size

    def rows(a):
        e = np.exp(1j * a)
        return e, -mR * e.imag, mR * e.real

    def tangent(c1, c2, t_prev):
        if n == 3:
            t = np.array([c1[1] * c2[2] - c1[2] * c2[1], c1[2] * c2[0] - c1[0] * c2[2],
                          c1[0] * c2[1] - c1[1] * c2[0]])
            nt = math.sqrt(t @ t)
            if nt < 1e-8 * (c1 @ c1 + c2 @ c2):
                return None
            t = t / nt
        else:
            tb = family_tangent(system, a)
            if tb.shape[1] != 1:
                return None
            t = tb[:, 0]
        return t if t_prev is None or t @ t_prev >= 0 else -t

    a = np.array(a0, float)
    _, c1, c2 = rows(a)
    t = tangent(c1, c2, None)
    pts = [a.copy()]
    for k in range(max_steps):
        if t is None:
            return np.array(pts), False
        a = a + step * t
        for _ in range(8):                  # least-norm Gauss-Newton back onto the set
            e, c1, c2 = rows(a)
            r = (mR * e).sum() - target
            if abs(r) < 1e-3 * atol:
                break
            g11, g12, g22 = c1 @ c1, c1 @ c2, c2 @ c2
            det = g11 * g22 - g12 * g12
            if det <= 0.0:
                return np.array(pts), False
            y1 = (g22 * r.real - g12 * r.imag) / det
            y2 = (g11 * r.imag - g12 * r.real) / det
            a = a - (c1 * y1 + c2 * y2)
        e, c1, c2 = rows(a)
        if not abs((mR * e).sum() - target) < atol:
            return np.array(pts), False
        t = tangent(c1, c2, t)
        if k >= 3 and np.abs(np.mod(a - pts[0] + math.pi, TWO_PI) - math.pi).max() < 0.75 * step:
            return np.array(pts), True
        pts.append(a.copy())
    return np.array(pts), False


def _dedupe(rows, same_balls: bool, tol: float = 1e-6) -> list:
    """The rows in order, each dropped when within tol [rad] of an earlier kept one (modulo 2 pi
    and relabelling of identical balls)."""
    if len(rows) == 0:
        return []
    P = np.array(rows, float).reshape(len(rows), -1)
    D = _cross_dist(P, P, same_balls)
    keep = np.zeros(len(P), bool)
    for i in range(len(P)):
        keep[i] = not np.any(D[i, :i][keep[:i]] < tol)
    return [P[i] for i in np.nonzero(keep)[0]]


def _starts(n: int, count: int) -> np.ndarray:
    """Deterministic starts: equal spacing in both senses at 8 rotations, then pseudo-random."""
    base = TWO_PI * np.arange(n) / n
    rows = [sg * base + TWO_PI * k / 8 for sg in (1.0, -1.0) for k in range(8)]
    rng = np.random.default_rng(20140)
    rows += list(rng.uniform(-math.pi, math.pi, (max(count - len(rows), 0), n)))
    return np.array(rows)


def _family_points(system, w: float, n_samples: int, step: float):
    """Sample points of every balanced family: list of (points (K, N), dimension, traced, length)."""
    b = system.balancer
    n = b.n_balls
    T = _ball_target(system, w)
    cap = float(np.sum(b.masses)) * b.race_radius
    atol = 1e-10 * cap
    same = bool(np.allclose(b.masses, b.masses[0]))
    seeds, res = _project(system, T, _starts(n, 24))
    seeds = seeds[res < atol]
    if seeds.size == 0:
        return []
    dims = [family_tangent(system, a).shape[1] for a in seeds]
    d = min(dims)           # the generic dimension; where the balls lie on one line it is larger
    if d == 0:
        return []
    seeds = seeds[np.array(dims) == d]
    fams = []
    if d == 1:
        covered = np.zeros(len(seeds), bool)
        for i, s in enumerate(seeds):
            if covered[i]:
                continue
            pts, closed = _trace(system, T, s, step, atol)
            covered |= _cross_dist(seeds, pts, same).min(axis=1) < 2.0 * step
            uniq = _dedupe(list(_wrap(pts)), same, 0.5 * step)      # one copy per relabelling
            idx = np.unique(np.round(np.linspace(0, len(uniq), n_samples, endpoint=False)).astype(int))
            fams.append((_regular(system, [uniq[i] for i in idx if i < len(uniq)], d), 1, closed,
                         step * len(pts) if closed else math.nan))
        return fams
    more, r2 = _project(system, T, _starts(n, 40 + 12 * n_samples))
    pool = np.concatenate([seeds, more[r2 < atol]])
    chosen = [pool[0]]                        # farthest-point subsample (modulo relabelling)
    dmin = _cross_dist(pool[0], pool, same)[0]
    while len(chosen) < n_samples and dmin.max() > 1e-6:
        k = int(np.argmax(dmin))
        chosen.append(pool[k])
        dmin = np.minimum(dmin, _cross_dist(pool[k], pool, same)[0])
    return [(_regular(system, _wrap(np.array(chosen)), d), d, False, math.nan)]


def _regular(system, pts, d: int) -> np.ndarray:
    """The points (K, N) [rad] where the family has its dimension d: a point with every ball on
    one line (the Jacobian of W loses rank, the family crosses itself there) is left out
    (the family is a manifold of dimension N - 2 where that Jacobian has full rank; Green et
    al. 2008)."""
    pts = np.asarray(pts, float).reshape(len(pts), system.balancer.n_balls)
    keep = np.array([family_tangent(system, a).shape[1] == d for a in pts], bool)
    return pts[keep] if len(pts) else pts


def deflate(A: npt.ArrayLike, E: npt.ArrayLike) -> dict:
    """Eigenvalues of A with the subspace spanned by E set aside (neutral directions).

    In an orthonormal basis [Q, C] with span Q = span E, A = [[Q'AQ, Q'AC], [C'AQ, C'AC]].
    When span E is invariant (A E in span E: C'AQ = 0) the matrix is block triangular and
    its eigenvalues are those of Q'AQ (the neutral ones, 0 for a family of equilibria of
    dx/dt = A x, 1 for a family of periodic orbits of a monodromy matrix) and of C'AC (the
    transverse ones, which decide stability).

    Parameters
    ----------
    A : array_like (n, n)
        State matrix [1/s] or monodromy matrix [-] (any consistent units).
    E : array_like (n, d)
        Columns spanning the neutral subspace [-] (in the state's units).

    Returns
    -------
    dict
        "neutral" (d,) and "transverse" (n - d,) eigenvalues; "invariance_residual"
        ||C'AQ|| / ||A|| [-] (0 when span E is exactly invariant).
    """
    A = np.asarray(A, float)
    E = np.asarray(E, float)
    n, d = E.shape
    Q, _ = np.linalg.qr(E)
    _, _, vh = np.linalg.svd(Q.T)
    C = vh[d:].T
    nA = max(np.linalg.norm(A, 2), 1e-300)
    return {"neutral": np.linalg.eigvals(Q.T @ A @ Q), "transverse": np.linalg.eigvals(C.T @ A @ C),
            "invariance_residual": float(np.linalg.norm(C.T @ A @ Q, 2) / nA)}
