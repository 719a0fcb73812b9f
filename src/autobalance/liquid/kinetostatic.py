"""Kinetostatic steady state of a liquid (Leblanc) balancer on a vertical rotor (seed 001): the
one home of the liquid's equilibrium angle alpha0 (001 eq 2-3) and friction angle beta (001 eq 6).

Notation of 001: rotor unbalance D (angle 0), liquid unbalance D0 at angle alpha from D,
k = D0/D, resultant D_c; the eccentricities e = D/(M+m), e_c = D_c/(M+m); delta is the rotor's
phase angle between the unbalance force and the deflection ("external resistance").

Each formula is written once (:func:`_alpha0` for 001 eq 3, :func:`_sin_beta` and
:func:`_beta` for 001 eq 6) and evaluated either with numpy (the public functions, which
validate and vectorise over arrays) or with :mod:`math` on floats
(:func:`liquid_angle_scalar`, the right-hand side of the run-up integrator in
:mod:`.dynamics`, where numpy's per-call overhead would dominate).
"""
from __future__ import annotations

import math
from types import SimpleNamespace
from typing import TYPE_CHECKING

import numpy as np

from ..models._validate import ParameterError, positive

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["alpha0", "alpha0_residual", "balancing_efficiency", "eccentricity_ratio",
           "friction_angle", "friction_force", "friction_tan_bound", "jeffcott_phase",
           "laminar_pipe_force", "liquid_angle_scalar", "residual_lambda0"]

#: Elementary functions on arrays (numpy) and on floats (math); same results, see the module doc.
_NUMPY = SimpleNamespace(sqrt=np.sqrt, arccos=np.arccos, arcsin=np.arcsin, clip=np.clip)
_MATH = SimpleNamespace(sqrt=math.sqrt, arccos=math.acos, arcsin=math.asin,
                        clip=lambda x, lo, hi: min(max(x, lo), hi))


def _alpha0(sin2_delta, k, ops=_NUMPY):
    """001 eq 3 from sin^2(delta): alpha0 = pi - arccos((s2 + sqrt((s2 - 1)(s2 - k^2)))/k) [rad].

    The square root is clipped at 0 where 001 eq 2 has no root (k < |sin delta|) and the arccos
    argument to [-1, 1] (see :func:`alpha0`). No validation.
    """
    s2 = sin2_delta
    root = ops.sqrt(ops.clip((s2 - 1.0) * (s2 - k * k), 0.0, math.inf))
    return math.pi - ops.arccos(ops.clip((s2 + root) / k, -1.0, 1.0))


def _sin_beta(mu, radius, arc, liquid_mass, omega):
    """001 eq 6 before clipping: sin(beta) = 8 pi mu R xi / (m omega), xi in rad (001 writes
    8 pi^2 mu R xi / (180 m omega) with xi in degrees) [-]. No validation."""
    return 8.0 * math.pi * mu * radius * arc / liquid_mass / omega


def _beta(sin_beta, ops=_NUMPY):
    """beta = arcsin(sin beta) [rad], sin(beta) clipped to [0, 1] (friction holds the liquid at
    sin(beta) >= 1: beta = pi/2, our clip)."""
    return ops.arcsin(ops.clip(sin_beta, 0.0, 1.0))


def _k(k):
    k = np.asarray(k, dtype=float)
    if np.any(~np.isfinite(k)) or np.any(k <= 0.0):
        raise ParameterError("k", k.tolist(), "k = D0/D must be > 0 and finite")
    return k


def eccentricity_ratio(k: float | npt.ArrayLike,
                       alpha: float | npt.ArrayLike) -> float | np.ndarray:
    """e_c / e = sqrt(1 + 2 k cos(alpha) + k^2) [-] (001, formula before eq 1).

    Parameters
    ----------
    k : float or array
        D0/D [-].
    alpha : float or array
        Angle of the liquid's unbalance from the rotor's [rad].
    """
    k = np.asarray(k, dtype=float)
    return np.sqrt(np.maximum(1.0 + 2.0 * k * np.cos(alpha) + k * k, 0.0))


def alpha0(delta: float | npt.ArrayLike, k: float | npt.ArrayLike) -> float | np.ndarray:
    """Liquid equilibrium angle alpha0 [rad] in (pi/2, pi] (001 eq 3).

    alpha0 = pi - arccos((sin^2 d + sqrt((sin^2 d - 1)(sin^2 d - k^2))) / k), the root of
    001 eq 2 that 001 selects. 001 states it for delta in (0, pi/2) and k >= sin(delta); it
    depends on sin^2(delta) only, so it is used unchanged for delta in (pi/2, pi). Where
    k < |sin delta| (001 eq 2 has no root) the square root is clipped at 0 (our choice: the
    continuous extension, cos alpha0 = -sin^2(delta)/k clipped to [-1, 1]).

    Parameters
    ----------
    delta : float or array
        Rotor phase angle [rad].
    k : float or array
        D0/D [-] > 0.
    """
    return _alpha0(np.sin(delta) ** 2, _k(k))


def alpha0_residual(alpha: float | npt.ArrayLike, delta: float | npt.ArrayLike,
                    k: float | npt.ArrayLike) -> float | np.ndarray:
    """Residual of 001 eq 2: sin(alpha) - sin(delta) sqrt(1 + 2k cos(alpha) + k^2)/k [-].

    Parameters
    ----------
    alpha : float or array
        Liquid angle from the rotor's unbalance [rad].
    delta : float or array
        Rotor phase angle [rad].
    k : float or array
        D0/D [-] > 0.
    """
    k = _k(k)
    return np.sin(alpha) - np.sin(delta) * eccentricity_ratio(k, alpha) / k


def residual_lambda0(k: float | npt.ArrayLike, alpha: float | npt.ArrayLike) -> float | np.ndarray:
    """lambda0 = k / sqrt(1 + 2 k cos(alpha0) + k^2) = D0/D_c [-] (001 eq 4).

    Infinite (complete balance) at k = 1, alpha0 = pi (001, after eq 4).

    Parameters
    ----------
    k : float or array
        D0/D [-] > 0.
    alpha : float or array
        Liquid angle alpha0 [rad].
    """
    k = _k(k)
    with np.errstate(divide="ignore"):
        return k / eccentricity_ratio(k, alpha)


def laminar_pipe_force(mu: float | npt.ArrayLike, density: float | npt.ArrayLike,
                       speed: float | npt.ArrayLike, length: float | npt.ArrayLike,
                       diameter: float | npt.ArrayLike) -> float | np.ndarray:
    """Laminar friction force F_T = pi/4 dP d^2 [N] in 001's first form of eq 5.

    dP = rho lambda (l/d) v^2/2 with the Hagen-Poiseuille lambda = 64/Re, Re = v rho d/mu; 001
    simplifies it to 8 pi mu l v (the diameter cancels), which :func:`friction_force` uses.

    Parameters
    ----------
    mu : float or array
        Dynamic viscosity [Pa*s].
    density : float or array
        Liquid density rho [kg/m^3].
    speed : float or array
        Flow speed v [m/s].
    length : float or array
        Length l of the flow [m].
    diameter : float or array
        Pipe diameter d [m].
    """
    re = speed * density * diameter / mu
    return (math.pi / 4 * diameter ** 2 * density * (64 / re) * (length / diameter)
            * speed ** 2 / 2)


def friction_force(mu: float, radius: float, arc: float, omega: float,
                   offset: float) -> float | np.ndarray:
    """Laminar viscous friction force F_T [N] on the liquid (001 eq 5).

    F_T = 8 pi mu l v with l = R xi (wetted arc; 001 writes pi R xi / 180 with xi in degrees)
    and v = omega |O1C| (Hagen-Poiseuille, lambda = 64/Re, as 001 derives it):
    F_T = 8 pi mu R xi omega |O1C|.

    Parameters
    ----------
    mu : float
        Dynamic viscosity [Pa*s] > 0.
    radius : float
        Chamber radius R [m].
    arc : float
        Arc xi occupied by the liquid [rad].
    omega : float
        Rotation speed [rad/s].
    offset : float
        |O1C|, distance of the liquid's mass centre from the rotation axis [m].
    """
    if np.any(np.asarray(mu) <= 0):
        raise ParameterError("mu", mu, "viscosity must be > 0")
    return 8.0 * math.pi * np.asarray(mu) * radius * arc * omega * offset


def friction_angle(mu: float | npt.ArrayLike, radius: float, arc: float, liquid_mass: float,
                   omega: float | npt.ArrayLike) -> float | np.ndarray:
    """Friction angle beta [rad] of the liquid, sin(beta) = F_T / F (001 eq 6).

    sin(beta) = 8 pi mu R xi / (m omega) (xi in rad), with F = m omega^2 |O1C| the centrifugal force
    (|O1C| cancels). With mu = rho nu and m = rho V the density cancels: beta depends on the
    kinematic viscosity only -- 001's "viscosity matters more than density". Where
    sin(beta) >= 1 friction holds the liquid and beta = pi/2 (our clip).

    Parameters
    ----------
    mu : float or array
        Dynamic viscosity [Pa*s] > 0.
    radius : float
        R [m].
    arc : float
        xi [rad].
    liquid_mass : float
        m = rho V [kg] > 0.
    omega : float or array
        [rad/s] > 0.
    """
    if np.any(np.asarray(mu) <= 0):
        raise ParameterError("mu", mu, "viscosity must be > 0")
    positive("liquid_mass", liquid_mass)
    return _beta(_sin_beta(np.asarray(mu), radius, arc, liquid_mass, np.asarray(omega, float)))


def liquid_angle_scalar(delta: float, k: float, mu: float, radius: float, arc: float,
                        liquid_mass: float, omega: float) -> float:
    """The liquid's equilibrium angle alpha0(delta, k) - beta(omega) [rad] (001 eq 3 and 6) for
    floats, without validation: the same formulas as :func:`alpha0` and
    :func:`friction_angle`, evaluated with :mod:`math` (the integrator's right-hand side calls it
    at every step). At omega <= 0 the liquid is held, beta = pi/2.

    Parameters
    ----------
    delta : float
        Rotor phase angle [rad].
    k : float
        D0/D [-] > 0.
    mu : float
        Dynamic viscosity [Pa*s] > 0.
    radius : float
        Chamber radius R [m].
    arc : float
        Arc xi occupied by the liquid [rad].
    liquid_mass : float
        m = rho V [kg] > 0.
    omega : float
        Rotation speed [rad/s].
    """
    beta = (0.5 * math.pi if omega <= 0.0 else
            _beta(_sin_beta(mu, radius, arc, liquid_mass, omega), _MATH))
    return _alpha0(math.sin(delta) ** 2, k, _MATH) - beta


def friction_tan_bound(mu: float | npt.ArrayLike, radius: float, arc: float,
                       liquid_mass: float, omega: float | npt.ArrayLike) -> float | np.ndarray:
    """|tan(beta)| bound of 001 eq 7: s / sqrt(1 - s^2), s = sin(beta) of eq 6 [-].

    Parameters
    ----------
    mu : float or array
        Dynamic viscosity [Pa*s] > 0.
    radius : float
        Chamber radius R [m].
    arc : float
        Arc xi occupied by the liquid [rad].
    liquid_mass : float
        m = rho V [kg] > 0.
    omega : float or array
        Rotation speed [rad/s] > 0.
    """
    return np.tan(friction_angle(mu, radius, arc, liquid_mass, omega))


def jeffcott_phase(ratio: float | npt.ArrayLike, zeta: float | npt.ArrayLike) -> float | np.ndarray:
    """Phase angle delta [rad] of a damped rotor, tan d = 2 zeta r / (1 - r^2) (textbook).

    Parameters
    ----------
    ratio : float or array
        omega / omega_n [-].
    zeta : float or array
        Damping ratio [-].
    """
    r = np.asarray(ratio, dtype=float)
    return np.arctan2(2.0 * np.asarray(zeta) * r, 1.0 - r * r)


def balancing_efficiency(k: float | npt.ArrayLike, delta: float | npt.ArrayLike,
                         beta: float | npt.ArrayLike = 0.0) -> float | np.ndarray:
    """e / e_c for the liquid at alpha0(delta, k) - beta (001 eq 3 and 6) [-].

    The ratio of the eccentricity without and with the liquid, i.e. 003's empirical efficiency
    (amplitude without / with liquid) when the liquid does not change the rotor's dynamics.

    Parameters
    ----------
    k : float or array
        D0/D [-] > 0.
    delta : float or array
        Rotor phase angle [rad].
    beta : float or array
        Friction angle of the liquid [rad] (001 eq 6).
    """
    return 1.0 / eccentricity_ratio(k, alpha0(delta, k) - np.asarray(beta))
