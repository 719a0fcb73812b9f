"""``autobalance study fill-map``: the fill map of any liquid-balancer machine
(:mod:`autobalance.studies._fill_map`). Registered on the ``study`` app by :mod:`autobalance.cli`."""
from __future__ import annotations

import time
from typing import Annotated, Optional

import typer

from ..config.ranges import VALUES_METAVAR, grammar_help
from .common import (ExecutorOpt, JsonOpt, PlotOpt, ProfileOpt, SetOpt, SourceArg, UnitsOpt,
                     WorkersOpt, guard, print_json)
from .study import OutOpt, QuickOpt, _finish, _prepare, app

__all__ = ["fill_map"]


@app.command("fill-map")
def fill_map(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
             units: UnitsOpt = None,
             fills: Annotated[Optional[str], typer.Option(
                 "--fills", metavar=VALUES_METAVAR, help=grammar_help(
                     "Fills", "50:350 ml:7", tail="default 0.25-2.5 times the machine's, 10 "
                                                 "fills"))] = None,
             speeds: Annotated[Optional[str], typer.Option(
                 "--speeds", metavar=VALUES_METAVAR, help=grammar_help(
                     "Speeds", "200:1000 rpm:81", tail="default 0.3-2 times the natural "
                                                      "frequency"))] = None,
             dynamic: Annotated[bool, typer.Option(
                 "--dynamic", help="Also run the wall film coupled with the rotor at constant "
                                   "speeds (up to 8, --quick 4, above every fill's entrainment "
                                   "speed): is the steady synchronous whirl reached?")] = False,
             duration: Annotated[Optional[str], typer.Option(
                 "--duration", help="Time at each speed of --dynamic, e.g. '10 s' (default "
                                    "6 s).")] = None,
             linear: Annotated[bool, typer.Option(
                 "--linear", help="Also the linear stability of the balanced state at every "
                                  "fill and speed (vertical axis; 0.02 s per point on 64 "
                                  "cells).")] = False,
             workers: WorkersOpt = None, executor: ExecutorOpt = None,
             quick: QuickOpt = False, out: OutOpt = None, plot: PlotOpt = None,
             json_: JsonOpt = False) -> None:
    """A liquid balancer's steady whirl over fill x speed with the liquid from physics (the
    quasi-static liquid in the displaced chamber; 003 Fig. 5-6 for any vertical-axis machine):
    where each fill balances, the resonance it gives, and the least fill that balances best at
    the nominal speed.\f

    Parameters
    ----------
    source, set_, profile, units, quick, out, plot, json_
        The options of every study (:mod:`autobalance.cli.study`).
    fills : str or None
        Fill volumes [m^3 or with units]: a range or a list
        (:func:`autobalance.config.ranges.parse_values`).
    speeds : str or None
        Speeds [rad/s or with units]: a range or a list.
    dynamic : bool
        Add the stability map (:func:`autobalance.studies._fill_map.compute_stability_map`).
    linear : bool
        Add the balanced state's linear stability (:func:`autobalance.studies.fill_map.
        compute_linear_map`).
    duration : str or None
        Time at each speed of the stability map [s or with units] (None: the library's).
    workers, executor
        The sweep's processes (:mod:`autobalance.cli.common`).
    """
    from ..config import parse_quantity
    from ..studies._fill_map import compute_fill_study, fill_map_summary
    from .liquid import _list

    t0 = time.perf_counter()
    with guard():
        cfg, _, du = _prepare(source, set_, profile, 16.0, plot, out, units=units,
                              balls="liquid", workers=workers, executor=executor)
        T = None if duration is None else parse_quantity(duration, "time", "--duration")
        V = None if fills is None else _list(fills, "volume", "--fills")
        W = None if speeds is None else _list(speeds, "speed", "--speeds")
        ds = compute_fill_study(cfg, fills=V, speeds=W, quick=quick, linear=linear,
                                dynamic=dynamic, duration=T, executor=executor, workers=workers,
                                progress=not json_)

        def fig():
            from ..plotting.liquid import fill_map_figure

            return fill_map_figure(ds, du.unit("speed"), du.factor("speed"),
                                   f"{cfg.name}: fill map (liquid from physics)")

        res = fill_map_summary(ds)
        res.update(_finish(ds, cfg, out, plot, fig, "study fill-map", t0))
    if json_:
        print_json(res)
        return
    typer.echo(f"{cfg.name}: fill map, {ds['fill'].size} fills x {ds['speed'].size} speeds "
               f"(resonance without liquid {du.fmt(res['resonance_without_liquid_rad_s'], 'speed')})")
    ring = "entrained" if ds.attrs.get("axis", "vertical") == "vertical" else "a ring"
    if "chamber_fill" in ds:
        typer.echo(f"  (fills: the total of {ds['chamber'].size} concentric chambers, each "
                   "scaled alike from the machine's)")
    for i, f in enumerate(res["fills"]):
        b = f["balances_from_rad_s"]
        each = "" if "chamber_fill" not in ds else " (" + " + ".join(
            f"{x * 1e6:.4g}" for x in ds["chamber_fill"].values[i]) + ")"
        typer.echo(f"  {f['fill_m3'] * 1e6:7.1f} ml{each}: resonance {du.fmt(f['resonance_rad_s'], 'speed')}, "
                   f"{ring} from {du.fmt(f['entrainment_speed_rad_s'], 'speed')}, balances "
                   + ("nowhere on the grid" if b is None else f"from {du.fmt(b, 'speed')}")
                   + f"; efficiency {f['efficiency_at_nominal']:.3g} at the nominal speed")
        if "balanced_unstable_rad_s" in f:
            u = f["balanced_unstable_rad_s"]
            film = any(g == g for g in ds["growth_rate"].values[i])     # not all NaN
            typer.echo("           balanced state " + (
                "unstable at " + ", ".join(f"{du.fmt(lo, 'speed')}-{du.fmt(hi, 'speed')}"
                                           for lo, hi in u) if u else "stable on the grid"
                if film else "not decided (no film on the grid)"))
    if "not_steady" in res:
        n = len(ds["dynamic_speed"])
        typer.echo(f"  coupled film at {', '.join(du.fmt(w, 'speed') for w in ds['dynamic_speed'].values)}"
                   f", {T:g} s each: the synchronous whirl is reached at")
        for i, v in enumerate(ds["fill"].values):
            ok = [du.fmt(w, "speed") for w, st in zip(ds["dynamic_speed"].values,
                                                       ds["steady"].values[i]) if st]
            typer.echo(f"    {v * 1e6:7.1f} ml: {len(ok)} of {n}" + (f" ({', '.join(ok)})"
                                                                   if 0 < len(ok) < n else ""))
        typer.echo("    (not reached: an asynchronous whirl or a transient slower than the run; "
                   "a longer --duration separates them)")
    typer.echo(f"  at {du.fmt(res['speed_on_grid_rad_s'], 'speed')}: best efficiency "
               f"{res['best_efficiency_at_nominal']:.3g}, reached (within "
               f"{100 * res['tie']:g} %) from {res['least_fill_within_tie_m3'] * 1e6:.1f} ml")
    if "least_stable_fill_within_tie_m3" in res:
        v = res["least_stable_fill_within_tie_m3"]
        typer.echo("  with its balanced state stable there (linear): " + (
            "no fill within the tie" if v is None else f"from {v * 1e6:.1f} ml"))
    for key in ("out", "plot"):
        if key in res:
            typer.echo(f"wrote {res[key]}")
