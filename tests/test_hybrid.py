"""Balls beside a liquid (core/hybrid.py, simulate/hybrid.py; docs/liquid/balls-beside-liquid.md sec. 3i): the ball
simulator with the wall films on the same rotor, checked against its two limits (a liquid of no
mass: the ball run; balls that cannot move: the Jeffcott rotor with the film), bad input, the
NetCDF file and the CLI end to end."""
from __future__ import annotations

import dataclasses
import json
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from autobalance.config import load_config
from autobalance.core.layout import S_EVENTS, S_STEPS
from autobalance.liquid.simulate import simulate_liquid
from autobalance.models import InitialState, MotorDrive, ParameterError
from autobalance.simulate import simulate

M_BALL, R_RACE = 0.05, 0.25            # two 50 g balls on a 0.25 m race beside 003's chamber
BALLS = ("balancer.n_balls=2", f"balancer.ball_mass={M_BALL} kg",
         f"balancer.race_radius={R_RACE} m", "balancer.ball_radius=10 mm",
         "balancer.damping=2.7 N*mm*s/rad")


def machine(*sets):
    return load_config("leblanc_003", [*BALLS, *sets])


def test_massless_liquid_is_the_ball_run():
    """A liquid of density 1e-3 kg/m^3 (mass 1.5e-7 kg) beside the balls: the run is the ball
    run without it, stepped at the films' pace (a pause every film step) instead of its own.
    Measured: 0.92e-3 of the peak amplitude, 5.1e-3 rad, 0.12 mm/s. The tolerance is the ball
    run's own sensitivity to its step sequence on this machine (slipping balls): the same run
    with a knot every millisecond of the same profile moves by 1.5e-3, 5.7e-3 rad and 0.16
    mm/s, and rtol 1e-6 -> 1e-7 by 1.1e-3, 2.6e-3 rad and 0.12 mm/s."""
    cfg = machine("balancer.rolling_resistance=0.002", "liquid.density=0.001 kg/m^3",
                  "profile.end_speed=60 rad/s", "profile.ramp_time=6 s", "profile.duration=8 s")
    a = simulate(cfg.system, cfg.spin)
    b = simulate(dataclasses.replace(cfg.system, liquid=None), cfg.spin)
    assert a.liquid is not None and a.liquid.steps > 1000 and b.liquid is None
    np.testing.assert_array_equal(a.t, b.t)
    assert np.max(np.abs(a.amplitude - b.amplitude)) < 5e-3 * np.max(b.amplitude)
    assert np.max(np.abs(a.alpha - b.alpha)) < 3e-2
    assert np.max(np.abs(a.grade_G - b.grade_G)) < 0.5
    assert np.max(np.abs(a.liquid.unbalance)) <= cfg.system.liquid.capacity   # rho V R: 3e-8


def test_locked_balls_are_the_film_rotor():
    """Balls that cannot move (stiction 1 at +-120 deg from D) are a fixed unbalance: the run
    settles, at a constant 40 1/s, on the state of the liquid-alone model (sw_coupled: the
    Jeffcott rotor with D + 2 m R cos 120 deg and the balls' mass). The two couple the same
    film to the rotor through different rotor integrators (RK4 sub-steps / DOPRI5 at rtol);
    measured 2.4e-4 in |w| and 6.6e-3 of |U| after 8 s (|w| within 0.8 % of the
    quasi-static closed form)."""
    prof = ("profile.kind=constant", "profile.speed=40 rad/s", "profile.duration=8 s")
    cfg = machine("balancer.rolling_resistance=1", "balancer.stiction=1",
                  "balancer.contact=none", *prof)
    a = 2 * np.pi / 3
    sim = simulate(cfg.system, cfg.spin, initial=InitialState(ball_angles=(a, -a)))
    assert np.max(np.abs(sim.alpha - sim.alpha[0])) < 1e-4            # the balls stayed put
    D = cfg.system.rotor.unbalance + 2 * M_BALL * R_RACE * np.cos(a)
    alone = load_config("leblanc_003", [f"rotor.mass={cfg.system.rotor.mass + 2 * M_BALL} kg",
                                        f"rotor.unbalance={D} kg*m", *prof])
    ref = simulate_liquid(alone.system, alone.spin)
    w = complex(sim.u[-1], sim.v[-1])
    assert abs(w - ref.deflection[-1]) < 2e-3 * abs(ref.deflection[-1])
    assert abs(sim.liquid.unbalance[-1] - ref.liquid_unbalance[-1]) \
        < 2e-2 * abs(ref.liquid_unbalance[-1])


@pytest.mark.slow          # 2.2 s: the fast tier stays under a minute
def test_locked_balls_on_a_horizontal_axis_are_the_film_rotor():
    """The same limit on a horizontal axis (leblanc_washer, gravity in the plane: the films see
    the chamber about the rotation axis, static sag included, and gravity's offset of their
    potential): at a constant 25 1/s, after 30 s (the liquid's slow mode needs it), the
    revolution-averaged whirl, the liquid's synchronous moment and the grade equal the
    liquid-alone model's. Measured (relative) 1.0e-3 in |w|, 8.0e-3 in U (4.8e-3 in
    |U|) and 5.4e-4 in G; after 15 s still converging: 5.0e-3, 4.1 % in U, 1.1 % in G."""
    from autobalance.liquid.simulate import revolution_average

    m, R, a = 0.2, 0.27, 2 * np.pi / 3
    prof = ("profile.kind=constant", "profile.speed=25 rad/s", "profile.duration=30 s")
    cfg = load_config("leblanc_washer", [
        "balancer.n_balls=2", f"balancer.ball_mass={m} kg", f"balancer.race_radius={R} m",
        "balancer.ball_radius=10 mm", "balancer.rolling_resistance=1", "balancer.stiction=1",
        "balancer.contact=none", *prof])
    sim = simulate(cfg.system, cfg.spin, initial=InitialState(ball_angles=(a, -a)))
    D = cfg.system.rotor.unbalance + 2 * m * R * np.cos(a)
    alone = load_config("leblanc_washer", [f"rotor.mass={cfg.system.rotor.mass + 2 * m} kg",
                                           f"rotor.unbalance={D} kg*m", *prof])
    ref = simulate_liquid(alone.system, alone.spin)
    w = revolution_average(sim.psi, sim.u + 1j * sim.v)[-1]
    w_ref = revolution_average(25.0 * ref.t, ref.deflection)[-1]
    assert abs(abs(w) - abs(w_ref)) < 5e-3 * abs(w_ref)
    U, U_ref = sim.liquid.synchronous_unbalance[-1], ref.synchronous_unbalance[-1]
    assert abs(U - U_ref) < 1e-2 * abs(U_ref)
    assert sim.grade_G[-1] == pytest.approx(ref.grade[-1], rel=1e-2)


@pytest.mark.parametrize("sets, spin, field", [
    (("liquid.axis=horizontal",), None, "gravity.g"),          # no in-plane gravity given
    (("gravity.g=9.81 m/s^2",), None, "gravity.g"),            # in the plane of a vertical axis
    (("profile.end_speed=10 rad/s",), None, "profile"),
    ((), MotorDrive("constant", 10.0, 10.0, 5.0), "profile.final_speed"),  # ends as a pool
])
def test_refusals(sets, spin, field):
    cfg = machine(*sets)
    with pytest.raises(ParameterError) as e:
        simulate(cfg.system, spin or cfg.spin)
    assert str(e.value).startswith(field) and "\n" not in str(e.value)


def test_liquid_analyses_refuse_balls():
    from autobalance.liquid.simulate import check_liquid_run
    cfg = machine()
    with pytest.raises(ParameterError, match="^balancer.n_balls .*autobalance simulate"):
        check_liquid_run(cfg.system, cfg.spin)


@pytest.mark.slow
def test_cli_end_to_end(tmp_path):
    """simulate --json reports the liquid beside the balls; the NetCDF file holds its
    histories; the grade includes the liquid's synchronous moment; --plot draws the ball run's
    figure with the liquid's moment as a grade."""
    nc = tmp_path / "r.nc"
    r = subprocess.run([sys.executable, "-m", "autobalance", "simulate", "leblanc_003",
                        *(f"--set={s}" for s in BALLS), "--set=profile.end_speed=40 rad/s",
                        "--set=profile.ramp_time=8 s", "--set=profile.duration=8 s",
                        "--json", "--out", str(nc), "--plot", str(tmp_path / "r.png")],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["status"] == "ok" and d["n_balls"] == 2 and d["liquid"]["film_steps"] > 0
    assert (tmp_path / "r.png").stat().st_size > 50_000     # the ball figure, the liquid's G
    from autobalance.liquid.spinup import spinup_of
    cfg = machine("profile.end_speed=40 rad/s", "profile.ramp_time=8 s", "profile.duration=8 s")
    assert d["liquid"]["film_start_s"] == spinup_of(cfg.system, cfg.spin)[0].lid_time
    assert d["liquid"]["film_start_speed_rad_s"] > 22.66           # later than 003 eq 6
    with xr.open_dataset(nc) as ds:
        U = ds.synchronous_unbalance_x + 1j * ds.synchronous_unbalance_y
        assert float(abs(U[-1])) == pytest.approx(d["liquid"]["liquid_unbalance_kg_m"])
        assert float(np.max(np.abs(ds.liquid_unbalance_x.where(ds.time < 4.0)))) == 0.0
        assert ds.chamber_unbalance_x.dims == ("time", "chamber")
        balls = ds.alpha.isel(time=-1).values
        D = load_config("leblanc_003").system.rotor.unbalance
        res = abs(D + M_BALL * R_RACE * np.exp(1j * balls).sum() + complex(U[-1]))
        assert float(ds.residual_unbalance[-1]) == pytest.approx(res, rel=1e-9)


SHORT = ("profile.end_speed=40 rad/s", "profile.ramp_time=6 s", "profile.duration=6 s")


@pytest.mark.slow
def test_sweep_monte_carlo_of_ball_starts(tmp_path):
    """A sweep of balls beside a liquid: a Monte Carlo over the balls' starts x two fills, on
    a real local pool of 2 processes; every stored run is the machine's own simulate run from
    that start (grade at the checkpoint, steps, events, ball angles), and it resumes."""
    from autobalance.sweep import spec_from_dict, sweep

    d = {"sweep": {"name": "hyb", "base": "leblanc_003", "set": [*BALLS, *SHORT]},
         "outputs": {"history_dt": "1 s"},
         "grid": {"liquid.volume": ["100 ml", "200 ml"]},
         "monte_carlo": {"kind": "random", "samples": 3, "seed": 7}}
    ds = sweep(spec_from_dict(d), tmp_path / "s", executor="local", workers=2, progress=False)
    assert ds.sizes["sample"] == 3 and int((ds["status"] != 0).sum()) == 0
    for i, v in enumerate(["100 ml", "200 ml"]):
        cfg = machine(*SHORT, f"liquid.volume={v}")
        for k in (0, 2):
            cell = ds.isel(liquid__volume=i, sample=k)
            a0 = tuple(float(x) for x in cell["start_angle"].values)
            sim = simulate(cfg.system, cfg.spin, initial=InitialState(ball_angles=a0))
            assert int(cell["steps"]) == int(sim.stats[S_STEPS])
            assert int(cell["events"]) == int(sim.stats[S_EVENTS])
            assert float(cell["grade_G"].values[-1]) == pytest.approx(
                sim.summary()["final"]["grade_G_mm_s"], rel=1e-12)
            assert float(cell["grade_G_history"].values[-1]) == pytest.approx(
                sim.grade_G[-1], rel=1e-12)
    again = sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False,
                  resume=True)
    assert again["grade_G"].equals(ds["grade_G"])


def test_sweep_refuses_a_horizontal_axis_up_front(tmp_path):
    from autobalance.sweep import SweepError, spec_from_dict, sweep

    d = {"sweep": {"name": "hyb", "base": "leblanc_003", "set": [*BALLS, *SHORT]},
         "grid": {"liquid.axis": ["vertical", "horizontal"]}}
    with pytest.raises(SweepError, match="liquid.axis"):
        sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False)
    assert not (tmp_path / "s").exists() or not any((tmp_path / "s").iterdir())


@pytest.mark.slow
def test_study_start_positions_takes_balls_beside_a_liquid(tmp_path):
    """The start-position Monte Carlo (simulations only) takes balls beside a liquid: each
    stored run is the machine's own simulate run from that start; studies with ball-only closed
    forms (tolerances) still refuse the liquid in one line."""
    nc = tmp_path / "mc.nc"
    sets = [f"--set={s}" for s in (*BALLS, *SHORT)]
    r = subprocess.run([sys.executable, "-m", "autobalance", "study", "start-positions",
                        "leblanc_003", *sets, "--random", "3", "--json", "--out", str(nc)],
                       capture_output=True, text=True, timeout=900)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["runs"] == 3 and d["failed"] == 0
    cfg = machine(*SHORT)
    with xr.open_dataset(nc) as ds:
        a0 = tuple(float(x) for x in ds["start_angle"].isel(sample=1).values)
        g = float(ds["grade_G"].isel(sample=1).values.ravel()[-1])
    sim = simulate(cfg.system, cfg.spin, initial=InitialState(ball_angles=a0))
    assert g == pytest.approx(sim.summary()["final"]["grade_G_mm_s"], rel=1e-12)
    bad = subprocess.run([sys.executable, "-m", "autobalance", "study", "tolerances",
                          "leblanc_003", *sets, "--method", "000"], capture_output=True,
                         text=True, timeout=600)
    lines = bad.stderr.strip().splitlines()
    assert bad.returncode == 2 and len(lines) == 1 and lines[0].startswith("error: method")


def test_liquid_moment_does_not_depend_on_the_output_spacing():
    """The liquid's synchronous moment is the revolution average on the films' own output grid
    (8 samples per revolution at least), not on the balls' output times: with the checkpoints
    only (save_dt = -1) an average over those would take two samples and give a wrong grade
    with exit 0. The final grade and moment are the same for every output spacing."""
    import dataclasses as dc

    cfg = machine(*SHORT)
    runs = [simulate(cfg.system, cfg.spin, options=dc.replace(cfg.options, save_dt=sd))
            for sd in (0.0, -1.0, 0.5)]
    for r in runs[1:]:
        assert r.grade_G[-1] == runs[0].grade_G[-1]
        assert r.liquid.synchronous_unbalance[-1] == runs[0].liquid.synchronous_unbalance[-1]


@pytest.mark.slow
def test_outside_the_wall_film_is_refused_or_reported():
    """The wall film's limits hold beside balls as for a liquid alone (liquid/film.films_state,
    liquid/simulate.inner_wall_status): a liquid too thick for a wall film is refused in one
    line before any work; a film that reaches its annulus' inner wall ends the run
    outside_model, naming the chamber (these ran silently with exit 0 before)."""
    thick = machine("liquid.chamber_radius=0.1 m", "liquid.inner_radius=0 m", "liquid.volume=1 l",
                    "profile.start_speed=60 rad/s", "profile.end_speed=100 rad/s")
    with pytest.raises(ParameterError) as e:
        simulate(thick.system, thick.spin)
    assert str(e.value).startswith("volume") and "wall film" in str(e.value)
    gap = machine('liquid.chamber_radius=["0.1 m", "0.2 m"]',
                  'liquid.inner_radius=[0, "0.197 m"]', 'liquid.volume=["100 ml", "150 ml"]',
                  "profile.duration=8 s", "profile.ramp_time=8 s")
    sim = simulate(gap.system, gap.spin, throw=False)
    ref = simulate_liquid(dataclasses.replace(gap.system, balancer=load_config(
        "leblanc_003").system.balancer), gap.spin, n_cells=64)
    assert ref.status == "outside_model"
    assert sim.status == "outside_model"
    assert "chamber R = 0.2 m" in sim.message and "0.197" in sim.message


TSR = ("profile.kind=tsr", "profile.nominal=100 rad/s", "profile.duration=20 s",
       "profile.runup_fraction=0.4", "profile.down_time=2 s", "profile.plateau_time=3 s",
       "profile.up_time=2 s", "profile.plateau=60 rad/s")


def _own_grades(cfg, n):
    """Each start of the n-per-ball start grid run by the machine's own simulate: grade_G
    [mm/s] at the profile's checkpoints, (start, checkpoint)."""
    from autobalance.sweep.plan import separate, start_grid

    b = cfg.system.balancer
    out = []
    for a in start_grid(n, b.n_balls, True):
        sim = simulate(cfg.system, cfg.spin,
                       initial=InitialState(ball_angles=tuple(separate(a, b.contact_angle))))
        out.append(np.interp(cfg.spin.checkpoints, sim.t, sim.grade_G))
    return np.array(out)


@pytest.mark.slow
def test_simulation_studies_take_balls_beside_a_liquid():
    """The studies that only simulate (unbalance range, plateau, run-up) take balls beside a
    liquid: their percentiles are those of the machine's own runs from the same starts, the
    run-up's "bare" run is the rotor without balls and with an empty chamber, and the closed
    forms the liquid is not in (the balls' operating boundaries, the stick threshold) are NaN
    instead of the balls' alone."""
    from autobalance.physics.iso1940 import unbalance_value
    from autobalance.studies._plateau import compute_plateau
    from autobalance.studies._runup import compute_runup
    from autobalance.studies.unbalance import compute_unbalance

    cfg = machine(*TSR)
    U = float(unbalance_value(5.0, cfg.system.total_mass, cfg.spin.nominal_speed))
    own = _own_grades(machine(*TSR, f"rotor.unbalance={U!r}"), 2)
    q = [5.0, 50.0, 95.0]
    ds = compute_unbalance(cfg, G=[5.0], n=2, executor="serial")
    np.testing.assert_allclose(ds["grade_G"].sel(case="nominal", G_ini=5.0).values,
                               np.percentile(own, q, axis=0).T, rtol=1e-12)
    assert np.isnan(ds["lower_boundary"].values).all() and np.isnan(ds["upper_boundary"]).all()

    fn = cfg.system.natural_frequencies[0]
    p = compute_plateau(cfg, ratios=[1.3], G=[5.0], n=2, executor="serial")
    own = _own_grades(machine(*TSR, f"rotor.unbalance={U!r}", f"profile.plateau={1.3 * fn!r}"), 2)
    assert float(p["grade_G_p95"].values.ravel()[0]) == pytest.approx(
        np.percentile(own[:, -1], 95), rel=1e-12)

    ru = compute_runup(machine(*SHORT))
    c = machine(*SHORT)
    sim = simulate(c.system, c.spin, options=dataclasses.replace(c.options,
                                                                 save_dt=-1.0))
    assert float(ru["final_grade"].values[0]) == pytest.approx(sim.grade_G[-1], rel=1e-12)
    bare = dataclasses.replace(c.system, liquid=None, balancer=dataclasses.replace(
        c.system.balancer, n_balls=0))
    sb = simulate(bare, c.spin)
    assert float(ru["max_amplitude_bare"].values[0]) == pytest.approx(
        sb.summary()["max_amplitude_m"], rel=1e-9)
    assert ru.attrs["balancer"] == "balls and liquid"


def test_closed_form_studies_refuse_a_liquid_naming_the_ones_that_take_it():
    from autobalance.studies._start_positions import compute_single

    with pytest.raises(ParameterError) as e:
        compute_single(machine())
    msg = str(e.value)
    assert msg.startswith("liquid") and "\n" not in msg
    assert "unbalance-range, plateau, sensitivity and runup" in msg
    assert "speed-map, immobility and tolerances (either axis) and design" in msg


def test_sensitivity_varies_the_liquid_viscosity_beside_balls():
    from autobalance.studies._sensitivity import default_variants

    v = default_variants(machine())
    nu = machine().system.liquid.kinematic_viscosity
    assert v["liquid viscosity x0.5"] == [f"liquid.kinematic_viscosity={0.5 * nu!r}"]
    assert v["liquid viscosity x2"] == [f"liquid.kinematic_viscosity={2 * nu!r}"]
    assert not any(k.startswith("liquid") for k in default_variants("vub_jeffcott_004"))


@pytest.mark.slow
def test_design_takes_balls_beside_a_liquid(tmp_path):
    """`design` beside a liquid: each candidate keeps the liquid, every grade it ranks is the
    candidate's own run (balls beside the liquid) from the start its sweep stored, and the
    tolerances are the bound beside the liquid (study tolerances of the picked design)."""
    from autobalance.config import load_config
    from autobalance.studies._design import DesignSpace, compute_design, design_summary
    from autobalance.studies._tolerances import compute_tolerances
    from autobalance.sweep.execute import open_sweep

    std = ("profile.kind=std", "profile.nominal=100 rad/s", "profile.runup_time=4 s",
           "profile.duration=8 s", "profile.runup_fraction=0.6")
    cfg = load_config("leblanc_003", [*BALLS, *std])
    ds = compute_design(cfg, space=DesignSpace(n_balls=(2,), capacity_ratios=(1.4,),
                                               profiles=("std",)),
                        unbalance_range=(0.02, 0.02), n_unbalance=1, starts=2,
                        refine_plateau=False, executor="serial", store_dir=tmp_path, budget=0)
    s = design_summary(ds)
    assert "tolerances_skipped" not in s
    assert ds.attrs["tolerance_own_worst_grade_G_mm_s"] == compute_tolerances(
        load_config("leblanc_003", [*BALLS, *std, *str(ds["sets"].values[
            list(ds["design"].values).index(ds.attrs["tolerances_design"])]).split("; ")]),
        grade=float(ds.attrs["grade"]))["worst_grade_G_mm_s"]
    sets = str(ds["sets"].values[0]).split("; ")
    cand = load_config("leblanc_003", [*BALLS, *std, *sets, "rotor.unbalance=0.02 kg*m"])
    assert cand.system.liquid is not None and cand.system.balancer.n_balls == 2
    (store,) = [p for p in tmp_path.glob("design-*/*") if p.is_dir()]
    raw = open_sweep(store)
    for k in range(2):
        a0 = tuple(float(x) for x in raw["start_angle"].isel(sample=k).values)
        sim = simulate(cand.system, cand.spin, initial=InitialState(ball_angles=a0))
        assert sim.liquid is not None
        assert float(ds["grade_G"].values[0, 0, k]) == pytest.approx(
            sim.summary()["final"]["grade_G_mm_s"], rel=1e-12)


@pytest.mark.slow
def test_run_up_with_massless_locked_balls_is_the_liquid_alone_run_up():
    """Balls of 1e-6 kg locked at +-90 deg from D (no unbalance, no mass to speak of) beside
    003's liquid, 0 -> 80 1/s in 16 s through Kollmann's band: the run of balls beside a liquid
    is the liquid-alone film run (simulate_liquid, sw_coupled) through the transient, not only
    in a steady whirl. Measured: peak 5.2500 vs 5.2505 mm, |w| within 0.2 %. The spin-up takes
    the ramp's acceleration whole and the film starts at 6.05 s: compared from 7 s on.
    Tolerance 0.5 %: the two integrate the rotor differently (DOPRI5 on w / RK4 on Z)."""
    from autobalance.config import load_config

    prof = ("profile.end_speed=80 rad/s", "profile.ramp_time=16 s", "profile.duration=16 s")
    alone = load_config("leblanc_003", list(prof))
    liq = simulate_liquid(alone.system, alone.spin)
    cfg = load_config("leblanc_003", ["balancer.n_balls=2", "balancer.ball_mass=1e-6 kg",
                                      "balancer.race_radius=0.1 m", "balancer.ball_radius=1 mm",
                                      "balancer.rolling_resistance=1", "balancer.stiction=1",
                                      "balancer.contact=none", *prof])
    hyb = simulate(cfg.system, cfg.spin, initial=InitialState(ball_angles=(np.pi / 2, 1.5 * np.pi)),
                   options=dataclasses.replace(cfg.options, save_dt=0.01))
    assert hyb.liquid.film_start == pytest.approx(liq.film_start, rel=1e-12)
    T = np.arange(7.0, 16.01, 1.0)
    a_liq = np.interp(T, liq.t, np.abs(liq.deflection))
    a_hyb = np.interp(T, hyb.t, hyb.amplitude)
    np.testing.assert_allclose(a_hyb, a_liq, rtol=5e-3)
    assert hyb.amplitude.max() == pytest.approx(np.abs(liq.deflection).max(), rel=1e-3)


@pytest.mark.slow
def test_runs_beside_a_liquid_on_threads_are_the_serial_runs():
    """The hybrid kernel releases the GIL (hybrid_integrate), so runs of balls beside a liquid
    share the cores on threads (the tolerances' simulation check does): two at once give the
    bits of the two one after another."""
    from concurrent.futures import ThreadPoolExecutor

    from autobalance.config import load_config

    cfg = load_config("leblanc_003", [
        "balancer.n_balls=2", "balancer.ball_mass=0.08 kg", "balancer.race_radius=0.25 m",
        "balancer.ball_radius=10 mm", "balancer.damping=20 N*mm*s/rad",
        "profile.end_speed=100 rad/s", "profile.ramp_time=8 s", "profile.duration=10 s"])
    inits = [InitialState(ball_angles=(a, a + 2.0)) for a in (0.3, 2.2)]

    def one(i):
        return simulate(cfg.system, cfg.spin, initial=i, options=cfg.options)

    serial = [one(i) for i in inits]
    with ThreadPoolExecutor(2) as ex:
        threaded = list(ex.map(one, inits))
    for a, b in zip(serial, threaded):
        np.testing.assert_array_equal(a.states, b.states)
        np.testing.assert_array_equal(a.liquid.unbalance, b.liquid.unbalance)
