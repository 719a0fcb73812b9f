"""``autobalance presets``, ``show`` and ``demo``: the machines shipped with the package."""
from __future__ import annotations

import json
import math
from pathlib import Path
from typing import Annotated, Any, Optional

import typer

from ..atomic import write_atomic
from ..config import describe, list_presets, load_config
from ..config.display import DISPLAY_KINDS, display_units
from ..config.schema import PROFILE_KINDS, SECTIONS
from ..jsonable import to_jsonable
from .common import JsonOpt, ProfileOpt, SetOpt, SourceArg, guard, load_machine, print_json
from .simulate import fmt_value, run_config, write_outputs


def presets(json_: JsonOpt = False) -> None:
    """List the presets shipped with the package.\f

    Parameters
    ----------
    json_ : bool
        Print ``{"presets": [...]}`` (name, description) instead of a table.
    """
    with guard():
        items = list_presets()
    if json_:
        print_json({"presets": items})
        return
    width = max((len(p["name"]) for p in items), default=4)
    for p in items:
        typer.echo(f"{p['name']:<{width}}  {p['description']}")


#: Derived quantities of ``show`` -> their display kind (also shown in the config's units).
DERIVED_KINDS = {"total_mass_kg": "mass", "eccentricity_m": "length",
                 "ball_capacity_kg_m": "unbalance", "natural_frequencies_rad_s": "speed"}


def _raw_key(dkey: str, raw_section: dict, fields=()) -> Optional[str]:
    """The key of the config file that a described key (``kx_N_m``) comes from (``kx``): the
    longest of the section's ``fields`` and file keys that it starts with, if the file has it
    (``unbalance_schedule_s_kg_m`` is not ``unbalance``)."""
    best = None
    for k in (*fields, *raw_section):
        if (dkey == k or dkey.startswith(k + "_")) and (best is None or len(k) > len(best)):
            best = k
    return best if best in raw_section else None


def show(source: SourceArg, set_: SetOpt = None, profile: ProfileOpt = None,
         json_: JsonOpt = False) -> None:
    """Show the full parameter set in SI with the source of each value, and the machine's
    sanity warnings (:func:`autobalance.physics.sanity.config_warnings`).\f

    Parameters
    ----------
    source, set_, profile, json_
        The shared options (:mod:`autobalance.cli.common`); the JSON object is
        :func:`autobalance.config.describe` (its derived eccentricity that of the grades,
        e = U/M_t), and ``warnings`` (a list of one-line strings).
    """
    from ..physics.sanity import config_warnings

    with guard():
        cfg = load_machine(source, set_, profile)
        d = describe(cfg)
        d["warnings"] = config_warnings(cfg)
    if json_:
        print_json(d)
        return
    typer.echo(f"{d['name']}: {d['description']}")
    typer.echo(f"source: {d['source']}")
    du = display_units(cfg)
    fields = {**{k: tuple(v) for k, v in SECTIONS.items()},
              "profile": tuple(PROFILE_KINDS.get(cfg.profile_kind, ()))}
    for section in ("rotor", "suspension", "balancer", "gravity", "liquid", "profile", "initial",
                    "options", "derived"):
        if section not in d:
            continue
        typer.echo(f"[{section}]")
        raw = cfg.raw.get(section, {}) if isinstance(cfg.raw.get(section), dict) else {}
        for key, value in d[section].items():
            if section == "derived" and key == "eccentricity_definition":
                continue                    # shown on the eccentricity's own line
            line = f"  {key:<30} {fmt_value(value)}"
            if section == "derived" and key in DERIVED_KINDS:
                vals = value if isinstance(value, (list, tuple)) else [value]
                shown = ", ".join(du.fmt(v, DERIVED_KINDS[key]) for v in vals)
                if du.unit(DERIVED_KINDS[key]) != DISPLAY_KINDS[DERIVED_KINDS[key]]:
                    line += f"   (= {shown})"        # in the units the config writes
            if section == "derived" and key == "eccentricity_m":
                line += f"   ({d['derived']['eccentricity_definition']})"
            rk = _raw_key(key, raw, fields.get(section, ()))
            if rk is not None:
                if isinstance(raw[rk], (str, list)) and str(raw[rk]) != str(value):
                    line += f"   (= {raw[rk]!s})" if isinstance(raw[rk], list) else \
                        f"   (= {raw[rk]})"
                src = d["sources"].get(f"{section}.{rk}")
                if src:
                    line += f"   # {src}"
            typer.echo(line)
    for w in d["warnings"]:
        typer.echo(f"warning: {w}")


def _num(v: Any, scale: float = 1.0) -> str:
    ok = isinstance(v, (int, float)) and not isinstance(v, bool) and math.isfinite(v)
    return f"{v * scale:.4g}" if ok else "-"


def _row(name: str, status: str, wall: Any, summary: dict) -> str:
    """One line of the demo table (G initial, G final [mm/s], max amplitude [mm])."""
    final = summary.get("final") if isinstance(summary.get("final"), dict) else {}
    return (f"{name:<20} {status:<10} {wall:>8.2f} {_num(summary.get('initial_grade_G_mm_s')):>10}"
            f" {_num(final.get('grade_G_mm_s')):>10} {_num(summary.get('max_amplitude_m'), 1e3):>12}")


def demo(out: Annotated[Path, typer.Option("--out-dir", metavar="DIR",
                                           help="Output directory.")] = Path("demo"),
         json_: JsonOpt = False) -> None:
    """Simulate every preset; write DIR/summary.json, DIR/<preset>.nc and DIR/<preset>.png.\f

    Parameters
    ----------
    out : Path
        Output directory (created).
    json_ : bool
        Print the summary of every run as one JSON object instead of a table.

    Exits with code 1 if a run's status is not ``"ok"`` (that preset's .nc and .png are not
    written). Each file is written atomically (:mod:`autobalance.atomic`).
    """
    results: dict[str, dict] = {}
    with guard():
        out.mkdir(parents=True, exist_ok=True)
        items = list_presets()
        if not json_:
            typer.echo(f"{'preset':<20} {'status':<10} {'wall [s]':>8} {'G0 [mm/s]':>10}"
                       f" {'G [mm/s]':>10} {'max amp [mm]':>12}")
        for p in items:
            cfg = load_config(p["name"])
            sim, wall = run_config(cfg)
            files = write_outputs(sim, out / f"{p['name']}.nc", out / f"{p['name']}.png",
                                  what=("--out-dir", "--out-dir"))
            summary = dict(sim.summary())
            summary.setdefault("status", sim.status)
            results[p["name"]] = {**summary, "wall_time_s": wall, "files": files}
            if not json_:
                typer.echo(_row(p["name"], sim.status, wall, summary))
        ok = all(r.get("status") == "ok" for r in results.values())
        report = {"status": "ok" if ok else "failed", "out": str(out), "presets": results}
        write_atomic(out / "summary.json", json.dumps(to_jsonable(report), indent=1,
                                                      allow_nan=False), "--out-dir")
    if json_:
        print_json(report)
    else:
        typer.echo(f"wrote {out / 'summary.json'}")
    if not ok:
        raise typer.Exit(1)
