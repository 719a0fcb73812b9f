"""Several concentric chambers in one machine (docs/liquid/machine.md sec. 3g): the
``[liquid]`` keys as per-chamber lists, their one-line errors, the films of all chambers
coupled with the one rotor (closed form of intact rings, independence, volume per chamber),
``simulate`` and ``sweep`` of the preset leblanc_003_three, and the one-chamber analyses'
refusals."""
from __future__ import annotations

import math

import numpy as np
import pytest
import xarray as xr

from autobalance.config import ConfigError, describe, from_dict, from_models, load_config
from autobalance.liquid.film import coupled_run, film_equilibrium, film_unbalance
from autobalance.models.liquid_balancer import LiquidBalancer, VerticalRotor
from autobalance.liquid.simulate import simulate_liquid
from autobalance.models import LiquidDevice, ParameterError

RADII = (0.1, 0.15, 0.2)
INNER = (0.0, 0.1, 0.15)
H, RHO = 0.05, 1000.0
_K = (25.0 + RHO * 150e-6) * 54.0 ** 2
BENCH = VerticalRotor(25.0, _K, 0.1 * 2 * math.sqrt(_K * (25.0 + RHO * 150e-6)), 0.01)
SHORT = ["profile.duration=8 s", "profile.ramp_time=8 s"]


def three(*sets):
    return load_config("leblanc_003_three", list(sets))


# -- the section ---------------------------------------------------------------------------------
def test_preset_lists_three_chambers_and_show_counts_them():
    cfg = three()
    L = cfg.system.liquid
    assert L.n_chambers == 3
    assert L.chamber_radius == RADII and L.inner_radius == INNER
    assert L.volume == pytest.approx((150e-6,) * 3) and L.chamber_height == (H,) * 3
    assert [c.chamber_radius for c in L.chambers] == list(RADII)
    assert all(c.n_chambers == 1 and c.density == RHO for c in L.chambers)
    assert cfg.system.total_mass == pytest.approx(25.45)
    assert L.capacity == pytest.approx(RHO * 150e-6 * sum(RADII))
    d = describe(cfg)
    assert d["derived"]["liquid_chambers"] == 3
    assert d["liquid"]["chamber_radius_m"] == list(RADII)
    assert describe(load_config("leblanc_003"))["derived"]["liquid_chambers"] == 1


@pytest.mark.parametrize("item, field", [
    ('liquid.volume=["100 ml", "100 ml"]', "liquid.volume"),            # 2 values for 3
    ('liquid.inner_radius=[0, "0.05 m", "0.15 m"]', "liquid.inner_radius[1]"),   # overlaps
    ('liquid.volume=["100 ml", "3 l", "100 ml"]', "liquid.volume[1]"),  # above its chamber
    ("liquid.partitions=[0, 0, 1]", "liquid.partitions[2]"),
    ('liquid.chamber_radius=["0.1 m", "-0.15 m", "0.2 m"]', "liquid.chamber_radius[1]"),
    ("liquid.volume=[]", "liquid.volume"),
    ("liquid.volume=[1, 2, 3] ml", "liquid.volume"),                      # not 6 ml each
])
def test_bad_chamber_lists_are_one_line(item, field):
    with pytest.raises(ConfigError) as e:
        three(item)
    msg = str(e.value).removeprefix("--set ")
    assert msg.startswith(field + " ") and "\n" not in msg


def test_round_trip_and_a_scalar_for_every_chamber():
    cfg = three()
    again = from_models(cfg.system, cfg.spin)
    assert again.system == cfg.system
    assert from_dict(again.raw).system == cfg.system
    L = three("liquid.volume=100 ml").system.liquid          # one value: every chamber
    assert L.n_chambers == 3 and L.volume == pytest.approx((1e-4,) * 3)
    one = LiquidDevice((0.2,), (0.05,), (1.5e-4,))            # one-element lists: one chamber
    assert one == LiquidDevice(0.2, 0.05, 1.5e-4) and one.chambers == (one,)


def test_one_chamber_analyses_refuse_several_in_one_line():
    with pytest.raises(ParameterError) as e:
        LiquidBalancer.of(three().system.liquid)
    assert e.value.field == "liquid.chamber_radius" and "3 concentric chambers" in str(e.value)
    assert "\n" not in str(e.value)


# -- the films of several chambers on one rotor ---------------------------------------------------
def _intact_whirl(W, vols):
    """Steady whirl while every film is an intact ring at rest on the displaced wall: each film's
    moment is rho pi R^2 H w (a full cylinder's mass, exactly on the uniform grid), so
    (k - (M + sum rho V) W^2 - W^2 sum rho pi R^2 H + i c W) w = W^2 D."""
    full = sum(RHO * math.pi * R * R * H for R in RADII)
    Mt = BENCH.mass + RHO * sum(vols)
    return W * W * BENCH.unbalance / (BENCH.stiffness - (Mt + full) * W * W
                                      + 1j * BENCH.damping * W)


def test_intact_rings_of_three_chambers_add_three_full_chambers():
    """At 40 1/s with D = 1000 g*cm every film stays a ring (|w| 0.9 mm < the films' 2.4-4.8
    mm): the coupled run from the dry rotor's whirl settles on the closed form of the intact
    rings (to 1e-6 of |w| after 10 s; measured 1.5e-7 on 64 cells with nu = 1e-5 m^2/s, whose
    film waves decay at 0.8-3 1/s; much more viscous films relax overdamped and slower), and each
    chamber keeps its own volume to round-off. Started on the closed form, it stays there."""
    W, vols = 40.0, (150e-6,) * 3
    Mt = BENCH.mass + RHO * sum(vols)
    w_dry = W * W * BENCH.unbalance / (BENCH.stiffness - Mt * W * W + 1j * BENCH.damping * W)
    r = coupled_run(BENCH, RADII, H, vols, W, 10.0, deflection=w_dry, viscosity=1e-5,
                    n_cells=64)
    w = _intact_whirl(W, vols)
    assert abs(r.deflection[-1] - w) <= 1e-6 * abs(w)
    still = coupled_run(BENCH, RADII, H, vols, W, 1.0, deflection=w, n_cells=64)
    assert np.abs(still.deflection - w).max() <= 1e-9 * abs(w)
    assert abs(w) > 1.5 * abs(w_dry)                   # the rings' mass, not balancing
    for f, v in zip(r.films, vols):
        assert f.thickness.min() > 0.0                # intact
        assert np.ptp(f.volume) <= 1e-13 * v
    assert np.array_equal(r.unbalance, sum(f.unbalance for f in r.films))
    for f, R in zip(r.films, RADII):                   # each film at rest on its wall
        eq = film_unbalance(film_equilibrium(150e-6, R, H, r.deflection[-1], 64), R, H, RHO)
        assert f.unbalance[-1] == pytest.approx(eq, rel=1e-5)


def test_one_film_as_a_list_is_the_scalar_call_and_a_vanishing_chamber_is_absent():
    """Lists of one film run the very same operations as scalars (bit for bit); a second
    chamber holding 1e-13 m^3 leaves the first chamber's run unchanged to 1e-7 (the chambers
    interact only through the rotor)."""
    W, T = 60.0, 1.0
    a = coupled_run(BENCH, 0.2, H, 150e-6, W, T, n_cells=64)
    b = coupled_run(BENCH, [0.2], [H], [150e-6], W, T, n_cells=[64])
    assert np.array_equal(a.deflection, b.deflection) and a.steps == b.steps
    c = coupled_run(BENCH, [0.1, 0.2], H, [1e-13, 150e-6], W, T, n_cells=64)
    assert np.abs(c.deflection - a.deflection).max() <= 1e-7 * np.abs(a.deflection).max()
    assert abs(c.films[0].unbalance).max() < 1e-12


def test_coupled_run_lists_must_agree():
    with pytest.raises(ParameterError) as e:
        coupled_run(BENCH, RADII, H, [1e-4, 1e-4], 40.0, 0.1)
    assert e.value.field == "volume" and "\n" not in str(e.value)
    with pytest.raises(ParameterError) as e:
        coupled_run(BENCH, RADII, H, [1e-4, 0.0, 1e-4], 40.0, 0.1)
    assert e.value.field == "volume[1]"


# -- simulate and sweep --------------------------------------------------------------------------
@pytest.mark.slow
def test_simulate_three_chambers(tmp_path):
    """The film starts where the last chamber's liquid reaches the lid in its spin-up from
    rest; the chambers' moments add up to the liquid's; the summary and the NetCDF carry each
    chamber."""
    from autobalance.liquid.simulate import film_start, film_start_speed
    from autobalance.liquid.spinup import spinup_of

    cfg = three(*SHORT)
    L = cfg.system.liquid
    sim = simulate_liquid(cfg.system, cfg.spin, n_cells=64)
    assert sim.status == "ok"
    fs = film_start(cfg.system, cfg.spin)      # the latest chamber's spin-up to the lid
    assert fs.rule == "spin-up" and sim.film_start == fs.time
    assert fs.time == max(r.lid_time for r in spinup_of(cfg.system, cfg.spin))
    assert sim.film_start_speed == fs.speed > max(film_start_speed(c) for c in L.chambers)
    assert sim.chamber_unbalance.shape == (sim.t.size, 3)
    assert np.allclose(sim.chamber_unbalance.sum(-1), sim.liquid_unbalance, rtol=1e-14, atol=0)
    s = sim.summary()
    assert [c["chamber_radius_m"] for c in s["chambers"]] == list(RADII)
    sim.to_netcdf(tmp_path / "r.nc")
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        assert ds["chamber_unbalance_x"].dims == ("time", "chamber")
        assert list(ds["chamber_radius"].values) == list(RADII)
    one = simulate_liquid(load_config("leblanc_003", SHORT).system, cfg.spin, n_cells=64)
    assert one.chamber_unbalance is None and "chambers" not in one.summary()


def test_a_film_at_an_inner_wall_names_its_chamber():
    """An annulus whose gap (3 mm) a whirling crescent fills: the run ends outside the model,
    and the message names that chamber."""
    cfg = three(*SHORT, 'liquid.chamber_radius=["0.1 m", "0.2 m"]',
                'liquid.inner_radius=[0, "0.197 m"]', 'liquid.volume=["100 ml", "150 ml"]')
    sim = simulate_liquid(cfg.system, cfg.spin, n_cells=64)
    assert sim.status == "outside_model"
    assert "chamber R = 0.2 m" in sim.message and "0.197" in sim.message


@pytest.mark.slow
def test_sweep_of_a_three_chamber_machine(tmp_path):
    """A grid over the unbalance: each cell is the machine's own simulate_liquid run."""
    from autobalance.sweep import spec_from_dict, sweep

    d = {"sweep": {"name": "three", "base": "leblanc_003_three", "set": SHORT},
         "grid": {"rotor.unbalance": ["1000 g*cm", "3000 g*cm"]}}
    ds = sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False)
    for i, u in enumerate(["1000 g*cm", "3000 g*cm"]):
        cfg = three(*SHORT, f"rotor.unbalance={u}")
        sim = simulate_liquid(cfg.system, cfg.spin)
        cell = ds.isel(rotor__unbalance=i, sample=0)
        assert int(cell["status"]) == 0 and int(cell["steps"]) == sim.steps
        assert float(cell["grade_G"].values[-1]) == sim.summary()["final"]["grade_G_mm_s"]


# -- the fill map ----------------------------------------------------------------------------------
@pytest.mark.slow
def test_fill_map_of_three_chambers_is_pools_and_intact_rings():
    """Large fills (1350 ml per chamber) stay intact rings: above its entrainment speed each
    chamber adds the mass of its full outer cylinder rho pi R^2 h and balances nothing, below it
    its liquid's mass only (a pool); the map equals that closed form at every speed, chamber by
    chamber (to 1e-9), and its fill is the total, each chamber scaled alike."""
    from autobalance.liquid.steady import pool_response, start_speed
    from autobalance.studies._fill_map import compute_fill_map

    cfg = three()
    s = cfg.system
    rot = VerticalRotor(s.rotor.mass, s.suspension.kx, s.suspension.cx, s.rotor.unbalance)
    W = np.linspace(10.0, 100.0, 37)
    ds = compute_fill_map("leblanc_003_three", fills=[4050e-6, 450e-6], speeds=W)
    assert ds["chamber_fill"].values[0] == pytest.approx([1350e-6] * 3)
    assert list(ds["chamber_radius"].values) == list(RADII)
    w0 = [start_speed(1350e-6, R, H, inner_radius=ri) for R, ri in zip(RADII, INNER)]
    assert ds["entrainment_speed"].values[0] == pytest.approx(max(w0), rel=1e-14)
    for j, w in enumerate(W):
        m = sum(RHO * math.pi * R * R * H if w >= w0k else RHO * 1350e-6
                for R, w0k in zip(RADII, w0))
        assert ds["amplitude"].values[0, j] == pytest.approx(
            abs(pool_response(rot, m / RHO, RHO, w)), rel=1e-9)
    e = ds["efficiency"].sel(fill=450e-6).values
    assert (e[W > 70] > 1.3).all()                     # 150 ml each balances above resonance


def test_fill_map_refusals_with_several_chambers():
    from autobalance.studies._fill_map import compute_fill_map

    with pytest.raises(ParameterError) as e:
        compute_fill_map("leblanc_003_three", fills=[5000e-6], speeds=[30.0, 40.0])
    assert e.value.field == "fills" and "until one is full" in str(e.value)
    with pytest.raises(ParameterError) as e:
        compute_fill_map("leblanc_003_three", sets=["liquid.partitions=[0, 4, 0]"],
                         speeds=[30.0, 40.0])
    assert e.value.field == "liquid.partitions"


@pytest.mark.slow
def test_stability_map_of_three_chambers_runs_each_fill(tmp_path):
    """--dynamic on several chambers: one sweep over the speeds per fill (every chamber's volume
    set), each cell the machine's own constant-speed run; resumable from the store."""
    from autobalance.studies._fill_map import compute_stability_map

    fills, speeds = [225e-6, 450e-6], [60.0]
    st = compute_stability_map("leblanc_003_three", fills=fills, speeds=speeds, duration=1.0,
                               executor="serial", store=tmp_path / "m")
    assert st["spread"].shape == (2, 1) and st["in_model"].values.all()
    assert sorted(p.name for p in (tmp_path / "m").iterdir()) == ["fill-0", "fill-1"]
    cfg = three("profile.kind=constant", "profile.speed=60", "profile.duration=1 s",
                'liquid.volume=["75 ml", "75 ml", "75 ml"]')
    sim = simulate_liquid(cfg.system, cfg.spin)
    hist = np.arange(0.0, 1.0 + 0.0025, 0.005)               # history_dt = duration / 200
    late = np.interp(hist[hist >= 0.75], sim.t, sim.amplitude)
    assert st["mean_amplitude"].values[0, 0] == pytest.approx(late.mean(), rel=1e-12)
    again = compute_stability_map("leblanc_003_three", fills=fills, speeds=speeds,
                                  duration=1.0, executor="serial", store=tmp_path / "m")
    assert again["spread"].equals(st["spread"])


# -- the command line --------------------------------------------------------------------------------
@pytest.mark.slow
def test_cli_three_chambers_end_to_end(tmp_path):
    """show lists the chambers; simulate --json reports each; --set with a list per chamber;
    study fill-map --json gives totals; the one-chamber analyses refuse in one line."""
    import json
    import subprocess
    import sys

    def cli(*args):
        return subprocess.run([sys.executable, "-m", "autobalance", *args], capture_output=True,
                              text=True, timeout=600)

    r = cli("show", "leblanc_003_three", "--set", 'liquid.volume=["100 ml","150 ml","200 ml"]')
    assert r.returncode == 0, r.stderr
    assert "[0.1, 0.15, 0.2]" in r.stdout and "liquid_chambers" in r.stdout
    nc = tmp_path / "r.nc"
    r = cli("simulate", "leblanc_003_three", *(f"--set={s}" for s in SHORT), "--json",
            "--out", str(nc))
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert [c["chamber_radius_m"] for c in d["chambers"]] == list(RADII)
    assert d["status"] == "ok" and nc.stat().st_size > 0
    r = cli("study", "fill-map", "leblanc_003_three", "--fills", "225, 450 ml",
            "--speeds", "40:100 rad/s:7", "--json")
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert [f["fill_m3"] for f in d["fills"]] == pytest.approx([225e-6, 450e-6])
    for args in (("response", "leblanc_003_three", "--model", "lumped"),
                 ("response", "leblanc_003_three", "--set", "liquid.partitions=4"),
                 ("show", "leblanc_003_three", "--set", "liquid.inner_radius=[0, 0.05, 0.15]")):
        r = cli(*args)
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 2 and len(lines) == 1 and "Traceback" not in r.stderr, r.stderr
        assert lines[0].startswith("error: liquid.")


@pytest.mark.slow
def test_liquid_simulate_of_three_chambers_is_the_fill_map_and_the_film_run(tmp_path):
    """``liquid simulate`` (quasi-static model) takes several chambers: its steady whirl, followed
    from root to root up the speeds (liquid/steady.chambers_steady_response), equals the fill
    map's at the machine's fill (each speed solved on its own, steady_amplitude) to 1e-9; its
    fill sweep at omega_n is the fill map's column; its run-up is simulate_liquid's through the
    same ramp from rest. The lumped model and partitions are refused in one line
    (test_cli_three_chambers_end_to_end)."""
    import json
    import subprocess
    import sys

    from autobalance.liquid.simulate import ramp_run_up
    from autobalance.studies._fill_map import compute_fill_map, default_fills

    cfg = three(*SHORT)
    r = subprocess.run([sys.executable, "-m", "autobalance", "liquid", "simulate",
                        "leblanc_003_three", *(f"--set={s}" for s in SHORT), "--speeds",
                        "5:100 rad/s:20", "--run-up", "--fill-sweep", "--json",
                        "--plot", str(tmp_path / "r.png")], capture_output=True, text=True,
                       timeout=600)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["chambers"] == 3 and d["radius_m"] == list(RADII)
    assert d["volume_m3"] == pytest.approx(cfg.system.liquid.total_volume, rel=1e-12)
    ws = np.asarray(d["omega_rad_s"])
    fm = compute_fill_map(cfg, fills=[cfg.system.liquid.total_volume], speeds=ws)
    np.testing.assert_allclose(d["amplitude_m"], fm["amplitude"].values[0], rtol=1e-9)
    wn = d["omega_n_rad_s"]
    vols = default_fills(cfg.system.liquid)
    at_wn = compute_fill_map(cfg, fills=vols, speeds=[wn, 2 * wn])["amplitude"].values[:, 0]
    sweep = d["fill_sweep"][2]
    assert sweep["omega_rad_s"] == pytest.approx(wn, rel=1e-12)
    np.testing.assert_allclose(sweep["amplitude_m"], at_wn, rtol=1e-9)
    ru = ramp_run_up(cfg.system, cfg.spin.nominal_speed, cfg.spin.duration)
    assert d["run_up"] == ru.summary()
    assert (tmp_path / "r.png").stat().st_size > 0
