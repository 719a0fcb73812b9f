"""Sanity warnings on a machine: legal values that will not balance as the user likely expects.

None of them refuses the machine: each is one line of text for ``show`` and the studies (and
the ``warnings`` list of their JSON). :func:`machine_warnings` checks the models, in closed form:

1. the rotor's unbalance above the balancer's capacity sum m_i R + rho V R (004 sec. 4.3:
   the balls reach at most every ball opposite the unbalance; 003 sec. 5.3: all of the liquid
   at the wall): the balancer cannot cancel it;
2. the nominal speed below the balancing onset (000 eq 12, :func:`.equilibria.
   balancing_onset_speed`): below it the balls gather on the heavy side and can reach the upper
   operating boundary G_ini + G_balls (004 sec. 4.3, Fig. 7);
3. a TSR plateau below that onset (004 sec. 4.6: the plateau belongs just above the first
   natural frequency): on the plateau the balls are pushed towards the unbalance, not freed;
4. a ball's density m / (4/3 pi r^3) outside :data:`DENSITY_RANGE` (element "ball" only: a
   roller's length is not modelled, a point mass has no size): a mass or radius in the wrong
   unit;
5. one ball: it cancels the unbalance only when m R = U (000 eq 12's one-ball balanced state);
   otherwise it leaves |U - m R|.

The onset is computed only when it can matter: the phase lag of each axis of the Jeffcott
rotor passes pi/2 at its undamped natural frequency sqrt(k/M_t) (000 eq 6-7), so above the
higher natural frequency both cos(phi) < 0 and eq 12's onset lies below; no root is sought
there. :func:`config_warnings` adds the bare numbers of the configuration that look like a
forgotten unit (:func:`autobalance.config.plausible.bare_number_warnings`).
"""
from __future__ import annotations

import math
from collections.abc import Callable
from typing import TYPE_CHECKING

import numpy as np

from .equilibria import balancing_onset_speed
from .iso1940 import grade_value

if TYPE_CHECKING:
    from ..config import Config
    from ..models import MotorDrive, SpeedProfile, System

__all__ = ["DENSITY_RANGE", "config_warnings", "machine_warnings"]

#: Plausible ball densities [kg/m^3]: 1 g/cm^3 (polymers) to 20 g/cm^3 (tungsten, 19.3).
DENSITY_RANGE = (1000.0, 20000.0)

#: SI unit of each kind the default formatter writes.
_SI = {"speed": "rad/s", "unbalance": "kg*m", "length": "m", "mass": "kg"}

#: A capacity within this fraction of the unbalance counts as equal (a design of m R = U
#: written in other units differs by round-off) [-].
_RTOL = 1e-9


def _si_fmt(value: float, kind: str) -> str:
    """``value`` [SI] as "<value> <SI unit>" (4 significant digits)."""
    return f"{value:.4g} {_SI[kind]}"


def _balancer_word(system: System) -> str:
    """"balls", "liquid" or "balls and liquid": what balances this machine."""
    n, liquid = system.balancer.n_balls, system.liquid is not None
    return "balls and liquid" if n and liquid else ("balls" if n else "liquid")


def _capacity(system: System) -> float:
    """The balancer's capacity [kg*m]: sum m_i R of the balls plus rho V R of the liquid."""
    liquid = system.liquid.capacity if system.liquid is not None else 0.0
    return system.balancer.capacity + liquid


def _onset_below(system: System, speeds: list) -> float | None:
    """The balancing onset [rad/s] (000 eq 12) when one of ``speeds`` [rad/s] may lie below
    it, else None; nothing is solved when every speed is at or above the higher natural
    frequency, where the onset is known to lie below (module docstring)."""
    if all(w >= max(system.natural_frequencies) for w in speeds):
        return None
    return balancing_onset_speed(system)


def _speed_warnings(system: System, spin, fmt, U: float) -> list[str]:
    """Warnings 2 and 3: the nominal speed and a TSR plateau below the balancing onset."""
    out = []
    W, word = spin.nominal_speed, _balancer_word(system)
    M, C = system.total_mass, _capacity(system)
    plateau = None
    if getattr(spin, "name", "") == "tsr" and hasattr(spin, "times"):
        after = [w for t, w in zip(spin.times, spin.speeds) if t > spin.checkpoints[0]]
        plateau = min(after) if after else None
    onset = _onset_below(system, [W] + ([] if plateau is None else [plateau]))
    if onset is None:
        return out
    if W < onset:
        g0, g1 = grade_value(U, M, W), grade_value(U + C, M, W)
        out.append(f"the nominal speed {fmt(W, 'speed')} is below the balancing onset "
                   f"{fmt(onset, 'speed')} (000 eq 12; first natural frequency "
                   f"{fmt(min(system.natural_frequencies), 'speed')}): there the {word} gather "
                   f"on the heavy side and make it worse (G{g0:.3g} -> up to G{g1:.3g})")
    if plateau is not None and plateau < onset:
        out.append(f"the TSR plateau {fmt(plateau, 'speed')} is below the balancing onset "
                   f"{fmt(onset, 'speed')} (000 eq 12): on the plateau the {word} are pushed "
                   "towards the unbalance, not freed (an unstable band; 004 sec. 4.6 puts the "
                   "plateau just above the first natural frequency)")
    return out


def _ball_warnings(system: System, fmt, U: float) -> list[str]:
    """Warnings 4 and 5: implausible ball densities, a single ball."""
    b, out = system.balancer, []
    if b.n_balls and b.element == "ball" and b.ball_radius > 0:
        volume = 4.0 / 3.0 * math.pi * b.ball_radius ** 3
        lo, hi = DENSITY_RANGE
        for m in dict.fromkeys(float(x) for x in b.masses):
            rho = m / volume
            if not lo <= rho <= hi:
                out.append(f"a ball of {fmt(m, 'mass')} and radius {fmt(b.ball_radius, 'length')}"
                           f" has a density of {rho:.4g} kg/m^3, outside {lo / 1e3:g}-"
                           f"{hi / 1e3:g} g/cm^3 (polymers to tungsten): a mass or radius in "
                           "the wrong unit?")
    if b.n_balls == 1:
        mR = float(b.masses[0]) * b.race_radius
        out.append(f"one ball cancels the unbalance only when m R = U (000 eq 12; here m R = "
                   f"{fmt(mR, 'unbalance')}, U = {fmt(U, 'unbalance')}); otherwise it leaves "
                   f"|U - m R| = {fmt(abs(U - mR), 'unbalance')}: two balls or more balance a "
                   "range of unbalances")
    return out


def machine_warnings(system: System, spin: SpeedProfile | MotorDrive,
                     fmt: Callable[[float, str], str] | None = None) -> list[str]:
    """The sanity warnings of a machine (module docstring: capacity, onset, TSR plateau, ball
    density, one ball), one line each; empty for a machine without a balancer but for the
    ball checks that need none.

    Parameters
    ----------
    system : autobalance.models.System
        The machine: rotor unbalance U [kg*m] (the largest of its schedule), balls m_i [kg] on
        R [m] with radius r [m], liquid rho V R [kg*m], suspension and total mass M_t [kg].
    spin : SpeedProfile or MotorDrive
        The speed profile or motor drive: its nominal speed [rad/s] and, for a tsr profile,
        its plateau [rad/s].
    fmt : callable or None
        ``fmt(value_si, kind)`` -> text for the kinds "speed", "unbalance", "length" and "mass"
        (e.g. :meth:`autobalance.config.display.DisplayUnits.fmt`); None = SI.

    Returns
    -------
    list of str
        The warnings, without a "warning:" prefix.
    """
    fmt = _si_fmt if fmt is None else fmt
    U = float(np.max(np.abs(system.rotor.unbalance_table()[1])))
    out = []
    if system.balancer.n_balls or system.liquid is not None:
        out += _capacity_warning(system, spin, fmt, U)
        out += _speed_warnings(system, spin, fmt, U)
    return out + _ball_warnings(system, fmt, U)


def _capacity_warning(system: System, spin, fmt, U: float) -> list[str]:
    """Warning 1: the unbalance U [kg*m] above the balancer's capacity."""
    C = _capacity(system)
    if not U > C * (1.0 + _RTOL):
        return []
    word = _balancer_word(system)
    what, formula = {"balls": ("ball", "sum m_i R"), "liquid": ("liquid", "rho V R")}.get(
        word, ("ball and liquid", "sum m_i R + rho V R"))
    left = grade_value(U - C, system.total_mass, spin.nominal_speed)
    return [f"an unbalance of {fmt(U, 'unbalance')} against a {what} capacity of "
            f"{fmt(C, 'unbalance')} ({formula}): the {word} cannot cancel it; at best "
            f"{fmt(U - C, 'unbalance')} = G{left:.3g} is left"]


def config_warnings(cfg: Config, units: str | None = None) -> list[str]:
    """Every sanity warning of a configured machine: the bare numbers that look like a
    forgotten unit (:func:`autobalance.config.plausible.bare_number_warnings`: they often
    explain the others), then :func:`machine_warnings` in the units the configuration writes
    (or ``units``, as ``--units``).

    Parameters
    ----------
    cfg : autobalance.config.Config
        The machine as loaded (its system, spin and the values as written).
    units : str or None
        Display units of the text (:func:`autobalance.config.display.display_units`).

    Returns
    -------
    list of str
        The warnings, one line each.
    """
    from ..config.display import display_units
    from ..config.plausible import bare_number_warnings

    du = display_units(cfg, units)
    return bare_number_warnings(cfg.raw) + machine_warnings(cfg.system, cfg.spin, du.fmt)
