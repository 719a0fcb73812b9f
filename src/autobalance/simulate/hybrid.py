"""One run of a machine with balls beside a liquid (a ``[balancer]`` with balls and a
``[liquid]`` section): the ball simulator with the wall films of the liquid's chambers on the
same rotor (:mod:`autobalance.core.hybrid`; docs/liquid/balls-beside-liquid.md sec. 3i).
:func:`autobalance.simulate` runs it for such a machine.

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
from ..core.layout import P_LQI, P_LQT, S_STATUS, RunStatus, carry_size
from ..limits import check_run
from ..liquid.film import FilmRun
from ..models.liquid_balancer import G_STANDARD
from ..liquid.simulate import (LiquidSimulation, chamber_films, check_liquid_run, film_samples,
                               inner_wall_status,
                               require_axis_gravity, require_liquid_machine, revolution_average,
                               simulate_liquid, spin_angle)
from ..liquid.spinup import PoolSpin, within_spinup
from ..liquid.start import FilmStart, _film_table, film_start, film_start_speed
from ..models import InitialState, MotorDrive, ParameterError, SimOptions, SpeedProfile, System
from .pack import run_inputs
from .result import Simulation, SimulationError

#: Coupling step of a pool's spin-up beside a motor-driven spin (:func:`_pool_phase`) [s]: the
#: pools' torque lags by one step (docs/liquid/balls-beside-liquid.md sec. 3i).
POOL_STEP = 1.0e-3
#: The note of a run whose motor started below the film's start on a horizontal axis.
RIGID_NOTE = ("before the film's start the liquid turned with the drum: its pool flow is not "
              "modelled, its effect on the run-up is bounded (docs/liquid/balls-beside-liquid.md sec. 3i)")

__all__ = ["LiquidPart", "check_hybrid", "check_liquid", "liquid_run", "simulate_hybrid",
           "simulate_liquid_motor"]


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


def check_liquid(system: System, spin: SpeedProfile | MotorDrive,
                 g_axial: float = G_STANDARD) -> None:
    """One-line errors, before any work, for a run of a machine with a liquid that the models
    do not cover: balls beside it (:func:`check_hybrid`), a liquid alone under a motor (the
    liquid machine's checks, then :func:`check_hybrid`'s of the drive), a liquid alone through
    a profile (:func:`autobalance.liquid.simulate.check_liquid_run`).

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section.
    spin : SpeedProfile or MotorDrive
        Its spin.
    g_axial : float
        Gravity along the vertical axis [m/s^2].
    """
    if not system.balancer.n_balls:
        if not isinstance(spin, MotorDrive):
            check_liquid_run(system, spin, g_axial)
            return
        require_liquid_machine(system)
    check_hybrid(system, spin, g_axial)


def _motor_start(system: System, spin: MotorDrive, g_axial: float) -> FilmStart:
    """A motor drive beside a liquid (docs/liquid/balls-beside-liquid.md sec. 3i). A drive that
    starts at or above the film's start speed starts the films at t = 0 turning with the chamber
    (rule "quasi-static"); one that starts below it runs :func:`_pool_phase` first (rule "pool"):
    on a vertical axis the pools spin up beside the kernel, on a horizontal one the liquid turns
    with the chamber until the film's start speed. Its end speed must reach the film's start
    speed. On a horizontal axis the kernel's spin row takes gravity's torque on the films' held
    moment (core/rhs.py)."""
    require_axis_gravity(system)
    liq = system.liquid
    w_f = film_start_speed(liq, system.gravity.g, g_axial)
    if spin.final_speed < w_f:
        raise ParameterError("profile.final_speed", spin.final_speed, f"must be >= the film's "
                             f"start speed {w_f:.4g} rad/s with a motor drive and a liquid "
                             "(below it the liquid stays a pool: docs/liquid/machine.md sec. 3e)")
    n = liq.n_chambers
    if spin.initial_speed >= w_f:
        fs = FilmStart(0.0, float(spin.initial_speed), (0.0,) * n, "quasi-static")
        chamber_films(system, fs, 256, 0j)       # the wall film's checks, before any work
        return fs
    if liq.axis == "horizontal":                 # the liquid turns with the chamber (_pool_phase)
        chamber_films(system, FilmStart(0.0, w_f, (0.0,) * n, "quasi-static"), 256, 0j)
        return FilmStart(0.0, float(spin.initial_speed), (0.0,) * n, "pool")
    why = next((f"with the chamber R = {c.chamber_radius:.4g} m more than half full (outside "
                "the spin-up model, docs/liquid/spin-up.md sec. 3h)" for c in liq.chambers
                if not within_spinup(c.chamber_radius, c.chamber_height, c.inner_radius,
                                     c.volume)), None)
    if why is not None:
        raise ParameterError("profile.initial_speed", spin.initial_speed, f"must be >= the "
                             f"film's start speed {w_f:.4g} rad/s with a motor drive {why}")
    return FilmStart(0.0, float(spin.initial_speed), (0.0,) * n, "pool")


def _pool_phase(system: System, g_axial: float, P: np.ndarray, B: np.ndarray, N: int,
                prof_t: np.ndarray, prof_w: np.ndarray, unb_t: np.ndarray, unb_u: np.ndarray,
                y: np.ndarray, t_end: float, rtol: float, atol: np.ndarray, h_max: float,
                budget: int, out_t: np.ndarray, out_y: np.ndarray, stats: np.ndarray,
                carry: np.ndarray) -> FilmStart | None:
    """A motor drive from below the film's start speed (docs/liquid/balls-beside-liquid.md sec. 3i),
    one coupling step of :data:`POOL_STEP` at a time. On a vertical axis each chamber's pool spins
    up (:class:`autobalance.liquid.spinup.PoolSpin`, the axisymmetric model of sec. 3h) beside
    the kernel: the pools' change of angular momentum reaches the spin as a torque one step late
    (as the films'); a chamber whose liquid has reached the lid turns on with the chamber at its
    lag, its moment of inertia in the kernel's spin row. On a horizontal axis the liquid turns
    with the chamber from the start, its moment of inertia rho V R^2 (the films' at their start)
    in the spin row, until the spin reaches the film's start speed. Returns where the film
    starts (the end of the step in which the last chamber reached the lid, with each chamber's
    lag; or in which the spin reached the film's start speed, lag 0), or None when the run ends
    (or fails) first: a pool throughout."""
    liq = system.liquid
    W = y[-1]
    horizontal = liq.axis == "horizontal"
    pools = [] if horizontal else [
        PoolSpin(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume, liq.density,
                 liq.kinematic_viscosity, g_axial, W) for c in liq.chambers]
    H = [p.momentum(W)[0] for p in pools]
    lags = [0.0] * liq.n_chambers
    t, Tl = 0.0, 0.0
    Ic = sum(liq.density * c.volume * c.chamber_radius ** 2 for c in liq.chambers) \
        if horizontal else 0.0
    w_f = film_start_speed(liq, system.gravity.g, g_axial) if horizontal else np.inf
    while True:
        t1 = min(t + POOL_STEP, t_end)
        P[P_LQI], P[P_LQT] = Ic, Tl
        integrate_span(P, B, N, prof_t, prof_w, unb_t, unb_u, y, t_end, rtol, atol, h_max,
                       budget, out_t, out_y, stats, t1 if t1 < t_end else np.inf, carry)
        if stats[S_STATUS] != float(RunStatus.RUNNING):
            P[P_LQI] = P[P_LQT] = 0.0
            return None                         # the end (or a failure) before the lid
        W1, dH = y[-1], 0.0
        for k, p in enumerate(pools):
            if p.lid_time is None:
                p.advance(t, t1 - t, W, W1)
                Hk, Ik = p.momentum(W1)
                dH += Hk - H[k]
                H[k] = Hk
                if p.lid_time is not None:      # from the next step on: rigid, at its lag
                    lags[k] = Hk / Ik - W1
                    Ic += Ik
        Tl = -dH / (t1 - t)
        t, W = t1, W1
        if W >= w_f or (pools and all(p.lid_time is not None for p in pools)):
            P[P_LQI] = P[P_LQT] = 0.0
            return FilmStart(t, float(W), tuple(lags), "rigid" if horizontal else "spin-up")


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
        Prescribed speed [rad/s] over time [s], or a motor drive (from any speed, on a
        vertical axis with every chamber at most half full below the film's start; to a speed
        at or above the film's start [rad/s]; docs/liquid/balls-beside-liquid.md sec. 3i).
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
    motor = isinstance(spin, MotorDrive)
    if fs.rule == "pool":            # a motor from below the film's start: the pools spin up
        fs = _pool_phase(system, g_axial, P, B, N, prof_t, prof_w, unb_t, unb_u, y, t_end, rtol,
                         atol, h_max, budget, out_t, out_y, stats, carry)
        if fs is None:               # the run's end (or its failure) came first: a pool
            nan = float("nan")
            part = LiquidPart(np.zeros(out_t.size, complex), np.zeros(out_t.size, complex),
                              np.zeros((out_t.size, system.liquid.n_chambers), complex), nan,
                              nan, 0)
            return _finish(Simulation(system, spin, initial, options, out_t, out_y, stats,
                                      order, liquid=part), "ok", "", throw)
        t0, w0 = fs.time, fs.speed
    elif t0 > 0.0:                   # the pool: the ball run up to the film's start
        pt, pw = np.zeros(prof_t.size + 1), np.zeros(prof_t.size + 1)
        m = with_knot(prof_t, prof_w, t0, pt, pw)
        integrate_span(P, B, N, pt[:m], pw[:m], unb_t, unb_u, y, t_end, rtol, atol, h_max,
                       budget, out_t, out_y, stats, t0, carry)
    liq = system.liquid
    gp = system.gravity.g if liq.axis == "horizontal" else 0.0
    gam = system.gravity.direction
    s = system.suspension                      # the static sag (inertial frame) [m]
    sag = system.total_mass * gp * complex(np.cos(gam) / s.kx, np.sin(gam) / s.ky)
    psi0 = y[N + 2]
    # the films at the film's start: the chamber about the rotation axis, + gravity's offset
    w_start = w0 if motor else spin.speed(t0)
    off0 = gp / w_start ** 2 * np.exp(1j * (gam - psi0)) if gp else 0j
    st = chamber_films(system, fs, n_cells, complex(y[0], y[1]) + sag * np.exp(-1j * psi0)
                       + off0)
    # the films' own output grid from t0, dense enough for the revolution average (as a liquid
    # alone: liquid.simulate.film_samples), whatever the balls' output times; a motor's spin
    # stays below its final speed (or starts above it and slows down to it)
    if motor:
        w_top = max(spin.final_speed, spin.initial_speed)
        tt, ww = np.array([0.0, t_end - t0]), np.array([w_top, w_top])
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
    status, message = inner_wall_status(runs, liq.chambers, t0)
    if status != "ok" and stats[S_STATUS] == 0.0:   # the balls' run completed; the film did not
        stats[S_STATUS] = float(RunStatus.OUTSIDE_MODEL)
    per_f = np.stack([r.unbalance for r in runs], axis=-1)          # (film samples, chambers)
    sync_f = revolution_average(out_psi if motor else spin_angle(tf, tt, ww),
                                per_f.sum(axis=1))

    def at_outputs(v):            # film grid -> the balls' output times; 0 before the film
        x = out_t - t0
        return np.where(x >= -1e-12 * max(1.0, t0),
                        np.interp(x, tf, v.real) + 1j * np.interp(x, tf, v.imag), 0.0)

    per = np.stack([at_outputs(per_f[:, j]) for j in range(per_f.shape[1])], axis=-1)
    part = LiquidPart(per.sum(axis=1), at_outputs(sync_f), per, float(t0), float(w0),
                      int(steps))
    sim = _finish(Simulation(system, spin, initial, options, out_t, out_y, stats, order,
                             liquid=part), status, message, throw)
    if fs.rule == "rigid" and sim.status == "ok":
        sim.message = RIGID_NOTE
    return sim


def _finish(sim: Simulation, status: str, message: str, throw: bool) -> Simulation:
    """The run with the film's own message when its status is the film's (a chamber's film
    at its inner wall: names the chamber and the time); raises for a failed run if ``throw``."""
    if status != "ok" and sim.status == status:
        sim.message = message
    if throw and sim.status != "ok":
        raise SimulationError(sim.message)
    return sim


def simulate_liquid_motor(system: System, spin: MotorDrive, *, n_cells: int = 256,
                          n_out: int | None = None,
                          g_axial: float = G_STANDARD) -> LiquidSimulation:
    """A liquid alone (no balls) under a motor drive: :func:`simulate_hybrid`'s kernel with no
    balls, the spin a degree of freedom taking the films' inertia and torque
    (docs/liquid/balls-beside-liquid.md sec. 3i), read as a run of
    :func:`autobalance.liquid.simulate.simulate_liquid`. The drive ends at or above the film's start
    speed. The run starts on the steady orbit of the rotor carrying the liquid as a rigid centred
    mass (as ``simulate_liquid``'s); from the film's start speed or above with the films turning
    with the chamber, from below it through :func:`_pool_phase` (the pools' spin-up on a vertical
    axis, the liquid turning with the drum on a horizontal one).

    Parameters
    ----------
    system : System
        Rotor (mass [kg], polar inertia [kg*m^2], unbalance [kg*m]), isotropic suspension and a
        ``[liquid]`` section; no balls; [gravity] in the plane for a horizontal axis.
    spin : MotorDrive
        The motor's torque law [N*m] from its initial speed [rad/s].
    n_cells : int
        Film cells around each wall [-].
    n_out : int or None
        Output samples over the run [-]; None: 1001, or 8 per revolution at the drive's larger
        end speed if more, at most 200 001 (as ``simulate_liquid``).
    g_axial : float
        Gravity along the vertical axis, for the entrainment speed [m/s^2].

    Returns
    -------
    LiquidSimulation
    """
    require_liquid_machine(system)
    if not isinstance(spin, MotorDrive):
        raise ParameterError("profile.kind", type(spin).__name__, "must be 'motor' here (a "
                             "prescribed profile runs with simulate_liquid)")
    w_top = max(spin.final_speed, spin.initial_speed)
    if n_out is None:
        n_out = film_samples(np.array([0.0, spin.duration]), np.array([w_top, w_top]))
    if isinstance(n_out, bool) or int(n_out) != n_out or n_out < 2:
        raise ParameterError("n_out", n_out, "must be an integer >= 2")
    # from the steady orbit of the rotor carrying the liquid as a rigid centred mass at the
    # initial speed, as simulate_liquid starts
    sim = simulate_hybrid(system, spin, initial=InitialState(steady_state=True),
                          options=SimOptions(save_dt=spin.duration / (n_out - 1)),
                          n_cells=n_cells, g_axial=g_axial, throw=False)
    part = sim.liquid
    ch = system.liquid.chambers
    return LiquidSimulation(system, sim.t, sim.speed, sim.u + 1j * sim.v, part.unbalance,
                            part.synchronous_unbalance, part.film_start, part.film_start_speed,
                            float(spin.nominal_speed), part.steps, sim.status,
                            sim.message if sim.status != "ok" or sim.message == RIGID_NOTE
                            else "" if part.film_start >= 0
                            else "no film: the drive ended before the film's start (" + (
                                "its speed; the liquid turned with the drum throughout)"
                                if system.liquid.axis == "horizontal" else
                                "the liquid reaching the lid; a pool throughout)"),
                            None if len(ch) == 1 else part.chamber_unbalance, motor=True,
                            time_to_final_speed=sim.summary()["time_to_final_speed_s"])


def liquid_run(system: System, spin: SpeedProfile | MotorDrive, *,
               n_cells: int = 256) -> LiquidSimulation:
    """A run of a liquid alone (no balls): :func:`autobalance.liquid.simulate.simulate_liquid`
    through a prescribed profile, :func:`simulate_liquid_motor` under a motor drive
    (:func:`autobalance.simulate.simulate` runs a liquid alone with it).

    Parameters
    ----------
    system : System
        A ``[liquid]`` section and no balls.
    spin : SpeedProfile or MotorDrive
        Prescribed speed [rad/s] over time [s], or a motor's torque law [N*m].
    n_cells : int
        Film cells around each wall [-].
    """
    if isinstance(spin, MotorDrive):
        return simulate_liquid_motor(system, spin, n_cells=n_cells)
    return simulate_liquid(system, spin, n_cells=n_cells)
