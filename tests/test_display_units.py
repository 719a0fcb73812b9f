"""Units in and out: text and figures in the units the user wrote (or --units), JSON in
SI; --grade G with its ISO 1940 class; ball angles wrapped in the summary."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.cli.common import class_text, grade_text
from autobalance.config import ConfigError, load_config, parse_quantity
from autobalance.config.display import DISPLAY_KINDS, display_units, written_unit
from autobalance.simulate.result import wrap_degrees

CENTRIFUGE = "examples/centrifuge.toml"
TOPLOADER = "examples/toploader.toml"
# the centrifuge's TSR profile shortened to 12 s (run-up 6 s, plateau 2 s)
SHORT = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s",
         "profile.plateau_time=2 s", "profile.up_time=1 s"]
runner = CliRunner()


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


def sets(items):
    return [x for s in items for x in ("--set", s)]


def assert_one_line_error(stderr: str, *needles: str):
    lines = stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:"), stderr
    for n in needles:
        assert n in lines[0], stderr


# -- display_units: as written ----------------------------------------------------------------
def test_units_as_written_in_the_example_machines():
    c = load_config(CENTRIFUGE)
    u = display_units(c)
    assert (u.unit("speed"), u.unit("unbalance"), u.unit("length"), u.unit("mass"),
            u.unit("time"), u.unit("grade")) == ("rpm", "g*m", "mm", "kg", "s", "mm/s")
    assert u.unit("force") == "N"                       # not written: SI
    assert u.fmt(c.spin.nominal_speed, "speed") == "4000 rpm"
    assert u.fmt(c.system.rotor.unbalance, "unbalance") == "0.573 g*m"
    assert u.fmt(c.system.balancer.race_radius, "length") == "45 mm"
    t = display_units(load_config(TOPLOADER))
    assert t.fmt(load_config(TOPLOADER).system.rotor.unbalance, "unbalance") == "0.05 kg*m"
    assert t.fmt(load_config(TOPLOADER).spin.nominal_speed, "speed") == "800 rpm"


def test_set_override_is_as_written_too():
    c = load_config(CENTRIFUGE, ["profile.nominal=70 Hz", "rotor.unbalance=30 g*cm"])
    u = display_units(c)
    # Hz are cycles per second, as in the config: 70 Hz in, 70 Hz out (not 70 / 2 pi)
    assert u.fmt(c.spin.nominal_speed, "speed") == "70 Hz"
    assert u.fmt(c.system.rotor.unbalance, "unbalance") == "30 g*cm"


def test_bare_numbers_and_no_config_are_si():
    c = load_config(CENTRIFUGE, ["profile.nominal=418.879", "rotor.unbalance=0.000573"])
    assert display_units(c).unit("speed") == "rpm"      # the plateau is still written in rpm
    c = load_config(CENTRIFUGE, ["profile.nominal=418.879", "profile.plateau=61.26",
                                 "rotor.unbalance=0.000573"])
    u = display_units(c)
    assert u.unit("speed") == "rad/s" and u.unit("unbalance") == "kg*m"
    assert display_units(None).units == DISPLAY_KINDS


_UNITS = {"speed": ["rpm", "Hz", "rad/s", "kHz", "deg/s"], "unbalance": ["g*m", "g*cm", "kg*mm"],
          "length": ["mm", "um", "cm"], "mass": ["g", "kg"], "force": ["N", "kN", "mN"],
          "time": ["s", "min", "ms"]}


@settings(max_examples=60, deadline=None)
@given(kind=st.sampled_from(sorted(_UNITS)), data=st.data(),
       x=st.floats(min_value=1e-3, max_value=1e5, allow_nan=False))
def test_written_value_round_trips(kind, data, x):
    """Any value written with a unit is shown back as written: parse (config) then display."""
    unit = data.draw(st.sampled_from(_UNITS[kind]))
    text = f"{x!r} {unit}"
    assert written_unit(text, kind) == unit
    u = display_units({"rotor": {"unbalance": text}} if kind == "unbalance" else
                      {"profile": {"nominal": text}} if kind == "speed" else
                      {"balancer": {"race_radius": text}} if kind == "length" else
                      {"rotor": {"mass": text}} if kind == "mass" else
                      {"suspension": {"dry_friction_force": text}} if kind == "force" else
                      {"profile": {"duration": text}})
    assert u.unit(kind) == unit
    assert u.to(parse_quantity(text, kind), kind) == pytest.approx(x, rel=1e-12)


# -- --units choice -----------------------------------------------------------------------------
def test_units_choice():
    c = load_config(CENTRIFUGE)
    si = display_units(c, "si")
    assert si.units == DISPLAY_KINDS
    assert si.fmt(c.spin.nominal_speed, "speed") == "418.9 rad/s"
    u = display_units(c, "speed=Hz, unbalance=g*mm")
    assert u.fmt(c.spin.nominal_speed, "speed") == "66.67 Hz"       # 4000 rpm
    assert u.fmt(c.system.rotor.unbalance, "unbalance") == "573 g*mm"
    assert u.unit("length") == "mm"                                # not chosen: as written
    assert display_units(c, "grade=mm/s").unit("grade") == "mm/s"


@pytest.mark.parametrize("choice, why", [
    ("speed=kg", "not a rotational speed unit"), ("colour=rpm", "unknown kind 'colour'"),
    ("speed", "not kind=unit"), ("grade=m/s", "always shown in mm/s"), ("", "no kind=unit"),
    ("speed=rpm,speed=Hz", "given twice"), ("unbalance=parsec", "not an unbalance unit")])
def test_bad_units_choice_one_line(choice, why):
    with pytest.raises(ConfigError) as e:
        display_units(load_config(CENTRIFUGE), choice)
    msg = str(e.value)
    assert "\n" not in msg and msg.startswith(f"--units = {choice!r}") and why in msg
    assert "allowed: 'si' or a comma list of kind=unit" in msg


def test_bad_units_and_grade_on_the_command_line_exit_2_before_running():
    r = run("simulate", CENTRIFUGE, "--units", "speed=furlong", "--json")
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, "--units", "speed=furlong", "allowed")
    r = run("simulate", CENTRIFUGE, "--grade", "-3", "--json")
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, "--grade", "-3")
    r = run("sweep", "no_such.toml", "--store", "x", "--grade", "0")
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, "--grade")


# -- grades and classes -------------------------------------------------------------------------
def test_grade_text_and_class():
    assert grade_text(16.0).startswith("G16 (ISO 1940 class G16")
    assert grade_text(6.3).startswith("G6.3 (ISO 1940 class G6.3")
    assert grade_text(10.0) == "G10 (not an ISO 1940 class; meets class G16)"
    assert "above the coarsest ISO 1940 class, G4000" in grade_text(5000.0)
    assert class_text(1.352) == "G2.5" and class_text(16.0) == "G16"
    assert class_text(16.5) == "G40" and class_text(1e5) == "above G4000"
    assert class_text(float("nan")) == "-"


# -- wrapped angles -----------------------------------------------------------------------------
def test_wrap_degrees_examples():
    assert wrap_degrees(-578.0) == pytest.approx(142.0)
    assert wrap_degrees(180.0) == 180.0 and wrap_degrees(-180.0) == 180.0
    assert wrap_degrees(-1225.9) == pytest.approx(-145.9)


@settings(max_examples=200, deadline=None)
@given(a=st.floats(min_value=-1e5, max_value=1e5, allow_nan=False))
def test_wrap_degrees_property(a):
    w = float(wrap_degrees(a))
    assert -180.0 < w <= 180.0
    turns = (a - w) / 360.0
    assert abs(turns - round(turns)) < 1e-9 * max(1.0, abs(turns))


# -- simulate end to end ------------------------------------------------------------------------
@pytest.fixture(scope="module")
def centrifuge_run(tmp_path_factory):
    """The 12 s centrifuge run, as JSON with its NetCDF history, and as text."""
    nc = tmp_path_factory.mktemp("run") / "c.nc"
    r = run("simulate", CENTRIFUGE, *sets(SHORT), "--grade", "6.3", "--out", nc, "--json")
    assert r.exit_code == 0, r.stderr
    t = run("simulate", CENTRIFUGE, *sets(SHORT), "--grade", "6.3")
    assert t.exit_code == 0, t.stderr
    return json.loads(r.stdout), nc, t.stdout


def test_simulate_json_stays_si_with_the_grade_and_classes(centrifuge_run):
    d, _, _ = centrifuge_run
    assert d["nominal_speed_rad_s"] == pytest.approx(4000 * 2 * math.pi / 60)
    assert d["grade_limit_mm_s"] == 6.3
    g = d["final"]["grade_G_mm_s"]
    assert d["meets_grade_limit"] == (g <= 6.3)
    for point in [d["final"], *d["checkpoints"]]:
        c = point["iso_class_G_mm_s"]
        k = [0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0, 250.0, 630.0, 1600.0, 4000.0].index(c)
        assert point["grade_G_mm_s"] <= c and (k == 0 or point["grade_G_mm_s"] > [
            0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0, 250.0, 630.0, 1600.0][k - 1])


def test_simulate_ball_angles_wrapped_history_unwrapped(centrifuge_run):
    import xarray as xr

    d, nc, _ = centrifuge_run
    with xr.open_dataset(nc) as ds:
        alpha = np.degrees(ds["alpha"].values)          # the NetCDF keeps the unwrapped history
        t = ds["time"].values
    assert np.abs(alpha).max() > 180.0                  # the balls went round during the run
    for point in [d["final"], *d["checkpoints"]]:
        k = int(np.argmin(np.abs(t - point["time_s"])))
        wrapped = np.array(point["ball_angles_deg"])
        assert ((wrapped > -180) & (wrapped <= 180)).all()
        turns = (alpha[k] - wrapped) / 360.0
        np.testing.assert_allclose(turns, np.round(turns), atol=1e-9)


def test_simulate_text_in_written_units_with_classes(centrifuge_run):
    d, _, text = centrifuge_run
    assert "target grade                     G6.3 (ISO 1940 class G6.3" in text
    assert "nominal_speed                    4000 rpm" in text
    res = 1e3 * d["final"]["residual_unbalance_kg_m"]               # g*m
    assert f"residual_unbalance             {res:.4g} g*m" in text
    cls = class_text(d["final"]["grade_G_mm_s"])
    verdict = "meets" if d["final"]["grade_G_mm_s"] <= 6.3 else "above"
    assert f"(ISO class {cls}; {verdict} G6.3)" in text
    assert "rad_s" not in text and "kg_m" not in text


def test_simulate_units_choice_in_text():
    r = run("simulate", CENTRIFUGE, *sets(SHORT), "--units", "speed=Hz,unbalance=g*mm")
    assert r.exit_code == 0, r.stderr
    assert "nominal_speed                    66.67 Hz" in r.stdout
    assert " g*mm" in r.stdout
    r = run("simulate", CENTRIFUGE, *sets(SHORT), "--units", "si")
    assert "nominal_speed                    418.9 rad/s" in r.stdout


@pytest.mark.slow
def test_simulate_plot_speed_axis_and_grade_line(tmp_path, monkeypatch):
    """--plot draws the spin speed in the written unit and the grade line at --grade with its
    class: the figure the command saved is inspected."""
    import autobalance.plotting as plotting

    figures = []
    real = plotting.plot_run

    def spy(sim, **kw):
        fig = real(sim, **kw)
        figures.append(fig)
        return fig

    monkeypatch.setattr(plotting, "plot_run", spy)      # the figure the CLI draws (and saves)
    png = tmp_path / "c.png"
    r = run("simulate", CENTRIFUGE, *sets(SHORT), "--grade", "2.5", "--plot", png)
    assert r.exit_code == 0, r.stderr
    assert png.stat().st_size > 0
    (fig,) = figures
    labels = {ax.get_ylabel(): ax for ax in fig.axes}
    speed_ax = labels["spin speed [rpm]"]
    assert max(line.get_ydata().max() for line in speed_ax.lines) == pytest.approx(4000.0)
    grade_ax = labels["grade G [mm/s]"]
    limit = [line for line in grade_ax.lines if line.get_label().startswith("G2.5")]
    assert len(limit) == 1 and limit[0].get_label() == grade_text(2.5)
    assert list(limit[0].get_ydata()) == [2.5, 2.5]


# -- refusals in the units the user wrote (config/display.as_written) ----------------------------
@settings(max_examples=40, deadline=None)
@given(rpm=st.floats(1.0, 1e5), limit=st.floats(1.0, 1e4))
def test_a_refusal_shows_its_value_as_written(rpm, limit):
    """A refusal ``key = <SI>: ... <x> rad/s`` of a key written in rpm reads ``key = <as
    written> (<SI> rad/s): ... <x> rad/s (<x in rpm> rpm)``: the written text itself, and the
    bound converted to 4 digits."""
    from autobalance.config.display import as_written

    text = f"{rpm!r} rpm"
    si = rpm * 2 * math.pi / 60
    msg = f"profile.speed = {si!r}: must be >= {limit:.6g} rad/s here"
    got = as_written(msg, {"profile": {"speed": text}})
    head, tail = got.split(": ", 1)
    assert head == f"profile.speed = {text} ({si:.6g} rad/s)"
    shown = float(tail.split("rad/s (")[1].split(" rpm)")[0])
    assert shown == pytest.approx(float(f"{limit:.6g}") * 60 / (2 * math.pi), rel=5e-4)


def test_a_refusal_is_unchanged_unless_its_value_is_the_written_one():
    """Bare numbers (SI as written), a refused number that is not the written value (a derived
    one), a key of no display kind and no configuration leave the message as it is."""
    from autobalance.config.display import as_written

    raw = {"rotor": {"mass": "-2 g"}, "balancer": {"race_radius": -0.1},
           "liquid": {"partitions": 2}}
    assert as_written("rotor.mass = -0.003: must be > 0", raw) == "rotor.mass = -0.003: must be > 0"
    assert as_written("balancer.race_radius = -0.1: must be > 0", raw).startswith(
        "balancer.race_radius = -0.1: ")
    assert as_written("liquid.partitions = 2: must be 0 or >= 3", raw).startswith(
        "liquid.partitions = 2: ")
    assert as_written("rotor.mass = -0.002: must be > 0", None) == "rotor.mass = -0.002: must be > 0"
    assert as_written("rotor.mass = -0.002: must be > 0", raw) == \
        "rotor.mass = -2 g (-0.002 kg): must be > 0"


def test_cli_refusals_speak_the_written_units():
    """End to end: a bad value at load time (the model's check) and a refusal after loading (a
    motor drive on a horizontal axis that ends below the film's start, before any work) both
    name the value as written and, for the second, the film's start speed in rpm too; one
    line, exit 2."""
    r = run("simulate", "washer_000", *sets(["rotor.mass=-2 g"]))
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, "rotor.mass = -2 g (-0.002 kg): must be > 0")
    r = run("simulate", "examples/toploader-ring.toml", "--profile", "motor",
            *sets(["profile.law=linear", "profile.torque=25 N*m", "profile.final_speed=150 rpm",
                   "profile.initial_speed=30 rpm", "profile.duration=5 s",
                   "rotor.polar_inertia=0.5 kg*m^2", "liquid.axis=horizontal",
                   "gravity.g=9.81"]))
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, "profile.final_speed = 150 rpm (15.708 rad/s)",
                          "19.06 rad/s (182 rpm)")


def test_the_entry_point_shows_the_liquid_groups_refusals_as_written(capsys):
    """The liquid group raises its errors to autobalance's entry point (main), which prints
    them as the other commands do: the value as written, its SI value beside it."""
    from autobalance.cli import main

    with pytest.raises(SystemExit) as e:
        main(["liquid", "stability", "--set", "liquid.volume=-3 ml"])
    assert e.value.code == 2
    assert_one_line_error(capsys.readouterr().err,
                          "liquid.volume = -3 ml (-3e-06 m^3): must be > 0")
