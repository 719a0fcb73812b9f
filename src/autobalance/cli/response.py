"""``autobalance response``: the steady-state response of any machine, and the speed and
ball-angle options it shares with the analysis commands.

* A ball-balancer machine or a bare rotor: the harmonic unbalance response of the suspended
  rotor over a speed grid (balls held out of it) and its critical speeds
  (:func:`autobalance.physics.response.response_table`); with ``--speed`` (and ``--angles``),
  at that one speed the drum's response to the unbalance and to each ball at those angles
  (000 eq 6-7, 37-38; :func:`autobalance.physics.vibratory.drum_response`).
* A machine with a ``[liquid]`` section: the steady whirl with the liquid against speed beside
  the same rotor without it (:func:`autobalance.studies.liquid_response.liquid_response`), and
  with ``--fill-sweep`` against fill.

Speeds are quantities with units (bare numbers in rad/s, :func:`parse_speed`); the text is in
the config's units (or ``--units``), the JSON in SI.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Annotated, Optional

import typer

from ..config import ConfigError, parse_quantity
from ..config.ranges import grammar_help, parse_list, parse_range
from .common import (JsonOpt, PlotOpt, ProfileOpt, SetOpt, SourceArg, UnitsOpt, as_options,
                     check_plot, guard, load_machine, print_json)

if TYPE_CHECKING:
    import numpy as np

    from ..config import Config

SpeedOpt = Annotated[Optional[str], typer.Option(
    "--speed", help="Spin speed, e.g. '1000 rpm' (bare number: rad/s); default the preset's.")]
AnglesOpt = Annotated[Optional[str], typer.Option(
    "--angles", help="Ball angles: a list 'a, b, c unit' (the unit on the last applies to "
                     "all), e.g. '120, -120 deg' (bare: rad).")]
SpeedsOpt = Annotated[Optional[str], typer.Option(
    "--speeds", metavar="LO:HI:N",
    help=grammar_help("Speed grid", "0:2000 rpm:200", lists=False,
                      tail="0 <= LO < HI, N >= 2 (LO > 0 with a liquid); default 200 points "
                           "up to 2x the nominal speed"))]
ModelOpt = Annotated[str, typer.Option(
    "--model", help="A liquid's model: physical (the liquid in the displaced chamber) or "
                    "lumped (the calibrated engagement of 003's bench).")]
PlacementOpt = Annotated[Optional[str], typer.Option(
    "--placement", help="The lumped liquid model's law: drach or deflection.")]
FillSweepOpt = Annotated[bool, typer.Option(
    "--fill-sweep", help="A liquid's amplitude against fill at 0.6, 0.8, 1, 1.2 omega_n (003 "
                         "Fig. 5).")]

#: Memory of one speed of ``response`` [B]: the numpy work arrays, five lists of Python floats
#: and their JSON text (generous).
RESPONSE_BYTES_PER_SPEED = 1024


def parse_speed(text: str, field: str) -> float:
    """A speed given on the command line.

    Parameters
    ----------
    text : str
        A quantity with units (``"1000 rpm"``, ``"50 Hz"``) or a bare number [rad/s].
    field : str
        The option for the message, e.g. ``"--speed"``.

    Returns
    -------
    float
        The speed [rad/s] (not checked for sign or finiteness).

    Raises
    ------
    ConfigError
        Not a speed (one line).
    """
    return parse_quantity(text, "speed", field)


def speed_at(cfg: Config, spec: Optional[str]) -> float:
    """``--speed``: one spin speed, default the configuration's nominal speed.

    Parameters
    ----------
    cfg : autobalance.config.Config
        The machine.
    spec : str or None
        The option's text (:func:`parse_speed`).

    Returns
    -------
    float
        The speed [rad/s], finite and > 0.

    Raises
    ------
    ConfigError
        Not a speed, or not finite and > 0 (one line).
    """
    w = cfg.spin.nominal_speed if spec is None else parse_speed(spec, "--speed")
    if not (math.isfinite(w) and w > 0):
        raise ConfigError(f"--speed = {spec!r}: must be > 0, e.g. '1000 rpm'")
    return w


def speed_grid(spec: Optional[str], nominal: float):
    """``--speeds LO:HI:N``: a grid of N speeds from LO to HI (:func:`autobalance.config.ranges.
    parse_range`: a unit written once applies to both ends, bare numbers in rad/s).

    N is an integer >= 2 (``1e3`` is read as 1000) whose table must fit the memory limit
    (:func:`autobalance.limits.check_memory`), checked before anything is allocated.

    Parameters
    ----------
    spec : str or None
        ``"LO:HI:N"``, e.g. ``"0:2000 rpm:200"``; None gives 200 points from 0 to twice
        ``nominal``.
    nominal : float
        The nominal speed [rad/s].

    Returns
    -------
    numpy.ndarray
        The speeds [rad/s].

    Raises
    ------
    ConfigError
        Malformed, or not 0 <= LO < HI with N >= 2 (one line).
    ResourceError
        The table would not fit the memory limit.
    """
    import numpy as np

    if spec is None:
        return np.linspace(0.0, 2.0 * nominal, 200)
    return parse_range(spec, "speed", "--speeds", min_points=2, low=0.0,
                       bytes_per_point=RESPONSE_BYTES_PER_SPEED, what="response table")


def ball_angles(cfg: Config, spec: Optional[str]) -> np.ndarray:
    """``--angles``: one angle per ball, default the configuration's initial ball angles.

    Parameters
    ----------
    cfg : autobalance.config.Config
        The machine.
    spec : str or None
        A list ``"a, b, c unit"`` of angles (:func:`autobalance.config.ranges.parse_list`:
        ``"120, -120 deg"``, ``"120 deg,-120 deg"``) or bare [rad].

    Returns
    -------
    numpy.ndarray
        The ball angles [rad].

    Raises
    ------
    ConfigError
        Not angles, or not one per ball (one line).
    """
    import numpy as np

    if spec is None:
        return np.asarray(cfg.initial.angles_for(cfg.system.balancer), float)
    vals = parse_list(spec, "angle", "--angles")
    n = cfg.system.balancer.n_balls
    if len(vals) != n:
        raise ConfigError(f"--angles = {spec!r}: needs {n} angles, one per ball")
    return np.asarray(vals, float)


def response(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
             speeds: SpeedsOpt = None, speed: SpeedOpt = None, angles: AnglesOpt = None,
             model: ModelOpt = "physical", placement: PlacementOpt = None,
             fill_sweep: FillSweepOpt = False, plot: PlotOpt = None, units: UnitsOpt = None,
             json_: JsonOpt = False) -> None:
    """Steady-state response: the rotor's harmonic unbalance response and critical speeds over
    a speed grid; with --speed at one speed the drum's response to the unbalance and to each
    ball; with a [liquid] section the whirl with the liquid beside the rotor without it.\f

    Parameters
    ----------
    source, set_, profile, units, json_
        The shared options (:mod:`autobalance.cli.common`); the JSON object is SI, the text in
        the config's units (or ``--units``).
    speeds : str
        Speed grid ``"LO:HI:N"`` [rad/s or with units] (:func:`speed_grid`).
    speed, angles : str
        One speed and the ball angles there (a ball-balancer machine; :func:`speed_at`,
        :func:`ball_angles`).
    model, placement, fill_sweep
        A liquid's model (``physical`` or ``lumped``), the lumped model's placement law, and
        the response against fill (:func:`autobalance.studies.liquid_response.liquid_response`).
    plot : str
        Figure of the response against speed (or against fill).
    """
    from ..config.display import display_units

    with guard():
        check_plot(plot, inputs={"the input config file": source})
        cfg = load_machine(source, set_, profile)
        du = display_units(cfg, units)
        if cfg.system.liquid is not None:
            if speed is not None or angles is not None:
                raise ConfigError(f"{'--speed' if speed is not None else '--angles'}: the "
                                  "drum's response at one speed takes a ball balancer; a "
                                  "liquid's response is over --speeds")
            return _liquid_response(cfg, speeds, model, placement, fill_sweep, plot, units,
                                    json_)
        cfg.system.require_balls("this command's analyses", allow_empty=True)
        for name, given in (("--model", model != "physical"), ("--placement", placement),
                            ("--fill-sweep", fill_sweep)):
            if given:
                raise ConfigError(f"{name}: takes a machine with a [liquid] section")
        if speed is not None or angles is not None:
            return _drum_response(cfg, speed, angles, plot, du, json_)
        grid = speed_grid(speeds, cfg.spin.nominal_speed)
        from ..physics.response import response_table

        table = dict(response_table(cfg.system, grid))
        result = {"name": cfg.name, "config": cfg.source, **table}
        if plot is not None:
            from ..atomic import save_figure
            from ..plotting import plot_response

            unit = du.unit("speed")
            fig = plot_response({**table, "title": f"{cfg.name}: unbalance response (balls "
                                 "held)"}, speed_unit=unit if unit in ("rpm", "Hz") else "rad/s")
            save_figure(fig, plot, "--plot", dpi=110)
            result["plot"] = str(plot)
    if json_:
        print_json(result)
        return
    typer.echo(f"{cfg.name}: harmonic response, {len(grid)} speeds "
               f"{du.fmt(grid[0], 'speed')} .. {du.fmt(grid[-1], 'speed')}")
    hz = table.get("natural_frequencies_hz", [])
    typer.echo("  natural frequencies: " + ", ".join(du.fmt(2 * math.pi * f, "speed")
                                                     for f in hz))
    w = list(table.get("speed_rad_s", []))
    for axis in ("x", "y"):
        amp = list(table.get(f"amplitude_{axis}_m", []))
        if amp and w:
            i = max(range(len(amp)), key=lambda j: -1.0 if amp[j] is None else amp[j])
            typer.echo(f"  peak amplitude {axis}: {du.fmt(amp[i], 'length')} at "
                       f"{du.fmt(w[i], 'speed')}")
    if plot is not None:
        typer.echo(f"  plot: {plot}")


def _liquid_response(cfg, speeds, model, placement, fill_sweep, plot, units, json_) -> None:
    """``response`` of a machine with a ``[liquid]`` section (:func:`response`)."""
    from ..studies.liquid_response import default_speeds, liquid_response
    from .liquid import _liquid_text_or_json

    ws = (default_speeds(cfg.system, cfg.spin.nominal_speed) if speeds is None else
          speed_grid(speeds, cfg.spin.nominal_speed))
    if ws[0] <= 0:
        raise ConfigError(f"--speeds = {speeds!r}: a liquid's response needs speeds > 0 (LO > "
                          "0), e.g. '5:100 rad/s:96'")
    with as_options({"model": "--model", "model.placement": "--placement",
                     "speeds": "--speeds"}):
        out = {"name": cfg.name, "config": cfg.source,
               **liquid_response(cfg.system, ws, model=model, placement=placement,
                                 fill_sweep=fill_sweep)}
        _liquid_text_or_json(cfg, out, plot, json_, units)


#: The values the drum's response at one speed shows as text.
DRUM_TEXT_KEYS = ("a_0x_m", "a_0y_m", "a_ix_m", "a_iy_m", "phi_x_rad", "phi_y_rad",
                  "amplitude_x_m", "amplitude_y_m", "residual_unbalance_kg_m")


def _drum_response(cfg, speed, angles, plot, du, json_) -> None:
    """``response --speed``: the drum's response at one speed to the unbalance and to each ball
    at ``--angles`` (000 eq 6-7, 37-38; :func:`autobalance.physics.vibratory.drum_response`)."""
    from ..physics.vibratory import drum_response, speed_regime
    from .simulate import shown

    if plot is not None:
        raise ConfigError("--plot: the response at one --speed is a few numbers; drop --speed "
                          "for the figure against speed")
    w = speed_at(cfg, speed)
    r = drum_response(cfg.system, w, ball_angles(cfg, angles))
    out = {"name": cfg.name, **r.as_dict(), "regime": speed_regime(cfg.system, w),
           "natural_frequencies_rad_s": list(cfg.system.natural_frequencies)}
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name} at {du.fmt(w, 'speed')} ({out['regime']} the suspension "
               "frequencies)")
    for k in DRUM_TEXT_KEYS:
        name, value = shown(k, out[k], du)
        if isinstance(value, list):
            value = ", ".join(v if isinstance(v, str) else f"{v:.4g}" for v in value)
        elif isinstance(value, float):
            value = f"{value:.4g}"
        typer.echo(f"  {name:<26} {value}")
