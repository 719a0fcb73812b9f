"""The inverse problem: which ball balancer and speed profile meet a target grade for a machine
whose initial unbalance is only known to lie in a range.

For every candidate design (:mod:`.design_space`) - ball count N, ball mass m (from the balls'
capacity N m R as a multiple of the largest expected unbalance), race radius R and speed
profile (the machine's standard run-up, a 3x slower run-up, a temporary speed reduction fitted
to the machine; 004 sec. 4.4-4.6) - the machine is simulated from uniform random ball start
positions at initial unbalances spread over the range (004 sec. 4.2-4.3's statistics,
generalised). A design *meets the target* when, at every studied unbalance, the
``confidence`` quantile of the final grade over the starts is at or below the target grade,
judged against the quantile's interval: meets, fails or undecided, with more starts where it
is undecided, cheapest candidate first, within a budget (:mod:`.design_verdicts`). Its
*margin* is the target minus the worst such quantile [mm/s], with its interval. The designs
are ranked decided "meets" first, then cheapest (least total ball mass, then shortest
profile), and the Pareto front of (total ball mass, worst quantile) is marked; the
recommendation is the cheapest design decided to meet the target (or none).

The plateau study (:mod:`.plateau`, 004 sec. 4.6) runs on the best TSR candidate, and its
recommended plateau joins the search as one more candidate. The recommended design also gets
the tolerances of :mod:`.tolerances` for the target grade.
"""
from __future__ import annotations

import json
import math
import time
from typing import TYPE_CHECKING

import numpy as np

from ..confidence import LEVEL
from ..models import ParameterError
from ..physics.iso1940 import grade_value
from .common import load, run_start_grid, store_path
from .design_space import (PLATEAU_RATIO, DesignSpace, candidate, candidate_designs,
                           profile_variants)
from .design_verdicts import VERDICT_ORDER, candidate_verdicts, decide, pad

if TYPE_CHECKING:
    from pathlib import Path

    import xarray as xr

    from ..config import Config

__all__ = ["DesignSpace", "candidate_designs", "compute_design", "design_summary",
           "profile_variants"]

#: Why a design beside a liquid may have no tolerances (docs/liquid/balls-beside-liquid.md sec. 3l),
#: before the bound's one-line refusal (a horizontal axis, two partitions, an anisotropic
#: suspension).
TOLERANCES_BESIDE_LIQUID = ("beside this liquid the tolerance bound does not hold; judge a "
                            "built design by simulation (study sensitivity)")


def compute_design(base: str | Path | Config, *, grade: float = 16.0, confidence: float = 0.95,
                   unbalance_range: tuple | None = None, n_unbalance: int | None = None,
                   starts: int | None = None,
                   space: DesignSpace | None = None, quick: bool = False, seed: int = 0,
                   store_dir: str | Path | None = None, executor: str = "local",
                   workers: int | None = None, scheduler: str | None = None,
                   progress: bool = False, refine_plateau: bool = True,
                   tolerances: bool = True, budget: int | None = None) -> xr.Dataset:
    """Search ball count, ball mass, race radius and speed profile for designs that meet a target
    grade over a range of initial unbalances (module docstring).

    Parameters
    ----------
    base : str, Path or Config
        The machine (with or without a balancer).
    grade : float
        Target ISO 1940 grade [mm/s] at the nominal speed.
    confidence : float
        Share of start positions that must meet the target at every studied unbalance [-], in
        (0, 1) (default 0.95, as 004's 95th percentile).
    unbalance_range : (float, float) or None
        Expected initial unbalance [kg*m] (lo, hi), 0 <= lo <= hi, hi > 0; None = 0.5-1.5 x the
        machine's.
    n_unbalance : int or None
        Unbalances studied across the range (>= 1; the ends included); None = 4 (quick 3).
    starts : int or None
        Uniform random ball start positions per unbalance and design (>= 1) in the first pass;
        None = 40 (quick 10).
    space : DesignSpace or None
        The candidates; None = :class:`DesignSpace` (quick: :meth:`DesignSpace.quick`).
    quick : bool
        The small space, 3 unbalances and 10 starts unless given.
    seed : int
        Seed of the start positions (the same starts for every design).
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where the sweeps run and are kept (one resumable store per design under ``store_dir``;
        None = temporary stores), as for
        :func:`autobalance.studies.common.run_start_grid`.
    progress : bool
        Show each sweep's progress bar on stderr.
    refine_plateau : bool
        Run the plateau study on the best TSR candidate (ratios :data:`REFINE_RATIOS`, the
        design's unbalances) and add its recommended plateau as one more candidate.
    tolerances : bool
        Add the allowed ring eccentricity, rolling resistance and suspension friction of the
        recommended design for the target grade (study tolerances, true bound).
    budget : int or None
        Most runs the sequential decision adds to the first pass (:mod:`.design_verdicts`);
        None: 4 x the first pass's runs; 0: none (the verdicts of the first pass).

    Returns
    -------
    xarray.Dataset
        grade_G [mm/s] over (design, unbalance, sample) at the last read-out (NaN where a
        cell has fewer starts than the largest); per design and unbalance the quantile and
        its interval quantile_ci [mm/s] and the starts run; per design worst_quantile and
        margin [mm/s] with their intervals, verdict ("meets", "fails", "undecided": against
        the intervals), meets (a decided "meets"), rank, pareto and plateau_ratio [-]; attrs
        with the search's counts (simulations run, those of the plateau study, the budget and
        what it bought), the recommended design (a decided "meets", or none), the plateau
        study's result (plateau_*) and the recommended design's tolerances (tolerance_*), and
        the settings.
    """
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True)     # simulations; beside a liquid too (sec. 3i)
    n_unbalance = (3 if quick else 4) if n_unbalance is None else n_unbalance
    starts = (10 if quick else 40) if starts is None else starts
    if not (0.0 < confidence < 1.0):
        raise ParameterError("confidence", confidence, "must be within (0, 1), e.g. 0.95")
    for name, v in (("n_unbalance", n_unbalance), ("starts", starts)):
        if isinstance(v, bool) or int(v) != v or v < 1:
            raise ParameterError(name, v, "must be an integer >= 1")
    U0 = cfg.system.rotor.unbalance
    lo, hi = (0.5 * U0, 1.5 * U0) if unbalance_range is None else map(float, unbalance_range)
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo <= hi and hi > 0):
        raise ParameterError("unbalance_range", (lo, hi), "must be 0 <= lo <= hi with hi > 0 [kg*m]")
    space = space or (DesignSpace.quick() if quick else DesignSpace())
    Us = np.linspace(lo, hi, n_unbalance) if n_unbalance > 1 else np.array([hi])
    variants = profile_variants(cfg)
    cands = candidate_designs(cfg, space, hi, variants)
    if not cands:
        raise ParameterError("profiles", space.profiles, f"none applies to this machine's "
                             f"{cfg.spin.name} profile; available: "
                             f"{', '.join(variants)}")
    M, wn = cfg.system.total_mass, cfg.spin.nominal_speed
    run = dict(seed=seed, store_dir=store_dir, executor=executor, workers=workers,
               scheduler=scheduler, progress=progress)
    g, refine = _first_pass(cfg, cands, Us, starts, quick, confidence, refine_plateau, run)
    first_pass = int(sum(np.asarray(gi).size for gi in g))
    # total ball mass, rounded to 1e-9 relative so that equal designs (2 x 3m/2 = 3 x m) tie
    ball_mass = np.array([c["n_balls"] * c["ball_mass"] for c in cands])
    ball_mass = np.array([float(f"{x:.9e}") for x in ball_mass])
    dur = np.array([c["duration"] for c in cands])
    # more starts where a verdict is undecided, cheapest candidate first (design_verdicts)
    cells = [[np.asarray(gi[u], float) for u in range(Us.size)] for gi in g]
    budget = 4 * first_pass if budget is None else int(budget)

    def run_more(d, units, k, rnd):
        more = _evaluate(cands[d], Us[units], k, **{**run, "seed": seed + 7919 * rnd},
                         tag=f"-more{rnd}")
        return list(more)
    cheapest = sorted(range(len(cands)), key=lambda k: (ball_mass[k], dur[k]))
    dec = decide(cells, cheapest, grade, confidence, budget, run_more)
    g = pad(cells)
    vd = candidate_verdicts(g, grade, confidence)
    # grades at the machine's nominal speed and total mass with the candidate's balls
    worst = vd["worst"]
    meets = vd["verdict"] == "meets"
    order = sorted(range(len(cands)), key=lambda k: (VERDICT_ORDER[vd["verdict"][k]],
                                                     ball_mass[k], dur[k], worst[k]))
    rank = np.empty(len(cands), int)
    rank[order] = np.arange(len(cands))
    pareto = np.array([not any((ball_mass[j] <= ball_mass[k]) and (worst[j] <= worst[k])
                               and ((ball_mass[j] < ball_mass[k]) or (worst[j] < worst[k]))
                               for j in range(len(cands))) for k in range(len(cands))])
    G_u = grade_value(Us, M, wn)
    # the tolerances to build the recommended design with (the cheapest decided to meet the
    # target, else the one closest to it): study tolerances for the same grade (closed form)
    pick = int(order[0]) if meets.any() else int(np.nanargmin(worst))
    tol, skipped = {}, ""
    if tolerances:
        try:
            tol = _design_tolerances(cands[pick]["config"], grade)
        except ParameterError as e:          # beside a liquid the bound has its limits
            if cfg.system.liquid is None:
                raise
            skipped = f"{TOLERANCES_BESIDE_LIQUID}: {e}"
    ds = xr.Dataset(
        _variables(cands, g, vd, confidence, rank, pareto, ball_mass, dur),
        coords={"design": [c["name"] for c in cands], "bound": ["lo", "hi"],
                "unbalance": ("unbalance", Us, {"units": "kg*m"}),
                "G_ini": ("unbalance", np.atleast_1d(G_u), {"units": "mm/s"})})
    ds.attrs.update({"study": "design", "grade": float(grade), "confidence": float(confidence),
                     "starts": int(starts), "seed": int(seed), "n_designs": len(cands),
                     "simulations": first_pass + dec["spent"],
                     "simulations_first_pass": first_pass,
                     "failed": int(sum(np.isnan(a).sum() for c in cells for a in c)),
                     "budget": dec["budget"], "budget_spent": dec["spent"],
                     "budget_rounds": dec["rounds"], "budget_exhausted": int(dec["exhausted"]),
                     "capped_at_max_starts": "; ".join(cands[d]["name"] for d in dec["capped"]),
                     "recommended": (str(cands[dec["recommended"]]["name"])
                                     if dec["recommended"] is not None else
                                     str(cands[int(order[0])]["name"]) if meets.any() else ""),
                     "confidence_level": LEVEL,
                     "profiles": "; ".join(f"{k}: {' '.join(v)}" for k, v in variants.items()),
                     "simulations_plateau_study": int(refine.get("simulations", 0)),
                     **{f"plateau_{k}": v for k, v in refine.items()
                        if k not in ("candidate", "simulations")},
                     "tolerances_design": str(cands[pick]["name"]) if tol else "",
                     "tolerances_skipped": skipped,
                     **{f"tolerance_{k}": v for k, v in tol.items()},
                     "wall_s": time.perf_counter() - t0})
    return ds


def _first_pass(cfg, cands: list, Us: np.ndarray, starts: int, quick: bool, confidence: float,
                refine_plateau: bool, run: dict) -> tuple[list, dict]:
    """Every candidate's final grades [mm/s] from ``starts`` random starts at each unbalance
    ``Us`` [kg*m], and the plateau study (004 sec. 4.6) on the best TSR candidate: its
    recommended plateau joins ``cands`` (in place) as one more candidate, judged like every
    other. Returns (grades per candidate (unbalance, start), the plateau study's result or
    {})."""
    g = [_evaluate(c, Us, starts, **run) for c in cands]
    refine = {}
    if refine_plateau and any(c["profile"] == "tsr" for c in cands):
        q0 = np.array([np.nanquantile(gi, confidence, axis=1).max() for gi in g])
        k = min((i for i, c in enumerate(cands) if c["profile"] == "tsr"), key=lambda i: q0[i])
        refine = _refine_plateau(cfg, cands[k], Us, starts, quick, **run)
        if refine["candidate"] is not None:
            cands.append(refine["candidate"])
            g.append(_evaluate(refine["candidate"], Us, starts, **run))
    return g, refine


def _variables(cands: list, g: np.ndarray, vd: dict, confidence: float, rank: np.ndarray,
               pareto: np.ndarray, ball_mass: np.ndarray, dur: np.ndarray) -> dict:
    """The design dataset's variables: the grades (design, unbalance, sample) [mm/s], the
    verdicts with their intervals (:func:`.design_verdicts.candidate_verdicts` as ``vd``), the
    rank and Pareto front, and each candidate's balls, profile and overrides."""
    v = vd
    meets = v["verdict"] == "meets"
    quant, worst, margin = v["quantile"], v["worst"], v["margin"]
    return {"grade_G": (("design", "unbalance", "sample"), g, {"units": "mm/s",
                                                               "long_name": "grade at the last read-out"}),
            "quantile": (("design", "unbalance"), quant, {"units": "mm/s",
                                                          "long_name": f"{100 * confidence:g} % quantile over starts"}),
            "quantile_ci": (("design", "unbalance", "bound"), np.stack([v["lo"], v["hi"]], -1),
                            {"units": "mm/s", "confidence_level": LEVEL,
                             "long_name": "interval of the quantile (order statistics; inf: "
                                          "unbounded)"}),
            "starts_run": (("design", "unbalance"), v["starts"], {"units": "1"}),
            "worst_quantile": ("design", worst, {"units": "mm/s"}),
            "worst_quantile_ci": (("design", "bound"), np.stack([v["worst_lo"], v["worst_hi"]], -1),
                                  {"units": "mm/s", "confidence_level": LEVEL}),
            "margin": ("design", margin, {"units": "mm/s", "long_name": "target - worst quantile"}),
            "margin_ci": (("design", "bound"), np.stack([v["margin_lo"], v["margin_hi"]], -1),
                          {"units": "mm/s", "confidence_level": LEVEL}),
            "verdict": ("design", v["verdict"].astype(str),
                        {"long_name": "meets, fails or undecided against the intervals"}),
            "meets": ("design", meets), "rank": ("design", rank), "pareto": ("design", pareto),
            "n_balls": ("design", [c["n_balls"] for c in cands]),
            "ball_mass": ("design", [c["ball_mass"] for c in cands], {"units": "kg"}),
            "total_ball_mass": ("design", ball_mass, {"units": "kg"}),
            "race_radius": ("design", [c["race_radius"] for c in cands], {"units": "m"}),
            "capacity": ("design", [c["capacity"] for c in cands], {"units": "kg*m"}),
            "profile": ("design", [c["profile"] for c in cands]),
            "sets": ("design", ["; ".join(c["sets"]) for c in cands],
                     {"long_name": "the --set overrides that make the design from the machine"}),
            "plateau_ratio": ("design", [c["plateau_ratio"] for c in cands],
                              {"units": "-", "long_name": "TSR plateau / first natural frequency"}),
            "duration": ("design", dur, {"units": "s"}),
            "profile_knots": ("design", [_knots(c["config"].spin) for c in cands],
                              {"long_name": "the profile's knots as JSON [[time s, speed rad/s], "
                                            "...] ([] for a motor drive)"})}


def _knots(spin) -> str:
    """A profile's knots as JSON ``[[t [s], speed [rad/s]], ...]``; ``[]`` for a motor drive."""
    times = getattr(spin, "times", None)
    if times is None:
        return "[]"
    return json.dumps([[float(t), float(w)] for t, w in zip(times, spin.speeds)])


def _evaluate(c: dict, Us, starts: int, *, seed, store_dir, executor, workers, scheduler,
              progress, tag: str = "") -> np.ndarray:
    """Final grades [mm/s] of one candidate, (unbalance, start): uniform random starts (the
    same for every candidate: one seed) at each unbalance; failed runs NaN. ``tag`` names a
    sweep of more starts (another seed) apart from the first."""
    # the candidate as a base of its own: its ball count changes the initial angles, which a
    # random Monte Carlo may not take as overrides
    raw = run_start_grid(c["config"], f"design-{c['name']}{tag}", (),
                         {"rotor.unbalance": [float(u) for u in Us]}, 0, samples=starts,
                         seed=seed, store=store_path(store_dir, f"design-{c['name']}{tag}"),
                         executor=executor, workers=workers, scheduler=scheduler,
                         progress=progress)
    gi = raw["grade_G"].where(raw["status"] == 0).isel(checkpoint=-1)
    return gi.transpose("rotor__unbalance", "sample").values


#: Plateau ratios [-] the design's plateau study tries (full, quick).
REFINE_RATIOS = (tuple(np.round(np.arange(0.98, 1.1601, 0.02), 3)), (1.0, 1.06, 1.12))


def _refine_plateau(cfg, cand: dict, Us, starts: int, quick: bool, *, seed, store_dir,
                    executor, workers, scheduler, progress) -> dict:
    """The plateau study (:func:`.plateau.compute_plateau`, 004 sec. 4.6's criterion) for one
    TSR candidate at the design's unbalances, with about ``starts`` grid starts per cell;
    returns the recommended ratio, the study's mean 95th percentiles and, when it differs
    from :data:`PLATEAU_RATIO`, the candidate with that plateau (else None)."""
    from ..sweep.plan import identical_balls, n_start_grid
    from ._plateau import compute_plateau, plateau_summary
    from .common import starts_for_runs

    b = cand["config"].system.balancer
    n = starts_for_runs(b.n_balls, starts, identical_balls(b))
    ratios = np.array(REFINE_RATIOS[1 if quick else 0])
    G = np.atleast_1d(grade_value(Us, cand["config"].system.total_mass,
                                  cand["config"].spin.nominal_speed))
    ds = compute_plateau(cand["config"], ratios=ratios, G=G, n=n, g_range=float(G.max()),
                         store_dir=store_path(store_dir, f"design-plateau-{cand['name']}"),
                         executor=executor, workers=workers, scheduler=scheduler,
                         prefix="design", budget=0, progress=progress)   # judged by decide
    ps = plateau_summary(ds)
    r = ps["recommended_plateau_ratio"]
    new = None
    if not math.isclose(r, PLATEAU_RATIO, rel_tol=1e-9):
        new = candidate(cfg, cand["n_balls"], cand["ball_mass"], cand["race_radius"],
                        cand["capacity_ratio"], "tsr", cand["ball_sets"], {}, r)
        if new is not None and math.isclose(new["plateau_ratio"], cand["plateau_ratio"],
                                            rel_tol=1e-9):
            new = None              # both raised to the same stable onset: the same candidate
    return {"candidate": new, "studied": cand["name"], "ratios": ratios,
            "mean_p95_grade_G_mm_s": np.asarray(ps["mean_p95_grade_G_mm_s"], float),
            "recommended_ratio": r, "at_grid_edge": int(ps["at_grid_edge"]),
            "simulations": int(ratios.size * G.size * n_start_grid(n, b.n_balls, identical_balls(b)))}


def _design_tolerances(config, grade: float) -> dict:
    """The tolerances for the target grade of a design (:func:`.tolerances.compute_tolerances`,
    the true bound) as flat SI attrs, with the study's notes (e.g. beside a liquid on a
    horizontal axis, the balanced state's Floquet verdict); feasible = 0 with the study's
    reason (and NaN tolerances) when it refuses, e.g. below the balancing onset."""
    from ._tolerances import compute_tolerances

    t = compute_tolerances(config, grade=grade)
    keys = ("max_eccentricity_m", "max_rolling_resistance", "max_suspension_friction_N")
    out = {"feasible": int(bool(t["feasible"])), "reason": t["reason"] or "",
           "own_worst_grade_G_mm_s": float(t["worst_grade_G_mm_s"]),
           "notes": "\n".join(t.get("warnings", []))}   # the study's notes, one a line
    out.update({k: float(t[k]) if t[k] is not None else math.nan for k in keys})
    return out


def design_summary(ds: xr.Dataset, top: int = 5) -> dict:
    """JSON-ready summary of a :func:`compute_design` result: the designs in rank order (the
    first ``top`` in full), the Pareto front and the counts.

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_design` result.
    top : int
        Designs listed in full.

    Returns
    -------
    dict
        grade_G_mm_s, confidence, confidence_level, simulations (simulations_first_pass,
        simulations_plateau_study), budget (runs, spent, rounds, exhausted, capped: the
        candidates left undecided at the most starts per cell), designs (name, n_balls,
        ball_mass_kg, total_ball_mass_kg, race_radius_m, capacity_kg_m, profile,
        plateau_ratio, duration_s, sets (the "path=value" overrides that make it from the
        machine), worst_quantile_grade_G_mm_s and margin_grade_G_mm_s with their intervals
        ``..._ci`` [lo, hi] (null: unbounded), verdict (meets, fails, undecided), meets (a
        decided "meets"), pareto, the per-unbalance quantiles with their intervals and starts,
        the profile's knots), n_meeting, n_undecided, pareto (names), best (the cheapest
        design decided to meet the target, or None),
        plateau_study (the studied design, ratios, mean 95th percentiles, recommended ratio)
        and tolerances (of the recommended design for the target grade), when computed.
    """
    order = np.argsort(ds["rank"].values)
    rows = []
    for k in order:
        d = ds.isel(design=int(k))
        rows.append({"name": str(d["design"].values), "n_balls": int(d["n_balls"]),
                     "ball_mass_kg": float(d["ball_mass"]),
                     "total_ball_mass_kg": float(d["total_ball_mass"]),
                     "race_radius_m": float(d["race_radius"]), "capacity_kg_m": float(d["capacity"]),
                     "profile": str(d["profile"].values),
                     "plateau_ratio": float(d["plateau_ratio"]), "duration_s": float(d["duration"]),
                     "sets": str(d["sets"].values).split("; "),
                     "worst_quantile_grade_G_mm_s": float(d["worst_quantile"]),
                     "worst_quantile_grade_G_mm_s_ci": [float(x) for x in d["worst_quantile_ci"]],
                     "margin_grade_G_mm_s": float(d["margin"]),
                     "margin_grade_G_mm_s_ci": [float(x) for x in d["margin_ci"]],
                     "verdict": str(d["verdict"].values), "meets": bool(d["meets"]),
                     "pareto": bool(d["pareto"]),
                     "quantile_grade_G_mm_s": d["quantile"].values,
                     "quantile_grade_G_mm_s_ci": d["quantile_ci"].values,
                     "starts": d["starts_run"].values,
                     "profile_knots_s_rad_s": json.loads(str(d["profile_knots"].values))
                     if "profile_knots" in d else []})
    best = next((r for r in rows if r["meets"]), None)
    a = ds.attrs
    out = {"grade_G_mm_s": a["grade"], "confidence": a["confidence"],
           "confidence_level": a.get("confidence_level", LEVEL),
           "unbalance_kg_m": ds["unbalance"].values, "G_ini_mm_s": ds["G_ini"].values,
           "starts": a["starts"], "simulations": a["simulations"],
           "simulations_first_pass": a.get("simulations_first_pass", a["simulations"]),
           "budget": {"runs": a.get("budget", 0), "spent": a.get("budget_spent", 0),
                      "rounds": a.get("budget_rounds", 0),
                      "exhausted": bool(a.get("budget_exhausted", 0)),
                      "capped": [x for x in str(a.get("capped_at_max_starts", "")).split("; ")
                                 if x]},
           "simulations_plateau_study": a.get("simulations_plateau_study", 0),
           "failed": a["failed"], "n_designs": ds.sizes["design"],
           "n_meeting": int(ds["meets"].sum()),
           "n_undecided": int((ds["verdict"] == "undecided").sum()), "best": best,
           "pareto": [r["name"] for r in rows if r["pareto"]],
           "designs": rows[:top], "all_designs": [r["name"] for r in rows]}
    if "plateau_recommended_ratio" in a:
        out["plateau_study"] = {
            "design": a["plateau_studied"], "ratios": np.atleast_1d(a["plateau_ratios"]),
            "mean_p95_grade_G_mm_s": np.atleast_1d(a["plateau_mean_p95_grade_G_mm_s"]),
            "recommended_plateau_ratio": float(a["plateau_recommended_ratio"]),
            "at_grid_edge": bool(a["plateau_at_grid_edge"])}
    if a.get("tolerances_skipped"):
        out["tolerances_skipped"] = str(a["tolerances_skipped"])
    if a.get("tolerances_design"):
        out["tolerances"] = {"design": a["tolerances_design"],
                             "feasible": bool(a["tolerance_feasible"]),
                             "reason": a["tolerance_reason"] or None,
                             **{k: (None if not math.isfinite(a[f"tolerance_{k}"])
                                    else float(a[f"tolerance_{k}"]))
                                for k in ("max_eccentricity_m", "max_rolling_resistance",
                                          "max_suspension_friction_N")},
                             "own_worst_grade_G_mm_s": float(a["tolerance_own_worst_grade_G_mm_s"]),
                             "notes": [n for n in str(a.get("tolerance_notes", "")).split("\n")
                                       if n]}
    return out
