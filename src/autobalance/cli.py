"""Command line interface (typer), thin: parse, call the library, print.

Every command takes ``--json`` and then prints exactly one JSON object on stdout (SI units,
snake_case keys with unit suffixes; NaN and inf become ``null``). Input errors (bad config, bad
value, unknown preset, unreadable file) print one line ``error: <message>`` on stderr and exit
with code 2, never a traceback. A simulation whose status is not ``"ok"`` exits with code 1.

The physics modules are imported inside the commands so that ``presets`` and ``show`` stay fast.
"""
from __future__ import annotations

import json
import math
import os
import sys
import time
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from .cli_common import (USER_ERRORS, _clean, _fail, _guard, _one_line, _print_json, check_grade,
                         check_executor, check_output_file, check_workers, quiet_dask_logs)
from .config import ConfigError, describe, list_presets, load_config, parse_quantity

app = typer.Typer(name="autobalance", no_args_is_help=True, add_completion=False,
                  pretty_exceptions_enable=False,
                  help="Simulate and design passive automatic balancers: presets, show, simulate, "
                       "response, sweep, analyze, liquid, reproduce, demo.")

SetOpt = Annotated[Optional[list[str]], typer.Option(
    "--set", "-s", metavar="PATH=VALUE",
    help="Override a value, e.g. --set suspension.kx='25 N/mm' (repeatable).")]
ProfileOpt = Annotated[Optional[str], typer.Option(
    "--profile", help="Switch the speed profile kind (constant, ramp, table, std, tsr, motor); "
                      "profile keys from the file that the new kind does not take are dropped.")]
JsonOpt = Annotated[bool, typer.Option("--json", help="Print one JSON object (SI) on stdout.")]
SourceArg = Annotated[str, typer.Argument(metavar="PRESET|CONFIG",
                                          help="Preset name or path of a .toml file.")]


def _fmt(v: Any, width: int = 6) -> str:
    if isinstance(v, bool) or v is None:
        return str(v)
    if isinstance(v, float):
        return f"{v:.{width}g}"
    if isinstance(v, (list, tuple)):
        items = [_fmt(x, width) for x in v[:6]]
        return "[" + ", ".join(items) + (", ...]" if len(v) > 6 else "]")
    return str(v)


def _echo_tree(key: str, value: Any, level: int) -> None:
    """Print a (nested) summary entry as indented ``key  value`` lines."""
    pad = "  " * level
    if isinstance(value, dict):
        typer.echo(f"{pad}{key}:")
        for k, v in value.items():
            _echo_tree(k, v, level + 1)
    elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
        for i, v in enumerate(value):
            _echo_tree(f"{key}[{i}]", v, level)
    else:
        typer.echo(f"{pad}{key:<{max(34 - 2 * level, 1)}} {_fmt(value)}")


def _overrides(sets: Optional[list[str]], profile: Optional[str]) -> list[str]:
    return list(sets or []) + ([f"profile.kind={profile}"] if profile else [])


PLOT_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")


def _check_output(path: Optional[Path], what: str) -> None:
    """Refuse an output file that could not be written (a directory, a missing or read-only
    directory, a wrong --plot suffix) before simulating."""
    if what == "--plot":
        check_output_file(path, what, "plot.png", PLOT_SUFFIXES)
    else:
        check_output_file(path, what, "run.nc")


def _run(cfg):
    """Simulate one configuration; returns (sim, wall time [s])."""
    from .simulate import simulate

    t0 = time.perf_counter()
    sim = simulate(cfg.system, cfg.spin, initial=cfg.initial, options=cfg.options, throw=False)
    return sim, time.perf_counter() - t0


def _write(sim, out: Optional[Path], plot: Optional[Path]) -> dict:
    """Write the NetCDF file and the figure; returns {"netcdf": path, "plot": path}."""
    files = {}
    if out is not None:
        sim.to_netcdf(out)
        files["netcdf"] = str(out)
    if plot is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from .plotting import plot_simulation

        fig = plot_simulation(sim)
        fig = fig[0] if isinstance(fig, tuple) else fig
        fig.savefig(plot, dpi=120)
        plt.close(fig)
        files["plot"] = str(plot)
    return files


# -- commands ---------------------------------------------------------------------------------
@app.command()
def presets(json_: JsonOpt = False) -> None:
    """List the presets shipped with the package."""
    with _guard():
        items = list_presets()
    if json_:
        _print_json({"presets": items})
        return
    width = max((len(p["name"]) for p in items), default=4)
    for p in items:
        typer.echo(f"{p['name']:<{width}}  {p['description']}")


def _raw_key(dkey: str, raw_section: dict) -> Optional[str]:
    best = None
    for k in raw_section:
        if (dkey == k or dkey.startswith(k + "_")) and (best is None or len(k) > len(best)):
            best = k
    return best


@app.command()
def show(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
         json_: JsonOpt = False) -> None:
    """Show the full parameter set in SI with the source of each value."""
    with _guard():
        cfg = load_config(source, _overrides(set_, profile))
        d = describe(cfg)
    if json_:
        _print_json(d)
        return
    typer.echo(f"{d['name']}: {d['description']}")
    typer.echo(f"source: {d['source']}")
    for section in ("rotor", "suspension", "balancer", "gravity", "profile", "initial", "options",
                    "derived"):
        typer.echo(f"[{section}]")
        raw = cfg.raw.get(section, {}) if isinstance(cfg.raw.get(section), dict) else {}
        for key, value in d[section].items():
            line = f"  {key:<30} {_fmt(value)}"
            rk = _raw_key(key, raw)
            if rk is not None:
                if isinstance(raw[rk], (str, list)) and str(raw[rk]) != str(value):
                    line += f"   (= {raw[rk]!s})" if isinstance(raw[rk], list) else \
                        f"   (= {raw[rk]})"
                src = d["sources"].get(f"{section}.{rk}")
                if src:
                    line += f"   # {src}"
            typer.echo(line)


@app.command("simulate")
def simulate_cmd(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
                 out: Annotated[Optional[Path], typer.Option(
                     "--out", help="Write the time history to this NetCDF file.")] = None,
                 plot: Annotated[Optional[Path], typer.Option(
                     "--plot", help="Save a figure of the run to this PNG file.")] = None,
                 json_: JsonOpt = False) -> None:
    """Simulate one run of a preset or config file."""
    with _guard():
        cfg = load_config(source, _overrides(set_, profile))
        _check_output(out, "--out")
        _check_output(plot, "--plot")
        sim, wall = _run(cfg)
        files = _write(sim, out, plot)
    result = dict(sim.summary())
    for key, value in (("name", cfg.name), ("config", cfg.source), ("wall_time_s", wall),
                       ("files", files)):
        result.setdefault(key, value)
    ok = sim.status == "ok"
    if json_:
        _print_json(result)
    else:
        typer.echo(f"{cfg.name}: status {sim.status} ({wall:.1f} s wall)")
        for key, value in result.items():
            if key not in ("name", "config", "status", "files", "wall_time_s", "message"):
                _echo_tree(key, value, 1)
        for kind, path in files.items():
            typer.echo(f"wrote {kind}: {path}")
        if not ok:
            typer.echo(f"simulation {sim.status}: {sim.message}", err=True)
    if not ok:
        raise typer.Exit(1)


#: Memory of one speed of ``response`` [B]: the numpy work arrays, five lists of Python floats
#: and their JSON text (generous).
RESPONSE_BYTES_PER_SPEED = 1024


def _count(text: str) -> int:
    """A point count: ``"200"``, or an integral float such as ``"1e3"``; 0 if neither."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        v = float(text)
    except ValueError:
        return 0
    return int(v) if math.isfinite(v) and v == int(v) else 0


def _speeds(spec: Optional[str], nominal: float):
    """``"lo:hi:n"`` (speeds with units or bare rad/s) -> array [rad/s]; default 0..2*nominal.

    n is a positive integer (``1e3`` is read as 1000) whose table must fit the memory limit
    (:func:`autobalance.limits.check_memory`), checked before anything is allocated."""
    import numpy as np

    from .limits import check_memory

    if spec is None:
        return np.linspace(0.0, 2.0 * nominal, 200)
    parts = spec.split(":")
    if len(parts) != 3:
        raise ConfigError(f"--speeds = {spec!r}: expected 'lo:hi:n', e.g. '0:2000 rpm:200' "
                          "(bare numbers in rad/s)")
    lo = parse_quantity(parts[0] or "0", "speed", "--speeds lo")
    hi = parse_quantity(parts[1], "speed", "--speeds hi")
    n = _count(parts[2].strip())
    if n < 2 or not (math.isfinite(lo) and math.isfinite(hi)) or lo < 0 or hi <= lo:
        raise ConfigError(f"--speeds = {spec!r}: need 0 <= lo < hi and an integer n >= 2")
    check_memory("--speeds", spec, float(n) * RESPONSE_BYTES_PER_SPEED,
                 f"response table of {n} speeds")
    return np.linspace(lo, hi, n)


@app.command()
def response(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
             speeds: Annotated[Optional[str], typer.Option(
                 "--speeds", metavar="LO:HI:N",
                 help="Speed grid, e.g. '0:2000 rpm:200' (bare numbers in rad/s); "
                      "default 200 points from 0 to 2x the nominal speed.")] = None,
             json_: JsonOpt = False) -> None:
    """Harmonic (steady-state) unbalance response of the suspended rotor and its critical speeds."""
    with _guard():
        cfg = load_config(source, _overrides(set_, profile))
        grid = _speeds(speeds, cfg.spin.nominal_speed)
        from .physics.response import response_table

        table = dict(response_table(cfg.system, grid))
    result = {"name": cfg.name, "config": cfg.source, **table}
    if json_:
        _print_json(result)
        return
    typer.echo(f"{cfg.name}: harmonic response, {len(grid)} speeds "
               f"{grid[0]:.4g} .. {grid[-1]:.4g} rad/s")
    hz = table.get("natural_frequencies_hz", [])
    typer.echo("  natural frequencies: " + ", ".join(
        f"{f:.4g} Hz ({f * 60:.4g} rpm)" for f in hz))
    w = list(table.get("speed_rad_s", []))
    for axis in ("x", "y"):
        amp = list(table.get(f"amplitude_{axis}_m", []))
        if amp and w:
            i = max(range(len(amp)), key=lambda j: amp[j])
            typer.echo(f"  peak amplitude {axis}: {amp[i]:.4g} m at {w[i]:.4g} rad/s "
                       f"({w[i] * 30 / math.pi:.4g} rpm)")


def _num(v: Any, scale: float = 1.0) -> str:
    ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
    return f"{v * scale:.4g}" if ok else "-"


def _row(name: str, status: str, wall: Any, summary: dict) -> str:
    """One line of the demo table (G initial, G final [mm/s], max amplitude [mm])."""
    final = summary.get("final") if isinstance(summary.get("final"), dict) else {}
    return (f"{name:<20} {status:<10} {wall:>8.2f} {_num(summary.get('initial_grade_G_mm_s')):>10}"
            f" {_num(final.get('grade_G_mm_s')):>10} {_num(summary.get('max_amplitude_m'), 1e3):>12}")


@app.command("sweep")
def sweep_cmd(spec: Annotated[Path, typer.Argument(metavar="SWEEP.toml",
                                                   help="Sweep description (TOML).")],
              store: Annotated[Path, typer.Option("--store", help="Store directory (durable, "
                                                  "resumable).")],
              scheduler: Annotated[Optional[str], typer.Option(
                  "--scheduler", help="Dask scheduler address (default: $DASK_SCHEDULER_ADDRESS)"
                  "; runs on that cluster.")] = None,
              workers: Annotated[Optional[int], typer.Option(
                  "--workers", help="Local worker processes (default: all cores).")] = None,
              executor: Annotated[Optional[str], typer.Option(
                  "--executor", help="serial, local (default) or dask.")] = None,
              resume: Annotated[bool, typer.Option(
                  "--resume", help="Continue an interrupted sweep in STORE.")] = False,
              grade: Annotated[float, typer.Option(
                  "--grade", help="Grade limit G [mm/s] for the share in the summary.")] = 16.0,
              plot: Annotated[Optional[Path], typer.Option(
                  "--plot", help="Write a summary figure (PNG/SVG/PDF).")] = None,
              json_: JsonOpt = False) -> None:
    """Run a grid / Monte-Carlo sweep into a durable store; print its summary."""
    from .sweep import SweepAborted, SweepError, SweepInterrupted, load_spec, summary_dict, sweep

    with _guard():
        try:
            check_output_file(plot, "--plot", "summary.png", (".png", ".svg", ".pdf"))
            check_grade(grade)
            check_workers(workers)      # >= 1, and their processes fit the memory limit
            check_executor(executor)
            sp = load_spec(spec)
            if scheduler or executor == "dask" or os.environ.get("DASK_SCHEDULER_ADDRESS"):
                quiet_dask_logs()
            t0 = time.perf_counter()
            ds = sweep(sp, store, executor=executor, workers=workers, scheduler=scheduler,
                       resume=resume, progress=True)
        except SweepError as e:
            _fail(str(e))
        except SweepInterrupted as e:       # Ctrl-C / SIGTERM: finished tasks kept
            _fail(str(e), 128 + int(e.signal))
        except SweepAborted as e:           # lost scheduler, dead workers: store intact
            _fail(str(e), 1)
        except KeyboardInterrupt:           # before the sweep started: nothing was run
            _fail("interrupted before the first task; nothing was changed", 130)
        wall = time.perf_counter() - t0
        summary = summary_dict(ds, grade)
        summary.update({"store": str(store), "result": str(Path(store) / "result.zarr"),
                        "wall_time_s": wall, "dims": {k: int(v) for k, v in ds.sizes.items()}})
        if plot is not None:
            from .plotting import plot_sweep

            plot_sweep(ds, grade).savefig(plot, dpi=110)
            summary["plot"] = str(plot)
    if json_:
        _print_json(summary)
        return
    typer.echo(f"sweep {summary['name']}: {summary['runs']} runs ({summary['failed_runs']} "
               f"failed) in {wall:.1f} s -> {summary['result']}")
    for c in summary["checkpoints"]:
        typer.echo(f"  t = {c['time_s']:g} s: G p5/p50/p95 = {c['grade_G_p5_mm_s']:.2f} / "
                   f"{c['grade_G_p50_mm_s']:.2f} / {c['grade_G_p95_mm_s']:.2f} mm/s, "
                   f"share <= G{grade:g}: {100 * c['share_below_limit']:.1f} %")


@app.command()
def demo(out: Annotated[Path, typer.Option("--out", help="Output directory.")] = Path("demo"),
         json_: JsonOpt = False) -> None:
    """Simulate every preset; write DIR/summary.json, DIR/<preset>.nc and DIR/<preset>.png."""
    results: dict[str, dict] = {}
    with _guard():
        out.mkdir(parents=True, exist_ok=True)
        items = list_presets()
        if not json_:
            typer.echo(f"{'preset':<20} {'status':<10} {'wall [s]':>8} {'G0 [mm/s]':>10}"
                       f" {'G [mm/s]':>10} {'max amp [mm]':>12}")
        for p in items:
            cfg = load_config(p["name"])
            sim, wall = _run(cfg)
            files = _write(sim, out / f"{p['name']}.nc", out / f"{p['name']}.png")
            summary = dict(sim.summary())
            summary.setdefault("status", sim.status)
            results[p["name"]] = {**summary, "wall_time_s": wall, "files": files}
            if not json_:
                typer.echo(_row(p["name"], sim.status, wall, summary))
        ok = all(r.get("status") == "ok" for r in results.values())
        report = {"status": "ok" if ok else "failed", "out": str(out), "presets": results}
        (out / "summary.json").write_text(json.dumps(_clean(report), indent=1, allow_nan=False))
    if json_:
        _print_json(report)
    else:
        typer.echo(f"wrote {out / 'summary.json'}")
    if not ok:
        raise typer.Exit(1)


def _register_subapps() -> None:
    """Sub-command groups living in their own modules."""
    from .cli_analyze import app as analyze_app
    from .cli_liquid import app as liquid_app
    from .cli_reproduce import reproduce

    app.add_typer(analyze_app, name="analyze",
                  help="Washer analysis (seed 000): response, vibratory forces, equilibria, "
                       "error bounds, tolerance design, kinetic-static model, studies; 004 "
                       "immobility.")
    app.command("reproduce")(reproduce)
    app.add_typer(liquid_app, name="liquid",
                  help="Liquid (Leblanc) balancers (seeds 001, 003): free surface, motion modes, "
                       "entrainment speeds, kinetostatics, run-up simulation.")


_register_subapps()


def main(argv: Optional[list[str]] = None) -> None:
    """Console entry point ``autobalance``: input errors, usage errors included (a bad option
    value, a missing argument, an unknown command), exit 2 with one line on stderr; Ctrl-C
    exits 130 with one line; never a traceback for either."""
    from typer._click.exceptions import NoArgsIsHelpError, UsageError

    try:
        rv = app(args=argv, prog_name="autobalance", standalone_mode=False)
    except NoArgsIsHelpError:           # the help was printed
        sys.exit(0)
    except UsageError as exc:
        cmd = exc.ctx.command_path if exc.ctx is not None else "autobalance"
        typer.echo(f"error: {' '.join(exc.format_message().split())} (see {cmd} --help)",
                   err=True)
        sys.exit(2)
    except USER_ERRORS as exc:
        typer.echo(f"error: {_one_line(exc)}", err=True)
        sys.exit(2)
    except KeyboardInterrupt as exc:    # a SweepInterrupted says what was kept
        typer.echo(f"error: {_one_line(exc) if str(exc) else 'interrupted'}", err=True)
        sys.exit(128 + int(getattr(exc, "signal", 2)))
    sys.exit(rv if isinstance(rv, int) else 0)


if __name__ == "__main__":
    main()
