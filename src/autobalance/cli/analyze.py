"""``autobalance analyze ...``: the seed-000 washer analysis on the command line.

Subcommands: forces, equilibria, bounds, kinetic-static, washer-study (the drum's response
at one speed is ``autobalance response --speed``, the tolerance design ``autobalance study
tolerances``, 004's immobility ``autobalance study immobility``, for any machine). Every one takes
``--json`` (one JSON object, SI, unit-suffixed keys) and, where useful, ``--plot FILE.png``.
Input errors print one line ``error: ...`` on stderr and exit with code 2.

The options of every analysis of a machine: ``source`` (``PRESET|CONFIG``) and ``set_``
(``--set PATH=VALUE``) as in :mod:`autobalance.cli.common`; ``speed`` (``--speed``) the spin
speed [rad/s] (a bare number, or with units: ``'1000 rpm'``), default the configuration's
nominal speed; ``angles`` (``--angles``) one angle per ball [rad] (bare, or ``'120 deg,-120
deg'``), default the initial ones; ``units`` (``--units``) the units of the text, default
those written in the configuration (:data:`autobalance.cli.common.UnitsOpt`); ``json_``
(``--json``) one JSON object instead of text (SI, whatever ``--units`` says).
"""
from __future__ import annotations

import math
from typing import Annotated, Optional

import typer

from ..config import ConfigError, parse_quantity
from ..config.display import display_units
from .common import (JsonOpt, PlotOpt, SetOpt, SourceArg, UnitsOpt, check_distinct, check_plot,
                     class_text, fail, guard, load_machine, print_json)
from .response import AnglesOpt, SpeedOpt, ball_angles, speed_at

app = typer.Typer(name="analyze", no_args_is_help=True, add_completion=False,
                  rich_markup_mode=None,     # help as written: no rich markup or :emoji: codes
                  pretty_exceptions_enable=False,
                  help="Seed-000 analysis: vibratory forces, equilibria and stability, error bounds, "
                       "kinetic-static model, the washer's studies.")


def _save(fig, path, what: str = "--plot") -> Optional[str]:
    """Save a figure, atomically (:func:`autobalance.atomic.save_figure`), to a path the command
    checked with :func:`check_plot` before computing; ``what`` names the option in an error."""
    from ..atomic import save_figure

    if path is None:
        return None
    save_figure(fig, path, what, dpi=110)
    return str(path)


def _values(du, values, kind: Optional[str] = None) -> str:
    """``"[v1, v2] unit"``: SI ``values`` in the display unit of ``kind`` (None: angles [rad])."""
    from ..config.display import number_text

    vals = [float(v) if kind is None else du.to(v, kind) for v in values]
    return f"[{', '.join(number_text(v) for v in vals)}] {'rad' if kind is None else du.unit(kind)}"


@app.command()
def forces(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None, angles: AnglesOpt = None,
           plot: PlotOpt = None,
           damping_plot: Annotated[Optional[str], typer.Option(
               "--damping-plot", metavar="FILE.png",
               help="Write 000 Fig. 7: the one-ball force for suspension damping x0.5/1/2, above "
                    "both and between the natural frequencies.")] = None,
           units: UnitsOpt = None, json_: JsonOpt = False) -> None:
    """Vibratory forces F_i on the balls and dF/dalpha (000 eq 8-12, 40-43); --plot: each ball's
    force against its angle with its rest band (this balancer); --damping-plot: Fig. 7.\f

    Parameters
    ----------
    source, set_, speed, angles, units, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`); forces in [N], the
        Jacobian in [N/rad] (JSON; the text in the display units).
    plot, damping_plot : str
        PNG files: the force on each of this balancer's balls against its own angle, the others
        at ``angles``, with the rest band +-f/r (000 eq 8, 21; Fig. 6 generalised); 000 Fig. 7.
    """
    with guard():
        config = {"the input config file": source}
        check_plot(plot, inputs=config)
        check_plot(damping_plot, what="--damping-plot", inputs=config)
        check_distinct({"--plot": plot, "--damping-plot": damping_plot})
        cfg = load_machine(source, set_, balls="needed")
        du = display_units(cfg, units)
        from ..physics.vibratory import force_jacobian, vibratory_components

        w = speed_at(cfg, speed)
        a = ball_angles(cfg, angles)
        comp = vibratory_components(cfg.system, w, a)
        out = {"name": cfg.name, "speed_rad_s": w, "ball_angles_rad": a,
               **{f"{k}_n": v for k, v in comp.items()},
               "jacobian_n_per_rad": force_jacobian(cfg.system, w, a)}
        if plot is not None or damping_plot is not None:
            from ..studies.washer_figures import plot_ball_forces, plot_vibratory_force_damping

            wx, wy = cfg.system.natural_frequencies
            speeds = [w, 0.5 * (wx + wy)]       # this speed and between the natural frequencies
            if plot is not None:
                out["plot"] = _save(plot_ball_forces(cfg.system, speeds, a), plot)
            if damping_plot is not None:
                out["damping_plot"] = _save(plot_vibratory_force_damping(cfg.system, speeds),
                                            damping_plot, "--damping-plot")
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name} at {du.fmt(w, 'speed')}: F = {_values(du, comp['F'], 'force')}")


def _full_verdict(system, w: float, alpha, family: bool) -> dict:
    """Linearised full model at one equilibrium (eigenvalues or Floquet), as CLI fields."""
    from ..studies.equilibria import full_stability

    f = full_stability(system, w, alpha, family=family)
    out = {"full_method": f["method"], "full_max_multiplier": f["max_modulus"],
           "full_stable": f["stable"]}
    if family:
        out.update(full_neutral_ok=f["neutral_ok"], full_neutral_kind=f["neutral_kind"],
                   full_neutral_distance=f["neutral_distance"],
                   full_neutral_sin_angle=f["neutral_sin_angle"])
    return out


@app.command()
def equilibria(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
               full: Annotated[bool, typer.Option("--full-model", help="Also the linearised full model "
                                                  "(eigenvalues in a steady rotor frame, else "
                                                  "Floquet multipliers by shooting).")] = False,
               units: UnitsOpt = None, json_: JsonOpt = False) -> None:
    """All ball equilibria and their stability (000 eq 12, linearised KS and full model):
    isolated ones, and for 3 or more balls the continuous balanced families as families.\f

    With N >= 3 balls the balanced positions form a family of dimension N - 2; its neutral
    directions are not counted as instability (docs/speed-map.md).

    Parameters
    ----------
    full : bool
        Also the linearised full model (for a family at each sample without ball overlap).
    source, set_, speed, units, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    """
    with guard():
        cfg = load_machine(source, set_, balls="needed")
        du = display_units(cfg, units)
        from ..physics.equilibria import balancing_onset_speed, find_equilibrium_set
        from ..physics.vibratory import speed_regime

        w = speed_at(cfg, speed)
        es = find_equilibrium_set(cfg.system, w)
        rows = []
        for e, bal in zip(es.isolated, es.balanced):
            d = e.as_dict()
            d["balanced"] = bal
            if full and not e.overlap:
                d.update(_full_verdict(cfg.system, w, e.alpha, False))
            rows.append(d)
        fams = []
        for f in es.families:
            d = f.as_dict()
            if full:
                v = [_full_verdict(cfg.system, w, p.alpha, True) if not p.overlap else None
                     for p in f.points]
                d["full_stable"] = [None if x is None else x["full_stable"] for x in v]
                d["full_max_multiplier"] = [None if x is None else x["full_max_multiplier"] for x in v]
                d["full_neutral_ok"] = [None if x is None else x["full_neutral_ok"] for x in v]
                d["full_neutral_kind"] = [None if x is None else x["full_neutral_kind"] for x in v]
                d["full_method"] = next((x["full_method"] for x in v if x), None)
            fams.append(d)
        out = {"name": cfg.name, "speed_rad_s": w, "regime": speed_regime(cfg.system, w),
               "balancing_onset_speed_rad_s": balancing_onset_speed(cfg.system),
               "balanced_unbalance_kg_m": abs(es.target_unbalance),
               "equilibria": rows, "families": fams}
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name} at {du.fmt(w, 'speed')} ({out['regime']}): {len(rows)} isolated "
               f"equilibri{'um' if len(rows) == 1 else 'a'}, {len(fams)} "
               f"famil{'y' if len(fams) == 1 else 'ies'} of balanced states")
    for d in rows:
        typer.echo(f"  alpha = {[round(v, 2) for v in d['alpha_deg']]} deg  static_stable = "
                   f"{d['static_stable']}  ks_stable = {d['ks_stable']}"
                   + (f"  full_stable = {d['full_stable']}" if "full_stable" in d else "")
                   + ("  (balanced)" if d["balanced"] else "")
                   + ("  (balls overlap)" if d["overlap"] else ""))
    for d in fams:
        reach = [not o for o in d["overlap"]]
        n_r = sum(reach)
        ks = sum(k and r for k, r in zip(d["ks_stable"], reach))
        text = (f"  family of dimension {d['dimension']}: {d['n_samples']} samples ({n_r} without "
                f"ball overlap), residual {du.fmt(d['residual_unbalance_min_kg_m'], 'unbalance')}"
                f" to {du.fmt(d['residual_unbalance_max_kg_m'], 'unbalance')}; ks_stable at "
                f"{ks}/{n_r}")
        if "full_stable" in d:
            fs = sum(bool(x) for x in d["full_stable"])
            text += f", full_stable at {fs}/{n_r} ({d['full_method']}, neutral directions removed)"
        typer.echo(text)
        a0 = next((a for a, o in zip(d["alpha_deg"], d["overlap"]) if not o), d["alpha_deg"][0])
        typer.echo(f"    e.g. alpha = {[round(v, 2) for v in a0]} deg")


def _bounds_text(out: dict, du) -> list:
    """Lines of the text output of :func:`bounds`: angles [rad], the rest in the display units."""
    def u(key):
        return du.fmt(out[key], "unbalance")

    family = out["neutral_directions"] > 0
    lines = [
        f"{out['name']} at {du.fmt(out['speed_rad_s'], 'speed')}, f/r = {out['f_r']:g}, "
        f"{out['n_balls']} balls",
        f"  rolling resistance: one ball (000 eq 24) {out['rolling_single_ball_rad']:.4g} rad, "
        f"two balls at +-120 deg (eq 32) {out['rolling_eq32_rad']:.4g} rad",
        f"    {out['n_balls']} balls (eq 27-31{', across the family' if family else ''}): "
        f"deviation <= {_values(du, out['rolling_max_deviation_rad'])}, residual <= "
        f"{u('rolling_max_residual_unbalance_kg_m')}"
        + (f", neutral directions: {out['neutral_directions']}" if family else ""),
        f"  race eccentricity (eq 46-47): deviation {_values(du, out['eccentricity_deviation_rad'])}, "
        f"residual {u('eccentricity_residual_unbalance_kg_m')}; one ball (eq 45) "
        f"{out['eccentricity_eq45_single_rad']:.4g} rad",
        f"  suspension dry friction (eq 49): deviation {out['friction_eq49_rad']:.4g} rad",
        f"  ball natural frequencies (eq 52): {_values(du, out['ball_frequencies_rad_s'], 'speed')}; "
        f"one ball (eq 54) {du.fmt(out['ball_frequency_eq54_rad_s'], 'speed')}, "
        f"(eq 55) {du.fmt(out['ball_frequency_eq55_rad_s'], 'speed')}"]
    if out["worst_separated"]:
        lines += [f"  worst case at rest (true bound): {u('worst_residual_kg_m')} = "
                  f"G{out['worst_grade_G_mm_s']:.3g} (class {class_text(out['worst_grade_G_mm_s'])}) = "
                  f"rolling {u('worst_rolling_kg_m')} + eccentricity {u('worst_eccentricity_kg_m')}"
                  f" + friction {u('worst_friction_kg_m')}"]
    else:
        lines += [f"  worst case at rest: no bound below the trivial {u('worst_residual_kg_m')} = "
                  f"G{out['worst_grade_G_mm_s']:.3g} (class {class_text(out['worst_grade_G_mm_s'])})"]
    lines.append(f"  capacity sum m_i R: {u('capacity_kg_m')}")
    return lines


@app.command()
def bounds(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
           f_r: Annotated[Optional[float], typer.Option("--f-r", help="f/r of every ball "
                                                        "(default: the machine's own).")] = None,
           plot: PlotOpt = None, units: UnitsOpt = None, json_: JsonOpt = False) -> None:
    """Position-error bounds (rolling resistance, eccentricity, dry friction, ball frequencies)
    and the true worst-case residual of the balls at rest, for any number of balls.\f

    The values are :func:`autobalance.physics.error_bounds.error_bound_summary`.

    Parameters
    ----------
    source, set_, speed, units, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    f_r : float
        Rolling-resistance coefficient f/r [-] in [0, 1] of every ball; default the machine's.
    plot : str
        PNG file: the worst-case residual of the machine's balancer against speed, by cause.
    """
    with guard():
        check_plot(plot, inputs={"the input config file": source})
        cfg = load_machine(source, set_, balls="needed")
        du = display_units(cfg, units)
        import numpy as np

        from ..physics.error_bounds import error_bound_summary

        w = speed_at(cfg, speed)
        fr = float(cfg.system.balancer.stiction[0]) if f_r is None else f_r
        if not (math.isfinite(fr) and 0 <= fr <= 1):
            raise ConfigError(f"--f-r = {f_r!r}: must be within [0, 1]: the rolling-resistance "
                              "coefficient f/r [-] (steel balls typically 0.001-0.01)")
        out = {"name": cfg.name,
               **error_bound_summary(cfg.system, w, fr, cfg.spin.nominal_speed)}
        if plot is not None:
            from ..physics.equilibria import balancing_onset_speed
            from ..studies.washer_figures import plot_residual_bound

            lo = 1.01 * balancing_onset_speed(cfg.system)
            speeds = np.geomspace(lo, max(2 * w, 1.5 * lo), 60)
            out["plot"] = _save(plot_residual_bound(cfg.system, speeds, fr), plot)
    if json_:
        print_json(out)
        return
    for line in _bounds_text(out, du):
        typer.echo(line)


@app.command("kinetic-static")
def kinetic_static(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
                   angles: AnglesOpt = None,
                   duration: Annotated[str, typer.Option("--duration", help="Length, e.g. '6 s'.")] = "6 s",
                   plot: PlotOpt = None, units: UnitsOpt = None, json_: JsonOpt = False) -> None:
    """Kinetic-static model (000 eq 13) vs the full model (Fig. 9 differences).\f

    Parameters
    ----------
    source, set_, speed, angles, units, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    duration : str
        Simulated time [s or with units], in (0, 600] s.
    plot : str
        PNG file: the differences against time.
    """
    with guard():
        check_plot(plot, inputs={"the input config file": source})
        cfg = load_machine(source, set_, balls="needed")
        du = display_units(cfg, units)
        from ..simulate.kinetic_static import compare_with_full

        w = speed_at(cfg, speed)
        dur = parse_quantity(duration, "time", "--duration")
        if not (math.isfinite(dur) and 0 < dur <= 600):
            raise ConfigError(f"--duration = {duration!r}: must be within (0, 600] s")
        c = compare_with_full(cfg.system, w, ball_angles(cfg, angles), dur)
        out = {"name": cfg.name, "speed_rad_s": w, "duration_s": dur,
               **{k: v for k, v in c.items() if k.startswith(("max_", "final_"))},
               "ks_final_alpha_rad": c["ks_alpha_rad"][-1], "full_final_alpha_rad": c["full_alpha_rad"][-1]}
        if plot is not None:
            from ..plotting.washer import plot_ks_comparison

            out["plot"] = _save(plot_ks_comparison(c), plot)
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name} at {du.fmt(w, 'speed')} for {du.fmt(dur, 'time')}: max |D_x| = "
               f"{du.fmt(out['max_D_x_m'], 'length', 3)}, max |D_y| = "
               f"{du.fmt(out['max_D_y_m'], 'length', 3)}, max |D_alpha| = "
               f"{out['max_D_alpha_rad']:.3g} rad; last second: {out['final_D_alpha_rad']:.2g} rad")


def _echo_rows(rows: list) -> None:
    """Print comparison rows: ``ok``/``MISS``, the quantity, published and computed values."""
    for r in rows:
        typer.echo(f"{'ok  ' if r['ok'] else 'MISS'} {r['quantity']}: published {r['published']}, "
                   f"ours {r['computed']} ({r['tolerance']})")


@app.command("washer-study")
def washer_study(which: Annotated[str, typer.Argument(help="fig13, fig16, fig18, table3, table4 or all")] = "all",
                 json_: JsonOpt = False) -> None:
    """Full simulations of 000 Fig. 13, 16, 18 and Tables 3-4 against the published numbers.\f

    Parameters
    ----------
    which : str
        One study (fig13, fig16, fig18, table3, table4) or all.
    json_ : bool
        Print the comparison rows as one JSON object instead of text.
    """
    names = ("fig13", "fig16", "fig18", "table3", "table4")
    if which != "all" and which not in names:
        fail(f"which = {which!r}: must be one of {', '.join(names)} or all")
    from ..papers.p000.washer import compare

    rows = compare(names if which == "all" else (which,))
    n_ok = sum(r["ok"] for r in rows)
    if json_:
        print_json({"study": "washer_000", "rows": rows, "ok": n_ok, "total": len(rows)})
        return
    _echo_rows(rows)
    typer.echo(f"{n_ok} of {len(rows)} within tolerance")
