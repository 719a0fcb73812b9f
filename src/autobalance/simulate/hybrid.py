"""One run of a machine with balls beside a liquid (a ``[balancer]`` with balls and a
``[liquid]`` section): the ball simulator with the wall films of the liquid's chambers on the
same rotor (:mod:`autobalance.core.hybrid`; docs/liquid.md sec. 3i). :func:`autobalance.simulate`
runs it for such a machine.

Before the film starts (:func:`autobalance.liquid.simulate.film_start`: from rest on a vertical
axis where the liquid's spin-up reaches the lid; otherwise where the profile reaches 003 eq 6's
entrainment speed, or g/Omega^2 = R/10 on a horizontal axis) the liquid is a pool centred in its
chamber: its mass moves with the rotor (M_t includes it) and it pulls nothing. From then on each
chamber's liquid is a wall film on the displaced wall (:func:`autobalance.liquid.film.
film_equilibrium`), lagging the chamber as the spin-up leaves it, coupled two-way with the
rotor and the balls.
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..core.hybrid import hybrid_integrate, with_knot
from ..core.integrate import integrate_span
from ..core.layout import S_STATUS, RunStatus, carry_size
from ..limits import check_run
from ..liquid.film import FilmRun
from ..liquid.models import G_STANDARD
from ..liquid.simulate import (chamber_films, film_samples, inner_wall_status,
                               require_axis_gravity, revolution_average, spin_angle)
from ..liquid.start import FilmStart, _film_table, film_start, film_start_speed
from ..models import InitialState, MotorDrive, ParameterError, SimOptions, SpeedProfile, System
from .result import Simulation, SimulationError

__all__ = ["LiquidPart", "check_hybrid", "simulate_hybrid"]


@dataclass(frozen=True)
class LiquidPart:
    """The liquid of a run of balls beside a liquid, over the run's output times.

    Parameters
    ----------
    unbalance : ndarray of complex (nt,)
        The films' summed first moment about the chamber centre, rotor frame; 0 before the
        film starts (a centred pool) [kg*m].
    synchronous_unbalance : ndarray of complex (nt,)
        ``unbalance`` averaged over one revolution (:func:`autobalance.liquid.simulate.revolution_average`) [kg*m].
    chamber_unbalance : ndarray of complex (nt, chambers)
        Each chamber's film moment, from the axis outwards [kg*m].
    film_start : float
        Time the film starts (:func:`autobalance.liquid.simulate.film_start`) [s].
    film_start_speed : float
        The profile's speed there [rad/s].
    steps : int
        Film time steps (coupling steps) [-].
    """

    unbalance: np.ndarray
    synchronous_unbalance: np.ndarray
    chamber_unbalance: np.ndarray
    film_start: float
    film_start_speed: float
    steps: int


def check_hybrid(system: System, spin: SpeedProfile | MotorDrive,
                 g_axial: float = G_STANDARD) -> FilmStart:
    """One-line errors, before any work, for what the run of balls beside a liquid does not
    cover (a motor drive, [gravity] that does not fit the axis, a profile that never reaches
    or later leaves the film's start speed, a chamber's liquid too thick for a wall film);
    returns where the film starts.

    Parameters
    ----------
    system : System
        Balls and a ``[liquid]`` section.
    spin : SpeedProfile or MotorDrive
        The spin.
    g_axial : float
        Gravity along the vertical axis [m/s^2] (003 eq 6).
    """
    if isinstance(spin, MotorDrive):
        return _motor_start(system, spin, g_axial)
    if not isinstance(spin, SpeedProfile):
        raise ParameterError("profile.kind", type(spin).__name__, "must be a speed profile or "
                             "a motor drive")
    require_axis_gravity(system)
    fs = film_start(system, spin, g_axial)
    chamber_films(system, fs, 256, 0j)           # the wall film's checks, before any work
    return fs


def _motor_start(system: System, spin: MotorDrive, g_axial: float) -> FilmStart:
    """A motor drive beside a liquid (docs/liquid.md sec. 3i): a vertical axis, and a drive
    that starts and ends at or above the film's start speed (the pool's spin-up under the
    kernel's spin is not modelled); the films start at t = 0 turning with the chamber."""
    system.liquid.vertical("with a motor drive beside a liquid (in-plane gravity torques the "
                           "films from outside: docs/liquid.md sec. 3i); a prescribed profile "
                           "takes it")
    require_axis_gravity(system)
    w_f = film_start_speed(system.liquid, system.gravity.g, g_axial)
    for field, w in (("profile.initial_speed", spin.initial_speed),
                     ("profile.final_speed", spin.final_speed)):
        if w < w_f:
            raise ParameterError(field, w, f"must be >= the film's start speed {w_f:.4g} rad/s "
                                 "with a motor drive beside a liquid (the pool's spin-up under "
                                 "a motor is not modelled: docs/liquid.md sec. 3i)")
    fs = FilmStart(0.0, float(spin.initial_speed), (0.0,) * system.liquid.n_chambers,
                   "quasi-static")
    chamber_films(system, fs, 256, 0j)           # the wall film's checks, before any work
    return fs


def simulate_hybrid(system: System, spin: SpeedProfile | MotorDrive, *,
                    initial: InitialState | None = None,
                    options: SimOptions | None = None, n_cells: int = 256,
                    g_axial: float = G_STANDARD, throw: bool = True) -> Simulation:
    """Run a machine with balls beside a liquid through its speed profile (module docstring).

    Parameters
    ----------
    system : System
        Rotor, suspension (any the ball simulator takes), balls and a ``[liquid]`` section
        ([gravity] in the plane on a horizontal axis).
    spin : SpeedProfile or MotorDrive
        Prescribed speed [rad/s] over time [s], or a motor drive (vertical axis, from and to
        speeds at or above the film's start [rad/s]; docs/liquid.md sec. 3i).
    initial : InitialState, optional
        Ball angles [rad] and rotor state at t = 0 (:func:`autobalance.simulate`'s default).
    options : SimOptions, optional
        The ball simulator's options (friction law, tolerances, output spacing).
    n_cells : int
        Film cells around each wall [-] (rounded up to a multiple of the partitions).
    g_axial : float
        Gravity along the axis, for the entrainment speed [m/s^2].
    throw : bool
        As :func:`autobalance.simulate`.

    Returns
    -------
    autobalance.result.Simulation
        The ball run's histories with ``liquid`` (:class:`LiquidPart`); its residual unbalance
        and grade include the liquid's synchronous moment.
    """
    from .run import run_inputs

    initial = initial or InitialState()
    options = options or SimOptions()
    fs = check_hybrid(system, spin, g_axial)
    check_run(system, spin, options)
    if isinstance(n_cells, bool) or int(n_cells) != n_cells or n_cells < 16:
        raise ParameterError("n_cells", n_cells, "must be an integer >= 16")
    t0, w0 = fs.time, fs.speed
    N = system.balancer.n_balls
    P, B, y, order, prof_t, prof_w, t_end, unb_t, unb_u, out_t, out_y, stats, atol, h_max = \
        run_inputs(system, spin, initial, options, liquid_ok=True)
    carry = np.zeros(carry_size(N))
    rtol, budget = options.rtol, int(options.max_steps)
    if t0 > 0.0:                     # the pool: the ball run up to the film's start
        pt, pw = np.zeros(prof_t.size + 1), np.zeros(prof_t.size + 1)
        m = with_knot(prof_t, prof_w, t0, pt, pw)
        integrate_span(P, B, N, pt[:m], pw[:m], unb_t, unb_u, y, t_end, rtol, atol, h_max,
                       budget, out_t, out_y, stats, t0, carry)
    liq = system.liquid
    ch = liq.chambers
    gp = system.gravity.g if liq.axis == "horizontal" else 0.0
    gam = system.gravity.direction
    s = system.suspension                      # the static sag (inertial frame) [m]
    sag = system.total_mass * gp * complex(np.cos(gam) / s.kx, np.sin(gam) / s.ky)
    psi0 = y[N + 2]
    # the films at the film's start: the chamber about the rotation axis, + gravity's offset
    off0 = gp / spin.speed(t0) ** 2 * np.exp(1j * (gam - psi0)) if gp else 0j
    st = chamber_films(system, fs, n_cells, complex(y[0], y[1]) + sag * np.exp(-1j * psi0)
                       + off0)
    # the films' own output grid from t0, dense enough for the revolution average (as a liquid
    # alone: liquid.simulate.film_samples), whatever the balls' output times; a motor's spin
    # stays below its final speed (or starts above it and slows down to it)
    motor = isinstance(spin, MotorDrive)
    if motor:
        w_top = max(spin.final_speed, spin.initial_speed)
        tt, ww = np.array([0.0, t_end]), np.array([w_top, w_top])
    else:
        _, tt, ww = _film_table(spin, film_start_speed(liq, system.gravity.g, g_axial), t0)
    dt_f = float(tt[-1]) / (film_samples(tt, ww) - 1)
    tf = np.arange(0.0, tt[-1] + 0.5 * dt_f, dt_f)
    out_h = np.zeros((tf.size, st.h.size))
    out_q = np.zeros((tf.size, st.h.size))
    out_psi = np.zeros(tf.size)
    steps = 0
    if t0 == 0.0 or stats[S_STATUS] == float(RunStatus.RUNNING):
        steps = hybrid_integrate(P, B, N, prof_t, prof_w, unb_t, unb_u, y, t0, t_end, rtol,
                                 atol, h_max, budget, out_t, out_y, stats, carry, st.h, st.q,
                                 st.theta, st.starts, st.Rs, st.Hs, st.rhos, st.nus, st.wall,
                                 gp, gam, sag, t0 + tf, out_h, out_q, out_psi)
        if steps < 0:
            raise FloatingPointError("simulate_hybrid: the film state became non-finite")
    runs = [FilmRun(tf, st.theta[o0:o1], out_h[:, o0:o1], out_q[:, o0:o1], f.radius, f.height,
                    f.density, steps)
            for f, o0, o1 in zip(st.films, st.starts[:-1], st.starts[1:])]
    status, message = inner_wall_status(runs, ch, t0)
    if status != "ok" and stats[S_STATUS] == 0.0:   # the balls' run completed; the film did not
        stats[S_STATUS] = float(RunStatus.OUTSIDE_MODEL)
    per_f = np.stack([r.unbalance for r in runs], axis=-1)          # (film samples, chambers)
    sync_f = revolution_average(out_psi if motor else spin_angle(tf, tt, ww),
                                per_f.sum(axis=1))

    def at_outputs(v):            # film grid -> the balls' output times; 0 before the film
        x = out_t - t0
        return np.where(x >= -1e-12 * max(1.0, t0),
                        np.interp(x, tf, v.real) + 1j * np.interp(x, tf, v.imag), 0.0)

    per = np.stack([at_outputs(per_f[:, j]) for j in range(len(ch))], axis=-1)
    U = per.sum(axis=1)
    part = LiquidPart(U, at_outputs(sync_f), per, float(t0), float(w0), int(steps))
    sim = Simulation(system, spin, initial, options, out_t, out_y, stats, order, liquid=part)
    if status != "ok" and sim.status == status:
        sim.message = message                   # names the chamber and the time
    if throw and sim.status != "ok":
        raise SimulationError(sim.message)
    return sim
