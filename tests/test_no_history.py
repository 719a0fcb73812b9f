"""The code and the documentation describe what is, not how it came to be: no development
history (session, stop or issue numbers, "until now", dated entries) in README, docs/, the
package, the benchmarks, the examples or the tests' text; history lives in CHANGELOG.md by
version and in the commit messages. Nor a path outside the project (a clone has no
../shared)."""
from __future__ import annotations

import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

#: What reads as development history, case-insensitive. A legitimate phrase that matches (a
#: run that "stops 5 s later") is rephrased ("ends 5 s later").
HISTORY = (
    r"\b(?:stop|stops|session|sessions|issue|issues)\s+#?\d+",     # stop 37, issue 15
    r"\b(?:previous|this|last|earlier|next|later) (?:session|stop)s?\b",
    r"\buntil now\b",
    r"\bpreviously\b",
    r"\bbit for bit the \w+ before\b",
    r"\b20[12]\d-[01]\d-[0-3]\d\b",                                  # a dated entry
    r"shared/seeds",                                                 # outside the project
)
PATTERN = re.compile("|".join(HISTORY), re.IGNORECASE)
#: A third-party tracker cited by number (not ours): allowed where it says whose.
FOREIGN = re.compile(r"\b(?:numba|numpy|scipy|xarray|dask|zarr|typer|click|pint|matplotlib)"
                     r"\s+issue\s+#?\d+", re.IGNORECASE)


def project_files() -> list[Path]:
    """README, docs/, src/, benchmarks/, examples/ and tests/ (this file aside: it holds the
    patterns)."""
    files = [ROOT / "README.md"]
    for sub, globs in (("docs", ("*.md",)), ("src", ("*.py", "*.toml")),
                       ("benchmarks", ("*.py", "*.md")), ("examples", ("*",)),
                       ("tests", ("*.py", "*.toml"))):
        for g in globs:
            files += sorted((ROOT / sub).rglob(g))
    return [f for f in files if f.is_file() and f.resolve() != Path(__file__).resolve()
            and "__pycache__" not in f.parts]


#: What opens a continued line: indentation and a comment or quote marker.
LEAD = re.compile(r"^\s*(?:#+|>|\*|//)?\s*")


def _reads_as_history(text: str) -> bool:
    return bool(PATTERN.search(FOREIGN.sub("", text)))


def history_lines(files: list[Path]) -> list[str]:
    """``path:line: text`` of every line that reads as development history, alone or joined
    with the next line (a phrase wrapped across two lines: "until stop" / "33")."""
    out = []
    for f in files:
        name = f.relative_to(ROOT) if ROOT in f.parents else f.name
        lines = f.read_text(encoding="utf-8", errors="replace").splitlines()
        for i, line in enumerate(lines, 1):
            nxt = lines[i] if i < len(lines) else ""
            if _reads_as_history(line) or (
                    not _reads_as_history(nxt)
                    and _reads_as_history(line.rstrip() + " " + LEAD.sub("", nxt))):
                out.append(f"{name}:{i}: {line.strip()[:100]}")
    return out


def test_no_development_history_in_the_project():
    found = history_lines(project_files())
    assert not found, f"{len(found)} lines of development history:\n" + "\n".join(found[:60])


@pytest.mark.parametrize("text", ["on by default since stop 37", "(issue 15; docs/liquid/index.md)",
                                  "this session's runs", "Until now it was refused",
                                  "see ../shared/seeds/README.md", "measured 2026-11-30"])
def test_the_check_finds_planted_history(tmp_path, text):
    """Self-test: each kind of history planted in a file is found; a foreign tracker is not."""
    f = tmp_path / "planted.md"
    f.write_text(f"A line.\n{text}\nnumba issue #2350 uses it the same way.\n")
    found = history_lines([f])
    assert len(found) == 1 and found[0].startswith("planted.md:2:")


def test_the_check_finds_history_wrapped_across_two_lines(tmp_path):
    """Self-test: a phrase split by a line break (here inside a comment) is found once, on its
    first line."""
    f = tmp_path / "planted.py"
    f.write_text("x = 1\n# refused until stop\n# 33, now accepted\ny = 2\n")
    assert [line.split(":")[1] for line in history_lines([f])] == ["2"]


def test_the_check_reads_every_part_of_the_project():
    parts = {f.relative_to(ROOT).parts[0] for f in project_files()}
    assert {"README.md", "docs", "src", "benchmarks", "examples", "tests"} <= parts
