"""The two harmonic (steady-state) response commands and the speed and ball-angle options they
share with the other analysis commands.

* ``autobalance response``: the unbalance response of the suspended rotor over a speed grid
  (balls held out of it) and its critical speeds (:func:`autobalance.physics.response.response_table`).
* ``autobalance analyze response``: at one speed, the drum response to the unbalance and to each
  ball at given angles (000 eq 6-7, 37-38; :func:`autobalance.physics.vibratory.drum_response`).

Both read the machine the same way (:func:`~autobalance.cli.common.load_machine`), take their
speeds as quantities with units (bare numbers in rad/s, :func:`parse_speed`) and default to the
configuration's nominal speed.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Annotated, Optional

import typer

from ..config import ConfigError, parse_quantity
from ..config.ranges import grammar_help, parse_list, parse_range
from .common import (JsonOpt, ProfileOpt, SetOpt, SourceArg, UnitsOpt, echo_fields, guard,
                     load_machine, print_json)

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
                      tail="0 <= LO < HI, N >= 2; default 200 points from 0 to 2x the "
                           "nominal speed"))]

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
             speeds: SpeedsOpt = None, units: UnitsOpt = None, json_: JsonOpt = False) -> None:
    """Harmonic (steady-state) unbalance response of the suspended rotor and its critical speeds.\f

    Parameters
    ----------
    source, set_, profile, units, json_
        The shared options (:mod:`autobalance.cli.common`); the JSON object is the table (SI),
        the text in the config's units (or ``--units``).
    speeds : str
        Speed grid ``"LO:HI:N"`` [rad/s or with units] (:func:`speed_grid`).
    """
    from ..config.display import display_units

    with guard():
        cfg = load_machine(source, set_, profile, balls="rotor")
        du = display_units(cfg, units)
        grid = speed_grid(speeds, cfg.spin.nominal_speed)
        from ..physics.response import response_table

        table = dict(response_table(cfg.system, grid))
    result = {"name": cfg.name, "config": cfg.source, **table}
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
            i = max(range(len(amp)), key=lambda j: amp[j])
            typer.echo(f"  peak amplitude {axis}: {du.fmt(amp[i], 'length')} at "
                       f"{du.fmt(w[i], 'speed')}")


#: The values ``analyze response`` shows as text.
DRUM_TEXT_KEYS = ("a_0x_m", "a_0y_m", "a_ix_m", "a_iy_m", "phi_x_rad", "phi_y_rad",
                  "amplitude_x_m", "amplitude_y_m", "residual_unbalance_kg_m")


def analyze_response(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
                     angles: AnglesOpt = None, json_: JsonOpt = False) -> None:
    """Drum response to the unbalance, each ball and the eccentricity (000 eq 6-7, 37-38).\f

    Parameters
    ----------
    source, set_, speed, angles, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    """
    with guard():
        cfg = load_machine(source, set_, balls="rotor")
        from ..physics.vibratory import drum_response, speed_regime

        w = speed_at(cfg, speed)
        r = drum_response(cfg.system, w, ball_angles(cfg, angles))
        out = {"name": cfg.name, **r.as_dict(), "regime": speed_regime(cfg.system, w),
               "natural_frequencies_rad_s": list(cfg.system.natural_frequencies)}
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name} at {w:.4g} rad/s ({out['regime']} the suspension frequencies)")
    echo_fields({k: out[k] for k in DRUM_TEXT_KEYS})
