"""Command line: JSON output, exit codes and one-line errors (autobalance.cli)."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.config import preset_path

runner = CliRunner()


def run(*args):
    return runner.invoke(app, list(args))


def run_main(*args):
    """The real entry point in a subprocess (python -m autobalance.cli)."""
    return subprocess.run([sys.executable, "-m", "autobalance.cli", *args],
                          capture_output=True, text=True, timeout=600)


def assert_one_line_error(stderr: str, field: str):
    lines = stderr.strip().splitlines()
    assert len(lines) == 1, stderr
    assert lines[0].startswith("error:") and field in lines[0], stderr
    assert "Traceback" not in stderr


# -- presets / show ---------------------------------------------------------------------------
def test_presets_json_lists_both():
    r = run("presets", "--json")
    assert r.exit_code == 0
    names = {p["name"] for p in json.loads(r.stdout)["presets"]}
    assert {"washer_000", "vub_jeffcott_004"} <= names


def test_presets_text():
    r = run("presets")
    assert r.exit_code == 0 and "washer_000" in r.stdout and "vub_jeffcott_004" in r.stdout


def test_show_json_si():
    r = run("show", "vub_jeffcott_004", "--json")
    assert r.exit_code == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["suspension"]["kx_N_m"] == pytest.approx(5.8e6)
    assert d["suspension"]["ky_N_m"] == pytest.approx(5.8e6)
    assert d["rotor"]["unbalance_kg_m"] == pytest.approx(16.53 * 19.3e-6)
    assert d["profile"]["nominal_rad_s"] == pytest.approx(2 * math.pi * 167)
    assert "Table 1" in d["sources"]["rotor.mass"]


def test_show_text_has_units_and_sources():
    r = run("show", "washer_000")
    assert r.exit_code == 0
    assert "kx_N_m" in r.stdout and "20 N/mm" in r.stdout and "000" in r.stdout


def test_show_set_and_profile():
    r = run("show", "washer_000", "--set", "suspension.kx=25 N/mm", "--profile", "ramp",
            "--set", "profile.start_speed=0", "--set", "profile.end_speed=1000 rpm",
            "--set", "profile.ramp_time=2 s", "--json")
    assert r.exit_code == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["suspension"]["kx_N_m"] == 25000.0 and d["profile"]["kind"] == "ramp"
    assert d["sources"]["suspension.kx"].startswith("--set")


def test_show_config_file(tmp_path):
    p = tmp_path / "mine.toml"
    p.write_text(preset_path("washer_000").read_text())
    r = run("show", str(p), "--json")
    assert r.exit_code == 0 and json.loads(r.stdout)["rotor"]["mass_kg"] == 37.0


# -- bad input: exit 2, one line on stderr ----------------------------------------------------
GOOD = {
    "rotor": 'mass = "10 kg"\nunbalance = "0.001 kg*m"',
    "suspension": 'kx = "10 N/mm"\nky = "10 N/mm"',
    "balancer": 'n_balls = 2\nball_mass = "5 g"\nrace_radius = "30 mm"\nball_radius = "3 mm"',
    "profile": 'kind = "constant"\nspeed = "100 Hz"\nduration = "1 s"',
    "initial": 'ball_angles = ["10 deg", "90 deg"]',
}


def toml_with(**sections) -> str:
    parts = []
    for name, body in {**GOOD, **sections}.items():
        if body is not None:
            parts.append(f"[{name}]\n{body}\n")
    return "\n".join(parts)


BAD_FILES = [
    ({"rotor": 'mass = "-5 kg"'}, "rotor.mass"),
    ({"rotor": "mass = 0"}, "rotor.mass"),
    ({"suspension": 'kx = "0 N/mm"\nky = 1'}, "suspension.kx"),
    ({"balancer": 'n_balls = 2\nball_mass = "5 g"\nrace_radius = "-30 mm"\nball_radius = "3 mm"'},
     "balancer.race_radius"),
    ({"rotor": 'mass = "nan"'}, "rotor.mass"),
    ({"rotor": "mass = nan"}, "rotor.mass"),
    ({"balancer": 'n_balls = 2\nball_mass = "5 g"\nrace_radius = "30 mm"\nball_radius = "3 mm"'
                  '\nfoo = 1'}, "balancer.foo"),
    ({"suspension": 'kx = "5 kg"\nky = 1'}, "suspension.kx"),
    ({"rotor": 'unbalance = "1 g*m"'}, "rotor.mass"),
    ({"profile": 'kind = "warp"'}, "profile.kind"),
    ({"initial": 'ball_angles = ["10 deg"]'}, "initial.ball_angles"),
]


@pytest.mark.parametrize("sections, field", BAD_FILES)
@pytest.mark.parametrize("command", ["show", "simulate"])
def test_bad_file_exit_2_one_line(tmp_path, sections, field, command):
    p = tmp_path / "bad.toml"
    p.write_text(toml_with(**sections))
    r = run(command, str(p))
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, field)
    assert r.stdout == ""


def test_good_file_is_valid(tmp_path):
    p = tmp_path / "good.toml"
    p.write_text(toml_with())
    r = run("show", str(p), "--json")
    assert r.exit_code == 0, r.stderr


def test_missing_rotor_mass_message(tmp_path):
    p = tmp_path / "bad.toml"
    p.write_text(toml_with(rotor='unbalance = "1 g*m"'))
    r = run("show", str(p))
    assert r.stderr.strip() == "error: rotor.mass: missing; required [kg]"


@pytest.mark.parametrize("args, field", [
    (["show", "nope"], "nope"),
    (["simulate", "nope", "--json"], "nope"),
    (["show", "washer_000", "--set", 'suspension.kx="5 kg"'], "suspension.kx"),
    (["show", "washer_000", "--set", "suspension.kx=5 kg"], "suspension.kx"),
    (["simulate", "washer_000", "--set", "suspension.kx=5 kg", "--json"], "suspension.kx"),
    (["show", "washer_000", "--set", "balancer.bogus=1"], "balancer.bogus"),
    (["show", "washer_000", "--set", "nonsense"], "nonsense"),
    (["show", "washer_000", "--profile", "warp"], "profile.kind"),
    (["show", "/nonexistent/dir/x.toml"], "x.toml"),
    (["response", "washer_000", "--speeds", "1:2"], "--speeds"),
    (["simulate", "washer_000", "--out", "/nonexistent/dir/x.nc"], "--out"),
    (["simulate", "washer_000", "--plot", "fig.xyz"], "--plot"),
])
def test_bad_arguments_exit_2(args, field):
    r = run(*args)
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, field)


def test_invalid_toml_exit_2(tmp_path):
    p = tmp_path / "broken.toml"
    p.write_text("[rotor\nmass = 1\n")
    r = run("show", str(p))
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, "invalid TOML")


@pytest.mark.slow
def test_main_entry_point_errors_no_traceback():
    r = run_main("show", "washer_000", "--set", 'suspension.kx="5 kg"')
    assert r.returncode == 2 and r.stdout == ""
    assert r.stderr.strip() == ("error: suspension.kx = '5 kg': expected a stiffness [N/m], "
                                "e.g. '20 N/mm'")
    r = run_main("simulate", "no_such_preset", "--json")
    assert r.returncode == 2 and r.stdout == ""
    assert_one_line_error(r.stderr, "no_such_preset")


@pytest.mark.slow
def test_main_entry_point_presets_json():
    r = run_main("presets", "--json")
    assert r.returncode == 0
    assert len(json.loads(r.stdout)["presets"]) >= 2


# -- end to end (need the physics modules) ----------------------------------------------------
@pytest.mark.slow
def test_simulate_json_and_files(tmp_path):
    nc, png = tmp_path / "w.nc", tmp_path / "w.png"
    r = run("simulate", "washer_000", "--set", "profile.duration=1 s", "--out", str(nc),
            "--plot", str(png), "--json")
    assert r.exit_code in (0, 1), r.stderr
    d = json.loads(r.stdout)  # exactly one JSON object
    assert "status" in d and d["files"]["netcdf"] == str(nc)
    assert (d["status"] == "ok") == (r.exit_code == 0)
    assert nc.stat().st_size > 0 and png.stat().st_size > 0
    import xarray as xr

    with xr.open_dataset(nc) as ds:
        assert "time" in ds.dims


def test_simulate_text_summary():
    r = run("simulate", "washer_000", "--set", "profile.duration=1 s")
    assert r.exit_code in (0, 1)
    assert "washer_000" in r.stdout and "status" in r.stdout


def test_simulate_failure_exit_1():
    r = run("simulate", "washer_000", "--set", "profile.duration=1 s",
            "--set", "options.max_steps=3", "--json")
    d = json.loads(r.stdout)
    assert d["status"] != "ok" and r.exit_code == 1


def test_response_json():
    r = run("response", "vub_jeffcott_004", "--json")
    assert r.exit_code == 0, r.stderr
    d = json.loads(r.stdout)
    assert len(d["speed_rad_s"]) == 200
    assert d["speed_rad_s"][-1] == pytest.approx(2 * 2 * math.pi * 167)
    assert d["natural_frequencies_hz"][0] == pytest.approx(94.2, abs=0.1)
    r = run("response", "washer_000", "--speeds", "0:2000 rpm:11", "--json")
    d = json.loads(r.stdout)
    assert len(d["amplitude_x_m"]) == 11
    assert d["speed_rad_s"][-1] == pytest.approx(2000 * math.pi / 30)


@pytest.mark.slow
def test_demo(tmp_path):
    out = tmp_path / "demo"
    r = run_main("demo", "--out-dir", str(out), "--json")
    assert r.returncode in (0, 1), r.stderr
    d = json.loads(r.stdout)
    assert json.loads((out / "summary.json").read_text()) == d
    for name in ("washer_000", "vub_jeffcott_004"):
        assert name in d["presets"]
        assert (out / f"{name}.nc").is_file() and (out / f"{name}.png").is_file()


# -- entry points and layering -----------------------------------------------------------------
def run_module(*args):
    """``python -m autobalance ...`` in a subprocess."""
    return subprocess.run([sys.executable, "-m", "autobalance", *args],
                          capture_output=True, text=True, timeout=600)


@pytest.mark.slow
def test_python_m_autobalance_help():
    r = run_module("--help")
    assert r.returncode == 0 and r.stderr == ""
    for command in ("presets", "show", "simulate", "response", "sweep", "demo", "analyze",
                    "reproduce", "liquid"):
        assert command in r.stdout
    assert "Usage: autobalance" in r.stdout
    assert "Parameters" not in r.stdout     # the docstrings' numpydoc part stays out of --help


@pytest.mark.slow
def test_python_m_autobalance_end_to_end():
    """Same output as the typer app in this process, same one-line errors as the script."""
    args = ("response", "washer_000", "--speeds", "0:2000 rpm:11", "--json")
    r = run_module(*args)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout) == json.loads(run(*args).stdout)
    r = run_module("show", "washer_000", "--set", 'suspension.kx="5 kg"')
    assert r.returncode == 2 and r.stdout == ""
    assert_one_line_error(r.stderr, "suspension.kx")


@pytest.mark.slow
def test_library_does_not_import_the_cli():
    code = ("import sys, autobalance, autobalance.report.runner, autobalance.jsonable; "
            "print([m for m in sys.modules if m.startswith('autobalance.cli')])")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and r.stdout.strip() == "[]", r.stdout + r.stderr


def test_reproduce_passes_the_scheduler_in_the_context(tmp_path, monkeypatch):
    """``--scheduler`` reaches the targets' sweeps through the Context, not the environment."""
    import importlib
    import os

    seen = []

    def fake_sweep(spec, store, **kw):
        seen.append({**kw, "env": os.environ.get("DASK_SCHEDULER_ADDRESS")})
        raise RuntimeError("stopped by the test")

    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    monkeypatch.setattr(importlib.import_module("autobalance.sweep"), "sweep", fake_sweep)
    r = run("reproduce", "tsr-mc", "--scheduler", "tcp://127.0.0.1:1", "--out-dir",
            str(tmp_path / "out"), "--json")
    assert r.exit_code == 1, r.output               # the target's error is in the report
    assert seen and seen[0]["scheduler"] == "tcp://127.0.0.1:1"
    assert seen[0]["executor"] == "dask" and seen[0]["env"] is None
    assert "DASK_SCHEDULER_ADDRESS" not in os.environ
    err = json.loads(r.stdout)["targets"][0]["error"]
    assert "stopped by the test" in err


def test_version_is_printed_and_exits_0(capsys):
    """``autobalance --version``: the package's version on stdout, exit code 0, no command run."""
    import autobalance
    from autobalance.cli import main

    with pytest.raises(SystemExit) as e:
        main(["--version"])
    assert e.value.code == 0
    assert capsys.readouterr().out == f"autobalance {autobalance.__version__}\n"
