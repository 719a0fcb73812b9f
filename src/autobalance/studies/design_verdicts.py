"""Verdicts of the design search made against the confidence of its Monte Carlo, and the
starts it adds until they are decided.

A candidate design meets the target when, at every studied unbalance, the ``confidence``
quantile of its final grade over random start positions is at or below the target grade. Each
quantile comes from a finite number of starts, so it is judged by its distribution-free
interval (:func:`autobalance.confidence.quantile_interval`): at one unbalance the design
*meets* the target when the interval's upper end is at or below it, *fails* when its lower end
is above it, and is *undecided* otherwise. Over the unbalances, a design fails where one
unbalance fails, meets where every one meets, and is undecided otherwise. Its worst quantile
is the largest over the unbalances, with the interval [largest lower end, largest upper end];
its margin is the target minus that, with the interval the other way round.

The decision is sequential (:func:`decide`): the candidates are taken cheapest first (total
ball mass, then profile length); for an undecided one, more starts are run at the unbalances
still undecided (:func:`autobalance.studies.sequential.refine`: doubling their number each
round) until the design is decided, a cell holds :data:`MAX_STARTS` starts, or the budget of
runs is spent. The search stops at the first
candidate decided "meets": it is the recommendation, and dearer ones cannot change it. The
95th percentile needs at least 72 starts at an unbalance before its upper end is bounded
(:func:`autobalance.confidence.runs_to_bound`), so a "meets" of the 95th percentile is never
decided on fewer.
"""
from __future__ import annotations

import math
from typing import Callable

import numpy as np

from ..confidence import quantile_interval, verdict
from .sequential import MAX_STARTS, refine

__all__ = ["MAX_STARTS", "VERDICT_ORDER", "candidate_verdicts", "decide", "pad"]

#: Sort rank of the verdicts: decided "meets" first, "fails" last.
VERDICT_ORDER = {"meets": 0, "undecided": 1, "fails": 2}


def pad(cells: list) -> np.ndarray:
    """Per candidate, per unbalance, the final grades [mm/s] as one array (design, unbalance,
    sample), NaN where a cell has fewer starts than the largest.

    Parameters
    ----------
    cells : list of list of ndarray
        ``cells[d][u]``: the grades of candidate d at unbalance u [mm/s] (NaN: failed runs).
    """
    n = max(a.size for c in cells for a in c)
    out = np.full((len(cells), len(cells[0]), n), np.nan)
    for d, c in enumerate(cells):
        for u, a in enumerate(c):
            out[d, u, :a.size] = a
    return out


def candidate_verdicts(g: np.ndarray, grade: float, confidence: float) -> dict:
    """The quantiles of a search's grades with their intervals and verdicts (module docstring).

    Parameters
    ----------
    g : ndarray
        Final grades [mm/s], (design, unbalance, sample), NaN for runs not run or failed.
    grade : float
        Target grade [mm/s].
    confidence : float
        The quantile [-] (0.95: the 95th percentile over the starts).

    Returns
    -------
    dict
        "quantile", "lo", "hi" (design, unbalance) [mm/s]; "cell_verdict" (design,
        unbalance); "worst", "worst_lo", "worst_hi", "margin", "margin_lo", "margin_hi"
        (design) [mm/s]; "verdict" (design): "meets", "fails" or "undecided"; "starts"
        (design, unbalance) [-], the finished runs.
    """
    q, lo, hi = quantile_interval(g, confidence, axis=-1)
    cell = np.array([[verdict(a, b, grade) for a, b in zip(la, ha)] for la, ha in zip(lo, hi)])
    worst = np.nanmax(q, axis=1)
    worst_lo, worst_hi = np.nanmax(lo, axis=1), np.max(hi, axis=1)
    out_v = np.where((cell == "fails").any(axis=1), "fails",
                     np.where((cell == "meets").all(axis=1), "meets", "undecided"))
    return {"quantile": q, "lo": lo, "hi": hi, "cell_verdict": cell, "worst": worst,
            "worst_lo": worst_lo, "worst_hi": worst_hi, "margin": grade - worst,
            "margin_lo": grade - worst_hi, "margin_hi": grade - worst_lo,
            "verdict": out_v, "starts": np.sum(np.isfinite(g), axis=-1)}


def decide(cells: list, order: list, grade: float, confidence: float, budget: int,
           run_more: Callable[[int, list, int, int], list]) -> dict:
    """Add starts to the candidates, cheapest first, until the first is decided "meets" or the
    budget is spent (module docstring).

    Parameters
    ----------
    cells : list of list of ndarray
        ``cells[d][u]``, the grades so far [mm/s]; extended in place.
    order : list of int
        The candidates, cheapest first.
    grade : float
        Target grade [mm/s].
    confidence : float
        The quantile [-].
    budget : int
        Most runs to add [-] (>= 0).
    run_more : callable
        ``run_more(d, units, k, round)`` -> the grades [mm/s] of ``k`` new starts of candidate
        d at the unbalances ``units`` (a list of indices), one array per unbalance, from the
        start stream of ``round`` (>= 1: new starts, independent of the earlier rounds').

    Returns
    -------
    dict
        "spent" runs [-], "rounds" [-], "budget" [-], "recommended" (the candidate index, or
        None), "exhausted" (the budget ran out first), "capped" (candidates left undecided
        at :data:`MAX_STARTS`).
    """
    spent, rounds, capped = 0, 0, []
    for d in order:
        def undecided(c, d=d):
            v = candidate_verdicts(pad([[c[u] for u in range(len(cells[d]))]]), grade,
                                   confidence)
            if v["verdict"][0] != "undecided":
                return []
            return [u for u, x in enumerate(v["cell_verdict"][0]) if x == "undecided"]

        mine = dict(enumerate(cells[d]))
        r = refine(mine, undecided, budget - spent,
                   lambda units, k, rnd, d=d: run_more(d, units, k, rnd),
                   first_round=rounds + 1)
        cells[d][:] = [mine[u] for u in range(len(cells[d]))]
        spent, rounds = spent + r["spent"], rounds + r["rounds"]
        if r["capped"]:
            capped.append(d)
        if r["exhausted"]:
            return {"spent": spent, "rounds": rounds, "budget": int(budget),
                    "recommended": None, "exhausted": True, "capped": capped}
        if candidate_verdicts(pad([cells[d]]), grade, confidence)["verdict"][0] == "meets":
            return {"spent": spent, "rounds": rounds, "budget": int(budget),
                    "recommended": d, "exhausted": False, "capped": capped}
    return {"spent": spent, "rounds": rounds, "budget": int(budget), "recommended": None,
            "exhausted": False, "capped": capped}


def verdict_text(v: str, lo: float, hi: float) -> str:
    """A design's verdict with its worst-quantile interval for text, e.g. ``"meets (worst
    G11.2-G14.9)"``.

    Parameters
    ----------
    v : str
        The verdict.
    lo, hi : float
        The worst quantile's interval [mm/s] (inf: unbounded).
    """
    hi_text = "unbounded" if not math.isfinite(hi) else f"G{hi:.3g}"
    return f"{v} (worst G{lo:.3g}-{hi_text})"
