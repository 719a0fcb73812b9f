"""``study runup`` (studies/_runup.py): the run-up of any machine with and without its balls.
The study answers 000's Table 1 questions for 000's washer exactly as the paper module's own
runs do, its time to speed meets the unloaded drive's closed form within the load of the
unbalance and balls (000 eq 15), and bad input is one line."""
from __future__ import annotations

import json
import math
from pathlib import Path

import pytest
import xarray as xr
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.config import from_models
from autobalance.models import InitialState, MotorDrive, ParameterError, SimOptions
from autobalance.papers.p000 import runup as p000
from autobalance.papers.p000.washer import W1000, washer
from autobalance.studies._runup import balancing_time, compute_runup, runup_summary

TOPLOADER = str(Path(__file__).resolve().parents[1] / "examples" / "toploader.toml")
runner = CliRunner()
MOTOR = ["profile.kind=motor", "profile.law=linear", "profile.torque=25 N*m",
         "profile.final_speed=1000 rpm", "profile.duration=12 s", "profile.hold_fraction=0.99"]


def _washer_cfg(law: str, hold: float):
    """000 Table 1's machine as a Config: two balls of m R = 0.025 kg m together at the bottom,
    gravity, T0 = 25 N m to 1000 rpm, histories every 2 ms (papers/p000/runup.runup)."""
    s = washer(Me=0.025, g=9.81)
    d = s.balancer.contact_angle
    start = (math.pi - d / 2 - 1e-3, math.pi + d / 2 + 1e-3)
    return from_models(s, MotorDrive(law, p000.T0, W1000, 25.0, hold_fraction=hold),
                       InitialState(ball_angles=start), SimOptions(save_dt=2e-3))


@pytest.mark.parametrize("laws,hold", [(("constant",), 1.0), (("linear", "harmonic"), 0.99)])
def test_the_study_answers_000_table1_as_the_paper_module_does(laws, hold):
    ds = compute_runup(_washer_cfg(laws[0], hold), laws=laws, bare=False, save_dt=2e-3)
    for law in laws:
        paper = p000._summary(p000.runup(0.025, law))
        c = runup_summary(ds)["cases"][law]
        assert c["t_speed_s"] == paper["t_f_s"]
        assert (c["x_max_m"], c["y_max_m"]) == (paper["x_max_m"], paper["y_max_m"])
        assert c["ball_revolutions"] == paper["revolutions"]
        assert c["final_grade_G_mm_s"] == paper["final_grade_G_mm_s"]


def test_time_to_speed_meets_the_closed_form_and_the_balls_change_the_whirl():
    ds = compute_runup("washer_000", laws=("constant", "linear"), sets=MOTOR)
    for law in ("constant", "linear"):
        d = ds.sel(case=law)
        # 000 eq 15: the unbalance and the balls load the drive by a few % (000 Table 1: t_f
        # 2.23 s against B_z w_f / T0 = 2.21 s); the simulated run-up is slower, not faster
        t, t0 = float(d["t_speed"]), float(d["t_speed_unloaded"])
        assert t0 <= t <= 1.05 * t0
        assert float(d["amplitude_ratio"]) == pytest.approx(
            float(d["max_amplitude"]) / float(d["max_amplitude_bare"]))
        assert float(d["max_amplitude"]) >= max(float(d["x_max"]), float(d["y_max"])) * (1 - 1e-12)
    assert ds["speed"].attrs["units"] == "rad/s" and ds["amplitude_bare"].dims == ("case", "time")


def test_balancing_time_is_the_last_time_above_the_threshold():
    t = [0.0, 1.0, 2.0, 3.0, 4.0]
    assert balancing_time(t, [0.0, 1.0, 0.2, 0.9, 0.01], 10.0, 0.05) == 3.0
    assert balancing_time(t, [0.0] * 5, 10.0) == 0.0


def test_a_prescribed_profile_runs_as_it_is():
    ds = compute_runup(TOPLOADER, bare=False)
    assert list(ds["case"].values) == ["std"] and "amplitude_bare" not in ds
    assert float(ds["t_speed"].sel(case="std")) == pytest.approx(20.0)     # 0.5 x 40 s
    assert math.isnan(float(ds["t_speed_unloaded"].sel(case="std")))
    with pytest.raises(ParameterError) as e:
        compute_runup(TOPLOADER, laws=("linear",))
    assert e.value.field == "laws" and "motor" in str(e.value)


@pytest.mark.slow
def test_cli_text_json_netcdf_and_plot(tmp_path):
    out, png = tmp_path / "r.nc", tmp_path / "r.png"
    args = ["study", "runup", "washer_000", *[x for s in MOTOR for x in ("--set", s)]]
    r = runner.invoke(app, [*args, "--law", "all", "--out", str(out), "--plot", str(png),
                            "--units", "speed=rpm"])
    assert r.exit_code == 0, r.output
    assert "constant: full speed at" in r.stdout and "harmonic: full speed never reached" in r.stdout
    assert "rpm" in r.stdout and png.stat().st_size > 10_000
    ds = xr.load_dataset(out)
    assert list(ds["case"].values) == ["constant", "linear", "harmonic"]
    assert ds.attrs["command"] == "study runup" and ds["max_amplitude"].attrs["units"] == "m"
    r = runner.invoke(app, [*args, "--json"])
    d = json.loads(r.stdout)
    assert set(d["cases"]) == {"linear"} and d["cases"]["linear"]["t_speed_s"] > 0


@pytest.mark.parametrize("extra,field", [
    (["--law", "cubic"], "--law"), (["--threshold", "0"], "--threshold"),
    (["--set", "balancer.n_balls=0", "--set", "initial.ball_angles=[]"], "balancer.n_balls")])
def test_bad_input_is_one_line(extra, field):
    r = runner.invoke(app, ["study", "runup", "washer_000", *[x for s in MOTOR for x in ("--set", s)],
                            *extra])
    assert r.exit_code == 2, r.output
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and field in lines[0], r.stderr
    r = runner.invoke(app, ["study", "runup", TOPLOADER, "--law", "linear"])
    assert r.exit_code == 2 and "motor" in r.stderr and len(r.stderr.strip().splitlines()) == 1
