"""Every page of docs/ that the project cites (``docs/liquid/film.md sec. 3d`` in a docstring, a
comment, an error message, a test or a page) exists, and a cited section number is a heading of
that page: a page moved or split leaves no citation pointing nowhere."""
from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
#: A cited page, with the section that may follow it ("sec. 3i", "sec. 7").
CITATION = re.compile(r"\bdocs/((?:[\w.-]+/)*[\w.-]+\.md)(?:\s+sec\.\s+(\d+[a-z]?)\b)?")


def citing_files() -> list[Path]:
    files = [ROOT / "README.md"]
    for sub, globs in (("src", ("*.py", "*.toml")), ("tests", ("*.py",)),
                       ("benchmarks", ("*.py",)), ("examples", ("*.toml",)), ("docs", ("*.md",))):
        for g in globs:
            files += sorted((ROOT / sub).rglob(g))
    return [f for f in files if f.is_file() and "__pycache__" not in f.parts
            and f.resolve() != Path(__file__).resolve()]           # this file plants broken ones


def headings(page: Path) -> set[str]:
    """The section numbers of a page's headings ("## 3i. Balls beside a liquid" -> 3i)."""
    return set(re.findall(r"^#+\s+(\d+[a-z]?)[.)\s]", page.read_text(encoding="utf-8"), re.M))


def broken_citations(files: list[Path], root: Path = ROOT) -> list[str]:
    out = []
    for f in files:
        text = f.read_text(encoding="utf-8", errors="replace")
        for m in CITATION.finditer(text):
            page, sec = root / "docs" / m.group(1), m.group(2)
            line = text.count("\n", 0, m.start()) + 1
            where = f"{f.relative_to(root) if root in f.parents else f.name}:{line}"
            if not page.is_file():
                out.append(f"{where}: docs/{m.group(1)} does not exist")
            elif sec and sec not in headings(page):
                out.append(f"{where}: docs/{m.group(1)} has no section {sec}")
    return out


def test_every_cited_page_and_section_exists():
    found = broken_citations(citing_files())
    assert not found, f"{len(found)} broken citations:\n" + "\n".join(found[:60])


def test_the_check_finds_a_missing_page_and_a_missing_section(tmp_path):
    """Self-test on a planted project: a page that is not there and a section a page lacks."""
    (tmp_path / "docs").mkdir()
    (tmp_path / "docs" / "model.md").write_text("# Model\n\n## 3. Balls\n\n## 3a. Rolling\n")
    f = tmp_path / "code.py"
    f.write_text("# docs/model.md sec. 3a and docs/model.md sec. 3\n"
                 "# docs/model.md sec. 4\n# docs/gone.md\n")
    assert broken_citations([f], tmp_path) == ["code.py:2: docs/model.md has no section 4",
                                               "code.py:3: docs/gone.md does not exist"]
