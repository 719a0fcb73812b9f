"""``balancer.contact = "none"``: 004's point masses, which pass through each other and may
coincide, beside the compliant contact. They must agree where the balls never touch,
differ where they start together, and the sweep must not keep coincident points together by
an accident of symmetric arithmetic (docs/sweeps.md)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from autobalance.models import InitialState, ParameterError
from autobalance.simulate import simulate
from autobalance.studies._start_positions import compute_start_positions, load
from autobalance.sweep.plan import COINCIDENT_SPLIT, split_coincident


def _run(contact: str, angles, *sets, checkpoints_only: bool = False):
    """One simulation; ``checkpoints_only``: the outputs a sweep stores (with a dense history
    the slip jumps' windows end at its samples, docs/numerics/index.md)."""
    cfg = load("vub_jeffcott_004", [f"balancer.contact={contact}", *sets])
    o = dataclasses.replace(cfg.options, save_dt=-1.0) if checkpoints_only else cfg.options
    return simulate(cfg.system, cfg.spin, initial=InitialState(ball_angles=tuple(angles)),
                    options=o)


def _gap_deg(r) -> float:
    a = r.alpha[-1]
    return abs(math.degrees(np.angle(np.exp(1j * (a[0] - a[1])))))


def _plateau(ratio: float) -> str:
    wn = load("vub_jeffcott_004").system.natural_frequencies[0]
    return f"profile.plateau={ratio * wn!r}"


@pytest.mark.slow
def test_balls_that_never_touch_give_the_same_run_with_and_without_contact():
    a, b = _run("compliant", (0.5, 3.0)), _run("none", (0.5, 3.0))
    assert _gap_deg(a) > 60                                  # far apart all along
    assert a.grade_G[-1] == b.grade_G[-1]                    # bit for bit
    assert np.array_equal(a.alpha, b.alpha)


def test_points_may_coincide_and_pass_where_balls_may_not():
    with pytest.raises(ParameterError) as e:
        _run("compliant", (1.0, 1.0))
    assert e.value.field == "initial.ball_angles"
    r = _run("none", (1.0, 1.0))                             # 004: points may coincide
    assert r.grade_G[-1] > 0
    cfg = load("vub_jeffcott_004", ["balancer.contact=none"])
    assert cfg.system.balancer.contact_angle == 0.0
    with pytest.raises(Exception) as bad:
        load("vub_jeffcott_004", ["balancer.contact=sticky"])
    assert "balancer.contact" in str(bad.value) and "\n" not in str(bad.value)


def test_split_coincident_spreads_only_coincident_balls_symmetrically():
    d = split_coincident([1.0, 1.0 + 2 * math.pi, 3.0]) - np.array([1.0, 1.0 + 2 * math.pi, 3.0])
    assert d[0] == pytest.approx(-COINCIDENT_SPLIT / 2, rel=1e-6)
    assert d[1] == pytest.approx(COINCIDENT_SPLIT / 2, rel=1e-6) and d[2] == 0.0
    three = split_coincident([0.5, 0.5, 0.5]) - 0.5
    assert three == pytest.approx([-COINCIDENT_SPLIT, 0.0, COINCIDENT_SPLIT], rel=1e-6, abs=1e-15)
    assert np.array_equal(split_coincident([0.3, 2.0]), [0.3, 2.0])


@pytest.mark.slow
def test_an_unstable_coincident_pair_splits_in_the_sweep_and_a_stable_one_does_not():
    """At a 1.02 Omega_n plateau the coincident state is unstable: started exactly together the
    stick kernel keeps the two points together (its arithmetic is symmetric), 1e-9 rad apart
    they split (004's mechanism for TSR worsening runs). At 1.06 it is stable: the spread
    decays and the outcome is the coincident one."""
    exact = _run("none", (1.0, 1.0), _plateau(1.02))
    eps = _run("none", (1.0, 1.0 + COINCIDENT_SPLIT), _plateau(1.02))
    assert _gap_deg(exact) < 1e-6 and _gap_deg(eps) > 10.0
    assert abs(exact.grade_G[-1] - eps.grade_G[-1]) > 1.0
    stable = [_run("none", (1.0, 1.0 + e), _plateau(1.06)) for e in (0.0, COINCIDENT_SPLIT)]
    assert stable[0].grade_G[-1] == pytest.approx(stable[1].grade_G[-1], abs=1e-6)
    # the sweep's start grid (its diagonal starts both balls at one angle) spreads them
    ds = compute_start_positions(load("vub_jeffcott_004", ["balancer.contact=none",
                                                           _plateau(1.02)]),
                                 n=2, executor="serial")
    a = ds["start_angle"].values                              # (sample, ball)
    gaps = np.abs(np.angle(np.exp(1j * (a[:, 0] - a[:, 1]))))
    assert sorted(gaps)[:2] == pytest.approx([COINCIDENT_SPLIT] * 2, rel=1e-6)
    g = ds["grade_G"].isel(checkpoint=-1).values
    coincident = int(np.argmin(gaps))
    assert g[coincident] == pytest.approx(
        _run("none", a[coincident], _plateau(1.02), checkpoints_only=True).grade_G[-1],
        rel=1e-12)


def test_without_contact_more_points_than_balls_fit_are_allowed():
    cfg = load("vub_jeffcott_004", ["balancer.contact=none", "balancer.n_balls=20",
                                    "initial.ball_angles=[" + ", ".join(["0.1"] * 20) + "]"])
    assert cfg.system.balancer.n_balls == 20
    with pytest.raises(Exception) as e:
        load("vub_jeffcott_004", ["balancer.n_balls=20"])
    assert "balancer.n_balls" in str(e.value)


def test_a_store_of_points_is_not_a_store_of_touching_balls():
    """The store identity (sweep/store.py) tells the contact models apart (the compliant one
    keeps the identity stores had before the field existed: tests/test_sweep.py's TINY)."""
    from autobalance.sweep import spec_from_dict
    from autobalance.sweep.plan import make_plan
    from autobalance.sweep.store import identity

    def ident(*sets):
        return identity(make_plan(spec_from_dict({
            "sweep": {"name": "c", "base": "vub_jeffcott_004", "set": list(sets)},
            "monte_carlo": {"kind": "start_grid", "n": 2}})))

    none = ident("balancer.contact=none")
    assert none != ident("balancer.contact=compliant") and none != ident()
