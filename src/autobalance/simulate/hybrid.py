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
from ..core.layout import N_S, S_STATUS, RunStatus, carry_size
from ..limits import check_run
from ..liquid.film import _theta, film_equilibrium, film_unbalance, partition_walls
from ..liquid.models import G_STANDARD
from ..liquid.simulate import require_axis_gravity, revolution_average
from ..liquid.start import FilmStart, film_start
from ..models import InitialState, MotorDrive, ParameterError, SimOptions, SpeedProfile, System
from .pack import atol_vector, initial_vector, pack_params, spin_arrays
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
    or later leaves the film's start speed); returns where the film starts.

    Parameters
    ----------
    system : System
        Balls and a ``[liquid]`` section.
    spin : SpeedProfile or MotorDrive
        The spin.
    g_axial : float
        Gravity along the vertical axis [m/s^2] (003 eq 6).
    """
    if isinstance(spin, MotorDrive) or not isinstance(spin, SpeedProfile):
        raise ParameterError("profile.kind", "motor", "balls beside a liquid need a prescribed "
                             "speed profile (constant, ramp, table, std or tsr)")
    require_axis_gravity(system)
    return film_start(system, spin, g_axial)


def simulate_hybrid(system: System, spin: SpeedProfile, *, initial: InitialState | None = None,
                    options: SimOptions | None = None, n_cells: int = 256,
                    g_axial: float = G_STANDARD, throw: bool = True) -> Simulation:
    """Run a machine with balls beside a liquid through its speed profile (module docstring).

    Parameters
    ----------
    system : System
        Rotor, suspension (any the ball simulator takes), balls and a ``[liquid]`` section
        ([gravity] in the plane on a horizontal axis).
    spin : SpeedProfile
        Prescribed speed [rad/s] over time [s].
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
    from .run import _h_max, _time_grid

    initial = initial or InitialState()
    options = options or SimOptions()
    fs = check_hybrid(system, spin, g_axial)
    check_run(system, spin, options)
    if isinstance(n_cells, bool) or int(n_cells) != n_cells or n_cells < 16:
        raise ParameterError("n_cells", n_cells, "must be an integer >= 16")
    t0, w0 = fs.time, fs.speed
    N = system.balancer.n_balls
    P, B = pack_params(system, spin, options, liquid_ok=True)
    y, order = initial_vector(system, spin, initial)
    prof_t, prof_w, t_end = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    out_t = _time_grid(spin, options, y.size)
    out_y = np.zeros((out_t.size, y.size))
    stats = np.zeros(N_S)
    carry = np.zeros(carry_size(N))
    atol = atol_vector(system, spin, options)
    h_max, rtol, budget = _h_max(spin, options), options.rtol, int(options.max_steps)
    if t0 > 0.0:                     # the pool: the ball run up to the film's start
        pt, pw = np.zeros(prof_t.size + 1), np.zeros(prof_t.size + 1)
        m = with_knot(prof_t, prof_w, t0, pt, pw)
        integrate_span(P, B, N, pt[:m], pw[:m], unb_t, unb_u, y, t_end, rtol, atol, h_max,
                       budget, out_t, out_y, stats, t0, carry)
    liq = system.liquid
    ch = liq.chambers
    cells = [c.partitions * -(-int(n_cells) // c.partitions) if c.partitions else int(n_cells)
             for c in ch]
    starts = np.concatenate([[0], np.cumsum(cells)]).astype(np.int64)
    theta = np.concatenate([_theta(n) for n in cells])
    wall = np.concatenate([partition_walls(n, c.partitions) for n, c in zip(cells, ch)])
    out_h = np.zeros((out_t.size, theta.size))
    out_q = np.zeros((out_t.size, theta.size))
    steps = 0
    gp = system.gravity.g if liq.axis == "horizontal" else 0.0
    gam = system.gravity.direction
    s = system.suspension                      # the static sag (inertial frame) [m]
    sag = system.total_mass * gp * complex(np.cos(gam) / s.kx, np.sin(gam) / s.ky)
    if t0 == 0.0 or stats[S_STATUS] == float(RunStatus.RUNNING):
        psi0 = y[N + 2]
        w = complex(y[0], y[1]) + sag * np.exp(-1j * psi0) \
            + gp / spin.speed(t0) ** 2 * np.exp(1j * (gam - psi0))    # + gravity's offset
        h = np.concatenate([film_equilibrium(c.volume, c.chamber_radius, c.chamber_height, w,
                                             n, c.partitions) for n, c in zip(cells, ch)])
        q = h * np.concatenate([np.full(n, lag * c.chamber_radius)       # the spin-up's lag
                                for n, c, lag in zip(cells, ch, fs.lag)])
        Rs, Hs = (np.array([getattr(c, k) for c in ch], float)
                  for k in ("chamber_radius", "chamber_height"))
        rhos = np.full(len(ch), liq.density)
        nus = np.full(len(ch), liq.kinematic_viscosity)
        steps = hybrid_integrate(P, B, N, prof_t, prof_w, unb_t, unb_u, y, t0, t_end, rtol,
                                 atol, h_max, budget, out_t, out_y, stats, carry, h,
                                 q, theta, starts, Rs, Hs, rhos, nus, wall, gp,
                                 gam, sag, out_h, out_q)
        if steps < 0:
            raise FloatingPointError("simulate_hybrid: the film state became non-finite")
    film = out_t >= t0 - 1e-12 * max(1.0, t0)
    per = np.zeros((out_t.size, len(ch)), complex)
    for j, (c, o0, o1) in enumerate(zip(ch, starts[:-1], starts[1:])):
        per[film, j] = film_unbalance(out_h[film, o0:o1], c.chamber_radius, c.chamber_height,
                                      liq.density)
    U = per.sum(axis=1)
    psi = out_y[:, N + 2]
    part = LiquidPart(U, revolution_average(psi, U), per, float(t0), float(w0), int(steps))
    sim = Simulation(system, spin, initial, options, out_t, out_y, stats, order, liquid=part)
    if throw and sim.status != "ok":
        raise SimulationError(sim.message)
    return sim
