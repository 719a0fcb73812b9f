"""Rotational speeds as drawings and motor plates write them, and the value guard of the parser.

A pure inverse time (``min^-1``, ``1/min``, ``/min``, ``Hz``, ``kHz``, ``1/s``, ``s^-1``) counts
revolutions per time; a unit carrying an angle (``rpm``, ``rev/min``, ``rps``, ``rev/s``,
``turn/s``, ``rad/s``, ``deg/s``) is an angle per time (autobalance.config.units.speed_si). The
same function shows speeds in ``--units``. Values other than ``<number> <unit expression>``
are refused before pint evaluates them.
"""
from __future__ import annotations

import json
import math
import signal
import time

import pytest

from autobalance.cli import main
from autobalance.config import ConfigError, load_config, parse_quantity
from autobalance.config.display import display_units
from autobalance.config.units import check_unit_expression, speed_si, registry

W1000 = 1000.0 * 2.0 * math.pi / 60.0           # 1000 revolutions per minute [rad/s]
W50 = 50.0 * 2.0 * math.pi                       # 50 revolutions per second [rad/s]


@pytest.mark.parametrize("text, expected", [
    ("1000 min^-1", W1000), ("1000 1/min", W1000), ("1000/min", W1000), ("1000 rpm", W1000),
    ("1000 rev/min", W1000), ("1000 min**-1", W1000), ("1000 min⁻¹", W1000),
    ("50 Hz", W50), ("0.05 kHz", W50), ("50 1/s", W50), ("50 s^-1", W50), ("50 rps", W50),
    ("50 rev/s", W50), ("50 turn/s", W50),
    ("100 rad/s", 100.0), ("360 deg/s", 2.0 * math.pi), ("6000 deg/min", math.radians(100.0)),
    ("100", 100.0), (100, 100.0),
])
def test_every_unit_of_the_rule_converts(text, expected):
    assert parse_quantity(text, "speed", "profile.speed") == pytest.approx(expected, rel=1e-14)


def test_the_written_numbers():
    assert parse_quantity("1000 min^-1", "speed") == pytest.approx(104.72, abs=5e-3)
    assert parse_quantity("50 1/s", "speed") == pytest.approx(314.16, abs=5e-3)
    # a revolution per minute is the same float whichever way it is written
    assert parse_quantity("1000 min^-1", "speed") == parse_quantity("1000 rpm", "speed")
    assert parse_quantity("1000/min", "speed") == parse_quantity("1000 rev/min", "speed")


def test_hz_keeps_its_float():
    """The presets' speeds in Hz give the floats they always gave (2 pi f)."""
    for f in (167.0, 100.0, 94.2, 0.5):
        assert parse_quantity(f"{f} Hz", "speed") == f * 2.0 * math.pi


def test_speed_si_is_the_one_rule():
    q = registry().Quantity
    assert speed_si(q(1.0, "1/min")) == speed_si(q(1.0, "rpm"))
    assert speed_si(q(1.0, "rad/s")) == 1.0
    with pytest.raises(Exception):
        speed_si(q(1.0, "kg"))


def test_a_speed_of_another_dimension_is_refused():
    for text in ("5 kg", "5 m/s", "5 rad", "5 rad^2/s"):
        with pytest.raises(ConfigError, match=r"^profile\.speed = .*rotational speed"):
            parse_quantity(text, "speed", "profile.speed")


@pytest.mark.parametrize("unit, shown", [("1/min", "1000 1/min"), ("min^-1", "1000 min^-1"),
                                         ("rpm", "1000 rpm"), ("rev/min", "1000 rev/min"),
                                         ("1/s", "16.67 1/s"), ("Hz", "16.67 Hz"),
                                         ("rad/s", "104.7 rad/s"), ("deg/s", "6000 deg/s")])
def test_display_round_trips(unit, shown):
    cfg = load_config("washer_000", ["profile.speed=1000 rpm"])
    u = display_units(cfg, f"speed={unit}")
    assert u.fmt(cfg.spin.nominal_speed, "speed") == shown
    assert u.to(parse_quantity(f"7 {unit}", "speed"), "speed") == pytest.approx(7.0, rel=1e-12)


def test_written_unit_is_shown_as_written():
    cfg = load_config("washer_000", ["profile.speed=1000 min^-1"])
    u = display_units(cfg)
    assert u.unit("speed") == "min^-1"
    assert u.fmt(cfg.spin.nominal_speed, "speed") == "1000 min^-1"


def _show(capsys, *sets):
    capsys.readouterr()
    with pytest.raises(SystemExit) as e:
        main(["show", "washer_000", *(f"--set={s}" for s in sets), "--json"])
    out = capsys.readouterr()
    assert e.value.code == 0, out.err
    return json.loads(out.out)


def test_show_end_to_end_min_inverse_equals_rpm(capsys):
    a = _show(capsys, "profile.speed=1000 min^-1")
    b = _show(capsys, "profile.speed=1000 rpm")
    assert a["profile"]["speed_rad_s"] == b["profile"]["speed_rad_s"]
    assert a["profile"]["speed_rad_s"] == pytest.approx(104.72, abs=5e-3)
    c = _show(capsys, "profile.speed=50 1/s")
    assert c["profile"]["speed_rad_s"] == _show(capsys, "profile.speed=50 Hz")["profile"][
        "speed_rad_s"]


@pytest.mark.parametrize("unit, shown", [("1/min", "1000 1/min"), ("1/s", "16.67 1/s"),
                                         ("rad/s", "104.7 rad/s")])
def test_units_option_shows_revolutions(capsys, unit, shown):
    """``--units speed=1/min`` on the command line shows 1000 for washer_000's 1000 rpm."""
    capsys.readouterr()
    with pytest.raises(SystemExit) as e:
        main(["simulate", "washer_000", "--set", "profile.duration=0.2 s", "--units",
              f"speed={unit}"])
    out = capsys.readouterr().out
    assert e.value.code == 0
    line = next(x for x in out.splitlines() if x.strip().startswith("nominal_speed"))
    assert line.split(None, 1)[1].strip() == shown, line


class _Timeout(Exception):
    pass


def _alarm(signum, frame):
    raise _Timeout()


@pytest.mark.parametrize("text", ["9**9**9 kg", "2**1000 kg", "1e3**5 m", "(1+2) kg",
                                  "kg**1000", "__import__ kg", "3 __import__", "3 kg**1000",
                                  "3 m^9", "3 sqrt(kg)", "3 kg+2", "1 2 kg", "3 kg*", "3 (kg",
                                  "3 kg " + "*kg" * 200, "3 kg; 2", "kg", "1e5e5 kg"])
def test_guard_refuses_expressions_quickly(text):
    kind = "length" if text.endswith(" m") else "mass"
    handler = signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(5)
    t0 = time.perf_counter()
    try:
        with pytest.raises(ConfigError) as e:
            parse_quantity(text, kind, "rotor.mass")
    finally:
        signal.alarm(0)
        signal.signal(signal.SIGALRM, handler)
    assert time.perf_counter() - t0 < 1.0
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(f"rotor.mass = {text!r}: ")


def test_guard_message_names_field_and_kind():
    with pytest.raises(ConfigError) as e:
        parse_quantity("9**9**9 kg", "mass", "rotor.mass")
    assert str(e.value) == ("rotor.mass = '9**9**9 kg': cannot parse; expected a mass [kg], "
                            "e.g. '37 kg'")


def test_guard_through_the_cli_is_one_line(capsys):
    capsys.readouterr()
    t0 = time.perf_counter()
    with pytest.raises(SystemExit) as e:
        main(["show", "washer_000", "--set", "rotor.mass=9**9**9 kg"])
    err = capsys.readouterr().err.strip().splitlines()
    assert e.value.code == 2 and len(err) == 1 and err[0].startswith("error: rotor.mass = ")
    assert time.perf_counter() - t0 < 5.0


@pytest.mark.parametrize("unit", ["N*mm*s/rad", "kg*m^2", "m^2/s", "min^-1", "1/min", "/min",
                                  "kg/(m*s)", "(m/s)^2", "%", "deg", "µm", "cSt", "g*cm",
                                  "s**-2", "N m", "min⁻¹", "m²", "kg·m"])
def test_unit_expressions_allowed(unit):
    assert check_unit_expression(unit) is None


@pytest.mark.parametrize("unit", ["m^5", "m**-9", "kg**1000", "kg+1", "2**3", "sqrt(m)",
                                  "__class__", "m^2.5", "kg*", "(kg", "kg)", "foo", "1 kg",
                                  "m⁵", "kg⁻¹⁰"])
def test_unit_expressions_refused(unit):
    assert check_unit_expression(unit) is not None


def test_display_choice_is_guarded():
    cfg = load_config("washer_000")
    with pytest.raises(ConfigError, match=r"^--units = 'speed=m\*\*9\*\*9'"):
        display_units(cfg, "speed=m**9**9")
