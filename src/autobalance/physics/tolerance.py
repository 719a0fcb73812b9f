"""Tolerance design of a ball balancer (000 eq 56-66) and its reverse.

Forward (:func:`design_tolerances`): a required residual unbalance q Me is split between the
causes with weights p_j (eq 56-57); each share gives a maximum race eccentricity (eq 58-60), a
maximum rolling-resistance coefficient (eq 61-63) and a maximum suspension friction force
(eq 64-66).

Reverse (:func:`predict_residual`): given the tolerances, the residual unbalance of each cause,
their sum (eq 57) and the efficiency RMe = (Me - dMe)/Me (000 Tables 3-4).

Both follow the paper's one-ball estimates with mR = Me and w >> w_x, w_y (e = Me/M) unless a
System is given, in which case the exact kinetic-static solutions are used as well: this is
the 000 method, kept as published for the seed-000 reproduction.

For any machine (N balls, its own masses, R, f/r, rho, F, gamma):
:func:`tolerances_for_grade` splits the residual unbalance of a target ISO 1940 grade between
the causes (000 eq 56-57) and solves the true worst-case bound of
:func:`autobalance.physics.worst_case.residual_bound` for each tolerance alone, so that
:func:`worst_case_prediction` at those tolerances gives back each cause's budget.
"""
from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from ..models._validate import finite as _finite
from ..models._validate import nonneg as _nonneg
from ..models._validate import positive as _positive
from .error_bounds import (eccentricity_equilibrium, rolling_deadband, suspension_friction_deviation)
from .iso1940 import grade_value, unbalance_value
from .worst_case import SyncLiquid, residual_bound
from .vibratory import gain_phase

if TYPE_CHECKING:
    from ..models import System

__all__ = ["DEFAULT_SPLIT", "SPLIT_CAUSES", "TOLERANCE_CAUSES", "TOLERANCE_FLOORS", "check_split",
           "design_tolerances", "predict_residual", "unreachable_tolerances",
           "tolerances_000", "tolerances_for_grade", "worst_case_prediction"]

#: The causes a tolerance is designed for, with the keyword of :func:`residual_bound` each sets.
TOLERANCE_CAUSES = {"eccentricity": "eccentricity", "rolling": "rolling_resistance",
                    "friction": "friction_force"}

#: 000's example split of the residual unbalance (text after eq 56).
DEFAULT_SPLIT = {"eccentricity": 0.50, "rolling": 0.35, "friction": 0.10, "other": 0.05}


#: The finest tolerance each designed cause can be built to: (floor, the key of the tolerance in
#: the results, why). Below it a target grade is unreachable with any balancer of this kind.
#: Eccentricity: a race cannot hold its balls' centres closer to the axis than the balls are
#: round, and the finest precision balls are round to 0.08 um (ISO 3290-1:2014, grade G3,
#: deviation from spherical form). Rolling resistance f/r: our choice of a floor two orders of
#: magnitude below hardened steel balls rolling on steel (f/r about 1e-3), i.e. far below any
#: ball and race pair; suspension friction has no floor (a viscous damper has none).
TOLERANCE_FLOORS = {
    "eccentricity": (0.08e-6, "max_eccentricity_m",
                     "the form accuracy of the finest precision balls, 0.08 um (ISO 3290-1 "
                     "grade G3)"),
    "rolling": (1e-5, "max_rolling_resistance",
                "1e-5, two orders of magnitude below hardened steel balls rolling on steel"),
}


def unreachable_tolerances(result: dict) -> list[str]:
    """The allowed tolerances of a design below what any ball balancer can be built to
    (:data:`TOLERANCE_FLOORS`), as sentences.

    Parameters
    ----------
    result : dict
        A result of :func:`tolerances_for_grade` or :func:`tolerances_000`: its
        "max_eccentricity_m" [m] and "max_rolling_resistance" [-] and the "split" [-].

    Returns
    -------
    list of str
        One sentence per tolerance that has a share of the budget and lies below its floor;
        empty when the target is reachable (or not feasible at all).
    """
    out = []
    names = {"eccentricity": "ring eccentricity", "rolling": "rolling resistance f/r"}
    for cause, (floor, key, why) in TOLERANCE_FLOORS.items():
        value = result.get(key)
        if value is None or not result.get("split", {}).get(cause, 0.0) > 0:
            continue
        if value < floor:
            shown = f"{value * 1e6:.3g} um" if cause == "eccentricity" else f"{value:.3g}"
            out.append(f"the {names[cause]} would have to be {shown}, below {why}")
    return out


#: The causes a split may name: the designed ones and "other", the reserve (000 eq 56).
SPLIT_CAUSES = (*TOLERANCE_CAUSES, "other")


def check_split(split: dict, field: str = "split") -> dict:
    """A split of the residual unbalance between its causes (000 eq 56-57), checked.

    Parameters
    ----------
    split : dict of str to float
        Weight p_j [-] per cause of :data:`SPLIT_CAUSES`, each >= 0, summing to 1.
    field : str
        The option or argument for the message.

    Returns
    -------
    dict
        The weights [-], with 0 for a designed cause not named.

    Raises
    ------
    ParameterError
        Not a dict, a cause not in :data:`SPLIT_CAUSES`, a negative weight, weights that do
        not sum to 1, or no weight on any designed cause (one line naming ``field``).
    """
    if not isinstance(split, dict) or not split:
        raise ParameterError(field, split, "must be a dict cause -> weight")
    out = {}
    for k, v in split.items():
        if k not in SPLIT_CAUSES:
            raise ParameterError(field, split, f"unknown cause {k!r}; allowed: "
                                 f"{', '.join(SPLIT_CAUSES)}")
        out[k] = _nonneg(f"{field}.{k}", v)
    if abs(sum(out.values()) - 1.0) > 1e-9:
        raise ParameterError(field, split, "weights must sum to 1 (000 eq 56)")
    if not any(out.get(k, 0.0) > 0 for k in TOLERANCE_CAUSES):
        raise ParameterError(field, split, "gives no share to eccentricity, rolling or "
                             "friction: every tolerance would be 0")
    for k in TOLERANCE_CAUSES:
        out.setdefault(k, 0.0)
    return out


def design_tolerances(unbalance: float, mass: float, race_radius: float, speed: float,
                      residual_fraction: float = 0.1, split: dict[str, float] | None = None,
                      friction_angle: float = math.radians(61.0), rolling_credit: float = 2.0,
                      friction_credit: float = 0.5) -> dict:
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
    p = check_split(DEFAULT_SPLIT if split is None else split)
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


def predict_residual(system: System, speed: float, f_r: float | None = None,
                     friction_force: float | None = None, friction_angle: float | None = None,
                     rolling_credit: float = 2.0) -> dict:
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


# -- any machine: tolerances from a target grade, and the true worst case ----------------------
def _solve_increasing(fun, target: float, x0: float, x_max: float):
    """Largest x in [0, x_max] found with fun(x) <= target, for a nondecreasing fun with
    fun(0) = 0 (bracket by doubling from x0, then Brent's method to 1e-10 of x; a jump of fun,
    e.g. where the balls lose their balanced state, is located like a root). Returns
    (x, fun(x))."""
    from scipy.optimize import brentq

    best = [0.0, 0.0]

    def f(x):
        v = fun(x)
        if v <= target and x >= best[0]:
            best[:] = [x, v]
        return v - target

    lo, hi = 0.0, min(max(x0, 1e-300), x_max)
    fhi = f(hi)
    if abs(fhi) <= 1e-12 * target:     # the guess solves it (a bound linear in x)
        return hi, fhi + target
    while fhi < 0 and hi < x_max:
        lo, hi = hi, min(2.0 * hi, x_max)
        fhi = f(hi)
    if fhi > 0 and abs(fhi) > 1e-12 * target:
        brentq(f, lo, hi, xtol=1e-300, rtol=1e-10, maxiter=200)
    return best[0], best[1]


def _rho_capacity(system, w: float, added_mass: float = 0.0) -> float:
    """Largest race eccentricity [m] for which the balls can cancel the unbalance for every
    eccentricity angle: |U + rho e^{i beta}(1/h + M_b)| within the capacity annulus (h with a
    liquid's added mass [kg])."""
    from .worst_case import synchronous_gain

    b = system.balancer
    c = b.masses * b.race_radius
    k = abs(1.0 / synchronous_gain(system, w, added_mass) + b.total_mass)
    U = system.rotor.unbalance
    total, inner = float(np.sum(c)), max(0.0, 2.0 * float(np.max(c)) - float(np.sum(c)))
    lim = (total - U) / k
    if inner > 0:
        lim = min(lim, (U - inner) / k)
    return max(lim, 0.0)


def _check_grade(grade) -> float:
    G = _finite("grade", grade)
    if G <= 0:
        raise ParameterError("grade", grade, "must be a grade G > 0 [mm/s], e.g. 16 (ISO 1940 G16)")
    return G


def tolerances_for_grade(system: System, speed: float, grade: float = 16.0, *,
                         nominal_speed: float | None = None, split: dict | None = None,
                         eccentricity_angle: float | None = None,
                         liquid: SyncLiquid | None = None) -> dict:
    """Largest race eccentricity, rolling resistance and suspension friction of a machine that
    keep its worst-case residual unbalance within a target ISO 1940 grade (000 eq 56-66 for any
    balancer).

    The residual of the grade, U_G = M_t G / (1000 Omega) (:func:`.iso1940.unbalance_value`),
    is split between the causes with the weights p_j (000 eq 56-57; the rest, e.g. "other",
    is kept in reserve). For each cause alone the true bound of
    :func:`~.worst_case.residual_bound` is solved for its tolerance so that it equals
    p_j U_G: eccentricity rho (exactly rho/|h|, 000 eq 46-47), one rolling-resistance
    coefficient for every ball (by false position on the bound) and the damper friction F
    (exactly e_f/|h|, 000 eq 48). The causes do not add (000: "the resultant effect is not a
    simple sum"; an eccentricity moves the balanced state and so the rolling dead band): when
    the bound with all three together exceeds the sum of their budgets, the three are scaled
    by one factor lambda < 1 solved so that it equals that sum. Each cause alone then stays
    within its budget, and the machine built with all three meets the sum exactly.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (rotor, suspension with its damper angle gamma, balancer).
    speed : float
        Speed w at which the balls settle [rad/s], > 0 (the bound's speed).
    grade : float
        Target grade G [mm/s], > 0 (default 16).
    nominal_speed : float, optional
        Omega of the grade [rad/s] (default ``speed``).
    split : dict of str to float, optional
        Weights p_j [-] per cause ("eccentricity", "rolling", "friction", others), summing to
        1 (000 eq 56); default :data:`DEFAULT_SPLIT` (000: 0.5, 0.35, 0.1, 0.05).
    eccentricity_angle : float or None
        beta [rad] of the eccentricity; None = any (the bound holds for every angle).
    liquid : SyncLiquid, optional
        A liquid beside the balls at ``speed`` (:func:`~.worst_case.residual_bound`): added
        mass kappa [kg], linear range [m], capacity [kg*m].

    Returns
    -------
    dict
        "feasible" (bool) and "reason" (None or why not), "target_grade_G_mm_s",
        "target_unbalance_kg_m", "split", "budget_kg_m" (per cause), "max_eccentricity_m",
        "max_rolling_resistance", "max_suspension_friction_N" (None when not feasible),
        "joint_scale" (lambda [-]), "bound_at_max_kg_m" (each cause's bound at its maximum),
        "design_worst_residual_kg_m" (the bound with all three at their maxima) and
        "design_meets_target".
    """
    w = _positive("speed", speed)
    G = _check_grade(grade)
    Om = w if nominal_speed is None else _positive("nominal_speed", nominal_speed)
    p = check_split(DEFAULT_SPLIT if split is None else split)
    mt = system.total_mass
    u_g = float(unbalance_value(G, mt, Om))
    budgets = {k: v * u_g for k, v in p.items()}
    out = {"speed_rad_s": w, "nominal_speed_rad_s": Om, "target_grade_G_mm_s": G,
           "target_unbalance_kg_m": u_g, "split": p, "budget_kg_m": budgets,
           "max_eccentricity_m": None, "max_rolling_resistance": None,
           "max_suspension_friction_N": None, "joint_scale": None, "bound_at_max_kg_m": None,
           "design_worst_residual_kg_m": None, "design_meets_target": False}
    zero = dict(rolling_resistance=0.0, eccentricity=0.0, friction_force=0.0,
                eccentricity_angle=eccentricity_angle, liquid=liquid)
    base = residual_bound(system, w, **zero)
    b = system.balancer
    if not base["balancing"]:
        return {**out, "feasible": False,
                "reason": f"speed {w:.4g} rad/s is below the balancing onset (000 eq 12: "
                          "g_x cos phi_x + g_y cos phi_y >= 0): the balls do not balance here"}
    if not base["balanced_exists"]:
        return {**out, "feasible": False,
                "reason": f"capacity short: the balls (sum m_i R = {base['capacity_kg_m']:.4g} "
                          f"kg*m) cannot cancel the unbalance {system.rotor.unbalance:.4g} kg*m"}
    if liquid is not None and not liquid.linear_range > 0:
        return {**out, "feasible": False,
                "reason": f"at {w:.4g} rad/s the liquid's rings are not intact (they touch a "
                          "wall): no bound beside it (docs/liquid/balls-beside-liquid.md sec. 3l)"}
    gain = base["gain_m_per_kg_m"]
    per_n = residual_bound(system, w, **{**zero, "friction_force": 1.0})["friction_displacement_m"]

    def bound_of(cause):
        key = TOLERANCE_CAUSES[cause]
        return lambda x: residual_bound(system, w, **{**zero, key: x})["worst_residual_kg_m"]

    guess = {"eccentricity": budgets["eccentricity"] * gain,
             "rolling": budgets["rolling"] * gain / (b.race_radius + system.gravity.g / (w * w)),
             "friction": budgets["friction"] * gain / max(per_n, 1e-300)}
    # beyond rho_cap the balls cannot cancel U + rho e^{i beta}(1/h + M_b) for every beta
    kappa = 0.0 if liquid is None else liquid.added_mass
    x_max = {"eccentricity": min(0.999 * b.race_radius, _rho_capacity(system, w, kappa)),
             "rolling": 1.0, "friction": 1e12}
    alone = {}
    for cause in TOLERANCE_CAUSES:
        alone[cause] = (0.0 if budgets[cause] <= 0 else
                        _solve_increasing(bound_of(cause), budgets[cause], guess[cause],
                                          x_max[cause])[0])

    def joint(lam):
        return residual_bound(system, w, rolling_resistance=lam * alone["rolling"],
                              eccentricity=lam * alone["eccentricity"],
                              friction_force=lam * alone["friction"],
                              eccentricity_angle=eccentricity_angle,
                              liquid=liquid)["worst_residual_kg_m"]

    total = sum(budgets[k] for k in TOLERANCE_CAUSES)
    lam = 1.0 if joint(1.0) <= total else _solve_increasing(joint, total, 0.5, 1.0)[0]
    tol = {k: lam * v for k, v in alone.items()}
    at_max = {k: bound_of(k)(tol[k]) for k in TOLERANCE_CAUSES}
    both = residual_bound(system, w, rolling_resistance=tol["rolling"],
                          eccentricity=tol["eccentricity"], friction_force=tol["friction"],
                          eccentricity_angle=eccentricity_angle, liquid=liquid)
    return {**out, "feasible": True, "reason": None,
            "max_eccentricity_m": tol["eccentricity"], "max_rolling_resistance": tol["rolling"],
            "max_suspension_friction_N": tol["friction"], "joint_scale": lam,
            "bound_at_max_kg_m": at_max,
            "design_worst_residual_kg_m": both["worst_residual_kg_m"],
            "design_meets_target": bool(both["separated"] and both["worst_residual_kg_m"] <= u_g)}


def tolerances_000(system: System, speed: float, residual_fraction: float, *,
                   nominal_speed: float | None = None, split: dict | None = None) -> dict:
    """000's own tolerance design (:func:`design_tolerances`, eq 56-66 with one ball of
    m R = Me, e = Me/M and w >> w_x, w_y) for a machine, in the keys of
    :func:`tolerances_for_grade`, with the true bound of the machine built with all three
    tolerances (:func:`~.worst_case.residual_bound`) beside it: how far the paper's estimate
    is from a guarantee for this balancer.

    Parameters
    ----------
    system : autobalance.models.System
        The machine: Me = rotor.unbalance [kg*m], M = rotor.mass [kg] (000: the drum without
        balls, 37 kg), R = balancer.race_radius [m], gamma = suspension.dry_friction_angle [rad].
    speed : float
        w [rad/s], > 0.
    residual_fraction : float
        q = required residual / Me [-] (000: 0.1), in (0, 1].
    nominal_speed : float, optional
        Omega of the target's grade [rad/s] (default ``speed``).
    split : dict of str to float, optional
        Weights p_j [-] per cause (000 eq 56); default :data:`DEFAULT_SPLIT`.

    Returns
    -------
    dict
        The keys of :func:`tolerances_for_grade` ("feasible" is always True: the estimate
        exists for any q) and "paper_000" (the whole :func:`design_tolerances` result).
    """
    w = _positive("speed", speed)
    Om = w if nominal_speed is None else _positive("nominal_speed", nominal_speed)
    U = system.rotor.unbalance
    d = design_tolerances(U, system.rotor.mass, system.balancer.race_radius, w,
                          residual_fraction=residual_fraction, split=split,
                          friction_angle=system.suspension.dry_friction_angle)
    tol = {"eccentricity": d["rho_max_m"], "rolling": d["f_r_max"],
           "friction": d["friction_force_max_n"]}
    both = residual_bound(system, w, rolling_resistance=tol["rolling"],
                          eccentricity=tol["eccentricity"], friction_force=tol["friction"],
                          eccentricity_angle=None)
    u_t = residual_fraction * U
    return {"speed_rad_s": w, "nominal_speed_rad_s": Om,
            "target_grade_G_mm_s": float(grade_value(u_t, system.total_mass, Om)),
            "target_unbalance_kg_m": u_t,
            "split": check_split(DEFAULT_SPLIT if split is None else split),
            "budget_kg_m": d["budgets_kg_m"], "feasible": True, "reason": None,
            "max_eccentricity_m": tol["eccentricity"], "max_rolling_resistance": tol["rolling"],
            "max_suspension_friction_N": tol["friction"], "joint_scale": None,
            "bound_at_max_kg_m": None,
            "design_worst_residual_kg_m": both["worst_residual_kg_m"],
            "design_meets_target": bool(both["separated"] and both["worst_residual_kg_m"] <= u_t),
            "paper_000": d}


def worst_case_prediction(system: System, speed: float, *, nominal_speed: float | None = None,
                          eccentricity_angle: float | str | None = None,
                          rolling_credit: float = 2.0, friction_credit: float = 2.0,
                          liquid: SyncLiquid | None = None) -> dict:
    """Worst-case and expected residual unbalance of a machine with its own tolerances
    (the reverse of :func:`tolerances_for_grade`; 000 Tables 3-4's RMe for any balancer).

    The worst case is the true bound of :func:`~.worst_case.residual_bound` (all causes
    together). Each cause alone is given too. "Expected" is a heuristic, not a bound: the
    eccentricity part rho/|h| is certain (000: "always give the deviation", eq 46-47), the
    dead-band part (rolling, friction) is divided by the credits (000 eq 62: "a small
    probability that the ball is at one of the maximums", factor 2; eq 65: friction "can be
    reduced by half").

    Parameters
    ----------
    system : autobalance.models.System
        The machine with its tolerances (balancer stiction, eccentricity; suspension friction).
    speed : float
        Speed w at which the balls settle [rad/s], > 0.
    nominal_speed : float, optional
        Omega of the grades [rad/s] (default ``speed``).
    eccentricity_angle : float or None or str
        beta [rad]; None = any angle (default), "system" = the balancer's own.
    rolling_credit, friction_credit : float
        Divisors of the rolling and friction parts for the expected value [-], >= 1.
    liquid : SyncLiquid, optional
        A liquid beside the balls at ``speed`` (:func:`~.worst_case.residual_bound`): added
        mass kappa [kg], linear range [m], capacity [kg*m].

    Returns
    -------
    dict
        "worst_residual_kg_m", "worst_grade_G_mm_s", "expected_residual_kg_m",
        "expected_grade_G_mm_s", "eccentricity_kg_m", "rolling_kg_m", "friction_kg_m"
        (each cause alone), "rme_worst", "rme_expected" ([-], RMe = (U - dU)/U of 000
        Tables 3-4; negative when the balls can leave more than U), "separated",
        "balancing", "capacity_kg_m", "trivial_bound_kg_m", "assumptions".
    """
    w = _positive("speed", speed)
    Om = w if nominal_speed is None else _positive("nominal_speed", nominal_speed)
    cr = _positive("rolling_credit", rolling_credit)
    cf = _positive("friction_credit", friction_credit)
    if cr < 1 or cf < 1:
        raise ParameterError("rolling_credit" if cr < 1 else "friction_credit",
                             cr if cr < 1 else cf, "must be >= 1 [-]")
    r = residual_bound(system, w, eccentricity_angle=eccentricity_angle, liquid=liquid)
    b = system.balancer
    alone = {"rolling": dict(eccentricity=0.0, friction_force=0.0),
             "friction": dict(eccentricity=0.0, rolling_resistance=0.0),
             "eccentricity": dict(rolling_resistance=0.0, friction_force=0.0)}
    parts = {k: residual_bound(system, w, eccentricity_angle=eccentricity_angle, liquid=liquid,
                               **kw)["worst_residual_kg_m"] for k, kw in alone.items()}
    worst = r["worst_residual_kg_m"]
    ecc = r["eccentricity_kg_m"]
    fric = r["friction_kg_m"]
    roll = max(worst - ecc - fric, 0.0)
    expected = ecc + roll / cr + fric / cf
    U = system.rotor.unbalance
    mt = system.total_mass
    return {"speed_rad_s": w, "nominal_speed_rad_s": Om, "worst_residual_kg_m": worst,
            "worst_grade_G_mm_s": float(grade_value(worst, mt, Om)),
            "expected_residual_kg_m": expected,
            "expected_grade_G_mm_s": float(grade_value(expected, mt, Om)),
            "eccentricity_kg_m": parts["eccentricity"], "rolling_kg_m": parts["rolling"],
            "friction_kg_m": parts["friction"],
            "rme_worst": (U - worst) / U if U > 0 else math.nan,
            "rme_expected": (U - expected) / U if U > 0 else math.nan,
            "separated": r["separated"], "balancing": r["balancing"],
            "balanced_exists": r["balanced_exists"], "capacity_kg_m": r["capacity_kg_m"],
            "trivial_bound_kg_m": r["trivial_bound_kg_m"],
            "rolling_resistance": [float(v) for v in b.stiction],
            "eccentricity_m": b.eccentricity,
            "suspension_friction_N": system.suspension.dry_friction_force,
            "assumptions": r["assumptions"],
            **{k: r[k] for k in ("liquid_added_mass_kg", "liquid_linear_range_m", "liquid_linear")
               if k in r}}
