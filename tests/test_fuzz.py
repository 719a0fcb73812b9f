"""Fuzzing input (hypothesis): generated bad configs, ``--set`` overrides, sweep files and
command-line arguments; input files that are not small UTF-8 TOML texts (devices, FIFOs,
directories, large, latin-1 and binary files); TOML nested thousands deep; values that are
expressions rather than a number and units; task files of a sweep store that are not its own
(copied from another machine's store, edited, cut short), which a resume recomputes. Each one must exit 2 with exactly one stderr line
``error: ...`` naming the field (and no traceback, no hang, nothing created). Two classes are
properties of good input: every rotational speed unit reads as written, and a range's unit
written once applies to both ends wherever it is written.

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

from autobalance.config import KINDS, PROFILE_KINDS, SECTIONS, preset_path

from conftest import run_main  # noqa: E402

# ~700 generated cases through the real entry point: 3-8 s per test on 2 cores (make test).
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
    (["study", "immobility", "vub_jeffcott_004", "--starts"], ["0", "-3", "1000000", "x"],
     "--starts"),
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


# -- rotational speed units ------------------------------------------------------------------------
#: Units of a rotational speed and their factor to rad/s: revolutions per time (a pure inverse
#: time counts revolutions, as on drawings and motor plates) or an angle per time.
SPEED_UNITS = {"rpm": 2 * math.pi / 60, "rev/min": 2 * math.pi / 60, "min^-1": 2 * math.pi / 60,
               "1/min": 2 * math.pi / 60, "/min": 2 * math.pi / 60, "Hz": 2 * math.pi,
               "1/s": 2 * math.pi, "s^-1": 2 * math.pi, "rps": 2 * math.pi,
               "rev/s": 2 * math.pi, "kHz": 2000 * math.pi, "rad/s": 1.0,
               "deg/s": math.pi / 180, "rad/min": 1 / 60}


@FUZZ
@given(value=st.floats(0.5, 5000.0), unit=st.sampled_from(sorted(SPEED_UNITS)))
def test_fuzz_rotational_units(capsys, value, unit):
    """Every speed unit reads as written: the washer's constant speed in the JSON of ``show``
    is the value times the unit's factor to rad/s (relative 1e-12)."""
    text = f"{value:.6g} {unit}"
    code, out, err = run_main(capsys, ["show", "washer_000", "--set", f"profile.speed={text}",
                                       "--json"])
    count("rotational units")
    assert code == 0, err
    got = json.loads(out)["profile"]["speed_rad_s"]
    assert math.isclose(got, float(f"{value:.6g}") * SPEED_UNITS[unit], rel_tol=1e-12), (text, got)


# -- ranges -------------------------------------------------------------------------------------
RANGE_UNITS = {"rpm": 2 * math.pi / 60, "min^-1": 2 * math.pi / 60, "Hz": 2 * math.pi,
               "rad/s": 1.0}


@FUZZ
@given(lo=st.integers(1, 400), span=st.integers(1, 1000), n=st.integers(2, 40),
       unit=st.sampled_from(sorted(RANGE_UNITS)), where=st.sampled_from(["hi", "lo", "both"]))
def test_fuzz_range_grammar(capsys, lo, span, n, unit, where):
    """``LO:HI unit:N``: a unit written once applies to both ends, wherever it is written."""
    hi = lo + span
    text = {"hi": f"{lo}:{hi} {unit}:{n}", "lo": f"{lo} {unit}:{hi}:{n}",
            "both": f"{lo} {unit}:{hi} {unit}:{n}"}[where]
    code, out, err = run_main(capsys, ["response", "vub_jeffcott_004", "--speeds", text, "--json"])
    count("ranges")
    assert code == 0, (text, err)
    f = RANGE_UNITS[unit]
    got = json.loads(out)["speed_rad_s"]
    assert len(got) == n
    assert math.isclose(got[0], lo * f, rel_tol=1e-12) and math.isclose(got[-1], hi * f,
                                                                         rel_tol=1e-12), text


@FUZZ
@given(text=st.sampled_from(["100:1500 rpm:0", "100:1500 rpm:1", "1500:100 rpm:10",
                             "100 kg:1500 rpm:10", "100 rpm:1500 kg:10", "100:1500 rpm:x",
                             "100:1500 rpm:2.5", "100:1500:10:3", ":1500 rpm:10",
                             "100:1500 rpm:1e12", "100 rpm:1500 Hz:nan", "a:b:c"]),
       option=st.sampled_from([("response", "vub_jeffcott_004", "--speeds"),
                               ("study", "speed-map", "examples/toploader.toml", "--speeds")]))
def test_fuzz_bad_ranges(capsys, text, option):
    code, out, err = run_main(capsys, [*option, text])
    count("ranges")
    assert_one_line(code, out, err, option[-1])


# -- input files that are not small TOML texts --------------------------------------------------
def _odd_file(tmp_path, kind: str) -> str:
    import os

    if kind == "fifo":
        path = tmp_path / "pipe.toml"
        if not path.exists():
            os.mkfifo(path)
        return str(path)
    if kind == "directory":
        return str(tmp_path)
    if kind == "large":
        path = tmp_path / "large.toml"
        path.write_text("# padding\n" * 300_000)          # 3 MB of comments
        return str(path)
    if kind == "latin-1":
        path = tmp_path / "latin.toml"
        path.write_bytes('name = "Gr\u00f6\u00dfe"\n'.encode("latin-1"))
        return str(path)
    if kind == "binary":
        path = tmp_path / "binary.toml"
        path.write_bytes(bytes(range(256)) * 8)
        return str(path)
    return kind                                          # a device path


ODD_FILES = ["/dev/zero", "/dev/urandom", "/dev/null", "fifo", "directory", "large", "latin-1",
             "binary"]


def _no_hang(seconds: int = 20):
    """An alarm that turns a hang into a failure of the test (a blocking read of a FIFO)."""
    import signal

    def boom(*_):
        raise AssertionError(f"hung for {seconds} s")
    signal.signal(signal.SIGALRM, boom)
    signal.alarm(seconds)


@FUZZ
@given(kind=st.sampled_from(ODD_FILES), role=st.sampled_from(["config", "sweep"]))
def test_fuzz_odd_input_files(tmp_path, capsys, kind, role):
    import signal

    path = _odd_file(tmp_path, kind)
    args = (["show", path] if role == "config" else
            ["sweep", path, "--store", str(tmp_path / "store"), "--executor", "serial"])
    _no_hang()
    try:
        code, out, err = run_main(capsys, args)
    finally:
        signal.alarm(0)
    count("odd input files")
    assert_one_line(code, out, err)
    assert not (tmp_path / "store").exists()


# -- deep nesting -------------------------------------------------------------------------------
@FUZZ
@given(depth=st.integers(40, 6000), shape=st.sampled_from(["array", "table"]),
       where=st.sampled_from(["config", "sweep", "--set"]))
def test_fuzz_deep_nesting(tmp_path, capsys, depth, shape, where):
    value = ("[" * depth + "1" + "]" * depth if shape == "array"
             else "{a = " * depth + "1" + " }" * depth)
    if where == "--set":
        args = ["show", "vub_jeffcott_004", "--set", f"rotor.mass={value}"]
    elif where == "config":
        cfg = tmp_path / "deep.toml"
        cfg.write_text(preset_path("vub_jeffcott_004").read_text() + f"\n[extra]\nx = {value}\n")
        args = ["show", str(cfg)]
    else:
        spec = tmp_path / "deep-sweep.toml"
        spec.write_text(f'[sweep]\nbase = "vub_jeffcott_004"\nx = {value}\n')
        args = ["sweep", str(spec), "--store", str(tmp_path / "store"), "--executor", "serial"]
    code, out, err = run_main(capsys, args)
    count("deep nesting")
    assert_one_line(code, out, err)
    assert "RecursionError" not in err and "maximum recursion" not in err


# -- values that are expressions, not a number and units ----------------------------------------
@st.composite
def expression(draw):
    a, b = draw(st.integers(2, 99)), draw(st.integers(2, 99))
    unit = draw(st.sampled_from(["kg", "g", "m", "mm"]))
    return draw(st.sampled_from([
        f"{a}**{b}**{b} {unit}", f"{a}**{b * 10} {unit}", f"{a}e3**{b} {unit}",
        f"({a}+{b}) {unit}", f"{a} * {b} {unit}", f"{a} {unit}**{b * 100}",
        f"{a} {unit}^{b + 4}", f"exp({a}) {unit}", f"__import__ {unit}",
        f"{a} {unit}{'*' * b}", f"{a}/{b} {unit}", f"{a} {unit}/0"]))


@FUZZ
@given(text=expression())
def test_fuzz_expressions_are_refused_at_once(capsys, text):
    """pint would evaluate these (``9**9**9`` never ends): only a number and a unit
    expression with small integer powers is read."""
    import signal
    import time

    t0 = time.perf_counter()
    _no_hang(10)
    try:
        code, out, err = run_main(capsys, ["show", "vub_jeffcott_004", "--set",
                                           f"rotor.mass={json.dumps(text)}"])
    finally:
        signal.alarm(0)
    count("expressions")
    assert_one_line(code, out, err, "rotor.mass")
    assert time.perf_counter() - t0 < 5.0


# -- task files that do not belong to the store ----------------------------------------------------
@pytest.fixture(scope="module")
def two_stores(tmp_path_factory):
    """The TINY sweep (20 runs in 7 task files) of the 004 preset and of the same preset with
    another rotor mass: the same run ranges, so the same task file names and shapes."""
    from conftest import TINY_SWEEP

    from autobalance.sweep import load_spec, sweep

    root = tmp_path_factory.mktemp("two-stores")
    out = {}
    for key, mass in (("ours", "16.53 kg"), ("theirs", "17 kg")):
        d = root / key
        (d / "cfg").mkdir(parents=True)
        text = preset_path("vub_jeffcott_004").read_text()
        (d / "cfg" / "base.toml").write_text(text.replace('mass = "16.53 kg"', f'mass = "{mass}"'))
        (d / "sweep.toml").write_text(TINY_SWEEP.replace('base = "vub_jeffcott_004"',
                                                         'base = "cfg/base.toml"'))
        out[key] = (d, sweep(load_spec(d / "sweep.toml"), d / "store", executor="serial",
                             progress=False))
    return out


@FUZZ
@given(picks=st.lists(st.tuples(st.integers(0, 6), st.sampled_from(["foreign", "edited",
                                                                    "truncated"])),
                      min_size=1, max_size=3, unique_by=lambda t: t[0]))
def test_fuzz_foreign_task_files(tmp_path, capsys, two_stores, picks):
    """Task files copied from another machine's store, edited and saved again, or cut short:
    a resume moves each aside (one warning line each) and recomputes its runs, and the result
    is the clean run's bit for bit."""
    import shutil

    import numpy as np
    from conftest import assert_bit_identical

    from autobalance.sweep import load_spec, sweep

    (ours, clean), (theirs, _) = two_stores["ours"], two_stores["theirs"]
    work = tmp_path / f"case-{len(COUNT)}-{sum(COUNT.values())}"
    shutil.copytree(ours, work)
    shutil.rmtree(work / "store" / "result.zarr", ignore_errors=True)
    names = sorted(p.name for p in (work / "store" / "tasks").glob("r*.npz"))
    for index, how in picks:
        victim = work / "store" / "tasks" / names[index]
        if how == "foreign":
            shutil.copyfile(theirs / "store" / "tasks" / names[index], victim)
        elif how == "edited":
            with np.load(victim) as z:
                arrays = {k: z[k] for k in z.files}
            arrays["grade_G"] = np.nextafter(arrays["grade_G"], 0.0)     # one ulp better
            with open(victim, "wb") as f:
                np.savez(f, **arrays)
        else:
            victim.write_bytes(victim.read_bytes()[: victim.stat().st_size // 2])
    capsys.readouterr()
    ds = sweep(load_spec(work / "sweep.toml"), work / "store", executor="serial",
               progress=False, resume=True)
    count("foreign task files")
    warnings = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("warning:")]
    assert len(warnings) == len(picks), warnings
    assert_bit_identical(ds, clean)


def test_fuzz_counts_reported():
    """Runs last in this module: prints how many cases were generated (for the note)."""
    total = sum(COUNT.values())
    print(f"\nfuzzed inputs: {total} ({', '.join(f'{k}: {v}' for k, v in COUNT.items())})")
    assert total >= 200
