"""``autobalance simulate``: one run of a preset or config file (and the pieces ``demo`` reuses:
:func:`run_config`, :func:`write_outputs`, the text formatting)."""
from __future__ import annotations

import math
import time
from pathlib import Path
from typing import TYPE_CHECKING, Annotated, Any, Optional

import typer

from .common import (DEFAULT_GRADE, GradeOpt, JsonOpt, PlotOpt, ProfileOpt, SetOpt, SourceArg,
                     UnitsOpt, check_distinct, check_grade, check_output_file, check_plot,
                     class_text, grade_text, guard, load_machine, print_json)

if TYPE_CHECKING:
    from ..config import Config
    from ..config.display import DisplayUnits
    from ..liquid.simulate import LiquidSimulation
    from ..simulate import Simulation

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


#: JSON key suffix -> display kind (:mod:`autobalance.config.display`), longest suffix first.
SUFFIX_KINDS = (("_rad_s", "speed"), ("_kg_m", "unbalance"), ("_mm_s", "grade"),
                ("_kg", "mass"), ("_N", "force"), ("_m", "length"), ("_s", "time"))


#: Unit suffixes of other kinds that end like one of :data:`SUFFIX_KINDS` (shown unchanged).
COMPOUND_SUFFIXES = ("_1_s", "_m2_s", "_m_s2", "_N_m", "_n_m", "_s_m", "_kg_m2", "_m_s")


def _number(v: Any) -> bool:
    return isinstance(v, (int, float)) and not isinstance(v, bool)


def shown(key: str, value: Any, units: DisplayUnits,
          grade: float | None = None) -> tuple[str, Any]:
    """A JSON summary entry (SI, unit-suffixed key) as the terminal shows it: the key without
    its suffix and the value in the display unit of its kind, e.g. ``("nominal_speed_rad_s",
    418.9)`` -> ``("nominal_speed", "4000 rpm")``; a grade with its ISO 1940 class and, given
    ``grade``, whether it meets that target. Other entries pass unchanged.

    Parameters
    ----------
    key : str
        JSON key (``_rad_s``, ``_kg_m``, ``_mm_s``, ``_kg``, ``_N``, ``_m``, ``_s`` suffixes
        are converted).
    value : Any
        Its value [SI]: a number or a list of numbers (None or NaN shown as such).
    units : autobalance.config.display.DisplayUnits
        The display units.
    grade : float, optional
        Target grade G [mm/s] for the grades' "meets" / "above" note.

    Returns
    -------
    tuple
        (shown key, shown value).
    """
    if key.endswith(COMPOUND_SUFFIXES):
        return key, value
    for suffix, kind in SUFFIX_KINDS:
        if not key.endswith(suffix) or len(key) == len(suffix):
            continue
        if _number(value):
            text = units.fmt(value, kind)
            if kind == "grade":
                note = class_text(value)
                if grade is not None and math.isfinite(value):
                    note += f"; {'meets' if value <= grade else 'above'} G{grade:g}"
                text += f" (ISO class {note})"
            return key[:-len(suffix)], text
        if isinstance(value, (list, tuple)) and value and all(_number(v) for v in value):
            items = [f"{units.to(v, kind):.4g}" for v in value[:6]]
            more = ", ..." if len(value) > 6 else ""
            return key[:-len(suffix)], f"[{', '.join(items)}{more}] {units.unit(kind)}"
        return key, value
    return key, value


def echo_tree(key: str, value: Any, level: int, units: DisplayUnits | None = None,
              grade: float | None = None) -> None:
    """Print a (nested) summary entry as indented ``key  value`` lines.

    Parameters
    ----------
    key : str
        Name of the entry.
    value : Any
        A value, a dict (printed as a sub-tree) or a list of dicts (one sub-tree each).
    level : int
        Indentation level (two spaces each).
    units : autobalance.config.display.DisplayUnits, optional
        Show unit-suffixed entries in these units (:func:`shown`); None: as given.
    grade : float, optional
        Target grade G [mm/s] noted beside every grade (with ``units``).
    """
    pad = "  " * level
    if isinstance(value, dict):
        typer.echo(f"{pad}{key}:")
        for k, v in value.items():
            if units is None or k != "iso_class_G_mm_s":    # the class is shown with the grade
                echo_tree(k, v, level + 1, units, grade)
    elif isinstance(value, list) and value and all(isinstance(v, dict) for v in value):
        for i, v in enumerate(value):
            echo_tree(f"{key}[{i}]", v, level, units, grade)
    else:
        if units is not None:
            key, value = shown(key, value, units, grade)
        typer.echo(f"{pad}{key:<{max(34 - 2 * level, 1)}} {fmt_value(value)}")


def run_config(cfg: Config) -> tuple[Simulation | LiquidSimulation, float]:
    """Simulate one configuration.

    Parameters
    ----------
    cfg : autobalance.config.Config
        The machine, speed profile, initial state and options.

    Returns
    -------
    sim : autobalance.result.Simulation or autobalance.liquid.simulate.LiquidSimulation
        The run (``status`` says whether it finished; it does not raise on failure); a system
        with a ``[liquid]`` section and no balls runs the liquid film model, one with balls
        beside the liquid the ball simulator with the films (``Simulation.liquid``).
    wall : float
        Wall time of the run [s].
    """
    from ..simulate import simulate

    t0 = time.perf_counter()
    sim = simulate(cfg.system, cfg.spin, initial=cfg.initial, options=cfg.options, throw=False)
    return sim, time.perf_counter() - t0


def write_outputs(sim: Simulation | LiquidSimulation, out: Optional[Path],
                  plot: str | Path | None, units: DisplayUnits | None = None,
                  grade: float = DEFAULT_GRADE, what: tuple = ("--out", "--plot")) -> dict:
    """Write a run's NetCDF file (SI; ball angles unwrapped) and its figure, each atomically
    (:mod:`autobalance.atomic`); a run whose status is not ``"ok"`` writes neither (the
    previous files stay as they were).

    Parameters
    ----------
    sim : autobalance.result.Simulation
        The run.
    out : Path or None
        NetCDF file, or None for none.
    plot : str or Path or None
        Figure file (format from its suffix), or None for none.
    units : autobalance.config.display.DisplayUnits, optional
        Units of the figure's speed axis (None: rpm).
    grade : float
        Target grade G [mm/s], drawn with its ISO 1940 class (:func:`grade_text`).
    what : tuple of str
        The options that named ``out`` and ``plot``, for an error message (``demo``: its
        ``--out`` directory for both).

    Returns
    -------
    dict
        ``{"netcdf": path, "plot": path}`` for the files written (empty for a failed run).

    Raises
    ------
    autobalance.atomic.OutputError
        A file could not be written (one line naming its option from ``what``; the previous
        file unchanged).
    """
    from ..atomic import atomic_output, save_figure

    files = {}
    if sim.status != "ok":
        return files
    if out is not None:
        with atomic_output(out, what[0]) as tmp:
            sim.to_netcdf(tmp)
        files["netcdf"] = str(out)
    if plot is not None:
        import matplotlib

        matplotlib.use("Agg")
        import matplotlib.pyplot as plt

        from ..plotting import plot_run

        speed = {} if units is None else {"speed_unit": units.unit("speed"),
                                          "speed_factor": units.factor("speed")}
        fig = plot_run(sim, grade_limit=grade, grade_label=grade_text(grade), **speed)
        save_figure(fig, plot, what[1], dpi=120)
        plt.close(fig)
        files["plot"] = str(plot)
    return files


def simulate_cmd(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
                 out: Annotated[Optional[Path], typer.Option(
                     "--out", help="Write the time history to this NetCDF file.")] = None,
                 plot: PlotOpt = None, json_: JsonOpt = False, grade: GradeOpt = DEFAULT_GRADE,
                 units: UnitsOpt = None) -> None:
    """Simulate one run of a preset or config file.\f

    Parameters
    ----------
    source, set_, profile, json_, grade, units
        The shared options (:mod:`autobalance.cli.common`); the JSON object is the run's summary
        (SI) with the target grade ``grade_limit_mm_s`` and ``meets_grade_limit`` (the final
        grade <= the target); the text shows values in ``units`` (default: as written in the
        config) and each grade with its ISO 1940 class.
    out : Path
        NetCDF file for the time history.
    plot : str
        Figure file (.png, .pdf, .svg, .jpg, .jpeg).

    Exits with code 1 if the run's status is not ``"ok"`` (then ``out`` and ``plot`` are not
    written), 2 on an input error (an output that is the config file or the other output, or
    that cannot be written, included).
    """
    from ..config.display import display_units

    with guard():
        grade = check_grade(grade)
        cfg = load_machine(source, set_, profile)
        shown_units = display_units(cfg, units)
        check_output_file(out, "--out", "run.nc", inputs={"the input config file": source})
        check_plot(plot, PLOT_SUFFIXES, inputs={"the input config file": source})
        check_distinct({"--out": out, "--plot": plot})
        sim, wall = run_config(cfg)
        files = write_outputs(sim, out, plot, shown_units, grade)
    result = dict(sim.summary())
    final_grade = result.get("final", {}).get("grade_G_mm_s", float("nan"))
    for key, value in (("name", cfg.name), ("config", cfg.source), ("wall_time_s", wall),
                       ("grade_limit_mm_s", grade),
                       ("meets_grade_limit", bool(final_grade <= grade)),
                       ("files", files)):
        result.setdefault(key, value)
    ok = sim.status == "ok"
    if json_:
        print_json(result)
    else:
        typer.echo(f"{cfg.name}: status {sim.status} ({wall:.1f} s wall)")
        if ok and sim.note:                 # e.g. a liquid that stayed a pool
            typer.echo(f"  note: {sim.note}")
        typer.echo(f"  {'target grade':<32} {grade_text(grade)}")
        for key, value in result.items():
            if key not in ("name", "config", "status", "files", "wall_time_s", "message",
                           "grade_limit_mm_s"):
                echo_tree(key, value, 1, shown_units, grade)
        for kind, path in files.items():
            typer.echo(f"wrote {kind}: {path}")
        if not ok:
            kept = ", ".join(f"{o} {str(p)!r}" for o, p in (("--out", out), ("--plot", plot)) if p)
            typer.echo(f"simulation {sim.status}: {sim.message}" + (
                f"; {kept} not written (any previous file is unchanged)" if kept else ""), err=True)
    if not ok:
        raise typer.Exit(1)
