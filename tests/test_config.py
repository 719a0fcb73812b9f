"""Configuration: presets, unit parsing, overrides and one-line errors (autobalance.config)."""
from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from autobalance.config import (PROFILE_KINDS, SECTIONS, Config, ConfigError, apply_overrides,
                                describe, from_dict, from_models, list_presets, load_config,
                                parse_quantity, preset_path, replace_values, source_comments)
from autobalance.models import MotorDrive, SpeedProfile

TWO_PI = 2 * math.pi


# -- presets ----------------------------------------------------------------------------------
def test_list_presets_has_both():
    names = {p["name"] for p in list_presets()}
    assert {"washer_000", "vub_jeffcott_004"} <= names
    for p in list_presets():
        assert p["description"] and preset_path(p["name"]).is_file()


def test_washer_000_values_si():
    cfg = load_config("washer_000")
    assert isinstance(cfg, Config)
    s = cfg.system
    assert s.rotor.mass == 37.0
    assert s.rotor.unbalance == pytest.approx(0.025)
    assert s.rotor.polar_inertia == pytest.approx(0.532)
    assert s.rotor.spin_damping == 0.0
    assert (s.suspension.kx, s.suspension.ky) == (20000.0, 6000.0)
    assert (s.suspension.cx, s.suspension.cy) == (200.0, 110.0)
    assert s.suspension.dry_friction_force == 0.0
    assert s.suspension.dry_friction_angle == pytest.approx(math.radians(61))
    b = s.balancer
    assert b.n_balls == 2 and b.element == "ball"
    assert b.ball_mass == pytest.approx((0.08929, 0.08929))
    assert b.race_radius == pytest.approx(0.28) and b.ball_radius == pytest.approx(0.014)
    assert b.damping == pytest.approx((0.014, 0.014))
    assert b.rolling_resistance == (0.0, 0.0) and b.eccentricity == 0.0
    assert b.eccentricity_angle == pytest.approx(math.pi / 2) and b.restitution == 0.5
    assert s.gravity.g == pytest.approx(9.81) and s.gravity.direction == pytest.approx(math.pi)
    assert isinstance(cfg.spin, SpeedProfile)
    assert cfg.spin.speeds == pytest.approx((1000 * TWO_PI / 60,) * 2)
    assert cfg.spin.duration == 8.0
    assert cfg.initial.ball_angles == pytest.approx((math.radians(90), math.radians(150)))
    assert cfg.initial.steady_state is True
    assert cfg.source == "washer_000" and s.name == "washer_000"


def test_vub_jeffcott_004_values_si():
    cfg = load_config("vub_jeffcott_004")
    s = cfg.system
    assert s.rotor.mass == pytest.approx(16.53)
    assert s.rotor.unbalance == pytest.approx(16.53 * 19.3e-6)
    assert s.suspension.kx == pytest.approx(5.8e6) and s.suspension.ky == pytest.approx(5.8e6)
    assert s.suspension.cx == pytest.approx(1510.0) and s.suspension.cy == pytest.approx(1510.0)
    b = s.balancer
    assert b.n_balls == 2 and b.element == "point"
    assert b.ball_mass == pytest.approx((7.6e-3, 7.6e-3))
    assert b.race_radius == pytest.approx(0.035) and b.ball_radius == pytest.approx(6.14e-3)
    assert b.damping == pytest.approx((2.7e-3, 2.7e-3))
    assert b.rolling_resistance == pytest.approx((0.002, 0.002))
    assert s.gravity.g == 0.0
    assert cfg.profile_kind == "tsr"
    assert cfg.spin.nominal_speed == pytest.approx(TWO_PI * 167)
    assert min(cfg.spin.speeds[2:]) == pytest.approx(TWO_PI * 100)
    assert cfg.spin.duration == 90.0 and cfg.spin.checkpoints == pytest.approx((18.0, 90.0))
    assert cfg.options.friction_law == "stick"
    assert cfg.initial.ball_angles == pytest.approx((math.pi / 4, 3 * math.pi / 4))
    # natural frequency of 004: 94.2 Hz
    assert s.natural_frequencies[0] / TWO_PI == pytest.approx(94.2, abs=0.1)


@pytest.mark.parametrize("name", ["washer_000", "vub_jeffcott_004"])
def test_every_preset_value_has_a_source_comment(name):
    text = preset_path(name).read_text()
    comments = source_comments(text)
    import tomllib

    raw = tomllib.loads(text)
    keys = [k for k, v in raw.items() if not isinstance(v, dict)]
    keys += [f"{s}.{k}" for s, t in raw.items() if isinstance(t, dict) for k in t]
    assert keys and all(comments.get(k) for k in keys), set(keys) - set(comments)


def test_describe_si_with_suffixes_and_sources():
    d = describe(load_config("vub_jeffcott_004"))
    assert d["suspension"]["kx_N_m"] == pytest.approx(5.8e6)
    assert d["rotor"]["mass_kg"] == pytest.approx(16.53)
    assert d["balancer"]["damping_N_m_s_rad"] == pytest.approx([2.7e-3, 2.7e-3])
    assert d["profile"]["kind"] == "tsr"
    assert d["profile"]["nominal_rad_s"] == pytest.approx(TWO_PI * 167)
    assert d["profile"]["times_s"][0] == 0.0
    assert "Table 1" in d["sources"]["suspension.kx"]
    assert d["derived"]["natural_frequencies_hz"][0] == pytest.approx(94.2, abs=0.1)
    import json

    json.dumps(d)  # JSON-able


# -- unit parsing -----------------------------------------------------------------------------
@pytest.mark.parametrize("text, kind, expected", [
    ("1000 rpm", "speed", 104.71975511965977),
    ("167 Hz", "speed", TWO_PI * 167),
    ("2 kHz", "speed", TWO_PI * 2000),
    ("50 rad/s", "speed", 50.0),
    ("50 1/s", "speed", TWO_PI * 50),
    ("1000 min^-1", "speed", 104.71975511965977),
    ("2.7 N*mm*s/rad", "rot_damping", 2.7e-3),
    ("3000 g*cm", "unbalance", 0.03),
    ("5.8 kN/mm", "stiffness", 5.8e6),
    ("200 kg/s", "damping", 200.0),
    ("1.510 kN*s/m", "damping", 1510.0),
    ("61 deg", "angle", math.radians(61)),
    ("0.532 kg*m^2", "inertia", 0.532),
    ("9.81 m/s^2", "acceleration", 9.81),
    ("25 N*m", "torque", 25.0),
    ("90 s", "time", 90.0),
    ("1.5 min", "time", 90.0),
    ("0.2 %", "ratio", 0.002),
    (42, "stiffness", 42.0),
    ("42", "stiffness", 42.0),
])
def test_parse_quantity(text, kind, expected):
    assert parse_quantity(text, kind) == pytest.approx(expected, rel=1e-12)


@pytest.mark.parametrize("text, kind", [("5 kg", "stiffness"), ("5 rad", "stiffness"),
                                        ("5 foo", "mass"), ("", "mass"), ("5 N/", "force"),
                                        (True, "mass"), ("3 m", "ratio")])
def test_parse_quantity_rejects(text, kind):
    with pytest.raises(ConfigError) as e:
        parse_quantity(text, kind, "a.b")
    assert str(e.value).startswith("a.b = ") and "\n" not in str(e.value)


@settings(max_examples=200, deadline=None)
@given(st.floats(min_value=1e-9, max_value=1e12, allow_nan=False, allow_infinity=False))
def test_stiffness_n_per_mm_round_trip(x):
    cfg = load_config("washer_000", [f"suspension.kx={x!r} N/mm"])
    assert cfg.system.suspension.kx == pytest.approx(x * 1000.0, rel=1e-12)


# -- overrides --------------------------------------------------------------------------------
def test_overrides_units_and_types():
    cfg = load_config("washer_000", ["suspension.kx=25 N/mm", 'rotor.unbalance="0.05 kg*m"',
                                     "balancer.rolling_resistance=1e-3", "profile.speed=100 Hz",
                                     "initial.ball_angles=[0, 3.0]",
                                     "balancer.ball_mass=['80 g', '90 g']",
                                     "name=my washer"])
    s = cfg.system
    assert s.suspension.kx == 25000.0 and s.rotor.unbalance == pytest.approx(0.05)
    assert s.balancer.rolling_resistance == (1e-3, 1e-3)
    assert s.balancer.ball_mass == pytest.approx((0.08, 0.09))
    assert cfg.spin.nominal_speed == pytest.approx(TWO_PI * 100)
    assert cfg.initial.ball_angles == (0.0, 3.0)
    assert s.name == "my washer"
    assert cfg.raw["suspension"]["kx"] == "25 N/mm"
    assert cfg.sources["suspension.kx"].startswith("--set")


def test_overrides_bare_list_of_quantities():
    cfg = load_config("washer_000", ["initial.ball_angles=[10 deg, 90 deg]"])
    assert cfg.initial.ball_angles == pytest.approx((math.radians(10), math.pi / 2))


def test_apply_overrides_does_not_modify_input():
    raw = {"suspension": {"kx": 1.0}}
    out = apply_overrides(raw, ["suspension.kx=2"])
    assert raw["suspension"]["kx"] == 1.0 and out["suspension"]["kx"] == 2


def test_profile_kind_switch_drops_preset_keys():
    cfg = load_config("washer_000", ["profile.kind=tsr", "profile.duration=90 s",
                                     "profile.nominal=167 Hz"])  # nominal: required (no default)
    assert cfg.profile_kind == "tsr"
    assert "speed" not in cfg.raw["profile"]  # came from the preset: dropped
    assert cfg.spin.nominal_speed == pytest.approx(TWO_PI * 167)
    cfg = load_config("vub_jeffcott_004", ["profile.kind=std"])
    assert cfg.profile_kind == "std" and "plateau" not in cfg.raw["profile"]
    assert cfg.spin.nominal_speed == pytest.approx(TWO_PI * 167)
    cfg = load_config("washer_000", ["profile.kind=motor", "profile.law=constant",
                                     "profile.torque=25 N*m", "profile.final_speed=1000 rpm"])
    assert isinstance(cfg.spin, MotorDrive) and cfg.spin.duration == 8.0


def test_profile_kind_switch_keeps_set_keys_and_rejects_them():
    with pytest.raises(ConfigError, match=r"^profile\.speed: unknown key for kind 'std'"):
        load_config("washer_000", ["profile.speed=10 Hz", "profile.kind=std"])


def test_config_file_path(tmp_path):
    p = tmp_path / "mine.toml"
    p.write_text(preset_path("washer_000").read_text().replace('name = "washer_000"', ""))
    cfg = load_config(str(p))
    assert cfg.source == str(p) and cfg.system.name == "mine"
    assert cfg.system.suspension.kx == 20000.0


def test_from_dict_minimal_defaults():
    cfg = from_dict({"rotor": {"mass": 10}, "suspension": {"kx": 1e5, "ky": "100 N/mm"},
                     "profile": {"kind": "ramp", "start_speed": 0, "end_speed": "600 rpm",
                                 "ramp_time": "5 s", "duration": "10 s"}})
    assert cfg.system.balancer.n_balls == 0 and cfg.system.suspension.ky == 1e5
    assert cfg.spin.speeds[-1] == pytest.approx(20 * math.pi)


def test_table_and_std_profiles():
    cfg = load_config("washer_000", ["profile.kind=table", "profile.times=[0, '2 s', '5 s']",
                                     "profile.speeds=[0, '600 rpm', '600 rpm']",
                                     "profile.checkpoints=['2 s']"])
    assert cfg.spin.times == (0.0, 2.0, 5.0) and cfg.spin.checkpoints == (2.0,)
    assert set(PROFILE_KINDS) == {"constant", "ramp", "table", "std", "tsr", "motor"}


# -- one-line errors --------------------------------------------------------------------------
BAD = [
    (["rotor.mass=-5 kg"], "rotor.mass"),
    (["rotor.mass=0"], "rotor.mass"),
    (["suspension.kx=0 N/mm"], "suspension.kx"),
    (["balancer.race_radius=-1 mm"], "balancer.race_radius"),
    (["balancer.ball_radius=-1"], "balancer.ball_radius"),
    (["rotor.mass=nan"], "rotor.mass"),
    (['rotor.mass="nan"'], "rotor.mass"),
    (["suspension.kx=5 kg"], "suspension.kx"),
    (["balancer.foo=1"], "balancer.foo"),
    (["foo.bar=1"], "foo.bar"),
    (["profile.kind=warp"], "profile.kind"),
    (["initial.ball_angles=['30 deg']"], "initial.ball_angles"),
    (["balancer.ball_mass=[1, -2]"], "balancer.ball_mass[1]"),
    # a unit outside a list: pint would read "[4, 2] g" as one product, 8 g for every ball
    (["balancer.ball_mass=[4, 2] g"], "balancer.ball_mass"),
    (["rotor.mass=1,5 kg"], "rotor.mass"),
    (["balancer.n_balls=two"], "balancer.n_balls"),
    (["profile.speed=fast"], "profile.speed"),
    (["profile.kind=motor"], "profile.law"),
    (["profile.kind=motor", "profile.law=cubic", "profile.torque=1", "profile.final_speed=1"],
     "profile.law"),
    (["options.friction_law=magic"], "options.friction_law"),
    (["rotor.unbalance_schedule=[[0, 1], [1]]"], "rotor.unbalance_schedule[1]"),
    (["nonsense"], "nonsense"),
]


@pytest.mark.parametrize("overrides, field", BAD)
def test_bad_overrides_one_line(overrides, field):
    with pytest.raises(ConfigError) as e:
        load_config("washer_000", overrides)
    msg = str(e.value)
    assert field in msg and "\n" not in msg


def test_error_messages_exact_format():
    with pytest.raises(ConfigError) as e:
        load_config("washer_000", ["suspension.kx=5 kg"])
    assert str(e.value) == "suspension.kx = '5 kg': expected a stiffness [N/m], e.g. '20 N/mm'"
    with pytest.raises(ConfigError) as e:
        load_config("washer_000", ["rotor.mass=0"])
    assert str(e.value) == "rotor.mass = 0.0: must be > 0"


def _raw(**changes):
    raw = {"rotor": {"mass": "10 kg"}, "suspension": {"kx": "1 N/mm", "ky": "1 N/mm"},
           "balancer": {"n_balls": 2, "ball_mass": "5 g", "race_radius": "30 mm",
                        "ball_radius": "3 mm"},
           "profile": {"kind": "constant", "speed": "100 rad/s", "duration": "1 s"}}
    for path, value in changes.items():
        section, key = path.split("__")
        if value is None:
            raw[section].pop(key)
        else:
            raw[section][key] = value
    return raw


def test_missing_required():
    with pytest.raises(ConfigError) as e:
        from_dict(_raw(rotor__mass=None))
    assert str(e.value) == "rotor.mass: missing; required [kg]"
    with pytest.raises(ConfigError, match=r"^suspension: missing"):
        from_dict({"rotor": {"mass": 1}, "profile": {"kind": "constant"}})
    with pytest.raises(ConfigError, match=r"^profile\.kind: missing"):
        from_dict(_raw(profile__kind=None))
    with pytest.raises(ConfigError, match=r"^profile\.speed: missing; required \[rad/s\]"):
        from_dict(_raw(profile__speed=None))


def test_unknown_key_lists_allowed():
    with pytest.raises(ConfigError) as e:
        from_dict(_raw(balancer__foo=1))
    msg = str(e.value)
    assert msg.startswith("balancer.foo: unknown key; allowed: n_balls, ball_mass")
    for key in SECTIONS["balancer"]:
        assert key in msg
    with pytest.raises(ConfigError, match=r"^extra: unknown key"):
        from_dict({**_raw(), "extra": 1})


def test_section_not_a_table():
    with pytest.raises(ConfigError, match=r"^rotor = 5: expected a table"):
        from_dict({**_raw(), "rotor": 5})


def test_unknown_preset_and_unreadable_file(tmp_path):
    with pytest.raises(ConfigError, match="unknown preset 'nope'"):
        load_config("nope")
    with pytest.raises(ConfigError, match="cannot read config file"):
        load_config(str(tmp_path / "missing.toml"))
    bad = tmp_path / "bad.toml"
    bad.write_text("[rotor\nmass = 1\n")
    with pytest.raises(ConfigError, match="invalid TOML") as e:
        load_config(str(bad))
    assert "\n" not in str(e.value)


def test_source_comments_ignores_hash_in_strings():
    text = '[a]\nx = "1 # not a comment" # the source\ny = 2\n'
    assert source_comments(text) == {"a.x": "the source"}


# -- the schema follows the models -------------------------------------------------------------
def test_sections_are_the_model_fields():
    import dataclasses

    from autobalance.config.schema import SECTION_MODELS

    def no_default(f):
        return f.default is dataclasses.MISSING and f.default_factory is dataclasses.MISSING

    for section, cls in [*SECTION_MODELS.items(), ("motor", MotorDrive), ("table", SpeedProfile)]:
        specs = SECTIONS.get(section) or PROFILE_KINDS[section]
        fields = [f for f in dataclasses.fields(cls) if f.name != "name"]
        assert list(specs) == [f.name for f in fields], section
        assert [s.required for s in specs.values()] == [no_default(f) for f in fields], section


# -- Configs changed and built in Python -------------------------------------------------------
def _models(cfg):
    return repr((cfg.system, cfg.spin, cfg.initial, cfg.options, cfg.profile_kind))


@pytest.mark.parametrize("base, values", [
    ("vub_jeffcott_004", {"balancer.rolling_resistance": 0.004}),
    ("vub_jeffcott_004", {"rotor.unbalance": "0.2 g*m", "options.rtol": 1e-7}),
    ("vub_jeffcott_004", {"profile.plateau": "96 Hz"}),
    ("vub_jeffcott_004", {"balancer.n_balls": 3, "initial.ball_angles": [0, 2, 4]}),
    ("vub_jeffcott_004", {"profile.kind": "std"}),
    ("vub_jeffcott_004", {"balancer.ball_mass": ["7 g", "8 g"], "name": "x"}),
    ("washer_000", {"profile.kind": "motor", "profile.law": "linear",
                    "profile.torque": "25 N*m", "profile.final_speed": "1000 rpm"}),
    ("washer_000", {"rotor.unbalance_schedule": [["0 s", "0.02 kg*m"], ["1 s", 0.03]],
                    "initial.steady_state": False, "suspension.base_frequency": "10 Hz"}),
])
def test_replace_values_same_models_as_set(base, values):
    import json

    got = replace_values(load_config(base), values)
    want = load_config(base, [f"{k}={json.dumps(v)}" for k, v in values.items()])
    assert _models(got) == _models(want)
    assert describe(got)["profile"] == describe(want)["profile"]
    assert all(got.sources[k].startswith("set ") for k in values)


@pytest.mark.parametrize("values", [
    {"rotor.mass": -1}, {"suspension.kx": "5 kg"}, {"balancer.n_balls": 3},
    {"profile.speed": 1}, {"rotor.foo": 1}, {"nothing": 1}, {"balancer.n_balls": "two"},
    {"balancer.rolling_resistance": 0.5, "balancer.stiction": 0.1},
    {"initial.ball_angles": ["30 deg"]}, {"options.friction_law": "magic"},
    {"rotor.unbalance_schedule": [[0, 1], [1]]}, {"profile.kind": "warp"},
])
def test_replace_values_errors_as_set(values):
    """The same one line as the --set of the same values (minus the --set of a bad path)."""
    import json

    with pytest.raises(ConfigError) as want:
        load_config("vub_jeffcott_004", [f"{k}={json.dumps(v)}" for k, v in values.items()])
    with pytest.raises(ConfigError) as got:
        replace_values(load_config("vub_jeffcott_004"), values)
    assert str(got.value) == str(want.value).removeprefix("--set ")


def test_replace_values_defaults_that_follow_other_keys():
    cfg = load_config("vub_jeffcott_004")
    # stiction left out of the preset: it follows rolling_resistance
    assert replace_values(cfg, {"balancer.rolling_resistance": 0.01}).system.balancer.stiction \
        == (0.01, 0.01)
    # given: it stays
    given = replace_values(cfg, {"balancer.stiction": 0.02})
    assert replace_values(given, {"balancer.rolling_resistance": 0.01}).system.balancer.stiction \
        == (0.02, 0.02)
    # per-ball values given as one number follow n_balls; None puts a key back to its default
    three = replace_values(cfg, {"balancer.n_balls": 3, "initial.ball_angles": None})
    assert three.system.balancer.ball_mass == (0.0076,) * 3
    assert three.initial.ball_angles is None and "ball_angles" not in three.raw["initial"]
    with pytest.raises(ConfigError, match=r"^rotor\.mass: missing; required \[kg\]$"):
        replace_values(cfg, {"rotor.mass": None})
    assert cfg.system.balancer.rolling_resistance == (0.002, 0.002)   # not changed


def test_replace_values_on_models_replaced_in_python():
    """A Config whose models were replaced in Python: its raw no longer describes them, so the
    keys are read off the models."""
    import dataclasses

    cfg = load_config("vub_jeffcott_004")
    b = dataclasses.replace(cfg.system.balancer, stiction=0.003)
    cfg = dataclasses.replace(cfg, system=dataclasses.replace(cfg.system, balancer=b))
    assert replace_values(cfg, {"balancer.rolling_resistance": 0.001}).system.balancer.stiction \
        == (0.003, 0.003)
    spin = SpeedProfile.constant(100.0, 2.0)
    cfg = dataclasses.replace(cfg, spin=spin)
    new = replace_values(cfg, {"profile.checkpoints": [1.0]})
    assert new.spin == dataclasses.replace(spin, checkpoints=(1.0,)) and new.spin.name == "constant"
    with pytest.raises(ConfigError, match=r"^profile\.plateau: unknown key for kind 'table'"):
        replace_values(cfg, {"profile.plateau": "90 Hz"})


def test_from_models_round_trip():
    import dataclasses

    cfg = load_config("vub_jeffcott_004")
    for spin in (cfg.spin, dict(cfg.raw["profile"])):
        m = from_models(cfg.system, spin, cfg.initial, cfg.options)
        back = from_dict(m.raw, source="x")
        assert (back.system, back.initial, back.options) == (m.system, m.initial, m.options)
        assert dataclasses.replace(back.spin, name=m.spin.name) == m.spin == cfg.spin
        assert describe(m)["profile"]["nominal_speed_rad_s"] == cfg.spin.nominal_speed
    assert m.profile_kind == "tsr" and "stiction" not in m.raw["balancer"]
    assert m.raw["balancer"]["ball_mass"] == 0.0076          # equal per-ball values: one number
    with pytest.raises(ConfigError, match=r"^initial\.ball_angles = \[0\.0\]: needs 2 values"):
        from_models(cfg.system, cfg.spin, dataclasses.replace(cfg.initial, ball_angles=(0.0,)))
