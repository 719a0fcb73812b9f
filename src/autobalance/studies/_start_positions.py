"""The start-position Monte Carlo of any machine (004 sec. 4.2 generalised): one run from many
ball start positions, the grade at each read-out of the profile, and its statistics; the single
run with a family of starts of a given grade (004 Fig. 4); the machine's grades (004 Table 1).

Every study takes ``base``, the machine: a preset name, a TOML config path or a Config built in
Python (:func:`autobalance.config.from_models`) (the profile, the
options and the balls come from it), and returns an :class:`xarray.Dataset` with units in attrs.
"""
from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING

import numpy as np

from ..confidence import verdict
from ..physics.immobility import stick_threshold_grade
from ..physics.iso1940 import grade_value as _grade
from ..physics.iso1940 import unbalance_value as grade_to_unbalance
from .statistics import (REGION_NAMES, TIE_MM_S, mode_value, plateau_speed, profile_text, regions,
                         start_position_stats)

from .common import checkpoint_labels, default_starts, load, run_start_grid, store_path

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    import xarray as xr

    from ..config import Config
    from ..models import System

__all__ = ["compute_machine", "compute_monte_carlo", "compute_single", "compute_start_positions",
           "start_family", "start_positions_summary"]


def start_family(G_start: float, system: System, nominal_speed: float,
                 n: int = 24) -> np.ndarray:
    """Ball start angles (n, 2) [rad] with the grade G_start [mm/s] at rest: ball 1 at
    alpha_1 = 2 pi k / n, ball 2 on |U + m R (e^{i alpha_1} + e^{i alpha_2})| = U(G_start)
    (law of cosines; the branch with alpha_2 - arg c > 0). Rows without a solution or with
    touching balls (closer than the contact angle) are dropped.

    Parameters
    ----------
    G_start : float
        ISO 1940 grade of the start configuration [mm/s] (004 Fig. 4: G14).
    system : autobalance.models.System
        Two identical balls m [kg] on radius R [m], rotor unbalance U [kg*m], total mass M_t [kg].
    nominal_speed : float
        Speed Omega_nom of the grade [rad/s].
    n : int
        Ball-1 angles tried, 2 pi k / n.

    Returns
    -------
    ndarray (K, 2)
        (alpha_1, alpha_2) [rad], K <= n rows.
    """
    U = system.rotor.unbalance
    Ug = float(grade_to_unbalance(G_start, system.total_mass, nominal_speed))
    mR = system.balancer.masses[0] * system.balancer.race_radius
    out = []
    for a1 in 2 * np.pi * np.arange(n) / n:
        c = U + mR * np.exp(1j * a1)
        x = (Ug**2 - abs(c) ** 2 - mR**2) / (2 * mR * abs(c))
        if abs(x) <= 1:
            a2 = float(np.angle(c) + math.acos(x))
            gap = abs(np.angle(np.exp(1j * (a2 - a1))))
            if gap >= system.balancer.contact_angle:
                out.append((a1, a2))
    return np.array(out)


def compute_single(base: str | Path, save_dt: float = 0.01, G_start: float | None = 14.0,
                   n_family: int = 24, limit: float = 16.0) -> xr.Dataset:
    """004 Fig. 4: one TSR run with the balancer and the same run without it, plus the family
    of starts with the same initial grade.

    The paper's start angles are unknown. We run the profile from ``n_family`` starts with the
    paper's initial grade G_start = G14 (:func:`start_family`; ball 1 every 360/n_family deg) and
    plot the first of them (lowest ball-1 angle with a solution: 75/198 deg; chosen before
    looking at the results; ``G_start=None``:
    the preset's 45/135 deg, no family). Rotor at rest at t = 0. attrs report how many of the
    family reproduce the paper's statements about its run (``limit``: the target grade [mm/s],
    004: G16).

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    save_dt : float
        Spacing of the stored time history of the shown run [s].
    G_start : float or None
        Initial grade of the family of starts [mm/s] (004: G14); None = the preset's start
        angles, no family.
    n_family : int
        Number of ball-1 angles of the family (:func:`start_family`).
    limit : float
        Target grade of the paper's statements [mm/s] (004: G16).

    Returns
    -------
    xarray.Dataset
        Time histories of speed [rad/s], amplitude with and without balancer [m], ball angles
        [rad], grade G [mm/s] and residual angle [rad]; the family's grades [mm/s] at the peak of
        the run-up, the STD and the TSR read-outs; attrs with the grades [mm/s], read-out times
        [s] and the family's match counts.
    """
    import dataclasses

    import xarray as xr

    from ..models import InitialState
    from ..simulate import simulate, simulate_batch

    t0 = time.perf_counter()
    cfg = load(base)
    sysm, spin = cfg.system, cfg.spin
    wn = spin.nominal_speed
    fam = None if G_start is None else start_family(G_start, sysm, wn, n_family or 24)
    ang = cfg.initial.ball_angles if fam is None else fam[0]
    opts = dataclasses.replace(cfg.options, save_dt=save_dt)
    sim = simulate(sysm, spin, initial=InitialState(ball_angles=tuple(ang)), options=opts)
    bare = dataclasses.replace(sysm, balancer=dataclasses.replace(sysm.balancer, n_balls=0))
    sim0 = simulate(bare, spin, initial=InitialState(ball_angles=()), options=opts)
    g_ini = float(_grade(sysm.rotor.unbalance, sysm.total_mass, wn))
    cps = np.asarray(spin.checkpoints)
    ds = xr.Dataset(
        {"speed": ("time", sim.speed, {"units": "rad/s"}),
         "amplitude": ("time", sim.amplitude, {"units": "m", "long_name": "with balancer"}),
         "amplitude_no_balancer": ("time", np.interp(sim.t, sim0.t, sim0.amplitude),
                                   {"units": "m", "long_name": "without balancer"}),
         "ball_angle": (("time", "ball"), np.angle(np.exp(1j * sim.alpha)), {"units": "rad"}),
         "grade_G": ("time", sim.grade_G, {"units": "mm/s"}),
         "cog_angle": ("time", sim.residual_angle, {"units": "rad",
                                                     "long_name": "direction of the residual unbalance"})},
        coords={"time": ("time", sim.t, {"units": "s"}), "ball": np.arange(2)})
    k_std = int(np.argmin(np.abs(sim.t - cps[0])))
    attrs = {
        "study": "single", "G_ini": g_ini, "G_start": float(sim.grade_G[0]),
        "G_peak_runup": float(sim.grade_G[:k_std + 1].max()),
        "G_STD": float(sim.grade_G[k_std]), "G_TSR": float(sim.grade_G[-1]),
        "start_angles_deg": [float(x) for x in np.degrees(ang)], "t_std_s": float(cps[0]),
        "t_tsr_s": float(cps[-1]), "status": sim.status, "profile": profile_text(spin)}
    if fam is not None and n_family:
        tt = np.unique(np.concatenate([np.arange(0.0, cps[0], 0.02), cps]))
        res = simulate_batch([sysm] * len(fam), spin,
                             [InitialState(ball_angles=tuple(a)) for a in fam], options=opts,
                             out_times=tt)
        G = res.grade_G
        ks = int(np.argmin(np.abs(tt - cps[0])))
        peak, gs, gt = G[:, :ks + 1].max(axis=1), G[:, ks], G[:, -1]
        match = (peak > g_ini) & (gs > limit) & (gs <= g_ini) & (gt <= limit) & (gt < gs)
        ds["family_start_angle"] = (("family", "ball"), fam, {"units": "rad"})
        ds["family_G_peak_runup"] = ("family", peak, {"units": "mm/s"})
        ds["family_G_STD"] = ("family", gs, {"units": "mm/s"})
        ds["family_G_TSR"] = ("family", gt, {"units": "mm/s"})
        ds["family_match"] = ("family", match.astype(np.int8))
        attrs.update({"family_n": int(len(fam)), "family_match": int(match.sum()),
                      "family_peak_gt_ini": int((peak > g_ini).sum()),
                      "family_std_in_16_ini": int(((gs > limit) & (gs <= g_ini)).sum()),
                      "family_tsr_le_16": int((gt <= limit).sum())})
    attrs["wall_s"] = time.perf_counter() - t0
    ds.attrs.update(attrs)
    return ds


def compute_start_positions(base: str | Path | Config, *, n: int | None = None,
                            samples: int | None = None, seed: int = 0,
                            grid: dict | None = None, sets: Sequence[str] = (),
                            grade: float = 16.0, quick: bool = False, name: str = "starts",
                            store: str | Path | None = None, executor: str = "local",
                            workers: int | None = None, scheduler: str | None = None,
                            progress: bool = False) -> xr.Dataset:
    """The start-position Monte Carlo of any machine (004 sec. 4.2 generalised): the grade at
    every read-out of the profile from many ball start positions (004's equispaced grid or
    uniform random angles), per cell of an optional grid, with its percentiles, mode, share
    at or below ``grade`` and, between the first and last read-outs, 004 Table 2's regions.

    Parameters
    ----------
    base : str, Path or Config
        The machine: a preset name, a TOML config path or a Config (its system, profile,
        options and balls).
    n : int or None
        Positions per ball of the start grid; None = :func:`default_starts`.
    samples : int or None
        Uniform random start angles per cell instead of the grid (``n`` ignored).
    seed : int
        Seed of the random angles.
    grid : dict of str to list or None
        Config path -> values (SI, as for :func:`run_start_grid`), e.g. {"rotor.unbalance":
        [...]}; None = the machine alone.
    sets : sequence of str
        "path=value" overrides applied to ``base`` for every run.
    grade : float
        Target ISO 1940 grade G [mm/s] of the shares.
    quick : bool
        The coarse default grid.
    name : str
        Name of the sweep (and of its store under ``store``).
    store : str, Path or None
        The sweep store directory (resumed: a rerun computes nothing), or None (temporary).
    executor, workers, scheduler : str, int or None
        Where the runs go (:func:`run_start_grid`).
    progress : bool
        Show a progress bar on stderr.

    Returns
    -------
    xarray.Dataset
        grade_G [mm/s] over (cell coordinates..., sample, checkpoint), status, start_angle
        [rad]; per cell and checkpoint: grade_p5/p50/p95 and mode [mm/s], share_below_grade [-];
        with two read-outs or more, region_share [-] over 004's regions (first vs last
        read-out); attrs: G_ini and G_balls [mm/s], grade [mm/s], checkpoint labels, counts.
    """
    import xarray as xr

    from ..confidence import LEVEL, bootstrap_interval, share_interval
    from ..sweep.summary import percentile_intervals, percentiles, share_below, share_intervals

    t0 = time.perf_counter()
    cfg = load(base, sets, allow_liquid=True)         # only simulations: a liquid beside is modelled
    grid = dict(grid or {})
    N = cfg.system.balancer.n_balls
    n = default_starts(N, quick) if (n is None and samples is None) else n
    raw = run_start_grid(base, name, sets, grid, n or 0, store=store, executor=executor,
                         workers=workers, scheduler=scheduler, samples=samples, seed=seed,
                         progress=progress)
    cell_dims = [d for d in raw["grade_G"].dims if d not in ("sample", "checkpoint")]
    ds = raw[["grade_G", "status", "start_angle"]].copy()
    p = percentiles(raw, "grade_G")
    p_ci = percentile_intervals(raw, "grade_G")
    for q in (5, 50, 95):
        ds[f"grade_p{q}"] = p.sel(percentile=q, drop=True).assign_attrs(units="mm/s")
        ds[f"grade_p{q}_ci"] = p_ci.sel(percentile=q, drop=True).assign_attrs(
            units="mm/s", confidence_level=LEVEL,
            long_name=f"interval of the {q}th percentile (order statistics; +-inf: unbounded)")
    ds["share_below_grade"] = share_below(raw, grade).assign_attrs(
        units="-", long_name=f"share of runs with G <= {grade:g} mm/s")
    ds["share_below_grade_ci"] = share_intervals(raw, grade).assign_attrs(
        confidence_level=LEVEL, long_name=f"interval of the share with G <= {grade:g} mm/s "
                                          "(Clopper-Pearson)")
    ds["runs_ok"] = (raw["status"] == 0).sum("sample").assign_attrs(
        units="1", long_name="runs that finished (the statistics' sample size)")
    g_ok = raw["grade_G"].where(raw["status"] == 0)
    stacked = g_ok.stack(_cell=cell_dims) if cell_dims else g_ok.expand_dims(_cell=[0])
    labels = checkpoint_labels(cfg.spin)
    modes = np.full((stacked.sizes["_cell"], len(labels)), np.nan)
    modes_ci = np.full((stacked.sizes["_cell"], len(labels), 2), np.nan)
    ties = (0.0, TIE_MM_S)                     # 004's strict table, and ties taken as equal
    region_rows = {tie: [] for tie in ties}
    g_ini = float(_grade(cfg.system.rotor.unbalance, cfg.system.total_mass, cfg.spin.nominal_speed))
    for k in range(stacked.sizes["_cell"]):
        gk = stacked.isel(_cell=k).transpose("sample", "checkpoint").values
        for j in range(len(labels)):
            col = gk[:, j][np.isfinite(gk[:, j])]
            if col.size:
                modes[k, j], *modes_ci[k, j] = bootstrap_interval(col, mode_value)
        if len(labels) >= 2:
            okr = np.isfinite(gk[:, 0]) & np.isfinite(gk[:, -1])
            gi = g_ini
            if "rotor__unbalance" in cell_dims:
                u = float(stacked.isel(_cell=k)["rotor__unbalance"])
                gi = float(_grade(u, cfg.system.total_mass, cfg.spin.nominal_speed))
            for tie in ties:
                region_rows[tie].append(regions(gk[okr, 0], gk[okr, -1], gi, tie) if okr.any()
                                        else dict.fromkeys(REGION_NAMES, np.nan))

    def per_cell(values, dim: str, coord):
        """(cell, dim) values -> a variable over the grid's cells (none without a grid)."""
        da = xr.DataArray(values, dims=("_cell", dim), coords={"_cell": stacked["_cell"], dim: coord})
        return da.unstack("_cell") if cell_dims else da.isel(_cell=0, drop=True)

    ds["grade_mode"] = per_cell(modes, "checkpoint", raw["checkpoint"]).assign_attrs(
        units="mm/s", long_name="mode (1 mm/s bins)")
    ds["grade_mode_ci"] = xr.concat(
        [per_cell(modes_ci[..., b], "checkpoint", raw["checkpoint"]) for b in (0, 1)],
        dim=xr.DataArray(["lo", "hi"], dims="bound")).transpose(..., "bound").assign_attrs(
        units="mm/s", confidence_level=LEVEL, long_name="interval of the mode (bootstrap)")
    if region_rows[0.0]:
        names = list(REGION_NAMES)
        strict, tied = ([[r[m] for m in names] for r in region_rows[tie]] for tie in ties)
        ds["region_share"] = per_cell(strict, "region", names).assign_attrs(
            units="-", long_name="004 Table 2 regions, first vs last read-out")
        ds["region_share_tied"] = per_cell(tied, "region", names).assign_attrs(
            units="-", tie_mm_s=TIE_MM_S,
            long_name=f"004 Table 2 regions, grades within {TIE_MM_S:g} mm/s taken as equal")
        n_both = (raw["status"] == 0).sum("sample")         # the runs the regions count
        for var in ("region_share", "region_share_tied"):
            _, lo, hi = share_interval(np.rint(ds[var] * n_both).values, n_both.broadcast_like(
                ds[var]).values)
            ds[f"{var}_ci"] = xr.DataArray(np.stack([lo, hi], -1), dims=(*ds[var].dims, "bound"),
                                           coords=ds[var].coords).assign_attrs(
                units="-", confidence_level=LEVEL, long_name="interval of the region share "
                                                             "(Clopper-Pearson)")
    ds = ds.assign_coords(checkpoint_label=("checkpoint", labels))
    for d in cell_dims:                   # the unstacked per-cell variables drop these attrs
        ds[d].attrs.update(raw[d].attrs)
    ok = raw["status"].values == 0
    ds.attrs.update({
        "study": "start_positions", "n_balls": N,
        "starts": (f"start grid, {n} positions per ball" if samples is None
                   else f"{samples} uniform random starts (seed {seed})"),
        "runs": int(ok.size), "failed": int((~ok).sum()), "grade": float(grade),
        "G_ini": g_ini, "G_balls": float(_grade(cfg.system.balancer.capacity,
                                                cfg.system.total_mass, cfg.spin.nominal_speed)),
        "nominal_speed_rad_s": float(cfg.spin.nominal_speed),
        "wall_s": time.perf_counter() - t0, "profile": profile_text(cfg.spin)})
    return ds


def _pair(da) -> list:
    """A (bound,) DataArray as [lo, hi] floats (+-inf where unbounded: null in JSON)."""
    return [float(v) for v in np.asarray(da).ravel()]


def _row(label: str, t: float, pq: dict, pq_ci: dict, mode: float, mode_ci, share: float,
         share_ci, runs: int, grade: float) -> dict:
    """One checkpoint's statistics with their intervals and the verdict of p95 <= grade."""
    return {"label": label, "time_s": float(t),
            **{f"p{q}_grade_G_mm_s": float(pq[q]) for q in (5, 50, 95)},
            **{f"p{q}_grade_G_mm_s_ci": _pair(pq_ci[q]) for q in (5, 50, 95)},
            "mode_grade_G_mm_s": float(mode), "mode_grade_G_mm_s_ci": _pair(mode_ci),
            "share_below_grade": float(share), "share_below_grade_ci": _pair(share_ci),
            "runs_ok": int(runs),
            "p95_verdict": verdict(*_pair(pq_ci[95]), grade)}


def _checkpoint_rows(ds, sel: dict) -> list:
    """Per checkpoint of one cell (``sel``: its grid coordinates) label, time [s],
    p5/p50/p95 and mode [mm/s], share at or below the target grade [-], each with its
    interval (``..._ci``), the runs counted and the verdict of p95 <= the target."""
    rows = []
    for i, t in enumerate(ds["checkpoint"].values):
        at = {**sel, "checkpoint": i}
        rows.append(_row(str(ds["checkpoint_label"].values[i]), t,
                         {q: ds[f"grade_p{q}"].isel(at) for q in (5, 50, 95)},
                         {q: ds[f"grade_p{q}_ci"].isel(at) for q in (5, 50, 95)},
                         ds["grade_mode"].isel(at), ds["grade_mode_ci"].isel(at),
                         ds["share_below_grade"].isel(at), ds["share_below_grade_ci"].isel(at),
                         ds["runs_ok"].isel(sel), ds.attrs["grade"]))
    return rows


def _region_rows(ds, sel: dict) -> dict:
    """004 Table 2's region shares of one cell, strict ("regions") and with ties taken as equal
    ("regions_tied"), with their intervals ("regions_ci", "regions_tied_ci": [lo, hi] per
    region); {} without two read-outs."""
    if "region_share" not in ds:
        return {}
    names = [str(r) for r in ds["region"].values]
    out = {}
    for key, var in (("regions", "region_share"), ("regions_tied", "region_share_tied")):
        out[key] = dict(zip(names, map(float, ds[var].isel(sel).values)))
        ci = ds[f"{var}_ci"].isel(sel).values
        out[f"{key}_ci"] = {n: [float(v) for v in ci[k]] for k, n in enumerate(names)}
    return out


def start_positions_summary(ds: xr.Dataset) -> dict:
    """JSON-ready summary of a :func:`compute_start_positions` result: per checkpoint its
    label, time [s], p5/p50/p95 and mode [mm/s] and share at or below the target grade; the
    region shares (004 Table 2). With a grid, the same per cell under "cells" (each with its
    coordinates in SI, keys with units), and "checkpoints" pooled over every cell.

    Parameters
    ----------
    ds : xarray.Dataset
        The study's dataset.

    Returns
    -------
    dict
        "grade_G_mm_s", "runs", "failed", "starts", "G_ini_mm_s", "G_balls_mm_s",
        "confidence_level", "checkpoints" (each percentile, the mode and the share with its
        interval ``..._ci`` = [lo, hi]: order statistics, bootstrap and Clopper-Pearson,
        :mod:`autobalance.confidence`; an end the runs cannot bound is null in JSON; "runs_ok",
        "p95_verdict" of p95 <= the target: meets, fails or undecided), "regions" and
        "regions_ci" (two read-outs or more), "cells" (with a grid).
    """
    from ..confidence import LEVEL, bootstrap_interval
    from ..sweep.summary import (grid_axes, percentile_intervals, percentiles, share_below,
                                 share_intervals)

    a = ds.attrs
    cells = [d for d in ds["grade_G"].dims if d not in ("sample", "checkpoint")]
    out = {"study": "start-positions", "grade_G_mm_s": a["grade"], "runs": a["runs"],
           "failed": a["failed"], "starts": a["starts"], "G_ini_mm_s": a["G_ini"],
           "G_balls_mm_s": a["G_balls"], "confidence_level": LEVEL}
    if not cells:
        out["checkpoints"] = _checkpoint_rows(ds, {})
        out.update(_region_rows(ds, {}))
        if "region_share" in ds:
            out["tie_mm_s"] = TIE_MM_S
        return out
    dims = (*cells, "sample")
    p = percentiles(ds, "grade_G", (5, 50, 95), dim=dims)
    p_ci = percentile_intervals(ds, "grade_G", (5, 50, 95), dim=dims)
    share = share_below(ds, a["grade"], dim=dims)
    share_ci = share_intervals(ds, a["grade"], dim=dims)
    g_ok = ds["grade_G"].where(ds["status"] == 0)
    pooled = []
    for i, t in enumerate(ds["checkpoint"].values):
        col = g_ok.isel(checkpoint=i).values.ravel()
        col = col[np.isfinite(col)]
        m, *m_ci = bootstrap_interval(col, mode_value) if col.size else (math.nan,) * 3
        pooled.append(_row(str(ds["checkpoint_label"].values[i]), t,
                           {q: p.sel(percentile=q).isel(checkpoint=i) for q in (5, 50, 95)},
                           {q: p_ci.sel(percentile=q).isel(checkpoint=i) for q in (5, 50, 95)},
                           m, m_ci, share.isel(checkpoint=i), share_ci.isel(checkpoint=i),
                           col.size, a["grade"]))
    out["checkpoints"] = pooled
    out["pooled_over_cells"] = True
    axes = {a["dim"]: a for a in grid_axes(ds)}
    out["grid"] = list(axes.values())
    rows = []
    for idx in np.ndindex(*(ds.sizes[d] for d in cells)):
        sel = dict(zip(cells, idx))
        rows.append({"coords": {axes[d]["key"]: axes[d]["values"][k] for d, k in sel.items()},
                     "checkpoints": _checkpoint_rows(ds, sel), **_region_rows(ds, sel)})
    out["cells"] = rows
    return out


def compute_monte_carlo(base: str | Path, n: int = 50, *, plateau_ratio: float | None = None,
                        store_dir: str | Path | None = None, executor: str = "local",
                        workers: int | None = None, scheduler: str | None = None,
                        limit: float = 16.0, prefix: str = "study") -> xr.Dataset:
    """004 sec. 4.2: n x n equispaced start positions, identical balls -> n(n+1)/2 runs
    (1275 for n = 50), G at the STD (18 s) and TSR (90 s) read-outs.

    ``plateau_ratio``: run with the TSR plateau at this multiple of Omega_n = sqrt(k/M_t)
    instead of the preset's 100 Hz (a sensitivity study; None = the preset). ``limit``: the
    target grade [mm/s] of the shares (004: G16). ``prefix``: the sweep's name prefix.

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    n : int
        Start positions per ball (004: 50).
    plateau_ratio : float or None
        TSR plateau speed as a multiple of Omega_n [-]; None = the preset's plateau.
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the sweeps run: ``store_dir`` holds one resumable store per sweep (a rerun
        of the same description computes nothing; None = temporary stores); ``executor``,
        ``workers`` and ``scheduler`` as for :func:`autobalance.studies.common.run_start_grid`.
    limit : float
        Target grade of the shares [mm/s] (004: G16).
    prefix : str
        Prefix of the sweeps' names.

    Returns
    -------
    xarray.Dataset
        G_STD and G_TSR [mm/s] per start, start angles [rad], status; attrs: 004 Table 2
        statistics (:func:`~autobalance.studies.statistics.start_position_stats`), G_ini and
        the balls' grade [mm/s], plateau [Hz] and its stick threshold [mm/s].
    """
    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base)
    plateau_speed(cfg.spin)         # a motor drive has no STD/TSR read-outs: refused before any run
    sets, name = [], f"mc-n{n}"
    if plateau_ratio is not None:
        fn = cfg.system.natural_frequencies[0]
        sets, name = [f"profile.plateau={plateau_ratio * fn!r}"], f"{name}-plateau{plateau_ratio:g}"
        cfg = load(base, sets)
    raw = compute_start_positions(base, n=n, sets=sets, grade=limit, name=f"{prefix}-{name}",
                                  store=store_path(store_dir, name), executor=executor,
                                  workers=workers, scheduler=scheduler)
    g = raw["grade_G"].values                      # (sample, checkpoint)
    ok = raw["status"].values == 0
    g_ini = float(_grade(cfg.system.rotor.unbalance, cfg.system.total_mass, cfg.spin.nominal_speed))
    w_pl = plateau_speed(cfg.spin)
    ds = xr.Dataset({"G_STD": ("sample", g[:, 0], {"units": "mm/s"}),
                     "G_TSR": ("sample", g[:, 1], {"units": "mm/s"}),
                     "start_angle": (("sample", "ball"), raw["start_angle"].values, {"units": "rad"}),
                     "status": ("sample", raw["status"].values)})
    ds.attrs.update({
        "study": "monte_carlo", "n": n, "runs": int(ok.size), "failed": int((~ok).sum()),
        "G_ini": g_ini, "G_balls": float(_grade(cfg.system.balancer.capacity, cfg.system.total_mass,
                                                cfg.spin.nominal_speed)),
        **start_position_stats(g[ok, 0], g[ok, 1], g_ini, limit),
        "plateau_hz": w_pl / (2 * np.pi),
        "G_stick_plateau": float(stick_threshold_grade(cfg.system, w_pl, cfg.spin.nominal_speed)),
        "wall_s": time.perf_counter() - t0, "profile": profile_text(cfg.spin)})
    return ds


def compute_machine(base: str | Path) -> xr.Dataset:
    """The machine's derived numbers (004 Table 1): resonance f_n = sqrt(k/M_t)/2pi [Hz] (Jeffcott), the rotor's
    grade G_ini and the balls' grade 2 m R / M_t Omega_nom [mm/s] (004 sec. 4), and the profile
    (004 Fig. 3, our reading: docs/model.md sec. 5) sampled every 0.1 s.

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).

    Returns
    -------
    xarray.Dataset
        speed [rad/s] against time [s]; attrs f_n_hz [Hz], G_ini and G_balls [mm/s],
        checkpoints_s [s] and the profile's text.
    """
    import xarray as xr

    cfg = load(base)
    s, spin = cfg.system, cfg.spin
    if not hasattr(spin, "speed"):
        from ..models import ParameterError

        raise ParameterError("profile.kind", spin.name, "a motor drive's speed is an outcome "
                             "of the run, not a table to sample: use a prescribed profile")
    t = np.arange(0.0, float(spin.duration) + 1e-9, 0.1)
    ds = xr.Dataset({"speed": ("time", np.asarray(spin.speed(t), float), {"units": "rad/s"})},
                    coords={"time": ("time", t, {"units": "s"})})
    ds.attrs.update({
        "study": "table1", "f_n_hz": float(s.natural_frequencies[0] / (2 * np.pi)),
        "G_ini": float(_grade(s.rotor.unbalance, s.total_mass, spin.nominal_speed)),
        "G_balls": float(_grade(s.balancer.capacity, s.total_mass, spin.nominal_speed)),
        "checkpoints_s": [float(c) for c in spin.checkpoints], "profile": profile_text(spin)})
    return ds
