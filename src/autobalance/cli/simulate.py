"""``autobalance simulate``: one run of a preset or config file (and the pieces ``demo`` reuses:
:func:`run_config`, :func:`write_outputs`, the text formatting)."""
from __future__ import annotations

import time
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from .common import (JsonOpt, PlotOpt, ProfileOpt, SetOpt, SourceArg, check_output_file,
                     check_plot, guard, load_machine, print_json)

#: Figure formats of ``simulate --plot``.
PLOT_SUFFIXES = (".png", ".pdf", ".svg", ".jpg", ".jpeg")


def fmt_value(v: Any, width: int = 6) -> str:
    """A summary value for the terminal: floats to ``width`` significant digits, lists to their
    first six items.

    Parameters
    ----------
    v : Any
        The value.
    width : int
        Significant digits of floats.

    Returns
    -------
    str
    """
    if isinstance(v, bool) or v is None:
        return str(v)
    if isinstance(v, float):
        return f"{v:.{width}g}"
    if isinstance(v, (list, tuple)):
        items = [fmt_value(x, width) for x in v[:6]]
        return "[" + ", ".join(items) + (", ...]" if len(v) > 6 else "]")
    return str(v)


def echo_tree(key: str, value: Any, level: int) -> None:
    """Print a (nested) summary entry as indented ``key  value`` lines.

    Parameters
    ----------
    key : str
        Name of the entry.
    value : Any
        A value, a dict (printed as a sub-tree) or a list of dicts (one sub-tree each).
    level : int
        Indentation level (two spaces each).
    """
    pad = "  " * level
    if isinstance(value, dict):
        typer.echo(f"{pad}{key}:")
        for k, v in value.items():
            echo_tree(k, v, level + 1)
    elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
        for i, v in enumerate(value):
            echo_tree(f"{key}[{i}]", v, level)
    else:
        typer.echo(f"{pad}{key:<{max(34 - 2 * level, 1)}} {fmt_value(value)}")


def run_config(cfg):
    """Simulate one configuration.

    Parameters
    ----------
    cfg : autobalance.config.Config
        The machine, speed profile, initial state and options.

    Returns
    -------
    sim : autobalance.result.Simulation
        The run (``status`` says whether it finished; it does not raise on failure).
    wall : float
        Wall time of the run [s].
    """
    from ..simulate import simulate

    t0 = time.perf_counter()
    sim = simulate(cfg.system, cfg.spin, initial=cfg.initial, options=cfg.options, throw=False)
    return sim, time.perf_counter() - t0


def write_outputs(sim, out: Optional[Path], plot) -> dict:
    """Write a run's NetCDF file and its figure.

    Parameters
    ----------
    sim : autobalance.result.Simulation
        The run.
    out : Path or None
        NetCDF file, or None for none.
    plot : str or Path or None
        Figure file (format from its suffix), or None for none.

    Returns
    -------
    dict
        ``{"netcdf": path, "plot": path}`` for the files written.
    """
    files = {}
    if out is not None:
        sim.to_netcdf(out)
        files["netcdf"] = str(out)
    if plot is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from ..plotting import plot_simulation

        fig = plot_simulation(sim)
        fig = fig[0] if isinstance(fig, tuple) else fig
        fig.savefig(plot, dpi=120)
        plt.close(fig)
        files["plot"] = str(plot)
    return files


def simulate_cmd(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
                 out: Annotated[Optional[Path], typer.Option(
                     "--out", help="Write the time history to this NetCDF file.")] = None,
                 plot: PlotOpt = None, json_: JsonOpt = False) -> None:
    """Simulate one run of a preset or config file.\f

    Parameters
    ----------
    source, set_, profile, json_
        The shared options (:mod:`autobalance.cli.common`); the JSON object is the run's summary.
    out : Path
        NetCDF file for the time history.
    plot : str
        Figure file (.png, .pdf, .svg, .jpg, .jpeg).

    Exits with code 1 if the run's status is not ``"ok"``, 2 on an input error.
    """
    with guard():
        cfg = load_machine(source, set_, profile)
        check_output_file(out, "--out", "run.nc")
        check_plot(plot, PLOT_SUFFIXES)
        sim, wall = run_config(cfg)
        files = write_outputs(sim, out, plot)
    result = dict(sim.summary())
    for key, value in (("name", cfg.name), ("config", cfg.source), ("wall_time_s", wall),
                       ("files", files)):
        result.setdefault(key, value)
    ok = sim.status == "ok"
    if json_:
        print_json(result)
    else:
        typer.echo(f"{cfg.name}: status {sim.status} ({wall:.1f} s wall)")
        for key, value in result.items():
            if key not in ("name", "config", "status", "files", "wall_time_s", "message"):
                echo_tree(key, value, 1)
        for kind, path in files.items():
            typer.echo(f"wrote {kind}: {path}")
        if not ok:
            typer.echo(f"simulation {sim.status}: {sim.message}", err=True)
    if not ok:
        raise typer.Exit(1)
