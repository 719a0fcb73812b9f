"""``autobalance analyze ...``: the seed-000 washer analysis on the command line.

Subcommands: response, forces, equilibria, bounds, tolerance, kinetic-static, washer-study
(004's immobility is ``autobalance study immobility``, for any machine). Every one takes
``--json`` (one JSON object, SI, unit-suffixed keys) and, where useful, ``--plot FILE.png``.
Input errors print one line ``error: ...`` on stderr and exit with code 2.

The options of every analysis of a machine: ``source`` (``PRESET|CONFIG``) and ``set_``
(``--set PATH=VALUE``) as in :mod:`autobalance.cli.common`; ``speed`` (``--speed``) the spin
speed [rad/s] (a bare number, or with units: ``'1000 rpm'``), default the configuration's
nominal speed; ``angles`` (``--angles``) one angle per ball [rad] (bare, or ``'120 deg,-120
deg'``), default the initial ones; ``json_`` (``--json``) one JSON object instead of text.
"""
from __future__ import annotations

import math
from typing import Annotated, Optional

import typer

from ..config import ConfigError, parse_quantity
from .common import (JsonOpt, PlotOpt, SetOpt, SourceArg, check_distinct, check_plot, echo_fields,
                     fail, guard, load_machine, print_json)
from .response import AnglesOpt, SpeedOpt, analyze_response, ball_angles, speed_at

app = typer.Typer(name="analyze", no_args_is_help=True, add_completion=False,
                  rich_markup_mode=None,     # help as written: no rich markup or :emoji: codes
                  pretty_exceptions_enable=False,
                  help="Seed-000 analysis: harmonic response, vibratory forces, equilibria and "
                       "stability, error bounds, tolerance design, kinetic-static model, studies.")
app.command("response")(analyze_response)


def _save(fig, path, what: str = "--plot") -> Optional[str]:
    """Save a figure, atomically (:func:`autobalance.atomic.save_figure`), to a path the command
    checked with :func:`check_plot` before computing; ``what`` names the option in an error."""
    from ..atomic import save_figure

    if path is None:
        return None
    save_figure(fig, path, what, dpi=110)
    return str(path)


@app.command()
def forces(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None, angles: AnglesOpt = None,
           plot: PlotOpt = None,
           damping_plot: Annotated[Optional[str], typer.Option(
               "--damping-plot", metavar="FILE.png",
               help="Write 000 Fig. 7: the one-ball force for suspension damping x0.5/1/2, above "
                    "both and between the natural frequencies.")] = None,
           json_: JsonOpt = False) -> None:
    """Vibratory forces F_i on the balls and dF/dalpha (000 eq 8-12, 40-43); --plot: each ball's
    force against its angle with its rest band (this balancer); --damping-plot: Fig. 7.\f

    Parameters
    ----------
    source, set_, speed, angles, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`); forces in [N], the Jacobian in [N/rad].
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
        from ..physics.vibratory import force_jacobian, vibratory_components

        w = speed_at(cfg, speed)
        a = ball_angles(cfg, angles)
        comp = vibratory_components(cfg.system, w, a)
        out = {"name": cfg.name, "speed_rad_s": w, "ball_angles_rad": a,
               **{f"{k}_n": v for k, v in comp.items()},
               "jacobian_n_per_rad": force_jacobian(cfg.system, w, a)}
        if plot is not None or damping_plot is not None:
            from .washer_figures import plot_ball_forces, plot_vibratory_force_damping

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
    typer.echo(f"{cfg.name} at {w:.4g} rad/s: F = {list(map(float, comp['F']))} N")


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
               json_: JsonOpt = False) -> None:
    """All ball equilibria and their stability (000 eq 12, linearised KS and full model):
    isolated ones, and for 3 or more balls the continuous balanced families as families.\f

    With N >= 3 balls the balanced positions form a family of dimension N - 2; its neutral
    directions are not counted as instability (docs/speed-map.md).

    Parameters
    ----------
    full : bool
        Also the linearised full model (for a family at each sample without ball overlap).
    source, set_, speed, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    """
    with guard():
        cfg = load_machine(source, set_, balls="needed")
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
    typer.echo(f"{cfg.name} at {w:.4g} rad/s ({out['regime']}): {len(rows)} isolated "
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
                f"ball overlap), residual {d['residual_unbalance_min_kg_m']:.4g}-"
                f"{d['residual_unbalance_max_kg_m']:.4g} kg*m; ks_stable at {ks}/{n_r}")
        if "full_stable" in d:
            fs = sum(bool(x) for x in d["full_stable"])
            text += f", full_stable at {fs}/{n_r} ({d['full_method']}, neutral directions removed)"
        typer.echo(text)
        a0 = next((a for a, o in zip(d["alpha_deg"], d["overlap"]) if not o), d["alpha_deg"][0])
        typer.echo(f"    e.g. alpha = {[round(v, 2) for v in a0]} deg")


def _error_bounds(cfg, w: float, fr: float) -> dict:
    """The position-error bounds of :func:`bounds` (000 eq 32, 45, 49, 54-55) at ``w`` [rad/s]
    for a rolling resistance ``fr`` = f/r [-] of every ball, and the true worst case of the
    residual unbalance of the balls at rest (:func:`autobalance.physics.worst_case.residual_bound`).
    On a family of balanced states (N >= 3) the deviations are those across the family and
    its neutral directions have frequency 0."""
    import dataclasses

    from ..physics import error_bounds as eb
    from ..physics.iso1940 import grade_class, grade_value
    from ..physics.worst_case import residual_bound

    s = cfg.system
    b = s.balancer
    e = s.rotor.unbalance / s.rotor.mass
    ideal = dataclasses.replace(s, balancer=dataclasses.replace(b, eccentricity=0.0))
    db = eb.rolling_deadband(ideal, w, fr)
    ecc = eb.eccentricity_equilibrium(s, w)
    sus = s.suspension
    wb = residual_bound(s, w, rolling_resistance=fr)
    g = float(grade_value(wb["worst_residual_kg_m"], s.total_mass, cfg.spin.nominal_speed))
    return {
        "name": cfg.name, "speed_rad_s": w, "f_r": fr, "n_balls": b.n_balls,
        "rolling_single_ball_rad": eb.rolling_deadband_single(s, w, fr),
        "rolling_eq32_rad": eb.symmetric_rolling_deviation(b.race_radius, e, fr),
        "rolling_max_deviation_rad": db["max_deviation_rad"],
        "rolling_max_residual_unbalance_kg_m": db["max_residual_unbalance_kg_m"],
        "neutral_directions": db["neutral_directions"],
        "eccentricity_deviation_rad": ecc["deviation_rad"],
        "eccentricity_residual_unbalance_kg_m": ecc["residual_unbalance_kg_m"],
        "eccentricity_eq45_single_rad": eb.eccentricity_deviation_single(
            e, b.eccentricity, b.eccentricity_angle),
        "friction_eq49_rad": eb.suspension_friction_deviation(
            sus.dry_friction_force, sus.dry_friction_angle, s.rotor.unbalance, w),
        "ball_frequency_eq54_rad_s": eb.ball_natural_frequency_single(s, w),
        "ball_frequency_eq55_rad_s": eb.ball_natural_frequency_approx(w, e, b.race_radius),
        "ball_frequencies_rad_s": eb.ball_natural_frequencies(ideal, w, db["alpha_eq_rad"]),
        "worst_residual_kg_m": wb["worst_residual_kg_m"], "worst_grade_G_mm_s": g,
        "worst_grade_class_G_mm_s": float(grade_class(g)),
        "worst_rolling_kg_m": wb["rolling_kg_m"], "worst_eccentricity_kg_m": wb["eccentricity_kg_m"],
        "worst_friction_kg_m": wb["friction_kg_m"], "worst_separated": wb["separated"],
        "capacity_kg_m": wb["capacity_kg_m"],
    }


@app.command()
def bounds(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
           f_r: Annotated[Optional[float], typer.Option("--f-r", help="f/r of every ball "
                                                        "(default: the machine's own).")] = None,
           plot: PlotOpt = None, json_: JsonOpt = False) -> None:
    """Position-error bounds (rolling resistance, eccentricity, dry friction, ball frequencies)
    and the true worst-case residual of the balls at rest, for any number of balls.\f

    Parameters
    ----------
    source, set_, speed, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    f_r : float
        Rolling-resistance coefficient f/r [-] in [0, 1] of every ball; default the machine's.
    plot : str
        PNG file: the worst-case residual of the machine's balancer against speed, by cause.
    """
    with guard():
        check_plot(plot, inputs={"the input config file": source})
        cfg = load_machine(source, set_, balls="needed")
        import numpy as np

        w = speed_at(cfg, speed)
        fr = float(cfg.system.balancer.stiction[0]) if f_r is None else f_r
        if not (math.isfinite(fr) and 0 <= fr <= 1):
            raise ConfigError(f"--f-r = {f_r!r}: must be within [0, 1]: the rolling-resistance "
                              "coefficient f/r [-] (steel balls typically 0.001-0.01)")
        out = _error_bounds(cfg, w, fr)
        if plot is not None:
            from ..physics.equilibria import balancing_onset_speed
            from .washer_figures import plot_residual_bound

            lo = 1.01 * balancing_onset_speed(cfg.system)
            speeds = np.geomspace(lo, max(2 * w, 1.5 * lo), 60)
            out["plot"] = _save(plot_residual_bound(cfg.system, speeds, fr), plot)
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name} at {w:.4g} rad/s, f/r = {fr:g}, {out['n_balls']} balls")
    echo_fields(out, skip=("name", "speed_rad_s", "f_r", "n_balls"))


def _tolerance_text(out: dict) -> list:
    """Lines of the text output of :func:`tolerance`."""
    from ..physics.iso1940 import grade_class

    G = out["target_grade_G_mm_s"]
    lines = [f"{out['name']} at {out['speed_rad_s']:.4g} rad/s ({out['speed_basis']}); target "
             f"G{G:g} (ISO class G{grade_class(G):g}): residual <= "
             f"{out['target_unbalance_kg_m']:.4g} kg*m"]
    if not out["feasible"]:
        lines.append(f"  not possible: {out['reason']}")
    else:
        lines += [f"  allowed (true worst case of the balanced region, each cause within its share, "
                  f"together within {100 * (1 - out['split'].get('other', 0.0)):.0f} %):",
                  f"    ring eccentricity      <= {out['max_eccentricity_m'] * 1e6:.4g} um",
                  f"    rolling resistance f/r <= {out['max_rolling_resistance']:.4g}",
                  f"    suspension friction F  <= {out['max_suspension_friction_N']:.4g} N per damper"]
    own = out["own_rolling_resistance"]
    fr = ", ".join(f"{v:g}" for v in sorted(set(own)))
    worst, Gw = out["worst_residual_kg_m"], out["worst_grade_G_mm_s"]
    rme = out["rme_worst"]
    rme_txt = (f"RMe {100 * rme:.1f} %" if rme >= 0 else
               f"{-100 * rme:.0f} % more than the rotor's own unbalance: balls at rest can add to it")
    lines += [f"  this machine (f/r = {fr}, rho = {out['own_eccentricity_m'] * 1e6:.4g} um, "
              f"F = {out['own_suspension_friction_N']:.4g} N):",
              f"    worst case (true bound, balanced region) {worst:.4g} kg*m = G{Gw:.3g} (class "
              f"G{out['worst_grade_class_G_mm_s']:g}); {rme_txt}",
              f"    expected (000 credits)  {out['expected_residual_kg_m']:.4g} kg*m = "
              f"G{out['expected_grade_G_mm_s']:.3g}",
              f"    meets G{G:g}: {'yes' if out['meets_target'] else 'no'}"]
    if "plateau_worst_residual_kg_m" in out:
        lines.append(f"    at the TSR plateau {out['plateau_speed_rad_s']:.4g} rad/s: worst "
                     f"{out['plateau_worst_residual_kg_m']:.4g} kg*m = G{out['plateau_worst_grade_G_mm_s']:.3g}")
    col = [v for v in out.get("collinear_residuals_kg_m", []) if v > worst]
    if col:
        lines.append("    balls stopped at a collinear equilibrium instead (outside the balanced region) "
                     "leave " + ", ".join(f"{v:.3g}" for v in col) + " kg*m")
    lines += [f"  note: {w}" for w in out["warnings"] if w != out.get("reason")]
    return lines


@app.command()
def tolerance(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
              grade: Annotated[float, typer.Option("--grade", help="Target ISO 1940 grade G "
                                                   "[mm/s] (default 16).")] = 16.0,
              fraction: Annotated[Optional[float], typer.Option(
                  "--residual-fraction", help="Also the 000 paper's method (one ball, mR = Me): required "
                                     "residual / Me, e.g. 0.1.")] = None,
              json_: JsonOpt = False) -> None:
    """Tolerances for a target grade (000 eq 56-66 for any balancer, on the true worst-case
    bound) and the worst case of the machine's own tolerances; --residual-fraction: the 000
    method.\f

    Parameters
    ----------
    source, set_, speed, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    grade : float
        Target grade G [mm/s], > 0.
    fraction : float
        Required residual unbalance as a fraction of M e [-] for the 000 paper's one-ball
        method (:func:`autobalance.physics.tolerance.design_tolerances`), in (0, 1].
    """
    with guard():
        cfg = load_machine(source, set_, balls="needed")
        from ..physics.tolerance import design_tolerances
        from ..studies._tolerances import compute_tolerances

        if not (math.isfinite(grade) and grade > 0):
            raise ConfigError(f"--grade = {grade!r}: must be a grade G > 0 [mm/s], e.g. 16 (ISO 1940 G16)")
        if fraction is not None and not (math.isfinite(fraction) and 0 < fraction <= 1):
            raise ConfigError(f"--residual-fraction = {fraction!r}: must be within (0, 1]: the required "
                              "residual / Me of the 000 method, e.g. 0.1")
        s = cfg.system
        w = speed_at(cfg, speed) if speed is not None else None
        out = compute_tolerances(cfg, grade=grade, speed=w)
        out["design"] = {k: out[k] for k in ("max_eccentricity_m", "max_rolling_resistance",
                                             "max_suspension_friction_N", "budget_kg_m")}
        if fraction is not None:
            out["paper_000"] = design_tolerances(s.rotor.unbalance, s.rotor.mass, s.balancer.race_radius,
                                                 out["speed_rad_s"], residual_fraction=fraction,
                                                 friction_angle=s.suspension.dry_friction_angle)
    if json_:
        print_json(out)
        return
    for line in _tolerance_text(out):
        typer.echo(line)
    if fraction is not None:
        d = out["paper_000"]
        typer.echo(f"  000 method (one ball, mR = Me, residual <= {fraction:g} Me): rho_max = "
                   f"{d['rho_max_m'] * 1e6:.3g} um, f/r max = {d['f_r_max']:.3g}, "
                   f"F max = {d['friction_force_max_n']:.3g} N")


@app.command("kinetic-static")
def kinetic_static(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
                   angles: AnglesOpt = None,
                   duration: Annotated[str, typer.Option("--duration", help="Length, e.g. '6 s'.")] = "6 s",
                   plot: PlotOpt = None, json_: JsonOpt = False) -> None:
    """Kinetic-static model (000 eq 13) vs the full model (Fig. 9 differences).\f

    Parameters
    ----------
    source, set_, speed, angles, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    duration : str
        Simulated time [s or with units], in (0, 600] s.
    plot : str
        PNG file: the differences against time.
    """
    with guard():
        check_plot(plot, inputs={"the input config file": source})
        cfg = load_machine(source, set_, balls="needed")
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
    typer.echo(f"{cfg.name}: max |D_x| = {out['max_D_x_m'] * 1e6:.3g} um, max |D_y| = "
               f"{out['max_D_y_m'] * 1e6:.3g} um, max |D_alpha| = {out['max_D_alpha_rad']:.3g} rad; "
               f"last second: {out['final_D_alpha_rad']:.2g} rad")


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
