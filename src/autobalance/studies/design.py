"""The inverse problem: which ball balancer and speed profile meet a target grade for a machine
whose initial unbalance is only known to lie in a range.

For every candidate design - ball count N, ball mass m (from the balls' capacity N m R as a
multiple of the largest expected unbalance), race radius R and speed profile (the machine's
standard run-up, a 3x slower run-up, a temporary speed reduction; 004 sec. 4.4-4.6) - the
machine is simulated from uniform random ball start positions at initial unbalances spread over
the range (004 sec. 4.2-4.3's statistics, generalised). A design *meets the target* when, at
every studied unbalance, the ``confidence`` quantile of the final grade over the starts is at or
below the target grade; its *margin* is the target minus the worst such quantile [mm/s]. The
designs are ranked cheapest first (least total ball mass, then shortest profile) and the Pareto
front of (total ball mass, worst quantile) is marked.

Sizing rules (ours, stated): a capacity below the largest unbalance cannot balance it (004 sec.
4.3: the residual is at least U - N m R); 004 sec. 4.3 also finds that an over-sized balancer
balances poorly, hence capacity ratios from 1.1 to 2. Steel balls keep their density: the ball
radius scales with the cube root of the mass. The TSR plateau is 1.06 x the first natural
frequency of the machine with the candidate's balls (004 sec. 3.2 chooses a plateau just
above resonance); the plateau study (:mod:`.plateau`, 004 sec. 4.6) then runs on the best TSR
candidate, and its recommended plateau joins the search as one more candidate. The
recommended design also gets the tolerances of :mod:`.tolerances` for the target grade.
"""
from __future__ import annotations

import math
import time
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from ..physics.iso1940 import grade_value
from .common import load, run_start_grid, store_path

if TYPE_CHECKING:
    from pathlib import Path

    import xarray as xr

    from ..config import Config

__all__ = ["DesignSpace", "candidate_designs", "compute_design", "design_summary",
           "profile_variants"]

#: TSR plateau of the candidate profiles as a multiple of the first natural frequency [-].
PLATEAU_RATIO = 1.06
#: Why a design beside a liquid may have no tolerances (docs/liquid.md sec. 3l), before the
#: bound's one-line refusal (a horizontal axis, two partitions, an anisotropic suspension).
TOLERANCES_BESIDE_LIQUID = ("beside this liquid the tolerance bound does not hold; judge a "
                            "built design by simulation (study sensitivity)")


@dataclass(frozen=True)
class DesignSpace:
    """The candidates the design search tries.

    Attributes
    ----------
    n_balls : tuple of int
        Ball counts N (>= 1).
    capacity_ratios : tuple of float
        Capacity N m R over the largest expected unbalance [-] (> 1).
    radii : tuple of float or None
        Race radii R [m]; None = the machine's.
    profiles : tuple of str
        Speed profiles from :func:`profile_variants`: "given", "std", "slow", "tsr".
    """

    n_balls: tuple = (2, 3)
    capacity_ratios: tuple = (1.1, 1.4, 2.0)
    radii: tuple | None = None
    profiles: tuple = ("std", "slow", "tsr")

    @classmethod
    def quick(cls) -> "DesignSpace":
        """A small space for a first look: 2 or 3 balls, capacity 1.2 or 1.8 x, std or tsr."""
        return cls(n_balls=(2, 3), capacity_ratios=(1.2, 1.8), profiles=("std", "tsr"))


def profile_variants(cfg: Config, plateau_ratio: float = PLATEAU_RATIO,
                     natural_frequency: float | None = None) -> dict:
    """The speed profiles a design may use, as ``--set`` overrides of the machine's profile
    (004 sec. 4.4: the standard run-up, a 3x slower run-up; 004 sec. 3.2: a temporary speed
    reduction to :data:`PLATEAU_RATIO` x the first natural frequency for 10/20/10 s).

    "given" is the machine's own profile as it is (no overrides). Only a std or tsr profile
    has variants; any other profile kind gives {"given": []} alone.

    Parameters
    ----------
    cfg : Config
        The machine (its ``spin``: nominal speed [rad/s], run-up time and read-out [s]).
    plateau_ratio : float
        The TSR plateau over the first natural frequency [-].
    natural_frequency : float or None
        That frequency [rad/s]; None = the machine's first (with its own balls; a candidate
        passes its own, with the candidate's balls).

    Returns
    -------
    dict of str to list of str
        Variant name -> "path=value" overrides (SI numbers).
    """
    spin = cfg.spin
    if getattr(spin, "name", "") not in ("std", "tsr"):
        return {"given": []}
    wn = spin.nominal_speed
    t_ru, t_read, dur = float(spin.times[1]), float(spin.checkpoints[0]), float(spin.duration)
    std_dur = max(dur if spin.name == "std" else t_read * 1.5, t_read)
    slow_ru = 3.0 * t_ru
    slow_dur = max(std_dur, slow_ru + (std_dur - t_read))
    tsr_dur = max(dur if spin.name == "tsr" else 0.0, t_read + 40.0 + max(10.0, std_dur - t_read))
    fn = cfg.system.natural_frequencies[0] if natural_frequency is None else natural_frequency
    wp = plateau_ratio * fn
    out = {
        "given": [],
        "std": ["profile.kind=std", f"profile.nominal={wn!r}", f"profile.runup_time={t_ru!r}",
                f"profile.duration={std_dur!r}", f"profile.runup_fraction={t_read / std_dur!r}"],
        "slow": ["profile.kind=std", f"profile.nominal={wn!r}", f"profile.runup_time={slow_ru!r}",
                 f"profile.duration={slow_dur!r}",
                 f"profile.runup_fraction={slow_ru / slow_dur!r}"],
    }
    if wp < wn:
        out["tsr"] = ["profile.kind=tsr", f"profile.nominal={wn!r}", f"profile.runup_time={t_ru!r}",
                      f"profile.duration={tsr_dur!r}", f"profile.runup_fraction={t_read / tsr_dur!r}",
                      f"profile.plateau={wp!r}", "profile.down_time=10.0",
                      "profile.plateau_time=20.0", "profile.up_time=10.0"]
    return out


def candidate_designs(cfg: Config, space: DesignSpace, U_max: float,
                      variants: dict | None = None) -> list:
    """Every candidate of ``space`` for a largest expected unbalance ``U_max`` [kg*m].

    Parameters
    ----------
    cfg : Config
        The machine; its balancer (if any) gives the ball radius, element, damping and rolling
        resistance of ball 1, which every candidate keeps (ball radius scaled as m^(1/3)).
    space : DesignSpace
        The candidates to try.
    U_max : float
        Largest expected initial unbalance [kg*m], > 0.
    variants : dict or None
        The machine's :func:`profile_variants` (None: computed here).

    Returns
    -------
    list of dict
        name, n_balls, ball_mass [kg], race_radius [m], capacity [kg*m], profile,
        plateau_ratio [-] (over the first natural frequency with the candidate's balls; NaN
        unless tsr), duration [s], ball_sets and sets (the "path=value"
        overrides that make the candidate's balls, and the whole candidate, from the machine)
        and config (the candidate's Config).
    """
    b = cfg.system.balancer
    variants = profile_variants(cfg) if variants is None else variants
    radii = space.radii or (b.race_radius,)
    m0, r0 = (float(b.masses[0]), b.ball_radius) if b.n_balls else (None, b.ball_radius)
    # ball 1's friction and damping (a machine without balls: 004 Table 1's mu_ref, no damping)
    mu = float(b.rolling_resistance[0]) if b.n_balls else 0.002
    mu_s = float(np.max(b.stiction)) if b.n_balls else mu
    damping = float(b.damping[0]) if b.n_balls else 0.0
    out = []
    for N in space.n_balls:
        for ratio in space.capacity_ratios:
            for R in radii:
                m = ratio * U_max / (N * R)
                r_ball = r0 if m0 is None else r0 * (m / m0) ** (1.0 / 3.0)
                ball = [f"balancer.n_balls={N}", f"balancer.ball_mass={m!r}",
                        f"balancer.race_radius={R!r}", f"balancer.ball_radius={r_ball!r}",
                        f"balancer.rolling_resistance={mu!r}", f"balancer.stiction={mu_s!r}",
                        f"balancer.damping={damping!r}",
                        "initial.ball_angles=[" + ", ".join(
                            repr(2 * math.pi * k / N) for k in range(N)) + "]"]
                for prof in space.profiles:
                    if prof not in variants:
                        continue
                    c = _candidate(cfg, N, m, R, ratio, prof, ball, variants,
                                   PLATEAU_RATIO if prof == "tsr" else math.nan)
                    if c is not None:
                        out.append(c)
    return out


def _candidate(cfg, N, m, R, ratio, prof, ball_sets, variants, plateau_ratio) -> dict | None:
    """One candidate design as :func:`candidate_designs` lists it; a TSR plateau is
    ``plateau_ratio`` x the first natural frequency of the machine with the candidate's balls
    (None when that plateau is not below the nominal speed)."""
    if prof == "tsr":
        fn = load(cfg, ball_sets, allow_liquid=True).system.natural_frequencies[0]
        variants = profile_variants(cfg, plateau_ratio, natural_frequency=fn)
        if "tsr" not in variants:
            return None
    sets = list(ball_sets) + list(variants[prof])
    cand = load(cfg, sets, allow_liquid=True)
    tag = prof if prof != "tsr" or plateau_ratio == PLATEAU_RATIO else f"tsr{plateau_ratio:.3g}"
    return {"name": f"{N}x{1e3 * m:.3g}g-R{1e3 * R:.3g}mm-{tag}", "n_balls": N, "ball_mass": m,
            "race_radius": R, "capacity": N * m * R, "capacity_ratio": ratio, "profile": prof,
            "plateau_ratio": plateau_ratio, "duration": float(cand.spin.duration),
            "ball_sets": list(ball_sets), "sets": sets, "config": cand}


def compute_design(base: str | Path | Config, *, grade: float = 16.0, confidence: float = 0.95,
                   unbalance_range: tuple | None = None, n_unbalance: int = 4, starts: int = 20,
                   space: DesignSpace | None = None, quick: bool = False, seed: int = 0,
                   store_dir: str | Path | None = None, executor: str = "local",
                   workers: int | None = None, scheduler: str | None = None,
                   progress: bool = False, refine_plateau: bool = True,
                   tolerances: bool = True) -> xr.Dataset:
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
    n_unbalance : int
        Unbalances studied across the range (>= 1; the ends included).
    starts : int
        Uniform random ball start positions per unbalance and design (>= 1).
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

    Returns
    -------
    xarray.Dataset
        grade_G [mm/s] over (design, unbalance, sample) at the last read-out; per design and
        unbalance the quantile [mm/s]; per design worst_quantile, margin [mm/s], meets, rank,
        pareto and plateau_ratio [-]; attrs with the search's counts (simulations run, those of
        the plateau study), the plateau study's result (plateau_*) and the recommended design's
        tolerances (tolerance_*), and the settings.
    """
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True)     # simulations; beside a liquid too (sec. 3i)
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
    if quick and unbalance_range is not None and n_unbalance == 4:
        n_unbalance = 3
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
    g = [_evaluate(c, Us, starts, **run) for c in cands]
    # the plateau study (004 sec. 4.6) on the best TSR candidate; its recommended plateau joins
    # the search as one more candidate, judged like every other
    refine = {}
    if refine_plateau and any(c["profile"] == "tsr" for c in cands):
        q0 = np.array([np.nanquantile(gi, confidence, axis=1).max() for gi in g])
        k = min((i for i, c in enumerate(cands) if c["profile"] == "tsr"), key=lambda i: q0[i])
        refine = _refine_plateau(cfg, cands[k], Us, starts, quick, **run)
        if refine["candidate"] is not None:
            cands.append(refine["candidate"])
            g.append(_evaluate(refine["candidate"], Us, starts, **run))
    g = np.array(g)
    # grades at the machine's nominal speed and total mass with the candidate's balls
    quant = np.nanquantile(g, confidence, axis=2)                          # (design, U)
    worst = quant.max(axis=1)
    margin = grade - worst
    meets = margin >= 0
    # total ball mass, rounded to 1e-9 relative so that equal designs (2 x 3m/2 = 3 x m) tie
    ball_mass = np.array([c["n_balls"] * c["ball_mass"] for c in cands])
    ball_mass = np.array([float(f"{x:.9e}") for x in ball_mass])
    dur = np.array([c["duration"] for c in cands])
    order = sorted(range(len(cands)), key=lambda k: (not meets[k], ball_mass[k], dur[k], worst[k]))
    rank = np.empty(len(cands), int)
    rank[order] = np.arange(len(cands))
    pareto = np.array([not any((ball_mass[j] <= ball_mass[k]) and (worst[j] <= worst[k])
                               and ((ball_mass[j] < ball_mass[k]) or (worst[j] < worst[k]))
                               for j in range(len(cands))) for k in range(len(cands))])
    G_u = grade_value(Us, M, wn)
    # the tolerances to build the recommended design with (the cheapest that meets the target,
    # else the one closest to it): study tolerances for the same grade (closed form)
    pick = int(order[0]) if meets.any() else int(np.argmin(worst))
    tol, skipped = {}, ""
    if tolerances:
        try:
            tol = _design_tolerances(cands[pick]["config"], grade)
        except ParameterError as e:          # beside a liquid the bound has its limits
            if cfg.system.liquid is None:
                raise
            skipped = f"{TOLERANCES_BESIDE_LIQUID}: {e}"
    ds = xr.Dataset(
        {"grade_G": (("design", "unbalance", "sample"), g, {"units": "mm/s",
                                                            "long_name": "grade at the last read-out"}),
         "quantile": (("design", "unbalance"), quant, {"units": "mm/s",
                                                       "long_name": f"{100 * confidence:g} % quantile over starts"}),
         "worst_quantile": ("design", worst, {"units": "mm/s"}),
         "margin": ("design", margin, {"units": "mm/s", "long_name": "target - worst quantile"}),
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
         "duration": ("design", dur, {"units": "s"})},
        coords={"design": [c["name"] for c in cands],
                "unbalance": ("unbalance", Us, {"units": "kg*m"}),
                "G_ini": ("unbalance", np.atleast_1d(G_u), {"units": "mm/s"})})
    ds.attrs.update({"study": "design", "grade": float(grade), "confidence": float(confidence),
                     "starts": int(starts), "seed": int(seed), "n_designs": len(cands),
                     "simulations": int(g.size), "failed": int(np.isnan(g).sum()),
                     "profiles": "; ".join(f"{k}: {' '.join(v)}" for k, v in variants.items()),
                     "simulations_plateau_study": int(refine.get("simulations", 0)),
                     **{f"plateau_{k}": v for k, v in refine.items()
                        if k not in ("candidate", "simulations")},
                     "tolerances_design": str(cands[pick]["name"]) if tol else "",
                     "tolerances_skipped": skipped,
                     **{f"tolerance_{k}": v for k, v in tol.items()},
                     "wall_s": time.perf_counter() - t0})
    return ds


def _evaluate(c: dict, Us, starts: int, *, seed, store_dir, executor, workers, scheduler,
              progress) -> np.ndarray:
    """Final grades [mm/s] of one candidate, (unbalance, start): uniform random starts (the
    same for every candidate: one seed) at each unbalance; failed runs NaN."""
    # the candidate as a base of its own: its ball count changes the initial angles, which a
    # random Monte Carlo may not take as overrides
    raw = run_start_grid(c["config"], f"design-{c['name']}", (),
                         {"rotor.unbalance": [float(u) for u in Us]}, 0, samples=starts,
                         seed=seed, store=store_path(store_dir, f"design-{c['name']}"),
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
    from .plateau import compute_plateau, plateau_summary
    from .common import starts_for_runs

    b = cand["config"].system.balancer
    n = starts_for_runs(b.n_balls, starts, identical_balls(b))
    ratios = np.array(REFINE_RATIOS[1 if quick else 0])
    G = np.atleast_1d(grade_value(Us, cand["config"].system.total_mass,
                                  cand["config"].spin.nominal_speed))
    ds = compute_plateau(cand["config"], ratios=ratios, G=G, n=n, g_range=float(G.max()),
                         store_dir=store_path(store_dir, f"design-plateau-{cand['name']}"),
                         executor=executor, workers=workers, scheduler=scheduler,
                         prefix="design", progress=progress)
    ps = plateau_summary(ds)
    r = ps["recommended_plateau_ratio"]
    new = None
    if not math.isclose(r, PLATEAU_RATIO, rel_tol=1e-9):
        new = _candidate(cfg, cand["n_balls"], cand["ball_mass"], cand["race_radius"],
                         cand["capacity_ratio"], "tsr", cand["ball_sets"], {}, r)
    return {"candidate": new, "studied": cand["name"], "ratios": ratios,
            "mean_p95_grade_G_mm_s": np.asarray(ps["mean_p95_grade_G_mm_s"], float),
            "recommended_ratio": r, "at_grid_edge": int(ps["at_grid_edge"]),
            "simulations": int(ratios.size * G.size * n_start_grid(n, b.n_balls, identical_balls(b)))}


def _design_tolerances(config, grade: float) -> dict:
    """The tolerances for the target grade of a design (:func:`.tolerances.compute_tolerances`,
    the true bound) as flat SI attrs, with the study's notes (e.g. beside a liquid on a
    horizontal axis, the balanced state's Floquet verdict); feasible = 0 with the study's
    reason (and NaN tolerances) when it refuses, e.g. below the balancing onset."""
    from .tolerances import compute_tolerances

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
        grade_G_mm_s, confidence, simulations (and simulations_plateau_study), designs (name,
        n_balls, ball_mass_kg, total_ball_mass_kg, race_radius_m, capacity_kg_m, profile,
        plateau_ratio, duration_s, sets (the "path=value" overrides that make it from the
        machine), worst_quantile_grade_G_mm_s, margin_grade_G_mm_s, meets, pareto), pareto (names), best (the first design that meets the target, or None),
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
                     "margin_grade_G_mm_s": float(d["margin"]), "meets": bool(d["meets"]),
                     "pareto": bool(d["pareto"]),
                     "quantile_grade_G_mm_s": d["quantile"].values})
    best = next((r for r in rows if r["meets"]), None)
    a = ds.attrs
    out = {"grade_G_mm_s": a["grade"], "confidence": a["confidence"],
           "unbalance_kg_m": ds["unbalance"].values, "G_ini_mm_s": ds["G_ini"].values,
           "starts": a["starts"], "simulations": a["simulations"],
           "simulations_plateau_study": a.get("simulations_plateau_study", 0),
           "failed": a["failed"], "n_designs": ds.sizes["design"],
           "n_meeting": int(ds["meets"].sum()), "best": best,
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
