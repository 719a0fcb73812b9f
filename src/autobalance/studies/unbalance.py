"""Residual grade against the initial unbalance, for any machine (004 sec. 4.3-4.5 generalised):
percentiles over start positions at each read-out, per (friction, damping) case, and the same
against a second speed profile (004 Fig. 9)."""
from __future__ import annotations

import time

import numpy as np

from ..physics.iso1940 import grade_value as _grade
from ..physics.iso1940 import unbalance_value as grade_to_unbalance
from .start_positions import case_sets, load, run_start_grid, store_path
from .statistics import profile_text

__all__ = ["compute_profile", "compute_unbalance", "unbalance_grid"]


def unbalance_grid(quick: bool):
    """Initial grades [mm/s] of the sweep: [G0, G50] every 5 (quick) or 2 mm/s (004 sec. 4.3).

    Parameters
    ----------
    quick : bool
        Steps of 5 mm/s instead of 2 mm/s.

    Returns
    -------
    ndarray
        G_ini [mm/s].
    """
    return np.arange(0.0, 50.1, 5.0) if quick else np.arange(0.0, 50.1, 2.0)


def compute_unbalance(base, cases=None, *, G=None, n: int = 50, quick: bool = False,
                      store_dir=None, executor="local", workers=None, scheduler=None,
                      prefix: str = "study"):
    """004 sec. 4.3-4.5: G_ini over [G0, G50] x the start grid for each (mu_r, c_r) case;
    5/50/95 % of G_STD (18 s) and G_TSR (90 s), valid ranges for G16 and efficiencies.

    ``cases``: name -> (mu_r, c_r), the factors on the machine's rolling resistance and damping
    (None: {"nominal": (1, 1)}); ``G``: the initial grades [mm/s] (None: :func:`unbalance_grid`).

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    cases : dict of str to (float, float) or None
        Case name -> (mu_r, c_r), factors [-] on the rolling resistance and the damping.
    G : array_like or None
        Initial grades [mm/s]; None = :func:`unbalance_grid`.
    n : int
        Start positions per ball (004: 50).
    quick : bool
        The coarse :func:`unbalance_grid`.
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the sweeps run: ``store_dir`` holds one resumable store per sweep (a rerun
        of the same description computes nothing; None = temporary stores); ``executor``,
        ``workers`` and ``scheduler`` as for :func:`autobalance.studies.start_positions.run_start_grid`.
    prefix : str
        Prefix of the sweeps' names.

    Returns
    -------
    xarray.Dataset
        grade_G [mm/s] over (case, G_ini [mm/s], procedure STD/TSR, percentile 5/50/95),
        failed_runs per case; attrs G_balls [mm/s], grid_step [mm/s].
    """
    cases = {"nominal": (1.0, 1.0)} if cases is None else dict(cases)
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base)
    Gv = unbalance_grid(quick) if G is None else np.asarray(G, float)
    U = grade_to_unbalance(Gv, cfg.system.total_mass, cfg.spin.nominal_speed)
    q = np.array([5.0, 50.0, 95.0])
    data = np.full((len(cases), Gv.size, 2, q.size), np.nan)
    failed = np.zeros(len(cases), int)
    for ci, case in enumerate(cases):
        mu_r, c_r = cases[case]
        raw = run_start_grid(base, f"{prefix}-unb-{case}-n{n}-g{Gv.size}", case_sets(cfg, mu_r, c_r),
                         {"rotor.unbalance": [float(u) for u in U]}, n,
                             store=store_path(store_dir, f"unbalance-{case}-n{n}-g{Gv.size}"),
                             executor=executor, workers=workers, scheduler=scheduler)
        g = raw["grade_G"].where(raw["status"] == 0)
        data[ci] = g.quantile(q / 100, dim="sample").transpose("rotor__unbalance", "checkpoint",
                                                               "quantile").values
        failed[ci] = int((raw["status"] != 0).sum())
    ds = xr.Dataset({"grade_G": (("case", "G_ini", "procedure", "percentile"), data,
                                 {"units": "mm/s", "long_name": "residual grade percentile"}),
                     "failed_runs": ("case", failed)},
                    coords={"case": list(cases), "G_ini": ("G_ini", Gv, {"units": "mm/s"}),
                            "procedure": ["STD", "TSR"], "percentile": q,
                            "mu_r": ("case", [cases[c][0] for c in cases]),
                            "c_r": ("case", [cases[c][1] for c in cases])})
    G_b = float(_grade(cfg.system.balancer.capacity, cfg.system.total_mass, cfg.spin.nominal_speed))
    ds.attrs.update({"study": "unbalance", "n": n, "G_balls": G_b, "grid_step": float(np.diff(Gv).max()),
                     "wall_s": time.perf_counter() - t0, "profile": profile_text(cfg.spin)})
    return ds


def compute_profile(base, other_sets, *, G=None, n: int = 50, quick: bool = False, store_dir=None,
                    executor="local", workers=None, scheduler=None, unbalance_ds=None,
                    prefix: str = "study", other_text: str = ""):
    """004 sec. 4.4, Fig. 9: 95 % isolines of the STD (18 s), TSR (90 s) and a 3x slower run-up
    (0 -> 167 Hz in 54 s, hold to 90 s, read at 90 s) against G_ini (nominal mu, c).

    ``other_sets``: the overrides that make the other profile ("slow"), e.g. 004's
    ``SLOW_SETS``; ``other_text``: its description for the attrs.

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    other_sets : iterable of str
        "path=value" overrides that make the other profile.
    G : array_like or None
        Initial grades [mm/s]; None = :func:`unbalance_grid`.
    n : int
        Start positions per ball.
    quick : bool
        The coarse :func:`unbalance_grid`.
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the sweeps run: ``store_dir`` holds one resumable store per sweep (a rerun
        of the same description computes nothing; None = temporary stores); ``executor``,
        ``workers`` and ``scheduler`` as for :func:`autobalance.studies.start_positions.run_start_grid`.
    unbalance_ds : xarray.Dataset or None
        A :func:`compute_unbalance` result to reuse for STD and TSR when it has the same grades,
        ``n`` and a "nominal" case; otherwise it is computed.
    prefix : str
        Prefix of the sweeps' names.
    other_text : str
        Description of the other profile for the attrs (default: ``other_sets`` joined).

    Returns
    -------
    xarray.Dataset
        grade_G [mm/s] over (G_ini [mm/s], procedure STD/TSR/slow, percentile 5/50/95).
    """
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base)
    Gv = unbalance_grid(quick) if G is None else np.asarray(G, float)
    if unbalance_ds is None or not np.array_equal(unbalance_ds["G_ini"].values, Gv) \
            or "nominal" not in unbalance_ds["case"].values or unbalance_ds.attrs["n"] != n:
        unbalance_ds = compute_unbalance(base, {"nominal": (1.0, 1.0)}, G=Gv, n=n,
                                         store_dir=store_dir, executor=executor, workers=workers,
                                         scheduler=scheduler, prefix=prefix)
    U = grade_to_unbalance(Gv, cfg.system.total_mass, cfg.spin.nominal_speed)
    raw = run_start_grid(base, f"{prefix}-slow-n{n}-g{Gv.size}", list(other_sets),
                         {"rotor.unbalance": [float(u) for u in U]}, n,
                         store=store_path(store_dir, f"slow-n{n}-g{Gv.size}"), executor=executor,
                         workers=workers, scheduler=scheduler)
    g = raw["grade_G"].where(raw["status"] == 0).isel(checkpoint=-1)
    q = np.array([5.0, 50.0, 95.0])
    slow = g.quantile(q / 100, dim="sample").transpose("rotor__unbalance", "quantile").values
    base = unbalance_ds["grade_G"].sel(case="nominal").values        # (G, procedure, q)
    data = np.concatenate([base, slow[:, None, :]], axis=1)
    ds = xr.Dataset({"grade_G": (("G_ini", "procedure", "percentile"), data, {"units": "mm/s"})},
                    coords={"G_ini": ("G_ini", Gv, {"units": "mm/s"}),
                            "procedure": ["STD", "TSR", "slow"], "percentile": q})
    ds.attrs.update({"study": "profile", "n": n, "wall_s": time.perf_counter() - t0,
                     "profile": profile_text(cfg.spin),
                     "slow_profile": other_text or "; ".join(other_sets)})
    return ds
