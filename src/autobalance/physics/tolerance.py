"""Tolerance design of a ball balancer (000 eq 56-66) and its reverse.

Forward (:func:`design_tolerances`): a required residual unbalance q Me is split between the
causes with weights p_j (eq 56-57); each share gives a maximum race eccentricity (eq 58-60), a
maximum rolling-resistance coefficient (eq 61-63) and a maximum suspension friction force
(eq 64-66).

Reverse (:func:`predict_residual`): given the tolerances, the residual unbalance of each cause,
their sum (eq 57) and the efficiency RMe = (Me - dMe)/Me (000 Tables 3-4).

Both follow the paper's one-ball estimates with mR = Me and w >> w_x, w_y (e = Me/M) unless a
System is given, in which case the exact kinetic-static solutions are used as well.
"""
from __future__ import annotations

import dataclasses
import math

import numpy as np

from ..models import ParameterError
from ..models._validate import finite as _finite
from ..models._validate import nonneg as _nonneg
from ..models._validate import positive as _positive
from .error_bounds import (eccentricity_equilibrium, rolling_deadband, suspension_friction_deviation)
from .vibratory import gain_phase

__all__ = ["DEFAULT_SPLIT", "design_tolerances", "predict_residual"]

#: 000's example split of the residual unbalance (text after eq 56).
DEFAULT_SPLIT = {"eccentricity": 0.50, "rolling": 0.35, "friction": 0.10, "other": 0.05}


def _split(split) -> dict:
    if not isinstance(split, dict) or not split:
        raise ParameterError("split", split, "must be a dict cause -> weight")
    out = {}
    for k, v in split.items():
        out[k] = _nonneg(f"split.{k}", v)
    if abs(sum(out.values()) - 1.0) > 1e-9:
        raise ParameterError("split", split, "weights must sum to 1 (000 eq 56)")
    for k in ("eccentricity", "rolling", "friction"):
        out.setdefault(k, 0.0)
    return out


def design_tolerances(unbalance, mass, race_radius, speed, residual_fraction=0.1,
                      split=None, friction_angle=math.radians(61.0), rolling_credit=2.0,
                      friction_credit=0.5) -> dict:
    """Maximum eccentricity, rolling resistance and suspension friction for a required balance.

    000 eq (56)-(66) for balls with m R = Me, w >> w_x, w_y, e = Me/M:

    * eq (57)-(58): budget of cause j, dMe_j = p_j q Me;
    * eq (59)-(60), beta = pi/2 (worst case): m R rho/e <= dMe_rho -> rho_max = p_rho q e;
    * eq (61)-(63): m R (f/r)(R/e) <= c_r dMe_r (c_r = 2: the error is rarely at the edge of the
      dead band) -> f/r <= c_r p_r q e/R;
    * eq (64)-(66): 2 m R d_f <= c_f dMe_f with eq (49) d_f = F cos(gamma)/(Me sin(2pi/3) w^2)
      (c_f = 1/2: "its impact can be reduced by half") ->
      F <= c_f p_f q Me^2 sin(2pi/3) w^2 / (2 m R cos(gamma)).

    Parameters
    ----------
    unbalance : float
        Me [kg*m], > 0.
    mass : float
        M [kg] (000: 37 kg), > 0.
    race_radius : float
        R [m], > 0.
    speed : float
        w [rad/s], > 0.
    residual_fraction : float
        q: required dMe_F / Me [-] (000: 0.1), in (0, 1].
    split : dict of str to float, optional
        Share p_j [-] per cause ("eccentricity", "rolling", "friction", others), summing to 1
        (eq 56); default :data:`DEFAULT_SPLIT`.
    friction_angle : float
        gamma [rad] (000: 61 deg).
    rolling_credit, friction_credit : float
        c_r, c_f [-] above (000: 2 and 1/2), > 0.

    Returns
    -------
    dict
        "budgets_kg_m" (per cause), "rho_max_m", "f_r_max", "friction_force_max_n",
        "friction_force_eq66_printed_n" (0.005 Me w^2 sin(2pi/3)/cos(gamma), eq 66 as printed),
        "eccentricity_m" (e).
    """
    U = _positive("unbalance", unbalance)
    M = _positive("mass", mass)
    R = _positive("race_radius", race_radius)
    w = _positive("speed", speed)
    q = _positive("residual_fraction", residual_fraction)
    if q > 1:
        raise ParameterError("residual_fraction", residual_fraction, "must be within (0, 1]")
    p = _split(DEFAULT_SPLIT if split is None else split)
    g = _finite("friction_angle", friction_angle)
    cr = _positive("rolling_credit", rolling_credit)
    cf = _positive("friction_credit", friction_credit)
    e = U / M
    mR = U
    budgets = {k: v * q * U for k, v in p.items()}
    rho_max = budgets["eccentricity"] * e / mR                                   # eq 60
    f_r_max = cr * budgets["rolling"] * e / (mR * R)                             # eq 63
    s = math.sin(2 * math.pi / 3)
    F_max = cf * budgets["friction"] * U * s * w * w / (2 * mR * math.cos(g))    # eq 65-66
    printed = 0.005 * U * w * w * s / math.cos(g)                                # eq 66 printed
    return {"budgets_kg_m": budgets, "rho_max_m": rho_max, "f_r_max": f_r_max,
            "friction_force_max_n": F_max, "friction_force_eq66_printed_n": printed,
            "eccentricity_m": e}


def predict_residual(system, speed, f_r=None, friction_force=None, friction_angle=None,
                     rolling_credit=2.0) -> dict:
    """Residual unbalance and efficiency RMe predicted from the tolerances (reverse of eq 56-66).

    Causes (each evaluated alone, then summed as 000 eq 57):

    * eccentricity rho, beta of the balancer: exact kinetic-static equilibrium (eq 46-47);
    * rolling resistance f/r: worst vertex of the N-ball dead band (eq 21-22, 27-29), and the
      "expected" share = worst / ``rolling_credit`` (000's factor 2, eq 62);
    * suspension friction F, gamma: two balls at +-2pi/3, 2 m R d_f with d_f from eq (49) (eq 65).

    Parameters
    ----------
    system : autobalance.models.System
        The machine; f/r, rho, beta, F and gamma default to its balancer / suspension values.
    speed : float
        w [rad/s], > 0.
    f_r : float, optional
        f/r [-], >= 0 (default: the balancer's rolling_resistance of ball 0).
    friction_force : float, optional
        F per damper [N] (default: suspension.dry_friction_force).
    friction_angle : float, optional
        gamma [rad] (default: suspension.dry_friction_angle).
    rolling_credit : float
        Divisor for the expected rolling share [-], > 0.

    Returns
    -------
    dict
        "eccentricity_kg_m", "rolling_worst_kg_m", "rolling_expected_kg_m", "friction_kg_m",
        "total_worst_kg_m", "total_expected_kg_m", "rme_worst", "rme_expected" ([-], 000 Tables
        3-4: RMe = (Me - dMe)/Me), "amplitude_worst_m" (max of the x, y amplitudes).
    """
    w = _positive("speed", speed)
    b = system.balancer
    fr = b.rolling_resistance[0] if f_r is None else _nonneg("f_r", f_r)
    F = system.suspension.dry_friction_force if friction_force is None \
        else _nonneg("friction_force", friction_force)
    gam = system.suspension.dry_friction_angle if friction_angle is None \
        else _finite("friction_angle", friction_angle)
    c = _positive("rolling_credit", rolling_credit)
    U = system.rotor.unbalance
    ecc = eccentricity_equilibrium(system, w)
    d_rho = ecc["residual_unbalance_kg_m"] if b.eccentricity > 0 else 0.0
    ideal = dataclasses.replace(system, balancer=dataclasses.replace(b, eccentricity=0.0))
    roll = rolling_deadband(ideal, w, fr)["max_residual_unbalance_kg_m"] if fr > 0 else 0.0
    fric = 0.0
    if F > 0:
        d_f = suspension_friction_deviation(F, gam, U, w)
        fric = float(np.sum(b.masses * b.race_radius)) * d_f
    worst = d_rho + roll + fric
    expected = d_rho + roll / c + fric
    gx, _, gy, _ = gain_phase(system, w)
    return {"eccentricity_kg_m": d_rho, "rolling_worst_kg_m": roll,
            "rolling_expected_kg_m": roll / c, "friction_kg_m": fric,
            "total_worst_kg_m": worst, "total_expected_kg_m": expected,
            "rme_worst": (U - worst) / U, "rme_expected": (U - expected) / U,
            "amplitude_worst_m": worst * max(gx, gy)}
