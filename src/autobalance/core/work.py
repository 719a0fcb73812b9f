"""The work arrays of the ball kernel's integration loop (core/integrate._integrate): one home
for integrate_span, core/hybrid.py and the slip jumps' measuring driver (core/expo.etd_window)."""
from __future__ import annotations

import numpy as np
from numba import njit

from .layout import NR
from .ramp import RAMP_TAYLOR, RAMP_TERMS


@njit(cache=True)
def rhs_work(N: int) -> tuple:
    """The work arrays of :func:`autobalance.core.rhs.rhs` for N balls, passed as one tuple
    ``rw`` through every kernel that evaluates it [-]:

    * lam (3N + 1,): the friction bookkeeping rhs fills (lam[i] the friction torque a stuck
      ball needs [N*m], lam[N + i] its static limit [N*m], lam[2N + i] its normal force [N]);
    * Mm, A (nq, nq), fv, bb (nq,), idx int (nq,): the mass matrix, right-hand side and the
      constrained solve's work (nq = N + NR + 1, layout.py);
    * trig (3N,): the cache of (alpha_i, cos alpha_i, sin alpha_i), NaN at the start.
    """
    nq = N + NR + 1
    return (np.zeros(3 * N + 1), np.zeros((nq, nq)), np.zeros(nq), np.zeros((nq, nq)),
            np.zeros(nq), np.zeros(nq, dtype=np.int64), np.full(3 * N, np.nan))


@njit(cache=True)
def ball_work(N: int) -> tuple:
    """The work arrays of _integrate for N balls, in the order of its arguments from K to ew1
    (rw: :func:`rhs_work`; ew3, ew1: the slip jumps' matrices and vectors, core/expo.py) [-]."""
    nq = N + NR + 1
    n = 2 * nq
    return (np.zeros((6, n)), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
            np.zeros(n), rhs_work(N), np.zeros(N, dtype=np.int64), np.ones(N), np.zeros(N),
            np.zeros(N), np.zeros(2), np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.int64),
            np.zeros((RAMP_TERMS + 1, RAMP_TAYLOR), dtype=np.complex128), np.zeros((10, N)),
            np.zeros((25, n - 1, n - 1)), np.zeros((19, n + 1)))
