"""``autobalance design`` and ``autobalance study tolerances``: what to build for a machine
(:mod:`autobalance.studies._design`, :mod:`autobalance.studies._tolerances`). The options and
helpers are those of :mod:`autobalance.cli.study`; registered by :mod:`autobalance.cli`."""
from __future__ import annotations

import math
import time
from typing import Annotated, Optional

import typer

from ..confidence import interval_text
from ..config import ConfigError
from ..config.ranges import grammar_help, parse_interval, parse_list
from .common import (ExecutorOpt, GradeOpt, JsonOpt, PlotOpt, ProfileOpt, SchedulerOpt, SetOpt,
                     SourceArg, UnitsOpt, WorkersOpt, grade_text, guard,
                     print_json)
from .study import (STUDY_FIELDS, OutOpt, QuickOpt, StoreOpt, _counts,
                    _factors, _finish, _prepare, _store, _study_errors, app, budget_text,
                    check_budget)
from .warn import machine_warnings_of

__all__ = ["design", "tolerances", "unbalance_interval"]


def unbalance_interval(spec: Optional[str]) -> tuple[float, float] | None:
    """``design --unbalance LO:HI``: the expected initial unbalances [kg*m]
    (:func:`autobalance.config.ranges.parse_interval`: a unit written once applies to both
    ends), 0 <= LO <= HI and HI > 0; None (not given): None, the machine's +-50 %.

    Parameters
    ----------
    spec : str or None
        The option's value, e.g. ``"3:9 g*cm"``.

    Returns
    -------
    tuple of float or None
        (LO, HI) [kg*m].
    """
    if spec is None:
        return None
    rng = parse_interval(spec, "unbalance", "--unbalance", low=0.0, strict=False)
    if rng[1] <= 0:
        raise ConfigError(f"--unbalance = {spec!r}: HI must be > 0")
    return rng


def design(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
           grade: GradeOpt = 16.0, units: UnitsOpt = None,
           confidence: Annotated[float, typer.Option(
               "--confidence", help="Share of start positions that must meet the grade at "
                                    "every unbalance of the range.")] = 0.95,
           unbalance: Annotated[Optional[str], typer.Option(
               "--unbalance", metavar="LO:HI", help=grammar_help(
                   "Expected initial unbalance range", "3:9 g*cm", lists=False, interval=True,
                   tail="0 <= LO <= HI, HI > 0; default 0.5-1.5 x the machine's"))] = None,
           balls: Annotated[Optional[str], typer.Option(
               "--balls", help="Ball counts to try, e.g. '2,3'.")] = None,
           capacity: Annotated[Optional[str], typer.Option(
               "--capacity", help="Ball capacity N m R as multiples of the largest unbalance, "
                                  "e.g. '1.1,1.4,2'.")] = None,
           radii: Annotated[Optional[str], typer.Option(
               "--radii", help="Race radii to try: a list 'a, b, c unit' (the unit on the "
                               "last applies to all), e.g. '40, 50 mm' (default the "
                               "machine's).")] = None,
           profiles: Annotated[Optional[str], typer.Option(
               "--profiles", help="Speed profiles to try: given (the machine's own), std, "
                                  "slow (3x slower run-up), tsr (default std,slow,tsr; quick "
                                  "std,tsr; a machine whose profile is not std or tsr: "
                                  "given).")] = None,
           starts: Annotated[Optional[int], typer.Option(
               "--random", help="Uniform random start positions per unbalance and design in "
                                "the first pass (default 40; quick 10).")] = None,
           n_unbalance: Annotated[Optional[int], typer.Option(
               "--n-unbalance", help="Unbalances across the range (default 4; quick 3).")] = None,
           seed: Annotated[int, typer.Option("--seed", help="Seed of the start positions.")] = 0,
           budget: Annotated[Optional[int], typer.Option(
               "--budget", metavar="RUNS",
               help="Most runs added where a verdict is undecided, cheapest design first "
                    "(default 4 x the first pass; 0: none).")] = None,
           refine_plateau: Annotated[bool, typer.Option(
               "--refine-plateau/--no-refine-plateau",
               help="Run the plateau study on the best TSR candidate and add its recommended "
                    "plateau as one more candidate.")] = True,
           quick: QuickOpt = False, store: StoreOpt = None, out: OutOpt = None,
           plot: PlotOpt = None, scheduler: SchedulerOpt = None, workers: WorkersOpt = None,
           executor: ExecutorOpt = None, json_: JsonOpt = False) -> None:
    """Design a ball balancer and speed profile: ball count, ball mass, race radius and
    profile that meet --grade at --confidence over an initial-unbalance range, cheapest first,
    with the Pareto front and each design's margin.\f

    Parameters
    ----------
    source, set_, profile, grade, units, quick, store, out, plot, scheduler, workers, executor, json_
        The options of every study (:mod:`autobalance.cli.study`).
    confidence : float
        Required share of start positions [-] in (0, 1).
    unbalance : str
        "LO:HI" unbalances (:func:`autobalance.config.ranges.parse_interval`: a unit written
        once applies to both ends; bare numbers kg*m).
    balls, capacity : str
        Comma-separated ball counts (integers >= 1) and capacity ratios (> 1).
    radii : str
        Race radii, a list "a, b, c unit" (:func:`autobalance.config.ranges.parse_list`;
        bare numbers: m).
    profiles : str
        Comma-separated profile variants (given, std, slow, tsr); None: std, slow, tsr (quick
        std, tsr), or given where the machine's profile has no variants (a ramp, a motor).
    starts, n_unbalance : int
        Random starts per unbalance and design; unbalances across the range (>= 1).
    seed : int
        Seed of the start positions.
    budget : int or None
        Most runs the sequential decision adds (>= 0; None: the library's default).
    refine_plateau : bool
        The plateau study on the best TSR candidate.
    """
    from ..studies._design import DesignSpace, compute_design, design_summary

    t0 = time.perf_counter()
    with guard(), _study_errors(STUDY_FIELDS):
        cfg, G, du = _prepare(source, set_, profile, grade, plot, out, workers, executor,
                              scheduler, store, units, balls="beside")
        if not (math.isfinite(confidence) and 0 < confidence < 1):
            raise ConfigError(f"--confidence = {confidence:g}: must be within (0, 1), e.g. 0.95")
        rng = unbalance_interval(unbalance)
        space = DesignSpace.quick() if quick else DesignSpace()
        kw = {}
        if balls is not None:
            nb = _factors(balls, "--balls")
            if any(int(v) != v for v in nb):
                raise ConfigError(f"--balls = {balls!r}: expected integers >= 1, e.g. '2,3'")
            kw["n_balls"] = tuple(int(v) for v in nb)
        if capacity is not None:
            cr = _factors(capacity, "--capacity")
            if min(cr) <= 1:
                raise ConfigError(f"--capacity = {capacity!r}: ratios must exceed 1 (a smaller "
                                  "capacity cannot balance the largest unbalance)")
            kw["capacity_ratios"] = cr
        if radii is not None:
            kw["radii"] = tuple(float(r) for r in parse_list(radii, "length", "--radii"))
            if min(kw["radii"]) <= 0:
                raise ConfigError(f"--radii = {radii!r}: expected positive lengths")
        names, own = _profiles(profiles, cfg)
        if names:
            kw["profiles"] = names
        _counts(random=starts, n_unbalance=n_unbalance)
        check_budget(budget)
        import dataclasses

        space = dataclasses.replace(space, **kw)
        ds = compute_design(cfg, grade=G, confidence=confidence, unbalance_range=rng,
                            n_unbalance=n_unbalance, starts=starts, space=space, seed=seed,
                            quick=quick, refine_plateau=refine_plateau, budget=budget,
                            store_dir=_store(store, cfg, "design", rng, space, starts, seed,
                                             quick, budget),
                            executor=executor, workers=workers, scheduler=scheduler,
                            progress=not json_)

        def fig():
            from ..plotting.tsr import plot_design

            return plot_design(ds, f"{cfg.name}: designs for {grade_text(G)} at "
                                   f"{100 * confidence:g} %")

        res = {"study": "design", "machine": cfg.name, **design_summary(ds)}
        res.update(_finish(ds, cfg, out, plot, fig, "design", t0))
    if json_:
        print_json(res)
        return
    u = res["unbalance_kg_m"]
    typer.echo(f"{cfg.name}: {res['n_designs']} designs x {len(u)} unbalances "
               f"({du.fmt(u[0], 'unbalance')} - {du.fmt(u[-1], 'unbalance')}, G{res['G_ini_mm_s'][0]:.3g}-"
               f"G{res['G_ini_mm_s'][-1]:.3g}) x {res['starts']} starts = "
               f"{res['simulations_first_pass']} simulations, {res['simulations']} with those "
               f"added to decide (+ {res['simulations_plateau_study']} in the plateau study); "
               f"target {grade_text(G)} for {100 * confidence:g} % of starts")
    if "plateau_study" in res:
        p = res["plateau_study"]
        typer.echo(f"  plateau study on {p['design']}: recommended {p['recommended_plateau_ratio']:.3g} x "
                   "the natural frequency (mean 95th percentile " + ", ".join(
                       f"{r:.3g}: G{v:.3g}" for r, v in zip(p["ratios"], p["mean_p95_grade_G_mm_s"]))
                   + ")" + ("; at the edge of the ratios studied" if p["at_grid_edge"] else ""))
    if own:
        typer.echo(f"  every design on the machine's own {cfg.spin.name} "
                   "profile ('given'; the std, slow and tsr variants are of std and tsr "
                   "profiles)")
    typer.echo(budget_text(res["budget"]))
    typer.echo(f"  {res['n_meeting']} design{' meets' if res['n_meeting'] == 1 else 's meet'} "
               f"the target at 95 % confidence, {res['n_undecided']} undecided" + (
        f"; recommended (the cheapest that meets it): {res['best']['name']} (margin "
        f"{res['best']['margin_grade_G_mm_s']:.2f} mm/s, "
        + interval_text(*res["best"]["margin_grade_G_mm_s_ci"], lambda v: f"{v:+.2f}")
        + " mm/s)" if res["best"] else "; no design is decided to meet it: none recommended "
        "(more starts, --random or --budget, or other candidates)"))
    for r in res["designs"]:
        lo, hi = r["worst_quantile_grade_G_mm_s_ci"]
        typer.echo(f"  {r['verdict']:>9} {r['name']:>24}: balls "
                   f"{1e3 * r['total_ball_mass_kg']:.3g} g, worst {100 * confidence:g} % grade "
                   f"G{r['worst_quantile_grade_G_mm_s']:.3g} ("
                   + interval_text(lo, hi, lambda g: f"G{g:.3g}", int(min(r["starts"])))
                   .replace(" runs", " starts at least") + f"), margin "
                   f"{r['margin_grade_G_mm_s']:+.2f} mm/s" + ("  (Pareto)" if r["pareto"] else ""))
        if r["profile_knots_s_rad_s"]:
            typer.echo(f"  {'':>9} {'':>24}  profile: " + ", ".join(
                f"{du.fmt(t, 'time')} {du.fmt(w, 'speed')}" for t, w in r["profile_knots_s_rad_s"]))
    _echo_tolerances(res, G, du)


def _echo_tolerances(res: dict, G: float, du) -> None:
    """The text of `design`'s tolerances: those of the recommended design for the target grade
    G [mm/s] (or why there are none) and the tolerances study's notes; lengths in ``du``."""
    t = res.get("tolerances")
    if res.get("tolerances_skipped"):
        typer.echo(f"  no tolerances: {res['tolerances_skipped']}")
    if t:
        if t["feasible"]:
            typer.echo(f"  to build {t['design']} for a worst case within {grade_text(G)}: ring "
                       f"eccentricity <= {du.fmt(t['max_eccentricity_m'], 'length')}, f/r <= "
                       f"{t['max_rolling_resistance']:.3g}, damper friction <= "
                       f"{t['max_suspension_friction_N']:.3g} N (study tolerances); with the "
                       f"friction simulated here the worst case is G{t['own_worst_grade_G_mm_s']:.3g}")
        else:
            typer.echo(f"  tolerances of {t['design']}: not feasible ({t['reason']})")
        for n in t.get("notes", []):
            typer.echo(f"    note: {n}")


def _profiles(spec: str | None, cfg) -> tuple[tuple, bool]:
    """The profiles `design` tries: (names, whether they are the machine's own by default).

    Parameters
    ----------
    spec : str or None
        ``--profiles`` (comma-separated: given, std, slow, tsr); None: the design space's
        default, or ``("given",)`` for a machine whose profile has no variants (a ramp, a table,
        a motor; :func:`autobalance.studies._design.profile_variants`).
    cfg : autobalance.config.Config
        The machine.
    """
    from ..studies._design import profile_variants

    if spec is None:
        own = list(profile_variants(cfg)) == ["given"]
        return (("given",) if own else ()), own
    names = tuple(p.strip() for p in spec.split(",") if p.strip())
    if not names or any(p not in ("given", "std", "slow", "tsr") for p in names):
        raise ConfigError(f"--profiles = {spec!r}: must be from given (the machine's own), std, "
                          "slow, tsr")
    return names, False


def _split(text: str) -> dict:
    """``--split "cause=share,..."`` -> {cause: share [-]}, checked
    (:func:`autobalance.physics.tolerance.check_split`)."""
    from ..models import ParameterError
    from ..physics.tolerance import check_split

    example = "'eccentricity=0.5,rolling=0.35,friction=0.1,other=0.05'"
    sp = {}
    for item in text.split(","):
        key, _, val = item.partition("=")
        try:
            sp[key.strip()] = float(val)
        except ValueError:
            raise ConfigError(f"--split = {text!r}: expected cause=share pairs, e.g. "
                              f"{example}") from None
    try:
        return check_split(sp, "--split")
    except ParameterError as e:
        raise ConfigError(f"--split = {text!r}: {e.allowed}, e.g. {example}") from None


@app.command("tolerances")
def tolerances(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
               grade: GradeOpt = 16.0, units: UnitsOpt = None,
               speed: Annotated[Optional[str], typer.Option(
                   "--speed", help="Speed of the bound, e.g. '800 rpm' (default the nominal "
                                   "speed).")] = None,
               split: Annotated[Optional[str], typer.Option(
                   "--split", help="Budget shares per cause, e.g. "
                                   "'eccentricity=0.5,rolling=0.35,friction=0.1,other=0.05' "
                                   "(000 eq 56's example; must sum to 1).")] = None,
               check: Annotated[int, typer.Option(
                   "--check", help="Also simulate this many random starts of the machine built "
                                   "with the designed tolerances (0: none).")] = 0,
               residual_fraction: Annotated[Optional[float], typer.Option(
                   "--residual-fraction", metavar="Q",
                   help="Target as 000 states it: a residual of Q x the machine's unbalance "
                        "(000: 0.1), instead of --grade.")] = None,
               method: Annotated[str, typer.Option(
                   "--method", help="bound: the true worst case of this balancer; 000: 000's "
                                    "one-ball estimate (eq 56-66 as published).")] = "bound",
               json_: JsonOpt = False) -> None:
    """Tolerances for a target grade: the largest ring eccentricity, rolling resistance and
    suspension friction whose worst-case residual stays within its share of the grade (000 eq
    56-66 generalised to N balls, with a true bound), and the worst case of the machine's own
    tolerances.\f

    Parameters
    ----------
    source, set_, profile, grade, units, json_
        The options of every study (:mod:`autobalance.cli.study`).
    speed : str
        The speed of the bound (with units; bare numbers rad/s).
    split : str
        "cause=share,..." over eccentricity, rolling, friction, other, summing to 1.
    check : int
        Random starts simulated with the designed tolerances (>= 0).
    residual_fraction : float
        Target residual / unbalance [-] in (0, 1].
    method : str
        "bound" or "000".
    """
    from ..config import parse_quantity
    from ..studies._tolerances import check_tolerances_by_simulation, compute_tolerances

    with guard():
        cfg, G, du = _prepare(source, set_, profile, grade, None, None, units=units,
                              balls="beside")
        w = None if speed is None else parse_quantity(speed, "speed", "--speed")
        if w is not None and not (math.isfinite(w) and w > 0):
            raise ConfigError(f"--speed = {speed!r}: must be a speed > 0, e.g. '800 rpm'")
        sp = None if split is None else _split(split)
        if check < 0:
            raise ConfigError(f"--check = {check}: must be an integer >= 0")
        if method not in ("bound", "000"):
            raise ConfigError(f"--method = {method!r}: must be bound (the true worst case) or "
                              "000 (000's one-ball estimate)")
        q = residual_fraction
        if q is not None and not (math.isfinite(q) and 0 < q <= 1):
            raise ConfigError(f"--residual-fraction = {q:g}: must be within (0, 1], e.g. 0.1")
        res = {"study": "tolerances", **compute_tolerances(cfg, grade=G, speed=w, split=sp,
                                                           residual_fraction=q, method=method)}
        G = res["target_grade_G_mm_s"]
        if check and res.get("feasible"):
            sim = check_tolerances_by_simulation(cfg, res, n=check)
            res["simulation_check"] = sim
    notes = list(res.get("warnings", []))        # the study's own notes, printed below
    res["warnings"] = machine_warnings_of(cfg, units) + notes
    if json_:
        print_json(res)
        return
    typer.echo(f"{cfg.name} at {du.fmt(res['speed_rad_s'], 'speed')}: target {grade_text(G)} = "
               f"{du.fmt(res['target_unbalance_kg_m'], 'unbalance')} residual"
               + (f" ({q:g} of the unbalance)" if q is not None else "")
               + ("; method 000 (one-ball estimate, not a bound)" if method == "000" else ""))
    if not res.get("feasible"):
        typer.echo(f"  not feasible: {res.get('reason')}")
    else:
        for why in res.get("unreachable", []):
            typer.echo(f"  unreachable: {why}")
        typer.echo(f"  allowed ({'all three at once' if method == 'bound' else 'each for its share'}"
                   "): ring eccentricity "
                   f"{du.fmt(res['max_eccentricity_m'], 'length')}, rolling resistance f/r "
                   f"{res['max_rolling_resistance']:.3g}, suspension friction "
                   f"{res['max_suspension_friction_N']:.3g} N" + (
                       f" (joint scale {res['joint_scale']:.3g})" if res["joint_scale"] is not None
                       else ""))
        if method == "000":
            typer.echo(f"  the true worst case with all three: "
                       f"{du.fmt(res['design_worst_residual_kg_m'], 'unbalance')} "
                       f"({'within' if res['design_meets_target'] else 'above'} the target)")
    typer.echo(f"  this machine's own tolerances: worst case "
               f"{du.fmt(res['worst_residual_kg_m'], 'unbalance')} = G{res['worst_grade_G_mm_s']:.3g} "
               f"({'meets' if res['meets_target'] else 'misses'} the target); expected "
               f"G{res['expected_grade_G_mm_s']:.3g}")
    if "liquid_added_mass_kg" in res:
        r_lin = res["liquid_linear_range_m"]
        typer.echo("  beside the liquid: " + (
            f"its synchronous moment is an added mass of {res['liquid_added_mass_kg']:.4g} kg "
            f"on the rotor while its rings hold (whirl up to {du.fmt(r_lin, 'length')})"
            if math.isfinite(r_lin) else "a pool at this speed (below its entrainment speed, "
            "003 eq 6): no moment, its mass moves with the rotor") + " (docs/liquid/balls-beside-liquid.md sec. 3l)")
    for wmsg in notes:
        typer.echo(f"  note: {wmsg}")
    if "simulation_check" in res:
        c = res["simulation_check"]
        typer.echo(f"  simulated with the designed tolerances: {len(c['residuals_kg_m'])} runs, "
                   f"largest residual {du.fmt(c['max_residual_kg_m'], 'unbalance')} against the "
                   f"bound {du.fmt(c['bound_kg_m'], 'unbalance')} ({c['n_violations']} above it, "
                   f"{c['n_trapped']} trapped in a collinear state)")
