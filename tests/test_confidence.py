"""The confidence of Monte-Carlo numbers (autobalance.confidence): the intervals contain the
truth about as often as they say, on distributions whose quantiles are known in closed form and
on a real machine whose grade distribution is known from many starts; decisions are made
against the interval.
"""
from __future__ import annotations

import math

import numpy as np
import pytest

from autobalance.confidence import (bootstrap_interval, interval_text, order_ranks,
                                    quantile_interval, runs_to_bound, share_interval, verdict)

REPEATS = 2000


def coverage(draw, truth: float, q: float, n: int, seed: int = 7) -> tuple[float, float]:
    """(share of repeated samples of n whose interval holds ``truth``, share with an unbounded
    end)."""
    rng = np.random.default_rng(seed)
    x = draw(rng, (REPEATS, n))
    _, lo, hi = quantile_interval(x, q)
    return (float(np.mean((lo <= truth) & (truth <= hi))),
            float(np.mean(np.isinf(hi) | np.isinf(lo))))


# -- closed forms -------------------------------------------------------------------------------
def test_order_ranks_are_the_binomial_ones():
    assert order_ranks(100, 0.5) == (40, 61)           # Hahn & Meeker Table A.15: 40, 61
    assert order_ranks(100, 0.95) == (90, 100)
    assert order_ranks(36, 0.95)[1] == 37              # 36 runs cannot bound a p95 above
    assert runs_to_bound(0.95) == 72                    # 0.95^72 = 0.0249 <= 0.025 < 0.95^71
    assert 0.95 ** 72 <= 0.025 < 0.95 ** 71
    assert order_ranks(0, 0.5) == (0, 1)


@pytest.mark.parametrize("n", [30, 100, 300])
@pytest.mark.parametrize("q", [0.05, 0.5, 0.95])
def test_percentile_intervals_cover_a_known_quantile(n, q):
    """Exponential(1): the q-quantile is -ln(1 - q). The order-statistic interval is exact
    up to the ranks' rounding: coverage between 95 % and 99 % (2000 samples: +-1 % at 2 sigma);
    where the runs cannot bound it (p5 or p95 of 30 runs) the end is infinite and says so."""
    truth = -math.log(1.0 - q)
    cov, unbounded = coverage(lambda r, s: r.exponential(size=s), truth, q, n)
    assert 0.94 <= cov <= 0.995, cov
    assert unbounded == (1.0 if n < runs_to_bound(q) else 0.0)


def test_percentile_intervals_cover_a_grade_like_mixture():
    """A two-mode mixture like a balancer's grades (most runs balanced near G1, a tail of
    runs stuck near G20): its 95th percentile from the mixture's own quantile function."""
    from scipy.optimize import brentq
    from scipy.stats import lognorm

    w, a, b = 0.9, lognorm(0.3, scale=1.0), lognorm(0.2, scale=20.0)
    cdf = lambda g: w * a.cdf(g) + (1 - w) * b.cdf(g)           # noqa: E731
    truth = brentq(lambda g: cdf(g) - 0.95, 0.1, 200.0)

    def draw(rng, shape):
        pick = rng.random(shape) < w
        return np.where(pick, a.rvs(size=shape, random_state=rng),
                        b.rvs(size=shape, random_state=rng))
    cov, _ = coverage(draw, truth, 0.95, 150)
    assert 0.94 <= cov <= 0.995, cov


@pytest.mark.parametrize("p", [0.5, 0.9, 0.97])
def test_share_intervals_cover_a_known_share(p):
    """Clopper-Pearson is exact: coverage >= 95 % for every true share (minus 1 % for the
    2000 repeats), and not much more."""
    rng = np.random.default_rng(3)
    k = rng.binomial(60, p, REPEATS)
    _, lo, hi = share_interval(k, np.full(REPEATS, 60))
    cov = float(np.mean((lo <= p) & (p <= hi)))
    assert 0.94 <= cov <= 0.995, cov


def test_share_interval_ends():
    s, lo, hi = share_interval([0, 10, 10], [10, 10, 0])
    assert lo[0] == 0.0 and hi[1] == 1.0 and math.isnan(s[2])
    assert math.isclose(hi[0], 1 - 0.025 ** 0.1, rel_tol=1e-9)    # (1 - level/2)^(1/n)


def test_bootstrap_interval_of_the_mode_covers_it():
    rng = np.random.default_rng(0)
    x = rng.normal(10.3, 0.6, 400)
    est, lo, hi = bootstrap_interval(x, lambda v: float(np.round(np.median(v), 1)))
    assert lo <= est <= hi and hi - lo < 0.3


def test_verdicts_are_made_against_the_interval():
    assert verdict(12.0, 15.0, 16.0) == "meets"
    assert verdict(16.5, 20.0, 16.0) == "fails"
    assert verdict(12.0, 17.0, 16.0) == "undecided"
    assert verdict(12.0, math.inf, 16.0) == "undecided"       # too few runs to bound it
    assert verdict(math.nan, math.nan, 16.0) == "undecided"
    assert interval_text(12.9, 16.4, lambda g: f"G{g:.3g}", 36) == "95 % CI G12.9-G16.4, 36 runs"
    assert interval_text(12.9, math.inf, lambda g: f"G{g:.3g}") == "95 % CI G12.9 or more"


# -- a real machine -------------------------------------------------------------------------------
@pytest.mark.slow
def test_intervals_cover_a_machines_grade_distribution(tmp_path):
    """The 004 rig on a 12 s run-up and plateau: 1200 uniform random starts give its grade
    distribution (the truth: their p50 and p95 at the last read-out); repeated samples of 80
    of those starts, drawn without replacement, give intervals that hold the truth about 95 %
    of the time (a finite population of 1200: slightly more)."""
    from autobalance.sweep import spec_from_dict, sweep

    sets = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s",
            "profile.plateau_time=2 s", "profile.up_time=1 s"]
    ds = sweep(spec_from_dict({"sweep": {"name": "truth", "base": "vub_jeffcott_004",
                                         "set": sets, "batch_size": 100},
                               "monte_carlo": {"kind": "random", "samples": 1200, "seed": 5}}),
               tmp_path / "store", executor="local", progress=False)
    g = ds["grade_G"].where(ds["status"] == 0).isel(checkpoint=-1).values
    g = g[np.isfinite(g)]
    assert g.size >= 1190
    rng = np.random.default_rng(11)
    picks = np.array([rng.choice(g, 80, replace=False) for _ in range(REPEATS)])
    for q in (0.5, 0.95):
        truth = float(np.quantile(g, q))
        _, lo, hi = quantile_interval(picks, q)
        cov = float(np.mean((lo <= truth) & (truth <= hi)))
        print(f"\ncoverage of the p{100 * q:g} (truth G{truth:.3g}) by 80-start intervals: "
              f"{100 * cov:.1f} %")
        assert 0.93 <= cov <= 0.995, (q, cov)


def test_share_intervals_of_a_sweep_count_each_cell_and_read_out():
    """sweep.summary.share_intervals on a grid of 3 values x 2 read-outs (status per run, grade
    per run and read-out; one failed run): each interval is Clopper-Pearson of that cell's own
    count, the failed run left out."""
    import xarray as xr

    from autobalance.sweep.summary import share_intervals

    g = np.array([[[1, 30], [2, 3], [20, 20], [5, 5], [9, 40]],       # (cell, sample, read-out)
                  [[1, 1], [1, 1], [1, 1], [1, 1], [1, 1]],
                  [[30, 30], [30, 1], [30, 30], [30, 30], [30, 30]]], float)
    status = np.zeros((3, 5), int)
    status[0, 4] = 3                                                    # a failed run
    ds = xr.Dataset({"grade_G": (("rotor__unbalance", "sample", "checkpoint"), g),
                     "status": (("rotor__unbalance", "sample"), status)},
                    coords={"rotor__unbalance": [0.1, 0.2, 0.3], "checkpoint": [0, 1]})
    ci = share_intervals(ds, 16.0).transpose("rotor__unbalance", "checkpoint", "bound").values
    for c in range(3):
        ok = status[c] == 0
        for k in range(2):
            hits = int(((g[c, :, k] <= 16) & ok).sum())
            _, lo, hi = share_interval(hits, int(ok.sum()))
            assert ci[c, k] == pytest.approx([float(lo), float(hi)]), (c, k)
