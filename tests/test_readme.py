"""The README's walk-through runs as written: its machine file and its four commands, each
within about the time the README states (the kernels compiled once), and each prints the numbers
the README quotes."""
from __future__ import annotations

import re
import subprocess
import sys
import time
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
SECTION = "## Ten minutes on a machine of your own"
#: What each command of the walk-through must print (quoted in the README's text).
QUOTED = {"show": ["674.6"], "speed-map": ["707.7 rpm"], "start-positions": ["p95 G9.82"],
          "design": ["recommended (the cheapest that meets it): 3x2.25g-R40mm-tsr"]}
#: Wall-time bound of each command [s]: three times the README's figure (2 s, 7 s, 10 s, about a
#: minute) for a loaded 2-core machine.
LIMIT = {"show": 6.0, "speed-map": 21.0, "start-positions": 30.0, "design": 180.0}


def walk_through() -> tuple[str, list[str]]:
    """The walk-through's TOML file and its commands, in order."""
    text = (ROOT / "README.md").read_text(encoding="utf-8")
    part = text.split(SECTION, 1)[1].split("\n## ", 1)[0]
    toml = re.search(r"```toml\n(.*?)```", part, re.S).group(1)
    commands = [c.strip() for c in re.findall(r"```\n\s*(autobalance [^\n]*)\n\s*```", part)]
    return toml, commands


def test_the_walk_through_is_there():
    toml, commands = walk_through()
    assert 'name = "separator"' in toml
    assert [c.split()[1] if c.split()[1] != "study" else c.split()[2] for c in commands] == \
        list(QUOTED)


@pytest.mark.slow
def test_the_walk_through_runs_as_written(tmp_path):
    toml, commands = walk_through()
    (tmp_path / "my_machine.toml").write_text(toml)
    exe = Path(sys.executable).with_name("autobalance")
    for cmd in commands:
        words = cmd.split()
        name = words[2] if words[1] == "study" else words[1]
        t0 = time.perf_counter()
        p = subprocess.run([str(exe), *words[1:]], cwd=tmp_path, capture_output=True, text=True,
                           timeout=600)
        wall = time.perf_counter() - t0
        assert p.returncode == 0, (cmd, p.stderr[-2000:])
        for q in QUOTED[name]:
            assert q in p.stdout, (cmd, q, p.stdout[-3000:])
        assert wall <= LIMIT[name], (cmd, wall)
    for png in ("map.png", "starts.png", "design.png"):
        assert (tmp_path / png).stat().st_size > 10_000
