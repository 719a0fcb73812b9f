"""Axisymmetric shallow-water equations of the liquid on the bottom of a rotating chamber with a
vertical axis, from rest until its free surface reaches the lid at the outer wall: the spin-up
of the liquid through 003's modes 1-3 (model: docs/liquid/spin-up.md sec. 3h).

Unknowns per ring of cells r_{i-1/2} < r < r_{i+1/2} (chamber frame, turning at Omega(t)): the
depth h [m] of the liquid along the axis, its radial discharge q = h u and its azimuthal
discharge s = h v [m^2/s], u and v relative to the chamber:

    (r h)_t + (r q)_r = 0
    (r q)_t + (r (q^2/h + g h^2/2))_r = g h^2/2 + r h omega^2 r - k r q
    (r s)_t + (r q v)_r = -r (q v / r + 2 Omega q + Omega' r h) - k r s + (r^2 T)_r / r
    T = nu h r d(v/r)/dr

The radial balance is that of the depth-averaged Euler equations in the rotating frame: the
pressure g h^2/2 against the centrifugal, Coriolis and curvature terms h (Omega^2 r + 2 Omega v
+ v^2/r) = h omega^2 r, omega = Omega + v/r the liquid's absolute angular velocity. k is the
bottom friction rate: the larger of the wall film's law (:func:`.shallow_water.friction_rate`:
a laminar layer 3 nu / h^2, turbulent Blasius) and the Ekman layer's sqrt(nu |Omega|) / h of a
layer deeper than the Ekman depth sqrt(nu / Omega) (Greenspan & Howard 1963, J. Fluid Mech. 17,
385: spin-up time h / sqrt(nu Omega) with one Ekman layer under a free surface). T is the
lateral viscous shear (molecular nu), with no slip (v = 0) on the inner and outer walls: the
side walls' shear, which spins up the liquid gathered at the wall.

Scheme: finite volumes in r with the face radii as weights; HLL flux on the hydrostatic
reconstruction of Audusse et al. (2004, SIAM J. Sci. Comput. 25, 2050; as the wall film,
core/shallow_water.py) over the *apparent bottom* B of the liquid's own rotation,
B_i - B_{i-1} = -(omega_f^2 / 2 g)(r_i^2 - r_{i-1}^2) (the "apparent topography" of rotating
shallow water, Bouchut, Le Sommer & Zeitlin 2004, J. Fluid Mech. 514, 35), which holds the
centrifugal, Coriolis and curvature terms; with the geometric source g h_i^2/2 (r_{i+1/2} -
r_{i-1/2}) of the same cell value, a liquid in rigid rotation at any speed, dry centre
included, is kept to round-off. Without it (B from the chamber's speed and the rest as a cell
source) the lag of the liquid did not converge under grid refinement (HLL's diffusion acts on
the departure from the chamber's paraboloid, large while the liquid lags: docs/liquid/spin-up.md
sec. 3h). The azimuthal discharge is carried by the mass flux (upwind); friction implicit; forward
Euler; reflecting walls at the inner wall (or the axis, face radius 0) and the outer wall.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .jit import kernel
from .rhs import profile_eval, profile_segment
from .shallow_water import CFL, DRY_FRACTION, friction_rate, hll_flux, sw_max_speed

if TYPE_CHECKING:
    import numpy as np


@kernel
def bottom_friction(h: float, u: float, v: float, nu: float, w: float, R: float) -> float:
    """Bottom friction rate k [1/s] of a layer of depth h [m] moving at (u, v) [m/s] over the
    bottom turning at w [rad/s]: the larger of :func:`.shallow_water.friction_rate` (laminar
    3 nu / h^2, turbulent Blasius) and the Ekman layer's sqrt(nu |w|) / h (module docstring);
    nu [m^2/s]; 0 for a dry cell (R [m]: the scale)."""
    if h <= DRY_FRACTION * R:
        return 0.0
    k = friction_rate(h, math.sqrt(u * u + v * v), nu, R)
    ke = math.sqrt(nu * abs(w)) / h
    return ke if ke > k else k


@kernel
def radial_step(h: np.ndarray, q: np.ndarray, s: np.ndarray, rf: np.ndarray, g: float,
                w: float, wd: float, dt: float, nu: float, R: float, hn: np.ndarray,
                qn: np.ndarray, sn: np.ndarray, fh: np.ndarray, fq: np.ndarray,
                fql: np.ndarray, fqr: np.ndarray, fs: np.ndarray) -> None:
    """One forward-Euler step dt [s] of the module's equations on the n cells between the face
    radii rf (n + 1) [m]: h, q, s the state [m, m^2/s, m^2/s]; gravity g [m/s^2] along the axis;
    spin w [rad/s] and its rate wd [rad/s^2]; nu [m^2/s]; R [m] (dry scale). Writes hn, qn,
    sn; fh, fq, fql, fqr, fs are work arrays (n + 1) of the face fluxes (fql, fqr: the radial
    momentum flux with the hydrostatic correction as seen from the cell inside / outside)."""
    n = h.shape[0]
    dry = DRY_FRACTION * R
    # the apparent bottom of the liquid's own rotation (in sn, free until the cells' update):
    # B_i - B_{i-1} = -(omega_f^2 / 2 g) (r_i^2 - r_{i-1}^2), omega = w + v / r the liquid's
    # absolute angular velocity, omega_f the mean of the two cells'
    rp = 0.0
    op = 0.0
    for i in range(n):
        rc_ = 0.5 * (rf[i] + rf[i + 1])
        om = w + (s[i] / h[i] / rc_ if h[i] > dry else 0.0)
        if i == 0:
            sn[0] = -om * om * rc_ * rc_ / (2.0 * g)
        else:
            of = 0.5 * (om + op)
            sn[i] = sn[i - 1] - of * of * (rc_ * rc_ - rp * rp) / (2.0 * g)
        rp = rc_
        op = om
    for f in range(n + 1):           # faces; 0 and n are walls (reflecting)
        if f == 0 or f == n:
            i = 0 if f == 0 else n - 1
            ui = q[i] / h[i] if h[i] > dry else 0.0
            if f == 0:
                _, f1 = hll_flux(h[i], -h[i] * ui, h[i], h[i] * ui, g, dry)
            else:
                _, f1 = hll_flux(h[i], h[i] * ui, h[i], -h[i] * ui, g, dry)
            fh[f] = 0.0
            fs[f] = 0.0
            fql[f] = f1
            fqr[f] = f1
            # no-slip wall: the lateral shear T = nu h r d(v/r)/dr with v = 0 on the wall
            rw = rf[f]
            rci = 0.5 * (rf[i] + rf[i + 1])
            vi = s[i] / h[i] if h[i] > dry else 0.0
            fq[f] = nu * h[i] * rw * (0.0 - vi / rci) / (rw - rci) if rw > 0.0 else 0.0
            continue
        i = f - 1
        j = f
        ri = 0.5 * (rf[i] + rf[i + 1])
        rj = 0.5 * (rf[j] + rf[j + 1])
        bi = sn[i]
        bj = sn[j]
        ul = q[i] / h[i] if h[i] > dry else 0.0
        ur = q[j] / h[j] if h[j] > dry else 0.0
        bs = max(bi, bj)
        hls = max(0.0, h[i] + bi - bs)
        hrs = max(0.0, h[j] + bj - bs)
        f0, f1 = hll_flux(hls, hls * ul, hrs, hrs * ur, g, dry)
        fh[f] = f0
        fq[f] = f1
        fql[f] = f1 + 0.5 * g * (h[i] * h[i] - hls * hls)
        fqr[f] = f1 + 0.5 * g * (h[j] * h[j] - hrs * hrs)
        vl = s[i] / h[i] if h[i] > dry else 0.0
        vr = s[j] / h[j] if h[j] > dry else 0.0
        fs[f] = f0 * (vl if f0 > 0.0 else vr)
        if h[i] > dry and h[j] > dry:      # the lateral shear T = nu h r d(v/r)/dr
            fq[f] = nu * min(h[i], h[j]) * rf[f] * (vr / rj - vl / ri) / (rj - ri)
        else:
            fq[f] = 0.0
    for i in range(n):
        r0 = rf[i]
        r1 = rf[i + 1]
        area = 0.5 * (r1 * r1 - r0 * r0)           # integral of r dr over the cell
        rc = 0.5 * (r0 + r1)
        hi = h[i] - dt / area * (r1 * fh[i + 1] - r0 * fh[i])
        if hi <= dry:
            hn[i] = max(hi, 0.0)
            qn[i] = 0.0
            sn[i] = 0.0
            continue
        v = s[i] / h[i] if h[i] > dry else 0.0
        qi = q[i] - dt / area * (r1 * fql[i + 1] - r0 * fqr[i]) \
            + dt * 0.5 * g * h[i] * h[i] * (r1 - r0) / area
        si = s[i] - dt / area * (r1 * fs[i + 1] - r0 * fs[i]) \
            - dt * (q[i] * v / rc + 2.0 * w * q[i] + wd * rc * h[i]) \
            + dt / (area * rc) * (r1 * r1 * fq[i + 1] - r0 * r0 * fq[i])
        k = bottom_friction(hi, qi / hi, si / hi, nu, w, R)
        hn[i] = hi
        qn[i] = qi / (1.0 + dt * k)
        sn[i] = si / (1.0 + dt * k)


@kernel
def wall_level(h: np.ndarray, rf: np.ndarray, w: float, g: float) -> float:
    """Height of the free surface at the outer wall [m]: the last cell's level h + b carried to
    the wall radius (exact for the lake at rest; b = -w^2 r^2 / (2 g))."""
    n = h.shape[0]
    rc = 0.5 * (rf[n - 1] + rf[n])
    R = rf[n]
    return h[n - 1] + w * w / (2.0 * g) * (R * R - rc * rc)


@kernel
def spinup_integrate(h: np.ndarray, q: np.ndarray, s: np.ndarray, rf: np.ndarray, g: float,
                     nu: float, lid: float, t_end: float, tt: np.ndarray, tw: np.ndarray,
                     out_t: np.ndarray, out_h: np.ndarray, out_q: np.ndarray,
                     out_s: np.ndarray, hn: np.ndarray, qn: np.ndarray, sn: np.ndarray,
                     fh: np.ndarray, fq: np.ndarray, fql: np.ndarray, fqr: np.ndarray,
                     fs: np.ndarray) -> tuple[int, float]:
    """Integrate from t = 0 until t_end [s] or until the free surface at the outer wall reaches
    the lid height ``lid`` [m] (:func:`wall_level`), with the CFL step (half of the wall film's
    Courant number: the cell next to the axis drains through a face of twice its mean radius),
    the spin from the table tt [s], tw [rad/s] (linear: its acceleration the slope of each
    segment, rhs.profile_eval); gravity g [m/s^2];
    nu [m^2/s]. h, q, s hold the initial state and are overwritten by the final one; out_h,
    out_q, out_s (len(out_t), n) receive the state at the sorted output times out_t [s] (rows
    after the stop are left alone). Returns (steps, stop time [s]); steps = -1 on a non-finite
    state. The stop time is t_end when the lid is not reached."""
    n = h.shape[0]
    R = rf[n]
    dr_min = R
    for i in range(n):
        if rf[i + 1] - rf[i] < dr_min:
            dr_min = rf[i + 1] - rf[i]
    t = 0.0
    steps = 0
    k = 0
    nout = out_t.shape[0]
    while True:
        while k < nout and out_t[k] <= t + 1e-12 * max(1.0, t):
            for i in range(n):
                out_h[k, i] = h[i]
                out_q[k, i] = q[i]
                out_s[k, i] = s[i]
            k += 1
        w, wd = profile_eval(t, profile_segment(t, tt), tt, tw)
        if wall_level(h, rf, w, g) >= lid or t >= t_end:
            return steps, t
        sp = sw_max_speed(h, q, g, R)
        dt = t_end - t
        if sp > 0.0 and 0.5 * CFL * dr_min / sp < dt:
            dt = 0.5 * CFL * dr_min / sp
        if 0.2 * dr_min * dr_min / nu < dt:          # the lateral shear, explicit
            dt = 0.2 * dr_min * dr_min / nu
        if k < nout and out_t[k] - t < dt and out_t[k] > t:
            dt = out_t[k] - t
        radial_step(h, q, s, rf, g, w, wd, dt, nu, R, hn, qn, sn, fh, fq, fql, fqr, fs)
        ok = True
        for i in range(n):
            h[i] = hn[i]
            q[i] = qn[i]
            s[i] = sn[i]
            if not (math.isfinite(h[i]) and math.isfinite(q[i]) and math.isfinite(s[i])):
                ok = False
        steps += 1
        if not ok:
            return -1, t
        t += dt
