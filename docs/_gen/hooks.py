"""mkdocs hooks of the documentation site (``mkdocs.yml``: ``hooks``).

* ``on_files`` adds the reference pages generated from the code (:data:`GENERATED`): they exist
  only in the build, never as committed copies, so they cannot drift from the code.
* ``on_page_markdown`` reads the pages' lists as GitHub does: a list may follow a paragraph
  without a blank line, and a nested list is indented by two spaces; Python-Markdown needs the
  blank line and four spaces, so the hook adds the one and doubles the other (the files stay as
  they are).
"""
from __future__ import annotations

import re
import sys
from pathlib import Path

from mkdocs.structure.files import File

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))      # docs/, for the _gen package

from _gen import cli_pages, config_keys  # noqa: E402

#: Generated page (path in the site's sources) -> the function that writes its markdown.
GENERATED = {
    "reference/config.md": config_keys.page,
    "reference/commands.md": cli_pages.commands_page,
    "reference/vocabulary.md": cli_pages.vocabulary_page,
}

_ITEM = re.compile(r"^(\s*)(?:[*+-]|\d+\.)\s")


def on_files(files, config):
    for uri, make in GENERATED.items():
        files.append(File.generated(config, uri, content=make()))
    return files


def on_page_markdown(markdown, page, config, files):
    return four_space_lists(blank_before_lists(markdown))


def blank_before_lists(markdown: str) -> str:
    """The markdown with a blank line before every list that follows a paragraph directly
    (GitHub starts a list there, Python-Markdown only after a blank line)."""
    out: list[str] = []
    fence = in_list = False
    prev = ""
    for line in markdown.split("\n"):
        if line.lstrip().startswith("```"):
            fence = not fence
        elif not fence:
            item = bool(_ITEM.match(line)) and not line.startswith(" ")
            if item and not in_list and prev.strip() and not prev.lstrip().startswith(("|", "#")):
                out.append("")
            if item:
                in_list = True
            elif line.strip() and not line.startswith(" ") and not prev.strip():
                in_list = False
        out.append(line)
        prev = line
    return "\n".join(out)


def _blocks(lines: list[str]):
    """(start, end) of each list block: from a list item at the left margin to the line before
    a blank line followed by a line at the left margin that is not a list item."""
    i, n = 0, len(lines)
    fence = False
    while i < n:
        line = lines[i]
        if line.lstrip().startswith("```"):
            fence = not fence
        if not fence and _ITEM.match(line) and not line.startswith(" "):
            j = i + 1
            while j < n:
                nxt = lines[j]
                if nxt.strip() and not nxt.startswith(" ") and not _ITEM.match(nxt) \
                        and not lines[j - 1].strip():
                    break
                if nxt.startswith("```"):
                    break
                j += 1
            yield i, j
            i = j
        else:
            i += 1


def four_space_lists(markdown: str) -> str:
    """The markdown with every list block nested by two spaces re-indented by four."""
    lines = markdown.split("\n")
    for start, end in _blocks(lines):
        nested = [len(m.group(1)) for ln in lines[start + 1:end] if (m := _ITEM.match(ln))
                  and m.group(1)]
        if not nested or min(nested) >= 4:
            continue
        for k in range(start + 1, end):
            ln = lines[k]
            indent = len(ln) - len(ln.lstrip(" "))
            if indent and ln.strip():
                lines[k] = " " * (2 * indent) + ln.lstrip(" ")
    return "\n".join(lines)
