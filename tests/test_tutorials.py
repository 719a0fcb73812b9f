"""The tutorials (docs/tutorials/*.md) run as written: every command of a page, in order, in a
fresh directory, exits 0 within the time the page states for it.

What a page runs, by convention:

* a ```` ```toml ```` block whose preceding line names a file in backticks and ends with a colon
  ("Save this as `spin-dryer.toml`:") is written to that file;
* every line of a ```` ```console ```` block that starts with ``$ `` is a command, run by bash in
  the directory with the venv's ``bin`` first on ``PATH``; it ends with a comment
  ``# under N s``, the most it may take (a command that compiled numba kernels, which happens
  once after installing or after an edit of ``core/``, is not held to it). A command ending in
  ``&`` is started in the background in a process group of its own and ended at the end of the
  page (by that group's id); after ``dask scheduler`` the test waits for its port;
* every ```` ```python ```` block is run as a script with the venv's Python;
* the repository's ``examples/`` are copied into the directory (the pages run from the
  repository's directory), and the Dask page's port 8786 is replaced by a free port.

The pages take half a minute to a minute each: ``slow``; the Dask page starts a real
``dask scheduler`` and ``dask worker``: ``dask``.
"""
from __future__ import annotations

import os
import re
import shutil
import signal
import socket
import subprocess
import sys
import time
from dataclasses import dataclass
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
TUTORIALS = ROOT / "docs" / "tutorials"
BIN = Path(sys.executable).parent
BOUND = re.compile(r"#\s*under (\d+(?:\.\d+)?) s\s*$")
DASK_PORT = "8786"


@dataclass
class Step:
    kind: str          # "file", "command", "python"
    text: str          # the file's contents, the command line, the script
    name: str = ""     # the file's name
    bound: float = 0.0  # a command's stated limit [s]
    line: int = 0


def steps(page: Path) -> list[Step]:
    """The steps of a tutorial page, in order (the conventions of the module docstring)."""
    lines = page.read_text(encoding="utf-8").split("\n")
    out: list[Step] = []
    i = 0
    while i < len(lines):
        m = re.match(r"```(\w*)\s*$", lines[i])
        if not m or not m.group(1):
            i += 1
            continue
        lang, start = m.group(1), i
        j = i + 1
        while not lines[j].startswith("```"):
            j += 1
        body = lines[i + 1:j]
        if lang == "toml":
            before = next((ln for ln in reversed(lines[:start]) if ln.strip()), "")
            named = re.search(r"`([\w.-]+\.toml)`[^`]*:\s*$", before)
            if named:
                out.append(Step("file", "\n".join(body) + "\n", name=named.group(1), line=start + 1))
        elif lang == "console":
            for k, ln in enumerate(body):
                if ln.startswith("$ "):
                    bound = BOUND.search(ln)
                    cmd = BOUND.sub("", ln[2:]).strip()
                    out.append(Step("command", cmd, bound=float(bound.group(1)) if bound else 0.0,
                                    line=start + 2 + k))
        elif lang == "python":
            out.append(Step("python", "\n".join(body) + "\n", line=start + 1))
        i = j + 1
    return out


def compiled_kernels() -> dict[str, float]:
    """The numba cache files of the package (and of NUMBA_CACHE_DIR) with their mtimes: a
    command that changes them compiled kernels."""
    roots = [ROOT / "src" / "autobalance"]
    if os.environ.get("NUMBA_CACHE_DIR"):
        roots.append(Path(os.environ["NUMBA_CACHE_DIR"]))
    out = {}
    for r in roots:
        for p in r.rglob("*.nb[ic]"):
            try:
                out[str(p)] = p.stat().st_mtime
            except OSError:
                pass
    return out


def _free_port() -> int:
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _wait_for_port(port: int, proc, timeout: float = 60.0) -> None:
    deadline = time.monotonic() + timeout
    while True:
        try:
            socket.create_connection(("127.0.0.1", port), 0.5).close()
            return
        except OSError:
            assert proc.poll() is None, "the scheduler exited"
            assert time.monotonic() < deadline, "the scheduler did not open its port"
            time.sleep(0.2)


def run_page(page: Path, tmp: Path) -> list[str]:
    """Run every step of ``page`` in ``tmp``; the measured times, one line each."""
    shutil.copytree(ROOT / "examples", tmp / "examples")
    env = dict(os.environ, PATH=f"{BIN}{os.pathsep}{os.environ.get('PATH', '')}",
               MPLBACKEND="Agg")
    env.pop("DASK_SCHEDULER_ADDRESS", None)
    port = str(_free_port())
    background: list[subprocess.Popen] = []
    report = []
    try:
        for step in steps(page):
            where = f"{page.name}:{step.line}"
            if step.kind == "file":
                (tmp / step.name).write_text(step.text, encoding="utf-8")
                continue
            if step.kind == "python":
                script = tmp / f"step_{step.line}.py"
                script.write_text(step.text, encoding="utf-8")
                r = subprocess.run([sys.executable, str(script)], cwd=tmp, env=env,
                                   capture_output=True, text=True, timeout=300)
                assert r.returncode == 0, f"{where}: {r.stderr[-3000:]}"
                continue
            cmd = step.text.replace(DASK_PORT, port)
            if cmd.endswith("&"):
                proc = subprocess.Popen(["bash", "-c", "exec " + cmd[:-1].strip()], cwd=tmp,
                                        env=env, start_new_session=True)
                background.append(proc)
                if cmd.startswith("dask scheduler"):
                    _wait_for_port(int(port), proc)
                continue
            assert step.bound, f"{where}: a command without its '# under N s'"
            before = compiled_kernels()
            t0 = time.monotonic()
            r = subprocess.run(["bash", "-c", cmd], cwd=tmp, env=env, capture_output=True,
                               text=True, timeout=max(600.0, 10 * step.bound))
            took = time.monotonic() - t0
            assert r.returncode == 0, f"{where}: {cmd}\n{r.stdout[-2000:]}\n{r.stderr[-3000:]}"
            compiled = compiled_kernels() != before
            report.append(f"{where}: {took:.1f} s (under {step.bound:g} s)"
                          + (", compiled kernels" if compiled else "") + f": {cmd}")
            if not compiled:
                assert took <= step.bound, f"{where}: took {took:.1f} s, the page says under " \
                                           f"{step.bound:g} s: {cmd}"
    finally:
        for proc in reversed(background):          # the process groups this test started
            if proc.poll() is None:
                os.killpg(proc.pid, signal.SIGTERM)
        for proc in reversed(background):
            try:
                proc.wait(timeout=30)
            except subprocess.TimeoutExpired:
                os.killpg(proc.pid, signal.SIGKILL)
                proc.wait()
    print("\n".join(report))
    return report


PAGES = {"ball-balancer.md": [pytest.mark.slow], "liquid-ring.md": [pytest.mark.slow],
         "dask-sweep.md": [pytest.mark.slow, pytest.mark.dask]}


def test_every_tutorial_is_run_here():
    assert sorted(p.name for p in TUTORIALS.glob("*.md")) == sorted(PAGES)


@pytest.mark.parametrize("name", sorted(PAGES))
def test_the_commands_state_their_time_well_under_a_minute(name):
    commands = [s for s in steps(TUTORIALS / name) if s.kind == "command"
                and not s.text.endswith("&")]
    assert commands
    for s in commands:
        assert 0 < s.bound <= 60, f"{name}:{s.line}: {s.text}"


def test_the_steps_are_read_by_the_conventions(tmp_path):
    page = tmp_path / "t.md"
    page.write_text("Save this as `m.toml`:\n\n```toml\n[rotor]\nmass = 1\n```\n\n```console\n"
                    "$ autobalance show m.toml      # under 5 s\noutput\n$ dask scheduler &\n```\n"
                    "\n```\nnot run\n```\n\n```python\nprint(1)\n```\n")
    got = [(s.kind, s.name or s.text.strip(), s.bound) for s in steps(page)]
    assert got == [("file", "m.toml", 0.0), ("command", "autobalance show m.toml", 5.0),
                   ("command", "dask scheduler &", 0.0), ("python", "print(1)", 0.0)]


@pytest.mark.parametrize("name", [pytest.param(n, marks=m) for n, m in sorted(PAGES.items())])
def test_the_tutorial_runs_as_written(name, tmp_path):
    report = run_page(TUTORIALS / name, tmp_path)
    assert report
