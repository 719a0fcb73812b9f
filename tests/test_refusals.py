"""Values and combinations a command must refuse, or report as not computed, instead of
answering something silently wrong: each through the real entry point ``autobalance.cli.main``
in this process, one line on stderr naming the option as the user typed it, exit code 2.

* ``--split`` of ``study tolerances``: only the causes it designs (and "other"), summing to 1,
  with a share for at least one designed cause.
* A target grade finer than any balancer can be built to says "unreachable".
* Quantities a run did not compute are null (``options.save_dt < 0`` keeps only the
  checkpoints: no settling time or revolutions).
* Conflicting options (``--n`` with ``--random``, ``--quick`` with ``--full``) and counts out
  of range (``liquid spinup --cells 0``) are refused; an error about a library field the user
  set through an option names the option (``--n``, ``--starts``, ``--cells``).
* The help of every command shows its text as written (no markup eaten, no ``:b:`` turned
  into an emoji).
"""
from __future__ import annotations

import json
import re

import pytest

from autobalance.cli import app

from conftest import run_main  # noqa: E402


def refused(capsys, args, *needles) -> str:
    code, out, err = run_main(capsys, args)
    lines = err.strip().splitlines()
    assert code == 2, (code, err, out[:300])
    assert len(lines) == 1 and lines[0].startswith("error:"), err
    assert "Traceback" not in err
    for n in needles:
        assert n in lines[0], (n, err)
    return lines[0]


# -- study tolerances --------------------------------------------------------------------------
@pytest.mark.parametrize("split, needle", [
    ("wobble=1", "unknown cause 'wobble'"),
    ("eccentricity=0.5,wobble=0.5", "unknown cause 'wobble'"),
    ("other=1", "no share to eccentricity, rolling or friction"),
    ("eccentricity=0.5,rolling=0.6", "must sum to 1"),
    ("eccentricity=-0.5,rolling=1.5", "must be >= 0"),
    ("eccentricity=x", "expected cause=share pairs"),
])
def test_split_refuses_unknown_causes_and_empty_designs(capsys, split, needle):
    refused(capsys, ["study", "tolerances", "examples/toploader.toml", "--split", split],
            "--split", needle)


def test_split_accepts_the_causes_it_designs(capsys):
    code, out, err = run_main(capsys, ["study", "tolerances", "examples/toploader.toml",
                                       "--split", "eccentricity=0.6,rolling=0.4", "--json"])
    assert code == 0, err
    res = json.loads(out)
    assert res["split"] == {"eccentricity": 0.6, "rolling": 0.4, "friction": 0.0}
    assert res["max_suspension_friction_N"] == 0.0 and res["max_eccentricity_m"] > 0


def test_a_grade_finer_than_any_balancer_is_unreachable(capsys):
    code, out, err = run_main(capsys, ["study", "tolerances", "examples/toploader.toml",
                                       "--grade", "0.001", "--json"])
    assert code == 0, err
    res = json.loads(out)
    assert res["feasible"] and not res["reachable"]
    assert len(res["unreachable"]) == 2            # eccentricity and rolling resistance
    assert res["max_eccentricity_m"] < 0.08e-6 and res["max_rolling_resistance"] < 1e-5
    code, out, err = run_main(capsys, ["study", "tolerances", "examples/toploader.toml",
                                       "--grade", "0.001"])
    lines = [ln for ln in out.splitlines() if "unreachable" in ln]
    assert len(lines) == 2 and "ISO 3290-1" in lines[0], out


def test_a_coarse_grade_is_reachable(capsys):
    code, out, err = run_main(capsys, ["study", "tolerances", "examples/toploader.toml",
                                       "--grade", "16", "--json"])
    assert code == 0, err
    res = json.loads(out)
    assert res["reachable"] and res["unreachable"] == []
    assert res["max_eccentricity_m"] > 0.08e-6


# -- what a run did not compute is null ---------------------------------------------------------
def test_checkpoints_only_leave_settling_and_revolutions_null(capsys):
    code, out, err = run_main(capsys, ["simulate", "vub_jeffcott_004", "--set",
                                       "options.save_dt=-1", "--json"])
    assert code == 0, err
    res = json.loads(out)
    assert res["ball_settle_time_s"] == [None, None]
    assert res["ball_revolutions"] == [None, None]
    code, out, err = run_main(capsys, ["simulate", "vub_jeffcott_004", "--json"])
    res = json.loads(out)
    assert all(isinstance(v, float) for v in res["ball_settle_time_s"] + res["ball_revolutions"])
    assert any(abs(v) > 0.01 for v in res["ball_revolutions"])


# -- resources ----------------------------------------------------------------------------------
def test_a_fine_save_dt_is_refused_by_the_whole_history(capsys, monkeypatch):
    """The guard counts the history with what is derived from it, not the largest array: 1 us
    on 004's 90 s run is 9e7 samples, 0.7 GB of state alone but ~36 GiB in all."""
    monkeypatch.setenv("AUTOBALANCE_MAX_MEMORY", "8 GiB")
    refused(capsys, ["simulate", "vub_jeffcott_004", "--set", "options.save_dt=1 us"],
            "options.save_dt", "derived", "GiB")


def test_a_huge_duration_names_the_duration(capsys):
    refused(capsys, ["simulate", "vub_jeffcott_004", "--set", "profile.duration=1e308"],
            "profile.duration", "at most 1e+09 s")


# -- options ------------------------------------------------------------------------------------
def test_errors_name_the_option_typed(capsys):
    refused(capsys, ["study", "start-positions", "examples/centrifuge.toml", "--starts", "100000"],
            "--starts = 100000", "AUTOBALANCE_MAX_MEMORY")
    line = refused(capsys, ["design", "examples/toploader.toml", "--random", "100000000"],
                   "--random")
    assert "monte_carlo" not in line


@pytest.mark.parametrize("args, needle", [
    (["study", "start-positions", "examples/centrifuge.toml", "--starts", "5", "--random", "5"],
     "--starts = 5 and --random = 5"),
    (["study", "sensitivity", "examples/centrifuge.toml", "--starts", "5", "--random", "5"],
     "--starts = 5 and --random = 5"),
    (["reproduce", "--quick", "--full"], "--quick and --full"),
])
def test_conflicting_options_are_refused(capsys, tmp_path, args, needle):
    refused(capsys, args + (["--out-dir", str(tmp_path / "o")] if args[0] == "reproduce" else []),
            needle)
    assert not (tmp_path / "o").exists()


@pytest.mark.parametrize("cells", ["0", "3", "100000000"])
def test_liquid_cells_out_of_range_name_the_option(capsys, cells):
    refused(capsys, ["liquid", "spinup", "leblanc_washer", "--cells", cells],
            f"--cells = {cells}", "must be an integer")
    refused(capsys, ["liquid", "spinup", "leblanc_003", "--cells", cells], "--cells")


# -- help as written ----------------------------------------------------------------------------
def _commands():
    import typer.main

    def walk(cmd, path):
        subs = getattr(cmd, "commands", None)
        if subs:
            for name, sub in subs.items():
                yield from walk(sub, path + [name])
        else:
            yield path, cmd
    return list(walk(typer.main.get_command(app), []))


def test_every_help_shows_its_text_as_written(capsys):
    """Brackets (``[liquid]``) and colons (``a:b:n``) of every option's help survive the
    rendering: no markup is interpreted and no ``:name:`` becomes an emoji."""
    checked = 0
    for path, cmd in _commands():
        code, out, err = run_main(capsys, [*path, "--help"])
        assert code == 0, (path, err)
        flat = " ".join(out.split())
        assert all(ord(ch) < 0x2000 for ch in out), (path, [ch for ch in out if ord(ch) >= 0x2000])
        for p in cmd.params:
            text = getattr(p, "help", None) or ""
            for token in re.findall(r"\[[^\]\s]+\]|\S*:\S*:\S*", text):
                assert token in flat, (path, p.name, token)
                checked += 1
    assert checked >= 10
