"""Readings of what 004 leaves open, taken together: how many of 004's published
Monte-Carlo quantities (sec. 4.2, Fig. 5-6, Table 2: two modes, four shares, five regions) each
reading reproduces, with the tolerances of the report's rows (:func:`.compare.compare_monte_carlo`).

This is an *identification*, not a reproduction: a reading that reproduces more quantities is a
more likely description of what 004 ran, nothing more. The report keeps our model (compliant
contact, exact stick, the 18 s run-up read off Fig. 3) and 004's stated parameters. A reading
that changes a parameter 004 states says so in its ``changes_stated`` text.

    python -m autobalance.papers.p004.readings --n 50 --store DIR     # paper size, ~5 min

The runs are :func:`autobalance.studies._sensitivity.compute_sensitivity` over the same starts,
so the readings' differences are paired.
"""
from __future__ import annotations

import argparse
import json
from typing import TYPE_CHECKING

import numpy as np

from ...studies._sensitivity import compute_sensitivity
from ...studies.common import load
from ...studies.statistics import start_position_stats
from .compare import compare_monte_carlo
from .published import G_LIMIT, PRESET, PUBLISHED

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    import xarray as xr

__all__ = ["READINGS", "compute_readings", "reading_rows", "readings_markdown"]

#: 004's model as its equations state it: point masses that may coincide (eq 8-10 have no
#: contact) and its tanh friction law (sec. 3.1), run on the slow manifold (physics/friction.py)
EQUATIONS_004 = ("balancer.contact=none", "options.friction_law=creep")


def _readings() -> dict:
    cfg = load(PRESET)
    runup = 0.78 * float(cfg.spin.times[1])                 # 14 s against our 18 s reading
    plateau = 1.02 * cfg.system.natural_frequencies[0]      # 004's "ideal" plateau
    ru = f"profile.runup_time={runup!r}"
    pl = f"profile.plateau={plateau!r}"
    stated = (f"changes 004's stated plateau, 100 Hz = 1.06 Omega_n (sec. 4.6), to its ideal "
              f"1.02 Omega_n ({plateau / (2 * np.pi):.1f} Hz)")
    return {
        "004's equations": (EQUATIONS_004, ""),
        "004's equations, 14 s run-up": ((*EQUATIONS_004, ru), ""),
        "004's equations, 14 s run-up, 1.02 plateau": ((*EQUATIONS_004, ru, pl), stated),
        "our model, 14 s run-up, 1.02 plateau": ((ru, pl), stated),
    }


#: name -> (overrides, text of the stated parameter it changes or ""), besides the base (our model)
READINGS = _readings()


def compute_readings(n: int = 50, *, readings: dict | None = None,
                     store_dir: str | Path | None = None, executor: str = "local",
                     workers: int | None = None, scheduler: str | None = None) -> xr.Dataset:
    """The start-position Monte Carlo of 004's machine under our model ("base") and each reading.

    Parameters
    ----------
    n : int
        Start positions per ball [-] (004: 50, 1275 runs per reading).
    readings : dict or None
        name -> (overrides, changes_stated); None = :data:`READINGS`.
    store_dir, executor, workers, scheduler : str, Path, int or None
        As for :func:`autobalance.studies._sensitivity.compute_sensitivity`.

    Returns
    -------
    xarray.Dataset
        The sensitivity dataset (grade_G [mm/s] per variant, sample, checkpoint), attrs
        ``changes_stated_json`` and ``n``.
    """
    readings = READINGS if readings is None else readings
    ds = compute_sensitivity(PRESET, {k: list(v[0]) for k, v in readings.items()}, n=n,
                             grade=G_LIMIT, store_dir=store_dir, executor=executor,
                             workers=workers, scheduler=scheduler)
    ds.attrs["changes_stated_json"] = json.dumps({k: v[1] for k, v in readings.items()})
    ds.attrs["n"] = int(n)
    return ds


def reading_rows(ds: xr.Dataset) -> list:
    """Per reading: the published Monte-Carlo quantities it reproduces under the report's
    tolerances, with Table 2's regions strict and tie-aware.

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_readings` result.

    Returns
    -------
    list of dict
        name, changes_stated, values (quantity -> computed, as the report's rows show it),
        reproduced (keys), count, count_tied (regions tie-aware), total.
    """
    stated = json.loads(ds.attrs.get("changes_stated_json", "{}"))
    g_ini = float(ds.attrs["G_ini"])
    out = []
    for name in [str(v) for v in ds["variant"].values]:
        g = ds["grade_G"].sel(variant=name).values
        ok = np.all(np.isfinite(g), axis=1)
        st = start_position_stats(g[ok, 0], g[ok, -1], g_ini, float(ds.attrs["grade"]))
        base = {"n": int(ds.attrs["n"]), "runs": int(ok.sum()), **st}
        tied = {**base, **{f"region_{r}": st[f"region_tied_{r}"]
                           for r in PUBLISHED["monte_carlo"]["regions"]}}
        rows = [r for r in compare_monte_carlo(_AttrsOnly(base)) if not r["key"].endswith("/runs")]
        rows_t = [r for r in compare_monte_carlo(_AttrsOnly(tied)) if not r["key"].endswith("/runs")]
        out.append({"name": name, "changes_stated": stated.get(name, ""),
                    "values": {r["key"].split("/", 1)[1]: r["computed"] for r in rows},
                    "reproduced": [r["key"].split("/", 1)[1] for r in rows if r["ok"]],
                    "count": sum(bool(r["ok"]) for r in rows),
                    "count_tied": sum(bool(r["ok"]) for r in rows_t), "total": len(rows)})
    return out


class _AttrsOnly:
    """The attrs a comparison reads, without the dataset's variables."""

    def __init__(self, attrs):
        self.attrs = attrs


def readings_markdown(ds: xr.Dataset) -> str:
    """The readings as a markdown table: 004's published values, then each reading's values and
    its count of reproduced quantities (report tolerances; regions strict / tie-aware).

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_readings` result.

    Returns
    -------
    str
    """
    rows = reading_rows(ds)
    keys = list(rows[0]["values"])
    p = PUBLISHED["monte_carlo"]

    def pub(k):
        if k.startswith("regions/"):
            return 100 * p["regions"][k.split("/")[1]]
        v = p[k]
        return v if k.startswith("mode") else 100 * v

    head = "| reading | " + " | ".join(keys) + " | reproduced (strict / tie-aware) |"
    lines = [head, "|" + "---|" * (len(keys) + 2),
             "| 004 published | " + " | ".join(f"{pub(k):g}" for k in keys) + " | - |"]
    for r in rows:
        cells = [f"**{r['values'][k]:g}**" if k in r["reproduced"] else f"{r['values'][k]:g}"
                 for k in keys]
        name = "our model (report)" if r["name"] == "base" else r["name"]
        if r["changes_stated"]:
            name += " (changes a stated parameter)"
        lines.append(f"| {name} | " + " | ".join(cells)
                     + f" | {r['count']} / {r['count_tied']} of {r['total']} |")
    return "\n".join(lines)


def main(argv: Sequence[str] | None = None) -> None:
    """Command line: run the readings and print the table (``--help``)."""
    ap = argparse.ArgumentParser(prog="python -m autobalance.papers.p004.readings",
                                 description=__doc__.split("\n\n")[0])
    ap.add_argument("--n", type=int, default=50, help="start positions per ball (004: 50)")
    ap.add_argument("--store", default=None, help="directory of resumable sweep stores")
    ap.add_argument("--executor", default="local", choices=("local", "serial"))
    ap.add_argument("--netcdf", default=None, help="write the dataset to this NetCDF file")
    a = ap.parse_args(argv)
    ds = compute_readings(a.n, store_dir=a.store, executor=a.executor)
    if a.netcdf:
        from ...atomic import OutputError, atomic_output

        try:
            with atomic_output(a.netcdf, "--netcdf") as tmp:
                ds.to_netcdf(tmp)
        except OutputError as exc:
            ap.exit(2, f"error: {exc}\n")
    print(readings_markdown(ds))
    for r in reading_rows(ds):
        if r["changes_stated"]:
            print(f"* {r['name']}: {r['changes_stated']}")
    print(f"({ds.attrs['runs_per_variant']} runs per reading, {ds.attrs['wall_s']:.0f} s)")


if __name__ == "__main__":
    main()
