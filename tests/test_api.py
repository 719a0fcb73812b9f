"""The public Python API as the README shows it, and the data products of a run."""
import json

import numpy as np
import pytest
import xarray as xr

import autobalance as ab
import autobalance.simulate  # noqa: F401  (must not shadow ab.simulate)
from autobalance.config import load_config


@pytest.mark.slow
def test_readme_snippet_runs():
    cfg = load_config("vub_jeffcott_004", ["balancer.rolling_resistance=0.001"])
    assert callable(ab.simulate)
    sim = ab.simulate(cfg.system, cfg.spin, initial=cfg.initial)
    cps = sim.summary()["checkpoints"]
    assert [c["time_s"] for c in cps] == [18.0, 90.0]
    inits = [ab.InitialState(ball_angles=(a, a + 2.0)) for a in np.linspace(0, 6, 4)]
    batch = ab.simulate_batch([cfg.system] * 4, cfg.spin, inits)
    assert batch.grade_G.shape == (4, 2) and batch.status == ["ok"] * 4


def test_netcdf_round_trip_has_units_and_provenance(tmp_path):
    cfg = load_config("washer_000")
    sim = ab.simulate(cfg.system, cfg.spin, initial=cfg.initial)
    path = tmp_path / "run.nc"
    sim.to_netcdf(path)
    with xr.open_dataset(path) as ds:
        assert ds["grade_G"].attrs["units"] == "mm/s"
        assert ds["alpha"].dims == ("time", "ball") and ds["alpha"].attrs["units"] == "rad"
        assert ds.attrs["autobalance_version"] == ab.__version__
        system = json.loads(ds.attrs["system"])
        assert system["suspension"]["kx"] == 20000.0
        assert np.allclose(ds["x"].values, sim.x)
        assert np.allclose(ds["residual_unbalance"].values, sim.residual_unbalance)
    assert sim.t[-1] == 8.0 and np.all(np.diff(sim.t) > 0)


def test_summary_is_strict_json():
    cfg = load_config("washer_000")
    sim = ab.simulate(cfg.system, cfg.spin, initial=cfg.initial)
    text = json.dumps(sim.summary(), allow_nan=False)
    d = json.loads(text)
    for key in ("final", "checkpoints", "max_amplitude_m", "x_max_m", "y_max_m",
                "ball_revolutions", "ball_settle_time_s", "solver"):
        assert key in d
    assert d["final"]["ball_angles_deg"][0] == sim.at(8.0)["ball_angles_deg"][0]


def test_sweep_is_the_function_and_the_package_still_imports():
    import autobalance.sweep as pkg  # noqa: F401
    from autobalance.sweep import SweepSpec  # noqa: F401
    assert callable(ab.sweep)
