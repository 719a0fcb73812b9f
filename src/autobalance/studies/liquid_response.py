"""The steady response of a liquid-balancer machine against speed, its response against fill
and its linear run-up: which of the liquid models answers each, for any machine with a
``[liquid]`` section (either axis, one or several chambers).

* ``model="physical"`` (the default): the quasi-static liquid in the displaced chamber
  (:func:`autobalance.liquid.steady.chambers_steady_response`, docs/liquid/models.md sec.
  3b-3d); below each chamber's start speed a centred pool (vertical axis) or a puddle held by
  gravity (horizontal axis, docs/liquid/stability.md sec. 3k); the run-up couples the wall film
  (:func:`autobalance.liquid.film.physical_run_up` for one chamber on a vertical axis, the
  film run of :func:`autobalance.liquid.simulate.ramp_run_up` otherwise).
* ``model="lumped"``: the calibrated engagement of 003's first release (docs/liquid/models.md
  sec. 3; :func:`autobalance.liquid.steady_response`, :func:`autobalance.liquid.run_up`), one
  chamber on 003's vertical bench.

``autobalance response`` on a machine with a ``[liquid]`` section prints :func:`liquid_response`.
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from ..liquid import LiquidBalancer, LiquidModel, RunUp, VerticalRotor
    from ..models import System

__all__ = ["LIQUID_MODELS", "FILL_SPEED_RATIOS", "LiquidMachine", "default_speeds",
           "liquid_machine", "liquid_response", "liquid_run_up", "machine_speeds",
           "natural_frequency"]

#: The liquid models of :func:`liquid_response`.
LIQUID_MODELS = ("physical", "lumped")
#: Speeds of the response against fill, as multiples of the natural frequency with the liquid
#: (003 Fig. 5) [-].
FILL_SPEED_RATIOS = (0.6, 0.8, 1.0, 1.2)


@dataclass(frozen=True)
class LiquidMachine:
    """A machine as the liquid models see it.

    Attributes
    ----------
    system : System
        The machine.
    model : str
        ``"physical"`` or ``"lumped"``.
    rotor : VerticalRotor
        Rotor mass without the liquid [kg], stiffness [N/m], damping [N*s/m], unbalance [kg*m].
    balancer : LiquidBalancer or None
        The one chamber of the lumped model and of the single-chamber film run-up; None with
        several chambers.
    chambers : list of tuple
        Each chamber's (radius [m], height [m], inner radius [m], volume [m^3]).
    lumped : LiquidModel
        The lumped model's choices (placement law; its g [m/s^2] the entrainment's).
    g : float
        Gravity of the steady response [m/s^2]: along a vertical axis (the entrainment), in the
        plane of a horizontal one (the film's start g/Omega^2 = R/10).
    """

    system: System
    model: str
    rotor: VerticalRotor
    balancer: LiquidBalancer | None
    chambers: list
    lumped: LiquidModel
    g: float

    @property
    def physical(self) -> bool:
        """True for the physical model."""
        return self.model == "physical"


def liquid_machine(system: System, model: str = "physical",
                   placement: str | None = None) -> LiquidMachine:
    """The liquid models' view of ``system``, checked for ``model``.

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section and no balls
        (:func:`autobalance.liquid.simulate.require_liquid_machine`).
    model : str
        ``"physical"`` or ``"lumped"`` (one chamber, vertical axis: 003's bench).
    placement : str, optional
        The lumped model's placement law (``"drach"``, the default, or ``"deflection"``).

    Returns
    -------
    LiquidMachine

    Raises
    ------
    ParameterError
        A model the machine does not fit (one line naming the key).
    """
    from ..liquid import LiquidModel
    from ..liquid.simulate import film_rotor, liquid_parts, require_liquid_machine

    if model not in LIQUID_MODELS:
        raise ParameterError("model", model, "must be 'physical' or 'lumped'")
    lumped = LiquidModel(**({"placement": placement} if placement else {}))
    require_liquid_machine(system)
    L = system.liquid
    chambers = [(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume)
                for c in L.chambers]
    if L.n_chambers > 1:
        if model == "lumped":
            raise ParameterError("liquid.chamber_radius", list(L.chamber_radius),
                                 f"{L.n_chambers} concentric chambers: the lumped model takes "
                                 "one chamber (the physical model takes several)")
        L.unpartitioned("the liquid's response")
        rot, bal = film_rotor(system), None
    else:
        rot, bal = liquid_parts(system)
    if model == "lumped":                   # the lumped model is 003's vertical bench
        L.vertical("for the lumped model (003's bench); the physical model takes a "
                   "horizontal axis")
    g = system.gravity.g if L.axis == "horizontal" else lumped.g
    return LiquidMachine(system, model, rot, bal, chambers, lumped, g)


def liquid_response(system: System, speeds: npt.ArrayLike, *, model: str = "physical",
                    placement: str | None = None, fill_sweep: bool = False) -> dict:
    """The steady synchronous whirl of a liquid-balancer machine at constant speeds, beside the
    same rotor without the liquid, with its entrainment speed and natural frequency; and, with
    ``fill_sweep``, the whirl against fill at 0.6, 0.8, 1 and 1.2 times the natural frequency
    (003 Fig. 5).

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section (:func:`liquid_machine`).
    speeds : array_like
        Speeds [rad/s]; increasing and > 0 for the physical model.
    model, placement : str
        The liquid model and the lumped model's placement law (:func:`liquid_machine`).
    fill_sweep : bool
        Also the response against the fill map's default fills
        (:func:`autobalance.studies._fill_map.default_fills`).

    Returns
    -------
    dict
        ``model``, ``axis``, ``volume_m3``, ``radius_m``, ``chambers``, ``liquid``,
        ``unbalance_kg_m``, ``capacity_kg_m`` (sum rho V R), ``k`` (capacity / unbalance),
        ``placement``, ``omega_0_rad_s`` (the speed above which every chamber's liquid is a
        ring, 003 eq 6 on a vertical axis), ``omega_n_rad_s`` (with the liquid's mass), the
        steady arrays (``omega_rad_s``, ``amplitude_m``, ``amplitude_dry_m``, ...), with
        several chambers ``omega_0_per_chamber_rad_s``, with ``fill_sweep`` ``fill_sweep``
        (one dict per speed: ``omega_rad_s``, ``volume_m3``, ``amplitude_m``,
        ``optimum_volume_m3``).
    """
    from ..liquid import fill_sweep as lumped_fill_sweep
    from ..liquid import steady_response
    from ..liquid.steady import (chambers_fill_sweep, chambers_steady_response,
                                 increasing_speeds, start_speed)
    from ._fill_map import chamber_fills, default_fills

    m = liquid_machine(system, model, placement)
    L, rot, bal = system.liquid, m.rotor, m.balancer
    ws = np.asarray(speeds, float)
    if m.physical:
        ws = increasing_speeds(ws)
        st = chambers_steady_response(rot, m.chambers, L.density, ws, m.g, L.axis)
    else:
        st = steady_response(rot, bal, ws, m.lumped)
    w0s = [start_speed(V, R, h, m.g, axis=L.axis, inner_radius=ri) for R, h, ri, V in m.chambers]
    wn = rot.natural_frequency(L.density * L.total_volume)
    capacity = L.density * sum(V * R for R, _, _, V in m.chambers)
    out = {"model": model, "axis": L.axis, "volume_m3": L.total_volume,
           "radius_m": L.chamber_radius, "chambers": len(m.chambers),
           "liquid": bal.liquid.name if bal is not None else "liquid",
           "unbalance_kg_m": rot.unbalance, "capacity_kg_m": capacity,
           "k": capacity / rot.unbalance if rot.unbalance else None,
           "placement": None if m.physical else m.lumped.placement,
           "omega_0_rad_s": max(w0s), "omega_n_rad_s": wn, **st}
    if len(m.chambers) > 1:
        out["omega_0_per_chamber_rad_s"] = w0s
    if fill_sweep:
        vols = default_fills(L)
        if m.physical:
            per = [[c[:3] + (v,) for c, v in zip(m.chambers, chamber_fills(L, f))] for f in vols]
            sw = [chambers_fill_sweep(rot, per, L.density, f * wn, m.g, L.axis)
                  for f in FILL_SPEED_RATIOS]
        else:
            sw = [lumped_fill_sweep(rot, bal, vols, f * wn, m.lumped) for f in FILL_SPEED_RATIOS]
        out["fill_sweep"] = [{"omega_rad_s": s["omega_rad_s"], "volume_m3": s["volume_m3"],
                              "amplitude_m": s["amplitude_m"],
                              "optimum_volume_m3": s["optimum_volume_m3"]} for s in sw]
    return out


def liquid_run_up(system: System, omega_end: float, duration: float, *,
                  model: str = "physical", placement: str | None = None) -> RunUp:
    """A linear run-up from rest to ``omega_end`` in ``duration`` of a liquid-balancer machine,
    by the model that covers it: the lumped model's (:func:`autobalance.liquid.run_up`); for
    the physical model, one chamber on a vertical axis the wall film started at 003 eq 6's
    speed (:func:`autobalance.liquid.film.physical_run_up`), otherwise the film run through the
    ramp (:func:`autobalance.liquid.simulate.ramp_run_up`).

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section (:func:`liquid_machine`).
    omega_end : float
        Final speed [rad/s] > 0.
    duration : float
        Time of the run-up [s] > 0.
    model, placement : str
        The liquid model and the lumped model's placement law.

    Returns
    -------
    RunUp
        Time [s], speed [rad/s], whirl amplitude with and without the liquid [m], the
        liquid's angle [rad] and unbalance [kg*m].
    """
    from ..liquid import run_up
    from ..liquid.film import physical_run_up
    from ..liquid.simulate import ramp_run_up

    m = liquid_machine(system, model, placement)
    if not m.physical:
        return run_up(m.rotor, m.balancer, m.lumped, omega_end, duration, n_out=1500)
    if m.balancer is None or system.liquid.axis == "horizontal":
        return ramp_run_up(system, omega_end, duration)
    return physical_run_up(m.rotor, m.balancer, omega_end, duration, m.lumped.g)


def natural_frequency(system: System) -> float:
    """The natural frequency of a liquid machine's rotor with the liquid's mass [rad/s]
    (:meth:`autobalance.liquid.VerticalRotor.natural_frequency`).

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section.
    """
    from ..liquid.simulate import film_rotor

    L = system.liquid
    return float(film_rotor(system).natural_frequency(L.density * L.total_volume))


def machine_speeds(system: System, nominal_speed: float, n: int, *, low: float = 0.0,
                   high: float = 1.5, high_nominal: float = 2.0) -> np.ndarray:
    """A liquid machine's own speed grid: ``n`` speeds from ``low`` times its natural frequency
    with the liquid omega_n (or, for ``low`` = 0, 1/``n`` of the top) up to the larger of
    ``high`` omega_n and ``high_nominal`` times the nominal speed.

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section.
    nominal_speed : float
        The profile's nominal speed [rad/s].
    n : int
        Number of speeds [-], >= 2.
    low, high, high_nominal : float
        Ratios [-] to omega_n and to the nominal speed.

    Returns
    -------
    ndarray
        Speeds [rad/s], increasing and > 0.
    """
    wn = natural_frequency(system)
    top = max(high * wn, high_nominal * float(nominal_speed))
    return np.linspace(low * wn if low > 0 else top / n, top, n)


def default_speeds(system: System, nominal_speed: float, n: int = 200) -> np.ndarray:
    """The default speeds of :func:`liquid_response`: ``n`` speeds up to the larger of twice the
    nominal speed and 1.5 times the natural frequency with the liquid (:func:`machine_speeds`).

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section.
    nominal_speed : float
        The profile's nominal speed [rad/s].
    n : int
        Number of speeds [-].

    Returns
    -------
    ndarray
        Speeds [rad/s], increasing and > 0.
    """
    return machine_speeds(system, nominal_speed, n)
