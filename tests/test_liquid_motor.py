"""A liquid under a motor drive (docs/liquid/balls-beside-liquid.md sec. 3i): a liquid alone through the kernel of
balls beside a liquid with no balls (`simulate_liquid_motor`), the pool's spin-up from rest
beside a motor-driven spin (`_pool_phase`), the CLI, and the one-line refusals. The references
are the prescribed-profile models run through the motor run's own speed history: the film
coupled with the Jeffcott rotor (`simulate_liquid`, another coupling) and the spin-up model
(`chamber_spinup`, sec. 3h)."""
from __future__ import annotations

import json
import math

import numpy as np
import pytest
import xarray as xr

from autobalance.config import load_config
from autobalance.liquid.simulate import simulate_liquid
from autobalance.liquid.spinup import chamber_spinup
from autobalance.liquid.start import film_start
from autobalance.models import ParameterError, SpeedProfile
from autobalance.simulate.hybrid import POOL_STEP, RIGID_NOTE, simulate_liquid_motor

#: 003's chamber (150 ml of water) on a rotor of 0.5 kg m^2 under 5 N*m up to 100 1/s.
MOTOR = ("profile.kind=motor", "profile.law=constant", "profile.torque=5 N*m",
         "profile.final_speed=100 rad/s", "profile.initial_speed=30 rad/s", "profile.duration=12 s",
         "rotor.polar_inertia=0.5 kg*m^2")


def machine(*sets):
    return load_config("leblanc_003", [*MOTOR, *sets])


def its_speed_history(sim, t_end):
    """The motor run's speed at its outputs as a prescribed profile (repeated speeds after the
    hold dropped; held to t_end)."""
    keep = np.concatenate([[True], np.diff(sim.speed) > 1e-9 * np.maximum(sim.speed[1:], 1.0)])
    tt, ww = sim.t[keep], sim.speed[keep]
    if tt[-1] < t_end:
        tt, ww = np.append(tt, t_end), np.append(ww, ww[-1])
    return SpeedProfile(tuple(tt), tuple(ww), nominal_speed=sim.nominal_speed)


@pytest.mark.slow
def test_a_liquid_alone_under_a_motor_is_the_film_run_of_its_speed_history():
    """From 30 1/s (above the film's start, 22.7 1/s) through the resonance: the same run
    through the other coupling (the film with the Jeffcott rotor at the motor run's speed, as
    a table) and the same start (the steady orbit with the liquid as a rigid mass). Measured:
    peak 4.792 against 4.794 mm, G at the end 88.62 against 88.57, the amplitude histories
    within 1.0 % of the peak (the largest gap where the motor reaches its hold)."""
    cfg = machine()
    a = simulate_liquid_motor(cfg.system, cfg.spin)
    assert a.status == "ok" and a.message == "" and a.motor and a.film_start == 0.0
    assert a.time_to_final_speed == pytest.approx(7.2, abs=0.3)
    b = simulate_liquid(cfg.system, its_speed_history(a, 12.0))
    assert np.max(a.amplitude) == pytest.approx(np.max(b.amplitude), rel=3e-3)
    assert a.grade[-1] == pytest.approx(b.grade[-1], rel=3e-3)
    gap = np.abs(a.amplitude - np.interp(a.t, b.t, b.amplitude))
    assert np.max(gap) < 0.02 * np.max(a.amplitude)
    assert abs(a.synchronous_unbalance[-1] - b.synchronous_unbalance[-1]) < 0.01 * abs(
        b.synchronous_unbalance[-1])


@pytest.mark.slow
def test_a_motor_from_rest_spins_the_pool_up_and_pays_for_it():
    """From rest the pool spins up beside the motor-driven spin until the liquid reaches the
    lid. (1) On a light rotor (J = 1e-3 kg m^2, 0.05 N*m, D = 0) the liquid takes most of the
    motor's impulse: at the lid J psi' + H_L = T t, H_L from the spin-up model run through the
    motor run's own speed history (independent of the coupling), to one coupling step's
    exchange (measured: H_L 0.130 of 0.163 N*m*s, the books 3.1e-5 out). (2) That spin-up puts
    the film's start within two coupling steps of the motor run's. (3) With an unbalance, the
    run after it is the film run of its speed history (measured: film start 3.507 against
    3.506 s, peak 4.960 against 4.962 mm, G 88.632 against 88.632)."""
    T = 0.05
    cfg = machine("profile.initial_speed=0 rad/s", "rotor.unbalance=0 kg*m",
                  f"profile.torque={T} N*m", "rotor.polar_inertia=1e-3 kg*m^2",
                  "profile.duration=4 s")
    s = cfg.system
    a = simulate_liquid_motor(s, cfg.spin)
    assert a.status == "ok" and 3.0 < a.film_start < 3.5
    prof = its_speed_history(a, 4.0)
    L, c = s.liquid, s.liquid.chambers[0]
    r = chamber_spinup(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume,
                       L.kinematic_viscosity, 9.80665, prof.times, prof.speeds)
    W = r.speed[-1]
    H_L = 2 * np.pi * L.density * float(((r.azimuthal[-1] + r.depth[-1] * W * r.r) * r.r)
                                        @ (0.5 * np.diff(r.faces ** 2)))
    impulse = T * r.lid_time
    assert H_L > 0.5 * impulse
    assert abs(impulse - s.rotor.polar_inertia * W - H_L) < 2 * T * POOL_STEP
    fs = film_start(s, prof)
    assert fs.rule == "spin-up" and abs(fs.time - a.film_start) < 2 * POOL_STEP
    # (3) with an unbalance on the 0.5 kg m^2 rotor under 5 N*m
    cfg = machine("profile.initial_speed=0 rad/s")
    a = simulate_liquid_motor(cfg.system, cfg.spin)
    b = simulate_liquid(cfg.system, its_speed_history(a, 12.0))
    assert abs(b.film_start - a.film_start) < 2 * POOL_STEP
    assert a.film_start_speed == pytest.approx(b.film_start_speed, rel=2e-3)
    assert np.max(a.amplitude) == pytest.approx(np.max(b.amplitude), rel=3e-3)
    assert a.grade[-1] == pytest.approx(b.grade[-1], rel=3e-3)


def test_a_motor_that_stops_before_the_lid_leaves_a_pool():
    """A drive too weak to reach the lid in its time: the liquid stays a pool (no film, U = 0),
    the run is the rotor with the pool's mass, and it says where the film started: nowhere."""
    cfg = machine("profile.initial_speed=0 rad/s", "profile.duration=0.3 s")
    a = simulate_liquid_motor(cfg.system, cfg.spin)
    assert a.status == "ok" and math.isnan(a.film_start) and a.steps == 0
    assert a.message.startswith("no film")
    assert np.all(a.liquid_unbalance == 0) and a.speed[-1] > 2.0


def test_a_motor_from_rest_on_a_horizontal_axis_turns_the_liquid_with_the_chamber():
    """The washer's ring (1 l at 0.26 m, horizontal axis) on a rotor without unbalance under a
    linear torque law T0 (1 - w/w_max) from rest: below the film's start speed
    sqrt(10 g/R) the liquid turns with the chamber, so the spin is the closed form
    w_max (1 - exp(-T0 t / ((J + rho V R^2) w_max))) (measured within 1e-9 of it); the film
    starts at the end of the coupling step in which the spin reaches that speed, turning with
    the chamber, and the run goes on to the drive's hold."""
    J, T0, w_max = 1.0, 20.0, 1000 * math.pi / 30
    cfg_sets = ["profile.kind=motor", "profile.law=linear", f"profile.torque={T0} N*m",
                "profile.final_speed=1000 rpm", "profile.initial_speed=0 rpm",
                f"rotor.polar_inertia={J} kg*m^2", "rotor.unbalance=0 kg*m"]
    cfg = load_config("leblanc_washer", [*cfg_sets, "profile.duration=3 s"])
    a = simulate_liquid_motor(cfg.system, cfg.spin)
    L = cfg.system.liquid
    tau = (J + L.density * L.volume * L.chamber_radius ** 2) * w_max / T0
    w_f = math.sqrt(10 * 9.81 / L.chamber_radius)
    t_f = -tau * math.log(1 - w_f / w_max)                 # the closed form reaches w_f
    before = a.t < a.film_start
    closed = w_max * (1 - np.exp(-a.t[before] / tau))
    assert np.abs(a.speed[before] - closed).max() < 1e-9 * w_max
    assert a.status == "ok" and t_f <= a.film_start <= t_f + POOL_STEP * (1 + 1e-9)
    assert w_f <= a.film_start_speed <= w_f + POOL_STEP * T0 / J
    assert np.all(a.liquid_unbalance[before] == 0) and a.steps > 0
    assert a.speed[-1] > 2 * w_f
    assert a.message == RIGID_NOTE                       # the run says what it assumed
    short = load_config("leblanc_washer", [*cfg_sets, "profile.duration=0.5 s"])
    b = simulate_liquid_motor(short.system, short.spin)  # ends before the film's start
    assert b.status == "ok" and math.isnan(b.film_start)
    assert b.message.startswith("no film") and "turned with the drum" in b.message


def test_refusals_of_a_motor_with_a_liquid():
    """One line each, before any work: a drive that ends below the film's start speed; one that
    starts below it in a chamber more than half full on a vertical axis (outside the spin-up
    model); a prescribed profile here."""
    for preset, sets, field in (
            ("leblanc_003", ("profile.final_speed=10 rad/s",), "profile.final_speed"),
            ("leblanc_003", ("profile.initial_speed=0 rad/s", "liquid.volume=2 l"),
             "profile.initial_speed")):
        cfg = load_config(preset, [*MOTOR, *sets])
        with pytest.raises(ParameterError) as e:
            simulate_liquid_motor(cfg.system, cfg.spin)
        assert e.value.field == field and "\n" not in str(e.value)
    cfg = load_config("leblanc_003", [])
    with pytest.raises(ParameterError) as e:
        simulate_liquid_motor(cfg.system, cfg.spin)
    assert e.value.field == "profile.kind"
    cfg = machine()
    with pytest.raises(ParameterError) as e:
        simulate_liquid(cfg.system, cfg.spin)
    assert e.value.field == "profile.kind" and "autobalance.simulate.simulate" in str(e.value)


@pytest.mark.slow
def test_cli_simulates_a_liquid_alone_under_a_motor_from_rest(tmp_path):
    """`autobalance simulate` of a liquid alone under a motor from rest: exit 0, the film's
    start and the time to full speed in the JSON summary, a NetCDF file xarray opens; a drive
    too short for the lid says so in a note."""
    from typer.testing import CliRunner

    from autobalance.cli import app

    out = tmp_path / "m.nc"
    sets = [x for m in MOTOR for x in ("--set", m.replace(" ", ""))]
    res = CliRunner().invoke(app, ["simulate", "leblanc_003", *sets, "--set",
                                   "profile.initial_speed=0/s", "--set", "profile.duration=6s",
                                   "--json", "--out", str(out)])
    assert res.exit_code == 0, res.output
    S = json.loads(res.output[res.output.index("{"):])
    S = S.get("summary", S)
    assert 3.0 < S["film_start_s"] < 4.0
    assert S["time_to_final_speed_s"] is None            # 100 1/s takes 10 s at 5 N*m
    with xr.open_dataset(out) as ds:
        assert ds["speed"].values[-1] > 50 and ds.attrs["spin"] == "motor"
        assert float(ds.attrs["film_start_s"]) == pytest.approx(S["film_start_s"])
    res = CliRunner().invoke(app, ["simulate", "leblanc_003", *sets, "--set",
                                   "profile.initial_speed=0/s", "--set", "profile.duration=0.3s"])
    assert res.exit_code == 0 and "note: no film" in res.output


@pytest.mark.slow
def test_runup_study_and_sweep_of_a_liquid_alone_under_a_motor(tmp_path):
    """`study runup` and `sweep` take a liquid alone under a motor from rest (through
    `liquid_run`): the study's amplitude before the film is the run's own (the pool spinning up
    beside the motor, not the quasi-steady bound), and each stored sweep cell is the machine's
    own run."""
    from autobalance.studies._runup import compute_runup
    from autobalance.sweep import spec_from_dict, sweep

    sets = [*MOTOR, "profile.initial_speed=0 rad/s", "profile.duration=6 s"]
    cfg = load_config("leblanc_003", sets)
    a = simulate_liquid_motor(cfg.system, cfg.spin)
    before = a.t < a.film_start
    assert before.sum() > 100
    assert a.max_amplitude_before_film == pytest.approx(np.max(a.amplitude[before]), rel=1e-12)
    ds = compute_runup("leblanc_003", sets=sets)
    assert float(ds["max_amplitude"].values[0]) == pytest.approx(np.max(a.amplitude), rel=1e-9)
    assert float(ds["final_grade"].values[0]) == pytest.approx(a.grade[-1], rel=1e-9)
    d = {"sweep": {"name": "motor", "base": "leblanc_003", "set": sets},
         "grid": {"profile.torque": ["5 N*m", "10 N*m"]}}
    st = sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False)
    assert int((st["status"] != 0).sum()) == 0
    cell = st.isel(profile__torque=0)
    assert float(cell["grade_G"].values.ravel()[-1]) == pytest.approx(a.grade[-1], rel=1e-9)
    assert int(cell["steps"].values.ravel()[0]) == a.steps
