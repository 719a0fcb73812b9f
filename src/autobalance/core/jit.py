"""Compilation flags of the numba kernels.

``kernel`` compiles with the numba runtime (NRT) off. None of these functions allocates: every
array is a borrowed argument that the caller keeps alive (the allocating entry points,
integrate.integrate and integrate_batch, keep the NRT). With the NRT on, numba reference-counts
each array argument on entry and exit of a call (an atomic increment and decrement per array)
whenever its reference-count pruning pass gives up on a large function; for rhs (18 arrays,
called ~8 times per step) that was ~130 ns of its ~300 ns. Switching it off changes no result.
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
