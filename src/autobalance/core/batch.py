"""Many runs of :func:`autobalance.core.integrate.integrate`, on ``numba.get_num_threads()``
Python threads (the kernel releases the GIL); runs that branch from a shared history
(``integrate_branches``).

Why threads and not a numba ``prange`` loop: numba compiles every jitted caller into its own
machine code with its whole call tree linked in and optimised again (numba/core/codegen.py,
``CPUCodeLibrary.finalize``), and a ``parallel=True`` function twice (its gufunc and itself). The
two ``prange`` drivers added ~23 s each to the kernels' ~95 s first compilation, for a loop
that a thread pool runs as fast: on one thread 6.28-6.33 ms a run against 6.24-6.25 with
``prange``, on two 3.36-3.38 against 3.52-3.63 ms (004's nominal runs in batches of 64;
docs/numerics/compilation.md, "Compilation cache").
"""
from __future__ import annotations

from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor

import numba
import numpy as np

from .integrate import integrate, integrate_span
from .layout import S_STATUS, RunStatus, carry_size

__all__ = ["integrate_batch", "integrate_branches", "each_run"]

#: stats[S_STATUS] of a run paused at the branch knot
RUNNING = float(RunStatus.RUNNING)


def each_run(n: int, run: Callable[[int], None]) -> None:
    """Call ``run(r)`` for r = 0 .. n-1 on ``numba.get_num_threads()`` threads, one run at a
    time per thread (dynamic scheduling: runs differ in length). An exception (Ctrl-C
    included) cancels the runs not yet started, waits for the ones running, and propagates."""
    k = min(numba.get_num_threads(), n)
    if k <= 1:
        for r in range(n):
            run(r)
        return
    ex = ThreadPoolExecutor(k, thread_name_prefix="autobalance-run")
    try:
        for _ in ex.map(run, range(n)):
            pass
    finally:
        ex.shutdown(wait=True, cancel_futures=True)


def integrate_batch(P: np.ndarray, B: np.ndarray, N: int, prof_t: np.ndarray,
                    prof_w: np.ndarray, unb_t: np.ndarray, unb_u: np.ndarray,
                    unb_n: np.ndarray, y0: np.ndarray, t_end: float, rtol: float,
                    atol: np.ndarray, h_max: float, max_steps: int, out_t: np.ndarray,
                    out_y: np.ndarray, stats: np.ndarray) -> None:
    """Many runs in one call, in parallel threads: P (n, N_P), B (n, N, N_B), y0 (n, 2nq),
    atol (n, 2nq), out_y (n, len(out_t), 2nq), stats (n, N_S); the speed profile is shared;
    unbalance tables per run: unb_t, unb_u (n, K), of which run r uses the first unb_n[r].
    Units as :func:`autobalance.core.integrate.integrate`."""
    def run(r: int) -> None:
        k = unb_n[r]
        integrate(P[r], B[r], N, prof_t, prof_w, unb_t[r, :k], unb_u[r, :k], y0[r], t_end,
                  rtol, atol[r], h_max, max_steps, out_t, out_y[r], stats[r])

    each_run(P.shape[0], run)


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
    C = carry_size(N)
    ys = np.empty((F * S, y0.shape[1]))
    ys[:S] = y0
    carry = np.zeros((F * S, C))
    k0 = prof_n[0]

    def prefix(s: int) -> None:
        k = unb_n[s]
        integrate_span(P[s], B[s], N, prof_t[0, :k0], prof_w[0, :k0], unb_t[s, :k],
                       unb_u[s, :k], ys[s], t_end[0], rtol, atol[s], h_max, max_steps, out_t,
                       out_y[s], stats[s], t_pause, carry[s])

    each_run(S, prefix)
    for arr in (ys, carry, out_y, stats):
        arr[S:] = np.tile(arr[:S], (F - 1,) + (1,) * (arr.ndim - 1))

    def branch(r: int) -> None:
        f, s = divmod(r, S)
        if stats[r, S_STATUS] != RUNNING:
            return                            # failed before the knot: in every branch
        k = unb_n[s]
        kf = prof_n[f]
        integrate_span(P[s], B[s], N, prof_t[f, :kf], prof_w[f, :kf], unb_t[s, :k],
                       unb_u[s, :k], ys[r], t_end[f], rtol, atol[s], h_max, max_steps, out_t,
                       out_y[r], stats[r], np.inf, carry[r])

    each_run(F * S, branch)
