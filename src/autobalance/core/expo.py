"""Exponential integration of slipping phases (docs/numerics/exponential-slip.md, "An
exponential integrator for the slipping phases").

Used by ``integrate`` as the slip jump (``slip_window``, under the conditions of
``simulate.pack.fast_paths``); ``etd_window`` takes constant steps over an event-free window of a
run, for ``benchmarks/slip_etd_bench.py``.

The stiffness of 004's rig in the rotor frame lives in the coupled rotor-ball dynamics (rotor
modes at omega_n +- Omega, up to ~1640 1/s). DOPRI5 then steps at its stability limit (~2 ms)
while a ball slips. Here the state, extended by the time, z = (y, t), obeys z' = F(z). It is
split as F(z) = L z + (F(z) - L z), with L the Jacobian of F at the window's start (finite
differences) and the remainder non-stiff as long as the Jacobian changes little. The explicit
exponential Runge-Kutta method of Hochbruck & Ostermann (2005, SIAM J. Numer. Anal. 43,
1069-1090, eq. (5.19), "ETDRK4-B"; stiff order 4 for any fixed L) then integrates the linear
part exactly:

    U_i = e^{c_i h L} z + h sum_j a_ij(h L) G_j,    G_j = F(U_j) - L U_j,
    z_new = e^{h L} z + h sum_i b_i(h L) G_i

with c = (0, 1/2, 1/2, 1, 1/2) and the coefficients a_ij, b_i built from the phi functions
phi_k(z) = sum_j z^j / (j + k)! at c_i h L, computed by scaling and squaring (core/phi.py;
Skaflestad & Wright 2009, Appl. Numer. Math. 59, 783-799).
"""
from __future__ import annotations

import math

import numpy as np
from numba import njit

from .dense import matvec_add as _matvec_add
from .jit import kernel
from .layout import B_KC, P_DELTA
from .phi import K_PHI, phi_double, phi_functions
from .rhs import neighbour_gap, profile_eval, profile_segment, rhs
from .work import ball_work


@kernel
def _to_state(z, y, n):
    """The rotor's and the balls' coordinates and rates of z into the kernel's state y."""
    nq = n // 2
    for i in range(nq - 1):
        y[i] = z[i]
        y[nq + i] = z[nq - 1 + i]


@kernel
def _F(z, n, P, B, N, sched, md, out, yw, fw, rw):
    """F(z) of the method's state z (``etd_window``): the right-hand side of the run with its
    modes, without the spin's rows (prescribed), and dt/dt = 1. yw, fw: work (n,)."""
    prof_t, prof_w, unb_t, unb_u = sched
    nq = n // 2
    m = n - 1
    t = z[m - 1]
    _to_state(z, yw, n)
    yw[nq - 1] = z[m]          # psi and psi' ride along; the prescribed spin uses the profile
    yw[n - 1] = z[m + 1]
    seg = profile_segment(t, prof_t)
    rhs(t, yw, P, B, N, seg, sched, md, fw, rw)
    for i in range(nq - 1):
        out[i] = fw[i]
        out[nq - 1 + i] = fw[nq + i]
    out[m - 1] = 1.0


@kernel
def jacobian(z: np.ndarray, n: int, P: np.ndarray, B: np.ndarray, N: int, sched: tuple,
             md: tuple, scale: np.ndarray, L: np.ndarray,
             f0: np.ndarray, f1: np.ndarray, zt: np.ndarray, yw: np.ndarray, fw: np.ndarray,
             rw: tuple) -> None:
    """L = dF/dz (m = n - 1 components of z: ``etd_window``) by forward differences, column j
    with the increment 1.5e-8 max(|z_j|, scale[j]) (scale: each component's typical magnitude).
    Any L serves the method (its order holds for every fixed L); a good one makes the remainder
    small."""
    m = n - 1
    _F(z, n, P, B, N, sched, md, f0, yw, fw, rw)
    for i in range(m + 2):
        zt[i] = z[i]
    for j in range(m):
        d = 1.5e-8 * max(scale[j], abs(z[j]))
        zt[j] = z[j] + d
        _F(zt, n, P, B, N, sched, md, f1, yw, fw, rw)
        zt[j] = z[j]
        for i in range(m):
            L[i, j] = (f1[i] - f0[i]) / d


@kernel
def _stage(U, n, L, Gi, P, B, N, sched, md, fz, yw, fw, rw):
    """Gi = F(U) - L U, Gi a row of the stages' G (fz: work). The row, not G and its index: an
    index passed as a constant would compile a copy per stage (core/jit.py)."""
    m = n - 1
    _F(U, n, P, B, N, sched, md, fz, yw, fw, rw)
    for r in range(m):
        Gi[r] = fz[r]
    _matvec_add(L, U, Gi, m, -1.0, True)      # fz - L U, each row's sum as before


@kernel
def etd_step(z: np.ndarray, h: float, n: int, L: np.ndarray, Ph: np.ndarray, Pf: np.ndarray,
             P: np.ndarray, B: np.ndarray, N: int, sched: tuple, md: tuple, G: np.ndarray,
             U: np.ndarray, fz: np.ndarray, yw: np.ndarray, fw: np.ndarray, rw: tuple,
             V: np.ndarray, W: np.ndarray, X: np.ndarray) -> None:
    """One ETDRK4-B step of size h [s] on the method's state z in place (module docstring;
    layout: ``etd_window``). Ph, Pf: phi_0..3 of h L / 2 and h L (phi_functions of h L); G
    (5, n - 1), U (n + 1,), fz, V, W, X (n - 1,), yw, fw (n,) work arrays. The terms the stages
    share are formed once (V = U2 starts U3 and U5, W starts U4 and z_new) and each phi meets
    one combination of the G's: 17 products with a matrix per step."""
    m = n - 1
    U[m] = z[m]                 # psi and psi' of the stages: not used by the rotor frame's rhs
    U[m + 1] = z[m + 1]
    for r in range(m):
        U[r] = z[r]
    _stage(U, n, L, G[0], P, B, N, sched, md, fz, yw, fw, rw)
    # U2 = e^{hL/2} z + h/2 phi1(hL/2) G1
    _matvec_add(Ph[0], z, V, m, 1.0, False)
    _matvec_add(Ph[1], G[0], V, m, 0.5 * h, True)
    for r in range(m):
        U[r] = V[r]
    _stage(U, n, L, G[1], P, B, N, sched, md, fz, yw, fw, rw)
    # U3 = e^{hL/2} z + h [(phi1/2 - phi2)(hL/2) G1 + phi2(hL/2) G2] = U2 + h phi2(hL/2) (G2 - G1)
    for r in range(m):
        U[r] = V[r]
        X[r] = G[1, r] - G[0, r]
    _matvec_add(Ph[2], X, U, m, h, True)
    _stage(U, n, L, G[2], P, B, N, sched, md, fz, yw, fw, rw)
    # U4 = e^{hL} z + h [(phi1 - 2 phi2)(hL) G1 + phi2(hL) (G2 + G3)]
    #    = W + h phi2(hL) (G2 + G3 - 2 G1),  W = e^{hL} z + h phi1(hL) G1
    _matvec_add(Pf[0], z, W, m, 1.0, False)
    _matvec_add(Pf[1], G[0], W, m, h, True)
    for r in range(m):
        U[r] = W[r]
        X[r] = G[1, r] + G[2, r] - 2.0 * G[0, r]
    _matvec_add(Pf[2], X, U, m, h, True)
    _stage(U, n, L, G[3], P, B, N, sched, md, fz, yw, fw, rw)
    # U5 = e^{hL/2} z + h [a51 G1 + a52 (G2 + G3) + a54 G4] with
    # a52 = phi2(hL/2)/2 - phi3(hL) + phi2(hL)/4 - phi3(hL/2)/2, a54 = phi2(hL/2)/4 - a52,
    # a51 = phi1(hL/2)/2 - 2 a52 - a54 = phi1(hL/2)/2 - a52 - phi2(hL/2)/4; with
    # d = G2 + G3 - G1 - G4: U5 = U2 + h [phi2(hL/2) ((G4 - G1)/4 + d/2) + phi2(hL) d/4
    # - phi3(hL) d - phi3(hL/2) d/2]
    for r in range(m):
        U[r] = V[r]
        fz[r] = G[1, r] + G[2, r] - G[0, r] - G[3, r]
        X[r] = 0.25 * (G[3, r] - G[0, r]) + 0.5 * fz[r]
    _matvec_add(Ph[2], X, U, m, h, True)
    _matvec_add(Pf[2], fz, U, m, 0.25 * h, True)
    _matvec_add(Pf[3], fz, U, m, -h, True)
    _matvec_add(Ph[3], fz, U, m, -0.5 * h, True)
    _stage(U, n, L, G[4], P, B, N, sched, md, fz, yw, fw, rw)
    # z_new = e^{hL} z + h [(phi1 - 3 phi2 + 4 phi3) G1 + (4 phi3 - phi2) G4 + (4 phi2 - 8 phi3) G5]
    #       = W + h phi2(hL) (4 G5 - 3 G1 - G4) + h phi3(hL) (4 G1 + 4 G4 - 8 G5)
    for r in range(m):
        U[r] = W[r]
        fz[r] = -3.0 * G[0, r] - G[3, r] + 4.0 * G[4, r]
        X[r] = 4.0 * G[0, r] + 4.0 * G[3, r] - 8.0 * G[4, r]
    _matvec_add(Pf[2], fz, U, m, h, True)
    _matvec_add(Pf[3], X, U, m, h, True)
    for r in range(m):
        z[r] = U[r]


#: Longest window of one slip jump [s] (integrate.py): the Jacobian is refreshed every
#: REFRESH steps inside it.
SLIP_WINDOW = 0.5
#: Steps between refreshes of L [-] (on whole runs 20 was as accurate as 10 and a little
#: faster; the window benchmark's etd_window takes its own).
REFRESH = 20


@kernel
def _pack(y, t, z, n):
    """z = (u, v, alpha_i, their rates, t, psi, psi') from the kernel's state y at t."""
    nq = n // 2
    m = n - 1
    for i in range(nq - 1):
        z[i] = y[i]
        z[nq - 1 + i] = y[nq + i]
    z[m - 1] = t
    z[m] = y[nq - 1]
    z[m + 1] = y[n - 1]


@kernel
def _scales(v, factor, t1, sc, n):
    """The typical magnitude of each of the method's m = n - 1 components: factor times the
    state's v [layout.py units] for the coordinates and rates, max(1, |t1|) [s] for the time."""
    nq = n // 2
    for i in range(nq - 1):
        sc[i] = v[i] * factor
        sc[nq - 1 + i] = v[nq + i] * factor
    sc[n - 2] = max(1.0, abs(t1))


@kernel
def _unpack(z, y, n, prof_t, prof_w, t0, psi0):
    """y from z at its time t1 = z[n - 2]; the prescribed spin from the profile: psi' its speed
    at t1 and psi by the trapezoid rule from (t0, psi0), exact within a linear segment."""
    nq = n // 2
    m = n - 1
    t1 = z[m - 1]
    _to_state(z, y, n)
    w0, _ = profile_eval(t0, profile_segment(t0, prof_t), prof_t, prof_w)
    w1, _ = profile_eval(t1, profile_segment(t1, prof_t), prof_t, prof_w)
    y[nq - 1] = psi0 + 0.5 * (w0 + w1) * (t1 - t0)
    y[n - 1] = w1


@kernel
def _scaled_phi(L, h, sc, m, hL, Ph, Pf, work, Ch, Cf):
    """phi_k(h L / 2) and phi_k(h L) through the balanced matrix D^-1 h L D, D = diag(sc) (the
    components' typical magnitudes): its norm is near the spectral radius, while h L's mixes
    metres and radians (1e7 against 1e3 1/s on 004's rig), and phi(D^-1 A D) = D^-1 phi(A) D.
    With Ch, Cf (4, m, m) also those of the step 2h: Ch = phi_k(h L), Cf = phi_k(2 h L) by one
    more doubling, the operations phi_functions(2 h L) makes (bit for bit) when it doubles at
    least twice; otherwise (||2 h L|| <= 1 on the balanced scale) by it. Ch.shape[0] == 0: none.
    """
    for i in range(m):
        for j in range(m):
            hL[i, j] = h * L[i, j] * sc[j] / sc[i]
    s = phi_functions(hL, m, Ph, Pf, work)
    coarse = Ch.shape[0] > 0
    if coarse:
        if s >= 2:
            for k in range(K_PHI + 1):
                for i in range(m):
                    for j in range(m):
                        Ch[k, i, j] = Pf[k, i, j]
                        Cf[k, i, j] = Pf[k, i, j]
            phi_double(Cf, m, work[2:6])
        else:
            for i in range(m):
                for j in range(m):
                    hL[i, j] = (2.0 * h) * L[i, j] * sc[j] / sc[i]
            phi_functions(hL, m, Ch, Cf, work)
    for i in range(m):
        for j in range(m):
            f = sc[i] / sc[j]               # once per entry, for the four phi_k
            for k in range(K_PHI + 1):
                Ph[k, i, j] *= f
                Pf[k, i, j] *= f
                if coarse:
                    Ch[k, i, j] *= f
                    Cf[k, i, j] *= f


@kernel
def _etd_run(z, t1, K, refresh, n, P, B, N, sched, md, sc, ew3, ew1, rw, check,
             mon, stick_tol, Ph, Pf, given):
    """z from its time to t1 [s] in K equal ETDRK4-B steps, L refreshed every ``refresh``
    steps into ew3[0] and Ph, Pf (phi_k of h L / 2 and h L); with ``given`` the first L and
    phi are already there. With ``check``, after each step every slipping ball must still slide
    its way (sgn alpha_dot > 0), every stuck ball be within its static limit (1 + stick_tol [-]) and,
    under the compliant contact model, every pair of neighbours keep its contact state
    (mon[3 + i]);
    else False is returned at once, with that step's end in mon[2] [s] and its start (the
    last step end that passed) in mon[3 + N]. And
    mon[:2] = (max |w| [m], its time [s]) is updated at the step ends. Returns (ok,
    right-hand-side evaluations)."""
    stuck, sgn, spin = md
    lam = rw[0]
    m = n - 1
    nq = n // 2
    h = (t1 - z[m - 1]) / K
    L, hL, work = ew3[0], ew3[1], ew3[10:16]
    G, U, fz, f0, zt, yw, fw = ew1[0:5], ew1[5], ew1[6], ew1[7], ew1[8], ew1[12], ew1[13]
    ne = 0
    for k in range(K):
        mon[3 + N] = z[m - 1]                  # the step's start: the last end that passed
        if k % refresh == 0 and not (given and k == 0):
            jacobian(z, n, P, B, N, sched, md, sc, L, f0, fz, zt, yw, fw, rw)
            ne += m + 1
            _scaled_phi(L, h, sc, m, hL, Ph, Pf, work, Ph[:0], Pf[:0])
        etd_step(z, h, n, L, Ph, Pf, P, B, N, sched, md, G, U, fz, yw, fw, rw,
                 ew1[16], ew1[17], ew1[18])
        ne += 5
        if k == K - 1:
            z[m - 1] = t1                      # the window's end exactly, not by summed steps
        if check:
            held = False
            if B[0, B_KC] > 0.0 and N > 1:
                # the compliant contacts must keep their state (mon[3 + i], from the window's
                # start): the contact force is smooth while it does, and the integrator counts
                # and steps each contact that starts or ends
                for i in range(N):
                    _, gap = neighbour_gap(z, i, N, P[P_DELTA])
                    if (gap < 0.0) != (mon[3 + i] == 1.0):
                        mon[2] = z[m - 1]
                        return False, ne
            for i in range(N):
                if stuck[i] == 0 and sgn[i] * z[nq + 1 + i] <= 0.0:
                    mon[2] = z[m - 1]
                    return False, ne
                held = held or stuck[i] == 1
            if held:            # a stuck ball's margin mu_s N R (1 + stick_tol) - |lambda|
                _F(z, n, P, B, N, sched, md, fz, yw, fw, rw)
                ne += 1
                for i in range(N):
                    if stuck[i] == 1 and lam[N + i] * (1.0 + stick_tol) - abs(lam[i]) <= 0.0:
                        mon[2] = z[m - 1]
                        return False, ne
            a = math.sqrt(z[0] * z[0] + z[1] * z[1])
            if a > mon[0]:
                mon[0] = a
                mon[1] = z[m - 1]
    return True, ne


@kernel
def _window(t, t1, K, h_etd, y, P, B, N, sched, md, atol, rtol, ew3, ew1, rw,
            stick_tol):
    """One try of a slip jump from t to t1 [s] with K coarse steps (``slip_window``). Returns
    (1 accepted, 0 a check failed, -1 the error estimate failed; right-hand-side evaluations;
    next h_etd [s]; max |w| [m] and its time [s]; the failing step's end [s] or t1)."""
    prof_t, prof_w, unb_t, unb_u = sched
    n = y.shape[0]
    m = n - 1
    nq = n // 2
    T = t1 - t
    zs, zc, zf = ew1[11], ew1[9], ew1[10]
    sc = ew1[14]
    mon = ew1[15]
    _pack(y, t, zs, n)
    for i in range(N):
        _, gap = neighbour_gap(zs, i, N, P[P_DELTA])
        mon[3 + i] = 1.0 if gap < 0.0 else 0.0
    _scales(atol, 1e6, t1, sc, n)
    # both runs start from zs: one Jacobian L0 serves them, and the fine run's phi functions
    # give the coarse run's by one more doubling (_scaled_phi)
    L, L0, hL, work = ew3[0], ew3[16], ew3[1], ew3[10:16]
    Ph, Pf, Fh, Ff = ew3[2:6], ew3[6:10], ew3[17:21], ew3[21:25]
    jacobian(zs, n, P, B, N, sched, md, sc, L0, ew1[7], ew1[6], ew1[8], ew1[12],
             ew1[13], rw)
    ne = m + 1
    _scaled_phi(L0, T / (2 * K), sc, m, hL, Fh, Ff, work, Ph, Pf)
    for j in range(m + 2):
        zc[j] = zs[j]
    for i in range(m):
        for j in range(m):
            L[i, j] = L0[i, j]
    mon[0] = 0.0
    ok, e = _etd_run(zc, t1, K, REFRESH, n, P, B, N, sched, md, sc, ew3, ew1, rw,
                     True, mon, stick_tol, Ph, Pf, True)
    ne += e
    for attempt in range(3):
        if not ok:
            return 0, ne, h_etd, 0.0, 0.0, mon[2]
        for j in range(m + 2):
            zf[j] = zs[j]
        if attempt > 0:             # the fine step halved: its phi functions from L0
            _scaled_phi(L0, T / (2 * K), sc, m, hL, Fh, Ff, work, Ph[:0], Pf[:0])
        for i in range(m):
            for j in range(m):
                L[i, j] = L0[i, j]
        mon[0] = 0.0
        mon[1] = t
        ok, e = _etd_run(zf, t1, 2 * K, REFRESH, n, P, B, N, sched, md, sc, ew3, ew1,
                         rw, True, mon, stick_tol, Fh, Ff, True)
        ne += e
        if not ok:
            return 0, ne, h_etd, 0.0, 0.0, mon[2]
        en = 0.0
        for i in range(nq - 1):
            for off_z, off_y in ((i, i), (nq - 1 + i, nq + i)):
                sc_i = atol[off_y] + rtol * max(abs(zs[off_z]), abs(zf[off_z]))
                q = (zf[off_z] - zc[off_z]) / 15.0 / sc_i
                en += q * q
        en = math.sqrt(en / (n - 2))
        if en <= 1.0:
            _unpack(zf, y, n, prof_t, prof_w, t, y[nq - 1])
            # the next window's coarse step: this one's (T / K), scaled as the error allows
            h_new = T / K * min(4.0, max(0.5, 0.9 * max(en, 1e-10) ** -0.2))
            return 1, ne, h_new, mon[0], mon[1], t1
        K *= 2
        for j in range(m + 2):
            zc[j] = zf[j]
    return -1, ne, T / (2 * K), 0.0, 0.0, t1




@kernel
def slip_window(t: float, t1: float, y: np.ndarray, h_etd: float, P: np.ndarray, B: np.ndarray,
                N: int, sched: tuple, md: tuple,
                atol: np.ndarray, rtol: float, ew3: np.ndarray, ew1: np.ndarray, rw: tuple,
                stick_tol: float, h_max: float) -> tuple[bool, int, float, float, float, float,
                                                          float]:
    """A slip jump: some ball slipping, y [state, layout.py] from t to t1 [s] by ETDRK4-B
    (integrate.py, ``P[P_ETD]``; docs/numerics/exponential-slip.md).

    The window is run with K and with 2K equal steps (K from the last window's step h_etd
    [s], the steps no longer than the run's largest step h_max [s]); Richardson's estimate
    (z_2K - z_K) / 15 in the kernel's error norm must be <= 1, else K doubles (three times at
    most). Every step end of both runs is checked: a slipping ball that stops or reverses
    there, or a stuck one beyond its static limit (1 + stick_tol [-]), ends the try. The
    window is then tried once more up to the start of the step that failed, if that is a
    coarse step or more past t, so that DOPRI5 steps only the rest of the way to the event it
    locates. On acceptance y holds the 2K-step solution at the window's end.

    Returns
    -------
    (ok, right-hand-side evaluations, next h_etd [s], max |w| [m] and its time [s] at the
    accepted run's step ends, the time [s] before which no jump should be tried again (the
    step end where a ball stopped, or t1), and the time reached [s] (t1, the shorter window's
    end, or t if none was accepted))
    """
    h = max(min(h_etd, h_max), 1e-9)
    K = max(2, int(math.ceil((t1 - t) / h)))
    st, ne, h_new, a, ta, t_next = _window(t, t1, K, h_etd, y, P, B, N, sched, md,
                                           atol, rtol, ew3, ew1, rw, stick_tol)
    if st == 1:
        return True, ne, h_new, a, ta, t1, t1
    t_good = ew1[15][3 + N]
    h = (t1 - t) / K
    if st == 0 and t_good - t >= h * (1.0 - 1e-9):
        st2, ne2, _, a, ta, _ = _window(t, t_good, max(2, int(round((t_good - t) / h))), h_etd, y,
                                        P, B, N, sched, md, atol, rtol, ew3, ew1, rw,
                                        stick_tol)
        ne += ne2
        if st2 == 1:
            return True, ne, h_etd, a, ta, t_next, t_good
    return False, ne, h_new, 0.0, 0.0, t_next, t


@njit(cache=True)
def etd_window(P: np.ndarray, B: np.ndarray, N: int, prof_t: np.ndarray, prof_w: np.ndarray,
               unb_t: np.ndarray, unb_u: np.ndarray, stuck: np.ndarray, sgn: np.ndarray,
               y: np.ndarray, t0: float, t1: float, nsteps: int, refresh: int,
               scale: np.ndarray) -> np.ndarray:
    """Integrate y from t0 to t1 [s] in nsteps equal ETDRK4-B steps with the balls' modes fixed
    (stuck, sgn), L refreshed every ``refresh`` steps; returns y at t1. The caller guarantees
    that the window has no stick-slip event and no profile knot, and a prescribed spin (a
    measuring tool, not a solver: benchmarks/slip_etd_bench.py).

    The method's state z (m = n - 1 components, then psi and psi'): the rotor's and the balls'
    coordinates, their rates and the time t; the spin (psi, psi') is prescribed, so it is left
    out of the exponential and set from the profile at t1 (psi by the trapezoid rule, exact on a
    linear speed ramp). ``scale``: the typical magnitude of each state component (n,).
    """
    sched = (prof_t, prof_w, unb_t, unb_u)
    n = y.shape[0]
    _, rw, md, _, jw = ball_work(N)
    md = (stuck, sgn, md[2])                      # the caller's modes, the work's spin
    ew3, ew1 = jw[2], jw[3]
    z, sc = ew1[11], ew1[14]
    _pack(y, t0, z, n)
    _scales(scale, 1.0, t1, sc, n)
    _etd_run(z, t1, nsteps, refresh, n, P, B, N, sched, md, sc, ew3, ew1, rw, False,
             ew1[15], 0.0, ew3[2:6], ew3[6:10], False)
    out = np.empty(n)
    _unpack(z, out, n, prof_t, prof_w, t0, y[n // 2 - 1])
    return out
