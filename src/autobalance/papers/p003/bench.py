"""The bench of seed 003 as the reproductions of 003 and 001 use it: the ``bench_003`` preset,
unit factors and the grid sizes of the quick and full variants.
"""
from __future__ import annotations

import functools

from ...liquid import Bench, load_bench
from ...validation.target import Context

__all__ = ["FIG5_RATIOS", "G10", "GCM", "ML", "QUICK", "bench", "grid"]

ML = 1e-6        # [m^3] per ml
GCM = 1e-5       # [kg*m] per g*cm
G10 = 10.0       # [m/s^2]: the gravity 003's printed speeds imply
#: 003's relative speeds omega/omega_r of Fig. 5 (and our choice for Fig. 6) [-].
FIG5_RATIOS = (0.6, 0.8, 1.0, 1.2)

#: What ``--quick`` changes in the liquid targets.
QUICK = "coarser speed/radius grids in the figures and data; the rows are the same"


@functools.lru_cache(maxsize=1)
def bench() -> Bench:
    """003's bench preset (R = 0.2 m, h = 0.05 m, 150 ml water, D = 3000 g*cm, omega_r = 54)."""
    return load_bench("bench_003")


def grid(ctx: Context, quick: int, full: int) -> int:
    """Number of grid points of a figure: ``quick`` in the quick variant, else ``full``.

    Parameters
    ----------
    ctx : Context
        Variant.
    quick, full : int
        Points in the quick and in the full variant.
    """
    return quick if ctx.quick else full
