"""The phi functions phi_0..phi_3 of a small matrix by scaling and squaring, for the
exponential integrator of core/expo.py (Skaflestad & Wright 2009, Appl. Numer. Math. 59,
783-799): a Taylor series at A / 2^s, ||A / 2^s||_1 <= 1/2, then s doublings
phi_k(2A) = 2^-k [phi_0(A) phi_k(A) + sum_{j=1..k} phi_j(A) / (k - j)!], where
phi_k(z) = sum_j z^j / (j + k)!. The last doubling's input is phi_k(A / 2), which the method
needs too.
"""
from __future__ import annotations

import math

import numpy as np

from .dense import matmul as _matmul
from .jit import kernel

#: Highest phi function computed (ETDRK4-B needs phi_0 .. phi_3) [-].
K_PHI = 3
#: Degree of the Taylor polynomial of phi_3 at the scaled argument (||B||_1 <= 1/2: the first
#: omitted term is below 0.5^13 / 16! = 5.8e-18) [-].
TAYLOR_DEGREE = 12


@kernel
def phi_functions(A: np.ndarray, m: int, half: np.ndarray, full: np.ndarray,
                  work: np.ndarray) -> int:
    """phi_0 .. phi_3 of the m x m matrix A into full[k, :m, :m], and of A / 2 into half.

    Parameters
    ----------
    A : ndarray (>= m, >= m)
        The matrix (leading m x m block) [-].
    m : int
        Its size.
    half, full : ndarray (4, >= m, >= m)
        Outputs: phi_k(A / 2), phi_k(A).
    work : ndarray (6, >= m, >= m)
        Work space.

    Returns
    -------
    int
        The number of doublings s (A was scaled by 2^-s, s >= 1).
    """
    nrm = 0.0
    for j in range(m):
        c = 0.0
        for i in range(m):
            c += abs(A[i, j])
        nrm = max(nrm, c)
    s = 1
    while nrm / 2.0 ** s > 0.5:
        s += 1
    sc = 2.0 ** -s
    B = work[0]
    T = work[1]
    for i in range(m):
        for j in range(m):
            B[i, j] = A[i, j] * sc
    # phi_3(B) = sum_{j<=12} B^j / (j + 3)! by Paterson & Stockmeyer (1973): with B2, B3, B4,
    # phi_3 = ((q3 B4 + q2) B4 + q1) B4 + q0, q_i = sum_{r<4} B^r / (4i + r + 3)! (q3 = I / 15!);
    # then phi_k = I / k! + B phi_{k+1}: 9 products in all
    B2 = work[2]
    B3 = work[3]
    B4 = work[4]
    _matmul(B, B, B2, m)
    _matmul(B2, B, B3, m)
    _matmul(B2, B2, B4, m)
    P = full
    P3 = P[K_PHI]
    for i in range(m):
        for j in range(m):
            P3[i, j] = 1.0 / math.gamma(TAYLOR_DEGREE + K_PHI + 1) if i == j else 0.0
    for blk in range(2, -1, -1):
        _matmul(P3, B4, T, m)
        c0 = 1.0 / math.gamma(4 * blk + 4)
        c1 = 1.0 / math.gamma(4 * blk + 5)
        c2 = 1.0 / math.gamma(4 * blk + 6)
        c3 = 1.0 / math.gamma(4 * blk + 7)
        for i in range(m):
            for j in range(m):
                P3[i, j] = (T[i, j] + c1 * B[i, j] + c2 * B2[i, j] + c3 * B3[i, j]
                            + (c0 if i == j else 0.0))
    for k in range(K_PHI - 1, -1, -1):
        _matmul(B, P[k + 1], T, m)
        for i in range(m):
            for j in range(m):
                P[k, i, j] = T[i, j] + (1.0 / math.gamma(k + 1) if i == j else 0.0)
    # s doublings; the input of the last one is phi_k(A / 2)
    for level in range(s):
        if level == s - 1:
            for k in range(K_PHI + 1):
                for i in range(m):
                    for j in range(m):
                        half[k, i, j] = P[k, i, j]
        phi_double(P, m, work[2:6])
    return s


@kernel
def phi_double(P: np.ndarray, m: int, Q: np.ndarray) -> None:
    """phi_k(2A) from phi_k(A), k = 0..3, in place: phi_k(2A) = 2^-k [phi_0(A) phi_k(A) +
    sum_{j=1..k} phi_j(A) / (k - j)!] (Skaflestad & Wright 2009, eq. 2.4).

    Parameters
    ----------
    P : ndarray (4, >= m, >= m)
        phi_0..3 of A on entry, of 2A on return [-].
    m : int
        Size of the matrices.
    Q : ndarray (4, >= m, >= m)
        Work space.
    """
    for k in range(K_PHI, -1, -1):
        _matmul(P[0], P[k], Q[k], m)
        for jj in range(1, k + 1):
            c = 1.0 / math.gamma(k - jj + 1)
            for i in range(m):
                for j in range(m):
                    Q[k, i, j] += c * P[jj, i, j]
        f = 2.0 ** -k
        for i in range(m):
            for j in range(m):
                Q[k, i, j] *= f
    for k in range(K_PHI + 1):
        for i in range(m):
            for j in range(m):
                P[k, i, j] = Q[k, i, j]
