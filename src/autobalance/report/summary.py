"""Counts of a report's rows per paper and in total (used by the runner, the HTML page, the
markdown table and the CLI)."""
from __future__ import annotations

from collections.abc import Sequence

from .registry import PAPERS

__all__ = ["counts", "summarize", "summary_lines"]


def counts(recs: Sequence[dict]) -> dict:
    """Counts of targets, published claims, pass, miss, not computed, unreported and errors of
    target records (the runner's dicts)."""
    c = {"targets": len(recs), "published": 0, "pass": 0, "miss": 0, "not computed": 0,
         "unreported": 0, "errors": 0}
    for rec in recs:
        c["published"] += len(rec["claims"])
        c["unreported"] += len(rec["unreported"])
        c["errors"] += rec["status"] == "error"
        for r in rec["rows"]:
            if r.get("key") in rec["claims"]:
                c[r["status"]] += 1
    return c


def summarize(recs: Sequence[dict]) -> dict:
    """Counts per paper and in total: published claims, pass, miss, not computed, unreported."""
    papers = {p: counts([r for r in recs if r["paper"] == p]) for p in PAPERS
              if any(r["paper"] == p for r in recs)}
    return {"papers": papers, "total": counts(recs)}


def summary_lines(summary: dict) -> list:
    """(paper, counts) per paper, then ("total", counts): the order of every summary table."""
    return list(summary["papers"].items()) + [("total", summary["total"])]
