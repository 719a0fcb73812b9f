"""Sweep engine (autobalance.sweep): plan, reproducibility, executors, durable store and resume,
refusals, one-line errors for bad descriptions, summaries. Real simulations, tiny sweeps."""
from __future__ import annotations

import dataclasses
import json
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.sweep import (SweepError, load_spec, make_plan, open_sweep, percentiles,
                               reduce_over, spec_from_dict, start_grid, summary_dict, sweep)
from autobalance.sweep.plan import separate

from conftest import LONG_SWEEP as RESUMABLE  # noqa: E402
from conftest import TINY_SWEEP as TINY  # noqa: E402
from conftest import assert_bit_identical, spec_of  # noqa: E402

SHORT_PROFILE = ('["profile.duration=12 s", "profile.runup_fraction=0.5", '
                 '"profile.down_time=1 s", "profile.plateau_time=2 s", "profile.up_time=1 s"]')


def write(tmp_path: Path, text: str, name: str = "sweep.toml") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p





def run_main(*args, timeout=300):
    """The real entry point in a subprocess (python -m autobalance.cli)."""
    return subprocess.run([sys.executable, "-m", "autobalance.cli", *args],
                          capture_output=True, text=True, timeout=timeout)


def assert_one_line_error(stderr: str, *needles: str):
    lines = stderr.strip().splitlines()
    assert len(lines) == 1, stderr
    assert lines[0].startswith("error:"), stderr
    for n in needles:
        assert n in lines[0], stderr
    assert "Traceback" not in stderr





def snapshot(root: Path) -> dict:
    """Every file below root: relative path -> (bytes, mtime_ns)."""
    return {str(p.relative_to(root)): (p.read_bytes(), p.stat().st_mtime_ns)
            for p in sorted(root.rglob("*")) if p.is_file()}


@pytest.fixture(scope="module")
def tiny_ds(tmp_path_factory):
    """The TINY sweep run serially once (reference for the other tests)."""
    store = tmp_path_factory.mktemp("tiny") / "store"
    ds = sweep(spec_of(TINY), store, executor="serial", progress=False)
    return ds, store


# -- plan -------------------------------------------------------------------------------------
def test_start_grid_004_counts():
    """004 sec. 4.2: 50 positions per ball, 2 identical balls -> 50*51/2 = 1275 samples."""
    base = {"sweep": {"base": "vub_jeffcott_004"}}
    plan50 = make_plan(spec_from_dict({**base, "monte_carlo": {"kind": "start_grid", "n": 50}}))
    assert plan50.n_balls == 2
    assert plan50.n_samples == 1275 and plan50.n_runs == 1275
    plan8 = make_plan(spec_from_dict({**base, "monte_carlo": {"kind": "start_grid", "n": 8}}))
    assert plan8.n_samples == 36
    # the raw grid: every unordered pair of the 8 positions once (swapped duplicates removed)
    raw = start_grid(8, 2, identical=True)
    assert raw.shape == (36, 2)
    pairs = {tuple(sorted(np.round(r / (2 * np.pi / 8)).astype(int))) for r in raw}
    assert len(pairs) == 36
    assert start_grid(8, 2, identical=False).shape == (64, 2)
    # every task is consecutive and covers the runs exactly once
    covered = [r for first, cnt in plan50.tasks for r in range(first, first + cnt)]
    assert covered == list(range(plan50.n_runs))
    assert all(cnt <= plan50.spec.batch_size for _, cnt in plan50.tasks)


def _circular_gaps(a):
    s = np.sort(np.mod(a, 2 * np.pi))
    return np.mod(np.diff(np.r_[s, s[0] + 2 * np.pi]), 2 * np.pi)


def test_separate_coinciding_to_contact_angle():
    delta = 0.352682147263204
    a = separate(np.array([1.0, 1.0]), delta)
    assert a[1] - a[0] == pytest.approx(delta, rel=1e-8)       # exactly the contact angle
    assert a.mean() == pytest.approx(1.0, abs=1e-15)            # centroid kept
    # balls that are already apart are not moved
    far = np.array([0.0, 2.0])
    assert np.array_equal(separate(far, delta), far)
    # the start grid: the coinciding samples (i, i) become pairs exactly delta apart, and no
    # sample of the plan has two balls closer than the contact angle
    plan = make_plan(spec_from_dict({"sweep": {"base": "vub_jeffcott_004"},
                                     "monte_carlo": {"kind": "start_grid", "n": 8}}))
    d = plan.cells[0].system.balancer.contact_angle
    raw = start_grid(8, 2, identical=True)
    same = raw[:, 0] == raw[:, 1]
    assert same.sum() == 8
    for r, s in zip(raw[same], plan.start_angles[same]):
        assert np.mod(s[1] - s[0], 2 * np.pi) == pytest.approx(d, rel=1e-8)
        assert s.mean() == pytest.approx(r.mean(), abs=1e-12)
    assert np.array_equal(plan.start_angles[~same], raw[~same])
    for s in plan.start_angles:
        assert _circular_gaps(s).min() >= d * (1 - 1e-9)


# -- reproducibility --------------------------------------------------------------------------
@pytest.mark.slow
def test_same_description_same_dataset_serial(tiny_ds, tmp_path):
    ds1, store1 = tiny_ds
    assert ds1.attrs["n_runs"] == 20 and ds1.attrs["n_missing_runs"] == 0
    assert dict(ds1.sizes)["balancer__rolling_resistance"] == 2
    assert dict(ds1.sizes)["sample"] == 10
    assert len(list((store1 / "tasks").glob("*.npz"))) == 7
    assert (ds1["status"] == 0).all()
    ds2 = sweep(spec_of(TINY), tmp_path / "s2", executor="serial", progress=False)
    assert ds1.identical(ds2)
    assert_bit_identical(ds1, ds2)
    # the stored Zarr holds the same bits
    assert_bit_identical(open_sweep(store1), ds1)
    assert_bit_identical(open_sweep(tmp_path / "s2"), ds2)


@pytest.mark.slow
def test_serial_equals_local_processes(tiny_ds, tmp_path):
    ds1, _ = tiny_ds
    ds2 = sweep(spec_of(TINY), tmp_path / "local", executor="local", workers=2, progress=False)
    assert ds1.identical(ds2)
    assert_bit_identical(ds1, ds2)



# -- grid cells on the models; bases built in Python ------------------------------------------
#: identity(make_plan(TINY)) with the code digest left out (store.code_digest changes with every
#: change of the simulator's code; an empty update leaves the digest as it was). It changes with
#: the package version and with what the resolved cells hold (the models' fields and defaults);
#: pinned so that a change of how the cells are built cannot change it unnoticed.
TINY_IDENTITY = "9d9d3113ee9f6d71"


def test_tiny_identity_unchanged_by_building_cells_on_the_models(monkeypatch):
    import importlib

    st = importlib.import_module("autobalance.sweep.store")
    monkeypatch.setattr(st, "code_digest", lambda: "")
    assert st.identity(make_plan(spec_of(TINY))) == TINY_IDENTITY


def test_python_base_gives_the_preset_base_results(tiny_ds, tmp_path):
    """The same sweep from a Config and from a System (+ its [profile] table) built in Python
    gives bit-identical outcome arrays as from the preset name."""
    import tomllib

    from autobalance.config import load_config

    ref, _ = tiny_ds
    d = tomllib.loads(TINY)
    del d["sweep"]["base"]
    cfg = load_config("vub_jeffcott_004")
    ds_cfg = sweep(d, tmp_path / "cfg", base=cfg, executor="serial", progress=False)
    assert_bit_identical(ds_cfg, ref)
    assert ds_cfg.attrs["base"] == "<python: vub_jeffcott_004>"
    ds_sys = sweep(d, tmp_path / "sys", base=cfg.system, spin=dict(cfg.raw["profile"]),
                   initial=cfg.initial, options=cfg.options, executor="serial", progress=False)
    assert_bit_identical(ds_sys, ref)


def test_python_built_system_cells_are_replaced_models():
    """A System and SpeedProfile built in Python: every cell is the base with its grid values
    (validated and converted like --set); stiction follows rolling_resistance by default."""
    import autobalance as ab
    from autobalance.config import from_models

    system = ab.System(ab.Rotor(mass=16.53, unbalance=3e-4),
                       ab.Suspension.isotropic(5.8e6, 1510.0),
                       ab.BallBalancer(2, ball_mass=7.6e-3, race_radius=0.035,
                                       ball_radius=6.14e-3, element="point", damping=2.7e-3,
                                       rolling_resistance=0.002), name="mine")
    spin = ab.SpeedProfile.constant(2 * np.pi * 100, 2.0)
    d = {"sweep": {"set": ["options.rtol=1e-7"]},
         "grid": {"balancer.rolling_resistance": [0.001, 0.004], "rotor.unbalance": ["0.1 g*m"]}}
    plan = make_plan(spec_from_dict(d, base=from_models(system, spin)))
    mu = [(0.001, 0.001), (0.004, 0.004)]
    assert [c.system.balancer.rolling_resistance for c in plan.cells] == mu
    assert [c.system.balancer.stiction for c in plan.cells] == mu
    assert [c.system.rotor.unbalance for c in plan.cells] == pytest.approx([1e-4, 1e-4])
    assert {c.options.rtol for c in plan.cells} == {1e-7}
    assert all(c.spin == spin and c.system.name == "mine" for c in plan.cells)
    assert plan.spec.base == "<python: mine>"
    # the same refusals, naming the grid point, the field, the value and what is allowed
    bad = {"sweep": {}, "grid": {"rotor.mass": ["1 kg", "-1 kg"]}}
    with pytest.raises(SweepError, match=r"^grid point rotor\.mass='-1 kg': rotor\.mass = -1\.0: "
                                         r"must be > 0$"):
        make_plan(spec_from_dict(bad, base=from_models(system, spin)))
    # a SpeedProfile built in Python is a speed table: its constructor arguments are unknown
    bad = {"grid": {"profile.plateau": ["90 Hz"]}}
    with pytest.raises(SweepError, match=r"profile\.plateau: unknown key for kind 'table'"):
        make_plan(spec_from_dict(bad, base=from_models(system, spin)))


def test_python_base_refusals(tmp_path):
    from autobalance.config import load_config

    cfg = load_config("vub_jeffcott_004")
    with pytest.raises(SweepError, match=r"^sweep\.base = 'washer_000': given twice"):
        spec_from_dict({"sweep": {"base": "washer_000"}}, base=cfg)
    with pytest.raises(SweepError, match=r"^base: the description has its base already"):
        sweep(spec_of(TINY), tmp_path / "s", base=cfg, executor="serial")
    with pytest.raises(SweepError, match=r"^spin: missing"):
        sweep({}, tmp_path / "s", base=cfg.system, executor="serial")
    assert not (tmp_path / "s").exists()


RANDOM = f"""
[sweep]
name = "random"
base = "vub_jeffcott_004"
set = {SHORT_PROFILE}
batch_size = 3

[monte_carlo]
kind = "random"
samples = 3
seed = SEED
"""


def test_random_monte_carlo_seeded(tmp_path):
    s1 = spec_of(RANDOM.replace("SEED", "1"))
    s2 = spec_of(RANDOM.replace("SEED", "2"))
    p1, p1b, p2 = make_plan(s1), make_plan(spec_of(RANDOM.replace("SEED", "1"))), make_plan(s2)
    assert p1.start_angles.shape == (3, 2)
    assert np.array_equal(p1.start_angles, p1b.start_angles)
    assert not np.array_equal(p1.start_angles, p2.start_angles)
    assert s1.digest() != s2.digest()
    a = sweep(s1, tmp_path / "a", executor="serial", progress=False)
    b = sweep(spec_of(RANDOM.replace("SEED", "1")), tmp_path / "b", executor="serial",
              progress=False)
    c = sweep(s2, tmp_path / "c", executor="serial", progress=False)
    assert_bit_identical(a, b)
    assert not np.array_equal(a["start_angle"].values, c["start_angle"].values)
    assert not np.array_equal(a["initial_grade_G"].values, c["initial_grade_G"].values)
    assert not np.array_equal(a["grade_G"].values, c["grade_G"].values)


# -- durable store: kill -9 and resume --------------------------------------------------------
@pytest.mark.slow
def test_resume_after_kill9(tmp_path):
    desc = write(tmp_path, RESUMABLE)
    n_tasks = len(make_plan(load_spec(desc)).tasks)
    assert n_tasks == 28
    store = tmp_path / "S"
    tasks = store / "tasks"
    proc = subprocess.Popen([sys.executable, "-m", "autobalance.cli", "sweep", str(desc),
                             "--store", str(store), "--executor", "serial"],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        deadline = time.monotonic() + 120
        while True:
            n = len(list(tasks.glob("*.npz"))) if tasks.exists() else 0
            if n >= 2:
                break
            assert proc.poll() is None, "sweep ended before it could be killed"
            assert time.monotonic() < deadline, "no task finished in time"
            time.sleep(0.005)
        os.kill(proc.pid, signal.SIGKILL)
        proc.wait(timeout=30)
    finally:
        if proc.poll() is None:
            proc.kill()
            proc.wait()
    assert proc.returncode == -signal.SIGKILL
    finished = {p.name: (p.read_bytes(), p.stat().st_mtime_ns) for p in tasks.glob("*.npz")}
    assert 2 <= len(finished) < n_tasks, len(finished)
    assert not (store / "result.zarr").exists()
    # the interrupted store reads as a partial dataset (unfinished runs NaN, status -1)
    part = open_sweep(store, desc)
    assert 0 < part.attrs["n_missing_runs"] < part.attrs["n_runs"]
    assert int((part["status"] == -1).sum()) == part.attrs["n_missing_runs"]

    r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial", "--resume",
                 "--json")
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    # finished tasks were kept as they were, not recomputed or rewritten
    for name, (data, mtime) in finished.items():
        p = tasks / name
        assert p.stat().st_mtime_ns == mtime, name
        assert p.read_bytes() == data, name
    assert len(list(tasks.glob("*.npz"))) == n_tasks
    assert not list(store.rglob("*.tmp")), list(store.rglob("*.tmp"))
    resumed = open_sweep(store)
    assert resumed.attrs["n_missing_runs"] == 0
    # an uninterrupted run into another store gives the same bits
    ref = sweep(load_spec(desc), tmp_path / "ref", executor="serial", progress=False)
    assert_bit_identical(resumed, ref)
    assert_bit_identical(resumed, open_sweep(tmp_path / "ref"))


# -- refusals ---------------------------------------------------------------------------------
@pytest.mark.slow
def test_store_refusals_change_nothing(tiny_ds, tmp_path):
    _, store = tiny_ds
    before = snapshot(store)
    desc = write(tmp_path, TINY)
    # an existing store without --resume
    r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial")
    assert r.returncode == 2
    assert_one_line_error(r.stderr, str(store), "--resume")
    # a store of another description (one grid value changed) with --resume
    other = write(tmp_path, TINY.replace("[0.001, 0.002]", "[0.001, 0.003]"), "other.toml")
    r = run_main("sweep", str(other), "--store", str(store), "--executor", "serial", "--resume")
    assert r.returncode == 2
    assert_one_line_error(r.stderr, str(store), "different sweep description")
    assert snapshot(store) == before
    # the same refusals from the Python API
    with pytest.raises(SweepError, match="exists"):
        sweep(load_spec(desc), store, executor="serial", progress=False)
    with pytest.raises(SweepError, match="different sweep description"):
        sweep(load_spec(other), store, executor="serial", progress=False, resume=True)
    assert snapshot(store) == before


def test_resume_of_finished_store_reruns_nothing(tiny_ds):
    ds, store = tiny_ds
    tasks_before = snapshot(store / "tasks")
    again = sweep(spec_of(TINY), store, executor="serial", resume=True, progress=False)
    assert snapshot(store / "tasks") == tasks_before
    assert_bit_identical(ds, again)


# -- bad sweep files --------------------------------------------------------------------------
BASE = '[sweep]\nbase = "vub_jeffcott_004"\n'
BAD = [
    ("unknown-grid-path", BASE + '[grid]\n"rotor.foo" = [1.0]\n', "grid.rotor.foo"),
    ("bad-grid-section", BASE + '[grid]\n"nosuch.mass" = [1.0]\n', "grid.nosuch.mass"),
    ("empty-grid", BASE + '[grid]\n"rotor.mass" = []\n', "grid.rotor.mass"),
    ("wrong-units", BASE + '[grid]\n"suspension.kx" = ["5 kg"]\n', "grid.suspension.kx"),
    ("mc-n-zero", BASE + '[monte_carlo]\nkind = "start_grid"\nn = 0\n', "monte_carlo.n"),
    ("mc-samples-negative", BASE + '[monte_carlo]\nkind = "random"\nsamples = -3\n',
     "monte_carlo.samples"),
    ("batch-size-zero", '[sweep]\nbase = "vub_jeffcott_004"\nbatch_size = 0\n',
     "sweep.batch_size"),
    ("unknown-mc-kind", BASE + '[monte_carlo]\nkind = "sobol"\n', "monte_carlo.kind"),
    ("missing-base", '[sweep]\nname = "x"\n', "sweep.base"),
    ("missing-sweep", '[grid]\n"rotor.mass" = ["1 kg"]\n', "sweep"),
    ("unknown-section", BASE + '[foo]\nx = 1\n', "foo"),
    ("model-rejects-grid-value", BASE + '[grid]\n"rotor.mass" = ["-1 kg"]\n',
     "grid point rotor.mass"),
    ("range-wrong-units", BASE + '[grid]\n"rotor.mass" = { start = "1 kg", stop = "2 s", num = 3 }\n',
     "grid.rotor.mass.stop"),
    ("unknown-base", '[sweep]\nbase = "no_such_preset"\n', "sweep.base"),
    ("bad-set", '[sweep]\nbase = "vub_jeffcott_004"\nset = ["rotor.foo=1"]\n', "sweep.set"),
    ("history-dt-units", BASE + '[outputs]\nhistory_dt = "1 kg"\n', "outputs.history_dt"),
]
# errors found while expanding the description into configs (make_plan), not while parsing it
PLAN_ERRORS = ("grid point rotor.mass", "sweep.base", "sweep.set")


@pytest.mark.parametrize("text, field", [b[1:] for b in BAD], ids=[b[0] for b in BAD])
def test_bad_sweep_file_exit_2_one_line(tmp_path, text, field):
    desc = write(tmp_path, text)
    store = tmp_path / "store"
    r = CliRunner().invoke(app, ["sweep", str(desc), "--store", str(store),
                                 "--executor", "serial"])
    assert r.exit_code == 2, (r.stdout, r.stderr, r.exception)
    assert_one_line_error(r.stderr, field)
    assert r.stdout == ""
    assert not store.exists()        # nothing was created for a rejected description
    with pytest.raises(SweepError, match=field.replace(".", r"\.")):
        load_spec(desc) if field not in PLAN_ERRORS else make_plan(load_spec(desc))


@pytest.mark.slow
@pytest.mark.parametrize("name", ["unknown-grid-path", "wrong-units", "model-rejects-grid-value"])
def test_bad_sweep_file_real_entry_point(tmp_path, name):
    """The real process: exit 2, one line on stderr, no traceback."""
    _, text, field = next(b for b in BAD if b[0] == name)
    desc = write(tmp_path, text)
    r = run_main("sweep", str(desc), "--store", str(tmp_path / "store"))
    assert r.returncode == 2
    assert_one_line_error(r.stderr, field)
    assert not (tmp_path / "store").exists()


def test_bad_executor_and_workers(tmp_path):
    desc = write(tmp_path, TINY)
    for args, field in [(["--executor", "threads"], "executor"), (["--workers", "0"], "workers"),
                        (["--executor", "dask"], "scheduler")]:
        r = CliRunner().invoke(app, ["sweep", str(desc), "--store", str(tmp_path / "st"), *args],
                               env={"DASK_SCHEDULER_ADDRESS": ""})
        assert r.exit_code == 2, (args, r.stderr, r.exception)
        assert_one_line_error(r.stderr, field)
        assert not (tmp_path / "st").exists()


# -- summaries --------------------------------------------------------------------------------
def test_summary_dict_ordered_and_shares(tiny_ds):
    ds, _ = tiny_ds
    s = summary_dict(ds, grade=16.0)
    assert s["runs"] == 20 and s["missing_runs"] == 0 and s["failed_runs"] == 0
    assert len(s["checkpoints"]) == ds.sizes["checkpoint"] >= 1
    for c in s["checkpoints"]:
        assert np.isfinite([c["grade_G_p5_mm_s"], c["grade_G_p50_mm_s"], c["grade_G_p95_mm_s"]]).all()
        assert c["grade_G_p5_mm_s"] <= c["grade_G_p50_mm_s"] <= c["grade_G_p95_mm_s"]
        assert 0.0 <= c["share_below_limit"] <= 1.0
    # the share is the fraction of runs at or below the limit at that checkpoint
    g = ds["grade_G"].values.reshape(-1, ds.sizes["checkpoint"])
    for i, c in enumerate(s["checkpoints"]):
        assert c["share_below_limit"] == pytest.approx(np.mean(g[:, i] <= 16.0))
    assert summary_dict(ds, grade=1e9)["checkpoints"][-1]["share_below_limit"] == 1.0
    assert summary_dict(ds, grade=0.0)["checkpoints"][-1]["share_below_limit"] == 0.0


def test_percentiles_dim(tiny_ds):
    ds, _ = tiny_ds
    p = percentiles(ds)
    assert "percentile" in p.dims and list(p["percentile"].values) == [5, 50, 95]
    assert "sample" not in p.dims
    assert "balancer__rolling_resistance" in p.dims and "checkpoint" in p.dims
    v = p.transpose("percentile", ...).values
    assert (np.diff(v, axis=0) >= 0).all()
    r = reduce_over(ds, keep="balancer__rolling_resistance", q=(10, 90))
    assert set(r.dims) == {"percentile", "balancer__rolling_resistance", "checkpoint"}
    assert list(r["percentile"].values) == [10, 90]


@pytest.mark.slow
def test_unbalance_grid_matches_individual_runs(tmp_path):
    """A grid over rotor.unbalance (004 Fig. 7) batches runs of different unbalance into one
    task; every run must equal its own single simulation."""
    import autobalance as ab
    from autobalance.config import load_config
    from autobalance.sweep import make_plan, spec_from_dict, sweep

    sets = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s",
            "profile.plateau_time=2 s", "profile.up_time=1 s"]
    d = {"sweep": {"name": "u", "base": "vub_jeffcott_004", "set": sets, "batch_size": 64},
         "grid": {"rotor.unbalance": ["0.1 g*m", "0.3 g*m", "0.6 g*m"]},
         "monte_carlo": {"kind": "start_grid", "n": 3}}
    spec = spec_from_dict(d)
    plan = make_plan(spec)
    assert len(plan.tasks) == 1                 # all cells share the profile: one task
    ds = sweep(spec, tmp_path / "s", executor="serial", progress=False)
    for i, u in enumerate(["0.1 g*m", "0.3 g*m", "0.6 g*m"]):
        cfg = load_config("vub_jeffcott_004", sets + [f"rotor.unbalance={u}"])
        for s in range(plan.n_samples):
            sim = ab.simulate(cfg.system, cfg.spin,
                              options=dataclasses.replace(cfg.options, save_dt=-1.0),
                              initial=ab.InitialState(ball_angles=tuple(plan.start_angles[s])))
            got = ds["grade_G"].isel(rotor__unbalance=i, sample=s).values
            assert got[-1] == sim.at(12.0)["grade_G_mm_s"]


def test_store_from_another_package_version_is_refused(tmp_path):
    import json

    from autobalance.sweep import StoreMismatch, spec_from_dict, sweep

    d = {"sweep": {"name": "v", "base": "vub_jeffcott_004",
                   "set": ["profile.duration=12 s", "profile.runup_fraction=0.5",
                           "profile.down_time=1 s", "profile.plateau_time=2 s",
                           "profile.up_time=1 s"]},
         "monte_carlo": {"kind": "start_grid", "n": 2}}
    store = tmp_path / "s"
    sweep(spec_from_dict(d), store, executor="serial", progress=False)
    meta = json.loads((store / "sweep.json").read_text())
    meta["autobalance_version"] = "0.0.1"
    (store / "sweep.json").write_text(json.dumps(meta))
    before = {p: p.read_bytes() for p in (store / "tasks").iterdir()}
    with pytest.raises(StoreMismatch, match="0.0.1"):
        sweep(spec_from_dict(d), store, executor="serial", progress=False, resume=True)
    assert {p: p.read_bytes() for p in (store / "tasks").iterdir()} == before


@pytest.mark.slow
def test_history_matches_checkpoints_and_profile(tmp_path):
    """[outputs] history_dt: the decimated histories are the states at their own times (the
    checkpoints come first in the request, the histories after, unsorted), so a history sample
    at a checkpoint time equals the checkpoint, and the speed follows the profile from rest."""
    from autobalance.sweep import sweep

    spec = spec_of(TINY + '\n[outputs]\nhistory_dt = "0.5 s"\n')
    ds = sweep(spec, tmp_path / "h", executor="serial", progress=False)
    t = ds["history_time"].values
    for k, tc in enumerate(ds["checkpoint"].values):          # 6 s (STD) and 12 s (TSR)
        j = int(np.flatnonzero(np.isclose(t, tc))[0])
        np.testing.assert_array_equal(ds["grade_G_history"].isel(history_time=j).values,
                                      ds["grade_G"].isel(checkpoint=k).values)
    spin = make_plan(spec).cells[0].spin
    w = ds["speed_history"].isel(balancer__rolling_resistance=0, sample=0).values
    np.testing.assert_allclose(w, np.interp(t, spin.times, spin.speeds), rtol=1e-9, atol=1e-9)
    assert w[0] == 0.0


def test_simulate_batch_any_order_of_out_times():
    import autobalance as ab
    from autobalance.config import load_config

    cfg = load_config("vub_jeffcott_004", ["profile.duration=12 s", "profile.runup_fraction=0.5",
                                           "profile.down_time=1 s", "profile.plateau_time=2 s",
                                           "profile.up_time=1 s"])
    ts = np.array([12.0, 3.0, 6.0, 0.0, 6.0])
    a = ab.simulate_batch([cfg.system], cfg.spin, options=cfg.options, out_times=ts)
    b = ab.simulate_batch([cfg.system], cfg.spin, options=cfg.options, out_times=np.sort(ts))
    order = np.argsort(ts, kind="stable")
    np.testing.assert_array_equal(a.states[:, order], b.states)
    np.testing.assert_array_equal(a.states[:, 2], a.states[:, 4])


# -- summary per grid cell ----------------------------------------------------------------------
def test_summary_per_grid_cell(tiny_ds):
    """Each cell's statistics are those of its own samples; the pooled line is unchanged."""
    ds, _ = tiny_ds
    s = summary_dict(ds, grade=16.0)
    assert [a["path"] for a in s["grid"]] == ["balancer.rolling_resistance"]
    assert len(s["cells"]) == ds.sizes["balancer__rolling_resistance"] == 2
    ok = ds["status"].values == 0
    for k, cell in enumerate(s["cells"]):
        mu = float(ds["balancer__rolling_resistance"].values[k])
        assert cell["coords"] == {"balancer.rolling_resistance": mu}
        assert cell["coords_as_given"] == {"balancer.rolling_resistance": [0.001, 0.002][k]}
        assert cell["ok_runs"] == int(ok[k].sum()) == 10 and cell["failed_runs"] == 0
        for i, c in enumerate(cell["checkpoints"]):
            g = ds["grade_G"].values[k, :, i][ok[k]]
            assert c["grade_G_p5_mm_s"] == pytest.approx(np.percentile(g, 5))
            assert c["grade_G_p50_mm_s"] == pytest.approx(np.percentile(g, 50))
            assert c["grade_G_p95_mm_s"] == pytest.approx(np.percentile(g, 95))
            assert c["share_below_limit"] == pytest.approx(np.mean(g <= 16.0))
    # the cells differ (otherwise per-cell statistics would prove nothing here)
    assert s["cells"][0]["checkpoints"][-1] != s["cells"][1]["checkpoints"][-1]
    g_all = ds["grade_G"].values[..., -1][ok]
    assert s["checkpoints"][-1]["grade_G_p95_mm_s"] == pytest.approx(np.percentile(g_all, 95))


def test_summary_cells_on_the_command_line(tmp_path):
    desc = write(tmp_path, TINY.replace('[0.001, 0.002]', '["0.001", "0.002"]'))
    r = CliRunner().invoke(app, ["sweep", str(desc), "--store", str(tmp_path / "st"),
                                 "--executor", "serial", "--json", "--grade", "6.3"])
    assert r.exit_code == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["grade_limit_mm_s"] == 6.3 and len(d["cells"]) == 2
    assert [c["coords"]["balancer.rolling_resistance"] for c in d["cells"]] == [0.001, 0.002]
    t = CliRunner().invoke(app, ["sweep", str(desc), "--store", str(tmp_path / "st"),
                                 "--executor", "serial", "--resume", "--grade", "6.3"])
    assert t.exit_code == 0, t.stderr
    assert "target grade: G6.3 (ISO 1940 class G6.3" in t.stdout
    assert "per grid cell (2):" in t.stdout
    for cell in d["cells"]:
        mu = cell["coords_as_given"]["balancer.rolling_resistance"]
        assert f"balancer.rolling_resistance = {mu} (10 runs):" in t.stdout
        c = cell["checkpoints"][-1]
        assert (f"G p5/p50/p95 = {c['grade_G_p5_mm_s']:.2f} / {c['grade_G_p50_mm_s']:.2f} / "
                f"{c['grade_G_p95_mm_s']:.2f} mm/s") in t.stdout


# -- balancer.n_balls as a grid axis; a base without balls --------------------------------------
CENTRIFUGE = str(Path(__file__).resolve().parents[1] / "examples" / "centrifuge.toml")
CENTRIFUGE_SHORT = ["profile.duration=12 s", "profile.runup_fraction=0.5",
                    "profile.down_time=1 s", "profile.plateau_time=2 s", "profile.up_time=1 s"]


def _centrifuge_spec(grid, mc, sets=()):
    return spec_from_dict({"sweep": {"name": "nb", "base": CENTRIFUGE,
                                     "set": CENTRIFUGE_SHORT + list(sets)},
                           "grid": grid, "monte_carlo": mc})


def test_n_balls_axis_2_vs_3_equals_single_runs(tmp_path):
    """2 against 3 balls (random starts per ball count): every run equals its own simulation
    of that machine; the 2-ball cell's third ball is NaN."""
    import autobalance as ab
    from autobalance.config import load_config, replace_values

    spec = _centrifuge_spec({"balancer.n_balls": [2, 3]},
                            {"kind": "random", "samples": 2, "seed": 5})
    plan = make_plan(spec)
    assert sorted(plan.angles) == [2, 3] and plan.n_balls == 3
    assert plan.angles[2].shape == (2, 2) and plan.angles[3].shape == (2, 3)
    assert all(plan.cells[r0 // 2].system.balancer.n_balls ==
               plan.cells[(r0 + n - 1) // 2].system.balancer.n_balls for r0, n in plan.tasks)
    # the 2-ball cell gets the angles a sweep of 2 balls alone gets
    alone = make_plan(_centrifuge_spec({}, {"kind": "random", "samples": 2, "seed": 5}))
    assert np.array_equal(alone.start_angles, plan.angles[2])
    ds = sweep(spec, tmp_path / "s", executor="serial", progress=False)
    assert ds["start_angle"].dims == ("balancer__n_balls", "sample", "ball")
    assert np.isnan(ds["ball_angle"].sel(balancer__n_balls=2).values[..., 2]).all()
    assert np.isfinite(ds["ball_angle"].sel(balancer__n_balls=3).values).all()
    base = load_config(CENTRIFUGE, CENTRIFUGE_SHORT)
    for n in (2, 3):
        cfg = replace_values(base, {"balancer.n_balls": n, "initial.ball_angles": None})
        assert cfg.system.balancer.ball_mass == (0.008,) * n      # identical balls broadcast
        for s in range(2):
            sim = ab.simulate(cfg.system, cfg.spin,
                              options=dataclasses.replace(cfg.options, save_dt=-1.0),
                              initial=ab.InitialState(ball_angles=tuple(plan.angles[n][s])))
            got = ds["grade_G"].sel(balancer__n_balls=n).isel(sample=s).values
            want = [sim.at(t)["grade_G_mm_s"] for t in cfg.spin.checkpoints]
            assert list(got) == want
    s = summary_dict(ds)
    assert [c["coords"] for c in s["cells"]] == [{"balancer.n_balls": 2}, {"balancer.n_balls": 3}]


def test_n_balls_axis_start_angles_follow():
    """Without a Monte-Carlo dimension the cell of the base's ball count keeps the written
    start angles and the others start equispaced, in any grid order; per-ball lists of equal
    values broadcast, lists of different values fail in one line naming the grid point."""
    plan = make_plan(_centrifuge_spec({"balancer.n_balls": [3, 2, 0]}, {"kind": "none"},
                                      ['balancer.ball_mass=["8 g", "8 g"]']))
    np.testing.assert_allclose(np.degrees(plan.angles[2]), [[45.0, 135.0]])
    np.testing.assert_allclose(np.degrees(plan.angles[3]), [[45.0, 165.0, 285.0]])
    assert plan.angles[0].shape == (1, 0)
    assert [c.system.balancer.n_balls for c in plan.cells] == [3, 2, 0]
    assert plan.cells[0].system.balancer.ball_mass == (0.008,) * 3
    assert len(plan.groups) == 3                         # one task group per ball count
    with pytest.raises(SweepError, match=r"^grid point balancer\.n_balls=3: balancer\.ball_mass"):
        make_plan(_centrifuge_spec({"balancer.n_balls": [2, 3]}, {"kind": "none"},
                                   ['balancer.ball_mass=["8 g", "9 g"]']))


def test_n_balls_axis_with_a_start_grid_of_other_sizes_is_refused(tmp_path):
    desc = write(tmp_path, f'''
[sweep]
base = "{CENTRIFUGE}"
[grid]
"balancer.n_balls" = [2, 3]
[monte_carlo]
kind = "start_grid"
n = 4
''')
    r = CliRunner().invoke(app, ["sweep", str(desc), "--store", str(tmp_path / "st")])
    assert r.exit_code == 2
    assert_one_line_error(r.stderr, "monte_carlo.kind = 'start_grid'", "10 for 2 balls",
                          "20 for 3 balls", "kind = 'random'")
    assert not (tmp_path / "st").exists()


def test_base_without_balls(tmp_path):
    """A base of 0 balls (start grid or random): runs, one start for the start grid, and the
    grade stays the rotor's own (closed form G = 1000 U / M Omega) at every checkpoint."""
    from autobalance.config import load_config
    from autobalance.physics.iso1940 import grade_value

    desc = write(tmp_path, f'''
[sweep]
base = "{CENTRIFUGE}"
set = {json.dumps(CENTRIFUGE_SHORT + ["balancer.n_balls=0"])}
[grid]
"rotor.unbalance" = ["0.3 g*m", "0.6 g*m"]
[monte_carlo]
kind = "start_grid"
n = 4
''')
    r = CliRunner().invoke(app, ["sweep", str(desc), "--store", str(tmp_path / "st"),
                                 "--executor", "serial", "--json"])
    assert r.exit_code == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["runs"] == 2 and d["failed_runs"] == 0 and d["dims"]["ball"] == 0
    cfg = load_config(CENTRIFUGE, CENTRIFUGE_SHORT + ["balancer.n_balls=0",
                                                      "initial.ball_angles=[]"])
    for cell, u in zip(d["cells"], (3e-4, 6e-4)):
        want = grade_value(u, cfg.system.total_mass, cfg.spin.nominal_speed)
        for c in cell["checkpoints"]:
            assert c["grade_G_p50_mm_s"] == pytest.approx(want, rel=1e-12)
    plan = make_plan(_centrifuge_spec({}, {"kind": "random", "samples": 3},
                                      ["balancer.n_balls=0"]))
    assert plan.start_angles.shape == (3, 0)


@pytest.mark.slow
def test_keyed_stores_resume_their_own_and_start_new_ones_beside(tmp_path):
    """keyed=True (the studies' stores): one store per identity under the directory; the same
    sweep resumes its own (nothing rerun), another option starts a new store instead of being
    refused, and the first store is left as it was."""
    from autobalance.models import SimOptions

    spec = spec_of(TINY)
    a = sweep(spec, tmp_path, executor="serial", progress=False, keyed=True)
    (first,) = [p for p in tmp_path.iterdir() if p.is_dir()]
    before = snapshot(first / "tasks")
    again = sweep(spec, tmp_path, executor="serial", progress=False, keyed=True, resume=True)
    assert_bit_identical(a, again)
    assert snapshot(first / "tasks") == before
    other = sweep(spec, tmp_path, executor="serial", progress=False, keyed=True, resume=True,
                  options=SimOptions(rtol=1e-7))
    assert len([p for p in tmp_path.iterdir() if p.is_dir()]) == 2
    assert snapshot(first / "tasks") == before
    assert other.sizes == a.sizes


def test_store_from_other_simulator_code_is_refused_and_keyed_stores_start_anew(tmp_path,
                                                                                monkeypatch):
    """The package version stays the same between commits, so a store made before a change of the
    simulator's code would have been resumed with the old results. The identity now includes
    the digest of the code that computes the runs (sweep/store.code_digest): an explicit store
    is refused in one line and left as it was; a keyed store (the studies', make run's) starts
    a new one beside it."""
    import importlib

    st = importlib.import_module("autobalance.sweep.store")
    from autobalance.studies.common import run_start_grid
    from autobalance.sweep import StoreMismatch, spec_from_dict, sweep

    sets = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s",
            "profile.plateau_time=2 s", "profile.up_time=1 s"]
    d = {"sweep": {"name": "v", "base": "vub_jeffcott_004", "set": sets},
         "monte_carlo": {"kind": "start_grid", "n": 2}}
    store = tmp_path / "s"
    sweep(spec_from_dict(d), store, executor="serial", progress=False)
    before = {p: p.read_bytes() for p in (store / "tasks").iterdir()}
    monkeypatch.setattr(st, "code_digest", lambda: "0" * 16)
    with pytest.raises(StoreMismatch, match="other code of autobalance") as e:
        sweep(spec_from_dict(d), store, executor="serial", progress=False, resume=True)
    assert "\n" not in str(e.value)
    assert {p: p.read_bytes() for p in (store / "tasks").iterdir()} == before
    monkeypatch.undo()
    keyed = tmp_path / "k"
    run_start_grid("vub_jeffcott_004", "k", sets, {}, 2, store=keyed, executor="serial")
    monkeypatch.setattr(st, "code_digest", lambda: "0" * 16)
    run_start_grid("vub_jeffcott_004", "k", sets, {}, 2, store=keyed, executor="serial")
    assert len([p for p in keyed.iterdir() if p.is_dir()]) == 2


@pytest.mark.slow
def test_code_digest_follows_the_simulator_not_the_cli(tmp_path):
    """code_digest changes with a byte of the kernel's source and not with the CLI's (a copy of
    the package, imported in a fresh interpreter)."""
    import shutil
    import subprocess
    import sys

    import autobalance

    src = Path(autobalance.__file__).parent

    def digest(edit=None):
        root = tmp_path / (edit or "orig")
        shutil.copytree(src, root / "autobalance",
                        ignore=shutil.ignore_patterns("__pycache__"))
        if edit:
            with open(root / "autobalance" / edit, "a") as f:
                f.write("\n# edited\n")
        r = subprocess.run([sys.executable, "-c", "from autobalance.sweep.store import "
                            "code_digest; print(code_digest())"], capture_output=True,
                           text=True, timeout=120, env={**os.environ, "PYTHONPATH": str(root)},
                           cwd=tmp_path)
        assert r.returncode == 0, r.stderr
        return r.stdout.strip()

    base = digest()
    assert len(base) == 16
    assert digest("core/rhs.py") != base
    assert digest("cli/simulate.py") == base


def test_progress_in_a_log_is_a_line_per_5_percent():
    """Progress on a stream that is not a terminal (a log file, a pipe): one line per 5 % of
    the runs and one at the end, never a line per update; on a terminal one line rewritten."""
    import io

    from autobalance.sweep.execute import Progress

    log = io.StringIO()
    p = Progress(400, stream=log)
    for _ in range(400):
        p.update(1)
    import re

    done = [int(re.search(r"\] (\d+)/400 runs", x).group(1))
            for x in log.getvalue().splitlines()]
    assert done == [1, *range(20, 401, 20)]                 # 21 lines

    class Tty(io.StringIO):
        def isatty(self):
            return True

    tty = Tty()
    p = Progress(50, stream=tty)
    for _ in range(50):
        p.update(1)
    assert tty.getvalue().count("\r") == 50 and tty.getvalue().count("\n") == 1
