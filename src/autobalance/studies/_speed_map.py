"""Will it balance: every equilibrium of the balls over a speed range, its stability, and the
speed ranges where the balanced state exists and is stable; the same against the suspension
damping. Method and cost: docs/speed-map.md.

At each speed the equilibria come in closed form (:func:`autobalance.physics.equilibria.
find_equilibrium_set`: isolated points and, for N >= 3 balls, continuous balanced families) and
each is judged in the linearised full model with the neutral directions of a family removed
(:func:`autobalance.studies.equilibria.full_stability`), or in the kinetic-static model
(000 eq 13, 52) when ``full`` is off.

Definitions (every flag over ``speed`` counts reachable states only, i.e. no two balls closer
than their contact angle):

* *balanced state*: an equilibrium with W = W*, the residual unbalance at which the force on
  every ball vanishes (:func:`autobalance.physics.equilibria.balanced_unbalance`; W* = 0 without
  race eccentricity). It exists when the balls' capacity closes the polygon
  sum m_i R e^{i alpha_i} = W* - U - sum m_i rho e^{i beta}; when the capacity is short there is
  none, and the map's residual is that of the least-residual stable state instead.
* ``balanced_exists``: a reachable balanced state exists; ``balanced_stable``: one of them is
  stable (for a family: at least one judged sample point).
* ``balanced_verdict``: the balanced state's verdict in four categories (VERDICTS): stable (one
  of its states is), no verdict (none is stable and at least one has no verdict: no converged
  orbit near it, or a family's multipliers not told apart from the others), unstable (every
  one judged unstable) or none (no reachable balanced state). No verdict is never unstable.
* *evaluation*: the balanced state judged at one (damping factor, speed), a grid point or a
  bisection step of a range edge; ``evaluations`` counts them and ``no_verdict`` those whose
  verdict is no verdict (at most ``evaluations``); ``states_judged`` and ``states_no_verdict``
  count the single equilibria and family samples judged.
* *best stable state*: the stable reachable equilibrium of least residual unbalance;
  ``residual_unbalance`` [kg*m] and ``grade`` [mm/s] (ISO 1940 with the speed itself, M_t).
  When no reachable state is stable, the least-residual kinetic-static-stable equilibrium whose
  balls overlap stands in (``best_kind`` = 3): balls gathered in contact, e.g. all of them
  opposite an unbalance larger than their capacity (residual U - sum m_i R) or, below
  resonance, with the unbalance. The kinetic-static model ignores the contact, so its residual
  is that of coincident balls (touching balls spread by their contact angle: a little more).
  NaN where nothing is stable.
"""
from __future__ import annotations

import math
import time
from typing import TYPE_CHECKING, Callable, Optional

import numpy as np

from ..models import ParameterError
from ..physics.equilibria import find_equilibrium_set
from ..liquid.start import film_start_speed, pool_machine
from ..physics.iso1940 import grade_value
from .equilibria import full_stability, steady_rotor_frame
from .common import load

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    import numpy.typing as npt
    import xarray as xr

    from ..config import Config

__all__ = ["NO_VERDICT", "STABLE", "UNSTABLE", "VERDICTS", "compute_speed_map", "no_verdict_ranges",
           "speed_map_summary", "verdict_codes"]

#: Default suspension-damping factors (full and quick) [-].
DAMPING_FACTORS = (0.25, 0.5, 1.0, 2.0, 4.0)
DAMPING_FACTORS_QUICK = (0.5, 1.0, 2.0)
#: Speed grid points (full and quick) [-].
N_SPEEDS, N_SPEEDS_QUICK = 120, 30
#: Range boundaries are bisected to this fraction of the speed (full and quick) [-].
RANGE_RTOL, RANGE_RTOL_QUICK = 1e-4, 1e-3
#: A full-model orbit farther than this from its kinetic-static equilibrium is another orbit:
#: no verdict (e.g. gravity stronger than the balls' centripetal acceleration) [rad].
ORBIT_DRIFT = 0.5
#: Sample points per family, and how many of them the Floquet route judges [-].
FAMILY_SAMPLES, FLOQUET_FAMILY_SAMPLES = 12, 4
#: Film cells around each wall of a liquid beside the balls [-] (docs/liquid/stability.md
#: sec. 3j-3k).
FILM_CELLS = 64
#: Verdicts on one state, and the balanced state's verdict codes over speed (index = code):
#: 0 no reachable balanced state, 1 unstable, 2 stable, 3 no verdict.
STABLE, UNSTABLE, NO_VERDICT = "stable", "unstable", "no verdict"
VERDICTS = ("none", UNSTABLE, STABLE, NO_VERDICT)


def _validate(speeds, damping_factors):
    try:
        w = np.asarray(speeds, float).ravel()
    except (TypeError, ValueError):
        raise ParameterError("speeds", speeds, "must be numbers [rad/s]") from None
    if w.size == 0 or not np.all(np.isfinite(w)) or np.any(w <= 0):
        raise ParameterError("speeds", w.tolist(), "must be a non-empty list of finite speeds > 0 [rad/s]")
    try:
        f = np.asarray(damping_factors, float).ravel()
    except (TypeError, ValueError):
        raise ParameterError("damping_factors", damping_factors, "must be numbers [-]") from None
    if f.size == 0 or not np.all(np.isfinite(f)) or np.any(f <= 0):
        raise ParameterError("damping_factors", f.tolist(),
                             "must be a non-empty list of finite factors > 0 [-]")
    return np.unique(w), [float(v) for v in dict.fromkeys(f.tolist())]


def _scaled(system, factor: float):
    """The machine with its suspension damping cx, cy multiplied by ``factor``."""
    import dataclasses

    s = system.suspension
    return dataclasses.replace(system, suspension=dataclasses.replace(s, cx=s.cx * factor, cy=s.cy * factor))


def _verdict(system, w: float, e, family: bool, full: bool, counts: dict) -> str:
    """Verdict on equilibrium e (STABLE, UNSTABLE or NO_VERDICT): linearised full model, or
    kinetic-static when not ``full``. No verdict where the full model finds no converged orbit
    near e, or (family) cannot tell the family's multipliers from the others."""
    counts["states_judged"] += 1
    if not full:
        return STABLE if e.ks_stable else UNSTABLE
    try:
        f = full_stability(system, w, e.alpha, family=family)
    except (ParameterError, ValueError, np.linalg.LinAlgError):
        counts["states_no_verdict"] += 1     # e.g. shooting pushed the balls into contact
        return NO_VERDICT
    drift = float(np.abs(np.angle(np.exp(1j * (f["orbit_alpha_rad"] - e.alpha)))).max())
    if not f["converged"] or drift > ORBIT_DRIFT or (family and not f["neutral_ok"]):
        counts["states_no_verdict"] += 1     # no orbit near this equilibrium: no verdict
        return NO_VERDICT
    return STABLE if f["stable"] else UNSTABLE


def _film_verdict(system, w: float, p, family: bool, counts: dict, n_cells: int) -> str:
    """Verdict on the balanced state p beside a liquid whose liquid is a film at w [rad/s]:
    the linearisation with the films (:func:`autobalance.studies.liquid_balanced.
    balanced_stability`, ``n_cells`` [-] around each wall)."""
    from .liquid_balanced import balanced_stability

    counts["states_judged"] += 1
    try:
        ok = balanced_stability(system, w, p.alpha, n_cells=n_cells, family=family).stable
    except (ParameterError, RuntimeError, np.linalg.LinAlgError):
        counts["states_no_verdict"] += 1     # not a fixed point (e.g. balls in contact): no verdict
        return NO_VERDICT
    return STABLE if ok else UNSTABLE


def _balanced_code(exists: bool, verdicts: list) -> int:
    """The balanced state's verdict code at one speed (VERDICTS) from its states' verdicts:
    stable if one is, else no verdict if one has none, else unstable; none without a state."""
    if STABLE in verdicts:
        return VERDICTS.index(STABLE)
    if NO_VERDICT in verdicts:
        return VERDICTS.index(NO_VERDICT)
    return VERDICTS.index(UNSTABLE) if exists else 0


def _evaluate(system, w: float, full: bool, floquet: bool, counts: dict,
              balanced_only: bool = False, n_cells: int = FILM_CELLS) -> dict:
    """One evaluation: every equilibrium at speed w [rad/s] and its verdict (balanced states
    only if asked), and the balanced state's verdict code (counted in ``counts``). Beside a
    liquid: below its film's start the liquid is a pool (its mass in the rotor's,
    :func:`autobalance.liquid.start.pool_machine`) and the balls' verdicts hold; from there on
    only the balanced states are judged, with the films (:func:`_film_verdict`)."""
    films = False
    if system.liquid is not None:
        films = w >= film_start_speed(system.liquid, system.gravity.g)
        liquid, system = system, pool_machine(system)
        balanced_only |= films
    es = find_equilibrium_set(system, w, method="closed_form", n_samples=FAMILY_SAMPLES)

    def judge(p, family: bool) -> str:
        if films:
            return _film_verdict(liquid, w, p, family, counts, n_cells)
        return _verdict(system, w, p, family, full, counts)

    exists = False
    bal_verdicts = []
    n_iso = n_stable = 0
    best = (math.inf, 0)
    contact = math.inf          # least residual of a kinetic-static-stable state with balls in contact
    for e, bal in zip(es.isolated, es.balanced):
        if e.overlap and e.ks_stable and not balanced_only:
            contact = min(contact, e.residual_unbalance)
        if e.overlap or (balanced_only and not bal):
            continue
        n_iso += 1
        exists |= bal
        v = judge(e, False)
        if bal:
            bal_verdicts.append(v)
        if v == STABLE:
            n_stable += 1
            best = min(best, (e.residual_unbalance, 1))
    n_fam = 0
    for f in es.families:
        reach = [p for p in f.points if not p.overlap]
        if not reach:
            continue
        n_fam += 1
        exists = True
        if (films or floquet and full) and len(reach) > FLOQUET_FAMILY_SAMPLES:
            idx = np.round(np.linspace(0, len(reach) - 1, FLOQUET_FAMILY_SAMPLES)).astype(int)
            reach = [reach[i] for i in idx]
        vs = [judge(p, True) for p in reach]
        bal_verdicts += vs
        ok = [p for p, v in zip(reach, vs) if v == STABLE]
        if ok:
            n_stable += 1
            best = min(best, (min(p.residual_unbalance for p in ok), 2))
    if not best[1] and math.isfinite(contact):
        best = (contact, 3)
    code = _balanced_code(exists, bal_verdicts)
    counts["evaluations"] += 1
    counts["no_verdict"] += VERDICTS[code] == NO_VERDICT
    return {"exists": exists, "stable": VERDICTS[code] == STABLE, "verdict": code,
            "n_isolated": n_iso, "n_families": n_fam, "n_stable": n_stable,
            "residual": best[0] if best[1] else math.nan, "kind": best[1], "films": films}


def _refine(pred: Callable[[float], bool], speeds: np.ndarray, flags: np.ndarray, rtol: float) -> list:
    """Speed ranges where pred holds: runs of True on the grid, each interior edge bisected
    until the bracket is below rtol x speed (edge = bracket midpoint); ends of the grid are kept."""
    out = []
    n = speeds.size
    k = 0
    while k < n:
        if not flags[k]:
            k += 1
            continue
        j = k
        while j + 1 < n and flags[j + 1]:
            j += 1
        lo = speeds[0] if k == 0 else _bisect(pred, speeds[k - 1], speeds[k], rtol)
        hi = speeds[-1] if j == n - 1 else _bisect(pred, speeds[j + 1], speeds[j], rtol)
        out.append([float(lo), float(hi)])
        k = j + 1
    return out


def _bisect(pred: Callable[[float], bool], bad: float, good: float, rtol: float) -> float:
    """Bisect the bracket (pred(bad) False, pred(good) True) to |good - bad| <= rtol x speed."""
    while abs(good - bad) > rtol * max(good, bad):
        mid = 0.5 * (bad + good)
        if pred(mid):
            good = mid
        else:
            bad = mid
    return 0.5 * (bad + good)


def _default_speeds(cfg, quick: bool) -> np.ndarray:
    lo = 0.3 * min(cfg.system.natural_frequencies)
    hi = max(1.3 * cfg.spin.nominal_speed, 3.0 * lo)
    return np.geomspace(lo, hi, N_SPEEDS_QUICK if quick else N_SPEEDS)


def _passes(system, w, factors, full: bool, floquet: bool, rtol: float, counts: dict, progress):
    """The grid at damping factor 1 (every equilibrium), the other factors (balanced states
    only) and the bisected range edges: rows of :func:`_evaluate` at factor 1, its stable ranges
    [rad/s], (exists, stable, verdict code) arrays over (factor, speed) and the NaN-padded
    ranges (factor, range, edge) [rad/s]. ``progress(done, total)`` after each grid point."""
    total = (1 + sum(f != 1.0 for f in factors)) * w.size
    done = 0

    def tick():
        nonlocal done
        done += 1
        if progress is not None:
            progress(done, total)

    def predicate(sys_f):
        def pred(x: float) -> bool:
            return _evaluate(sys_f, x, full, floquet, counts, balanced_only=True)["stable"]
        return pred

    rows = []
    for wk in w:
        rows.append(_evaluate(system, float(wk), full, floquet, counts))
        tick()
    main = np.array([[r["exists"], r["stable"], r["verdict"]] for r in rows], np.int8).T
    ranges = _refine(predicate(system), w, main[1].astype(bool), rtol)
    dmp = np.zeros((3, len(factors), w.size), np.int8)
    dmp_ranges = []
    for i, f in enumerate(factors):
        if f == 1.0:
            dmp[:, i] = main
            dmp_ranges.append(ranges)
            continue
        sys_f = _scaled(system, f)
        for k, wk in enumerate(w):
            r = _evaluate(sys_f, float(wk), full, floquet, counts, balanced_only=True)
            dmp[:, i, k] = r["exists"], r["stable"], r["verdict"]
            tick()
        dmp_ranges.append(_refine(predicate(sys_f), w, dmp[1, i].astype(bool), rtol))
    nr = max([1] + [len(r) for r in dmp_ranges])
    rng = np.full((len(factors), nr, 2), np.nan)
    for i, r in enumerate(dmp_ranges):
        if r:
            rng[i, :len(r)] = r
    return rows, ranges, dmp, rng


def compute_speed_map(base: str | Path | Config, *, speeds: npt.ArrayLike | None = None,
                      damping_factors: Sequence[float] | None = None, quick: bool = False,
                      full: bool = True,
                      progress: Optional[Callable[[int, int], None]] = None) -> xr.Dataset:
    """Equilibria of the balls and their stability over speed and suspension damping.

    Parameters
    ----------
    base : str, Path or Config
        The machine: a preset name, a TOML config path or a Config
        (:func:`autobalance.studies.common.load`).
    speeds : array_like, optional
        Spin speeds [rad/s], > 0 (sorted, duplicates merged). Default: 120 (quick: 30)
        geometrically spaced points from 0.3 x the lowest natural frequency to 1.3 x the
        profile's nominal speed.
    damping_factors : sequence of float, optional
        Factors on the suspension damping cx, cy [-], > 0; default (0.25, 0.5, 1, 2, 4), quick
        (0.5, 1, 2).
    quick : bool
        Coarser defaults and range tolerance (RANGE_RTOL_QUICK).
    full : bool
        Judge stability in the linearised full model (eigenvalues in a steady rotor frame,
        Floquet multipliers otherwise); False: the kinetic-static model (000 eq 13, 52).
    progress : callable(done: int, total: int), optional
        Called after each (damping factor, speed) grid point (bisection steps are not counted
        in ``total``).

    Returns
    -------
    xarray.Dataset
        Over ``speed`` [rad/s]: ``balanced_exists``, ``balanced_stable`` (int8 0/1),
        ``balanced_verdict`` (int8: 0 none, 1 unstable, 2 stable, 3 no verdict; CF
        ``flag_values``/``flag_meanings``), ``n_isolated``, ``n_families``, ``n_stable``
        (int16), ``best_kind`` (0 none, 1 isolated, 2 family, 3 balls in contact),
        ``residual_unbalance`` [kg*m] and ``grade`` [mm/s] of the best stable state; over
        (``damping_factor`` [-], ``speed``): ``balanced_exists_damping``,
        ``balanced_stable_damping``, ``balanced_verdict_damping``; over (``damping_factor``,
        ``range``, ``edge``): ``stable_ranges_damping`` [rad/s] (NaN-padded). Attributes:
        ``stable_ranges_rad_s`` (flattened [lo1, hi1, lo2, hi2, ...]),
        ``natural_frequencies_rad_s``, ``nominal_speed_rad_s``, ``range_rtol``, ``method``,
        the counts ``evaluations``, ``no_verdict``, ``states_judged``, ``states_no_verdict``
        (module docstring) and ``wall_s``. Every value is NetCDF-writable (no booleans, no
        nested lists).
    """

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True)
    system = cfg.system
    if system.liquid is not None:
        from .liquid_balanced import require_balanced_liquid

        require_balanced_liquid(system)
        if not full:
            raise ParameterError("full", full, "must be True beside a liquid: the kinetic-static "
                                 "model has no films (docs/liquid/stability.md sec. 3k)")
    w, factors = _validate(_default_speeds(cfg, quick) if speeds is None else speeds,
                           (DAMPING_FACTORS_QUICK if quick else DAMPING_FACTORS)
                           if damping_factors is None else damping_factors)
    if system.balancer.n_balls < 1:
        raise ParameterError("balancer.n_balls", system.balancer.n_balls, "needs at least one ball")
    rtol = RANGE_RTOL_QUICK if quick else RANGE_RTOL
    floquet = not steady_rotor_frame(pool_machine(system))
    method = ("floquet" if floquet else "eigenvalues") if full else "kinetic_static"
    if system.liquid is not None:
        method += "+films"
    counts = {"evaluations": 0, "no_verdict": 0, "states_judged": 0, "states_no_verdict": 0}
    rows, ranges, dmp, rng = _passes(system, w, factors, full, floquet, rtol, counts, progress)
    mt = system.total_mass
    ds = _dataset(rows, w, factors, dmp, rng, mt)
    if system.liquid is not None:
        ds["liquid_film"] = ("speed", np.array([r["films"] for r in rows], np.int8),
                             {"units": "1", "long_name": "the liquid is a film (003 eq 6): only "
                                                         "the balanced states are judged, with "
                                                         "the films"})
        ds.attrs.update({"film_from_rad_s": float(film_start_speed(system.liquid, system.gravity.g)),
                         "film_cells": FILM_CELLS, "liquid_axis": system.liquid.axis})
    ds.attrs.update({
        "study": "speed_map", "machine": cfg.name or str(base), "n_balls": int(system.balancer.n_balls),
        "stable_ranges_rad_s": np.array(ranges, float).ravel(),
        "natural_frequencies_rad_s": np.array(system.natural_frequencies, float),
        "nominal_speed_rad_s": float(cfg.spin.nominal_speed),
        "total_mass_kg": float(mt), "capacity_kg_m": float(system.balancer.capacity),
        "range_rtol": float(rtol), "method": method, "full": int(bool(full)), "quick": int(bool(quick)),
        "evaluations": int(counts["evaluations"]), "no_verdict": int(counts["no_verdict"]),
        "states_judged": int(counts["states_judged"]),
        "states_no_verdict": int(counts["states_no_verdict"]),
        "verdict_codes": "balanced_verdict: " + ", ".join(f"{k} {v}" for k, v in enumerate(VERDICTS)),
        "evaluation": "the balanced state judged at one speed and damping factor (grid points "
                      "and bisection steps): one verdict each",
        "definitions": "balanced: W = W* (zero residual without race eccentricity); only states "
                       "without ball overlap count; best stable state: least residual among stable ones"
                       + ("; beside a liquid: a pool (a puddle on a horizontal axis) below "
                          "film_from_rad_s (its mass in the rotor's), only the balanced states "
                          "judged, with the films (Floquet under gravity on a horizontal axis), "
                          "above it"
                          if system.liquid is not None else ""),
        "wall_s": float(time.perf_counter() - t0),
    })
    return ds


def _dataset(rows, w, factors, dmp, rng, mt):
    """The speed map's variables and coordinates (:func:`compute_speed_map`): rows of
    ``_evaluate`` per speed w [rad/s], the damping factors [-], the (exists, stable, verdict
    code) arrays and stable ranges [rad/s] per factor, the total mass mt [kg]."""
    import xarray as xr

    res = np.array([r["residual"] for r in rows])
    flags = {"units": "1", "flag_values": np.arange(len(VERDICTS), dtype=np.int8),
             "flag_meanings": " ".join(v.replace(" ", "_") for v in VERDICTS)}
    return xr.Dataset(
        {
            "balanced_exists": ("speed", np.array([r["exists"] for r in rows], np.int8),
                                {"units": "1", "long_name": "a reachable balanced state exists (W = W*)"}),
            "balanced_stable": ("speed", np.array([r["stable"] for r in rows], np.int8),
                                {"units": "1", "long_name": "a reachable balanced state is stable"}),
            "balanced_verdict": ("speed", np.array([r["verdict"] for r in rows], np.int8),
                                 {**flags, "long_name": "the balanced state: 0 none, 1 unstable, "
                                                        "2 stable, 3 no verdict"}),
            "n_isolated": ("speed", np.array([r["n_isolated"] for r in rows], np.int16),
                           {"units": "1", "long_name": "reachable isolated equilibria"}),
            "n_families": ("speed", np.array([r["n_families"] for r in rows], np.int16),
                           {"units": "1", "long_name": "reachable balanced families"}),
            "n_stable": ("speed", np.array([r["n_stable"] for r in rows], np.int16),
                         {"units": "1", "long_name": "stable isolated equilibria and families"}),
            "best_kind": ("speed", np.array([r["kind"] for r in rows], np.int8),
                          {"units": "1", "long_name": "best stable state: 0 none, 1 isolated, "
                                                      "2 family, 3 balls in contact (kinetic-static)"}),
            "residual_unbalance": ("speed", res, {"units": "kg*m",
                                                  "long_name": "residual unbalance of the best stable state"}),
            "grade": ("speed", grade_value(res, mt, w), {"units": "mm/s",
                                                        "long_name": "ISO 1940 grade of the best stable state at this speed"}),
            "balanced_exists_damping": (("damping_factor", "speed"), dmp[0],
                                        {"units": "1", "long_name": "balanced state exists"}),
            "balanced_stable_damping": (("damping_factor", "speed"), dmp[1],
                                        {"units": "1", "long_name": "balanced state stable"}),
            "balanced_verdict_damping": (("damping_factor", "speed"), dmp[2],
                                         {**flags, "long_name": "the balanced state: 0 none, "
                                                                "1 unstable, 2 stable, 3 no verdict"}),
            "stable_ranges_damping": (("damping_factor", "range", "edge"), rng,
                                      {"units": "rad/s", "long_name": "speed ranges of a stable balanced state (NaN: none)"}),
        },
        coords={"speed": ("speed", w, {"units": "rad/s", "long_name": "spin speed"}),
                "damping_factor": ("damping_factor", np.array(factors),
                                   {"units": "1", "long_name": "factor on the suspension damping cx, cy"}),
                "edge": ("edge", np.array([0, 1], np.int8), {"long_name": "0 lower, 1 upper"})},
    )


def _pairs(flat) -> list:
    a = np.asarray(flat, float).ravel()
    return [[float(a[i]), float(a[i + 1])] for i in range(0, a.size - 1, 2)]


def verdict_codes(ds: xr.Dataset, damping: bool = False) -> np.ndarray:
    """The balanced state's verdict codes (index into VERDICTS) of a speed map, over ``speed``
    or, with ``damping``, over (``damping_factor``, ``speed``); derived from the exists/stable
    flags (no no-verdict) for a map without them.

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_speed_map` dataset.
    damping : bool
        The (damping factor, speed) map instead of the speed grid.

    Returns
    -------
    ndarray of int8
        0 none, 1 unstable, 2 stable, 3 no verdict.
    """
    tail = "_damping" if damping else ""
    if f"balanced_verdict{tail}" in ds:
        return ds[f"balanced_verdict{tail}"].values.astype(np.int8)
    stable = ds[f"balanced_stable{tail}"].values > 0
    exists = ds[f"balanced_exists{tail}"].values > 0
    return np.where(stable, 2, np.where(exists, 1, 0)).astype(np.int8)


def no_verdict_ranges(speeds: npt.ArrayLike, codes: npt.ArrayLike) -> list:
    """Runs of grid speeds [rad/s] where the balanced state has no verdict, as [first, last].

    Parameters
    ----------
    speeds : array_like (K,)
        The grid [rad/s], increasing.
    codes : array_like (K,)
        Verdict codes [-] (:func:`verdict_codes`).

    Returns
    -------
    list of [float, float]
        Grid speeds [rad/s] (not bisected: a run's edges lie within one grid step outside).
    """
    w = np.asarray(speeds, float)
    nv = np.asarray(codes) == VERDICTS.index(NO_VERDICT)
    out = []
    k = 0
    while k < w.size:
        if nv[k]:
            j = k
            while j + 1 < w.size and nv[j + 1]:
                j += 1
            out.append([float(w[k]), float(w[j])])
            k = j
        k += 1
    return out


def speed_map_summary(ds: xr.Dataset) -> dict:
    """JSON-ready summary of a :func:`compute_speed_map` dataset (SI, unit-suffixed keys).

    Parameters
    ----------
    ds : xarray.Dataset
        A speed map (also after a NetCDF round trip).

    Returns
    -------
    dict
        ``stable_ranges_rad_s`` (list of [lo, hi]; interior edges bisected to ``range_rtol`` x
        speed, edges at the grid's ends are the grid's ends), ``no_verdict_ranges_rad_s`` (runs
        of grid speeds without a verdict, [first, last]), ``speeds_rad_s`` and
        ``balanced_verdict`` (per grid speed: "none", "unstable", "stable" or "no verdict"),
        ``natural_frequencies_rad_s``, ``nominal_speed_rad_s``, ``speed_grid_rad_s`` ([first,
        last]), ``damping`` (per factor: ``damping_factor``, its ``stable_ranges_rad_s`` and
        ``no_verdict_ranges_rad_s``), ``counts`` (speeds, speeds with a balanced state, with a
        stable one, without a verdict, most isolated equilibria and families at one speed), the
        method, range tolerance, wall time and the evaluation counts: ``evaluations`` (the
        balanced state judged at one speed and damping factor, grid points and bisection steps),
        ``no_verdict`` (evaluations without a verdict), ``states_judged`` and
        ``states_no_verdict`` (equilibria and family samples judged, and those without one).
    """
    a = ds.attrs
    w = ds["speed"].values
    codes = verdict_codes(ds)
    dcodes = verdict_codes(ds, damping=True)
    damping = []
    for i, f in enumerate(ds["damping_factor"].values):
        r = ds["stable_ranges_damping"].values[i]
        damping.append({"damping_factor": float(f),
                        "stable_ranges_rad_s": [[float(lo), float(hi)] for lo, hi in r if np.isfinite(lo)],
                        "no_verdict_ranges_rad_s": no_verdict_ranges(w, dcodes[i])})
    res = ds["residual_unbalance"].values
    return {
        "machine": str(a.get("machine", "")),
        "stable_ranges_rad_s": _pairs(a["stable_ranges_rad_s"]),
        "no_verdict_ranges_rad_s": no_verdict_ranges(w, codes),
        "range_rtol": float(a["range_rtol"]),
        "natural_frequencies_rad_s": [float(v) for v in np.atleast_1d(a["natural_frequencies_rad_s"])],
        "nominal_speed_rad_s": float(a["nominal_speed_rad_s"]),
        "speed_grid_rad_s": [float(w[0]), float(w[-1])],
        "speeds_rad_s": [float(v) for v in w],
        "balanced_verdict": [VERDICTS[int(c)] for c in codes],
        "damping": damping,
        "counts": {"speeds": int(w.size),
                   "balanced_exists": int(ds["balanced_exists"].values.sum()),
                   "balanced_stable": int(ds["balanced_stable"].values.sum()),
                   "balanced_no_verdict": int((codes == VERDICTS.index(NO_VERDICT)).sum()),
                   "max_isolated": int(ds["n_isolated"].values.max()),
                   "max_families": int(ds["n_families"].values.max())},
        "least_residual_unbalance_kg_m": float(np.nanmin(res)) if np.isfinite(res).any() else None,
        "method": str(a["method"]),
        "evaluations": int(a["evaluations"]),
        "no_verdict": int(a["no_verdict"]),
        "states_judged": int(a.get("states_judged", 0)),
        "states_no_verdict": int(a.get("states_no_verdict", 0)),
        "wall_s": float(a["wall_s"]),
        **({"film_from_rad_s": float(a["film_from_rad_s"]),
            "liquid_axis": str(a.get("liquid_axis", "vertical"))} if "film_from_rad_s" in a else {}),
    }
