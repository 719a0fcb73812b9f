"""The machine-agnostic studies: the same study runs on a preset, a TOML path or a
Config built in Python, and gives the same numbers for the same machine; no file under papers/
is needed."""
import numpy as np
import pytest

from autobalance.config import load_config
from autobalance.studies import _immobility as immobility
from autobalance.studies import _plateau as plateau
from autobalance.studies import _start_positions as start_positions
from autobalance.studies import common, statistics, unbalance

SHORT = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s",
         "profile.plateau_time=2 s", "profile.up_time=1 s"]


@pytest.fixture(scope="module")
def machine(tmp_path_factory):
    """A short-profile TSR machine as a Config object (not a preset name)."""
    return load_config("vub_jeffcott_004", SHORT)


@pytest.mark.slow
def test_monte_carlo_same_from_a_preset_and_from_a_python_config(machine, tmp_path):
    a = common.run_start_grid("vub_jeffcott_004", "a", SHORT, {}, 4, executor="serial")
    b = common.run_start_grid(machine, "b", [], {}, 4, executor="serial")
    assert a.sizes["sample"] == 10 and np.array_equal(a["grade_G"].values, b["grade_G"].values)
    ds = start_positions.compute_monte_carlo(machine, 4, executor="serial", limit=10.0)
    assert ds.attrs["runs"] == 10 and 0.0 <= ds.attrs["share_G16_TSR"] <= 1.0
    assert ds.attrs["share_G16_TSR"] == pytest.approx(np.mean(ds["G_TSR"].values <= 10.0))
    assert sum(ds.attrs[f"region_{r}"] for r in ("I.A", "I.B", "II", "III", "IV")) == pytest.approx(1.0)


@pytest.mark.slow
def test_unbalance_and_plateau_on_a_python_config(machine):
    ds = unbalance.compute_unbalance(machine, G=[5.0, 25.0], n=3, executor="serial")
    assert ds["grade_G"].shape == (1, 2, 2, 3) and np.isfinite(ds["grade_G"].values).all()
    pl = plateau.compute_plateau(machine, {"low friction": (0.5, 1.0)}, ratios=[1.02, 1.06],
                                 G=[10.0], n=3, executor="serial")
    assert list(pl["case"].values) == ["low friction"] and pl.attrs["ideal"][0] in (1.02, 1.06)


def test_immobility_scales_the_machines_own_friction(machine):
    ds = immobility.compute_immobility(machine, G_ini=20.0, mu_r=(0.5, 2.0), n_conf=24,
                                       speeds=2 * np.pi * np.array([80.0, 100.0, 160.0]))
    im = ds["immobility"].values[:, 0, :]
    assert np.all((0.0 <= im) & (im <= 1.0)) and np.all(im[1] >= im[0])   # more friction: stickier
    assert ds.attrs["plateau_hz"] == pytest.approx(100.0)


def test_statistics_limits():
    # p95 - limit = -11, +4, -11: crossings at 10 * 11/15 and 10 + 10 * 4/15 (linear)
    ranges, eff = statistics.valid_ranges([0, 10, 20], [5, 20, 5], limit=16.0, span=20.0)
    assert ranges == [(0.0, pytest.approx(110 / 15)), (pytest.approx(10 + 40 / 15), 20.0)]
    assert eff == pytest.approx((110 / 15 + 20 - 10 - 40 / 15) / 20)
    g = np.array([3.2, 3.7, 3.9, 8.0])
    assert statistics.mode(g)[0] == 3.5
    assert statistics.regions([1.0], [2.0], 3.0)["I.A"] == 1.0


def test_cases_scale_each_balls_own_friction():
    """A (mu_r, c_r) case scales every ball's rolling resistance, not ball 1's for all."""
    from autobalance.config import replace_values

    assert common.case_sets("vub_jeffcott_004", 0.5, 1.0)[0] == "balancer.rolling_resistance=0.001"
    two = replace_values(load_config("vub_jeffcott_004"), {"balancer.rolling_resistance": [0.002, 0.004]})
    sets = common.case_sets(two, 0.5, 2.0)
    assert sets[0] == "balancer.rolling_resistance=[0.001, 0.002]"
    assert common.load(two, sets).system.balancer.rolling_resistance == (0.001, 0.002)
