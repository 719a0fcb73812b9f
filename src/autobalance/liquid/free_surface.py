"""Free surface of a liquid in a closed rotating cylinder and its four motion modes (seed 003).

A volume V of liquid fills a closed cylinder (radius R, height h) that turns at omega about its
vertical axis. Euler's equilibrium of an ideal fluid (003 eq 1-3) makes the free surface the
paraboloid z(r) = z_* + omega^2 r^2 / (2 g); the liquid depth at radius r is that paraboloid
clipped to the chamber, clip(z(r), 0, h). With s = r^2 the depth is a clipped *linear* ramp in s,
so the volume has a closed form in every regime:

====== ====================================== ====================================
regime wetted bottom centre? (z_* >= 0)        surface reaches the lid? (z(R) > h)
====== ====================================== ====================================
A      yes                                     no   -> 003 eq 4 (modes 1, 2)
B      no (dry centre)                         no   -> mode 3 (V <= V_c/2)
C      yes                                     yes  -> mode 3 (V > V_c/2 only)
D      no (dry centre)                         yes  -> 003 eq 5 (mode 4)
====== ====================================== ====================================

All functions are pure, take SI values and work on scalars.
"""
from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..models._validate import ParameterError, finite, nonneg, positive
from ..models.liquid_balancer import G_STANDARD

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

__all__ = ["FreeSurface", "MODE_NAMES", "bottom_touch_speed", "entrainment_speed",
           "free_surface", "gravity_mode_speed", "lid_touch_speed", "liquid_volume",
           "mode_speeds", "motion_mode", "surface_height", "surface_profiles"]

#: 003 sec. 5.1 names of the four motion modes (1..4).
MODE_NAMES = {1: "full priority of gravity", 2: "partial priority of gravity",
              3: "partial priority of centrifugal forces", 4: "full priority of centrifugal forces"}


def _check(volume, radius, height, g, omega=0.0, inner_radius=0.0):
    R = positive("radius", radius)
    h = positive("height", height)
    V = positive("volume", volume)
    positive("g", g)
    nonneg("omega", omega)
    ri = nonneg("inner_radius", inner_radius)
    if ri >= R:
        raise ParameterError("inner_radius", inner_radius, f"must be < the radius {R!r} m")
    vc = math.pi * (R * R - ri * ri) * h
    if V >= vc:
        raise ParameterError("volume", volume, f"must be < the chamber volume pi (R^2 - r_i^2) h "
                             f"= {vc:.6g} m^3 ({vc * 1e6:.6g} ml)")
    return V, R, h


def liquid_volume(z_star: float, omega: float, radius: float, height: float,
                  g: float = G_STANDARD) -> float:
    """Volume under the clipped paraboloid z_* + omega^2 r^2/(2g) in the chamber (003 eq 3-5).

    V = pi * integral_0^{R^2} clip(z_* + a s, 0, h) ds with a = omega^2/(2g), s = r^2; this is
    the material balance of 003 sec. 5.2 written once for every regime.

    Parameters
    ----------
    z_star : float
        Height of the paraboloid's vertex on the axis [m] (may be < 0: dry centre).
    omega : float
        Rotation speed [rad/s].
    radius, height : float
        Chamber R, h [m].
    g : float
        Gravity [m/s^2].

    Returns
    -------
    float
        Liquid volume [m^3].
    """
    S = radius * radius
    a = omega * omega / (2.0 * g)
    if a == 0.0:
        return math.pi * S * min(max(z_star, 0.0), height)
    # s-interval where 0 < depth < h, then the wetted-to-the-lid part (no 0/0 round-off)
    sa = min(max(-z_star / a, 0.0), S)
    sb = min(max((height - z_star) / a, 0.0), S)
    return math.pi * ((sb - sa) * (z_star + 0.5 * a * (sa + sb)) + height * (S - sb))


@dataclass(frozen=True)
class FreeSurface:
    """Free surface of the liquid at one speed (all lengths [m], speeds [rad/s]).

    Attributes
    ----------
    z_star : vertex height on the axis (< 0: the centre of the bottom is dry).
    regime : "A", "B", "C" or "D" (module docstring).
    mode : 003 motion mode 1..4.
    wall_height : liquid height at the wall, min(z(R), h).
    r_dry : radius of the dry bottom disc (0 if the bottom is wet).
    r_lid : radius inside which the liquid does not touch the lid (R if it does not touch).
    h0 : fill level at rest V/(pi R^2).
    """

    omega: float
    volume: float
    radius: float
    height: float
    g: float
    z_star: float
    regime: str
    mode: int
    wall_height: float
    r_dry: float
    r_lid: float
    h0: float

    def depth(self, r: float | npt.ArrayLike) -> np.ndarray:
        """Liquid depth clip(z_* + omega^2 r^2/(2g), 0, h) [m] at radii r [m] (003 eq 3).

        Parameters
        ----------
        r : float or array
            Radii [m], 0 <= r <= R.
        """
        r = np.asarray(r, dtype=float)
        return np.clip(self.z_star + self.omega ** 2 * r * r / (2.0 * self.g), 0.0, self.height)

    def mean_radius(self, n: int = 40001) -> float:
        """Volume-weighted mean radius of the liquid [m]: integral r^2 z dr / integral r z dr.

        It sets the unbalance the liquid can create.

        Parameters
        ----------
        n : int
            Points of the trapezoidal rule over 0..R.
        """
        r = np.linspace(0.0, self.radius, n)
        d = self.depth(r)
        from scipy.integrate import trapezoid      # numpy < 2 has no np.trapezoid

        return float(trapezoid(r * r * d, r) / trapezoid(r * d, r))

    def to_dict(self) -> dict:
        """The surface as a dict with SI units in the keys (``omega_rad_s``, ``z_star_m``, ...)."""
        d = asdict(self)
        return {"omega_rad_s": d["omega"], "volume_m3": d["volume"], "radius_m": d["radius"],
                "height_m": d["height"], "g_m_s2": d["g"], "z_star_m": d["z_star"],
                "regime": d["regime"], "mode": d["mode"], "mode_name": MODE_NAMES[d["mode"]],
                "wall_height_m": d["wall_height"], "r_dry_m": d["r_dry"],
                "r_lid_m": d["r_lid"], "h0_m": d["h0"]}


def _vertex(V: float, R: float, h: float, omega: float, g: float) -> tuple[float, str]:
    """Vertex height z_* [m] and regime from the volume balance (closed form per regime)."""
    S = R * R
    a = omega * omega / (2.0 * g)
    Vp = V / math.pi
    tol = 1e-12 * max(h, a * S)
    # A: wet bottom, below the lid -- 003 eq 4: z_* = h0 - omega^2 R^2 / (4 g)
    z = Vp / S - 0.5 * a * S
    if z >= -tol and z + a * S <= h + tol:
        return z, "A"
    # B: dry centre, below the lid: V/pi = a (S - s0)^2 / 2
    z = math.sqrt(2.0 * a * Vp) - a * S
    if z < tol and z + a * S <= h + tol:
        return z, "B"
    # C: wet bottom, touching the lid: V/pi = h S - (h - z_*)^2 / (2 a)
    z = h - math.sqrt(max(2.0 * a * (S * h - Vp), 0.0))
    if z >= -tol and z + a * S > h - tol:
        return z, "C"
    # D: dry centre, touching the lid -- 003 eq 5
    return 0.5 * h - a * (S * h - Vp) / h, "D"


def gravity_mode_speed(volume: float, radius: float, g: float = G_STANDARD,
                       gravity_fraction: float = 0.25) -> float:
    """End of mode 1 (full priority of gravity) [rad/s]; our criterion, 003 gives none.

    Mode 1 lasts while the centre of the surface has sunk by less than ``gravity_fraction`` of
    the rest level h0: omega^2 R^2/(4 g) < f h0 (from 003 eq 4), i.e. omega_1 = sqrt(f) * omega_b.

    Parameters
    ----------
    volume : float
        V [m^3].
    radius : float
        R [m].
    g : float
        Gravity [m/s^2].
    gravity_fraction : float
        f in (0, 1] [-].
    """
    f = positive("gravity_fraction", gravity_fraction)
    if f > 1.0:
        raise ParameterError("gravity_fraction", gravity_fraction, "must be in (0, 1]")
    return math.sqrt(f) * bottom_touch_speed(volume, radius, g)


def bottom_touch_speed(volume: float, radius: float, g: float = G_STANDARD) -> float:
    """Speed at which the paraboloid's vertex reaches the bottom, z_* = 0 [rad/s] (003 eq 4).

    omega = (2/R) sqrt(g h0) = (2/R^2) sqrt(g V / pi). Valid while the surface is below the lid
    there (V <= pi R^2 h / 2); above half filling the lid is reached first.

    Parameters
    ----------
    volume : float
        Liquid volume V [m^3].
    radius : float
        Chamber radius R [m].
    g : float
        Gravity [m/s^2].
    """
    V = positive("volume", volume)
    R = positive("radius", radius)
    return 2.0 / (R * R) * math.sqrt(positive("g", g) * V / math.pi)


def lid_touch_speed(volume: float, radius: float, height: float, g: float = G_STANDARD) -> float:
    """First speed at which the surface touches the lid [rad/s] (003 eq 4-6, our extension).

    V <= V_c/2: in regime B the wall height is H = omega sqrt(V/(pi g)), so the lid is reached at
    omega_0 = sqrt(pi g h^2 / V) (= 003 eq 6). V > V_c/2: in regime A, H = h0 + omega^2 R^2/(4 g)
    reaches h at (2/R) sqrt(g (h - h0)).

    Parameters
    ----------
    volume : float
        Liquid volume V [m^3], 0 < V < pi R^2 h.
    radius : float
        Chamber radius R [m].
    height : float
        Chamber height h [m].
    g : float
        Gravity [m/s^2].
    """
    V, R, h = _check(volume, radius, height, g)
    h0 = V / (math.pi * R * R)
    if h0 <= 0.5 * h:
        return math.sqrt(math.pi * g * h * h / V)
    return 2.0 / R * math.sqrt(g * (h - h0))


def entrainment_speed(volume: float, radius: float, height: float,
                      g: float = G_STANDARD, inner_radius: float = 0.0) -> float:
    """Start of mode 4, the liquid spans bottom to lid (003 eq 6) [rad/s].

    omega_0 = sqrt(pi g h^2 / V) for V <= V_c/2 (003 eq 6). For V > V_c/2 the same balance on the
    empty volume gives sqrt(pi g h^2 / (V_c - V)) (our extension: regime C -> D at z_* = 0).
    In an annulus (inner wall r_i) the surface r^2 = r_b^2 + 2 g z / omega^2 spans bottom to lid
    inside the chamber (r_b >= r_i, r_t <= R) holding V = pi h (R^2 - r_b^2) - pi g h^2/omega^2
    from omega^2 = pi g h^2 / min(V, V_c - V) on, with V_c = pi (R^2 - r_i^2) h: the same formula
    with the annulus' volume (our derivation; 003 writes the cylinder).

    Parameters
    ----------
    volume : float
        Liquid volume V [m^3], 0 < V < pi R^2 h.
    radius : float
        Chamber radius R [m].
    height : float
        Chamber height h [m].
    g : float
        Gravity [m/s^2].
    inner_radius : float
        Inner wall r_i [m], 0 <= r_i < R (0: 003's cylinder).
    """
    V, R, h = _check(volume, radius, height, g, inner_radius=inner_radius)
    vc = math.pi * (R * R - inner_radius * inner_radius) * h
    return math.sqrt(math.pi * g * h * h / min(V, vc - V))


def mode_speeds(volume: float, radius: float, height: float, g: float = G_STANDARD,
                gravity_fraction: float = 0.25) -> dict:
    """Speeds [rad/s] where the modes change: end of mode 1, 2 and 3 (start of mode 4).

    Parameters
    ----------
    volume : float
        Liquid volume V [m^3], 0 < V < pi R^2 h.
    radius : float
        Chamber radius R [m].
    height : float
        Chamber height h [m].
    g : float
        Gravity [m/s^2].
    gravity_fraction : float
        Mode-1 criterion f in (0, 1] [-] (:func:`gravity_mode_speed`).

    Returns
    -------
    dict
        ``omega_1_rad_s`` (mode 1 -> 2, our criterion :func:`gravity_mode_speed`),
        ``omega_2_rad_s`` (mode 2 -> 3: bottom touch if V <= V_c/2 else lid touch),
        ``omega_0_rad_s`` (mode 3 -> 4, 003 eq 6), plus ``bottom_touch_rad_s`` and
        ``lid_touch_rad_s``.
    """
    V, R, h = _check(volume, radius, height, g)
    h0 = V / (math.pi * R * R)
    w_b = bottom_touch_speed(V, R, g) if h0 <= 0.5 * h else entrainment_speed(V, R, h, g)
    w_l = lid_touch_speed(V, R, h, g)
    w2 = min(bottom_touch_speed(V, R, g), w_l) if h0 <= 0.5 * h else w_l
    w1 = min(gravity_mode_speed(V, R, g, gravity_fraction), w2)
    return {"omega_1_rad_s": w1, "omega_2_rad_s": w2,
            "omega_0_rad_s": entrainment_speed(V, R, h, g),
            "bottom_touch_rad_s": w_b, "lid_touch_rad_s": w_l}


def motion_mode(omega: float, volume: float, radius: float, height: float,
                g: float = G_STANDARD, gravity_fraction: float = 0.25) -> int:
    """003 motion mode (1..4) at speed omega (003 sec. 5.1, boundaries of :func:`mode_speeds`).

    Parameters
    ----------
    omega : float
        Rotation speed [rad/s] >= 0.
    volume : float
        Liquid volume V [m^3], 0 < V < pi R^2 h.
    radius : float
        Chamber radius R [m].
    height : float
        Chamber height h [m].
    g : float
        Gravity [m/s^2].
    gravity_fraction : float
        Mode-1 criterion f in (0, 1] [-].
    """
    s = mode_speeds(volume, radius, height, g, gravity_fraction)
    w = nonneg("omega", omega)
    if w >= s["omega_0_rad_s"]:
        return 4
    if w >= s["omega_2_rad_s"]:
        return 3
    return 2 if w >= s["omega_1_rad_s"] else 1


def free_surface(omega: float, volume: float, radius: float, height: float,
                 g: float = G_STANDARD, gravity_fraction: float = 0.25) -> FreeSurface:
    """Free surface of V in the closed chamber turning at omega (003 eq 2-5, every regime).

    Parameters
    ----------
    omega : float
        Rotation speed [rad/s] >= 0.
    volume : float
        Liquid volume V [m^3], 0 < V < pi R^2 h.
    radius, height : float
        Chamber R, h [m].
    g : float
        Gravity [m/s^2].
    gravity_fraction : float
        Mode-1 criterion of :func:`gravity_mode_speed` [-].

    Returns
    -------
    FreeSurface
    """
    V, R, h = _check(volume, radius, height, g, finite("omega", omega))
    z, regime = _vertex(V, R, h, omega, g)
    a = omega * omega / (2.0 * g)
    r_dry = math.sqrt(-z / a) if z < 0.0 else 0.0
    r_lid = min(math.sqrt((h - z) / a), R) if a > 0.0 and regime in "CD" else R
    return FreeSurface(omega=float(omega), volume=V, radius=R, height=h, g=g, z_star=z,
                       regime=regime, mode=motion_mode(omega, V, R, h, g, gravity_fraction),
                       wall_height=min(z + a * R * R, h), r_dry=r_dry, r_lid=r_lid,
                       h0=V / (math.pi * R * R))


def surface_height(r: float | npt.ArrayLike, omega: float, volume: float, radius: float,
                   height: float, g: float = G_STANDARD) -> np.ndarray:
    """Liquid depth [m] at radii r (vectorised :meth:`FreeSurface.depth`).

    Parameters
    ----------
    r : float or array
        Radii [m], 0 <= r <= R.
    omega : float
        Rotation speed [rad/s] >= 0.
    volume : float
        Liquid volume V [m^3], 0 < V < pi R^2 h.
    radius : float
        Chamber radius R [m].
    height : float
        Chamber height h [m].
    g : float
        Gravity [m/s^2].
    """
    return free_surface(omega, volume, radius, height, g).depth(r)


def surface_profiles(omegas: Sequence[float], volume: float, radius: float, height: float,
                     g: float = G_STANDARD, n: int = 1201, wall_zoom: float = 0.1) -> dict:
    """Liquid depth z(r) [m] at several speeds on one radial grid, for a figure (003 eq 3-5).

    The grid has ``n`` points over the whole radius and ``n`` more over the last ``wall_zoom``
    fraction of it at the wall, where the surface of the fast modes lies.

    Parameters
    ----------
    omegas : sequence of float
        Speeds [rad/s].
    volume : float
        Liquid volume V [m^3].
    radius : float
        Chamber radius R [m].
    height : float
        Chamber height h [m].
    g : float
        Gravity [m/s^2].
    n : int
        Points per part of the grid.
    wall_zoom : float
        Fraction of the radius next to the wall sampled densely [-].

    Returns
    -------
    dict
        ``omega_rad_s``, ``r_m`` (grid), ``depth_m`` (speeds x grid), ``mode``, ``regime`` (one
        per speed), ``volume_m3``, ``radius_m``, ``height_m``, ``g_m_s2``, ``wall_zoom``.
    """
    r = np.union1d(np.linspace(0.0, radius, n),
                   np.linspace(radius - wall_zoom * radius, radius, n))
    fss = [free_surface(w, volume, radius, height, g) for w in omegas]
    return {"omega_rad_s": np.array([float(w) for w in omegas]), "r_m": r,
            "depth_m": np.array([f.depth(r) for f in fss]), "mode": [f.mode for f in fss],
            "regime": [f.regime for f in fss], "volume_m3": volume, "radius_m": radius,
            "height_m": height, "g_m_s2": g, "wall_zoom": wall_zoom}
