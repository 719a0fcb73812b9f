"""Reproduction targets of the liquid seeds 003 and 001 (autobalance.papers.p003.targets,
autobalance.papers.p001.targets).

The targets are not run here: rows, figures (SVG) and data (NetCDF) come from the session's quick
report (`quick_report` in conftest.py, `autobalance reproduce all --quick`)."""
import numpy as np
import pytest
import xarray as xr

from types import SimpleNamespace

from autobalance.papers.p001 import targets as t001
from autobalance.papers.p003 import targets as t003
from autobalance.validation.target import Rows, Target, claims
from conftest import assert_rows_answer_claims, report_rows, svg_text

tl = SimpleNamespace(TARGETS=t003.TARGETS + t001.TARGETS, ITEMS_003=t003.ITEMS_003,
                     ITEMS_001=t001.ITEMS_001, PUBLISHED={**t003.PUBLISHED, **t001.PUBLISHED})

COMPUTED = [t for t in tl.TARGETS if t.run is not None]


@pytest.fixture
def rows(report_targets):
    """rows("003-fig4") -> that target's rows of the quick report, by key without its prefix."""
    return lambda tid: report_rows(report_targets[tid])


@pytest.fixture
def data(quick_report, report_targets):
    """data("003-fig4") -> the target's dataset as the report wrote it (NetCDF); a target that
    writes several (001-eq3-4: its closed forms and the comparison with the physics) gives its
    first, data("001-eq3-4", 1) the next."""
    _, out = quick_report
    opened = []

    def load(tid, k=0):
        opened.append(xr.open_dataset(out / report_targets[tid]["data"][k]))
        return opened[-1]

    yield load
    for ds in opened:
        ds.close()


def test_items_each_in_exactly_one_target():
    for paper, items in (("003", tl.ITEMS_003), ("001", tl.ITEMS_001)):
        covered = [i for t in tl.TARGETS if t.paper == paper for i in t.items]
        assert sorted(covered) == sorted(items)
        assert len(covered) == len(set(covered))
    assert all(isinstance(t, Target) and t.id.startswith(t.paper + "-") for t in tl.TARGETS)
    assert len({t.id for t in tl.TARGETS}) == len(tl.TARGETS)


def test_published_sections_have_sources():
    for t in tl.TARGETS:
        assert t.published is tl.PUBLISHED[t.id]
        assert t.published["source"].startswith(t.paper)
    for t in tl.TARGETS:
        if t.run is None:  # photographs and schematics: descriptions only, no claims
            assert claims(t) == [] and t.notes


@pytest.mark.parametrize("target", COMPUTED, ids=lambda t: t.id)
def test_rows_answer_every_claim(quick_report, report_targets, target):
    _, out = quick_report
    rec = report_targets[target.id]
    assert_rows_answer_claims(target, rec["rows"])  # quick computes everything
    assert rec["figures"]
    for png in rec["figures"]:  # axis labels with units (shared axes label one panel)
        svg = svg_text((out / png).with_suffix(".svg"))
        assert any("[" in x for ax in svg["axes"] for x in ax["xlabel"]), png
        assert any("[" in y for ax in svg["axes"] for y in ax["ylabel"]), png
    assert rec["run_notes"]


@pytest.mark.parametrize("target", COMPUTED, ids=lambda t: t.id)
def test_data_is_netcdf(data, report_targets, target):
    for k in range(len(report_targets[target.id]["data"])):
        ds = data(target.id, k).load()
        assert ds.data_vars
        assert all(isinstance(a, (str, int, float, np.number)) for a in ds.attrs.values())
    assert report_targets[target.id]["data"]                   # every computed target writes one


def test_003_speeds_g10_pass_standard_g_misses(rows):
    """003 eq 4, eq 6 at half a unit of the last printed digit: all pass with g = 10 m/s^2;
    with standard gravity 0.89, 19.8 and 16.2 miss (28 passes: +-0.5)."""
    r = rows("003-eq4-6")
    assert all(r[k]["ok"] for k in r if k.endswith("g10"))
    assert r["omega0_rad_s/V200ml/g10"]["computed"] == pytest.approx(19.817, abs=1e-3)
    assert r["omega0_rad_s/V300ml/g10"]["computed"] == pytest.approx(16.180, abs=1e-3)
    assert r["bottom_touch_rad_s/g10"]["computed"] == pytest.approx(0.892, abs=1e-3)
    assert r["omega0_rad_s/V100ml/g_standard"]["ok"]
    for k in ("bottom_touch_rad_s", "omega0_rad_s/V200ml", "omega0_rad_s/V300ml"):
        assert not r[f"{k}/g_standard"]["ok"]
    assert r["omega0_rad_s/V300ml/g_standard"]["computed"] == pytest.approx(16.023, abs=1e-3)


def test_003_fig4_free_surface(rows, data):
    r = rows("003-fig4")
    assert all(x["ok"] for x in r.values())
    assert r["shape_above_omega0"]["computed"] < 0.005
    assert list(data("003-fig4")["mode"].values) == [1, 2, 3, 4, 4]


def test_003_fig5_optimum_fill_and_misses(rows, data):
    """The liquid from physics (docs/liquid/film.md sec. 3d, 4): below resonance every fill raises
    the whirl (the least fill is best), above it the whirl falls with the fill until the film
    breaks and then stays flat; the resonance falls with the fill."""
    r = rows("003-fig5")
    assert r["optimum_fill_ml/R200mm"]["computed"] == "0.6: 50; 0.8: 50; 1.0: 250-350; 1.2: 150-350"
    for k in ("optimum_fill_ml/R100mm", "optimum_fill_ml/R150mm", "optimum_fill_ml/R200mm",
              "liquid_reduces_amplitude", "off_optimum/strength", "resonance_rad_s",
              "suspension_frequency_hz"):
        assert not r[k]["ok"], k  # docs/liquid/validation.md sec. 4 misses
    for k in ("sufficient_fill_unbalance", "off_optimum/direction",
              "critical_speed_falls_with_fluid_mass"):
        assert r[k]["ok"], k
    assert r["resonance_rad_s"]["computed"] == "49.0-54.5"
    amp = data("003-fig5")["amplitude_m"].sel(radius_m=0.2)
    assert (amp.sel(omega_ratio=0.8).isel(volume_ml=slice(1, None))
            > amp.sel(omega_ratio=0.8, volume_ml=0.0)).all()          # raises below resonance
    assert (amp.sel(omega_ratio=1.2).isel(volume_ml=slice(1, None))
            < amp.sel(omega_ratio=1.2, volume_ml=0.0)).all()          # lowers above it


def test_003_fig6_radius_and_speed_range(rows):
    r = rows("003-fig6")
    assert r["larger_radius_better"]["ok"]
    assert not r["effective_all_speeds"]["ok"] and r["effective_all_speeds"]["computed"] < 1.0
    assert not r["peak_near_resonance"]["ok"] and r["peak_near_resonance"]["computed"] == "0 of 9"


def test_003_fig7_states(rows):
    r = rows("003-fig7")
    for k in ("a_entrained_rad_s", "d_effective_at_80", "surface_cylindrical",
              "ring_shifted_centre", "entrainment_observed_rad_s", "entrainment_falls_with_fill",
              "omega0_over_omega_r", "no_balancing_before_entrainment"):
        assert r[k]["ok"], k
    for k in ("b_opposite_at_30", "c_against_at_54", "balancing_onset_over_omega_r",
              "entrainment_depends_on_unbalance"):
        assert not r[k]["ok"], k
    assert r["b_opposite_at_30"]["computed"] < 30          # on the unbalance's side (physics)
    assert r["balancing_onset_over_omega_r"]["computed"] >= 0.9
    assert r["no_balancing_before_entrainment"]["computed"] == pytest.approx(1.0, abs=0.02)


def test_001_kinetostatics_and_friction(rows):
    r = rows("001-eq3-4")
    assert r["eq3_solves_eq2"]["ok"] and r["k1_complete_balance"]["ok"]
    assert not r["rises_with_phase_angle"]["ok"]  # 001's damping trend: a miss (docs §4)
    assert all(x["ok"] for x in rows("001-eq5-7").values())


def test_001_liquid_trends(rows):
    """With the liquid from physics every 001 trend misses for a physical reason: below
    resonance the liquid raises the whirl, and the steady synchronous whirl does not depend on
    viscosity (a liquid turning rigidly with the chamber: exactly 1.0)."""
    r = rows("001-fig3-6")
    assert not any(x["ok"] for x in r.values())
    by_v, by_d = (float(x) for x in r["viscosity_over_density"]["computed"].split(" / "))
    assert by_v == 1.0 and by_d == pytest.approx(1.0, abs=0.05)
    assert r["viscosity_at_optimum"]["computed"] == 1.0
    assert float(r["all_regimes"]["computed"].split(" / ")[0]) < 1.0     # before resonance


def test_rows_convention_keys_and_published_come_from_the_path():
    """validation.target.Rows (the one row convention): key = prefix/path, published = the leaf
    (a (lo, hi) range shown as 'lo-hi'), an unknown path fails, shown= overrides the display."""
    rows = Rows("003-fig5", tl.PUBLISHED["003-fig5"])
    r = rows.add("resonance_rad_s", "omega_n [1/s]", "53.8-54.2", "spans", False, "why")
    assert r == {"key": "003-fig5/resonance_rad_s", "quantity": "omega_n [1/s]",
                 "published": "49-57", "computed": "53.8-54.2", "tolerance": "spans",
                 "ok": False, "note": "why"} and rows == [r]
    assert rows.add("optimum_fill_ml/R200mm", "fill [ml]", "150", "50 ml", True)["published"] == 150.0
    m = rows.missing("suspension_frequency_hz", "f [Hz]", shown="9-10 Hz")
    assert m["computed"] is None and m["published"] == "9-10 Hz" and len(rows) == 3
    with pytest.raises(KeyError):
        rows.add("no_such_claim", "x", 1, "-", True)
    t = next(t for t in tl.TARGETS if t.id == "003-eq4-6")
    assert Rows.of(t).prefix == t.key_prefix and Rows.of(t).section is t.published
