"""One entry point for a single run of any machine and one for many runs of balls: ``simulate``
and ``simulate_batch``.

Both refuse, before allocating or integrating, a run that cannot fit the limits of
:mod:`autobalance.limits` (one-line :class:`~autobalance.limits.ResourceError`).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..core.batch import integrate_batch, integrate_branches
from ..core.integrate import integrate
from ..core.layout import N_S, S_STATUS, RunStatus
from ..limits import check_run
from .pack import (RunInputs, _h_max, atol_vector, initial_vector, pack_params, run_inputs,
                   spin_arrays)
from ..models import InitialState, MotorDrive, SimOptions, SpeedProfile, System
from .result import BatchResult, Simulation, SimulationError

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..liquid.simulate import LiquidSimulation


def simulate(system: System, spin: SpeedProfile | MotorDrive, *, initial: InitialState | None = None,
             options: SimOptions | None = None, throw: bool = True,
             n_cells: int = 256) -> Simulation | LiquidSimulation:
    """Simulate one run of any machine the configuration accepts: the rotor with its ball
    balancer, a liquid balancer, or balls beside a liquid, through a speed profile or a motor
    run-up. The one place that chooses the kernel:

    * balls (or a bare rotor): the compiled DOPRI5 kernel (:func:`autobalance.core.integrate.
      integrate`);
    * a liquid alone: the wall-film model (:func:`autobalance.simulate.hybrid.liquid_run`;
      ``initial`` and ``options`` do not apply, the film starts where the liquid's spin-up puts
      it);
    * balls beside a liquid: the kernel with the films (:func:`autobalance.simulate.hybrid.
      simulate_hybrid`).

    Parameters
    ----------
    system : System
        Rotor, suspension, balancer (or ``[liquid]``) and gravity (SI dataclasses).
    spin : SpeedProfile or MotorDrive
        Prescribed spin speed [rad/s] vs time [s], or a motor torque law (spin as a DOF).
    initial : InitialState, optional
        Ball angles [rad] relative to the unbalance, rotor displacement [m]; default balls at
        pi/4 + k 2pi/N at rest, rotor at rest.
    options : SimOptions, optional
        Friction law, tolerances, output spacing.
    throw : bool
        If True a numerical failure (or a liquid leaving its model) raises SimulationError; if
        False it is reported in the result's ``status`` / ``message`` and the partial history
        is returned.
    n_cells : int
        Film cells around each wall of a liquid [-].

    Returns
    -------
    Simulation or LiquidSimulation
        The run (:class:`autobalance.simulate.result.Run`: ``status``, ``message``, ``note``,
        ``summary()``, ``to_xarray()``, ``to_netcdf(path)``, ``figure()``).

    Raises
    ------
    ResourceError
        Before integrating: the run cannot finish within ``options.max_steps`` (lower bound of
        the steps) or the run-time limit, or its stored history exceeds the memory limit
        (:mod:`autobalance.limits`).
    """
    initial = initial or InitialState()
    options = options or SimOptions()
    if system.liquid is not None:
        from .hybrid import liquid_run, simulate_hybrid     # the liquid models load on demand

        if system.balancer.n_balls:                # balls beside a liquid
            return simulate_hybrid(system, spin, initial=initial, options=options, throw=throw)
        run = liquid_run(system, spin, n_cells=n_cells)
        if throw and run.status != "ok":
            raise SimulationError(run.message)
        return run
    check_run(system, spin, options)
    return run_packed(system, spin, initial, options,
                      run_inputs(system, spin, initial, options), throw)


def run_packed(system: System, spin: SpeedProfile | MotorDrive, initial: InitialState,
               options: SimOptions, r: RunInputs, throw: bool = True) -> Simulation:
    """The balls' kernel on the inputs :func:`~.pack.run_inputs` packed for this run (``r``;
    :func:`simulate` checks the run against the limits first).

    Parameters
    ----------
    system : System
        The machine (SI dataclasses; the result keeps it).
    spin : SpeedProfile or MotorDrive
        Prescribed spin speed [rad/s] vs time [s], or a motor torque law.
    initial : InitialState
        Ball angles [rad], rotor displacement [m] and velocity [m/s] at the start.
    options : SimOptions
        Tolerances, step budget, output spacing.
    r : RunInputs
        The kernel's inputs; its history and statistics arrays are filled.
    throw : bool
        Raise SimulationError on a numerical failure, else report it in ``status``.

    Returns
    -------
    Simulation
    """
    integrate(r.P, r.B, system.balancer.n_balls, r.prof_t, r.prof_w, r.unb_t, r.unb_u, r.y0,
              r.t_end, options.rtol, r.atol, r.h_max, int(options.max_steps), r.out_t, r.out_y,
              r.stats)
    sim = Simulation(system, spin, initial, options, r.out_t, r.out_y, r.stats, r.order)
    if throw and sim.status != "ok":
        raise SimulationError(sim.message)
    return sim


def _pack_runs(systems: list[System], spin, initials, options: SimOptions):
    """The kernel arrays of many runs of one spin (simulate_batch, simulate_branches): P, B,
    N, y0, ball orders, atol, unbalance tables (unb_t, unb_u padded to the longest, unb_n); checks
    the run against the limits with the stiffest suspension (the largest step bound)."""
    if not systems:
        raise ValueError("simulate_batch: systems is empty")
    n_runs = len(systems)
    if initials is None:
        initials = [InitialState()] * n_runs
    if len(initials) != n_runs:
        raise ValueError(f"simulate_batch: {len(initials)} initial states for {n_runs} systems")
    N = systems[0].balancer.n_balls
    if any(s.balancer.n_balls != N for s in systems):
        raise ValueError("simulate_batch: all systems must have the same number of balls")
    check_run(max(systems, key=lambda s: max(s.natural_frequencies)), spin, options)
    packed = [pack_params(s, spin, options) for s in systems]
    Ps = np.stack([p for p, _ in packed])
    Bs = np.stack([b for _, b in packed]) if N else np.zeros((n_runs, 0, 8))
    inits = [initial_vector(s, spin, i) for s, i in zip(systems, initials)]
    y0 = np.stack([y for y, _ in inits])
    orders = np.stack([o for _, o in inits]) if N else np.zeros((n_runs, 0), int)
    atol = np.stack([atol_vector(s, spin, options) for s in systems])
    tables = [s.rotor.unbalance_table() for s in systems]
    unb_n = np.array([t.size for t, _ in tables], np.int64)
    K = int(unb_n.max())
    unb_t = np.zeros((n_runs, K))
    unb_u = np.zeros((n_runs, K))
    for r, (t, u) in enumerate(tables):
        unb_t[r, :t.size], unb_t[r, t.size:] = t, t[-1]
        unb_u[r, :u.size], unb_u[r, u.size:] = u, u[-1]
    return Ps, Bs, N, y0, orders, atol, unb_t, unb_u, unb_n


def simulate_batch(systems: list[System], spin: SpeedProfile | MotorDrive,
                   initials: list[InitialState] | None = None, *, options: SimOptions | None = None,
                   out_times: npt.ArrayLike | None = None) -> BatchResult:
    """Run many parameter / initial-condition sets of the same ball count in one compiled call.

    All runs share the spin profile; everything else (parameters, unbalance schedule, initial
    state) is per run. They run in parallel threads (core/batch.py). Only the states at ``out_times`` [s] (default: the
    profile's checkpoints; any order, the result keeps it) and the run statistics are kept. A failed run is a status in the
    result, never an exception; a batch that cannot fit the step budget or the run-time limit
    (:func:`autobalance.limits.check_run`) is refused before it starts (ResourceError).

    Parameters
    ----------
    systems : list of System
        One machine per run, all with the same number of balls.
    spin : SpeedProfile or MotorDrive
        The spin shared by all runs.
    initials : list of InitialState or None
        One initial state per run (None: the default state for every run).
    options : SimOptions or None
        Numerical options shared by all runs (None: the defaults).
    out_times : array_like or None
        Times at which the states are kept [s] (None: ``spin.checkpoints``).

    Returns
    -------
    BatchResult
        States (n_runs, n_times, 2*nq), ball angles [rad], residual unbalance [kg*m], grade G
        [mm/s], maximal amplitude [m] and one status label per run.

    Raises
    ------
    ValueError
        No systems, a number of initial states other than of systems, or different ball
        counts.
    ResourceError
        Before integrating: the step budget or the run-time limit cannot be met.
    """
    options = options or SimOptions()
    Ps, Bs, N, y0, orders, atol, unb_t, unb_u, unb_n = _pack_runs(systems, spin, initials, options)
    prof_t, prof_w, t_end = spin_arrays(spin)
    out_t = np.asarray(spin.checkpoints if out_times is None else out_times, float)
    # the integrator fills its output times in increasing order: sort, then restore the caller's
    order = np.argsort(out_t, kind="stable")
    out_ys = np.zeros((len(systems), out_t.size, y0.shape[1]))
    stats = np.zeros((len(systems), N_S))
    integrate_batch(Ps, Bs, N, prof_t, prof_w, unb_t, unb_u, unb_n, y0, t_end, options.rtol,
                    atol, _h_max(spin, options), int(options.max_steps), out_t[order], out_ys,
                    stats)
    out_y = np.empty_like(out_ys)
    out_y[:, order] = out_ys
    status = [RunStatus.of(s).label for s in stats[:, S_STATUS]]
    return BatchResult(systems, spin, options, out_t, out_y, stats, orders, status)


def branch_knot(spins: list) -> float:
    """The knot time t_b [s] up to which the speed profiles ``spins`` agree, when runs of them can
    share their history up to it (:func:`simulate_branches`): the latest profile knot with 0 <
    t_b < duration before which every knot (time and speed) is the same, for prescribed
    profiles of one nominal speed (it sets the grade and the tolerances) and one duration (it
    sets the largest step); 0.0 when there is none (also for fewer than two profiles, or a
    motor drive).

    Parameters
    ----------
    spins : list of SpeedProfile or MotorDrive
        The profiles.

    Returns
    -------
    float
        The branch knot t_b [s], or 0.0.
    """
    if len(spins) < 2 or not all(isinstance(s, SpeedProfile) for s in spins):
        return 0.0
    if len({float(s.nominal_speed) for s in spins}) > 1 or len({float(s.duration) for s in spins}) > 1:
        return 0.0
    knots = [spin_arrays(s)[:2] for s in spins]
    t0, w0 = knots[0]
    j = 0
    while j + 1 < min(t.size for t, _ in knots) and all(
            t[j + 1] == t0[j + 1] and w[j + 1] == w0[j + 1] for t, w in knots):
        j += 1
    t_b = float(t0[j])
    return t_b if 0.0 < t_b < spins[0].duration else 0.0


def simulate_branches(systems: list[System], spins: list[SpeedProfile],
                      initials: list[InitialState] | None = None, *,
                      options: SimOptions | None = None,
                      out_times: npt.ArrayLike | None = None) -> list[BatchResult]:
    """:func:`simulate_batch` of every run under each of several speed profiles that agree up to
    a knot (:func:`branch_knot`; e.g. the plateau speeds of a temporary speed reduction after the
    same run-up): each run's history up to the knot is integrated once and continued under
    every profile. The results are those of separate :func:`simulate_batch` calls, bit for bit.

    Parameters
    ----------
    systems : list of System
        One machine per run, all with the same number of balls.
    spins : list of SpeedProfile
        The profiles, at least two, equal up to a knot after t = 0.
    initials : list of InitialState or None
        One initial state per run (None: the default state for every run).
    options : SimOptions or None
        Numerical options shared by all runs (None: the defaults).
    out_times : array_like or None
        Times at which the states are kept [s] (None: the first profile's checkpoints).

    Returns
    -------
    list of BatchResult
        One per profile, in the order of ``spins``.

    Raises
    ------
    ValueError
        Profiles without a shared knot (:func:`branch_knot` is 0), and as simulate_batch.
    ResourceError
        Before integrating: a profile's step budget or the run-time limit cannot be met.
    """
    options = options or SimOptions()
    t_b = branch_knot(spins)
    if not t_b:
        raise ValueError("simulate_branches: the speed profiles share no knot after t = 0 "
                         "(prescribed profiles of one nominal speed and duration)")
    for sp in spins[1:]:
        check_run(max(systems, key=lambda s: max(s.natural_frequencies)), sp, options)
    Ps, Bs, N, y0, orders, atol, unb_t, unb_u, unb_n = _pack_runs(systems, spins[0], initials,
                                                                  options)
    knots = [spin_arrays(sp) for sp in spins]
    prof_n = np.array([t.size for t, _, _ in knots], np.int64)
    prof_t = np.zeros((len(spins), int(prof_n.max())))
    prof_w = np.zeros_like(prof_t)
    for f, (t, w, _) in enumerate(knots):
        prof_t[f, :t.size], prof_w[f, :w.size] = t, w
    t_end = np.array([te for _, _, te in knots])
    out_t = np.asarray(spins[0].checkpoints if out_times is None else out_times, float)
    order = np.argsort(out_t, kind="stable")
    S, F = len(systems), len(spins)
    out_ys = np.zeros((F * S, out_t.size, y0.shape[1]))
    stats = np.zeros((F * S, N_S))
    integrate_branches(Ps, Bs, N, prof_t, prof_w, prof_n, unb_t, unb_u, unb_n, y0, t_end, t_b,
                       options.rtol, atol, _h_max(spins[0], options), int(options.max_steps),
                       out_t[order], out_ys, stats)
    out_y = np.empty_like(out_ys)
    out_y[:, order] = out_ys
    return [BatchResult(systems, sp, options, out_t, out_y[f * S:(f + 1) * S],
                        stats[f * S:(f + 1) * S], orders,
                        [RunStatus.of(s).label for s in stats[f * S:(f + 1) * S, S_STATUS]])
            for f, sp in enumerate(spins)]
