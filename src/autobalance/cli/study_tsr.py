"""``autobalance study unbalance-range`` and ``autobalance study plateau``: the valid range of
initial unbalance and the lower plateau of a temporary speed reduction, each decided at 95 %
confidence with more starts where undecided (:mod:`autobalance.studies.unbalance`,
:mod:`autobalance.studies._plateau`). The options and helpers are those of
:mod:`autobalance.cli.study`; registered by :mod:`autobalance.cli`."""
from __future__ import annotations

import time
from typing import Annotated, Optional

import typer

from ..confidence import interval_text
from .common import (ExecutorOpt, GradeOpt, JsonOpt, PlotOpt, ProfileOpt, SchedulerOpt, SetOpt,
                     SourceArg, UnitsOpt, WorkersOpt, check_grade, grade_text, guard,
                     print_json)
from .study import (BudgetOpt, OutOpt, QuickOpt, StartsOpt, StoreOpt, _counts, _factors,
                    _finish, _prepare, _store, _study_errors, app, budget_text, check_budget)

__all__ = ["plateau", "unbalance_range"]

SeedOpt = Annotated[int, typer.Option("--seed", help="Seed of the random starts added where "
                                                     "undecided.")]


@app.command("unbalance-range")
def unbalance_range(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
                    grade: GradeOpt = 16.0, units: UnitsOpt = None,
                    g_max: Annotated[Optional[float], typer.Option(
                        "--g-max", help="Largest initial grade [mm/s] (default 1.5 x the "
                                        "balancer's grade: balls and liquid).")] = None,
                    steps: Annotated[Optional[int], typer.Option(
                        "--steps", help="Grid intervals of the initial grade (default 25; "
                                        "quick 10).")] = None,
                    n: StartsOpt = None, budget: BudgetOpt = None, seed: SeedOpt = 0,
                    quick: QuickOpt = False, store: StoreOpt = None, out: OutOpt = None,
                    plot: PlotOpt = None, scheduler: SchedulerOpt = None,
                    workers: WorkersOpt = None, executor: ExecutorOpt = None,
                    json_: JsonOpt = False) -> None:
    """Residual grade against the initial unbalance (5/50/95 % over start positions), the
    operating boundaries, the valid initial-unbalance ranges for --grade and their efficiency
    (004 sec. 4.3).\f

    Parameters
    ----------
    source, set_, profile, grade, units, quick, store, out, plot, scheduler, workers, executor, json_
        The options of every study (:mod:`autobalance.cli.study`).
    g_max : float
        Largest initial grade of the grid [mm/s] (> 0).
    steps : int
        Intervals of the initial-grade grid (>= 1).
    n : int
        Start positions per ball (>= 1).
    budget : int or None
        Most runs added where a grid point's 95th percentile is undecided against --grade.
    seed : int
        Seed of the added starts.
    """
    from ..studies.common import capacity_grades, default_starts
    from ..studies.unbalance import compute_unbalance, default_grades, unbalance_summary

    t0 = time.perf_counter()
    with guard(), _study_errors():
        cfg, G, du = _prepare(source, set_, profile, grade, plot, out, workers, executor,
                              scheduler, store, units, balls="balancer")
        if g_max is not None:
            check_grade(g_max, "--g-max")
        _counts(steps=steps, starts=n)
        check_budget(budget)
        s = cfg.system
        G_b, G_l = capacity_grades(cfg)
        Gv = default_grades(G_b + G_l, quick, g_max, steps)
        top = float(Gv[-1])
        nn = n or default_starts(s.balancer.n_balls, quick)
        ds = compute_unbalance(cfg, G=Gv, n=nn, grade=G, budget=budget, seed=seed,
                               store_dir=_store(store, cfg, "unbalance-range", list(Gv)),
                               executor=executor,
                               workers=workers, scheduler=scheduler, prefix="study",
                               progress=not json_)

        def fig():
            from ..plotting.tsr import plot_unbalance

            return plot_unbalance(ds, G, f"{cfg.name}: residual grade against initial unbalance")

        res = {"study": "unbalance-range", "machine": cfg.name, "n": nn,
               **unbalance_summary(ds, G), "budget": _budget(ds)}
        res.update(_finish(ds, cfg, out, plot, fig, "study unbalance-range", t0))
    if json_:
        print_json(res)
        return
    starts = f"{nn} starts per ball" if s.balancer.n_balls else "one run (a liquid alone)"
    cap = "; ".join(f"{k} G{v:.3g}" for k, v in (("balls", G_b), ("liquid", G_l)) if v)
    typer.echo(f"{cfg.name}: initial grade 0-{top:.3g} mm/s in {Gv.size} steps x {starts}; "
               f"{cap}; target {grade_text(G)}")
    from ..physics.iso1940 import unbalance_value

    def u(g: float) -> str:               # a grade as the unbalance it is, in the config's unit
        return du.fmt(float(unbalance_value(g, s.total_mass, cfg.spin.nominal_speed)),
                      "unbalance", 3)

    def ranges(rs) -> str:
        return ", ".join(f"[G{lo:.3g}, G{hi:.3g}] ({u(lo)} - {u(hi)})" for lo, hi in rs) \
            or "none"

    _echo_budget(res["budget"], "a grid point was undecided")
    for proc, d in res["cases"]["nominal"].items():
        typer.echo(f"  {proc:>8}: valid initial unbalance {ranges(d['valid_ranges_grade_G_mm_s'])}"
                   f"; efficiency {100 * d['efficiency']:.0f} %")
        if "sure_valid_ranges_grade_G_mm_s" in d:
            lo, hi = d["efficiency_ci"]
            undecided = d["p95_verdicts"].count("undecided")
            typer.echo(f"  {'':>8}  at 95 % confidence: valid "
                       f"{ranges(d['sure_valid_ranges_grade_G_mm_s'])}, possibly valid "
                       f"{ranges(d['possible_valid_ranges_grade_G_mm_s'])} (a boundary lies "
                       f"between grid points); efficiency {100 * lo:.0f}-{100 * hi:.0f} %"
                       + (f"; {undecided} of {len(d['p95_verdicts'])} initial grades undecided "
                          "(more starts, --starts or --budget, decide them)" if undecided else ""))


@app.command("plateau")
def plateau(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
            grade: GradeOpt = 16.0, units: UnitsOpt = None,
            n: Annotated[Optional[int], typer.Option(
                "--starts", help="Start positions per ball (default: at most 210 runs per cell, "
                            "20 for 2 balls, 9 for 3; quick 36 runs: 8 / 5).")] = None,
            ratios: Annotated[Optional[str], typer.Option(
                "--ratios", help="Plateau speeds as multiples of the natural frequency, e.g. "
                                 "'1.0,1.05,1.1,1.15' (default 0.96-1.12 every 0.01; quick "
                                 "0.98,1.02,1.06,1.10).")] = None,
            budget: BudgetOpt = None, seed: SeedOpt = 0,
            quick: QuickOpt = False, store: StoreOpt = None, out: OutOpt = None,
            plot: PlotOpt = None, scheduler: SchedulerOpt = None, workers: WorkersOpt = None,
            executor: ExecutorOpt = None, json_: JsonOpt = False) -> None:
    """The lower plateau of a temporary speed reduction: plateau x initial-unbalance map of the
    95th percentile, the recommended plateau (004 sec. 4.6) and how sharp the optimum is.\f

    Parameters
    ----------
    source, set_, profile, grade, units, quick, store, out, plot, scheduler, workers, executor, json_
        The options of every study (:mod:`autobalance.cli.study`); the profile must be a tsr.
    n : int
        Start positions per ball (>= 1).
    ratios : str
        Comma-separated plateau / natural-frequency ratios [-] (> 0).
    budget : int or None
        Most runs added while other plateaus are not distinguishable from the best.
    seed : int
        Seed of the added starts.
    """
    from ..studies._plateau import compute_plateau, plateau_summary

    t0 = time.perf_counter()
    with guard(), _study_errors():
        cfg, G, du = _prepare(source, set_, profile, grade, plot, out, workers, executor,
                              scheduler, store, units, balls="beside")
        _counts(starts=n)
        check_budget(budget)
        rr = None if ratios is None else sorted(_factors(ratios, "--ratios"))
        ds = compute_plateau(cfg, n=n, quick=quick, ratios=rr, budget=budget, seed=seed,
                             store_dir=_store(store, cfg, "plateau", rr, quick),
                             executor=executor, workers=workers, scheduler=scheduler,
                             prefix="study", progress=not json_)

        def fig():
            from ..plotting.tsr import plot_plateau

            return plot_plateau(ds, G, f"{cfg.name}: lower plateau of the speed reduction")

        res = {"study": "plateau", "machine": cfg.name, "n": int(ds.attrs["n"]), "grade_G_mm_s": G,
               **plateau_summary(ds), "budget": _budget(ds)}
        p95 = res["p95_grade_G_mm_s"]
        k = list(res["plateau_ratios"]).index(res["recommended_plateau_ratio"])
        res["recommended_meets_grade_share"] = float((p95[k] <= G).mean())
        res.update(_finish(ds, cfg, out, plot, fig, "study plateau", t0))
    if json_:
        print_json(res)
        return
    lo, hi = res["near_optimal_ratios"]
    typer.echo(f"{cfg.name}: recommended plateau {du.fmt(res['recommended_plateau_rad_s'], 'speed')} = "
               f"{res['recommended_plateau_ratio']:.3g} x the natural frequency; mean 95th "
               f"percentile G{res['best_mean_p95_grade_G_mm_s']:.3g} over G_ini <= "
               f"{ds.attrs['g_range']:.3g} mm/s")
    typer.echo(f"  within {res['near_mm_s']:g} mm/s of the best: ratios {lo:.3g}-{hi:.3g}; "
               "neighbours: " + ", ".join(f"{r:.3g} -> G{v:.3g}" for r, v in
                                          res["neighbours_mean_p95_grade_G_mm_s"].items()))
    _echo_budget(res["budget"], "plateaus were not distinguishable from the best")
    if "indistinguishable_ratios" in res:
        same = res["indistinguishable_ratios"]
        best = interval_text(*res["best_mean_p95_grade_G_mm_s_ci"], lambda g: f"G{g:.3g}")
        typer.echo(f"  the best's mean 95th percentile: {best}; " + (
            "no other plateau comes as close: the recommendation is decided"
            if res["recommended_decided"] else
            f"{len(same)} of {len(res['plateau_ratios'])} plateaus are not distinguishable "
            f"from it ({min(same):.3g}-{max(same):.3g} x the natural frequency): more starts "
            "per cell (--starts or --budget) decide between them"))
    if res["at_grid_edge"]:
        typer.echo("  the best plateau is at the edge of the studied ratios: the optimum may lie "
                   "outside (widen the range)")
    typer.echo(f"  at the recommended plateau the 95th percentile meets {grade_text(G)} for "
               f"{100 * res['recommended_meets_grade_share']:.0f} % of the initial grades studied")


def _echo_budget(budget: dict, what: str) -> None:
    """The budget line (:func:`autobalance.cli.study.budget_text`) unless no run was allowed
    or added (``--budget 0``)."""
    if budget["runs"] or budget["spent"]:
        typer.echo(budget_text(budget, what))


def _budget(ds) -> dict:
    """The sequential step of a study's result as JSON: runs (the budget), spent, rounds,
    exhausted, capped (the most starts per cell stopped it), first_pass (the start grid's
    runs)."""
    a = ds.attrs
    return {"runs": int(a.get("budget", 0)), "spent": int(a.get("budget_spent", 0)),
            "rounds": int(a.get("budget_rounds", 0)),
            "exhausted": bool(a.get("budget_exhausted", 0)),
            "capped": "yes" if a.get("budget_capped", 0) else "",
            "first_pass": int(a.get("simulations_first_pass", 0))}
