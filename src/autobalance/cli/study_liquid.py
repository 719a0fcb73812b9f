"""``autobalance study fill-map``: the fill map of any liquid-balancer machine
(:mod:`autobalance.studies.fill_map`). Registered on the ``study`` app by :mod:`autobalance.cli`."""
from __future__ import annotations

import time
from typing import Annotated, Optional

import typer

from .common import JsonOpt, PlotOpt, ProfileOpt, SetOpt, SourceArg, UnitsOpt, guard, print_json
from .study import OutOpt, QuickOpt, _finish, _prepare, app

__all__ = ["fill_map"]


@app.command("fill-map")
def fill_map(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
             units: UnitsOpt = None,
             fills: Annotated[Optional[str], typer.Option(
                 "--fills", help="Fills: 'a:b:n' or 'a, b, c' with units, e.g. '50:350 ml:7' "
                                 "(default: 0.25-2.5 times the machine's, 10 fills).")] = None,
             speeds: Annotated[Optional[str], typer.Option(
                 "--speeds", help="Speeds: 'a:b:n' or 'a, b, c' with units, e.g. '20:100 1/s:81' "
                                  "(default: 0.3-2 times the natural frequency).")] = None,
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
        Fill volumes [m^3 or with units].
    speeds : str or None
        Speeds [rad/s or with units].
    """
    from ..studies.fill_map import compute_fill_map, fill_map_summary
    from .liquid import _list

    t0 = time.perf_counter()
    with guard():
        cfg, _, du = _prepare(source, set_, profile, 16.0, plot, out, units=units,
                              balls="liquid")
        V = None if fills is None else _list(fills, "volume", "--fills")
        W = None if speeds is None else _list(speeds, "speed", "--speeds")
        ds = compute_fill_map(cfg, fills=V, speeds=W, quick=quick)

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
    for f in res["fills"]:
        b = f["balances_from_rad_s"]
        typer.echo(f"  {f['fill_m3'] * 1e6:7.1f} ml: resonance {du.fmt(f['resonance_rad_s'], 'speed')}, "
                   f"entrained from {du.fmt(f['entrainment_speed_rad_s'], 'speed')}, balances "
                   + ("nowhere on the grid" if b is None else f"from {du.fmt(b, 'speed')}")
                   + f"; efficiency {f['efficiency_at_nominal']:.3g} at the nominal speed")
    typer.echo(f"  at {du.fmt(res['speed_on_grid_rad_s'], 'speed')}: best efficiency "
               f"{res['best_efficiency_at_nominal']:.3g}, reached (within "
               f"{100 * res['tie']:g} %) from {res['least_fill_within_tie_m3'] * 1e6:.1f} ml")
    for key in ("out", "plot"):
        if key in res:
            typer.echo(f"wrote {res[key]}")
