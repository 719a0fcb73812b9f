"""Sweeps on a real Dask cluster (distributed.LocalCluster, 2 worker processes on loopback):
bit-identical to the serial executor, robust to a worker killed mid-sweep, selected by
DASK_SCHEDULER_ADDRESS."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

import pytest
from distributed import Client, LocalCluster

from autobalance.sweep import make_plan, open_sweep, sweep

from conftest import LONG_SWEEP as LONGER  # noqa: E402
from conftest import SLOW_SWEEP as SLOW  # noqa: E402
from conftest import TINY_SWEEP as TINY  # noqa: E402
from conftest import assert_bit_identical, spec_of  # noqa: E402

# Every test here starts a real Dask cluster (LocalCluster or `dask scheduler` / `dask worker`).
pytestmark = pytest.mark.dask


def run_task_counts(cluster):
    """How often the scheduler saw run_task finish (memory) and lose its worker (suspicious)."""
    pre = cluster.scheduler.task_prefixes.get("run_task")
    if pre is None:
        return 0, 0
    return pre.state_counts["memory"], pre.suspicious


@pytest.fixture(scope="module")
def cluster():
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as c:
        with Client(c) as client:
            client.wait_for_workers(2, timeout=120)
        yield c


@pytest.fixture(scope="module")
def serial_tiny(tmp_path_factory):
    return sweep(spec_of(TINY), tmp_path_factory.mktemp("serial") / "s", executor="serial",
                 progress=False)


def test_dask_equals_serial(cluster, serial_tiny, tmp_path):
    m0, _ = run_task_counts(cluster)
    ds = sweep(spec_of(TINY), tmp_path / "dask", executor="dask",
               scheduler=cluster.scheduler_address, progress=False)
    m1, _ = run_task_counts(cluster)
    assert m1 - m0 == len(make_plan(spec_of(TINY)).tasks) == 7   # really ran on the cluster
    assert ds.attrs["n_missing_runs"] == 0
    assert ds.identical(serial_tiny)
    assert_bit_identical(ds, serial_tiny)
    assert_bit_identical(open_sweep(tmp_path / "dask"), serial_tiny)


def test_dask_scheduler_address_env_api(cluster, serial_tiny, tmp_path, monkeypatch):
    monkeypatch.setenv("DASK_SCHEDULER_ADDRESS", cluster.scheduler_address)
    m0, _ = run_task_counts(cluster)
    ds = sweep(spec_of(TINY), tmp_path / "env", progress=False)     # no executor, no scheduler
    m1, _ = run_task_counts(cluster)
    assert m1 - m0 == 7
    assert_bit_identical(ds, serial_tiny)


def test_dask_scheduler_address_env_cli(cluster, serial_tiny, tmp_path):
    desc = tmp_path / "tiny.toml"
    desc.write_text(TINY)
    env = dict(os.environ, DASK_SCHEDULER_ADDRESS=cluster.scheduler_address)
    m0, _ = run_task_counts(cluster)
    r = subprocess.run([sys.executable, "-m", "autobalance.cli", "sweep", str(desc),
                        "--store", str(tmp_path / "cli"), "--json"],
                       capture_output=True, text=True, timeout=300, env=env)
    assert r.returncode == 0, r.stderr
    m1, _ = run_task_counts(cluster)
    assert m1 - m0 == 7
    assert_bit_identical(open_sweep(tmp_path / "cli"), serial_tiny)


def test_worker_killed_mid_sweep(cluster, tmp_path):
    """SIGKILL one worker process while it holds tasks: the scheduler reschedules them (the
    nanny restarts the worker) and the sweep completes with the serial result."""
    spec = spec_of(LONGER)
    n_tasks = len(make_plan(spec).tasks)
    store = tmp_path / "dask"
    box: dict = {}

    def target():
        try:
            box["ds"] = sweep(spec, store, executor="dask", scheduler=cluster.scheduler_address,
                              progress=False)
        except BaseException as e:   # noqa: BLE001 - reported by the test thread
            box["error"] = e

    _, s0 = run_task_counts(cluster)
    th = threading.Thread(target=target, daemon=True)
    with Client(cluster.scheduler_address, set_as_default=False) as client:
        th.start()
        tasks = store / "tasks"
        deadline = time.monotonic() + 120
        victim = None
        while victim is None:
            assert th.is_alive(), box
            assert time.monotonic() < deadline, "the sweep did not start on the cluster"
            done = len(list(tasks.glob("*.npz"))) if tasks.exists() else 0
            if done >= 2:
                busy = [w for w, keys in client.processing().items()
                        if any(str(k).startswith("run_task") for k in keys)]
                if busy:
                    victim = busy[0]
            time.sleep(0.005)
        pid = client.run(os.getpid, workers=[victim])[victim]
        os.kill(pid, signal.SIGKILL)
        done_at_kill = len(list(tasks.glob("*.npz")))
        th.join(timeout=240)
        assert not th.is_alive(), "the sweep hangs after a worker was killed"
    assert "error" not in box, repr(box.get("error"))
    assert done_at_kill < n_tasks                      # the kill happened mid-sweep
    _, s1 = run_task_counts(cluster)
    assert s1 > s0                                     # a task was lost with the worker ...
    ds = box["ds"]                                     # ... and rerun elsewhere
    assert ds.attrs["n_missing_runs"] == 0
    assert len(list(tasks.glob("*.npz"))) == n_tasks
    assert not list(store.rglob("*.tmp"))
    ref = sweep(spec, tmp_path / "serial", executor="serial", progress=False)
    assert_bit_identical(ds, ref)
    assert_bit_identical(open_sweep(store), ref)


def test_reproduce_target_on_the_cluster_equals_local(cluster, tmp_path, monkeypatch):
    """`autobalance reproduce 004-fig5-6-table2 --scheduler ADDR`: the Monte Carlo's tasks run on
    the cluster and the report rows equal the local-process run's."""
    import json

    from typer.testing import CliRunner

    from autobalance.cli import app

    monkeypatch.delenv("DASK_SCHEDULER_ADDRESS", raising=False)
    runner = CliRunner()
    m0, _ = run_task_counts(cluster)
    r = runner.invoke(app, ["reproduce", "004-fig5-6-table2", "--json", "--out-dir", str(tmp_path / "d"),
                            "--scheduler", cluster.scheduler_address])
    assert r.exit_code == 0, r.output
    m1, _ = run_task_counts(cluster)
    assert m1 > m0                                              # really ran on the cluster
    assert "DASK_SCHEDULER_ADDRESS" not in os.environ          # restored
    r2 = runner.invoke(app, ["reproduce", "004-fig5-6-table2", "--json", "--out-dir", str(tmp_path / "l")])
    assert r2.exit_code == 0, r2.output
    rows = [json.loads(x.stdout)["targets"][0]["rows"] for x in (r, r2)]
    assert rows[0] == rows[1] and rows[0][0]["computed"] == 78


# -- a real `dask scheduler` / `dask worker` pair in their own processes ------------------------
def _free_port() -> int:
    import socket

    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


class RealCluster:
    """`dask scheduler` and `dask worker` started as the command-line programs, on loopback."""

    def __init__(self, tmp_path, n_workers=1):
        self.port = _free_port()
        self.address = f"tcp://127.0.0.1:{self.port}"
        dask = os.path.join(os.path.dirname(sys.executable), "dask")
        self.log = open(tmp_path / f"cluster-{self.port}.log", "w")
        self.scheduler = subprocess.Popen(
            [dask, "scheduler", "--host", "127.0.0.1", "--port", str(self.port),
             "--no-dashboard"], stdout=self.log, stderr=self.log)
        self.workers = [subprocess.Popen(
            [dask, "worker", self.address, "--nthreads", "1", "--no-dashboard",
             "--name", f"w{i}"], stdout=self.log, stderr=self.log) for i in range(n_workers)]
        with Client(self.address, timeout="60s") as c:
            c.wait_for_workers(n_workers, timeout=120)

    def stop(self):
        for p in self.workers + [self.scheduler]:
            if p.poll() is None:
                p.kill()
            p.wait()
        self.log.close()


def _wait_for_tasks(proc, store, n, timeout=120.0):
    deadline = time.monotonic() + timeout
    while len(list((store / "tasks").glob("r*.npz"))) < n if (store / "tasks").exists() else True:
        assert proc.poll() is None, proc.communicate()
        assert time.monotonic() < deadline, "no task finished in time"
        time.sleep(0.01)


def _cli_sweep_running(cl, tmp_path):
    """`autobalance sweep SLOW --scheduler` on the cluster, returned once 2 tasks are stored."""
    desc = tmp_path / "slow.toml"
    desc.write_text(SLOW)
    store = tmp_path / "s"
    proc = subprocess.Popen(_cli("sweep", str(desc), "--store", str(store), "--scheduler",
                                 cl.address), stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                            text=True)
    _wait_for_tasks(proc, store, 2)
    return desc, store, proc


@pytest.fixture(scope="module")
def serial_slow(tmp_path_factory):
    return sweep(spec_of(SLOW), tmp_path_factory.mktemp("serial") / "slow", executor="serial",
                 progress=False)


def _cli(*args):
    return [sys.executable, "-m", "autobalance.cli", *args]


def _one_error_line(stderr):
    lines = [ln for ln in stderr.strip().splitlines() if ln.startswith("error:")]
    assert len(lines) == 1, stderr
    assert "Traceback" not in stderr, stderr
    return lines[0]


def test_real_dask_worker_killed_mid_sweep_bit_identical(tmp_path, serial_slow):
    """kill -9 of the `dask worker` process (its nanny restarts it) while the CLI sweep runs on
    the cluster: the sweep completes, bit-identical to the serial run."""
    import psutil

    cl = RealCluster(tmp_path)
    try:
        desc, store, proc = _cli_sweep_running(cl, tmp_path)
        kids = psutil.Process(cl.workers[0].pid).children(recursive=True)
        for k in kids:                                 # the worker process under the nanny
            k.kill()
        out, err = proc.communicate(timeout=300)
    finally:
        cl.stop()
    assert kids
    assert proc.returncode == 0, err
    assert_bit_identical(open_sweep(store), serial_slow)


def test_real_dask_scheduler_lost_one_line_then_resume(tmp_path, serial_slow):
    """kill -9 of the `dask scheduler` mid-sweep: one line saying the store is intact and how to
    resume (exit 1), no traceback; --resume on a new cluster gives the serial result bit for
    bit."""
    cl = RealCluster(tmp_path)
    try:
        desc, store, proc = _cli_sweep_running(cl, tmp_path)
        cl.scheduler.kill()
        t0 = time.monotonic()
        out, err = proc.communicate(timeout=180)
        waited = time.monotonic() - t0
    finally:
        cl.stop()
    print(f"lost scheduler noticed after {waited:.1f} s")
    assert proc.returncode == 1, err
    line = _one_error_line(err)
    assert "lost the Dask scheduler" in line and "--resume" in line and "intact" in line, line
    n_plan = len(make_plan(spec_of(SLOW)).tasks)
    kept = len(list((store / "tasks").glob("r*.npz")))
    assert 0 < kept < n_plan
    cl2 = RealCluster(tmp_path)
    try:
        r = subprocess.run(_cli("sweep", str(desc), "--store", str(store), "--resume",
                                "--scheduler", cl2.address), capture_output=True, text=True,
                           timeout=300)
    finally:
        cl2.stop()
    assert r.returncode == 0, r.stderr
    assert_bit_identical(open_sweep(store), serial_slow)


def test_dask_branch_tasks_equal_serial_unbranched(cluster, tmp_path):
    """A plateau sweep's branch tasks (one result per grid cell) on the cluster store what the
    serial executor stores without branching."""
    from test_branch import PLATEAU_SWEEP

    spec = spec_of(PLATEAU_SWEEP)
    m0, _ = run_task_counts(cluster)
    ds = sweep(spec, tmp_path / "dask", executor="dask", scheduler=cluster.scheduler_address,
               progress=False)
    m1, _ = run_task_counts(cluster)
    assert m1 - m0 == len(make_plan(spec).tasks) == 8
    ref = sweep(spec, tmp_path / "serial", executor="serial", progress=False, branch=False)
    assert_bit_identical(ds, ref)


def test_a_task_on_a_two_thread_worker_runs_on_one_numba_thread():
    """numba's thread count is per thread: the worker set-up reaches one of a worker's task
    threads, so every task sets its own (sweep/task.one_thread_on_dask), or the batches of
    two task threads would each take both cores (core/batch.py)."""
    import numba

    from autobalance.sweep.task import one_thread_on_dask

    def count_in_task():
        one_thread_on_dask()
        return numba.get_num_threads()

    if numba.config.NUMBA_NUM_THREADS < 2:
        pytest.skip("one core: nothing to oversubscribe")

    with LocalCluster(n_workers=1, threads_per_worker=2, processes=True, host="127.0.0.1",
                      dashboard_address=":0") as c, Client(c) as client:
        client.wait_for_workers(1, timeout=120)
        untouched = client.submit(numba.get_num_threads, pure=False).result()
        assert untouched == numba.config.NUMBA_NUM_THREADS
        assert client.submit(count_in_task, pure=False).result() == 1
    k = numba.get_num_threads()
    one_thread_on_dask()                       # outside a worker: the caller's count stays
    assert numba.get_num_threads() == k
