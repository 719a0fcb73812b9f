"""004's readings (papers/p004/readings.py): each reading of what 004 leaves open is counted
against the report's own Monte-Carlo rows, and a reading that changes a stated parameter says so."""
from __future__ import annotations

import numpy as np
import pytest

from autobalance.papers.p004.compare import compare_monte_carlo
from autobalance.papers.p004.readings import (EQUATIONS_004, READINGS, compute_readings, main,
                                              reading_rows, readings_markdown)
from autobalance.studies.statistics import start_position_stats


@pytest.fixture(scope="module")
def small():
    two = {k: READINGS[k] for k in ("004's equations", "004's equations, 14 s run-up, 1.02 plateau")}
    return compute_readings(3, readings=two, executor="serial")


@pytest.mark.slow
def test_counts_are_the_report_rows_that_pass(small):
    rows = reading_rows(small)
    assert [r["name"] for r in rows] == ["base", "004's equations",
                                         "004's equations, 14 s run-up, 1.02 plateau"]
    for r, name in zip(rows, small["variant"].values):
        g = small["grade_G"].sel(variant=name).values
        st = start_position_stats(g[:, 0], g[:, -1], small.attrs["G_ini"], 16.0)

        class A:
            attrs = {"n": 3, "runs": 6, **st}
        ok = [x["key"].split("/", 1)[1] for x in compare_monte_carlo(A) if x["ok"]
              and not x["key"].endswith("/runs")]
        assert r["reproduced"] == ok and r["count"] == len(ok) and r["total"] == 11
        assert r["count_tied"] >= 0
    assert rows[0]["changes_stated"] == "" and rows[1]["changes_stated"] == ""
    assert "plateau" in rows[2]["changes_stated"]                 # a stated parameter moved
    assert set(EQUATIONS_004) <= set(READINGS["004's equations, 14 s run-up"][0])


@pytest.mark.slow
def test_the_table_shows_the_published_values_and_bolds_what_is_reproduced(small):
    md = readings_markdown(small)
    lines = md.splitlines()
    assert lines[2].startswith("| 004 published | 15 | 11 | 85 | 80 |")
    for line, r in zip(lines[3:], reading_rows(small)):
        assert line.count("**") == 2 * r["count"]
        assert line.endswith(f"{r['count']} / {r['count_tied']} of 11 |")
    assert "(changes a stated parameter)" in lines[-1]


@pytest.mark.slow
def test_command_line_prints_the_table(capsys, tmp_path):
    main(["--n", "2", "--executor", "serial", "--netcdf", str(tmp_path / "r.nc")])
    out = capsys.readouterr().out
    assert "| 004 published |" in out and "runs per reading" in out
    import xarray as xr
    with xr.open_dataset(tmp_path / "r.nc") as ds:
        assert ds.sizes["variant"] == 1 + len(READINGS)
        assert np.isfinite(ds["grade_G"].values).all()
