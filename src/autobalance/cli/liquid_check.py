"""``autobalance liquid kinetostatic-check``: 001's kinetostatic laws against the liquid from
physics on a machine (:func:`autobalance.liquid.kinetostatic_check.kinetostatic_vs_physics`;
docs/liquid/kinetostatics.md sec. 2b). Registered on the liquid group (:mod:`autobalance.cli.liquid`)."""
from __future__ import annotations

from typing import Annotated, Optional

import typer

from ..config import ConfigError
from ..config.ranges import VALUES_METAVAR, grammar_help
from .common import JsonOpt, PlotOpt, SetOpt, UnitsOpt
from .liquid import _check_plot, _increasing, _list, _machine, _out, _q, app
from .liquid_figures import save_plot


@app.command("kinetostatic-check")
def kinetostatic_check(source: Annotated[str, typer.Argument(
                           metavar="PRESET|CONFIG", help="A machine with a [liquid] section "
                           "(one chamber, vertical axis).")] = "leblanc_003",
                       sets: SetOpt = None,
                       liquid: Annotated[Optional[str], typer.Option(
                           help="One of 001's liquids (sets density and viscosity).")] = None,
                       omega: Annotated[Optional[str], typer.Option(
                           "--speeds", metavar=VALUES_METAVAR, help=grammar_help(
                           "Speeds", "40:100 rad/s:13", tail="increasing; default 13 speeds "
                           "from 0.75 omega_n to 1.85 omega_n or the nominal speed"))] = None,
                       settle: Annotated[str, typer.Option(
                           help="Also run the coupled film this long at each speed ('0 s': "
                                "the quasi-static liquid only).")] = "4 s",
                       as_json: JsonOpt = False, plot: PlotOpt = None,
                       units: UnitsOpt = None):
    """001's liquid angle (eq 3), friction angle (eq 6) and residual (eq 1) against the liquid
    from physics, speed by speed.\f

    Parameters
    ----------
    source : str
        Preset name or .toml file of the machine (one chamber on a vertical axis).
    sets : list of str
        ``PATH=VALUE`` overrides (``--set``).
    liquid : str
        One of 001's liquids (density and viscosity); default the machine's.
    omega : str or None
        Increasing speeds [rad/s, or with units]; None: 13 from 0.75 omega_n to the larger of
        1.85 omega_n and the nominal speed (:func:`autobalance.studies.liquid_response.
        machine_speeds`).
    settle : str
        Time of each coupled-film run [s, or with units]; 0: none.
    as_json : bool
        One JSON object instead of text.
    plot : str
        Figure (.png, .pdf, .svg): the liquid's angle and the residual against speed.
    units : str
        Units of the text's speeds (JSON stays SI): default as written in the machine's config.
    """
    from ..config.display import display_units
    from ..liquid.kinetostatic_check import kinetostatic_vs_physics
    from ..plotting.liquid_check import kinetostatic_check_figure

    from ..studies.liquid_response import liquid_machine

    cfg = _machine(source, sets, None, liquid, None, None)
    m = liquid_machine(cfg.system)
    rot, bal, chambers = m.rotor, m.balancer, m.chambers
    L = cfg.system.liquid
    if bal is None:
        raise ConfigError(f"liquid.chamber_radius = {list(L.chamber_radius)}: 001's laws take "
                          "one chamber")
    L.vertical("for 001's kinetostatic laws (a vertical rotor)")
    _check_plot(plot, source)
    if omega is None:
        from ..studies.liquid_response import machine_speeds

        ws = [float(w) for w in machine_speeds(cfg.system, cfg.spin.nominal_speed, 13,
                                               low=0.75, high=1.85, high_nominal=1.0)]
    else:
        ws = _list(omega, "speed", "--speeds")
        _increasing(ws, omega, "must be increasing speeds > 0")
    t = _q(settle, "time", "settle")
    if not 0 <= t <= 60:
        raise ConfigError(f"--settle = {settle!r}: must be 0-60 s")
    res = kinetostatic_vs_physics(rot, chambers[0], L.density, L.kinematic_viscosity, ws,
                                  arc=bal.arc, settle_time=t)
    out = {"machine": cfg.name, "liquid": liquid or bal.liquid.name, "density_kg_m3": L.density,
           "kinematic_viscosity_m2_s": L.kinematic_viscosity, "arc_rad": bal.arc,
           "settle_s": t, **res}
    if plot:
        save_plot(kinetostatic_check_figure(res, f"{cfg.name}: 001's kinetostatics against the "
                                            "liquid from physics"), plot)
        out["plot"] = plot
    if as_json:
        _out(out, True)
        return
    _table(out, display_units(cfg, units))


def _table(out: dict, du) -> None:
    """The comparison as a table, one speed per row, speeds in ``du``'s unit (a DisplayUnits),
    angles in degrees."""
    film = "alpha_film_deg" in out
    typer.echo(f"{out['machine']}: {out['liquid']} (rho {out['density_kg_m3']:g} kg/m^3, nu "
               f"{out['kinematic_viscosity_m2_s']:.3g} m^2/s); angles from the unbalance D [deg]")
    head = (f"{'omega[' + du.unit('speed') + ']':>10}  delta     k   alpha_qs"
            + ("  alpha_film" if film else "")
            + "  alpha0(001)  beta(001)  ec/e  ec/e(001)")
    typer.echo(head)
    for i, w in enumerate(out["omega_rad_s"]):
        row = (f"{w * du.factor('speed'):10.4g} {out['delta_deg'][i]:6.1f} {out['k'][i]:5.3f} "
               f"{out['alpha_deg'][i]:10.1f}")
        if film:
            row += f" {out['alpha_film_deg'][i]:11.1f}"
        row += (f" {out['alpha0_deg'][i]:12.1f} {out['beta_deg'][i]:10.2f} "
                f"{out['ec_over_e'][i]:5.3f} {out['ec_over_e_001'][i]:10.3f}")
        typer.echo(row)
    typer.echo("nan: no liquid ring (below the entrainment speed) or no root of 001 eq 2 "
               "(k < sin delta)")
