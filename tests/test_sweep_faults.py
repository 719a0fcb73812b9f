"""Nothing silently wrong: store identity, tasks keyed by run, per-cell options, the
store lock, prompt interruption (real SIGINT / SIGTERM / kill -9 on real processes), write
errors, corrupted task files, failed runs, resource guards, start placement up to capacity.

Every test runs the real thing: subprocesses of the real entry point, real signals, real files.
"""
from __future__ import annotations

import dataclasses
import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import psutil
import pytest

import autobalance as ab
from autobalance.config import load_config, preset_path
from autobalance.sweep import (StoreMismatch, SweepError, load_spec, make_plan,
                               open_sweep, spec_from_dict, sweep)
from autobalance.sweep.plan import separate

from conftest import SLOW_SWEEP as SLOW  # noqa: E402
from conftest import TINY_SWEEP as TINY  # noqa: E402
from conftest import assert_bit_identical, file_modes_bind, spec_of  # noqa: E402

SHORT = ["profile.duration=12 s", "profile.runup_fraction=0.5", "profile.down_time=1 s",
         "profile.plateau_time=2 s", "profile.up_time=1 s"]

def write(tmp_path: Path, text: str, name: str = "sweep.toml") -> Path:
    p = tmp_path / name
    p.write_text(text)
    return p


def cli(*args):
    return [sys.executable, "-m", "autobalance.cli", *args]


def run_main(*args, timeout=300, **kw):
    return subprocess.run(cli(*args), capture_output=True, text=True, timeout=timeout, **kw)


def one_line(stderr: str, *needles: str) -> str:
    lines = [ln for ln in stderr.strip().splitlines() if not ln.startswith(("[", "slow:", "tiny:"))]
    assert len(lines) == 1, stderr
    assert lines[0].startswith("error:"), stderr
    for n in needles:
        assert n in lines[0], stderr
    assert "Traceback" not in stderr
    return lines[0]


def n_task_files(store: Path) -> int:
    d = store / "tasks"
    return len(list(d.glob("r*.npz"))) if d.is_dir() else 0


def terminal_signals() -> None:
    """In the child before exec: Ctrl-C as a terminal leaves it (default disposition). A test
    run started in the background of a non-interactive shell inherits SIGINT ignored, and
    Python then keeps ignoring it, as ``nohup`` intends; the interrupt tests need a terminal."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


def wait_for_tasks(proc, store: Path, n: int, timeout: float = 120.0) -> None:
    deadline = time.monotonic() + timeout
    while n_task_files(store) < n:
        assert proc.poll() is None, "the sweep ended before it could be interrupted"
        assert time.monotonic() < deadline, "no task finished in time"
        time.sleep(0.01)


def files(store: Path) -> dict:
    return {str(p.relative_to(store)): p.read_bytes() for p in sorted(store.rglob("*"))
            if p.is_file() and p.name != "lock"}


@pytest.fixture(scope="module")
def slow_ref(tmp_path_factory):
    """The SLOW sweep run once on local processes (reference)."""
    d = tmp_path_factory.mktemp("slowref")
    return sweep(spec_of(SLOW), d / "s", executor="local", workers=2, progress=False)


@pytest.fixture(scope="module")
def tiny_ref(tmp_path_factory):
    d = tmp_path_factory.mktemp("tinyref")
    return sweep(spec_of(TINY), d / "s", executor="serial", progress=False)


# -- 1. batch_size is not part of the results ------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("first, second", [(1, 8), (8, 64), (3, 1)])
def test_batch_size_change_resumes_exactly_the_missing_runs(tiny_ref, tmp_path, first, second):
    store = tmp_path / "s"
    sweep(spec_of(TINY.replace("batch_size = 3", f"batch_size = {first}")), store,
          executor="serial", progress=False)
    task_files = sorted((store / "tasks").glob("r*.npz"))
    for p in task_files[1::3]:                       # lose a third of the tasks
        p.unlink()
    kept = {p.name: p.read_bytes() for p in (store / "tasks").glob("r*.npz")}
    ds = sweep(spec_of(TINY.replace("batch_size = 3", f"batch_size = {second}")), store,
               executor="serial", progress=False, resume=True)
    assert_bit_identical(ds, tiny_ref)
    assert_bit_identical(open_sweep(store), tiny_ref)
    for name, data in kept.items():                  # finished tasks untouched
        assert (store / "tasks" / name).read_bytes() == data


@pytest.mark.slow
def test_finished_store_resumed_with_another_batch_size_is_untouched(tiny_ref, tmp_path):
    store = tmp_path / "s"
    sweep(spec_of(TINY.replace("batch_size = 3", "batch_size = 1")), store, executor="serial",
          progress=False)
    before = files(store)
    ds = sweep(spec_of(TINY.replace("batch_size = 3", "batch_size = 8")), store,
               executor="serial", progress=False, resume=True)
    assert files(store) == before
    assert_bit_identical(ds, tiny_ref)


# -- 2. an edited base config is another sweep ------------------------------------------------
@pytest.mark.slow
def test_edited_base_config_is_refused(tmp_path):
    base = tmp_path / "base.toml"
    base.write_text(preset_path("vub_jeffcott_004").read_text())
    desc = write(tmp_path, TINY.replace('base = "vub_jeffcott_004"', 'base = "base.toml"'))
    store = tmp_path / "s"
    r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial", "--json")
    assert r.returncode == 0, r.stderr
    text = base.read_text()
    assert 'rolling_resistance = 0.002' in text and 'mass = "16.53 kg"' in text
    base.write_text(text.replace('rolling_resistance = 0.002', 'rolling_resistance = 0.004')
                    .replace('mass = "16.53 kg"', 'mass = "17 kg"'))
    for p in sorted((store / "tasks").glob("r*.npz"))[:3]:
        p.unlink()
    before = files(store)
    r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial", "--resume")
    assert r.returncode == 2
    one_line(r.stderr, str(store), "base config")
    assert files(store) == before
    with pytest.raises(StoreMismatch, match="base config"):
        open_sweep(store, desc)


# -- 3. options grids: every run with its own cell's options ----------------------------------
def test_options_grid_each_run_uses_its_cells_options(tmp_path):
    d = {"sweep": {"name": "opt", "base": "vub_jeffcott_004", "set": SHORT, "batch_size": 64},
         "grid": {"options.rtol": [1e-6, 1e-9]},
         "monte_carlo": {"kind": "start_grid", "n": 4}}
    spec = spec_from_dict(d)
    plan = make_plan(spec)
    n_s = plan.n_samples
    for first, count in plan.tasks:                  # no task spans the two cells
        assert first // n_s == (first + count - 1) // n_s
    ds = sweep(spec, tmp_path / "s", executor="serial", progress=False)
    for i, rtol in enumerate([1e-6, 1e-9]):
        cfg = load_config("vub_jeffcott_004", SHORT + [f"options.rtol={rtol}"])
        for s in (0, n_s - 1):
            # checkpoints only, as the sweep stores: a stored history would cut the slip
            # jumps' windows at its samples (docs/numerics/index.md)
            sim = ab.simulate(cfg.system, cfg.spin,
                              options=dataclasses.replace(cfg.options, save_dt=-1.0),
                              initial=ab.InitialState(ball_angles=tuple(plan.start_angles[s])))
            cell = ds.isel(options__rtol=i, sample=s)
            assert int(cell["steps"]) == sim.summary()["solver"]["steps"], (rtol, s)
            assert float(cell["grade_G"][-1]) == sim.at(12.0)["grade_G_mm_s"]
    steps = ds["steps"].values
    assert (steps[1] != steps[0]).sum() >= n_s // 2   # the cells really ran differently


def test_an_options_override_is_part_of_the_store_identity(tmp_path):
    """sweep(..., options=) on a preset base: the runs use the override, and a resume with other
    options is refused in one line instead of mixing runs of both in one store."""
    d = {"sweep": {"name": "optover", "base": "vub_jeffcott_004", "set": SHORT},
         "monte_carlo": {"kind": "start_grid", "n": 2}}
    store = tmp_path / "s"
    loose = ab.SimOptions(rtol=1e-4)
    ds = sweep(spec_from_dict(d), store, executor="serial", progress=False, options=loose)
    cfg = load_config("vub_jeffcott_004", SHORT)
    a0 = tuple(make_plan(spec_from_dict(d)).start_angles[0])
    sim = ab.simulate(cfg.system, cfg.spin, options=dataclasses.replace(loose, save_dt=-1.0),
                      initial=ab.InitialState(ball_angles=a0))
    assert int(ds["steps"].isel(sample=0)) == sim.summary()["solver"]["steps"]
    first = sorted((store / "tasks").glob("r*.npz"))[0]
    first.unlink()
    before = files(store)
    with pytest.raises(StoreMismatch) as e:
        sweep(spec_from_dict(d), store, executor="serial", progress=False, resume=True,
              options=ab.SimOptions(rtol=1e-8))
    assert "\n" not in str(e.value)
    assert files(store) == before
    sweep(spec_from_dict(d), store, executor="serial", progress=False, resume=True, options=loose)


# -- 5. failed runs have no outcome ------------------------------------------------------------
def test_failed_runs_are_nan_with_status(tmp_path):
    d = {"sweep": {"name": "fail", "base": "vub_jeffcott_004", "set": SHORT},
         "grid": {"options.max_steps": [200, 20_000_000]},
         "monte_carlo": {"kind": "start_grid", "n": 2}}
    ds = sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False)
    failed = ds.isel(options__max_steps=0)
    assert (failed["status"] == 1).all()             # max_steps
    for v in ("grade_G", "residual_unbalance", "ball_angle", "max_amplitude"):
        assert np.isnan(failed[v].values).all(), v
    assert np.isfinite(failed["initial_grade_G"].values).all()
    assert ((failed["steps"] > 0) & (failed["steps"] <= 200)).all()
    ok = ds.isel(options__max_steps=1)
    assert (ok["status"] == 0).all() and np.isfinite(ok["grade_G"].values).all()
    from autobalance.sweep import summary_dict
    s = summary_dict(ds)
    assert s["failed_runs"] == failed.sizes["sample"]


# -- 4. one process per store ------------------------------------------------------------------
@pytest.mark.slow
def test_second_process_is_refused_while_first_runs(slow_ref, tmp_path):
    desc = write(tmp_path, SLOW)
    store = tmp_path / "s"
    a = subprocess.Popen(cli("sweep", str(desc), "--store", str(store), "--workers", "2"),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        wait_for_tasks(a, store, 2)
        for args in (["--resume"], []):
            r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial", *args)
            assert r.returncode == 2, r.stderr
            one_line(r.stderr, str(store), "in use by process", str(a.pid))
        out, err = a.communicate(timeout=300)
    finally:
        if a.poll() is None:
            a.kill()
    assert a.returncode == 0, err
    assert_bit_identical(open_sweep(store), slow_ref)


@pytest.mark.slow
def test_concurrent_resumes_of_a_finished_store(tiny_ref, tmp_path):
    """Two `--resume` at once on a finished store, repeated: each exits 0 or is refused in one
    line; the dataset stays bit-identical (issue: 9 of 12 trials corrupted result.zarr)."""
    desc = write(tmp_path, TINY)
    store = tmp_path / "s"
    assert run_main("sweep", str(desc), "--store", str(store), "--executor", "serial").returncode == 0
    counts = {"ok": 0, "refused": 0}
    for _ in range(4):
        procs = [subprocess.Popen(cli("sweep", str(desc), "--store", str(store), "--resume",
                                      "--executor", "serial"),
                                  stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
                 for _ in range(2)]
        for p in procs:
            out, err = p.communicate(timeout=120)
            if p.returncode == 0:
                counts["ok"] += 1
            else:
                assert p.returncode == 2, err
                one_line(err, "in use")
                counts["refused"] += 1
        assert_bit_identical(open_sweep(store), tiny_ref)
    assert counts["ok"] >= 4


@pytest.mark.slow
def test_stale_lock_after_kill9_is_no_obstacle(slow_ref, tmp_path):
    desc = write(tmp_path, SLOW)
    store = tmp_path / "s"
    a = subprocess.Popen(cli("sweep", str(desc), "--store", str(store), "--workers", "2"),
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    try:
        wait_for_tasks(a, store, 2)
        workers = psutil.Process(a.pid).children(recursive=True)
        os.kill(a.pid, signal.SIGKILL)
        a.wait(timeout=30)
    finally:
        if a.poll() is None:
            a.kill()
    assert "process" in (store / "lock").read_text()  # the dead owner's stamp is still there
    # its workers die with it (PR_SET_PDEATHSIG)
    gone, alive = psutil.wait_procs(workers, timeout=10)
    assert not alive, alive
    r = run_main("sweep", str(desc), "--store", str(store), "--resume", "--workers", "2")
    assert r.returncode == 0, r.stderr
    assert_bit_identical(open_sweep(store), slow_ref)


# -- interruption --------------------------------------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("sig", [signal.SIGINT, signal.SIGTERM])
def test_interrupt_stops_promptly_keeps_tasks_no_orphans(slow_ref, tmp_path, sig):
    """Ctrl-C (SIGINT to the whole process group, as a terminal sends it) or SIGTERM to the
    sweep: it stops with one line before the sweep is done (the work left is not finished first;
    the 60 s communicate timeout is only a hang guard), every finished task kept, no worker
    left; --resume then gives the uninterrupted result bit for bit."""
    desc = write(tmp_path, SLOW)
    store = tmp_path / "s"
    a = subprocess.Popen(cli("sweep", str(desc), "--store", str(store), "--workers", "2"),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         start_new_session=True, preexec_fn=terminal_signals)
    try:
        wait_for_tasks(a, store, 4)
        workers = psutil.Process(a.pid).children(recursive=True)
        assert len(workers) >= 2
        t0 = time.monotonic()
        if sig == signal.SIGINT:
            os.killpg(a.pid, sig)                    # the terminal's Ctrl-C
        else:
            os.kill(a.pid, sig)
        out, err = a.communicate(timeout=60)
        elapsed = time.monotonic() - t0
    finally:
        if a.poll() is None:
            os.killpg(a.pid, signal.SIGKILL)
    print(f"signal {sig.name}: exit after {elapsed:.2f} s")
    assert a.returncode == 128 + sig, err
    line = one_line(err, "--resume", "runs kept")
    assert ("interrupted" in line) if sig == signal.SIGINT else ("terminated" in line)
    assert n_task_files(store) < len(make_plan(load_spec(desc)).tasks)   # it did not run on
    gone, alive = psutil.wait_procs(workers, timeout=5)
    assert not alive, alive
    kept = n_task_files(store)
    assert 0 < kept < len(make_plan(load_spec(desc)).tasks)
    assert not (store / "result.zarr").exists()
    r = run_main("sweep", str(desc), "--store", str(store), "--resume", "--workers", "2")
    assert r.returncode == 0, r.stderr
    assert_bit_identical(open_sweep(store), slow_ref)


def test_a_stopped_pool_survives_the_exit_hooks_race_on_its_wakeup_pipe():
    """concurrent.futures' exit hook pokes every pool's wake-up pipe without a lock: it may see the
    pipe open and write after the pool's manager closed it. That state, made deterministic on a
    real pool stopped by _stop_pool (the Ctrl-C and write-error path): the poke does not raise,
    where the unpatched one does (it printed "Exception ignored ... Bad file descriptor" after
    the one-line error, in fresh-clone runs of the two tests above and below)."""
    import multiprocessing as mp
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import _ThreadWakeup

    from autobalance.sweep.execute import _stop_pool

    ex = ProcessPoolExecutor(max_workers=1, mp_context=mp.get_context("spawn"))
    ex.submit(pow, 2, 3).result(timeout=60)
    wakeup = ex._executor_manager_thread_wakeup
    _stop_pool(ex)
    assert wakeup._closed                          # the manager closed the pipe
    wakeup._closed = False                         # the hook's check passed just before that
    wakeup.wakeup()                                # the hook's write: no exception
    with pytest.raises(OSError):
        _ThreadWakeup.wakeup(wakeup)               # what the unpatched pipe does
    wakeup._closed = True


# -- write errors ----------------------------------------------------------------------------------
@pytest.mark.slow
def test_read_only_store_fails_before_computing(tmp_path):
    tmp_path.chmod(0o755)
    desc = write(tmp_path, TINY)
    desc.chmod(0o644)
    store = tmp_path / "s"
    assert run_main("sweep", str(desc), "--store", str(store), "--executor", "serial").returncode == 0
    for p in sorted((store / "tasks").glob("r*.npz"))[:2]:
        p.unlink()
    before = files(store)
    for p in [store, *store.rglob("*")]:
        p.chmod(0o555 if p.is_dir() else 0o444)
    try:
        r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial",
                     "--resume", **file_modes_bind())
    finally:
        for p in [store, *store.rglob("*")]:
            p.chmod(0o755 if p.is_dir() else 0o644)
    assert r.returncode == 2, r.stderr
    one_line(r.stderr, str(store), "cannot write", "nothing was run")
    assert files(store) == before


@pytest.mark.slow
def test_write_error_mid_sweep_stops_at_once(tmp_path):
    """The tasks directory becomes read-only while the sweep runs: the sweep stops at the next
    write with one line instead of computing every remaining task."""
    tmp_path.chmod(0o777)
    desc = write(tmp_path, SLOW)
    desc.chmod(0o644)
    store = tmp_path / "s"
    a = subprocess.Popen(cli("sweep", str(desc), "--store", str(store), "--workers", "2"),
                         stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                         **file_modes_bind())
    try:
        wait_for_tasks(a, store, 2)
        (store / "tasks").chmod(0o555)
        out, err = a.communicate(timeout=120)
    finally:
        (store / "tasks").chmod(0o755)
        if a.poll() is None:
            a.kill()
    assert a.returncode == 2, err
    one_line(err, "cannot write task file", "finished tasks are kept")
    assert n_task_files(store) < len(make_plan(load_spec(desc)).tasks) // 2


# -- corrupted task files ----------------------------------------------------------------------------
@pytest.mark.slow
def test_corrupted_task_file_named_then_recomputed(tiny_ref, tmp_path):
    desc = write(tmp_path, TINY)
    store = tmp_path / "s"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    import shutil
    shutil.rmtree(store / "result.zarr")
    victims = sorted((store / "tasks").glob("r*.npz"))[1:3]
    victims[0].write_bytes(victims[0].read_bytes()[:100])        # truncated
    victims[1].write_bytes(b"\0" * 1000)                         # garbage
    with pytest.raises(SweepError, match=victims[0].name):
        open_sweep(store, desc)
    r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial", "--resume")
    assert r.returncode == 0, r.stderr
    assert "Traceback" not in r.stderr
    warnings = [ln for ln in r.stderr.splitlines() if ln.startswith("warning:")]
    assert len(warnings) == 2 and all("moved aside" in w for w in warnings), r.stderr
    assert sorted(p.name for p in (store / "tasks").glob("*.corrupt")) == \
        sorted(v.name + ".corrupt" for v in victims)
    assert_bit_identical(open_sweep(store), tiny_ref)


# -- the Python API from a script without a __main__ guard ----------------------------------------
@pytest.mark.slow
def test_script_without_main_guard_fails_clearly_and_reruns(tmp_path):
    script = tmp_path / "run.py"
    store = tmp_path / "s"
    body = (f"import autobalance as ab\nfrom autobalance.sweep import load_spec\n"
            f"ab.sweep(load_spec({str(write(tmp_path, TINY))!r}), {str(store)!r}, "
            f"executor='local', workers=2, progress=False)\nprint('done')\n")
    script.write_text(body)
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300)
    assert r.returncode != 0
    assert "__main__" in r.stderr and "SweepAborted" in r.stderr, r.stderr
    assert "RuntimeError" not in r.stderr, r.stderr                # no child tracebacks
    # the failed attempt does not block the corrected script (no --resume needed)
    script.write_text(body.replace("ab.sweep(", "if __name__ == '__main__':\n    ab.sweep("))
    r = subprocess.run([sys.executable, str(script)], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    assert open_sweep(store).attrs["n_missing_runs"] == 0


# -- resource guards -------------------------------------------------------------------------------
@pytest.mark.slow
@pytest.mark.parametrize("mc, field", [
    ('kind = "random"\nsamples = 1000000000000', "monte_carlo.samples"),
    ('kind = "start_grid"\nn = 100000', "monte_carlo.n"),
])
def test_huge_monte_carlo_refused_at_once(tmp_path, mc, field):
    desc = write(tmp_path, f'[sweep]\nbase = "vub_jeffcott_004"\n[monte_carlo]\n{mc}\n')
    time.monotonic()
    r = run_main("sweep", str(desc), "--store", str(tmp_path / "s"), timeout=60)
    assert r.returncode == 2, r.stderr
    one_line(r.stderr, field, "limit", "AUTOBALANCE_")
    assert not (tmp_path / "s").exists()


@pytest.mark.slow
def test_memory_limit_setting_is_honoured(tmp_path):
    d = {"sweep": {"base": "vub_jeffcott_004"}, "monte_carlo": {"kind": "start_grid", "n": 50}}
    make_plan(spec_from_dict(d))                      # 1275 runs: fine by default
    env = dict(os.environ, AUTOBALANCE_MAX_MEMORY="100 KiB")
    desc = write(tmp_path, '[sweep]\nbase = "vub_jeffcott_004"\n[monte_carlo]\nkind = "start_grid"\nn = 50\n')
    r = run_main("sweep", str(desc), "--store", str(tmp_path / "s"), env=env, timeout=60)
    assert r.returncode == 2
    one_line(r.stderr, "monte_carlo.n = 50", "100 KiB")


@pytest.mark.slow
def test_unreachable_scheduler_creates_nothing(tmp_path):
    desc = write(tmp_path, TINY)
    store = tmp_path / "s"
    time.monotonic()
    r = run_main("sweep", str(desc), "--store", str(store), "--scheduler", "tcp://127.0.0.1:9",
                 timeout=120)
    assert r.returncode == 2, r.stderr
    one_line(r.stderr, "--scheduler", "127.0.0.1:9", "nothing was created")
    assert not store.exists()


@pytest.mark.slow
def test_store_that_is_a_file(tmp_path):
    desc = write(tmp_path, TINY)
    f = tmp_path / "afile"
    f.write_text("mine")
    r = run_main("sweep", str(desc), "--store", str(f))
    assert r.returncode == 2
    one_line(r.stderr, "--store", "afile", "not a directory")
    assert f.read_text() == "mine"


# -- start placement up to the race's capacity ---------------------------------------------------
def _gaps(a):
    s = np.sort(np.mod(a, 2 * np.pi))
    return np.diff(np.concatenate([s, s[:1] + 2 * np.pi]))


@pytest.mark.parametrize("n_balls", [8, 12, 17])
def test_start_grid_with_many_balls(n_balls):
    set_ = [f"balancer.n_balls={n_balls}"]
    d = {"sweep": {"base": "vub_jeffcott_004", "set": set_},
         "monte_carlo": {"kind": "start_grid", "n": 2}}
    plan = make_plan(spec_from_dict(d))
    delta = plan.cells[0].system.balancer.contact_angle
    assert plan.n_samples == n_balls + 1
    for a in plan.start_angles:
        assert _gaps(a).min() >= delta * (1 - 1e-9)


@pytest.mark.slow
def test_random_starts_with_ten_balls_every_seed():
    for seed in range(20):
        d = {"sweep": {"base": "vub_jeffcott_004", "set": ["balancer.n_balls=10"]},
             "monte_carlo": {"kind": "random", "samples": 20, "seed": seed}}
        plan = make_plan(spec_from_dict(d))
        delta = plan.cells[0].system.balancer.contact_angle
        assert min(_gaps(a).min() for a in plan.start_angles) >= delta * (1 - 1e-9)


def test_separate_at_capacity_and_beyond():
    delta = 2 * np.pi / 17
    a = separate(np.zeros(17), delta * (1 - 1e-6))
    assert _gaps(a).min() >= delta * (1 - 1e-6) * (1 - 1e-9)
    with pytest.raises(SweepError, match="do not fit"):
        separate(np.zeros(18), delta)


@pytest.mark.slow
def test_unreadable_result_is_assembled_again(tiny_ref, tmp_path):
    """A finished store whose result.zarr was damaged (e.g. by an older version without the
    lock): --resume rebuilds it from the task files, with a warning."""
    store = tmp_path / "s"
    sweep(spec_of(TINY), store, executor="serial", progress=False)
    meta = store / "result.zarr" / ".zmetadata"
    meta.write_text("{ not json")
    desc = write(tmp_path, TINY)
    r = run_main("sweep", str(desc), "--store", str(store), "--executor", "serial", "--resume")
    assert r.returncode == 0, r.stderr
    assert "assembled again" in r.stderr and "Traceback" not in r.stderr
    assert_bit_identical(open_sweep(store), tiny_ref)


@pytest.mark.parametrize("where", ["grid", "set"])
def test_start_angles_given_beside_a_monte_carlo_are_refused(where):
    """The Monte-Carlo dimension sets every run's start angles: angles given in the grid or in
    sweep.set would be silently ignored, so they are refused."""
    d = {"sweep": {"base": "vub_jeffcott_004"}, "monte_carlo": {"kind": "start_grid", "n": 2}}
    if where == "grid":
        d["grid"] = {"initial.ball_angles": [0.1, 0.2]}
    else:
        d["sweep"]["set"] = ["initial.ball_angles=[0.1, 2.0]"]
    with pytest.raises(SweepError, match="initial.ball_angles is set by monte_carlo"):
        make_plan(spec_from_dict(d))
