"""The liquid in a displaced chamber, quasi-statically: rigid rotation about the
*rotation axis* while the chamber's centre is displaced by the rotor's deflection.

In a frame turning with the rotor at Omega, a liquid in rigid rotation is in equilibrium under the
centrifugal and gravity potentials (Euler's equations; 003 eq 1-3 for a centred chamber). Its
pressure is constant on the surfaces Omega^2 |x - x0|^2 / 2 + g z = const, where x is measured
from the rotation axis in the plane of rotation and z along it:

* **vertical axis** (003's bench; gravity along the axis): x0 = 0, and the free surface is the
  paraboloid z = z* + Omega^2 |x|^2 / (2 g) about the *rotation axis* (Newton's bucket), clipped
  to the chamber (bottom z = 0, lid z = h);
* **planar** (no gravity along the axis: a horizontal axis, or the limit Omega^2 R >> g): the
  surface is the cylinder |x - x0| = r_s through the whole height; on a horizontal axis gravity g
  in the plane moves its centre to x0 = (g / Omega^2) u, u the upward unit vector (the potential
  Omega^2 |x|^2/2 - g x.u = Omega^2 |x - x0|^2/2 + const).

The chamber is an annulus (inner radius r_i, 0 for a cylinder; outer R; height h) whose centre is
at c = the rotor's deflection from the axis. At height z the liquid fills the annulus outside the
circle |x - x0| = r_s(z) (r_s^2 = (z - z*) / a, a = Omega^2 / 2g, for the paraboloid; everything
below the vertex). The regimes of the issue then follow from the geometry alone:

* **intact ring**: the surface circle lies inside the outer wall; the liquid's first moment about
  the chamber centre is exactly that of the missing core, rho pi r_s^2 h (c - x0) (closed form,
  :func:`intact_ring_unbalance`): with x0 = 0 and V = pi (R^2 - r_s^2) h, U = rho (V_c - V) c.
  The classical result for a partly filled rotor: the liquid pulls like a full chamber
  (Ehrich, *Handbook of Rotordynamics*, 1992, sec. 5 "fluid-filled rotors"; Kollmann 1962);
* **crescent**: once the circle crosses the outer wall (|c - x0| > R - r_s) the film breaks and the
  liquid gathers on the far side: the lens of the two circles is cut out in closed form
  (:func:`lens`), and r_s (or z*) solves the volume balance;
* **dry** and **lid-touching** regions: the clip of the paraboloid to [0, h].

The per-layer area and moment are closed forms (circle-circle lens); the vertical axis integrates
them over the height (adaptive quadrature with the tangency kinks as break points). Everything
here is SI and pure; the dynamic (shallow-water) model is not here.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from scipy.integrate import quad
from scipy.optimize import brentq

from ..models._validate import ParameterError, nonneg, positive
from ..models.liquid_balancer import G_STANDARD

__all__ = ["QuasiStatic", "intact_ring_unbalance", "layer", "lens", "quasi_static",
           "segment_area"]

#: Relative tolerance of the volume balance (root) and of the height quadrature [-].
RTOL = 1e-11


def segment_area(r: float, t: float) -> float:
    """Area of the part of a disk of radius r beyond a chord at signed distance t from its centre
    [m^2]: r^2 acos(t/r) - t sqrt(r^2 - t^2) (t = -r: the whole disk; t = r: nothing).

    Parameters
    ----------
    r : float
        Disk radius [m].
    t : float
        Signed distance of the chord from the centre [m], clipped to [-r, r].
    """
    t = min(max(t, -r), r)
    return r * r * math.acos(t / r) - t * math.sqrt(max(r * r - t * t, 0.0)) if r > 0 else 0.0


def lens(a: float, b: float, D: float) -> tuple[float, float]:
    """Area [m^2] and first moment [m^3] of the intersection of the disk of radius a centred at
    the origin with the disk of radius b centred at distance D on the +x axis; the moment is about
    the origin, along +x.

    Closed form (two circular segments cut by the common chord at x = d1 = (D^2 + a^2 - b^2)/2D):
    area S(a, d1) + S(b, D - d1) with S = :func:`segment_area`. The two segments' own moments
    about their centres, (2/3) (r^2 - t^2)^(3/2), are equal and opposite (both are (2/3) of the
    half chord cubed), so the moment about the origin is D S(b, D - d1).

    Parameters
    ----------
    a : float
        Radius of the disk at the origin [m], >= 0.
    b : float
        Radius of the other disk [m], >= 0.
    D : float
        Distance between the centres [m], >= 0.

    Returns
    -------
    (float, float)
        Area [m^2] and x-moment about the origin [m^3].
    """
    if a <= 0.0 or b <= 0.0 or D >= a + b:
        return 0.0, 0.0
    if D <= b - a:                               # disk a inside disk b
        return math.pi * a * a, 0.0
    if D <= a - b:                               # disk b inside disk a
        A = math.pi * b * b
        return A, A * D
    d1 = (D * D + a * a - b * b) / (2.0 * D)
    s2 = segment_area(b, D - d1)
    return segment_area(a, d1) + s2, D * s2


def layer(R: float, r_inner: float, r_s: float, offset: complex) -> tuple[float, complex]:
    """Area [m^2] and first moment about the chamber centre [m^3] (complex, in the plane) of the
    liquid in one layer: the annulus r_inner <= |x - c| <= R outside the surface circle
    |x - x0| = r_s, with offset = x0 - c (the surface centre seen from the chamber centre).

    Parameters
    ----------
    R : float
        Outer wall radius [m].
    r_inner : float
        Inner wall radius [m] (0: a cylinder).
    r_s : float
        Radius of the surface circle [m] (0: the whole annulus is liquid).
    offset : complex
        x0 - c [m]: the surface circle's centre relative to the chamber centre.

    Returns
    -------
    (float, complex)
        Liquid area [m^2] and its first moment about the chamber centre [m^3].
    """
    D = abs(offset)
    e = offset / D if D > 0 else 0.0
    aR, mR = lens(R, r_s, D)
    ai, mi = lens(r_inner, r_s, D)
    area = math.pi * (R * R - r_inner * r_inner) - (aR - ai)
    return area, -(mR - mi) * e


def intact_ring_unbalance(density: float, chamber_volume: float, volume: float,
                          offset: complex) -> complex:
    """Unbalance of an intact liquid ring about the chamber centre [kg*m]: rho (V_c - V) (c - x0),
    the missing core's mass times the chamber's offset from the surface axis (module docstring;
    a cylinder or an annulus whose inner wall lies inside the core, free surface through the
    whole height).

    Parameters
    ----------
    density : float
        rho [kg/m^3].
    chamber_volume : float
        V_c = pi R^2 h [m^3] (the outer wall's cylinder).
    volume : float
        Liquid volume V [m^3].
    offset : complex
        c - x0 [m]: the chamber centre relative to the surface axis (the deflection, for a
        vertical axis).

    Returns
    -------
    complex
        [kg*m], along the deflection.
    """
    return density * (chamber_volume - volume) * offset


@dataclass(frozen=True)
class QuasiStatic:
    """The liquid's quasi-static state in a displaced chamber (:func:`quasi_static`).

    Parameters
    ----------
    unbalance : complex
        First moment of the liquid's mass about the chamber centre [kg*m] (in the plane, the
        deflection along +x when it is real).
    mass : float
        Liquid mass rho V [kg]; it translates with the chamber. The centrifugal pull of the liquid
        on the rotor is Omega^2 (mass * c + unbalance) [N].
    regime : str
        "ring" (the surface circle inside the outer wall at every height) or "crescent" (it
        crosses the wall: the film broken); "rest" at Omega = 0.
    surface : float
        The surface's parameter that closes the volume balance: r_s [m] (planar) or the
        paraboloid's vertex height z* [m] (vertical axis, may be < 0: dry centre).
    dry_bottom : bool
        Part of the bottom is dry (vertical axis) / the inner annulus is uncovered.
    lid : bool
        The surface reaches the lid somewhere (vertical axis).
    """

    unbalance: complex
    mass: float
    regime: str
    surface: float
    dry_bottom: bool
    lid: bool


def _check(R, h, r_inner, volume, density, speed, g):
    positive("chamber.radius", R)
    positive("chamber.height", h)
    nonneg("chamber.inner_radius", r_inner)
    if r_inner >= R:
        raise ParameterError("chamber.inner_radius", r_inner, f"must be < the radius {R!r} m")
    positive("volume", volume)
    vc = math.pi * (R * R - r_inner * r_inner) * h
    if volume >= vc:
        raise ParameterError("volume", volume, f"must be < the chamber's volume {vc:.6g} m^3")
    positive("density", density)
    nonneg("speed", speed)
    nonneg("g", g)


def quasi_static(radius: float, height: float, volume: float, density: float, speed: float,
                 deflection: complex, *, inner_radius: float = 0.0, g: float = G_STANDARD,
                 axis: str = "vertical", up: complex = 1j) -> QuasiStatic:
    """The liquid of a chamber displaced by ``deflection`` from the rotation axis, in rigid
    rotation at ``speed`` (module docstring): its unbalance about the chamber centre and regime.

    Parameters
    ----------
    radius : float
        Outer wall radius R [m].
    height : float
        Chamber height h [m].
    volume : float
        Liquid volume V [m^3], 0 < V < the chamber's volume.
    density : float
        Liquid density rho [kg/m^3].
    speed : float
        Spin speed Omega [rad/s], >= 0 (planar axes need > 0).
    deflection : complex
        Chamber centre relative to the rotation axis [m], in the rotor frame.
    inner_radius : float
        Inner wall radius r_i [m] (0: a cylinder).
    g : float
        Gravity [m/s^2].
    axis : str
        "vertical" (gravity along the axis: paraboloid clipped to bottom and lid), "horizontal"
        (gravity in the plane, direction ``-up``) or "planar" (no gravity: the Omega -> infinity
        limit of both).
    up : complex
        Direction opposite to gravity in the plane of rotation, rotor frame ("horizontal";
        normalised here) [-].

    Returns
    -------
    QuasiStatic
    """
    R, h, ri = float(radius), float(height), float(inner_radius)
    _check(R, h, ri, volume, density, speed, g)
    c = complex(deflection)
    mass = density * volume
    if axis in ("planar", "horizontal"):
        if speed <= 0:
            raise ParameterError("speed", speed, f"must be > 0 on a {axis} axis (the liquid "
                                 "rests in the bottom of the chamber at 0)")
        x0 = 0j if axis == "planar" else (g / speed ** 2) * up / abs(up)
        off = x0 - c
        target = volume / h

        def excess(rs):
            return layer(R, ri, rs, off)[0] - target

        hi = R + abs(off)
        rs = brentq(excess, 0.0, hi, xtol=RTOL * R, rtol=4.5 * 2.2205e-16) if excess(0.0) > 0 else 0.0
        area, mom = layer(R, ri, rs, off)
        ring = rs + abs(off) <= R and (ri == 0.0 or rs >= ri + abs(off))
        return QuasiStatic(density * h * mom, mass, "ring" if ring else "crescent", rs,
                           rs < ri + abs(off) and ri > 0, False)
    if axis != "vertical":
        raise ParameterError("axis", axis, "must be 'vertical', 'horizontal' or 'planar'")
    if speed == 0.0:
        return QuasiStatic(0j, mass, "rest", volume / (math.pi * (R * R - ri * ri)), False, False)
    return _vertical(R, h, ri, volume, density, speed, c, g, mass)


def _vertical(R, h, ri, V, rho, W, c, g, mass):
    """Vertical axis: layers at height z hold the annulus outside r_s(z) = sqrt((z - z*)/a)."""
    a = W * W / (2.0 * g)
    off = -c
    D = abs(off)
    # r_s^2 at which the surface circle is tangent to a wall: kinks of the layer area
    kinks = sorted({max(x, 0.0) ** 2 for x in (R - D, R + D, ri - D, ri + D, D - ri) if x > 0})

    def integral(zs, which):
        full = max(0.0, zs)                       # below the vertex the layers are full
        s_top = (h - zs) / a
        s_lo = (full - zs) / a
        pts = [s for s in kinks if s_lo < s < s_top]

        def f(s):
            A, M = layer(R, ri, math.sqrt(s), off)
            return A if which == 0 else (M.real if which == 1 else M.imag)

        full_val = math.pi * (R * R - ri * ri) * full if which == 0 else 0.0
        if s_top <= s_lo:
            return full_val
        val, _ = quad(f, s_lo, s_top, points=pts or None, epsabs=RTOL * R ** 4, epsrel=RTOL,
                      limit=200)
        return full_val + a * val

    def excess(zs):
        return integral(zs, 0) - V

    lo, hi = -a * (R + D) ** 2, h
    zs = brentq(excess, lo, hi, xtol=RTOL * h, rtol=4.5 * 2.2205e-16)
    U = rho * complex(integral(zs, 1), integral(zs, 2))
    s_bottom = max(-zs, 0.0) / a                 # r_s^2 at the bottom (0: wet centre)
    s_top = (h - zs) / a                          # r_s^2 at the lid
    ring = math.sqrt(s_top) + D <= R              # a full ring up to the lid
    dry = zs < 0.0 and (ri == 0.0 or math.sqrt(s_bottom) > ri - D)
    lid = s_top < (R + D) ** 2
    return QuasiStatic(U, mass, "ring" if ring else "crescent", zs, dry, lid)

