"""The documentation site (mkdocs.yml, docs/): it builds with ``mkdocs build --strict`` (a broken
internal link or anchor, a page left out of the nav or a docstring mkdocstrings cannot read
fails), its reference pages are generated from the code (docs/_gen: the configuration keys from
``autobalance.config.schema`` and the models, the commands and options from the typer app, the
vocabulary from ``autobalance.cli.vocabulary``), and every command line of the pages names only
options its command takes.

The build takes about 10 s (mkdocstrings renders the API pages): it is ``slow``. The checks of
the generated pages' markdown and of the pages' command lines run in the fast tier.
"""
from __future__ import annotations

import dataclasses
import functools
import re
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"

sys.path.insert(0, str(DOCS))                   # the generators: docs/_gen

GENERATED = ("reference/config.md", "reference/commands.md", "reference/vocabulary.md")


@pytest.fixture(scope="module")
def gen():
    pytest.importorskip("mkdocs")
    from _gen import cli_pages, config_keys, hooks
    return {"config": config_keys, "cli": cli_pages, "hooks": hooks}


# -- the build -----------------------------------------------------------------------------------
@pytest.mark.slow
def test_the_site_builds_strict_with_the_generated_reference(tmp_path):
    pytest.importorskip("mkdocs")
    pytest.importorskip("mkdocstrings")
    site = tmp_path / "site"
    r = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "--site-dir",
                        str(site)], cwd=ROOT, capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stdout[-3000:] + r.stderr[-6000:]
    assert "WARNING" not in r.stderr, r.stderr[-6000:]
    config = (site / "reference/config/index.html").read_text(encoding="utf-8")
    for text in ("rotor.mass", "without the balls", "profile.runup_fraction",
                 "profile.hold_fraction", "balancer.rolling_resistance", "liquid.axis"):
        assert text in config, text
    commands = (site / "reference/commands/index.html").read_text(encoding="utf-8")
    for text in ("study start-positions", "--starts", "--residual-fraction", "--out-dir"):
        assert text in commands, text
    vocabulary = (site / "reference/vocabulary/index.html").read_text(encoding="utf-8")
    assert "--n-conf" in vocabulary and "--full-model" in vocabulary
    for page in ("reference/api/simulate", "reference/api/models", "reference/api/studies",
                 "tutorials/ball-balancer", "liquid/stability", "numerics/kernel"):
        assert (site / page / "index.html").is_file(), page
    api = (site / "reference/api/simulate/index.html").read_text(encoding="utf-8")
    assert "simulate_batch" in api
    # generated in the build only, never as a file of docs/
    assert not any((DOCS / p).exists() for p in GENERATED)


# -- the generated pages ---------------------------------------------------------------------------
def test_the_config_page_has_every_key_with_unit_default_and_meaning(gen):
    from autobalance.config import schema

    page = gen["config"].page()
    for section, specs in schema.SECTIONS.items():
        assert f"## [{section}]" in page
        for key in specs:
            row = next(ln for ln in page.splitlines() if ln.startswith(f"| `{section}.{key}` |"))
            meaning = row.rstrip(" |").split(" | ")[-1]
            assert meaning.strip(), f"{section}.{key} has no meaning (its model's docstring)"
    for kind, specs in schema.PROFILE_KINDS.items():
        assert f'### kind = "{kind}"' in page
        block = page.split(f'### kind = "{kind}"')[1].split("###")[0]
        for key in specs:
            assert f"| `profile.{key}` |" in block, (kind, key)
    assert "without the balls" in page                        # rotor.mass's meaning
    assert "**required**" in page


def test_the_config_page_defaults_are_the_dataclasses(gen):
    from autobalance.models import Rotor, SimOptions

    page = gen["config"].page()
    rtol = next(f.default for f in dataclasses.fields(SimOptions) if f.name == "rtol")
    assert f"| `options.rtol` | `-` | `{rtol:.6g}` |" in page
    assert "| `rotor.mass` | `kg` |  | **required** | &gt; 0 |" in page
    assert dataclasses.fields(Rotor)[0].name == "mass"


def test_the_numpydoc_parser_reads_shared_entries(gen):
    doc = """Summary.

    Parameters
    ----------
    kx, ky : float
        Stiffness [N/m],
        both axes.
    c : float
        Damping [N*s/m].

    Returns
    -------
    float
    """
    assert gen["config"].parameters(doc) == {"kx": "Stiffness [N/m], both axes.",
                                             "ky": "Stiffness [N/m], both axes.",
                                             "c": "Damping [N*s/m]."}


def test_the_commands_page_has_every_command_and_option(gen):
    cli = gen["cli"]
    page = cli.commands_page()
    for path, cmd, _ctx in cli.commands():
        assert f"\n## {' '.join(path)}\n" in page, path
        section = page.split(f"\n## {' '.join(path)}\n")[1].split("\n## ")[0]
        for name in cli.option_names(cmd):
            assert re.search(rf"(?<![\w-]){re.escape(name)}(?![\w-])", section), (path, name)
    assert "--starts" in page and "--n-conf" in page        # and the former names


def test_the_vocabulary_page_has_every_name_and_former_name(gen):
    from autobalance.cli.vocabulary import DEPRECATED, STUDY_SHARED, VOCABULARY

    page = gen["cli"].vocabulary_page()
    for name in VOCABULARY:
        assert f"| `{name}` |" in page, name
    for name in STUDY_SHARED:
        assert f"`{name}`" in page
    for path, table in DEPRECATED.items():
        for old, new in table.items():
            assert f"| `autobalance {' '.join(path)}` | `{old}` | `{new}` |" in page


def test_nested_lists_are_read_as_github_reads_them(gen):
    fix = gen["hooks"].four_space_lists
    text = "* a\n  * b\n    * c\n  more b\n* d\n\nText.\n\n    code\n"
    assert fix(text) == "* a\n    * b\n        * c\n    more b\n* d\n\nText.\n\n    code\n"
    four = "* a\n    * b\n"
    assert fix(four) == four
    blank = gen["hooks"].blank_before_lists
    assert blank("Text:\n* a\n  * b\nlazy\n* c\n\n```\nx:\n* y\n```\n") == \
        "Text:\n\n* a\n  * b\nlazy\n* c\n\n```\nx:\n* y\n```\n"


# -- the pages ---------------------------------------------------------------------------------------
def pages(generated_too: bool = True) -> list[Path]:
    """The pages of docs/; without the two that ``autobalance reproduce`` writes
    (VALIDATION*.md, checked against a quick run by tests/test_report.py) if not
    ``generated_too``."""
    return sorted(p for p in DOCS.rglob("*.md") if "_gen" not in p.parts
                  and (generated_too or not p.name.startswith("VALIDATION")))


def test_the_relative_links_of_the_pages_stay_inside_docs():
    bad = []
    for page in pages():
        text = re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S)
        for target in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", target) or target.startswith("#"):
                continue
            path = (page.parent / target.split("#")[0]).resolve()
            generated = path in {(DOCS / g).resolve() for g in GENERATED}
            if DOCS.resolve() not in path.parents or not (path.exists() or generated):
                bad.append(f"{page.relative_to(ROOT)}: {target}")
    assert not bad, "\n".join(bad)


@functools.lru_cache(maxsize=1)
def command_options() -> dict[str, set[str]]:
    """{command: its option names} of every command of the app."""
    from _gen import cli_pages

    return {" ".join(p): set(cli_pages.option_names(c)) | {"--help"}
            for p, c, _x in cli_pages.commands()}


def doc_command_lines(text: str):
    """(line, command, arguments) of every command line of a page: the lines of its code
    blocks that run ``autobalance`` (continuations joined), and its inline code spans that
    start with ``autobalance`` or with a command's name and give an option."""
    known = set(command_options())
    groups = {k.split()[0] for k in known if " " in k}

    def command(tokens):
        if len(tokens) > 1 and tokens[0] in groups and f"{tokens[0]} {tokens[1]}" in known:
            return f"{tokens[0]} {tokens[1]}"
        return tokens[0] if tokens and tokens[0] in known else None

    lines = text.split("\n")
    fence, para, start = False, [], 0
    out = []

    def spans():
        for m in re.finditer(r"`([^`]+)`", " ".join(para)):
            args = re.sub(r"^(?:python -m )?autobalance\s+", "", m.group(1).strip())
            cmd = command(args.split())
            if cmd and "--" in args:
                out.append((start + 1, cmd, args))

    i = 0
    while i < len(lines):
        line = lines[i]
        if line.startswith("```"):
            if not fence:
                spans()
                para = []
            fence = not fence
        elif fence:
            first = i
            while line.rstrip().endswith("\\") and i + 1 < len(lines):
                i += 1
                line = line.rstrip()[:-1] + " " + lines[i]
            line = re.sub(r"^\$ ", "", line.strip()).split(" #")[0]
            m = re.search(r"(?:^|\s)(?:python -m )?autobalance\s+(.*)", line)
            if m and command(m.group(1).split()):
                out.append((first + 1, command(m.group(1).split()), m.group(1)))
        elif not line.strip():
            spans()
            para = []
        else:
            if not para:
                start = i
            para.append(line)
        i += 1
    spans()
    return out


def test_every_command_line_of_the_pages_uses_options_of_its_command():
    options = command_options()
    bad, seen = [], 0
    for page in pages(generated_too=False):
        for line, cmd, args in doc_command_lines(page.read_text(encoding="utf-8")):
            seen += 1
            for opt in re.findall(r"(?<![\w-])--[a-zA-Z][\w-]*", args):
                if opt not in options[cmd]:
                    bad.append(f"{page.relative_to(ROOT)}:{line}: {cmd} has no {opt}: {args[:80]}")
    assert seen > 100                                # the pages were read
    assert not bad, "\n".join(bad)


def test_the_command_line_check_finds_a_former_option_name():
    text = "Run\n\n```\nautobalance study speed-map m.toml --damping 0.5,1\n```\n\nor `study " \
           "runup m.toml\n--fraction 0.1`.\n"
    found = [(cmd, args.split()[-2]) for _n, cmd, args in doc_command_lines(text)]
    assert found == [("study speed-map", "--damping"), ("study runup", "--fraction")]
