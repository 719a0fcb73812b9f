"""Many runs of :func:`autobalance.core.integrate.integrate` in one compiled call, in parallel
threads (numba ``prange``); runs that branch from a shared history (``integrate_branches``)."""
from __future__ import annotations

import numpy as np
from numba import njit, prange

from .integrate import integrate, integrate_span
from .layout import N_C, S_STATUS, RunStatus

__all__ = ["integrate_batch", "integrate_branches"]

#: stats[S_STATUS] of a run paused at the branch knot
RUNNING = float(RunStatus.RUNNING)


@njit(cache=True, parallel=True)
def integrate_batch(P: np.ndarray, B: np.ndarray, N: int, prof_t: np.ndarray,
                    prof_w: np.ndarray, unb_t: np.ndarray, unb_u: np.ndarray,
                    unb_n: np.ndarray, y0: np.ndarray, t_end: float, rtol: float,
                    atol: np.ndarray, h_max: float, max_steps: int, out_t: np.ndarray,
                    out_y: np.ndarray, stats: np.ndarray) -> None:
    """Many runs in one call, in parallel threads: P (n, N_P), B (n, N, N_B), y0 (n, 2nq),
    atol (n, 2nq), out_y (n, len(out_t), 2nq), stats (n, N_S); the speed profile is shared;
    unbalance tables per run: unb_t, unb_u (n, K), of which run r uses the first unb_n[r]."""
    nrun = P.shape[0]
    for r in prange(nrun):
        k = unb_n[r]
        integrate(P[r], B[r], N, prof_t, prof_w, unb_t[r, :k], unb_u[r, :k], y0[r], t_end,
                  rtol, atol[r], h_max, max_steps, out_t, out_y[r], stats[r])


@njit(cache=True, parallel=True)
def integrate_branches(P: np.ndarray, B: np.ndarray, N: int, prof_t: np.ndarray,
                       prof_w: np.ndarray, prof_n: np.ndarray, unb_t: np.ndarray,
                       unb_u: np.ndarray, unb_n: np.ndarray, y0: np.ndarray, t_end: np.ndarray,
                       t_pause: float, rtol: float, atol: np.ndarray, h_max: float,
                       max_steps: int, out_t: np.ndarray, out_y: np.ndarray,
                       stats: np.ndarray) -> None:
    """S runs that branch into F speed profiles at the knot ``t_pause`` [s]: each run's history up
    to the knot is integrated once (integrate_span) and continued under every profile, bit for
    bit as F * S separate runs. Per run (S): P, B, unbalance tables (unb_t, unb_u, unb_n as in
    integrate_batch), y0, atol; per profile (F): the knots prof_t, prof_w (F, K), of which
    profile f uses the first prof_n[f], equal up to t_pause, and t_end (F,). out_y
    (F * S, len(out_t), 2nq) and stats (F * S, N_S), branch-major (run f * S + s). A run that
    fails before the knot fails in every branch, as it would alone."""
    S = P.shape[0]
    F = prof_n.shape[0]
    n = y0.shape[1]
    C = N_C + 9 * N + 7
    ys = np.empty((F * S, n))
    carry = np.zeros((F * S, C))
    k0 = prof_n[0]
    for s in prange(S):
        ys[s] = y0[s]
        k = unb_n[s]
        integrate_span(P[s], B[s], N, prof_t[0, :k0], prof_w[0, :k0], unb_t[s, :k],
                       unb_u[s, :k], ys[s], t_end[0], rtol, atol[s], h_max, max_steps, out_t,
                       out_y[s], stats[s], t_pause, carry[s])
    for r in prange(S, F * S):
        s = r % S
        ys[r] = ys[s]
        carry[r] = carry[s]
        out_y[r] = out_y[s]
        stats[r] = stats[s]
    for r in prange(F * S):
        f = r // S
        s = r % S
        if stats[r, S_STATUS] != RUNNING:
            continue                          # failed before the knot: in every branch
        k = unb_n[s]
        kf = prof_n[f]
        integrate_span(P[s], B[s], N, prof_t[f, :kf], prof_w[f, :kf], unb_t[s, :k],
                       unb_u[s, :k], ys[r], t_end[f], rtol, atol[s], h_max, max_steps, out_t,
                       out_y[r], stats[r], np.inf, carry[r])
