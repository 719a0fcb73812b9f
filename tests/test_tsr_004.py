"""Seed-004 TSR studies (papers/p004/tsr.py, cli/reproduce.py): quick variants only.

Checks the comparison-row machinery, that every published number is compared (never silently
skipped), the immobility closed form against the kernel, and the CLI end to end. The studies
themselves (single run, Monte Carlo, unbalance range, profile, immobility, plateau, descent) are
not run again here: their rows and NetCDF data are those of the session's quick report
(`quick_report` in conftest.py)."""
import json
import math
import shutil

import numpy as np
import pytest
import xarray as xr
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.papers.p004 import tsr as t

ROW_KEYS = {"key", "quantity", "published", "computed", "tolerance", "ok", "note"}


def _check_rows(rows):
    assert rows
    for r in rows:
        assert set(r) - {"status"} == ROW_KEYS          # the report adds the status it derived
        assert isinstance(r["ok"], bool)
        json.dumps(r, default=float)
        if r["computed"] is None:          # not computed: must be reported as a miss
            assert r["ok"] is False and "not computed" in r["note"]


def _published_numbers(d):
    """Every number in a PUBLISHED entry (source strings excluded)."""
    if isinstance(d, dict):
        return [x for k, v in d.items() if k != "source" for x in _published_numbers(v)]
    if isinstance(d, (list, tuple)):
        return [x for v in d for x in _published_numbers(v)]
    return [d] if isinstance(d, (int, float)) else []


# -- immobility: closed form vs kernel ---------------------------------------------------------
@pytest.mark.parametrize("alpha", [(0.3, 2.0), (1.0, -2.5), (3.0, 3.6), (-1.2, 0.4)])
@pytest.mark.parametrize("f_hz", [60.0, 94.2, 100.0, 167.0])
def test_immobility_closed_form_equals_kernel(alpha, f_hz):
    s = t._cfg().system
    w = 2 * np.pi * f_hz
    a = np.array(alpha)
    lam, lim, acc = t.kernel_required_friction(s, w, a)
    Ft = t.tangential_force(s, w, a)
    R = s.balancer.race_radius
    # required friction torque = -(driving torque F_t R), 004 eq 1 / eq 10 ball row
    np.testing.assert_allclose(lam, -Ft * R, rtol=1e-9, atol=1e-15)
    np.testing.assert_allclose(lim, 0.002 * s.balancer.masses * R * R * w * w, rtol=1e-12)
    assert np.all(np.abs(acc) < 1e-9)       # steady orbit: the rotor does not accelerate
    stuck = bool(np.all(np.abs(lam) <= lim))
    assert stuck == bool(t.immobile_mask(s, w, a))


def test_steady_deflection_matches_pack_orbit():
    from autobalance.physics.response import steady_orbit_start

    s = t._cfg().system
    a = np.array([0.4, 2.9])
    for w in (300.0, 592.0, 1049.0):
        x, y, _, _ = steady_orbit_start(s, w, a)
        z = t.steady_deflection(s, w, a)
        assert abs(z - complex(x, y)) < 1e-12 * max(abs(z), 1e-12)


def test_immobility_limits_and_eq1_direction():
    s = t._cfg().system
    # far below resonance the deflection is tiny: nothing moves; near resonance most can
    im = t.immobility(s, 2 * np.pi * np.array([30.0, 95.0]), n_conf=40)
    assert im[0] == 1.0 and im[1] < 0.5
    # 004 eq 1: the force drives a ball towards the deflection (gamma > 0 -> F_t > 0)
    a = np.array([0.0, np.pi])
    w = 2 * np.pi * 80.0
    z = t.steady_deflection(s, w, a)
    g = np.angle(z * np.exp(-1j * a))
    assert np.all(np.sign(t.tangential_force(s, w, a)) == np.sign(np.sin(g)))


@pytest.mark.parametrize("f_hz", [96.08, 100.0, 167.0])
def test_stick_threshold_bounds_immobility(f_hz):
    """Every configuration whose residual grade is below G* is immobile (closed form). At the
    plateau speeds some configuration just above G* can move: the bound is sharp there. (At
    167 Hz, G* = 50.5 is only reached with both balls near the unbalance, along w: all stick.)"""
    s = t._cfg().system
    w, wn = 2 * np.pi * f_hz, t._cfg().spin.nominal_speed
    g_star = float(t.stick_threshold_grade(s, w, wn))
    pos = 2 * np.pi * np.arange(240) / 240
    a = np.stack([x.ravel() for x in np.meshgrid(pos, pos, indexing="ij")], axis=-1)
    ut = s.rotor.unbalance + np.sum(s.balancer.masses * s.balancer.race_radius * np.exp(1j * a), -1)
    g_res = t._grade(np.abs(ut), s.total_mass, wn)
    stuck = t.immobile_mask(s, w, a)
    assert g_res.min() < g_star < g_res.max()
    assert stuck[g_res <= g_star].all()
    band = (g_res > g_star) & (g_res < 1.05 * g_star)
    assert band.sum() > 20
    assert stuck[band].all() if f_hz == 167.0 else not stuck[band].all()
    # 004 Table 1 at the 100 Hz plateau: G* = mu R Omega_nom / A, A = 5.45 (hand calculation)
    if f_hz == 100.0:
        assert abs(g_star - 13.47) < 0.01


def test_plateau_speed_of_the_preset():
    assert t.plateau_speed(t._cfg().spin) == pytest.approx(2 * np.pi * 100.0)


# -- statistics helpers ------------------------------------------------------------------------
def test_regions_partition_and_table2():
    rng = np.random.default_rng(1)
    s, u = rng.uniform(0, 40, 500), rng.uniform(0, 40, 500)
    r = t.regions(s, u, 20.0)
    assert math.isclose(sum(r.values()), 1.0)
    # a hand case per region
    assert t.regions([10], [12], 20)["I.A"] == 1 and t.regions([12], [10], 20)["I.B"] == 1
    assert t.regions([25], [10], 20)["II"] == 1 and t.regions([25], [30], 20)["III"] == 1
    assert t.regions([10], [25], 20)["IV"] == 1


def test_regions_with_a_tie_tolerance_count_unchanged_runs_as_unchanged():
    """Strict Table 2 regions split a run that the speed reduction left unchanged by round-off
    (G_TSR = G_STD + 1e-6 is I.A, - 1e-6 is I.B); with the tie tolerance both are I.B, and
    grades at G_INI within it count as G_INI. A tie of 0 is the strict table."""
    from autobalance.studies.statistics import TIE_MM_S

    assert t.regions([13.5], [13.5 + 1e-6], 20)["I.A"] == 1
    assert t.regions([13.5], [13.5 + 1e-6], 20, TIE_MM_S)["I.B"] == 1
    assert t.regions([13.5], [13.5 - 1e-6], 20, TIE_MM_S)["I.B"] == 1
    assert t.regions([13.5], [13.5 + 0.1], 20, TIE_MM_S)["I.A"] == 1            # a real change
    assert t.regions([20.0 + 1e-6], [10.0], 20)["II"] == 1
    assert t.regions([20.0 + 1e-6], [10.0], 20, TIE_MM_S)["I.B"] == 1           # at G_INI: success
    rng = np.random.default_rng(2)
    s = rng.uniform(0, 40, 2000)
    u = np.where(rng.random(2000) < 0.5, s + rng.normal(0, 1e-3, 2000), rng.uniform(0, 40, 2000))
    for tie in (0.0, 1e-4, TIE_MM_S, 0.5):
        r = t.regions(s, u, 20.0, tie)
        assert math.isclose(sum(r.values()), 1.0)                              # still a partition
    assert t.regions(s, u, 20.0, 0.0) == t.regions(s, u, 20.0)
    strict, tied = t.regions(s, u, 20.0), t.regions(s, u, 20.0, TIE_MM_S)
    assert tied["I.A"] < strict["I.A"] and tied["I.B"] > strict["I.B"]


@settings(max_examples=300, deadline=None)
@given(st.sampled_from([0.0, 5.0, 10.0, 20.0]), st.sampled_from([0.0, 5.0, 10.0, 20.0]),
       st.floats(0, 40), st.sampled_from([0.0, 1e-6, 0.02, 1.0]),
       st.sampled_from([0.0, 1e-7, -1e-7, 0.01, -0.01, 3.0]))
def test_every_run_is_in_exactly_one_region_even_on_ties(s, u, g_ini, tie, eps):
    """Ties (equal grades, or grades snapped together by the tie tolerance) leave no run out."""
    r = t.regions([s + eps], [u], g_ini, tie)
    assert sorted(r.values()) == [0.0, 0.0, 0.0, 0.0, 1.0]
    r = t.regions([s], [s + eps], s, tie)
    assert sorted(r.values()) == [0.0, 0.0, 0.0, 0.0, 1.0]


def test_valid_ranges_interpolation():
    G = np.array([0.0, 10, 20, 30, 40, 50])
    p95 = np.array([12.0, 20, 20, 14, 14, 30])
    r, eff = t.valid_ranges(G, p95)
    assert len(r) == 2
    assert r[0] == (0.0, 5.0)
    assert math.isclose(r[1][0], 20 + 10 * 4 / 6) and math.isclose(r[1][1], 40 + 10 * 2 / 16)
    assert math.isclose(eff, (5 + (r[1][1] - r[1][0])) / 50)
    assert t.valid_ranges(G, np.full(6, 30.0)) == ([], 0.0)
    assert t.valid_ranges(G, np.full(6, 1.0)) == ([(0.0, 50.0)], 1.0)


def test_share_tolerance_is_binomial():
    # 2 sigma of the difference of two binomial shares, 1275 runs each
    assert math.isclose(t._share_tol(0.85, 1275), 2 * math.sqrt(0.85 * 0.15 * 2 / 1275))


def test_grade_conversion_roundtrip():
    cfg = t._cfg()
    s, w = cfg.system, cfg.spin.nominal_speed
    U = t.grade_to_unbalance(20.0, s.total_mass, w)
    assert math.isclose(float(t._grade(U, s.total_mass, w)), 20.0)
    assert abs(float(t._grade(s.rotor.unbalance, s.total_mass, w)) - 20.0) < 0.5


# -- every published number is compared ---------------------------------------------------------
def test_unbalance_rows_cover_every_case_even_when_not_computed():
    import xarray as xr

    G = np.array([0.0, 10, 20, 30, 40, 50])
    data = np.full((1, 6, 2, 3), 30.0)
    data[0, :2, 1, 2] = 10.0                              # TSR p95 fine at G0-G10
    ds = xr.Dataset({"grade_G": (("case", "G_ini", "procedure", "percentile"), data)},
                    coords={"case": ["nominal"], "G_ini": G, "procedure": ["STD", "TSR"],
                            "percentile": [5.0, 50.0, 95.0], "mu_r": ("case", [1.0]),
                            "c_r": ("case", [1.0])})
    ds.attrs.update({"grid_step": 10.0, "G_balls": 33.7})
    rows = t.compare_unbalance(ds)
    _check_rows(rows)
    # 5 cases x 2 procedures x (range, efficiency)
    assert len(rows) == 20
    pub = [r["published"] for r in rows if "efficiency" in r["quantity"]]
    want = [100 * v[p]["efficiency"] for k, v in t.PUBLISHED["unbalance"].items() if k != "source"
            for p in ("STD", "TSR")]
    assert sorted(pub) == sorted(want)
    missing = [r for r in rows if r["computed"] is None]
    assert len(missing) == 16 and not any(r["ok"] for r in missing)
    std_eff = next(r for r in rows if "mu_r=1 c_r=1 STD efficiency" in r["quantity"])
    assert std_eff["computed"] == 0.0 and std_eff["ok"]       # '/' published, none computed


def test_plateau_rows_cover_both_published_ideals():
    import xarray as xr

    ratios = np.array([0.98, 1.02, 1.06])
    ds = xr.Dataset({"grade_G_p95": (("case", "plateau_ratio", "G_ini"), np.ones((1, 3, 2)))},
                    coords={"case": ["nominal"], "plateau_ratio": ratios, "G_ini": [5.0, 15.0]})
    ds.attrs.update({"ideal": [1.02], "ratio_step": 0.04, "f_n_hz": 94.23})
    rows = t.compare_plateau(ds)
    _check_rows(rows)
    pubs = [r["published"] for r in rows]
    assert 1.02 in pubs and 1.03 in pubs
    assert [r["ok"] for r in rows] == [True, True, False]   # c0.5 not computed -> miss


def test_monte_carlo_rows_cover_table2_and_shares():
    import xarray as xr

    rng = np.random.default_rng(0)
    n = 10
    s = rng.uniform(5, 25, n * (n + 1) // 2)
    ds = xr.Dataset({"G_STD": ("sample", s), "G_TSR": ("sample", s * 0.8),
                     "status": ("sample", np.zeros(s.size, int))})
    a = {"n": n, "runs": s.size, "G_ini": 20.2, "G_balls": 33.7, "mode_STD": 15.0, "mode_STD_se": 0.5,
         "mode_TSR": 11.0, "mode_TSR_se": 0.5, "median_STD": 15.0, "median_TSR": 12.0,
         "share_G16_STD": 0.85, "share_G16_TSR": 0.8, "success_STD": 0.95, "success_TSR": 0.98}
    a.update({f"region_{k}": v for k, v in t.regions(s, s * 0.8, 20.2).items()})
    ds.attrs.update(a)
    rows = t.compare_monte_carlo(ds)
    _check_rows(rows)
    pub = t.PUBLISHED["monte_carlo"]
    got = {r["published"] for r in rows}
    for k, v in pub["regions"].items():
        assert 100 * v in got
    for k in ("share_G16_STD", "share_G16_TSR", "success_STD", "success_TSR"):
        assert 100 * pub[k] in got
    for k in ("mode_STD", "mode_TSR", "runs"):
        assert pub[k] in got
    assert len(rows) == 1 + 2 + 4 + 5


def test_published_numbers_all_reach_a_row():
    """Every number in PUBLISHED appears as a published value of some comparison row."""
    import xarray as xr

    rows = []
    # single: from a synthetic dataset
    single = xr.Dataset(attrs={"G_ini": 20.2, "G_start": 14.0, "G_peak_runup": 30.0, "G_STD": 18.0,
                               "G_TSR": 5.0, "start_angles_deg": [0.0, 160.0], "family_n": 14,
                               "family_match": 3, "family_peak_gt_ini": 10,
                               "family_std_in_16_ini": 3, "family_tsr_le_16": 14})
    rows += t.compare_single(single)
    rows += t.compare_plateau(xr.Dataset(
        {"grade_G_p95": (("case", "plateau_ratio", "G_ini"), np.ones((2, 2, 1)))},
        coords={"case": ["nominal", "c0.5"], "plateau_ratio": [1.02, 1.03], "G_ini": [5.0]},
        attrs={"ideal": [1.02, 1.03], "ratio_step": 0.01, "f_n_hz": 94.23}))
    got = set()
    for r in rows:
        got.add(r["published"])
    for k in ("G_ini", "G_start", "G_peak_runup", "G_STD", "G_TSR"):
        assert t.PUBLISHED["single"][k] in got
    for v in t.PUBLISHED["plateau"]["ideal"].values():
        assert v in got
    rows = t.compare_descent(xr.Dataset(attrs={
        "half_drop_median": 1.09, "half_drop_p95": 1.1, "G_ini": 5.0, "runs": 1275,
        "ratio_end": 0.9, "down_time_s": 60.0, "p95_min": 17.0, "p95_min_ratio": 1.05,
        "p95_rise_ratio": math.nan, "p95_max_after": 17.0}))
    assert [r["published"] for r in rows] == [1.1, "some outcomes deteriorate"]
    assert [r["ok"] for r in rows] == [True, False]


# -- the studies themselves, quick variants, as the quick report ran them ---------------------------
@pytest.fixture
def study(quick_report, report_targets):
    """study("004-fig4") -> (the report's record of that target, its dataset as written)."""
    _, out = quick_report
    opened = []

    def get(tid):
        rec = report_targets[tid]
        (nc,) = rec["data"]
        opened.append(xr.open_dataset(out / nc))
        return rec, opened[-1]

    yield get
    for ds in opened:
        ds.close()


def test_single_run_quick(quick_report, study):
    _, out = quick_report
    rec, ds = study("004-fig4")
    assert ds.attrs["status"] == "ok"
    assert abs(ds.attrs["G_start"] - 14.0) < 1e-6
    # without balancer the grade never changes; amplitude peaks at the resonance crossing
    k = int(np.argmax(ds["amplitude_no_balancer"].values))
    f = ds["speed"].values[k] / (2 * np.pi)
    assert 85 < f < 100
    rows = rec["rows"]
    _check_rows(rows)
    assert len(rows) == 6 and not rec["unreported"]
    assert rows[0]["ok"] and rows[1]["ok"]
    assert (out / "figures" / "004-fig4-tsr-single.png").stat().st_size > 1000


def test_compute_immobility_rows_quick(study):
    rec, ds = study("004-fig8-10")
    assert ds["immobility"].dims == ("mu_r", "c_r", "speed")
    assert ds["immobility"].shape == (5, 4, 91)
    _check_rows(rec["rows"])
    assert len(rec["rows"]) == 4


def test_monte_carlo_quick(quick_report, study):
    """12 x 12 start grid (78 runs), and the sensitivity run at 004's ideal plateau."""
    _, out = quick_report
    rec, ds = study("004-fig5-6-table2")
    assert ds.attrs["runs"] == 78 and ds.attrs["failed"] == 0
    reg = sum(ds.attrs[f"region_{k}"] for k in ("I.A", "I.B", "II", "III", "IV"))
    assert math.isclose(reg, 1.0)
    rows = rec["rows"]
    _check_rows(rows)
    assert rows[0]["computed"] == 78 and rows[0]["ok"] and len(rows) == 12
    assert ds.attrs["G_stick_plateau"] == pytest.approx(13.47, abs=0.01)
    assert "G* = 13.47" in next(r["note"] for r in rows if r["key"] == "monte_carlo/mode_TSR")
    assert sorted(p.name for p in (out / "stores").glob("mc-*")) == ["mc-n12", "mc-n12-plateau1.02"]
    # the sensitivity run at 004's ideal plateau: reported in the notes and saved with the data
    assert "plateau at 004's ideal 1.02 Omega_n (96.1 Hz)" in rec["run_notes"]
    assert ds["G_TSR_ideal"].shape == ds["G_TSR"].shape
    assert abs(ds.attrs["ideal_G_stick_plateau"] - 11.46) < 0.01


def test_unbalance_and_profile_quick(study):
    rec, ub = study("004-fig7-11-12-table3-4")
    assert ub["grade_G"].dims == ("case", "G_ini", "procedure", "percentile")
    assert ub["grade_G"].shape == (len(t.UNBALANCE_CASES), 11, 2, 3)     # G0-G50 every 5 mm/s
    assert np.all(np.isfinite(ub["grade_G"].values))
    p = ub["grade_G"].sel(case="nominal", percentile=95.0).values
    assert np.all(p >= ub["grade_G"].sel(case="nominal", percentile=5.0).values)
    _check_rows(rec["rows"])
    prec, pr = study("004-fig9")
    assert list(pr["procedure"].values) == ["STD", "TSR", "slow"]
    np.testing.assert_array_equal(pr["grade_G"].sel(procedure="STD").values,
                                  ub["grade_G"].sel(case="nominal", procedure="STD").values)
    _check_rows(prec["rows"])
    assert len(prec["rows"]) == 3


def test_plateau_quick(study):
    rec, ds = study("004-fig14-16")
    assert ds["grade_G_p95"].dims == ("case", "plateau_ratio", "G_ini")
    assert ds["grade_G_p95"].shape == (len(t.PLATEAU_CASES), 4, 3)
    ideal = json.loads(ds.attrs["ideal"])                 # list attributes are JSON in NetCDF
    assert ideal[0] in ds["plateau_ratio"].values
    rows = rec["rows"]
    _check_rows(rows)
    assert rows[0]["ok"]                           # 100 Hz / f_n = 1.06


def test_half_drop_and_rise_after_min_synthetic():
    r = np.linspace(1.5, 0.9, 61)                   # descending speed ratio, step 0.01
    g = np.where(r > 1.2, 20.0, np.where(r > 1.1, 20.0 - 100.0 * (1.2 - r), 10.0))
    assert t._half_drop(r, g) == pytest.approx(1.15)     # 20 -> 10: halfway (15) at 1.15
    assert math.isnan(t._half_drop(r, np.full_like(r, 7.0)))
    g2 = g.copy()
    g2[r < 0.97] = 12.0                            # the worst outcomes deteriorate below 0.97
    d = t._rise_after_min(r, g2)
    assert d["p95_min"] == 10.0 and d["p95_rise_ratio"] == pytest.approx(0.96)
    assert math.isnan(t._rise_after_min(r, g)["p95_rise_ratio"])


def test_descent_quick(study):
    """004 Fig. 13: a small descent (6 x 6 start grid); every grade stays within the balancer's
    reach and the rows are well formed."""
    rec, ds = study("004-fig13")
    assert ds.attrs["runs"] == 21 and ds.attrs["failed"] == 0
    r = ds["ratio"].values
    assert r[0] == pytest.approx(167.0 / ds.attrs["f_n_hz"]) and r[-1] == pytest.approx(0.9)
    assert np.all(np.diff(r) < 0)                   # the speed decreases along the descent
    assert ds["grade_G"].dims[0] == "percentile"
    g = ds["grade_G"].values
    assert np.all(np.diff(g, axis=0) >= 0)          # percentiles ordered
    assert g.max() <= ds.attrs["G_ini"] + ds.attrs["G_balls"] + 1e-9
    rows = rec["rows"]
    _check_rows(rows)
    assert [x["key"] for x in rows] == ["descent/prompt_reduction", "descent/worse_near_resonance"]


# -- CLI ---------------------------------------------------------------------------------------------
runner = CliRunner()


@pytest.mark.slow
def test_cli_immobility_json_and_plot(tmp_path):
    png = tmp_path / "im.png"
    r = runner.invoke(app, ["study", "immobility", "vub_jeffcott_004", "--json", "--plot", str(png),
                            "--mu-r", "0.5,1", "--c-r", "1,1.4", "--starts", "24"])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    # the machine's own grade (ISO 1940 with the total mass): 1e3 U / (M + 2 m) Omega_nom
    assert d["G_ini_mm_s"] == pytest.approx(1e3 * 0.319029e-3 / (16.53 + 2 * 0.0076)
                                            * 2 * np.pi * 167, rel=1e-9)
    assert np.asarray(d["immobility_by_case"]).shape[:2] == (2, 2)
    assert png.stat().st_size > 1000 and d["plot"] == str(png)


@pytest.mark.slow
def test_cli_reproduce_single_target_text(tmp_path):
    """One target by name, text output: the summary line, one progress line, its figure and a
    report of that target alone (004-table1-fig3: the cheapest 004 target; 004-fig4's own rows
    and figure are checked on the quick report above)."""
    r = runner.invoke(app, ["reproduce", "004-table1-fig3", "--out-dir", str(tmp_path)])
    assert r.exit_code == 0, r.output
    assert "published quantities reproduced" in r.stdout
    assert r.stderr.startswith("[1/1] 004-table1-fig3")   # progress, one line per target
    assert (tmp_path / "figures" / "004-table1-fig3-profile.png").stat().st_size > 1000
    rep = json.loads((tmp_path / "report.json").read_text())
    assert [x["id"] for x in rep["targets"]] == ["004-table1-fig3"]
    assert len(rep["targets"][0]["rows"]) == 3 and not rep["targets"][0]["unreported"]


def test_cli_reproduce_monte_carlo_json_resumes(quick_report, report_targets, tmp_path):
    """The sweep stores are reused: given the quick report's finished Monte-Carlo stores, a
    rerun (another executor) computes nothing new and gives the report's rows."""
    _, out = quick_report
    for store in ("mc-n12", "mc-n12-plateau1.02"):
        shutil.copytree(out / "stores" / store, tmp_path / "stores" / store)
    def files():
        """Every file of the stores but the lock (taken by each run) and its mtime."""
        return {p.relative_to(tmp_path): p.stat().st_mtime_ns
                for p in (tmp_path / "stores").rglob("*") if p.is_file() and p.name != "lock"}

    before = files()
    args = ["reproduce", "004-fig5-6-table2", "--executor", "serial", "--json", "--out-dir", str(tmp_path)]
    r = runner.invoke(app, args)
    assert r.exit_code == 0, r.output
    assert json.loads(r.stdout)["targets"][0]["rows"] == report_targets["004-fig5-6-table2"]["rows"]
    assert sorted(p.name for p in (tmp_path / "stores").iterdir()) == ["mc-n12", "mc-n12-plateau1.02"]
    assert files() == before                                # nothing computed or written again


@pytest.mark.parametrize("args,word", [
    (["reproduce", "004-bogus"], "TARGET"),
    (["reproduce", "004", "--workers", "0"], "--workers"),
    (["reproduce", "004", "--executor", "threads"], "--executor"),
    (["reproduce", "004", "--executor", "dask"], "--scheduler"),
    (["study", "immobility", "vub_jeffcott_004", "--c-r", "-1"], "--c-r"),
    (["study", "immobility", "vub_jeffcott_004", "--g-ini", "-3"], "--g-ini"),
])
def test_cli_bad_input_one_line_exit_2(args, word, monkeypatch):
    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    r = runner.invoke(app, args)
    assert r.exit_code == 2
    out = r.output.strip()
    assert out.startswith("error:") and word in out and "\n" not in out


def test_cli_reproduce_out_is_a_file(tmp_path):
    f = tmp_path / "x"
    f.write_text("keep")
    r = runner.invoke(app, ["reproduce", "004-fig8-10", "--out-dir", str(f)])
    assert r.exit_code == 2 and "--out" in r.output and f.read_text() == "keep"


def test_cli_every_target_listed():
    r = runner.invoke(app, ["reproduce", "004", "--list"])
    assert r.exit_code == 0
    for tg in t.TARGETS:
        assert tg.id in r.output


# -- immobility with in-plane gravity (a horizontal axis; physics/immobility.py) -------------
@pytest.mark.parametrize("alpha, f_hz", [((0.3, 2.0), 30.0), ((1.0, -2.5), 100.0)])
def test_immobility_with_gravity_is_the_kernels_over_a_revolution(alpha, f_hz):
    """004's rig turned horizontal (g = 9.81 m/s^2 in the plane): at any spin angle the kernel's
    stuck-ball friction is the steady part less the weight's tangential part, m g sin(phi) R,
    and its limit mu_s m R (R Omega^2 + g cos phi) (000 eq 50, phi the ball's angle from
    gravity; 8 angles, to 1e-9). Through a revolution the ball stays iff |F_t| + m g
    sqrt(1 + mu_s^2) <= mu_s m R Omega^2: the mask agrees with those expressions sampled at
    3600 angles, and differs from the mask without gravity where gravity decides."""
    import dataclasses

    s0 = t._cfg().system
    s = dataclasses.replace(s0, gravity=dataclasses.replace(s0.gravity, g=9.81))
    w = 2 * np.pi * f_hz
    a = np.array(alpha)
    m, R, mu = s.balancer.masses, s.balancer.race_radius, np.asarray(s.balancer.stiction)
    Ft = t.tangential_force(s, w, a)
    gdir = s.gravity.direction
    for psi in np.linspace(0.0, 2 * np.pi, 8, endpoint=False):
        lam, lim, _ = t.kernel_required_friction(s, w, a, phase=psi)
        phi = psi + a - gdir
        np.testing.assert_allclose(lam, -(Ft - m * 9.81 * np.sin(phi)) * R, rtol=1e-9,
                                   atol=1e-12 * float(np.max(m)) * R * R * w * w)
        np.testing.assert_allclose(lim, mu * m * R * (R * w * w + 9.81 * np.cos(phi)),
                                   rtol=1e-9)
    phi = np.linspace(0.0, 2 * np.pi, 3600, endpoint=False)[:, None]
    margin = np.abs(Ft - m * 9.81 * np.sin(phi)) - mu * m * (R * w * w + 9.81 * np.cos(phi))
    closed = np.abs(Ft) + m * 9.81 * np.sqrt(1 + mu * mu) - mu * m * R * w * w
    np.testing.assert_allclose(margin.max(axis=0), closed, rtol=0, atol=1e-6 * float(m.max()))
    assert bool(t.immobile_mask(s, w, a)) == bool(np.all(closed <= 0))
    if f_hz < 59.6:             # below gravity's own speed: it alone moves the balls
        assert t.immobile_mask(s0, w, a) and not t.immobile_mask(s, w, a)


def test_gravity_alone_moves_balls_below_its_speed():
    """Below Omega^2 = g sqrt(1 + mu_s^2) / (mu_s R) (59.6 Hz on 004's rig: mu_s = 0.002,
    R = 35 mm) no ball at rest stays: immobility 0, G* = 0; far above it (167 Hz) G* moves by
    the relative g / (mu_s R Omega^2) only, so `study immobility` does not give a horizontal
    machine the vertical one's numbers."""
    import dataclasses

    s0 = t._cfg().system
    s = dataclasses.replace(s0, gravity=dataclasses.replace(s0.gravity, g=9.81))
    R, mu = s.balancer.race_radius, float(np.max(s.balancer.stiction))
    w_g = math.sqrt(9.81 * math.sqrt(1 + mu * mu) / (mu * R))
    wn = t._cfg().spin.nominal_speed
    assert t.immobility(s, 0.9 * w_g, n_conf=24) == 0.0
    assert t.stick_threshold_grade(s, 0.9 * w_g, wn) == 0.0
    assert t.immobility(s0, 0.9 * w_g, n_conf=24) == 1.0          # without gravity: all stay
    hi = 2 * np.pi * 167.0
    assert float(t.stick_threshold_grade(s, hi, wn)) == pytest.approx(
        float(t.stick_threshold_grade(s0, hi, wn)), rel=2 * 9.81 / (mu * R * hi * hi))
