"""The lower speed of a temporary speed reduction, for any machine (004 sec. 4.6 generalised):
the plateau map (plateau speed x initial unbalance -> 95th percentile of the final grade, the
ideal plateau) and a gradual descent read along the speed (004 Fig. 13)."""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from ..confidence import LEVEL, quantile_interval
from ..physics.immobility import stick_threshold_grade
from ..physics.iso1940 import grade_value as _grade
from ..physics.iso1940 import unbalance_value as grade_to_unbalance
from .common import case_sets, load, run_start_grid, starts_for_runs, store_path
from .sequential import SEED_STEP, budget_attrs, default_budget, refine
from .statistics import half_drop, plateau_speed, profile_text, rise_after_min

if TYPE_CHECKING:
    from pathlib import Path

    import numpy.typing as npt
    import xarray as xr

    from ..models import BallBalancer

__all__ = ["DESCENT_PCT", "PLATEAU_RUNS", "compute_descent", "compute_plateau",
           "default_grid", "default_plateau_starts", "plateau_summary", "refine_plateaus"]

#: Most start configurations per cell of the plateau map (full, quick): 004 Fig. 14-15's
#: n = 20 positions for two balls (210 runs), 36 (n = 8) for a first look.
PLATEAU_RUNS = (210, 36)


def default_plateau_starts(balancer: BallBalancer, quick: bool) -> int:
    """Start positions per ball of the plateau map: the most whose grid stays within
    :data:`PLATEAU_RUNS` per cell (n = 20 / 8 for two balls, 9 / 5 for three), so that a map of
    153 cells costs about the same for any ball count.

    Parameters
    ----------
    balancer : autobalance.models.Balancer
        The balls (their number, and whether they are identical).
    quick : bool
        The coarse map.

    Returns
    -------
    int
        Positions per ball n (>= 1).
    """
    from ..sweep.plan import identical_balls

    return starts_for_runs(balancer.n_balls, PLATEAU_RUNS[1 if quick else 0],
                           identical_balls(balancer))


def default_grid(G_balls: float, quick: bool):
    """(plateau / Omega_n ratios [-], initial grades [mm/s]) of the plateau map of a machine whose
    balls make the grade G_balls [mm/s]: ratios 0.96-1.12 every 0.01 (004 Fig. 14-15's range
    around the first natural frequency) x G_ini in [0, G_balls] (9 values; 004: [G0, G32] for
    G34 balls, the under-excited range TSR serves); quick: 4 ratios x 3 grades.

    Parameters
    ----------
    G_balls : float
        ISO 1940 grade of the balls' capacity at the nominal speed [mm/s].
    quick : bool
        The coarse map.

    Returns
    -------
    ratios : ndarray
        Plateau speed / Omega_n [-].
    grades : ndarray
        Initial grades G_ini [mm/s].
    """
    if quick:
        return np.array([0.98, 1.02, 1.06, 1.10]), np.array([0.15, 0.45, 0.75]) * G_balls
    return np.round(np.arange(0.96, 1.1201, 0.01), 3), np.linspace(0.0, G_balls, 9)


DESCENT_PCT = (5.0, 25.0, 50.0, 75.0, 95.0)


def _require_tsr(spin, what: str) -> None:
    """Refuse, in one line, a profile that is not a temporary speed reduction: ``what`` (the
    plateau study, the descent) varies its lower plateau. A motor drive's speed follows its
    torque law (000 eq 15-18) and has no plateau to vary."""
    kind = getattr(spin, "name", type(spin).__name__)
    if kind == "tsr":
        return
    from ..models import ParameterError

    why = ("a motor drive's speed follows its torque law, with no plateau to vary; "
           if kind == "motor" else "")
    raise ParameterError("profile.kind", kind, f"{what} needs a temporary speed reduction: "
                         f"{why}use a tsr profile (e.g. --profile tsr)")



def compute_plateau(base: str | Path, cases: dict[str, tuple[float, float]] | None = None, *,
                    ratios: npt.ArrayLike | None = None, G: npt.ArrayLike | None = None,
                    n: int | None = None, quick: bool = False,
                    store_dir: str | Path | None = None, executor: str = "local",
                    workers: int | None = None, scheduler: str | None = None,
                    g_range: float | None = None, prefix: str = "study",
                    budget: int | None = None, seed: int = 0,
                    progress: bool = False) -> xr.Dataset:
    """004 sec. 4.6, Fig. 14-15: the lower TSR plateau (as Omega/Omega_n) x G_ini in [G0, G34] ->
    95th percentile of G_TSR (90 s); ideal plateau = argmin of its mean over G_ini <= ``g_range``
    [mm/s] (004: G34). ``cases``: name -> (mu_r, c_r) factors (None: {"nominal": (1, 1)}).

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    cases : dict of str to (float, float) or None
        Case name -> (mu_r, c_r), factors [-] on the rolling resistance and the damping.
    ratios : array_like or None
        Plateau speeds as multiples of Omega_n [-]; None = :func:`default_grid`.
    G : array_like or None
        Initial grades [mm/s]; None = :func:`default_grid`.
    n : int or None
        Start positions per ball; None = :func:`default_plateau_starts`.
    quick : bool
        The coarse :func:`default_grid` (and start grid).
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the sweeps run: ``store_dir`` holds one resumable store per sweep (a rerun
        of the same description computes nothing; None = temporary stores); ``executor``,
        ``workers`` and ``scheduler`` as for :func:`autobalance.studies.common.run_start_grid`.
    g_range : float or None
        Largest G_ini of the mean that picks the ideal plateau [mm/s] (004: G34); None = the
        balls' grade G_balls.
    prefix : str
        Prefix of the sweeps' names.
    budget : int or None
        Most runs [-] the sequential step adds (:func:`refine_plateaus`) where the recommended
        plateau is not distinguishable from others; None = as many as the start grid ran
        (:data:`autobalance.studies.sequential.BUDGET_FACTOR`), 0 = the start grid alone
        (004's protocol).
    seed : int
        Seed of the added random starts.
    progress : bool
        Show each sweep's progress bar on stderr.

    Returns
    -------
    xarray.Dataset
        grade_G_p95 [mm/s] over (case, plateau_ratio [-], G_ini [mm/s]) with its interval
        grade_G_p95_ci, the starts of each cell, the mean over G_ini mean_p95 [mm/s] with
        mean_p95_ci; attrs: ideal ratio per case [-], f_n_hz [Hz], budget, budget_spent,
        budget_rounds, budget_exhausted, budget_capped.
    """
    cases = {"nominal": (1.0, 1.0)} if cases is None else dict(cases)
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True)        # simulations only: a liquid beside is modelled
    s = cfg.system
    _require_tsr(cfg.spin, "the plateau study")
    fn = s.natural_frequencies[0]
    n = default_plateau_starts(s.balancer, quick) if n is None else n
    G_b = float(_grade(s.balancer.capacity, s.total_mass, cfg.spin.nominal_speed))
    g_range = G_b if g_range is None else g_range
    r0, g0 = default_grid(G_b, quick)
    ratios = r0 if ratios is None else np.asarray(ratios, float)
    Gv = g0 if G is None else np.asarray(G, float)
    U = grade_to_unbalance(Gv, s.total_mass, cfg.spin.nominal_speed)
    inside = Gv <= g_range
    cells, sets = {}, {}
    for ci, case in enumerate(cases):
        mu_r, c_r = cases[case]
        sets[ci] = case_sets(cfg, mu_r, c_r)
        raw = run_start_grid(base, f"{prefix}-plateau-{case}-n{n}", sets[ci],
                             {"profile.plateau": [float(r * fn) for r in ratios],
                              "rotor.unbalance": [float(u) for u in U]}, n,
                             store=store_path(store_dir, f"plateau-{case}-n{n}-r{ratios.size}-g{Gv.size}"),
                             executor=executor, workers=workers, scheduler=scheduler,
                             progress=progress)
        cells.update(_final_grades(raw, ci, range(ratios.size), range(Gv.size)))
    first = sum(a.size for a in cells.values())
    budget = default_budget(budget, first)

    def run_more(keys, k, rnd):
        out = {}
        for ci, case in enumerate(cases):
            mine = [key for key in keys if key[0] == ci]
            if not mine:
                continue
            ri = sorted({key[1] for key in mine})
            gj = sorted({key[2] for key in mine})
            raw = run_start_grid(base, f"{prefix}-plateau-{case}-more{rnd}", sets[ci],
                                 {"profile.plateau": [float(ratios[i] * fn) for i in ri],
                                  "rotor.unbalance": [float(U[j]) for j in gj]}, 0,
                                 samples=k, seed=seed + SEED_STEP * rnd,
                                 store=store_path(store_dir, f"plateau-{case}-n{n}-more{rnd}"),
                                 executor=executor, workers=workers, scheduler=scheduler,
                                 progress=progress)
            out.update(_final_grades(raw, ci, ri, gj))
        return [out[key] for key in keys]

    ref = refine(cells, lambda c: refine_plateaus(c, len(cases), ratios.size, inside), budget,
                 run_more)
    est, lo, hi, starts = _cell_quantiles(cells, (len(cases), ratios.size, Gv.size))
    ds = xr.Dataset({"grade_G_p95": (("case", "plateau_ratio", "G_ini"), est, {"units": "mm/s"}),
                     "grade_G_p95_ci": (("case", "plateau_ratio", "G_ini", "bound"),
                                        np.stack([lo, hi], -1),
                                        {"units": "mm/s", "confidence_level": LEVEL,
                                         "long_name": "interval of the 95th percentile (order "
                                                      "statistics; inf: unbounded)"}),
                     "starts": (("case", "plateau_ratio", "G_ini"), starts,
                                {"units": "1", "long_name": "runs of the cell (start grid and "
                                                            "added random starts)"})},
                    coords={"case": list(cases), "plateau_ratio": ratios,
                            "G_ini": ("G_ini", Gv, {"units": "mm/s"}), "bound": ["lo", "hi"]})
    mean, mean_ci = _mean_over_range(est, lo, hi, inside)
    ds["mean_p95"] = (("case", "plateau_ratio"), mean, {"units": "mm/s"})
    ds["mean_p95_ci"] = (("case", "plateau_ratio", "bound"), mean_ci,
                         {"units": "mm/s", "confidence_level": LEVEL})
    ds.attrs.update({"study": "plateau", "n": n, "f_n_hz": fn / (2 * np.pi), "G_balls": G_b,
                     "g_range": float(g_range),
                     "ideal": [float(ratios[np.nanargmin(m)]) for m in mean],
                     "ratio_step": float(np.diff(ratios).min()) if ratios.size > 1 else 0.0,
                     **budget_attrs(first, budget, ref, seed),
                     "wall_s": time.perf_counter() - t0, "profile": profile_text(cfg.spin)})
    return ds


def _final_grades(raw: xr.Dataset, case: int, ri, gj) -> dict:
    """(case, ratio index, G_ini index) -> the final grades [mm/s] of a plateau sweep over the
    ratios ``ri`` and initial grades ``gj`` (indices, in the sweep's order); failed runs NaN."""
    g = raw["grade_G"].where(raw["status"] == 0).isel(checkpoint=-1).transpose(
        "profile__plateau", "rotor__unbalance", "sample").values
    return {(case, i, j): g[a, b] for a, i in enumerate(ri) for b, j in enumerate(gj)}


def _cell_quantiles(cells: dict, shape: tuple) -> tuple:
    """The 95th percentile [mm/s] of every cell with its interval (order statistics) and the
    runs it holds, as arrays of ``shape`` (the cells' keys are indices into it)."""
    est, lo, hi = (np.full(shape, np.nan) for _ in range(3))
    starts = np.zeros(shape, int)
    for key, a in cells.items():
        est[key], lo[key], hi[key] = (float(x) for x in quantile_interval(a, 0.95))
        starts[key] = a.size
    return est, lo, hi, starts


def _mean_over_range(est, lo, hi, inside) -> tuple:
    """The mean over the initial grades ``inside`` the range of the 95th percentiles (case,
    ratio, G_ini) and its interval: the mean of the bounds bounds the mean (each at the
    confidence level; an unbounded one leaves the mean unbounded)."""
    mean = np.nanmean(np.where(inside, est, np.nan), axis=2)
    ci = np.stack([np.mean(b[:, :, inside], axis=2) for b in (lo, hi)], -1)
    return mean, ci


def refine_plateaus(cells: dict, n_cases: int, n_ratios: int, inside: np.ndarray) -> list:
    """The cells that leave a plateau study's recommendation undecided: per case, where more
    than one plateau is not distinguishable from the best (their mean 95th percentile's
    interval reaches below the best's upper end), every cell of those plateaus within the
    range of initial grades the mean is taken over.

    Parameters
    ----------
    cells : dict
        (case, ratio, G_ini) index -> final grades [mm/s].
    n_cases, n_ratios : int
        The map's sizes.
    inside : ndarray of bool
        The initial grades the mean runs over [-].
    """
    n_g = inside.size
    est, lo, hi, _ = _cell_quantiles(cells, (n_cases, n_ratios, n_g))
    mean, ci = _mean_over_range(est, lo, hi, inside)
    todo = []
    for c in range(n_cases):
        if not np.isfinite(mean[c]).any():
            continue
        same = _not_distinguishable(ci[c], int(np.nanargmin(mean[c])))
        if len(same) > 1:
            todo += [(c, i, j) for i in same for j in range(n_g) if inside[j]]
    return todo


def compute_descent(base: str | Path, *, G_ini: float = 5.0, n: int = 50, ratio_end: float = 0.9,
                    down_time: float = 60.0, history_dt: float = 0.25,
                    store_dir: str | Path | None = None, executor: str = "local",
                    workers: int | None = None, scheduler: str | None = None,
                    prefix: str = "study") -> xr.Dataset:
    """004 sec. 4.6, Fig. 13: after the standard run-up (18 s to 167 Hz), a slow linear descent
    to ``ratio_end`` Omega_n in ``down_time`` [s]; the residual grade G [mm/s] of every start is
    read every ``history_dt`` [s] and its percentiles over the n(n+1)/2 starts are returned
    against the speed ratio Omega/Omega_n [-]. Also the stick threshold G*(Omega)
    (:func:`stick_threshold_grade`; NaN beside a liquid, which it leaves out) at the same speeds.

    004 does not give its descent rate ("a gradual speed reduction"); ours is 82 Hz in 60 s
    (1.4 Hz/s), a fifth of the TSR profile's 6.7 Hz/s.

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    G_ini : float
        Initial grade [mm/s] (sets the rotor's unbalance).
    n : int
        Start positions per ball.
    ratio_end : float
        End of the descent as a multiple of Omega_n [-].
    down_time : float
        Length of the descent [s].
    history_dt : float
        Spacing of the grade read-outs [s].
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the sweeps run: ``store_dir`` holds one resumable store per sweep (a rerun
        of the same description computes nothing; None = temporary stores); ``executor``,
        ``workers`` and ``scheduler`` as for :func:`autobalance.studies.common.run_start_grid`.
    prefix : str
        Prefix of the sweeps' names.

    Returns
    -------
    xarray.Dataset
        grade_G percentiles (:data:`DESCENT_PCT`) [mm/s] and G_stick [mm/s] against the speed
        ratio [-], with the read-out time [s]; attrs: :func:`half_drop` and
        :func:`rise_after_min` read-outs.
    """
    import xarray as xr

    t0 = time.perf_counter()
    machine = load(base, allow_liquid=True)    # simulations (G_stick: balls alone, below)
    _require_tsr(machine.spin, "the descent")
    s0 = machine.system
    fn = s0.natural_frequencies[0]
    U = float(grade_to_unbalance(G_ini, s0.total_mass, machine.spin.nominal_speed))
    sets = [f"rotor.unbalance={U!r}", f"profile.plateau={ratio_end * fn!r}",
            f"profile.down_time={down_time!r}", "profile.plateau_time=1.0", "profile.up_time=1.0"]
    cfg = load(base, sets, allow_liquid=True)
    name = f"descent-g{G_ini:g}-n{n}-r{ratio_end:g}-t{down_time:g}-dt{history_dt:g}"
    raw = run_start_grid(base, f"{prefix}-{name}", sets, {}, n, store=store_path(store_dir, name),
                         executor=executor, workers=workers, scheduler=scheduler,
                         history_dt=history_dt)
    t = raw["history_time"].values
    t_read = cfg.spin.checkpoints[0]
    sel = (t >= t_read) & (t <= t_read + down_time + 1e-9)
    speed = np.interp(t[sel], cfg.spin.times, cfg.spin.speeds)
    ok = raw["status"].values == 0
    g = raw["grade_G_history"].values[ok][:, sel]                       # (run, time)
    pct = np.percentile(g, DESCENT_PCT, axis=0)
    ratio = speed / fn
    ds = xr.Dataset({"grade_G": (("percentile", "ratio"), pct, {"units": "mm/s"}),
                     "G_stick": ("ratio", _stick(cfg.system, speed, cfg.spin.nominal_speed),
                                 {"units": "mm/s", "long_name": "stick threshold G*"}),
                     "time": ("ratio", t[sel], {"units": "s"})},
                    coords={"percentile": list(DESCENT_PCT),
                            "ratio": ("ratio", ratio, {"long_name": "Omega / Omega_n"})})
    med, p95 = pct[DESCENT_PCT.index(50.0)], pct[DESCENT_PCT.index(95.0)]
    ds.attrs.update({
        "study": "descent", "n": n, "runs": int(ok.size), "failed": int((~ok).sum()),
        "G_ini": G_ini, "G_balls": float(_grade(cfg.system.balancer.capacity, cfg.system.total_mass,
                                                cfg.spin.nominal_speed)),
        "f_n_hz": fn / (2 * np.pi), "standard_ratio": plateau_speed(machine.spin) / fn,
        "down_time_s": down_time, "ratio_end": ratio_end,
        "half_drop_median": half_drop(ratio, med), "half_drop_p95": half_drop(ratio, p95),
        **rise_after_min(ratio, p95),
        "wall_s": time.perf_counter() - t0, "profile": profile_text(cfg.spin)})
    return ds


def _stick(system, speed, nominal_speed):
    """:func:`stick_threshold_grade` [mm/s] at ``speed`` [rad/s] (grade at ``nominal_speed``
    [rad/s]); NaN beside a liquid, whose moment the closed form (a Jeffcott rotor with balls
    alone) does not hold."""
    if system.liquid is not None:
        return np.full(np.shape(speed), np.nan)
    return stick_threshold_grade(system, speed, nominal_speed)


def plateau_summary(ds: xr.Dataset, case: str | None = None, near: float = 1.0) -> dict:
    """The recommended plateau of a :func:`compute_plateau` map by 004 sec. 4.6's criterion (the
    ratio with the least mean 95th percentile over G_ini <= g_range) and how sharp that optimum
    is: the mean 95th percentile at the neighbouring ratios and the band of ratios whose mean is
    within ``near`` [mm/s] of the best, JSON-ready.

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_plateau` result.
    case : str or None
        The case to read (None: the first).
    near : float
        Width of the near-optimal band [mm/s].

    Returns
    -------
    dict
        recommended_plateau_ratio [-], recommended_plateau_rad_s, best_mean_p95_grade_G_mm_s,
        neighbours (ratio -> mean p95 [mm/s]), near_optimal_ratios (lo, hi) [-], at_grid_edge
        (the best ratio is the first or last studied: the optimum may lie outside), and the map;
        with the intervals: mean_p95_grade_G_mm_s_ci (per ratio [lo, hi]; null where the runs
        of a cell cannot bound its 95th percentile), best_mean_p95_grade_G_mm_s_ci,
        indistinguishable_ratios (the plateaus whose interval reaches below the best's upper
        end: not distinguishable from the best at the confidence level), recommended_decided
        (only the best is left).
    """
    case = str(ds["case"].values[0]) if case is None else case
    m = ds["mean_p95"].sel(case=case).values
    r = ds["plateau_ratio"].values
    wn = 2 * np.pi * float(ds.attrs["f_n_hz"])
    k = int(np.nanargmin(m))
    nb = {float(r[j]): float(m[j]) for j in (k - 1, k + 1) if 0 <= j < r.size}
    band = r[np.isfinite(m) & (m <= m[k] + near)]
    return {"case": case, "recommended_plateau_ratio": float(r[k]),
            "recommended_plateau_rad_s": float(r[k] * wn), "natural_frequency_rad_s": wn,
            "best_mean_p95_grade_G_mm_s": float(m[k]), "G_balls_mm_s": float(ds.attrs["G_balls"]),
            "neighbours_mean_p95_grade_G_mm_s": nb,
            "near_optimal_ratios": [float(band.min()), float(band.max())],
            "at_grid_edge": bool(k in (0, r.size - 1)),
            "near_mm_s": float(near), "plateau_ratios": r,
            "mean_p95_grade_G_mm_s": m, "G_ini_mm_s": ds["G_ini"].values,
            "p95_grade_G_mm_s": ds["grade_G_p95"].sel(case=case).values,
            **_indistinguishable(ds, case, r, k)}


def _indistinguishable(ds: xr.Dataset, case: str, r: np.ndarray, k: int) -> dict:
    """The intervals of the mean 95th percentiles of one case and the plateaus not
    distinguishable from the best one, ``r[k]`` (:func:`plateau_summary`); {} for a map
    without intervals."""
    if "mean_p95_ci" not in ds:
        return {}
    ci = ds["mean_p95_ci"].sel(case=case).values               # (ratio, bound)
    same = [float(r[i]) for i in _not_distinguishable(ci, k)]
    return {"mean_p95_grade_G_mm_s_ci": ci, "best_mean_p95_grade_G_mm_s_ci": ci[k],
            "indistinguishable_ratios": same, "recommended_decided": len(same) == 1,
            "confidence_level": float(ds["mean_p95_ci"].attrs.get("confidence_level", LEVEL))}


def _not_distinguishable(ci: np.ndarray, k: int) -> list:
    """The plateaus (indices) whose mean 95th percentile is not distinguishable from the best
    one, ``k``: their interval's lower end reaches below the best's upper end (``ci``: ratio,
    bound [mm/s]; NaN is not compared)."""
    return [i for i in range(len(ci)) if ci[i, 0] <= ci[k, 1]]
