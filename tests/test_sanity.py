"""Sanity warnings on a machine (physics/sanity.py, config/plausible.py): every warning fires on
the machine it is written for and stays silent on its near neighbour; none refuses the machine;
``show`` and the studies print them as ``warning:`` lines and list them under ``warnings`` in
JSON; no preset or example warns."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.config import list_presets, load_config
from autobalance.config.plausible import bare_number_warnings
from autobalance.physics.equilibria import balancing_onset_speed
from autobalance.physics.iso1940 import grade_value
from autobalance.physics.sanity import config_warnings, machine_warnings

ROOT = Path(__file__).resolve().parents[1]
CENTRIFUGE = str(ROOT / "examples" / "centrifuge.toml")
EXAMPLES = sorted(str(p) for p in (ROOT / "examples").glob("*.toml"))
runner = CliRunner()

#: The centrifuge with a balancer of 2 x 0.6 g on R = 10 mm (capacity 1.2 g*cm) against 2 g*cm.
SMALL_BALLS = ["rotor.unbalance=2 g*cm", "balancer.ball_mass=0.6 g",
               "balancer.race_radius=10 mm", "balancer.ball_radius=2 mm"]
ONE_BALL = ["balancer.n_balls=1", "initial.ball_angles=[0]"]


def _warnings(base, sets=()):
    return config_warnings(load_config(base, list(sets)))


def _only(found, word):
    hits = [w for w in found if word in w]
    assert len(hits) == 1, found
    return hits[0]


# -- 1. unbalance above the capacity -------------------------------------------------------------
def test_unbalance_above_the_ball_capacity():
    w = _only(_warnings(CENTRIFUGE, SMALL_BALLS), "capacity")
    assert "an unbalance of 2 g*cm against a ball capacity of 1.2 g*cm" in w
    cfg = load_config(CENTRIFUGE, SMALL_BALLS)
    left = grade_value(0.8e-5, cfg.system.total_mass, cfg.spin.nominal_speed)
    assert "0.8 g*cm" in w and f"G{left:.3g}" in w


def test_capacity_equal_to_the_unbalance_or_above_is_silent():
    assert not _warnings(CENTRIFUGE, [*SMALL_BALLS[1:], "rotor.unbalance=1.2 g*cm"])
    assert not _warnings(CENTRIFUGE, [*SMALL_BALLS[1:], "rotor.unbalance=1 g*cm"])


def test_the_liquid_counts_in_the_capacity():
    # leblanc_003: rho V R = U by design (round-off apart): no warning; more unbalance warns
    assert not _warnings("leblanc_003")
    w = _only(_warnings("leblanc_003", ["rotor.unbalance=0.05 kg*m"]), "capacity")
    assert "liquid capacity of 0.03 kg*m (rho V R)" in w


def test_the_largest_unbalance_of_a_schedule_counts():
    sched = ["rotor.unbalance_schedule=[['0 s', '1 g*cm'], ['1 s', '2 g*cm']]"]
    w = _only(_warnings(CENTRIFUGE, [*SMALL_BALLS[1:], "rotor.unbalance=1 g*cm", *sched]),
              "capacity")
    assert "2 g*cm" in w


# -- 2. nominal speed below the balancing onset ----------------------------------------------
def test_a_nominal_speed_below_resonance_warns_with_the_grades():
    sets = ["profile.kind=constant", "profile.speed=500 rpm", "profile.duration=10 s"]
    cfg = load_config(CENTRIFUGE, sets)
    w = _only(config_warnings(cfg), "nominal speed")
    s, W = cfg.system, cfg.spin.nominal_speed
    g0 = grade_value(s.rotor.unbalance, s.total_mass, W)
    g1 = grade_value(s.rotor.unbalance + s.balancer.capacity, s.total_mass, W)
    assert "500 rpm is below the balancing onset 551 rpm" in w
    assert f"(G{g0:.3g} -> up to G{g1:.3g})" in w
    assert not _warnings(CENTRIFUGE, [*sets[:1], "profile.speed=560 rpm", sets[2]])


def test_the_onset_not_the_first_natural_frequency_decides():
    # 000's washer: natural frequencies 2.02 and 3.69 Hz, eq 12's onset 3.52 Hz between them
    s = load_config("washer_000").system
    onset = balancing_onset_speed(s) / (2 * math.pi)
    assert min(s.natural_frequencies) < 2 * math.pi * onset < max(s.natural_frequencies)
    assert not _warnings("washer_000", [f"profile.speed={onset * 1.02} Hz"])
    _only(_warnings("washer_000", [f"profile.speed={onset * 0.98} Hz"]), "balancing onset")


# -- 3. a TSR plateau below the onset ----------------------------------------------------------
def test_a_tsr_plateau_below_the_onset():
    w = _only(_warnings(CENTRIFUGE, ["profile.plateau=500 rpm"]), "plateau")
    assert w.startswith("the TSR plateau 500 rpm is below the balancing onset 551 rpm")
    assert not _warnings(CENTRIFUGE, ["profile.plateau=560 rpm"])
    found = _warnings(CENTRIFUGE, ["profile.nominal=500 rpm", "profile.plateau=450 rpm"])
    assert [w[:20] for w in found] == ["the nominal speed 50", "the TSR plateau 450 "]


# -- 4. ball density -------------------------------------------------------------------------
def test_a_ball_too_light_for_its_size():
    sets = ["balancer.element=ball", "balancer.ball_mass=0.4 g", "balancer.ball_radius=10 mm"]
    w = _only(_warnings(CENTRIFUGE, sets), "density")
    assert "95.49 kg/m^3" in w and "outside 1-20 g/cm^3" in w
    # the same mass as a point (no size) or a roller (its length is not modelled): silent
    for element in ("point", "roller"):
        assert not [x for x in _warnings(CENTRIFUGE, [f"balancer.element={element}", *sets[1:]])
                    if "density" in x]


def test_steel_balls_and_a_lead_ball_are_plausible_but_a_heavy_tiny_one_is_not():
    assert not _warnings(CENTRIFUGE, ["balancer.element=ball"])          # 8 g, 6.25 mm steel
    assert not _warnings(CENTRIFUGE, ["balancer.element=ball", "balancer.ball_mass=11.6 g"])
    w = _only(_warnings(CENTRIFUGE, ["balancer.element=ball", "balancer.ball_radius=2 mm"]),
              "density")
    assert "2.387e+05 kg/m^3" in w


# -- 5. one ball -----------------------------------------------------------------------------
def test_one_ball():
    w = _only(_warnings(CENTRIFUGE, [*ONE_BALL, "rotor.unbalance=0.2 g*m"]), "one ball")
    assert "m R = 0.36 g*m, U = 0.2 g*m" in w and "|U - m R| = 0.16 g*m" in w
    assert not [x for x in _warnings(CENTRIFUGE) if "one ball" in x]


# -- 6. bare numbers that look like a forgotten unit -------------------------------------------
@pytest.mark.parametrize("sets, key, text", [
    (["balancer.race_radius=15", "balancer.ball_radius=6.25 mm"], "balancer.race_radius",
     "15 m, above the plausible 2 m"),
    (["profile.nominal=2e5"], "profile.nominal", "200000 rad/s, above the plausible 100000 rad/s"),
    (["rotor.mass=2e4"], "rotor.mass", "20000 kg, above the plausible 10000 kg"),
    (["balancer.ball_mass=[20000, 0.008]"], "balancer.ball_mass[0]", "20000 kg"),
    (["rotor.unbalance_schedule=[[0, 20]]"], "rotor.unbalance_schedule[0][1]", "20 kg*m"),
])
def test_a_bare_number_beyond_its_kind(sets, key, text):
    cfg = load_config(CENTRIFUGE, sets)
    w = _only(bare_number_warnings(cfg.raw), key)
    assert w.startswith(f"{key} = ") and "has no unit, so it is SI" in w and text in w
    assert w in config_warnings(cfg)


def test_a_bare_liquid_volume_and_plausible_or_united_values_are_silent():
    # a 150 m^3 fill does not fit the chamber (refused): the check reads the values as written
    w = _only(bare_number_warnings({"liquid": {"volume": [150, "100 ml"]}}), "liquid.volume")
    assert w.startswith("liquid.volume[0] = 150") and "150 m^3" in w and "'150 ml'" in w
    for sets in (["balancer.race_radius=0.045"], ["balancer.race_radius=1.9"],
                 ["profile.nominal=400"], ["rotor.mass=12"]):
        assert not bare_number_warnings(load_config(CENTRIFUGE, sets).raw), sets
    # a value with its unit is taken as meant, however large
    raw = {"rotor": {"mass": "20 t"}, "balancer": {"race_radius": "15 m"}}
    assert bare_number_warnings(raw) == []


# -- the machine as a whole ------------------------------------------------------------------
def test_machine_warnings_in_si_without_a_formatter():
    cfg = load_config(CENTRIFUGE, SMALL_BALLS)
    w = _only(machine_warnings(cfg.system, cfg.spin), "capacity")
    assert "an unbalance of 2e-05 kg*m against a ball capacity of 1.2e-05 kg*m" in w


def test_a_bare_rotor_has_no_balancer_warnings():
    cfg = load_config(CENTRIFUGE, ["balancer.n_balls=0", "initial.ball_angles=[]",
                                   "profile.nominal=300 rpm", "profile.plateau=200 rpm"])
    assert machine_warnings(cfg.system, cfg.spin) == []


@pytest.mark.parametrize("machine", [p["name"] for p in list_presets()] + EXAMPLES)
def test_no_preset_or_example_warns(machine):
    assert config_warnings(load_config(machine)) == []


# -- on the command line -----------------------------------------------------------------------
def test_show_prints_the_warnings_and_lists_them_in_json():
    r = runner.invoke(app, ["show", CENTRIFUGE, *sum((["--set", s] for s in ONE_BALL), [])])
    assert r.exit_code == 0, r.output
    lines = [x for x in r.stdout.splitlines() if x.startswith("warning: ")]
    assert len(lines) == 2 and "one ball" in lines[1] and "capacity" in lines[0]
    r = runner.invoke(app, ["show", CENTRIFUGE, "--json",
                            *sum((["--set", s] for s in ONE_BALL), [])])
    d = json.loads(r.stdout)
    assert [f"warning: {w}" for w in d["warnings"]] == lines


def test_show_uses_the_eccentricity_of_the_grades():
    cfg = load_config("washer_000")
    s = cfg.system
    r = runner.invoke(app, ["show", "washer_000", "--json"])
    d = json.loads(r.stdout)["derived"]
    assert d["eccentricity_m"] == pytest.approx(s.rotor.unbalance / s.total_mass, rel=1e-15)
    assert d["eccentricity_m"] < s.rotor.eccentricity          # M_t > M: the balls' mass
    assert d["eccentricity_definition"] == "e = U/M_t"
    assert json.loads(r.stdout)["warnings"] == []
    text = runner.invoke(app, ["show", "washer_000"]).stdout
    derived = text[text.index("[derived]"):].splitlines()
    line = next(x for x in derived if "eccentricity_m" in x)
    assert "(e = U/M_t)" in line and f"{d['eccentricity_m']:.6g}" in line
    assert "warning:" not in text


def test_a_study_prints_the_warnings_first_and_lists_them_in_json(tmp_path):
    sets = sum((["--set", s] for s in SMALL_BALLS), [])
    r = runner.invoke(app, ["study", "immobility", CENTRIFUGE, "--quick", "--starts", "12",
                            *sets])
    assert r.exit_code == 0, r.output                       # a warning never refuses
    assert r.stdout.splitlines()[0].startswith("warning: an unbalance of 2 g*cm")
    out = tmp_path / "imm.nc"
    r = runner.invoke(app, ["study", "immobility", CENTRIFUGE, "--quick", "--starts", "12",
                            "--json", "--out", str(out), *sets])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)                                 # stdout is JSON alone
    assert len(d["warnings"]) == 1 and d["warnings"][0].startswith("an unbalance of 2 g*cm")
    import xarray as xr

    with xr.open_dataset(out) as ds:
        assert json.loads(ds.attrs["warnings"]) == d["warnings"]
    r = runner.invoke(app, ["study", "immobility", CENTRIFUGE, "--quick", "--starts", "12",
                            "--json"])
    assert json.loads(r.stdout)["warnings"] == []
