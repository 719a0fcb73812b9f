"""``autobalance liquid spinup`` on a horizontal axis: the liquid in time from a puddle at rest
(or from a ring, for a profile that starts turning) through the machine's profile
(:func:`autobalance.liquid.rimming.horizontal_spinup`; docs/liquid/horizontal-axis.md sec. 3n)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
import typer

from .common import print_json

if TYPE_CHECKING:
    from ..config import Config
    from ..liquid.rimming import RimSpinUp
    from ..models import LiquidDevice

#: What each end of a run means, for the text [-].
ENDS = {"closed": "closed into a ring",
        "broken": "the ring broke: liquid at its top no longer held",
        "end": "no event by the profile's end",
        "unheld": "left the model: more than 1 % of the liquid where nothing holds it on the "
                  "wall (a real liquid falls)",
        "too_thick": "left the model: a layer thicker than the chamber's gap"}


def chamber_report(run: RimSpinUp, chamber: LiquidDevice, down: float) -> dict:
    """One chamber's run as the command reports it (SI; angles in degrees, named so): its end,
    and the liquid's centre of mass there, its angle measured from the bottom in the turning
    direction (up the rising wall).

    Parameters
    ----------
    run : autobalance.liquid.rimming.RimSpinUp
        Its run.
    chamber : autobalance.models.LiquidDevice
        Its chamber (R, r_i [m], V [m^3]).
    down : float
        Gravity's inertial angle [rad].
    """
    m = run.moment[-1]
    up = float(np.degrees(np.angle(m * np.exp(-1j * down))))
    mean = chamber.volume / (2 * math.pi * run.radius * run.height)
    return {"chamber_radius_m": chamber.chamber_radius, "inner_radius_m": chamber.inner_radius,
            "volume_m3": chamber.volume, "status": run.status,
            "stop_time_s": run.stop_time, "stop_speed_rad_s": run.stop_speed,
            "liquid_speed_at_stop_rad_s": float(run.liquid_speed[-1]),
            "centre_of_mass_m": float(abs(m) / chamber.volume),
            "centre_of_mass_from_bottom_deg": up,
            "thinnest_over_mean": float(run.depth[-1].min() / mean),
            "thickest_over_mean": float(run.depth[-1].max() / mean),
            "most_held_by_nothing": run.most_loose, "steps": run.steps}


def horizontal_spinup_command(cfg: Config, cells: int, plot: str | None,
                              as_json: bool) -> None:
    """Run and print ``liquid spinup`` for a machine on a horizontal axis (module docstring).

    Parameters
    ----------
    cfg : autobalance.config.Config
        The loaded machine and profile.
    cells : int
        Cells around each wall [-].
    plot : str or None
        Figure file.
    as_json : bool
        One JSON object.
    """
    from ..config.display import display_units
    from ..liquid.rimming import horizontal_spinup
    from ..liquid.start import film_start_speed
    from .liquid_figures import chamber_label

    s = cfg.system
    runs = horizontal_spinup(s, cfg.spin, n_cells=cells)
    w_f = film_start_speed(s.liquid, s.gravity.g)
    chambers = [chamber_report(r, c, s.gravity.direction) for r, c in zip(runs, s.liquid.chambers)]
    out = {"system": s.name, "profile": getattr(cfg.spin, "name", ""), "axis": "horizontal",
           "model": "circumferential shallow water, the liquid's own rotation and gravity "
                    "normal to the wall, second order (autobalance.liquid.rimming)",
           "cells": cells, "film_start_rad_s": w_f, "chambers": chambers}
    du = display_units(cfg)                     # speeds and lengths as the config writes them
    if plot:
        from ..plotting.rimming import rimming_figure
        from .liquid_figures import save_plot

        fig = rimming_figure(runs, [chamber_label(du, c.chamber_radius, c.volume)
                                    for c in s.liquid.chambers], w_f,
                             f"{s.name}: the liquid on its horizontal axis")
        save_plot(fig, plot)
        out["plot"] = str(plot)
    if as_json:
        print_json(out)
        return
    for c in chambers:
        typer.echo(chamber_label(du, c["chamber_radius_m"], c["volume_m3"]) + ": "
                   f"{ENDS[c['status']]} at {du.fmt(c['stop_speed_rad_s'], 'speed', 5)}, "
                   f"t = {c['stop_time_s']:.3f} s; the liquid at "
                   f"{du.fmt(c['liquid_speed_at_stop_rad_s'], 'speed', 4)}, its centre of mass "
                   f"{c['centre_of_mass_m'] * 1e3:.4g} mm from the axis, "
                   f"{c['centre_of_mass_from_bottom_deg']:.4g} deg from the bottom")
    typer.echo(f"the film model starts at {du.fmt(w_f, 'speed', 5)} (g/Omega^2 = R/10)")
    if plot:
        typer.echo(f"plot: {plot}")
