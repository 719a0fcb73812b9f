"""Residual grade against the initial unbalance, for any machine (004 sec. 4.3-4.5 generalised):
percentiles over start positions at each read-out, per (friction, damping) case, and the same
against a second speed profile (004 Fig. 9)."""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from ..confidence import LEVEL, quantile_interval
from ..physics.iso1940 import unbalance_value as grade_to_unbalance
from .common import (capacity_grades, case_sets, checkpoint_labels, load, run_start_grid,
                     store_path)
from .sequential import SEED_STEP, budget_attrs, default_budget, refine
from .statistics import profile_text, valid_ranges

if TYPE_CHECKING:
    from collections.abc import Iterable
    from pathlib import Path

    import numpy.typing as npt
    import xarray as xr

__all__ = ["compute_profile", "compute_unbalance", "default_grades", "operating_boundaries",
           "unbalance_summary"]


def default_grades(G_balls: float, quick: bool, g_max: float | None = None,
                   steps: int | None = None) -> np.ndarray:
    """Initial grades [mm/s] of the unbalance study of a machine whose balancer makes the grade
    G_balls [mm/s]: [0, 1.5 G_balls] in 25 steps (quick: 10), which covers the balls' whole
    operating range (under- and over-excited balancer, 004 sec. 4.3: [G0, G50] for G34 balls).

    Parameters
    ----------
    G_balls : float
        ISO 1940 grade of the balancer's capacity at the nominal speed [mm/s]: the balls' sum
        m R, plus a liquid's rho V R (:func:`autobalance.studies.common.capacity_grades`).
    quick : bool
        10 steps instead of 25.
    g_max : float or None
        The grid's largest grade [mm/s] (None: 1.5 G_balls).
    steps : int or None
        Intervals of the grid (None: 25, 10 when ``quick``).

    Returns
    -------
    ndarray
        G_ini [mm/s].
    """
    top = 1.5 * G_balls if g_max is None else float(g_max)
    return np.linspace(0.0, top, (steps or (10 if quick else 25)) + 1)


def compute_unbalance(base: str | Path, cases: dict[str, tuple[float, float]] | None = None, *,
                      G: npt.ArrayLike | None = None, n: int = 50, quick: bool = False,
                      store_dir: str | Path | None = None, executor: str = "local",
                      workers: int | None = None, scheduler: str | None = None,
                      prefix: str = "study", grade: float = 16.0, budget: int | None = None,
                      seed: int = 0, progress: bool = False) -> xr.Dataset:
    """004 sec. 4.3-4.5: G_ini over [G0, G50] x the start grid for each (mu_r, c_r) case;
    5/50/95 % of G_STD (18 s) and G_TSR (90 s), valid ranges for G16 and efficiencies.

    ``cases``: name -> (mu_r, c_r), the factors on the machine's rolling resistance and damping
    (None: {"nominal": (1, 1)}); ``G``: the initial grades [mm/s] (None: :func:`default_grades`).

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls; a liquid beside them or alone: one run per grade without balls).
    cases : dict of str to (float, float) or None
        Case name -> (mu_r, c_r), factors [-] on the rolling resistance and the damping.
    G : array_like or None
        Initial grades [mm/s]; None = :func:`default_grades`.
    n : int
        Start positions per ball (004: 50).
    quick : bool
        The coarse :func:`default_grades`.
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the sweeps run: ``store_dir`` holds one resumable store per sweep (a rerun
        of the same description computes nothing; None = temporary stores); ``executor``,
        ``workers`` and ``scheduler`` as for :func:`autobalance.studies.common.run_start_grid`.
    prefix : str
        Prefix of the sweeps' names.
    grade : float
        The target grade [mm/s] the valid ranges are decided for (004: G16): where the 95th
        percentile of a read-out is undecided against it, the sequential step
        (:func:`autobalance.studies.sequential.refine`) adds random starts.
    budget : int or None
        Most runs [-] the sequential step adds; None = as many as the start grid ran
        (:data:`autobalance.studies.sequential.BUDGET_FACTOR`), 0 = the start grid alone
        (004's protocol).
    seed : int
        Seed of the added random starts.
    progress : bool
        Show each sweep's progress bar on stderr.

    Returns
    -------
    xarray.Dataset
        grade_G [mm/s] over (case, G_ini [mm/s], procedure = the profile's read-outs
        (:func:`~autobalance.studies.common.checkpoint_labels`; 004: STD/TSR),
        percentile 5/50/95) with its interval grade_G_ci, runs_ok (the runs each G_ini
        counts, start grid and added starts), failed_runs per case, the operating boundaries
        [mm/s] (:func:`operating_boundaries`; NaN beside a liquid, whose moment they leave
        out); attrs G_balls and G_liquid (:func:`.common.capacity_grades`) [mm/s], grid_step
        [mm/s], grade [mm/s], budget, budget_spent, budget_rounds, budget_exhausted,
        budget_capped.
    """
    cases = {"nominal": (1.0, 1.0)} if cases is None else dict(cases)
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True, liquid_alone=True)    # simulations: a liquid is modelled
    G_b, G_l = capacity_grades(cfg)
    Gv = default_grades(G_b + G_l, quick) if G is None else np.asarray(G, float)
    U = grade_to_unbalance(Gv, cfg.system.total_mass, cfg.spin.nominal_speed)
    q = np.array([5.0, 50.0, 95.0])
    labels = checkpoint_labels(cfg.spin)
    cells, sets = {}, {}
    for ci, case in enumerate(cases):
        mu_r, c_r = cases[case]
        sets[ci] = case_sets(cfg, mu_r, c_r)
        raw = run_start_grid(base, f"{prefix}-unb-{case}-n{n}-g{Gv.size}", sets[ci],
                             {"rotor.unbalance": [float(u) for u in U]}, n,
                             store=store_path(store_dir, f"unbalance-{case}-n{n}-g{Gv.size}"),
                             executor=executor, workers=workers, scheduler=scheduler,
                             progress=progress)
        cells.update(_grades(raw, ci, range(Gv.size)))
    first = sum(len(a) for a in cells.values())
    budget = (0 if cfg.system.balancer.n_balls == 0         # a liquid alone: one run
              else default_budget(budget, first))

    def run_more(keys, k, rnd):
        out = {}
        for ci, case in enumerate(cases):
            js = sorted({j for c, j in keys if c == ci})
            if js:
                raw = run_start_grid(base, f"{prefix}-unb-{case}-more{rnd}", sets[ci],
                                     {"rotor.unbalance": [float(U[j]) for j in js]}, 0,
                                     samples=k, seed=seed + SEED_STEP * rnd,
                                     store=store_path(store_dir, f"unbalance-{case}-n{n}-more{rnd}"),
                                     executor=executor, workers=workers, scheduler=scheduler,
                                     progress=progress)
                out.update(_grades(raw, ci, js))
        return [out[key] for key in keys]

    ref = refine(cells, lambda c: _undecided(c, grade), budget, run_more)
    data = np.full((len(cases), Gv.size, len(labels), q.size), np.nan)
    data_ci = np.full(data.shape + (2,), np.nan)
    runs_ok = np.zeros((len(cases), Gv.size), int)
    failed = np.zeros(len(cases), int)
    for (ci, j), a in cells.items():
        for m, qq in enumerate(q):
            est, lo, hi = quantile_interval(a, qq / 100.0, axis=0)
            data[ci, j, :, m], data_ci[ci, j, :, m, 0], data_ci[ci, j, :, m, 1] = est, lo, hi
        ok = np.isfinite(a).all(axis=1)
        runs_ok[ci, j] += int(ok.sum())
        failed[ci] += int((~ok).sum())
    ds = xr.Dataset({"grade_G": (("case", "G_ini", "procedure", "percentile"), data,
                                 {"units": "mm/s", "long_name": "residual grade percentile"}),
                     "grade_G_ci": (("case", "G_ini", "procedure", "percentile", "bound"),
                                    data_ci, {"units": "mm/s", "confidence_level": LEVEL,
                                              "long_name": "interval of the percentile (order "
                                                           "statistics; +-inf: unbounded)"}),
                     "runs_ok": (("case", "G_ini"), runs_ok,
                                 {"units": "1", "long_name": "runs the percentiles count"}),
                     "failed_runs": ("case", failed)},
                    coords={"case": list(cases), "G_ini": ("G_ini", Gv, {"units": "mm/s"}),
                            "procedure": labels, "percentile": q, "bound": ["lo", "hi"],
                            "mu_r": ("case", [cases[c][0] for c in cases]),
                            "c_r": ("case", [cases[c][1] for c in cases])})
    lo, hi = operating_boundaries(Gv, G_b)
    if cfg.system.liquid is not None:           # the boundaries are the balls' alone
        lo, hi = np.full_like(lo, np.nan), np.full_like(hi, np.nan)
    ds["lower_boundary"] = ("G_ini", lo, {"units": "mm/s", "long_name": "every ball opposite "
                                          "the unbalance: |G_ini - G_balls|"})
    ds["upper_boundary"] = ("G_ini", hi, {"units": "mm/s", "long_name": "every ball with the "
                                          "unbalance: G_ini + G_balls"})
    ds.attrs.update({"study": "unbalance", "n": n, "G_balls": G_b, "G_liquid": G_l,
                     "grid_step": float(np.diff(Gv).max()) if Gv.size > 1 else 0.0,
                     "grade": float(grade), **budget_attrs(first, budget, ref, seed),
                     "wall_s": time.perf_counter() - t0, "profile": profile_text(cfg.spin)})
    return ds


def _grades(raw: xr.Dataset, case: int, js) -> dict:
    """(case, G_ini index) -> the final grades [mm/s] (sample, read-out) of a sweep over the
    initial unbalances ``js`` (in its order); failed runs NaN."""
    g = raw["grade_G"].where(raw["status"] == 0).transpose("rotor__unbalance", "sample",
                                                           "checkpoint").values
    return {(case, j): g[a] for a, j in enumerate(js)}


def _undecided(cells: dict, grade: float) -> list:
    """The cells whose 95th percentile is undecided against ``grade`` [mm/s] at some read-out
    (:func:`autobalance.confidence.verdict` of its interval)."""
    from ..confidence import verdict

    out = []
    for key, a in cells.items():
        _, lo, hi = quantile_interval(a, 0.95, axis=0)
        if any(verdict(x, y, grade) == "undecided" for x, y in zip(lo, hi)):
            out.append(key)
    return out


def compute_profile(base: str | Path, other_sets: Iterable[str], *,
                    G: npt.ArrayLike | None = None, n: int = 50, quick: bool = False,
                    store_dir: str | Path | None = None, executor: str = "local",
                    workers: int | None = None, scheduler: str | None = None,
                    unbalance_ds: xr.Dataset | None = None, prefix: str = "study",
                    other_text: str = "") -> xr.Dataset:
    """004 sec. 4.4, Fig. 9: 95 % isolines of the STD (18 s), TSR (90 s) and a 3x slower run-up
    (0 -> 167 Hz in 54 s, hold to 90 s, read at 90 s) against G_ini (nominal mu, c).

    ``other_sets``: the overrides that make the other profile ("slow"), e.g. 004's
    ``SLOW_SETS``; ``other_text``: its description for the attrs.

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    other_sets : iterable of str
        "path=value" overrides that make the other profile.
    G : array_like or None
        Initial grades [mm/s]; None = :func:`default_grades`.
    n : int
        Start positions per ball.
    quick : bool
        The coarse :func:`default_grades`.
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the sweeps run: ``store_dir`` holds one resumable store per sweep (a rerun
        of the same description computes nothing; None = temporary stores); ``executor``,
        ``workers`` and ``scheduler`` as for :func:`autobalance.studies.common.run_start_grid`.
    unbalance_ds : xarray.Dataset or None
        A :func:`compute_unbalance` result to reuse for STD and TSR when it has the same grades,
        ``n`` and a "nominal" case; otherwise it is computed.
    prefix : str
        Prefix of the sweeps' names.
    other_text : str
        Description of the other profile for the attrs (default: ``other_sets`` joined).

    Returns
    -------
    xarray.Dataset
        grade_G [mm/s] over (G_ini [mm/s], procedure STD/TSR/slow, percentile 5/50/95).
    """
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True, liquid_alone=True)    # simulations: a liquid is modelled
    G_b, G_l = capacity_grades(cfg)
    Gv = default_grades(G_b + G_l, quick) if G is None else np.asarray(G, float)
    if unbalance_ds is None or not np.array_equal(unbalance_ds["G_ini"].values, Gv) \
            or "nominal" not in unbalance_ds["case"].values or unbalance_ds.attrs["n"] != n:
        unbalance_ds = compute_unbalance(base, {"nominal": (1.0, 1.0)}, G=Gv, n=n,
                                         store_dir=store_dir, executor=executor, workers=workers,
                                         scheduler=scheduler, prefix=prefix, budget=0)
    U = grade_to_unbalance(Gv, cfg.system.total_mass, cfg.spin.nominal_speed)
    raw = run_start_grid(base, f"{prefix}-slow-n{n}-g{Gv.size}", list(other_sets),
                         {"rotor.unbalance": [float(u) for u in U]}, n,
                         store=store_path(store_dir, f"slow-n{n}-g{Gv.size}"), executor=executor,
                         workers=workers, scheduler=scheduler)
    g = raw["grade_G"].where(raw["status"] == 0).isel(checkpoint=-1)
    q = np.array([5.0, 50.0, 95.0])
    slow = g.quantile(q / 100, dim="sample").transpose("rotor__unbalance", "quantile").values
    base = unbalance_ds["grade_G"].sel(case="nominal").values        # (G, procedure, q)
    data = np.concatenate([base, slow[:, None, :]], axis=1)
    ds = xr.Dataset({"grade_G": (("G_ini", "procedure", "percentile"), data, {"units": "mm/s"})},
                    coords={"G_ini": ("G_ini", Gv, {"units": "mm/s"}),
                            "procedure": [*checkpoint_labels(cfg.spin), "slow"], "percentile": q})
    ds.attrs.update({"study": "profile", "n": n, "wall_s": time.perf_counter() - t0,
                     "profile": profile_text(cfg.spin),
                     "slow_profile": other_text or "; ".join(other_sets)})
    return ds


def operating_boundaries(G_ini: npt.ArrayLike,
                         G_balls: float) -> tuple[np.ndarray, np.ndarray]:
    """The residual grades between which a ball balancer operates (004 sec. 4.3, Fig. 7's dashed
    lines): every ball opposite the unbalance, |G_ini - G_balls|, and every ball with it,
    G_ini + G_balls [mm/s] (ISO 1940 grades are linear in the unbalance).

    Parameters
    ----------
    G_ini : array_like
        Initial grades of the rotor [mm/s].
    G_balls : float
        Grade of the balls' capacity sum m_i R [mm/s].

    Returns
    -------
    lower, upper : ndarray
        [mm/s].
    """
    g = np.asarray(G_ini, float)
    return np.abs(g - G_balls), g + G_balls


def unbalance_summary(ds: xr.Dataset, grade: float = 16.0) -> dict:
    """The valid initial-unbalance ranges and efficiency of each case and read-out (004 sec. 4.3:
    where the 95th percentile is <= ``grade``; efficiency = their length over the studied
    span of G_ini) of a :func:`compute_unbalance` result, JSON-ready.

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_unbalance` result.
    grade : float
        Target grade [mm/s].

    Returns
    -------
    dict
        grade_G_mm_s, G_balls_mm_s, G_ini_mm_s, confidence_level and, per case -> read-out:
        valid_ranges_grade_G_mm_s (list of [lo, hi], from the 95th percentiles), efficiency
        [-], p5/p50/p95 curves [mm/s] with their intervals (``..._ci``, per G_ini [lo, hi];
        null where the runs cannot bound it), p95_verdicts (per G_ini: meets, fails or
        undecided for p95 <= grade), and the ranges the intervals allow: sure_valid_ranges
        (where the interval's upper end is <= grade: valid at the confidence level),
        possible_valid_ranges (where its lower end is; outside them the grade is missed at
        that level), efficiency_ci [lo, hi] from the two. A boundary of a valid range lies
        between the sure and the possible range's.
    """
    Gv = ds["G_ini"].values
    span = float(Gv.max() - Gv.min()) or 1.0
    out = {"grade_G_mm_s": float(grade), "G_balls_mm_s": float(ds.attrs["G_balls"]),
           "G_ini_mm_s": Gv, "lower_boundary_grade_G_mm_s": ds["lower_boundary"].values,
           "upper_boundary_grade_G_mm_s": ds["upper_boundary"].values,
           "confidence_level": float(ds["grade_G_ci"].attrs.get("confidence_level", LEVEL))
           if "grade_G_ci" in ds else None, "cases": {}}
    for case in ds["case"].values:
        per = {}
        for proc in ds["procedure"].values:
            g = ds["grade_G"].sel(case=case, procedure=proc)
            rng, eff = valid_ranges(Gv, g.sel(percentile=95.0).values, grade, span)
            row = {"valid_ranges_grade_G_mm_s": [list(r) for r in rng], "efficiency": eff,
                   **{f"p{int(q)}_grade_G_mm_s": g.sel(percentile=q).values
                      for q in (5.0, 50.0, 95.0)}}
            if "grade_G_ci" in ds:
                row.update(_valid_range_intervals(ds["grade_G_ci"].sel(case=case, procedure=proc),
                                                  Gv, grade, span))
            per[str(proc)] = row
        out["cases"][str(case)] = per
    return out


def _runs(x: np.ndarray, ok: np.ndarray, widen: bool) -> list:
    """[lo, hi] of each maximal run of grid points with ``ok``; ``widen``: each run extended to
    the grid points beside it (where a boundary may lie)."""
    out, k = [], 0
    while k < ok.size:
        if not ok[k]:
            k += 1
            continue
        j = k
        while j + 1 < ok.size and ok[j + 1]:
            j += 1
        a, b = (max(k - 1, 0), min(j + 1, ok.size - 1)) if widen else (k, j)
        out.append([float(x[a]), float(x[b])])
        k = j + 1
    return out


def _valid_range_intervals(ci: xr.DataArray, Gv: np.ndarray, grade: float, span: float) -> dict:
    """The percentiles' intervals of one case and read-out (``ci``: G_ini, percentile, bound),
    the verdict of p95 <= ``grade`` at each initial grade, and the valid ranges they allow
    (:func:`unbalance_summary`): surely valid, the runs of grid points decided "meets";
    possibly valid, the runs not decided "fails" widened to the grid points beside them (a
    boundary lies between a point that meets and one that fails)."""
    from ..confidence import verdict

    lo95 = ci.sel(percentile=95.0, bound="lo").values
    hi95 = ci.sel(percentile=95.0, bound="hi").values
    verdicts = [verdict(a, b, grade) for a, b in zip(lo95, hi95)]
    sure = _runs(Gv, np.array([v == "meets" for v in verdicts]), widen=False)
    possible = _runs(Gv, np.array([v != "fails" for v in verdicts]), widen=True)
    length = lambda rs: sum(b - a for a, b in rs) / span                     # noqa: E731
    return {**{f"p{int(q)}_grade_G_mm_s_ci": ci.sel(percentile=q).values
               for q in (5.0, 50.0, 95.0)},
            "p95_verdicts": verdicts,
            "sure_valid_ranges_grade_G_mm_s": sure,
            "possible_valid_ranges_grade_G_mm_s": possible,
            "efficiency_ci": [length(sure), length(possible)]}
