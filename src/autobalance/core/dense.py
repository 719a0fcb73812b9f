"""Small dense products of the exponential slip jumps (core/expo.py, core/phi.py): the matrix
product and the matrix-vector product of the leading m x m block, m = n - 1 = 2 N + 5 for N
balls.

numba compiles a loop whose trip count is a constant into unrolled, vectorised code; with m
known only at run time it keeps generic loops. So each product dispatches the sizes of one to
four balls (m = 7, 9, 11, 13) to a copy compiled for that size (:func:`_sized`: the one loop
body inlined with the size a constant), and any other to the loop body with m. Every copy runs
the same operations in the same order: the results are bit for bit those of the generic loop
(tests/test_dense.py). On this machine (2 balls, m = 9) a product costs 208 instead of 334 ns,
a matrix-vector product 25 instead of 36 ns. The sized matrix-vector products are called, not
inlined into their callers: inlined, they added 15 s to the kernels' compilation and ran no
faster.
"""
from __future__ import annotations

import numpy as np

from .jit import inline_kernel, kernel

#: m of the copies compiled for a fixed size: one to four balls
SIZES = (7, 9, 11, 13)


@inline_kernel
def _mm_loop(A, B, C, m):
    """C[:m, :m] = A[:m, :m] @ B[:m, :m], row-wise saxpy (the inner loop runs along rows)."""
    for i in range(m):
        for j in range(m):
            C[i, j] = 0.0
        for k in range(m):
            a = A[i, k]
            for j in range(m):
                C[i, j] += a * B[k, j]


@inline_kernel
def _mv_loop(M, x, out, m, scale, accumulate):
    """out[:m] (+)= scale * M[:m, :m] @ x[:m], each row's sum in column order."""
    for i in range(m):
        s = 0.0
        for j in range(m):
            s += M[i, j] * x[j]
        out[i] = (out[i] if accumulate else 0.0) + scale * s


def _sized(size: int):
    """The two products with m = ``size`` a compile-time constant (the loop bodies inlined)."""

    @kernel
    def mm(A, B, C):
        _mm_loop(A, B, C, size)

    @kernel         # called, not inlined: 22 call sites x 4 sizes inlined cost 15 s to compile
    def mv(M, x, out, scale, accumulate):
        _mv_loop(M, x, out, size, scale, accumulate)

    return mm, mv


_MM7, _MV7 = _sized(7)
_MM9, _MV9 = _sized(9)
_MM11, _MV11 = _sized(11)
_MM13, _MV13 = _sized(13)


@kernel
def matmul(A: np.ndarray, B: np.ndarray, C: np.ndarray, m: int) -> None:
    """C[:m, :m] = A[:m, :m] @ B[:m, :m].

    Parameters
    ----------
    A, B : ndarray (>= m, >= m)
        The factors (leading m x m blocks) [-].
    C : ndarray (>= m, >= m)
        Output (its leading block; the rest untouched) [-].
    m : int
        The size.
    """
    if m == 9:
        _MM9(A, B, C)
    elif m == 7:
        _MM7(A, B, C)
    elif m == 11:
        _MM11(A, B, C)
    elif m == 13:
        _MM13(A, B, C)
    else:
        _mm_loop(A, B, C, m)


@inline_kernel
def matvec_add(M: np.ndarray, x: np.ndarray, out: np.ndarray, m: int, scale: float,
               accumulate: bool) -> None:
    """out[:m] = (out[:m] if accumulate else 0) + scale * M[:m, :m] @ x[:m].

    Parameters
    ----------
    M : ndarray (>= m, >= m)
        The matrix (leading m x m block) [-].
    x : ndarray (>= m,)
        The vector [-].
    out : ndarray (>= m,)
        Output (its first m entries) [-].
    m : int
        The size.
    scale : float
        Factor of the product [-].
    accumulate : bool
        Add to ``out`` instead of overwriting it.
    """
    if m == 9:
        _MV9(M, x, out, scale, accumulate)
    elif m == 7:
        _MV7(M, x, out, scale, accumulate)
    elif m == 11:
        _MV11(M, x, out, scale, accumulate)
    elif m == 13:
        _MV13(M, x, out, scale, accumulate)
    else:
        _mv_loop(M, x, out, m, scale, accumulate)
