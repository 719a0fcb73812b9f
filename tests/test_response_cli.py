"""``autobalance response`` for every machine: the rotor's harmonic response over a speed grid,
the drum's response at one ``--speed`` (000 eq 6-7, 37-38), a liquid balancer's steady whirl
against speed (autobalance.studies.liquid_response); the former ``analyze response`` and
``liquid simulate`` give the same numbers with a warning; bad input in one line."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
from conftest import run_main

from autobalance.config import load_config
from autobalance.physics.vibratory import drum_response
from autobalance.studies.liquid_response import default_speeds, liquid_response, liquid_run_up

RPM = 2 * math.pi / 60


def test_drum_response_at_one_speed_is_000_eq_6_7_in_the_configs_units(capsys):
    cfg = load_config("washer_000")
    code, out, err = run_main(capsys, ["response", "washer_000", "--speed", "1000 rpm",
                                       "--angles", "120, -120 deg", "--json"])
    assert code == 0, err
    d = json.loads(out)
    r = drum_response(cfg.system, 1000 * RPM, np.radians([120.0, -120.0])).as_dict()
    assert d["a_0x_m"] == pytest.approx(r["a_0x_m"], rel=1e-12)
    assert d["residual_unbalance_kg_m"] == pytest.approx(r["residual_unbalance_kg_m"], rel=1e-12)
    code, text, _ = run_main(capsys, ["response", "washer_000", "--speed", "1000 rpm"])
    assert code == 0 and text.splitlines()[0].startswith("washer_000 at 1000 rpm")
    code, si, _ = run_main(capsys, ["response", "washer_000", "--speed", "1000 rpm",
                                    "--units", "si"])
    assert code == 0 and "104.7 rad/s" in si.splitlines()[0]


def test_the_former_analyze_response_is_response_with_a_warning(capsys):
    args = ["washer_000", "--speed", "900 rpm", "--json"]
    code, now, err = run_main(capsys, ["response", *args])
    assert code == 0 and not err
    code, was, err = run_main(capsys, ["analyze", "response", *args])
    assert code == 0 and json.loads(was) == json.loads(now)
    assert err.strip() == ("warning: analyze response is deprecated: use response --speed S "
                           "[--angles A] (the old name goes in 0.4.0)")


def test_response_figure_against_speed(tmp_path, capsys):
    p = tmp_path / "r.png"
    code, out, err = run_main(capsys, ["response", "washer_000", "--speeds", "0:2000 rpm:50",
                                       "--plot", p])
    assert code == 0, err
    assert p.stat().st_size > 5000 and f"plot: {p}" in out


def test_liquid_response_default_speeds_reach_past_resonance_and_the_nominal_speed():
    s = load_config("leblanc_003")
    w = default_speeds(s.system, s.spin.nominal_speed)
    r = liquid_response(s.system, w)
    assert w.size == 200 and w[0] > 0 and np.all(np.diff(w) > 0)
    assert w[-1] == pytest.approx(max(2 * s.spin.nominal_speed, 1.5 * r["omega_n_rad_s"]))
    # the liquid balances above resonance: far above it the whirl tends to its residual
    # (k = 1: all of the unbalance), below the dry rotor's
    top = w > 1.5 * r["omega_n_rad_s"]
    assert np.all(np.asarray(r["amplitude_m"])[top] < np.asarray(r["amplitude_dry_m"])[top])


@pytest.mark.parametrize("machine, extra", [
    ("leblanc_003", []),
    ("leblanc_003", ["--model", "lumped", "--fill-sweep"]),
    ("examples/toploader-ring.toml", ["--fill-sweep"]),
])
def test_response_of_a_liquid_is_the_former_liquid_simulate(machine, extra, capsys):
    speeds = "20:90 rad/s:8"
    code, now, err = run_main(capsys, ["response", machine, "--speeds", speeds, *extra,
                                       "--json"])
    assert code == 0 and not err, err
    code, was, err = run_main(capsys, ["liquid", "simulate", machine, "--speeds", speeds,
                                       *extra, "--json"])
    assert code == 0 and err.startswith("warning: liquid simulate is deprecated: use response")
    now, was = json.loads(now), json.loads(was)
    for key in ("omega_rad_s", "amplitude_m", "amplitude_dry_m", "omega_0_rad_s",
                "omega_n_rad_s", "fill_sweep"):
        assert now.get(key) == was.get(key)


@pytest.mark.slow
def test_liquid_run_up_takes_the_model_that_covers_the_machine():
    """One vertical chamber: the film from 003 eq 6's speed omega_0 over the rest of the ramp
    (the bench's 0 -> 60 rad/s in 12 s leaves 12 (1 - omega_0/60) s); the lumped model from
    rest."""
    from autobalance.liquid.steady import start_speed

    s = load_config("leblanc_003").system
    phys = liquid_run_up(s, 60.0, 12.0)
    lump = liquid_run_up(s, 60.0, 12.0, model="lumped")
    c = s.liquid.chambers[0]
    w0 = start_speed(c.volume, c.chamber_radius, c.chamber_height)
    assert phys.omega[0] == pytest.approx(w0, rel=1e-9)
    assert phys.t[-1] - phys.t[0] == pytest.approx(12.0 * (1 - w0 / 60.0), rel=1e-6)
    assert lump.t[0] == 0.0 and lump.omega[0] == 0.0 and lump.t[-1] == 12.0
    assert phys.omega[-1] == pytest.approx(60.0, rel=1e-6)
    assert lump.omega[-1] == pytest.approx(60.0, rel=1e-6)


@pytest.mark.parametrize("args, start", [
    (["response", "washer_000", "--speed", "5 kg"], "error: --speed"),
    (["response", "washer_000", "--model", "lumped"], "error: --model: takes a machine with"),
    (["response", "washer_000", "--fill-sweep"], "error: --fill-sweep: takes a machine with"),
    (["response", "washer_000", "--speed", "900 rpm", "--plot", "x.png"], "error: --plot"),
    (["response", "leblanc_003", "--speed", "30"], "error: --speed: the drum's response"),
    (["response", "leblanc_003", "--speeds", "0:100:10"], "error: --speeds = '0:100:10'"),
    (["response", "leblanc_003", "--model", "wet"], "error: --model = 'wet'"),
    (["response", "leblanc_003_three", "--model", "lumped"],
     "error: liquid.chamber_radius = "),
])
def test_bad_input_one_line(args, start, capsys, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_main(capsys, args)
    assert code == 2 and not out
    assert err.startswith(start) and len(err.strip().splitlines()) == 1, err


@pytest.mark.slow
def test_liquid_commands_default_to_the_machines_own_speeds(capsys):
    """Without --speeds, liquid stability and kinetostatic-check take the machine's range
    (machine_speeds): on 003's bench (omega_n 54 rad/s, nominal 100 rad/s) 10.8-120 rad/s and
    40.5-100 rad/s; on the top-loader's ring (omega_n 16.7 rad/s, 800 rpm) other speeds."""
    from autobalance.studies.liquid_response import machine_speeds, natural_frequency

    code, out, err = run_main(capsys, ["liquid", "stability", "leblanc_003", "--json"])
    assert code == 0, err
    w = json.loads(out)["omega_rad_s"]
    assert len(w) == 45 and w[0] == pytest.approx(0.2 * 54.0) and w[-1] == pytest.approx(120.0)
    code, out, err = run_main(capsys, ["liquid", "kinetostatic-check", "leblanc_003",
                                       "--settle", "0 s", "--json"])
    assert code == 0, err
    w = json.loads(out)["omega_rad_s"]
    assert len(w) == 13 and w[0] == pytest.approx(40.5) and w[-1] == pytest.approx(100.0)
    ring = load_config("examples/toploader-ring.toml")
    wn = natural_frequency(ring.system)
    g = machine_speeds(ring.system, ring.spin.nominal_speed, 45, low=0.2, high=2.2,
                       high_nominal=1.2)
    assert g[0] == pytest.approx(0.2 * wn) and g[-1] == pytest.approx(1.2 * 800 * RPM)
