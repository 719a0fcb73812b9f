"""``autobalance study speed-map`` and ``autobalance study sensitivity``: where the machine
balances and which modelling choices matter (:mod:`autobalance.studies._speed_map`,
:mod:`autobalance.studies._sensitivity`). The options and helpers are those of
:mod:`autobalance.cli.study`; registered by :mod:`autobalance.cli`."""
from __future__ import annotations

import math
import time
from typing import Annotated, Optional

import typer

from ..config import ConfigError
from ..config.ranges import grammar_help, parse_range
from .common import (ExecutorOpt, GradeOpt, JsonOpt, PlotOpt, ProfileOpt, SchedulerOpt, SetOpt,
                     SourceArg, UnitsOpt, WorkersOpt, grade_text, guard,
                     print_json)
from .study import (MAX_MAP_SPEEDS, OutOpt, QuickOpt, RandomOpt, StartsOpt, StoreOpt, _counts,
                    _factors, _finish, _prepare, _store, _study_errors, app)

__all__ = ["map_speeds", "sensitivity", "speed_map"]


@app.command("sensitivity")
def sensitivity(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
                grade: GradeOpt = 16.0, units: UnitsOpt = None,
                vary: Annotated[Optional[list[str]], typer.Option(
                    "--vary", metavar="PATH=VALUE[;PATH=VALUE]",
                    help="One variant: overrides as for --set, several joined by ';' "
                         "(repeatable; default: contact none, ball damping and rolling "
                         "resistance x0.5 and x2, run-up x0.78, TSR plateau x0.96).")] = None,
                n: StartsOpt = None, samples: RandomOpt = None,
                seed: Annotated[int, typer.Option("--seed", help="Seed of --random and of "
                                                  "the bootstrap.")] = 0,
                z: Annotated[float, typer.Option(
                    "--z", help="An effect counts when it exceeds this many standard "
                                "errors.")] = 2.0,
                quick: QuickOpt = False, store: StoreOpt = None, out: OutOpt = None,
                plot: PlotOpt = None, scheduler: SchedulerOpt = None,
                workers: WorkersOpt = None, executor: ExecutorOpt = None,
                json_: JsonOpt = False) -> None:
    """Which modelling choices move which results: the start-position Monte Carlo of the
    machine and of each variant over the same starts, and each variant's effect on the modes,
    medians, 95th percentile, shares <= --grade and 004 Table 2's regions, with its bootstrap
    standard error.\f

    Parameters
    ----------
    source, set_, profile, grade, units, quick, store, out, plot, scheduler, workers, executor,
    json_
        The options of every study (:mod:`autobalance.cli.study`); the figure is each
        variant's effect on each quantity against its standard error.
    vary : list of str
        Variants: "path=value" overrides joined by ';'.
    n, samples, seed : int
        The starts (grid or random) and the seed.
    z : float
        Significance threshold [-] (> 0).
    """
    from ..plotting.sensitivity import plot_sensitivity
    from ..studies._sensitivity import compute_sensitivity, sensitivity_summary

    t0 = time.perf_counter()
    with guard(), _study_errors():
        cfg, G, du = _prepare(source, set_, profile, grade, plot, out, workers, executor,
                              scheduler, store, units, balls="beside")
        _counts(starts=n, random=samples)
        if not (math.isfinite(z) and z > 0):
            raise ConfigError(f"--z = {z:g}: must be a number > 0, e.g. 2")
        variants = None
        if vary:
            variants = {}
            for v in vary:
                sets = [x.strip() for x in v.split(";") if x.strip()]
                if not sets or any("=" not in x for x in sets):
                    raise ConfigError(f"--vary = {v!r}: expected PATH=VALUE[;PATH=VALUE], e.g. "
                                      "'balancer.contact=none'")
                variants[v] = sets
        ds = compute_sensitivity(cfg, variants, n=n, samples=samples, seed=seed, grade=G,
                                 quick=quick,
                                 store_dir=_store(store, cfg, "sensitivity", variants, n,
                                                  samples, seed, quick),
                                 executor=executor, workers=workers,
                                 scheduler=scheduler, progress=not json_)
        res = {**sensitivity_summary(ds, z), "machine": cfg.name}
        res.update(_finish(ds, cfg, out, plot, lambda: plot_sensitivity(
            ds, z, f"{cfg.name}: sensitivity"), "study sensitivity", t0))
    if json_:
        print_json(res)
        return
    typer.echo(f"{cfg.name}: {res['runs_used']} runs per variant ({res['starts']}); target "
               f"{grade_text(G)}; effects beyond {z:g} standard errors (paired bootstrap)")
    b = res["base"]
    u = res["units"]
    typer.echo("  base: " + ", ".join(f"{q} {_q_text(u[q], v)}" for q, v in b.items()))
    for name, d in res["variants"].items():
        sig = [f"{q} {_q_text(u[q], e['effect'], sign=True)} (+-{_q_text(u[q], e['se'])})"
               for q, e in d["effects"].items() if e["significant"]]
        typer.echo(f"  {name}: " + (", ".join(sig) if sig else "no effect beyond the noise"))


def _q_text(unit: str, v: float, sign: bool = False) -> str:
    """A sensitivity quantity of the given unit (the study's ``units``) as text: grades
    ("mm/s") in mm/s, shares ("-") in %."""
    if unit == "mm/s":
        return f"{v:+.2f}" if sign else f"{v:.2f}"
    return f"{100 * v:+.1f} %" if sign else f"{100 * v:.1f} %"


def map_speeds(spec: Optional[str]):
    """``study speed-map --speeds LO:HI:N``: the speed grid [rad/s]
    (:func:`autobalance.config.ranges.parse_range`), 0 < LO < HI (at rest the balls have no
    equilibrium) and 2 <= N <= :data:`MAX_MAP_SPEEDS` (each speed costs 0.1-0.5 s,
    docs/speed-map.md); None (not given): None, the study's default grid.

    Parameters
    ----------
    spec : str or None
        The option's value, e.g. ``"200:5000 rpm:120"``.

    Returns
    -------
    numpy.ndarray or None
        The speeds [rad/s].
    """
    if spec is None:
        return None
    return parse_range(spec, "speed", "--speeds", min_points=2, max_points=MAX_MAP_SPEEDS,
                       low=0.0, above=True)


@app.command("speed-map")
def speed_map(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
              units: UnitsOpt = None,
              speeds: Annotated[Optional[str], typer.Option(
                  "--speeds", metavar="LO:HI:N", help=grammar_help(
                      "Speed grid", "200:5000 rpm:120", lists=False,
                      tail=f"0 < LO < HI, 2 <= N <= {MAX_MAP_SPEEDS}; default 0.3 x the first "
                           "natural frequency to 1.3 x nominal"))] = None,
              damping: Annotated[Optional[str], typer.Option(
                  "--c-r", help="Factors on the suspension damping for the second map, "
                                "e.g. '0.5,1,2'.")] = None,
              ks_only: Annotated[bool, typer.Option(
                  "--ks-only", help="Judge stability in the kinetic-static model (000 eq 13) "
                                    "instead of the linearised full model.")] = False,
              quick: QuickOpt = False, out: OutOpt = None, plot: PlotOpt = None,
              json_: JsonOpt = False) -> None:
    """Will it balance: every equilibrium of the balls over speed (isolated ones and the
    balanced families of N >= 3 balls), its stability in the linearised full model, and the
    speed ranges where the balanced state exists and is stable; the same against damping.\f

    Parameters
    ----------
    source, set_, profile, units, quick, out, plot, json_
        The options of every study (:mod:`autobalance.cli.study`; no ``--grade``: the verdict
        is the balanced state's existence and stability).
    speeds : str
        "LO:HI:N" speeds (:func:`autobalance.config.ranges.parse_range`; a unit written
        once applies to both ends, bare numbers rad/s), 2 <= N <= MAX_MAP_SPEEDS points.
    damping : str
        Comma-separated positive factors [-] on cx, cy.
    ks_only : bool
        Kinetic-static verdicts only (faster, not the full model).
    """
    from ..studies._speed_map import compute_speed_map, speed_map_summary

    t0 = time.perf_counter()
    with guard():
        cfg, _, du = _prepare(source, set_, profile, 16.0, plot, out, units=units,
                              balls="beside")
        grid = map_speeds(speeds)
        facs = None if damping is None else _factors(damping, "--c-r")
        ds = compute_speed_map(cfg, speeds=grid, damping_factors=facs, quick=quick,
                               full=not ks_only)

        def fig():
            from ..plotting.speed_map import plot_speed_map

            return plot_speed_map(ds, speed_unit=du.unit("speed"))

        res = {"study": "speed-map", **speed_map_summary(ds), "machine": cfg.name}
        res.update(_finish(ds, cfg, out, plot, fig, "study speed-map", t0))
    if json_:
        print_json(res)
        return
    rng = ", ".join(f"{du.fmt(lo, 'speed')} - {du.fmt(hi, 'speed')}" for lo, hi in res["stable_ranges_rad_s"])
    typer.echo(f"{cfg.name}: balanced and stable at {rng or 'no speed of the grid'} "
               f"({res['method']}); natural frequencies "
               + ", ".join(du.fmt(w, "speed") for w in res["natural_frequencies_rad_s"])
               + f"; nominal {du.fmt(res['nominal_speed_rad_s'], 'speed')}")
    if "film_from_rad_s" in res:
        h = res.get("liquid_axis") == "horizontal"
        typer.echo(f"  beside the liquid: a {'puddle' if h else 'pool'} below "
                   f"{du.fmt(res['film_from_rad_s'], 'speed')} (the balls' verdicts, with its "
                   "mass), a film from there: only the balanced state is judged, with the films "
                   + ("(Floquet about its periodic state under gravity, docs/liquid/horizontal-axis.md sec. 3m)"
                      if h else "(docs/liquid/stability.md sec. 3k)"))
    def spans(ranges) -> str:
        return ", ".join(du.fmt(lo, "speed") if lo == hi else
                         f"{du.fmt(lo, 'speed')} - {du.fmt(hi, 'speed')}" for lo, hi in ranges)

    if res["no_verdict_ranges_rad_s"]:
        typer.echo(f"  no verdict at grid speeds {spans(res['no_verdict_ranges_rad_s'])} (neither "
                   "stable nor unstable: no converged orbit, or a family's multipliers not told "
                   "apart from the others)")
    typer.echo(f"  {res['evaluations']} evaluations (the balanced state judged at one speed and "
               f"damping factor, grid points and bisection steps), {res['no_verdict']} without a "
               f"verdict; {res['states_judged']} states judged, {res['states_no_verdict']} "
               "without a verdict")
    c = res["counts"]
    typer.echo(f"  {c['speeds']} speeds: a balanced state at {c['balanced_exists']}, stable at "
               f"{c['balanced_stable']}, no verdict at {c['balanced_no_verdict']}; at most "
               f"{c['max_isolated']} isolated equilibria and {c['max_families']} families at one "
               "speed")
    for d in res["damping"]:
        nv = (f"; no verdict at {spans(d['no_verdict_ranges_rad_s'])}"
              if d["no_verdict_ranges_rad_s"] else "")
        typer.echo(f"  damping x{d['damping_factor']:g}: stable at "
                   f"{spans(d['stable_ranges_rad_s']) or 'no speed'}{nv}")
