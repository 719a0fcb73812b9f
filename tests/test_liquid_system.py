"""The liquid balancer as part of the one System: the ``[liquid]`` section (config, show,
--set, Python), `simulate` with the wall-film model, and one-line refusals where a ball
analysis or the film model does not apply."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from autobalance.config import ConfigError, describe, from_dict, from_models, load_config, \
    replace_values
from autobalance.liquid.free_surface import entrainment_speed
from autobalance.models.liquid_balancer import VerticalRotor
from autobalance.liquid.film import film_run
from autobalance.liquid.simulate import revolution_average, simulate_liquid
from autobalance.liquid.steady import synchronous_deflection
from autobalance.models import LiquidDevice, MotorDrive, ParameterError, SpeedProfile
from autobalance.physics.response import axis_response
from autobalance.simulate import simulate


def bench(*sets):
    return load_config("leblanc_003", list(sets))


# -- the section -------------------------------------------------------------------------------
def test_preset_is_003s_bench():
    """leblanc_003 is 003's bench (sec. 4.2-5.3): R = 0.2 m, h = 0.05 m, 150 ml water,
    D = 3000 g*cm, k set by omega_r = 54 1/s with the liquid, our damping ratio 0.1; the papers'
    bench is that machine through the one adapter (liquid_parts)."""
    from autobalance.liquid.simulate import liquid_parts
    from autobalance.papers.p003.bench import bench as paper_bench

    s = bench().system
    L = s.liquid
    assert (L.chamber_radius, L.chamber_height) == (0.2, 0.05)
    assert L.volume == pytest.approx(150e-6) and L.density == 1000.0
    assert s.rotor.unbalance == pytest.approx(0.03)
    assert s.total_mass == pytest.approx(25.15)
    assert s.natural_frequencies[0] == pytest.approx(54.0, rel=1e-12)
    assert s.suspension.cx / (2 * math.sqrt(s.suspension.kx * s.total_mass)) == \
        pytest.approx(0.1, rel=1e-12)
    rotor, bal = liquid_parts(s)
    b = paper_bench()
    assert b.rotor == rotor and b.balancer.volume == bal.volume
    assert b.balancer.chamber == bal.chamber and b.balancer.arc == L.friction_arc


def test_units_and_describe():
    cfg = bench("liquid.volume=0.2 l", "liquid.kinematic_viscosity=5 cSt")
    L = cfg.system.liquid
    assert L.volume == pytest.approx(2e-4) and L.kinematic_viscosity == pytest.approx(5e-6)
    d = describe(cfg)
    assert d["liquid"]["volume_m3"] == pytest.approx(2e-4)
    assert d["liquid"]["axis"] == "vertical"
    assert d["derived"]["liquid_mass_kg"] == pytest.approx(0.2)
    assert d["derived"]["liquid_capacity_kg_m"] == pytest.approx(0.04)
    assert d["derived"]["total_mass_kg"] == pytest.approx(25.2)
    assert "liquid" not in describe(load_config("vub_jeffcott_004"))


@pytest.mark.parametrize("item, field", [
    ("liquid.volume=7 l", "liquid.volume"),             # more than the 6.28 l chamber
    ("liquid.volume=0 ml", "liquid.volume"),
    ("liquid.volume=5 kg", "liquid.volume"),             # wrong kind of unit
    ("liquid.axis=sideways", "liquid.axis"),
    ("liquid.density=-1", "liquid.density"),
    ("liquid.kinematic_viscosity=1 m/s", "liquid.kinematic_viscosity"),
    ("liquid.friction_arc=400 deg", "liquid.friction_arc"),
    ("liquid.partitions=1", "liquid.partitions"),        # 0 or 2..64
])
def test_bad_values_one_line(item, field):
    with pytest.raises(ConfigError) as e:
        bench(item)
    msg = str(e.value)
    assert msg.removeprefix("--set ").startswith(field) and "\n" not in msg


def test_python_round_trip_and_adding_a_section():
    cfg = bench()
    again = from_models(cfg.system, cfg.spin)
    assert again.system == cfg.system
    assert from_dict(again.raw).system == cfg.system
    bare = load_config("vub_jeffcott_004", ["balancer.n_balls=0", "initial.ball_angles=[]"])
    with pytest.raises(ConfigError, match=r"^liquid.chamber_radius: missing"):
        replace_values(bare, {"liquid.volume": "100 ml"})
    added = replace_values(bare, {"liquid.chamber_radius": "0.1 m", "liquid.chamber_height":
                                  "50 mm", "liquid.volume": "100 ml"})
    L = added.system.liquid
    assert isinstance(L, LiquidDevice) and L.axis == "vertical" and L.density == 1000.0
    assert (L.chamber_radius, L.chamber_height, L.volume) == pytest.approx((0.1, 0.05, 1e-4))
    assert added.system.total_mass == pytest.approx(bare.system.total_mass + 0.1)


# -- simulate ----------------------------------------------------------------------------------
def test_film_starts_where_the_spin_up_reaches_the_lid():
    """A ramp 0 -> 100 1/s in 20 s from rest: the liquid spins up from a flat layer at rest and
    the film starts where it reaches the lid (liquid/spinup.py; 28.8 1/s against 003 eq 6's
    22.7), lagging the chamber as the spin-up leaves it; the run starts there on the
    synchronous orbit of the rotor with its liquid as a rigid mass."""
    from autobalance.liquid.simulate import film_start
    from autobalance.liquid.spinup import spinup_of

    cfg = bench()
    s, L = cfg.system, cfg.system.liquid
    sim = simulate_liquid(s, cfg.spin, n_cells=64, n_out=201)
    spun = spinup_of(s, cfg.spin)[0]
    w0 = 100.0 * spun.lid_time / 20.0
    assert sim.film_start == spun.lid_time and sim.film_start_speed == pytest.approx(w0)
    assert w0 > entrainment_speed(L.volume, L.chamber_radius, L.chamber_height) + 5.0
    fs = film_start(s, cfg.spin)
    assert fs.rule == "spin-up" and fs.lag[0] == spun.liquid_speed[-1] - spun.speed[-1] < -3.0
    assert sim.t[0] == pytest.approx(sim.film_start) and sim.t[-1] == pytest.approx(20.0)
    assert sim.speed[0] == pytest.approx(w0) and sim.speed[-1] == pytest.approx(100.0)
    a0 = axis_response(s.total_mass, s.suspension.kx, s.suspension.cx, s.rotor.unbalance, w0)[0]
    assert sim.amplitude[0] == pytest.approx(a0, rel=1e-12)
    dry = axis_response(s.rotor.mass, s.suspension.kx, s.suspension.cx, s.rotor.unbalance,
                        sim.speed)[0]
    np.testing.assert_allclose(sim.amplitude_without_liquid, dry, rtol=1e-12)
    summary = sim.summary()
    assert summary["final"]["grade_G_mm_s"] == pytest.approx(
        1e3 * abs(s.rotor.unbalance + sim.synchronous_unbalance[-1]) / s.total_mass * 100.0)


def test_film_starts_at_the_entrainment_speed_on_a_turning_start():
    """A profile that starts at or above omega_0 (003 eq 6) starts with the ring turning with
    the chamber (no film lag); one that starts turning below it spins the pool up from its
    rigid rotation at the first speed, and reaches the lid later than the profile reaches
    omega_0; a horizontal axis keeps the quasi-static rule (sec. 3e)."""
    from autobalance.liquid.simulate import film_start

    cfg = bench()
    L = cfg.system.liquid
    w0 = entrainment_speed(L.volume, L.chamber_radius, L.chamber_height)
    fs = film_start(cfg.system, SpeedProfile.ramp(30.0, 100.0, 5.0, 5.0))
    assert (fs.time, fs.speed, fs.lag, fs.rule) == (0.0, w0, (0.0,), "quasi-static")
    fs = film_start(cfg.system, SpeedProfile.ramp(10.0, 100.0, 20.0, 20.0))
    t_eq6 = 20.0 * (w0 - 10.0) / 90.0
    assert fs.rule == "spin-up" and fs.time > t_eq6 and fs.speed > w0 and fs.lag[0] < 0.0
    washer = load_config("leblanc_washer")
    assert film_start(washer.system, washer.spin).rule == "quasi-static"


def test_steady_whirl_matches_the_quasi_static_liquid():
    """At a constant 40 1/s (below resonance, where the synchronous whirl is stable) the run
    settles on the quasi-static root (liquid/steady.py, planar: the film has no axial gravity).
    Tolerance 2 |w|/R: the film's wall height is first order in |w|/R (docs/liquid/film.md sec. 3c);
    measured 0.93 % at |w|/R = 0.0094, the same on 128, 256 and 512 cells."""
    cfg = bench()
    s, L = cfg.system, cfg.system.liquid
    sim = simulate_liquid(s, SpeedProfile.constant(40.0, 6.0), n_cells=128, n_out=301)
    rotor = VerticalRotor(s.rotor.mass, s.suspension.kx, s.suspension.cx, s.rotor.unbalance)
    w = synchronous_deflection(rotor, L.chamber_radius, L.chamber_height, L.volume, L.density,
                               40.0, axis="planar")
    assert abs(sim.deflection[-1] - sim.deflection[-30]) < 1e-3 * abs(w)     # settled
    assert abs(sim.deflection[-1] - w) < 2 * abs(w) / L.chamber_radius * abs(w)


@pytest.mark.parametrize("sets, field", [
    (("balancer.n_balls=2", "balancer.ball_mass=0.1 kg", "balancer.race_radius=0.1 m",
      "balancer.ball_radius=5 mm"), "balancer.n_balls"),
    (("liquid.axis=horizontal",), "gravity.g"),                 # no in-plane gravity given
    (("suspension.ky=50 N/mm",), "suspension.ky"),
    (("gravity.g=9.81 m/s^2",), "gravity.g"),
    (("profile.end_speed=10 rad/s",), "profile"),           # never reaches omega_0 (~15 1/s)
])
def test_film_model_refusals(sets, field):
    cfg = bench(*sets)
    with pytest.raises(ParameterError) as e:
        simulate_liquid(cfg.system, cfg.spin)
    assert str(e.value).startswith(field) and "\n" not in str(e.value)


def test_profile_dipping_below_omega_0_and_motor_refused():
    cfg = bench()
    dip = SpeedProfile([0.0, 5.0, 8.0, 10.0], [0.0, 60.0, 10.0, 60.0])
    with pytest.raises(ParameterError, match="falls below the film model.s start speed"):
        simulate_liquid(cfg.system, dip)
    with pytest.raises(ParameterError, match="^profile.kind"):
        simulate_liquid(cfg.system, MotorDrive("constant", 10.0, 50.0, 5.0))


def test_simulate_runs_a_liquid_alone_and_the_ball_paths_refuse_it():
    """``simulate`` runs a liquid alone with the film model (the same run as simulate_liquid);
    the ball kernel's batch and the ball studies would take the liquid as a rigid mass:
    refused."""
    from autobalance.simulate import simulate_batch

    cfg = bench()
    run, ref = simulate(cfg.system, cfg.spin), simulate_liquid(cfg.system, cfg.spin)
    assert type(run) is type(ref) and run.status == "ok" and run.note is None
    np.testing.assert_array_equal(run.grade, ref.grade)
    with pytest.raises(ParameterError, match="^liquid = .*no liquid model"):
        simulate_batch([cfg.system], cfg.spin)
    from autobalance.studies.common import load
    with pytest.raises(ParameterError, match="^liquid = .*ball balancers"):
        load("leblanc_003")


# -- CLI end to end ----------------------------------------------------------------------------
def run_cli(*args, cwd=None):
    return subprocess.run([sys.executable, "-m", "autobalance", *args], capture_output=True,
                          text=True, timeout=600, cwd=cwd)


@pytest.mark.slow
def test_cli_simulate_show_and_refusals(tmp_path):
    nc, png = tmp_path / "run.nc", tmp_path / "run.png"
    r = run_cli("simulate", "leblanc_003", "--set", "profile.duration=8 s",
                "--set", "profile.ramp_time=8 s", "--json", "--out", str(nc), "--plot", str(png))
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["model"] == "liquid wall film" and d["status"] == "ok"
    assert d["final"]["speed_rad_s"] == pytest.approx(100.0)
    assert math.isfinite(d["final"]["grade_G_mm_s"]) and d["files"]["netcdf"] == str(nc)
    with xr.open_dataset(nc) as ds:
        assert {"amplitude", "liquid_unbalance_x", "grade", "speed"} <= set(ds.data_vars)
        assert ds.attrs["film_start_s"] == pytest.approx(d["film_start_s"])
    assert png.stat().st_size > 10_000
    r = run_cli("show", "leblanc_003", "--set", "liquid.volume=300 ml")
    assert r.returncode == 0 and "[liquid]" in r.stdout and "(= 300 ml)" in r.stdout
    for args, field in ((("study", "start-positions", "leblanc_003"), "balancer.n_balls"),
                        (("analyze", "bounds", "leblanc_003"), "liquid"),
                        (("simulate", "leblanc_003", "--set", "liquid.axis=horizontal"),
                         "gravity.g"),
                        (("simulate", "leblanc_003", "--set", "liquid.volume=7 l"),
                         "liquid.volume")):
        r = run_cli(*args)
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 2 and len(lines) == 1, r.stderr
        assert lines[0].startswith(f"error: {field}") and "Traceback" not in r.stderr


# -- a horizontal axis: gravity in the chamber's plane ---------------------------------------------
def test_revolution_average_removes_the_counter_rotating_part():
    psi = np.linspace(0.0, 40 * np.pi, 4001)
    U = 0.3 - 0.1j + 0.05 * np.exp(-1j * psi)
    avg = revolution_average(psi, U)
    np.testing.assert_allclose(avg, 0.3 - 0.1j, atol=1e-6)   # trapezoid on 100 samples/rev
    assert revolution_average(psi, np.full(psi.size, 2.0)) == pytest.approx(2.0)


@pytest.mark.slow
def test_gravity_forces_the_film_as_a_linear_wave():
    """A film on the wall of a drum turning at constant Omega on a horizontal axis: gravity
    is the wall height b = -(g/Omega^2) cos(gamma - Omega t - theta) (core/shallow_water.py),
    a forced wave e^{i(theta + Omega t)} in the rotor frame. The linearised film (eta_t + q_x =
    0, q_t + G eta0 eta_x = -G eta0 b_x - lambda q, G = Omega^2 R, laminar lambda = 3 nu/eta0^2)
    answers with H = -i G eta0 B / R / (i G eta0 / R - Omega R (i Omega + lambda)). The scheme is
    first order: measured error 8.2 / 3.2 / 1.3 % on 128 / 256 / 512 cells after 20 s (the
    free waves have decayed to e^-5)."""
    R, Hc, V, W, g, gam, nu = 0.2, 0.05, 150e-6, 50.0, 9.81, -np.pi / 2, 1.0e-6
    eta0 = V / (2 * np.pi * R * Hc)
    B = -(g / W ** 2) * np.exp(-1j * gam)
    lam, G = 3 * nu / eta0 ** 2, W * W * R
    H = -(1j * G * eta0 / R) * B / (1j * G * eta0 / R - W * R * (1j * W + lam))
    errors = []
    for n in (128, 256, 512):
        run = film_run(R, Hc, V, W, 20.0, viscosity=nu, n_cells=n, gravity=g,
                       gravity_direction=gam, save_dt=1.0)
        mode = 2 * np.mean(run.thickness[-1] * np.exp(-1j * run.theta))
        errors.append(abs(mode - H * np.exp(1j * W * run.t[-1])) / abs(H))
    assert errors[0] > errors[1] > errors[2] and errors[2] < 0.02, errors


def test_horizontal_rotor_sags_statically_under_its_liquid():
    """D = 0 on a horizontal axis at constant speed: the liquid held by gravity stands still
    in the inertial frame, so the rotor settles at the static sag M_t g / k (exactly, whatever
    the film): the whirl about the sag vanishes and the synchronous moment with it. A thin,
    viscous film (0.2 l, 50 cSt: friction rate 9 1/s) so that its free waves die within the
    run; measured whirl 3.7e-4 of the sag, synchronous moment 6e-6 of the capacity. (With the
    preset's 1 l of water the laminar film's waves decay at 0.004 1/s: 5 % of the sag is still
    sloshing after 12 s.)"""
    cfg = load_config("leblanc_washer", ["rotor.unbalance=0 kg*m", "liquid.volume=0.2 l",
                                         "liquid.kinematic_viscosity=50 cSt"])
    s = cfg.system
    sim = simulate_liquid(s, SpeedProfile.constant(60.0, 12.0), n_cells=128)
    sag = s.total_mass * s.gravity.g / s.suspension.kx
    assert sim.film_start_speed == pytest.approx(np.sqrt(9.81 / (0.1 * 0.26)))
    late = sim.t > 6.0
    assert np.max(sim.amplitude[late]) < 1e-3 * sag, (np.max(sim.amplitude[late]), sag)
    assert np.max(np.abs(sim.synchronous_unbalance[late])) < 1e-4 * s.liquid.capacity
    assert np.min(np.abs(sim.liquid_unbalance[late])) > 2e-3 * s.liquid.capacity   # a puddle


# -- sweep ---------------------------------------------------------------------------------------
SHORT = ["profile.duration=8 s", "profile.ramp_time=8 s"]


@pytest.mark.slow
def test_liquid_sweep_equals_its_single_runs(tmp_path):
    """A grid over the fill: each cell's stored grade and residual equal simulate_liquid's own
    (read at the checkpoint); the history is NaN before the film forms; resume adds nothing."""
    from autobalance.sweep import spec_from_dict, sweep

    d = {"sweep": {"name": "fill", "base": "leblanc_003", "set": SHORT},
         "grid": {"liquid.volume": ["100 ml", "300 ml"]},
         "outputs": {"history_dt": "1 s"}}
    ds = sweep(spec_from_dict(d), tmp_path / "s", executor="local", workers=2, progress=False)
    for i, v in enumerate(["100 ml", "300 ml"]):
        cfg = bench(*SHORT, f"liquid.volume={v}")
        sim = simulate_liquid(cfg.system, cfg.spin)
        cell = ds.isel(liquid__volume=i, sample=0)
        assert float(cell["grade_G"].values[-1]) == sim.summary()["final"]["grade_G_mm_s"]
        assert float(cell["residual_unbalance"].values[-1]) == pytest.approx(
            sim.residual_unbalance[-1], rel=1e-12)
        assert int(cell["status"]) == 0 and int(cell["steps"]) == sim.steps
        amp = cell["amplitude_history"].values
        before = ds["history_time"].values < sim.film_start
        assert np.isnan(amp[before]).all() and np.isfinite(amp[~before]).all()
    again = sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False,
                  resume=True)
    assert again["grade_G"].equals(ds["grade_G"])


@pytest.mark.parametrize("extra, needle", [
    ({"monte_carlo": {"kind": "random", "samples": 3}}, "monte_carlo.kind"),
    ({"grid": {"liquid.axis": ["vertical", "horizontal"]}}, "gravity.g"),
    # too thick for a wall film: refused before any run, not at run time after the first cell's
    ({"sweep": {"set": SHORT + ["liquid.chamber_radius=0.1 m", "liquid.inner_radius=0 m"]},
      "grid": {"liquid.volume": ["100 ml", "1 l"]}}, "grid point liquid.volume='1 l': volume"),
])
def test_liquid_sweep_refusals(tmp_path, extra, needle):
    from autobalance.sweep import SweepError, spec_from_dict, sweep

    d = {"sweep": {"name": "bad", "base": "leblanc_003", "set": SHORT},
         "grid": {"liquid.volume": ["100 ml"]}}
    for k, v in extra.items():
        d[k] = {**d.get(k, {}), **v}
    with pytest.raises(SweepError) as e:
        sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False)
    assert needle in str(e.value) and "\n" not in str(e.value)
    assert not (tmp_path / "s").exists()


def test_store_identity_sees_the_liquid():
    """System's repr leaves the liquid out (ball stores keep their identity); the store's
    identity adds it, so a resume with another fill is refused, not mixed."""
    from autobalance.sweep import make_plan, spec_from_dict
    from autobalance.sweep.store import identity

    def ident(volume):
        d = {"sweep": {"name": "f", "base": "leblanc_003", "set": SHORT + [f"liquid.volume={volume}"]},
             "grid": {"rotor.unbalance": ["1000 g*cm"]}}
        return identity(make_plan(spec_from_dict(d)))

    assert ident("100 ml") == ident("100 ml") != ident("101 ml")


SHORT_RUN = ("profile.duration=8 s", "profile.ramp_time=8 s", "profile.end_speed=80 rad/s")


@pytest.mark.slow
def test_unbalance_range_and_runup_studies_take_a_liquid_alone():
    """A liquid balancer alone in the studies that only simulate and need no ball starts: the
    unbalance range is one film run per initial grade (every percentile that run's grade at the
    read-out, equal to simulate_liquid's), its default grid scaled by the liquid's capacity
    rho V R; the run-up's final grade is simulate_liquid's, its peak at least the film run's,
    "without" the rotor with its chamber empty. The studies with ball closed forms still
    refuse a liquid alone in one line."""
    from autobalance.physics.iso1940 import unbalance_value
    from autobalance.studies._plateau import compute_plateau
    from autobalance.studies._runup import compute_runup
    from autobalance.studies.unbalance import compute_unbalance

    cfg = bench(*SHORT_RUN)
    ds = compute_unbalance(cfg, G=[30.0, 90.0], n=50, executor="serial")
    assert ds.sizes["G_ini"] == 2 and ds.attrs["G_balls"] == 0.0
    assert ds.attrs["G_liquid"] == pytest.approx(1e3 * cfg.system.liquid.capacity
                                                 / cfg.system.total_mass * 80.0)
    for G in (30.0, 90.0):
        U = float(unbalance_value(G, cfg.system.total_mass, cfg.spin.nominal_speed))
        c = bench(*SHORT_RUN, f"rotor.unbalance={U!r}")
        sim = simulate_liquid(c.system, c.spin)
        g = ds["grade_G"].sel(case="nominal", G_ini=G).values          # (procedure, pct)
        np.testing.assert_allclose(g, sim.at(c.spin.checkpoints)["grade_G"][:, None]
                                   * np.ones((1, 3)), rtol=1e-9)
    assert np.isnan(ds["lower_boundary"].values).all()

    ru = compute_runup(cfg)
    sim = simulate_liquid(cfg.system, cfg.spin)
    assert float(ru["final_grade"].values[0]) == pytest.approx(sim.grade[-1], rel=1e-12)
    assert float(ru["max_amplitude"].values[0]) >= float(np.max(sim.amplitude))
    assert np.isnan(ru["ball_revolutions"].values[0]) and ru.attrs["balancer"] == "liquid"
    assert float(ru["amplitude_ratio"].values[0]) < 1.0       # the liquid lowers the peak
    with pytest.raises(ParameterError, match="^balancer.n_balls"):
        compute_plateau(cfg)
