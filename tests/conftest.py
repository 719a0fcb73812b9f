"""Shared systems built from the models directly (the presets are tested in test_config.py)."""
import json
import shutil
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import autobalance as ab

RPM = 2 * np.pi / 60


def vub_004(mu=0.002, c=1510.0, n=2, unbalance=16.53 * 19.3e-6, **kw):
    """004 Table 1 Jeffcott rig (point-mass balls, no gravity)."""
    return ab.System(
        ab.Rotor(mass=16.53, unbalance=unbalance),
        ab.Suspension.isotropic(5.8e6, c),
        ab.BallBalancer(n, 0.0076, 0.035, 0.00614, element="point", damping=2.7e-3,
                        rolling_resistance=mu, **kw),
        name="vub_004")


def washer_000(Me=0.025, c_i=2.0, f_r=0.0, g=9.81, rho=0.0, beta=np.pi / 2, n=2,
               normal="drum", **rotor_kw):
    """000 washer with mR = Me per ball; ball damping D = c_i m R^2 (000 eq 4 writes c_i m R)."""
    R = 0.28
    m = Me / R
    return ab.System(
        ab.Rotor(mass=37.0, unbalance=Me, **rotor_kw),
        ab.Suspension(kx=20e3, ky=6e3, cx=200.0, cy=110.0),
        ab.BallBalancer(n, m, R, 0.014, element="ball", damping=c_i * m * R * R,
                        rolling_resistance=f_r, eccentricity=rho, eccentricity_angle=beta),
        ab.Gravity(g, np.pi), name="washer_000")


@pytest.fixture
def rng():
    return np.random.default_rng(12345)


def run_main(capsys, args) -> tuple:
    """The real entry point ``autobalance.cli.main`` in this process: (exit code, stdout,
    stderr) of the command ``args``."""
    from autobalance.cli import main

    capsys.readouterr()
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in args])
    out = capsys.readouterr()
    return e.value.code, out.out, out.err


# Sweep descriptions shared by tests/test_sweep*.py.
# 2 grid values x start_grid n = 4 (10 samples for 2 identical balls) = 20 runs, 7 tasks of <= 3,
# on a 12 s run-up / plateau / run-down profile (~1 s for the whole sweep).
TINY_SWEEP = """
[sweep]
name = "tiny"
base = "vub_jeffcott_004"
set = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s", "profile.plateau_time=2 s", "profile.up_time=1 s"]
batch_size = 3

[grid]
"balancer.rolling_resistance" = [0.001, 0.002]

[monte_carlo]
kind = "start_grid"
n = 4
"""

# 55 runs in 28 tasks of 2: long enough to interrupt in the middle. The stuck ramps are
# stepped (the creep law: its holds are closed forms, its ramps are not) so that the runs keep
# this length: the fault tests need a sweep that is still running, not a fast one.
LONG_SWEEP = """
[sweep]
name = "resumable"
base = "vub_jeffcott_004"
set = ["profile.duration=30 s", "profile.runup_fraction=0.4", "profile.down_time=4 s", "profile.plateau_time=5 s", "profile.up_time=4 s", "options.friction_law=creep"]
batch_size = 2

[monte_carlo]
kind = "start_grid"
n = 10
"""


# ~210 runs in tasks of 2 (~0.05-0.1 s each): several seconds on 2 workers, long enough to
# interrupt or kill from outside in the middle (tests/test_sweep_faults.py, test_sweep_dask.py).
SLOW_SWEEP = LONG_SWEEP.replace('name = "resumable"', 'name = "slow"').replace("n = 10", "n = 20")


def spec_of(text: str):
    """A SweepSpec from TOML text."""
    import tomllib

    from autobalance.sweep import spec_from_dict
    return spec_from_dict(tomllib.loads(text))


def assert_bit_identical(a, b):
    """Same data variables, dims, dtypes and bytes (not approx); same coordinates."""
    assert set(a.data_vars) == set(b.data_vars)
    assert dict(a.sizes) == dict(b.sizes)
    for v in a.data_vars:
        x, y = a[v], b[v]
        assert x.dims == y.dims, v
        assert x.dtype == y.dtype, v
        assert x.values.tobytes() == y.values.tobytes(), f"{v} differs"
    for c in a.coords:
        assert np.array_equal(a[c].values, b[c].values), c


# Reproduction targets (tests/test_targets_*.py): the row contract of autobalance.validation.target.
ROW_FIELDS = {"key", "quantity", "published", "computed", "tolerance", "ok", "note"}


def assert_rows_answer_claims(target, rows, allow_not_computed=False):
    """Each claim of ``target`` has exactly one row with the 7 fields; a miss says why."""
    from autobalance.validation.target import claims, status

    keys = [r["key"] for r in rows]
    assert len(keys) == len(set(keys)), target.id
    assert set(keys) == set(claims(target)), target.id
    allowed = ("pass", "miss", "not computed") if allow_not_computed else ("pass", "miss")
    for r in rows:
        assert set(r) - {"status"} == ROW_FIELDS, r      # the report adds the status it derived
        assert status(r) in allowed, r
        assert r.get("status", status(r)) == status(r), r
        if not r["ok"]:
            assert r["note"], r["key"]


def file_modes_bind() -> dict:
    """subprocess kwargs that make file modes bind the child even when the tests run as root:
    drop CAP_DAC_OVERRIDE and CAP_DAC_READ_SEARCH from its capability bounding set (prctl
    PR_CAPBSET_DROP) before exec, so a read-only directory is read-only for it too (the real
    kernel check, no mock)."""
    import os

    if os.geteuid() != 0:
        return {}
    import ctypes

    libc = ctypes.CDLL(None, use_errno=True)

    def drop():
        for cap in (1, 2):                           # CAP_DAC_OVERRIDE, CAP_DAC_READ_SEARCH
            if libc.prctl(24, cap, 0, 0, 0) != 0:    # PR_CAPBSET_DROP
                os._exit(97)
    return {"preexec_fn": drop}


# -- the real quick report, once per test session ------------------------------------------------
# Every test that takes the `quick_report` fixture is marked `report` (pytest_collection_modifyitems
# below): test_report.py, test_golden_rows.py, test_targets_*.py and test_tsr_004.py read its rows,
# figures and data instead of running the targets again.
ROOT = Path(__file__).resolve().parents[1]
_REPORT_TIMES: dict = {}


def _autobalance_exe() -> Path:
    """The console script of the interpreter running the tests (then PATH, then ./.venv)."""
    here = Path(sys.executable).parent / "autobalance"
    return here if here.exists() else Path(shutil.which("autobalance") or ROOT / ".venv" / "bin" / "autobalance")


@pytest.fixture(scope="session")
def quick_report(tmp_path_factory):
    """`autobalance reproduce all --quick --json` as a user runs it (a real process):
    (the report dict, its out directory with figures/, data/ and stores/)."""
    out = tmp_path_factory.mktemp("report")
    t0 = time.perf_counter()
    p = subprocess.run([str(_autobalance_exe()), "reproduce", "all", "--quick", "--out-dir", str(out), "--json"],
                       capture_output=True, text=True, timeout=1800)
    assert p.returncode == 0, p.stderr[-3000:]
    rep = json.loads(p.stdout)
    _REPORT_TIMES.update(process_s=time.perf_counter() - t0, report_s=rep["wall_time_s"],
                         targets={t["id"]: t["wall_time_s"] for t in rep["targets"]})
    return rep, out


@pytest.fixture(scope="session")
def report_targets(quick_report):
    """The quick report's target records by id (rows, figures, data, run_notes, ...)."""
    rep, _ = quick_report
    return {t["id"]: t for t in rep["targets"]}


def report_rows(rec) -> dict:
    """A target record's rows by key without the ``<prefix>/`` of its claims."""
    return {r["key"].split("/", 1)[1]: r for r in rec["rows"]}


def pytest_collection_modifyitems(config, items):
    for item in items:
        if "quick_report" in getattr(item, "fixturenames", ()):
            item.add_marker(pytest.mark.report)


def pytest_terminal_summary(terminalreporter):
    """Wall times of the quick report (information, not a test: budgets live in benchmarks/)."""
    if not _REPORT_TIMES:
        return
    t = _REPORT_TIMES
    slow = sorted(t["targets"].items(), key=lambda kv: -kv[1])[:6]
    terminalreporter.write_sep("-", "quick report wall time")
    terminalreporter.write_line(f"process {t['process_s']:.0f} s, targets {t['report_s']:.0f} s; slowest: "
                                + ", ".join(f"{k} {v:.0f} s" for k, v in slow))


# -- figures as written (SVG): the text of titles and axis labels ---------------------------------
_SVG = "{http://www.w3.org/2000/svg}"


def svg_text(path) -> dict:
    """Texts of a matplotlib SVG by role: ``suptitle`` (figure texts) and per drawn axes its
    ``texts`` (title and annotations), ``xlabel`` and ``ylabel``. matplotlib writes each text as
    paths preceded by a comment holding the string, inside groups named figure_1 / axes_N /
    matplotlib.axis_N (xtick_N / ytick_N for tick labels) / text_N."""
    import xml.etree.ElementTree as ET

    tree = ET.parse(path, parser=ET.XMLParser(target=ET.TreeBuilder(insert_comments=True)))

    def gid(e):
        return e.get("id", "") if e.tag == _SVG + "g" else ""

    def text_of(e):
        return " ".join(c.text.strip() for c in e if c.tag is ET.Comment)

    def texts(parent):
        return [text_of(c) for c in parent if gid(c).startswith("text_")]

    fig = next(e for e in tree.getroot().iter() if gid(e) == "figure_1")
    axes = []
    for ax in (c for c in fig if gid(c).startswith("axes_")):
        rec = {"texts": texts(ax), "xlabel": [], "ylabel": []}
        for i, axis in enumerate(c for c in ax if gid(c).startswith("matplotlib.axis_")):
            ticks = {gid(c).split("_")[0] for c in axis} & {"xtick", "ytick"}
            which = "x" if ticks == {"xtick"} else "y" if ticks == {"ytick"} else "xy"[min(i, 1)]
            rec[which + "label"] += [t for t in texts(axis) if t]
        axes.append(rec)
    return {"suptitle": texts(fig), "axes": axes}
