"""``autobalance reproduce ...``: the seed-004 temporary-speed-reduction studies (typer sub-app).

Commands: tsr-single, tsr-monte-carlo, tsr-unbalance, tsr-profile, tsr-plateau, immobility.
Each takes ``--quick/--full`` (coarse grids for the test suite vs the paper's grids),
``--out DIR`` (writes DIR/<study>.nc, DIR/<study>.png, DIR/<study>_rows.json and, for sweeps,
the durable sweep stores DIR/stores/..., reused on a rerun) and ``--json`` (one JSON object:
study, variant, comparison rows, wall time). Input errors: one line on stderr, exit code 2.
``immobility`` is also meant to be registered as ``autobalance analyze immobility``.
"""
from __future__ import annotations

import json
import time
from pathlib import Path
from typing import Annotated, Optional

import typer

from .cli_common import _clean, _guard, _print_json
from .config import ConfigError

app = typer.Typer(name="reproduce", no_args_is_help=True, add_completion=False,
                  pretty_exceptions_enable=False,
                  help="Seed-004 TSR studies against the paper: single run, start-position Monte "
                       "Carlo, initial-unbalance sweep, speed profile, plateau map, immobility.")

QuickOpt = Annotated[bool, typer.Option("--quick/--full", help="Coarse grids (seconds) or the "
                                                               "paper's grids (minutes).")]
OutOpt = Annotated[Optional[Path], typer.Option("--out", metavar="DIR",
                                                help="Write data (.nc), figure (.png), rows (.json).")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object (SI) on stdout.")]
WorkersOpt = Annotated[Optional[int], typer.Option("--workers", help="Local processes (default: all cores).")]
ExecOpt = Annotated[str, typer.Option("--executor", help="serial | local | dask")]
NOpt = Annotated[Optional[int], typer.Option("--n", help="Start positions per ball (default: "
                                                         "quick 8, full 50).")]


def _check_n(n, lo=1):
    if n is not None and n < lo:
        raise ConfigError(f"--n = {n}: must be an integer >= {lo}")


def _cases(spec: str, allowed: dict) -> tuple:
    names = list(allowed) if spec.strip() == "all" else [c.strip() for c in spec.split(",") if c.strip()]
    for c in names:
        if c not in allowed:
            raise ConfigError(f"--cases = {spec!r}: unknown case {c!r}; allowed: "
                              f"{', '.join(allowed)} or all")
    if not names:
        raise ConfigError(f"--cases = {spec!r}: give at least one case")
    return tuple(names)


def _write(out: Path, name: str, ds, rows, meta: dict) -> dict:
    """Data (NetCDF), figure (PNG) and rows (JSON) into ``out``; returns the paths written."""
    from .plotting import tsr as plots
    from .studies.tsr_004 import STUDIES

    out.mkdir(parents=True, exist_ok=True)
    clean = ds.copy()
    clean.attrs = {k: (json.dumps(_clean(v)) if isinstance(v, (list, dict, bool)) else v)
                   for k, v in ds.attrs.items()}
    for c in clean.coords:
        if clean[c].dtype == object:
            clean = clean.assign_coords({c: clean[c].astype(str)})
    nc = out / f"{name}.nc"
    clean.to_netcdf(nc)
    png = out / f"{name}.png"
    getattr(plots, STUDIES[name][2])(ds).savefig(png, dpi=110)
    rj = out / f"{name}_rows.json"
    rj.write_text(json.dumps(_clean({**meta, "rows": rows}), indent=1, allow_nan=False))
    return {"data": str(nc), "figure": str(png), "rows": str(rj)}


def _finish(name: str, ds, quick: bool, out: Optional[Path], as_json: bool, t0: float, extra=None):
    from .studies.tsr_004 import STUDIES

    rows = STUDIES[name][1](ds)
    meta = {"study": name, "variant": "quick" if quick else "full",
            "wall_time_s": round(time.perf_counter() - t0, 2),
            "profile": ds.attrs.get("profile", ""), **(extra or {})}
    files = _write(out, name, ds, rows, meta) if out is not None else {}
    n_ok = sum(r["ok"] for r in rows)
    if as_json:
        _print_json({**meta, "n_rows": len(rows), "n_ok": n_ok, "rows": rows, "files": files})
        return
    typer.echo(f"{name} ({meta['variant']}, {meta['wall_time_s']:.1f} s): {n_ok}/{len(rows)} rows ok")
    for r in rows:
        typer.echo(f"  [{'ok ' if r['ok'] else 'MISS'}] {r['quantity']}: published {r['published']}, "
                   f"computed {r['computed']} (tol {r['tolerance']})")
    for k, v in files.items():
        typer.echo(f"  {k}: {v}")


def _stores(out):
    return None if out is None else Path(out) / "stores"


@app.command("tsr-single")
def tsr_single(quick: QuickOpt = True, out: OutOpt = None, as_json: JsonOpt = False):
    """004 Fig. 4: one TSR run with and without the balancer, from G14 starts."""
    from .studies.tsr_004 import compute_single

    t0 = time.perf_counter()
    with _guard():
        ds = compute_single(save_dt=0.02 if quick else 0.005)
        _finish("tsr-single", ds, quick, out, as_json, t0)


@app.command("tsr-monte-carlo")
def tsr_monte_carlo(quick: QuickOpt = True, out: OutOpt = None, as_json: JsonOpt = False,
                    n: NOpt = None, executor: ExecOpt = "local", workers: WorkersOpt = None):
    """004 Fig. 5-6, Table 2: n x n start positions (full: 1275 runs)."""
    from .studies.tsr_004 import compute_monte_carlo

    t0 = time.perf_counter()
    with _guard():
        _check_n(n)
        n = n or (8 if quick else 50)
        ds = compute_monte_carlo(n, store_dir=_stores(out), executor=executor, workers=workers)
        _finish("tsr-monte-carlo", ds, quick, out, as_json, t0, {"n": n, "runs": ds.attrs["runs"]})


@app.command("tsr-unbalance")
def tsr_unbalance(quick: QuickOpt = True, out: OutOpt = None, as_json: JsonOpt = False,
                  n: NOpt = None, cases: Annotated[str, typer.Option(
                      "--cases", help="nominal, mu0.5, mu0.25, c0.6, c0.5 (comma list) or all")] = "nominal",
                  executor: ExecOpt = "local", workers: WorkersOpt = None):
    """004 Fig. 7, Tables 3-4: G_ini over [G0, G50] x start grid; valid G16 ranges, efficiency."""
    from .studies.tsr_004 import UNBALANCE_CASES, compute_unbalance

    t0 = time.perf_counter()
    with _guard():
        _check_n(n)
        cs = _cases(cases, UNBALANCE_CASES)
        n = n or (8 if quick else 50)
        ds = compute_unbalance(cs, n=n, quick=quick, store_dir=_stores(out), executor=executor,
                               workers=workers)
        _finish("tsr-unbalance", ds, quick, out, as_json, t0, {"n": n, "cases": list(cs)})


@app.command("tsr-profile")
def tsr_profile(quick: QuickOpt = True, out: OutOpt = None, as_json: JsonOpt = False,
                n: NOpt = None, executor: ExecOpt = "local", workers: WorkersOpt = None):
    """004 Fig. 9: STD vs 3x slower run-up vs TSR (95 % isolines against G_ini)."""
    from .studies.tsr_004 import compute_profile

    t0 = time.perf_counter()
    with _guard():
        _check_n(n)
        n = n or (8 if quick else 50)
        ds = compute_profile(n=n, quick=quick, store_dir=_stores(out), executor=executor,
                             workers=workers)
        _finish("tsr-profile", ds, quick, out, as_json, t0, {"n": n})


@app.command("tsr-plateau")
def tsr_plateau(quick: QuickOpt = True, out: OutOpt = None, as_json: JsonOpt = False,
                n: NOpt = None, cases: Annotated[str, typer.Option(
                    "--cases", help="nominal, c0.5 (comma list) or all")] = "nominal",
                executor: ExecOpt = "local", workers: WorkersOpt = None):
    """004 Fig. 14-15: lower plateau x G_ini -> 95 % residual G; the ideal plateau."""
    from .studies.tsr_004 import PLATEAU_CASES, compute_plateau

    t0 = time.perf_counter()
    with _guard():
        _check_n(n)
        cs = _cases(cases, PLATEAU_CASES)
        n = n or (6 if quick else 20)
        ds = compute_plateau(cs, n=n, quick=quick, store_dir=_stores(out), executor=executor,
                             workers=workers)
        _finish("tsr-plateau", ds, quick, out, as_json, t0, {"n": n, "cases": list(cs)})


def _floats(spec: str, name: str) -> tuple:
    try:
        vals = tuple(float(x) for x in spec.split(",") if x.strip())
    except ValueError:
        raise ConfigError(f"{name} = {spec!r}: expected comma-separated numbers, e.g. '0.5,1,2'") from None
    if not vals or any(not (v > 0) for v in vals):
        raise ConfigError(f"{name} = {spec!r}: expected positive numbers, e.g. '0.5,1,2'")
    return vals


@app.command("immobility")
def immobility_cmd(quick: QuickOpt = True, out: OutOpt = None, as_json: JsonOpt = False,
                   g_ini: Annotated[float, typer.Option("--g-ini", help="Initial unbalance grade "
                                                                        "[mm/s] (004: 20).")] = 20.0,
                   mu_r: Annotated[str, typer.Option("--mu-r", help="Friction factors mu/mu_ref.")] = "0.25,0.5,1,2,5",
                   c_r: Annotated[str, typer.Option("--c-r", help="Damping factors c/c_ref.")] = "0.5,0.6,1,1.4",
                   n_conf: Annotated[int, typer.Option("--n-conf", help="Positions per ball (full).")] = 100):
    """004 Fig. 8/10: share of ball configurations at rest that cannot move, vs speed
    (closed form, no time integration)."""
    from .studies.tsr_004 import compute_immobility

    t0 = time.perf_counter()
    with _guard():
        if not (g_ini >= 0):
            raise ConfigError(f"--g-ini = {g_ini}: must be >= 0 [mm/s]")
        if n_conf < 2:
            raise ConfigError(f"--n-conf = {n_conf}: must be an integer >= 2")
        ds = compute_immobility(G_ini=g_ini, mu_r=_floats(mu_r, "--mu-r"), c_r=_floats(c_r, "--c-r"),
                                n_conf=n_conf, quick=quick)
        _finish("immobility", ds, quick, out, as_json, t0, {"G_ini_mm_s": g_ini})


__all__ = ["app"]
