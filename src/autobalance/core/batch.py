"""Many runs of :func:`autobalance.core.integrate.integrate` in one compiled call, in parallel
threads (numba ``prange``)."""
from __future__ import annotations

from typing import TYPE_CHECKING

from numba import njit, prange

from .integrate import integrate

if TYPE_CHECKING:
    import numpy as np

__all__ = ["integrate_batch"]


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
