"""Which modelling choices move which results, for any machine (004 sec. 4.2's
statistics as the results): the start-position Monte Carlo of the machine as given and of one
variant per changed choice, over the same starts, and each variant's effect on every quantity
with its sampling uncertainty.

A choice the paper (or the user) leaves open - contact model, run-up time, plateau, ball
damping, rolling resistance, friction law - is changed one at a time. Because every variant
runs from the same start positions, the effect of a change is a paired difference; its
uncertainty is the standard deviation of that difference over a bootstrap of the starts
(resampled together for the base and the variant).
"""
from __future__ import annotations

import json
import time
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from ..physics.iso1940 import grade_value
from .common import load
from ._start_positions import compute_start_positions
from .statistics import TIE_MM_S, mode_value, regions

if TYPE_CHECKING:
    from pathlib import Path

    import xarray as xr

    from ..config import Config

__all__ = ["QUANTITIES", "compute_sensitivity", "default_variants", "quantities",
           "sensitivity_summary"]

#: The quantities whose sensitivity is reported (first / last read-out of the profile; 004
#: sec. 4.2: STD and TSR) [mm/s or -].
QUANTITIES = ("mode_first", "mode_last", "median_first", "median_last", "p95_last",
              "share_first", "share_last", "region_I.A", "region_I.B", "region_II",
              "region_III", "region_IV")


def quantities(g_first: np.ndarray, g_last: np.ndarray, g_ini: float, grade: float) -> dict:
    """The results a sensitivity study follows, from the grades [mm/s] of one set of runs at
    the first and last read-outs: modes (1 mm/s bins), medians and the last 95th percentile
    [mm/s], the shares at or below ``grade`` [-] and 004 Table 2's regions with ties within
    :data:`~.statistics.TIE_MM_S` taken as equal [-].

    Parameters
    ----------
    g_first, g_last : ndarray
        Grades at the first and last read-outs [mm/s], one per run, finite.
    g_ini : float
        Initial grade [mm/s].
    grade : float
        Target grade [mm/s].

    Returns
    -------
    dict of str to float
        :data:`QUANTITIES` -> value.
    """
    s, t = np.asarray(g_first, float), np.asarray(g_last, float)
    out = {"mode_first": mode_value(s), "mode_last": mode_value(t),
           "median_first": float(np.median(s)), "median_last": float(np.median(t)),
           "p95_last": float(np.percentile(t, 95)),
           "share_first": float(np.mean(s <= grade)), "share_last": float(np.mean(t <= grade))}
    out.update({f"region_{k}": v for k, v in regions(s, t, g_ini, TIE_MM_S).items()})
    return out


def default_variants(base: str | Path | Config) -> dict:
    """The modelling choices a machine's results are tested against, one change each, as
    "path=value" overrides (SI numbers) named by what they change: 004's point masses
    (contact none), ball damping x0.5 and x2, rolling resistance (and stiction) x0.5 and x2,
    the run-up time x0.78 (004: an 18 s reading of Fig. 3 against 14 s; of a motor drive,
    whose run-up time scales as B_z w_f / T0 (000 eq 15), the torque T0 / 0.78) and, for a TSR
    profile, the plateau x0.96 (004: 1.06 against 1.02 Omega_n); beside a liquid, its viscosity
    x0.5 and x2 (the films' wall shear, docs/liquid/film.md sec. 3d).

    Parameters
    ----------
    base : str, Path or Config
        The machine.

    Returns
    -------
    dict of str to list of str
        Variant name -> overrides.
    """
    cfg = load(base, allow_liquid=True)        # simulations only: a liquid beside is modelled
    b = cfg.system.balancer
    out = {}
    if b.n_balls == 0:
        return out

    def per_ball(values, f):
        v = [float(x) * f for x in values]
        return repr(v[0]) if len(set(v)) <= 1 else "[" + ", ".join(map(repr, v)) + "]"

    if b.contact == "compliant" and b.n_balls > 1:
        out["contact none"] = ["balancer.contact=none"]
    for f in (0.5, 2.0):
        if any(float(x) > 0 for x in b.damping):
            out[f"ball damping x{f:g}"] = [f"balancer.damping={per_ball(b.damping, f)}"]
        if any(float(x) > 0 for x in b.rolling_resistance) and max(b.stiction) * f <= 1.0:
            out[f"rolling resistance x{f:g}"] = [
                f"balancer.rolling_resistance={per_ball(b.rolling_resistance, f)}",
                f"balancer.stiction={per_ball(b.stiction, f)}"]
    if cfg.system.liquid is not None:                 # a liquid beside: its viscosity is uncertain
        for f in (0.5, 2.0):
            out[f"liquid viscosity x{f:g}"] = [
                f"liquid.kinematic_viscosity={cfg.system.liquid.kinematic_viscosity * f!r}"]
    spin = cfg.spin
    if getattr(spin, "name", "") in ("std", "tsr"):
        out["run-up x0.78"] = [f"profile.runup_time={0.78 * float(spin.times[1])!r}"]
    elif getattr(spin, "name", "") == "motor":     # run-up time ~ B_z w_f / T0 (000 eq 15)
        out["run-up x0.78"] = [f"profile.torque={spin.torque / 0.78!r}"]
    if getattr(spin, "name", "") == "tsr":
        from .statistics import plateau_speed

        out["plateau x0.96"] = [f"profile.plateau={0.96 * plateau_speed(spin)!r}"]
    return out


def compute_sensitivity(base: str | Path | Config, variants: dict | None = None, *,
                        n: int | None = None, samples: int | None = None, seed: int = 0,
                        grade: float = 16.0, quick: bool = False, n_boot: int = 200,
                        store_dir: str | Path | None = None, executor: str = "local",
                        workers: int | None = None, scheduler: str | None = None,
                        progress: bool = False) -> xr.Dataset:
    """The start-position Monte Carlo of the machine and of each variant over the same starts,
    and each variant's effect on :data:`QUANTITIES` with its bootstrap standard error.

    Parameters
    ----------
    base : str, Path or Config
        The machine.
    variants : dict of str to list of str or None
        Variant name -> "path=value" overrides; None = :func:`default_variants`.
    n, samples, seed, quick : int, int, int, bool
        The starts, as for :func:`.start_positions.compute_start_positions` (a variant that
        changes the ball count cannot share them and is refused).
    grade : float
        Target grade of the shares [mm/s].
    n_boot : int
        Bootstrap resamples of the starts (>= 2).
    store_dir, executor, workers, scheduler : str, Path, int or None
        Where and how the runs go (one resumable store per variant under ``store_dir``; None =
        temporary stores), as for :func:`.common.run_start_grid`.
    progress : bool
        Show each Monte Carlo's progress bar on stderr.

    Returns
    -------
    xarray.Dataset
        value (variant, quantity) with "base" first; effect and effect_se (variant, quantity)
        [same units: mm/s or -], effect / se as z; grade_G (variant, sample, checkpoint);
        attrs: starts, runs, wall time, the overrides of each variant.
    """
    import xarray as xr

    from .common import store_path

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True)        # simulations only: a liquid beside is modelled
    variants = default_variants(cfg) if variants is None else dict(variants)
    if not variants:
        raise ParameterError("variants", variants, "needs at least one change to study")
    if isinstance(n_boot, bool) or int(n_boot) != n_boot or n_boot < 2:
        raise ParameterError("n_boot", n_boot, "must be an integer >= 2")
    N = cfg.system.balancer.n_balls
    names = ["base", *variants]
    cfgs = {"base": cfg}
    for name, sets in variants.items():
        if any(str(x).split("=")[0].strip() == "balancer.n_balls" for x in sets):
            raise ParameterError(f"variants[{name!r}]", list(sets), "must keep the ball count "
                                 "(the variants share the base's start positions)")
        c = load(cfg, list(sets), allow_liquid=True)
        if c.system.balancer.n_balls != N:
            raise ParameterError(f"variants[{name!r}]", sets, "must keep the ball count (the "
                                 "variants share the base's start positions)")
        cfgs[name] = c
    grades, status = [], []
    for k, name in enumerate(names):
        ds = compute_start_positions(cfgs[name], n=n, samples=samples, seed=seed, grade=grade,
                                     quick=quick, name=f"sensitivity-{k}",
                                     store=store_path(store_dir, f"sensitivity-{k}"),
                                     executor=executor, workers=workers, scheduler=scheduler,
                                     progress=progress)
        grades.append(ds["grade_G"].transpose("sample", "checkpoint").values)
        status.append(ds["status"].values)
        if k == 0:
            cps = ds["checkpoint"].values
            starts_text = ds.attrs["starts"]
    g = np.array(grades)                                      # (variant, sample, checkpoint)
    ok = np.all(np.array(status) == 0, axis=0)                # runs every variant finished
    s = cfg.system
    g_ini = float(grade_value(s.rotor.unbalance, s.total_mass, cfg.spin.nominal_speed))
    idx = np.nonzero(ok)[0]

    def q_of(v, sel):
        return quantities(g[v, sel, 0], g[v, sel, -1], g_ini, grade)

    vals = np.array([[q_of(v, idx)[q] for q in QUANTITIES] for v in range(len(names))])
    rng = np.random.default_rng(seed)
    boots = np.empty((n_boot, len(names), len(QUANTITIES)))
    for b in range(n_boot):
        sel = rng.choice(idx, idx.size)
        boots[b] = [[q_of(v, sel)[q] for q in QUANTITIES] for v in range(len(names))]
    eff = vals - vals[0]
    se = np.std(boots - boots[:, :1], axis=0)
    with np.errstate(divide="ignore", invalid="ignore"):
        z = np.where(se > 0, eff / se, np.where(eff == 0, 0.0, np.inf))
    units = ["mm/s" if q.startswith(("mode", "median", "p95")) else "-" for q in QUANTITIES]
    out = xr.Dataset(
        {"value": (("variant", "quantity"), vals), "effect": (("variant", "quantity"), eff),
         "effect_se": (("variant", "quantity"), se,
                       {"long_name": "bootstrap SE of the paired difference"}),
         "z": (("variant", "quantity"), z, {"units": "-", "long_name": "effect / effect_se"}),
         "grade_G": (("variant", "sample", "checkpoint"), g, {"units": "mm/s"})},
        coords={"variant": names, "quantity": list(QUANTITIES),
                "unit": ("quantity", units), "checkpoint": ("checkpoint", cps, {"units": "s"})})
    out.attrs.update({"study": "sensitivity", "grade": float(grade), "G_ini": g_ini,
                      "starts": starts_text, "runs_per_variant": int(g.shape[1]),
                      "runs_used": int(idx.size), "n_boot": int(n_boot),
                      "tie_mm_s": TIE_MM_S,
                      "overrides_json": json.dumps({k: list(v) for k, v in variants.items()}),
                      "wall_s": time.perf_counter() - t0})
    return out


def sensitivity_summary(ds: xr.Dataset, z: float = 2.0) -> dict:
    """JSON-ready summary of :func:`compute_sensitivity`: the base's quantities, and per
    variant every effect with its SE and whether it exceeds ``z`` standard errors.

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_sensitivity` result.
    z : float
        Significance threshold [-] (effect / SE).

    Returns
    -------
    dict
        "base" (quantity -> value), "variants" (name -> {"overrides", "effects": quantity ->
        {"value", "effect", "se", "significant"}}), "runs_per_variant", "runs_used".
    """
    qs = [str(q) for q in ds["quantity"].values]
    over = json.loads(ds.attrs["overrides_json"])
    out = {"study": "sensitivity", "grade_G_mm_s": ds.attrs["grade"],
           "G_ini_mm_s": ds.attrs["G_ini"], "starts": ds.attrs["starts"],
           "runs_per_variant": ds.attrs["runs_per_variant"], "runs_used": ds.attrs["runs_used"],
           "tie_mm_s": ds.attrs["tie_mm_s"], "z": float(z),
           "units": dict(zip(qs, map(str, ds["unit"].values))),
           "base": {q: float(v) for q, v in zip(qs, ds["value"].sel(variant="base").values)},
           "variants": {}}
    for name in [str(v) for v in ds["variant"].values[1:]]:
        d = ds.sel(variant=name)
        eff = {}
        for q, v, e, se in zip(qs, d["value"].values, d["effect"].values, d["effect_se"].values):
            sig = bool(abs(e) > z * se) if se > 0 else bool(e != 0)
            eff[q] = {"value": float(v), "effect": float(e), "se": float(se), "significant": sig}
        out["variants"][name] = {"overrides": over.get(name, []), "effects": eff}
    return out
