"""One command-line vocabulary (autobalance.cli.vocabulary), checked over every command: each
option name is in the vocabulary, a name takes the same kind of value in every command, every
study takes the shared study options, the former names of an option are gone from its command
but still accepted (with a warning naming the new one); and the check itself fails on a planted
inconsistency."""
from __future__ import annotations

import json
from typing import Annotated, Optional

import pytest
import typer
from conftest import run_main

from autobalance.cli import app
from autobalance.cli.vocabulary import (DEPRECATED, DEPRECATED_COMMANDS, STUDY_SHARED,
                                        VOCABULARY, rewrite_deprecated)


def options(typer_app) -> dict[tuple, dict[str, str]]:
    """Command path -> {option name: the kind of value it takes} of every command of an app
    (and of a group that has options of its own, the program at path ()):
    "flag", or the annotated type ("int", "float", "str", "Path", with "[]" when repeatable)."""
    out = {}

    def walk(c, path):
        kinds = {}
        for p in c.params:
            if not type(p).__name__.endswith("Option"):
                continue
            if p.is_flag:
                kind = "flag"
            else:
                ann = getattr(getattr(p, "type_descriptor", None), "annotation", None)
                kind = getattr(ann, "__name__", str(ann)).replace("list", "str")
                kind += "[]" if p.multiple else ""
            for o in (*p.opts, *p.secondary_opts):
                kinds[o] = kind
        if hasattr(c, "commands"):          # a group: its own options (the program's --version)
            if set(kinds) - {"--help"}:
                out[path] = kinds
            for name, sub in c.commands.items():
                walk(sub, path + (name,))
            return
        out[path] = kinds
    walk(typer.main.get_command(typer_app), ())
    return out


def inconsistencies(table: dict[tuple, dict[str, str]], vocabulary: dict[str, str]) -> list:
    """What breaks the vocabulary in ``table`` (:func:`options`): names not in it, a name taking
    different kinds of value, a study without the shared options, a former name still there."""
    bad, kinds = [], {}
    for path, opts in table.items():
        cmd = " ".join(path)
        for name, kind in opts.items():
            if name == "--help":
                continue
            if name not in vocabulary:
                bad.append(f"{cmd}: {name} is not in the vocabulary")
            kinds.setdefault(name, {}).setdefault(kind, []).append(cmd)
        if path[:1] == ("study",):
            bad += [f"{cmd}: no {s}" for s in STUDY_SHARED if s not in opts]
        for old, new in DEPRECATED.get(path, {}).items():
            if old in opts:
                bad.append(f"{cmd}: the former name {old} is still an option")
            if new not in opts:
                bad.append(f"{cmd}: {old} is said to be {new}, which it does not take")
    for path, (now, _) in DEPRECATED_COMMANDS.items():
        cmd = " ".join(path)
        if now is not None and path in table:
            bad.append(f"{cmd}: merged into {' '.join(now)} but still a command")
        target = table.get(now or path)
        if target is None:
            bad.append(f"{cmd}: said to be {' '.join(now or path)}, which is not a command")
            continue
        for old, new in DEPRECATED.get(path, {}).items():
            missing = [t for t in new.split() if t.startswith("-") and t not in target]
            if missing:
                bad.append(f"{cmd}: {old} is said to be {new}, which {' '.join(now or path)} "
                           "does not take")
    for name, by_kind in kinds.items():
        if len(by_kind) > 1:
            bad.append(f"{name} takes different values: {by_kind}")
    return bad


def test_every_command_speaks_the_vocabulary():
    table = options(app)
    assert len(table) >= 30
    assert not inconsistencies(table, VOCABULARY)


def test_every_name_of_the_vocabulary_is_used():
    used = {name for opts in options(app).values() for name in opts}
    assert not set(VOCABULARY) - used


def test_the_check_fails_on_a_planted_inconsistency():
    """Self-test: a study that calls its start positions --n, takes --starts as a float
    somewhere else and lacks --units is caught, each on its own line."""
    planted = typer.Typer()
    study = typer.Typer()
    planted.add_typer(study, name="study")

    @study.command("one")
    def one(n: Annotated[int, typer.Option("--n")] = 3,
            set_: Annotated[Optional[list[str]], typer.Option("--set")] = None,
            profile: Annotated[Optional[str], typer.Option("--profile")] = None,
            grade: Annotated[float, typer.Option("--grade")] = 16.0,
            json_: Annotated[bool, typer.Option("--json")] = False) -> None:
        """One."""

    @study.command("two")
    def two(starts: Annotated[float, typer.Option("--starts")] = 3.0) -> None:
        """Two."""

    @planted.command("three")
    def three(starts: Annotated[int, typer.Option("--starts")] = 3) -> None:
        """Three."""

    bad = inconsistencies(options(planted), VOCABULARY)
    assert any("study one: --n is not in the vocabulary" in b for b in bad)
    assert any("study one: no --units" in b for b in bad)
    assert any(b.startswith("--starts takes different values") for b in bad)
    assert any("study two: no --set" in b for b in bad)


@pytest.mark.parametrize("argv, expect", [
    (["study", "plateau", "m.toml", "--n", "5"], ["study", "plateau", "m.toml", "--starts", "5"]),
    (["design", "m.toml", "--starts=20"], ["design", "m.toml", "--random=20"]),
    (["reproduce", "004", "--out", "x"], ["reproduce", "004", "--out-dir", "x"]),
    (["liquid", "surface", "--omega", "1, 2 rad/s", "--g", "9.8"],
     ["liquid", "surface", "--speeds", "1, 2 rad/s", "--gravity", "9.8"]),
    (["simulate", "m.toml", "--out", "r.nc"], ["simulate", "m.toml", "--out", "r.nc"]),
    (["study", "plateau", "--", "--n"], ["study", "plateau", "--", "--n"]),
])
def test_former_names_are_rewritten_for_their_command_only(argv, expect):
    out, warnings = rewrite_deprecated(argv)
    assert out == expect
    assert len(warnings) == (0 if out == argv else len({a.partition("=")[0] for a in argv}
                                                       - {a.partition("=")[0] for a in out}))


@pytest.mark.parametrize("argv, expect, said", [
    (["analyze", "response", "w", "--speed", "9"], ["response", "w", "--speed", "9"],
     ["analyze response"]),
    (["analyze", "tolerance", "w", "--residual-fraction=0.1", "--grade", "6"],
     ["study", "tolerances", "w", "--method", "000", "--residual-fraction=0.1", "--grade", "6"],
     ["analyze tolerance", "analyze tolerance --residual-fraction"]),
    (["analyze", "tolerance", "w", "--fraction", "0.1"],
     ["study", "tolerances", "w", "--method", "000", "--residual-fraction", "0.1"],
     ["analyze tolerance", "analyze tolerance --fraction"]),
    (["liquid", "simulate", "--omega", "1:2:3"], ["liquid", "simulate", "--speeds", "1:2:3"],
     ["liquid simulate", "liquid simulate --omega"]),
])
def test_merged_commands_are_rewritten_to_the_command_now(argv, expect, said):
    out, warnings = rewrite_deprecated(argv)
    assert out == expect
    assert [w.split(" is deprecated")[0] for w in warnings] == [f"warning: {x}" for x in said]


def test_a_merged_command_that_is_still_a_command_is_caught():
    """Self-test of the merged-command check: a planted group still holding its former
    command, and a merge into a command that does not exist, are both reported."""
    planted = typer.Typer()
    group = typer.Typer()
    planted.add_typer(group, name="analyze")

    @group.command("response")
    def response(json_: Annotated[bool, typer.Option("--json")] = False) -> None:
        """Response."""

    @group.command("bounds")
    def bounds(json_: Annotated[bool, typer.Option("--json")] = False) -> None:
        """Bounds."""

    bad = inconsistencies(options(planted), VOCABULARY)
    assert "analyze response: merged into response but still a command" in bad
    assert "analyze response: said to be response, which is not a command" in bad


def test_a_former_name_still_works_and_says_what_to_use(capsys):
    code, out, err = run_main(capsys, ["study", "immobility", "examples/centrifuge.toml",
                                       "--quick", "--n-conf", "3", "--json"])
    assert code == 0, err
    assert err.strip().splitlines()[0] == ("warning: study immobility --n-conf is deprecated: "
                                           "use --starts (the old name goes in 0.4.0)")
    code, now, err = run_main(capsys, ["study", "immobility", "examples/centrifuge.toml",
                                       "--quick", "--starts", "3", "--json"])
    assert code == 0 and "warning" not in err
    drop = lambda d: {k: v for k, v in d.items() if k != "wall_time_s"}      # noqa: E731
    assert drop(json.loads(out)) == drop(json.loads(now))
    code, _, err = run_main(capsys, ["study", "immobility", "examples/centrifuge.toml",
                                     "--n-conf", "1"])
    assert code == 2 and "--starts = 1" in err          # the error names the option's name now


@pytest.mark.parametrize("argv, expect", [
    (["study", "speed-map", "m.toml", "--grade", "6.3", "--quick"],
     ["study", "speed-map", "m.toml", "--quick"]),
    (["study", "speed-map", "m.toml", "--grade=6.3"], ["study", "speed-map", "m.toml"]),
    (["study", "plateau", "m.toml", "--grade", "6.3"], ["study", "plateau", "m.toml", "--grade",
                                                         "6.3"]),
])
def test_an_option_without_effect_is_dropped_with_its_value_and_said(argv, expect):
    out, warnings = rewrite_deprecated(argv)
    assert out == expect
    if out != argv:
        assert warnings == ["warning: study speed-map --grade has no effect (its verdict is "
                            "whether the balanced state exists and is stable, which no target "
                            "grade changes); it goes in 0.4.0"]
    else:
        assert warnings == []
