"""``autobalance study ...``: the design studies of :mod:`autobalance.studies` for any preset or
config file.

Every study takes the machine (``PRESET|CONFIG`` with ``--set`` and ``--profile``), the target
grade ``--grade G`` [mm/s] (default 16, printed with its ISO 1940 class), ``--units`` (the
units of the text: default those written in the config), ``--json`` (one
object, SI, unit-suffixed keys), ``--out FILE.nc`` (the study's dataset as NetCDF with units and
provenance), ``--plot FILE.png`` and ``--quick`` (a coarse version that finishes in under two
minutes on two cores). The studies that run simulations keep them in a resumable sweep store
(``--store DIR``: a rerun computes nothing that is already there), show a progress bar on stderr
and run on a Dask cluster with ``--scheduler``. Input errors print one line ``error: ...`` and
exit 2.
"""
from __future__ import annotations

import math
import os
import time
from contextlib import contextmanager
from pathlib import Path
from typing import Annotated, Iterator, Optional

import typer

from ..confidence import interval_text
from ..config import ConfigError
from ..config.ranges import grammar_help
from .common import (ExecutorOpt, GradeOpt, JsonOpt, PlotOpt, ProfileOpt, SchedulerOpt, SetOpt,
                     SourceArg, UnitsOpt, WorkersOpt, as_options, check_distinct, check_executor,
                     check_grade, check_output_file, check_plot, check_workers, fail, grade_text,
                     guard, load_machine, print_json, quiet_dask_logs)

app = typer.Typer(name="study", no_args_is_help=True, add_completion=False,
                  rich_markup_mode=None,     # help as written: no rich markup or :emoji: codes
                  pretty_exceptions_enable=False,
                  help="Design studies of any machine: speed map, start positions, unbalance "
                       "range, TSR plateau, immobility, tolerances, sensitivity.")

QuickOpt = Annotated[bool, typer.Option(
    "--quick", help="Coarse grids: finishes in under 2 minutes on 2 cores.")]
OutOpt = Annotated[Optional[Path], typer.Option(
    "--out", metavar="FILE.nc", help="Write the study's dataset (NetCDF, units and provenance).")]
StoreOpt = Annotated[Optional[Path], typer.Option(
    "--store", metavar="DIR", help="Keep the simulations in resumable sweep stores under DIR "
                                   "(a rerun computes only what is missing).")]

StartsOpt = Annotated[Optional[int], typer.Option(
    "--starts", help="Start positions per ball of 004's equispaced grid (default 50 for 2 balls, "
                "20 for 3; quick 12 / 8).")]
RandomOpt = Annotated[Optional[int], typer.Option(
    "--random", help="Uniform random start angles instead of the grid: this many.")]

BudgetOpt = Annotated[Optional[int], typer.Option(
    "--budget", metavar="RUNS",
    help="Most runs added where the decision is undecided at 95 % confidence (default: as many "
         "as the start grid ran; 0: none).")]

#: Most speeds of a ``study speed-map --speeds`` grid.
MAX_MAP_SPEEDS = 2000
#: Figure formats of ``--plot``.
PLOT_SUFFIXES = (".png", ".svg", ".pdf")


def _counts(**values) -> None:
    """Refuse a count option below 1 (``--starts``, ``--steps``, ...); None (not given) passes;
    ``starts`` and ``random`` (the two ways of choosing the start positions) given together are
    refused."""
    for name, v in values.items():
        if v is not None and v < 1:
            raise ConfigError(f"--{name.replace('_', '-')} = {v}: must be an integer >= 1")
    if values.get("starts") is not None and values.get("random") is not None:
        raise ConfigError(f"--starts = {values['starts']} and --random = {values['random']}: "
                          "give one of them (--starts N: 004's equispaced grid of N positions "
                          "per ball; --random K: K random starts)")


#: The sweep fields the shared study options set (:func:`_study_errors` names the options).
STUDY_FIELDS = {"monte_carlo.n": "--starts", "monte_carlo.samples": "--random",
                "monte_carlo.seed": "--seed"}


def check_budget(budget: Optional[int]) -> None:
    """Refuse a negative ``--budget`` in one line (None: the study's default)."""
    if budget is not None and budget < 0:
        raise ConfigError(f"--budget = {budget}: must be an integer >= 0 (runs)")


def budget_text(budget: dict, what: str = "a verdict was undecided") -> str:
    """The line a study prints of its sequential step (:func:`autobalance.studies.sequential.
    refine`): the budget, what it bought and why it stopped, from a study's JSON ``budget``
    (runs, spent, rounds, exhausted, capped: a text or a list of the candidates capped)."""
    rounds, capped = budget["rounds"], budget["capped"]
    capped = capped if isinstance(capped, str) else ", ".join(capped)
    return (f"  budget: up to {budget['runs']} more runs where {what}; spent {budget['spent']} "
            f"in {rounds} round{'' if rounds == 1 else 's'}"
            + ("; the budget ran out first" if budget["exhausted"] else "")
            + (f"; left undecided at the most starts per cell: {capped}" if capped else ""))


@contextmanager
def _study_errors(fields: dict | None = None) -> Iterator[None]:
    """Sweep failures inside a study -> one line and the sweep command's exit codes; an error
    about a field an option set names the option (``fields``: field -> option, default
    :data:`STUDY_FIELDS`; :func:`autobalance.cli.common.as_options`)."""
    from ..sweep import SweepAborted, SweepError, SweepInterrupted

    try:
        with as_options(STUDY_FIELDS if fields is None else fields):
            yield
    except SweepError as e:
        fail(str(e))
    except SweepInterrupted as e:
        fail(f"{e} (rerun the same command with the same --store to continue)"
             if e.resumable else str(e), 128 + int(e.signal))
    except SweepAborted as e:
        fail(str(e), 1)


def _prepare(source, set_, profile, grade, plot, out, workers=None, executor=None,
             scheduler=None, store=None, units=None, balls: str = "needed"):
    """The checks every study makes before any work; the machine, the target grade [mm/s] and
    the display units of the text and figures. The machine's sanity warnings are printed
    here, ``warning: ...`` lines before the study's text (:func:`.warn.echo_warnings`)."""
    from ..config.display import display_units
    from .warn import echo_warnings

    config = {"the input config file": source}
    check_plot(plot, PLOT_SUFFIXES, inputs=config)
    check_output_file(out, "--out", "study.nc", (".nc",), inputs=config)
    check_distinct({"--out": out, "--plot": plot})
    G = check_grade(grade)
    check_workers(workers)
    check_executor(executor, workers, scheduler)
    if store is not None and store.exists() and not store.is_dir():
        raise ConfigError(f"--store {str(store)!r}: exists and is not a directory")
    if scheduler or executor == "dask" or os.environ.get("DASK_SCHEDULER_ADDRESS"):
        quiet_dask_logs()
    cfg = load_machine(source, set_, profile, balls=balls)
    du = display_units(cfg, units)
    echo_warnings(cfg, units)
    return cfg, G, du


def _finish(ds, cfg, out, plot, fig_fn, command: str, t0: float) -> dict:
    """Write the NetCDF (with provenance) and the figure, each atomically (a failed write leaves
    the previous file: :mod:`autobalance.atomic`); return their paths, the wall time and the
    machine's sanity warnings (``warnings``, also an attribute of the NetCDF)."""
    from .. import __version__
    from ..atomic import atomic_output, save_figure
    from ..jsonable import netcdf_safe
    from .warn import machine_warnings_of

    done = {"wall_time_s": time.perf_counter() - t0, "warnings": machine_warnings_of(cfg)}
    if out is not None:
        ds = ds.copy()
        ds.attrs.update({"autobalance_version": __version__, "command": command,
                         "machine": cfg.name, "machine_source": str(cfg.source),
                         "created": time.strftime("%Y-%m-%dT%H:%M:%S%z"),
                         "warnings": done["warnings"]})
        with atomic_output(out, "--out") as tmp:
            netcdf_safe(ds).to_netcdf(tmp)
        done["out"] = str(out)
    if plot is not None:
        import logging

        # matplotlib logs a fallback line per missing TeX font when a log axis is drawn
        logging.getLogger("matplotlib.font_manager").setLevel(logging.ERROR)
        save_figure(fig_fn(), plot, "--plot", dpi=110)
        done["plot"] = str(plot)
    return done


def _store(store: Optional[Path], cfg, *parts) -> Optional[Path]:
    """The study's directory under ``--store``: one per machine and study arguments (a short
    digest of both), so that a rerun resumes its own sweeps and a changed machine starts new
    ones beside them; None without ``--store``."""
    if store is None:
        return None
    import hashlib
    import json

    from ..config import describe
    from ..jsonable import to_jsonable

    key = json.dumps(to_jsonable([describe(cfg), *parts]), sort_keys=True)
    d = store / f"{parts[0]}-{hashlib.sha256(key.encode()).hexdigest()[:10]}"
    d.mkdir(parents=True, exist_ok=True)
    return d


@app.command("start-positions")
def start_positions(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
                    grade: GradeOpt = 16.0, units: UnitsOpt = None,
                    n: StartsOpt = None, samples: RandomOpt = None,
                    seed: Annotated[int, typer.Option("--seed", help="Seed of --random.")] = 0,
                    grid: Annotated[Optional[list[str]], typer.Option(
                        "--grid", metavar="PATH=V1,V2|PATH=LO:HI:N",
                        help="Repeat the Monte Carlo per cell of a grid of config values "
                             "PATH=VALUES (repeatable). " + grammar_help(
                                 "VALUES", "rotor.unbalance=2:8 g*cm:4",
                                 tail="or 'rotor.unbalance=4, 8 g*cm'; N >= 1"))] = None,
                    quick: QuickOpt = False, store: StoreOpt = None, out: OutOpt = None,
                    plot: PlotOpt = None, scheduler: SchedulerOpt = None,
                    workers: WorkersOpt = None, executor: ExecutorOpt = None,
                    json_: JsonOpt = False) -> None:
    """Monte Carlo over ball start positions: the grade at each read-out of the profile
    (percentiles, mode, share <= --grade) and 004 Table 2's regions (004 sec. 4.2).\f

    Parameters
    ----------
    source, set_, profile, grade, units, quick, store, out, plot, scheduler, workers, executor, json_
        The options of every study (:mod:`autobalance.cli.study`).
    n : int
        Start positions per ball of the grid (>= 1).
    samples : int
        Random starts instead of the grid (>= 1).
    seed : int
        Seed of the random starts.
    grid : list of str
        Grid axes "PATH=V1,V2,..." or "PATH=LO:HI:N" (:mod:`autobalance.config.ranges`;
        values with units, bare numbers SI).
    """
    from ..studies._start_positions import compute_start_positions, start_positions_summary
    from .sweep import _coord_text

    t0 = time.perf_counter()
    with guard(), _study_errors():
        cfg, G, du = _prepare(source, set_, profile, grade, plot, out, workers, executor,
                              scheduler, store, units, balls="beside")
        _counts(starts=n, random=samples)
        axes = _grid(grid)
        if axes and "balancer.n_balls" in axes and samples is None:
            raise ConfigError("--grid balancer.n_balls=...: needs --random K (the start grid's "
                              "size depends on the ball count; K random starts suit every count)")
        ds = compute_start_positions(cfg, n=n, samples=samples, seed=seed, grade=G, quick=quick,
                                     name="start-positions", grid=axes,
                                     store=_store(store, cfg, "start-positions", n, samples, seed,
                                                  quick, axes),
                                     executor=executor, workers=workers,
                                     scheduler=scheduler, progress=not json_)

        def fig():
            from ..plotting.tsr import plot_start_positions

            return plot_start_positions(ds, f"{cfg.name}: grade over ball start positions")

        res = {**start_positions_summary(ds), "machine": cfg.name}
        res.update(_finish(ds, cfg, out, plot, fig, "study start-positions", t0))
    if json_:
        print_json(res)
        return
    typer.echo(f"{cfg.name}: {res['runs']} runs ({res['starts']}), {res['failed']} failed; "
               f"target {grade_text(G)}; initial G{res['G_ini_mm_s']:.3g}, balls "
               f"G{res['G_balls_mm_s']:.3g}")
    for c in res["checkpoints"]:
        where = (f"t = {c['time_s']:g} s" if c["label"].startswith("t=")
                 else f"{c['label']} (t = {c['time_s']:g} s)")
        typer.echo(f"  {where:>18}: G p5/p50/p95 = "
                   f"{c['p5_grade_G_mm_s']:.2f} / {c['p50_grade_G_mm_s']:.2f} / "
                   f"{c['p95_grade_G_mm_s']:.2f} mm/s, mode {c['mode_grade_G_mm_s']:.1f}, "
                   f"share <= G{G:g}: {100 * c['share_below_grade']:.1f} %")
        typer.echo(f"  {'':>18}  p95 G{c['p95_grade_G_mm_s']:.3g} ("
                   + interval_text(*c["p95_grade_G_mm_s_ci"], lambda g: f"G{g:.3g}",
                                   c["runs_ok"]).replace(" runs", " starts")
                   + f"), share {interval_text(*c['share_below_grade_ci'], _percent)}: "
                   f"p95 <= G{G:g} {c['p95_verdict']}")
    if res.get("cells"):
        typer.echo(f"  (pooled over {len(res['cells'])} grid cells; per cell at the last read-out:)")
        for c in res["cells"]:
            cell = {"coords": c["coords"], "coords_as_given": {
                ax["path"]: c["coords"][ax["key"]] for ax in res["grid"]}}
            where = ", ".join(_coord_text(ax, cell, du, "display") for ax in res["grid"])
            last = c["checkpoints"][-1]
            typer.echo(f"    {where}: G p50/p95 = {last['p50_grade_G_mm_s']:.2f} / "
                       f"{last['p95_grade_G_mm_s']:.2f} mm/s ("
                       + interval_text(*last["p95_grade_G_mm_s_ci"], lambda g: f"G{g:.3g}",
                                       last["runs_ok"]).replace(" runs", " starts")
                       + f"), share <= G{G:g}: {100 * last['share_below_grade']:.1f} %; "
                       f"p95 <= G{G:g} {last['p95_verdict']}")
    if res.get("regions"):
        typer.echo("  004 Table 2 regions (first vs last read-out): " + ", ".join(
            f"{k} {100 * v:.1f} %" for k, v in res["regions"].items())
            + f"; grades within {res['tie_mm_s']:g} mm/s taken as equal: " + ", ".join(
            f"{k} {100 * v:.1f} %" for k, v in res["regions_tied"].items()))


def _percent(share: float) -> str:
    """A share [-] as a percentage for text."""
    return f"{100 * share:.1f} %"


def _grid(specs) -> dict | None:
    """``--grid`` options "PATH=V1,V2,..." or "PATH=LO:HI:N" -> {path: SI values}: the values
    in the grammar of :mod:`autobalance.config.ranges` for the kind of PATH (a unit written
    once applies to both ends or to every item, N >= 1), then the sweep description's own axis
    parser (:func:`autobalance.sweep.spec.grid_axis`: kinds, distinct values, one-line errors)."""
    from ..config.ranges import is_range, list_items, parse_range
    from ..config.units import KINDS
    from ..sweep.spec import SweepError, field_kind, grid_axis

    if not specs:
        return None
    out = {}
    for spec in specs:
        path, eq, rhs = spec.partition("=")
        path = path.strip()
        if not eq or not path or not rhs.strip():
            raise ConfigError(f"--grid = {spec!r}: expected PATH=V1,V2,... or PATH=LO:HI:N, e.g. "
                              "'rotor.unbalance=4 g*cm,8 g*cm'")
        if path in out:
            raise ConfigError(f"--grid = {spec!r}: {path} is given twice")
        try:
            kind = field_kind(path)
            if kind not in KINDS:                   # int, text, bool: the values as written
                if is_range(rhs):
                    raise ConfigError(f"--grid = {spec!r}: {path} takes a list V1,V2,..., "
                                      "not a range")
                axis = grid_axis(path, [_value(v) for v in rhs.split(",")])
            elif is_range(rhs):
                v = parse_range(rhs, kind, f"--grid {path}", min_points=1, increasing=False)
                axis = grid_axis(path, {"start": float(v[0]), "stop": float(v[-1]),
                                        "num": int(v.size)})
            else:
                axis = grid_axis(path, [_value(v) for v in list_items(rhs, kind,
                                                                      f"--grid {path}")])
        except SweepError as e:
            raise ConfigError(f"--grid: {e}") from None
        out[path] = list(axis.si)
    return out


def _value(text: str):
    """One value of ``--grid``: an int, a float or a quantity with units (as in a config)."""
    t = text.strip()
    for kind in (int, float):
        try:
            return kind(t)
        except ValueError:
            pass
    return t


@app.command("immobility")
def immobility(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
               grade: GradeOpt = 16.0, units: UnitsOpt = None,
               g_ini: Annotated[Optional[float], typer.Option(
                   "--g-ini", help="Initial unbalance grade [mm/s] (default: the machine's).")] = None,
               mu_r: Annotated[str, typer.Option("--mu-r", help="Factors on the rolling "
                                                 "resistance, e.g. '0.5,1,2'.")] = "1",
               c_r: Annotated[str, typer.Option("--c-r", help="Factors on the suspension "
                                                "damping, e.g. '0.5,1'.")] = "1",
               n_conf: Annotated[Optional[int], typer.Option(
                   "--starts", help="Positions per ball of the grid of balls at rest (default "
                   "100; 36 with --quick).")] = None,
               quick: QuickOpt = False, out: OutOpt = None, plot: PlotOpt = None,
               json_: JsonOpt = False) -> None:
    """Immobility of balls at rest against speed and the stick threshold G*(speed) for this
    machine's balls, friction and suspension (004 sec. 4.4-4.5; closed form, isotropic
    suspension).\f

    Parameters
    ----------
    source, set_, profile, grade, units, quick, out, plot, json_
        The options of every study (:mod:`autobalance.cli.study`).
    g_ini : float
        Initial grade [mm/s] (default: the machine's unbalance at its nominal speed).
    mu_r, c_r : str
        Comma-separated factors [-] on the balls' rolling resistance and the suspension damping.
    n_conf : int or None
        Positions per ball (>= 2; n_conf^N configurations; None: the library's default).
    """
    from ..studies._immobility import compute_immobility, immobility_summary

    t0 = time.perf_counter()
    with guard():
        cfg, G, du = _prepare(source, set_, profile, grade, plot, out, units=units,
                              balls="beside")
        if g_ini is not None and not (math.isfinite(g_ini) and g_ini >= 0):
            raise ConfigError(f"--g-ini = {g_ini}: must be a finite grade >= 0 [mm/s], e.g. 20")
        if n_conf is not None and n_conf < 2:
            raise ConfigError(f"--starts = {n_conf}: must be an integer >= 2")
        mus, cs = _factors(mu_r, "--mu-r"), _factors(c_r, "--c-r")
        ds = compute_immobility(cfg, G_ini=g_ini, mu_r=mus, c_r=cs, n_conf=n_conf, quick=quick,
                                field="--starts")
        gi = ds.attrs["G_ini"]

        def fig():
            from ..plotting.tsr import plot_immobility

            return plot_immobility(ds, f"{cfg.name}: immobility at G_ini = G{gi:.3g}",
                                   stick=cfg.system.liquid is None, speed_unit=du.unit("speed"))

        res = {"study": "immobility", "machine": cfg.name, "grade_G_mm_s": G,
               **immobility_summary(ds, cfg.spin.nominal_speed)}
        res.update(_finish(ds, cfg, out, plot, fig, "study immobility", t0))
    if json_:
        print_json(res)
        return
    typer.echo(f"{cfg.name} at G_ini = G{gi:.3g}: least immobility {100 * res['least_immobility']:.1f} % "
               f"at {du.fmt(res['least_immobility_speed_rad_s'], 'speed')}; natural frequency "
               f"{du.fmt(res['natural_frequency_rad_s'], 'speed')}")
    gs = res["stick_threshold_at_nominal_grade_G_mm_s"]
    if cfg.system.liquid is not None:
        typer.echo("  beside the liquid: the balls at rest on the rotor's steady orbit with the "
                   "quasi-static liquid (docs/liquid/stability.md sec. 3k); no stick threshold G* (a "
                   "closed form of the balls alone)")
        if "ring_holds" in res:
            typer.echo(_ring_holds_text(res["ring_holds"], res["speeds_rad_s"], du))
        return
    typer.echo(f"  stick threshold at the nominal speed: G*{gs:.3g} mm/s "
               f"({'below' if gs <= G else 'above'} the target {grade_text(G)}): balls that "
               "stop at this speed leave about this grade")


def _ring_holds_text(share, speeds, du) -> str:
    """The text line of `study immobility` beside a liquid on a horizontal axis: where the
    steady orbit keeps the rings intact under gravity's offset (share [-] per speed [rad/s])."""
    import numpy as np

    full = speeds[share >= 1.0]
    where = (f"every configuration's from {du.fmt(float(full.min()), 'speed')}" if full.size
             else f"at most {100 * float(np.nanmax(share)):.0f} % of the configurations'")
    return ("  horizontal axis: the liquid's orbit is planar (gravity's offset g/Omega^2 of its "
            f"surface left out, its pull on the balls kept); exact while the rings hold, {where} "
            "(elsewhere first order in g/(Omega^2 R); ring_holds in --json and --out)")


def _factors(spec: str, name: str) -> tuple:
    """A list of positive factors [-], e.g. '0.5,1,2' (:func:`autobalance.config.ranges.
    parse_list` of dimensionless numbers), for the option ``name`` as typed."""
    from ..config.ranges import parse_list

    vals = tuple(float(v) for v in parse_list(spec, "ratio", name))
    if any(v <= 0 for v in vals):
        raise ConfigError(f"{name} = {spec!r}: expected positive numbers, e.g. '0.5,1,2'")
    return vals
