"""Compilation flags of the numba kernels.

``kernel`` compiles with the numba runtime (NRT) off. None of these functions allocates: every
array is a borrowed argument that the caller keeps alive (the allocating entry points,
integrate.integrate and batch.integrate_batch, keep the NRT). With the NRT on, numba reference-counts
each array argument on entry and exit of a call (an atomic increment and decrement per array)
unless its reference-count pruning pass removes the pair. In rhs (18 arrays, ~8 calls per step)
it did not, and that cost ~130 of its ~300 ns per call. Switching the NRT off changes no result.
``_nrt`` is a private numba option (numba issue #2350 uses it the same way); a kernel that tried
to allocate would fail to compile (typing error), not misbehave.

``inline_kernel`` also inlines the function into its compiled callers (numba IR inlining),
for small helpers called per vector component: a call between numba functions passes every
array as its exploded struct (7-9 words each).
"""
from __future__ import annotations

from numba import njit

try:        # ``_nrt`` is a CPU target option of numba (numba/core/cpu.py), private by name
    from numba.core.cpu import CPUTargetOptions
    _NO_NRT = {"_nrt": False} if hasattr(CPUTargetOptions, "_nrt") else {}
except ImportError:                                   # pragma: no cover - other numba layouts
    _NO_NRT = {}


def kernel(fn):
    """njit(cache=True) without the NRT (no allocation inside; see the module docstring). A
    numba without the option compiles with the NRT: slower, same results."""
    return njit(cache=True, **_NO_NRT)(fn)


def inline_kernel(fn):
    """kernel, inlined into its compiled callers (see the module docstring)."""
    return njit(cache=True, inline="always", **_NO_NRT)(fn)
