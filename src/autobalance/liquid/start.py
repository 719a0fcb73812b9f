"""Where a run's wall film starts (docs/liquid/machine.md sec. 3e, spin-up.md sec. 3h): the
quasi-static start speed omega_f (003 eq 6 on a vertical axis; g/Omega^2 = R/10 on a horizontal one)
and, for a run-up on a vertical axis, the spin-up from rest to the lid (:mod:`.spinup`). Used by the
liquid's own runs (:mod:`.simulate`) and by balls beside a liquid
(:mod:`autobalance.simulate.hybrid`).
"""
from __future__ import annotations

import functools
from typing import NamedTuple

import numpy as np

from ..models import LiquidDevice, ParameterError, SpeedProfile, System
from ..models.liquid_balancer import G_STANDARD
from .spinup import chamber_spinup, within_spinup
from .steady import start_speed

__all__ = ["FilmStart", "film_start", "film_start_speed", "pool_machine"]


def film_start_speed(device: LiquidDevice, g_plane: float = 0.0,
                     g_axial: float = G_STANDARD) -> float:
    """Speed from which the wall-film model holds [rad/s]: :func:`.steady.start_speed` of the
    machine's chamber, fill and axis (vertical: 003 eq 6's entrainment speed; horizontal: where
    gravity's offset g/Omega^2 of the potential is R/10); with several chambers the largest,
    where every chamber's liquid is a ring.

    Parameters
    ----------
    device : autobalance.models.LiquidDevice
        The chambers (R, h [m]), fills V [m^3] and axis.
    g_plane : float
        In-plane gravity for a horizontal axis [m/s^2].
    g_axial : float
        Gravity along a vertical axis [m/s^2].
    """
    g = g_plane if device.axis == "horizontal" else g_axial
    return max(start_speed(c.volume, c.chamber_radius, c.chamber_height, g, axis=c.axis,
                           inner_radius=c.inner_radius) for c in device.chambers)


def _film_table(spin: SpeedProfile, w0: float,
                start: float | None = None) -> tuple[float, np.ndarray, np.ndarray]:
    """(t0, times from t0 [s], speeds [rad/s]) of the profile from its first reaching w0, or
    from ``start`` [s] (a later time, where the spin-up model puts the ring on the wall)."""
    t = np.asarray(spin.times, float)
    w = np.asarray(spin.speeds, float)
    above = np.nonzero(w >= w0)[0]
    if above.size == 0:
        raise ParameterError("profile", f"max {w.max():.4g} rad/s", f"never reaches the film "
                             f"model's start speed {w0:.4g} rad/s (below it the liquid is a "
                             "pool, not a wall film; docs/liquid/machine.md sec. 3e)")
    i = int(above[0])
    t0 = t[0] if i == 0 else t[i - 1] + (w0 - w[i - 1]) / (w[i] - w[i - 1]) * (t[i] - t[i - 1])
    if start is not None and start > t0:
        t0 = float(start)
        i = int(np.searchsorted(t, t0, side="right"))
    tt = np.concatenate([[t0], t[i:][t[i:] > t0]])
    ww = np.interp(tt, t, w)
    ww[0] = max(ww[0], w0) if start is None else ww[0]
    low = np.nonzero(ww < w0 * (1 - 1e-12))[0]
    if low.size:
        raise ParameterError("profile", f"{ww[low[0]]:.4g} rad/s at {tt[low[0]]:.4g} s",
                             f"falls below the film model's start speed {w0:.4g} rad/s after "
                             "reaching it; the film model needs the liquid on the wall")
    if tt[-1] <= t0:
        raise ParameterError("profile", f"end at {t[-1]:.4g} s", f"reaches the film model's "
                             f"start speed {w0:.4g} rad/s only at its end: nothing to simulate")
    return float(t0), tt - t0, ww


class FilmStart(NamedTuple):
    """Where a run's wall film starts (:func:`film_start`).

    Parameters
    ----------
    time : float
        t0 [s] on the profile.
    speed : float
        The profile's speed there, or omega_f (:func:`film_start_speed`) by the quasi-static
        rule (a profile that starts above it starts there with a ring) [rad/s].
    lag : tuple of float
        Per chamber, the liquid's mean angular speed minus the chamber's there [rad/s] (0: a
        ring turning with the chamber).
    rule : str
        ``"spin-up"`` (a vertical axis, a profile starting below omega_f: where the spin-up
        model's liquid reaches the lid, the latest chamber's) or ``"quasi-static"`` (where the
        profile first reaches :func:`film_start_speed`); or ``"pool"`` before a run of a
        motor drive from below omega_f, whose film's start the run finds
        (:func:`autobalance.simulate.hybrid.simulate_hybrid`): then ``"spin-up"`` on a
        vertical axis, ``"rigid"`` on a horizontal one (the liquid turned with the chamber).
    """

    time: float
    speed: float
    lag: tuple
    rule: str


def film_start(system: System, spin: SpeedProfile, g_axial: float = G_STANDARD) -> FilmStart:
    """Where the wall film of a run starts (docs/liquid/machine.md sec. 3e, spin-up.md sec. 3h). On
    a vertical axis, for a profile that starts below :func:`film_start_speed` (003 eq 6), the liquid
    spins up (:func:`autobalance.liquid.spinup.spinup_of`: from a flat layer at rest, or from the
    pool turning with the chamber at the profile's first speed) and the film starts when the last
    chamber's liquid reaches the lid, with each chamber's lag there. Otherwise (a profile that
    starts at or above it: a ring from the start; a horizontal axis) where the profile first
    reaches :func:`film_start_speed`, with the liquid a ring turning with the chamber; so too
    when a chamber is more than half full (its surface touches the lid before the bottom dries:
    outside the spin-up model).

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section.
    spin : SpeedProfile
        Its profile.
    g_axial : float
        Gravity along a vertical axis [m/s^2].

    Returns
    -------
    FilmStart
    """
    liq = system.liquid
    w0 = film_start_speed(liq, system.gravity.g, g_axial)
    t0, _, _ = _film_table(spin, w0)
    covered = all(within_spinup(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume)
                  for c in liq.chambers)
    if liq.axis != "vertical" or spin.speeds[0] >= w0 or not covered:
        return FilmStart(t0, w0, (0.0,) * liq.n_chambers, "quasi-static")
    lids = [_lid(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume,
                 liq.kinematic_viscosity, g_axial, tuple(spin.times), tuple(spin.speeds))
            for c in liq.chambers]
    for (t_lid, _), c in zip(lids, liq.chambers):
        if t_lid is None:
            raise ParameterError("profile", f"end at {spin.duration:.4g} s", "comes before the "
                                 f"liquid of the chamber R = {c.chamber_radius:.4g} m reaches "
                                 "the lid in its spin-up (docs/liquid/spin-up.md sec. 3h): "
                                 "no ring for the film model; give a longer or faster run-up")
    t1 = max(t_lid for t_lid, _ in lids)
    _film_table(spin, w0, t1)
    return FilmStart(t1, float(spin.speed(t1)), tuple(lag for _, lag in lids), "spin-up")


@functools.lru_cache(maxsize=256)
def _lid(radius: float, height: float, inner_radius: float, volume: float, viscosity: float,
         g: float, times: tuple, speeds: tuple) -> tuple[float | None, float]:
    """(time [s] the chamber's liquid reaches the lid, or None; the liquid's mean angular speed
    minus the chamber's there [rad/s]) of :func:`autobalance.liquid.spinup.spinup_run` through
    the profile (times [s], speeds [rad/s]), from rest or from the pool turning at the first
    speed (:func:`autobalance.liquid.spinup.rigid_pool`). Cached: the cells of a sweep that
    differ in the rotor or the balls only share their liquid's spin-up."""
    r = chamber_spinup(radius, height, inner_radius, volume, viscosity, g, times, speeds)
    return r.lid_time, float(r.liquid_speed[-1] - r.speed[-1])


def pool_machine(system: System) -> System:
    """The machine with its liquid as a pool (below the film's start,
    docs/liquid/balls-beside-liquid.md sec. 3i): its mass moves with the rotor and it pulls nothing,
    so the ball models take the machine with the liquid's mass added to the rotor's and no
    ``[liquid]`` section. M_t is kept.

    Parameters
    ----------
    system : System
        The machine (a ``[liquid]`` section; the rotor's mass M [kg]).

    Returns
    -------
    System
        Rotor mass M + rho V [kg], ``liquid`` None (the same machine without a liquid).
    """
    import dataclasses

    if system.liquid is None:
        return system
    rotor = dataclasses.replace(system.rotor, mass=system.rotor.mass + system.liquid.mass)
    return dataclasses.replace(system, rotor=rotor, liquid=None)
