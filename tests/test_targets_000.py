"""Seed 000 reproduction targets (studies.targets_000): coverage of the paper's items, one row per
published number, figures and data, the quick-mode time budget, and the key numbers.

Every computed target runs once (module fixture, ``Context(quick=True)``). The numbers asserted
here are the ones tests/test_washer_000.py and tests/test_analysis_washer.py assert on the same
cases (their tolerances are justified there and in docs/VALIDATION.md); this file checks that the
report's rows carry them with the right verdicts.
"""
import math
import re
import time

import numpy as np
import pytest
from matplotlib.figure import Figure

from autobalance.validation.target import Context
from conftest import assert_rows_answer_claims
from autobalance.papers.p000.targets import ITEMS_000, PUBLISHED, TARGETS

W1000 = 1000 * 2 * math.pi / 60


@pytest.fixture(scope="module")
def outcomes():
    out, times = {}, {}
    t0 = time.perf_counter()
    for t in TARGETS:
        if t.run is not None:
            t1 = time.perf_counter()
            out[t.id] = t.run(Context(quick=True))
            times[t.id] = time.perf_counter() - t1
    out["_total_s"] = time.perf_counter() - t0
    out["_times"] = times
    return out


def _rows(outcomes, tid):
    return {r["key"].split("/", 1)[1]: r for r in outcomes[tid].rows}


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


def test_quick_budget(outcomes):
    """All 000 targets in --quick within 90 s on the 2-core machine (kernels cached on disk)."""
    assert outcomes["_total_s"] < 90.0, outcomes["_times"]


@pytest.mark.parametrize("t", [t for t in TARGETS if t.run is not None], ids=lambda t: t.id)
def test_rows_answer_every_claim(outcomes, t):
    o = outcomes[t.id]
    assert_rows_answer_claims(t, o.rows)               # quick computes every published number
    assert all(r["quantity"].startswith("000 ") for r in o.rows)


@pytest.mark.parametrize("t", [t for t in TARGETS if t.run is not None], ids=lambda t: t.id)
def test_figures_and_data(outcomes, t, tmp_path):
    o = outcomes[t.id]
    seed_figs = [i for i in t.items if i.startswith("Fig.")]
    if seed_figs:
        assert o.figures
    titles = []
    for name, f in o.figures.items():
        assert isinstance(f, Figure)
        texts = [f._suptitle.get_text() if f._suptitle else ""] + [a.get_title() for a in f.axes]
        assert any("000" in s and ("Fig." in s or "Table" in s) for s in texts), name
        assert any("[" in a.get_ylabel() for a in f.axes), name
        xl = {a.get_xlabel() for a in f.axes if a.get_visible()} - {""}
        assert xl and all("[" in x for x in xl - {"case"}), (name, xl)   # units on numeric axes
        titles += texts
    named = " ".join(titles).replace("Fig. 10-11", "Fig. 10 Fig. 11")
    for item in seed_figs:
        assert re.search(re.escape(item) + r"\b", named), item
    if o.data is not None:
        ds = o.data
        assert all(v.dtype != object for v in ds.data_vars.values())
        assert all(isinstance(v, (str, int, float, np.integer, np.floating)) for v in ds.attrs.values())
        ds.to_netcdf(tmp_path / f"{t.id}.nc")
    assert o.notes


# -- the numbers -------------------------------------------------------------------------------
def _ok(rows):
    return {k: r["ok"] for k, r in rows.items()}


def test_fig5(outcomes):
    r = _rows(outcomes, "000-fig5")
    assert r["alpha1_deg"]["computed"] == pytest.approx(120.0, abs=0.5)
    assert r["alpha2_deg"]["computed"] == pytest.approx(-120.0, abs=0.5)
    assert 3.0 < r["balancing_time_s/c_i_2"]["computed"] < 6.0 and not r["balancing_time_s/c_i_2"]["ok"]
    assert r["balancing_time_s/c_i_7.1"]["computed"] == pytest.approx(1.5, abs=0.5)
    assert r["balancing_time_s/c_i_7.1"]["ok"]


def test_tables_1_2(outcomes):
    """t_f: only Table 1 constant (the calibration) passes; every x_max, y_max and revolution count
    within its tolerance (test_washer_000.py asserts the same on the same runs)."""
    r = _rows(outcomes, "000-table1-2")
    assert len(r) == 24
    miss = {k for k, v in r.items() if not v["ok"]}
    assert miss == {f"table{t}/{law}/t_f_s" for t in (1, 2) for law in ("constant", "linear", "harmonic")} \
        - {"table1/constant/t_f_s"}
    assert r["table1/constant/t_f_s"]["computed"] == pytest.approx(2.23, rel=0.05)
    assert r["table1/harmonic/t_f_s"]["computed"] == "not reached in 25 s"
    assert r["table1/linear/t_f_s"]["computed"] == pytest.approx(-0.532 * W1000 / 25 * math.log(0.01), rel=0.05)


def test_fig10_11(outcomes):
    r = _rows(outcomes, "000-fig10-11")
    assert _ok(r) == {"fig10/ball_direction": True, "fig11/revolutions": True,
                      "fig10/amplitude_with_vs_without_balls": False,
                      "fig11/amplitude_with_vs_without_balls": False}
    assert r["fig11/revolutions"]["computed"] == pytest.approx(7.6, abs=2.5)


def test_closed_form_targets(outcomes):
    r = _rows(outcomes, "000-fig12-eq32")
    assert all(_ok(r).values())
    assert r["eq32_deg"]["computed"] == pytest.approx(2.4, abs=0.05)
    t = _rows(outcomes, "000-tolerance")
    assert _ok(t) == {"eq58_fraction_of_Me": True, "eq60_rho_max_um/Me_0.025": True,
                      "eq60_rho_max_um/Me_0.05": True, "eq62_fraction_of_Me": True,
                      "eq63_f_r_max": False, "eq65_fraction_of_Me": True, "eq66_F_max_N": False}
    assert t["eq63_f_r_max"]["computed"] == pytest.approx(1.69e-4, rel=0.01)
    assert t["eq66_F_max_N"]["computed"] == pytest.approx(4.90, abs=0.01)
    assert "2.45 N" in t["eq66_F_max_N"]["note"] and "49 N" in t["eq66_F_max_N"]["note"]
    f3 = _rows(outcomes, "000-fig3")
    assert _ok(f3) == {"a_930rpm_m_s2": True, "A_930rpm_mm": True, "A_680rpm_mm": False, "A_720rpm_mm": True}
    f15 = _rows(outcomes, "000-fig15")
    assert f15["beta_of_max_deviation_deg"]["ok"]


def test_fig6_7_fig9(outcomes):
    r = _rows(outcomes, "000-fig6-7")
    assert _ok(r) == {"fig6/fig6a/stable_alpha_deg": True, "fig6/fig6b/stable_alpha_deg": True,
                      "fig6/fig6b/negative_to_positive_extreme": False, "fig7/force_with_more_damping": True}
    assert r["fig6/fig6b/negative_to_positive_extreme"]["computed"] > 2.5
    r = _rows(outcomes, "000-fig9")
    assert _ok(r) == {"D_x_um": True, "D_y_um": True, "D_alpha_rad": False}
    assert r["D_alpha_rad"]["computed"] == pytest.approx(0.058, rel=0.1)


def test_washer_studies(outcomes):
    """Same verdicts as tests/test_analysis_washer.py (Fig. 13, 16, 18, Tables 3-4), now keyed."""
    r13 = _rows(outcomes, "000-fig13")
    assert _ok(r13) == {"d_alpha1_deg": False, "d_alpha2_deg": True, "impact_time_wt": False}
    r16 = _rows(outcomes, "000-fig16")
    assert not any(_ok(r16).values())
    assert r16["d_alpha1_deg"]["computed"] == pytest.approx(43.5, abs=0.3)
    r18 = _rows(outcomes, "000-fig18")
    assert _ok(r18) == {"eq49_bound_rad": True, "d_alpha1_rad": True, "d_alpha2_rad": False}
    t = _rows(outcomes, "000-table3-4")
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
