"""The Monte-Carlo studies and ``design`` on a motor-driven machine (``[profile] kind =
"motor"``, 000 eq 15-18): each runs end to end (text, JSON, --out NetCDF, --plot) or refuses in
one line naming what it needs. The machine is small so that a run takes a fraction of a second:
2 kg on 8 N/mm (10 Hz), two 5 g balls on R = 30 mm, a linear-law motor of 0.3 N*m to 1200 rpm
held at 95 % (reached at 2.5 s), 4 s."""
from __future__ import annotations

import json
import math

import pytest
import xarray as xr
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.config import load_config
from autobalance.models import MotorDrive, ParameterError
from autobalance.studies._plateau import compute_descent, compute_plateau
from autobalance.studies._sensitivity import default_variants
from autobalance.studies._start_positions import compute_machine, compute_monte_carlo
from autobalance.studies.statistics import plateau_speed, profile_text

MACHINE = """\
name = "small_motor"
description = "2 kg rotor on 8 N/mm, 2 x 5 g balls on R = 30 mm, linear motor to 1200 rpm"

[rotor]
mass = "2 kg"
unbalance = "10 g*cm"
polar_inertia = "0.002 kg*m^2"

[suspension]
kx = "8 N/mm"
ky = "8 N/mm"
cx = "12 N*s/m"
cy = "12 N*s/m"

[balancer]
n_balls = 2
ball_mass = "5 g"
race_radius = "30 mm"
ball_radius = "5.4 mm"
element = "point"
damping = "0.05 N*mm*s/rad"
rolling_resistance = 0.002

[profile]
kind = "motor"
law = "linear"
torque = "0.3 N*m"
hold_fraction = 0.95
final_speed = "1200 rpm"
duration = "4 s"

[initial]
ball_angles = ["45 deg", "135 deg"]

[options]
friction_law = "stick"
"""

runner = CliRunner()
FAST = ["--executor", "serial"]


@pytest.fixture(scope="module")
def motor(tmp_path_factory):
    path = tmp_path_factory.mktemp("motor") / "small_motor.toml"
    path.write_text(MACHINE, encoding="utf-8")
    return str(path)


def _run(*args):
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == 0, r.output
    return r


def _json(*args):
    return json.loads(_run(*args, "--json").stdout)


def _refusal(*args, words=()):
    r = runner.invoke(app, [str(a) for a in args])
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    assert "Traceback" not in r.output
    for w in words:
        assert w in lines[0], lines[0]
    return lines[0]


# -- the pieces that assumed a knot table ------------------------------------------------------
def test_profile_text_names_the_motor_drive(motor):
    spin = load_config(motor).spin
    assert isinstance(spin, MotorDrive)
    assert profile_text(spin) == ("motor: linear law, T0 = 0.3 N*m to 20.0 Hz (held at 95 %), "
                                  "from 0.0 Hz, 4 s")
    assert profile_text(load_config("vub_jeffcott_004").spin).startswith("0 s: 0.0 Hz; 18 s")


def test_plateau_speed_refuses_a_motor_drive_and_a_profile_without_one(motor):
    with pytest.raises(ParameterError, match="motor drive has no speed plateau"):
        plateau_speed(load_config(motor).spin)
    with pytest.raises(ParameterError, match="no speed after its first read-out"):
        plateau_speed(load_config("washer_000").spin)
    assert plateau_speed(load_config("vub_jeffcott_004").spin) == pytest.approx(2 * math.pi * 100)


def test_the_studies_that_vary_a_tsr_refuse_a_motor_drive_before_any_run(motor):
    cfg = load_config(motor)
    for fn, what in ((compute_plateau, "the plateau study"), (compute_descent, "the descent")):
        with pytest.raises(ParameterError, match=f"{what} needs a temporary speed reduction: "
                                                 "a motor drive's speed follows its torque law"):
            fn(cfg)
    with pytest.raises(ParameterError, match="motor drive has no speed plateau"):
        compute_monte_carlo(cfg, n=2)
    with pytest.raises(ParameterError, match="outcome of the run"):
        compute_machine(cfg)


def test_plateau_cli_refuses_a_motor_drive_in_one_line(motor):
    _refusal("study", "plateau", motor, "--quick", *FAST,
             words=("profile.kind = 'motor'", "plateau study", "torque law", "tsr"))


def test_design_without_its_profile_variants_refuses_them_in_one_line(motor):
    _refusal("design", motor, "--quick", "--profiles", "std", *FAST,
             words=("motor profile", "given"))


def test_sensitivity_varies_the_motor_run_up_through_its_torque(motor):
    v = default_variants(load_config(motor))
    assert v["run-up x0.78"] == [f"profile.torque={0.3 / 0.78!r}"]
    assert not [k for k in v if "plateau" in k]
    # a prescribed profile keeps its run-up time
    assert default_variants("vub_jeffcott_004")["run-up x0.78"][0].startswith("profile.runup_time=")


# -- end to end --------------------------------------------------------------------------------
@pytest.mark.slow
def test_start_positions_on_a_motor_drive(motor, tmp_path):
    text = _run("study", "start-positions", motor, "--starts", 3, *FAST).stdout
    assert "small_motor: 6 runs (start grid, 3 positions per ball), 0 failed" in text
    assert "t = 4 s: G p5/p50/p95" in text and "warning" not in text
    out, png = tmp_path / "sp.nc", tmp_path / "sp.png"
    d = _json("study", "start-positions", motor, "--starts", 3, *FAST, "--out", out, "--plot", png)
    assert d["runs"] == 6 and d["failed"] == 0 and d["warnings"] == []
    (c,) = d["checkpoints"]                       # one read-out: the end of the run
    assert c["label"] == "t=4 s" and c["time_s"] == 4.0
    assert 0 <= c["p5_grade_G_mm_s"] <= c["p95_grade_G_mm_s"] < d["G_balls_mm_s"]
    assert "regions" not in d                     # 004's regions need two read-outs
    with xr.open_dataset(out) as ds:
        assert ds.attrs["profile"].startswith("motor: linear law")
        assert ds.sizes["checkpoint"] == 1 and ds.sizes["sample"] == 6
    assert png.stat().st_size > 10_000


@pytest.mark.slow
def test_unbalance_range_on_a_motor_drive(motor, tmp_path):
    args = ("study", "unbalance-range", motor, "--starts", 2, "--steps", 2, *FAST)
    text = _run(*args).stdout
    assert "in 3 steps x 2 starts per ball" in text and "t=4 s: valid initial unbalance" in text
    out, png = tmp_path / "ur.nc", tmp_path / "ur.png"
    d = _json(*args, "--out", out, "--plot", png)
    assert list(d["cases"]["nominal"]) == ["t=4 s"] and len(d["G_ini_mm_s"]) == 3
    with xr.open_dataset(out) as ds:
        assert list(ds["procedure"].values) == ["t=4 s"]
        assert ds.attrs["profile"].startswith("motor:")
    assert png.stat().st_size > 10_000


@pytest.mark.slow
def test_sensitivity_on_a_motor_drive(motor, tmp_path):
    args = ("study", "sensitivity", motor, "--starts", 2, "--vary", "profile.torque=0.4 N*m", *FAST)
    text = _run(*args).stdout
    assert "3 runs per variant" in text and "profile.torque=0.4 N*m:" in text
    out = tmp_path / "sens.nc"
    d = _json(*args, "--out", out)
    assert d["runs_used"] == 3 and list(d["variants"]) == ["profile.torque=0.4 N*m"]
    with xr.open_dataset(out) as ds:
        assert list(ds["variant"].values) == ["base", "profile.torque=0.4 N*m"]
        assert ds.sizes["checkpoint"] == 1


@pytest.mark.slow
def test_runup_on_a_motor_drive(motor, tmp_path):
    text = _run("study", "runup", motor, "--law", "constant,linear").stdout
    assert "constant: full speed at" in text and "linear: full speed at" in text
    out, png = tmp_path / "ru.nc", tmp_path / "ru.png"
    d = _json("study", "runup", motor, "--law", "constant,linear", "--out", out, "--plot", png)
    lin = d["cases"]["linear"]
    # 000 eq 15: the loaded drive is slower than the unloaded closed form, by little
    assert lin["t_speed_unloaded_s"] <= lin["t_speed_s"] <= 1.1 * lin["t_speed_unloaded_s"]
    with xr.open_dataset(out) as ds:
        assert list(ds["case"].values) == ["constant", "linear"] and ds.attrs["motor"] == 1
    assert png.stat().st_size > 10_000


@pytest.mark.slow
def test_design_on_a_motor_drive(motor, tmp_path):
    out, png = tmp_path / "design.nc", tmp_path / "design.png"
    d = _json("design", motor, "--quick", "--random", 2, "--n-unbalance", 2, "--balls", 2,
              "--capacity", 1.5, *FAST, "--out", out, "--plot", png)
    (row,) = d["designs"]                  # decided or not with 2 starts: it ran on the motor
    assert d["n_designs"] == 1 and row["profile"] == "given" and row["duration_s"] == 4.0
    assert row["worst_quantile_grade_G_mm_s"] > 0 and d["warnings"] == []
    with xr.open_dataset(out) as ds:
        assert list(ds["profile"].values) == ["given"]
    assert png.stat().st_size > 10_000


@pytest.mark.slow
def test_a_warned_motor_machine_still_runs_and_says_so(motor):
    sets = ["--set", "balancer.n_balls=1", "--set", "initial.ball_angles=[0]"]
    text = _run("study", "start-positions", motor, "--starts", 2, *FAST, *sets).stdout
    assert text.splitlines()[0].startswith("warning: one ball cancels the unbalance only")
    d = _json("study", "start-positions", motor, "--starts", 2, *FAST, *sets)
    assert len(d["warnings"]) == 1 and d["runs"] == 2
