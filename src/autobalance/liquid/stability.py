"""Linear stability of a rotor whose liquid is a film on the chamber wall, at a constant speed,
about its centred state (no unbalance: the rotor on the axis, every film uniform and at rest on
its wall). This is the classical question of partly filled rotors: they can whirl
asynchronously above resonance (Kollmann 1962; Wolf 1968, ASME J. Appl. Mech. 35, 676-682;
Ehrich 1992), which the quasi-static liquid (liquid/steady.py) cannot show (docs/liquid/stability.md
sec. 3j).

Method (our choice): the linearisation of the very scheme the film runs use. One time step
dt of :func:`autobalance.core.shallow_water.sw_coupled` (the films' finite volumes coupled with
the Jeffcott rotor) maps the state x = (Z, Z', w'', eta, q) to the next; its Jacobian at the
centred state, by central differences, has eigenvalues mu, and lambda = ln(mu) / dt are the
growth rates [1/s] and whirl frequencies [rad/s] (rotor frame) of the state's small
perturbations. The largest real part decides: > 0 unstable. As the run's own map is
linearised, a film run started near the centred state grows or decays at exactly that rate
(tests/test_liquid_stability.py); the cells and dt set how close it is to the continuous
film's (their convergence is tested there too).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..models._validate import ParameterError, positive
from .film import FilmsState, films_state
from .maps import (SHOOT_TOL, FinerGrid, compartments, jacobian, linear_modes,
                   multiplier_modes, periodic_state)
from ..models.liquid_balancer import VerticalRotor

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from ..models import System

__all__ = ["NoPeriodicFilm", "RingStability", "compartments", "jacobian", "linear_modes",
           "machine_stability", "multiplier_modes", "periodic_state",
           "ring_floquet", "ring_stability", "unstable_ranges"]

#: The map's step as a fraction of the films' CFL step at the centred state [-] (the runs' own step;
#: just below it, so that
#: a perturbed state takes one step too).
DT_FRACTION = 0.999
#: Fractions of the in-plane gravity through which the shooting continues where the full
#: gravity at once does not converge (the films' flow then changes friction law on the way) [-].
GRAVITY_LADDER = (1.0 / 16.0, 1.0 / 8.0, 0.25, 0.5, 0.75, 1.0)
#: A periodic state thinner than this fraction of a film's mean thickness somewhere is a film
#: breaking into a crescent: its map is not smooth there and no verdict is claimed [-].
WET_FRACTION = 0.02


class NoPeriodicFilm(ParameterError):
    """Under gravity no periodic state with an intact film was found at this speed (the film
    breaks into a crescent, or the shooting found none): the linear stability claims no
    verdict there."""


@dataclass(frozen=True)
class RingStability:
    """Result of :func:`ring_stability`.

    Attributes
    ----------
    speed : float
        Omega [rad/s].
    eigenvalues : ndarray of complex
        lambda = ln(mu) / dt of every mode [1/s], largest real part first.
    dt : float
        The linearised map's step [s] (on a horizontal axis the period 2 pi / Omega).
    state : ndarray or None
        The state linearised about, as the map's state vector [mixed units] (on a horizontal
        axis the periodic state at the spin angle 0; None: the centred state).
    steps : int
        The scheme's steps in the map [-] (1; on a horizontal axis the period's grid).
    """

    speed: float
    eigenvalues: np.ndarray
    dt: float
    state: np.ndarray | None = None
    steps: int = 1

    @property
    def growth_rate(self) -> float:
        """Largest real part of the eigenvalues [1/s] (> 0: unstable)."""
        return float(self.eigenvalues[0].real)

    @property
    def whirl_frequency(self) -> float:
        """|Im| of the least stable eigenvalue [rad/s] (rotor frame)."""
        return float(abs(self.eigenvalues[0].imag))

    @property
    def stable(self) -> bool:
        """Every perturbation decays."""
        return self.growth_rate < 0.0


def _step_map(rotor, st, Mt, speed, dt):
    """x -> x after one step of sw_coupled at the constant ``speed`` [rad/s], on the real
    state vector (Z, Z', w'' as real pairs [kg*m, kg*m/s, m/s^2], then eta [m], q [m^2/s])."""
    from ..core.shallow_water import sw_coupled

    n = st.h.size
    tt = np.array([0.0, 1.0])
    tw = np.full(2, float(speed))
    empty = np.zeros(0)

    def f(x):
        h = x[6:6 + n].copy()
        q = x[6 + n:].copy()
        work = [np.zeros(n) for _ in range(9)]
        steps, Z, Y, wdd = sw_coupled(h, q, st.theta, st.starts, st.Rs, st.Hs, st.rhos, st.nus,
                                      Mt, rotor.stiffness, rotor.damping, 0.0,
                                      complex(x[0], x[1]), complex(x[2], x[3]), dt, tt, tw,
                                      0.0, 0.0, st.wall, empty, np.zeros((0, n)),
                                      np.zeros((0, n)), np.zeros(0, complex), *work,
                                      complex(x[4], x[5]))
        if steps != 1:
            raise RuntimeError(f"ring_stability: the map took {steps} steps, not 1")
        return np.concatenate([[Z.real, Z.imag, Y.real, Y.imag, wdd.real, wdd.imag], h, q])

    return f


def ring_stability(rotor: VerticalRotor, radius: float | Sequence[float],
                   height: float | Sequence[float], volume: float | Sequence[float],
                   speed: float, *, density: float = 1000.0, viscosity: float = 1.0e-6,
                   n_cells: int | Sequence[int] = 64,
                   partitions: int | Sequence[int] = 0,
                   gravity: float = 0.0) -> RingStability:
    """The linear stability of the centred state of a Jeffcott rotor with the wall films of one
    or more concentric chambers at the constant spin ``speed`` (module docstring); with gravity
    in the chamber's plane (a horizontal axis), of its periodic state (:func:`ring_floquet`).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg] (without the liquid), k [N/m], c [N*s/m]; its unbalance is not used (the centred
        state is the balanced one).
    radius, height : float or sequence
        Chamber R, H [m] (a sequence: one chamber each).
    volume : float or sequence
        Liquid volume V [m^3] (a wall film, :func:`autobalance.liquid.film.films_state`).
    speed : float
        Omega [rad/s], > 0.
    density : float
        rho [kg/m^3].
    viscosity : float
        nu [m^2/s].
    n_cells : int or sequence
        Cells around each wall [-] (a sequence: one count per chamber; the Jacobian is square
        in twice their total).
    partitions : int or sequence
        Radial walls per chamber [-].
    gravity : float
        Gravity in the chamber's plane g_p [m/s^2] (a horizontal axis; 0: a vertical one).

    Returns
    -------
    RingStability
    """
    from ..core.shallow_water import films_dt
    from ..models._validate import nonneg

    W = positive("speed", speed)
    gp = nonneg("gravity", gravity)
    cells = list(n_cells) if isinstance(n_cells, (list, tuple, np.ndarray)) else [n_cells]
    if any(isinstance(n, bool) or int(n) != n or not 8 <= n <= 1024 for n in cells):
        raise ParameterError("n_cells", n_cells, "must be an integer in [8, 1024]")
    st = films_state(radius, height, volume, density, viscosity,
                     [int(n) for n in cells] if len(cells) > 1 else int(cells[0]), partitions,
                     0.0, 0j)
    Mt = rotor.mass + float(np.sum(st.rhos * [f.volume for f in st.films]))
    if gp > 0.0:
        return ring_floquet(rotor, st, Mt, W, gp)
    dt = DT_FRACTION * films_dt(st.h, st.q, st.starts, st.Rs, W, math.inf)
    f = _step_map(rotor, st, Mt, W, dt)
    n = st.h.size
    x0 = np.concatenate([np.zeros(6), st.h, st.q])
    # perturbation sizes per block: the rotor's moment on the film's scale, the film's own
    hscale = float(np.max(st.h))
    scale = np.concatenate([np.full(2, Mt * hscale), np.full(2, Mt * hscale * W),
                            np.full(2, hscale * W * W), np.full(n, hscale),
                            np.full(n, hscale * W * float(np.max(st.Rs)))])
    # each compartment keeps its volume: a uniform change of its film is a steady state too, an
    # eigenvalue mu = 1 that decides nothing; one per compartment is dropped
    n_inv = sum(max(1, f.partitions) for f in st.films)
    lam = linear_modes(f, x0, scale, dt, n_inv, "ring_stability")
    return RingStability(W, lam, dt)


def _ring_period_map(rotor, st, Mt: float, W: float, gp: float, m: int):
    """The one-revolution map P of sw_coupled at the constant spin W [rad/s] under in-plane
    gravity gp [m/s^2] (pointing down, -pi/2, at the spin angle 0) in m equal steps, on
    :func:`_step_map`'s state; also the thinnest film [m] of its last evaluation. The steps
    are pinned to the grid by the run's own output times (the kernel steps to each), so P is
    smooth in x; a state whose CFL step is shorter takes more steps: ValueError. m = 0: P
    returns the number of CFL steps a revolution from x takes."""
    from ..core.shallow_water import sw_coupled

    n = st.h.size
    T = 2.0 * math.pi / W
    if m == 0:              # the steps of a revolution at the CFL step, from x
        m, out_t = 1, np.zeros(0)
    else:
        out_t = np.arange(1, m) * (T / m)
    tt = np.array([0.0, 2.0 * T])
    tw = np.full(2, float(W))
    work = [np.zeros(n) for _ in range(9)]
    thinnest = [math.inf]

    def P(x):
        h, q = x[6:6 + n].copy(), x[6 + n:].copy()
        out_h, out_q = np.zeros((out_t.size, n)), np.zeros((out_t.size, n))
        steps, Z, Y, wdd = sw_coupled(h, q, st.theta, st.starts, st.Rs, st.Hs, st.rhos, st.nus,
                                      Mt, rotor.stiffness, rotor.damping, 0.0,
                                      complex(x[0], x[1]), complex(x[2], x[3]), T, tt, tw, gp,
                                      -0.5 * math.pi, st.wall, out_t, out_h, out_q,
                                      np.zeros(out_t.size, complex), *work, complex(x[4], x[5]))
        if not out_t.size:
            return steps
        if steps != m:
            raise ValueError(steps)
        thinnest[0] = min(float(out_h.min()), float(h.min()))
        return np.concatenate([[Z.real, Z.imag, Y.real, Y.imag, wdd.real, wdd.imag], h, q])

    return P, thinnest


def ring_floquet(rotor: VerticalRotor, st: FilmsState, Mt: float, speed: float,
                 gravity: float) -> RingStability:
    """The linear stability of a rotor with wall films under gravity in the chamber's plane (a
    horizontal axis) at a constant spin: Floquet's theory about its periodic state (our
    method, docs/liquid/horizontal-axis.md sec. 3m). Gravity turns at -Omega in the rotor frame, so
    the state the centred state becomes (the rotor's static sag M_t g / k, the films flowing over
    the wall that passes under the potential offset by g / Omega^2) repeats every revolution
    T = 2 pi / Omega in the rotor frame. The scheme's one-revolution map P
    (:func:`_ring_period_map`, m steps of sw_coupled) has that state as a fixed point, found
    by :func:`periodic_state` from :func:`_ring_guess` (where that does not converge, through
    GRAVITY_LADDER's fractions of g); the eigenvalues mu of its monodromy are the Floquet
    multipliers, lambda = ln(mu) / T. A compartment's volume is neutral and dropped (as
    without gravity). Im(lambda) is defined modulo Omega: ``whirl_frequency`` is the one in
    [0, Omega / 2].

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg] (without the liquid), k [N/m], c [N*s/m].
    st : autobalance.liquid.film.FilmsState
        The films (uniform; their layout, walls and properties).
    Mt : float
        M plus the liquids' masses [kg].
    speed : float
        Omega [rad/s], > 0.
    gravity : float
        g_p [m/s^2], > 0.

    Returns
    -------
    RingStability
        ``dt`` is the period T [s], ``state`` the periodic state at the spin angle 0; no
        periodic state with an intact film: :class:`NoPeriodicFilm` on ``speed``.
    """
    from ..core.shallow_water import films_dt

    W, gp = float(speed), float(gravity)
    T = 2.0 * math.pi / W
    n = st.h.size
    hs = float(np.max(st.h))
    scale = np.concatenate([np.full(2, Mt * hs), np.full(2, Mt * hs * W), np.full(2, hs * W * W),
                            np.full(n, hs), np.full(n, hs * W * float(np.max(st.Rs)))])
    groups = [6 + c for c in compartments(st)]
    x_flat = _ring_guess(rotor, st, Mt, W, 0.0)
    # the grid: the CFL step of the guess, or finer where a revolution from it needs more
    m = max(int(math.ceil(T / (DT_FRACTION * films_dt(st.h, st.q, st.starts, st.Rs, W,
                                                      math.inf)))),
            int(math.ceil(1.2 * _ring_period_map(rotor, st, Mt, W, gp, 0)[0](
                _ring_guess(rotor, st, Mt, W, gp)))))
    # gravity in steps from where the film barely feels it, each from the last state scaled
    # (continuation), where the full gravity at once does not converge
    out = None
    for ladder in ((1.0,), GRAVITY_LADDER):
        x, g0 = _ring_guess(rotor, st, Mt, W, gp * ladder[0]), gp * ladder[0]
        for frac in ladder:
            x = x_flat + (x - x_flat) * (gp * frac / g0)
            g0 = gp * frac
            out = _shoot(rotor, st, Mt, W, g0, x, m, scale, groups)
            if out[2] > SHOOT_TOL:
                break
            x, m = out[0], out[3]
        if out[2] <= SHOOT_TOL and g0 == gp:
            break
    x, J, res, m, thinnest = out
    if res > SHOOT_TOL:
        raise NoPeriodicFilm("speed", round(W, 6), "has no periodic state under gravity: the "
                             f"shooting ended at a scaled residual {res:.3g}")
    if thinnest < WET_FRACTION * float(np.min(st.h)):
        raise NoPeriodicFilm("speed", round(W, 6), "has no intact film under gravity there: "
                             f"the film thins to {thinnest:.3g} m (a crescent); the "
                             "linear stability needs a faster spin or more liquid")
    lam = multiplier_modes(J, T, len(groups), "ring_stability")
    return RingStability(W, lam, T, x, m)


def _ring_guess(rotor, st, Mt: float, W: float, gp: float) -> np.ndarray:
    """The first guess of the periodic state under in-plane gravity gp [m/s^2] at the spin W
    [rad/s] (:func:`_step_map`'s state): the chamber at its static sag M_t g / k, held in the
    inertial frame, and the films uniform, turning with the wall."""
    from ..core.shallow_water import films_moment

    sag = Mt * gp / rotor.stiffness * -1j           # down, inertial = rotor frame at psi = 0
    U, Ud = films_moment(st.h, st.q, st.theta, st.starts, st.Rs, st.Hs, st.rhos)
    Z, Y, a = Mt * sag + U, Mt * (-1j * W * sag) + Ud, -W * W * sag
    return np.concatenate([[Z.real, Z.imag, Y.real, Y.imag, a.real, a.imag], st.h, st.q])


def _shoot(rotor, st, Mt, W, gp, x, m, scale, groups):
    """:func:`periodic_state` of the ring's period map from x on m steps a revolution, the grid
    made 1.25 times finer from the state reached where the shooting needs it (up to 6 times):
    (x*, monodromy, scaled residual, m, the thinnest film on the way [m]); the residual is inf
    where no grid served."""
    for _ in range(6):
        P, thinnest = _ring_period_map(rotor, st, Mt, W, gp, m)
        try:
            x, J, res = periodic_state(P, x, scale, groups, "ring_stability")
            P(x)
            return x, J, res, m, thinnest[0]
        except FinerGrid as e:      # a state needed a shorter step than the period's grid
            x, m = e.x, int(math.ceil(1.25 * m))
    return x, None, math.inf, m, 0.0


def unstable_ranges(speeds: np.ndarray, growth: np.ndarray) -> list[tuple[float, float]]:
    """Speed ranges [rad/s] where the growth rate [1/s] on the grid ``speeds`` [rad/s] is > 0,
    each edge where the linear interpolation between grid points crosses 0 (an end of the grid
    where it is still > 0).

    Parameters
    ----------
    speeds : ndarray
        Increasing speeds [rad/s].
    growth : ndarray
        Growth rate at each [1/s] (NaN: not decided, a range ends at the speed before).

    Returns
    -------
    list of (float, float)
    """
    out, lo = [], None
    for i, (w, g) in enumerate(zip(speeds, growth)):
        if not np.isfinite(g):                  # no film there (a pool): not decided
            if lo is not None:
                out.append((float(lo), float(speeds[i - 1])))
                lo = None
            continue
        if g > 0 and lo is None:          # from the grid's first speed or its first film
            lo = (w if i == 0 or not np.isfinite(growth[i - 1]) else
                  w - g * (w - speeds[i - 1]) / (g - growth[i - 1]))
        elif g <= 0 and lo is not None:
            out.append((float(lo), float(w - g * (w - speeds[i - 1]) / (g - growth[i - 1]))))
            lo = None
    if lo is not None:
        out.append((float(lo), float(speeds[-1])))
    return out


def machine_stability(system: System, speeds: npt.ArrayLike, n_cells: int = 64) -> dict:
    """:func:`ring_stability` of a machine's ``[liquid]`` section over ``speeds``: the growth
    rate and whirl frequency of its least stable perturbation and the unstable ranges (about
    the centred state on a vertical axis, the periodic state on a horizontal one).

    Parameters
    ----------
    system : autobalance.models.System
        A liquid balancer alone (balls are not in the linearisation), on a vertical axis or a
        horizontal one with [gravity] in the plane; its rotor M [kg], k [N/m], c [N*s/m].
    speeds : array_like
        Increasing speeds [rad/s], > 0.
    n_cells : int
        Cells around each wall [-].

    Returns
    -------
    dict
        omega_rad_s, growth_rate_1_s, whirl_frequency_rad_s (rotor frame; both NaN below
        film_from_rad_s, the largest entrainment speed, 003 eq 6, where a pool is not a film;
        on a horizontal axis also where the periodic state's film breaks, :class:`NoPeriodicFilm`),
        unstable_ranges_rad_s, omega_n_rad_s (the rotor with its liquid as a rigid mass), cells,
        axis ("vertical" or "horizontal": Floquet about the periodic state, :func:`ring_floquet`),
        no_periodic_film_rad_s (the speeds above the film's start left undecided so).
    """
    from .simulate import chamber_cells, film_rotor, require_liquid_machine
    from .start import film_start_speed

    require_liquid_machine(system)
    L = system.liquid
    if system.balancer.n_balls:
        raise ParameterError("balancer.n_balls", system.balancer.n_balls, "must be 0: the "
                             "linear stability has the liquid's films and the rotor, not balls")
    from .steady import increasing_speeds

    W = increasing_speeds(speeds)
    rotor = film_rotor(system)
    ch = L.chambers
    gp = system.gravity.g if L.axis == "horizontal" else 0.0
    # below a chamber's entrainment speed (003 eq 6; g / Omega^2 = R / 10 on a horizontal axis)
    # its liquid is a pool or a puddle, not a film
    w0 = film_start_speed(L, system.gravity.g)
    g = np.full(W.size, np.nan)
    f = np.full(W.size, np.nan)
    none = []
    for i, w in enumerate(W):
        if w >= w0:
            try:
                r = ring_stability(rotor, [c.chamber_radius for c in ch],
                                   [c.chamber_height for c in ch], [c.volume for c in ch], w,
                                   density=L.density, viscosity=L.kinematic_viscosity,
                                   n_cells=chamber_cells(ch, n_cells),
                                   partitions=[c.partitions for c in ch], gravity=gp)
            except NoPeriodicFilm:          # a crescent under gravity: not decided
                none.append(float(w))
                continue
            g[i], f[i] = r.growth_rate, r.whirl_frequency
    return {"omega_rad_s": W, "growth_rate_1_s": g, "whirl_frequency_rad_s": f,
            "film_from_rad_s": w0, "unstable_ranges_rad_s": unstable_ranges(W, g),
            "omega_n_rad_s": rotor.natural_frequency(L.density * L.total_volume),
            "cells": int(n_cells), "axis": L.axis, "no_periodic_film_rad_s": none}
