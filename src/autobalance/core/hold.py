"""Exact solution of a constant-speed hold with every ball stuck (isotropic rotor).

With all balls stuck (alpha_dot = alpha_ddot = 0), a constant spin speed W, an isotropic linear
suspension (k, c), no gravity, no base motion, no dry friction and a constant unbalance, the u, v
rows of the equations of motion (004 eq 8-9 with phi_dot = phi_ddot = 0) are, with w = u + i v,

    M_t w'' + (c + 2 i W M_t) w' + (k - M_t W^2 + i c W) w = W^2 Ut,                      (H1)
    Ut = U + sum_i m_i (R e^{i alpha_i} + rho e^{i beta})          [kg*m, constant]

a constant-coefficient equation (the Jeffcott rotor in its rotating frame). Its exact solution is
w = w_ss + A e^{s1 tau} + B e^{s2 tau} with w_ss = W^2 Ut / (k - M_t W^2 + i c W) and s1, s2 the
roots of M_t s^2 + (c + 2 i W M_t) s + (k - M_t W^2 + i c W) = 0 (the inertial roots shifted by
-iW). The friction torque a stuck ball needs (004 eq 10 with phi'' = 0) is affine in
X = w'' + 2 i W w' - W^2 w:  lambda_i = m_i R Im(e^{-i alpha_i} X) + const_i, so

    |lambda_i(tau)| <= |lambda_i,ss| + m_i R sum_j |(s_j^2 + 2 i W s_j - W^2) C_j|       (H2)

for all tau >= 0 (Re s_j < 0). If (H2) is within every ball's static limit mu_s N_i R (N_i =
m_i R W^2 constant), the balls stay stuck for the whole hold and the state at any time follows
from (H1) in closed form: the integrator jumps to the end of the segment.
"""
from __future__ import annotations

import cmath
import math
from typing import TYPE_CHECKING

from .jit import kernel
from .layout import (B_M, NR, P_CX, P_KX, P_MT,
                     P_R, S_AMAX, S_TAMAX, S_XMAX, S_YMAX)

if TYPE_CHECKING:
    import numpy as np


@kernel
def hold_roots(P: np.ndarray, W: float) -> tuple[complex, complex, complex]:
    """Roots s1, s2 [1/s] and the static response factor 1/(k - M_t W^2 + i c W) [m/N]."""
    mt = P[P_MT]
    k = P[P_KX]
    c = P[P_CX]
    b = complex(c, 2.0 * W * mt)
    k0 = complex(k - mt * W * W, c * W)
    disc = cmath.sqrt(b * b - 4.0 * mt * k0)
    s1 = (-b + disc) / (2.0 * mt)
    s2 = (-b - disc) / (2.0 * mt)
    return s1, s2, 1.0 / k0


@kernel
def hold_coeffs(w0: complex, wd0: complex, wss: complex, s1: complex,
                s2: complex) -> tuple[complex, complex]:
    """C1, C2 of w - w_ss = C1 e^{s1 t} + C2 e^{s2 t} from w(0) = w0, w'(0) = wd0."""
    z0 = w0 - wss
    c1 = (wd0 - s2 * z0) / (s1 - s2)
    return c1, z0 - c1


@kernel
def hold_state(tau: float, wss: complex, s1: complex, s2: complex, c1: complex,
               c2: complex) -> tuple[complex, complex]:
    """w(tau), w'(tau) [m, m/s]."""
    e1 = cmath.exp(s1 * tau)
    e2 = cmath.exp(s2 * tau)
    return wss + c1 * e1 + c2 * e2, s1 * c1 * e1 + s2 * c2 * e2


@kernel
def hold_transient_bound(W: float, s1: complex, s2: complex, c1: complex,
                         c2: complex) -> float:
    """sum_j |(s_j^2 + 2 i W s_j - W^2) C_j|: bound of |X - X_ss| for tau >= 0 (eq H2) [m/s^2]."""
    p1 = (s1 * s1 + 2j * W * s1 - W * W) * c1
    p2 = (s2 * s2 + 2j * W * s2 - W * W) * c2
    return abs(p1) + abs(p2)


@kernel
def record_amplitude(a1: float, t: float, stats: np.ndarray) -> None:
    """Keep a1 [m] at t [s] as the run's maximal amplitude if it is larger (isotropic rotor
    without gravity: max|x| = max|y| = max|w|)."""
    if a1 > stats[S_AMAX]:
        stats[S_AMAX] = a1
        stats[S_TAMAX] = t
        stats[S_XMAX] = a1
        stats[S_YMAX] = a1


@kernel
def peak_samples(f_max: float, life: float) -> tuple[int, float]:
    """Number of samples and spacing [s] over a transient's life [s]: 16 per period of its
    fastest frequency f_max [rad/s], at most 8192."""
    n = min(8192, 16 + int(16.0 * life * f_max / (2.0 * math.pi)))
    return n, life / n


@kernel
def vertex(f0: float, f1: float, f2: float) -> float:
    """Abscissa in (-1, 1) of the vertex of the parabola through (-1, f0), (0, f1), (1, f2)
    [-] (0 when it is not a maximum)."""
    cu = f0 - 2.0 * f1 + f2
    if cu >= 0.0:
        return 0.0
    return max(-1.0, min(1.0, 0.5 * (f0 - f2) / cu))


@kernel
def hold_peak(t: float, tau_end: float, wss: complex, s1: complex, s2: complex, c1: complex,
              c2: complex, stats: np.ndarray) -> None:
    """Largest |w| [m] of a hold starting at t [s] (amplitude monitor): skipped when
    |w_ss| + |C1| + |C2| cannot beat the run's maximum; else |w| sampled 16 times per period
    of the transient's fastest rotor-frame frequency over 16 decay times and refined at the
    vertex of the parabola through the largest sample and its neighbours. A transient that
    could raise the maximum by at most 1e-9 of it is not sampled."""
    if abs(wss) + abs(c1) + abs(c2) <= stats[S_AMAX] * (1.0 + 1e-9):
        return
    rate = min(-s1.real, -s2.real)
    life = tau_end if rate <= 0.0 else min(tau_end, 16.0 / rate)
    f_max = max(abs(s1.imag), max(abs(s2.imag), abs(s1.imag - s2.imag)))
    n, dt = peak_samples(f_max, life)
    kb = 0
    ab = abs(hold_state(0.0, wss, s1, s2, c1, c2)[0])
    for k in range(1, n + 1):
        a1 = abs(hold_state(k * dt, wss, s1, s2, c1, c2)[0])
        if a1 > ab:
            ab = a1
            kb = k
    tb = kb * dt
    if 0 < kb < n:
        x = vertex(abs(hold_state(tb - dt, wss, s1, s2, c1, c2)[0]), ab,
                   abs(hold_state(tb + dt, wss, s1, s2, c1, c2)[0]))
        tb += x * dt
        ab = max(ab, abs(hold_state(tb, wss, s1, s2, c1, c2)[0]))
    record_amplitude(ab, t + tb, stats)


@kernel
def hold_outputs(t: float, t_to: float, kout: int, out_t: np.ndarray, out_y: np.ndarray,
                 y: np.ndarray, N: int, W: float, wss: complex, s1: complex, s2: complex,
                 c1: complex, c2: complex, rate: np.ndarray) -> int:
    """Outputs at out_t in (.., t_to] [s] of a hold starting at t [s] at speed W [rad/s], from
    the closed form; ball i's angle advances at rate[NR + i] [rad/s] (its creep speed, or 0).
    Returns the next output index."""
    nq = N + NR + 1
    while kout < out_t.shape[0] and out_t[kout] <= t_to:
        tau = out_t[kout] - t
        w, wd = hold_state(tau, wss, s1, s2, c1, c2)
        for j in range(2 * nq):
            out_y[kout, j] = y[j]
        for i in range(N):
            out_y[kout, NR + i] += rate[NR + i] * tau
        out_y[kout, 0] = w.real
        out_y[kout, 1] = w.imag
        out_y[kout, nq] = wd.real
        out_y[kout, nq + 1] = wd.imag
        out_y[kout, nq - 1] = y[nq - 1] + W * tau
        kout += 1
    return kout


@kernel
def hold_finish(t: float, tau_end: float, t_out: float, kout: int, out_t: np.ndarray,
                out_y: np.ndarray, y: np.ndarray, N: int, W: float, wss: complex, s1: complex,
                s2: complex, c1: complex, c2: complex, rate: np.ndarray,
                stats: np.ndarray) -> int:
    """Take a hold from t to t + tau_end [s] in closed form: outputs up to t_out [s]
    (hold_outputs), the amplitude monitor (hold_peak), and y advanced to the end (balls at
    rate[NR + i] [rad/s]). Returns the next output index."""
    nq = N + NR + 1
    kout = hold_outputs(t, t_out, kout, out_t, out_y, y, N, W, wss, s1, s2, c1, c2, rate)
    hold_peak(t, tau_end, wss, s1, s2, c1, c2, stats)
    w, wd = hold_state(tau_end, wss, s1, s2, c1, c2)
    y[0] = w.real
    y[1] = w.imag
    y[nq] = wd.real
    y[nq + 1] = wd.imag
    y[nq - 1] += W * tau_end
    for i in range(N):
        y[NR + i] += rate[NR + i] * tau_end
    return kout


@kernel
def ball_unbalance(y: np.ndarray, B: np.ndarray, N: int, R: float, rho: float, beta: float,
                   U: float) -> complex:
    """Ut = U + sum m_i (R e^{i alpha_i} + rho e^{i beta}) [kg*m] (eq H1)."""
    ut = complex(U, 0.0)
    for i in range(N):
        m = B[i, B_M]
        ut += m * (R * cmath.exp(1j * y[NR + i]) + rho * cmath.exp(1j * beta))
    return ut


@kernel
def hold_margin_ok(lam_ss: np.ndarray, lim: np.ndarray, N: int, B: np.ndarray, R: float,
                   bound: float) -> bool:
    """(H2) for every ball with a relative margin of 1e-9."""
    for i in range(N):
        need = abs(lam_ss[i]) + B[i, B_M] * R * bound
        if need > lim[i] * (1.0 - 1e-9):
            return False
    return True


__all__ = ["hold_roots", "hold_coeffs", "hold_state", "hold_transient_bound",
           "ball_unbalance", "hold_margin_ok", "hold_finish", "hold_outputs", "hold_peak", "peak_samples", "record_amplitude",
           "vertex", "math", "P_R"]
