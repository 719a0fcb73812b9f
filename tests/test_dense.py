"""core/dense.py: the products compiled for a fixed size give bit for bit what the generic loop
gives (same operations in the same order), for the sizes of one to four balls and around them,
and agree with numpy."""
import numpy as np
import pytest
from numba import njit

from autobalance.core.dense import SIZES, _mm_loop, _mv_loop, matmul, matvec_add


@njit
def _generic_matmul(A, B, C, m):
    _mm_loop(A, B, C, m)              # the loop body with m known at run time only


@njit
def _generic_matvec_add(M, x, out, m, scale, accumulate):
    _mv_loop(M, x, out, m, scale, accumulate)


@njit
def _call_matvec(M, x, out, m, scale, accumulate):
    matvec_add(M, x, out, m, scale, accumulate)      # an inline kernel: called from compiled code


@pytest.mark.parametrize("m", sorted(set(SIZES) | {5, 8, 15}))
def test_fixed_size_products_equal_the_generic_loop(m):
    rng = np.random.default_rng(m)
    big = m + 3                       # the kernels pass leading blocks of larger work arrays
    A, B = rng.normal(size=(big, big)) * 1e3, rng.normal(size=(big, big)) * 1e-5
    x = rng.normal(size=big)
    C, Cg = np.full((big, big), 7.0), np.full((big, big), 7.0)
    matmul(A, B, C, m)
    _generic_matmul(A, B, Cg, m)
    assert np.array_equal(C, Cg)
    np.testing.assert_allclose(C[:m, :m], A[:m, :m] @ B[:m, :m], rtol=1e-12, atol=1e-12)
    assert np.all(C[m:, :] == 7.0) and np.all(C[:, m:] == 7.0)
    for scale, acc in ((1.0, False), (-1.0, True), (0.37, True)):
        out, outg = np.full(big, 3.0), np.full(big, 3.0)
        _call_matvec(A, x, out, m, scale, acc)
        _generic_matvec_add(A, x, outg, m, scale, acc)
        assert np.array_equal(out, outg)
        ref = (3.0 if acc else 0.0) + scale * (A[:m, :m] @ x[:m])
        np.testing.assert_allclose(out[:m], ref, rtol=1e-12, atol=1e-9)
        assert np.all(out[m:] == 3.0)
