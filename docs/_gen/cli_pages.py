"""The pages of the commands and of the option vocabulary, from the typer app.

:func:`commands_page` walks ``autobalance.cli.app`` as click sees it
(``typer.main.get_command``; typer vendors click as ``typer._click``): one section per command
with its usage, its help (the docstring up to ``\\f``), its arguments and its options as
``--help`` prints them. :func:`vocabulary_page` gives every option name with its one meaning
(:data:`autobalance.cli.vocabulary.VOCABULARY`), the commands that take it, the options every
study takes (``STUDY_SHARED``) and the former names and commands still accepted
(``DEPRECATED``, ``DEPRECATED_COMMANDS``).
"""
from __future__ import annotations

import inspect
import re

import typer
from typer import _click as click

from autobalance.cli import app
from autobalance.cli import vocabulary as vocab

PROG = "autobalance"


def _root():
    return typer.main.get_command(app)


def commands(group=None, path=(), parent=None):
    """(path, command, context) of every leaf command, in the app's order."""
    group = group or _root()
    ctx = click.Context(group, info_name=path[-1] if path else PROG, parent=parent)
    for name, cmd in group.commands.items():
        sub = path + (name,)
        if getattr(cmd, "commands", None):
            yield from commands(cmd, sub, ctx)
        else:
            yield sub, cmd, click.Context(cmd, info_name=name, parent=ctx)


def help_text(cmd) -> str:
    """The command's help as ``--help`` shows it: its docstring up to ``\\f``."""
    return inspect.cleandoc((cmd.help or "").split("\f")[0]).strip()


_ROLE = re.compile(r":(?:data|func|class|meth|attr|mod):`~?([^`]+)`")


def _cell(text: str) -> str:
    """One table cell: one line, Sphinx roles as code, and outside code the characters
    markdown would read as emphasis or HTML escaped."""
    parts = _ROLE.sub(r"`\1`", " ".join(str(text).split())).replace("``", "`").split("`")
    for i in range(0, len(parts), 2):
        parts[i] = (parts[i].replace("*", "\\*").replace("_", "\\_").replace("<", "&lt;")
                    .replace(">", "&gt;").replace("|", "\\|"))
    return "`".join(parts)


def _text(text: str) -> str:
    """A command's help as markdown paragraphs: Sphinx roles as code, emphasis characters
    outside code escaped."""
    return "\n\n".join(_cell(par).replace("\\|", "|") for par in text.split("\n\n"))


def _code(text: str) -> str:
    """Inline code in a table cell (a pipe in code does not end the cell)."""
    return "`" + text + "`"


def _anchor(path) -> str:
    return "-".join(path)


def option_names(cmd) -> list[str]:
    return [n for p in cmd.params if p.param_type_name == "option"
            for n in (*p.opts, *p.secondary_opts)]


def commands_page() -> str:
    """The markdown of every command with its usage, arguments and options."""
    root = _root()
    rows = list(commands())
    out = ["# Commands and options", "",
           "Every command of `autobalance`, generated from the command-line app when this site "
           "is built: the same text as `autobalance COMMAND --help`. The meaning of each option "
           "name, the same in every command, is in the [vocabulary](vocabulary.md).", "",
           help_text(root), "",
           "| command | what it does |", "|---|---|"]
    for path, cmd, _ctx in rows:
        first = help_text(cmd).split("\n\n")[0]
        out.append(f"| [`{' '.join(path)}`](#{_anchor(path)}) | {_cell(first)} |")
    out.append("")
    for path, cmd, ctx in rows:
        out += [f"## {' '.join(path)}", "", "```",
                cmd.get_usage(ctx).strip(), "```", "", _text(help_text(cmd)), ""]
        args = [p for p in cmd.params if p.param_type_name == "argument"]
        if args:
            out += ["| argument | meaning |", "|---|---|"]
            for p in args:
                name, desc = p.get_help_record(ctx) or (p.make_metavar(ctx), "")
                out.append(f"| {_code(name)} | {_cell(desc)} |")
            out.append("")
        opts = [p for p in cmd.params if p.param_type_name == "option" and not p.hidden]
        if opts:
            out += ["| option | meaning |", "|---|---|"]
            for p in opts:
                record = p.get_help_record(ctx)
                if record is None:
                    continue
                names, desc = record
                if not desc:
                    desc = next((vocab.VOCABULARY[n] for n in p.opts if n in vocab.VOCABULARY), "")
                out.append(f"| {_code(names)} | {_cell(desc)} |")
            out.append("")
        old = vocab.DEPRECATED.get(tuple(path))
        if old:
            out += ["Former option names, still accepted until " + vocab.REMOVED_IN + ": "
                    + ", ".join(f"`{a}` (now `{b}`)" for a, b in old.items()) + ".", ""]
    return "\n".join(out) + "\n"


def vocabulary_page() -> str:
    """The markdown of the option vocabulary, the shared study options and former names."""
    takers: dict[str, list[str]] = {}
    for path, cmd, _ctx in commands():
        for n in option_names(cmd):
            takers.setdefault(n, []).append(" ".join(path))
    out = ["# Option vocabulary", "",
           "One option name has one meaning in every command that takes it "
           "(`autobalance.cli.vocabulary.VOCABULARY`, checked against every command by "
           "`tests/test_cli_vocabulary.py`); this page is generated from it when the site is "
           "built. Each command's own options are in [Commands and options](commands.md).", "",
           "| option | meaning | taken by |", "|---|---|---|"]
    own = set(option_names(_root()))                   # the program's own: --version
    for name, meaning in vocab.VOCABULARY.items():
        cmds = takers.get(name, [])
        where = ", ".join([f"`{PROG}`"] * (name in own)
                          + [f"[{c}](commands.md#{c.replace(' ', '-')})" for c in cmds])
        out.append(f"| `{name}` | {_cell(meaning)} | {where} |")
    studies = [" ".join(p) for p, _c, _x in commands() if p[0] == "study"]
    out += ["", "## Options of every study", "",
            "Every `autobalance study` command takes "
            + ", ".join(f"`{o}`" for o in vocab.STUDY_SHARED) + " ("
            + ", ".join(f"`{s}`" for s in studies) + "); the other options of each are in "
            "its section of [Commands and options](commands.md).", "",
            *study_matrix(), "",
            "## Former option names", "",
            f"These names are still accepted, with a warning that names the new one, until "
            f"version {vocab.REMOVED_IN}:", "",
            "| command | former name | use |", "|---|---|---|"]
    for path, table in vocab.DEPRECATED.items():
        for a, b in table.items():
            out.append(f"| `{PROG} {' '.join(path)}` | `{a}` | `{b}` |")
    out += ["", "## Former commands", "",
            f"These commands are still accepted, with a warning that names what to use, until "
            f"version {vocab.REMOVED_IN}:", "", "| former command | use |", "|---|---|"]
    for path, (_now, use) in vocab.DEPRECATED_COMMANDS.items():
        out.append(f"| `{PROG} {' '.join(path)}` | {_cell(use)} |")
    return "\n".join(out) + "\n"


#: The options some studies take and others do not, in the order of the matrix's columns.
MATRIX_OPTIONS = ("--grade", "--quick", "--out", "--plot", "--starts", "--random", "--seed",
                  "--budget", "--speeds", "--store", "--executor", "--workers", "--scheduler")


def study_matrix() -> list[str]:
    """The lines of a table: which study (and ``design``) takes which of
    :data:`MATRIX_OPTIONS`."""
    rows = [(p, c) for p, c, _x in commands() if p[0] == "study" or p == ("design",)]
    out = ["### Which study takes which option", "",
           "| command | " + " | ".join(f"`{o}`" for o in MATRIX_OPTIONS) + " |",
           "|---|" + "---|" * len(MATRIX_OPTIONS)]
    for path, cmd in rows:
        names = set(option_names(cmd))
        cells = ["yes" if o in names else "" for o in MATRIX_OPTIONS]
        out.append(f"| [{' '.join(path)}](commands.md#{_anchor(path)}) | "
                   + " | ".join(cells) + " |")
    return out


__all__ = ["MATRIX_OPTIONS", "commands", "commands_page", "study_matrix", "vocabulary_page"]
