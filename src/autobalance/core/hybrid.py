"""Balls beside a liquid: the ball kernel (integrate.py, with its exact stick-slip) and the wall
films of core/shallow_water.py advanced together, one film time step at a time.

Coupling (explicit, as :func:`.shallow_water.sw_coupled` couples the films with the Jeffcott
rotor): over a step [t, t + dt] (the films' CFL step)

1. every film takes one step forced by the chamber's deflection w, its rate w' (rotor frame) and
   w'' (from the previous step), read from the ball kernel's state at t;
2. the rotor and the balls are integrated over [t, t + dt] by the ball kernel, paused at t + dt
   (a knot added to the profile: ``integrate_span``'s pause), with the films' summed moment U
   and its rate U' frozen at their values at t (P_LQX..P_LQDY): the chamber feels
   W^2 U - i W' U - 2 i W U' (rhs.py);
3. the films' new moment changes the total first moment Z = M_t w + U + (balls) and its rate
   Z' by nothing: over the step Z moved by M_t w' (the kernel's) and the held U', i.e. by U' dt
   of the films' change dU; the chamber's deflection and rate take the rest,
   w -= (dU - U' dt) / M_t, w' -= dU' / M_t (the films' acceleration felt by the rotor;
   sw_coupled keeps Z and Z' through the films' update in the same way). Were the deflection
   to take all of dU, the rotor would lag by U' dt / M_t every step, which leaves a synchronous
   whirl (U' = 0 in the rotor frame) alone but changes its transients and growth rates
   (docs/liquid/stability.md sec. 3k).

With a film of no mass this is the ball kernel's run stepped at the films' pace; with balls that
cannot move it is the Jeffcott rotor with a film (tests/test_hybrid.py checks both).

A motor-driven spin (layout.P_SPIN = 1; docs/liquid/balls-beside-liquid.md sec. 3i): the films take
Omega = psi' from the kernel's state at t and Omega' from its last step; the kernel holds, besides U
and U', the films' second moment I_c (in its spin row, with -i psi'' U in its mass matrix) and their
torque on the spin, -(the films' change of relative angular momentum H_rel) / dt of the last
film step (films_spin): the wall shear's and the partitions' torque, one step late.
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .jit import kernel

from .integrate import _integrate
from .layout import (NR, P_LQDX, P_LQDY, P_LQI, P_LQT, P_LQX, P_LQY, P_MT, P_SPIN, S_STATUS,
                     RunStatus)
from .rhs import profile_eval, profile_segment
from .work import ball_work
from .shallow_water import (_emit, accept_state, films_dt, films_moment, films_spin, films_step,
                            gravity_offset)

_RUNNING = float(RunStatus.RUNNING)


@njit(cache=True)
def with_knot(prof_t: np.ndarray, prof_w: np.ndarray, t1: float, pt: np.ndarray,
              pw: np.ndarray) -> int:
    """The profile (prof_t [s], prof_w [rad/s]) with a knot at t1 [s] (its speed interpolated)
    written into pt, pw (len(prof_t) + 1); returns the knots written (no new knot when t1 is one
    within 1e-12 relative)."""
    n = prof_t.shape[0]
    m = 0
    done = False
    tol = 1e-12 * max(1.0, abs(t1))
    for k in range(n):
        if not done and abs(prof_t[k] - t1) <= tol:
            done = True
        elif not done and prof_t[k] > t1:
            seg = k - 1 if k > 0 else 0
            ws, _ = profile_eval(t1, seg, prof_t, prof_w)
            pt[m] = t1
            pw[m] = ws
            m += 1
            done = True
        pt[m] = prof_t[k]
        pw[m] = prof_w[k]
        m += 1
    if not done:
        pt[m] = t1
        pw[m] = prof_w[n - 1]
        m += 1
    return m


@kernel
def _freeze(P: np.ndarray, U: complex, Ud: complex, Ic: float, Tl: float) -> None:
    """The films' moment U [kg*m], rate U' [kg*m/s], second moment I_c [kg*m^2] and torque on
    the spin [N*m] that the ball kernel holds fixed over a coupling step (layout.P_LQX..P_LQT;
    the last two read only with a motor-driven spin)."""
    P[P_LQX] = U.real
    P[P_LQY] = U.imag
    P[P_LQDX] = Ud.real
    P[P_LQDY] = Ud.imag
    P[P_LQI] = Ic
    P[P_LQT] = Tl


@kernel
def _spin_speed(t: float, y: np.ndarray, motor: bool, prof_t: np.ndarray,
                prof_w: np.ndarray) -> float:
    """The spin speed [rad/s] at t [s]: the kernel's psi' (motor-driven) or the profile's."""
    if motor:
        return y[y.shape[0] - 1]
    W, _ = profile_eval(t, profile_segment(t, prof_t), prof_t, prof_w)
    return W


@njit(cache=True, nogil=True)
def hybrid_integrate(P: np.ndarray, B: np.ndarray, N: int, prof_t: np.ndarray,
                     prof_w: np.ndarray, unb_t: np.ndarray, unb_u: np.ndarray, y: np.ndarray,
                     t0: float, t_end: float, rtol: float, atol: np.ndarray, h_max: float,
                     max_steps: int, out_t: np.ndarray, out_y: np.ndarray, stats: np.ndarray,
                     carry: np.ndarray, h: np.ndarray, q: np.ndarray, theta: np.ndarray,
                     starts: np.ndarray, Rs: np.ndarray, Hs: np.ndarray, rhos: np.ndarray,
                     nus: np.ndarray, wall: np.ndarray, gp: float, gdir: float, sag: complex,
                     film_t: np.ndarray, out_h: np.ndarray, out_q: np.ndarray,
                     out_psi: np.ndarray) -> int:
    """From t0 [s] to t_end [s]: the ball run (P, B, N, profile, unbalance table, y, rtol, atol,
    h_max, max_steps, out_t, out_y, stats as integrate.integrate_span; ``carry`` its paused
    state at t0, or carry[C_WHERE] = 0 with t0 = 0) with the films of concentric chambers
    (h, q, theta, starts, Rs, Hs, rhos, nus, wall as shallow_water.sw_coupled, holding their
    state at t0) beside the balls (module docstring); a horizontal axis: in-plane gravity gp
    [m/s^2] at the inertial angle gdir [rad] in the films' potential (shallow_water.
    gravity_offset, with the kernel's spin angle) and the static sag [m] (inertial frame: the
    kernel's deflection is from the static equilibrium, the films need the chamber's position
    about the rotation axis). out_h, out_q (len(film_t), cells) receive the films at their own
    sorted output times film_t [s] from t0 on (dense enough for the revolution average, whatever
    the balls' outputs; rows before t0 are left alone), out_psi the kernel's spin angle [rad]
    there. Returns the film steps; -1 on a non-finite film. The run's status is the ball
    kernel's (stats)."""
    nq = N + NR + 1
    n = 2 * nq
    n_c = h.shape[0]
    np_ = prof_t.shape[0] + 1
    pt = np.zeros(np_)
    pw = np.zeros(np_)
    fw = np.zeros((9, n_c))              # the films' work arrays
    hn, qn, fh, fq, fqr, hl, hr, b, a = fw[0], fw[1], fw[2], fw[3], fw[4], fw[5], fw[6], fw[7], fw[8]
    sw, rw, md, ct, jw = ball_work(N)
    spin = md[2]

    Mt = P[P_MT]
    motor = P[P_SPIN] == 1.0
    t = t0
    kout = 0
    while kout < film_t.shape[0] and film_t[kout] < t - 1e-12 * max(1.0, t):
        kout += 1
    U, Ud = films_moment(h, q, theta, starts, Rs, Hs, rhos)
    Ic, Hr = films_spin(h, q, starts, Rs, Hs, rhos)
    Tl = 0.0
    W0 = _spin_speed(t, y, motor, prof_t, prof_w)
    W_prev = W0
    Wd_m = 0.0
    wd_prev = complex(y[nq], y[nq + 1]) - 1j * W0 * sag * complex(math.cos(y[nq - 1]),
                                                                  -math.sin(y[nq - 1]))
    wdd = 0j
    steps = 0
    tol = 1e-12 * max(1.0, t_end)
    while True:
        k0 = kout
        kout = _emit(film_t, out_h, out_q, kout, t, h, q)
        for k in range(k0, kout):
            out_psi[k] = y[nq - 1]
        if t >= t_end - tol:
            break
        if motor:                   # the kernel's spin; its rate from the last step
            W = y[n - 1]
            Wd = Wd_m
        else:
            W, Wd = profile_eval(t, profile_segment(t, prof_t), prof_t, prof_w)
        psi = y[nq - 1]
        rot = complex(math.cos(psi), -math.sin(psi))
        w = complex(y[0], y[1]) + sag * rot              # the chamber about the rotation axis
        wd = complex(y[nq], y[nq + 1]) - 1j * W * sag * rot
        off = gravity_offset(gp, gdir, psi, W) if gp != 0.0 else 0j
        dt = films_dt(h, q, starts, Rs, W, t_end - t)
        if kout < film_t.shape[0] and film_t[kout] - t < dt:
            dt = film_t[kout] - t
        t1 = t + dt
        if t1 >= t_end - tol:
            t1 = t_end
            dt = t1 - t
        # 1. the films' step, forced by the chamber's motion at t
        films_step(h, q, theta, starts, Rs, nus, wall, W, Wd, w, off, wd, wdd, dt, hn, qn, fh,
                   fq, fqr, hl, hr, b, a)
        # 2. rotor and balls over [t, t1] with the films' moment frozen
        _freeze(P, U, Ud, Ic, Tl)
        m = with_knot(prof_t, prof_w, t1, pt, pw)
        t_pause = t1 if t1 < t_end else np.inf
        _integrate(P, B, N, pt[:m], pw[:m], unb_t, unb_u, t_end, rtol, atol, h_max, max_steps,
                   out_t, out_y, stats, y, sw, rw, md, ct, jw, t_pause, carry)
        # 3. the films' update, taken up by the chamber
        steps += 1
        if not accept_state(h, q, hn, qn):
            return -1
        U1, Ud1 = films_moment(h, q, theta, starts, Rs, Hs, rhos)
        # Z and Z' kept: over the step Z moved by the kernel's M_t w' and the held U' (so U'
        # dt is already in it); the chamber takes the rest of the films' change
        dU = (U1 - U - dt * Ud) / Mt
        dUd = (Ud1 - Ud) / Mt
        y[0] -= dU.real
        y[1] -= dU.imag
        y[nq] -= dUd.real
        y[nq + 1] -= dUd.imag
        U = U1
        Ud = Ud1
        if motor:                   # the films' torque on the spin over the next step
            Ic, Hr1 = films_spin(h, q, starts, Rs, Hs, rhos)
            Tl = -(Hr1 - Hr) / dt
            Hr = Hr1
            Wd_m = (y[n - 1] - W_prev) / dt
            W_prev = y[n - 1]
        Wn = _spin_speed(t1, y, motor, prof_t, prof_w)
        psi1 = y[nq - 1]
        wd_new = complex(y[nq], y[nq + 1]) - 1j * Wn * sag * complex(math.cos(psi1),
                                                                    -math.sin(psi1))
        wdd = (wd_new - wd_prev) / dt
        wd_prev = wd_new
        t = t1
        if stats[S_STATUS] != _RUNNING and t < t_end:
            break                  # the ball run failed (step budget, stall): its status says
    _freeze(P, 0j, 0j, 0.0, 0.0)
    return steps
