"""Fault-injection trials of the sweep store, with real processes and real signals.

Prints, for each kind of trial, how many gave a bit-identical dataset, a clean one-line refusal,
or a corrupted / wrong result, and the seconds from Ctrl-C / SIGTERM to exit:

* kill -9 of `autobalance sweep` at ~30/60/90 % of its tasks, then `--resume`;
* Ctrl-C (SIGINT to the process group) and SIGTERM mid-sweep, then `--resume`;
* two `--resume` started at once on a finished store;
* a second sweep started on a store while the first runs;
* `--resume` with another batch size after losing a third of the tasks.

Usage: ``python benchmarks/faults.py [--trials N]`` (default 4 per kind; a few minutes).
"""
from __future__ import annotations

import argparse
import os
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

# the tests' 210-run sweep (~0.05-0.1 s per task of 2): long enough to interrupt mid-way
sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "tests"))
from conftest import SLOW_SWEEP as SPEC  # noqa: E402


def cli(*args):
    return [sys.executable, "-m", "autobalance.cli", *map(str, args)]


def n_tasks(store: Path) -> int:
    d = store / "tasks"
    return len(list(d.glob("r*.npz"))) if d.is_dir() else 0


def identical(a, b) -> bool:
    if set(a.data_vars) != set(b.data_vars):
        return False
    return all(a[v].values.tobytes() == b[v].values.tobytes() for v in a.data_vars)


def load(store: Path):
    from autobalance.sweep import open_sweep

    try:
        return open_sweep(store)
    except Exception:   # noqa: BLE001 - a corrupted store is what we count
        return None


def start(desc, store, *extra, new_session=False):
    return subprocess.Popen(cli("sweep", desc, "--store", store, *extra),
                            stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                            start_new_session=new_session)


def wait_tasks(proc, store, n, timeout=120):
    t0 = time.monotonic()
    while n_tasks(store) < n:
        if proc.poll() is not None or time.monotonic() - t0 > timeout:
            return False
        time.sleep(0.005)
    return True


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--trials", type=int, default=4)
    args = ap.parse_args()
    from autobalance.sweep import load_spec, make_plan, sweep

    root = Path(tempfile.mkdtemp(prefix="ab-faults-"))
    desc = root / "faults.toml"
    desc.write_text(SPEC)
    total = len(make_plan(load_spec(desc)).tasks)
    ref = sweep(load_spec(desc), root / "ref", workers=2, progress=False)
    rows = []

    def record(kind, outcome, extra=""):
        rows.append((kind, outcome, extra))

    for t in range(args.trials):
        # kill -9 at 30/60/90 %, then resume
        for frac in (0.3, 0.6, 0.9):
            store = root / f"k{t}-{frac}"
            p = start(desc, store, "--workers", "2")
            wait_tasks(p, store, int(frac * total))
            p.kill()
            p.wait()
            r = subprocess.run(cli("sweep", desc, "--store", store, "--resume", "--workers", 2),
                               capture_output=True, text=True)
            ds = load(store)
            ok = r.returncode == 0 and ds is not None and identical(ds, ref)
            record(f"kill -9 at {int(frac * 100)} % + resume", "identical" if ok else "corrupted")
        # Ctrl-C and SIGTERM
        for sig in (signal.SIGINT, signal.SIGTERM):
            store = root / f"s{t}-{sig.name}"
            p = start(desc, store, "--workers", "2", new_session=True)
            wait_tasks(p, store, 4)
            t0 = time.monotonic()
            (os.killpg if sig == signal.SIGINT else os.kill)(p.pid, sig)
            _, err = p.communicate()
            dt = time.monotonic() - t0
            one = (sum(ln.startswith("error:") for ln in err.splitlines()) == 1
                   and "Traceback" not in err)   # besides the estimate and progress lines
            r = subprocess.run(cli("sweep", desc, "--store", store, "--resume", "--workers", 2),
                               capture_output=True, text=True)
            ds = load(store)
            ok = one and p.returncode == 128 + sig and r.returncode == 0 and ds is not None \
                and identical(ds, ref)
            record(f"{sig.name} + resume", "identical" if ok else "corrupted", dt)
        # two resumes at once on a finished store
        store = root / "ref"
        ps = [start(desc, store, "--resume", "--executor", "serial") for _ in range(2)]
        outs = [(p.wait(), p.stderr.read()) for p in ps]
        ds = load(store)
        for rc, err in outs:
            if rc == 0:
                record("two --resume on a finished store", "identical"
                       if ds is not None and identical(ds, ref) else "corrupted")
            else:
                record("two --resume on a finished store",
                       "refused" if rc == 2 and "in use" in err else "corrupted")
        # a second process while the first runs
        store = root / f"c{t}"
        a = start(desc, store, "--workers", "2")
        wait_tasks(a, store, 2)
        b = subprocess.run(cli("sweep", desc, "--store", store, "--resume"), capture_output=True,
                           text=True)
        a.wait()
        ds = load(store)
        record("second process while the first runs",
               "refused" if b.returncode == 2 and "in use" in b.stderr else "corrupted")
        record("first process after the refusal", "identical"
               if a.returncode == 0 and ds is not None and identical(ds, ref) else "corrupted")
        # resume with another batch size
        store = root / f"b{t}"
        sweep(load_spec(desc), store, workers=2, progress=False)
        files = sorted((store / "tasks").glob("r*.npz"))
        for f in files[t % 3::3]:
            f.unlink()
        bs = [1, 8, 64, 5][t % 4]
        desc2 = root / f"faults-bs{bs}.toml"
        desc2.write_text(SPEC.replace("batch_size = 2", f"batch_size = {bs}"))
        r = subprocess.run(cli("sweep", desc2, "--store", store, "--resume", "--workers", 2),
                           capture_output=True, text=True)
        ds = load(store)
        record(f"resume with batch_size {bs}", "identical" if r.returncode == 0 and ds is not None
               and identical(ds, ref) else "corrupted")

    kinds = list(dict.fromkeys(k for k, _, _ in rows))
    print(f"{'trial kind':<42} {'trials':>6} {'identical':>9} {'refused':>8} {'corrupted':>9}"
          f"  signal-to-exit [s]")
    for k in kinds:
        sel = [(o, x) for kk, o, x in rows if kk == k]
        dts = [x for o, x in sel if isinstance(x, float)]
        dt = f"  {min(dts):.2f}-{max(dts):.2f} (median {np.median(dts):.2f})" if dts else ""
        print(f"{k:<42} {len(sel):>6} {sum(o == 'identical' for o, _ in sel):>9} "
              f"{sum(o == 'refused' for o, _ in sel):>8} {sum(o == 'corrupted' for o, _ in sel):>9}"
              f"{dt}")


if __name__ == "__main__":
    main()
