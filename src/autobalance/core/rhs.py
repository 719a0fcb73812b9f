"""Equations of motion of a rotor with an N-ball balancer, in the rotor-fixed frame.

Derivation: docs/model.md. Lagrange's equations in the coordinates q = (u, v, alpha_1..N, psi),
x + i y = (u + i v) e^{i psi}, written as M(q) q'' = f(q, q', t) + friction. They reduce to
000 eq (2)-(4) (constant speed, rho = 0, translate to the inertial frame), 000 eq (15)-(18)
(motor-driven spin), 000 eq (33)-(36) (race eccentricity rho, beta), 000 eq (50) (gravity on the
balls) and 004 eq (8)-(10) (Jeffcott rotor, isotropic suspension). Rolling resistance is Coulomb
(000 eq 20, 004 "mu F_n") with exact stick (switch model, Leine et al. 1998), the 004 tanh law,
or exact stick with stuck balls creeping along the tanh law's slow manifold (P_FLAW = 2;
:func:`creep_speed`, twin of autobalance.physics.friction.creep_speed).

Units: SI throughout ([m], [kg], [rad], [s], [N], [N*m]).

Size: ``rhs`` assembles the mass matrix, the force vector and the constraint rows of one
evaluation into preallocated work arrays, in parts inlined into it at numba IR level
(:func:`autobalance.core.jit.inline_kernel`: no call, no exploded array structs): the balls'
rows (``_ball_rows``), their contacts (``_contacts``) and the solve for a prescribed or a
motor-driven spin (``_solve_prescribed``, ``_solve_driven``). The split changed no bit of any
result (nine runs' full histories compared: TSR with stick, tanh and creep, three balls,
motor drive with gravity, the washer with dry friction, the examples).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from .jit import inline_kernel, kernel
from .layout import (B_CC, B_D, B_I, B_KC, B_M, B_MU, B_MUS, B_RR, NR, P_BAX, P_BAY, P_BETA, P_BPX,
                     P_BPY, P_BW, P_BZ, P_CPHI, P_CX, P_CY, P_DELTA, P_FDRY, P_FLAW, P_G, P_GDIR,
                     P_GDRY, P_KX, P_KY, P_LAW, P_LQDX, P_LQDY, P_LQI, P_LQT, P_LQX, P_LQY,
                     P_MT, P_NMODEL, P_R, P_RHO, P_T0, P_VDRY, P_VSAT, P_WF, P_ISO)

if TYPE_CHECKING:
    import numpy as np


#: |lambda| / (mu N R) is clipped to this below 1 in the creep law: at the limit the slow
#: manifold ends (the ball slips) and atanh diverges; atanh(1 - 1e-12) = 14.2.
CREEP_RATIO_MAX = 1.0 - 1e-12


@kernel
def creep_speed(lam: float, lim: float, vsat: float) -> float:
    """Creep of a stuck ball on the tanh law's slow manifold, -v_sat atanh(lam / lim) [rad/s]
    (compiled twin of autobalance.physics.friction.creep_speed): lam the friction torque the
    ball needs [N*m], lim = mu N R [N*m], vsat [rad/s]."""
    if lim <= 0.0:
        return 0.0
    r = lam / lim
    if r > CREEP_RATIO_MAX:
        r = CREEP_RATIO_MAX
    elif r < -CREEP_RATIO_MAX:
        r = -CREEP_RATIO_MAX
    return -vsat * math.atanh(r)


@kernel
def profile_eval(t: float, seg: int, prof_t: np.ndarray,
                 prof_w: np.ndarray) -> tuple[float, float]:
    """Speed [rad/s] and acceleration [rad/s^2] of a piecewise-linear profile on segment seg."""
    n = prof_t.shape[0]
    if seg >= n - 1:
        return prof_w[n - 1], 0.0
    t0 = prof_t[seg]
    t1 = prof_t[seg + 1]
    slope = (prof_w[seg + 1] - prof_w[seg]) / (t1 - t0)
    return prof_w[seg] + slope * (t - t0), slope


@kernel
def profile_segment(t: float, prof_t: np.ndarray) -> int:
    """Index k of the segment with prof_t[k] <= t < prof_t[k+1] (last knot -> n-1)."""
    n = prof_t.shape[0]
    k = 0
    while k < n - 1 and t >= prof_t[k + 1]:
        k += 1
    return k


@kernel
def table_interp(t: float, tt: np.ndarray, vv: np.ndarray) -> float:
    """Linear interpolation in a short table, held constant outside."""
    n = tt.shape[0]
    if n == 1 or t <= tt[0]:
        return vv[0]
    if t >= tt[n - 1]:
        return vv[n - 1]
    k = 0
    while t >= tt[k + 1]:
        k += 1
    a = (t - tt[k]) / (tt[k + 1] - tt[k])
    return vv[k] + a * (vv[k + 1] - vv[k])


@kernel
def motor_torque(law: float, t0: float, wf: float, w: float) -> float:
    """000 Table 1 torque laws T_m(w) [N*m]: constant, linear T0(1 - w/w_f), harmonic."""
    if law == 0:
        return t0
    if law == 1:
        return t0 * (1.0 - w / wf)
    return t0 * (1.0 - math.sin(0.5 * math.pi * w / wf))


@kernel
def neighbour_gap(y: np.ndarray, i: int, N: int, delta: float) -> tuple[int, float]:
    """Next ball j after ball i (cyclic order) and their free angular gap beyond the contact
    angle delta [rad]; negative = overlap (balls in one race keep their order)."""
    j = i + 1
    wrap = 0.0
    if j == N:
        j = 0
        wrap = 2.0 * math.pi
    return j, y[NR + j] + wrap - y[NR + i] - delta


@kernel
def cholesky_solve(A: np.ndarray, b: np.ndarray, n: int) -> bool:
    """Solve A x = b in place (x returned in b) for the leading n x n SPD block of A."""
    for j in range(n):
        s = A[j, j]
        for k in range(j):
            s -= A[j, k] * A[j, k]
        if s <= 0.0:
            return False
        d = math.sqrt(s)
        A[j, j] = d
        for i in range(j + 1, n):
            s = A[i, j]
            for k in range(j):
                s -= A[i, k] * A[j, k]
            A[i, j] = s / d
    for i in range(n):
        s = b[i]
        for k in range(i):
            s -= A[i, k] * b[k]
        b[i] = s / A[i, i]
    for i in range(n - 1, -1, -1):
        s = b[i]
        for k in range(i + 1, n):
            s -= A[k, i] * b[k]
        b[i] = s / A[i, i]
    return True


@kernel
def _suspension_force(t, u, v, ud, vd, psi, psid, P):
    """Suspension force (000 eq 2-3, 48: anisotropic springs and dampers, base motion, dry
    friction of two dampers at +-gamma) in the inertial frame, rotated to the rotor frame [N]."""
    cp = math.cos(psi)
    sp = math.sin(psi)
    x = u * cp - v * sp
    yy = u * sp + v * cp
    wr = ud - psid * v
    wi = vd + psid * u
    xd = wr * cp - wi * sp
    yd = wr * sp + wi * cp
    xb = 0.0
    yb = 0.0
    xbd = 0.0
    ybd = 0.0
    if P[P_BW] > 0.0:
        wb = P[P_BW]
        xb = P[P_BAX] * math.cos(wb * t + P[P_BPX])
        yb = P[P_BAY] * math.cos(wb * t + P[P_BPY])
        xbd = -P[P_BAX] * wb * math.sin(wb * t + P[P_BPX])
        ybd = -P[P_BAY] * wb * math.sin(wb * t + P[P_BPY])
    Fx = -P[P_KX] * (x - xb) - P[P_CX] * (xd - xbd)
    Fy = -P[P_KY] * (yy - yb) - P[P_CY] * (yd - ybd)
    if P[P_FDRY] > 0.0:
        cg = math.cos(P[P_GDRY])
        sg = math.sin(P[P_GDRY])
        for side in (-1.0, 1.0):
            vs = cg * xd + side * sg * yd
            ff = -P[P_FDRY] * math.tanh(vs / P[P_VDRY])
            Fx += ff * cg
            Fy += ff * side * sg
    return Fx * cp + Fy * sp, -Fx * sp + Fy * cp


@kernel
def rhs(t: float, y: np.ndarray, P: np.ndarray, B: np.ndarray, N: int, seg: int, sched: tuple,
        md: tuple, dy: np.ndarray, rw: tuple) -> bool:
    """Time derivative dy of the state y; also the friction bookkeeping in lam.

    Parameters
    ----------
    t : float
        Time [s].
    y : ndarray (2*nq,)
        State (layout.py).
    P, B : ndarray
        Scalar and per-ball parameters (layout.py), SI.
    seg : int
        Segment of the speed profile the current step lies in.
    sched : tuple
        The prescribed schedules (prof_t, prof_w, unb_t, unb_u): the speed profile's knots [s]
        and speeds [rad/s], the unbalance table's times [s] and values [kg*m].
    md : tuple
        The modes (stuck, sgn, spin) of :func:`autobalance.core.work.ball_work`: stuck int
        (N,), 1 if ball i is stuck to the race (alpha_i'' = 0, friction from the constraint);
        sgn (N,), the direction of sliding of a slipping ball (+1/-1), which kinetic friction
        opposes; spin (2,), spin[0] 0 a prescribed profile, 1 motor-driven, 2 held at the
        constant speed spin[1] [rad/s].
    dy : ndarray (2*nq,)
        Output derivative.
    rw : tuple
        The work arrays (lam, Mm, fv, A, bb, idx, trig) of :func:`autobalance.core.work.
        rhs_work`. Output in lam: lam[i] = friction torque a stuck ball needs [N*m];
        lam[N+i] = static limit mu_s*N_i*R [N*m]; lam[2N+i] = normal force N_i [N]. trig
        caches (alpha_i, cos alpha_i, sin alpha_i) across calls, NaN-initialised: a stuck ball
        keeps its angle bit for bit through the stages of a step, so its cos/sin are reused
        (values identical to recomputing them).

    Returns
    -------
    ok : bool
        False if the mass matrix is not positive definite (non-physical parameters).
    """
    stuck, sgn, spin = md
    prof_t, prof_w, unb_t, unb_u = sched
    lam, Mm, fv, A, bb, idx, trig = rw
    nq = N + NR + 1
    ip = nq - 1
    u = y[0]
    v = y[1]
    psi = y[ip]
    ud = y[nq]
    vd = y[nq + 1]
    R = P[P_R]
    Mt = P[P_MT]
    rho = P[P_RHO]
    beta = P[P_BETA]
    U = table_interp(t, unb_t, unb_u)

    mode = spin[0]
    if mode == 0.0:
        psid, psidd = profile_eval(t, seg, prof_t, prof_w)
    elif mode == 2.0:
        psid = spin[1]
        psidd = 0.0
    else:
        psid = y[2 * nq - 1]
        psidd = 0.0
    if P[P_ISO] == 1.0:
        # isotropic suspension in the rotor frame: F = -k w - c (w' + i psi' w)  (004 eq 8-9)
        Fu = -P[P_KX] * u - P[P_CX] * (ud - psid * v)
        Fv = -P[P_KX] * v - P[P_CX] * (vd + psid * u)
    else:
        Fu, Fv = _suspension_force(t, u, v, ud, vd, psi, psid, P)


    cb = 0.0       # every use of cos/sin(beta) is multiplied by rho
    sb = 0.0
    if rho != 0.0:
        cb = math.cos(beta)
        sb = math.sin(beta)
    driven = mode == 1.0
    for i in range(nq):
        fv[i] = 0.0
    for i in range(N):       # ball-ball entries of the mass matrix are zero
        for j in range(N):
            Mm[NR + i, NR + j] = 0.0

    a_u = 2.0 * psid * vd + psid * psid * u       # -(Re of velocity part of rotated accel.)
    a_v = 2.0 * psid * ud - psid * psid * v       # +(Im of velocity part of rotated accel.)
    # psi row, old (inertial) form: accumulated below
    Mpp = P[P_BZ] + U * u
    fpp = -U * a_v
    Sm, SmS, SmC, cent_u, cent_v, Mpp, fpp = _ball_rows(y, P, B, N, stuck, sgn, lam, Mm, fv,
                                                        trig, psi, psid, a_u, a_v, cb, sb,
                                                        driven, Mpp, fpp)
    _contacts(y, P, B, N, fv)

    # translational rows (000 eq 2-3/16-17/34-35, 004 eq 8-9 in the rotor frame)
    Mm[0, 0] = Mt
    Mm[1, 1] = Mt
    for i in range(N):
        Mm[0, NR + i] = Mm[NR + i, 0]
        Mm[1, NR + i] = Mm[NR + i, 1]
    Mm[0, ip] = -Mt * v - Sm * rho * sb - R * SmS
    Mm[1, ip] = Mt * u + U + Sm * rho * cb + R * SmC
    fv[0] = Fu + Mt * a_u + U * psid * psid + Sm * rho * psid * psid * cb + R * cent_u
    fv[1] = Fv - Mt * a_v + Sm * rho * psid * psid * sb + R * cent_v
    lqx = P[P_LQX]
    lqy = P[P_LQY]
    lqdx = P[P_LQDX]
    lqdy = P[P_LQDY]
    if lqx != 0.0 or lqy != 0.0 or lqdx != 0.0 or lqdy != 0.0:
        # a liquid beside the balls (core/hybrid.py, prescribed spin): its moment U and rate U'
        # frozen over the coupling step pull the chamber with W^2 U - i W' U - 2 i W U' (the
        # rotor-frame inertia of U with U'' = 0; the Z'' equation of shallow_water.sw_coupled)
        fv[0] += psid * psid * lqx + psidd * lqy + 2.0 * psid * lqdy
        fv[1] += psid * psid * lqy - psidd * lqx - 2.0 * psid * lqdx

    if not driven:
        return _solve_prescribed(y, P, N, stuck, Mm, fv, dy, lam, bb, B, psid, psidd)
    # a motor-driven spin beside a liquid (docs/liquid/balls-beside-liquid.md sec. 3i): -i psi'' U
    # joins M (the translational rows here, the psi row in _solve_driven); the psi row gains the
    # films' second moment I_c, Re(conj(U) w) and Im(conj(U) a), a the velocity part of the
    # rotor-frame acceleration, and their held torque (0 without a liquid: no bit changes)
    Mm[0, ip] -= lqy
    Mm[1, ip] += lqx
    Mpp += P[P_LQI] + lqx * u + lqy * v
    fpp += P[P_LQT] - (lqx * a_v + lqy * a_u)
    return _solve_driven(y, P, B, N, stuck, Mm, fv, dy, lam, bb, A, idx, psid, U, Sm, SmS, SmC,
                         cb, sb, Mpp, fpp)


@inline_kernel
def _ball_rows(y: np.ndarray, P: np.ndarray, B: np.ndarray, N: int, stuck: np.ndarray,
               sgn: np.ndarray, lam: np.ndarray, Mm: np.ndarray, fv: np.ndarray,
               trig: np.ndarray, psi: float, psid: float, a_u: float, a_v: float,
               cb: float, sb: float, driven: bool, Mpp: float,
               fpp: float) -> tuple[float, float, float, float, float, float, float]:
    """The balls' rows of M and f (Lagrange in alpha_i), their normal forces and friction
    limits into lam, and (motor-driven spin) their share of the psi row; returns the sums
    (sum m, sum m sin a, sum m cos a, centrifugal u and v sums, M_psipsi, f_psi) the rotor's
    rows need. Part of :func:`rhs` (inlined; see there for the arguments)."""
    nq = N + NR + 1
    ip = nq - 1
    u = y[0]
    v = y[1]
    R = P[P_R]
    rho = P[P_RHO]
    beta = P[P_BETA]
    g = P[P_G]
    gdir = P[P_GDIR]
    has_g = g > 0.0
    Sm = 0.0
    SmS = 0.0
    SmC = 0.0
    cent_u = 0.0
    cent_v = 0.0
    for i in range(N):
        a = y[NR + i]
        ad = y[nq + NR + i]
        m = B[i, B_M]
        Ii = B[i, B_I]
        rr = B[i, B_RR]
        if a == trig[i]:
            c = trig[N + i]
            s = trig[2 * N + i]
        else:
            c = math.cos(a)
            s = math.sin(a)
            trig[i] = a
            trig[N + i] = c
            trig[2 * N + i] = s
        thd = psid + ad
        th = psi + a
        Sm += m
        SmS += m * s
        SmC += m * c
        cent_u += m * thd * thd * c
        cent_v += m * thd * thd * s
        k = NR + i
        # ball row (Lagrange in alpha_i; 000 eq 4/18/36/50, 004 eq 10)
        Mm[k, 0] = -m * R * s
        Mm[k, 1] = m * R * c
        Mm[k, k] = m * R * R + Ii * rr * rr
        cab = 0.0
        sab = 0.0
        if rho != 0.0:
            cab = math.cos(a - beta)
            sab = math.sin(a - beta)
        Mm[k, ip] = m * R * (u * c + v * s) + m * R * R - Ii * rr + m * R * rho * cab
        fk = -m * R * (s * a_u + c * a_v) - m * R * rho * psid * psid * sab
        fk -= B[i, B_D] * ad
        sthg = 0.0
        cthg = 0.0
        if has_g:
            sthg = math.sin(th - gdir)
            cthg = math.cos(th - gdir)
        # gravity, tangential to the race: m R g.e_t (000 eq 50, 004 eq 10)
        fk -= m * R * g * sthg
        # normal force of the race on the ball
        if P[P_NMODEL] == 0.0:
            nf = m * (R * thd * thd + g * cthg)
        else:
            nf = m * R * psid * psid
        if nf < 0.0:
            nf = 0.0
        lam[2 * N + i] = nf
        lam[N + i] = B[i, B_MUS] * nf * R
        lam[i] = 0.0
        if P[P_FLAW] == 1.0:
            fk -= B[i, B_MU] * nf * R * math.tanh(ad / P[P_VSAT])
        elif stuck[i] == 0:
            fk -= sgn[i] * B[i, B_MU] * nf * R
        fv[k] = fk
        if driven:
            # psi row contributions (old form), see docs/model.md
            tb = sb * a_u + cb * a_v
            ta = s * a_u + c * a_v
            Mm[ip, k] = m * rho * R * cab + m * R * R - Ii * rr
            Mpp += m * (rho * (v * sb + u * cb) + rho * rho + 2.0 * rho * R * cab
                        + R * (v * s + u * c) + R * R) + Ii
            fpp -= m * (rho * (tb - R * thd * thd * sab) + R * (ta + rho * psid * psid * sab))
            if has_g:
                fpp -= m * g * (rho * math.sin(psi + beta - gdir) + R * sthg)
    return Sm, SmS, SmC, cent_u, cent_v, Mpp, fpp


@inline_kernel
def _contacts(y: np.ndarray, P: np.ndarray, B: np.ndarray, N: int, fv: np.ndarray) -> None:
    """Ball-ball contact forces into fv. Part of :func:`rhs` (inlined)."""
    nq = N + NR + 1
    # ball-ball contact: compliant spring-dashpot between neighbours (order preserved)
    if N > 1:
        for i in range(N):
            j, gap = neighbour_gap(y, i, N, P[P_DELTA])
            if gap < 0.0:
                pen_rate = y[nq + NR + i] - y[nq + NR + j]
                fc = B[i, B_KC] * (-gap) + B[i, B_CC] * pen_rate
                if fc > 0.0:
                    fv[NR + j] += fc
                    fv[NR + i] -= fc


@inline_kernel
def _solve_prescribed(y: np.ndarray, P: np.ndarray, N: int, stuck: np.ndarray, Mm: np.ndarray,
                      fv: np.ndarray, dy: np.ndarray, lam: np.ndarray, bb: np.ndarray,
                      B: np.ndarray, psid: float, psidd: float) -> bool:
    """dy for a prescribed spin (the 2x2 Schur complement below); lam of the stuck balls.
    Part of :func:`rhs` (inlined)."""
    nq = N + NR + 1
    ip = nq - 1
    R = P[P_R]
    Mt = P[P_MT]
    # Prescribed spin (psi'' = psidd known). The balls couple only to the rotor: ball row
    # k = NR + i reads b_i . (u'', v'') + J_i alpha_i'' = g_i, b_i = (M[k,0], M[k,1]),
    # J_i = M[k,k] (constant), g_i = f_k - M[k,psi] psidd. Eliminating the free balls'
    # alpha_i'' leaves the 2x2 Schur complement S = M_t I - sum b_i b_i^T / J_i for
    # x = (u'', v''); then alpha_i'' = (g_i - b_i . x) / J_i. The reduced mass matrix is
    # positive definite iff every J_i > 0 and S is (ok). bb holds 1/J_i.
    fric = P[P_FLAW] == 1.0
    creep = P[P_FLAW] == 2.0
    s00 = Mt
    s11 = Mt
    s01 = 0.0
    r0 = fv[0] - Mm[0, ip] * psidd
    r1 = fv[1] - Mm[1, ip] * psidd
    ok = Mt > 0.0
    for i in range(N):
        if fric or stuck[i] == 0:
            k = NR + i
            J = Mm[k, k]
            if J <= 0.0:
                ok = False
                continue
            iJ = 1.0 / J
            bb[i] = iJ
            b0 = Mm[k, 0]
            b1 = Mm[k, 1]
            gJ = (fv[k] - Mm[k, ip] * psidd) * iJ
            s00 -= b0 * b0 * iJ
            s11 -= b1 * b1 * iJ
            s01 -= b0 * b1 * iJ
            r0 -= b0 * gJ
            r1 -= b1 * gJ
    det = s00 * s11 - s01 * s01
    if not ok or s00 <= 0.0 or det <= 0.0:
        ok = False
        x0 = math.nan
        x1 = math.nan
    else:
        idet = 1.0 / det
        x0 = (s11 * r0 - s01 * r1) * idet
        x1 = (s00 * r1 - s01 * r0) * idet
    for j in range(nq):
        dy[j] = y[nq + j]
    dy[nq] = x0
    dy[nq + 1] = x1
    for i in range(N):
        k = NR + i
        if fric or stuck[i] == 0:
            dy[nq + k] = (fv[k] - Mm[k, ip] * psidd - Mm[k, 0] * x0 - Mm[k, 1] * x1) * bb[i]
        else:
            # required friction of a stuck ball: lam_i = M[k,:] q'' - f_k
            lam[i] = -fv[k] + Mm[k, 0] * x0 + Mm[k, 1] * x1 + Mm[k, ip] * psidd
            dy[k] = 0.0
            if creep:
                dy[k] = creep_speed(lam[i], B[i, B_MU] * lam[2 * N + i] * R, P[P_VSAT])
            dy[nq + k] = 0.0
    dy[nq + ip] = psidd
    dy[ip] = psid
    return ok


@inline_kernel
def _solve_driven(y: np.ndarray, P: np.ndarray, B: np.ndarray, N: int, stuck: np.ndarray,
                  Mm: np.ndarray, fv: np.ndarray, dy: np.ndarray, lam: np.ndarray,
                  bb: np.ndarray, A: np.ndarray, idx: np.ndarray, psid: float, U: float,
                  Sm: float, SmS: float, SmC: float, cb: float, sb: float, Mpp: float,
                  fpp: float) -> bool:
    """dy for a motor-driven spin (Cholesky solve of the free unknowns); lam of the stuck
    balls. Part of :func:`rhs` (inlined)."""
    nq = N + NR + 1
    ip = nq - 1
    u = y[0]
    v = y[1]
    psi = y[ip]
    R = P[P_R]
    rho = P[P_RHO]
    g = P[P_G]
    gdir = P[P_GDIR]
    has_g = g > 0.0
    # motor-driven spin: general solve of the free unknowns u'', v'', alpha'' of slipping
    # balls and psi''
    nf_ = 0
    idx[nf_] = 0
    nf_ += 1
    idx[nf_] = 1
    nf_ += 1
    for i in range(N):
        if P[P_FLAW] == 1.0 or stuck[i] == 0:
            idx[nf_] = NR + i
            nf_ += 1
    # psi row = old psi row + u*(v row) - v*(u row)  (coordinate change, docs/model.md)
    Mm[ip, 0] = -Sm * rho * sb - R * SmS - P[P_LQY]      # (+ the liquid's held moment)
    Mm[ip, 1] = U + Sm * rho * cb + R * SmC + P[P_LQX]
    Mm[ip, ip] = Mpp
    fpp += motor_torque(P[P_LAW], P[P_T0], P[P_WF], psid) - P[P_CPHI] * psid
    if has_g:
        sg = math.sin(psi - gdir)
        fpp -= g * U * sg
        if P[P_LQX] != 0.0 or P[P_LQY] != 0.0:
            # and on a liquid's held moment U_L beside the balls (core/hybrid.py; a horizontal
            # axis): -g Im(U_L e^(i(psi - gdir))), as on the unbalance
            # (docs/liquid/balls-beside-liquid.md sec. 3i)
            fpp -= g * (P[P_LQX] * sg + P[P_LQY] * math.cos(psi - gdir))
    for j in range(nq):
        Mm[ip, j] += u * Mm[1, j] - v * Mm[0, j]
    fv[ip] = fpp + u * fv[1] - v * fv[0]
    idx[nf_] = ip
    nf_ += 1
    for a_ in range(nf_):
        ia = idx[a_]
        bb[a_] = fv[ia]
        for b_ in range(nf_):
            A[a_, b_] = Mm[ia, idx[b_]]
    ok = cholesky_solve(A, bb, nf_)

    for j in range(nq):
        dy[j] = y[nq + j]
        dy[nq + j] = 0.0
    for a_ in range(nf_):
        dy[nq + idx[a_]] = bb[a_]
    # required friction of stuck balls: lam_i = M[k,:] q'' - f_k
    if P[P_FLAW] != 1.0:
        for i in range(N):
            if stuck[i] == 1:
                k = NR + i
                s_ = -fv[k]
                for j in range(nq):
                    s_ += Mm[k, j] * dy[nq + j]
                lam[i] = s_
                dy[k] = 0.0
                if P[P_FLAW] == 2.0:
                    dy[k] = creep_speed(s_, B[i, B_MU] * lam[2 * N + i] * R, P[P_VSAT])
    return ok
