"""Tolerances of any machine's balancer from a target ISO 1940 grade (000 eq 56-66 generalised
to N balls and any balancer), the true worst case of the machine's own tolerances, and a Monte
Carlo of real simulations of the machine built with the tolerances at their limits.

Beside a liquid (vertical axis, isotropic suspension) the bounds take the liquid's synchronous
moment (:func:`autobalance.liquid.synchronous.synchronous_liquid`,
docs/liquid/balls-beside-liquid.md sec. 3l) and the simulations are runs of balls beside the films
(:mod:`autobalance.simulate.hybrid`).

:func:`compute_tolerances` is closed form (:mod:`autobalance.physics.tolerance`,
:mod:`autobalance.physics.worst_case`); :func:`check_tolerances_by_simulation` integrates
the full model (:func:`autobalance.simulate.simulate_batch`) from random start angles with the
eccentricity at a random angle. Both return JSON-ready dicts (SI, unit-suffixed keys).
"""
from __future__ import annotations

import dataclasses
import math
import time
from typing import TYPE_CHECKING

import numpy as np

from ..models import InitialState, ParameterError
from ..physics.iso1940 import grade_class, grade_value
from ..physics.worst_case import attained_residual, residual_bound
from ..physics.iso1940 import unbalance_value
from ..physics.tolerance import (tolerances_000, tolerances_for_grade, unreachable_tolerances,
                                 worst_case_prediction)
from .common import load
from .statistics import plateau_speed

if TYPE_CHECKING:
    from pathlib import Path

    import xarray as xr

    from ..config import Config
    from ..models import System

__all__ = ["CAUSES", "check_tolerances_by_simulation", "collinear_residuals",
           "compute_tolerances", "machine_with_tolerances", "tolerances_dataset"]

#: The tolerance designs :func:`compute_tolerances` offers: the true bound for any balancer,
#: or 000's one-ball estimate (the paper's method, kept for its reproduction).
METHODS = {"bound": "000 eq 56-66 generalised: the true worst-case bound of this balancer",
           "000": "000 eq 56-66 as published: one ball with m R = Me, e = Me/M, w >> w_n"}

#: Keys of a tolerance dict (as :func:`compute_tolerances` returns them).
TOLERANCE_KEYS = ("max_eccentricity_m", "max_rolling_resistance", "max_suspension_friction_N")


def liquid_at(system: System):
    """speed [rad/s] -> the machine's liquid in a synchronous whirl (SyncLiquid), or None for
    no liquid; one-line errors for what the bound beside a liquid does not take (two
    partitions: :func:`~autobalance.liquid.synchronous.synchronous_liquid`; an anisotropic
    suspension). On a horizontal axis the liquid sees the machine's in-plane gravity.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (balls, perhaps a ``[liquid]`` section; suspension kx, ky [N/m]).
    """
    if system.liquid is None:
        return lambda speed: None
    from ..models.liquid_balancer import G_STANDARD
    from ..liquid.synchronous import check_synchronous, synchronous_liquid

    sus = system.suspension
    if not sus.is_isotropic:
        raise ParameterError("suspension", f"kx={sus.kx:g}, ky={sus.ky:g}, cx={sus.cx:g}, "
                             f"cy={sus.cy:g}", "must be isotropic for the tolerances beside a "
                             "liquid (the liquid follows the forward whirl only)")
    check_synchronous(system.liquid)
    g = system.gravity.g if system.liquid.axis == "horizontal" else G_STANDARD
    return lambda speed: synchronous_liquid(system.liquid, speed, g)


def _settle_speed(cfg, speed):
    """The bound's speed [rad/s] and how it was chosen."""
    nominal = cfg.spin.nominal_speed
    if speed is None:
        return nominal, "nominal speed of the profile"
    w = float(speed)
    if not (math.isfinite(w) and w > 0):
        raise ParameterError("speed", speed, "must be a finite speed > 0 [rad/s]")
    return w, "given"


def compute_tolerances(base: str | Path | Config, *, grade: float = 16.0,
                       speed: float | None = None,
                       split: dict | None = None, residual_fraction: float | None = None,
                       method: str = "bound") -> dict:
    """Allowed race eccentricity, rolling resistance and suspension friction of a machine for a
    target grade, and the true worst case of its own tolerances (000 eq 56-66 generalised).

    The target residual is U_G = M_t G / (1000 Omega) at the profile's nominal speed Omega
    (:func:`autobalance.physics.iso1940.unbalance_value`); the bound is taken at ``speed``
    (default Omega), where the balls last move. A TSR profile also gets the bound at its
    plateau (the balls settle there and stay at rest on the way up when they cannot move at
    Omega). The eccentricity angle is unknown: every bound holds for all angles.

    Parameters
    ----------
    base : str, Path or Config
        The machine: a preset name, a TOML config path or a Config.
    grade : float
        Target grade G [mm/s], > 0 (default 16).
    speed : float or None
        Speed of the bound w [rad/s] (None: the nominal speed).
    split : dict of str to float or None
        Shares of the target residual per cause [-] (000 eq 56; default 000's 0.5
        eccentricity, 0.35 rolling, 0.1 friction, 0.05 other).
    residual_fraction : float or None
        Target as 000 states it: residual = q x the machine's unbalance [-], in (0, 1]
        (000: q = 0.1), instead of ``grade``.
    method : str
        "bound" (default): each tolerance from the true bound of this balancer
        (:func:`~autobalance.physics.tolerance.tolerances_for_grade`); "000": 000's
        one-ball estimate (:func:`~autobalance.physics.tolerance.tolerances_000`, its
        "paper_000" result included), with the true bound of the machine built with it.

    Returns
    -------
    dict
        JSON-ready: "max_eccentricity_m", "max_rolling_resistance",
        "max_suspension_friction_N", "budget_kg_m" (per cause), "target_grade_G_mm_s",
        "target_unbalance_kg_m", "worst_residual_kg_m" (the bound for the machine's own
        tolerances), "worst_grade_G_mm_s", "expected_residual_kg_m", "attained_residual_kg_m",
        "meets_target", "capacity_kg_m", "collinear_residuals_kg_m" (where balls trapped
        outside the balanced region end), "feasible", "reason", "reachable" (feasible and no
        tolerance below what any balancer can be built to), "unreachable" (those, as
        sentences: :func:`~autobalance.physics.tolerance.unreachable_tolerances`),
        "warnings", ...
        (docs/tolerances.md).
    """
    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True)
    s = cfg.system
    if method not in METHODS:
        raise ParameterError("method", method, "must be one of: " + "; ".join(
            f"{k!r} ({v})" for k, v in METHODS.items()))
    if method == "000" and s.liquid is not None:
        raise ParameterError("method", method, "is 000's one-ball estimate without a liquid; "
                             "'bound' takes the liquid beside the balls")
    liq = liquid_at(s)
    w, basis = _settle_speed(cfg, speed)
    liq_w = liq(w)                    # the liquid at the bound's speed (None without one)
    Om = cfg.spin.nominal_speed
    U, mt = s.rotor.unbalance, s.total_mass
    if residual_fraction is not None:
        q = float(residual_fraction)
        if not (math.isfinite(q) and 0 < q <= 1) or U <= 0:
            raise ParameterError("residual_fraction", residual_fraction,
                                 "must be within (0, 1] of a machine with an unbalance > 0")
        grade = float(grade_value(q * U, mt, Om))
    if method == "000":
        q = (float(residual_fraction) if residual_fraction is not None
             else float(unbalance_value(grade, mt, Om)) / U if U > 0 else math.inf)
        if not q <= 1:
            raise ParameterError("grade", grade, f"the 000 method needs a target residual at "
                                 f"most the unbalance (G{float(grade_value(U, mt, Om)):.4g} here)")
        d = tolerances_000(s, w, q, nominal_speed=Om, split=split)
    else:
        d = tolerances_for_grade(s, w, grade, nominal_speed=Om, split=split, liquid=liq_w)
    p = worst_case_prediction(s, w, nominal_speed=Om, liquid=liq_w)
    att = attained_residual(s, w, eccentricity_angle=None, n_starts=8, liquid=liq_w)
    u_g = d["target_unbalance_kg_m"]
    warnings = []
    if not d["feasible"]:
        warnings.append(d["reason"])
    unreachable = unreachable_tolerances(d) if d["feasible"] else []
    if p["balancing"] and not p["separated"]:
        warnings.append("at the speed of the bound the balls can rest almost anywhere with the "
                        "machine's own tolerances (no dead-band gap): the worst case is the trivial bound "
                        "U + M_b rho + sum m_i R; it depends on where they last moved")
    if not p.get("liquid_linear", True):
        warnings.append("at the speed of the bound the balls' rest states reach whirls beyond "
                        f"the liquid's linear range ({p['liquid_linear_range_m']:.3g} m: its rings "
                        "break): no bound beside this liquid; the worst case is the trivial "
                        "bound")
    if p["rme_worst"] < 0:
        warnings.append("in the worst case the balls at rest leave more than the rotor's own "
                        "unbalance (e.g. clustered on the heavy side)")
    out = {
        "name": cfg.name, "method": method, "speed_rad_s": w, "speed_basis": basis,
        "nominal_speed_rad_s": Om,
        "unbalance_kg_m": U, "total_mass_kg": mt, "capacity_kg_m": p["capacity_kg_m"],
        "target_grade_G_mm_s": d["target_grade_G_mm_s"],
        "target_grade_class_G_mm_s": float(grade_class(d["target_grade_G_mm_s"])),
        "target_unbalance_kg_m": u_g, "split": d["split"], "budget_kg_m": d["budget_kg_m"],
        "feasible": d["feasible"], "reason": d["reason"],
        "reachable": d["feasible"] and not unreachable, "unreachable": unreachable,
        "max_eccentricity_m": d["max_eccentricity_m"],
        "max_rolling_resistance": d["max_rolling_resistance"],
        "max_suspension_friction_N": d["max_suspension_friction_N"],
        "joint_scale": d["joint_scale"], "bound_at_max_kg_m": d["bound_at_max_kg_m"],
        "design_worst_residual_kg_m": d["design_worst_residual_kg_m"],
        "own_rolling_resistance": p["rolling_resistance"], "own_eccentricity_m": p["eccentricity_m"],
        "own_suspension_friction_N": p["suspension_friction_N"],
        "worst_residual_kg_m": p["worst_residual_kg_m"],
        "worst_grade_G_mm_s": p["worst_grade_G_mm_s"],
        "worst_grade_class_G_mm_s": float(grade_class(p["worst_grade_G_mm_s"])),
        "expected_residual_kg_m": p["expected_residual_kg_m"],
        "expected_grade_G_mm_s": p["expected_grade_G_mm_s"],
        "attained_residual_kg_m": att["attained_residual_kg_m"],
        "cause_residual_kg_m": {"eccentricity": p["eccentricity_kg_m"],
                                "rolling": p["rolling_kg_m"], "friction": p["friction_kg_m"]},
        "rme_worst": p["rme_worst"], "rme_expected": p["rme_expected"],
        "meets_target": bool(p["separated"] and p["worst_residual_kg_m"] <= u_g),
        "separated": p["separated"], "balancing": p["balancing"],
        "assumptions": p["assumptions"], "warnings": warnings,
    }
    if "paper_000" in d:
        out["paper_000"] = d["paper_000"]
        out["design_meets_target"] = d["design_meets_target"]
    out["collinear_residuals_kg_m"] = collinear_residuals(s)
    if s.liquid is not None:
        out.update({"liquid_added_mass_kg": p["liquid_added_mass_kg"],
                    "liquid_linear_range_m": p["liquid_linear_range_m"],
                    "liquid_linear": p["liquid_linear"]})
        warnings.append("beside a liquid the collinear residuals are of the rotor and balls "
                        "alone (the liquid's rings are broken at such whirls)")
        if s.liquid.axis == "horizontal":
            out["balanced_growth_rate_1_s"] = _horizontal_verdict(s, Om, warnings)
    if getattr(cfg, "profile_kind", "") == "tsr":
        wp = plateau_speed(cfg.spin)
        pp = residual_bound(s, wp, eccentricity_angle=None, liquid=liq(wp))
        out.update({"plateau_speed_rad_s": wp,
                    "plateau_worst_residual_kg_m": pp["worst_residual_kg_m"],
                    "plateau_worst_grade_G_mm_s": float(grade_value(pp["worst_residual_kg_m"], mt, Om))})
    out["elapsed_s"] = time.perf_counter() - t0
    return out


def _horizontal_verdict(system: System, speed: float, warnings: list) -> float:
    """The growth rate [1/s] of the balanced state of balls beside a liquid on a horizontal
    axis at ``speed`` [rad/s] (Floquet about its periodic state under gravity,
    docs/liquid/horizontal-axis.md sec. 3m; NaN where not decided), and its note appended to
    ``warnings``."""
    from .liquid_balanced import balanced_machine_stability

    try:
        gr = float(balanced_machine_stability(system, [speed])["growth_rate_1_s"][0])
    except ParameterError:      # e.g. three balls under gravity: not yet
        gr = math.nan
    verdict = ("not decided" if not math.isfinite(gr) else
               "linearly stable" if gr < 0 else "unstable")
    warnings.append(f"on a horizontal axis the balanced state beside the liquid is {verdict} "
                    f"at the nominal speed (growth rate {gr:.3g} 1/s, Floquet about its periodic "
                    "state, docs/liquid/horizontal-axis.md sec. 3m); a run-up can still end in an asynchronous "
                    "whirl beyond the rings' range, where the bound says nothing: check with "
                    "--check (sec. 3l)")
    return gr


def collinear_residuals(system: System, max_balls: int = 12) -> list:
    """Residual unbalances |U + sum_j s_j m_j R| [kg*m], s_j = +-1, of the collinear
    equilibria (every ball on the unbalance's line, with it or against it; no eccentricity),
    sorted: where balls that stop outside the balanced region end (friction and ball contact
    hold these equilibria). Empty beyond ``max_balls`` balls.

    Parameters
    ----------
    system : autobalance.models.System
        U [kg*m] of the rotor, m_j [kg] and R [m] of the balancer.
    max_balls : int
        Largest ball count enumerated (2^N sign patterns).

    Returns
    -------
    list of float
        Distinct residuals [kg*m], ascending (rounded to 1e-12 of the capacity).
    """
    import itertools

    b = system.balancer
    if b.n_balls > max_balls or b.n_balls < 1:
        return []
    c = b.masses * b.race_radius
    tol = 1e-12 * float(np.sum(c))
    vals = sorted({round(abs(system.rotor.unbalance + float(np.dot(sg, c))) / tol) * tol
                   for sg in itertools.product((-1.0, 1.0), repeat=b.n_balls)})
    return [float(v) for v in vals]


def machine_with_tolerances(system: System, tolerances: dict,
                            eccentricity_angle: float = 0.0) -> System:
    """The machine with its balancer and suspension at the tolerances' limits.

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    tolerances : dict
        "max_eccentricity_m" [m], "max_rolling_resistance" [-] (every ball; stiction equal)
        and "max_suspension_friction_N" [N] per damper, e.g. from :func:`compute_tolerances`.
    eccentricity_angle : float
        beta of the eccentricity [rad].

    Returns
    -------
    System
    """
    vals = {}
    for k in TOLERANCE_KEYS:
        v = tolerances.get(k) if isinstance(tolerances, dict) else None
        if v is None or not (isinstance(v, (int, float)) and math.isfinite(v) and v >= 0):
            raise ParameterError(f"tolerances.{k}", v, "must be a finite number >= 0 "
                                 "(a result of compute_tolerances with feasible = true)")
        vals[k] = float(v)
    b = dataclasses.replace(system.balancer, eccentricity=vals["max_eccentricity_m"],
                            eccentricity_angle=float(eccentricity_angle),
                            rolling_resistance=vals["max_rolling_resistance"], stiction=None)
    sus = dataclasses.replace(system.suspension, dry_friction_force=vals["max_suspension_friction_N"])
    return dataclasses.replace(system, balancer=b, suspension=sus)


def _random_starts(rng, balancer, n: int) -> list:
    """n start configurations, angles uniform and sorted, neighbours >= 1.05 contact angles."""
    out = []
    gap_min = 1.05 * balancer.contact_angle
    nb = balancer.n_balls
    if nb * gap_min >= 2 * math.pi:
        raise ParameterError("balancer.n_balls", nb, "too many balls to place without contact")
    while len(out) < n:
        a = np.sort(rng.uniform(0.0, 2 * math.pi, nb))
        gaps = np.diff(np.concatenate([a, a[:1] + 2 * math.pi])) if nb > 1 else np.array([math.inf])
        if gaps.min() >= gap_min:
            out.append(a)
    return out


def check_tolerances_by_simulation(base: str | Path | Config, tolerances: dict, *, n: int = 20,
                                   seed: int = 0,
                                   duration: float | str | None = None) -> dict:
    """Monte Carlo of full simulations of the machine built with the tolerances at their limits
    (eccentricity at a random angle, every ball's f/r, the damper friction), from random ball
    start angles through the machine's own speed profile, against the worst-case bound.

    The bound covers the rest states of the balanced region. A run can also stop at a
    collinear equilibrium (all balls on one line through the centre, e.g. two touching
    opposite the unbalance and one with it): an equilibrium that friction and the balls'
    contact hold, outside that region. Such runs are counted as trapped, not as violations.

    Parameters
    ----------
    base : str, Path or Config
        The machine (its profile, options, gravity).
    tolerances : dict
        "max_eccentricity_m" [m], "max_rolling_resistance" [-], "max_suspension_friction_N"
        [N], and optionally "speed_rad_s" (the bound's speed [rad/s], default the nominal).
    n : int
        Runs (>= 1).
    seed : int
        Seed of the random start angles and eccentricity angles.
    duration : float or str or None
        Profile duration [s] or with units (an override of ``profile.duration``; None: the
        machine's own).

    Returns
    -------
    dict
        JSON-ready: "residuals_kg_m" (at the last read-out), "grades_G_mm_s", "statuses",
        "final_angles_rad", "trapped" (per run: above the bound with every ball within a
        contact angle of one line, i.e. stopped at a collinear equilibrium outside the balanced
        region the bound covers), "n_trapped", "n_violations" (above the bound and not
        trapped), "max_residual_kg_m" and "mean_residual_kg_m" (runs not trapped),
        "max_residual_all_kg_m", "bound_kg_m", "expected_kg_m", "max_over_bound" [-],
        "bound_over_max" [-], "holds" (no violation), "start_angles_rad",
        "eccentricity_angles_rad", "speed_rad_s", "n_runs", "n_failed", "elapsed_s".
    """
    from ..simulate import simulate_batch

    t0 = time.perf_counter()
    if isinstance(n, bool) or int(n) != n or n < 1:
        raise ParameterError("n", n, "must be an integer >= 1 (runs)")
    n = int(n)
    sets = []
    if duration is not None:
        sets.append(f"profile.duration={duration if isinstance(duration, str) else repr(float(duration))}")
    cfg = load(base, sets, allow_liquid=True)
    s0 = cfg.system
    tol_speed = tolerances.get("speed_rad_s") if isinstance(tolerances, dict) else None
    w, _ = _settle_speed(cfg, tol_speed)
    liq = liquid_at(s0)
    machine_with_tolerances(s0, tolerances)          # validates before any work
    rng = np.random.default_rng(int(seed))
    betas = rng.uniform(0.0, 2 * math.pi, n)
    starts = _random_starts(rng, s0.balancer, n)
    systems = [machine_with_tolerances(s0, tolerances, b) for b in betas]
    inits = [InitialState(ball_angles=tuple(float(v) for v in a)) for a in starts]
    t_read = cfg.spin.checkpoints[-1] if cfg.spin.checkpoints else cfg.spin.duration
    res = (simulate_batch(systems, cfg.spin, inits, options=cfg.options, out_times=[t_read])
           if s0.liquid is None else _hybrid_runs(systems, cfg, inits, t_read))
    final = res.residual_unbalance[:, -1]
    ok = np.array([st == "ok" for st in res.status])
    pred = worst_case_prediction(systems[0], w, nominal_speed=cfg.spin.nominal_speed,
                                 eccentricity_angle=None, liquid=liq(w))
    bound = pred["worst_residual_kg_m"]
    collinear = np.array([_collinear(a, s0.balancer.contact_angle) for a in res.alpha[:, -1]])
    above = ok & (final > bound)
    trapped = above & collinear
    inside = ok & ~trapped
    good = final[inside]
    mx = float(good.max()) if good.size else math.nan
    return {
        "name": cfg.name, "speed_rad_s": w, "read_out_s": float(t_read),
        "duration_s": float(cfg.spin.duration), "n_runs": n, "n_failed": int((~ok).sum()),
        "statuses": list(res.status), "tolerances": {k: float(tolerances[k]) for k in TOLERANCE_KEYS},
        "eccentricity_angles_rad": betas, "start_angles_rad": np.array(starts),
        "final_angles_rad": res.alpha[:, -1], "residuals_kg_m": final,
        "grades_G_mm_s": res.grade_G[:, -1], "trapped": trapped,
        "n_trapped": int(trapped.sum()), "n_violations": int((above & ~collinear).sum()),
        "max_residual_kg_m": mx, "max_residual_all_kg_m": float(final[ok].max()) if ok.any() else math.nan,
        "mean_residual_kg_m": float(good.mean()) if good.size else math.nan,
        "bound_kg_m": bound, "expected_kg_m": pred["expected_residual_kg_m"],
        "max_over_bound": mx / bound if bound > 0 else math.nan,
        "bound_over_max": bound / mx if mx > 0 else math.inf,
        "holds": bool(good.size and not (above & ~collinear).any()),
        "separated": pred["separated"], "elapsed_s": time.perf_counter() - t0,
    }


def _hybrid_runs(systems, cfg, inits, t_read: float):
    """Runs of balls beside a liquid (:func:`autobalance.simulate`, the films of
    :mod:`autobalance.simulate.hybrid`) read out at ``t_read`` [s], in the fields of a
    BatchResult that :func:`check_tolerances_by_simulation` reads. The runs share the cores in
    threads: the hybrid kernel releases the GIL (core/hybrid.py; docs/numerics/compilation.md)."""
    import os
    from concurrent.futures import ThreadPoolExecutor
    from types import SimpleNamespace

    from ..simulate import simulate

    def one(pair):
        return simulate(pair[0], cfg.spin, initial=pair[1], options=cfg.options, throw=False)

    with ThreadPoolExecutor(max_workers=max(1, min(len(systems), os.cpu_count() or 1))) as ex:
        sims = list(ex.map(one, zip(systems, inits)))
    k = [int(np.argmin(np.abs(r.t - t_read))) for r in sims]
    return SimpleNamespace(
        residual_unbalance=np.array([[r.residual_unbalance[j]] for r, j in zip(sims, k)]),
        grade_G=np.array([[r.grade_G[j]] for r, j in zip(sims, k)]),
        alpha=np.array([[r.alpha[j]] for r, j in zip(sims, k)]),
        status=[r.status for r in sims])


def _collinear(alpha, contact_angle: float) -> bool:
    """All balls within a contact angle of one line through the centre (a collinear
    equilibrium, e.g. one ball with the unbalance and two touching opposite it)."""
    a = np.mod(np.asarray(alpha, float), math.pi)          # a line: angles mod pi
    for ref in a:
        d = np.abs(np.angle(np.exp(2j * (a - ref)))) / 2   # distance mod pi
        if d.max() <= contact_angle:
            return True
    return False


#: The causes of the residual of a tolerance budget, in the order of 000 eq 56.
CAUSES = ("eccentricity", "rolling", "friction", "other")


def tolerances_dataset(res: dict) -> xr.Dataset:
    """A tolerance study (:func:`compute_tolerances`, with its ``simulation_check`` if run) as
    a dataset: per cause of 000 eq 56 its share of the target residual ``budget`` [kg m], the
    worst-case residual of that tolerance at its allowed limit ``at_limit`` [kg m] (NaN where
    the method gives none) and of the machine's own ``own`` [kg m]; the summary's numbers and
    texts as attrs.

    Parameters
    ----------
    res : dict
        :func:`compute_tolerances`'s result.
    """
    import xarray as xr

    def per_cause(d: dict | None) -> np.ndarray:
        d = d or {}
        return np.array([float(d.get(c, np.nan)) for c in CAUSES])

    scalars = {k: v for k, v in res.items()           # NetCDF attrs: numbers and text
               if isinstance(v, (int, float, str)) and not isinstance(v, bool)}
    scalars.update({k: int(v) for k, v in res.items() if isinstance(v, bool)})
    unit = {"units": "kg m"}
    ds = xr.Dataset(
        {"budget": ("cause", per_cause(res.get("budget_kg_m")),
                    {**unit, "long_name": "share of the target residual (000 eq 56)"}),
         "at_limit": ("cause", per_cause(res.get("bound_at_max_kg_m")),
                      {**unit, "long_name": "worst-case residual at the allowed tolerance"}),
         "own": ("cause", per_cause(res.get("cause_residual_kg_m")),
                 {**unit, "long_name": "worst-case residual of the machine's own tolerance"})},
        coords={"cause": list(CAUSES)}, attrs=scalars)
    sim = res.get("simulation_check")
    if sim:
        ds["simulated_residual"] = ("run", np.asarray(sim["residuals_kg_m"], float),
                                    {**unit, "long_name": "residual of a simulated run with "
                                     "the tolerances at their limits"})
    return ds
