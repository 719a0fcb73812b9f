"""The pieces of one step of the ball kernel's integration loop (:func:`autobalance.core.
integrate._integrate`): the Dormand-Prince 5(4) step and its continuous extension, the event
functions and their location on the step's interpolant, the modes after an event, the arrival
at a closed-form hold, the step-size control and the carry of a paused run. References: Hairer,
Norsett, Wanner, Solving ODEs I, sec. II.4-II.6 (DOPRI5, step-size control, dense output and
event location); Leine, van Campen, van de Vrande, Nonlinear Dyn. 16 (1998) 41-54 (the switch
model's mode changes).
"""
from __future__ import annotations

import numpy as np

from .jit import inline_kernel, kernel
from .layout import (B_MUS, NR, C_EN, C_ENOLD, C_EVI, C_EVK, C_H, C_HACC, C_HETD, C_KOUT, C_NETD,
                     C_NEV, C_NEXT, C_NHOLD, C_NRAMP, C_NREJ, C_NRHS, C_NSTEPS, C_SPIN0, C_SPIN1,
                     C_STALL, C_T, C_WHERE, N_C, P_WHOLD, RunStatus, S_THOLD)
from .rhs import rhs


#: relative tolerance of the static friction limit: a stuck ball breaks away when the friction it
#: needs exceeds mu_s N R (1 + STICK_TOL); the same bound is used by the event function and by
#: the mode resolution, so a ball at the limit neither chatters nor stalls the integrator
STICK_TOL = 1e-9

#: largest creep of a stuck ball [rad] within one closed-form jump of a hold under the creep law
#: (P_FLAW = 2): the jump is cut into chunks, each advancing the balls at their creep speed at the
#: chunk's midpoint (docs/numerics/kernel.md, "The tanh law's slow manifold")
CREEP_CHUNK = 1e-5

#: event kinds of _event_g / _locate / _modes, and "no event"; numpy integers, not Python ones:
#: a Python constant passed to a kernel compiles a copy of it per value (core/jit.py)
SLIP_STOP, BREAKAWAY, NO_EVENT = np.int64(0), np.int64(1), np.int64(-1)

#: stats[S_STATUS] of a run paused by integrate_span
_RUNNING = float(RunStatus.RUNNING)

# Dormand-Prince 5(4) tableau
C2, C3, C4, C5 = 1 / 5, 3 / 10, 4 / 5, 8 / 9
A21 = 1 / 5
A31, A32 = 3 / 40, 9 / 40
A41, A42, A43 = 44 / 45, -56 / 15, 32 / 9
A51, A52, A53, A54 = 19372 / 6561, -25360 / 2187, 64448 / 6561, -212 / 729
A61, A62, A63, A64, A65 = 9017 / 3168, -355 / 33, 46732 / 5247, 49 / 176, -5103 / 18656
A71, A73, A74, A75, A76 = 35 / 384, 500 / 1113, 125 / 192, -2187 / 6784, 11 / 84
E1, E3, E4, E5, E6, E7 = 71 / 57600, -71 / 16695, 71 / 1920, -17253 / 339200, 22 / 525, -1 / 40
# DOPRI5's continuous extension of order 4 (Hairer, Norsett & Wanner I, II.6, code dopri5.f
# "contd5"; Shampine 1986)
D1, D3, D4 = -12715105075 / 11282082432, 87487479700 / 32700410799, -10690763975 / 1880347072
D5, D6, D7 = 701980252875 / 199316789632, -1453857185 / 822651844, 69997945 / 29380423


@inline_kernel
def _hermite(y0, f0, y1, f1, h, th, j):
    """Cubic Hermite interpolant of component j at fraction th of a step of size h."""
    th2 = th * th
    th3 = th2 * th
    h00 = 2 * th3 - 3 * th2 + 1
    h10 = th3 - 2 * th2 + th
    h01 = -2 * th3 + 3 * th2
    h11 = th3 - th2
    return h00 * y0[j] + h10 * h * f0[j] + h01 * y1[j] + h11 * h * f1[j]


@kernel
def _dense(y0, f0, y1, f1, K, h, th, out):
    """DOPRI5's continuous extension at fraction th of the accepted step of size h from y0
    (derivative f0, stages K[2..5], end y1 with FSAL derivative f1): order 4, no RHS
    evaluation (Hairer, Norsett & Wanner I, II.6, dopri5.f "contd5")."""
    for j in range(y0.shape[0]):
        yd = y1[j] - y0[j]
        bs = h * f0[j] - yd
        r5 = h * (D1 * f0[j] + D3 * K[2, j] + D4 * K[3, j] + D5 * K[4, j] + D6 * K[5, j]
                  + D7 * f1[j])
        out[j] = y0[j] + th * (yd + (1.0 - th) * (bs + th * ((yd - h * f1[j] - bs)
                                                           + (1.0 - th) * r5)))


@kernel
def _dopri_step(t, y, f0, h, P, B, N, seg, sched, md, K, ytmp, y1, f1, err, rw):
    """One DOPRI5 step; returns (ok); y1, f1 (FSAL) and the error vector err are filled."""
    n = y.shape[0]
    for j in range(n):
        ytmp[j] = y[j] + h * A21 * f0[j]
    ok = rhs(t + C2 * h, ytmp, P, B, N, seg, sched, md, K[1], rw)
    for j in range(n):
        ytmp[j] = y[j] + h * (A31 * f0[j] + A32 * K[1, j])
    ok &= rhs(t + C3 * h, ytmp, P, B, N, seg, sched, md, K[2], rw)
    for j in range(n):
        ytmp[j] = y[j] + h * (A41 * f0[j] + A42 * K[1, j] + A43 * K[2, j])
    ok &= rhs(t + C4 * h, ytmp, P, B, N, seg, sched, md, K[3], rw)
    for j in range(n):
        ytmp[j] = y[j] + h * (A51 * f0[j] + A52 * K[1, j] + A53 * K[2, j] + A54 * K[3, j])
    ok &= rhs(t + C5 * h, ytmp, P, B, N, seg, sched, md, K[4], rw)
    for j in range(n):
        ytmp[j] = y[j] + h * (A61 * f0[j] + A62 * K[1, j] + A63 * K[2, j] + A64 * K[3, j]
                              + A65 * K[4, j])
    ok &= rhs(t + h, ytmp, P, B, N, seg, sched, md, K[5], rw)
    for j in range(n):
        y1[j] = y[j] + h * (A71 * f0[j] + A73 * K[2, j] + A74 * K[3, j] + A75 * K[4, j]
                            + A76 * K[5, j])
    ok &= rhs(t + h, y1, P, B, N, seg, sched, md, f1, rw)
    for j in range(n):
        err[j] = h * (E1 * f0[j] + E3 * K[2, j] + E4 * K[3, j] + E5 * K[4, j] + E6 * K[5, j]
                      + E7 * f1[j])
    return ok


@kernel
def _resolve(t, y, P, B, N, seg, sched, md, f, rw):
    """Consistent stick/slip modes at a switching instant (a small friction complementarity
    problem solved by pivoting): release the stuck ball whose required friction exceeds its
    static limit by the largest ratio; re-stick a ball at zero relative speed whose
    acceleration opposes its assigned sliding direction (it cannot slide that way); repeat."""
    stuck, sgn, spin = md
    lam = rw[0]
    nq = N + NR + 1
    for _ in range(4 * N + 4):
        rhs(t, y, P, B, N, seg, sched, md, f, rw)
        worst = -1
        wr = 1.0
        for i in range(N):
            if stuck[i] == 1:
                lim = lam[N + i]
                need = abs(lam[i])
                if need > lim * (1.0 + STICK_TOL) + 1e-300:
                    r = need / lim if lim > 0.0 else 1e300
                    if r > wr:
                        wr = r
                        worst = i
        if worst >= 0:
            stuck[worst] = 0
            sgn[worst] = -1.0 if lam[worst] > 0.0 else 1.0
            continue
        back = -1
        for i in range(N):
            if (stuck[i] == 0 and B[i, B_MUS] > 0.0 and y[nq + NR + i] == 0.0
                    and sgn[i] * f[nq + NR + i] < 0.0):
                back = i
                break
        if back < 0:
            return
        stuck[back] = 1


@kernel
def _event_g(kind, i, th, t, h, y0, f0, y1, f1, ytmp, P, B, N, seg, sched, md, ftmp,
             rw):
    """Switching function of event (kind, i) at fraction th of the step."""
    stuck, sgn, spin = md
    lam = rw[0]
    nq = N + NR + 1
    if kind == 0:      # slipping ball stops
        return sgn[i] * _hermite(y0, f0, y1, f1, h, th, nq + NR + i)
    if kind == 2:      # driven spin reaches hold speed
        return P[P_WHOLD] - _hermite(y0, f0, y1, f1, h, th, 2 * nq - 1)
    for j in range(y0.shape[0]):   # stuck ball breaks away
        ytmp[j] = _hermite(y0, f0, y1, f1, h, th, j)
    rhs(t + th * h, ytmp, P, B, N, seg, sched, md, ftmp, rw)
    return lam[N + i] * (1.0 + STICK_TOL) - abs(lam[i])


@kernel
def _locate(kind, i, ga, gb, a_, t, h, y0, f0, y1, f1, ytmp, P, B, N, seg, sched, md,
            ftmp, rw):
    """Step fraction in (a_, 1] where the switching function (kind, i) crosses from g(a_) = ga
    > 0 to g(1) = gb <= 0 (Illinois method on the Hermite interpolant, 1e-7 in fraction).
    Returns (fraction, number of evaluations)."""
    b_ = 1.0
    side = 0
    nev = 0
    th = b_
    for _ in range(40):
        th = (a_ * gb - b_ * ga) / (gb - ga)
        gt = _event_g(kind, i, th, t, h, y0, f0, y1, f1, ytmp, P, B, N, seg, sched, md, ftmp, rw)
        nev += 1
        if gt > 0.0:
            a_ = th
            ga = gt
            if side == 1:
                gb *= 0.5
            side = 1
        else:
            b_ = th
            gb = gt
            if side == -1:
                ga *= 0.5
            side = -1
        if b_ - a_ < 1e-7 or gt == 0.0:
            break
    return b_, nev


@kernel
def _modes(ev_kind, ev_i, t, y, P, B, N, seg, sched, md, f0, rw, gs, stats, exact):
    """The modes after a step that ends in an event (``ev_kind`` of ball ``ev_i``) or at a
    profile knot, or after a closed-form jump (ev_kind -1, every ball stuck): the event's mode
    change, the balls that stopped within round-off, the constrained solve (f0, lam, stick
    margins gs). Returns the RHS evaluations it made."""
    stuck, sgn, spin = md
    lam = rw[0]
    nq = N + NR + 1
    v_ev = 0.0
    if ev_kind == 0:
        # the stop is located on the Hermite interpolant and the state comes from the continuous
        # extension, where the stopping ball's speed is zero to its accuracy, not exactly: a
        # ball in exactly its state (coincident balls) stops with it
        v_ev = y[nq + NR + ev_i]
        y[nq + NR + ev_i] = 0.0
        stuck[ev_i] = 1
    elif ev_kind == 1:
        stuck[ev_i] = 0
        sgn[ev_i] = -1.0 if lam[ev_i] > 0.0 else 1.0
    elif ev_kind == 2:
        spin[0] = 2.0
        spin[1] = y[2 * nq - 1]
        stats[S_THOLD] = t
    if exact:
        # any other slipping ball that stopped within round-off joins the stuck set
        for i in range(N):
            if stuck[i] == 0 and B[i, B_MUS] > 0.0 and (
                    sgn[i] * y[nq + NR + i] <= 0.0
                    or (y[nq + NR + i] == v_ev and sgn[i] == sgn[ev_i])):
                y[nq + NR + i] = 0.0
                stuck[i] = 1
        if ev_kind == 1:
            _resolve(t, y, P, B, N, seg, sched, md, f0, rw)
            # the released ball must stay released even if lambda is marginal now
            if stuck[ev_i] == 1:
                stuck[ev_i] = 0
                sgn[ev_i] = -1.0 if lam[ev_i] > 0.0 else 1.0
        _resolve(t, y, P, B, N, seg, sched, md, f0, rw)
        ne = N + 1
    else:
        rhs(t, y, P, B, N, seg, sched, md, f0, rw)
        ne = 1
    for i in range(N):
        gs[i] = lam[N + i] * (1.0 + STICK_TOL) - abs(lam[i])
    return ne


@kernel
def _hold_arrival(ib, t, y, P, B, N, seg, sched, md, f0, rw, gs):
    """The end of a hold solved until its first breakaway (ramp.hold_breakaway): ball ``ib``
    (>= 0) breaks away there and is released as the integrator releases it (ev_kind 1), then
    the constrained solve (f0, lam, stick margins gs). Returns the events (0 or 1)."""
    stuck, sgn, spin = md
    lam = rw[0]
    nev = 0
    if ib >= 0:
        rhs(t, y, P, B, N, seg, sched, md, f0, rw)
        nev = 1
        sgn[ib] = -1.0 if lam[ib] > 0.0 else 1.0
        _resolve(t, y, P, B, N, seg, sched, md, f0, rw)
        if stuck[ib] == 1:
            stuck[ib] = 0
            sgn[ib] = -1.0 if lam[ib] > 0.0 else 1.0
    _resolve(t, y, P, B, N, seg, sched, md, f0, rw)
    for i in range(N):
        gs[i] = lam[N + i] * (1.0 + STICK_TOL) - abs(lam[i])
    return nev


@inline_kernel
def _next_h(en, en_old, h_acc, h, h_max):
    """The next trial step and the controller's memory after an accepted step of error norm
    ``en``: PI step control (Hairer, Norsett, Wanner I, II.4, DOPRI5 code: beta = 0.04) keeps
    the step smooth where the stability boundary limits it."""
    en_c = max(en, 1e-10)
    fac = min(5.0, max(0.2, 0.9 * en_c ** -(0.2 - 0.75 * 0.04) * en_old ** 0.04))
    en_old = max(en_c, 1e-4)
    h = min(h_max, h_acc * fac if h_acc > 0.0 else h)
    if h <= 0.0:
        h = 1e-6
    return h, en_old


@kernel
def _carry_out(carry, where, N, n, t, h, en, en_old, h_acc, nsteps, nrej, nev, stall, next_try,
               nhold, nramp, nrhs, kout, ev_kind, ev_i, spin, stuck, sgn, in_contact, gs, lam,
               f0, next_etd, h_etd):
    """Store the loop's state of a run paused on arriving at a knot (layout.C_*)."""
    carry[C_WHERE] = where
    carry[C_T] = t
    carry[C_H] = h
    carry[C_EN] = en
    carry[C_ENOLD] = en_old
    carry[C_HACC] = h_acc
    carry[C_NSTEPS] = nsteps
    carry[C_NREJ] = nrej
    carry[C_NEV] = nev
    carry[C_STALL] = stall
    carry[C_NEXT] = next_try
    carry[C_NHOLD] = nhold
    carry[C_NRAMP] = nramp
    carry[C_NRHS] = nrhs
    carry[C_KOUT] = kout
    carry[C_SPIN0] = spin[0]
    carry[C_SPIN1] = spin[1]
    carry[C_EVK] = ev_kind
    carry[C_EVI] = ev_i
    carry[C_NETD] = next_etd
    carry[C_HETD] = h_etd
    k = N_C
    for i in range(N):
        carry[k + i] = stuck[i]
        carry[k + N + i] = sgn[i]
        carry[k + 2 * N + i] = in_contact[i]
        carry[k + 3 * N + i] = gs[i]
    k += 4 * N
    for i in range(3 * N + 1):
        carry[k + i] = lam[i]
    k += 3 * N + 1
    for j in range(n):
        carry[k + j] = f0[j]


@kernel
def _carry_in(carry, N, n, spin, stuck, sgn, in_contact, gs, lam, f0):
    """The loop's state of a paused run (the inverse of _carry_out): the per-ball flags, lam and
    f0 into their arrays, the scalars returned."""
    spin[0] = carry[C_SPIN0]
    spin[1] = carry[C_SPIN1]
    k = N_C
    for i in range(N):
        stuck[i] = int(carry[k + i])
        sgn[i] = carry[k + N + i]
        in_contact[i] = int(carry[k + 2 * N + i])
        gs[i] = carry[k + 3 * N + i]
    k += 4 * N
    for i in range(3 * N + 1):
        lam[i] = carry[k + i]
    k += 3 * N + 1
    for j in range(n):
        f0[j] = carry[k + j]
    return (carry[C_T], carry[C_H], carry[C_EN], carry[C_ENOLD], carry[C_HACC],
            int(carry[C_NSTEPS]), int(carry[C_NREJ]), int(carry[C_NEV]), int(carry[C_STALL]),
            int(carry[C_NEXT]), int(carry[C_NHOLD]), int(carry[C_NRAMP]), int(carry[C_NRHS]),
            int(carry[C_KOUT]), int(carry[C_EVK]), int(carry[C_EVI]), carry[C_NETD],
            carry[C_HETD])
