"""The studies as a Python API (autobalance.studies): each study a function of the machine (a
preset, a file, a Config, or a System with its profile) and keyword arguments in SI or pint
quantities, returning a result with .to_xarray(), .summary() and .plot(); the same answer as
the command line's JSON."""
from __future__ import annotations

import json

import numpy as np
import pytest
import xarray as xr
from conftest import run_main

from autobalance import studies
from autobalance.config import load_config, registry

CENTRIFUGE = "examples/centrifuge.toml"


def test_every_study_is_a_function_of_the_package():
    for name in ("start_positions", "unbalance_range", "plateau", "speed_map", "immobility",
                 "sensitivity", "runup", "fill_map", "tolerances", "design"):
        assert callable(getattr(studies, name)), name
        assert name in studies.__all__


def test_a_system_and_its_profile_pint_quantities_and_changes(tmp_path):
    """The machine as models built in Python, a change given as a pint quantity and the target
    grade as one: the same result as the file with the change written in it."""
    cfg = load_config(CENTRIFUGE)
    u = registry()
    r = studies.start_positions(cfg.system, profile=cfg.spin, starts=3, executor="serial",
                                changes={"rotor.unbalance": 0.4 * u("g*m")},
                                grade=16 * u("mm/s"))
    ref = studies.start_positions(CENTRIFUGE, starts=3, executor="serial",
                                  changes={"rotor.unbalance": "0.4 g*m"})
    assert isinstance(r.to_xarray(), xr.Dataset)
    assert np.array_equal(r.to_xarray()["grade_G"].values, ref.to_xarray()["grade_G"].values)
    s = r.summary()
    assert s["study"] == "start-positions" and s["machine"] == cfg.name
    fig = r.plot(tmp_path / "sp.png")
    assert fig is not None and (tmp_path / "sp.png").stat().st_size > 10_000


def test_the_api_gives_the_command_lines_answer(capsys):
    """study immobility and speed-map: the API's summary is the CLI's JSON (but the wall time
    and the warnings the CLI adds)."""
    def cli(*args):
        code, out, err = run_main(capsys, [*args, "--json"])
        assert code == 0, err
        return json.loads(out)

    def same(api: dict, c: dict):
        api = json.loads(json.dumps(api, default=lambda x: np.asarray(x).tolist()))
        for k, v in api.items():
            if k in c and k not in ("wall_time_s", "wall_s"):
                assert c[k] == pytest.approx(v) if isinstance(v, float) else c[k] == v, k

    same(studies.immobility(CENTRIFUGE, quick=True, starts=5).summary(),
         cli("study", "immobility", CENTRIFUGE, "--quick", "--starts", "5"))
    same(studies.speed_map(CENTRIFUGE, quick=True).summary(),
         cli("study", "speed-map", CENTRIFUGE, "--quick"))


def test_tolerances_and_speeds_as_quantities():
    u = registry()
    a = studies.tolerances(CENTRIFUGE, grade=6.3, speed=3000 * u("rpm")).summary()
    b = studies.tolerances(CENTRIFUGE, grade=6.3, speed="3000 rpm").summary()
    c = studies.tolerances(CENTRIFUGE, grade=6.3, speed=3000 * np.pi / 30).summary()
    assert a["max_eccentricity_m"] == b["max_eccentricity_m"] == pytest.approx(
        c["max_eccentricity_m"], rel=1e-12)
    assert studies.tolerances(CENTRIFUGE).to_xarray().attrs["max_eccentricity_m"] > 0


def test_bad_machines_are_refused_in_one_line():
    cfg = load_config(CENTRIFUGE)
    with pytest.raises(ValueError, match="profile="):
        studies.as_config(cfg.system)
    with pytest.raises(TypeError, match="machine = 3"):
        studies.as_config(3)
    from autobalance.config import ConfigError
    with pytest.raises(ConfigError, match="rotor.nothing"):
        studies.as_config(CENTRIFUGE, {"rotor.nothing": 1})


def test_fill_map_composes_the_linear_map_like_the_command_line():
    """studies.fill_map(linear=True) is the fill map with the balanced state's stability at
    every point, as `study fill-map --linear` writes it; volumes and speeds as quantities."""
    u = registry()
    r = studies.fill_map("leblanc_003", fills=[150 * u("ml")], speeds=["30 rad/s", "60 rad/s"],
                         linear=True)
    ds = r.to_xarray()
    assert ds["growth_rate"].shape == (1, 2) and ds["fill"].values == pytest.approx([150e-6])
    from autobalance.studies._fill_map import compute_fill_map, compute_linear_map

    ref = compute_linear_map("leblanc_003", fills=ds["fill"].values, speeds=[30.0, 60.0])
    assert np.array_equal(ds["growth_rate"].values, ref["growth_rate"].values)
    plain = studies.fill_map("leblanc_003", fills=[150e-6], speeds=[30.0, 60.0]).to_xarray()
    assert "growth_rate" not in plain
    assert np.array_equal(plain["amplitude"].values,
                          compute_fill_map("leblanc_003", fills=[150e-6],
                                           speeds=[30.0, 60.0])["amplitude"].values)


def test_tolerances_gives_its_budget_per_cause_a_figure_and_a_check(tmp_path):
    """studies.tolerances: the budget per cause of 000 eq 56 as data (summing to the target),
    the residual at each allowed limit within its share, a figure in the config's unbalance
    unit, and check= simulated runs (refused when not an integer >= 0)."""
    r = studies.tolerances(CENTRIFUGE, grade=6.3, check=2)
    ds = r.to_xarray()
    s = r.summary()
    assert list(ds["cause"].values) == ["eccentricity", "rolling", "friction", "other"]
    assert float(ds["budget"].sum()) == pytest.approx(s["target_unbalance_kg_m"], rel=1e-12)
    lim, bud = ds["at_limit"].values[:3], ds["budget"].values[:3]
    assert np.all(lim <= bud * (1 + 1e-9)) and np.isnan(ds["at_limit"].values[3])
    assert ds["simulated_residual"].size == 2 == len(s["simulation_check"]["residuals_kg_m"])
    fig = r.plot(tmp_path / "t.png")
    assert fig.axes[0].get_ylabel() == "residual unbalance [g*m]"
    assert (tmp_path / "t.png").stat().st_size > 10_000
    assert "simulation_check" not in studies.tolerances(CENTRIFUGE, grade=6.3).summary()
    with pytest.raises(ValueError, match="check = -1"):
        studies.tolerances(CENTRIFUGE, check=-1)
