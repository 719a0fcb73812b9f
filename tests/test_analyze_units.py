"""``autobalance analyze forces|equilibria|bounds|kinetic-static``: the text in the units the
configuration writes (washer_000 writes its speeds in rpm, its unbalance in kg*m and its race
radius in m) or those ``--units`` chooses; the JSON object in SI with the same keys whatever
``--units`` says. ``bounds`` shows :func:`autobalance.physics.error_bounds.error_bound_summary`.
"""
from __future__ import annotations

import json

import pytest
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.config import load_config
from autobalance.config.display import number_text
from autobalance.jsonable import to_jsonable
from autobalance.models import ParameterError
from autobalance.physics.error_bounds import error_bound_summary

runner = CliRunner()
KS = ["--duration", "0.2 s"]          # a short kinetic-static comparison

#: command -> its arguments after ``analyze`` and the keys of its JSON object.
CASES = {
    "forces": (["forces", "washer_000"],
               {"name", "speed_rad_s", "ball_angles_rad", "F_n", "F_x_n", "F_y_n", "F_rho_n",
                "F_x0_n", "F_xball_n", "F_xrho_n", "F_y0_n", "F_yball_n", "F_yrho_n",
                "jacobian_n_per_rad"}),
    "equilibria": (["equilibria", "washer_000"],
                   {"name", "speed_rad_s", "regime", "balancing_onset_speed_rad_s",
                    "balanced_unbalance_kg_m", "equilibria", "families"}),
    "bounds": (["bounds", "washer_000", "--f-r", "1e-3"],
               {"name", "speed_rad_s", "f_r", "n_balls", "rolling_single_ball_rad",
                "rolling_eq32_rad", "rolling_max_deviation_rad",
                "rolling_max_residual_unbalance_kg_m", "neutral_directions",
                "eccentricity_deviation_rad", "eccentricity_residual_unbalance_kg_m",
                "eccentricity_eq45_single_rad", "friction_eq49_rad", "ball_frequency_eq54_rad_s",
                "ball_frequency_eq55_rad_s", "ball_frequencies_rad_s", "worst_residual_kg_m",
                "worst_grade_G_mm_s", "worst_grade_class_G_mm_s", "worst_rolling_kg_m",
                "worst_eccentricity_kg_m", "worst_friction_kg_m", "worst_separated",
                "capacity_kg_m"}),
    "kinetic-static": (["kinetic-static", "washer_000", *KS],
                       {"name", "speed_rad_s", "duration_s", "max_D_x_m", "max_D_y_m",
                        "max_D_alpha_rad", "final_D_x_m", "final_D_y_m", "final_D_alpha_rad",
                        "ks_final_alpha_rad", "full_final_alpha_rad"}),
}
COMMANDS = [pytest.param(c, marks=pytest.mark.slow) if c == "kinetic-static" else c
            for c in CASES]


def analyze(*args) -> str:
    r = runner.invoke(app, ["analyze", *map(str, args)])
    assert r.exit_code == 0, r.output
    return r.stdout


@pytest.mark.parametrize("cmd", COMMANDS)
def test_text_speed_in_the_written_unit_and_in_si(cmd):
    args, _ = CASES[cmd]
    text = analyze(*args)
    assert "washer_000 at 1000 rpm" in text and "rad/s" not in text, text
    text = analyze(*args, "--units", "si")
    assert "washer_000 at 104.7 rad/s" in text and "rpm" not in text, text


@pytest.mark.parametrize("cmd", COMMANDS)
def test_json_is_si_with_the_same_keys_whatever_units_says(cmd):
    args, keys = CASES[cmd]
    out = json.loads(analyze(*args, "--json"))
    assert set(out) == keys
    assert out["speed_rad_s"] == pytest.approx(1000 * 2 * 3.141592653589793 / 60, rel=1e-12)
    for units in ("si", "speed=Hz,unbalance=g*mm,length=um,force=kN"):
        assert json.loads(analyze(*args, "--units", units, "--json")) == out


def test_forces_text_in_the_chosen_units():
    si = json.loads(analyze("forces", "washer_000", "--json"))["F_n"]
    text = analyze("forces", "washer_000", "--units", "force=mN,speed=Hz")
    assert (f"washer_000 at 16.67 Hz: F = [{number_text(1e3 * si[0])}, "
            f"{number_text(1e3 * si[1])}] mN") in text, text


def test_equilibria_family_residual_in_the_written_unbalance_unit():
    args = ["equilibria", "washer_000", "--set", "balancer.n_balls=3",
            "--set", "initial.ball_angles=[0, 2, 4]", "--set", "rotor.unbalance=25 g*m"]
    text = analyze(*args)
    assert "family of dimension 1" in text and " g*m to " in text and "kg*m" not in text, text


def test_bounds_text_unbalances_in_the_written_or_chosen_unit():
    args = ["bounds", "washer_000", "--f-r", "1e-3", "--set", "balancer.eccentricity=0.1 mm"]
    out = json.loads(analyze(*args, "--json"))
    text = analyze(*args, "--set", "rotor.unbalance=25 g*m")
    assert "at 1000 rpm, f/r = 0.001, 2 balls" in text
    assert "kg*m" not in text and ("worst case at rest (true bound): "
                                   f"{number_text(1e3 * out['worst_residual_kg_m'])} g*m") in text
    text = analyze(*args, "--units", "unbalance=g*mm,speed=Hz")
    assert f"capacity sum m_i R: {number_text(1e6 * out['capacity_kg_m'])} g*mm" in text, text
    hz = out["ball_frequency_eq55_rad_s"] / (2 * 3.141592653589793)
    assert f"(eq 55) {number_text(hz)} Hz" in text, text


def test_bounds_json_is_the_library_summary():
    sets = ["balancer.eccentricity=0.1 mm", "suspension.dry_friction_force=5 N"]
    out = json.loads(analyze("bounds", "washer_000", "--f-r", "1e-3", "--speed", "800 rpm",
                             *[x for s in sets for x in ("--set", s)], "--json"))
    cfg = load_config("washer_000", sets)
    lib = error_bound_summary(cfg.system, out["speed_rad_s"], 1e-3, cfg.spin.nominal_speed)
    assert out == json.loads(json.dumps(to_jsonable({"name": "washer_000", **lib})))


@pytest.mark.parametrize("kw", [{"rolling_resistance": -1e-3}, {"speed": 0.0},
                                {"nominal_speed": float("nan")}])
def test_error_bound_summary_refuses_bad_input(kw):
    cfg = load_config("washer_000")
    args = {"speed": 100.0, "rolling_resistance": 1e-3, "nominal_speed": 104.7, **kw}
    with pytest.raises(ParameterError) as ei:
        error_bound_summary(cfg.system, **args)
    assert "\n" not in str(ei.value)


@pytest.mark.slow
def test_kinetic_static_lengths_and_time_in_the_chosen_units():
    out = json.loads(analyze("kinetic-static", "washer_000", *KS, "--json"))
    text = analyze("kinetic-static", "washer_000", *KS, "--units", "length=um,time=ms")
    assert f"for 200 ms: max |D_x| = {number_text(1e6 * out['max_D_x_m'], 3)} um" in text, text
