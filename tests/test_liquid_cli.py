"""CLI of the liquid balancer (typer app, before registration as ``autobalance liquid``)."""
import json
import subprocess
import sys

import pytest
from typer.testing import CliRunner

from autobalance.cli.liquid import app
from autobalance.config import ConfigError
from autobalance.models import ParameterError

runner = CliRunner()


def _json(args):
    r = runner.invoke(app, args + ["--json"])
    assert r.exit_code == 0, r.output
    return json.loads(r.stdout)


def test_speeds_json_reproduces_003_with_g10():
    """003 eq 6 numbers (tolerance: half a unit of the last printed digit, g = 10 m/s^2)."""
    d = _json(["speeds", "--volume", "100, 200, 300 ml", "--gravity", "10 m/s^2"])
    w0 = [r["omega_0_rad_s"] for r in d["speeds"]]
    assert w0 == pytest.approx([28.0, 19.8, 16.2], abs=0.05 + 0.45 * (w0[0] > 27))
    assert d["speeds"][0]["bottom_touch_rad_s"] == pytest.approx(0.89, abs=0.005)


@pytest.mark.slow
def test_surface_json_and_plot(tmp_path):
    png = tmp_path / "s.png"
    d = _json(["surface", "--speeds", "0, 0.6, 10, 28, 60 rad/s", "--plot", str(png)])
    assert [s["mode"] for s in d["surfaces"]] == [1, 2, 3, 4, 4]  # 28 > omega_0 = 27.75 (standard g)
    for s in d["surfaces"]:
        assert s["volume_check_m3"] == pytest.approx(d["volume_m3"], rel=1e-9)
    assert png.stat().st_size > 10_000


def test_modes_and_kinetostatic_json():
    d = _json(["modes", "--speeds", "0:40 rad/s:5"])
    assert d["mode"] == sorted(d["mode"]) and d["mode"][-1] == 4
    k = _json(["kinetostatic", "--delta", "10, 30 deg", "--k", "1.2", "--liquid", "viscous_97"])
    assert all(abs(x) < 1e-9 for x in k["eq2_residual"]) and k["beta_deg"] > 5


@pytest.mark.slow
def test_simulate_json_and_plots(tmp_path):
    png = tmp_path / "r.png"
    d = _json(["simulate", "--model", "lumped", "--speeds", "10:90 rad/s:9", "--plot", str(png)])
    assert d["k"] == pytest.approx(1.0) and len(d["amplitude_m"]) == 9
    assert d["machine"] == "leblanc_003" and d["placement"] == "drach"
    assert png.stat().st_size > 10_000
    f = _json(["simulate", "--model", "lumped", "--speeds", "54 rad/s", "--fill-sweep",
               "--plot", str(tmp_path / "f.png")])
    assert all(s["optimum_volume_m3"] == pytest.approx(150e-6) for s in f["fill_sweep"][1:])


@pytest.mark.slow
def test_simulate_physical_model_json_run_up_and_fill_sweep(tmp_path):
    """``--model physical``: the quasi-static liquid's steady whirl (below omega_0 the liquid is a
    centred pool: the rotor with its mass, pool_response), the coupled film's run-up from
    omega_0 and the fill sweep, in the lumped model's keys; the liquid lowers the whirl above
    resonance only."""
    png = tmp_path / "p.png"
    d = _json(["simulate", "--model", "physical", "--speeds", "15:80 rad/s:14", "--run-up",
               "--plot", str(png)])
    assert d["model"] == "physical" and d["placement"] is None
    amp, dry, w = d["amplitude_m"], d["amplitude_dry_m"], d["omega_rad_s"]
    from autobalance.liquid.steady import pool_response
    from autobalance.papers.p003.bench import bench
    b = bench()
    below = [(a, x) for a, x in zip(amp, w) if x < d["omega_0_rad_s"]]
    assert below and all(a == pytest.approx(abs(pool_response(b.rotor, b.balancer.volume, 1000.0, x)))
                         for a, x in below)
    assert all(a < b for a, b, x in zip(amp, dry, w) if x >= 1.2 * d["omega_n_rad_s"])
    assert all(a > b for a, b, x in zip(amp, dry, w) if d["omega_0_rad_s"] <= x <= 0.8 * d["omega_n_rad_s"])
    ru = d["run_up"]
    assert ru["peak_amplitude_m"] < ru["peak_amplitude_dry_m"]
    assert png.stat().st_size > 10_000
    f = _json(["simulate", "--model", "physical", "--speeds", "54 rad/s", "--fill-sweep"])
    assert len(f["fill_sweep"]) == 4 and f["fill_sweep"][3]["optimum_volume_m3"] >= 150e-6


@pytest.mark.slow
def test_simulate_takes_any_liquid_machine_and_its_overrides():
    """``liquid simulate`` takes a System: the shortcuts are overrides of the machine's keys, so
    ``--volume`` and ``--set liquid.volume`` give the same run, and 001's liquids set the
    density and viscosity; the suspension keeps its values (k of 003's bench)."""
    a = _json(["simulate", "--speeds", "40, 60 rad/s", "--volume", "200 ml"])
    b = _json(["simulate", "leblanc_003", "--speeds", "40, 60 rad/s", "--set", "liquid.volume=200 ml"])
    assert a["amplitude_m"] == b["amplitude_m"] and a["volume_m3"] == pytest.approx(2e-4)
    c = _json(["simulate", "--speeds", "60 rad/s", "--liquid", "heavy_1650"])
    assert c["liquid"] == "heavy_1650" and c["capacity_kg_m"] == pytest.approx(1650 * 150e-6 * 0.2)
    d = _json(["simulate", "--speeds", "60 rad/s"])
    assert d["omega_n_rad_s"] == pytest.approx(54.0) and c["omega_n_rad_s"] < 54.0  # same k


def test_simulate_on_a_horizontal_axis_is_the_fill_maps_model(tmp_path):
    """``liquid simulate`` on the washer's ring (horizontal axis): its start speed is
    sqrt(g / (R/10)), its steady amplitudes are the fill map's (steady_amplitude, axis
    "horizontal": a puddle below the start, the planar ring above) to the root's tolerance, and
    so are its fill sweeps; the lumped model (003's vertical bench) is refused."""
    import math

    from autobalance.config import load_config
    from autobalance.liquid.simulate import film_rotor
    from autobalance.liquid.steady import chambers_fill_sweep, steady_amplitude

    d = _json(["simulate", "leblanc_washer", "--speeds", "10:120 rad/s:12", "--fill-sweep",
               "--plot", str(tmp_path / "f.png")])
    s = load_config("leblanc_washer").system
    c, g = s.liquid.chambers[0], s.gravity.g
    ch = [(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume)]
    assert d["axis"] == "horizontal"
    assert d["omega_0_rad_s"] == pytest.approx(math.sqrt(g / (0.1 * c.chamber_radius)), rel=1e-12)
    rot = film_rotor(s)
    ref = [steady_amplitude(rot, ch, s.liquid.density, w, g, axis="horizontal")
           for w in d["omega_rad_s"]]
    assert d["amplitude_m"] == pytest.approx(ref, rel=1e-8)
    sw = d["fill_sweep"][2]                                      # at omega_n
    per = [[ch[0][:3] + (v,)] for v in sw["volume_m3"]]
    want = chambers_fill_sweep(rot, per, s.liquid.density, sw["omega_rad_s"], g, "horizontal")
    assert sw["amplitude_m"] == pytest.approx(list(want["amplitude_m"]), rel=1e-8)
    assert (tmp_path / "f.png").stat().st_size > 10_000


def test_simulate_text_speaks_the_machines_units():
    """The text of ``liquid simulate`` shows unit-suffixed values in the units the machine was
    written in (the washer's speeds in rpm), or SI with ``--units si``; JSON stays SI."""
    import math

    r = runner.invoke(app, ["simulate", "leblanc_washer", "--speeds", "10:120 rad/s:12"])
    assert r.exit_code == 0, r.output
    w0 = math.sqrt(9.81 / 0.026) * 30 / math.pi                # sqrt(g/(R/10)) [rpm]
    line = next(x for x in r.output.splitlines() if x.startswith("omega_0 "))
    assert line.split()[-1] == "rpm" and float(line.split()[1]) == pytest.approx(w0, rel=1e-3)
    r = runner.invoke(app, ["simulate", "leblanc_washer", "--speeds", "10:120 rad/s:12",
                            "--units", "si"])
    assert any(x.startswith("omega_0 ") and x.endswith("rad/s") for x in r.output.splitlines())


@pytest.mark.slow
def test_simulate_run_up_on_a_horizontal_axis_is_the_machines_run():
    """``liquid simulate --run-up`` on the washer (a linear run-up 0 -> 1000 rpm in 30 s, the
    preset's own profile) is the film model with gravity through that profile: its peak equals
    `autobalance simulate`'s run of the machine."""
    from autobalance.config import load_config
    from autobalance.liquid.simulate import simulate_liquid

    d = _json(["simulate", "leblanc_washer", "--speeds", "20, 60, 100 rad/s", "--run-up"])
    cfg = load_config("leblanc_washer")
    sim = simulate_liquid(cfg.system, cfg.spin)
    assert d["run_up"]["peak_amplitude_m"] == pytest.approx(float(sim.amplitude.max()), rel=1e-9)
    assert d["run_up"]["final_amplitude_m"] == pytest.approx(float(sim.amplitude[-1]), rel=1e-9)


@pytest.mark.parametrize("args, exc", [
    (["simulate", "--model", "exact"], ConfigError),
    (["surface", "--volume", "7 l"], ParameterError),          # larger than the chamber
    (["surface", "--radius", "-0.2 m"], ParameterError),       # negative size
    (["speeds", "--volume", "100 kg"], ConfigError),           # wrong unit
    (["kinetostatic", "--k", "-1"], ParameterError),
    (["simulate", "--liquid", "honey"], ConfigError),
    (["simulate", "--placement", "magic"], ConfigError),       # names the option
    (["simulate", "leblanc_washer", "--model", "lumped"], ParameterError),  # horizontal axis
    (["simulate", "vub_jeffcott_004"], ConfigError),                       # no [liquid]
    (["simulate", "--set", "liquid.partitions=4"], ParameterError),        # not in this model
    (["simulate", "--set", "suspension.ky=1e5"], ParameterError),          # anisotropic
    (["simulate", "--set", "suspension.dry_friction_force=70 N"], ParameterError),  # not modelled
    (["simulate", "--set", "gravity.g=9.81 m/s^2"], ParameterError),       # in-plane g, vertical
    (["simulate", "--volume", "7 l"], ConfigError),                        # over the chamber
])
def test_bad_input_raises_one_line(args, exc):
    r = runner.invoke(app, args)
    assert isinstance(r.exception, exc)
    assert "\n" not in str(r.exception)


@pytest.mark.slow
def test_standalone_bad_input_exit_2_no_traceback():
    """Subprocess (``python -m autobalance liquid ...``): one ``error:`` line, exit code 2
    (the entry point's main() turns the group's exceptions into that line)."""
    p = subprocess.run([sys.executable, "-m", "autobalance", "liquid", "surface", "--volume",
                        "7 l"], capture_output=True, text=True, timeout=60)
    assert p.returncode == 2
    assert p.stderr.startswith("error: volume") and p.stderr.count("\n") == 1
    assert "Traceback" not in p.stderr
