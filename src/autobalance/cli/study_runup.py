"""``autobalance study runup``: the run-up of any machine, with and without its balls
(:mod:`autobalance.studies._runup`). Registered on the ``study`` app by :mod:`autobalance.cli`."""
from __future__ import annotations

import math
import time
from typing import Annotated, Optional

import typer

from ..config import ConfigError
from .common import (JsonOpt, PlotOpt, ProfileOpt, SetOpt, SourceArg, UnitsOpt, guard,
                     print_json)
from .study import OutOpt, _finish, _prepare, app

__all__ = ["runup"]


@app.command("runup")
def runup(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
          units: UnitsOpt = None,
          law: Annotated[Optional[str], typer.Option(
              "--law", help="Torque laws to compare for a motor-driven machine: "
                            "'constant,linear,harmonic' or 'all' (default: the config's).")] = None,
          bare: Annotated[bool, typer.Option(
              "--bare/--no-bare", help="Also run without the balls (the amplitude ratio).")] = True,
          fraction: Annotated[float, typer.Option(
              "--threshold", help="Balancing threshold as a fraction of e = U/M_t [-].")] = 0.05,
          out: OutOpt = None, plot: PlotOpt = None, json_: JsonOpt = False) -> None:
    """The run-up: time to full speed, whirl through resonance with and without the balls,
    ball travel, balancing time and the grade it leaves (000 Tables 1-2, Fig. 10-11, for any
    machine; the torque laws of a motor drive side by side).\f

    Parameters
    ----------
    source, set_, profile, units, out, plot, json_
        The options of every study (:mod:`autobalance.cli.study`).
    law : str or None
        Comma-separated torque laws, or "all" (motor-driven machines only).
    bare : bool
        Also simulate the machine without its balls.
    fraction : float
        Threshold of the balancing time as a fraction of the rotor's eccentricity [-].
    """
    from ..models import MotorDrive
    from ..studies._runup import compute_runup, runup_summary

    t0 = time.perf_counter()
    with guard():
        cfg, _, du = _prepare(source, set_, profile, 16.0, plot, out, units=units,
                              balls="balancer")
        if not (math.isfinite(fraction) and fraction > 0):
            raise ConfigError(f"--threshold = {fraction}: must be a number > 0, e.g. 0.05")
        laws = None
        if law is not None:
            laws = (MotorDrive.LAWS if law.strip() == "all"
                    else tuple(x.strip() for x in law.split(",") if x.strip()))
            bad = [x for x in laws if x not in MotorDrive.LAWS]
            if bad or not laws:
                raise ConfigError(f"--law = {law!r}: must be 'all' or a comma-separated list of "
                                  f"{', '.join(MotorDrive.LAWS)}")
            if not isinstance(cfg.spin, MotorDrive):
                raise ConfigError(f"--law = {law!r}: needs a motor-driven machine ([profile] "
                                  f"kind = \"motor\"); {cfg.name} has a prescribed profile")
        ds = compute_runup(cfg, laws=laws, bare=bare, fraction=fraction)

        def fig():
            from ..plotting.runup import plot_runup

            return plot_runup(ds, du.unit("speed"), f"{cfg.name}: run-up")

        res = runup_summary(ds)
        res.update(_finish(ds, cfg, out, plot, fig, "study runup", t0))
    if json_:
        print_json(res)
        return
    e = res["eccentricity_m"]
    typer.echo(f"{cfg.name}: run-up to {du.fmt(res['nominal_speed_rad_s'], 'speed')} "
               f"(natural frequencies {', '.join(du.fmt(w, 'speed') for w in res['natural_frequencies_rad_s'])}; "
               f"e = U/M_t = {du.fmt(e, 'length')})")
    T = float(ds["time"].values[-1])
    for name, c in res["cases"].items():
        ts = c["t_speed_s"]
        line = f"  {name}: full speed {'never reached' if ts is None else f'at {ts:.2f} s'}"
        if c.get("t_speed_unloaded_s") is not None:
            line += f" (unloaded drive, closed form: {c['t_speed_unloaded_s']:.2f} s)"
        line += f"; whirl peak {du.fmt(c['max_amplitude_m'], 'length')}"
        if "amplitude_ratio" in c:
            what = ds.attrs.get("balancer", "balls")
            line += (f" with the {what}, {du.fmt(c['max_amplitude_bare_m'], 'length')} without "
                     f"(x{c['amplitude_ratio']:.2f})")
        tb = c["balancing_time_s"]
        when = ("still above at the end" if tb >= T - 1e-9 else f"last above at {tb:.2f} s")
        typer.echo(line)
        rev = c["ball_revolutions"]
        travel = "" if rev is None else f"balls travel {rev:.2f} rev relative to the rotor; "
        typer.echo(f"    {travel}whirl "
                   f"{100 * res['balancing_fraction']:g} % of e: {when}; final grade "
                   f"G{c['final_grade_G_mm_s']:.3g} mm/s")
