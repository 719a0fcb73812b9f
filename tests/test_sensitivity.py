"""``study sensitivity``: one change at a time over the same starts, each effect a paired
difference with a bootstrap standard error."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest
import xarray as xr
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.models import ParameterError
from autobalance.studies._sensitivity import (QUANTITIES, compute_sensitivity, default_variants,
                                             quantities, sensitivity_summary)
from autobalance.studies._start_positions import compute_start_positions, load

CENTRIFUGE = str(Path(__file__).resolve().parents[1] / "examples" / "centrifuge.toml")
TOPLOADER = str(Path(__file__).resolve().parents[1] / "examples" / "toploader.toml")
runner = CliRunner()


def test_quantities_by_hand():
    s = np.array([10.2, 10.7, 12.0, 30.0])
    t = np.array([10.2, 9.0, 12.5, 25.0])
    q = quantities(s, t, 20.0, 12.2)
    assert q["mode_first"] == 10.5 and q["mode_last"] == 9.5       # fullest 1 mm/s bin
    assert q["median_first"] == pytest.approx(11.35) and q["share_first"] == 0.75
    assert q["share_last"] == 0.5 and q["p95_last"] == pytest.approx(np.percentile(t, 95))
    # runs: a tie (I.B, not I.A), I.B, I.A, above G_INI at both read-outs (III)
    assert (q["region_I.A"], q["region_I.B"], q["region_III"]) == (0.25, 0.5, 0.25)
    assert set(q) == set(QUANTITIES)


@pytest.mark.slow
def test_a_change_that_changes_nothing_has_no_effect_and_no_noise():
    cfg = load(CENTRIFUGE)
    same = f"balancer.restitution={cfg.system.balancer.restitution!r}"
    ds = compute_sensitivity(cfg, {"same": [same], "contact none": ["balancer.contact=none"]},
                             samples=6, executor="serial", n_boot=20)
    assert np.all(ds["effect"].sel(variant="same").values == 0)
    assert np.all(ds["effect_se"].sel(variant="same").values == 0)
    s = sensitivity_summary(ds)
    assert not any(e["significant"] for e in s["variants"]["same"]["effects"].values())
    assert s["variants"]["contact none"]["overrides"] == ["balancer.contact=none"]


@pytest.mark.slow
def test_each_value_is_the_variants_own_monte_carlo_and_effects_are_differences():
    """The variant's row equals an independent start-position run of that variant (same
    seed, so the same starts); the effect is the difference from the base's row."""
    ds = compute_sensitivity(CENTRIFUGE, {"mu x2": ["balancer.rolling_resistance=0.004",
                                                    "balancer.stiction=0.004"]},
                             samples=8, seed=4, executor="serial", n_boot=10)
    alone = compute_start_positions(load(CENTRIFUGE, ["balancer.rolling_resistance=0.004",
                                                      "balancer.stiction=0.004"]),
                                    samples=8, seed=4, executor="serial")
    g = alone["grade_G"].transpose("sample", "checkpoint").values
    v = ds["value"].sel(variant="mu x2")
    assert float(v.sel(quantity="median_last")) == pytest.approx(np.median(g[:, -1]), rel=1e-12)
    assert float(v.sel(quantity="share_first")) == pytest.approx(np.mean(g[:, 0] <= 16.0))
    eff = ds["effect"].sel(variant="mu x2").values
    assert eff == pytest.approx(v.values - ds["value"].sel(variant="base").values)
    assert np.all(ds["effect_se"].values >= 0)


def test_default_variants_follow_the_machine():
    c = default_variants(CENTRIFUGE)                      # 2 balls, tsr profile
    assert {"contact none", "ball damping x0.5", "rolling resistance x2", "run-up x0.78",
            "plateau x0.96"} <= set(c)
    t = default_variants(TOPLOADER)                       # std profile: no plateau
    assert "plateau x0.96" not in t and "run-up x0.78" in t
    one = default_variants(load(CENTRIFUGE, ["balancer.n_balls=1",
                                            "initial.ball_angles=[0.5]"]))
    assert "contact none" not in one                      # one ball: nothing to touch


@pytest.mark.slow
def test_cli_json_netcdf_and_bad_input(tmp_path):
    r = runner.invoke(app, ["study", "sensitivity", CENTRIFUGE, "--random", "4", "--executor",
                            "serial", "--vary", "balancer.contact=none", "--json",
                            "--out", str(tmp_path / "s.nc"), "--plot", str(tmp_path / "s.png")])
    assert r.exit_code == 0, r.output
    assert (tmp_path / "s.png").stat().st_size > 10_000
    d = json.loads(r.stdout)
    assert d["runs_used"] == 4 and list(d["variants"]) == ["balancer.contact=none"]
    assert set(d["base"]) == set(QUANTITIES)
    ds = xr.load_dataset(tmp_path / "s.nc")
    assert ds.attrs["command"] == "study sensitivity" and ds.sizes["variant"] == 2
    for args, field in ((["--z", "0"], "--z"), (["--vary", "nonsense"], "--vary"),
                        (["--vary", "balancer.n_balls=3"], "balancer.n_balls"),
                        (["--random", "0"], "--random")):
        r = runner.invoke(app, ["study", "sensitivity", CENTRIFUGE, *args])
        assert r.exit_code == 2, r.output
        lines = r.stderr.strip().splitlines()
        assert len(lines) == 1 and lines[0].startswith("error:") and field in lines[0], r.stderr
    with pytest.raises(ParameterError):
        compute_sensitivity(CENTRIFUGE, {}, samples=2)


def test_the_figure_shows_each_effect_and_greys_the_noise():
    """plot_sensitivity on a planted dataset: one cell per variant and quantity, its text the
    effect (mm/s for a grade, percentage points for a share), grey within z standard errors,
    the colour effect / SE clipped at Z_CLIP."""
    from autobalance.plotting.sensitivity import Z_CLIP, plot_sensitivity

    eff = np.array([[0.0, 0.0], [1.5, 0.02], [-0.3, -0.25]])
    se = np.array([[0.0, 0.0], [0.5, 0.05], [0.5, 0.0]])
    ds = xr.Dataset({"effect": (("variant", "quantity"), eff),
                     "effect_se": (("variant", "quantity"), se)},
                    coords={"variant": ["base", "mu x2", "contact none"],
                            "quantity": ["median_last", "share_last"],
                            "unit": ("quantity", ["mm/s", "-"])}, attrs={"starts": 12})
    ax = plot_sensitivity(ds, z=2.0).axes[0]
    cells = {(round(t.get_position()[1]), round(t.get_position()[0])): t for t in ax.texts}
    assert {k: t.get_text() for k, t in cells.items()} == {
        (0, 0): "+1.50", (0, 1): "+2", (1, 0): "-0.30", (1, 1): "-25"}
    grey = {k for k, t in cells.items() if t.get_color() == "0.6"}
    assert grey == {(0, 1), (1, 0)}                  # 0.4 and 0.6 standard errors
    z = ax.images[0].get_array()
    assert z[0, 0] == pytest.approx(3.0) and z[1, 1] == -Z_CLIP   # -0.25 with no noise: clipped
    assert [t.get_text() for t in ax.get_yticklabels()] == ["mu x2", "contact none"]
