"""The quick report against a committed reference (tests/data/): `autobalance reproduce all
--quick --json` must give the reference's rows — same keys, same verdicts, the same published
numbers and tolerances, and computed values equal to 1e-9 relative (the simulations are
deterministic: two runs of the same code agree bit for bit). The 003-fig5, -fig6 and -fig7 rows
are those of the liquid from physics. A change of the model or the kernel that moves a row on
purpose updates the reference with it. The rows such a change moves first are the stick-slip
runs' statistics of 004's quick variants (one start position moving from one 1.97 G bin to the
next moves an efficiency by 0.1 %; a flat minimum of the descent's p95 can be read at another
plateau), and round-off rows such as 001-eq5-7's (the relative error of an identity, 1e-16
against a 1e-12 tolerance), as under a change of tolerance; their verdicts stay."""
import json
import math
from pathlib import Path

import pytest

GOLDEN = Path(__file__).parent / "data" / "quick_rows_golden.json"
REL = 1e-9


def _same(a, b, rel=REL):
    """Values equal to `rel` relative (numbers), recursively for lists and dicts, exact otherwise."""
    if isinstance(a, bool) or isinstance(b, bool) or a is None or b is None or isinstance(a, str):
        return a == b
    if isinstance(a, (int, float)) and isinstance(b, (int, float)):
        if math.isnan(a) or math.isnan(b):
            return math.isnan(a) and math.isnan(b)
        return math.isclose(a, b, rel_tol=rel, abs_tol=0.0) or a == b
    if isinstance(a, list) and isinstance(b, list):
        return len(a) == len(b) and all(_same(x, y, rel) for x, y in zip(a, b))
    if isinstance(a, dict) and isinstance(b, dict):
        return a.keys() == b.keys() and all(_same(a[k], b[k], rel) for k in a)
    return a == b


def test_same_value_rule_can_fail():
    assert _same(1.0, 1.0 + 1e-12) and not _same(1.0, 1.0 + 1e-8)
    assert not _same("pass", "miss") and not _same([1.0, 2.0], [1.0]) and _same(None, None)
    assert not _same(0.0, 1e-300) and _same(float("nan"), float("nan"))


@pytest.mark.report
def test_quick_rows_match_the_golden_rows(quick_report):
    rep, _ = quick_report
    golden = {r["key"]: r for r in json.loads(GOLDEN.read_text())["rows"]}
    now = {r["key"]: r for t in rep["targets"] for r in t["rows"]}
    assert sorted(now) == sorted(golden), (set(now) ^ set(golden))
    changed = [k for k in golden
               if any(not _same(golden[k][f], now[k][f]) for f in ("published", "computed", "tolerance", "status"))]
    assert not changed, "\n".join(f"{k}: {golden[k]['computed']!r} ({golden[k]['status']}) -> "
                                  f"{now[k]['computed']!r} ({now[k]['status']})" for k in changed[:20])
