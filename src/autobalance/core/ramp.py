"""Stuck-ball phases without stepping: linear speed ramps (R1-R4) and holds that end in a
breakaway (R5), on the isotropic rotor of core/hold.py.

With every ball stuck, an isotropic linear suspension (k, c), no gravity, base motion or dry
friction, a constant unbalance and a prescribed spin Omega(t) = W + a tau (a piecewise-linear
profile), the u, v rows of the equations of motion (004 eq 8-9 with alpha' = alpha'' = 0) are,
with w = u + i v in the rotor frame and psi' = Omega,

    M_t w'' + B(t) w' + D(t) w = F(t),                                                     (R1)
    B = c + 2 i Omega M_t,  D = k - M_t Omega^2 + i c Omega + i M_t a,  F = Ut (Omega^2 - i a),

with Ut as in core/hold.py (H1). It is (H1) with the Euler term i M_t a w and the tangential
unbalance force -i a Ut added; it follows from Newton's law for the centre of mass,
d^2/dt^2 (M_t z + Ut e^{i psi}) = -k z - c z' with z = w e^{i psi} the inertial displacement.
For a = 0 it is (H1), whose closed form core/hold.py uses.

Particular solution (R2). The slowly varying solution is the asymptotic series
w_p = g_0 + g_1 + ... + g_J with

    D g_0 = F,    D g_{j+1} = -(B g_j' + M_t g_j''),                                         (R2)

the quasi-static response and its corrections in powers of the ramp rate (the method of
multiple scales for a slowly varying linear oscillator; Bender & Orszag, *Advanced Mathematical
Methods for Scientists and Engineers*, 1978, ch. 10-11). D, B and F are polynomials of degree
<= 2 in tau, so each g_j is computed as a truncated Taylor series at the evaluation time by
series division (`ramp_series`). The truncated sum solves (R1) up to the residual
r = M_t g_J'' + B g_J' (computable). A ramp keeps the fewest terms whose residual passes (R3)
with RAMP_TERMS_MARGIN to spare at its start (`_terms`), all RAMP_TERMS + 1 for a chunk that
then fails.

Transient (R3). In the inertial frame the error e = z - z_p of any solution obeys the
*constant-coefficient* equation M_t e'' + c e' + k e = -r e^{i psi}: the homogeneous part is
C1 e^{s1 tau} + C2 e^{s2 tau} with s1, s2 the roots of M_t s^2 + c s + k (core/hold.py with
W = 0), fitted to the state at the start of the ramp, and the part forced by the residual is
bounded by |e| <= ||h||_1 max|r|, ||h||_1 <= (1/sigma1 + 1/sigma2) / (M_t |s1 - s2|) with
sigma_j = -Re s_j (the impulse response h = (e^{s1 t} - e^{s2 t}) / (M_t (s1 - s2))). A jump is
taken only where that bound is below 1e-3 of the local error tolerance.

Stick test (R4). The friction a stuck ball needs is affine in the rotor's inertial acceleration
(004 eq 10): lambda_i = lambda_i,p + m_i R Im(e^{-i alpha_i} e^{-i psi} z_tr''), where lambda_i,p
is the kernel's own constrained solve (core/rhs.py) on the particular state, and
|z_tr''| <= sum_j |s_j^2 C_j| e^{-sigma_j tau} decreases. lambda_i,p and the limit mu_s N_i R are
smooth on the time scale of the ramp: they are sampled at both ends and the middle of each
chunk, and a chunk is accepted when the parabola through the three margins, less four times its
curvature term and the transient bound, stays positive. Chunks grow while the curvature is small
against the margin and shrink as a breakaway approaches; below 20 integrator steps the jump stops
and the integrator takes over (it locates the breakaway, core/integrate.py).

Holds that end in a breakaway (R5). Where the bound (H2) of core/hold.py fails, the hold's
closed form still holds until the first breakaway. `hold_breakaway` finds it: with the balls'
angles and the speed fixed, the kernel's constrained solve is linear in the rotor state, so
lambda_i and the limit mu_s N_i R are affine in (w - w_ss, w'); five right-hand-side
evaluations give the maps. The margins mu_s N_i R (1 + STICK_TOL) - |lambda_i| of the closed
form are sampled 16 times per period of the transient's fastest rotor-frame frequency and the
crossing located by the Illinois method to 1e-9 of a sample interval (the integrator's event
location on its Hermite interpolant: 1e-7 in step fraction, on 1.5 ms steps against 0.3 ms
samples here). The scan stops early where (H2) with the transient decayed to
tau, |lambda_ss| + m_i R sum_j |P_j| e^{Re(s_j) tau} <= mu_s N_i R, proves the rest of the hold
stuck. This is the stick-slip ratchet of 004's plateau (a ball sticks and slips at the rotor's
backward whirl frequency): its stuck spells are jumped, its slips stepped.
"""
from __future__ import annotations

import cmath
import math

import numpy as np

from .hold import (ball_unbalance, hold_coeffs, hold_roots, hold_state, peak_samples,
                   record_amplitude, vertex)
from .jit import inline_kernel, kernel
from .layout import B_M, NR, P_BETA, P_CX, P_KX, P_MT, P_R, P_RHO, S_AMAX
from .rhs import profile_eval, rhs

#: correction terms g_1..g_J of the series (R2); the work array holds (J + 1, 2 J + 3) complex
RAMP_TERMS = 10
RAMP_TAYLOR = 2 * RAMP_TERMS + 3
#: the residual's error bound (R3) must stay below this fraction of the local error tolerance
RAMP_ERR_FRACTION = 1e-3
#: a ramp keeps the fewest terms g_0..g_J whose residual at its start is within this fraction
#: of the bound (R3) asks (:func:`_terms`); a chunk that fails (R3) with them takes all
RAMP_TERMS_MARGIN = 1e-3
#: first and largest chunk of the stick test (R4) [s]
RAMP_CHUNK0 = 0.02
RAMP_CHUNK_MAX = 0.5


@inline_kernel
def _residual(ser: np.ndarray, J: int, mt: float, b0: complex) -> complex:
    """Residual r_J = M_t g_J'' + B g_J' [N] of the series truncated after g_J (R2), at the
    evaluation time (tau = 0 of the Taylor coefficients ``ser``); mt = M_t [kg], b0 = B(0) =
    c + 2 i W M_t [kg/s]."""
    return 2.0 * mt * ser[J, 2] + b0 * ser[J, 1]


@kernel
def ramp_series(P: np.ndarray, ut: complex, W: float, a: float,
                ser: np.ndarray) -> tuple[complex, complex, complex]:
    """Particular solution (R2) at speed W [rad/s] and ramp rate a [rad/s^2].

    Returns w_p [m], w_p' [m/s] and the residual r [N] of the truncated series; ``ser`` is the
    complex work array of the Taylor coefficients of each g_j: its shape (J + 1, 2 J + 3) sets
    the terms g_0..g_J kept (at most (RAMP_TERMS + 1, RAMP_TAYLOR); a leading block of the work
    array, :func:`_terms`). Each coefficient depends only on those before it, so a shorter
    series' terms are bit for bit the longer one's.
    """
    mt = P[P_MT]
    k = P[P_KX]
    c = P[P_CX]
    d0 = complex(k - mt * W * W, c * W + mt * a)
    inv = 1.0 / d0
    d1 = complex(-2.0 * mt * W * a, c * a)
    d2 = -mt * a * a
    b0 = complex(c, 2.0 * mt * W)
    b1 = complex(0.0, 2.0 * mt * a)
    nj = ser.shape[0]
    nk = ser.shape[1]
    for m in range(nk):
        if m == 0:
            acc = ut * complex(W * W, -a)
        elif m == 1:
            acc = ut * (2.0 * W * a)
        elif m == 2:
            acc = ut * (a * a)
        else:
            acc = 0j
        if m >= 1:
            acc -= d1 * ser[0, m - 1]
        if m >= 2:
            acc -= d2 * ser[0, m - 2]
        ser[0, m] = acc * inv
    for j in range(1, nj):
        for m in range(nk - 2 * j):
            hm = b0 * (m + 1) * ser[j - 1, m + 1] + mt * (m + 2) * (m + 1) * ser[j - 1, m + 2]
            if m >= 1:
                hm += b1 * m * ser[j - 1, m]
            acc = -hm
            if m >= 1:
                acc -= d1 * ser[j, m - 1]
            if m >= 2:
                acc -= d2 * ser[j, m - 2]
            ser[j, m] = acc * inv
    w = 0j
    wd = 0j
    for j in range(nj):
        w += ser[j, 0]
        wd += ser[j, 1]
    r = _residual(ser, nj - 1, mt, b0)
    return w, wd, r


@kernel
def _state(tau: float, psi0: float, W0: float, a: float, P: np.ndarray, ut: complex,
           s1: complex, s2: complex, c1: complex, c2: complex,
           ser: np.ndarray) -> tuple[complex, complex, complex, complex, complex]:
    """At tau [s] into the ramp: full w, w' and particular w_p, w_p' [m, m/s], residual r [N]."""
    W = W0 + a * tau
    psi = psi0 + W0 * tau + 0.5 * a * tau * tau
    wp, wpd, r = ramp_series(P, ut, W, a, ser)
    z, zd = hold_state(tau, 0j, s1, s2, c1, c2)
    rot = cmath.exp(complex(0.0, -psi))
    return wp + z * rot, wpd + (zd - 1j * W * z) * rot, wp, wpd, r


@kernel
def _margins(t: float, W: float, psi: float, wp: complex, wpd: complex, y: np.ndarray,
             P: np.ndarray, B: np.ndarray, N: int, seg: int, sched: tuple, md: tuple,
             ytmp: np.ndarray, ftmp: np.ndarray, rw: tuple, qc: np.ndarray) -> None:
    """qc[i] = mu_s N_i R (1 - 1e-9) - |lambda_i,p| [N*m] on the particular state (R4)."""
    lam = rw[0]
    nq = N + NR + 1
    n = 2 * nq
    for j in range(n):
        ytmp[j] = y[j]
    ytmp[0] = wp.real
    ytmp[1] = wp.imag
    ytmp[nq] = wpd.real
    ytmp[nq + 1] = wpd.imag
    ytmp[nq - 1] = psi
    ytmp[n - 1] = W
    rhs(t, ytmp, P, B, N, seg, sched, md, ftmp, rw)
    for i in range(N):
        qc[i] = lam[N + i] * (1.0 - 1e-9) - abs(lam[i])


@kernel
def _err_ok(r: complex, wp: complex, wpd: complex, L0: float, L1: float, W: float,
            atol: np.ndarray, rtol: float, nq: int) -> bool:
    """(R3): the residual's effect on w and w' within RAMP_ERR_FRACTION of the tolerance."""
    ar = abs(r)
    okp = L0 * ar <= RAMP_ERR_FRACTION * (atol[0] + rtol * abs(wp))
    okv = (L1 + W * L0) * ar <= RAMP_ERR_FRACTION * (atol[nq] + rtol * abs(wpd))
    return okp and okv


@kernel
def _terms(ser: np.ndarray, P: np.ndarray, W: float, wp: complex, wpd: complex, L0: float,
           L1: float, atol: np.ndarray, rtol: float, nq: int) -> int:
    """The number J + 1 of terms to keep, ``ser[:J + 1, :2 J + 3]`` (``ser``: all RAMP_TERMS + 1
    terms computed at speed W [rad/s]): the fewest terms g_0..g_J whose residual
    r_J = M_t g_J'' + B g_J' passes (R3) with RAMP_TERMS_MARGIN to spare. Away from resonance
    the terms fall by 1e-3-1e-4 each (J = 3-5 of 10), and the series' cost goes with the
    square of the terms kept."""
    mt = P[P_MT]
    b0 = complex(P[P_CX], 2.0 * mt * W)
    nj = ser.shape[0]
    for J in range(1, ser.shape[0]):
        r = _residual(ser, J, mt, b0)
        if _err_ok(r / RAMP_TERMS_MARGIN, wp, wpd, L0, L1, W, atol, rtol, nq):
            nj = J + 1
            break
    return nj


@kernel
def _peak_abs(t0: float, span: float, n: int, psi0: float, W0: float, a: float, P: np.ndarray,
              ut: complex, s1: complex, s2: complex, c1: complex, c2: complex,
              ser: np.ndarray) -> tuple[float, float]:
    """max |w| [m] over tau in [t0, t0 + span] [s] of a ramp, and its tau [s]: n + 1 samples,
    then successive parabolic interpolation about the largest one (the spacing divided by 4
    five times)."""
    dt = span / n
    kb = 0
    ab = abs(_state(t0, psi0, W0, a, P, ut, s1, s2, c1, c2, ser)[0])
    for k in range(1, n + 1):
        a1 = abs(_state(t0 + k * dt, psi0, W0, a, P, ut, s1, s2, c1, c2, ser)[0])
        if a1 > ab:
            ab = a1
            kb = k
    tb = t0 + kb * dt
    lo = t0
    hi = t0 + span
    for _ in range(5):
        fl = abs(_state(max(lo, tb - dt), psi0, W0, a, P, ut, s1, s2, c1, c2, ser)[0])
        fr = abs(_state(min(hi, tb + dt), psi0, W0, a, P, ut, s1, s2, c1, c2, ser)[0])
        x = vertex(fl, ab, fr)
        tv = min(hi, max(lo, tb + x * dt))
        av = abs(_state(tv, psi0, W0, a, P, ut, s1, s2, c1, c2, ser)[0])
        if av > ab:
            ab = av
            tb = tv
        dt *= 0.25
    return ab, tb


@kernel
def _ramp_peak(t: float, tau_end: float, psi0: float, W0: float, a: float, P: np.ndarray,
               ut: complex, s1: complex, s2: complex, c1: complex, c2: complex, ser: np.ndarray,
               stats: np.ndarray) -> None:
    """Largest |w| [m] over the transient's life in a ramp starting at t [s], as
    core/hold.py's hold_peak: skipped when max |w_p| + |C1| + |C2| cannot
    beat the run's maximum (|w_p| at 64 points, refined at the vertex,
    +0.1 %); else sampled 16 times per period of the fastest rotor-frame
    frequency of the transient and refined about the largest. The chunks' own samples and
    peaks cover the rest of the ramp."""
    cmag = abs(c1) + abs(c2)
    if cmag == 0.0:
        return
    life = min(tau_end, 16.0 / min(-s1.real, -s2.real))
    up = _peak_abs(0.0, life, np.int64(64), psi0, W0, a, P, ut, s1, s2, 0j, 0j, ser)[0]
    if up * 1.001 + cmag <= stats[S_AMAX]:
        return
    f_max = max(abs(s1.imag - W0), max(abs(s2.imag - W0), abs(s1.imag - s2.imag))) + abs(a) * life
    n, _ = peak_samples(f_max, life)
    ab, tb = _peak_abs(0.0, life, n, psi0, W0, a, P, ut, s1, s2, c1, c2, ser)
    record_amplitude(ab, t + tb, stats)


@kernel
def _chunk_peak(t: float, tau: float, dt: float, aa: float, am: float, ab: float, psi0: float,
                W0: float, a: float, P: np.ndarray, ut: complex, s1: complex, s2: complex,
                c1: complex, c2: complex, ser: np.ndarray, stats: np.ndarray) -> float:
    """Amplitude monitor of the chunk [tau, tau + dt] [s] of a ramp starting at t [s]: |w| [m]
    at its start, middle and end (aa, am, ab), and an interior peak refined by successive
    parabolic interpolation; returns ab."""
    record_amplitude(am, t + tau + 0.5 * dt, stats)
    record_amplitude(ab, t + tau + dt, stats)
    if vertex(aa, am, ab) != 0.0:
        ap, tp = _peak_abs(tau, dt, np.int64(2), psi0, W0, a, P, ut, s1, s2, c1, c2, ser)
        record_amplitude(ap, t + tp, stats)
    return ab


@kernel
def _outputs(t: float, t_to: float, kout: int, out_t: np.ndarray, out_y: np.ndarray,
             y: np.ndarray, N: int, psi0: float, W0: float, a: float, P: np.ndarray, ut: complex,
             s1: complex, s2: complex, c1: complex, c2: complex, ser: np.ndarray) -> int:
    """Outputs at out_t in (.., t_to] [s] of a ramp starting at t [s] from the closed form (the
    balls' angles and rates as in y); returns the next output index."""
    nq = N + NR + 1
    n = 2 * nq
    while kout < out_t.shape[0] and out_t[kout] <= t_to:
        tk = out_t[kout] - t
        wk, wdk, _, _, _ = _state(tk, psi0, W0, a, P, ut, s1, s2, c1, c2, ser)
        for j in range(n):
            out_y[kout, j] = y[j]
        out_y[kout, 0] = wk.real
        out_y[kout, 1] = wk.imag
        out_y[kout, nq] = wdk.real
        out_y[kout, nq + 1] = wdk.imag
        out_y[kout, nq - 1] = psi0 + W0 * tk + 0.5 * a * tk * tk
        out_y[kout, n - 1] = W0 + a * tk
        kout += 1
    return kout


@kernel
def ramp_jump(t: float, t_seg: float, h: float, y: np.ndarray, P: np.ndarray, B: np.ndarray,
              N: int, seg: int, sched: tuple, md: tuple,
              atol: np.ndarray, rtol: float, out_t: np.ndarray, out_y: np.ndarray, kout: int,
              stats: np.ndarray, ser: np.ndarray, q: np.ndarray, ytmp: np.ndarray,
              ftmp: np.ndarray, rw: tuple) -> tuple[float, int, int]:
    """Advance a stuck-ball ramp from t towards t_seg [s] without stepping (R1-R4).

    On return y holds the state at the new time; outputs in (t, new time] are written to out_y
    and the amplitude statistics updated. Returns (new time [s], next output index, number of
    right-hand-side evaluations); new time == t when the jump is refused at its start. ``q`` is
    a (>= 3, N) float work array; h [s] is the integrator's current step.
    """
    prof_t, prof_w, unb_t, unb_u = sched
    nq = N + NR + 1
    n = 2 * nq
    ip = nq - 1
    W0, a = profile_eval(t, seg, prof_t, prof_w)
    ut = ball_unbalance(y, B, N, P[P_R], P[P_RHO], P[P_BETA], unb_u[0])
    s1, s2, _ = hold_roots(P, 0.0)
    sg1 = -s1.real
    sg2 = -s2.real
    ds = abs(s1 - s2)
    if sg1 <= 0.0 or sg2 <= 0.0 or ds <= 1e-9 * (abs(s1) + abs(s2)):
        return t, kout, 0
    L0 = (1.0 / sg1 + 1.0 / sg2) / (P[P_MT] * ds)
    L1 = (abs(s1) / sg1 + abs(s2) / sg2) / (P[P_MT] * ds)
    psi0 = y[ip]
    wp, wpd, r = ramp_series(P, ut, W0, a, ser)
    nrhs = 0
    if not _err_ok(r, wp, wpd, L0, L1, W0, atol, rtol, nq):
        return t, kout, nrhs
    nj = _terms(ser, P, W0, wp, wpd, L0, L1, atol, rtol, nq)
    sj = ser[:nj, :2 * nj + 1]
    if sj.shape[0] < ser.shape[0]:      # the transient is fitted to the series that is used
        wp, wpd, r = ramp_series(P, ut, W0, a, sj)
    rot0 = cmath.exp(complex(0.0, psi0))
    dw = complex(y[0], y[1]) - wp
    dwd = complex(y[nq], y[nq + 1]) - wpd
    c1, c2 = hold_coeffs(dw * rot0, (dwd + 1j * W0 * dw) * rot0, 0j, s1, s2)
    p1 = abs(s1 * s1 * c1)
    p2 = abs(s2 * s2 * c2)
    _margins(t, W0, psi0, wp, wpd, y, P, B, N, seg, sched, md, ytmp, ftmp, rw, q[0])
    nrhs += 1
    for i in range(N):
        if q[0, i] - B[i, B_M] * P[P_R] * (p1 + p2) <= 0.0:
            return t, kout, nrhs
    span = t_seg - t
    dmin = 20.0 * h
    dt = min(RAMP_CHUNK0, span)
    tau = 0.0
    aa = abs(complex(y[0], y[1]))
    while tau < span * (1.0 - 1e-12):
        dt = min(dt, span - tau)
        if span - tau - dt < 1e-9 * span:
            dt = span - tau
        tm = tau + 0.5 * dt
        tb = tau + dt
        wm, _, wpm, wpdm, rm = _state(tm, psi0, W0, a, P, ut, s1, s2, c1, c2, sj)
        _margins(t + tm, W0 + a * tm, psi0 + W0 * tm + 0.5 * a * tm * tm, wpm, wpdm, y, P, B, N,
                 seg, sched, md, ytmp, ftmp, rw, q[1])
        wb, _, wpb, wpdb, rb = _state(tb, psi0, W0, a, P, ut, s1, s2, c1, c2, sj)
        _margins(t + tb, W0 + a * tb, psi0 + W0 * tb + 0.5 * a * tb * tb, wpb, wpdb, y, P, B, N,
                 seg, sched, md, ytmp, ftmp, rw, q[2])
        nrhs += 2
        ok = (_err_ok(rm, wpm, wpdm, L0, L1, W0 + a * tm, atol, rtol, nq)
              and _err_ok(rb, wpb, wpdb, L0, L1, W0 + a * tb, atol, rtol, nq))
        if not ok and sj.shape[0] < ser.shape[0]:
            sj = ser[:ser.shape[0], :ser.shape[1]]     # every term from here on, same chunk
            continue
        tr = p1 * math.exp(-sg1 * tau) + p2 * math.exp(-sg2 * tau)
        ratio = 0.0
        for i in range(N):
            kap = abs(q[1, i] - 0.5 * (q[0, i] + q[2, i]))
            low = min(q[0, i], min(q[1, i], q[2, i])) - B[i, B_M] * P[P_R] * tr
            if low - 4.0 * kap <= 0.0:
                ok = False
            elif low > 0.0:
                ratio = max(ratio, kap / low)
        if not ok:
            if dt * 0.25 >= dmin:
                dt *= 0.25
                continue
            break
        aa = _chunk_peak(t, tau, dt, aa, abs(wm), abs(wb), psi0, W0, a, P, ut, s1, s2, c1, c2,
                         sj, stats)
        kout = _outputs(t, t + tb, kout, out_t, out_y, y, N, psi0, W0, a, P, ut, s1, s2, c1, c2,
                        sj)
        tau = tb
        for i in range(N):
            q[0, i] = q[2, i]
        if ratio < 0.01:
            dt = min(2.0 * dt, RAMP_CHUNK_MAX)
        elif ratio > 0.1:
            dt = max(0.5 * dt, dmin)
    if tau <= 0.0:
        return t, kout, nrhs
    _ramp_peak(t, tau, psi0, W0, a, P, ut, s1, s2, c1, c2, sj, stats)
    w, wd, _, _, _ = _state(tau, psi0, W0, a, P, ut, s1, s2, c1, c2, sj)
    y[0] = w.real
    y[1] = w.imag
    y[nq] = wd.real
    y[nq + 1] = wd.imag
    y[ip] = psi0 + W0 * tau + 0.5 * a * tau * tau
    y[n - 1] = W0 + a * tau
    if tau >= span * (1.0 - 1e-12):
        return t_seg, kout, nrhs
    return t + tau, kout, nrhs


@kernel
def _hold_affine(t: float, W: float, wss: complex, y: np.ndarray, P: np.ndarray, B: np.ndarray,
                 N: int, seg: int, sched: tuple, md: tuple, q: np.ndarray, ytmp: np.ndarray,
                 ftmp: np.ndarray, rw: tuple) -> None:
    """The friction each stuck ball needs and its static limit [N*m] as affine functions of
    (w - w_ss, w') during a hold (R5): with the balls' angles and the speed fixed, the kernel's
    constrained solve is linear in the rotor state. Rows 0-4 of q: lambda_i at the steady
    state and its derivatives along Re w, Im w, Re w', Im w'; rows 5-9: the same for the
    limit. Five right-hand-side evaluations."""
    lam = rw[0]
    nq = N + NR + 1
    dw = max(abs(wss), 1e-12)
    dv = dw * max(W, 1.0)
    for k in range(5):
        for j in range(2 * nq):
            ytmp[j] = y[j]
        ytmp[0] = wss.real + (dw if k == 1 else 0.0)
        ytmp[1] = wss.imag + (dw if k == 2 else 0.0)
        ytmp[nq] = dv if k == 3 else 0.0
        ytmp[nq + 1] = dv if k == 4 else 0.0
        rhs(t, ytmp, P, B, N, seg, sched, md, ftmp, rw)
        for i in range(N):
            if k == 0:
                q[0, i] = lam[i]
                q[5, i] = lam[N + i]
            else:
                d = dw if k <= 2 else dv
                q[k, i] = (lam[i] - q[0, i]) / d
                q[5 + k, i] = (lam[N + i] - q[5, i]) / d


@kernel
def _hold_margin(tau: float, s1: complex, s2: complex, c1: complex, c2: complex, N: int,
                 q: np.ndarray, stick_tol: float, ball: int) -> tuple[float, int]:
    """Smallest margin mu_s N_i R (1 + stick_tol) - |lambda_i| [N*m] at tau [s] into a hold
    (of ball ``ball`` only if >= 0) and the ball that has it, from the affine maps of
    _hold_affine (R5)."""
    d, dv = hold_state(tau, 0j, s1, s2, c1, c2)
    gmin = math.inf
    imin = -1
    for i in range(N):
        if ball >= 0 and i != ball:
            continue
        lm = q[0, i] + q[1, i] * d.real + q[2, i] * d.imag + q[3, i] * dv.real + q[4, i] * dv.imag
        li = q[5, i] + q[6, i] * d.real + q[7, i] * d.imag + q[8, i] * dv.real + q[9, i] * dv.imag
        g = li * (1.0 + stick_tol) - abs(lm)
        if g < gmin:
            gmin = g
            imin = i
    return gmin, imin


@kernel
def hold_breakaway(t: float, tau_max: float, W: float, wss: complex, s1: complex, s2: complex,
                   c1: complex, c2: complex, y: np.ndarray, P: np.ndarray, B: np.ndarray, N: int,
                   seg: int, sched: tuple, md: tuple,
                   q: np.ndarray, ytmp: np.ndarray, ftmp: np.ndarray, rw: tuple,
                   stick_tol: float) -> tuple[float, int, int]:
    """First breakaway of a hold at speed W [rad/s] starting at t [s], within tau_max [s] (R5).

    ``q`` is a (10, N) float work array. Returns (tau [s], ball, right-hand-side evaluations):
    ball >= 0 breaks away at tau; -1: none within tau_max; -2: the scan ended at tau without a
    breakaway (sample budget).
    """
    _hold_affine(t, W, wss, y, P, B, N, seg, sched, md, q, ytmp, ftmp, rw)
    f_max = max(abs(s1.imag), abs(s2.imag))
    dtau = 2.0 * math.pi / (16.0 * max(f_max, 1e-300))
    if dtau > tau_max:
        dtau = tau_max
    P1 = abs((s1 * s1 + 2j * W * s1 - W * W) * c1)
    P2 = abs((s2 * s2 + 2j * W * s2 - W * W) * c2)
    tau = 0.0
    for _ in range(65536):
        # (H2) from here on: the rest of the hold stays stuck
        tr = P1 * math.exp(s1.real * tau) + P2 * math.exp(s2.real * tau)
        done = True
        for i in range(N):
            if abs(q[0, i]) + B[i, B_M] * P[P_R] * tr > q[5, i] * (1.0 - 1e-9):
                done = False
        if done or tau >= tau_max:
            return tau_max, -1, 5
        tb = min(tau + dtau, tau_max)
        gb, _ = _hold_margin(tb, s1, s2, c1, c2, N, q, stick_tol, np.int64(-1))
        if gb < 0.0:
            # earliest crossing among the balls below their limit at tb (Illinois)
            best = tb
            bball = -1
            for i in range(N):
                g1, _ = _hold_margin(tb, s1, s2, c1, c2, N, q, stick_tol, i)
                g0, _ = _hold_margin(tau, s1, s2, c1, c2, N, q, stick_tol, i)
                if g1 >= 0.0:
                    continue
                if g0 <= 0.0:
                    return tau, i, 5
                a_ = tau
                b_ = tb
                side = 0
                for _ in range(100):
                    x = (a_ * g1 - b_ * g0) / (g1 - g0)
                    gx, _ = _hold_margin(x, s1, s2, c1, c2, N, q, stick_tol, i)
                    if gx > 0.0:
                        a_ = x
                        g0 = gx
                        if side == 1:
                            g1 *= 0.5
                        side = 1
                    else:
                        b_ = x
                        g1 = gx
                        if side == -1:
                            g0 *= 0.5
                        side = -1
                    if b_ - a_ < 1e-9 * dtau or gx == 0.0:
                        break
                if bball < 0 or b_ < best:
                    best = b_
                    bball = i
            return best, bball, 5
        tau = tb
    return tau, -2, 5
