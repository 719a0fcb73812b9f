"""Linear stability of a rotor whose liquid is a film on the chamber wall, at a constant speed,
about its centred state (no unbalance: the rotor on the axis, every film uniform and at rest on
its wall). This is the classical question of partly filled rotors: they can whirl
asynchronously above resonance (Kollmann 1962; Wolf 1968, ASME J. Appl. Mech. 35, 676-682;
Ehrich 1992), which the quasi-static liquid (liquid/steady.py) cannot show (docs/liquid.md
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
from typing import TYPE_CHECKING, Callable

import numpy as np

from ..models._validate import ParameterError, positive
from .film import films_state
from .models import VerticalRotor

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from ..models import System

__all__ = ["RingStability", "linear_modes", "machine_stability", "require_vertical",
           "ring_stability", "unstable_ranges"]

#: Relative size of the state's perturbations of the central differences [-].
EPS = 1e-6
#: The map's step as a fraction of the films' CFL step at the centred state [-] (the runs' own step;
#: just below it, so that
#: a perturbed state takes one step too).
DT_FRACTION = 0.999


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
        The linearised map's step [s].
    """

    speed: float
    eigenvalues: np.ndarray
    dt: float

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
                   partitions: int | Sequence[int] = 0) -> RingStability:
    """The linear stability of the centred state of a Jeffcott rotor with the wall films of one
    or more concentric chambers at the constant spin ``speed`` (module docstring).

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

    Returns
    -------
    RingStability
    """
    from ..core.shallow_water import films_dt

    W = positive("speed", speed)
    cells = list(n_cells) if isinstance(n_cells, (list, tuple, np.ndarray)) else [n_cells]
    if any(isinstance(n, bool) or int(n) != n or not 8 <= n <= 1024 for n in cells):
        raise ParameterError("n_cells", n_cells, "must be an integer in [8, 1024]")
    st = films_state(radius, height, volume, density, viscosity,
                     [int(n) for n in cells] if len(cells) > 1 else int(cells[0]), partitions,
                     0.0, 0j)
    Mt = rotor.mass + float(np.sum(st.rhos * [f.volume for f in st.films]))
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


def linear_modes(f: Callable[[np.ndarray], np.ndarray], x0: np.ndarray, scale: np.ndarray,
                 dt: float, n_neutral: int, what: str) -> np.ndarray:
    """The eigenvalues lambda = ln(mu) / dt [1/s] of a one-step map f about its fixed point x0,
    largest real part first: the Jacobian by central differences (step EPS x ``scale`` per
    state entry), its eigenvalues mu, and the ``n_neutral`` closest to 1 dropped after checking
    |mu - 1| < 1e-7 (the conserved volumes, a balanced family: steady states that decide
    nothing; ``what`` names the caller in the error).

    Parameters
    ----------
    f : callable
        x -> x after one step dt of the linearised scheme (state units as x0's).
    x0 : ndarray
        The fixed point [mixed: each entry's own unit].
    scale : ndarray
        Each entry's perturbation scale [mixed: the entry's unit].
    dt : float
        The map's step [s].
    n_neutral : int
        Neutral modes to drop [-].
    what : str
        The caller, for the error message.

    Returns
    -------
    ndarray of complex
        lambda [1/s], sorted by decreasing real part (a mode the map sends to 0: -inf).
    """
    J = np.empty((x0.size, x0.size))
    for j in range(x0.size):
        e = EPS * scale[j]
        xp = x0.copy()
        xm = x0.copy()
        xp[j] += e
        xm[j] -= e
        J[:, j] = (f(xp) - f(xm)) / (2.0 * e)
    mu = np.linalg.eigvals(J).astype(complex)
    near = np.argsort(np.abs(mu - 1.0))[:n_neutral]
    if n_neutral and np.max(np.abs(mu[near] - 1.0)) > 1e-7:
        raise RuntimeError(f"{what}: the neutral modes were not found "
                           f"(|mu - 1| = {np.max(np.abs(mu[near] - 1.0)):.3g})")
    mu = np.delete(mu, near)
    with np.errstate(divide="ignore"):
        lam = np.log(mu) / dt
    return lam[np.argsort(-lam.real)]


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


def require_vertical(system: System) -> None:
    """One-line error unless the machine's liquid turns about a vertical axis: the balanced
    state (uniform films) is a fixed point of the rotor frame only without gravity in the
    chamber's plane.

    Parameters
    ----------
    system : autobalance.models.System
        A machine with a ``[liquid]`` section.
    """
    system.liquid.vertical("for the linear stability (its centred state, uniform films, exists "
                           "without gravity in the chamber's plane); autobalance simulate runs a "
                           "horizontal machine")


def machine_stability(system: System, speeds: npt.ArrayLike, n_cells: int = 64) -> dict:
    """:func:`ring_stability` of a machine's ``[liquid]`` section over ``speeds``: the growth
    rate and whirl frequency of its least stable perturbation and the unstable ranges.

    Parameters
    ----------
    system : autobalance.models.System
        A liquid balancer alone on a vertical axis (the centred state is uniform there only;
        balls are not in the linearisation); its rotor M [kg], k [N/m], c [N*s/m].
    speeds : array_like
        Increasing speeds [rad/s], > 0.
    n_cells : int
        Cells around each wall [-].

    Returns
    -------
    dict
        omega_rad_s, growth_rate_1_s, whirl_frequency_rad_s (rotor frame; both NaN below
        film_from_rad_s, the largest entrainment speed, 003 eq 6, where a pool is not a film),
        unstable_ranges_rad_s, omega_n_rad_s (the rotor with its liquid as a rigid mass), cells.
    """
    from .simulate import chamber_cells, film_rotor, require_liquid_machine
    from .start import film_start_speed

    require_liquid_machine(system)
    L = system.liquid
    if system.balancer.n_balls:
        raise ParameterError("balancer.n_balls", system.balancer.n_balls, "must be 0: the "
                             "linear stability has the liquid's films and the rotor, not balls")
    require_vertical(system)
    from .steady import increasing_speeds

    W = increasing_speeds(speeds)
    rotor = film_rotor(system)
    ch = L.chambers
    # below a chamber's entrainment speed (003 eq 6) its liquid is a pool, not a film
    w0 = film_start_speed(L)
    g = np.full(W.size, np.nan)
    f = np.full(W.size, np.nan)
    for i, w in enumerate(W):
        if w >= w0:
            r = ring_stability(rotor, [c.chamber_radius for c in ch],
                               [c.chamber_height for c in ch], [c.volume for c in ch], w,
                               density=L.density, viscosity=L.kinematic_viscosity,
                               n_cells=chamber_cells(ch, n_cells),
                               partitions=[c.partitions for c in ch])
            g[i], f[i] = r.growth_rate, r.whirl_frequency
    return {"omega_rad_s": W, "growth_rate_1_s": g, "whirl_frequency_rad_s": f,
            "film_from_rad_s": w0, "unstable_ranges_rad_s": unstable_ranges(W, g),
            "omega_n_rad_s": rotor.natural_frequency(L.density * L.total_volume),
            "cells": int(n_cells)}
