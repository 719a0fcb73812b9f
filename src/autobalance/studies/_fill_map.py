"""The fill map of a liquid balancer (any machine with a ``[liquid]`` section): the steady whirl
over fill x speed with the liquid from physics (the quasi-static liquid in the displaced
chamber, :func:`autobalance.liquid.steady.physical_fill_sweep`; below each fill's start speed
a centred pool on a vertical axis, a puddle held by gravity on a horizontal one), beside the
rotor without liquid. It answers the design questions of
003 Fig. 5-6 for any machine: which fill balances at which speed, how much, and where the
resonance moves. docs/liquid/machine.md sec. 3f.
"""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    import xarray as xr

    from ..config import Config
    from ..models import LiquidDevice

__all__ = ["compute_fill_map", "compute_fill_study", "compute_linear_map", "compute_stability_map",
           "default_fills", "dynamic_speeds", "fill_map_summary"]

#: Time at each speed of the coupled film's runs of the stability map [s].
DYNAMIC_DURATION = 6.0

#: Default speeds, as fractions of the natural frequency with the chamber's liquid [-].
SPEED_RATIOS = (0.3, 2.0)
#: Efficiencies within this fraction of the best count as equal [-] (above resonance the
#: physical model's efficiency is flat in the fill once the film closes into an intact ring).
TIE = 0.01


def default_fills(device: LiquidDevice) -> np.ndarray:
    """The default fills of a liquid balancer's maps and sweeps: 10 fills from 0.25 to 2.5 times
    its own, each at most 0.9 of the chamber; with several chambers the total of all chambers,
    each chamber's fill scaled alike (:func:`chamber_fills`), at most 0.9 of the fullest
    chamber.

    Parameters
    ----------
    device : autobalance.models.LiquidDevice
        The ``[liquid]`` section (volumes V and chamber volumes [m^3]).

    Returns
    -------
    ndarray
        Fills [m^3].
    """
    cap = min(0.9 * c.chamber_volume / c.volume for c in device.chambers)
    return np.minimum(np.linspace(0.25, 2.5, 10), cap) * device.total_volume


def chamber_fills(device: LiquidDevice, fill: float) -> list[float]:
    """Each chamber's volume [m^3] for the total fill ``fill`` [m^3]: the machine's own volumes
    scaled alike (one chamber: ``[fill]``).

    Parameters
    ----------
    device : autobalance.models.LiquidDevice
        The ``[liquid]`` section.
    fill : float
        Total fill [m^3].
    """
    return [float(fill) * c.volume / device.total_volume for c in device.chambers]


def compute_fill_map(base: str | Path | Config, *, fills: Sequence[float] | None = None,
                     speeds: Sequence[float] | None = None, quick: bool = False,
                     sets: Sequence[str] = ()) -> xr.Dataset:
    """Steady whirl amplitude over fill x speed for a liquid-balancer machine.

    Parameters
    ----------
    base : str, Path or Config
        The machine (a ``[liquid]`` section; its volume is replaced by each fill).
    fills : sequence of float or None
        Fills [m^3], > 0 and below the chamber volume; None: :func:`default_fills`.
    speeds : sequence of float or None
        Increasing speeds [rad/s]; None: from 0.3 times the natural frequency with the
        machine's liquid as rigid mass to 2 times it or the nominal speed if higher, 36 speeds
        (quick) or 121.
    quick : bool
        Coarser default speed grid.
    sets : sequence of str
        Overrides "path=value" (as --set).

    Returns
    -------
    xarray.Dataset
        ``amplitude`` (fill, speed) [m], ``amplitude_without_liquid`` (speed) [m], ``efficiency``
        (fill, speed) [-] (> 1: the liquid lowers the whirl), ``entrained`` (fill, speed) (the
        speed is above the fill's ``entrainment_speed`` [rad/s]: 003 eq 6 on a vertical axis,
        the ring's start g/Omega^2 = R/10 on a horizontal one, :func:`autobalance.liquid.steady.
        start_speed`), ``resonance`` (fill) [rad/s] (the speed of the largest whirl on the
        grid). On a horizontal axis the ring is the planar quasi-static liquid.
    """
    import xarray as xr

    from ..config import Config, load_config, replace_values
    from ..config.overrides import parse_override
    from ..models.liquid_balancer import G_STANDARD, LiquidBalancer
    from ..liquid.simulate import film_rotor, require_liquid_machine
    from ..liquid.steady import pool_response, start_speed, steady_amplitude

    t0 = time.perf_counter()
    cfg = (replace_values(base, dict(parse_override(s) for s in sets)) if sets else base) \
        if isinstance(base, Config) else load_config(base, list(sets))
    s = cfg.system
    require_liquid_machine(s)         # one-line refusals of what the liquid models do not cover
    L = s.liquid
    for c in L.chambers:
        LiquidBalancer.of(c)          # and of partitions, which the quasi-static liquid has not
    rotor = film_rotor(s)
    g = s.gravity.g if L.axis == "horizontal" else G_STANDARD
    V = np.asarray(default_fills(L) if fills is None else fills, float)
    v_top = min(c.chamber_volume / c.volume for c in L.chambers) * L.total_volume
    if V.ndim != 1 or V.size < 1 or np.any(V <= 0) or np.any(V >= v_top):
        raise ParameterError("fills", [float(x) for x in np.atleast_1d(V)], f"must be volumes in (0, "
                             f"{v_top:.4g}) m^3 (" + ("the chamber)" if L.n_chambers == 1 else
                             "the total of all chambers, scaled alike, until one is full)"))
    wn = np.sqrt(s.suspension.kx / s.total_mass)
    top = max(SPEED_RATIOS[1] * wn, float(cfg.spin.nominal_speed))
    W = np.asarray(np.linspace(SPEED_RATIOS[0] * wn, top, 36 if quick else 121)
                   if speeds is None else speeds, float)
    if W.ndim != 1 or W.size < 2 or np.any(W <= 0) or np.any(np.diff(W) <= 0):
        raise ParameterError("speeds", [float(x) for x in np.atleast_1d(W)], "must be >= 2 increasing "
                             "speeds > 0 [rad/s]")
    per = [[(c.chamber_radius, c.chamber_height, c.inner_radius, v)
            for c, v in zip(L.chambers, chamber_fills(L, f))] for f in V]
    amp = np.array([[steady_amplitude(rotor, p, L.density, w, g, axis=L.axis) for w in W]
                    for p in per])
    dry = np.abs(pool_response(rotor, 0.0, L.density, W))
    w0 = np.array([max(start_speed(v, R, h, g, axis=L.axis, inner_radius=ri)
                       for R, h, ri, v in p) for p in per])
    vertical = L.axis == "vertical"
    ds = xr.Dataset(
        {"amplitude": (("fill", "speed"), amp, {"units": "m", "long_name": "steady whirl"}),
         "amplitude_without_liquid": ("speed", dry, {"units": "m"}),
         "efficiency": (("fill", "speed"), dry[None, :] / amp,
                        {"units": "1", "long_name": "A(no liquid) / A(liquid)"}),
         "entrained": (("fill", "speed"), W[None, :] >= w0[:, None]),
         "entrainment_speed": ("fill", w0, {"units": "rad/s", "long_name": "003 eq 6" if vertical
                                            else "ring start: g/Omega^2 = R/10"}),
         "resonance": ("fill", W[np.argmax(amp, axis=1)], {"units": "rad/s"}),
         **({} if L.n_chambers == 1 else {"chamber_fill": (
             ("fill", "chamber"), np.array([[x[3] for x in p] for p in per]),
             {"units": "m^3", "long_name": "each chamber's volume (the total scaled alike)"})})},
        coords={"fill": ("fill", V, {"units": "m^3", **({} if L.n_chambers == 1 else {
                    "long_name": "total of all chambers"})}),
                "speed": ("speed", W, {"units": "rad/s"}),
                **({} if L.n_chambers == 1 else {"chamber_radius": (
                    "chamber", [c.chamber_radius for c in L.chambers], {"units": "m"})})},
        attrs={"machine": cfg.name, "axis": L.axis,
               "model": "quasi-static liquid in the displaced chamber (vertical axis); a centred "
               "pool below the entrainment speed" if vertical else "quasi-static liquid in the "
               "displaced chamber, planar (horizontal axis; gravity's offset g/Omega^2 <= R/10 "
               "left out); a puddle held by gravity (a mass, no unbalance) below the ring's "
               "start speed",
               "nominal_speed_rad_s": float(cfg.spin.nominal_speed),
               "resonance_without_liquid_rad_s": float(W[np.argmax(dry)]),
               "wall_time_s": time.perf_counter() - t0})
    return ds


def compute_linear_map(base: str | Path | Config, *, fills: Sequence[float],
                       speeds: Sequence[float], n_cells: int = 64) -> xr.Dataset:
    """The linear stability of the balanced (centred) state over fill x speed
    (:func:`autobalance.liquid.stability.ring_stability`, docs/liquid/stability.md sec. 3j): the
    growth rate of its least stable perturbation; NaN below the fill's entrainment speed (a pool).
    On a horizontal axis about the periodic state under gravity (Floquet,
    docs/liquid/horizontal-axis.md sec. 3m; NaN also where no periodic state with an intact film
    exists).

    Parameters
    ----------
    base : str, Path or Config
        The machine (a liquid balancer alone).
    fills : sequence of float
        Total fills [m^3] (several chambers scaled alike, :func:`chamber_fills`).
    speeds : sequence of float
        Speeds [rad/s].
    n_cells : int
        Cells around each wall [-].

    Returns
    -------
    xarray.Dataset
        ``growth_rate`` (fill, speed) [1/s], ``balanced_stable`` (fill, speed) (growth rate < 0).
    """
    import dataclasses

    import xarray as xr

    from ..config import load_config
    from ..liquid.stability import machine_stability

    s = (base if hasattr(base, "system") else load_config(base)).system
    L = s.liquid
    g = np.full((len(fills), len(speeds)), np.nan)
    for i, v in enumerate(fills):            # the machine with this fill, every chamber scaled
        vols = chamber_fills(L, v)
        liq = dataclasses.replace(L, volume=vols[0] if L.n_chambers == 1 else tuple(vols))
        g[i] = machine_stability(dataclasses.replace(s, liquid=liq), speeds,
                                 n_cells)["growth_rate_1_s"]
    return xr.Dataset({"growth_rate": (("fill", "linear_speed"), g, {
                           "units": "1/s", "long_name": "growth rate of the balanced state's "
                           "least stable perturbation (NaN: a pool)"}),
                       "balanced_stable": (("fill", "linear_speed"), g < 0.0)},
                      coords={"fill": ("fill", np.asarray(fills, float), {"units": "m^3"}),
                              "linear_speed": ("linear_speed", np.asarray(speeds, float),
                                               {"units": "rad/s"})},
                      attrs={"linear_cells": int(n_cells)})


def fill_map_summary(ds: xr.Dataset) -> dict:
    """The fill map's answers (SI): per fill its resonance, the speeds where it balances
    (efficiency > 1) and its efficiency at the nominal speed; the fills within :data:`TIE` of
    the best efficiency at the nominal speed and the least of them (the design's fill: no more
    liquid than balances).

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`compute_fill_map`'s result.

    Returns
    -------
    dict
        With :func:`compute_linear_map`'s growth rates also: per fill
        ``balanced_unstable_rad_s``, the speed ranges where the balanced state is unstable;
        ``balanced_stable_at_nominal`` per fill; ``least_stable_fill_within_tie_m3``, the least
        fill within the tie whose balanced state is stable at the nominal speed (None if none).
    """
    W = ds["speed"].values
    wn = float(ds.attrs["nominal_speed_rad_s"])
    k = int(np.argmin(np.abs(W - wn)))
    fills = []
    for i, v in enumerate(ds["fill"].values):
        e = ds["efficiency"].values[i]
        helps = W[e > 1.0]
        fills.append({"fill_m3": float(v), "resonance_rad_s": float(ds["resonance"].values[i]),
                      "entrainment_speed_rad_s": float(ds["entrainment_speed"].values[i]),
                      "balances_from_rad_s": float(helps.min()) if helps.size else None,
                      "efficiency_at_nominal": float(e[k])})
        if "growth_rate" in ds:          # the balanced state's linear stability (sec. 3j)
            from ..liquid.stability import unstable_ranges

            fills[-1]["balanced_unstable_rad_s"] = unstable_ranges(
                ds["linear_speed"].values, ds["growth_rate"].values[i])
    e = ds["efficiency"].values[:, k]
    good = ds["fill"].values[e >= (1 - TIE) * e.max()]
    extra = {}
    if "growth_rate" in ds:          # the balanced state at the nominal speed (sec. 3j)
        kl = int(np.argmin(np.abs(ds["linear_speed"].values - wn)))
        ok = ds["growth_rate"].values[:, kl] < 0.0
        both = ds["fill"].values[(e >= (1 - TIE) * e.max()) & ok]
        extra["balanced_stable_at_nominal"] = [bool(x) for x in ok]
        extra["least_stable_fill_within_tie_m3"] = float(both.min()) if both.size else None
    if "steady" in ds:
        bad = np.argwhere(~ds["steady"].values)
        extra["not_steady"] = [(float(ds["fill"].values[i]), float(ds["dynamic_speed"].values[j]))
                               for i, j in bad]
    return {**extra,"machine": ds.attrs["machine"], "nominal_speed_rad_s": wn,
            "speed_on_grid_rad_s": float(W[k]),
            "resonance_without_liquid_rad_s": ds.attrs["resonance_without_liquid_rad_s"],
            "best_efficiency_at_nominal": float(e.max()),
            "least_fill_within_tie_m3": float(good.min()),
            "fills_within_tie_m3": [float(v) for v in good], "tie": TIE,
            "fills": fills}


#: A whirl whose amplitude spreads by more than this fraction of its mean over the last quarter
#: of a constant-speed run is not the steady synchronous whirl [-] (our criterion).
SPREAD_MAX = 0.05


def compute_stability_map(base: str | Path | Config, *, fills: Sequence[float],
                          speeds: Sequence[float], duration: float = DYNAMIC_DURATION,
                          store: str | Path | None = None, executor: str | None = None,
                          workers: int | None = None, progress: bool = False) -> xr.Dataset:
    """Whether the steady synchronous whirl is reached, over fill x speed: the wall film
    coupled with the rotor (:func:`autobalance.liquid.simulate.simulate_liquid`) at each
    constant speed for ``duration``, as one sweep (resumable with ``store``). Partly filled
    rotors can whirl asynchronously above resonance (Kollmann 1962; Ehrich 1992); this map
    shows where the model does.

    Parameters
    ----------
    base : str, Path or Config
        A liquid-balancer machine.
    fills : sequence of float
        Fills [m^3].
    speeds : sequence of float
        Constant speeds [rad/s], each above every fill's entrainment speed (003 eq 6).
    duration : float
        Time at each speed [s].
    store : path or None
        Sweep store (None: a temporary directory).
    executor, workers : str or None, int or None
        As :func:`autobalance.sweep.sweep`.
    progress : bool
        Show the sweep's progress bar.

    Returns
    -------
    xarray.Dataset
        ``spread`` (fill, speed) [-]: (max - min) / mean over the last quarter of the whirl
        amplitude (vertical axis) or of the synchronous residual unbalance |D + U_s| (horizontal
        axis: a revolution average, free of gravity's once-per-revolution wobble about the sag); ``steady`` (spread < :data:`SPREAD_MAX`: the synchronous whirl is reached
        within ``duration``; not reached is an asynchronous whirl or a transient slower than
        ``duration``, which a longer run separates; and the run in the model); ``in_model``
        (the run's status is ok: the film did not reach an annulus' inner wall);
        ``mean_amplitude`` [m] over the last quarter.
    """
    import xarray as xr

    from ..sweep import spec_from_dict, sweep
    from .common import sweep_root

    from ..config import load_config

    device = (base if hasattr(base, "system") else load_config(base)).system.liquid
    T = float(duration)
    if not (np.isfinite(T) and T > 0):
        raise ParameterError("duration", duration, "must be > 0 [s]")
    common = ["profile.kind=constant", f"profile.duration={T!r}",
              f"profile.speed={float(speeds[0])!r}"]
    several = device is not None and device.n_chambers > 1
    # one chamber: one sweep over fill x speed; several: one sweep over the speeds per fill,
    # each with every chamber's volume (a grid value is one number per key)
    runs = [(None, common, {"liquid.volume": [float(v) for v in fills]})] if not several else [
        (f"fill-{i}", common + ["liquid.volume=" + repr(chamber_fills(device, v))], {})
        for i, v in enumerate(fills)]
    if not hasattr(base, "system"):
        base_file, base = str(base), None
    else:
        base_file = None
    parts = []
    with sweep_root(store) as root:
        for sub, sets, grid in runs:
            spec = {"sweep": {"name": "stability-map", "batch_size": 4, "set": sets},
                    "grid": {**grid, "profile.speed": [float(w) for w in speeds]},
                    "outputs": {"history_dt": T / 200.0}}
            if base_file is not None:
                spec["sweep"]["base"] = base_file
            where = root / sub if sub else root / "map" if store is None else root
            part = sweep(spec_from_dict(spec, "stability map", base=base), where,
                         executor=executor, workers=workers, progress=progress,
                         resume=store is not None, keyed=store is not None)
            parts.append(part.load())
        ds = parts[0] if not several else xr.concat(parts, dim="liquid__volume")
    late_of = lambda name: ds[name].isel(sample=0).where(ds["history_time"] >= 0.75 * T,  # noqa: E731
                                                         drop=True)
    mean = late_of("amplitude_history").mean("history_time")
    # the whirl's amplitude; on a horizontal axis the grade of the synchronous residual
    # unbalance (a revolution average), free of gravity's once-per-revolution wobble
    horizontal = device is not None and device.axis == "horizontal"
    q = late_of("grade_G_history" if horizontal else "amplitude_history")
    spread = (q.max("history_time") - q.min("history_time")) / q.mean("history_time")
    in_model = ds["status"].isel(sample=0).values == 0     # e.g. the film off the inner wall
    out = xr.Dataset({"spread": (("fill", "speed"), spread.values, {"units": "1"}),
                      "steady": (("fill", "speed"), (spread.values < SPREAD_MAX) & in_model),
                      "in_model": (("fill", "speed"), in_model,
                                   {"long_name": "run status ok (the wall-film model holds)"}),
                      "mean_amplitude": (("fill", "speed"), mean.values, {"units": "m"})},
                     coords={"fill": ("fill", np.asarray(fills, float), {"units": "m^3"}),
                             "speed": ("speed", np.asarray(speeds, float), {"units": "rad/s"})},
                     attrs={"duration_s": T, "spread_max": SPREAD_MAX,
                            "model": "wall film coupled with the rotor, constant speed"})
    return out


def dynamic_speeds(ds: xr.Dataset, n: int) -> np.ndarray:
    """Up to ``n`` speeds of a fill map for its stability map [rad/s]: those above every fill's
    entrainment speed (by 2 %), evenly picked.

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`compute_fill_map`'s result.
    n : int
        Most speeds [-].
    """
    W = ds["speed"].values
    ok = W[W >= 1.02 * float(ds["entrainment_speed"].max())]
    if ok.size == 0:
        raise ParameterError("speeds", f"up to {W[-1]:.4g} rad/s", "none above every fill's "
                             "entrainment speed: no film to run")
    return ok[np.unique(np.linspace(0, ok.size - 1, min(int(n), ok.size)).round().astype(int))]


def compute_fill_study(base: str | Path | Config, *, fills: Sequence[float] | None = None,
                       speeds: Sequence[float] | None = None, quick: bool = False,
                       linear: bool = False, dynamic: bool = False,
                       duration: float | None = None,
                       executor: str | None = None, workers: int | None = None,
                       progress: bool = False) -> xr.Dataset:
    """The fill map (:func:`compute_fill_map`) with, on request, the balanced state's linear
    stability at every point (:func:`compute_linear_map`) and the wall film coupled with the
    rotor at up to 8 speeds (4 when ``quick``) above every fill's entrainment speed
    (:func:`compute_stability_map` at :func:`dynamic_speeds`, its axis ``dynamic_speed``).

    Parameters
    ----------
    base : str, Path or Config
        The machine, with a ``[liquid]`` section.
    fills, speeds : sequence of float or None
        Fills [m^3] and speeds [rad/s] (None: :func:`compute_fill_map`'s defaults).
    quick : bool
        The coarse grids.
    linear : bool
        Add the linear stability (vertical axis).
    dynamic : bool
        Add the coupled film's runs.
    duration : float or None
        Time at each speed of the coupled runs [s] (None: :data:`DYNAMIC_DURATION`).
    executor, workers, progress : str, int, bool or None
        Where the coupled runs go (:func:`compute_stability_map`).
    """
    ds = compute_fill_map(base, fills=fills, speeds=speeds, quick=quick)
    if linear:
        ds = ds.merge(compute_linear_map(base, fills=ds["fill"].values,
                                         speeds=ds["speed"].values))
    if dynamic:
        stab = compute_stability_map(base, fills=ds["fill"].values,
                                     speeds=dynamic_speeds(ds, 4 if quick else 8),
                                     duration=DYNAMIC_DURATION if duration is None else duration,
                                     executor=executor, workers=workers,
                                     progress=progress)
        ds = ds.merge(stab.rename(speed="dynamic_speed"))
    return ds
