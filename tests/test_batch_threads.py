"""Batches on Python threads (core/batch.py): the same bytes on one thread or two, an error in
one run stops the batch, and Ctrl-C interrupts a long batch at once (it does not wait for the
whole numba prange loop)."""
from __future__ import annotations

import os
import signal
import subprocess
import sys
import threading
import time

import numba
import pytest

import autobalance as ab
from autobalance.core.batch import each_run
from autobalance.simulate import simulate_batch

from conftest import vub_004


def test_one_thread_and_two_give_the_same_bytes():
    prof = ab.SpeedProfile.tsr(duration=12.0, runup_fraction=0.25, down_time=2.0,
                               plateau_time=3.0, up_time=2.0)
    systems = [vub_004(mu=mu) for mu in (0.001, 0.002, 0.004, 0.002, 0.003, 0.0)]
    inits = [ab.InitialState(ball_angles=(a, a + 1.5 + a / 3)) for a in range(6)]
    opts = ab.SimOptions(save_dt=-1)
    k = numba.get_num_threads()
    try:
        numba.set_num_threads(1)
        one = simulate_batch(systems, prof, inits, options=opts)
    finally:
        numba.set_num_threads(k)
    two = simulate_batch(systems, prof, inits, options=opts)
    assert k >= 2 or os.cpu_count() == 1
    assert one.states.tobytes() == two.states.tobytes()
    assert one.stats.tobytes() == two.stats.tobytes()


def test_an_error_in_one_run_stops_the_batch_and_propagates():
    started = []
    lock = threading.Lock()

    def run(r: int) -> None:
        with lock:
            started.append(r)
        time.sleep(0.01)
        if r == 3:
            raise ValueError("run 3 failed")

    with pytest.raises(ValueError, match="run 3 failed"):
        each_run(200, run)
    assert 4 <= len(started) < 200        # the runs after the failure were not started


_LONG_BATCH = """
import sys, numpy as np
import autobalance as ab
from autobalance.config import load_config
from autobalance.simulate import simulate_batch
cfg = load_config("vub_jeffcott_004")
inits = [ab.InitialState(ball_angles=(a, a + 2.0)) for a in np.linspace(0, 6, 6000)]
simulate_batch([cfg.system] * 2, cfg.spin, inits[:2], options=cfg.options)   # compiled / loaded
print("ready", flush=True)
try:
    simulate_batch([cfg.system] * 6000, cfg.spin, inits, options=cfg.options)
    print("finished", flush=True)
except KeyboardInterrupt:
    print("interrupted", flush=True)
    sys.exit(130)
"""


@pytest.mark.slow
def test_ctrl_c_interrupts_a_long_batch_at_once():
    """6000 runs of 004's 90 s profile take ~18 s on two threads; Ctrl-C 0.5 s in must stop
    the batch within a few seconds (the runs in flight finish, ~6 ms each)."""
    p = subprocess.Popen([sys.executable, "-c", _LONG_BATCH], stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    try:
        assert p.stdout.readline().strip() == "ready", p.stderr.read()
        time.sleep(0.5)
        p.send_signal(signal.SIGINT)
        t = time.perf_counter()
        out, err = p.communicate(timeout=60)
        waited = time.perf_counter() - t
    finally:
        p.kill()
    assert out.strip() == "interrupted", err
    assert p.returncode == 130
    assert waited < 5.0
