"""More starts where a decision is undecided (autobalance.studies.sequential): the budget is
never overspent, samples double per round up to the cap, every round draws its own starts; the
design's candidate search, the plateau study and the unbalance study decide with it (and with
no budget reproduce the start grid alone, 004's protocol)."""
from __future__ import annotations

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from autobalance.confidence import quantile_interval, verdict
from autobalance.studies.design_verdicts import decide
from autobalance.studies.sequential import MAX_STARTS, refine


def _sampler(truths: dict, seen: list):
    """run_more for cells whose grades are normal around ``truths[key]`` (sd 1): the round's
    own stream (seeded by the round), recorded in ``seen``."""
    def run_more(keys, k, rnd):
        seen.append((tuple(keys), k, rnd))
        rng = np.random.default_rng(1000 + rnd)
        return [truths[key] + rng.standard_normal(k) for key in keys]
    return run_more


def _undecided(target: float):
    def f(cells):
        out = []
        for key, a in cells.items():
            _, lo, hi = quantile_interval(a, 0.95)
            if verdict(float(lo), float(hi), target) == "undecided":
                out.append(key)
        return out
    return f


def test_refine_decides_the_cells_it_can_and_leaves_the_others():
    """Cells far from the target are decided once they hold enough starts (20 never bound a
    95th percentile from above: 72 do); a cell whose 95th percentile (truth + 1.645 sd) lies
    on the target stays undecided until the cap."""
    truths = {"low": 10.0, "high": 20.0, "edge": 16.0 - 1.645}
    rng = np.random.default_rng(0)
    cells = {k: v + rng.standard_normal(20) for k, v in truths.items()}
    seen = []
    r = refine(cells, _undecided(16.0), 10 ** 6, _sampler(truths, seen))
    assert verdict(*[float(x) for x in quantile_interval(cells["low"], 0.95)[1:]], 16.0) == "meets"
    assert verdict(*[float(x) for x in quantile_interval(cells["high"], 0.95)[1:]], 16.0) == "fails"
    assert r["capped"] and not r["decided"] and r["undecided"] == ["edge"]
    assert len(cells["edge"]) == MAX_STARTS and 72 <= len(cells["low"]) < MAX_STARTS
    # the samples double each round, and each round has its own number (its own starts)
    assert [k for _, k, _ in seen][:3] == [20, 40, 80]
    assert [rnd for _, _, rnd in seen] == list(range(1, len(seen) + 1))
    assert r["spent"] == sum(k * len(keys) for keys, k, _ in seen)


@settings(max_examples=60, deadline=None)
@given(budget=st.integers(0, 3000), n0=st.integers(1, 100), first=st.integers(1, 50),
       m=st.integers(1, 4))
def test_refine_never_overspends_nor_passes_the_cap(budget, n0, first, m):
    """Whatever the budget and the first samples, the runs added are within the budget, no
    cell passes MAX_STARTS, and the rounds are numbered on from ``first_round``."""
    cells = {i: np.zeros(n0) for i in range(m)}
    seen = []

    def run_more(keys, k, rnd):
        seen.append(rnd)
        return [np.zeros(k) for _ in keys]

    r = refine(cells, lambda c: list(c), budget, run_more, first_round=first)
    assert r["spent"] <= budget
    assert r["spent"] == sum(len(a) for a in cells.values()) - m * n0
    assert all(len(a) <= max(n0, MAX_STARTS) for a in cells.values())
    assert seen == list(range(first, first + r["rounds"]))
    assert r["exhausted"] or r["capped"]


def test_decide_stops_at_the_cheapest_decided_meets():
    """Three candidates cheapest first: the first fails (decided by its 20 starts: its 95th
    percentile's lower end is far above the target), the second meets after more starts, the
    third is never run; the rounds are numbered across candidates."""
    target = 16.0
    truths = {0: 30.0, 1: 11.0, 2: 5.0}
    rng = np.random.default_rng(3)
    cells = [[truths[d] + rng.standard_normal(20) for _ in range(2)] for d in range(3)]
    calls = []

    def run_more(d, units, k, rnd):
        calls.append((d, tuple(units), k, rnd))
        g = np.random.default_rng(rnd)
        return [truths[d] + g.standard_normal(k) for _ in units]

    r = decide(cells, [0, 1, 2], target, 0.95, 10 ** 5, run_more)
    assert r["recommended"] == 1 and not r["exhausted"]
    assert {c[0] for c in calls} == {1}
    assert min(len(a) for a in cells[1]) >= 72 and len(cells[2][0]) == 20
    assert [c[3] for c in calls] == list(range(1, len(calls) + 1))
    assert r["spent"] == sum(k * len(u) for _, u, k, _ in calls)


def test_decide_reports_a_spent_budget():
    cells = [[np.full(20, 10.0)]]
    r = decide(cells, [0], 16.0, 0.95, 30, lambda d, u, k, rnd: [np.full(k, 10.0) for _ in u])
    assert r == {"spent": 30, "rounds": 2, "budget": 30, "recommended": None,
                 "exhausted": True, "capped": []}


# -- the studies ----------------------------------------------------------------------------------
@pytest.mark.slow
def test_plateau_study_adds_starts_until_the_recommendation_is_decided(tmp_path):
    """The plateau study on 004's rig, three plateaus x two initial grades from 15 grid starts
    per cell: the intervals cannot tell the plateaus apart (a 95th percentile needs 72 runs
    before its upper end is bounded); with a budget it adds random starts only at the plateaus
    not distinguishable from the best, until one is left; without one (004's protocol) it is
    the start grid alone, and a rerun of the same study from its stores computes nothing."""
    from autobalance.studies._plateau import compute_plateau, plateau_summary

    kw = dict(ratios=[0.98, 1.02, 1.10], G=[10.0, 20.0], n=5, executor="serial")
    grid = compute_plateau("vub_jeffcott_004", budget=0, **kw)
    assert (grid["starts"].values == 15).all() and grid.attrs["budget_spent"] == 0
    assert not plateau_summary(grid)["recommended_decided"]
    ds = compute_plateau("vub_jeffcott_004", budget=6000, store_dir=tmp_path, **kw)
    s = plateau_summary(ds)
    assert s["recommended_decided"] and s["recommended_plateau_ratio"] == 1.02
    starts = ds["starts"].sel(case="nominal").values
    assert starts[1].min() > starts.min() >= 72           # the best got the most starts
    assert ds.attrs["budget_spent"] == starts.sum() - 6 * 15 <= 6000
    lo, hi = s["best_mean_p95_grade_G_mm_s_ci"]
    assert lo <= s["best_mean_p95_grade_G_mm_s"] <= hi < np.inf
    again = compute_plateau("vub_jeffcott_004", budget=6000, store_dir=tmp_path, **kw)
    assert np.array_equal(again["grade_G_p95"].values, ds["grade_G_p95"].values)


@pytest.mark.slow
def test_unbalance_study_decides_the_grid_points_it_can():
    """The unbalance study at three initial grades: with a budget, every grid point whose 95th
    percentile was undecided against G16 gets more starts, and only those: G60 (against G34
    balls) fails on its 15 grid starts already (its interval's lower end is above G16); the
    others need >= 72 starts for a bounded upper end."""
    from autobalance.studies.unbalance import compute_unbalance, unbalance_summary

    kw = dict(G=np.array([2.0, 20.0, 60.0]), n=5, executor="serial", grade=16.0)
    grid = compute_unbalance("vub_jeffcott_004", budget=0, **kw)
    assert (grid["runs_ok"].values == 15).all()
    ds = compute_unbalance("vub_jeffcott_004", budget=3000, **kw)
    runs = ds["runs_ok"].sel(case="nominal").values
    assert runs[2] == 15 and runs[:2].min() >= 72
    assert ds.attrs["budget_spent"] == runs.sum() - 45 <= 3000
    v = unbalance_summary(ds, 16.0)["cases"]["nominal"]
    for proc in v:
        assert v[proc]["p95_verdicts"][2] == "fails"
    assert ds.attrs["budget_exhausted"] == 0
