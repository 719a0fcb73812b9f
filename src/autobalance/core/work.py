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
    """The arrays of _integrate's loop for N balls, as the five groups it takes [-]:

    * sw, the step's work: K (6, n) the stages, ytmp, y1, f0, f1, ftmp, err (n,);
    * rw, the work of rhs (:func:`rhs_work`);
    * md, the modes: stuck int (N,) (1: ball i stuck), sgn (N,) the sign of its slip, spin
      (2,) the spin's state under a motor drive (layout.P_SPIN);
    * ct, the contacts: gs, ge (N,) the stick margins at the start and end of a trial step,
      in_contact, viol int (N,) per-ball flags;
    * jw, the jumps' work: ser, qr (the stuck ramps, core/ramp.py), ew3, ew1 (the slip jumps'
      matrices and vectors, core/expo.py);

    n = 2 nq, nq = N + NR + 1 (layout.py).
    """
    nq = N + NR + 1
    n = 2 * nq
    sw = (np.zeros((6, n)), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n), np.zeros(n),
          np.zeros(n))
    md = (np.zeros(N, dtype=np.int64), np.ones(N), np.zeros(2))
    ct = (np.zeros(N), np.zeros(N), np.zeros(N, dtype=np.int64), np.zeros(N, dtype=np.int64))
    jw = (np.zeros((RAMP_TERMS + 1, RAMP_TAYLOR), dtype=np.complex128), np.zeros((10, N)),
          np.zeros((25, n - 1, n - 1)), np.zeros((19, n + 1)))
    return sw, rhs_work(N), md, ct, jw
