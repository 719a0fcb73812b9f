"""The run-up of any machine (000 sec. "Variable spin velocity", Tables 1-2, Fig. 10-11, asked of
any machine): how long the drive takes to reach speed, how large the whirl grows on the way
through resonance with and without the balancer, how far the balls travel relative to the rotor,
when the whirl last exceeds a fraction of the rotor's own eccentricity, and the grade it leaves.

A motor-driven machine (``[profile] kind = "motor"``) is run under each torque law asked for
(000 Table 1: constant, linear, harmonic), from the config's own torque, final speed and hold
fraction; a prescribed profile (std, tsr, ramp, table) is run as it is. Each case runs with the
balls and, unless ``bare=False``, without them (the same machine with ``n_balls = 0``; beside a
liquid, its chamber empty too), so the effect of the balancer on the run-up is a ratio of two
simulations. Balls beside a liquid run with :func:`autobalance.simulate.hybrid.simulate_hybrid`,
a liquid alone with :func:`autobalance.liquid.simulate.simulate_liquid` (a prescribed profile;
before its film starts, the liquid is a centred pool, quasi-steady); "without" is then the
rotor with its chamber empty. The unloaded drive's time to
speed in closed form (:func:`autobalance.physics.runup.runup_time_closed_form`, 000 eq 15) is
given beside the simulated one.
"""
from __future__ import annotations

import dataclasses
import math
import time
from typing import TYPE_CHECKING

import numpy as np

from ..models import MotorDrive, ParameterError
from ..physics.runup import runup_time_closed_form
from .common import load

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    import numpy.typing as npt
    import xarray as xr

    from ..config import Config

__all__ = ["BALANCING_FRACTION", "balancing_time", "compute_runup", "runup_summary"]

#: The whirl amplitude a run-up is balanced below, as a fraction of the rotor's eccentricity
#: e = U / M_t (the amplitude of the unbalanced rotor far above resonance, 000 eq 6-7) [-].
BALANCING_FRACTION = 0.05

#: Default spacing of the stored histories: this many samples per revolution at full speed.
SAMPLES_PER_REV = 20


def balancing_time(t: npt.ArrayLike, amplitude: npt.ArrayLike, eccentricity: float,
                   fraction: float = BALANCING_FRACTION) -> float:
    """Last time [s] at which the whirl amplitude exceeds ``fraction`` of the rotor's
    eccentricity e = U/M_t (000 Fig. 5: "balanced in just 1.5 seconds"; the amplitude of the
    unbalanced rotor far above resonance is e, 000 eq 6-7); 0 if it never does.

    Parameters
    ----------
    t : array_like
        Times [s].
    amplitude : array_like
        Whirl amplitude |w| at those times [m].
    eccentricity : float
        e = U / M_t [m].
    fraction : float
        Threshold as a fraction of e [-].

    Returns
    -------
    float
        [s].
    """
    k = np.nonzero(np.asarray(amplitude) > fraction * eccentricity)[0]
    return float(np.asarray(t)[k[-1]]) if k.size else 0.0


def _time_to_speed(spin, summary) -> float:
    """First time [s] the spin reaches its full speed: the motor's hold speed (the kernel's
    record), or the first knot of a prescribed profile at its highest speed; NaN if never."""
    if isinstance(spin, MotorDrive):
        t = summary.get("time_to_final_speed_s")
        return math.nan if t is None else float(t)
    w = np.asarray(spin.speeds, float)
    return float(np.asarray(spin.times, float)[int(np.argmax(w >= w.max()))])


def _cases(cfg, laws):
    """name -> spin of each case: the motor drive under each law, or the prescribed profile."""
    spin = cfg.spin
    if isinstance(spin, MotorDrive):
        laws = (spin.law,) if laws is None else tuple(laws)
        for law in laws:
            if law not in MotorDrive.LAWS:
                raise ParameterError("laws", law, f"must be among {list(MotorDrive.LAWS)}")
        if not laws:
            raise ParameterError("laws", list(laws), "needs at least one torque law")
        return {law: dataclasses.replace(spin, law=law) for law in dict.fromkeys(laws)}
    if laws is not None:
        raise ParameterError("laws", list(laws), "torque laws need a motor-driven machine "
                                                 "([profile] kind = \"motor\"); this one has a "
                                                 f"prescribed {getattr(spin, 'name', 'profile')} profile")
    return {getattr(spin, "name", "") or "profile": spin}


def _liquid_case(s, spin, tg, ecc, fraction):
    """One case of a liquid balancer alone (no balls): the film model
    (:func:`autobalance.simulate.simulate` of a liquid alone: a prescribed profile or a motor), its whirl
    read on ``tg`` [s]; before the film starts the liquid is a centred pool (quasi-steady, as
    ``LiquidSimulation.max_amplitude_before_film``). (row, histories) as compute_runup's."""
    from ..liquid.simulate import film_rotor, spin_angle
    from ..liquid.steady import pool_response
    from ..simulate import simulate

    sim = simulate(s, spin, throw=False)
    if sim.status != "ok":
        raise ParameterError("liquid", "the run-up", sim.message)
    S = sim.summary()
    # the spin over the run: the profile's table, or the motor's speed at the outputs
    tt, ww = (sim.t, sim.speed) if sim.motor else (np.asarray(spin.times, float),
                                                   np.asarray(spin.speeds, float))
    speed = np.interp(tg, tt, ww, right=np.nan)
    before = tg < sim.t[0]           # before the run's own samples: a prescribed profile's pool
    amp = np.interp(tg, sim.t, sim.amplitude, right=np.nan)
    amp[before] = np.abs(pool_response(film_rotor(s), s.liquid.total_volume, s.liquid.density,
                                       speed[before]))
    xy = sim.deflection * np.exp(1j * spin_angle(sim.t, tt, ww))      # inertial frame
    pool = S["max_amplitude_before_film_m"]
    row = {"t_speed": _time_to_speed(spin, S),
           "max_amplitude": max(S["max_amplitude_m"], pool),
           "x_max": max(float(np.max(np.abs(xy.real))), pool),
           "y_max": max(float(np.max(np.abs(xy.imag))), pool),
           "ball_revolutions": math.nan,
           "balancing_time": balancing_time(np.concatenate([tg[before], sim.t]),
                                            np.concatenate([amp[before], sim.amplitude]),
                                            ecc, fraction),
           "final_grade": float(S["final"]["grade_G_mm_s"])}
    return row, {"speed": speed, "amplitude": amp}


def compute_runup(base: str | Path | Config, *, laws: Sequence[str] | None = None,
                  sets: Sequence[str] = (), bare: bool = True,
                  fraction: float = BALANCING_FRACTION,
                  save_dt: float | None = None) -> xr.Dataset:
    """Simulate the machine's run-up per case, with and without its balls.

    Parameters
    ----------
    base : str, Path or Config
        The machine (its profile decides the cases; its initial state starts the balls).
    laws : sequence of str or None
        Torque laws to compare for a motor-driven machine (None: the config's own law).
    sets : sequence of str
        "path=value" overrides, as for ``--set``.
    bare : bool
        Also run each case without the balls (the amplitude ratio needs it); beside a liquid,
        without the liquid too (an empty chamber: the rotor without any balancer).
    fraction : float
        Threshold of the balancing time as a fraction of the eccentricity U/M_t [-].
    save_dt : float or None
        Spacing of the stored histories [s] (None: 20 samples per revolution at full speed).

    Returns
    -------
    xarray.Dataset
        Per case: t_speed [s] (time to reach full speed; NaN if never), t_speed_unloaded
        [s] (closed form, motor drives; NaN for a law that only approaches its final speed
        with hold_fraction = 1), max_amplitude, x_max, y_max [m] with the balls and
        bare, amplitude_ratio [-], ball_revolutions [-] (mean |revolutions| relative to the
        rotor), balancing_time [s], final_grade [mm/s]; histories speed [rad/s], amplitude [m]
        and amplitude_bare [m] against time [s].
    """
    import xarray as xr

    from ..simulate import simulate

    t0 = time.perf_counter()
    if not (math.isfinite(fraction) and fraction > 0):
        raise ParameterError("fraction", fraction, "must be a finite number > 0")
    cfg = load(base, sets, allow_liquid=True, liquid_alone=True)   # simulations: liquid modelled
    cases = _cases(cfg, laws)
    s = cfg.system
    W = cfg.spin.nominal_speed
    if save_dt is None:
        save_dt = 2 * math.pi / W / SAMPLES_PER_REV
    durations = {float(c.duration) for c in cases.values()}
    tg = np.arange(0.0, max(durations) + 0.5 * save_dt, save_dt)
    opts = dataclasses.replace(cfg.options, save_dt=save_dt)
    # bare: no balls, and an empty chamber (the liquid analyses' "without liquid")
    bare_sys = dataclasses.replace(s, balancer=dataclasses.replace(s.balancer, n_balls=0),
                                   liquid=None)
    ecc = s.rotor.unbalance / s.total_mass
    rows, hist = [], []
    for name, spin in cases.items():
        if s.balancer.n_balls == 0:                 # a liquid alone: the film model
            r, h = _liquid_case(s, spin, tg, ecc, fraction)
        else:
            sim = simulate(s, spin, initial=cfg.initial, options=opts)
            S = sim.summary()
            r = {"t_speed": _time_to_speed(spin, S), "max_amplitude": S["max_amplitude_m"],
                 "x_max": S["x_max_m"], "y_max": S["y_max_m"],
                 "ball_revolutions": float(np.mean(np.abs(np.asarray(S["ball_revolutions"],
                                                                    float)))),
                 "balancing_time": balancing_time(sim.t, sim.amplitude, ecc, fraction),
                 "final_grade": float(S["final"]["grade_G_mm_s"])}
            h = {"speed": np.interp(tg, sim.t, sim.speed, right=np.nan),
                 "amplitude": np.interp(tg, sim.t, sim.amplitude, right=np.nan)}
        r["t_speed_unloaded"] = math.nan
        if isinstance(spin, MotorDrive) and (spin.law == "constant" or spin.hold_fraction < 1):
            tau = s.rotor.polar_inertia * spin.final_speed / spin.torque
            r["t_speed_unloaded"] = runup_time_closed_form(spin.law, spin.hold_fraction, tau)
        if bare:
            sb = simulate(bare_sys, spin, initial=dataclasses.replace(cfg.initial, ball_angles=(),
                                                                      ball_speeds=None),
                          options=opts)
            Sb = sb.summary()
            r.update({"max_amplitude_bare": Sb["max_amplitude_m"], "x_max_bare": Sb["x_max_m"],
                      "y_max_bare": Sb["y_max_m"],
                      "amplitude_ratio": r["max_amplitude"] / Sb["max_amplitude_m"]})
            h["amplitude_bare"] = np.interp(tg, sb.t, sb.amplitude, right=np.nan)
        rows.append(r)
        hist.append(h)
    names = list(cases)
    units = {"t_speed": "s", "t_speed_unloaded": "s", "max_amplitude": "m", "x_max": "m",
             "y_max": "m", "max_amplitude_bare": "m", "x_max_bare": "m", "y_max_bare": "m",
             "amplitude_ratio": "1", "ball_revolutions": "1", "balancing_time": "s",
             "final_grade": "mm/s"}
    data = {k: ("case", np.array([r[k] for r in rows], float), {"units": u})
            for k, u in units.items() if k in rows[0]}
    for k, u in (("speed", "rad/s"), ("amplitude", "m"), ("amplitude_bare", "m")):
        if k in hist[0]:
            data[k] = (("case", "time"), np.array([h[k] for h in hist]), {"units": u})
    ds = xr.Dataset(data, coords={"case": names, "time": ("time", tg, {"units": "s"})})
    ds.attrs.update({"study": "runup", "machine": cfg.name, "motor": int(isinstance(cfg.spin, MotorDrive)),
                     "nominal_speed_rad_s": float(W), "eccentricity_m": float(ecc),
                     "balancing_fraction": float(fraction),
                     "balancer": ("balls" if s.liquid is None else "liquid" if not
                                  s.balancer.n_balls else "balls and liquid"),
                     "natural_frequencies_rad_s": [float(w) for w in s.natural_frequencies],
                     "wall_s": time.perf_counter() - t0})
    return ds


def runup_summary(ds: xr.Dataset) -> dict:
    """JSON-ready summary of :func:`compute_runup`: per case the scalars (SI, unit-suffixed keys).

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_runup` result.

    Returns
    -------
    dict
        "cases": name -> {quantity_unit: value (None for NaN)}, plus the machine's nominal speed
        [rad/s], eccentricity [m] and natural frequencies [rad/s].
    """
    suffix = {"s": "_s", "m": "_m", "1": "", "mm/s": "_mm_s"}
    cases = {}
    for name in [str(c) for c in ds["case"].values]:
        d = ds.sel(case=name)
        cases[name] = {}
        for k, v in d.data_vars.items():
            if "time" in v.dims:
                continue
            x = float(v.values)
            key = k + suffix[v.attrs["units"]] if k != "final_grade" else "final_grade_G_mm_s"
            cases[name][key] = None if math.isnan(x) else x
    a = ds.attrs
    return {"study": "runup", "machine": a["machine"], "nominal_speed_rad_s": a["nominal_speed_rad_s"],
            "eccentricity_m": a["eccentricity_m"], "balancing_fraction": a["balancing_fraction"],
            "natural_frequencies_rad_s": list(a["natural_frequencies_rad_s"]), "cases": cases}
