"""Confidence of the numbers that come from sampling, and decisions made against it.

Every Monte-Carlo statistic of the package (a percentile of the grade over start positions, the
share of runs at or below a grade, a mode) is an estimate from a finite sample: this module
gives its interval and decides a target against that interval, not against the estimate.

* **Percentiles** (:func:`quantile_interval`): the distribution-free interval of the q-quantile
  from order statistics (Hahn and Meeker 1991, *Statistical Intervals*, sec. 5.2; David and
  Nagaraja 2003, *Order Statistics*, sec. 7.1). Of n runs, the number B below the true
  quantile is Binomial(n, q); [x_(l), x_(u)] (1-based order statistics) covers the quantile
  with probability P(l <= B <= u - 1) >= level, l and u chosen with at most (1 - level)/2 on
  either side. It holds for any continuous distribution and is conservative for a discrete
  one. Where the sample is too small (the 95th percentile of fewer than 72 runs at 95 %), an
  end is unbounded: ``-inf`` or ``inf``, and :func:`runs_to_bound` says how many runs would
  bound it.
* **Shares** (:func:`share_interval`): the Clopper-Pearson interval of a binomial proportion
  (Clopper and Pearson 1934, Biometrika 26(4) 404-413), exact: its coverage is at least
  ``level`` for every true share.
* **Modes** (:func:`bootstrap_interval`): the percentile bootstrap (Efron and Tibshirani 1993,
  *An Introduction to the Bootstrap*, sec. 13.3), approximate.
* **Decisions** (:func:`verdict`): a target ``value <= target`` is met when the upper end of
  the interval is at or below it, failed when the lower end is above it, and undecided
  otherwise (more runs decide it).

The equispaced start grid of 004 sec. 4.2 is a systematic sample of the uniform distribution of
start angles; its intervals are those of a random sample of the same size (for the chaotic
stick-slip outcomes, grid points a grid step apart are as good as independent).

This module imports nothing of the package.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Callable

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["LEVEL", "VERDICTS", "bootstrap_interval", "interval_text", "order_ranks",
           "quantile_interval", "runs_to_bound", "share_interval", "verdict"]

#: The confidence level of every interval the package reports [-].
LEVEL = 0.95
#: The three verdicts of a target against an interval.
VERDICTS = ("meets", "fails", "undecided")


def _check(level: float, q: float | None = None) -> None:
    if not (isinstance(level, (int, float)) and 0 < level < 1):
        raise ValueError(f"level = {level!r}: must be within (0, 1), e.g. 0.95")
    if q is not None and not (isinstance(q, (int, float)) and 0 <= q <= 1):
        raise ValueError(f"q = {q!r}: must be a quantile within [0, 1], e.g. 0.95")


def order_ranks(n: int, q: float, level: float = LEVEL) -> tuple[int, int]:
    """The 1-based ranks (l, u) of the order statistics that bound the q-quantile of n runs
    with probability >= ``level`` (see the module docstring).

    Parameters
    ----------
    n : int
        Sample size [-], >= 0.
    q : float
        Quantile [-] in [0, 1] (0.95 for the 95th percentile).
    level : float
        Confidence level [-] in (0, 1).

    Returns
    -------
    (l, u) : tuple of int
        l in 0..n (0: no lower bound), u in 1..n+1 (n + 1: no upper bound); P(l <= B < u)
        >= level for B ~ Binomial(n, q).
    """
    from scipy.stats import binom

    _check(level, q)
    n = int(n)
    if n <= 0:
        return 0, 1
    tail = (1.0 - level) / 2.0
    k = np.arange(n + 1)
    cdf = binom.cdf(k, n, q)                    # P(B <= k)
    # largest l with P(B <= l - 1) <= tail: cdf[l - 1] <= tail
    low = np.flatnonzero(cdf[:-1] <= tail)
    l_rank = int(low[-1] + 1) if low.size else 0
    # smallest u with P(B >= u) = 1 - cdf[u - 1] <= tail
    up = np.flatnonzero(1.0 - cdf[:-1] <= tail)
    u_rank = int(up[0] + 1) if up.size else n + 1
    return l_rank, u_rank


def quantile_interval(sample: npt.ArrayLike, q: float, level: float = LEVEL,
                      axis: int = -1) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The q-quantile of a sample with its distribution-free interval (order statistics).

    Parameters
    ----------
    sample : array_like
        Values [any unit] along ``axis``; NaN (failed runs) are left out, each slice on its
        own.
    q : float
        Quantile [-] in [0, 1].
    level : float
        Confidence level [-].
    axis : int
        The axis of the samples.

    Returns
    -------
    (estimate, lo, hi) : tuple of ndarray
        The quantile by linear interpolation between order statistics (numpy's default, as
        every percentile of the package) and the interval's ends [unit of ``sample``]; an end
        the sample cannot bound is ``-inf`` / ``inf``; NaN where a slice has no value.
    """
    _check(level, q)
    x = np.moveaxis(np.asarray(sample, float), axis, -1)
    xs = np.sort(x, axis=-1)                    # NaN sort last
    n = np.sum(np.isfinite(x), axis=-1)
    est = np.full(n.shape, np.nan)
    lo = np.full(n.shape, np.nan)
    hi = np.full(n.shape, np.nan)
    for idx in np.ndindex(*n.shape):
        m = int(n[idx])
        if m == 0:
            continue
        row = xs[idx][:m]
        est[idx] = np.quantile(row, q)
        l_rank, u_rank = order_ranks(m, q, level)
        lo[idx] = row[l_rank - 1] if l_rank >= 1 else -math.inf
        hi[idx] = row[u_rank - 1] if u_rank <= m else math.inf
    return est, lo, hi


def runs_to_bound(q: float, level: float = LEVEL) -> int:
    """The fewest runs whose order statistics bound the q-quantile from both sides at
    ``level`` (72 for the 95th percentile at 95 %).

    Parameters
    ----------
    q : float
        Quantile [-] in (0, 1).
    level : float
        Confidence level [-].

    Returns
    -------
    int
        n [-]: with fewer runs an end of :func:`quantile_interval` is unbounded.
    """
    _check(level, q)
    tail = (1.0 - level) / 2.0
    # both ends bounded once P(B = n) <= tail and P(B = 0) <= tail
    need = max(math.log(tail) / math.log(q) if 0 < q < 1 else math.inf,
               math.log(tail) / math.log(1.0 - q) if 0 < q < 1 else math.inf)
    n = max(int(math.floor(need)), 1)
    while True:                     # the smallest n whose ranks are both inside 1..n
        l_rank, u_rank = order_ranks(n, q, level)
        if l_rank >= 1 and u_rank <= n:
            return n
        n += 1


def share_interval(hits: npt.ArrayLike, n: npt.ArrayLike,
                   level: float = LEVEL) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """A share k/n with its Clopper-Pearson interval (exact binomial).

    Parameters
    ----------
    hits : array_like
        Runs that meet the condition, k [-].
    n : array_like
        Runs [-] (same shape); 0 gives NaN.
    level : float
        Confidence level [-].

    Returns
    -------
    (share, lo, hi) : tuple of ndarray
        k/n and the interval's ends [-] in [0, 1].
    """
    from scipy.stats import beta

    _check(level)
    k = np.asarray(hits, float)
    m = np.asarray(n, float)
    tail = (1.0 - level) / 2.0
    with np.errstate(invalid="ignore", divide="ignore"):
        share = np.where(m > 0, k / np.where(m > 0, m, 1.0), np.nan)
        lo = np.where(k > 0, beta.ppf(tail, k, m - k + 1), 0.0)
        hi = np.where(k < m, beta.ppf(1.0 - tail, k + 1, m - k), 1.0)
    lo = np.where(m > 0, lo, np.nan)
    hi = np.where(m > 0, hi, np.nan)
    return share, lo, hi


def bootstrap_interval(sample: npt.ArrayLike, statistic: Callable[[np.ndarray], float],
                       level: float = LEVEL, n_boot: int = 400,
                       seed: int = 0) -> tuple[float, float, float]:
    """A statistic of a sample with its percentile-bootstrap interval (approximate).

    Parameters
    ----------
    sample : array_like
        Values [any unit]; non-finite ones are left out.
    statistic : callable
        ndarray -> float [unit of the statistic], e.g. the mode of 1 mm/s bins.
    level : float
        Confidence level [-].
    n_boot : int
        Bootstrap resamples [-].
    seed : int
        Seed of the resampling (the interval is reproducible).

    Returns
    -------
    (estimate, lo, hi) : tuple of float
        The statistic of the sample and the (1 - level)/2 and (1 + level)/2 quantiles of its
        bootstrap distribution; NaN for an empty sample.
    """
    _check(level)
    x = np.asarray(sample, float)
    x = x[np.isfinite(x)]
    if x.size == 0:
        return math.nan, math.nan, math.nan
    rng = np.random.default_rng(seed)
    boots = np.array([statistic(rng.choice(x, x.size)) for _ in range(int(n_boot))])
    tail = (1.0 - level) / 2.0
    return (float(statistic(x)), float(np.quantile(boots, tail)),
            float(np.quantile(boots, 1.0 - tail)))


def verdict(lo: float, hi: float, target: float) -> str:
    """Whether ``value <= target`` holds, judged on the value's interval [lo, hi].

    Parameters
    ----------
    lo, hi : float
        The interval's ends [unit of the value] (``inf`` where unbounded).
    target : float
        The limit [same unit].

    Returns
    -------
    str
        "meets" (hi <= target), "fails" (lo > target) or "undecided" (the interval straddles
        the target, or is NaN).
    """
    if math.isfinite(hi) and hi <= target:
        return "meets"
    if not math.isnan(lo) and lo > target:
        return "fails"
    return "undecided"


def interval_text(lo: float, hi: float, fmt: Callable[[float], str], n: int | None = None,
                  level: float = LEVEL) -> str:
    """An interval as text: ``"95 % CI G12.9-G16.4, 36 starts"``; an unbounded end as
    ``"above G13.1"`` / ``"below ..."``.

    Parameters
    ----------
    lo, hi : float
        The interval's ends [unit of the value].
    fmt : callable
        float -> str, the value in the user's units (e.g. ``lambda g: f"G{g:.3g}"``).
    n : int or None
        The sample size, shown when given.
    level : float
        Confidence level [-].
    """
    pct = f"{100 * level:g} % CI"
    if math.isnan(lo) or math.isnan(hi):
        body = "not computed"
    elif math.isinf(hi) and math.isinf(lo):
        body = "unbounded"
    elif math.isinf(hi):
        body = f"{fmt(lo)} or more"
    elif math.isinf(lo):
        body = f"up to {fmt(hi)}"
    else:
        body = f"{fmt(lo)}-{fmt(hi)}"
    return f"{pct} {body}" + (f", {n} runs" if n is not None else "")
