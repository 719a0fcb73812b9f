"""Seed 000 reproduction targets (papers.p000.targets): coverage of the paper's items, one row per
published number, figures and data, and the key numbers.

The targets are not run here: the rows, figures (SVG) and data (NetCDF) are those of the session's
quick report (`quick_report` in conftest.py, `autobalance reproduce all --quick`). The numbers
asserted here are the ones tests/test_washer_000.py and tests/test_analysis_washer.py assert on the
same cases (their tolerances are justified there and in docs/VALIDATION.md); this file checks that
the report's rows carry them with the right verdicts. Wall times are in the report
(``wall_time_s``) and in the session's terminal summary, not asserted.
"""
import math
import re

import numpy as np
import pytest
import xarray as xr

from autobalance.papers.p000.targets import ITEMS_000, PUBLISHED, TARGETS
from conftest import assert_rows_answer_claims, report_rows, svg_text

W1000 = 1000 * 2 * math.pi / 60
COMPUTED = [t for t in TARGETS if t.run is not None]


@pytest.fixture
def rows(report_targets):
    """rows("000-fig5") -> that target's rows of the quick report, by key without its prefix."""
    return lambda tid: report_rows(report_targets[tid])


# -- structure ---------------------------------------------------------------------------------
def test_every_item_in_exactly_one_target():
    items = [i for t in TARGETS for i in t.items]
    assert len(items) == len(set(items))
    assert set(items) == set(ITEMS_000)
    assert {f"Fig. {k}" for k in range(1, 20)} | {f"Table {k}" for k in range(1, 5)} <= set(ITEMS_000)
    assert {"eq 32", "eq 49", "eq 60", "eq 63", "eq 66"} <= set(ITEMS_000)
    ids = [t.id for t in TARGETS]
    assert len(ids) == len(set(ids)) and all(i.startswith("000-") and i == i.lower() for i in ids)
    assert all(t.paper == "000" for t in TARGETS)


def test_targets_without_run_explain_why():
    none = [t for t in TARGETS if t.run is None]
    assert {i for t in none for i in t.items} == {"Fig. 1", "Fig. 2", "Fig. 4", "Fig. 8", "Fig. 14", "Fig. 17"}
    assert all(t.notes and not t.published for t in none)


@pytest.mark.parametrize("t", COMPUTED, ids=lambda t: t.id)
def test_rows_answer_every_claim(report_targets, t):
    rec = report_targets[t.id]
    assert_rows_answer_claims(t, rec["rows"])          # quick computes every published number
    assert all(r["quantity"].startswith("000 ") for r in rec["rows"])


@pytest.mark.parametrize("t", COMPUTED, ids=lambda t: t.id)
def test_figures_and_data(quick_report, report_targets, t):
    """Each figure as written (SVG): titled with the seed's item, units on every numeric axis;
    every seed figure of the target named in a title; the data readable as NetCDF."""
    _, out = quick_report
    rec = report_targets[t.id]
    seed_figs = [i for i in t.items if i.startswith("Fig.")]
    if seed_figs:
        assert rec["figures"]
    titles = []
    for png in rec["figures"]:
        svg = svg_text((out / png).with_suffix(".svg"))
        texts = svg["suptitle"] + [s for ax in svg["axes"] for s in ax["texts"]]
        assert any("000" in s and ("Fig." in s or "Table" in s) for s in texts), png
        assert any("[" in y for ax in svg["axes"] for y in ax["ylabel"]), png
        xl = {x for ax in svg["axes"] for x in ax["xlabel"]} - {""}
        assert xl and all("[" in x for x in xl - {"case"}), (png, xl)   # units on numeric axes
        titles += texts
    named = " ".join(titles).replace("Fig. 10-11", "Fig. 10 Fig. 11")
    for item in seed_figs:
        assert re.search(re.escape(item) + r"\b", named), item
    for nc in rec["data"]:
        with xr.open_dataset(out / nc) as ds:
            assert ds.data_vars
            assert all(isinstance(v, (str, int, float, np.integer, np.floating))
                       for v in ds.attrs.values())
    assert rec["run_notes"]


# -- the numbers -------------------------------------------------------------------------------
def _ok(rows):
    return {k: r["ok"] for k, r in rows.items()}


def test_fig5(rows):
    r = rows("000-fig5")
    assert r["alpha1_deg"]["computed"] == pytest.approx(120.0, abs=0.5)
    assert r["alpha2_deg"]["computed"] == pytest.approx(-120.0, abs=0.5)
    assert 3.0 < r["balancing_time_s/c_i_2"]["computed"] < 6.0 and not r["balancing_time_s/c_i_2"]["ok"]
    assert r["balancing_time_s/c_i_7.1"]["computed"] == pytest.approx(1.5, abs=0.5)
    assert r["balancing_time_s/c_i_7.1"]["ok"]


def test_tables_1_2(rows):
    """t_f: only Table 1 constant (the calibration) passes; every x_max, y_max and revolution count
    within its tolerance (test_washer_000.py asserts the same on the same runs)."""
    r = rows("000-table1-2")
    assert len(r) == 24
    miss = {k for k, v in r.items() if not v["ok"]}
    assert miss == {f"table{t}/{law}/t_f_s" for t in (1, 2) for law in ("constant", "linear", "harmonic")} \
        - {"table1/constant/t_f_s"}
    assert r["table1/constant/t_f_s"]["computed"] == pytest.approx(2.23, rel=0.05)
    assert r["table1/harmonic/t_f_s"]["computed"] == "not reached in 25 s"
    assert r["table1/linear/t_f_s"]["computed"] == pytest.approx(-0.532 * W1000 / 25 * math.log(0.01), rel=0.05)


def test_fig10_11(rows):
    r = rows("000-fig10-11")
    assert _ok(r) == {"fig10/ball_direction": True, "fig11/revolutions": True,
                      "fig10/amplitude_with_vs_without_balls": False,
                      "fig11/amplitude_with_vs_without_balls": False}
    assert r["fig11/revolutions"]["computed"] == pytest.approx(7.6, abs=2.5)


def test_closed_form_targets(rows):
    r = rows("000-fig12-eq32")
    assert all(_ok(r).values())
    assert r["eq32_deg"]["computed"] == pytest.approx(2.4, abs=0.05)
    t = rows("000-tolerance")
    assert _ok(t) == {"eq58_fraction_of_Me": True, "eq60_rho_max_um/Me_0.025": True,
                      "eq60_rho_max_um/Me_0.05": True, "eq62_fraction_of_Me": True,
                      "eq63_f_r_max": False, "eq65_fraction_of_Me": True, "eq66_F_max_N": False}
    assert t["eq63_f_r_max"]["computed"] == pytest.approx(1.69e-4, rel=0.01)
    assert t["eq66_F_max_N"]["computed"] == pytest.approx(4.90, abs=0.01)
    assert "2.45 N" in t["eq66_F_max_N"]["note"] and "49 N" in t["eq66_F_max_N"]["note"]
    f3 = rows("000-fig3")
    assert _ok(f3) == {"a_930rpm_m_s2": True, "A_930rpm_mm": True, "A_680rpm_mm": False, "A_720rpm_mm": True}
    f15 = rows("000-fig15")
    assert f15["beta_of_max_deviation_deg"]["ok"]


def test_fig6_7_fig9(rows):
    r = rows("000-fig6-7")
    assert _ok(r) == {"fig6/fig6a/stable_alpha_deg": True, "fig6/fig6b/stable_alpha_deg": True,
                      "fig6/fig6b/negative_to_positive_extreme": False, "fig7/force_with_more_damping": True}
    assert r["fig6/fig6b/negative_to_positive_extreme"]["computed"] > 2.5
    r = rows("000-fig9")
    assert _ok(r) == {"D_x_um": True, "D_y_um": True, "D_alpha_rad": False}
    assert r["D_alpha_rad"]["computed"] == pytest.approx(0.058, rel=0.1)


def test_washer_studies(rows):
    """Same verdicts as tests/test_analysis_washer.py (Fig. 13, 16, 18, Tables 3-4), now keyed."""
    r13 = rows("000-fig13")
    assert _ok(r13) == {"d_alpha1_deg": False, "d_alpha2_deg": True, "impact_time_wt": False}
    r16 = rows("000-fig16")
    assert not any(_ok(r16).values())
    assert r16["d_alpha1_deg"]["computed"] == pytest.approx(43.5, abs=0.3)
    r18 = rows("000-fig18")
    assert _ok(r18) == {"eq49_bound_rad": True, "d_alpha1_rad": True, "d_alpha2_rad": False}
    t = rows("000-table3-4")
    assert len(t) == 40
    assert {k for k, v in t.items() if not v["ok"]} == {
        "table3/rho_0.5mm/d_alpha2_deg", "table3/rho_1mm/d_alpha2_deg", "table3/rho_1mm/A_mm"}
    assert t["table4/rho_0.5mm/d_alpha1_deg"]["computed"] == pytest.approx(18.4, abs=1.2)
    assert t["table4/rho_1mm/RMe_pct"]["computed"] == pytest.approx(29.3, abs=2.0)


def test_published_sections_are_the_paper():
    assert PUBLISHED["fig13"]["impact_time_wt"] == 35.0
    assert PUBLISHED["table3"]["rho_1mm"] == {"A_mm": 0.38, "d_alpha1_deg": 37.5, "d_alpha2_deg": 7.8,
                                              "RMe_pct": 44.4}
    assert PUBLISHED["table4"]["rho_0.05mm"]["d_alpha2_deg"] == 1.5
    assert PUBLISHED["tolerance"]["eq60_rho_max_um"] == {"Me_0.025": 34.0, "Me_0.05": 67.0}


def test_svg_text_reads_titles_and_labels(tmp_path):
    """The SVG reader used above tells titles from axis labels (and can fail)."""
    from matplotlib.figure import Figure

    f = Figure()
    a, b = f.subplots(1, 2)
    f.suptitle("000 Fig. 99 (test)")
    a.set(title="left", xlabel="speed [rad/s]", ylabel="amplitude [mm]")
    b.set(title="right", xlabel="case")
    b.text(0.5, 0.5, "note")
    f.savefig(tmp_path / "f.svg")
    svg = svg_text(tmp_path / "f.svg")
    assert svg["suptitle"] == ["000 Fig. 99 (test)"]
    assert svg["axes"] == [{"texts": ["left"], "xlabel": ["speed [rad/s]"], "ylabel": ["amplitude [mm]"]},
                           {"texts": ["note", "right"], "xlabel": ["case"], "ylabel": []}]
