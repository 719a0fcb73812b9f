"""More starts where a Monte-Carlo decision is undecided: the sequential step every study that
decides against a confidence interval shares (the design's verdicts, the plateau study's
recommendation, the unbalance study's valid ranges).

A study holds its final grades in *cells* (one per candidate and unbalance, per plateau and
initial grade, ...), each a growing sample of start positions. After each round it says
which cells still leave its decision undecided; those get as many new starts as the smallest
of them holds (the sample doubles each round), from a start stream of their own per round,
until nothing is undecided, a cell would pass :data:`MAX_STARTS`, or the next round would
overspend the budget of runs (the last round is then cut to what the budget allows).
"""
from __future__ import annotations

from typing import Callable, Hashable

import numpy as np

__all__ = ["BUDGET_FACTOR", "MAX_STARTS", "SEED_STEP", "budget_attrs", "default_budget",
           "refine"]

#: Most starts one cell reaches by the sequential step [-].
MAX_STARTS = 1280
#: Seed offset of the start stream of each round [-]: round r draws from ``seed + SEED_STEP r``.
SEED_STEP = 7919
#: Default budget of a study's sequential step, in units of its first pass's runs [-].
BUDGET_FACTOR = 1


def default_budget(budget: int | None, first: int) -> int:
    """The runs [-] a study's sequential step may add.

    Parameters
    ----------
    budget : int or None
        The runs asked for [-]; None = :data:`BUDGET_FACTOR` x ``first``.
    first : int
        The runs of the study's first pass [-].
    """
    return BUDGET_FACTOR * int(first) if budget is None else int(budget)


def budget_attrs(first: int, budget: int, result: dict, seed: int) -> dict:
    """A study's NetCDF attrs of its sequential step: simulations_first_pass, budget,
    budget_spent, budget_rounds, budget_exhausted, budget_capped (0/1) and seed.

    Parameters
    ----------
    first : int
        The runs of the first pass [-].
    budget : int
        The runs the step could add [-].
    result : dict
        What :func:`refine` returned.
    seed : int
        Seed of the added starts.
    """
    return {"simulations_first_pass": int(first), "budget": int(budget),
            "budget_spent": int(result["spent"]), "budget_rounds": int(result["rounds"]),
            "budget_exhausted": int(result["exhausted"]),
            "budget_capped": int(result["capped"]), "seed": int(seed)}


def refine(cells: dict, undecided: Callable[[dict], list], budget: int,
           run_more: Callable[[list, int, int], list], *, first_round: int = 1) -> dict:
    """Add starts to the undecided cells, doubling their samples each round, until none is
    left, a cell reaches :data:`MAX_STARTS` or the budget is spent (module docstring).

    Parameters
    ----------
    cells : dict
        Key -> the grades so far [mm/s], an array whose first axis is the start (NaN: failed
        runs, which count as run); extended in place.
    undecided : callable
        ``undecided(cells)`` -> the keys whose samples leave the decision open (empty: decided).
    budget : int
        Most runs to add [-] (>= 0).
    run_more : callable
        ``run_more(keys, k, round)`` -> the grades of ``k`` new starts at each of ``keys``, one
        array per key in that order, drawn from the start stream of ``round``.
    first_round : int
        Number of the first round here (a caller that refines several sets of cells numbers
        the rounds on, so that no two draw the same starts).

    Returns
    -------
    dict
        "spent" runs [-], "rounds" [-], "decided" (nothing left undecided), "exhausted" (the
        budget ran out first), "capped" (stopped at :data:`MAX_STARTS`), "undecided" (the
        keys left).
    """
    spent, rounds = 0, 0
    while True:
        todo: list[Hashable] = list(undecided(cells))
        out = {"spent": spent, "rounds": rounds, "decided": not todo, "exhausted": False,
               "capped": False, "undecided": todo}
        if not todo:
            return out
        have = min(len(cells[key]) for key in todo)
        k = min(have, MAX_STARTS - have)
        if k <= 0:
            return {**out, "capped": True}
        if spent + k * len(todo) > budget:
            k = (budget - spent) // len(todo)
            if k <= 0:
                return {**out, "exhausted": True}
        new = run_more(todo, int(k), first_round + rounds)
        rounds += 1
        for key, a in zip(todo, new):
            cells[key] = np.concatenate([cells[key], np.asarray(a, float)])
        spent += int(k) * len(todo)
