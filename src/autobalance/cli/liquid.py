"""``autobalance liquid ...``: liquid (Leblanc) balancer commands (seeds 001, 003).

Every command takes ``--json`` (one JSON object on stdout, SI, unit-suffixed keys). Values take
units: ``--volume "100 ml"``, ``--radius "0.2 m"``, ``--speeds "28 rad/s"``, ``--delta "30 deg"``.

The liquid options: ``volume`` the liquid volume [m^3], ``radius`` and ``height`` the chamber's
[m], ``omega`` the speed(s) [rad/s], ``g`` the gravity [m/s^2] (each with units, or a bare number
in SI; where several are allowed a range ``LO:HI:N`` or a list ``a, b, c unit``, the grammar of
:mod:`autobalance.config.ranges`);
``as_json`` (``--json``) one JSON object instead of text.
Input errors raise ConfigError / ParameterError / ResourceError with one-line messages; they
leave this group's commands as exceptions (so the group can be driven as a library), and
``autobalance``'s entry point (:func:`autobalance.cli.main`) prints them as ``error: ...`` and
exits with code 2.
"""
from __future__ import annotations

import math
from typing import Annotated, Optional

import numpy as np
import typer

from ..config import ConfigError
from ..config.ranges import VALUES_METAVAR, grammar_help, parse_values, written_unit
from ..jsonable import to_jsonable
from ..models import ParameterError
from .common import (JsonOpt, PlotOpt, SetOpt, UnitsOpt, as_options, check_plot, load_machine,
                     print_json)
from .liquid_figures import plot_liquid_response, save_plot

app = typer.Typer(name="liquid", no_args_is_help=True, add_completion=False,
                  rich_markup_mode=None,     # help as written: no rich markup or :emoji: codes
                  pretty_exceptions_enable=False,
                  help="Liquid (Leblanc) balancers: free surface, modes, kinetostatics, dynamics.")

VolOpt = Annotated[str, typer.Option("--volume", "-V", help="Liquid volume, e.g. '100 ml'.")]
ROpt = Annotated[str, typer.Option("--radius", "-R", help="Chamber radius, e.g. '0.2 m'.")]
HOpt = Annotated[str, typer.Option("--height", help="Chamber height, e.g. '0.05 m'.")]
GOpt = Annotated[str, typer.Option(
    "--gravity", help="Gravity; 003's printed speeds use '10 m/s^2'.")]

#: Figure formats of the liquid commands' ``--plot``.
PLOT_SUFFIXES = (".png", ".pdf", ".svg")


def _out(obj: dict, as_json: bool, units=None) -> None:
    """One JSON object, or ``key  value`` lines: with ``units``, a DisplayUnits, unit-suffixed
    numbers and lists of numbers in those units (:func:`.simulate.shown`); numbers to 4-6
    significant digits, long lists cut to their first 8 values."""
    if as_json:
        print_json(obj)
        return
    from .simulate import shown

    for k, v in to_jsonable(obj).items():
        if units is not None and not isinstance(v, bool):
            k, v = shown(k, v, units)
        if isinstance(v, list):
            items = [f"{x:.4g}" if isinstance(x, float) else str(x) for x in v[:8]]
            v = f"[{', '.join(items)}{', ...' if len(v) > 8 else ''}]"
        elif isinstance(v, float):
            v = f"{v:.6g}"
        typer.echo(f"{k:<34} {v}")


def _units(units: Optional[str], **written: str):
    """The display units of a liquid command without a machine: ``--units``, else each kind in
    the unit its option was written in (kind -> the option's text, e.g. ``speed="0:600
    rpm:4"``), SI for the others (:func:`autobalance.config.display.display_units`)."""
    from ..config.display import display_units

    if units is None:
        parts = [f"{kind}={u}" for kind, text in written.items()
                 if text and (u := written_unit(text))]
        units = ",".join(parts) or None
    return display_units(None, units)


def _q(value: str, kind: str, field: str) -> float:
    from ..config import parse_quantity
    return parse_quantity(value, kind, field)


#: Memory of one value of a range or list [B]: its result row (a dict of floats) and JSON text.
LIST_BYTES_PER_POINT = 2048
#: Help of ``--speeds`` where it takes several speeds.
OMEGA_HELP = grammar_help("Speeds", "0:60 rad/s:13")


def _increasing(ws: list[float], omega: str, allowed: str) -> None:
    """ConfigError naming ``--speeds`` unless the speeds ``ws`` [rad/s] increase and are > 0."""
    if any(b <= a for a, b in zip(ws, ws[1:])) or min(ws) <= 0:
        raise ConfigError(f"--speeds = {omega!r}: {allowed}")


def _list(value: str, kind: str, option: str) -> list[float]:
    """The values [SI unit of ``kind``] of a liquid option ``option`` (as typed, e.g.
    ``"--speeds"``): a range ``LO:HI:N`` with N >= 1 or a list ``a, b, c unit``
    (:func:`autobalance.config.ranges.parse_values`), the table within the memory limit."""
    return [float(v) for v in parse_values(value, kind, option, min_points=1,
                                           bytes_per_point=LIST_BYTES_PER_POINT)]


def _check_plot(plot: Optional[str], source: Optional[str] = None) -> None:
    """Refuse a figure file that cannot be written or is the config ``source`` ('': none)."""
    check_plot(plot or None, PLOT_SUFFIXES, inputs={"the input config file": source})


def _liquid(name: str):
    """A liquid of 001's table (papers/p001/liquids_001.toml) by name; ConfigError naming the
    known ones."""
    from ..papers.p001.liquids import liquids_001

    lq = liquids_001()
    if name not in lq:
        raise ConfigError(f"--liquid = {name!r}: one of {', '.join(lq)} (001's liquids), or "
                          "give the machine's with --set liquid.density=... "
                          "--set liquid.kinematic_viscosity=...")
    return lq[name]


@app.command()
def surface(volume: VolOpt = "100 ml", radius: ROpt = "0.2 m", height: HOpt = "0.05 m",
            omega: Annotated[str, typer.Option("--speeds", metavar=VALUES_METAVAR,
                                               help=OMEGA_HELP)] = "0, 0.6, 0.89, 10, 28, 60 rad/s",
            g: GOpt = "9.80665 m/s^2", as_json: JsonOpt = False, plot: PlotOpt = None,
            units: UnitsOpt = None):
    """Free surface z(r) = z_* + omega^2 r^2/(2g) clipped to the chamber (003 eq 2-5).\f

    Parameters
    ----------
    volume, radius, height, omega, g, as_json
        The liquid options (:mod:`autobalance.cli.liquid`); ``omega`` may list several speeds.
    plot : str
        Figure of the surfaces (.png, .pdf, .svg).
    units : str
        Units of the text: default the units the speeds and the radius were written in.
    """
    from ..liquid import free_surface, liquid_volume

    _check_plot(plot)
    V, R, h = (_q(volume, "volume", "volume"), _q(radius, "length", "radius"),
               _q(height, "length", "height"))
    gg = _q(g, "acceleration", "gravity")
    ws = _list(omega, "speed", "--speeds")
    rows = []
    for w in ws:
        fs = free_surface(w, V, R, h, gg)
        d = fs.to_dict()
        d["volume_check_m3"] = liquid_volume(fs.z_star, w, R, h, gg)
        rows.append(d)
    if plot:
        from ..liquid import surface_profiles
        from ..plotting.liquid import surface_figure
        save_plot(surface_figure(surface_profiles(ws, V, R, h, gg)), plot)
    du = _units(units, speed=omega, length=radius)
    _out({"volume_m3": V, "radius_m": R, "height_m": h, "g_m_s2": gg, "surfaces": rows,
          "plot": plot} if as_json else
         {f"omega={du.fmt(r['omega_rad_s'], 'speed')}": f"mode {r['mode']} regime "
          f"{r['regime']} z*={du.fmt(r['z_star_m'], 'length')} wall="
          f"{du.fmt(r['wall_height_m'], 'length')} r_dry={du.fmt(r['r_dry_m'], 'length')}"
          for r in rows}, as_json)


@app.command()
def speeds(volume: Annotated[str, typer.Option(
               "--volume", "-V", metavar=VALUES_METAVAR,
               help=grammar_help("Volumes", "100, 200, 300 ml"))] = "100, 200, 300 ml",
           radius: ROpt = "0.2 m", height: HOpt = "0.05 m", g: GOpt = "9.80665 m/s^2",
           gravity_fraction: Annotated[float, typer.Option(help="Mode-1 criterion f: centre "
                                                           "sunk by f*h0.")] = 0.25,
           as_json: JsonOpt = False, units: UnitsOpt = None):
    """Mode-change speeds: bottom touch (003 eq 4), lid touch, entrainment omega_0 (003 eq 6).\f

    Parameters
    ----------
    volume, radius, height, g, as_json
        The liquid options (:mod:`autobalance.cli.liquid`); ``volume`` may list several volumes.
    gravity_fraction : float
        Mode-1 criterion f [-]: the centre of the surface sunk by f*h0.
    units : str
        Units of the text: default SI (rad/s).
    """
    from ..liquid import mode_speeds

    R, h, gg = _q(radius, "length", "radius"), _q(height, "length", "height"), \
        _q(g, "acceleration", "g")
    vols = _list(volume, "volume", "--volume")
    rows = [dict(volume_m3=V, **mode_speeds(V, R, h, gg, gravity_fraction)) for V in vols]
    sp = _units(units).fmt
    _out({"radius_m": R, "height_m": h, "g_m_s2": gg, "speeds": rows} if as_json else
         {f"V={r['volume_m3'] * 1e6:.4g} ml": f"omega_1={sp(r['omega_1_rad_s'], 'speed')} "
          f"omega_2={sp(r['omega_2_rad_s'], 'speed')} bottom="
          f"{sp(r['bottom_touch_rad_s'], 'speed')} omega_0={sp(r['omega_0_rad_s'], 'speed')}"
          for r in rows}, as_json)


@app.command()
def modes(volume: VolOpt = "300 ml", radius: ROpt = "0.2 m", height: HOpt = "0.05 m",
          omega: Annotated[str, typer.Option("--speeds", metavar=VALUES_METAVAR,
                                               help=OMEGA_HELP)] = "0:60 rad/s:13",
          g: GOpt = "9.80665 m/s^2", as_json: JsonOpt = False, units: UnitsOpt = None):
    """003 motion mode (1..4) at each speed.\f

    Parameters
    ----------
    volume, radius, height, omega, g, as_json
        The liquid options (:mod:`autobalance.cli.liquid`); one mode per speed of ``omega``.
    units : str
        Units of the text: default the unit the speeds were written in.
    """
    from ..liquid import MODE_NAMES, mode_speeds, motion_mode

    V, R, h = (_q(volume, "volume", "volume"), _q(radius, "length", "radius"),
               _q(height, "length", "height"))
    gg = _q(g, "acceleration", "gravity")
    ws = _list(omega, "speed", "--speeds")
    m = [motion_mode(w, V, R, h, gg) for w in ws]
    _out({"volume_m3": V, "omega_rad_s": ws, "mode": m,
          "mode_name": [MODE_NAMES[i] for i in m], **mode_speeds(V, R, h, gg)}, as_json,
         None if as_json else _units(units, speed=omega))


@app.command()
def kinetostatic(delta: Annotated[str, typer.Option(
                     metavar=VALUES_METAVAR,
                     help=grammar_help("Rotor phase angles", "10, 30, 60 deg"))] = "10, 30, 60 deg",
                 k: Annotated[float, typer.Option(help="k = D0/D.")] = 1.1,
                 liquid: Annotated[str, typer.Option(help="Liquid of liquids_001 for beta.")] = "water",
                 volume: VolOpt = "150 ml", radius: ROpt = "0.2 m",
                 omega: Annotated[str, typer.Option("--speed", help="Speed for beta.")] = (
                     "30 rad/s"),
                 arc: Annotated[str, typer.Option(help="Liquid arc xi (001 eq 5).")] = "180 deg",
                 as_json: JsonOpt = False, units: UnitsOpt = None):
    """Liquid angle alpha0 (001 eq 3), e_c/e, lambda0 (001 eq 4), friction angle beta (eq 6).\f

    Parameters
    ----------
    delta : str
        Rotor phase angle(s) [rad or with units].
    k : float
        Capacity ratio k = D0/D [-], > 0.
    liquid : str
        Liquid of liquids_001 (for the friction angle beta).
    volume, radius, omega, as_json
        The liquid options (:mod:`autobalance.cli.liquid`); ``omega`` is the speed for beta.
    arc : str
        Liquid arc xi [rad or with units] (001 eq 5).
    units : str
        Units of the text: default the unit the speed was written in.
    """
    from ..liquid import (alpha0, alpha0_residual, balancing_efficiency, eccentricity_ratio,
                          friction_angle, friction_tan_bound, residual_lambda0)

    ds = np.array(_list(delta, "angle", "--delta"))
    if k <= 0 or not math.isfinite(k):
        raise ParameterError("k", k, "k = D0/D must be > 0 and finite")
    L = _liquid(liquid)
    V, R = _q(volume, "volume", "volume"), _q(radius, "length", "radius")
    w = _q(omega, "speed", "speed")
    xi = _q(arc, "angle", "arc")
    a0 = alpha0(ds, k)
    beta = float(friction_angle(L.dynamic_viscosity, R, xi, L.density * V, w))
    _out({"k": k, "delta_deg": np.degrees(ds), "alpha0_deg": np.degrees(a0),
          "eq2_residual": alpha0_residual(a0, ds, k),
          "ec_over_e": eccentricity_ratio(k, a0), "lambda0": residual_lambda0(k, a0),
          "liquid": liquid, "density_kg_m3": L.density,
          "kinematic_viscosity_m2_s": L.kinematic_viscosity, "omega_rad_s": w,
          "beta_deg": math.degrees(beta),
          "tan_beta_bound": float(friction_tan_bound(L.dynamic_viscosity, R, xi,
                                                     L.density * V, w)),
          "efficiency_with_friction": balancing_efficiency(k, ds, beta)}, as_json,
         None if as_json else _units(units, speed=omega))


def _machine(source, sets, radius, liquid, volume, unbalance):
    """The machine of ``liquid simulate`` with its ``--set`` and the shortcut options: the
    shortcuts are overrides of the machine's own keys (``--volume`` is ``liquid.volume``,
    ``--radius`` ``liquid.chamber_radius``, ``--unbalance`` ``rotor.unbalance``; ``--liquid``
    sets 001's density and viscosity); the suspension keeps its values."""
    sets = list(sets or [])
    for key, value in (("liquid.volume", volume), ("liquid.chamber_radius", radius),
                       ("rotor.unbalance", unbalance)):
        if value:
            sets.append(f"{key}={value}")
    if liquid:
        L = _liquid(liquid)
        sets += [f"liquid.density={L.density!r}",
                 f"liquid.kinematic_viscosity={L.kinematic_viscosity!r}"]
    return load_machine(source, sets, balls="liquid")


@app.command(hidden=True)
def simulate(source: Annotated[str, typer.Argument(
                 metavar="PRESET|CONFIG", help="A machine with a [liquid] section (either "
                 "axis).")] = "leblanc_003",
             sets: SetOpt = None,
             volume: Annotated[Optional[str], typer.Option(
                 "--volume", "-V", help="Shortcut for --set liquid.volume=...")] = None,
             radius: Annotated[Optional[str], typer.Option(
                 "--radius", "-R", help="Shortcut for --set liquid.chamber_radius=...")] = None,
             unbalance: Annotated[Optional[str], typer.Option(
                 help="Shortcut for --set rotor.unbalance=..., e.g. '2000 g*cm'.")] = None,
             liquid: Annotated[Optional[str], typer.Option(
                 help="One of 001's liquids (sets density and viscosity).")] = None,
             placement: Annotated[Optional[str], typer.Option(
                 help="drach | deflection (the lumped model's law)")] = None,
             omega: Annotated[str, typer.Option(
                 "--speeds", metavar=VALUES_METAVAR, help=grammar_help(
                 "Steady speeds", "5:100 rad/s:96", tail="increasing and > 0 for --model "
                 "physical"))] = "5:100 rad/s:96",
             run: Annotated[bool, typer.Option("--run-up/--no-run-up",
                                               help="Also integrate the run-up.")] = False,
             fill: Annotated[bool, typer.Option("--fill-sweep", help="Amplitude vs fill at "
                                                "0.6, 0.8, 1, 1.2 omega_n (003 Fig. 5).")] = False,
             model_kind: Annotated[str, typer.Option(
                 "--model", help="physical (the liquid in the displaced chamber; the run-up "
                                 "couples the wall film and starts at omega_0) or lumped (the "
                                 "calibrated engagement of the first release).")] = "physical",
             as_json: JsonOpt = False, plot: PlotOpt = None, units: UnitsOpt = None):
    """Deprecated (goes in 0.4.0): use response (the steady response against speed, --fill-sweep
    against fill) and simulate (the run-up through the profile).\f

    The machine is any config with a ``[liquid]`` section (default the ``leblanc_003``
    preset, 003's bench); ``autobalance simulate`` runs it through its own profile with the
    coupled film instead. On a horizontal axis (physical model only) the liquid is a puddle
    below the film's start g/Omega^2 = R/10 and the planar ring above it (as ``study
    fill-map``; docs/liquid/stability.md sec. 3k), and the run-up is the film model's with gravity.

    Parameters
    ----------
    source : str
        Preset name or .toml file of the machine.
    sets : list of str
        ``PATH=VALUE`` overrides (``--set``).
    volume, radius, unbalance, liquid : str
        Shortcuts for overrides: the liquid volume [m^3], chamber radius [m], rotor unbalance
        [kg m] (with units or bare SI), one of 001's liquids; default the machine's.
    placement : str
        The lumped model's placement law, drach or deflection (default drach).
    omega, as_json
        The liquid options (:mod:`autobalance.cli.liquid`); ``omega`` lists the steady speeds.
    run : bool
        Also integrate a linear run-up from rest to the profile's nominal speed over its
        duration (leblanc_003: 0 -> 100 rad/s in 20 s).
    fill : bool
        Amplitude vs fill at 0.6, 0.8, 1, 1.2 omega_n (003 Fig. 5), over the fill map's default
        fills (:func:`autobalance.studies._fill_map.default_fills`).
    model_kind : str
        "physical" (docs/liquid/models.md sec. 3b-3d) or "lumped" (sec. 3).
    plot : str
        Figure (.png, .pdf, .svg): the response, or the fill sweep with ``--fill-sweep``.
    units : str
        Units of the text (JSON stays SI): default as written in the machine's config.
    """
    from ..config.display import display_units
    from ..studies.liquid_response import liquid_response, liquid_run_up

    if model_kind not in ("lumped", "physical"):
        raise ConfigError(f"--model = {model_kind!r}: must be 'physical' or 'lumped'")
    cfg = _machine(source, sets, radius, liquid, volume, unbalance)
    _check_plot(plot, source)
    ws = _list(omega, "speed", "--speeds")
    if model_kind == "physical":
        _increasing(ws, omega, "the physical model needs increasing speeds > 0")
    with as_options({"model": "--model", "model.placement": "--placement"}):
        out = {"machine": cfg.name, **liquid_response(cfg.system, ws, model=model_kind,
                                                      placement=placement, fill_sweep=fill)}
        if liquid and out["chambers"] == 1:
            out["liquid"] = liquid
        if run:
            out["run_up"] = liquid_run_up(cfg.system, float(cfg.spin.nominal_speed),
                                          float(cfg.spin.duration), model=model_kind,
                                          placement=placement)
    _liquid_text_or_json(cfg, out, plot, as_json, units)


def _liquid_text_or_json(cfg, out: dict, plot: Optional[str], as_json: bool,
                         units: Optional[str]) -> None:
    """Print a liquid machine's steady response (:func:`autobalance.studies.liquid_response.
    liquid_response`, with its run-up under ``run_up``) as JSON or as text in the config's
    units (or ``units``), after writing its figure to ``plot``."""
    from ..config.display import display_units
    from ..studies.liquid_response import liquid_machine

    ru = out.pop("run_up", None)
    if ru is not None:
        out["run_up"] = ru.summary()
    if plot:
        m = liquid_machine(cfg.system, out["model"], out["placement"])
        plot_liquid_response(plot, out, out["omega_0_rad_s"], out["omega_n_rad_s"], ru,
                             out.get("fill_sweep"), cfg.system.liquid, out["liquid"], m.rotor,
                             m.lumped, "physical model" if m.physical else None)
        out["plot"] = plot
    if not as_json:
        out = {k: v for k, v in out.items() if not isinstance(v, (np.ndarray, list, dict))} | {
            "max_amplitude_m": float(np.nanmax(out["amplitude_m"])),
            "max_amplitude_dry_m": float(np.max(out["amplitude_dry_m"]))}
    _out(out, as_json, None if as_json else display_units(cfg, units))


@app.command()
def spinup(source: Annotated[str, typer.Argument(
               metavar="PRESET|CONFIG", help="A machine with a [liquid] section; its profile "
               "from rest.")] = "leblanc_003",
           sets: SetOpt = None,
           cells: Annotated[Optional[int], typer.Option(
               "--cells", help="Cells per chamber (vertical: 100 of equal bottom area; "
               "horizontal: 256 around the wall).")] = None,
           plot: PlotOpt = None, as_json: JsonOpt = False):
    """The liquid's spin-up from rest through 003's modes 1-3 until it reaches the lid (mode 4,
    the entrainment), from the axisymmetric shallow-water model (docs/liquid/spin-up.md sec. 3h),
    beside 003 eq 4 and eq 6's quasi-static speeds. On a horizontal axis the liquid in time
    around the wall from a puddle at rest, or from a ring if the profile starts turning, until
    it closes into a ring, breaks, or leaves the model (docs/liquid/horizontal-axis.md sec. 3n).\f

    Parameters
    ----------
    source : str
        Preset or config with a ``[liquid]`` section.
    sets : list of str
        ``--set`` overrides (e.g. ``profile.ramp_time=60 s``, ``liquid.volume=300 ml``).
    cells : int or None
        Cells per chamber [-] (None: 100 on a vertical axis, 256 on a horizontal one).
    plot : str or None
        Figure file (liquid speed vs chamber speed; depth at the lid).
    as_json : bool
        One JSON object.
    """
    from ..liquid import mode_speeds
    from ..models.liquid_balancer import G_STANDARD
    from ..liquid.spinup import spinup_of
    from ..liquid.steady import start_speed

    _check_plot(plot, source)
    cfg = load_machine(source, sets, balls="liquid")
    with as_options({"n_cells": "--cells"}):
        if cfg.system.liquid.axis == "horizontal":
            from .liquid_rimming import horizontal_spinup_command
            return horizontal_spinup_command(cfg, 256 if cells is None else cells, plot,
                                             as_json)
        cells = 100 if cells is None else cells
        runs = spinup_of(cfg.system, cfg.spin, n_cells=cells)
    chambers = []
    for r, c in zip(runs, cfg.system.liquid.chambers):
        # the run stops where the liquid reaches the lid (at t = 0 for a pool that already
        # touches it: a profile that starts above eq 6, no mode change)
        lid = None if r.lid_time is None else {"speed_rad_s": float(r.speed[-1]),
                                               "liquid_speed_rad_s": float(r.liquid_speed[-1])}
        qs = {"omega_0_rad_s": start_speed(c.volume, c.chamber_radius, c.chamber_height,
                                           G_STANDARD, axis="vertical",
                                           inner_radius=c.inner_radius)}
        if c.inner_radius == 0.0:                 # 003 eq 4-6's modes (a cylinder)
            qs = {**mode_speeds(c.volume, c.chamber_radius, c.chamber_height), **qs}
        chambers.append({
            "chamber_radius_m": c.chamber_radius, "inner_radius_m": c.inner_radius,
            "volume_m3": c.volume, "rest_level_m": r.rest_level,
            "mode_changes": r.mode_changes(),
            "entrainment_time_s": r.lid_time,
            "entrainment_speed_rad_s": None if lid is None else lid["speed_rad_s"],
            "liquid_speed_at_lid_rad_s": None if lid is None else lid["liquid_speed_rad_s"],
            "quasi_static": qs, "steps": r.steps})
    out = {"system": cfg.system.name, "profile": getattr(cfg.spin, "name", ""),
           "model": "axisymmetric shallow water, apparent bottom, Ekman/laminar bottom and "
                    "side-wall shear (autobalance.liquid.spinup)",
           "cells": cells, "chambers": chambers}
    from ..config.display import display_units
    from .liquid_figures import chamber_label

    du = display_units(cfg)                     # speeds and lengths as the config writes them
    if plot:
        from ..plotting.liquid import spinup_figure

        fig = spinup_figure(runs, [chamber_label(du, c.chamber_radius, c.volume)
                                   for c in cfg.system.liquid.chambers],
                            [c["quasi_static"]["omega_0_rad_s"] for c in chambers],
                            f"{cfg.system.name}: the liquid's spin-up from rest")
        save_plot(fig, plot)
        out["plot"] = str(plot)
    if not as_json:
        for c in chambers:
            e = c["entrainment_speed_rad_s"]
            typer.echo(chamber_label(du, c["chamber_radius_m"], c["volume_m3"]) + ": "
                       + (f"entrained (lid) at {du.fmt(e, 'speed', 5)}, t = "
                          f"{c['entrainment_time_s']:.3f} s"
                          if e is not None else "not entrained by the profile's end")
                       + f"; 003 eq 6: {du.fmt(c['quasi_static']['omega_0_rad_s'], 'speed', 5)}")
        if plot:
            typer.echo(f"plot: {plot}")
        return
    _out(out, True)


@app.command()
def stability(source: Annotated[str, typer.Argument(
                  metavar="PRESET|CONFIG", help="A machine with a [liquid] section (a vertical "
                  "or horizontal axis), alone or beside balls.")] = "leblanc_003",
              sets: SetOpt = None,
              omega: Annotated[Optional[str], typer.Option(
                  "--speeds", metavar=VALUES_METAVAR, help=grammar_help(
                  "Speeds", "10:120 rad/s:45", tail="increasing; default 45 speeds from 0.2 "
                  "omega_n to 2.2 omega_n or 1.2x the nominal speed"))] = None,
              cells: Annotated[int, typer.Option(
                  "--cells", help="Cells around each wall.")] = 64,
              plot: PlotOpt = None, as_json: JsonOpt = False):
    """Linear stability of the centred state (no unbalance) against speed: the growth rate of
    the least stable perturbation of the rotor with its wall films and the unstable ranges
    (Kollmann's band of partly filled rotors; docs/liquid/stability.md sec. 3j); on a horizontal axis
    of the periodic state under gravity (Floquet, sec. 3m). With balls beside the liquid: the
    balanced state's, balls and films together (sec. 3k).\f

    Parameters
    ----------
    source : str
        Preset or config with a ``[liquid]`` section (balls beside it: the balanced state; on
        a horizontal axis one or two balls).
    sets : list of str
        ``--set`` overrides.
    omega : str or None
        Speeds [rad/s] (with units), increasing; None: 45 from 0.2 omega_n to the larger of 2.2
        omega_n and 1.2 times the nominal speed (:func:`autobalance.studies.liquid_response.
        machine_speeds`).
    cells : int
        Cells around each wall [-] (first order: the growth rates converge as 1/cells).
    plot : str or None
        Figure file (growth rate against speed).
    as_json : bool
        One JSON object.
    """
    from ..liquid.stability import machine_stability
    from ..studies.liquid_balanced import balanced_machine_stability

    _check_plot(plot, source)
    cfg = load_machine(source, sets, balls="liquid")
    if omega is None:
        from ..studies.liquid_response import machine_speeds

        ws = [float(w) for w in machine_speeds(cfg.system, cfg.spin.nominal_speed, 45,
                                               low=0.2, high=2.2, high_nominal=1.2)]
    else:
        ws = _list(omega, "speed", "--speeds")
    balls = cfg.system.balancer.n_balls > 0
    with as_options({"n_cells": "--cells"}):
        res = (balanced_machine_stability(cfg.system, ws, cells) if balls
               else machine_stability(cfg.system, ws, cells))
    if balls:               # the balanced state of the balls beside the liquid (sec. 3k)
        model = ("the run of balls beside the liquid linearised about the balanced state "
                 "(autobalance.studies.liquid_balanced); below the film's start the balls' "
                 "linearised model with the liquid as a pool")
    else:
        model = ("the film runs' step linearised about the centred state "
                 "(autobalance.liquid.stability)")
    if res.get("axis") == "horizontal":
        model += "; on a horizontal axis over a revolution: Floquet (docs/liquid/horizontal-axis.md sec. 3m)"
    out = {"system": cfg.system.name, "model": model, **res}
    if plot:
        from ..plotting.liquid import stability_figure

        save_plot(stability_figure(res, f"{cfg.system.name}: linear stability"), plot)
        out["plot"] = str(plot)
    if not as_json:
        from ..config.display import display_units

        # speeds in the unit --speeds was written in (e.g. rpm), else as the config writes them
        unit = written_unit(omega or "")
        du = display_units(cfg, f"speed={unit}" if unit else None)
        sp = lambda x: du.fmt(x, "speed")       # noqa: E731
        rng = ", ".join(f"{sp(lo)} - {sp(hi)}" for lo, hi in res["unstable_ranges_rad_s"])
        w0 = res["film_from_rad_s"]
        verdict = ("unstable at " + rng if rng else "stable" if np.isfinite(
            res["growth_rate_1_s"]).any() else "not decided (no speed with a film)")
        state = ("balanced state of the balls" if balls else "centred state") + (
            " under gravity (horizontal axis)" if res.get("axis") == "horizontal" else "")
        if balls:
            verdict = ("unstable at " + rng if rng else "stable" if np.isfinite(
                res["growth_rate_1_s"]).any() else "not decided (no balanced state: the "
                "balls' capacity is short)")
        typer.echo(f"{cfg.system.name}: {state} {verdict} over {sp(ws[0])} - {sp(ws[-1])} "
                   f"(a film from {sp(w0)}; {cells} cells; omega_n {sp(res['omega_n_rad_s'])})")
        if res.get("no_periodic_film_rad_s"):
            typer.echo("no verdict at " + ", ".join(sp(w) for w in res["no_periodic_film_rad_s"])
                       + ": no periodic state with an intact film under gravity")
        if plot:
            typer.echo(f"plot: {plot}")
        return
    _out(out, True)
