"""The liquid film on the outer wall of a rotating, displaced chamber, in time: the
depth-averaged shallow-water equations along the circumference
(:mod:`autobalance.core.shallow_water`, docs/liquid/film.md sec. 3c) driven by a prescribed spin
Omega(t) and a prescribed chamber displacement c(t) in the rotor frame. The film is the liquid
of 003's mode 4 (a ring on the wall, lid to bottom); its first moment about the chamber centre is
the liquid's unbalance. Not yet coupled to the rotor, and no spin-up from rest (modes 1-3).

:func:`film_equilibrium` is the film at rest on the displaced wall (the scheme's well-balanced
steady state, in closed form); it is the thin-film limit of
:func:`autobalance.liquid.quasistatic.quasi_static` (planar axis).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..core.shallow_water import sw_integrate, wall_height
from ..models._validate import ParameterError, finite, nonneg, positive
from ..models.liquid_balancer import G_STANDARD, LiquidBalancer, VerticalRotor

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from .dynamics import RunUp

__all__ = ["CoupledRun", "FilmRun", "FilmsState", "coupled_run", "film_equilibrium", "film_run",
           "film_unbalance", "films_state",
           "film_wave_speed", "physical_run_up"]


def _theta(n: int) -> np.ndarray:
    return (np.arange(n) + 0.5) * (2 * np.pi / n)


def film_unbalance(thickness: npt.ArrayLike, radius: float, height: float,
                   density: float) -> complex:
    """First moment of a thin film about the chamber centre [kg*m]: rho H R^2 sum(eta e^{i
    theta}) dtheta over the cells (thin film: the liquid at radius R).

    Parameters
    ----------
    thickness : array_like (..., n)
        Film thickness eta per cell [m].
    radius : float
        Wall radius R [m].
    height : float
        Chamber height H [m] (the film spans it).
    density : float
        rho [kg/m^3].

    Returns
    -------
    complex or ndarray of complex
        [kg*m].
    """
    eta = np.asarray(thickness, float)
    th = _theta(eta.shape[-1])
    return density * height * radius ** 2 * (2 * np.pi / eta.shape[-1]) * (eta * np.exp(1j * th)).sum(-1)


def film_wave_speed(thickness: float, speed: float, radius: float) -> float:
    """Linear wave speed of the film relative to the wall, sqrt(g eta), g = Omega^2 R [m/s]
    (shallow water under the centrifugal gravity; the standing mode k of the ring has the
    frequency k sqrt(g eta) / R).

    Parameters
    ----------
    thickness : float
        Mean film thickness eta [m].
    speed : float
        Spin speed Omega [rad/s].
    radius : float
        Wall radius R [m].
    """
    return math.sqrt(speed * speed * radius * thickness)


def partition_walls(n_cells: int, partitions: int) -> np.ndarray:
    """The interfaces of ``partitions`` equally spaced radial walls on the ring of cells: 1 at
    the interface i + 1/2 after the last cell of each compartment, 0 elsewhere (the kernels'
    ``wall``; the first compartment starts at theta = 0).

    Parameters
    ----------
    n_cells : int
        Cells around the wall [-], a multiple of ``partitions``.
    partitions : int
        Radial walls [-]: 0 (none) or >= 2.
    """
    p = int(partitions)
    if p != partitions or p < 0 or p == 1:
        raise ParameterError("partitions", partitions, "must be 0 (none) or an integer >= 2")
    wall = np.zeros(int(n_cells), np.int8)
    if p:
        if n_cells % p:
            raise ParameterError("n_cells", n_cells, f"must be a multiple of the {p} partitions")
        wall[n_cells // p - 1::n_cells // p] = 1
    return wall


def film_equilibrium(volume: float, radius: float, height: float, deflection: complex,
                     n_cells: int = 256, partitions: int = 0) -> np.ndarray:
    """The film at rest on the wall of a chamber displaced by c: eta = max(0, C + Re(c e^{-i
    theta})) per cell [m], C from the volume V = H R sum(eta) dtheta (the centrifugal "lake at
    rest"; dry where the wall is nearest the axis once |c| exceeds the mean thickness); with
    partitions, each compartment holds V / partitions at its own level C_k.

    Parameters
    ----------
    volume : float
        Liquid volume V [m^3].
    radius : float
        Wall radius R [m].
    height : float
        Chamber height H [m].
    deflection : complex
        Chamber centre relative to the rotation axis, rotor frame [m].
    n_cells : int
        Cells around the wall [-].
    partitions : int
        Radial walls [-] (:func:`partition_walls`).

    Returns
    -------
    ndarray (n_cells,)
        [m].
    """
    from scipy.optimize import brentq

    th = _theta(n_cells)
    c = complex(deflection)
    b = np.empty(n_cells)
    wall_height(th, c.real, c.imag, b)               # the scheme's own wall, b = -Re(c e^{-i theta})
    parts = max(int(partitions), 1)
    partition_walls(n_cells, partitions)
    out = np.empty(n_cells)
    m = n_cells // parts
    for k in range(parts):
        rise = -b[k * m:(k + 1) * m]
        target = volume / parts / (height * radius * 2 * np.pi / n_cells)

        def excess(C):
            return np.maximum(C + rise, 0.0).sum() - target

        lo, hi = -abs(deflection), target / m + abs(deflection)
        if excess(hi) <= 0.0:        # c = 0: the uniform film's own level, short by round-off
            hi *= 1.0 + 1e-12
        C = brentq(excess, lo, hi, xtol=1e-15 * radius, rtol=4.5 * 2.2205e-16)
        out[k * m:(k + 1) * m] = np.maximum(C + rise, 0.0)
    return out


@dataclass(frozen=True)
class FilmRun:
    """A run of :func:`film_run`.

    Parameters
    ----------
    t : ndarray (nt,)
        Output times [s].
    theta : ndarray (n,)
        Cell centres [rad], chamber frame, from the rotor's unbalance direction.
    thickness : ndarray (nt, n)
        Film thickness eta [m].
    discharge : ndarray (nt, n)
        eta v [m^2/s], v the film's speed relative to the wall.
    radius, height, density : float
        R [m], H [m], rho [kg/m^3].
    steps : int
        Time steps taken [-].
    """

    t: np.ndarray
    theta: np.ndarray
    thickness: np.ndarray
    discharge: np.ndarray
    radius: float
    height: float
    density: float
    steps: int

    @property
    def volume(self) -> np.ndarray:
        """Liquid volume at each output time [m^3] (H R sum(eta) dtheta)."""
        return self.height * self.radius * (2 * np.pi / self.theta.size) * self.thickness.sum(-1)

    @property
    def unbalance(self) -> np.ndarray:
        """The film's first moment about the chamber centre at each output time [kg*m]."""
        return film_unbalance(self.thickness, self.radius, self.height, self.density)

    def inner_wall_time(self, inner_radius: float) -> float | None:
        """First output time [s] at which the film is as thick as the annulus' gap R - r_i (it
        reaches the inner wall, where the wall-film model no longer holds); None if never or
        for a cylinder (r_i = 0).

        Parameters
        ----------
        inner_radius : float
            Inner wall r_i [m].
        """
        if inner_radius <= 0.0:
            return None
        hit = np.nonzero(self.thickness.max(axis=-1) >= self.radius - inner_radius)[0]
        return float(self.t[hit[0]]) if hit.size else None


class _Film(NamedTuple):
    """One chamber's film, checked (:func:`_film`): R, H [m], V [m^3], rho [kg/m^3],
    nu [m^2/s], cells [-], radial partitions [-]."""

    radius: float
    height: float
    volume: float
    density: float
    viscosity: float
    n_cells: int
    partitions: int


def _film(radius, height, volume, density, viscosity, n_cells, partitions=0,
          tag: str = "") -> _Film:
    """The one-line checks of a wall film's parameters (``tag``, e.g. "[1]", is appended to the
    field names): positive R, H [m], V [m^3], rho [kg/m^3], nu [m^2/s]; an integer number of
    cells >= 8; a thin film, mean thickness V / (2 pi R H) <= R/4."""
    R, H = positive(f"radius{tag}", radius), positive(f"height{tag}", height)
    V = positive(f"volume{tag}", volume)
    rho = positive(f"density{tag}", density)
    nu = positive(f"viscosity{tag}", viscosity)
    if int(n_cells) != n_cells or n_cells < 8:
        raise ParameterError(f"n_cells{tag}", n_cells, "must be an integer >= 8")
    if V / (2 * np.pi * R * H) > 0.25 * R:
        raise ParameterError(f"volume{tag}", volume, "a wall film needs a mean thickness "
                             f"V / (2 pi R H) <= R/4, i.e. V <= {0.5 * np.pi * R * R * H:.4g} m^3")
    return _Film(R, H, V, rho, nu, int(n_cells), partitions)


def _speed_table(speed, t_end):
    """(times [s], speeds [rad/s]) of a constant or tabulated spin, which must be > 0."""
    tw, w = _table(speed, t_end, "speed")
    if np.any(w.real <= 0) or np.any(w.imag != 0):
        raise ParameterError("speed", "table" if w.size > 2 else float(w[0].real),
                             "must be > 0 [rad/s]: the film model needs the centrifugal field")
    return tw, w.real


def _table(value, t_end, name):
    """(times, values) of a constant or of a (times, values) pair, values as complex."""
    if isinstance(value, tuple) and len(value) == 2:
        t = np.asarray(value[0], float)
        v = np.asarray(value[1], complex)
        if t.ndim != 1 or t.size < 2 or v.shape != t.shape or np.any(np.diff(t) <= 0):
            raise ParameterError(name, "table", "needs increasing times and one value per time")
        return t, v
    return np.array([0.0, t_end]), np.full(2, complex(value))


def film_run(radius: float, height: float, volume: float,
             speed: float | tuple[npt.ArrayLike, npt.ArrayLike], t_end: float, *,
             deflection: complex | tuple[npt.ArrayLike, npt.ArrayLike] = 0j,
             density: float = 1000.0, viscosity: float = 1.0e-6, n_cells: int = 256,
             save_dt: float | None = None,
             initial: tuple[npt.ArrayLike, npt.ArrayLike] | None = None,
             gravity: float = 0.0, gravity_direction: float = -0.5 * np.pi,
             partitions: int = 0) -> FilmRun:
    """Integrate the film (module docstring) from t = 0 to ``t_end``.

    Parameters
    ----------
    radius : float
        Wall radius R [m].
    height : float
        Chamber height H [m].
    volume : float
        Liquid volume V [m^3] (a thin film: V << 2 pi R^2 H).
    speed : float or (array, array)
        Spin Omega [rad/s], constant or a table (times [s], speeds [rad/s]); > 0 throughout.
    t_end : float
        End time [s].
    deflection : complex or (array, array)
        Chamber centre relative to the rotation axis, rotor frame [m]: constant or a table
        (times [s], complex values [m]); its rates come from the table's finite differences.
    density : float
        rho [kg/m^3].
    viscosity : float
        Kinematic viscosity nu [m^2/s].
    n_cells : int
        Cells around the wall [-].
    save_dt : float or None
        Output spacing [s] (None: 200 outputs).
    initial : (array, array) or None
        Initial (eta [m], q [m^2/s]) per cell; None: a uniform film at rest relative to the wall.
    gravity : float
        Gravity in the chamber's plane g_p [m/s^2] (a horizontal axis; 0: none).
    gravity_direction : float
        Its inertial direction gamma [rad] (-pi/2: down); the spin angle is 0 at t = 0.
    partitions : int
        Equally spaced radial walls [-] (:func:`partition_walls`; 0: none).

    Returns
    -------
    FilmRun
    """
    fl = _film(radius, height, volume, density, viscosity, n_cells)
    R, H, V, nu, n = fl.radius, fl.height, fl.volume, fl.viscosity, fl.n_cells
    T = positive("t_end", t_end)
    tw, w = _speed_table(speed, T)
    tc, c = _table(deflection, T, "deflection")
    tt = np.union1d(tw, tc)
    wv = np.interp(tt, tw, w.real)
    cv = np.interp(tt, tc, c.real) + 1j * np.interp(tt, tc, c.imag)
    cd = np.gradient(cv, tt) if tt.size > 2 else np.full(tt.size, (cv[-1] - cv[0]) / (tt[-1] - tt[0]))
    cdd = np.gradient(cd, tt) if tt.size > 2 else np.zeros(tt.size, complex)
    th = _theta(n)
    if initial is None:
        h = np.full(n, V / (H * R * 2 * np.pi))
        q = np.zeros(n)
    else:
        h, q = (np.array(x, float) for x in initial)
        if h.shape != (n,) or q.shape != (n,) or np.any(h < 0) or not np.all(np.isfinite(h)):
            raise ParameterError("initial", "arrays", f"needs eta >= 0 and q, {n} finite values each")
    nonneg("save_dt", save_dt if save_dt is not None else 0.0)
    out_t = np.linspace(0.0, T, 201) if not save_dt else np.arange(0.0, T + 0.5 * save_dt, save_dt)
    out_h = np.zeros((out_t.size, n))
    out_q = np.zeros((out_t.size, n))
    work = [np.zeros(n) for _ in range(9)]
    steps = sw_integrate(h, q, th, R, nu, T, tt, wv, cv.real, cv.imag, cd.real, cd.imag,
                         cdd.real, cdd.imag, nonneg("gravity", gravity),
                         finite("gravity_direction", gravity_direction),
                         partition_walls(n, partitions), out_t, out_h, out_q, *work)
    if steps < 0:
        raise FloatingPointError("film_run: the film state became non-finite")
    return FilmRun(out_t, th, out_h, out_q, R, H, float(density), int(steps))


@dataclass(frozen=True)
class CoupledRun:
    """A run of :func:`coupled_run`.

    Parameters
    ----------
    t : ndarray (nt,)
        Output times [s].
    deflection : ndarray (nt,) of complex
        The chamber's (rotor's) deflection w in the rotor frame [m].
    films : tuple of FilmRun
        The film of each chamber at the same times, from the axis outwards.
    steps : int
        Time steps [-].
    """

    t: np.ndarray
    deflection: np.ndarray
    films: tuple[FilmRun, ...]
    steps: int

    @property
    def film(self) -> FilmRun:
        """The film of a one-chamber run (ValueError for several: use :attr:`films`)."""
        if len(self.films) != 1:
            raise ValueError(f"this run has {len(self.films)} films: use .films")
        return self.films[0]

    @property
    def unbalance(self) -> np.ndarray:
        """The films' summed first moment about the chamber centre at each output time
        [kg*m]."""
        return sum(f.unbalance for f in self.films)


def _per_film(name: str, value, n: int) -> tuple:
    """A scalar (every film) or a sequence of n values (one per film) as a tuple of n."""
    if isinstance(value, (list, tuple, np.ndarray)):
        if len(value) != n:
            raise ParameterError(name, list(value), f"needs {n} values (one per chamber) or one "
                                 "scalar")
        return tuple(value)
    return (value,) * n


class FilmsState(NamedTuple):
    """The films of one or more concentric chambers as the kernels hold them, one after the
    other (:func:`autobalance.core.shallow_water.films_moment`'s layout): the checked films,
    starts (films + 1), cell angles theta [rad], partition walls, thickness h [m], discharge q
    [m^2/s]; per film R, H [m], rho [kg/m^3], nu [m^2/s]."""

    films: list
    starts: np.ndarray
    theta: np.ndarray
    wall: np.ndarray
    h: np.ndarray
    q: np.ndarray
    Rs: np.ndarray
    Hs: np.ndarray
    rhos: np.ndarray
    nus: np.ndarray


def films_state(radius: float | Sequence[float], height: float | Sequence[float],
                volume: float | Sequence[float], density: float | Sequence[float],
                viscosity: float | Sequence[float], n_cells: int | Sequence[int],
                partitions: int | Sequence[int], film_speed: float | Sequence[float],
                centre: complex) -> FilmsState:
    """The films' starting state (the one home of the films' checks and layout, for
    :func:`coupled_run` and the run of balls beside a liquid): each film checked
    (:func:`_film`: a thin wall film; the chamber keys take a scalar for all or one value per
    film), at rest on a wall displaced by ``centre`` [m] relative to the potential's centre
    (:func:`film_equilibrium`), moving along it at ``film_speed`` [m/s].

    Parameters
    ----------
    radius, height : float or sequence
        Chamber R, H [m].
    volume : float or sequence
        Liquid volume V [m^3].
    density : float or sequence
        rho [kg/m^3].
    viscosity : float or sequence
        nu [m^2/s].
    n_cells : int or sequence
        Cells around each wall [-].
    partitions : int or sequence
        Radial walls per chamber [-].
    film_speed : float or sequence
        Each film's initial speed along its wall relative to it [m/s].
    centre : complex
        The wall's centre from the centre of the centrifugal (and gravity) potential [m].
    """
    keys = {"radius": radius, "height": height, "volume": volume, "density": density,
            "viscosity": viscosity, "n_cells": n_cells, "partitions": partitions}  # _Film's order
    nf = max((len(v) for v in keys.values() if isinstance(v, (list, tuple, np.ndarray))),
             default=1)
    cols = {k: _per_film(k, v, nf) for k, v in keys.items()}
    films = [_film(*(cols[k][f] for k in keys), tag="" if nf == 1 else f"[{f}]")
             for f in range(nf)]
    starts = np.concatenate([[0], np.cumsum([f.n_cells for f in films])]).astype(np.int64)
    th = np.concatenate([_theta(f.n_cells) for f in films])
    wall = np.concatenate([partition_walls(f.n_cells, f.partitions) for f in films])
    h = np.concatenate([film_equilibrium(f.volume, f.radius, f.height, centre, f.n_cells,
                                         f.partitions) for f in films])
    v0 = _per_film("film_speed", film_speed, nf)
    q = h * np.concatenate([np.full(f.n_cells, finite("film_speed", v)) for f, v in zip(films, v0)])
    Rs, Hs, rhos, nus = (np.array([getattr(f, k) for f in films], float)
                         for k in ("radius", "height", "density", "viscosity"))
    return FilmsState(films, starts, th, wall, h, q, Rs, Hs, rhos, nus)


def coupled_run(rotor: VerticalRotor, radius: float | Sequence[float],
                height: float | Sequence[float], volume: float | Sequence[float],
                speed: float | tuple[npt.ArrayLike, npt.ArrayLike], t_end: float, *,
                density: float | Sequence[float] = 1000.0,
                viscosity: float | Sequence[float] = 1.0e-6,
                n_cells: int | Sequence[int] = 256, save_dt: float | None = None,
                deflection: complex = 0j, velocity: complex = 0j, gravity: float = 0.0,
                gravity_direction: float = -0.5 * np.pi,
                partitions: int | Sequence[int] = 0,
                film_speed: float | Sequence[float] = 0.0) -> CoupledRun:
    """The film of one chamber, or of several concentric chambers on the same rotor, coupled
    two-way with an isotropic Jeffcott rotor at a prescribed spin
    (:func:`autobalance.core.shallow_water.sw_coupled`): the rotor's deflection moves every
    wall (centrifugal wall height, frame accelerations) and the films' summed first moment pulls
    the rotor. Starts with the rotor at ``deflection`` moving at ``velocity`` in the rotor
    frame, and each film at rest on the displaced wall (:func:`film_equilibrium`, with
    gravity's offset of the potential, core/shallow_water.py).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg] (without the liquid), k [N/m], c [N*s/m], D [kg*m] (on the rotor frame's x axis).
    radius, height : float or sequence
        Chamber R, H [m]; a sequence gives one chamber each (the chamber keys below then take
        a scalar for all or one value each).
    volume : float or sequence
        Liquid volume V [m^3] (a wall film).
    speed : float or (array, array)
        Spin Omega [rad/s], constant or a table (times [s], speeds [rad/s]), > 0.
    t_end : float
        End time [s].
    density : float or sequence
        rho [kg/m^3].
    viscosity : float or sequence
        nu [m^2/s].
    n_cells : int or sequence
        Cells around each wall [-] (a multiple of its partitions).
    save_dt : float or None
        Output spacing [s] (None: 200 outputs).
    deflection : complex
        Initial deflection w(0) [m].
    velocity : complex
        Initial deflection rate w'(0) in the rotor frame [m/s].
    gravity : float
        Gravity in the chamber's plane g_p [m/s^2] (a horizontal axis; 0: a vertical one).
    gravity_direction : float
        Its inertial direction gamma [rad] (-pi/2: down); the spin angle is 0 at t = 0.
    partitions : int or sequence
        Equally spaced radial walls per chamber [-] (:func:`partition_walls`; 0: none).
    film_speed : float or sequence
        Each film's initial speed along its wall relative to it [m/s] (q = eta v; negative: a
        liquid lagging the chamber, as the spin-up from rest leaves it, liquid/spinup.py).

    Returns
    -------
    CoupledRun
    """
    from ..core.shallow_water import films_moment, sw_coupled

    T = positive("t_end", t_end)
    tw, wv = _speed_table(speed, T)
    gp, gdir = nonneg("gravity", gravity), finite("gravity_direction", gravity_direction)
    off = gp / wv[0] ** 2 * np.exp(1j * gdir)
    st = films_state(radius, height, volume, density, viscosity, n_cells, partitions,
                     film_speed, complex(deflection) + off)
    films, starts, th, wall, h, q, Rs, Hs, rhos, nus = st
    Mt = rotor.mass + float(np.sum(rhos * [f.volume for f in films]))
    U, Ud = films_moment(h, q, th, starts, Rs, Hs, rhos)
    Z0 = Mt * complex(deflection) + U
    Y0 = Mt * complex(velocity) + Ud
    out_t = np.linspace(0.0, T, 201) if not save_dt else np.arange(0.0, T + 0.5 * save_dt, save_dt)
    out_h, out_q = np.zeros((out_t.size, h.size)), np.zeros((out_t.size, h.size))
    out_w = np.zeros(out_t.size, complex)
    work = [np.zeros(h.size) for _ in range(9)]
    steps, Z, Y, _ = sw_coupled(h, q, th, starts, Rs, Hs, rhos, nus, Mt, rotor.stiffness,
                                rotor.damping, rotor.unbalance, Z0, complex(Y0), T, tw, wv,
                                gp, gdir, wall, out_t, out_h, out_q, out_w, *work, 0j)
    if steps < 0:
        raise FloatingPointError("coupled_run: the state became non-finite")
    runs = tuple(FilmRun(out_t, th[o0:o1], out_h[:, o0:o1], out_q[:, o0:o1], f.radius, f.height,
                         f.density, int(steps))
                 for f, o0, o1 in zip(films, starts[:-1], starts[1:]))
    return CoupledRun(out_t, out_w, runs, int(steps))


def physical_run_up(rotor: VerticalRotor, bal: LiquidBalancer, omega_end: float, duration: float,
                    g: float = G_STANDARD, n_cells: int = 256, n_out: int = 1500) -> RunUp:
    """A run-up with the wall film coupled to the rotor (:func:`coupled_run`), as the lumped
    model's :class:`autobalance.liquid.RunUp`: linear in speed from the entrainment speed omega_0
    (003 eq 6; below it the liquid is not a ring on the wall and the film model does not apply)
    to ``omega_end`` over the part of ``duration`` the bench's linear run-up 0 -> omega_end would
    spend there; the empty rotor over the same ramp.

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    bal : LiquidBalancer
        Chamber, liquid (rho [kg/m^3], nu [m^2/s]) and volume [m^3].
    omega_end : float
        Final speed [rad/s].
    duration : float
        Time of the whole run-up from rest [s] (the rate omega_end / duration [rad/s^2]).
    g : float
        Gravity [m/s^2] (for omega_0).
    n_cells : int
        Film cells [-].
    n_out : int
        Output samples [-].

    Returns
    -------
    RunUp
        t [s] from the start at omega_0, omega [rad/s], amplitude and amplitude_dry [m],
        liquid_angle [rad] and liquid_unbalance [kg*m] of the film's moment.
    """
    from .dynamics import RunUp
    from .free_surface import entrainment_speed

    R, h, V, ri = bal.chamber.radius, bal.chamber.height, bal.volume, bal.chamber.inner_radius
    w0 = entrainment_speed(V, R, h, g, inner_radius=ri)
    if not w0 < omega_end:
        raise ParameterError("omega_end", omega_end, f"must exceed the entrainment speed {w0:.4g} rad/s")
    T = duration * (omega_end - w0) / omega_end
    table = (np.array([0.0, T]), np.array([w0, omega_end]))
    dt = T / (n_out - 1)
    wet = coupled_run(rotor, R, h, V, table, T, density=bal.liquid.density,
                      viscosity=bal.liquid.kinematic_viscosity, n_cells=n_cells, save_dt=dt)
    touch = wet.film.inner_wall_time(ri)
    if touch is not None:
        raise ParameterError("chamber.inner_radius", ri, f"the film reaches the inner wall at "
                             f"{touch:.3g} s of the run-up (thicker than R - r_i = "
                             f"{R - ri:.4g} m): the wall-film model does not cover it")
    dry = coupled_run(rotor, R, h, 1e-12, table, T, n_cells=16, save_dt=dt)
    U = wet.film.unbalance
    return RunUp(t=wet.t, omega=np.interp(wet.t, table[0], table[1]),
                 amplitude=np.abs(wet.deflection), liquid_angle=np.angle(U),
                 liquid_unbalance=np.abs(U), amplitude_dry=np.abs(dry.deflection))
