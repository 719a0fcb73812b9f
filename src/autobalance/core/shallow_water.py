"""Depth-averaged shallow-water (Saint-Venant) equations of a liquid film on the outer wall of a
rotating, displaced chamber, along its circumference (model: docs/liquid/film.md sec. 3c).

Unknowns per cell of the periodic wall coordinate x = R theta (chamber frame): the film thickness
eta [m] and its tangential discharge q = eta v [m^2/s] (v relative to the wall):

    eta_t + q_x = 0
    q_t + (q^2/eta + g eta^2/2)_x = -g eta b_x + eta a(x, t) - eta k(eta, v) v

with g = Omega^2 R the centrifugal "gravity" across the film, b = -Re(c e^{-i theta}) the wall's
height in the centrifugal potential when the chamber centre is displaced by c from the rotation
axis (the film gathers where the wall is farthest from the axis), a the tangential inertial
acceleration of the chamber frame (Euler -Omega' R, the chamber's own motion) and k the wall
friction rate (laminar film 3 nu / eta^2, turbulent Blasius).

Gravity in the chamber's plane (a horizontal axis), g_p e^{i gamma} in the inertial frame, is
g_p e^{i(gamma - psi)} in the rotor frame (psi the spin angle). With the centrifugal field its
potential is -Omega^2 |r + g_p e^{i(gamma - psi)} / Omega^2|^2 / 2 + const: gravity moves the
centre of the potential by -g_p e^{i(gamma - psi)}/Omega^2, so the wall height is b of the
effective displacement c + g_p e^{i(gamma - psi)}/Omega^2 (the free surface of a rotating
horizontal drum is a circle offset by g/Omega^2; first order in g/(Omega^2 R) like b itself).

Scheme: finite volumes, HLL flux on the hydrostatic reconstruction of Audusse, Bouchut, Bristeau,
Klein & Perthame (2004, SIAM J. Sci. Comput. 25, 2050-2065): well balanced (a film at rest on any
wall profile stays at rest to round-off, dry cells included) and positivity preserving under the
CFL condition; friction implicit (stable for thin films); forward Euler in time, first order in
space. All kernels work on preallocated arrays (core/jit.py).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .jit import kernel
from .rhs import profile_eval, profile_segment, table_interp

if TYPE_CHECKING:
    import numpy as np

#: Films thinner than this fraction of R are dry: no velocity, no friction [-].
DRY_FRACTION = 1e-12
#: Courant number of the time step [-] (positivity of the hydrostatic reconstruction needs <= 1/2).
CFL = 0.45
#: Reynolds number (4 eta |v| / nu) below which the Blasius law is under the laminar one and is
#: not evaluated [-] (it crosses at (96 / 0.3164)^(4/3) = 2039: friction_rate is continuous).
RE_BLASIUS = 2000.0


@kernel
def hll_flux(hl: float, ql: float, hr: float, qr: float, g: float,
             dry: float) -> tuple[float, float]:
    """HLL flux (Harten, Lax & van Leer 1983) of the shallow-water equations between the states
    (hl, ql) and (hr, qr) [m, m^2/s], gravity g [m/s^2], dry threshold [m]: (F_eta, F_q)."""
    ul = ql / hl if hl > dry else 0.0
    ur = qr / hr if hr > dry else 0.0
    cl = math.sqrt(g * hl)
    cr = math.sqrt(g * hr)
    sl = min(ul - cl, ur - cr)
    sr = max(ul + cl, ur + cr)
    fl0 = ql
    fl1 = ql * ul + 0.5 * g * hl * hl
    fr0 = qr
    fr1 = qr * ur + 0.5 * g * hr * hr
    if sl >= 0.0:
        return fl0, fl1
    if sr <= 0.0:
        return fr0, fr1
    if sr - sl <= 0.0:
        return 0.0, 0.0
    f0 = (sr * fl0 - sl * fr0 + sl * sr * (hr - hl)) / (sr - sl)
    f1 = (sr * fl1 - sl * fr1 + sl * sr * (qr - ql)) / (sr - sl)
    return f0, f1


@kernel
def friction_rate(h: float, v: float, nu: float, R: float) -> float:
    """Wall friction rate k [1/s] of a film of thickness h [m] moving at v [m/s] relative to the
    wall, kinematic viscosity nu [m^2/s]: the larger of the laminar film's 3 nu / h^2 (half
    Poiseuille profile) and the turbulent Blasius law lambda/(8 h) |v|, lambda = 0.3164 Re^-1/4,
    Re = 4 h |v| / nu (hydraulic diameter of a wide film); 0 for a dry cell (R: the scale).
    The larger of the two, not a switch at a Reynolds number: Blasius overtakes the laminar law
    at Re = (96 / 0.3164)^(4/3) = 2039 (in pipe flow's transition range), so k is continuous
    (a switch at Re 2300 made it jump by 9 % and the films' step discontinuous;
    docs/liquid/horizontal-axis.md sec. 3m)."""
    if h <= DRY_FRACTION * R:
        return 0.0
    k = 3.0 * nu / (h * h)
    re = 4.0 * h * abs(v) / nu
    if re > RE_BLASIUS:
        kt = 0.3164 * re ** -0.25 / (8.0 * h) * abs(v)
        if kt > k:
            k = kt
    return k


@kernel
def accept_state(h: np.ndarray, q: np.ndarray, hn: np.ndarray, qn: np.ndarray) -> bool:
    """Copy a step's new state hn, qn [m, m^2/s] into h, q; False if any of it is not finite
    (the films', the horizontal spin-up's)."""
    ok = True
    for i in range(h.shape[0]):
        h[i] = hn[i]
        q[i] = qn[i]
        if not (math.isfinite(h[i]) and math.isfinite(q[i])):
            ok = False
    return ok


@kernel
def sw_step(h: np.ndarray, q: np.ndarray, b: np.ndarray, a: np.ndarray, g: float, dx: float,
            dt: float, nu: float, R: float, wall: np.ndarray, hn: np.ndarray, qn: np.ndarray,
            fh: np.ndarray, fq: np.ndarray, fqr: np.ndarray, hl: np.ndarray,
            hr: np.ndarray) -> None:
    """One forward-Euler step dt [s] of the film (module docstring) on n periodic cells of width
    dx [m]: h, q the state [m, m^2/s]; b the wall height [m] and a the tangential acceleration
    [m/s^2] per cell; g [m/s^2]; nu [m^2/s]; R [m] (dry scale); wall[i] != 0 makes the interface
    i + 1/2 a radial partition (a reflecting wall: each side sees its own mirror state, no mass
    crosses). Writes hn, qn; fh, fq, fqr, hl, hr are work arrays (n,) for the interface fluxes
    (fq the momentum flux into cell i + 1 side as seen from cell i, fqr as seen from cell i + 1)
    and reconstructed depths (left / right of the interface i + 1/2)."""
    n = h.shape[0]
    dry = DRY_FRACTION * R
    for i in range(n):
        j = i + 1 if i + 1 < n else 0
        ul = q[i] / h[i] if h[i] > dry else 0.0
        ur = q[j] / h[j] if h[j] > dry else 0.0
        if wall[i] != 0:
            # mirror states: (h_i, u_i | h_i, -u_i) and (h_j, -u_j | h_j, u_j)
            _, f1 = hll_flux(h[i], h[i] * ul, h[i], -h[i] * ul, g, dry)
            _, f1r = hll_flux(h[j], -h[j] * ur, h[j], h[j] * ur, g, dry)
            fh[i] = 0.0
            fq[i] = f1
            fqr[i] = f1r
            hl[i] = h[i]
            hr[i] = h[j]
            continue
        bs = max(b[i], b[j])
        hls = max(0.0, h[i] + b[i] - bs)
        hrs = max(0.0, h[j] + b[j] - bs)
        f0, f1 = hll_flux(hls, hls * ul, hrs, hrs * ur, g, dry)
        fh[i] = f0
        fq[i] = f1
        fqr[i] = f1
        hl[i] = hls
        hr[i] = hrs
    for i in range(n):
        k = i - 1 if i > 0 else n - 1
        # F_{i+1/2}^- - F_{i-1/2}^+ with the hydrostatic corrections of Audusse et al. (2004)
        dh = fh[i] - fh[k]
        dq = (fq[i] + 0.5 * g * (h[i] * h[i] - hl[i] * hl[i])) \
            - (fqr[k] + 0.5 * g * (h[i] * h[i] - hr[k] * hr[k]))
        hi = h[i] - dt / dx * dh
        qi = q[i] - dt / dx * dq
        if hi <= dry:
            hn[i] = max(hi, 0.0)
            qn[i] = 0.0
            continue
        qi += dt * hi * a[i]
        kf = friction_rate(hi, qi / hi, nu, R)
        hn[i] = hi
        qn[i] = qi / (1.0 + dt * kf)


@kernel
def sw_max_speed(h: np.ndarray, q: np.ndarray, g: float, R: float) -> float:
    """Largest |v| + sqrt(g h) over the cells [m/s] (the CFL speed)."""
    dry = DRY_FRACTION * R
    s = 0.0
    for i in range(h.shape[0]):
        c = math.sqrt(g * max(h[i], 0.0))
        v = abs(q[i] / h[i]) if h[i] > dry else 0.0
        if v + c > s:
            s = v + c
    return s


@kernel
def wall_height(theta: np.ndarray, cx: float, cy: float, b: np.ndarray) -> None:
    """b = -(cx cos theta + cy sin theta) [m]: the wall's height in the centrifugal potential of a
    chamber displaced by (cx, cy) [m] from the axis (first order in |c|/R)."""
    for i in range(theta.shape[0]):
        b[i] = -(cx * math.cos(theta[i]) + cy * math.sin(theta[i]))


@kernel
def gravity_rotor_frame(gp: float, gdir: float, psi: float) -> complex:
    """In-plane gravity g_p e^{i(gamma - psi)} [m/s^2] in the rotor frame turned by the spin
    angle psi [rad]; gp [m/s^2] at the inertial angle gdir = gamma [rad] (module docstring)."""
    return gp * complex(math.cos(gdir - psi), math.sin(gdir - psi))


@kernel
def gravity_offset(gp: float, gdir: float, psi: float, w: float) -> complex:
    """Rotor-frame shift [m] of the centre of the centrifugal-plus-gravity potential:
    g_p e^{i(gamma - psi)} / w^2 (module docstring), w [rad/s] > 0."""
    return gravity_rotor_frame(gp, gdir, psi) / (w * w)


@kernel
def frame_acceleration(theta: np.ndarray, R: float, w: float, wd: float, cx: float, cy: float,
                       vx: float, vy: float, ax: float, ay: float, a: np.ndarray) -> None:
    """Tangential inertial acceleration of the chamber frame at each wall cell [m/s^2]: the
    Euler term -w' R and -(c'' + 2 i w c' + i w' c) . e_theta of the chamber's motion c(t) in
    the rotor frame (w [rad/s], wd [rad/s^2], c [m], c' [m/s], c'' [m/s^2] as x, y parts);
    e_theta = (-sin theta, cos theta). The centrifugal part is the wall height b."""
    px = ax - 2.0 * w * vy - wd * cy
    py = ay + 2.0 * w * vx + wd * cx
    for i in range(theta.shape[0]):
        s = math.sin(theta[i])
        c = math.cos(theta[i])
        a[i] = -wd * R - (-px * s + py * c)


@kernel
def _emit(out_t, out_h, out_q, kout, t, h, q):
    """Store the film state at every output time out_t[k] <= t from k = kout on; returns the next
    output index."""
    while kout < out_t.shape[0] and out_t[kout] <= t:
        for i in range(h.shape[0]):
            out_h[kout, i] = h[i]
            out_q[kout, i] = q[i]
        kout += 1
    return kout


@kernel
def sw_integrate(h: np.ndarray, q: np.ndarray, theta: np.ndarray, R: float, nu: float,
                 t_end: float, tt: np.ndarray, tw: np.ndarray,
                 tcx: np.ndarray, tcy: np.ndarray, tvx: np.ndarray, tvy: np.ndarray,
                 tax: np.ndarray, tay: np.ndarray, gp: float, gdir: float, wall: np.ndarray,
                 out_t: np.ndarray, out_h: np.ndarray, out_q: np.ndarray, hn: np.ndarray,
                 qn: np.ndarray, fh: np.ndarray, fq: np.ndarray, fqr: np.ndarray,
                 hl: np.ndarray, hr: np.ndarray, b: np.ndarray, a: np.ndarray) -> int:
    """Integrate the film from t = 0 to t_end [s] with the CFL time step, the forcing read from
    the tables tt [s] of spin w [rad/s] (linear; w' [rad/s^2] the slope of each segment,
    rhs.profile_eval) and the chamber's displacement c, c', c'' ([m], [m/s], [m/s^2]; x and y
    parts), linearly interpolated; in-plane gravity gp [m/s^2] at
    the inertial angle gdir [rad], the spin angle psi = 0 at t = 0; partitions at the interfaces
    where wall != 0 (:func:`sw_step`). h, q hold the initial state
    and are overwritten by the final one; out_h, out_q (len(out_t), n) receive the state at the
    sorted output times out_t [s]. Returns the number of steps (-1: a non-finite state)."""
    n = h.shape[0]
    dx = R * 2.0 * math.pi / n
    t = 0.0
    psi = 0.0
    kout = 0
    nout = out_t.shape[0]
    steps = 0
    kout = _emit(out_t, out_h, out_q, kout, t, h, q)
    while t < t_end:
        w, wd = profile_eval(t, profile_segment(t, tt), tt, tw)
        g = w * w * R
        s = sw_max_speed(h, q, g, R)
        dt = t_end - t
        if s > 0.0 and CFL * dx / s < dt:
            dt = CFL * dx / s
        if kout < nout and out_t[kout] - t < dt and out_t[kout] > t:
            dt = out_t[kout] - t
        cx = table_interp(t, tt, tcx)
        cy = table_interp(t, tt, tcy)
        off = gravity_offset(gp, gdir, psi, w) if gp != 0.0 else 0j
        wall_height(theta, cx + off.real, cy + off.imag, b)
        frame_acceleration(theta, R, w, wd, cx, cy, table_interp(t, tt, tvx),
                           table_interp(t, tt, tvy), table_interp(t, tt, tax), table_interp(t, tt, tay), a)
        sw_step(h, q, b, a, g, dx, dt, nu, R, wall, hn, qn, fh, fq, fqr, hl, hr)
        psi += w * dt + 0.5 * wd * dt * dt
        ok = accept_state(h, q, hn, qn)
        steps += 1
        if not ok:
            return -1
        t += dt
        kout = _emit(out_t, out_h, out_q, kout, t + 1e-12 * max(1.0, t), h, q)
    return steps



@kernel
def film_moment(h: np.ndarray, q: np.ndarray, theta: np.ndarray, R: float, H: float,
                rho: float) -> tuple[complex, complex]:
    """The thin film's first moment about the chamber centre U = rho H R^2 sum(eta e^{i theta})
    dtheta [kg*m] and its rate U' = i rho H R sum(q e^{i theta}) dtheta [kg*m/s] (continuity,
    integrated by parts on the periodic wall)."""
    n = h.shape[0]
    dth = 2.0 * math.pi / n
    u = 0j
    ud = 0j
    for i in range(n):
        e = complex(math.cos(theta[i]), math.sin(theta[i]))
        u += h[i] * e
        ud += q[i] * e
    return rho * H * R * R * dth * u, 1j * rho * H * R * dth * ud


@kernel
def _rotor_rate(Z, Y, U, Ud, w_, wd_, Mt, k, c, D, F):
    """Z'' of the rotor-plus-liquid first moment Z = M_t w + U in the rotor frame (module
    docstring of sw_coupled) with the external force F [N] in the rotor frame (gravity on M_t);
    returns (w, w', Y')."""
    w = (Z - U) / Mt
    wd = (Y - Ud) / Mt
    yd = -2j * w_ * Y - 1j * wd_ * Z + w_ * w_ * Z - c * (wd + 1j * w_ * w) - k * w \
        + D * complex(w_ * w_, -wd_) + F
    return w, wd, yd


@kernel
def _gravity_force(Mt, gp, gdir, psi):
    """Gravity on M_t in the rotor frame, M_t g_p e^{i(gamma - psi)} [N]."""
    return Mt * gravity_rotor_frame(gp, gdir, psi)


@kernel
def films_moment(h: np.ndarray, q: np.ndarray, theta: np.ndarray, starts: np.ndarray,
                 Rs: np.ndarray, Hs: np.ndarray, rhos: np.ndarray) -> tuple[complex, complex]:
    """:func:`film_moment` summed over the films of concentric chambers stored one after the
    other: film f holds the cells starts[f] to starts[f + 1] - 1 and has the wall radius Rs[f]
    [m], height Hs[f] [m] and density rhos[f] [kg/m^3]. Returns (U [kg*m], U' [kg*m/s])."""
    u = 0j
    ud = 0j
    for f in range(starts.shape[0] - 1):
        o0 = starts[f]
        o1 = starts[f + 1]
        uf, udf = film_moment(h[o0:o1], q[o0:o1], theta[o0:o1], Rs[f], Hs[f], rhos[f])
        u += uf
        ud += udf
    return u, ud


@kernel
def films_spin(h: np.ndarray, q: np.ndarray, starts: np.ndarray, Rs: np.ndarray,
               Hs: np.ndarray, rhos: np.ndarray) -> tuple[float, float]:
    """The thin films' (:func:`films_moment`'s layout) second moment about the chamber centre
    I_c = sum rho H R^3 sum(eta) dtheta [kg*m^2] (the liquid at R) and their angular momentum
    relative to the wall H_rel = sum rho H R^2 sum(q) dtheta [kg*m^2/s] (q = eta v, v relative
    to the wall): the liquid's terms in the spin equation (docs/liquid/balls-beside-liquid.md
    sec. 3i)."""
    ic = 0.0
    hr = 0.0
    for f in range(starts.shape[0] - 1):
        o0 = starts[f]
        o1 = starts[f + 1]
        sh = 0.0
        sq = 0.0
        for i in range(o0, o1):
            sh += h[i]
            sq += q[i]
        c = rhos[f] * Hs[f] * Rs[f] * Rs[f] * 2.0 * math.pi / (o1 - o0)
        ic += c * Rs[f] * sh
        hr += c * sq
    return ic, hr


@kernel
def films_dt(h: np.ndarray, q: np.ndarray, starts: np.ndarray, Rs: np.ndarray, W: float,
             dt: float) -> float:
    """The CFL step [s] of the most restrictive of the films stored one after the other
    (:func:`films_moment`'s layout; wall radii Rs [m]) at the spin W [rad/s], at most dt [s]."""
    for f in range(starts.shape[0] - 1):
        o0 = starts[f]
        o1 = starts[f + 1]
        s = sw_max_speed(h[o0:o1], q[o0:o1], W * W * Rs[f], Rs[f])
        dx = Rs[f] * 2.0 * math.pi / (o1 - o0)
        if s > 0.0 and CFL * dx / s < dt:
            dt = CFL * dx / s
    return dt


@kernel
def films_step(h: np.ndarray, q: np.ndarray, theta: np.ndarray, starts: np.ndarray,
               Rs: np.ndarray, nus: np.ndarray, wall: np.ndarray, W: float, Wd: float,
               w: complex, off: complex, wd: complex, wdd: complex, dt: float, hn: np.ndarray,
               qn: np.ndarray, fh: np.ndarray, fq: np.ndarray, fqr: np.ndarray, hl: np.ndarray,
               hr: np.ndarray, b: np.ndarray, a: np.ndarray) -> None:
    """One step dt [s] of every film (:func:`films_moment`'s layout; radii Rs [m], viscosities
    nus [m^2/s], partitions where wall != 0) into hn, qn: :func:`sw_step` on the wall height of
    the chamber displaced by w + off [m] (off: gravity's offset of the potential,
    :func:`gravity_offset`) and the frame accelerations of its rate wd [m/s] and acceleration
    wdd [m/s^2] (rotor frame) at the spin W [rad/s], W' [rad/s^2]; fh..a work arrays."""
    for f in range(starts.shape[0] - 1):
        o0 = starts[f]
        o1 = starts[f + 1]
        R = Rs[f]
        wall_height(theta[o0:o1], w.real + off.real, w.imag + off.imag, b[o0:o1])
        frame_acceleration(theta[o0:o1], R, W, Wd, w.real, w.imag, wd.real, wd.imag,
                           wdd.real, wdd.imag, a[o0:o1])
        sw_step(h[o0:o1], q[o0:o1], b[o0:o1], a[o0:o1], W * W * R,
                R * 2.0 * math.pi / (o1 - o0), dt, nus[f], R, wall[o0:o1], hn[o0:o1],
                qn[o0:o1], fh[o0:o1], fq[o0:o1], fqr[o0:o1], hl[o0:o1], hr[o0:o1])


@kernel
def sw_coupled(h: np.ndarray, q: np.ndarray, theta: np.ndarray, starts: np.ndarray,
               Rs: np.ndarray, Hs: np.ndarray, rhos: np.ndarray, nus: np.ndarray, Mt: float,
               k: float, c: float, D: float, Z0: complex, Y0: complex, t_end: float,
               tt: np.ndarray, tw: np.ndarray, gp: float, gdir: float,
               wall: np.ndarray, out_t: np.ndarray, out_h: np.ndarray, out_q: np.ndarray,
               out_w: np.ndarray, hn: np.ndarray, qn: np.ndarray, fh: np.ndarray, fq: np.ndarray,
               fqr: np.ndarray, hl: np.ndarray, hr: np.ndarray, b: np.ndarray,
               a: np.ndarray, wdd0: complex) -> tuple[int, complex, complex, complex]:
    """The films of one or more concentric chambers coupled two-way with an isotropic Jeffcott
    rotor (mass M_t = M + the liquids' masses, stiffness k [N/m], damping c [N*s/m], unbalance
    D [kg*m] on the rotor frame's x axis) at the prescribed spin w(t) (table tt [s], tw
    [rad/s], linear; w' the slope of each segment, rhs.profile_eval). Film f holds the cells
    starts[f] to starts[f + 1] - 1 of h, q, theta and wall (and of the work arrays), with its
    wall radius Rs[f] [m], height Hs[f] [m], density rhos[f] [kg/m^3] and viscosity nus[f]
    [m^2/s]; every chamber is on the same rotor, so every film sees the same deflection.

    The rotor's balance in the rotor frame, with the liquid's pull written through the total
    first moment Z = M_t w + U (w the chamber's deflection [m], U the films' summed moment
    [kg*m]): Z'' + 2 i W Z' + i W' Z - W^2 Z + c (w' + i W w) + k w = D (W^2 - i W') + M_t g_p
    e^{i(gamma - psi)}, so the films' acceleration never needs differentiating; in-plane
    gravity gp [m/s^2] at the inertial angle gdir [rad] (0: a vertical axis), psi = 0 at t = 0;
    partitions where wall != 0 (:func:`sw_step`). Each time step (CFL of the most restrictive
    film) advances the rotor by 4 RK4 sub-steps with U, U' frozen (explicit coupling), and every
    film by one step forced by the deflection and by w'' from the previous step (wdd0 [m/s^2]
    before the first). h, q, and the returned (Z, Y, w'') are the final state; out_h, out_q
    (len(out_t), total cells) the films at out_t and out_w the deflection. Returns (steps, Z, Y,
    w''); steps = -1 on a non-finite state."""
    t = 0.0
    Z = Z0
    Y = Y0
    kout = 0
    nout = out_t.shape[0]
    steps = 0
    wdd = wdd0
    psi = 0.0
    U, Ud = films_moment(h, q, theta, starts, Rs, Hs, rhos)
    wd_prev = (Y - Ud) / Mt
    while t < t_end:
        W, Wd = profile_eval(t, profile_segment(t, tt), tt, tw)
        U, Ud = films_moment(h, q, theta, starts, Rs, Hs, rhos)
        w = (Z - U) / Mt
        wd = (Y - Ud) / Mt
        k0 = kout
        kout = _emit(out_t, out_h, out_q, kout, t, h, q)
        for j in range(k0, kout):
            out_w[j] = w
        dt = films_dt(h, q, starts, Rs, W, t_end - t)
        if kout < nout and out_t[kout] - t < dt:
            dt = out_t[kout] - t
        # film steps, forced by the chamber's deflection and motion at t
        off = gravity_offset(gp, gdir, psi, W) if gp != 0.0 else 0j
        films_step(h, q, theta, starts, Rs, nus, wall, W, Wd, w, off, wd, wdd, dt, hn, qn, fh, fq,
                   fqr, hl, hr, b, a)
        # rotor: 4 RK4 sub-steps with the films' moment frozen
        hs = dt / 4.0
        for j in range(4):
            t0 = j * hs          # the spin angle within the step: psi + W tau + W' tau^2 / 2
            F0 = _gravity_force(Mt, gp, gdir, psi + W * t0 + 0.5 * Wd * t0 * t0)
            th = t0 + 0.5 * hs
            Fh = _gravity_force(Mt, gp, gdir, psi + W * th + 0.5 * Wd * th * th)
            t1 = t0 + hs
            F1 = _gravity_force(Mt, gp, gdir, psi + W * t1 + 0.5 * Wd * t1 * t1)
            _, _, k1 = _rotor_rate(Z, Y, U, Ud, W, Wd, Mt, k, c, D, F0)
            _, _, k2 = _rotor_rate(Z + 0.5 * hs * Y, Y + 0.5 * hs * k1, U, Ud, W, Wd, Mt, k, c, D,
                                   Fh)
            _, _, k3 = _rotor_rate(Z + 0.5 * hs * (Y + 0.5 * hs * k1), Y + 0.5 * hs * k2, U, Ud,
                                   W, Wd, Mt, k, c, D, Fh)
            _, _, k4 = _rotor_rate(Z + hs * (Y + 0.5 * hs * k2), Y + hs * k3, U, Ud, W, Wd, Mt,
                                   k, c, D, F1)
            Z = Z + hs * (Y + hs / 6.0 * (k1 + k2 + k3))
            Y = Y + hs / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
        psi += W * dt + 0.5 * Wd * dt * dt
        ok = accept_state(h, q, hn, qn) and math.isfinite(Z.real) and math.isfinite(Z.imag)
        steps += 1
        if not ok:
            return -1, Z, Y, wdd
        U, Ud = films_moment(h, q, theta, starts, Rs, Hs, rhos)
        wd_new = (Y - Ud) / Mt
        wdd = (wd_new - wd_prev) / dt
        wd_prev = wd_new
        t += dt
    U, Ud = films_moment(h, q, theta, starts, Rs, Hs, rhos)
    k0 = kout
    kout = _emit(out_t, out_h, out_q, kout, math.inf, h, q)
    for j in range(k0, kout):
        out_w[j] = (Z - U) / Mt
    return steps, Z, Y, wdd
