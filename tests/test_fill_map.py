"""`study fill-map`: a liquid balancer's steady whirl over fill x speed with the liquid from
physics, for any vertical-axis machine (studies/_fill_map.py; docs/liquid/machine.md sec. 3f)."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest
import xarray as xr

from autobalance.config import load_config
from autobalance.models.liquid_balancer import VerticalRotor
from autobalance.liquid.steady import pool_response, ring_response
from autobalance.models import ParameterError
from autobalance.studies._fill_map import compute_fill_map, fill_map_summary


#: 003's bench as a cylinder (its chamber is an annulus 0.15-0.2 m): room for a 3 l fill.
CYLINDER = ["liquid.inner_radius=0 m"]


@pytest.fixture(scope="module")
def fmap():
    return compute_fill_map("leblanc_003", fills=np.array([50, 150, 3000]) * 1e-6, sets=CYLINDER,
                            speeds=np.linspace(20.0, 100.0, 33))


def rotor_of(cfg):
    s = cfg.system
    return VerticalRotor(s.rotor.mass, s.suspension.kx, s.suspension.cx, s.rotor.unbalance)


def test_limits_pool_and_intact_ring(fmap):
    """Below a fill's entrainment speed (003 eq 6) the liquid is a centred pool (its mass only);
    a large fill stays an intact ring and adds a full chamber's mass, balancing nothing
    (liquid/steady.py ring_response): both closed forms to round-off."""
    cfg = load_config("leblanc_003", CYLINDER)
    rot, L = rotor_of(cfg), cfg.system.liquid
    W = fmap["speed"].values
    for i, v in enumerate(fmap["fill"].values):
        below = ~fmap["entrained"].values[i]
        np.testing.assert_allclose(fmap["amplitude"].values[i][below],
                                   np.abs(pool_response(rot, v, L.density, W[below])), rtol=1e-12)
    big = fmap["entrained"].values[2]
    ring = np.abs([ring_response(rot, L.chamber_volume, 3e-3, L.density, w) for w in W[big]])
    np.testing.assert_allclose(fmap["amplitude"].values[2][big], ring, rtol=1e-9)
    np.testing.assert_allclose(fmap["amplitude_without_liquid"].values,
                               np.abs(pool_response(rot, 0.0, L.density, W)), rtol=1e-12)


def test_the_liquid_helps_only_above_resonance(fmap):
    e = fmap["efficiency"].sel(fill=150e-6, method="nearest").values
    W = fmap["speed"].values
    assert (e[(W > 30) & (W < 48)] < 1).all() and (e[W > 60] > 1.2).all()
    d = fill_map_summary(fmap)
    assert d["least_fill_within_tie_m3"] == min(d["fills_within_tie_m3"])
    assert d["fills"][1]["balances_from_rad_s"] > 45.0
    res = fmap["resonance"].values
    assert res[1] < d["resonance_without_liquid_rad_s"]           # added mass lowers it


def test_refusals_are_one_line():
    with pytest.raises(ParameterError, match="^liquid"):
        compute_fill_map("vub_jeffcott_004")
    with pytest.raises(ParameterError, match="^gravity.g"):          # horizontal needs gravity
        compute_fill_map("leblanc_washer", sets=["gravity.g=0"])
    with pytest.raises(ParameterError, match="^suspension.dry_friction_force"):  # not modelled
        compute_fill_map("leblanc_003", sets=["suspension.dry_friction_force=70 N"])

    with pytest.raises(ParameterError, match="^fills"):
        compute_fill_map("leblanc_003", fills=[0.0])
    with pytest.raises(ParameterError, match="^speeds"):
        compute_fill_map("leblanc_003", speeds=[50.0, 40.0])


@pytest.mark.slow
def test_cli_end_to_end(tmp_path):
    nc, png = tmp_path / "fm.nc", tmp_path / "fm.png"
    r = subprocess.run([sys.executable, "-m", "autobalance", "study", "fill-map", "leblanc_003",
                        "--fills", "50:200 ml:4", "--speeds", "30:90 rad/s:13", "--json",
                        "--linear", "--out", str(nc), "--plot", str(png)],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert len(d["fills"]) == 4 and d["out"] == str(nc)
    lo, hi = d["fills"][2]["balanced_unstable_rad_s"][0]      # 150 ml: sec. 3j's 47.5-82 1/s
    assert 45.0 < lo < 50.0 and 80.0 < hi < 85.0
    with xr.open_dataset(nc) as ds:
        assert ds["amplitude"].shape == (4, 13) and ds.attrs["command"] == "study fill-map"
        assert ds["growth_rate"].shape == (4, 13)
    assert png.stat().st_size > 10_000
    r = subprocess.run([sys.executable, "-m", "autobalance", "study", "fill-map",
                        "vub_jeffcott_004"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 2 and r.stderr.startswith("error: liquid") and \
        len(r.stderr.strip().splitlines()) == 1


def test_linear_map_is_ring_stability_per_point_and_a_pool_below_entrainment():
    """compute_linear_map: each point is ring_stability of that fill at that speed (the
    machine's chamber), NaN below the fill's entrainment speed (003 eq 6: a pool, no film); a
    horizontal axis is refused in one line."""
    from autobalance.liquid.simulate import film_rotor
    from autobalance.liquid.stability import machine_stability, ring_stability
    from autobalance.studies._fill_map import compute_linear_map

    cfg = load_config("leblanc_003")
    L = cfg.system.liquid
    lm = compute_linear_map(cfg, fills=[75e-6, 300e-6], speeds=[20.0, 60.0])
    g = lm["growth_rate"].values
    assert np.isnan(g[0, 0]) and np.isfinite(g[1, 0])        # 75 ml: a pool until 32 1/s
    r = ring_stability(film_rotor(cfg.system), L.chamber_radius, L.chamber_height, 300e-6,
                       60.0, density=L.density, viscosity=L.kinematic_viscosity)
    assert g[1, 1] == r.growth_rate and not lm["balanced_stable"].values[1, 1]
    # a horizontal axis: Floquet about the periodic state (sec. 3m), the machine's own
    w = compute_linear_map("leblanc_washer", fills=[1e-3], speeds=[1000 * math.pi / 30],
                           n_cells=32)["growth_rate"].values[0, 0]
    washer = load_config("leblanc_washer").system
    ref = machine_stability(washer, [1000 * math.pi / 30], n_cells=32)["growth_rate_1_s"][0]
    assert w == pytest.approx(ref, rel=1e-6) and w < 0      # the fill scaled: round-off


@pytest.mark.slow
def test_stability_map_tells_steady_from_asynchronous_whirl():
    """The coupled film at constant speed (one sweep, local processes): 75 ml at 45 1/s settles
    on the synchronous whirl; 300 ml of water at 80 1/s (1.5 omega_r) keeps whirling
    asynchronously (docs/liquid/film.md sec. 3d), its amplitude spreading by > 50 % of its mean."""
    from autobalance.studies._fill_map import SPREAD_MAX, compute_stability_map

    st = compute_stability_map("leblanc_003", fills=[75e-6, 300e-6], speeds=[45.0, 80.0],
                               duration=6.0, executor="local", workers=2)
    assert bool(st["steady"].sel(fill=75e-6, speed=45.0))
    assert float(st["spread"].sel(fill=75e-6, speed=45.0)) < 0.1 * SPREAD_MAX
    assert not bool(st["steady"].sel(fill=300e-6, speed=80.0))
    assert float(st["spread"].sel(fill=300e-6, speed=80.0)) > 0.5
    assert (st["mean_amplitude"] > 0).all()


@pytest.mark.slow
def test_example_top_loader_ring_reaches_its_nominal_speed():
    """examples/toploader-ring.toml (make run's liquid design study): the default speeds reach
    the nominal 800 rpm, and there the liquid balances."""
    ds = compute_fill_map("examples/toploader-ring.toml", quick=True)
    assert ds["speed"].values[-1] == pytest.approx(800 * 2 * np.pi / 60)
    d = fill_map_summary(ds)
    assert d["speed_on_grid_rad_s"] == pytest.approx(800 * 2 * np.pi / 60)
    assert d["best_efficiency_at_nominal"] > 1.0


def test_horizontal_axis_puddle_below_the_ring_and_planar_ring_above():
    """A washer's Leblanc ring (horizontal axis): below the ring's start speed sqrt(g/(R/10))
    the liquid is a puddle held by gravity, a mass without unbalance (pool_response); above it
    the planar quasi-static liquid, whose intact ring adds the mass of the full chamber and
    balances nothing (ring_response); both closed forms to round-off."""
    cfg = load_config("leblanc_washer")
    s, L = cfg.system, cfg.system.liquid
    rot = rotor_of(cfg)
    W = np.linspace(10.0, 150.0, 29)
    V = np.array([0.5e-3, 5.5e-3])
    ds = compute_fill_map("leblanc_washer", fills=V, speeds=W)
    w_ring = np.sqrt(s.gravity.g / (0.1 * L.chamber_radius))
    assert ds.attrs["axis"] == "horizontal"
    np.testing.assert_allclose(ds["entrainment_speed"].values, w_ring, rtol=1e-14)
    below = W < w_ring
    assert below.any() and (~below).any()
    for i, v in enumerate(V):
        np.testing.assert_allclose(ds["amplitude"].values[i][below],
                                   np.abs(pool_response(rot, v, L.density, W[below])), rtol=1e-12)
    vc = np.pi * L.chamber_radius ** 2 * L.chamber_height           # 6.4 l: 5.5 l stays a ring
    ring = np.abs([ring_response(rot, vc, V[1], L.density, w) for w in W[~below]])
    np.testing.assert_allclose(ds["amplitude"].values[1][~below], ring, rtol=1e-6)


@pytest.mark.slow
def test_horizontal_stability_map_reads_the_synchronous_part():
    """On a horizontal axis the stability map measures the spread of the synchronous residual
    unbalance (a revolution average: gravity's once-per-revolution wobble about the sag is not
    unsteadiness). The washer's 250 ml ring at 1000 rpm is steady (spread 0.005); 1000 ml at
    740 rpm is not (0.14, while the raw amplitude spreads by 0.20)."""
    from autobalance.studies._fill_map import compute_stability_map
    w = np.array([740.0, 1000.0]) * np.pi / 30
    st = compute_stability_map("leblanc_washer", fills=[250e-6, 1000e-6], speeds=w,
                               executor="serial")
    assert bool(st["steady"].values[0, 1]) and st["spread"].values[0, 1] < 0.01
    assert not st["steady"].values[1, 0] and st["spread"].values[1, 0] > 0.1
    assert st["in_model"].values.all()
