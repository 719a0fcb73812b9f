"""The spin-up of the liquid from rest on a vertical axis, through 003's modes 1-3 until it
reaches the lid at the outer wall (mode 4, where the wall film of :mod:`.film` takes over): the
axisymmetric shallow-water equations of :mod:`autobalance.core.spinup` (docs/liquid/spin-up.md
sec. 3h).

With a slow run-up and a liquid that follows the chamber, the model's mode changes are the
quasi-static speeds of :mod:`.free_surface` (003 eq 4 and 6); otherwise the liquid lags and
forms its ring later, by an amount the viscosity and the run-up rate set, not a ramp.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..core.spinup import spinup_integrate
from ..models import MotorDrive, SpeedProfile, System
from ..models._validate import ParameterError, nonneg, positive
from ..models.liquid_balancer import G_STANDARD

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

__all__ = ["PoolSpin", "SpinUp", "chamber_spinup", "output_times", "rigid_pool",
           "speed_table", "spinup_of", "spinup_run", "up_to_stop", "within_spinup"]

#: Mode 1 (full priority of gravity) lasts while the surface at the inner wall (the axis) has
#: sunk by less than this fraction of the rest level (as :func:`.free_surface.gravity_mode_speed`,
#: our criterion) [-].
GRAVITY_FRACTION = 0.25
#: The bottom at the inner wall (the axis) counts as dry (mode 3) below this fraction of the rest
#: level: a viscous film drains there for long after the ideal paraboloid has left it (our
#: criterion) [-].
DRY_LEVEL = 0.01
#: Cells of equal bottom area per chamber by default: the entrainment speed within 0.05 % of 200
#: cells' and 0.2 % of 800 cells' (docs/liquid/spin-up.md sec. 3h) [-].
DEFAULT_CELLS = 100
#: Most cells per chamber: the steps grow as the cells (CFL on the outermost, narrowest cell) and
#: each step's work too; 800 cells took 60 s for 60 s of run-up, 2000 take about 6 min [-].
MAX_CELLS = 2000


def _cells(radius: float, inner_radius: float, n: int) -> tuple[np.ndarray, np.ndarray,
                                                                  np.ndarray]:
    """(faces [m], centres [m], integral of r dr per cell [m^2]) of the model's n cells of equal
    bottom area from the inner wall r_i (or the axis) to the outer wall R [m]."""
    rf = np.sqrt(np.linspace(inner_radius * inner_radius, radius * radius, n + 1))
    return rf, 0.5 * (rf[1:] + rf[:-1]), 0.5 * np.diff(rf ** 2)


def _spin_sums(depth: np.ndarray, azimuthal: np.ndarray, r: np.ndarray,
               weights: np.ndarray) -> tuple:
    """(sum r h v r dr [m^4/s], sum r^2 h r dr [m^5]) over the cells (the last axis): the
    liquid's angular momentum relative to the chamber and its moment of inertia about the axis,
    each over 2 pi rho (v relative to the chamber)."""
    return (azimuthal * r) @ weights, (depth * r ** 2) @ weights


@dataclass(frozen=True)
class SpinUp:
    """A run of :func:`spinup_run`.

    Parameters
    ----------
    t : ndarray (nt,)
        Output times [s] (up to the stop).
    r : ndarray (n,)
        Cell centres [m].
    faces : ndarray (n + 1,)
        Face radii [m], inner wall (or axis) to outer wall.
    depth : ndarray (nt, n)
        Liquid depth h along the axis [m].
    radial : ndarray (nt, n)
        Radial discharge h u [m^2/s].
    azimuthal : ndarray (nt, n)
        Azimuthal discharge h v [m^2/s], v relative to the chamber.
    speed : ndarray (nt,)
        Chamber spin Omega [rad/s].
    lid_time : float or None
        Time the surface reaches the lid at the outer wall [s] (mode 4); None if not by t_end.
    rest_level : float
        Depth of the liquid at rest h0 [m].
    steps : int
        Time steps [-].
    """

    t: np.ndarray
    r: np.ndarray
    faces: np.ndarray
    depth: np.ndarray
    radial: np.ndarray
    azimuthal: np.ndarray
    speed: np.ndarray
    lid_time: float | None
    rest_level: float
    steps: int

    @property
    def _weights(self) -> np.ndarray:
        return 0.5 * np.diff(self.faces ** 2)            # integral of r dr per cell [m^2]

    @property
    def volume(self) -> np.ndarray:
        """Liquid volume at each output time [m^3] (2 pi sum of h r dr)."""
        return 2 * np.pi * self.depth @ self._weights

    @property
    def liquid_speed(self) -> np.ndarray:
        """The liquid's mean angular velocity in the inertial frame [rad/s]: its angular
        momentum over its moment of inertia, Omega + sum(r h v dA) / sum(r^2 h dA)."""
        rel, inertia = _spin_sums(self.depth, self.azimuthal, self.r, self._weights)
        return self.speed + rel / inertia

    @property
    def mode(self) -> np.ndarray:
        """003's motion mode at each output time (sec. 5.1): 1 while the surface at the inner
        wall (the axis) has sunk by less than :data:`GRAVITY_FRACTION` of the rest level, 2
        while it is wet, 3 once it is dry (below :data:`DRY_LEVEL` of the rest level), 4 at the
        lid [-]."""
        inner = self.depth[:, 0]
        m = np.where(inner >= (1 - GRAVITY_FRACTION) * self.rest_level, 1,
                     np.where(inner > DRY_LEVEL * self.rest_level, 2, 3))
        if self.lid_time is not None:
            m = np.where(self.t >= self.lid_time, 4, m)
        return m

    def mode_changes(self) -> list[dict]:
        """The time of each mode change after the first mode [s], with the chamber's and the
        liquid's speeds there [rad/s]: modes 2 and 3 where the depth at the inner wall crosses
        its threshold (:attr:`mode`), linear between the two outputs around it; mode 4 at the
        lid time (the run's end, exact)."""
        m = self.mode
        inner = self.depth[:, 0]
        level = {2: (1 - GRAVITY_FRACTION) * self.rest_level, 3: DRY_LEVEL * self.rest_level}
        out = []
        for k in range(int(m[0]) + 1, 5):
            i = np.nonzero(m >= k)[0]
            if not i.size:
                continue
            j = int(i[0])
            t = float(self.t[j])
            if k in level and j > 0 and inner[j - 1] > inner[j]:
                f = float(np.clip((inner[j - 1] - level[k]) / (inner[j - 1] - inner[j]), 0, 1))
                t = float(self.t[j - 1] + f * (self.t[j] - self.t[j - 1]))
            out.append({"mode": k, "time_s": t,
                        "speed_rad_s": float(np.interp(t, self.t, self.speed)),
                        "liquid_speed_rad_s": float(np.interp(t, self.t, self.liquid_speed))})
        return out


def spinup_run(radius: float, height: float, volume: float,
               speed: tuple[npt.ArrayLike, npt.ArrayLike], t_end: float, *,
               inner_radius: float = 0.0, viscosity: float = 1.0e-6, g: float = G_STANDARD,
               n_cells: int = DEFAULT_CELLS, save_dt: float | None = None,
               initial: tuple[npt.ArrayLike, npt.ArrayLike, npt.ArrayLike] | None = None
               ) -> SpinUp:
    """The liquid, at rest in the inertial frame at t = 0 (a flat layer), spun up by the
    chamber's bottom (module docstring) until its surface reaches the lid at the outer wall or
    ``t_end``.

    Parameters
    ----------
    radius, height : float
        Chamber R, h [m].
    volume : float
        Liquid volume V [m^3], at most half the chamber (the surface must dry the inner wall's
        foot before it reaches the lid: 003 eq 5-6's case).
    speed : (array, array)
        Spin table (times [s] from 0, speeds [rad/s] >= 0), linear between its points.
    t_end : float
        Latest stop [s].
    inner_radius : float
        Inner wall r_i [m] (0: a cylinder).
    viscosity : float
        nu [m^2/s].
    g : float
        Gravity along the axis [m/s^2].
    n_cells : int
        Cells of equal bottom area from the inner wall (axis) to the outer wall [-] (100: the
        entrainment speed within 0.2 % of 800 cells', docs/liquid/spin-up.md sec. 3h).
    save_dt : float or None
        Output spacing [s] (None: 400 outputs).
    initial : (array, array, array) or None
        Initial (h [m], h u [m^2/s], h v [m^2/s]) per cell (v relative to the chamber); None:
        the flat layer at rest in the inertial frame.

    Returns
    -------
    SpinUp
    """
    R, H = positive("radius", radius), positive("height", height)
    V = positive("volume", volume)
    ri = nonneg("inner_radius", inner_radius)
    if ri >= R:
        raise ParameterError("inner_radius", inner_radius, f"must be < radius {R!r} m")
    area = math.pi * (R * R - ri * ri)
    if not within_spinup(R, H, ri, V):
        raise ParameterError("volume", volume, "the spin-up model needs at most half the "
                             f"chamber, V <= {0.5 * area * H:.4g} m^3 (a fuller chamber touches "
                             "the lid before its inner wall's foot dries)")
    T = positive("t_end", t_end)
    nu, gg = positive("viscosity", viscosity), positive("g", g)
    if isinstance(n_cells, bool) or int(n_cells) != n_cells or not 8 <= n_cells <= MAX_CELLS:
        raise ParameterError("n_cells", n_cells, f"must be an integer in [8, {MAX_CELLS}] (the "
                             "run's time grows as its square: 800 cells take about a minute)")
    n = int(n_cells)
    tt, tw = speed_table(speed)
    rf, rc, _ = _cells(R, ri, n)
    h0 = V / area
    if initial is None:
        h = np.full(n, h0)
        q = np.zeros(n)
        s = -h * tw[0] * rc            # at rest in the inertial frame
    else:
        h, q, s = (np.array(x, float) for x in initial)
        if any(x.shape != (n,) for x in (h, q, s)) or np.any(h < 0) \
                or not all(np.all(np.isfinite(x)) for x in (h, q, s)):
            raise ParameterError("initial", "arrays", f"needs h >= 0, q and s, {n} finite "
                                 "values each")
    out_t = output_times(T, save_dt)
    out = [np.full((out_t.size, n), np.nan) for _ in range(3)]
    work = [np.zeros(n) for _ in range(3)] + [np.zeros(n + 1) for _ in range(5)]
    steps, t_stop = spinup_integrate(h, q, s, rf, gg, nu, H, T, tt, tw, out_t, *out, *work)
    if steps < 0:
        raise FloatingPointError("spinup_run: the state became non-finite")
    t, rows = up_to_stop(out_t, t_stop, out, (h, q, s))
    lid = float(t_stop) if t_stop < T else None
    return SpinUp(t, rc, rf, rows[0], rows[1], rows[2], np.interp(t, tt, tw), lid, h0,
                  int(steps))


def speed_table(speed: tuple[npt.ArrayLike, npt.ArrayLike]) -> tuple[np.ndarray, np.ndarray]:
    """A spin-up model's speed table, checked: (times [s], speeds [rad/s]) as float arrays;
    one line naming ``speed`` unless the times increase and the speeds are finite and >= 0.

    Parameters
    ----------
    speed : (array, array)
        Times [s] from 0 and speeds [rad/s], linear between the points.
    """
    tt = np.asarray(speed[0], float)
    tw = np.asarray(speed[1], float)
    if tt.ndim != 1 or tt.size < 2 or tw.shape != tt.shape or np.any(np.diff(tt) <= 0) \
            or np.any(tw < 0) or not np.all(np.isfinite(tw)):
        raise ParameterError("speed", "table", "needs increasing times and speeds >= 0 [rad/s]")
    return tt, tw


def output_times(t_end: float, save_dt: float | None) -> np.ndarray:
    """A spin-up model's output times [s]: 401 from 0 to ``t_end``, or every ``save_dt`` [s].

    Parameters
    ----------
    t_end : float
        The run's latest stop [s].
    save_dt : float or None
        Output spacing [s], > 0 (None: 401 outputs).
    """
    if not save_dt:
        return np.linspace(0.0, t_end, 401)
    return np.arange(0.0, t_end + 0.5 * save_dt, positive("save_dt", save_dt))


def up_to_stop(out_t: np.ndarray, t_stop: float, rows: Sequence[np.ndarray],
               finals: Sequence) -> tuple[np.ndarray, list[np.ndarray]]:
    """The outputs of a run that stopped at ``t_stop`` [s]: the output times up to it and each
    row (first axis over ``out_t``), with the final state ``finals`` appended at ``t_stop``
    when the stop falls between two outputs.

    Parameters
    ----------
    out_t : ndarray
        Output times [s].
    t_stop : float
        The stop [s].
    rows : sequence of ndarray
        The kernel's outputs, one row per output time [any units].
    finals : sequence
        The state at the stop, one value or array per row [the rows' units].
    """
    keep = out_t <= t_stop + 1e-12 * max(1.0, t_stop)
    t = out_t[keep]
    if t[-1] < t_stop:
        return np.append(t, t_stop), [np.concatenate([o[keep], np.asarray(x, float)[None]])
                                      for o, x in zip(rows, finals)]
    return t, [o[keep] for o in rows]


def spinup_of(system: System, spin: SpeedProfile | MotorDrive, *, n_cells: int = DEFAULT_CELLS,
              g: float = G_STANDARD) -> list[SpinUp]:
    """The spin-up of each chamber's liquid of a machine through its speed profile, from rest
    in the inertial frame at the profile's start, or, for a profile that starts turning, from
    the pool turning with the chamber at that speed (:func:`rigid_pool`); the chambers spin up
    independently (the model is axisymmetric, the rotor's whirl is not in it).

    Parameters
    ----------
    system : autobalance.models.System
        A machine with a ``[liquid]`` section on a vertical axis.
    spin : autobalance.models.SpeedProfile
        Its prescribed speed [rad/s] over time [s].
    n_cells : int
        Cells per chamber [-].
    g : float
        Gravity along the axis [m/s^2].

    Returns
    -------
    list of SpinUp
        One per chamber, from the axis outwards; each stops where its liquid reaches the lid.
    """
    liq = system.liquid
    if liq is None:
        raise ParameterError("liquid", None, "needs a [liquid] section (e.g. the preset "
                             "leblanc_003)")
    liq.vertical("for the spin-up model (gravity along the axis holds the liquid on the "
                 "bottom)")
    if not isinstance(spin, SpeedProfile):
        raise ParameterError("profile.kind", "motor", "the spin-up model needs a prescribed "
                             "speed profile (constant, ramp, table, std or tsr)")
    return [chamber_spinup(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume,
                           liq.kinematic_viscosity, g, spin.times, spin.speeds, n_cells)
            for c in liq.chambers]


def chamber_spinup(radius: float, height: float, inner_radius: float, volume: float,
                   viscosity: float, g: float, times: Sequence[float], speeds: Sequence[float],
                   n_cells: int = DEFAULT_CELLS) -> SpinUp:
    """One chamber's :func:`spinup_run` through a profile's knots (times [s] from 0, speeds
    [rad/s]) to its last time: from rest, or, for a profile that starts turning, from the pool
    turning with the chamber at the first speed (:func:`rigid_pool`).

    Parameters
    ----------
    radius, height, inner_radius : float
        R, h, r_i [m].
    volume : float
        V [m^3].
    viscosity : float
        nu [m^2/s].
    g : float
        Gravity along the axis [m/s^2].
    times, speeds : sequence of float
        The profile's knots [s], [rad/s].
    n_cells : int
        Cells [-].
    """
    tt, ww = np.asarray(times, float), np.asarray(speeds, float)
    W0 = float(ww[0])
    return spinup_run(radius, height, volume, (tt, ww), float(tt[-1]), inner_radius=inner_radius,
                      viscosity=viscosity, g=g, n_cells=n_cells,
                      initial=None if W0 == 0.0 else rigid_pool(radius, inner_radius, volume, W0,
                                                                g, n_cells))


def within_spinup(radius: float, height: float, inner_radius: float, volume: float) -> bool:
    """Whether the spin-up model covers the chamber: at most half full, so that the surface dries
    the bottom (at the axis or the inner wall) before it reaches the lid (003 eq 5-6's case).

    Parameters
    ----------
    radius, height, inner_radius : float
        R, h, r_i [m].
    volume : float
        V [m^3].
    """
    return volume <= 0.5 * math.pi * (radius * radius - inner_radius * inner_radius) * height


def rigid_pool(radius: float, inner_radius: float, volume: float, speed: float, g: float,
               n_cells: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The liquid turning with the chamber at ``speed`` (003 eq 3's paraboloid h = C +
    Omega^2 r^2 / 2g, dry where negative, C from the volume), on :func:`spinup_run`'s cells: the
    initial state (h [m], hu, hv [m^2/s]) of a chamber that has turned at its profile's first
    speed for long.

    Parameters
    ----------
    radius, inner_radius : float
        R, r_i [m].
    volume : float
        V [m^3].
    speed : float
        Omega [rad/s].
    g : float
        Gravity along the axis [m/s^2].
    n_cells : int
        Cells [-].
    """
    _, rc, area = _cells(radius, inner_radius, int(n_cells))
    rise = speed * speed * rc * rc / (2.0 * g)

    def vol(C):
        return 2.0 * np.pi * np.maximum(0.0, C + rise) @ area

    lo, hi = -float(rise[-1]), volume / (2.0 * np.pi * area.sum())
    for _ in range(200):                    # bisection: vol(C) increases with C
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if vol(mid) < volume else (lo, mid)
    h = np.maximum(0.0, hi + rise)
    h *= volume / (2.0 * np.pi * h @ area)  # the volume to round-off
    return h, np.zeros_like(h), np.zeros_like(h)


class PoolSpin:
    """A chamber's liquid in its spin-up (:func:`spinup_run`'s model) advanced one coupling step
    at a time under a spin known only step by step: a motor drive, whose torque the liquid's
    change of angular momentum loads (docs/liquid/balls-beside-liquid.md sec. 3i). From rest (a flat
    layer at rest in the inertial frame) or, for a drive that starts turning, from the pool turning
    with the chamber (:func:`rigid_pool`); until its surface reaches the lid at the outer wall.

    Parameters
    ----------
    radius, height, inner_radius : float
        R, h, r_i [m].
    volume : float
        V [m^3], at most half the chamber (:func:`within_spinup`).
    density : float
        rho [kg/m^3].
    viscosity : float
        nu [m^2/s].
    g : float
        Gravity along the axis [m/s^2].
    speed : float
        The chamber's spin at the start [rad/s].
    n_cells : int
        Cells of equal bottom area [-].
    """

    def __init__(self, radius: float, height: float, inner_radius: float, volume: float,
                 density: float, viscosity: float, g: float, speed: float,
                 n_cells: int = DEFAULT_CELLS):
        n = int(n_cells)
        self.rf, self.rc, self.weights = _cells(radius, inner_radius, n)
        if speed == 0.0:
            self.h = np.full(n, volume / (math.pi * (radius ** 2 - inner_radius ** 2)))
            self.q, self.s = np.zeros(n), np.zeros(n)
        else:
            self.h, self.q, self.s = rigid_pool(radius, inner_radius, volume, speed, g, n)
        self.lid, self.rho, self.nu, self.g = float(height), float(density), float(viscosity), g
        self.lid_time: float | None = None
        self._out = (np.zeros(0), np.zeros((0, n)), np.zeros((0, n)), np.zeros((0, n)))
        self._work = [np.zeros(n) for _ in range(3)] + [np.zeros(n + 1) for _ in range(5)]

    def advance(self, t: float, dt: float, w0: float, w1: float) -> bool:
        """Advance over [t, t + dt] with the chamber's spin linear from w0 to w1; stops where
        the surface reaches the lid (``lid_time`` [s] set). Returns whether it has.

        Parameters
        ----------
        t : float
            The step's start on the run's clock [s].
        dt : float
            Its length [s].
        w0, w1 : float
            The chamber's spin at its start and end [rad/s].
        """
        if self.lid_time is not None:
            return True
        tt = np.array([0.0, dt])
        tw = np.array([w0, w1])
        steps, t_stop = spinup_integrate(self.h, self.q, self.s, self.rf, self.g, self.nu,
                                         self.lid, dt, tt, tw, *self._out, *self._work)
        if steps < 0:
            raise FloatingPointError("PoolSpin.advance: the state became non-finite")
        if t_stop < dt * (1.0 - 1e-9):
            self.lid_time = t + t_stop
        return self.lid_time is not None

    def momentum(self, w: float) -> tuple[float, float]:
        """(H, I): the liquid's angular momentum about the axis in the inertial frame [kg*m^2/s]
        (the azimuthal discharge is relative to the chamber), and its moment of inertia about
        the axis [kg*m^2] (2 pi rho sum of r^2 h r dr).

        Parameters
        ----------
        w : float
            The chamber's spin [rad/s].
        """
        c = 2.0 * math.pi * self.rho
        rel, inertia = _spin_sums(self.h, self.s, self.rc, self.weights)
        return c * float(rel) + c * float(inertia) * w, c * float(inertia)
