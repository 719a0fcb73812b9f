"""The liquid of a chamber on a horizontal axis in time, from a puddle at rest or from a ring
turning with the chamber: the circumferential shallow-water model of
:mod:`autobalance.core.rimming` (docs/liquid/horizontal-axis.md sec. 3n), with the normal
acceleration of the liquid's own rotation and of gravity.

What it answers, and where it stops:
* from a puddle (a profile from rest): how the wall drags it (its lag, how far up the rising
  wall it is carried) and, if it stays inside the model, where it closes into a ring;
* from a ring (a profile that starts turning, e.g. a run-down): whether the ring holds, and
  the speed at which it breaks;
* the run stops where the state leaves the model: more than :data:`autobalance.core.rimming.
  LOOSE_MAX` of the liquid where nothing holds it on the wall (G <= 0; a real liquid falls),
  or a layer thicker than the chamber's gap. On water puddles the single-layer model leaves
  it while the wall shoves the puddle up its rising side (docs/liquid/horizontal-axis.md sec. 3n):
  the transition from puddle to ring needs a wall layer the depth average does not have.

The rotor's whirl is not in the model (the chamber turns about its centre), as in the vertical
axis' spin-up (:mod:`.spinup`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import brentq

from ..core import rimming as _k
from ..models import SpeedProfile, System
from ..models._validate import ParameterError, nonneg, positive
from .spinup import output_times, speed_table, up_to_stop

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["RING_LEVEL", "STATUS", "RimSpinUp", "closing_centroid", "closing_ring",
           "horizontal_spinup", "puddle_at_rest", "rimming_run"]

#: The ring is closed once every cell holds at least this fraction of the ring's mean thickness
#: V / (2 pi R H) (and the liquid is held all round); as the vertical spin-up's dry level
#: (:data:`.spinup.DRY_LEVEL`), our criterion [-].
RING_LEVEL = 0.01
#: Cells around the wall by default [-] (docs/liquid/horizontal-axis.md sec. 3n).
DEFAULT_CELLS = 256
#: The run's end, by the kernel's status [-].
STATUS = {_k.RUN_TO_END: "end", _k.STOP_CLOSED: "closed", _k.STOP_BROKEN: "broken",
          _k.LEFT_UNHELD: "unheld", _k.LEFT_TOO_THICK: "too_thick"}
#: Most cells [-] (the run's time grows as the square of the cells).
MAX_CELLS = 4096


def _cell_angles(n: int) -> np.ndarray:
    return (np.arange(n) + 0.5) * (2 * math.pi / n)


def puddle_at_rest(radius: float, height: float, volume: float, g: float,
                   gravity_direction: float, n_cells: int,
                   inner_radius: float = 0.0) -> np.ndarray:
    """The puddle at rest in the bottom of the chamber [m] per cell (the model's equilibrium at
    Omega = 0, spin angle 0: the surface P + G h = L with G = g cos(theta - gamma), the
    horizontal chord of the thin-layer model; L from the volume R H sum(h) dtheta = V).

    Parameters
    ----------
    radius, height : float
        Chamber R and axial width H [m].
    volume : float
        V [m^3]: the puddle's surface must lie below the axis and clear the inner wall.
    g : float
        Gravity [m/s^2].
    gravity_direction : float
        Its inertial angle gamma [rad] (-pi/2: down).
    n_cells : int
        Cells [-].
    inner_radius : float
        Inner wall r_i [m] (0: a cylinder).
    """
    th = _cell_angles(n_cells)
    c = np.cos(th - gravity_direction)
    target = volume / (radius * height * 2 * math.pi / n_cells)

    def depth(L):
        return np.where(c > 0, np.maximum(0.0, (L + g * radius * c) / np.where(c > 0, g * c, 1)),
                        0.0)

    if volume > 0.5 * math.pi * (radius * radius - inner_radius * inner_radius) * height \
            or depth(0.0).sum() <= target:
        raise ParameterError("liquid.volume", volume, "the horizontal spin-up needs a puddle "
                             "whose surface lies below the axis: at most half the chamber")
    L = brentq(lambda L: depth(L).sum() - target, -g * radius, 0.0, xtol=1e-14 * g * radius)
    h = depth(L)
    if inner_radius > 0 and h.max() >= radius - inner_radius:
        raise ParameterError("liquid.volume", volume, f"the puddle at rest reaches the inner "
                             f"wall ({h.max():.4g} m deep, gap {radius - inner_radius:.4g} m): "
                             "outside the horizontal spin-up model")
    return h


def closing_ring(radius: float, height: float, volume: float) -> float:
    """The model's quasi-static ring at its closing: a = Omega^2 R / g where the thin layer in
    rigid rotation, h = R (1 + c) / (a + c) (c = cos of the angle from the bottom; P + G h =
    const with zero thickness at the top), holds the volume: mean h / R = 1 - sqrt((a - 1) /
    (a + 1)) = V / (2 pi R^2 H) (our closed form; to O(h/R) the exact geometry's g / Omega^2 =
    R - r_s, r_s = sqrt(R^2 - V / (pi H)), where the offset surface circle of rigid rotation
    (:mod:`.quasistatic`) touches the wall; 205 rpm for the washer's ring) [-].

    Parameters
    ----------
    radius, height : float
        R, H [m].
    volume : float
        V [m^3], below the cylinder's pi R^2 H.
    """
    s = (1.0 - volume / (2 * math.pi * radius * radius * height)) ** 2
    return (1.0 + s) / (1.0 - s)


def closing_centroid(radius: float, height: float, volume: float, n_cells: int) -> float:
    """Distance of the liquid's centre of mass from the axis [m] in the model's quasi-static
    ring at its closing (:func:`closing_ring`), on the model's cells: where a spin-up's liquid
    must have risen to before its ring counts as closed (:func:`rimming_run`).

    Parameters
    ----------
    radius, height : float
        R, H [m].
    volume : float
        V [m^3].
    n_cells : int
        Cells [-].
    """
    a = closing_ring(radius, height, volume)
    c = np.cos(_cell_angles(n_cells))
    h = (1.0 + c) / (a + c)
    return float(radius * abs((h * c).sum()) / h.sum())


@dataclass(frozen=True)
class RimSpinUp:
    """A run of :func:`rimming_run`.

    Parameters
    ----------
    t : ndarray (nt,)
        Output times [s] (up to the stop).
    theta : ndarray (n,)
        Cell angles in the chamber frame [rad].
    depth : ndarray (nt, n)
        Layer thickness h [m].
    discharge : ndarray (nt, n)
        h v [m^2/s], v relative to the wall.
    speed : ndarray (nt,)
        Chamber spin Omega [rad/s].
    spin_angle : ndarray (nt,)
        psi [rad].
    loose : ndarray (nt,)
        Share of the liquid where nothing holds it on the wall (G <= 0) [-].
    status : str
        How the run ended (:data:`STATUS`): "closed" (a puddle closed into a ring), "broken"
        (a ring broke), "end" (neither by the end), "unheld" or "too_thick" (it left the
        model: more than :data:`autobalance.core.rimming.LOOSE_MAX` of the liquid held by
        nothing; a layer thicker than the chamber's gap).
    stop_time : float
        Time of the end [s].
    most_loose : float
        The largest share held by nothing over the run [-] (every step).
    radius, height : float
        R, H [m].
    steps : int
        Time steps [-].
    """

    t: np.ndarray
    theta: np.ndarray
    depth: np.ndarray
    discharge: np.ndarray
    speed: np.ndarray
    spin_angle: np.ndarray
    loose: np.ndarray
    status: str
    stop_time: float
    most_loose: float
    radius: float
    height: float
    steps: int

    @property
    def ring_time(self) -> float | None:
        """Time the puddle closed into a ring [s], or None."""
        return self.stop_time if self.status == "closed" else None

    @property
    def stop_speed(self) -> float:
        """The chamber's speed at the end [rad/s]."""
        return float(self.speed[-1])

    @property
    def volume(self) -> np.ndarray:
        """Liquid volume at each output time [m^3]: R H sum(h) dtheta."""
        return self.depth.sum(axis=1) * self.radius * self.height * 2 * math.pi / self.theta.size

    @property
    def liquid_speed(self) -> np.ndarray:
        """The liquid's mean angular velocity in the inertial frame [rad/s]: Omega + sum(h v) /
        (R sum(h))."""
        return self.speed + self.discharge.sum(axis=1) / (self.radius * self.depth.sum(axis=1))

    @property
    def moment(self) -> np.ndarray:
        """The liquid's first moment about the axis over its density [m^4], in the inertial
        frame: R^2 H dtheta sum(h e^{i(theta + psi)})."""
        d = self.radius ** 2 * self.height * 2 * math.pi / self.theta.size
        return d * (self.depth * np.exp(1j * (self.theta[None, :] + self.spin_angle[:, None]))
                    ).sum(axis=1)


def rimming_run(radius: float, height: float, volume: float,
                speed: tuple[npt.ArrayLike, npt.ArrayLike], t_end: float, *,
                g: float, gravity_direction: float = -math.pi / 2, inner_radius: float = 0.0,
                viscosity: float = 1.0e-6, n_cells: int = DEFAULT_CELLS,
                save_dt: float | None = None,
                initial: tuple[npt.ArrayLike, npt.ArrayLike] | None = None,
                stop_at_event: bool = True) -> RimSpinUp:
    """The liquid of a chamber on a horizontal axis through a spin table (module docstring):
    from the puddle at rest in the inertial frame (:func:`puddle_at_rest`) if the table starts
    at rest, until it closes into a ring (every cell at least :data:`RING_LEVEL` of the mean
    thickness, held all round, its centre of mass risen to the quasi-static ring's at its
    closing, :func:`closing_centroid`); else from a uniform ring turning with the chamber,
    until the ring breaks (a cell below that level, or liquid held by nothing). Either run
    also stops at ``t_end`` or where it leaves the model.

    Parameters
    ----------
    radius, height : float
        Chamber R and axial width H [m].
    volume : float
        Liquid volume V [m^3].
    speed : (array, array)
        Spin table (times [s] from 0, speeds [rad/s] >= 0), linear between its points.
    t_end : float
        Latest stop [s].
    g : float
        Gravity in the plane of rotation [m/s^2], > 0.
    gravity_direction : float
        Its inertial angle [rad] (-pi/2: down; the spin angle is 0 at t = 0).
    inner_radius : float
        Inner wall r_i [m] (0: a cylinder); no layer may be thicker than the gap R - r_i.
    viscosity : float
        nu [m^2/s].
    n_cells : int
        Cells around the wall [-].
    save_dt : float or None
        Output spacing [s] (None: 401 outputs).
    initial : (array, array) or None
        Initial (h [m], h v [m^2/s]) per cell instead (then the run looks for the ring's
        closing if the first speed is 0, else for its breaking).
    stop_at_event : bool
        Stop at the closing or breaking (else run on to ``t_end`` or out of the model).

    Returns
    -------
    RimSpinUp
    """
    R, H, V = positive("radius", radius), positive("height", height), positive("volume", volume)
    ri = nonneg("inner_radius", inner_radius)
    if ri >= R:
        raise ParameterError("inner_radius", inner_radius, f"must be < radius {R!r} m")
    gg, nu, T = positive("gravity.g", g), positive("viscosity", viscosity), positive("t_end", t_end)
    if isinstance(n_cells, bool) or int(n_cells) != n_cells or not 16 <= n_cells <= MAX_CELLS:
        raise ParameterError("n_cells", n_cells, f"must be an integer in [16, {MAX_CELLS}]")
    n = int(n_cells)
    tt, tw = speed_table(speed)
    th = _cell_angles(n)
    mean = V / (2 * math.pi * R * H)
    from_rest = tw[0] == 0.0
    if initial is not None:
        h, q = (np.array(x, float) for x in initial)
        if any(x.shape != (n,) for x in (h, q)) or np.any(h < 0) \
                or not all(np.all(np.isfinite(x)) for x in (h, q)):
            raise ParameterError("initial", "arrays", f"needs h >= 0 and q, {n} finite values "
                                 "each")
    elif from_rest:
        h, q = puddle_at_rest(R, H, V, gg, gravity_direction, n, ri), np.zeros(n)
    else:
        if mean >= R - ri:
            raise ParameterError("liquid.volume", V, f"a ring {mean:.4g} m thick does not fit "
                                 f"the gap {R - ri:.4g} m")
        h, q = np.full(n, mean), np.zeros(n)           # a ring turning with the chamber
    out_t = output_times(T, save_dt)
    out_h, out_q = (np.full((out_t.size, n), np.nan) for _ in range(2))
    out_psi, out_loose = (np.full(out_t.size, np.nan) for _ in range(2))
    work = [np.zeros(n), np.zeros(n), np.zeros((10, n))] + [np.zeros(n) for _ in range(7)]
    stop = _k.RUN_TO_END if not stop_at_event else (_k.STOP_CLOSED if from_rest
                                                    else _k.STOP_BROKEN)
    status, steps, t_stop, worst, psi, loose = _k.rim_integrate(
        h, q, th, R, H, gg, float(gravity_direction), nu, RING_LEVEL * mean,
        closing_centroid(R, H, V, n), R - ri, stop, T, tt, tw, out_t, out_h, out_q, out_psi,
        out_loose, *work)
    if steps < 0:
        raise FloatingPointError("rimming_run: the state became non-finite")
    t, rows = up_to_stop(out_t, t_stop, (out_h, out_q, out_psi, out_loose), (h, q, psi, loose))
    return RimSpinUp(t, th, rows[0], rows[1], np.interp(t, tt, tw), rows[2], rows[3],
                     STATUS[int(status)], float(t_stop), float(worst), R, H, int(steps))


def horizontal_spinup(system: System, spin: SpeedProfile, *,
                      n_cells: int = DEFAULT_CELLS) -> list[RimSpinUp]:
    """Each chamber's liquid of a machine on a horizontal axis through its speed profile
    (:func:`rimming_run`: from a puddle at rest if the profile starts at rest, else from a ring
    turning with the chamber), with the machine's in-plane gravity and liquid.

    Parameters
    ----------
    system : autobalance.models.System
        A machine with a ``[liquid]`` section on a horizontal axis (no partitions) and
        ``[gravity]`` in the plane.
    spin : autobalance.models.SpeedProfile
        Its prescribed speed [rad/s] over time [s].
    n_cells : int
        Cells around each wall [-].

    Returns
    -------
    list of RimSpinUp
        One per chamber, from the axis outwards.
    """
    liq = system.liquid
    if liq is None or liq.axis != "horizontal":
        raise ParameterError("liquid.axis", None if liq is None else liq.axis,
                             "must be horizontal for the horizontal spin-up (a vertical axis: "
                             "autobalance.liquid.spinup)")
    liq.unpartitioned("the horizontal spin-up (a partitioned ring carries its liquid in its "
                      "compartments)")
    if not isinstance(spin, SpeedProfile):
        raise ParameterError("profile.kind", "motor", "the horizontal spin-up needs a "
                             "prescribed speed profile (constant, ramp, table, std or tsr)")
    g = positive("gravity.g", system.gravity.g)
    tt, ww = np.asarray(spin.times, float), np.asarray(spin.speeds, float)
    return [rimming_run(c.chamber_radius, c.chamber_height, c.volume, (tt, ww), float(tt[-1]),
                        g=g, gravity_direction=system.gravity.direction,
                        inner_radius=c.inner_radius, viscosity=liq.kinematic_viscosity,
                        n_cells=n_cells) for c in liq.chambers]
