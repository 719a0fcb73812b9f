"""Many runs of :func:`autobalance.core.integrate.integrate` in one compiled call, in parallel
threads (numba ``prange``)."""
from __future__ import annotations

from numba import njit, prange

from .integrate import integrate

__all__ = ["integrate_batch"]


@njit(cache=True, parallel=True)
def integrate_batch(P, B, N, prof_t, prof_w, unb_t, unb_u, unb_n, y0, t_end, rtol, atol,
                    h_max, max_steps, out_t, out_y, stats):
    """Many runs in one call, in parallel threads: P (n, N_P), B (n, N, N_B), y0 (n, 2nq),
    atol (n, 2nq), out_y (n, len(out_t), 2nq), stats (n, N_S); the speed profile is shared;
    unbalance tables per run: unb_t, unb_u (n, K), of which run r uses the first unb_n[r]."""
    nrun = P.shape[0]
    for r in prange(nrun):
        k = unb_n[r]
        integrate(P[r], B[r], N, prof_t, prof_w, unb_t[r, :k], unb_u[r, :k], y0[r], t_end,
                  rtol, atol[r], h_max, max_steps, out_t, out_y[r], stats[r])
