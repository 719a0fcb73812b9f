"""Outputs written whole or not at all (:mod:`autobalance.atomic`, docs/outputs.md).

* :mod:`autobalance.atomic` on real files: a write replaces the file; an exception or Ctrl-C in
  the writer keeps the previous file and leaves no temporary file; a symbolic link's target is
  replaced and the link kept; real EFBIG (a lowered file size limit) and ENOSPC (``/dev/full``)
  failures keep the previous file; a device or FIFO is never replaced.
* The command line under a real file size limit (RLIMIT_FSIZE set in the child, SIGXFSZ ignored,
  which survives exec, so the write fails with EFBIG / "NetCDF: HDF error"): one line, exit 2,
  the previous file byte-identical.
* kill -9 of real processes while they write each kind of output (``simulate --out`` NetCDF,
  ``simulate --plot`` PNG, a study's ``--out`` and ``--plot``, the report's JSON, HTML and
  markdown through :func:`autobalance.report.runner.write_report`): each trial waits until the
  temporary file appears, waits a delay and kills. Every output then holds its previous bytes
  (or is absent) or is a complete new file, never a part; a trial whose temporary file is left
  behind was killed during the write, and each kind must have such trials.
* A run that fails (``--set options.max_steps=500``: exit 1) leaves the previous ``--out``.
* Outputs that are the input config file (also through a link), the other output, a device or a
  FIFO: refused before any work, one line, exit 2, nothing written.

``pytest -s`` prints the number of kill -9 trials.
"""
from __future__ import annotations

import errno
import json
import os
import pickle
import resource
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from typer.testing import CliRunner

from autobalance.atomic import (OutputError, atomic_output, final_target, same_file,
                                save_figure, write_atomic)
from autobalance.cli import app

EXE = Path(sys.executable).with_name("autobalance")
PNG_END = b"IEND\xaeB`\x82"
#: Variables every simulation NetCDF holds (Simulation.to_xarray).
SIM_VARS = {"x", "y", "u", "v", "amplitude", "alpha"}
#: kill -9 trials per kind of output, for the count printed at the end.
TRIALS: dict[str, dict[str, int]] = {}


def temps(final: Path) -> list[Path]:
    """The temporary files of ``final`` in its directory (a library writer's nested one too)."""
    key = f".{final.name}."
    return [p for p in final.parent.iterdir() if key in p.name and ".tmp" in p.name]


def small_netcdf(path: Path) -> bytes:
    """Write a small valid NetCDF file (one variable ``previous``) and return its bytes."""
    import numpy as np
    import xarray as xr

    xr.Dataset({"previous": ("t", np.arange(8.0))}).to_netcdf(path, engine="netcdf4")
    return path.read_bytes()


def small_png(path: Path) -> bytes:
    """Write a small valid PNG and return its bytes."""
    from matplotlib.figure import Figure

    fig = Figure(figsize=(1, 1))
    fig.add_subplot().plot([0, 1])
    fig.savefig(path, dpi=20)
    return path.read_bytes()


def netcdf_complete(path: Path, names=SIM_VARS) -> bool:
    """Whether ``path`` opens as NetCDF, reads whole and holds the variables ``names``."""
    import xarray as xr

    try:
        with xr.open_dataset(path, engine="netcdf4") as ds:
            ds.load()
            return set(names) <= set(ds.data_vars)
    except (OSError, ValueError, RuntimeError):
        return False


def png_complete(path: Path) -> bool:
    """Whether ``path`` is a whole PNG (signature and final IEND chunk)."""
    data = path.read_bytes()
    return data.startswith(b"\x89PNG") and data.endswith(PNG_END)


def assert_whole(final: Path, previous: bytes | None, complete) -> None:
    """The file at ``final``: its previous bytes (absent if none) while a temporary file of it is
    left; else the previous bytes (never written) or a complete new file (``complete(path)``)."""
    if temps(final):
        if previous is None:
            assert not final.exists(), f"{final.name}: a file appeared while its write was killed"
        else:
            assert final.read_bytes() == previous, f"{final.name}: changed by a killed write"
        return
    if previous is None and not final.exists():
        return
    assert final.exists(), f"{final.name}: the previous file is gone"
    data = final.read_bytes()
    assert data == previous or complete(final), f"{final.name}: a partial file ({len(data)} B)"


def _written(final: Path, data: bool) -> bool:
    """Whether a temporary file of ``final`` exists (with ``data``: holds at least one byte)."""
    for t in temps(final):
        try:
            if not data or t.stat().st_size > 0:
                return True
        except FileNotFoundError:           # renamed meanwhile
            pass
    return False


def kill_while_writing(cmd: list, cwd: Path, final: Path, delay: float, data: bool,
                       timeout: float = 180.0) -> tuple[bool, int, int]:
    """Start ``cmd``, wait until a temporary file of ``final`` appears (``data``: until it holds
    bytes), wait ``delay`` [s], then kill -9 the process.

    Returns (killed: False when the process ended first, with exit code 0; number of temporary
    files of ``final`` left; their total size [B]).
    """
    with open(cwd / "stderr.txt", "wb") as err:
        proc = subprocess.Popen(cmd, cwd=cwd, stdout=subprocess.DEVNULL, stderr=err)
        try:
            end = time.monotonic() + timeout
            while not _written(final, data):
                if proc.poll() is not None:
                    break
                assert time.monotonic() < end, f"no temporary file of {final.name}"
                time.sleep(0.0005)
            else:
                time.sleep(delay)
        finally:
            ended = proc.poll() is not None
            proc.kill()
            proc.wait()
    if ended:
        assert proc.returncode == 0, (cmd, proc.returncode, (cwd / "stderr.txt").read_text())
    left = temps(final)
    return not ended, len(left), sum(p.stat().st_size for p in left if p.exists())


def run_kill_trials(kind: str, cmd: list, cwd: Path, plan: list, outputs: dict,
                    previous: dict) -> dict:
    """kill -9 trials of one kind: ``plan`` lists (file to wait for, delay [s], wait for its
    first bytes); ``outputs`` maps each output of ``cmd`` to its completeness test;
    ``previous`` maps each output to the bytes it holds when a trial starts (the first trial:
    no previous files). Returns the counts."""
    counts = {"trials": 0, "killed while writing": 0, "with partial data written": 0,
              "ended first": 0}
    for i, (target, delay, data) in enumerate(plan):
        start = {}
        for f in outputs:
            for t in temps(f):          # what an earlier killed trial left: a user deletes it
                t.unlink()
            start[f] = None if i == 0 else previous[f]
            if start[f] is None:
                f.unlink(missing_ok=True)
            else:
                f.write_bytes(start[f])
        killed, n_left, size = kill_while_writing(cmd, cwd, target, delay, data)
        for f, complete in outputs.items():
            assert_whole(f, start[f], complete)
        counts["trials"] += 1
        counts["killed while writing"] += n_left > 0
        counts["with partial data written"] += size > 0
        counts["ended first"] += not killed
    TRIALS[kind] = counts
    assert counts["killed while writing"] >= 1, (kind, counts)
    return counts


@pytest.fixture(scope="module", autouse=True)
def _print_trials():
    yield
    if TRIALS:
        total = sum(c["trials"] for c in TRIALS.values())
        print(f"\nkill -9 trials: {total} ("
              + "; ".join(f"{k}: {', '.join(f'{v} {n}' for n, v in c.items())}"
                          for k, c in TRIALS.items()) + ")")


# -- the module on real files -------------------------------------------------------------------
def test_success_replaces_and_keeps_the_mode(tmp_path):
    f = tmp_path / "run.json"
    f.write_text("old")
    f.chmod(0o640)
    with atomic_output(f) as tmp:
        assert tmp.parent == tmp_path and tmp.name.startswith(".run.json.")
        assert tmp.suffix == ".json" and tmp.exists() and f.read_text() == "old"
        tmp.write_text("new")
    assert f.read_text() == "new" and (f.stat().st_mode & 0o777) == 0o640
    assert not temps(f)
    assert write_atomic(tmp_path / "t.txt", "ü") == tmp_path / "t.txt"
    assert (tmp_path / "t.txt").read_bytes() == "ü".encode()


@pytest.mark.parametrize("exc", [ValueError("bug in the writer"), KeyboardInterrupt()])
def test_exception_keeps_the_previous_file(tmp_path, exc):
    f = tmp_path / "run.nc"
    f.write_bytes(b"previous")
    with pytest.raises(type(exc)):          # not a write error: passes unchanged
        with atomic_output(f, "--out") as tmp:
            tmp.write_bytes(b"half")
            raise exc
    assert f.read_bytes() == b"previous" and not temps(f)
    with pytest.raises(ValueError):
        with atomic_output(tmp_path / "new.nc") as tmp:
            raise ValueError("x")
    assert not (tmp_path / "new.nc").exists() and not list(tmp_path.glob(".new.nc.*"))


def test_symlink_target_replaced_link_kept(tmp_path):
    (tmp_path / "real").mkdir()
    target = tmp_path / "real" / "data.json"
    target.write_text("old")
    link = tmp_path / "link.json"
    link.symlink_to(target)
    assert final_target(link) == target.resolve() and same_file(link, target)
    write_atomic(link, "new")
    assert link.is_symlink() and os.readlink(link) == str(target)
    assert target.read_text() == "new" and not temps(target) and not temps(link)


def test_file_too_large_keeps_the_previous_file(tmp_path):
    """A real EFBIG: this process's file size limit lowered (SIGXFSZ ignored), then raised."""
    f = tmp_path / "big.bin"
    f.write_bytes(b"previous")
    soft, hard = resource.getrlimit(resource.RLIMIT_FSIZE)
    old = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
    resource.setrlimit(resource.RLIMIT_FSIZE, (1 << 20, hard))
    try:
        with pytest.raises(OutputError) as e:
            write_atomic(f, b"x" * (4 << 20), "--out")
    finally:
        resource.setrlimit(resource.RLIMIT_FSIZE, (soft, hard))
        signal.signal(signal.SIGXFSZ, old)
    assert e.value.errno == errno.EFBIG and isinstance(e.value, OSError)
    assert str(e.value) == (f"--out {str(f)!r}: File too large (the file size limit, ulimit -f, "
                            f"is {1 << 20} bytes); the previous file is unchanged")
    assert f.read_bytes() == b"previous" and not temps(f)
    again = pickle.loads(pickle.dumps(e.value))         # crosses process boundaries whole
    assert str(again) == str(e.value) and again.errno == errno.EFBIG


def test_no_space_keeps_the_previous_file(tmp_path):
    """A real ENOSPC (``/dev/full``) raised inside the writer."""
    if not os.path.exists("/dev/full"):
        pytest.skip("no /dev/full")
    f = tmp_path / "fig.png"
    f.write_bytes(b"previous")
    with pytest.raises(OutputError) as e:
        with atomic_output(f, "--plot") as tmp:
            tmp.write_bytes(b"part")
            with open("/dev/full", "wb") as full:
                full.write(b"x" * 4096)
    assert e.value.errno == errno.ENOSPC
    assert str(e.value).startswith(f"--plot {str(f)!r}: No space left on device")
    assert str(e.value).endswith("; the previous file is unchanged")
    assert f.read_bytes() == b"previous" and not temps(f)
    with pytest.raises(OutputError, match="nothing was written"):
        with atomic_output(tmp_path / "none.png") as tmp:
            with open("/dev/full", "wb") as full:
                full.write(b"x")
    assert not (tmp_path / "none.png").exists()


def test_devices_and_fifos_are_never_replaced(tmp_path):
    fifo = tmp_path / "pipe.nc"
    os.mkfifo(fifo)
    for path in (fifo, Path("/dev/null")):
        with pytest.raises(OutputError, match="not a regular file"):
            write_atomic(path, "x", "--out")
    assert fifo.is_fifo() and Path("/dev/null").is_char_device()


def test_figures_infer_the_format_from_the_final_suffix(tmp_path):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(1, 1))
    for suffix, head in ((".png", b"\x89PNG"), (".svg", b"<?xml"), (".pdf", b"%PDF")):
        save_figure(fig, tmp_path / f"f{suffix}", dpi=20)
        assert (tmp_path / f"f{suffix}").read_bytes().startswith(head)
    assert not list(tmp_path.glob(".*"))


# -- the command line ---------------------------------------------------------------------------
def _refused(r, *words):
    """Exit 2, one stderr line ``error: ...`` with ``words``, nothing on stdout, no traceback."""
    lines = r.stderr.strip().splitlines()
    assert r.exit_code == 2, (r.exit_code, r.stderr, r.exception)
    assert len(lines) == 1 and lines[0].startswith("error: "), r.stderr
    assert all(w in lines[0] for w in words), (words, lines[0])
    assert r.stdout == "" and "Traceback" not in r.stderr
    return lines[0]


def test_outputs_that_are_inputs_or_each_other_are_refused(tmp_path, monkeypatch):
    from autobalance.config import preset_path

    monkeypatch.chdir(tmp_path)
    run = CliRunner().invoke
    cfg = tmp_path / "m.toml"
    cfg.write_bytes(preset_path("vub_jeffcott_004").read_bytes())
    text = cfg.read_bytes()
    (tmp_path / "link.toml").symlink_to(cfg)
    os.link(cfg, tmp_path / "hard.toml")
    line = _refused(run(app, ["simulate", "m.toml", "--out", "m.toml"]))
    assert line == "error: --out 'm.toml' is the input config file; give another file name"
    for other in ("link.toml", "hard.toml", str(cfg)):
        _refused(run(app, ["simulate", "m.toml", "--out", other]), "--out", "input config file")
        _refused(run(app, ["simulate", other, "--out", "m.toml"]), "--out", "input config file")
    (tmp_path / "cfg.png").write_bytes(text)
    _refused(run(app, ["simulate", "cfg.png", "--plot", "cfg.png"]), "--plot",
             "input config file")
    line = _refused(run(app, ["simulate", "m.toml", "--out", "x.png", "--plot", "x.png"]))
    assert line == ("error: --out and --plot are the same file 'x.png'; give each its own "
                    "file name")
    (tmp_path / "y.png").symlink_to(tmp_path / "x.png")     # a dangling link: one file
    _refused(run(app, ["simulate", "m.toml", "--out", "y.png", "--plot", "x.png"]),
             "--out 'y.png' and --plot 'x.png' are the same file")
    _refused(run(app, ["analyze", "forces", "washer_000", "--plot", "f.png",
                       "--damping-plot", "./f.png"]), "--plot", "--damping-plot")
    (tmp_path / "l.png").symlink_to(tmp_path / "s.nc")
    _refused(run(app, ["study", "immobility", "m.toml", "--out", "s.nc", "--plot", "l.png"]),
             "--out 's.nc' and --plot 'l.png' are the same file")
    sweep = tmp_path / "s.png"
    sweep.write_text('[sweep]\nbase = "vub_jeffcott_004"\n[monte_carlo]\nkind = "start_grid"\n'
                     'n = 2\n')
    _refused(run(app, ["sweep", "s.png", "--store", "st", "--plot", "s.png"]), "--plot",
             "the sweep file")
    assert not (tmp_path / "st").exists()
    assert cfg.read_bytes() == text and not (tmp_path / "x.png").exists()
    assert sorted(p.name for p in tmp_path.iterdir()) == ["cfg.png", "hard.toml", "l.png",
                                                          "link.toml", "m.toml", "s.png",
                                                          "y.png"]


def test_devices_and_fifos_are_refused_as_outputs(tmp_path):
    fifo = tmp_path / "out.nc"
    os.mkfifo(fifo)
    run = CliRunner().invoke
    line = _refused(run(app, ["simulate", "vub_jeffcott_004", "--out", "/dev/null"]))
    assert line == ("error: --out '/dev/null': is a character device, not a regular file; give "
                    "a file name, e.g. run.nc")
    _refused(run(app, ["simulate", "vub_jeffcott_004", "--out", str(fifo)]), "--out", "a FIFO")
    _refused(run(app, ["study", "immobility", "vub_jeffcott_004", "--out", str(fifo)]),
             "--out", "a FIFO")
    _refused(run(app, ["simulate", "vub_jeffcott_004", "--plot", "/dev/null"]), "--plot")
    assert fifo.is_fifo() and Path("/dev/null").is_char_device()


@pytest.mark.slow
def test_failing_run_keeps_the_previous_out(tmp_path):
    good = tmp_path / "good.nc"
    previous = small_netcdf(good)
    png = tmp_path / "good.png"
    previous_png = small_png(png)
    r = CliRunner().invoke(app, ["simulate", "vub_jeffcott_004", "--set", "options.max_steps=500",
                                 "--out", str(good), "--plot", str(png)])
    assert r.exit_code == 1, (r.exit_code, r.stderr)
    assert good.read_bytes() == previous and png.read_bytes() == previous_png
    assert "wrote" not in r.stdout
    assert f"--out {str(good)!r}, --plot {str(png)!r} not written" in r.stderr
    assert not temps(good) and not temps(png)


@pytest.mark.slow
def test_file_size_limit_on_the_command_line(tmp_path):
    """The CLI writes a NetCDF (~7 MB) under a 1 MB file size limit: one line, exit 2."""
    good = tmp_path / "run.nc"
    previous = small_netcdf(good)
    limit = 1_000_000

    def limit_file_size():
        resource.setrlimit(resource.RLIMIT_FSIZE, (limit, limit))

    old = signal.signal(signal.SIGXFSZ, signal.SIG_IGN)     # inherited through exec
    try:
        p = subprocess.run([str(EXE), "simulate", "vub_jeffcott_004", "--out", str(good)],
                           cwd=tmp_path, capture_output=True, text=True, timeout=300,
                           preexec_fn=limit_file_size)
    finally:
        signal.signal(signal.SIGXFSZ, old)
    assert p.returncode == 2, p.stderr
    assert p.stderr.strip().splitlines() == [
        f"error: --out {str(good)!r}: File too large (the file size limit, ulimit -f, is "
        f"{limit} bytes); the previous file is unchanged"], p.stderr
    assert "wrote" not in p.stdout
    assert good.read_bytes() == previous and not temps(good)


# -- kill -9 while writing ----------------------------------------------------------------------
@pytest.mark.slow
def test_kill_while_writing_netcdf(tmp_path):
    out = tmp_path / "run.nc"
    previous = small_netcdf(tmp_path / "prev.nc")
    c = run_kill_trials("simulate --out", [str(EXE), "simulate", "vub_jeffcott_004", "--out",
                                           str(out)], tmp_path,
                        [(out, 0.0, False), (out, 0.0, True), (out, 0.1, True)],
                        {out: netcdf_complete}, {out: previous})
    assert c["with partial data written"] >= 1, c


@pytest.mark.slow
def test_kill_while_writing_png(tmp_path):
    plot = tmp_path / "run.png"
    previous = small_png(tmp_path / "prev.png")
    run_kill_trials("simulate --plot", [str(EXE), "simulate", "vub_jeffcott_004", "--plot",
                                        str(plot)], tmp_path,
                    [(plot, 0.0, False), (plot, 0.3, False), (plot, 0.0, True)],
                    {plot: png_complete}, {plot: previous})


@pytest.mark.slow
def test_kill_while_writing_a_study(tmp_path):
    out, plot = tmp_path / "s.nc", tmp_path / "s.png"
    previous = {out: small_netcdf(tmp_path / "prev.nc"), plot: small_png(tmp_path / "prev.png")}
    run_kill_trials("study --out/--plot",
                    [str(EXE), "study", "immobility", "vub_jeffcott_004", "--quick",
                     "--out", str(out), "--plot", str(plot)], tmp_path,
                    [(out, 0.0, False), (plot, 0.0, False), (out, 0.0, True)],
                    {out: lambda p: netcdf_complete(p, ()), plot: png_complete}, previous)


#: A subprocess writing the reproduction report (one target with a long note: ~4 MB files).
REPORT_SCRIPT = """
import sys
from autobalance.report.runner import run_targets, write_report
from autobalance.validation.target import Context, Target
target = Target("kill-0", "000", ("Fig. 1",), "kill -9 trial", notes="x" * 4_000_000)
write_report(run_targets([target], Context(quick=True)), sys.argv[1])
"""


@pytest.mark.slow
def test_kill_while_writing_the_report(tmp_path):
    out = tmp_path / "report"
    out.mkdir()
    files = {"json": out / "report.json", "html": out / "report.html",
             "markdown": out / "VALIDATION.md"}

    def json_complete(p):
        try:
            return len(json.loads(p.read_text())["targets"][0]["notes"]) == 4_000_000
        except ValueError:
            return False

    complete = {files["json"]: json_complete,
                files["html"]: lambda p: p.read_text().rstrip().endswith("</html>"),
                files["markdown"]: lambda p: "x" * 4_000_000 in p.read_text()}
    previous = {f: f"previous {k}\n".encode() for k, f in files.items()}
    c = run_kill_trials("report json/html/md", [sys.executable, "-c", REPORT_SCRIPT, str(out)],
                        tmp_path, [(files["json"], 0.0, False), (files["html"], 0.0, True),
                                   (files["json"], 0.0, True), (files["markdown"], 0.0, True)],
                        complete, previous)
    assert c["with partial data written"] >= 1, c
