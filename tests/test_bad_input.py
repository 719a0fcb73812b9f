"""Reported bad-input bugs: each is refused with one line (field, value, what is allowed), exit
code 2 in the CLI, before anything is allocated or integrated - never a silently wrong result,
a traceback or a hang."""
from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import pytest
from typer.testing import CliRunner

import autobalance as ab
from autobalance.cli import app
from autobalance.config import ConfigError, load_config
from autobalance.limits import ResourceError
from autobalance.models import ParameterError, SpeedProfile
from autobalance.simulate import simulate, simulate_batch

runner = CliRunner()
EXE = Path(sys.executable).with_name("autobalance")
TWO_PI = 2 * math.pi


def run(*args):
    return runner.invoke(app, [str(a) for a in args])


def assert_refused(r, field: str):
    """Exit 2, exactly one stderr line ``error: ...`` naming ``field``, no traceback."""
    stderr = r.stderr
    lines = stderr.strip().splitlines()
    code = r.exit_code if hasattr(r, "exit_code") else r.returncode
    assert code == 2, (code, stderr, getattr(r, "exception", None))
    assert len(lines) == 1, stderr
    assert lines[0].startswith("error:") and field in lines[0], stderr
    assert "Traceback" not in stderr and r.stdout == ""


def run_exe(*args, env=None):
    return subprocess.run([str(EXE), *map(str, args)], capture_output=True, text=True,
                          timeout=120, env={**os.environ, **(env or {})})


# -- 1. profile semantics ---------------------------------------------------------------------
@pytest.mark.parametrize("plateau", ["167 Hz", "200 Hz"])
def test_tsr_plateau_must_be_below_nominal(plateau):
    r = run("show", "vub_jeffcott_004", "--set", f"profile.plateau={plateau}")
    assert_refused(r, "profile.plateau")
    assert "must be below profile.nominal" in r.stderr
    with pytest.raises(ParameterError, match=r"^profile\.plateau = .*below profile\.nominal"):
        SpeedProfile.tsr(nominal=TWO_PI * 100.0, plateau=TWO_PI * 100.0)


def test_a_constant_profile_refuses_another_start_speed():
    """SpeedProfile.constant(start_speed=) other than the speed is refused, not ignored: a run
    meant to start elsewhere does not silently start at full speed."""
    assert ab.SpeedProfile.constant(100.0, 1.0, start_speed=100.0).speeds == (100.0, 100.0)
    with pytest.raises(ab.ParameterError) as e:
        ab.SpeedProfile.constant(100.0, 1.0, start_speed=50.0)
    assert e.value.field == "profile.start_speed" and "ramp" in str(e.value)


def test_tsr_default_knots_unchanged():
    """The 004 presets and studies use runup_time = runup_fraction * duration (or none): same
    knots as before the run-up-hold fix."""
    p = SpeedProfile.tsr()
    assert p.times == (0.0, 18.0, 28.0, 48.0, 58.0, 90.0)
    assert p.speeds == (0.0, TWO_PI * 167.0, TWO_PI * 100.0, TWO_PI * 100.0, TWO_PI * 167.0,
                        TWO_PI * 167.0)
    assert p.checkpoints == (18.0, 90.0)
    assert SpeedProfile.tsr(runup_time=18.0) == p
    s = SpeedProfile.standard_runup()
    assert s.times == (0.0, 18.0, 90.0) and s.checkpoints == (18.0, 90.0)
    cfg = load_config("vub_jeffcott_004")
    assert cfg.spin.times == p.times and cfg.spin.speeds == p.speeds


def test_tsr_short_runup_keeps_the_hold_at_nominal():
    """runup_time < runup_fraction x duration: hold nominal to the STD read-out (18 s), then the
    reduction - not a ramp down from 12 s with the read-out taken at 141.9 Hz."""
    cfg = load_config("vub_jeffcott_004", ["profile.runup_time=12 s"])
    assert cfg.spin.times == (0.0, 12.0, 18.0, 28.0, 48.0, 58.0, 90.0)
    assert cfg.spin.checkpoints[0] == 18.0
    assert float(cfg.spin.speed(18.0)) == TWO_PI * 167.0
    assert float(cfg.spin.speed(28.0)) == TWO_PI * 100.0
    std = SpeedProfile.standard_runup(runup_time=12.0)
    assert std.times == (0.0, 12.0, 90.0) and float(std.speed(18.0)) == TWO_PI * 167.0


@pytest.mark.parametrize("kind", ["std", "tsr"])
def test_std_tsr_need_nominal_in_a_config(kind):
    r = run("show", "washer_000", "--profile", kind)
    assert_refused(r, "profile.nominal")
    assert "profile.nominal: missing; required" in r.stderr
    # given: fine (and the preset that has it still loads)
    r = run("show", "washer_000", "--profile", kind, "--set", "profile.nominal=167 Hz",
            "--set", "profile.duration=90 s")
    assert r.exit_code == 0, r.stderr
    assert load_config("vub_jeffcott_004", [f"profile.kind={kind}"]).spin.nominal_speed \
        == pytest.approx(TWO_PI * 167.0)


def test_std_nominal_missing_in_a_file(tmp_path):
    toml = tmp_path / "m.toml"
    from autobalance.config import preset_path

    body = preset_path("vub_jeffcott_004").read_text()
    body = "\n".join(line for line in body.splitlines() if not line.startswith("nominal"))
    toml.write_text(body)
    with pytest.raises(ConfigError, match=r"^profile\.nominal: missing; required"):
        load_config(str(toml))
    # an unknown key is still reported before the missing one
    with pytest.raises(ConfigError, match=r"^profile\.speed: unknown key for kind 'std'"):
        load_config("washer_000", ["profile.speed=10 Hz", "profile.kind=std"])


# -- 2. physical ranges -----------------------------------------------------------------------
@pytest.mark.parametrize("field,value", [("rolling_resistance", "5"), ("stiction", "-0.1"),
                                         ("stiction", "1.5")])
def test_friction_coefficients_within_0_1(field, value):
    r = run("show", "vub_jeffcott_004", "--set", f"balancer.{field}={value}")
    assert_refused(r, f"balancer.{field}")
    assert "[0, 1]" in r.stderr and "0.001-0.01" in r.stderr


def test_friction_coefficient_per_ball_names_the_ball():
    with pytest.raises(ParameterError, match=r"^balancer\.rolling_resistance\[1\] = 2"):
        ab.BallBalancer(2, 0.0076, 0.035, 0.00614, rolling_resistance=(0.002, 2.0))


@pytest.mark.parametrize("n", ["1e12", "1e9", "100", "inf"])
def test_n_balls_huge_is_refused_at_once(n):
    r = run("show", "vub_jeffcott_004", "--set", f"balancer.n_balls={n}")
    assert_refused(r, "balancer.n_balls")
    if n != "inf":
        assert "AUTOBALANCE_MAX_BALLS" in r.stderr


@pytest.mark.slow
def test_n_balls_from_toml_file_is_refused_quickly(tmp_path):
    from autobalance.config import preset_path

    body = preset_path("vub_jeffcott_004").read_text().replace("n_balls = 2 ", "n_balls = 1e9 ")
    toml = tmp_path / "many.toml"
    toml.write_text(body)
    r = run_exe("show", toml)
    assert_refused(r, "balancer.n_balls")
    assert "1000000000" in r.stderr and "64" in r.stderr


def test_n_balls_limit_is_a_setting(monkeypatch):
    monkeypatch.setenv("AUTOBALANCE_MAX_BALLS", "1")
    with pytest.raises(ConfigError, match=r"^balancer\.n_balls = 2: at most 1 balls"):
        load_config("vub_jeffcott_004")
    monkeypatch.setenv("AUTOBALANCE_MAX_BALLS", "200")
    with pytest.raises(ConfigError, match=r"do not fit in the race \(at most 17\)"):
        load_config("vub_jeffcott_004", ["balancer.n_balls=100"])


# -- 3. --grade -------------------------------------------------------------------------------
@pytest.mark.parametrize("grade", ["nan", "-5", "0", "inf"])
def test_sweep_grade_is_checked(grade, tmp_path):
    r = run("sweep", tmp_path / "none.toml", "--store", tmp_path / "s", "--grade", grade)
    assert_refused(r, "--grade")
    assert "ISO 1940 grade G > 0 [mm/s]" in r.stderr
    assert not (tmp_path / "s").exists()


def test_check_grade():
    from autobalance.cli.common import check_grade

    assert check_grade(16) == 16.0
    with pytest.raises(ConfigError, match=r"^--grade = nan: must be a finite ISO 1940 grade"):
        check_grade(float("nan"))


# -- 4. resource guards -----------------------------------------------------------------------
def test_tiny_save_dt_is_refused_before_allocating():
    r = run("simulate", "vub_jeffcott_004", "--set", "options.save_dt=1e-9 s")
    assert_refused(r, "options.save_dt")
    assert "AUTOBALANCE_MAX_MEMORY" in r.stderr


def test_huge_duration_is_refused_before_integrating():
    r = run("simulate", "vub_jeffcott_004", "--set", "profile.duration=1e12 s",
            "--set", "options.save_dt=-1")
    assert_refused(r, "profile.duration")
    assert "at most 1e+09 s" in r.stderr          # longer than any profile may describe
    cfg = load_config("vub_jeffcott_004", ["profile.duration=1e8 s"])   # ramps of 1e7 s
    opts = ab.SimOptions(save_dt=-1)
    with pytest.raises(ResourceError, match=r"^profile\.duration"):
        simulate(cfg.system, cfg.spin, options=opts)
    with pytest.raises(ResourceError, match=r"^profile\.duration"):
        simulate_batch([cfg.system] * 2, cfg.spin, options=opts)


def test_resource_checks_pass_the_presets():
    from autobalance.limits import check_run

    for name in ("vub_jeffcott_004", "washer_000"):
        cfg = load_config(name)
        assert check_run(cfg.system, cfg.spin, cfg.options) < cfg.options.max_steps


def test_immobility_n_conf_is_refused_before_allocating():
    r = run("study", "immobility", "vub_jeffcott_004", "--starts", "1000000")
    assert_refused(r, "--starts")
    from autobalance.papers.p004.tsr import immobility

    s = load_config("vub_jeffcott_004").system
    with pytest.raises(ResourceError, match=r"^n_conf = 1000000"):
        immobility(s, [100.0], 1_000_000)
    assert immobility(s, [TWO_PI * 50.0], 12).shape == (1,)


@pytest.mark.parametrize("spec", ["0:1500 rpm:1e9", "0:1500 rpm:1e12", "0:1500 rpm:2.5",
                                  "0:1500 rpm:-3", "0:1500 rpm:inf"])
def test_response_speed_count(spec):
    r = run("response", "vub_jeffcott_004", "--speeds", spec)
    assert_refused(r, "--speeds")


def test_response_speed_count_integral_float_accepted():
    r = run("response", "washer_000", "--speeds", "0:2000 rpm:1e1", "--json")
    assert r.exit_code == 0, r.stderr
    import json

    assert len(json.loads(r.stdout)["speed_rad_s"]) == 10


@pytest.mark.slow
def test_response_speed_count_memory_limit_is_a_setting():
    r = run_exe("response", "washer_000", "--speeds", "0:2000 rpm:100000",
                env={"AUTOBALANCE_MAX_MEMORY": "1 MB"})
    assert_refused(r, "--speeds")
    assert "AUTOBALANCE_MAX_MEMORY" in r.stderr


def test_reproduce_workers_bounded():
    r = run("reproduce", "--workers", "100000", "--out-dir", "unused-dir")
    assert_refused(r, "--workers")
    assert not Path("unused-dir").exists()


@pytest.mark.slow
def test_liquid_count_bounded():
    from autobalance.cli.liquid import app as liquid_app

    r = CliRunner().invoke(liquid_app, ["surface", "--speeds", "0:60 rad/s:1000000000"])
    assert isinstance(r.exception, ResourceError) and "--speeds" in str(r.exception)
    p = run_exe("liquid", "surface", "--speeds", "0:60 rad/s:1000000000")
    assert_refused(p, "--speeds")


# -- 5. output files checked before the work --------------------------------------------------
@pytest.mark.parametrize("opt,example", [("--out", "run.nc"), ("--plot", "plot.png")])
def test_simulate_output_is_a_directory(tmp_path, opt, example):
    r = run("simulate", "vub_jeffcott_004", opt, tmp_path)
    assert_refused(r, opt)
    assert f"is a directory; give a file name, e.g. {tmp_path / example}" in r.stderr
    assert "wall" not in r.stdout  # nothing simulated


@pytest.mark.slow
def test_simulate_output_not_writable(tmp_path):
    """A read-only directory / file (the kernel's permission check, made binding for root by
    dropping CAP_DAC_OVERRIDE in the child): refused before simulating."""
    from conftest import file_modes_bind

    ro = tmp_path / "ro"
    ro.mkdir()
    (ro / "x.png").write_bytes(b"")
    (ro / "x.png").chmod(0o444)
    ro.chmod(0o555)
    try:
        p = subprocess.run([str(EXE), "simulate", "vub_jeffcott_004", "--out", str(ro / "x.nc")],
                           capture_output=True, text=True, timeout=120, **file_modes_bind())
        assert_refused(p, "--out")
        assert f"directory {str(ro)!r} is not writable" in p.stderr
        p = subprocess.run([str(EXE), "simulate", "vub_jeffcott_004", "--plot", str(ro / "x.png")],
                           capture_output=True, text=True, timeout=120, **file_modes_bind())
        assert_refused(p, "--plot")
        assert "the file is not writable" in p.stderr
    finally:
        ro.chmod(0o755)


def test_analyze_plot_is_checked_first(tmp_path):
    r = run("analyze", "kinetic-static", "washer_000", "--plot", tmp_path)
    assert_refused(r, "--plot")
    r = run("analyze", "forces", "washer_000", "--damping-plot", tmp_path / "none" / "f.png")
    assert_refused(r, "--damping-plot")
    r = run("study", "immobility", "vub_jeffcott_004", "--plot", tmp_path)
    assert_refused(r, "--plot")


@pytest.mark.slow
def test_subprocess_out_directory(tmp_path):
    p = run_exe("simulate", "washer_000", "--out", tmp_path)
    assert_refused(p, "--out")
