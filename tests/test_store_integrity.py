"""Store integrity and inputs refused before they exhaust the machine.

Store: every task file carries its store's identity and a content digest, result.zarr a digest
recorded in sweep.json; a foreign or edited task file is moved aside and recomputed on
--resume (refused in one line elsewhere), a tampered result is assembled again on --resume
(refused by open_sweep), a sweep file moved with its base config resumes, an older store
format is refused.

Inputs: grids and Monte-Carlo sizes refused before anything is allocated; config files,
sweep files and --set values that are not small UTF-8 TOML (devices, FIFOs, directories, big
files, deep nesting, latin-1, binary) refused in one line; --resume of a missing store,
conflicting --executor/--workers and bad Dask schedulers refused at once.

Real files, real processes, a real Dask LocalCluster on 127.0.0.1.
"""
from __future__ import annotations

import json
import os
import shutil
import signal
import socket
import subprocess
import sys
import threading
import time
from pathlib import Path

import numpy as np
import pytest
from typer.testing import CliRunner

from autobalance.cli import app
from autobalance.config import ConfigError, load_config, preset_path
from autobalance.config.overrides import parse_override
from autobalance.limits import ResourceError
from autobalance.sweep import (StoreMismatch, SweepError, load_spec, open_sweep, spec_from_dict,
                               sweep)

from conftest import TINY_SWEEP as TINY  # noqa: E402
from conftest import assert_bit_identical  # noqa: E402

runner = CliRunner()


def cli(*args):
    return [sys.executable, "-m", "autobalance.cli", *map(str, args)]


def run_main(*args, timeout=120, **kw):
    """The real entry point in a subprocess, with a hang guard."""
    t0 = time.monotonic()
    r = subprocess.run(cli(*args), capture_output=True, text=True, timeout=timeout, **kw)
    r.elapsed = time.monotonic() - t0
    return r


def one_line(stderr: str, *needles: str) -> str:
    """The single ``error:`` line of stderr (progress and estimate lines aside)."""
    lines = [ln for ln in stderr.strip().splitlines()
             if not ln.startswith(("[", "tiny:", "integrity:"))]
    assert len(lines) == 1, stderr
    assert lines[0].startswith("error:"), stderr
    for n in needles:
        assert n in lines[0], stderr
    assert "Traceback" not in stderr and "Exception ignored" not in stderr, stderr
    return lines[0]


def warnings_of(stderr: str) -> list:
    return [ln for ln in stderr.splitlines() if ln.startswith("warning:")]


def write_pair(root: Path, mass: str = "16.53 kg") -> Path:
    """root/sweep.toml (the TINY sweep) on the base config root/cfg/base.toml (the 004 preset
    with the rotor mass ``mass``)."""
    (root / "cfg").mkdir(parents=True, exist_ok=True)
    text = preset_path("vub_jeffcott_004").read_text()
    assert 'mass = "16.53 kg"' in text
    (root / "cfg" / "base.toml").write_text(text.replace('mass = "16.53 kg"', f'mass = "{mass}"'))
    desc = root / "sweep.toml"
    desc.write_text(TINY.replace('base = "vub_jeffcott_004"', 'base = "cfg/base.toml"'))
    return desc


def files(store: Path) -> dict:
    return {str(p.relative_to(store)): p.read_bytes() for p in sorted(store.rglob("*"))
            if p.is_file() and p.name != "lock"}


@pytest.fixture(scope="module")
def clean(tmp_path_factory):
    """The TINY sweep on a file base, run once without interruption (the reference)."""
    root = tmp_path_factory.mktemp("clean")
    desc = write_pair(root)
    return sweep(load_spec(desc), root / "store", executor="serial", progress=False)


# -- task files: foreign, edited --------------------------------------------------------------
@pytest.mark.slow
def test_foreign_task_file_is_moved_aside_and_recomputed(clean, tmp_path):
    """A task file copied from a store of another base config (same run range, so the same
    name and shapes) is refused by open_sweep and recomputed on --resume; the result is the
    clean run's bit for bit."""
    desc = write_pair(tmp_path / "a")
    store = tmp_path / "a" / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    other = write_pair(tmp_path / "b", mass="17 kg")
    sweep(load_spec(other), tmp_path / "b" / "store", executor="serial", progress=False)
    name = "r000000003-000000006.npz"
    ours, theirs = store / "tasks" / name, tmp_path / "b" / "store" / "tasks" / name
    with np.load(ours) as a, np.load(theirs) as b:
        assert a["grade_G"].shape == b["grade_G"].shape
        assert np.abs(a["grade_G"] - b["grade_G"]).max() > 0.1    # really another machine
    shutil.copyfile(theirs, ours)
    with pytest.raises(SweepError, match=r"r000000003-000000006\.npz.*another store") as e:
        open_sweep(store, desc)
    assert "\n" not in str(e.value)
    r = run_main("sweep", desc, "--store", store, "--executor", "serial", "--resume")
    assert r.returncode == 0, r.stderr
    (w,) = warnings_of(r.stderr)
    assert name in w and "another store" in w and "moved aside" in w, w
    assert (store / "tasks" / (name + ".corrupt")).read_bytes() == theirs.read_bytes()
    assert_bit_identical(open_sweep(store), clean)
    assert_bit_identical(open_sweep(store, desc), clean)


def test_edited_task_file_is_detected_and_recomputed(clean, tmp_path, capsys):
    """A task file whose grades were changed and saved again with every other field as it was
    (a valid file of the right shapes) no longer matches its content digest."""
    desc = write_pair(tmp_path)
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    victim = store / "tasks" / "r000000006-000000009.npz"
    with np.load(victim) as z:
        arrays = {k: z[k] for k in z.files}
    arrays["grade_G"] = arrays["grade_G"] * 0.5          # "better" grades
    with open(victim, "wb") as f:
        np.savez(f, **arrays)
    with pytest.raises(SweepError, match="content digest"):
        open_sweep(store, desc)
    capsys.readouterr()
    ds = sweep(load_spec(desc), store, executor="serial", progress=False, resume=True)
    (w,) = warnings_of(capsys.readouterr().err)
    assert victim.name in w and "content digest" in w and "moved aside" in w, w
    assert_bit_identical(ds, clean)
    assert_bit_identical(open_sweep(store), clean)


def test_task_files_swapped_between_run_ranges_are_detected(clean, tmp_path, capsys):
    """Two task files of the same length renamed to each other's runs: the digest binds a
    file's contents to the run range of its name."""
    desc = write_pair(tmp_path)
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    a, b = store / "tasks" / "r000000000-000000003.npz", store / "tasks" / "r000000003-000000006.npz"
    tmp = a.with_name("swap")
    a.rename(tmp)
    b.rename(a)
    tmp.rename(b)
    with pytest.raises(SweepError, match="renamed"):
        open_sweep(store, desc)
    ds = sweep(load_spec(desc), store, executor="serial", progress=False, resume=True)
    assert len(warnings_of(capsys.readouterr().err)) == 2
    assert_bit_identical(ds, clean)


def test_task_file_without_digests_is_corrupt(clean, tmp_path, capsys):
    """A task file of the earlier layout (no identity, no digest) copied into a store."""
    desc = write_pair(tmp_path)
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    victim = store / "tasks" / "r000000000-000000003.npz"
    with np.load(victim) as z:
        arrays = {k: z[k] for k in z.files if k != "integrity"}
    with open(victim, "wb") as f:
        np.savez(f, **arrays)
    with pytest.raises(SweepError, match="no content digest"):
        open_sweep(store, desc)
    ds = sweep(load_spec(desc), store, executor="serial", progress=False, resume=True)
    assert len(warnings_of(capsys.readouterr().err)) == 1
    assert_bit_identical(ds, clean)


# -- result.zarr -------------------------------------------------------------------------------
@pytest.mark.parametrize("how", ["chunk-byte", "attribute"])
def test_tampered_result_is_refused_then_assembled_again_on_resume(clean, tmp_path, capsys, how):
    desc = write_pair(tmp_path)
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    res = store / "result.zarr"
    if how == "chunk-byte":
        chunk = next(p for p in sorted((res / "grade_G").iterdir()) if not p.name.startswith("."))
        b = bytearray(chunk.read_bytes())
        b[-1] ^= 1
        chunk.write_bytes(bytes(b))
    else:                                            # valid JSON, another value
        za = res / ".zattrs"
        attrs = json.loads(za.read_text())
        attrs["n_missing_runs"] = 3
        za.write_text(json.dumps(attrs))
        zm = res / ".zmetadata"
        meta = json.loads(zm.read_text())
        meta["metadata"][".zattrs"]["n_missing_runs"] = 3
        zm.write_text(json.dumps(meta))
    tasks = files(store / "tasks")
    with pytest.raises(SweepError, match="does not match the digest") as e:
        open_sweep(store)
    assert "\n" not in str(e.value) and "--resume" in str(e.value)
    capsys.readouterr()
    ds = sweep(load_spec(desc), store, executor="serial", progress=False, resume=True)
    (w,) = warnings_of(capsys.readouterr().err)
    assert "result.zarr" in w and "assembled again" in w, w
    assert_bit_identical(ds, clean)
    assert_bit_identical(open_sweep(store), clean)
    assert files(store / "tasks") == tasks               # nothing recomputed


def test_result_digest_is_recorded_in_sweep_json(tmp_path):
    from autobalance.sweep.store import STORE_FORMAT, result_digest

    desc = write_pair(tmp_path)
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    meta = json.loads((store / "sweep.json").read_text())
    assert meta["store_format"] == STORE_FORMAT
    assert meta["result_digest"] == result_digest(store / "result.zarr")
    assert len(meta["result_digest"]) == 64


@pytest.mark.parametrize("drop", [("store_format", "result_digest"),
                                  ("store_format", "result_digest", "identity")],
                         ids=["task-files-by-run", "task-files-by-index"])
def test_store_of_an_earlier_format_is_refused_in_one_line(tmp_path, drop):
    """The sweep.json of the two earlier layouts: without the store format and the result's
    digest (task files without digests), and also without the identity (task files by
    index)."""
    desc = write_pair(tmp_path)
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    meta = json.loads((store / "sweep.json").read_text())
    for key in drop:
        del meta[key]
    (store / "sweep.json").write_text(json.dumps(meta))
    before = files(store)
    for call in (lambda: sweep(load_spec(desc), store, executor="serial", progress=False,
                               resume=True),
                 lambda: open_sweep(store), lambda: open_sweep(store, desc)):
        with pytest.raises(StoreMismatch, match="earlier store format") as e:
            call()
        assert "\n" not in str(e.value)
    assert files(store) == before


# -- moved sweep file and base config ---------------------------------------------------------
def test_sweep_file_moved_with_its_base_resumes(clean, tmp_path):
    """The base config enters the store's identity by its path relative to the sweep file
    (and by its values): the pair moved elsewhere resumes; its base edited does not."""
    desc = write_pair(tmp_path / "here")
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    (store / "tasks" / "r000000003-000000006.npz").unlink()
    kept = files(store / "tasks")
    shutil.move(tmp_path / "here", tmp_path / "there" / "deeper")
    moved = tmp_path / "there" / "deeper" / "sweep.toml"
    assert not desc.exists()
    ds = sweep(load_spec(moved), store, executor="serial", progress=False, resume=True)
    assert_bit_identical(ds, clean)
    for name, data in kept.items():
        assert (store / "tasks" / name).read_bytes() == data
    base = moved.parent / "cfg" / "base.toml"
    base.write_text(base.read_text().replace('mass = "16.53 kg"', 'mass = "17 kg"'))
    with pytest.raises(StoreMismatch, match="base config"):
        sweep(load_spec(moved), store, executor="serial", progress=False, resume=True)


def test_sweep_file_with_an_absolute_base_moved_alone_resumes(clean, tmp_path):
    """An absolute base path names the same file wherever the sweep file goes."""
    write_pair(tmp_path / "pair")
    base = (tmp_path / "pair" / "cfg" / "base.toml").resolve()
    desc = tmp_path / "a" / "sweep.toml"
    desc.parent.mkdir()
    desc.write_text(TINY.replace('base = "vub_jeffcott_004"', f'base = "{base}"'))
    store = tmp_path / "store"
    sweep(load_spec(desc), store, executor="serial", progress=False)
    (store / "tasks" / "r000000000-000000003.npz").unlink()
    moved = tmp_path / "b" / "c" / "sweep.toml"
    moved.parent.mkdir(parents=True)
    shutil.move(desc, moved)
    ds = sweep(load_spec(moved), store, executor="serial", progress=False, resume=True)
    assert_bit_identical(ds, clean)


# -- grid and Monte-Carlo sizes before any allocation --------------------------------------------
HUGE = '[sweep]\nbase = "vub_jeffcott_004"\n[grid]\n"rotor.unbalance" = ' \
       '{ start = "0.1 g*m", stop = "0.2 g*m", num = 1000000000 }\n'
FIELD = 'grid."rotor.unbalance".num = 1000000000'


@pytest.mark.slow
def test_grid_of_1e9_values_refused_within_a_second_without_allocating(tmp_path):
    desc = tmp_path / "huge.toml"
    desc.write_text(HUGE)
    code = ("import json, resource, time\n"
            "from autobalance.sweep import load_spec, make_plan\n"
            "from autobalance.limits import ResourceError\n"
            "r0 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
            "t0 = time.perf_counter()\n"
            "try:\n"
            f"    make_plan(load_spec({str(desc)!r}))\n"
            "    msg = 'accepted'\n"
            "except ResourceError as e:\n"
            "    msg = str(e)\n"
            "dt = time.perf_counter() - t0\n"
            "r1 = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss\n"
            "print(json.dumps({'msg': msg, 'seconds': dt, 'rss_kib': r1 - r0}))\n")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["msg"].startswith(FIELD) and "AUTOBALANCE_MAX_MEMORY" in out["msg"], out
    assert out["seconds"] < 1.0, out
    assert out["rss_kib"] < 50 * 1024, out                  # np.linspace alone: 8 GB
    r = run_main("sweep", desc, "--store", tmp_path / "s", timeout=60)
    assert r.returncode == 2
    one_line(r.stderr, FIELD, "limit")
    assert not (tmp_path / "s").exists()


def test_grid_sizes_refused_from_their_lengths():
    t0 = time.perf_counter()
    with pytest.raises(ResourceError, match=r'^grid\."rotor\.unbalance"\.num = 1000000000: '):
        spec_from_dict({"sweep": {"base": "vub_jeffcott_004"},
                        "grid": {"rotor.unbalance": {"start": 1e-4, "stop": 2e-4,
                                                     "num": 1_000_000_000}}})
    # two axes that fit alone: the product is named
    with pytest.raises(ResourceError, match=r"^grid = '1000 x 1000 = 1000000 cells'"):
        spec_from_dict({"sweep": {"base": "vub_jeffcott_004"},
                        "grid": {"rotor.unbalance": {"start": 1e-4, "stop": 2e-4, "num": 1000},
                                 "rotor.mass": {"start": 10, "stop": 20, "num": 1000}}})
    assert time.perf_counter() - t0 < 1.0


@pytest.mark.parametrize("mc, field", [
    ({"kind": "start_grid", "n": 1_000_000_000}, "monte_carlo.n = 1000000000"),
    ({"kind": "random", "samples": 10**15}, "monte_carlo.samples"),
])
def test_monte_carlo_sizes_refused_before_the_samples_are_built(mc, field):
    from autobalance.sweep import make_plan

    d = {"sweep": {"base": "vub_jeffcott_004", "set": ["balancer.n_balls=17"]},
         "monte_carlo": mc}
    t0 = time.perf_counter()
    with pytest.raises(ResourceError, match=field):
        make_plan(spec_from_dict(d))
    assert time.perf_counter() - t0 < 5.0


def test_tiny_history_step_refused_naming_it():
    from autobalance.sweep import make_plan

    d = {"sweep": {"base": "vub_jeffcott_004"}, "monte_carlo": {"kind": "start_grid", "n": 50},
         "outputs": {"history_dt": "1e-9 s"}}
    with pytest.raises(ResourceError, match=r"^outputs\.history_dt = "):
        make_plan(spec_from_dict(d))


# -- input files: one reader for configs and sweep files ---------------------------------------
def _deep(root: Path) -> Path:
    p = root / "deep.toml"
    p.write_text("a = " + "[" * 5000 + "]" * 5000 + "\n")
    return p


def _deep_inline(root: Path) -> Path:
    p = root / "deep_inline.toml"
    p.write_text("a = " + "{b = " * 5000 + "1" + "}" * 5000 + "\n")
    return p


def _big(root: Path) -> Path:
    p = root / "big.toml"
    p.write_text("# padding\n" * (2 * 2**20 // 10 + 1))
    return p


def _latin1(root: Path) -> Path:
    p = root / "latin1.toml"
    p.write_bytes('name = "café"\n'.encode("latin-1"))
    return p


def _binary(root: Path) -> Path:
    p = root / "binary.toml"
    p.write_bytes(bytes(range(256)) * 8)
    return p


def _fifo(root: Path) -> Path:
    p = root / "pipe.toml"
    os.mkfifo(p)
    return p


INPUTS = {                      # name -> (make path, words of the refusal)
    "dev-zero": (lambda root: Path("/dev/zero"), ["'/dev/zero'", "character device"]),
    "dev-urandom": (lambda root: Path("/dev/urandom"), ["'/dev/urandom'", "character device"]),
    "fifo": (_fifo, ["pipe.toml", "FIFO"]),
    "directory": (lambda root: root, ["is a directory"]),
    "2-MiB": (_big, ["big.toml", "2 MiB", "1 MiB", "AUTOBALANCE_MAX_FILE_SIZE"]),
    "5000-deep": (_deep, ["deep.toml", "nested", "AUTOBALANCE_MAX_NESTING"]),
    "5000-deep-inline": (_deep_inline, ["deep_inline.toml", "nested"]),
    "latin-1": (_latin1, ["latin1.toml", "not UTF-8", "0xe9", "offset 11", "line 1"]),
    "binary": (_binary, ["binary.toml", "NUL byte at offset 0"]),
}


@pytest.mark.slow
@pytest.mark.parametrize("command", ["simulate", "sweep", "sweep.base"])
@pytest.mark.parametrize("name", list(INPUTS))
def test_input_file_refused_in_one_line_quickly(tmp_path, name, command):
    make, words = INPUTS[name]
    d = tmp_path / "in"
    d.mkdir()
    path = make(d)
    if command == "simulate":
        args = ["simulate", path]
    elif command == "sweep":
        args = ["sweep", path, "--store", tmp_path / "s"]
    else:                                            # the sweep file's base config
        desc = tmp_path / "sweep.toml"
        desc.write_text(f'[sweep]\nbase = "{path}"\n' if name != "directory"
                        else f'[sweep]\nbase = "{path}/"\n')
        args = ["sweep", desc, "--store", tmp_path / "s"]
    r = run_main(*args, timeout=60)
    assert r.returncode == 2, (r.returncode, r.stderr)
    line = one_line(r.stderr, *words)
    assert r.stdout == ""
    assert r.elapsed < 30, r.elapsed
    assert len(line) < 400, line
    assert not (tmp_path / "s").exists()


@pytest.mark.parametrize("name", ["directory", "2-MiB", "5000-deep", "5000-deep-inline",
                                  "latin-1", "binary"])
def test_input_file_refused_by_the_python_api(tmp_path, name):
    make, words = INPUTS[name]
    path = make(tmp_path)
    with pytest.raises(ConfigError) as e:
        load_config(path)
    with pytest.raises(SweepError) as s:
        load_spec(path)
    for err in (e, s):
        assert "\n" not in str(err.value)
        for w in words:
            assert w in str(err.value)


def test_nesting_below_the_parser_limit_is_measured(tmp_path, monkeypatch):
    """40 levels parse, and are refused by the limit; the limit is a setting."""
    p = tmp_path / "d40.toml"
    p.write_text("a = " + "[" * 40 + "]" * 40 + "\n")
    with pytest.raises(SweepError, match="nested more than 32 levels"):
        load_spec(p)
    monkeypatch.setenv("AUTOBALANCE_MAX_NESTING", "100")
    with pytest.raises(SweepError, match="a: unknown section"):
        load_spec(p)                                # parsed; the description is then checked
    monkeypatch.setenv("AUTOBALANCE_MAX_FILE_SIZE", "10 B")
    with pytest.raises(SweepError, match="more than the limit of 10 B"):
        load_spec(p)


@pytest.mark.parametrize("value", ["[" * 5000 + "]" * 5000, "[" * 5000, "{a = " * 5000 + "1",
                                   "[" * 40 + "]" * 40])
def test_deep_set_value_refused(value):
    with pytest.raises(ConfigError, match=r"^--set rotor\.mass=\[|^--set rotor\.mass=\{") as e:
        parse_override(f"rotor.mass={value}")
    assert "nested" in str(e.value) and len(str(e.value)) < 300
    assert parse_override("initial.ball_angles=[0, 3.1]") == ("initial.ball_angles", [0, 3.1])


@pytest.mark.slow
def test_deep_set_value_refused_by_the_cli_and_in_a_sweep_file(tmp_path):
    deep = "[" * 5000 + "]" * 5000
    r = run_main("simulate", "vub_jeffcott_004", "--set", f"rotor.mass={deep}", timeout=60)
    assert r.returncode == 2
    one_line(r.stderr, "--set rotor.mass=", "nested")
    desc = tmp_path / "sweep.toml"
    desc.write_text(f'[sweep]\nbase = "vub_jeffcott_004"\nset = ["rotor.mass={deep}"]\n')
    r = run_main("sweep", desc, "--store", tmp_path / "s", timeout=60)
    assert r.returncode == 2
    one_line(r.stderr, "sweep.set", "nested")


# -- options -----------------------------------------------------------------------------------
def test_resume_of_a_missing_store_is_refused(tmp_path):
    desc = write_pair(tmp_path)
    store = tmp_path / "nothing-here"
    r = runner.invoke(app, ["sweep", str(desc), "--store", str(store), "--resume",
                            "--executor", "serial"])
    assert r.exit_code == 2, r.stderr
    one_line(r.stderr, "--resume", str(store), "no sweep store")
    assert not store.exists()
    with pytest.raises(SweepError, match="--resume: there is no sweep store"):
        sweep(load_spec(desc), store, executor="serial", progress=False, resume=True)
    assert not store.exists()


@pytest.mark.parametrize("args, words", [
    (["--executor", "serial", "--workers", "2"], ["--executor serial", "--workers 2",
                                                  "conflicting"]),
    (["--executor", "dask", "--scheduler", "tcp://127.0.0.1:1", "--workers", "2"],
     ["--executor dask", "--workers 2", "conflicting"]),
    (["--scheduler", "tcp://127.0.0.1:1", "--workers", "2"],
     ["--workers 2", "--scheduler 'tcp://127.0.0.1:1'", "conflicting"]),
])
def test_conflicting_executor_and_workers_are_refused(tmp_path, args, words):
    desc = write_pair(tmp_path)
    r = runner.invoke(app, ["sweep", str(desc), "--store", str(tmp_path / "s"), *args],
                      env={"DASK_SCHEDULER_ADDRESS": ""})
    assert r.exit_code == 2, r.stderr
    one_line(r.stderr, *words)
    assert not (tmp_path / "s").exists()


def test_serial_sweep_with_workers_refused_by_the_python_api(tmp_path):
    desc = write_pair(tmp_path)
    with pytest.raises(SweepError, match="conflicting"):
        sweep(load_spec(desc), tmp_path / "s", executor="serial", workers=2, progress=False)
    assert not (tmp_path / "s").exists()
    # one worker is what a serial sweep has
    sweep(load_spec(desc), tmp_path / "s", executor="serial", workers=1, progress=False)


@pytest.mark.parametrize("address", ["not a url", "tcp://127.0.0.1", "127.0.0.1:99999",
                                     "http://127.0.0.1:8786", "tcp://:8786"])
def test_malformed_scheduler_address_refused_at_once(address):
    from autobalance.sweep.scheduler import parse_address

    t0 = time.perf_counter()
    with pytest.raises(SweepError, match="not a scheduler address"):
        parse_address(address)
    assert time.perf_counter() - t0 < 0.1
    assert parse_address("tcp://127.0.0.1:8786") == ("tcp", "127.0.0.1", 8786)
    assert parse_address("[::1]:8786") == ("tcp", "::1", 8786)


@pytest.mark.slow
def test_malformed_scheduler_refused_by_the_cli_without_waiting(tmp_path):
    desc = write_pair(tmp_path)
    r = run_main("sweep", desc, "--store", tmp_path / "s", "--scheduler", "not a url",
                 timeout=60)
    assert r.returncode == 2
    one_line(r.stderr, "--scheduler 'not a url'", "not a scheduler address")
    assert r.elapsed < 15, r.elapsed                       # it waited 20 s at exit
    assert not (tmp_path / "s").exists()


def _closed_port() -> int:
    s = socket.socket()
    s.bind(("127.0.0.1", 0))
    port = s.getsockname()[1]
    s.close()
    return port


class SilentServer:
    """A TCP port on 127.0.0.1 that accepts connections and never answers (another service)."""

    def __init__(self):
        self.sock = socket.socket()
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(8)
        self.port = self.sock.getsockname()[1]
        self.conns = []
        threading.Thread(target=self._accept, daemon=True).start()

    def _accept(self):
        while True:
            try:
                c, _ = self.sock.accept()
            except OSError:
                return
            self.conns.append(c)

    def close(self):
        for c in self.conns:
            c.close()
        self.sock.close()


@pytest.mark.slow
def test_unreachable_scheduler_fails_in_one_line_within_seconds(tmp_path):
    desc = write_pair(tmp_path)
    silent = SilentServer()
    try:
        for address, why in [(f"tcp://127.0.0.1:{_closed_port()}", "Connection refused"),
                             (f"tcp://127.0.0.1:{silent.port}", "no Dask reply within 3 s")]:
            r = run_main("sweep", desc, "--store", tmp_path / "s", "--scheduler", address,
                         timeout=60)
            assert r.returncode == 2, r.stderr
            one_line(r.stderr, f"--scheduler {address!r}", "no Dask scheduler answers", why,
                     "nothing was created")
            assert r.elapsed < 20, (address, r.elapsed)
    finally:
        silent.close()
    assert not (tmp_path / "s").exists()


@pytest.mark.dask
def test_scheduler_probe_reaches_a_real_cluster_and_refuses_a_worker():
    from distributed import LocalCluster

    from autobalance.sweep.scheduler import connect

    with LocalCluster(n_workers=1, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as cluster:
        client = connect(cluster.scheduler_address)
        try:
            assert client.submit(sum, [1, 2]).result(timeout=60) == 3
            (worker,) = client.scheduler_info()["workers"]
        finally:
            client.close()
        with pytest.raises(SweepError, match="it is a Worker, not a scheduler"):
            connect(worker)


# -- a study with a temporary store --------------------------------------------------------------
@pytest.mark.slow
def test_interrupted_study_without_store_offers_no_resume(tmp_path):
    """``design --quick`` without --store runs its sweeps in a temporary directory, deleted on
    the way out: Ctrl-C must not say "continue with --resume" about it."""
    root = Path(__file__).resolve().parents[1]
    p = subprocess.Popen(cli("design", root / "examples" / "toploader.toml", "--quick"),
                         stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                         cwd=tmp_path, start_new_session=True,
                         preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    try:
        deadline = time.monotonic() + 120
        err = []
        while time.monotonic() < deadline:
            ln = p.stderr.readline()
            err.append(ln)
            if "runs to compute" in ln or not ln:
                break
        assert p.poll() is None, "".join(err)
        os.killpg(p.pid, signal.SIGINT)
        rest = p.communicate(timeout=60)[1]
    finally:
        if p.poll() is None:
            os.killpg(p.pid, signal.SIGKILL)
    assert p.returncode == 130, rest
    (line,) = [ln for ln in rest.splitlines() if ln.startswith("error:")]
    assert "nothing kept" in line and "--store DIR" in line, line
    assert "continue with --resume" not in line, line
    assert "Traceback" not in rest
