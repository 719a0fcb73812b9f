"""The speed map on a horizontal axis: the Floquet verdict of the balanced state under gravity
against direct simulations, for 2 balls (an isolated periodic state) and 3 balls (a family the
balls drift along), the evaluation counts, and no verdict as its own category in the summary,
the NetCDF file, the figure and the CLI text.

The machine is tests/data/grinder_3balls.toml: a 1.5 kg angle grinder on an isotropic mount
(w_n = 149.4 rad/s), balls of 4 g on R = 25 mm, ball damping 0.15 N*mm*s/rad, gravity in the
plane, no rolling resistance. Without gravity (eigenvalue route) its balanced state is stable
from 160.6 rad/s with 2 balls and from 161.95 rad/s with 3 balls.
"""
from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest

from autobalance.models import InitialState, SimOptions, SpeedProfile
from autobalance.physics.equilibria import find_equilibrium_set
from autobalance.simulate import simulate
from autobalance.simulate.result import residual_unbalance_history
from autobalance.studies.equilibria import _ideal, full_stability, steady_rotor_frame
from autobalance.studies._speed_map import (FLOQUET_FAMILY_SAMPLES, _bisect, compute_speed_map,
                                           speed_map_summary)
from autobalance.studies._start_positions import load

GRINDER = str(Path(__file__).parent / "data" / "grinder_3balls.toml")
REVS = 150              # revolutions simulated from each perturbed balanced state [-]
PERTURBATION = 0.02     # offset of ball i: +-0.02 rad, alternating [rad]


def _grinder(n: int, g: float = 9.81):
    sets = [f"balancer.n_balls={n}", f"gravity.g={g} m/s^2"]
    if n == 2:
        sets.append('initial.ball_angles=["0 deg", "100 deg"]')
    return load(GRINDER, sets)


def _balanced_states(system, w: float):
    """The balanced states the speed map judges at w [rad/s]: the isolated balanced points, or
    FLOQUET_FAMILY_SAMPLES evenly spread reachable samples of the family; (alpha, family)."""
    es = find_equilibrium_set(system, w, method="closed_form", n_samples=12)
    out = [(e.alpha, False) for e, b in zip(es.isolated, es.balanced) if b and not e.overlap]
    for f in es.families:
        reach = [p for p in f.points if not p.overlap]
        idx = np.round(np.linspace(0, len(reach) - 1, FLOQUET_FAMILY_SAMPLES)).astype(int)
        out += [(reach[i].alpha, True) for i in idx]
    return out, es.target_unbalance


def _run(system, w: float, alpha, target: complex) -> np.ndarray:
    """|<W>_rev - W*| / capacity per revolution [-] of a run at constant w [rad/s] started at
    alpha [rad] + PERTURBATION (-1)^i with the drum on its steady orbit (W averaged over each
    revolution: gravity's once-per-revolution wobble left out)."""
    T = 2 * math.pi / w
    a0 = np.asarray(alpha) + PERTURBATION * (-1.0) ** np.arange(alpha.size)
    sim = simulate(system, SpeedProfile.constant(w, REVS * T),
                   initial=InitialState(ball_angles=tuple(a0), steady_state=True),
                   options=SimOptions(save_dt=T / 16))
    W = residual_unbalance_history(system, sim.alpha, sim.t) - target
    k = np.minimum((sim.t / T).astype(int), REVS - 1)
    cnt = np.bincount(k, minlength=REVS)
    mean = (np.bincount(k, W.real, REVS) + 1j * np.bincount(k, W.imag, REVS)) / cnt
    return np.abs(mean) / system.balancer.capacity


@pytest.mark.parametrize("n,w,expect", [
    (2, 145.0, False), (2, 155.0, False), (2, 170.0, True), (2, 188.5, True), (2, 230.4, True),
    (3, 145.0, False), (3, 155.0, False), (3, 170.0, True), (3, 188.5, True), (3, 230.4, True),
])
def test_floquet_verdict_under_gravity_agrees_with_simulations(n, w, expect):
    """Floquet verdict of every balanced state the map judges against a run of 150 revolutions
    from it, perturbed by +-0.02 rad (rolling resistance 0). Predicted edges: 160.6 rad/s
    (2 balls) and 161.95 rad/s (3 balls); 188.5 and 230.4 rad/s are 1800 and 2200 rpm.
    Measured |<W>_rev - W*| / capacity, first revolution -> largest, last:

    * 2 balls: 145 rad/s 0.015 -> 1.57, 0.42 and 155 rad/s 0.014 -> 1.53, 1.28 (grows; max
      |mu| 1.125 and 1.074); 170, 188.5, 230.4 rad/s 0.014 -> last 0.0013, 0.0012, 0.0007
      (decays; max |mu| 0.856, 0.889, 0.916).
    * 3 balls, four samples of the family: 145 rad/s 0.014-0.027 -> 1.34, 0.89-1.30 (max |mu|
      1.13-1.16); 155 rad/s 0.013-0.024 -> 0.24-1.33, i.e. 10-105 x the first (1.04-1.12);
      170, 188.5, 230.4 rad/s 0.009-0.021 -> last 0.0004-0.0013 (0.86-0.97). The decay stops
      near 1e-3 of the capacity, the wobble's second-order offset, while the balls drift along
      the family (3e-4 rad per revolution at 170 rad/s), which the runs follow at W = W*.

    Stable: the last revolution below 0.2 x the first; unstable: some revolution above 3 x the
    first."""
    system = _ideal(_grinder(n).system)
    assert not steady_rotor_frame(system)
    states, target = _balanced_states(system, w)
    assert len(states) == (1 if n == 2 else FLOQUET_FAMILY_SAMPLES)
    for alpha, family in states:
        f = full_stability(system, w, alpha, family=family)
        assert f["method"] == "floquet" and f["converged"], f["shooting_residual"]
        if family:
            assert f["neutral_ok"] and f["neutral_kind"] == "slow"
        assert f["stable"] is expect, (w, alpha, f["max_modulus"])
        r = _run(system, w, alpha, target)
        if expect:
            assert r[-1] < 0.2 * r[0], r[[0, -1]]
        else:
            assert r.max() > 3.0 * r[0], (r[0], r.max())


@pytest.mark.parametrize("n", [2, 3])
def test_speed_map_edge_under_gravity_is_the_gravity_free_one(n):
    """The map's lower edge on the horizontal axis (Floquet) lies between the simulated
    unstable 155 rad/s and stable 170 rad/s and within 0.2 % of the edge without gravity
    (eigenvalue route): 2 balls 160.6 rad/s, 3 balls 161.95 rad/s with and without gravity."""
    speeds = np.geomspace(145.0, 250.0, 5)
    on = compute_speed_map(_grinder(n), speeds=speeds, damping_factors=[1.0], quick=True)
    off = compute_speed_map(_grinder(n, 0.0), speeds=speeds, damping_factors=[1.0], quick=True)
    assert on.attrs["method"] == "floquet" and off.attrs["method"] == "eigenvalues"
    (lo, hi), = speed_map_summary(on)["stable_ranges_rad_s"]
    (lo0, _), = speed_map_summary(off)["stable_ranges_rad_s"]
    assert 155.0 < lo < 170.0 and hi == speeds[-1]
    assert lo == pytest.approx(lo0, rel=2e-3)
    assert on.attrs["no_verdict"] == 0


@pytest.fixture(scope="module")
def nv_map():
    """3 balls under gravity from 100 rad/s, two damping factors: no verdict at 100 rad/s (one
    sample's shooting runs the balls into contact, the others are unstable)."""
    return compute_speed_map(_grinder(3), speeds=[100.0, 145.0, 175.0, 230.0],
                             damping_factors=[1.0, 2.0], quick=True)


def test_counts_are_one_evaluation_per_speed_and_verdict(nv_map):
    """An evaluation is the balanced state judged at one (damping factor, speed): each grid
    point and each bisection step once. The bisection steps are replayed with a predicate that
    flips at the reported edge; no verdict counts evaluations, not states."""
    ds = nv_map
    s = speed_map_summary(ds)
    w = ds["speed"].values
    steps = 0
    for d in s["damping"]:
        (lo, _), = d["stable_ranges_rad_s"]
        k = int(np.searchsorted(w, lo))
        calls = []
        _bisect(lambda x: calls.append(x) or x > lo, w[k - 1], w[k], ds.attrs["range_rtol"])
        steps += len(calls)
    assert s["evaluations"] == 2 * w.size + steps
    codes = ds["balanced_verdict_damping"].values
    assert s["no_verdict"] == int((codes == 3).sum()) == 2
    assert s["no_verdict"] <= s["states_no_verdict"] <= s["states_judged"]
    assert s["states_judged"] == FLOQUET_FAMILY_SAMPLES * s["evaluations"]


def test_no_verdict_is_its_own_category(nv_map, tmp_path):
    """Summary (per-speed verdicts, no-verdict ranges), NetCDF round trip and figure: the
    no-verdict speed is drawn in its own colour and hatch with a legend entry, never red."""
    import xarray as xr
    from matplotlib.colors import to_rgba

    from autobalance.plotting.speed_map import VERDICT_STYLE, plot_speed_map

    ds = nv_map
    s = speed_map_summary(ds)
    assert s["balanced_verdict"] == ["no verdict", "unstable", "stable", "stable"]
    assert s["no_verdict_ranges_rad_s"] == [[100.0, 100.0]]
    assert [d["no_verdict_ranges_rad_s"] for d in s["damping"]] == [[[100.0, 100.0]]] * 2
    assert s["counts"]["balanced_no_verdict"] == 1 and s["counts"]["balanced_stable"] == 2
    assert list(ds["balanced_stable"].values) == [0, 0, 1, 1]
    json.dumps(s, allow_nan=False)
    p = tmp_path / "map.nc"
    ds.to_netcdf(p)
    back = xr.open_dataset(p)
    assert speed_map_summary(back) == s
    fig = plot_speed_map(back)
    ax = fig.axes[1]
    mesh = ax.collections[0]
    rgba = mesh.to_rgba(np.asarray(mesh.get_array()).reshape(2, 4))
    for row in rgba:
        assert tuple(row[0]) == to_rgba(VERDICT_STYLE[3][1]) != to_rgba("tab:red")
        assert tuple(row[1]) == to_rgba("tab:red") and tuple(row[2]) == to_rgba("tab:green")
    hatched = [q for q in ax.patches if q.get_hatch()]
    assert len(hatched) == 2
    assert "no verdict" in [t.get_text() for t in ax.get_legend().get_texts()]
    assert "balanced state: no verdict" in [t.get_text() for t in fig.axes[0].get_legend().get_texts()]


@pytest.mark.slow
def test_cli_text_names_the_evaluations_and_the_no_verdict_speeds():
    """`study speed-map` text: the no-verdict grid speeds, evaluations and no verdicts counted
    once per (damping factor, speed), and JSON with the per-speed verdicts."""
    from typer.testing import CliRunner

    from autobalance.cli import app

    args = ["study", "speed-map", GRINDER, "--speeds", "100:175:2", "--c-r", "1", "--quick",
            "--units", "speed=rad/s"]
    r = CliRunner().invoke(app, args)
    assert r.exit_code == 0, r.output
    assert "no verdict at grid speeds 100 rad/s" in r.stdout
    line = next(x for x in r.stdout.splitlines() if "evaluations (the balanced state" in x)
    n_eval, n_nv = int(line.split()[0]), int(line.split("), ")[1].split()[0])
    assert n_nv == 1 and n_eval > 2
    j = CliRunner().invoke(app, args + ["--json"])
    out = json.loads(j.stdout)
    assert out["balanced_verdict"] == ["no verdict", "stable"] and out["no_verdict"] == 1
    assert out["evaluations"] == n_eval and out["no_verdict_ranges_rad_s"] == [[100.0, 100.0]]
