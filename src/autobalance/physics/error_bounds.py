"""Position-error bounds of the balls and the residual unbalance they leave (seed 000).

* Rolling resistance, 000 eq (20)-(32): a ball cannot move while |F_i| <= F_ir = m R w^2 f/r.
* Race eccentricity, 000 eq (44)-(47): the equilibrium itself moves.
* Suspension dry friction, 000 eq (48)-(49): a small residual force cannot move the tub.
* Ball natural frequency about its equilibrium, 000 eq (52)-(55).
* All of them at one speed, with the true worst case of the balls at rest:
  :func:`error_bound_summary`.

Pure functions of SI floats/arrays (angles [rad], speeds [rad/s], lengths [m], forces [N],
unbalances [kg*m]); a System is passed where the harmonic response is needed.
"""
from __future__ import annotations

import dataclasses
import itertools
import math
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from ..models._validate import array as _array
from ..models._validate import finite as _finite
from ..models._validate import nonneg as _nonneg
from ..models._validate import positive as _positive
from .equilibria import find_equilibria
from .iso1940 import grade_class, grade_value
from .unbalance import residual_unbalance
from .vibratory import _speed, force_jacobian, gain_phase
from .worst_case import residual_bound

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = [
    "ball_natural_frequencies", "ball_natural_frequency_approx", "ball_natural_frequency_single",
    "eccentricity_deviation_exact", "error_bound_summary", "eccentricity_deviation_single", "eccentricity_equilibrium", "eccentricity_residual_linear",
    "friction_force_for_deviation", "rolling_deadband", "rolling_deadband_single",
    "rolling_resistance_force", "symmetric_rolling_deviation", "suspension_friction_deviation",
    "suspension_is_stuck",
]


def _out(a):
    return float(a) if np.ndim(a) == 0 else a


# -- rolling resistance ------------------------------------------------------------------------
def rolling_resistance_force(ball_mass: float | npt.ArrayLike, race_radius: float,
                             speed: float | npt.ArrayLike, f_r: float | npt.ArrayLike):
    """Rolling resistance of a ball F_ir = m R w^2 f/r [N] (000 eq 20).

    Parameters
    ----------
    ball_mass : float or array_like
        m [kg], > 0.
    race_radius : float
        R [m], > 0.
    speed : float or array_like
        w [rad/s], >= 0.
    f_r : float or array_like
        Coefficient of rolling resistance over ball radius f/r [-], >= 0.
    """
    m = _array("ball_mass", ball_mass, strict=True)
    R = _positive("race_radius", race_radius)
    w = _array("speed", speed, strict=False)
    fr = _array("f_r", f_r, strict=False)
    return _out(m * R * w * w * fr)


def rolling_deadband_single(system: System, speed: float | npt.ArrayLike, f_r: float,
                            static_moment: float | None = None):
    """Largest position error of one ball from rolling resistance (000 eq 24, Fig. 12) [rad].

    |Delta alpha_r| <= 2 R (f/r) / |a_x cos(phi_x) + a_y cos(phi_y)|, with a_x, a_y the drum
    amplitudes for the ball's static moment S = m R (= Me in 000). Between the suspension
    frequencies the denominator crosses zero and the bound is infinite (no balancing).

    Parameters
    ----------
    system : autobalance.models.System
        Drum and suspension (M_t [kg], kx, ky [N/m], cx, cy [N*s/m]); R [m] of its balancer.
    speed : float or array_like
        Spin speed w [rad/s], > 0.
    f_r : float
        f/r [-], >= 0.
    static_moment : float, optional
        S [kg*m]; default the unbalance Me (000: mR = Me).

    Returns
    -------
    float or ndarray
        Delta alpha_max [rad] (inf where the denominator vanishes).
    """
    w = _array("speed", speed, strict=True)
    fr = _nonneg("f_r", f_r)
    S = system.rotor.unbalance if static_moment is None else _positive("static_moment", static_moment)
    R = system.balancer.race_radius
    gx, px, gy, py = gain_phase(system, w)
    den = np.abs(S * (np.asarray(gx) * np.cos(px) + np.asarray(gy) * np.cos(py)))
    with np.errstate(divide="ignore"):
        return _out(np.where(den > 0, 2.0 * R * fr / den, np.inf))


def symmetric_rolling_deviation(race_radius: float, eccentricity: float, f_r: float) -> float:
    """Symmetric deviation of two balls at +-120 deg, 000 eq (32): 2 (R/e)(f/r) [rad].

    Eq (30)-(31) are |d1 - d2/2| <= (R/e)(f/r) and |d2 - d1/2| <= (R/e)(f/r) (w >> w_x, w_y,
    a = e, phi = pi); d1 = d2 gives eq (32).

    Parameters
    ----------
    race_radius : float
        R [m], > 0.
    eccentricity : float
        e = Me/M [m], > 0.
    f_r : float
        f/r [-], >= 0.
    """
    R = _positive("race_radius", race_radius)
    e = _positive("eccentricity", eccentricity)
    return 2.0 * R / e * _nonneg("f_r", f_r)


def rolling_deadband(system: System, speed: float, f_r: float,
                     alpha_eq: npt.ArrayLike | None = None) -> dict:
    """Dead band of N balls about their equilibrium from rolling resistance (000 eq 21-22, 27-31).

    Linearising F_i about the equilibrium, |sum_j J_ij d_j| <= m_i R w^2 f/r for every ball
    (eq 27-29 with the exact Jacobian instead of a = e, phi = pi). The dead band is the
    parallelotope d = J^-1 (F_r * s), |s_i| <= 1; its vertices s in {-1, 1}^N give the largest
    deviations. The residual unbalance at each vertex is eq (22), evaluated exactly. On a
    continuous family of balanced states (N >= 3, J singular) the band is unbounded along the
    family, where neither the forces nor the residual change: the deviations are then those
    across the family (linear programs, d orthogonal to the null space of J). This is the
    linearised band about one equilibrium; the true worst case over every rest state is
    :func:`autobalance.physics.worst_case.residual_bound`.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (N >= 1 balls).
    speed : float
        w [rad/s], > 0.
    f_r : float
        f/r [-], >= 0.
    alpha_eq : array_like (N,), optional
        Equilibrium [rad]; default the stable equilibrium of least residual unbalance.

    Returns
    -------
    dict
        "alpha_eq_rad", "vertices_rad" (2^N, N), "max_deviation_rad" (N,) (eq 28-29),
        "residual_unbalance_kg_m" (2^N,) (eq 22), "max_residual_unbalance_kg_m",
        "max_amplitude_x_m", "max_amplitude_y_m" (eq 25-26 on the worst vertex).
    """
    w = _speed(speed)
    fr = _nonneg("f_r", f_r)
    b = system.balancer
    if alpha_eq is None:
        stable = [e for e in find_equilibria(system, w) if e.ks_stable and not e.overlap]
        if not stable:
            raise ParameterError("speed", w, "no stable equilibrium of the balls at this speed")
        alpha_eq = stable[0].alpha
    a = np.asarray(alpha_eq, float)
    J = force_jacobian(system, w, a)
    Fr = b.masses * b.race_radius * w * w * fr
    sv = np.linalg.svd(J, compute_uv=False)
    neutral = int(np.sum(sv <= 1e-9 * sv.max())) if sv.max() > 0 else b.n_balls
    if neutral == 0:
        S = np.array(list(itertools.product((-1.0, 1.0), repeat=b.n_balls)))
        V = np.linalg.solve(J, (Fr * S).T).T
    else:
        V = _transverse_deadband(system, J, Fr, a, neutral)
    res = np.abs(residual_unbalance(system, a + V))
    gx, _, gy, _ = gain_phase(system, w)
    rmax = float(res.max())
    return {"alpha_eq_rad": a, "vertices_rad": V, "max_deviation_rad": np.abs(V).max(axis=0),
            "residual_unbalance_kg_m": res, "max_residual_unbalance_kg_m": rmax,
            "max_amplitude_x_m": rmax * gx, "max_amplitude_y_m": rmax * gy,
            "neutral_directions": neutral}


def _transverse_deadband(system, J, Fr, alpha, neutral: int, n_dir: int = 72) -> np.ndarray:
    """Extreme points of the dead band |J d| <= Fr across a family of equilibria (N >= 3: J
    singular; moving along the family's neutral directions changes no force and no residual).

    Linear programs over d orthogonal to the null space of J: max and min of each d_k, and the
    extremes of the linearised residual change sum_j m_j R i e^{i alpha_j} d_j in ``n_dir``
    directions. Returns the optimal vertices (rows) [rad]."""
    from scipy.optimize import linprog

    n = J.shape[0]
    _, _, vt = np.linalg.svd(J)
    null = vt[n - neutral:]
    A_ub = np.vstack([J, -J])
    b_ub = np.concatenate([Fr, Fr])
    b = system.balancer
    dW = b.masses * b.race_radius * 1j * np.exp(1j * np.asarray(alpha, float))
    objectives = [np.eye(n)[k] * sgn for k in range(n) for sgn in (1.0, -1.0)]
    objectives += [np.real(np.exp(-1j * phi) * dW) for phi in 2 * np.pi * np.arange(n_dir) / n_dir]
    rows = []
    for obj in objectives:
        r = linprog(-obj, A_ub=A_ub, b_ub=b_ub, A_eq=null, b_eq=np.zeros(neutral),
                    bounds=[(None, None)] * n, method="highs")
        if r.status == 0:
            rows.append(r.x)
    return np.array(rows) if rows else np.zeros((1, n))


# -- eccentricity ------------------------------------------------------------------------------
def eccentricity_deviation_single(eccentricity: float, rho: float, beta: float | npt.ArrayLike):
    """Deviation of one ball from alpha_f = pi caused by a race eccentricity, 000 eq (45) [rad].

    Delta alpha_rho = -rho sin(beta) / (e + rho cos(beta))  (w >> w_x, w_y, rho << R).

    Parameters
    ----------
    eccentricity : float
        e = Me/M [m], > 0.
    rho : float
        Race eccentricity [m], >= 0.
    beta : float or array_like
        Angle of the eccentricity from the unbalance [rad].
    """
    e = _positive("eccentricity", eccentricity)
    r = _nonneg("rho", rho)
    b = np.asarray(beta, float)
    if not np.all(np.isfinite(b)):
        raise ParameterError("beta", beta, "must be finite [rad]")
    return _out(-r * np.sin(b) / (e + r * np.cos(b)))


def eccentricity_deviation_exact(system: System, speed: float, rho: float,
                                 betas: npt.ArrayLike) -> np.ndarray:
    """Deviation of one ball from alpha_f = pi for a race eccentricity: the exact root of 000
    eq (44) [rad], the counterpart of eq (45) (000 Fig. 15).

    For each beta the kinetic-static equilibria of ``system`` with the balancer's eccentricity
    set to (rho, beta) are found (:func:`find_equilibria`); the stable one nearest pi is taken.

    Parameters
    ----------
    system : autobalance.models.System
        The machine with one ball (000: m R = Me).
    speed : float
        w [rad/s], > 0.
    rho : float
        Race eccentricity [m], >= 0.
    betas : array_like
        Angles of the eccentricity from the unbalance [rad].

    Returns
    -------
    ndarray
        Delta alpha_rho [rad] per beta, wrapped to (-pi, pi]; NaN where no equilibrium is stable.
    """
    w = _speed(speed)
    r = _nonneg("rho", rho)
    b = np.atleast_1d(np.asarray(betas, float))
    if not np.all(np.isfinite(b)):
        raise ParameterError("betas", betas, "must be finite [rad]")
    if system.balancer.n_balls != 1:
        raise ParameterError("balancer.n_balls", system.balancer.n_balls, "must be 1 (000 eq 44)")
    out = np.full(b.shape, np.nan)
    for k, beta in enumerate(b):
        bal = dataclasses.replace(system.balancer, eccentricity=r, eccentricity_angle=float(beta))
        st = [e for e in find_equilibria(dataclasses.replace(system, balancer=bal), w) if e.ks_stable]
        dev = [float(np.angle(np.exp(1j * (e.alpha[0] - math.pi)))) for e in st]
        if dev:
            out[k] = min(dev, key=abs)
    return out


def eccentricity_equilibrium(system: System, speed: float) -> dict:
    """Ball positions with a race eccentricity, 000 eq (46), and the residual unbalance (eq 47).

    Solves F_i(alpha) = 0 with rho, beta of the balancer (:func:`find_equilibria`) and takes the
    stable equilibrium nearest the ideal one (same system with rho = 0).

    Parameters
    ----------
    system : autobalance.models.System
        The machine with ``balancer.eccentricity`` rho [m] and ``eccentricity_angle`` beta [rad].
    speed : float
        w [rad/s], > 0.

    Returns
    -------
    dict
        "alpha_ideal_rad", "alpha_rad", "deviation_rad" (alpha - ideal, wrapped),
        "residual_unbalance_kg_m" (exact |W|), "residual_linear_kg_m" (eq 47, from the
        deviations only), "amplitude_x_m", "amplitude_y_m".
    """
    w = _speed(speed)
    b = system.balancer
    ideal_sys = dataclasses.replace(system, balancer=dataclasses.replace(b, eccentricity=0.0))
    ideal = [e for e in find_equilibria(ideal_sys, w) if e.ks_stable and not e.overlap]
    cands = [e for e in find_equilibria(system, w) if e.ks_stable and not e.overlap]
    if not ideal or not cands:
        raise ParameterError("speed", w, "no stable equilibrium of the balls at this speed")
    a0 = ideal[0].alpha
    best = min(cands, key=lambda e: np.abs(np.angle(np.exp(1j * (e.alpha - a0)))).max())
    dev = np.angle(np.exp(1j * (best.alpha - a0)))
    lin = eccentricity_residual_linear(b.masses * b.race_radius, a0, dev)
    gx, _, gy, _ = gain_phase(system, w)
    return {"alpha_ideal_rad": a0, "alpha_rad": best.alpha, "deviation_rad": dev,
            "residual_unbalance_kg_m": best.residual_unbalance, "residual_linear_kg_m": lin,
            "amplitude_x_m": best.residual_unbalance * gx,
            "amplitude_y_m": best.residual_unbalance * gy}


def eccentricity_residual_linear(static_moments: npt.ArrayLike, alpha_f: npt.ArrayLike,
                                 deviation: npt.ArrayLike) -> float:
    """Residual unbalance from small ball deviations, 000 eq (47) [kg*m].

    dMe_x = -sum m_i R sin(alpha_if) d_i, dMe_y = sum m_i R cos(alpha_if) d_i; returns |dMe|.

    Parameters
    ----------
    static_moments : array_like (N,)
        m_i R [kg*m].
    alpha_f : array_like (N,)
        Ideal positions [rad].
    deviation : array_like (N,)
        Deviations d_i [rad].
    """
    S = np.asarray(static_moments, float)
    a = np.asarray(alpha_f, float)
    d = np.asarray(deviation, float)
    if not (S.shape == a.shape == d.shape):
        raise ParameterError("deviation", d.tolist(), f"needs {S.size} values like static_moments")
    return float(abs(np.sum(S * d * (-np.sin(a) + 1j * np.cos(a)))))


# -- suspension dry friction -------------------------------------------------------------------
def suspension_friction_deviation(friction_force: float, angle: float, unbalance: float,
                                  speed: float | npt.ArrayLike, alpha_f: float = 2 * math.pi / 3):
    """Largest ball error that the suspension dry friction can hold, 000 eq (48)-(49) [rad].

    Two balls of mR = Me near +-alpha_f: w^2 |Me + 2 m R cos(alpha_f + d)| <= 2 F cos(gamma)
    linearises to |d| < F cos(gamma) / (Me sin(alpha_f) w^2) (eq 49).

    Parameters
    ----------
    friction_force : float
        F of one damper [N] (000: 2F = 140 N), >= 0.
    angle : float
        gamma, damper inclination to x [rad] (000: 61 deg).
    unbalance : float
        Me [kg*m], > 0.
    speed : float or array_like
        w [rad/s], > 0.
    alpha_f : float
        Ideal ball angle [rad] (2 pi/3 for two balls with mR = Me).
    """
    F = _nonneg("friction_force", friction_force)
    g = _finite("angle", angle)
    U = _positive("unbalance", unbalance)
    w = _array("speed", speed, strict=True)
    af = _finite("alpha_f", alpha_f)
    s = math.sin(af)
    if abs(s) < 1e-12:
        raise ParameterError("alpha_f", alpha_f, "must not be a multiple of pi")
    return _out(F * math.cos(g) / (U * abs(s) * w * w))


def friction_force_for_deviation(deviation: float, angle: float, unbalance: float, speed: float,
                                 alpha_f: float = 2 * math.pi / 3) -> float:
    """Inverse of eq (49): the damper force F [N] that holds a ball error d [rad] (000 eq 64-66).

    Parameters
    ----------
    deviation : float
        d [rad], >= 0.
    angle : float
        gamma [rad].
    unbalance : float
        Me [kg*m], > 0.
    speed : float
        w [rad/s], > 0.
    alpha_f : float
        Ideal ball angle [rad].
    """
    d = _nonneg("deviation", deviation)
    g = _finite("angle", angle)
    c = math.cos(g)
    if abs(c) < 1e-12:
        raise ParameterError("angle", angle, "cos(angle) must not be 0")
    return d * _positive("unbalance", unbalance) * abs(math.sin(_finite("alpha_f", alpha_f))) \
        * _positive("speed", speed) ** 2 / abs(c)


def suspension_is_stuck(residual_x: float, speed: float, friction_force: float,
                        angle: float) -> bool:
    """000 eq (48): the tub cannot move along x when w^2 |dMe_x| <= 2 F cos(gamma).

    Parameters
    ----------
    residual_x : float
        x component of the residual unbalance [kg*m].
    speed : float
        w [rad/s], > 0.
    friction_force : float
        F per damper [N], >= 0.
    angle : float
        gamma [rad].
    """
    return bool(_positive("speed", speed) ** 2 * abs(_finite("residual_x", residual_x))
                <= 2 * _nonneg("friction_force", friction_force) * math.cos(_finite("angle", angle)))


# -- ball natural frequency --------------------------------------------------------------------
def ball_natural_frequency_single(system: System, speed: float,
                                  static_moment: float | None = None) -> float:
    """Natural frequency of one ball about alpha = pi, 000 eq (53)-(54) [rad/s].

    w_alpha = w sqrt((-a_0x cos(phi_x) - a_0y cos(phi_y)) / (2 R)); NaN when the radicand is
    negative (alpha = pi unstable, eq 12).

    Parameters
    ----------
    system : autobalance.models.System
        Drum (Me [kg*m], M_t [kg], suspension) and R [m] of its balancer.
    speed : float
        w [rad/s], > 0.
    static_moment : float, optional
        Unused by eq 54 except to state mR = Me [kg*m]; kept for symmetry (default Me).
    """
    w = _speed(speed)
    gx, px, gy, py = gain_phase(system, w)
    U = system.rotor.unbalance
    rad = (-U * gx * math.cos(px) - U * gy * math.cos(py)) / (2.0 * system.balancer.race_radius)
    return w * math.sqrt(rad) if rad >= 0 else math.nan


def ball_natural_frequency_approx(speed: float, eccentricity: float, race_radius: float) -> float:
    """000 eq (55): w_alpha ~ w sqrt(e/R) for w >> w_x, w_y [rad/s].

    Parameters
    ----------
    speed : float
        w [rad/s], > 0.
    eccentricity : float
        e = Me/M [m], > 0.
    race_radius : float
        R [m], > 0.
    """
    return _positive("speed", speed) * math.sqrt(_positive("eccentricity", eccentricity)
                                                 / _positive("race_radius", race_radius))


def ball_natural_frequencies(system: System, speed: float, alpha: npt.ArrayLike) -> np.ndarray:
    """Natural frequencies of N balls about an equilibrium, 000 eq (52) with m_z [rad/s].

    Undamped: I_eff d'' = R J d with I_eff = m R^2 + I (R/r)^2; for each eigenvalue lambda of
    R J / I_eff the oscillation frequency |Im sqrt(lambda)| (sqrt(-lambda) for a real negative
    one; a damped suspension makes J non-symmetric and lambda slightly complex). 0 for a neutral
    direction (|lambda| <= 1e-9 max |lambda|: along the family of balanced states of N >= 3),
    NaN for a diverging one (Re lambda >= 0).

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speed : float
        w [rad/s], > 0.
    alpha : array_like (N,)
        Equilibrium [rad].
    """
    b = system.balancer
    R = b.race_radius
    ieff = b.masses * R * R + b.inertias * (R / b.ball_radius) ** 2
    lam = np.linalg.eigvals(R * force_jacobian(system, speed, alpha) / ieff[:, None])
    scale = np.abs(lam).max()
    neutral = np.abs(lam) <= 1e-9 * scale if scale > 0 else np.ones(lam.shape, bool)
    freq = np.abs(np.sqrt(lam.astype(complex)).imag)
    out = np.where(neutral, 0.0, np.where(lam.real < 0, freq, np.nan))
    return np.sort(out)


# -- every bound at one speed ------------------------------------------------------------------
def error_bound_summary(system: System, speed: float, rolling_resistance: float,
                        nominal_speed: float) -> dict:
    """Every position-error bound of the balls at one speed, and the true worst-case residual
    unbalance of the balls at rest: rolling resistance (000 eq 24, 27-32), race eccentricity
    (eq 44-47), suspension dry friction (eq 48-49), the balls' natural frequencies (eq 52-55)
    and :func:`autobalance.physics.worst_case.residual_bound` with its ISO 1940 grade.

    The N-ball bands and frequencies are taken about the balanced state of the balancer with
    its race eccentricity set to 0 (the rolling dead band of the ideal race); on a family of
    balanced states (N >= 3) the deviations are those across the family and its neutral
    directions have frequency 0.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (N >= 1 balls); its race eccentricity, damper friction and geometry.
    speed : float
        Spin speed w [rad/s], > 0, above the balancing onset (000 eq 12).
    rolling_resistance : float
        Rolling-resistance coefficient f/r of every ball [-], >= 0.
    nominal_speed : float
        Highest nominal operating speed Omega [rad/s] of the ISO 1940 grade.

    Returns
    -------
    dict
        ``speed_rad_s``, ``f_r``, ``n_balls``; rolling resistance: ``rolling_single_ball_rad``
        (eq 24), ``rolling_eq32_rad`` (eq 32), ``rolling_max_deviation_rad`` (N,) and
        ``rolling_max_residual_unbalance_kg_m`` (eq 27-31, 22), ``neutral_directions``;
        eccentricity: ``eccentricity_deviation_rad`` (N,), ``eccentricity_residual_unbalance_kg_m``
        (eq 46-47), ``eccentricity_eq45_single_rad`` (eq 45); ``friction_eq49_rad``
        (eq 49); ball frequencies: ``ball_frequency_eq54_rad_s``, ``ball_frequency_eq55_rad_s``,
        ``ball_frequencies_rad_s`` (N,) (eq 52); the worst case at rest: ``worst_residual_kg_m``,
        ``worst_grade_G_mm_s``, ``worst_grade_class_G_mm_s``, ``worst_rolling_kg_m``,
        ``worst_eccentricity_kg_m``, ``worst_friction_kg_m``, ``worst_separated``,
        ``capacity_kg_m``. Angles [rad], frequencies [rad/s], unbalances [kg*m], grades [mm/s].
    """
    w = _speed(speed)
    fr = _nonneg("rolling_resistance", rolling_resistance)
    omega = _positive("nominal_speed", nominal_speed)
    s, b, sus = system, system.balancer, system.suspension
    e = s.rotor.unbalance / s.rotor.mass
    ideal = dataclasses.replace(s, balancer=dataclasses.replace(b, eccentricity=0.0))
    db = rolling_deadband(ideal, w, fr)
    ecc = eccentricity_equilibrium(s, w)
    wb = residual_bound(s, w, rolling_resistance=fr)
    g = float(grade_value(wb["worst_residual_kg_m"], s.total_mass, omega))
    return {
        "speed_rad_s": w, "f_r": fr, "n_balls": b.n_balls,
        "rolling_single_ball_rad": rolling_deadband_single(s, w, fr),
        "rolling_eq32_rad": symmetric_rolling_deviation(b.race_radius, e, fr),
        "rolling_max_deviation_rad": db["max_deviation_rad"],
        "rolling_max_residual_unbalance_kg_m": db["max_residual_unbalance_kg_m"],
        "neutral_directions": db["neutral_directions"],
        "eccentricity_deviation_rad": ecc["deviation_rad"],
        "eccentricity_residual_unbalance_kg_m": ecc["residual_unbalance_kg_m"],
        "eccentricity_eq45_single_rad": eccentricity_deviation_single(
            e, b.eccentricity, b.eccentricity_angle),
        "friction_eq49_rad": suspension_friction_deviation(
            sus.dry_friction_force, sus.dry_friction_angle, s.rotor.unbalance, w),
        "ball_frequency_eq54_rad_s": ball_natural_frequency_single(s, w),
        "ball_frequency_eq55_rad_s": ball_natural_frequency_approx(w, e, b.race_radius),
        "ball_frequencies_rad_s": ball_natural_frequencies(ideal, w, db["alpha_eq_rad"]),
        "worst_residual_kg_m": wb["worst_residual_kg_m"], "worst_grade_G_mm_s": g,
        "worst_grade_class_G_mm_s": float(grade_class(g)),
        "worst_rolling_kg_m": wb["rolling_kg_m"], "worst_eccentricity_kg_m": wb["eccentricity_kg_m"],
        "worst_friction_kg_m": wb["friction_kg_m"], "worst_separated": wb["separated"],
        "capacity_kg_m": wb["capacity_kg_m"],
    }
