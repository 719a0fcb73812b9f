"""The balanced state of balls beside a liquid and its linear stability at a constant speed
(docs/liquid/stability.md sec. 3k): the rotor on the axis, the balls where they cancel the
unbalance, every film uniform and at rest on its wall. Whether it stays balanced decides what
the speed map reports for such a machine.

Method (our choice, as sec. 3j for a liquid alone): the linearisation of the coupling the run of
balls beside a liquid uses (core/hybrid.py), one film step dt at a time:

1. every film takes one step of :func:`autobalance.core.shallow_water.films_step`, forced by the
   chamber's deflection w, rate w' and the last step's w'' (rotor frame);
2. the rotor and the balls advance over dt with the films' moment U and rate U' held: here by
   the exact propagator expm([[A, B], [0, 0]] dt) of the kernel's right-hand side linearised
   about the balanced state (A: the ideal machine, rolling resistance and dry friction off, as
   the balls-alone speed map; B: the held moment's pull W^2 U - 2 i W U'; both central
   differences of :func:`autobalance.simulate.probe.rotor_frame_derivative`). The run
   integrates the same equations with DOPRI5 to its tolerance;
3. the films' new moment is taken up by the chamber, Z and Z' kept: w -= (dU - U' dt) / M_t,
   w' -= dU' / M_t.

The eigenvalues of the map's Jacobian (:func:`autobalance.liquid.stability.linear_modes`) give
the growth rates; a compartment's volume and, for N >= 3 balls, the balanced family's N - 2
directions are neutral and dropped. The liquid's mass moves with the rotor; below the film's
start (003 eq 6) the liquid is a pool and the balls-alone closed forms hold on
:func:`autobalance.liquid.start.pool_machine`. On a horizontal axis the same map over a
revolution, Floquet's about the periodic state under gravity (studies/liquid_floquet.py,
sec. 3m).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..liquid.stability import DT_FRACTION, RingStability, linear_modes
from ..models import ParameterError
from ..models._validate import positive
from .ball_propagator import ball_propagator as _ball_propagator
from .ball_propagator import flat as _flat

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = ["balanced_machine_stability", "balanced_stability", "require_balanced_liquid",
           "uniform_films"]

#: The balanced state's residual force, scaled by (L w^2, w^2), above which ``alpha`` is refused [-].
BALANCED_TOL = 1e-9


def uniform_films(system: System, n_cells: int):
    """The chambers' films uniform and at rest on the centred wall: the runs' own films
    (:func:`autobalance.liquid.simulate.chamber_films`: the wall film's checks, the cells
    rounded up to whole compartments) with no lag.

    Parameters
    ----------
    system : autobalance.models.System
        A ``[liquid]`` section.
    n_cells : int
        Cells per chamber [-] before rounding.

    Returns
    -------
    autobalance.liquid.film.FilmsState
    """
    from ..liquid.simulate import chamber_films
    from ..liquid.start import FilmStart

    lag = (0.0,) * len(system.liquid.chambers)
    return chamber_films(system, FilmStart(0.0, 0.0, lag, "quasi-static"), n_cells, 0j)


def require_balanced_liquid(system: System) -> System:
    """One-line errors for a machine of balls beside a liquid whose balanced state is neither a
    fixed point of the rotor frame with uniform films nor, on a horizontal axis, a periodic
    state about one (an anisotropic suspension, base motion, an unbalance schedule, a race
    eccentricity, gravity that does not fit the axis, a family of 3 or more balls under
    gravity) or whose liquid is not a thin wall film (:func:`uniform_films`'s checks, before
    any work); returns its ideal pool machine (the liquid's mass in the rotor's, rolling
    resistance and dry friction off; in-plane gravity kept).

    Parameters
    ----------
    system : autobalance.models.System
        Balls and a ``[liquid]`` section.

    Returns
    -------
    autobalance.models.System
    """
    from ..liquid.simulate import require_axis_gravity
    from ..liquid.start import pool_machine
    from .equilibria import _ideal, steady_rotor_frame

    if system.liquid is None or system.balancer.n_balls < 1:
        raise ParameterError("machine", system.name or "machine",
                             "needs balls and a [liquid] section for the balanced state beside "
                             "a liquid")
    require_axis_gravity(system)
    if system.liquid.axis == "horizontal" and system.balancer.n_balls > 2:
        raise ParameterError("balancer.n_balls", system.balancer.n_balls, "must be 1 or 2 beside "
                             "a liquid on a horizontal axis (gravity keeps the balanced family "
                             "of 3 or more balls only nearly; not yet)")
    if system.balancer.eccentricity != 0.0:
        raise ParameterError("balancer.eccentricity", system.balancer.eccentricity,
                             "must be 0 beside a liquid: the balanced state then has a residual "
                             "whirl, and the films are not uniform")
    uniform_films(system, 64)
    pool = pool_machine(system)
    if not steady_rotor_frame(_flat(pool)):
        s = system.suspension
        raise ParameterError("suspension", f"kx {s.kx:.6g} N/m, ky {s.ky:.6g} N/m",
                             "must be isotropic, without base motion or an unbalance schedule, "
                             "for the balanced state beside a liquid (a fixed point of the "
                             "rotor frame)")
    return _ideal(pool)


def balanced_stability(system: System, speed: float, alpha: npt.ArrayLike, *,
                       n_cells: int = 64, family: bool = False) -> RingStability:
    """The linear stability of a balanced state of balls beside a liquid at the constant spin
    ``speed`` (module docstring); on a horizontal axis Floquet's about its periodic state under
    gravity (:func:`autobalance.studies.liquid_floquet.balanced_floquet`,
    docs/liquid/horizontal-axis.md sec. 3m).

    Parameters
    ----------
    system : autobalance.models.System
        Balls and a ``[liquid]`` section, isotropic suspension (:func:`require_balanced_liquid`;
        on a horizontal axis one or two balls and [gravity] in the plane); M [kg], k [N/m],
        c [N*s/m], the balls' m [kg], R [m] and damping.
    speed : float
        Omega [rad/s], > 0, where every chamber's liquid is a film (above 003 eq 6's
        entrainment speed: the caller's choice).
    alpha : array_like (N,)
        The balanced state's ball angles [rad] (sum m_i R e^{i alpha_i} cancels the unbalance;
        :func:`autobalance.physics.equilibria.find_equilibrium_set`; without gravity).
    n_cells : int
        Cells around each wall [-].
    family : bool
        alpha lies on a balanced family (N >= 3): its N - 2 neutral directions are dropped.

    Returns
    -------
    autobalance.liquid.stability.RingStability
        Growth rates [1/s] of every mode (rotor frame), the step dt [s].
    """
    from ..core.shallow_water import films_dt, films_moment, films_step

    W = positive("speed", speed)
    pool = require_balanced_liquid(system)
    if isinstance(n_cells, bool) or int(n_cells) != n_cells or not 8 <= n_cells <= 1024:
        raise ParameterError("n_cells", n_cells, "must be an integer in [8, 1024]")
    N = system.balancer.n_balls
    a = np.asarray(alpha, float).ravel()
    if a.size != N or not np.all(np.isfinite(a)):
        raise ParameterError("alpha", a.tolist(), f"must be {N} finite ball angles [rad]")
    ch = system.liquid.chambers
    st = uniform_films(system, int(n_cells))
    Mt = pool.total_mass
    L = max(pool.rotor.unbalance, pool.balancer.capacity) / Mt
    dt = DT_FRACTION * films_dt(st.h, st.q, st.starts, st.Rs, W, math.inf)
    Phi, Gam, _, res = _ball_propagator(_flat(pool), W, a, dt, L)
    if res > BALANCED_TOL:
        raise ParameterError("alpha", [round(float(x), 6) for x in a],
                             f"is not a balanced state at {W:.6g} rad/s (scaled residual "
                             f"force {res:.3g})")
    if system.liquid.axis == "horizontal":
        from .liquid_floquet import balanced_floquet

        return balanced_floquet(system, pool, W, a, st)
    m = Phi.shape[0]
    nc = st.h.size
    work = [np.zeros(nc) for _ in range(9)]
    z_ref = np.concatenate([[0.0, 0.0], a, np.zeros(N + 2)])
    r = N + 2                                   # index of the rotor's rate u'

    def step(x):
        z = x[:m]
        h, q = x[m + 2:m + 2 + nc].copy(), x[m + 2 + nc:].copy()
        w, wd = complex(z[0], z[1]), complex(z[r], z[r + 1])
        films_step(h, q, st.theta, st.starts, st.Rs, st.nus, st.wall, W, 0.0, w, 0j, wd,
                   complex(x[m], x[m + 1]), dt, *work)
        U, Ud = films_moment(h, q, st.theta, st.starts, st.Rs, st.Hs, st.rhos)
        U1, Ud1 = films_moment(work[0], work[1], st.theta, st.starts, st.Rs, st.Hs, st.rhos)
        z1 = z_ref + Phi @ (z - z_ref) + Gam @ np.array([U.real, U.imag, Ud.real, Ud.imag])
        dU, dUd = (U1 - U - dt * Ud) / Mt, (Ud1 - Ud) / Mt
        z1[0] -= dU.real
        z1[1] -= dU.imag
        z1[r] -= dUd.real
        z1[r + 1] -= dUd.imag
        wdd = (complex(z1[r], z1[r + 1]) - wd) / dt
        return np.concatenate([z1, [wdd.real, wdd.imag], work[0], work[1]])

    hs = float(np.max(st.h))
    x0 = np.concatenate([z_ref, [0.0, 0.0], st.h, st.q])
    scale = np.concatenate([[hs] * 2, [1.0] * N, [hs * W] * 2, [W] * N, [hs * W * W] * 2,
                            np.full(nc, hs), np.full(nc, hs * W * float(np.max(st.Rs)))])
    n_neutral = sum(max(1, c.partitions) for c in ch) + (N - 2 if family else 0)
    return RingStability(W, linear_modes(step, x0, scale, dt, n_neutral, "balanced_stability"),
                         dt)


def _balanced_states(system, w: float) -> list:
    """(alpha [rad], family) of every reachable balanced state at w [rad/s] of the machine with
    its liquid as a pool, without in-plane gravity (the balls' closed forms; a family's four
    sample points)."""
    from ..liquid.start import pool_machine
    from ..physics.equilibria import find_equilibrium_set

    es = find_equilibrium_set(_flat(pool_machine(system)), w, method="closed_form",
                              n_samples=4)
    out = [(e.alpha, False) for e, b in zip(es.isolated, es.balanced) if b and not e.overlap]
    return out + [(p.alpha, True) for f in es.families for p in f.points if not p.overlap]


def balanced_machine_stability(system: System, speeds: npt.ArrayLike,
                               n_cells: int = 64) -> dict:
    """The balanced state of balls beside a liquid over ``speeds``: the growth rate and whirl
    frequency of its least stable perturbation (of its most stable sample on a family), the
    unstable ranges, and the balls' angles. Below the film's start (003 eq 6) the liquid is a
    pool and the balls' linearised full model of the pool machine decides
    (:func:`autobalance.studies.equilibria.linearised_full`; on a horizontal axis, where it is
    a puddle, their Floquet multipliers, :func:`autobalance.studies.equilibria.floquet_full`);
    from there :func:`balanced_stability` (Floquet about the periodic state under gravity on a
    horizontal axis, docs/liquid/horizontal-axis.md sec. 3m).

    Parameters
    ----------
    system : autobalance.models.System
        Balls and a ``[liquid]`` section (:func:`require_balanced_liquid`).
    speeds : array_like
        Increasing speeds [rad/s], > 0.
    n_cells : int
        Cells around each wall [-].

    Returns
    -------
    dict
        As :func:`autobalance.liquid.stability.machine_stability` (omega_rad_s,
        growth_rate_1_s, whirl_frequency_rad_s, film_from_rad_s, unstable_ranges_rad_s,
        omega_n_rad_s, cells; NaN where no balanced state exists: the balls' capacity is short),
        ball_angles_rad (speed, ball), axis, no_periodic_film_rad_s (speeds left undecided:
        no periodic state with an intact film under gravity).
    """
    from ..liquid.start import film_start_speed
    from ..liquid.stability import NoPeriodicFilm, unstable_ranges
    from .equilibria import floquet_full, linearised_full

    pool = require_balanced_liquid(system)
    from ..liquid.steady import increasing_speeds

    W = increasing_speeds(speeds)
    N = system.balancer.n_balls
    horizontal = system.liquid.axis == "horizontal"
    w0 = film_start_speed(system.liquid, system.gravity.g)
    g, f = np.full(W.size, np.nan), np.full(W.size, np.nan)
    angles = np.full((W.size, N), np.nan)
    none = []
    for i, w in enumerate(W):
        for a, fam in _balanced_states(system, float(w)):
            if w >= w0:
                try:
                    r = balanced_stability(system, w, a, n_cells=n_cells, family=fam)
                except NoPeriodicFilm:          # under gravity: not decided
                    none.append(float(w))
                    continue
                gi, fi = r.growth_rate, r.whirl_frequency
            elif horizontal:        # the balls' Floquet multipliers with the liquid as a puddle
                lf = floquet_full(pool, w, a)
                gi = math.log(max(lf["max_modulus"], 1e-300)) * w / (2 * math.pi)
                fi = float(abs(np.angle(lf["multipliers"][np.argmax(np.abs(
                    lf["multipliers"]))]))) * w / (2 * math.pi)
            else:
                lf = linearised_full(pool, w, a, family=fam)
                gi = math.log(max(lf["max_modulus"], 1e-300)) * w / (2 * math.pi)
                lam = lf["eigenvalues_1_s"]
                fi = float(abs(lam[np.argmin(np.abs(lam.real - gi))].imag))
            if not np.isfinite(g[i]) or gi < g[i]:
                g[i], f[i], angles[i] = gi, fi, a
    return {"omega_rad_s": W, "growth_rate_1_s": g, "whirl_frequency_rad_s": f,
            "film_from_rad_s": w0, "unstable_ranges_rad_s": unstable_ranges(W, g),
            "omega_n_rad_s": float(system.natural_frequencies[0]), "cells": int(n_cells),
            "ball_angles_rad": angles, "axis": system.liquid.axis,
            "no_periodic_film_rad_s": sorted(set(none))}
