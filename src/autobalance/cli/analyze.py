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
from .common import (JsonOpt, PlotOpt, SetOpt, SourceArg, check_plot, echo_fields, fail, guard,
                     load_machine, print_json)
from .response import AnglesOpt, SpeedOpt, analyze_response, ball_angles, speed_at

app = typer.Typer(name="analyze", no_args_is_help=True, add_completion=False,
                  pretty_exceptions_enable=False,
                  help="Seed-000 analysis: harmonic response, vibratory forces, equilibria and "
                       "stability, error bounds, tolerance design, kinetic-static model, studies.")
app.command("response")(analyze_response)


def _save(fig, path) -> Optional[str]:
    """Save a figure to a path the command checked with :func:`check_plot` before computing."""
    if path is None:
        return None
    fig.savefig(path, dpi=110)
    return str(path)


@app.command()
def forces(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None, angles: AnglesOpt = None,
           plot: PlotOpt = None,
           damping_plot: Annotated[Optional[str], typer.Option(
               "--damping-plot", metavar="FILE.png",
               help="Write 000 Fig. 7: the one-ball force for suspension damping x0.5/1/2, above "
                    "both and between the natural frequencies.")] = None,
           json_: JsonOpt = False) -> None:
    """Vibratory forces F_i on the balls and dF/dalpha (000 eq 8-12, 40-43); --plot: Fig. 6;
    --damping-plot: Fig. 7.\f

    Parameters
    ----------
    source, set_, speed, angles, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`); forces in [N], the Jacobian in [N/rad].
    plot, damping_plot : str
        PNG files for 000 Fig. 6 and Fig. 7.
    """
    with guard():
        check_plot(plot)
        check_plot(damping_plot, what="--damping-plot")
        cfg = load_machine(source, set_)
        from ..physics.vibratory import force_jacobian, vibratory_components

        w = speed_at(cfg, speed)
        a = ball_angles(cfg, angles)
        comp = vibratory_components(cfg.system, w, a)
        out = {"name": cfg.name, "speed_rad_s": w, "ball_angles_rad": a,
               **{f"{k}_n": v for k, v in comp.items()},
               "jacobian_n_per_rad": force_jacobian(cfg.system, w, a)}
        if plot is not None or damping_plot is not None:
            from .washer_figures import plot_vibratory_force, plot_vibratory_force_damping

            wx, wy = cfg.system.natural_frequencies
            speeds = [w, 0.5 * (wx + wy)]       # this speed and between the natural frequencies
            if plot is not None:
                out["plot"] = _save(plot_vibratory_force(cfg.system, speeds), plot)
            if damping_plot is not None:
                out["damping_plot"] = _save(plot_vibratory_force_damping(cfg.system, speeds),
                                            damping_plot)
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
               full: Annotated[bool, typer.Option("--full", help="Also the linearised full model "
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
        cfg = load_machine(source, set_)
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
    for a rolling resistance ``fr`` = f/r [-]."""
    import dataclasses

    from ..physics import error_bounds as eb

    s = cfg.system
    b = s.balancer
    e = s.rotor.unbalance / s.rotor.mass
    ideal = dataclasses.replace(s, balancer=dataclasses.replace(b, eccentricity=0.0))
    db = eb.rolling_deadband(ideal, w, fr)
    ecc = eb.eccentricity_equilibrium(s, w)
    sus = s.suspension
    return {
        "name": cfg.name, "speed_rad_s": w, "f_r": fr,
        "rolling_single_ball_rad": eb.rolling_deadband_single(s, w, fr),
        "rolling_eq32_rad": eb.symmetric_rolling_deviation(b.race_radius, e, fr),
        "rolling_max_deviation_rad": db["max_deviation_rad"],
        "rolling_max_residual_unbalance_kg_m": db["max_residual_unbalance_kg_m"],
        "eccentricity_deviation_rad": ecc["deviation_rad"],
        "eccentricity_residual_unbalance_kg_m": ecc["residual_unbalance_kg_m"],
        "eccentricity_eq45_single_rad": eb.eccentricity_deviation_single(
            e, b.eccentricity, b.eccentricity_angle),
        "friction_eq49_rad": eb.suspension_friction_deviation(
            sus.dry_friction_force, sus.dry_friction_angle, s.rotor.unbalance, w),
        "ball_frequency_eq54_rad_s": eb.ball_natural_frequency_single(s, w),
        "ball_frequency_eq55_rad_s": eb.ball_natural_frequency_approx(w, e, b.race_radius),
        "ball_frequencies_rad_s": eb.ball_natural_frequencies(ideal, w, db["alpha_eq_rad"]),
    }


@app.command()
def bounds(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
           f_r: Annotated[Optional[float], typer.Option("--f-r", help="f/r (default: the preset's "
                                                        "rolling_resistance).")] = None,
           plot: PlotOpt = None, json_: JsonOpt = False) -> None:
    """Position-error bounds: rolling resistance, eccentricity, dry friction, ball frequency.\f

    Parameters
    ----------
    source, set_, speed, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    f_r : float
        Rolling-resistance coefficient f/r [-] in [0, 1]; default the preset's.
    plot : str
        PNG file: the rolling deviation against speed.
    """
    with guard():
        check_plot(plot)
        cfg = load_machine(source, set_)
        import numpy as np

        w = speed_at(cfg, speed)
        fr = cfg.system.balancer.rolling_resistance[0] if f_r is None else f_r
        if not (math.isfinite(fr) and 0 <= fr <= 1):
            raise ConfigError(f"--f-r = {f_r!r}: must be within [0, 1]: the rolling-resistance "
                              "coefficient f/r [-] (steel balls typically 0.001-0.01)")
        out = _error_bounds(cfg, w, fr)
        if plot is not None:
            from .washer_figures import plot_rolling_deviation

            out["plot"] = _save(plot_rolling_deviation(cfg.system, np.linspace(1.0, 2 * w, 400)),
                                plot)
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name} at {w:.4g} rad/s, f/r = {fr:g}")
    echo_fields(out, skip=("name",))


@app.command()
def tolerance(source: SourceArg, set_: SetOpt = None, speed: SpeedOpt = None,
              fraction: Annotated[float, typer.Option("--fraction", help="Required residual "
                                                      "unbalance / Me (000: 0.1).")] = 0.1,
              json_: JsonOpt = False) -> None:
    """Tolerance design (000 eq 56-66) and the residual predicted for the preset's tolerances.\f

    Parameters
    ----------
    source, set_, speed, json_
        The options of every analysis (:mod:`autobalance.cli.analyze`).
    fraction : float
        Required residual unbalance as a fraction of M e [-].
    """
    with guard():
        cfg = load_machine(source, set_)
        from ..physics.tolerance import design_tolerances, predict_residual

        s, w = cfg.system, speed_at(cfg, speed)
        d = design_tolerances(s.rotor.unbalance, s.rotor.mass, s.balancer.race_radius, w,
                              residual_fraction=fraction,
                              friction_angle=s.suspension.dry_friction_angle)
        p = predict_residual(s, w)
        out = {"name": cfg.name, "speed_rad_s": w, "design": d, "predicted": p}
    if json_:
        print_json(out)
        return
    typer.echo(f"{cfg.name}: rho_max = {d['rho_max_m'] * 1e6:.3g} um, f/r max = {d['f_r_max']:.3g}, "
               f"F max = {d['friction_force_max_n']:.3g} N; predicted RMe (worst) = "
               f"{p['rme_worst'] * 100:.1f} %")


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
        check_plot(plot)
        cfg = load_machine(source, set_)
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
