"""Seed 004's studies on its machine: the machine-agnostic studies of :mod:`autobalance.studies`
called with the ``vub_jeffcott_004`` preset, 004's cases and 004's target grade G16. No physics
here: each function is one call."""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ...studies import _immobility as _imm
from ...studies import _plateau as _pl
from ...studies import _start_positions as _sp
from ...studies import unbalance as _unb
from .published import (C_R, G_LIMIT, G_TSR_RANGE, MU_R, PLATEAU_CASES, PRESET, SLOW_SETS,
                        UNBALANCE_CASES, immobility_speeds_hz, plateau_grid, unbalance_grid)

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    import xarray as xr
    from numpy.typing import ArrayLike

__all__ = ["compute_descent", "compute_immobility", "compute_monte_carlo", "compute_plateau",
           "compute_profile", "compute_single", "compute_table1", "compute_unbalance"]

SLOW_TEXT = "0 -> 167 Hz linear in 54 s (3 x 18 s), hold to 90 s"


def _cfg(overrides=()):
    """004's machine (the preset) with ``overrides``."""
    return _sp.load(PRESET, overrides)


def compute_table1() -> xr.Dataset:
    """004 Table 1's derived numbers (:func:`autobalance.studies._start_positions.compute_machine`)."""
    return _sp.compute_machine(PRESET)


def compute_single(save_dt: float = 0.01, G_start: float | None = 14.0,
                   n_family: int = 24) -> xr.Dataset:
    """004 Fig. 4 (:func:`autobalance.studies._start_positions.compute_single`); save_dt [s],
    G_start [mm/s]."""
    return _sp.compute_single(PRESET, save_dt, G_start, n_family, limit=G_LIMIT)


def compute_monte_carlo(n: int = 50, *, plateau_ratio: float | None = None,
                        store_dir: str | Path | None = None, executor: str = "local",
                        workers: int | None = None,
                        scheduler: str | None = None) -> xr.Dataset:
    """004 sec. 4.2, Fig. 5-6, Table 2 (:func:`autobalance.studies._start_positions.compute_monte_carlo`)."""
    return _sp.compute_monte_carlo(PRESET, n, plateau_ratio=plateau_ratio, store_dir=store_dir,
                                   executor=executor, workers=workers, scheduler=scheduler,
                                   limit=G_LIMIT, prefix="tsr")


def compute_unbalance(cases: Sequence[str] = ("nominal",), *, G: ArrayLike | None = None,
                      n: int = 50, quick: bool = False, store_dir: str | Path | None = None,
                      executor: str = "local", workers: int | None = None,
                      scheduler: str | None = None) -> xr.Dataset:
    """004 sec. 4.3-4.5, Fig. 7, Tables 3-4 for the named :data:`UNBALANCE_CASES`
    (:func:`autobalance.studies.unbalance.compute_unbalance`); G [mm/s]."""
    G = unbalance_grid(quick) if G is None else G
    return _unb.compute_unbalance(PRESET, {c: UNBALANCE_CASES[c] for c in cases}, G=G, n=n,
                                  quick=quick, store_dir=store_dir, executor=executor,
                                  workers=workers, scheduler=scheduler, prefix="tsr",
                                  budget=0)     # 004's protocol: the start grid alone


def compute_profile(*, G: ArrayLike | None = None, n: int = 50, quick: bool = False,
                    store_dir: str | Path | None = None, executor: str = "local",
                    workers: int | None = None, scheduler: str | None = None,
                    unbalance_ds: xr.Dataset | None = None) -> xr.Dataset:
    """004 sec. 4.4, Fig. 9 with the 3x slower run-up :data:`SLOW_SETS`
    (:func:`autobalance.studies.unbalance.compute_profile`); G [mm/s]."""
    G = unbalance_grid(quick) if G is None else G
    return _unb.compute_profile(PRESET, SLOW_SETS, G=G, n=n, quick=quick, store_dir=store_dir,
                                executor=executor, workers=workers, scheduler=scheduler,
                                unbalance_ds=unbalance_ds, prefix="tsr", other_text=SLOW_TEXT)


def compute_immobility(*, G_ini: float = 20.0, mu_r: Sequence[float] = MU_R,
                       c_r: Sequence[float] = C_R, speeds_hz: ArrayLike | None = None,
                       n_conf: int | None = None, quick: bool = False,
                       field: str = "n_conf") -> xr.Dataset:
    """004 Fig. 8/10 (:func:`autobalance.studies._immobility.compute_immobility`); G_ini [mm/s],
    speeds_hz [Hz], n_conf positions per ball (None: the study's default, coarser when
    ``quick``)."""
    f = immobility_speeds_hz(quick) if speeds_hz is None else np.asarray(speeds_hz, float)
    return _imm.compute_immobility(PRESET, G_ini=G_ini, mu_r=mu_r, c_r=c_r, speeds=2 * np.pi * f,
                                   n_conf=n_conf, quick=quick, field=field)


def compute_plateau(cases: Sequence[str] = ("nominal",), *, ratios: ArrayLike | None = None,
                    G: ArrayLike | None = None, n: int = 20, quick: bool = False,
                    store_dir: str | Path | None = None, executor: str = "local",
                    workers: int | None = None,
                    scheduler: str | None = None) -> xr.Dataset:
    """004 sec. 4.6, Fig. 14-16 for the named :data:`PLATEAU_CASES`
    (:func:`autobalance.studies._plateau.compute_plateau`); ratios [-], G [mm/s]."""
    r0, g0 = plateau_grid(quick)
    ratios = r0 if ratios is None else ratios
    G = g0 if G is None else G
    return _pl.compute_plateau(PRESET, {c: PLATEAU_CASES[c] for c in cases}, ratios=ratios, G=G,
                               n=n, quick=quick, store_dir=store_dir, executor=executor,
                               workers=workers, scheduler=scheduler, g_range=G_TSR_RANGE,
                               prefix="tsr", budget=0)     # 004's protocol: the start grid alone


def compute_descent(*, G_ini: float = 5.0, n: int = 50, ratio_end: float = 0.9,
                    down_time: float = 60.0, history_dt: float = 0.25,
                    store_dir: str | Path | None = None, executor: str = "local",
                    workers: int | None = None,
                    scheduler: str | None = None) -> xr.Dataset:
    """004 sec. 4.6, Fig. 13 (:func:`autobalance.studies._plateau.compute_descent`); G_ini [mm/s],
    down_time and history_dt [s]."""
    return _pl.compute_descent(PRESET, G_ini=G_ini, n=n, ratio_end=ratio_end, down_time=down_time,
                               history_dt=history_dt, store_dir=store_dir, executor=executor,
                               workers=workers, scheduler=scheduler, prefix="tsr")
