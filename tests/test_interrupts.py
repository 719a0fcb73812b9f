"""Ctrl-C at any moment of a command: one line on stderr, never a traceback.

The console script holds SIGINT while the package loads (``_autobalance_entry``), and
:func:`autobalance.cli.main` turns a KeyboardInterrupt into one line from there on; a sweep
stops its workers and says what it kept. Each trial starts the real console script of this
virtual environment as a process and sends it SIGINT after a delay.

CPython's own start-up (its ``site`` import, the first ~30 ms) runs before any code of the
package; a SIGINT there ends the interpreter in its own way. A trial whose traceback comes from
there (``Fatal Python error`` or frames in ``<frozen site>`` only) is counted apart and must be
rare; every trial that reached the package must end in one line.
"""
from __future__ import annotations

import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest

pytestmark = pytest.mark.slow

EXE = Path(sys.executable).with_name("autobalance")
DELAYS = (0.05, 0.1, 0.2, 0.3, 0.4, 0.6, 1.0, 2.0)


def _interpreter_start_up(err: str) -> bool:
    """Whether a traceback is CPython's own, from before the console script ran."""
    return "Fatal Python error" in err or ("<frozen site>" in err and "_autobalance_entry"
                                           not in err and "autobalance" not in err)


def _trial(args: list, delay: float, cwd: Path) -> tuple[int, str, str]:
    p = subprocess.Popen([str(EXE), *args], cwd=cwd, stdout=subprocess.PIPE,
                         stderr=subprocess.PIPE, text=True)
    time.sleep(delay)
    p.send_signal(signal.SIGINT)
    out, err = p.communicate(timeout=120)
    return p.returncode, out, err


@pytest.mark.parametrize("command", ["sweep", "show"])
def test_ctrl_c_at_any_moment_is_one_line(tmp_path, command):
    spec = tmp_path / "s.toml"
    spec.write_text('[sweep]\nbase = "vub_jeffcott_004"\nbatch_size = 4\n'
                    '[monte_carlo]\nkind = "start_grid"\nn = 6\n')
    args = (["sweep", str(spec), "--store", str(tmp_path / "st")] if command == "sweep"
            else ["show", "vub_jeffcott_004"])
    bad, early, clean = [], 0, 0
    for delay in DELAYS:
        shutil.rmtree(tmp_path / "st", ignore_errors=True)
        code, out, err = _trial(args, delay, tmp_path)
        if code == 0 or (out and not err):
            clean += 1                     # done before the signal, or in the interpreter's exit
            continue
        if "Traceback" in err or "Fatal Python error" in err:
            if _interpreter_start_up(err):
                early += 1
                continue
            bad.append((delay, err[-800:]))
            continue
        lines = err.strip().splitlines()
        assert code == 130, (delay, code, err)
        assert lines and lines[-1].startswith("error: interrupted"), (delay, err)
        assert not [ln for ln in lines if not (ln.startswith("error:") or ln.startswith("[")
                                               or "runs to compute" in ln)], (delay, err)
        clean += 1
    print(f"\nCtrl-C trials of {command}: {clean} clean, {early} in CPython's start-up, "
          f"{len(bad)} with a traceback")
    assert not bad, bad
    assert early <= 1, "most trials must reach the package's own code"


def test_entry_point_is_the_console_script():
    text = EXE.read_text()
    assert "from _autobalance_entry import main" in text, text
