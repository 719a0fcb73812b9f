"""Fuzzing bad input (hypothesis): generated bad configs, ``--set`` overrides, sweep files and
command-line arguments. Each one must exit 2 with exactly one stderr line ``error: ...`` naming
the field (and no traceback, no hang, nothing created).

Every case goes through the real entry point ``autobalance.cli.main`` in this process (the
console script is that function), so usage errors are included. The number of generated cases
is counted and printed (``-s`` shows it) so the closing note can give it.
"""
from __future__ import annotations

import json
import math
import tomllib

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st

from autobalance.cli import main
from autobalance.config import KINDS, PROFILE_KINDS, SECTIONS, preset_path

# ~280 generated cases through the real entry point: 3-8 s per test on 2 cores (make test).
pytestmark = pytest.mark.slow

COUNT: dict[str, int] = {}
FUZZ = settings(max_examples=60, deadline=None, derandomize=True,
                suppress_health_check=[HealthCheck.function_scoped_fixture,
                                       HealthCheck.too_slow])

# a sample value of each physical kind, in units that are wrong for every *other* dimensioned kind
UNIT_OF = {"mass": "3 kg", "unbalance": "3 g*m", "inertia": "3 kg*m^2",
           "rot_damping": "3 N*m*s/rad", "stiffness": "3 N/mm", "damping": "3 N*s/m",
           "force": "3 N", "torque": "3 N*m*s", "length": "3 mm", "velocity": "3 mm/s",
           "acceleration": "3 m/s^2", "speed": "3 rpm", "time": "3 s", "volume": "3 ml",
           "density": "3 kg/m^3", "kin_viscosity": "3 cSt"}
DIMLESS = {"angle", "ratio", "speed"}   # rpm, deg and bare ratios are all 1/s or 1: not "wrong"


def run_main(capsys, args) -> tuple[int, str, str]:
    capsys.readouterr()
    with pytest.raises(SystemExit) as e:
        main([str(a) for a in args])
    out = capsys.readouterr()
    return e.value.code, out.out, out.err


def assert_one_line(code, out, err, *needles):
    lines = err.strip().splitlines()
    assert code == 2, (code, err, out[:300])
    assert len(lines) == 1, err
    assert lines[0].startswith("error:"), err
    for n in needles:
        assert n in lines[0], (n, err)
    assert "Traceback" not in err


def count(kind: str) -> None:
    COUNT[kind] = COUNT.get(kind, 0) + 1


def wrong_value(kind: str, shape: str):
    """Values that no field of this kind and shape may accept."""
    always = [st.just("nan"), st.just("inf"), st.just("-inf"), st.just("abc"),
              st.just("3 wibbles"), st.just({"a": 1}), st.just(""),
              st.text(alphabet="!@#$%^&|~", min_size=1, max_size=5)]
    if kind == "int":
        return st.one_of(*always, st.just(1.5), st.just("two"), st.just(float("nan")),
                         st.just(True))
    if kind == "bool":
        return st.one_of(st.just(3), st.just("yes please"), st.just([1]), st.just({"a": 1}))
    if kind == "text":
        return st.one_of(st.just(5), st.just("no-such-choice-xyz"), st.just([1]),
                         st.just({"a": 1}))
    wrong_units = [u for k, u in UNIT_OF.items()
                   if k != kind and not (kind in DIMLESS and k in DIMLESS)
                   and KINDS[k][0] != KINDS[kind][0]]
    opts = always + [st.sampled_from(wrong_units), st.just(True), st.just(float("nan")),
                     st.just(float("inf"))]
    if shape == "scalar":
        opts.append(st.just([1.0, 2.0]))
    return st.one_of(*opts)


FIELDS = [(sec, key, f) for sec, keys in SECTIONS.items() for key, f in keys.items()
          if f.shape != "pairs" and f.kind != "text" or (f.kind == "text" and f.choices)]
TSR_FIELDS = [("profile", k, f) for k, f in PROFILE_KINDS["tsr"].items()]


@st.composite
def bad_field(draw, fields=tuple(FIELDS + TSR_FIELDS)):
    sec, key, f = draw(st.sampled_from(fields))
    return sec, key, draw(wrong_value(f.kind, f.shape))


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, float) and not math.isfinite(v):
        return {"nan": "nan", "inf": "inf", "-inf": "-inf"}[repr(v)]
    if isinstance(v, dict):
        return "{ " + ", ".join(f"{k} = {toml_value(x)}" for k, x in v.items()) + " }"
    if isinstance(v, list):
        return "[" + ", ".join(toml_value(x) for x in v) + "]"
    return json.dumps(v)


def preset_with(sec: str, key: str, value) -> str:
    """The 004 preset's TOML (003's liquid bench for a ``[liquid]`` key) with ``[sec] key``
    replaced by ``value``."""
    name = "leblanc_003" if sec == "liquid" else "vub_jeffcott_004"
    raw = tomllib.loads(preset_path(name).read_text())
    raw.setdefault(sec, {})[key] = value
    lines = []
    for k, v in raw.items():
        if not isinstance(v, dict):
            lines.append(f"{k} = {toml_value(v)}")
    for s, table in raw.items():
        if isinstance(table, dict):
            lines.append(f"[{s}]")
            lines += [f"{k} = {toml_value(v)}" for k, v in table.items()]
    return "\n".join(lines) + "\n"


# -- configs ------------------------------------------------------------------------------------
@FUZZ
@given(bad=bad_field())
def test_fuzz_bad_config_file(tmp_path, capsys, bad):
    sec, key, value = bad
    cfg = tmp_path / "bad.toml"
    cfg.write_text(preset_with(sec, key, value))
    code, out, err = run_main(capsys, ["show", cfg])
    count("config files")
    assert_one_line(code, out, err, f"{sec}.{key}")


@FUZZ
@given(bad=bad_field())
def test_fuzz_bad_set_override(capsys, bad):
    sec, key, value = bad
    base = "leblanc_003" if sec == "liquid" else "vub_jeffcott_004"
    code, out, err = run_main(capsys, ["show", base, "--set", f"{sec}.{key}={toml_value(value)}"])
    count("--set overrides")
    assert_one_line(code, out, err, f"{sec}.{key}")


@FUZZ
@given(path=st.one_of(
    st.from_regex(r"[a-z]{1,8}\.[a-z_]{1,12}", fullmatch=True),
    st.sampled_from(["rotor", "rotor.", ".mass", "rotor.mass.x", "profile.nope", "x.y.z"])),
    value=st.sampled_from(["1", "'2 kg'", "[1, 2]"]))
def test_fuzz_unknown_set_path(capsys, path, value):
    sec, _, key = path.partition(".")
    known = sec in SECTIONS and key in SECTIONS[sec] or sec == "profile" and any(
        key in k for k in PROFILE_KINDS.values())
    if known:
        return
    code, out, err = run_main(capsys, ["show", "vub_jeffcott_004", "--set", f"{path}={value}"])
    count("--set overrides")
    assert_one_line(code, out, err, path.split("=")[0] if "." in path else path)


# -- sweep files -----------------------------------------------------------------------------------
GOOD = {"sweep": {"base": "vub_jeffcott_004", "batch_size": 4},
        "grid": {"balancer.rolling_resistance": [0.001, 0.002]},
        "monte_carlo": {"kind": "start_grid", "n": 3}}
SWEEP_BAD = [
    (("sweep", "batch_size"), st.sampled_from([0, -1, 1.5, "x", True]), "sweep.batch_size"),
    (("sweep", "base"), st.sampled_from([3, "no_such_preset", "missing.toml"]), "base"),
    (("sweep", "set"), st.sampled_from(["rotor.mass=1", [1], ["rotor.mass"],
                                        ["rotor.mass=abc"]]), "set"),
    (("sweep", "bogus"), st.just(1), "sweep.bogus"),
    (("monte_carlo", "kind"), st.sampled_from(["lhs", 3, ""]), "monte_carlo.kind"),
    (("monte_carlo", "n"), st.sampled_from([0, -5, 2.5, "ten", 10**6]), "monte_carlo.n"),
    (("outputs", "history_dt"), st.sampled_from(["-1 s", "3 kg", "nan", "x"]),
     "outputs.history_dt"),
    (("grid", "balancer.rolling_resistance"), st.sampled_from([[], [[1]], [0.1, 0.1],
                                                               ["3 kg"], [5.0], "x"]),
     "rolling_resistance"),
    (("grid", "rotor.nope"), st.just([1, 2]), "rotor.nope"),
    (("grid", "profile.plateau"), st.sampled_from([["200 Hz"], ["-3 Hz"], ["3 kg"]]),
     "profile.plateau"),
    (("grid", "balancer.n_balls"), st.sampled_from([[10**9], [1.5], ["x"]]), "n_balls"),
    (("bogus", None), st.just({"a": 1}), "bogus"),
]


@FUZZ
@given(case=st.sampled_from(range(len(SWEEP_BAD))), data=st.data())
def test_fuzz_bad_sweep_file(tmp_path, capsys, case, data):
    (sec, key), values, needle = SWEEP_BAD[case]
    value = data.draw(values)
    d = json.loads(json.dumps(GOOD))
    if key is None:
        d[sec] = value
    else:
        d.setdefault(sec, {})[key] = value
    lines = []
    for s, table in d.items():
        lines.append(f"[{s}]")
        lines += [f'"{k}" = {toml_value(v)}' for k, v in table.items()]
    spec = tmp_path / "sweep.toml"
    spec.write_text("\n".join(lines) + "\n")
    store = tmp_path / "store"
    code, out, err = run_main(capsys, ["sweep", spec, "--store", store, "--executor", "serial"])
    count("sweep files")
    assert_one_line(code, out, err, needle)
    assert not store.exists()


# -- command-line arguments ----------------------------------------------------------------------
@FUZZ
@given(case=st.sampled_from([
    (["sweep", "{spec}", "--store", "{store}", "--grade"], ["nan", "-5", "0", "inf", "x"],
     "--grade"),
    (["sweep", "{spec}", "--store", "{store}", "--workers"], ["0", "-1", "x", "100000000"],
     "--workers"),
    (["sweep", "{spec}", "--store", "{store}", "--executor"], ["gpu", ""], "executor"),
    (["sweep", "{spec}", "--store"], ["{spec}"], "--store"),
    (["response", "vub_jeffcott_004", "--speeds"],
     ["0:1500 rpm:1e12", "1:0:10", "a:b:c", "0:100", "0:1 kg:10", "0:100:1"], "--speeds"),
    (["study", "immobility", "vub_jeffcott_004", "--n-conf"], ["0", "-3", "1000000", "x"],
     "--n-conf"),
    (["simulate", "vub_jeffcott_004", "--out"], ["{dir}", "{dir}/none/x.nc"], "--out"),
    (["simulate", "vub_jeffcott_004", "--plot"], ["{dir}/x.txt", "{dir}"], "--plot"),
    (["simulate", "vub_jeffcott_004", "--profile"], ["warp", "7"], "profile"),
    (["show"], ["no_such_preset"], "unknown preset 'no_such_preset'"),
    (["show"], ["{dir}/missing.toml"], "missing.toml"),
    (["reproduce"], ["no-such-target"], "no-such-target"),
]), pick=st.integers(0, 5))
def test_fuzz_bad_cli_arguments(tmp_path, capsys, case, pick):
    prefix, values, needle = case
    spec = tmp_path / "ok.toml"
    spec.write_text('[sweep]\nbase = "vub_jeffcott_004"\nbatch_size = 4\n'
                    '[monte_carlo]\nkind = "start_grid"\nn = 2\n')
    subst = {"{spec}": str(spec), "{store}": str(tmp_path / "store"), "{dir}": str(tmp_path)}

    def fill(a):
        for k, v in subst.items():
            a = a.replace(k, v)
        return a
    args = [fill(a) for a in prefix] + [fill(values[pick % len(values)])]
    code, out, err = run_main(capsys, args)
    count("command-line arguments")
    assert_one_line(code, out, err, needle)
    assert not (tmp_path / "store").exists()


def test_fuzz_counts_reported():
    """Runs last in this module: prints how many cases were generated (for the note)."""
    total = sum(COUNT.values())
    print(f"\nfuzzed bad inputs: {total} ({', '.join(f'{k}: {v}' for k, v in COUNT.items())})")
    assert total >= 200
