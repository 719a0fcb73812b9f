"""The library owns the defaults: every option a study command shares with its function of
:mod:`autobalance.studies` has the same default in both, or the command leaves it to the
library (None). A default written twice that drifted (the command's 100 starts against the
function's 20) is found here."""
from __future__ import annotations

import inspect

import pytest
from typer.main import get_command

from autobalance import studies
from autobalance.cli import app
from autobalance.studies._runup import BALANCING_FRACTION

#: Command -> (its function, {the command's parameter: the function's, where they differ}).
PAIRS = {
    ("study", "start-positions"): (studies.start_positions, {"n": "starts", "samples": "random"}),
    ("study", "unbalance-range"): (studies.unbalance_range, {"n": "starts"}),
    ("study", "plateau"): (studies.plateau, {"n": "starts"}),
    ("study", "speed-map"): (studies.speed_map, {"damping": "c_r"}),
    ("study", "immobility"): (studies.immobility, {"n_conf": "starts"}),
    ("study", "sensitivity"): (studies.sensitivity, {"n": "starts", "samples": "random",
                                                     "vary": "variants"}),
    ("study", "runup"): (studies.runup, {"law": "laws", "fraction": "threshold"}),
    ("study", "fill-map"): (studies.fill_map, {}),
    ("study", "tolerances"): (studies.tolerances, {}),
    ("design",): (studies.design, {"samples": "random"}),
}
#: Where the function's None means a value of the library, that value: the command may write
#: it out (its help shows it), but only as the library has it.
LIBRARY_VALUES = {("study", "runup", "threshold"): BALANCING_FRACTION}


def _command(path: tuple[str, ...]):
    cmd = get_command(app)
    for name in path:
        cmd = cmd.commands[name]
    return cmd


def _same(cli, api) -> bool:
    """The command's default against the function's: a comma list of factors ("1") is the
    function's tuple of floats."""
    if isinstance(cli, str) and isinstance(api, tuple):
        return tuple(float(x) for x in cli.split(",")) == tuple(map(float, api))
    return cli == api


def drifted(path, fn, rename) -> list[str]:
    """``command --option: CLI default != library default`` for each default written twice
    and different."""
    sig = inspect.signature(fn).parameters
    out = []
    for p in _command(path).params:
        name = rename.get(p.name, p.name)
        if name not in sig or p.default is None:
            continue
        api = LIBRARY_VALUES.get((*path, name), sig[name].default)
        if not _same(p.default, api):
            out.append(f"{' '.join(path)} {p.opts[0]}: {p.default!r} != {api!r}")
    return out


@pytest.mark.parametrize("path", sorted(PAIRS), ids=" ".join)
def test_a_commands_defaults_are_its_functions(path):
    fn, rename = PAIRS[path]
    assert drifted(path, fn, rename) == []


def test_the_check_finds_a_default_written_twice_that_drifted():
    """Self-test: a function whose grade default is not the command's 16."""
    def planted(machine, *, grade=10.0, z=2.0):
        """A study."""
    found = drifted(("study", "sensitivity"), planted, {})
    assert found == ["study sensitivity --grade: 16.0 != 10.0"]


def test_every_study_command_is_paired():
    group = _command(("study",))
    assert {("study", c) for c in group.commands if not group.commands[c].hidden} <= set(PAIRS)
