"""One grammar for ranges and lists on the command line (autobalance.config.ranges).

``LO:HI:N`` with a unit written once applying to both ends, ``LO:HI`` for an interval, and the
list ``a, b, c unit``. The grammar cases are tested on the parser; then every option of the CLI
whose metavar or help says ``LO:HI`` (found by walking the typer app) is given the same grid
with the unit on HI only and on both ends, and must return the same SI values. An option that
says ``LO:HI`` and has no probe below fails the test until it gets one.
"""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
import typer

from autobalance.cli import app, main
from autobalance.cli.liquid import _list
from autobalance.cli.study import _grid
from autobalance.cli.study_design import unbalance_interval
from autobalance.cli.study_maps import map_speeds
from autobalance.config import ConfigError
from autobalance.config.ranges import (LIST_GRAMMAR, RANGE_GRAMMAR, grammar_help, list_items,
                                       parse_interval, parse_list, parse_range, parse_values,
                                       written_unit)
from autobalance.limits import ResourceError

RPM = 2.0 * math.pi / 60.0                      # [rad/s] per rpm


# -- the grammar ------------------------------------------------------------------------------
@pytest.mark.parametrize("text", ["100:1500 rpm:30", "100 rpm:1500:30", "100 rpm:1500 rpm:30",
                                  " 100 rpm : 1500 rpm : 30 ", "100:1500/min:30",
                                  "100 min^-1:1500 rpm:30", "100:1500 rpm:3e1"])
def test_a_unit_written_once_applies_to_both_ends(text):
    w = parse_range(text, "speed", "--speeds")
    assert w == pytest.approx(np.linspace(100 * RPM, 1500 * RPM, 30), rel=1e-14)


def test_bare_numbers_are_si():
    assert list(parse_range("100:1500:3", "speed", "--speeds")) == [100.0, 800.0, 1500.0]
    assert list(parse_range("1:3:3", "volume", "--fills")) == [1.0, 2.0, 3.0]


def test_two_compatible_units_are_each_converted():
    w = parse_range("600 rpm:25 Hz:3", "speed", "--speeds")
    assert w == pytest.approx([600 * RPM, (600 * RPM + 50 * math.pi) / 2, 50 * math.pi])
    v = parse_range("100 ml:0.2 l:2", "volume", "--fills")
    assert v == pytest.approx([1e-4, 2e-4])


@pytest.mark.parametrize("text, why", [
    ("100:1500 rpm:0", "N must be an integer >= 2"),
    ("100:1500 rpm:2.5", "N must be an integer >= 2"),
    ("100:1500 rpm:-3", "N must be an integer >= 2"),
    ("100:1500 rpm:inf", "N must be an integer >= 2"),
    ("100:1500 rpm:x", "N must be an integer >= 2"),
    ("100 rpm:1500 kg:30", "1500 kg: expected a rotational speed"),
    ("100 kg:1500 rpm:30", "100 kg: expected a rotational speed"),
    ("100:1500 rpm", "expected LO:HI:N"),
    ("100:200:300:4", "expected LO:HI:N"),
    ("1500:100 rpm:30", "LO must be below HI"),
    ("a:b:3", "cannot read 'a'"),
    ("9**9:1 rpm:3", "cannot read '9**9'"),
    (":1500 rpm:3", "cannot read ''"),
])
def test_range_refusals_are_one_line(text, why):
    with pytest.raises(ConfigError) as e:
        parse_range(text, "speed", "--speeds")
    msg = str(e.value)
    assert msg.startswith(f"--speeds = {text!r}: ") and why in msg and "\n" not in msg


def test_the_exact_message():
    with pytest.raises(ConfigError) as e:
        parse_range("100:1500 rpm:0", "speed", "--speeds")
    assert str(e.value) == "--speeds = '100:1500 rpm:0': N must be an integer >= 2"


def test_bounds_of_the_option():
    assert parse_range("5:5:1", "ratio", "--x", min_points=1, increasing=False).size == 1
    with pytest.raises(ConfigError, match="N must be at most 10"):
        parse_range("1:2:11", "ratio", "--x", max_points=10)
    with pytest.raises(ConfigError, match="LO must be > 0"):
        parse_range("0:2 rpm:3", "speed", "--x", low=0.0, above=True)
    with pytest.raises(ConfigError, match="LO must be >= 0"):
        parse_range("-1:2 rpm:3", "speed", "--x", low=0.0)
    assert parse_range("3:1:3", "ratio", "--x", increasing=False)[0] == 3.0


def test_memory_is_checked_before_allocating():
    with pytest.raises(ResourceError, match=r"^--speeds = '0:1500 rpm:1e12': the table"):
        parse_range("0:1500 rpm:1e12", "speed", "--speeds", bytes_per_point=1024)


def test_interval():
    assert parse_interval("3:9 g*cm", "unbalance", "--unbalance") == pytest.approx((3e-5, 9e-5))
    assert parse_interval("3 g*cm:0.09 g*m", "unbalance", "--u") == pytest.approx((3e-5, 9e-5))
    assert parse_interval("2:2 g*cm", "unbalance", "--u", strict=False) == pytest.approx(
        (2e-5, 2e-5))
    for text, why in [("2:1 g*cm", "LO must be below HI"), ("5", "expected LO:HI"),
                      ("1:2:3", "expected LO:HI"), ("1 kg:2 g*cm", "expected an unbalance")]:
        with pytest.raises(ConfigError) as e:
            parse_interval(text, "unbalance", "--unbalance")
        assert str(e.value).startswith(f"--unbalance = {text!r}: ") and why in str(e.value)


def test_lists():
    assert parse_list("0, 0.6, 28 rad/s", "speed", "--speeds") == pytest.approx([0, 0.6, 28])
    assert parse_list("300, 600 rpm", "speed", "--speeds") == pytest.approx([300 * RPM, 600 * RPM])
    assert parse_list("1 ml, 2 ml", "volume", "--fills") == pytest.approx([1e-6, 2e-6])
    assert parse_list("1, 2", "volume", "--fills") == pytest.approx([1.0, 2.0])
    assert parse_list("600 rpm, 20 Hz", "speed", "--o") == pytest.approx([600 * RPM, 40 * math.pi])
    assert list_items("4, 8 g*cm", "unbalance", "--grid") == ["4 g*cm", "8 g*cm"]
    for text, why in [("100 rpm, 200", "write the unit on the last item"),
                      ("", "expected a value or a list"), ("1,,2", "expected a value or a list"),
                      ("1, 2 kg", "1 kg: expected a rotational speed")]:
        with pytest.raises(ConfigError) as e:
            parse_list(text, "speed", "--speeds")
        assert str(e.value).startswith(f"--speeds = {text!r}: ") and why in str(e.value)
    with pytest.raises(ConfigError, match="at most 2 values"):
        parse_list("1, 2, 3", "ratio", "--x", max_points=2)


def test_values_take_either_form_and_the_written_unit():
    assert parse_values("0:60 rad/s:4", "speed", "--speeds") == pytest.approx([0, 20, 40, 60])
    assert parse_values("10, 20 rad/s", "speed", "--speeds") == pytest.approx([10, 20])
    assert written_unit("400:900 rpm:6") == "rpm"
    assert written_unit("400 rpm:900:6") == "rpm"
    assert written_unit("1, 2/min") == "1/min"
    assert written_unit("1:2:3") == ""


def test_help_states_the_grammar():
    h = grammar_help("Speeds", "100:1500 rpm:30", tail="default x")
    assert h.startswith("Speeds: " + RANGE_GRAMMAR) and LIST_GRAMMAR in h
    assert h.endswith("e.g. '100:1500 rpm:30'; default x.")


# -- every range option of the CLI ------------------------------------------------------------
class Refused(Exception):
    """A command that exited 2: its one stderr line."""


def _cli(args, extract):
    """A probe running ``autobalance <args(text)> --json`` in this process -> extract(JSON)."""
    def probe(capsys, text):
        capsys.readouterr()
        with pytest.raises(SystemExit) as e:
            main([*args(text), "--json"])
        out = capsys.readouterr()
        if e.value.code != 0:
            lines = out.err.strip().splitlines()
            assert e.value.code == 2 and len(lines) == 1 and lines[0].startswith("error: ")
            raise Refused(lines[0])
        return extract(json.loads(out.out))
    return probe


def _call(fn):
    """A probe calling the option's parse function (the commands run minutes)."""
    return lambda capsys, text: fn(text)


#: (command, option) -> (probe(capsys, text) -> SI values, LO, HI, N (None: LO:HI), unit,
#: SI per unit).
PROBES = {
    ("response", "--speeds"): (
        _cli(lambda t: ["response", "washer_000", "--speeds", t], lambda d: d["speed_rad_s"]),
        100, 1500, 3, "rpm", RPM),
    ("study speed-map", "--speeds"): (_call(map_speeds), 100, 1500, 3, "rpm", RPM),
    # the fill map's fills and speeds: the command's own parse call (the map takes minutes)
    ("study fill-map", "--fills"): (_call(lambda t: _list(t, "volume", "--fills")),
                                    100, 300, 3, "ml", 1e-6),
    ("study fill-map", "--speeds"): (_call(lambda t: _list(t, "speed", "--speeds")),
                                     300, 600, 4, "rpm", RPM),
    ("study start-positions", "--grid"): (
        _call(lambda t: _grid([f"rotor.unbalance={t}"])["rotor.unbalance"]),
        2, 8, 3, "g*cm", 1e-5),
    ("design", "--unbalance"): (_call(unbalance_interval), 3, 9, None, "g*cm", 1e-5),
    ("liquid surface", "--speeds"): (
        _cli(lambda t: ["liquid", "surface", "--speeds", t],
             lambda d: [s["omega_rad_s"] for s in d["surfaces"]]), 10, 60, 3, "rpm", RPM),
    ("liquid modes", "--speeds"): (
        _cli(lambda t: ["liquid", "modes", "--speeds", t], lambda d: d["omega_rad_s"]),
        10, 60, 3, "rpm", RPM),
    ("liquid speeds", "--volume"): (
        _cli(lambda t: ["liquid", "speeds", "--volume", t],
             lambda d: [s["volume_m3"] for s in d["speeds"]]), 100, 200, 3, "ml", 1e-6),
    ("liquid kinetostatic", "--delta"): (
        _cli(lambda t: ["liquid", "kinetostatic", "--delta", t],
             lambda d: [math.radians(x) for x in d["delta_deg"]]),
        10, 60, 3, "deg", math.pi / 180),
    ("liquid simulate", "--speeds"): (      # the deprecated command: response of a liquid
        _cli(lambda t: ["response", "leblanc_003", "--speeds", t], lambda d: d["omega_rad_s"]),
        300, 600, 2, "rpm", RPM),
    ("liquid stability", "--speeds"): (
        _cli(lambda t: ["liquid", "stability", "--speeds", t], lambda d: d["omega_rad_s"]),
        300, 600, 2, "rpm", RPM),
    ("liquid kinetostatic-check", "--speeds"): (
        _cli(lambda t: ["liquid", "kinetostatic-check", "--speeds", t, "--settle", "0 s"],
             lambda d: d["omega_rad_s"]), 300, 600, 2, "rpm", RPM),
}


def _range_options():
    """(command path, option, help) of every option whose metavar or help says LO:HI."""
    def walk(cmd, path):
        if hasattr(cmd, "commands"):
            for name, sub in cmd.commands.items():
                yield from walk(sub, (*path, name))
            return
        for p in cmd.params:
            if getattr(p, "param_type_name", "") != "option":
                continue
            if "LO:HI" in (p.metavar or "") or "LO:HI" in (p.help or ""):
                yield " ".join(path), max(p.opts, key=len), p.help or ""
    return list(walk(typer.main.get_command(app), ()))


RANGE_OPTIONS = _range_options()


def test_every_range_option_has_a_probe():
    found = {(c, o) for c, o, _ in RANGE_OPTIONS}
    assert found == set(PROBES), (
        f"range options without a probe: {sorted(found - set(PROBES))}; "
        f"probes of no option: {sorted(set(PROBES) - found)}")


@pytest.mark.parametrize("command, option, help_", RANGE_OPTIONS,
                         ids=[f"{c} {o}" for c, o, _ in RANGE_OPTIONS])
def test_every_range_option_states_the_grammar(command, option, help_):
    form = "LO:HI, from LO to HI" if PROBES[(command, option)][3] is None else RANGE_GRAMMAR
    assert form in help_ and "a unit written once applies to both ends" in help_, help_
    assert "a:b:n" not in help_ and "1/s" not in help_


@pytest.mark.parametrize("key", sorted(PROBES), ids=[" ".join(k) for k in sorted(PROBES)])
def test_every_range_option_reads_the_unit_on_both_ends(capsys, key):
    probe, lo, hi, n, unit, per = PROBES[key]
    tail = "" if n is None else f":{n}"
    only_hi = probe(capsys, f"{lo}:{hi} {unit}{tail}")
    both = probe(capsys, f"{lo} {unit}:{hi} {unit}{tail}")
    only_lo = probe(capsys, f"{lo} {unit}:{hi}{tail}")
    want = [lo * per, hi * per] if n is None else list(np.linspace(lo * per, hi * per, n))
    assert list(only_hi) == list(both) == list(only_lo)
    assert list(both) == pytest.approx(want, rel=1e-12)


@pytest.mark.parametrize("key", [k for k in sorted(PROBES) if PROBES[k][3] is not None],
                         ids=[" ".join(k) for k in sorted(PROBES) if PROBES[k][3] is not None])
def test_every_range_option_refuses_n_zero_in_one_line(capsys, key):
    option = key[1]
    probe, lo, hi, n, unit, per = PROBES[key]
    text = f"{lo}:{hi} {unit}:0"
    with pytest.raises((ConfigError, Refused)) as e:
        probe(capsys, text)
    msg = str(e.value)
    assert "\n" not in msg and f"{option}" in msg and f"{text!r}: N must be an integer >= " in msg
