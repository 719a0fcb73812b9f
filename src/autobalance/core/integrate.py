"""Adaptive Dormand-Prince 5(4) integration with exact Coulomb stick-slip (switch model).

The mode of every ball (stuck, or slipping in direction sgn) is frozen during a step, so the right
hand side is smooth inside a step and the error control is honest. After an accepted step the
switching functions are checked:
  * slipping ball i: g = sgn_i * alpha_dot_i crosses zero  -> the ball stops (stick candidate);
  * stuck ball i:    g = mu_s N_i R - |lambda_i| < 0        -> the ball breaks away;
  * motor-driven spin: psi_dot reaches the hold speed      -> the controller takes over.
The earliest crossing is located on the cubic Hermite interpolant of the step (Illinois method),
the state there is taken from DOPRI5's continuous extension of the step (core/step.py
``_dense``), and the modes are re-resolved: stuck balls are released one
at a time, largest |lambda|/limit first, until every stuck ball's required friction is within its
static limit (coupled stuck balls are solved together because lambda comes from the full
constrained system). References: Leine, van Campen, van de Vrande, Nonlinear Dyn. 16 (1998)
41-54 (switch model); Hairer, Norsett, Wanner, Solving ODEs I, sec. II.5 (DOPRI5) and II.6
(dense output, event location).

The pieces of a step (the DOPRI5 step and its continuous extension, the event location, the
modes after an event, the step-size control, the carry of a paused run) are in core/step.py;
this module holds the loop. Size: ``_integrate`` (the inner loop, a state machine over a dozen
work arrays that live for the whole run) is the compiled exception to the 100-line rule; split
into numba calls, the control flow of one step would be spread over functions sharing every
array. Batches: core/batch.py.
"""
from __future__ import annotations

import math

import numpy as np

from .jit import kernel
from .layout import (B_KC, B_MUS, C_WHERE, carry_size, N_S, NR, P_BETA, P_DELTA, P_ETD,
                     P_FLAW, P_HC, P_HOLDS, P_R, P_RAMPS, P_RHO, P_SPIN, P_SYM, P_WHOLD, S_AMAX,
                     S_EVENTS, S_HOLDS, S_IMPACTS, S_RAMPS, S_REJECTED, S_RHS, S_STATUS, S_STEPS,
                     S_TAMAX, S_TFINAL, S_THOLD, S_XMAX, S_YMAX)
from .hold import ball_unbalance, hold_coeffs, hold_finish, hold_margin_ok, hold_roots, hold_state
from .expo import slip_window, SLIP_WINDOW
from .ramp import hold_breakaway, ramp_jump
from .rhs import neighbour_gap, profile_segment, rhs
from .work import ball_work
from .step import (_carry_in, _carry_out, _dense, _dopri_step, _event_g, _hermite, _hold_arrival,
                   _locate, _modes, _next_h, _resolve, _RUNNING, BREAKAWAY, CREEP_CHUNK, NO_EVENT,
                   SLIP_STOP, STICK_TOL)


def integrate(P: np.ndarray, B: np.ndarray, N: int, prof_t: np.ndarray, prof_w: np.ndarray,
              unb_t: np.ndarray, unb_u: np.ndarray, y0: np.ndarray, t_end: float, rtol: float,
              atol: np.ndarray, h_max: float, max_steps: int, out_t: np.ndarray,
              out_y: np.ndarray, stats: np.ndarray) -> np.ndarray:
    """Integrate one run from t = 0 to t_end.

    Parameters
    ----------
    P, B, N : parameters (layout.py) and number of balls.
    prof_t, prof_w : piecewise-linear speed profile knots [s], [rad/s].
    unb_t, unb_u : unbalance table [s], [kg*m].
    y0 : initial state (layout.py).
    t_end : end time [s].
    rtol : relative tolerance [-]; atol : absolute tolerance per state component.
    h_max : largest step [s].
    max_steps : step budget.
    out_t : sorted output times [s]; out_y : (len(out_t), 2*nq) filled with the state there.
    stats : (N_S,) filled with the run statistics (layout.S_*).
    """
    y = y0.copy()
    integrate_span(P, B, N, prof_t, prof_w, unb_t, unb_u, y, t_end, rtol, atol, h_max,
                   max_steps, out_t, out_y, stats, np.inf, np.zeros(carry_size(N)))
    return y


def integrate_span(P: np.ndarray, B: np.ndarray, N: int, prof_t: np.ndarray,
                   prof_w: np.ndarray, unb_t: np.ndarray, unb_u: np.ndarray, y: np.ndarray,
                   t_end: float, rtol: float, atol: np.ndarray, h_max: float, max_steps: int,
                   out_t: np.ndarray, out_y: np.ndarray, stats: np.ndarray, t_pause: float,
                   carry: np.ndarray) -> None:
    """integrate() from a carried state, with an optional pause: the branching of runs that
    share the start of their history (the same machine, start and profile up to a knot).

    ``carry`` (layout.carry_size(N)) with carry[C_WHERE] = 0 starts from y at t = 0. The run
    stops at its first arrival at or after ``t_pause`` [s] (the end of a closed-form jump or of
    a slip jump, or a step that ends on a profile knot), before it reads the profile there,
    with stats[S_STATUS] = RUNNING, its state in y, out_y filled up to that time and everything
    else the loop carries in ``carry``. Called again with that y, carry, out_y and stats, and a profile equal
    up to that time, it continues bit for bit as the run without the pause. With t_pause a
    knot, the stop is on the knot and the later segments may differ (branching). With a
    motor-driven spin (no knots) the step is clipped to t_pause and the run stops there (the
    coupling steps of core/hybrid.py; not bit for bit the run without the pause). t_pause = inf:
    the whole run.
    """
    _integrate(P, B, N, prof_t, prof_w, unb_t, unb_u, t_end, rtol, atol, h_max, max_steps,
               out_t, out_y, stats, y, *ball_work(N), t_pause, carry)


@kernel
def _integrate(P, B, N, prof_t, prof_w, unb_t, unb_u, t_end, rtol, atol, h_max, max_steps,
               out_t, out_y, stats, y, sw, rw, md, ct, jw, t_pause, carry):
    """The integration loop of integrate(), on preallocated work arrays (no allocation: the
    kernel runs without the numba runtime, core/jit.py). y holds the initial state on entry and
    the final state on return; sw, rw, md, ct, jw: the step's work, the work of rhs() (rw[0] =
    lam, its friction bookkeeping), the modes, the contacts and the jumps' work
    (work.ball_work); gs / ge: stick margins mu_s N R - |lambda| at the start / end of the trial
    step; t_pause, carry: see integrate_span()."""
    sched = (prof_t, prof_w, unb_t, unb_u)
    K, ytmp, y1, f0, f1, ftmp, err = sw
    stuck, sgn, spin = md
    gs, ge, in_contact, viol = ct
    ser, qr, ew3, ew1 = jw
    lam = rw[0]
    nq = N + NR + 1
    n = 2 * nq
    ip = nq - 1
    nout = out_t.shape[0]
    exact = P[P_FLAW] != 1.0          # exact stick-slip, with (2) or without (0) creep
    creep = P[P_FLAW] == 2.0
    # isotropic, no gravity, no base motion: max|x| = max|y| = max|w| (no sub-sampling needed)
    symmetric = P[P_SYM] == 1.0
    # static conditions of a closed-form hold, derived from the model by simulate/pack.fast_paths
    can_hold = P[P_HOLDS] == 1.0
    can_ramp = P[P_RAMPS] == 1.0
    # slip jumps: the stuck ramps' conditions (pack.py), the exact law without creep
    can_etd = P[P_ETD] == 1.0 and exact and not creep
    where = int(carry[C_WHERE])
    status = 0
    en = 0.0
    h_acc = 0.0
    ev_kind = NO_EVENT
    ev_i = NO_EVENT
    if where == 0:
        spin[0] = P[P_SPIN]
        for j in range(N_S):
            stats[j] = 0.0
        stats[S_THOLD] = -1.0
        kout = 0
        t = 0.0
        # initial modes: balls at rest relative to the race start stuck if they can
        if exact:
            for i in range(N):
                if B[i, B_MUS] > 0.0 and y[nq + NR + i] == 0.0:
                    stuck[i] = 1
                else:
                    sgn[i] = 1.0 if y[nq + NR + i] >= 0.0 else -1.0
        seg = profile_segment(t, prof_t)
        _resolve(t, y, P, B, N, seg, sched, md, f0, rw)
        nrhs = N + 1
        for i in range(N):
            gs[i] = lam[N + i] * (1.0 + STICK_TOL) - abs(lam[i])
        while kout < nout and out_t[kout] <= t:
            for j in range(n):
                out_y[kout, j] = y[j]
            kout += 1
        amax = math.sqrt(y[0] ** 2 + y[1] ** 2)
        stats[S_AMAX] = amax
        # initial step: a fraction of a revolution / of the fastest natural period
        h = min(h_max, 1e-4)
        nsteps = 0
        en_old = 1e-4
        nrej = 0
        nev = 0
        stall = 0
        next_try = 0
        nhold = 0
        nramp = 0
        next_etd = 0.0
        h_etd = 0.05
    else:
        # ---- continue a paused run: the arrival at the knot, with this profile's next segment
        t, h, en, en_old, h_acc, nsteps, nrej, nev, stall, next_try, nhold, nramp, nrhs, kout, \
            ev_kind, ev_i, next_etd, h_etd = _carry_in(carry, N, n, spin, stuck, sgn, in_contact,
                                                       gs, lam, f0)
        seg = profile_segment(t, prof_t)
        if where == 3:                # the hold's end, with its breakaway if any (ev_i)
            nev += _hold_arrival(ev_i, t, y, P, B, N, seg, sched, md, f0, rw, gs)
            nrhs += 2 * N + 3
        else:                         # a jump's end (no event) or a step's
            nrhs += _modes(ev_kind, ev_i, t, y, P, B, N, seg, sched, md, f0, rw, gs,
                           stats, exact)
        if where == 4 and stall > 50:
            status = 2
        elif where == 4 and ev_kind < 0:
            h, en_old = _next_h(en, en_old, h_acc, h, h_max)
    paused = 0
    while t < t_end and status == 0:
        if nsteps + nrej >= max_steps:
            status = 1
            break
        # ---- constant-speed hold with every ball stuck: exact jump (core/hold.py) --------
        if can_hold and nsteps >= next_try:
            flat = seg >= prof_t.shape[0] - 1 or prof_w[seg + 1] == prof_w[seg]
            all_stuck = True
            for i in range(N):
                if stuck[i] == 0:
                    all_stuck = False
            t_seg = t_end
            if seg < prof_t.shape[0] - 1 and prof_t[seg + 1] < t_end:
                t_seg = prof_t[seg + 1]
            if can_ramp and not flat and all_stuck and t_seg - t > 20.0 * h:
                # ---- linear speed ramp with every ball stuck: no stepping (core/ramp.py) ----
                t_new, kout, ne = ramp_jump(t, t_seg, h, y, P, B, N, seg, sched, md,
                                            atol, rtol, out_t, out_y, kout, stats, ser, qr, ytmp,
                                            ftmp, rw)
                nrhs += ne
                if t_new > t:
                    t = t_new
                    nramp += 1
                    if t < t_seg:
                        next_try = nsteps + 20
                    if t >= t_pause:
                        paused = 1
                        ev_kind = NO_EVENT
                        break
                    seg = profile_segment(t, prof_t)
                    nrhs += _modes(NO_EVENT, NO_EVENT, t, y, P, B, N, seg, sched, md,
                                   f0, rw, gs, stats, exact)
                    continue
                next_try = nsteps + 20
            if flat and all_stuck and t_seg - t > 20.0 * h:
                W = prof_w[seg] if seg < prof_t.shape[0] else prof_w[prof_t.shape[0] - 1]
                ut = ball_unbalance(y, B, N, P[P_R], P[P_RHO], P[P_BETA], unb_u[0])
                s1, s2, Hk = hold_roots(P, W)
                wss = W * W * ut * Hk
                c1, c2 = hold_coeffs(complex(y[0], y[1]), complex(y[nq], y[nq + 1]), wss, s1, s2)
                for j in range(n):
                    ytmp[j] = y[j]
                ytmp[0] = wss.real
                ytmp[1] = wss.imag
                ytmp[nq] = 0.0
                ytmp[nq + 1] = 0.0
                rhs(t, ytmp, P, B, N, seg, sched, md, ftmp, rw)
                nrhs += 1
                p1 = (s1 * s1 + 2j * W * s1 - W * W) * c1
                p2 = (s2 * s2 + 2j * W * s2 - W * W) * c2
                if hold_margin_ok(lam, lam[N:2 * N], N, B, P[P_R], abs(p1) + abs(p2)):
                    tau_end = t_seg - t
                    if creep:
                        # stuck balls creep (tanh slow manifold): jump at most CREEP_CHUNK of
                        # creep, at the creep speeds of the chunk's midpoint (f1[NR + i])
                        rhs(t, y, P, B, N, seg, sched, md, ftmp, rw)
                        cmax = 0.0
                        for i in range(N):
                            cmax = max(cmax, abs(ftmp[NR + i]))
                        if cmax * tau_end > CREEP_CHUNK:
                            tau_end = CREEP_CHUNK / cmax
                            t_seg = t + tau_end
                        w, wd = hold_state(0.5 * tau_end, wss, s1, s2, c1, c2)
                        for j in range(n):
                            y1[j] = y[j] + 0.5 * tau_end * ftmp[j] if NR <= j < ip else y[j]
                        y1[0], y1[1], y1[nq], y1[nq + 1] = w.real, w.imag, wd.real, wd.imag
                        y1[ip] = y[ip] + 0.5 * W * tau_end
                        rhs(t + 0.5 * tau_end, y1, P, B, N, seg, sched, md, f1, rw)
                        nrhs += 2
                    else:
                        for i in range(N):
                            f1[NR + i] = 0.0
                    kout = hold_finish(t, tau_end, t_seg, kout, out_t, out_y, y, N, W, wss, s1,
                                       s2, c1, c2, f1, stats)
                    t = t_seg
                    nhold += 1
                    if t >= t_pause:
                        paused = 2
                        ev_kind = NO_EVENT
                        break
                    seg = profile_segment(t, prof_t)
                    nrhs += _modes(NO_EVENT, NO_EVENT, t, y, P, B, N, seg, sched, md,
                                   f0, rw, gs, stats, exact)
                    continue
                if can_ramp:
                    # ---- the hold until its first breakaway, without stepping (ramp.py R5) ----
                    tau_b, ib, ne = hold_breakaway(t, t_seg - t, W, wss, s1, s2, c1, c2, y, P, B, N,
                                                   seg, sched, md, qr, ytmp, ftmp, rw,
                                                   STICK_TOL)
                    nrhs += ne
                    if tau_b > 1e-12 * max(1.0, t):
                        t_to = t_seg if ib == -1 else t + tau_b
                        for i in range(N):
                            f1[NR + i] = 0.0
                        kout = hold_finish(t, tau_b, t_to, kout, out_t, out_y, y, N, W, wss,
                                           s1, s2, c1, c2, f1, stats)
                        t = t_to
                        nhold += 1
                        if ib == -2:
                            next_try = nsteps + 20
                        if t >= t_pause:
                            paused = 3
                            ev_kind = NO_EVENT
                            ev_i = ib
                            break
                        seg = profile_segment(t, prof_t)
                        nev += _hold_arrival(ib, t, y, P, B, N, seg, sched, md, f0,
                                             rw, gs)
                        nrhs += 2 * N + 3
                        continue
                next_try = nsteps + 20
        # ---- a ball slipping: a slip jump by ETDRK4-B (core/expo.py), to the next knot or
        # output, at most SLIP_WINDOW ahead (a pause waits for its end); DOPRI5 on from where
        # it ends (a failed window is retried up to the step that failed: slip_window)
        if can_etd and t >= next_etd and spin[0] == 0.0:
            t_w = min(t_end, t + SLIP_WINDOW)      # not t_pause: the run pauses at the end
            if seg < prof_t.shape[0] - 1 and prof_t[seg + 1] < t_w:
                t_w = prof_t[seg + 1]
            if kout < nout and t < out_t[kout] < t_w:
                t_w = out_t[kout]
            slipping = False
            for i in range(N):
                if stuck[i] == 0:
                    slipping = True
            if slipping and t_w - t > 20.0 * h:
                ok_e, ne, h_etd, a_e, ta_e, next_etd, t_reach = slip_window(t, t_w, y, h_etd, P, B,
                                                                            N, sched, md, atol,
                                                                            rtol, ew3, ew1, rw,
                                                                            STICK_TOL, h_max)
                nrhs += ne
                if ok_e:
                    t = t_reach
                    if a_e > stats[S_AMAX]:
                        stats[S_AMAX] = a_e
                        stats[S_TAMAX] = ta_e
                        stats[S_XMAX] = a_e
                        stats[S_YMAX] = a_e
                    while kout < nout and out_t[kout] <= t:
                        for j in range(n):
                            out_y[kout, j] = y[j]
                        kout += 1
                    if t >= t_pause:
                        paused = 1
                        ev_kind = NO_EVENT
                        break
                    seg = profile_segment(t, prof_t)
                    nrhs += _modes(NO_EVENT, NO_EVENT, t, y, P, B, N, seg, sched, md,
                                   f0, rw, gs, stats, exact)
                    continue
        # two balls in compliant contact: DOPRI5 resolves the contact's oscillation (docs/
        # numerics/contacts.md, "Resting contacts"); at its stability limit it chatters spuriously.
        # A pair whose balls are both stuck has no such mode (their angles are held): no cap
        if h > P[P_HC] > 0.0:
            for i in range(N):
                if in_contact[i] == 1 and (stuck[i] == 0 or stuck[(i + 1) % N] == 0):
                    h = P[P_HC]
                    break
        # hard stops at profile knots (a motor-driven spin: at the pause, core/hybrid.py)
        t_stop = t_end
        if spin[0] == 0.0 and seg < prof_t.shape[0] - 1 and prof_t[seg + 1] < t_stop:
            t_stop = prof_t[seg + 1]
        elif spin[0] != 0.0 and t_pause < t_stop:
            t_stop = t_pause
        last = False
        if t + h >= t_stop - 1e-12 * max(1.0, abs(t_stop)):
            h = t_stop - t
            last = True
        if h < 1e-14 * max(1.0, t):
            status = 2
            break
        ok = _dopri_step(t, y, f0, h, P, B, N, seg, sched, md, K, ytmp, y1, f1, err,
                         rw)
        nrhs += 6
        en = 0.0
        finite = ok
        for j in range(n):
            if j == ip or (j == n - 1 and spin[0] != 1.0):
                continue
            sc = atol[j] + rtol * max(abs(y[j]), abs(y1[j]))
            q = err[j] / sc
            en += q * q
            if not math.isfinite(y1[j]):
                finite = False
        en = math.sqrt(en / (n - 2))
        if not finite:
            if h < 1e-12:
                status = 3
                break
            h *= 0.25
            nrej += 1
            continue
        if en > 1.0:
            h *= max(0.2, 0.9 * en ** -0.2)
            nrej += 1
            continue
        # ---- accepted trial step: events ------------------------------------------------
        for i in range(N):
            ge[i] = lam[N + i] * (1.0 + STICK_TOL) - abs(lam[i])
        ev_kind = NO_EVENT
        ev_i = NO_EVENT
        th_ev = 2.0
        shrink = False
        if exact:
            for i in range(N):
                if stuck[i] == 0 and B[i, B_MUS] > 0.0:
                    g1 = sgn[i] * y1[nq + NR + i]
                    if g1 < 0.0:
                        g0 = sgn[i] * y[nq + NR + i]
                        a_ = 0.0
                        ga = g0
                        gb = g1
                        if ga <= 0.0 and sgn[i] * f0[nq + NR + i] > 0.0:
                            # freshly released ball (alpha_dot = 0): bracket a positive value
                            thp = 0.5
                            for _ in range(30):
                                gp = _event_g(SLIP_STOP, i, thp, t, h, y, f0, y1, f1, ytmp, P, B, N,
                                              seg, sched, md, ftmp, rw)
                                if gp > 0.0:
                                    a_ = thp
                                    ga = gp
                                    break
                                thp *= 0.5
                        if ga <= 0.0 and g0 == 0.0 and h > 1e-9 * max(1.0, t):
                            shrink = True     # released ball reverses within the step
                            break
                        if ga <= 0.0:
                            th = 0.0
                        else:
                            th, ne = _locate(SLIP_STOP, i, ga, gb, a_, t, h, y, f0, y1, f1, ytmp, P,
                                             B, N, seg, sched, md, ftmp, rw)
                        if th < th_ev:
                            th_ev = th
                            ev_kind = 0
                            ev_i = i
            if shrink:
                h *= 0.1
                nrej += 1
                continue
            any_stuck = False
            for i in range(N):
                if stuck[i] == 1:
                    any_stuck = True
            if any_stuck:
                # lam is from the FSAL evaluation f1 = f(t+h, y1) with the current modes;
                # snapshot the violations first: locating one event overwrites lam
                for i in range(N):
                    viol[i] = 1 if stuck[i] == 1 and abs(lam[i]) > lam[N + i] * (1.0 + STICK_TOL) else 0
                for i in range(N):
                    if viol[i] == 1:
                        ga = gs[i]
                        gb = ge[i]
                        if ga <= 0.0 or gb >= 0.0:
                            th = 0.0 if ga <= 0.0 else 1.0
                        else:
                            th, ne = _locate(BREAKAWAY, i, ga, gb, 0.0, t, h, y, f0, y1, f1, ytmp,
                                             P, B, N, seg, sched, md, ftmp, rw)
                            nrhs += ne
                        if th < th_ev:
                            th_ev = th
                            ev_kind = 1
                            ev_i = i
        if spin[0] == 1.0 and y1[2 * nq - 1] >= P[P_WHOLD]:
            g0 = P[P_WHOLD] - y[2 * nq - 1]
            g1 = P[P_WHOLD] - y1[2 * nq - 1]
            th = g0 / (g0 - g1) if g0 > g1 else 1.0
            if th < th_ev:
                th_ev = th
                ev_kind = 2
                ev_i = NO_EVENT
        h_acc = h
        if ev_kind >= 0:
            nev += 1
            if th_ev <= 1e-12:
                stall += 1
            else:
                stall = 0
            if th_ev < 1.0:
                h_ev = th_ev * h
                if h_ev > 1e-15 * max(1.0, t):
                    # the state at the event from the accepted step's continuous extension,
                    # and its derivative with the modes before the event (for lam and outputs)
                    _dense(y, f0, y1, f1, K, h, th_ev, ytmp)
                    for j in range(n):
                        y1[j] = ytmp[j]
                    rhs(t + h_ev, y1, P, B, N, seg, sched, md, f1, rw)
                    nrhs += 1
                else:
                    for j in range(n):
                        y1[j] = y[j]
                        f1[j] = f0[j]
                    h_ev = 0.0
                h_acc = h_ev
                last = False
        # ---- output and monitors on (t, t + h_acc] ------------------------------------
        t1 = t + h_acc
        if last:
            t1 = t_stop
        while kout < nout and out_t[kout] <= t1:
            th = (out_t[kout] - t) / h_acc if h_acc > 0.0 else 1.0
            for j in range(n):
                out_y[kout, j] = _hermite(y, f0, y1, f1, h_acc, th, j)
            kout += 1
        if h_acc > 0.0 and symmetric:
            a1 = math.sqrt(y1[0] ** 2 + y1[1] ** 2)
            if a1 > stats[S_AMAX]:
                stats[S_AMAX] = a1
                stats[S_TAMAX] = t1
                stats[S_XMAX] = a1
                stats[S_YMAX] = a1
        elif h_acc > 0.0:
            psid = abs(y1[2 * nq - 1])
            nsub = 1 + int(psid * h_acc * 2.5)
            if nsub > 64:
                nsub = 64
            for ks in range(1, nsub + 1):
                th = ks / nsub
                uu = _hermite(y, f0, y1, f1, h_acc, th, 0)
                vv = _hermite(y, f0, y1, f1, h_acc, th, 1)
                ps = _hermite(y, f0, y1, f1, h_acc, th, ip)
                c = math.cos(ps)
                s = math.sin(ps)
                xx = abs(uu * c - vv * s)
                yy = abs(uu * s + vv * c)
                if xx > stats[S_XMAX]:
                    stats[S_XMAX] = xx
                if yy > stats[S_YMAX]:
                    stats[S_YMAX] = yy
            a1 = math.sqrt(y1[0] ** 2 + y1[1] ** 2)
            if a1 > stats[S_AMAX]:
                stats[S_AMAX] = a1
                stats[S_TAMAX] = t1
        # contact bookkeeping (counts contacts started; none without a contact model, where
        # balls pass through each other)
        if N > 1 and B[0, B_KC] > 0.0:
            for i in range(N):
                j, gap = neighbour_gap(y1, i, N, P[P_DELTA])
                if gap < 0.0 and in_contact[i] == 0:
                    in_contact[i] = 1
                    stats[S_IMPACTS] += 1.0
                elif gap >= 0.0:
                    in_contact[i] = 0
        t = t1
        for j in range(n):
            y[j] = y1[j]
            f0[j] = f1[j]
        nsteps += 1
        for i in range(N):
            gs[i] = ge[i]
        if last and spin[0] == 0.0:
            if t >= t_pause:
                paused = 4
                break
            seg = profile_segment(t, prof_t)
        elif last and t >= t_pause:
            paused = 4                 # a motor-driven spin, at the pause (no knot)
            break
        # ---- mode changes ----------------------------------------------------------------
        if ev_kind >= 0 or last:
            nrhs += _modes(ev_kind, ev_i, t, y, P, B, N, seg, sched, md, f0, rw, gs,
                           stats, exact)
            if stall > 50:
                status = 2
                break
            if ev_kind >= 0:
                continue
        h, en_old = _next_h(en, en_old, h_acc, h, h_max)
    if paused > 0:
        _carry_out(carry, paused, N, n, t, h, en, en_old, h_acc, nsteps, nrej, nev, stall,
                   next_try, nhold, nramp, nrhs, kout, ev_kind, ev_i, spin, stuck, sgn,
                   in_contact, gs, lam, f0, next_etd, h_etd)
        stats[S_STATUS] = _RUNNING
        stats[S_STEPS] = nsteps
        stats[S_TFINAL] = t
        return
    carry[C_WHERE] = 0.0
    # fill any remaining outputs (t_end reached exactly)
    while kout < nout:
        for j in range(n):
            out_y[kout, j] = y[j]
        kout += 1
    stats[S_STATUS] = status
    stats[S_STEPS] = nsteps
    stats[S_REJECTED] = nrej
    stats[S_EVENTS] = nev
    stats[S_RHS] = nrhs
    stats[S_TFINAL] = t
    stats[S_HOLDS] = nhold
    stats[S_RAMPS] = nramp
