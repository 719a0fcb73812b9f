"""Compilation flags of the numba kernels.

``kernel`` compiles with the numba runtime (NRT) off. None of these functions allocates: every
array is a borrowed argument that the caller keeps alive (work.ball_work, which allocates them,
keeps the NRT). With the NRT on, numba reference-counts
each array argument on entry and exit of a call (an atomic increment and decrement per array)
unless its reference-count pruning pass removes the pair. In rhs (18 arrays, ~8 calls per step)
it did not, and that cost ~130 of its ~300 ns per call. Switching the NRT off changes no result.
``_nrt`` is a private numba option (numba issue #2350 uses it the same way); a kernel that tried
to allocate would fail to compile (typing error), not misbehave.

An integer constant passed to a kernel (``f(0, ...)``) is typed as that literal value, and
numba compiles the callee once per value: a copy of its whole call tree each (``_stage`` of
the slip jumps was five). Call sites pass ``np.int64(...)``, a module-level numpy integer, or
the array row instead of an index (docs/numerics/compilation.md, "Compilation cache").

``inline_kernel`` also inlines the function into its compiled callers (numba IR inlining),
for small helpers called per vector component: a call between numba functions passes every
array as its exploded struct (7-9 words each).
"""
from __future__ import annotations

import hashlib
from collections.abc import Callable
from pathlib import Path
from typing import Any

from numba import njit


def _drop_stale_cache(here: Path = Path(__file__).parent) -> bool:
    """In a source checkout, delete the compiled cache of every kernel in this package when any
    of its sources changed.

    numba keys a cached kernel on its own file only, so a kernel that calls one in another file
    (batch -> integrate -> rhs) kept stale machine code after that file changed: a silently wrong
    result in a working copy. One hash of all ``core/*.py`` sources, stamped beside the cache,
    makes a change anywhere in core recompile everything. A source checkout is ``src/autobalance/
    core`` under a ``pyproject.toml``; anywhere else (an installed release, whose files an
    install replaces together, so numba's own check of each file invalidates every kernel) this
    does nothing, and so it does where the cache is unwritable. Returns True if it deleted.
    """
    if not (here.parents[2] / "pyproject.toml").is_file():
        return False
    try:
        h = hashlib.sha256(b"".join(p.read_bytes() for p in sorted(here.glob("*.py")))).hexdigest()
        cache = here / "__pycache__"
        stamp = cache / "core-sources.sha256"
        if stamp.is_file() and stamp.read_text() == h:
            return False
        for p in cache.glob("*.nb[ic]"):
            p.unlink(missing_ok=True)
        cache.mkdir(exist_ok=True)
        stamp.write_text(h)
        return True
    except OSError:                                    # pragma: no cover - read-only install
        return False


_drop_stale_cache()

try:        # ``_nrt`` is a CPU target option of numba (numba/core/cpu.py), private by name
    from numba.core.cpu import CPUTargetOptions
    _NO_NRT = {"_nrt": False} if hasattr(CPUTargetOptions, "_nrt") else {}
except ImportError:                                   # pragma: no cover - other numba layouts
    _NO_NRT = {}


def kernel(fn: Callable[..., Any]) -> Any:
    """njit(cache=True, nogil=True) without the NRT (no allocation inside; see the module
    docstring). A numba without the option compiles with the NRT: slower, same results. The GIL
    is released on a call from Python (core/batch.py calls the loop from Python threads)."""
    return njit(cache=True, nogil=True, **_NO_NRT)(fn)


def inline_kernel(fn: Callable[..., Any]) -> Any:
    """kernel, inlined into its compiled callers (see the module docstring)."""
    return njit(cache=True, inline="always", **_NO_NRT)(fn)
