"""Equilibria of N balls with continuous families, their stability in the linearised full
model with the family's neutral directions removed, and the speed map.

Tiers: closed forms (the family W = W*, its tangent, the aligned equilibria, 000 eq 12 at the
natural frequency), properties (hypothesis), checks against nonlinear simulations started near
each equilibrium, the speed map (boundaries, NetCDF, summary, figure) and bad input.
"""
from __future__ import annotations

import dataclasses
import functools
import json
import math

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from autobalance.config import ConfigError
from autobalance.models import ParameterError
from autobalance.physics.equilibria import (_newton, aligned_equilibria, balanced_unbalance, deflate,
                                            family_tangent, find_equilibria, find_equilibrium_set,
                                            force_phasor)
from autobalance.physics.unbalance import residual_unbalance
from autobalance.physics.vibratory import vibratory_forces
from autobalance.studies.equilibria import (NEUTRAL_TOL, _ideal, floquet_full, full_stability,
                                            linearised_full, steady_rotor_frame, verify_by_simulation)
from autobalance.studies._start_positions import load
from autobalance.studies._speed_map import compute_speed_map, speed_map_summary

TOP = "examples/toploader.toml"
CEN = "examples/centrifuge.toml"


@functools.lru_cache(maxsize=None)
def _machine(name: str):
    return load(name).system


@pytest.fixture(scope="module")
def top():
    """The 3-ball top-loader (ring eccentricity 0.1 mm) without friction (the ideal model)."""
    return _ideal(load(TOP).system)


@pytest.fixture(scope="module")
def cen():
    """The 2-ball centrifuge without friction."""
    return _ideal(load(CEN).system)


def _with(system, **balancer):
    return dataclasses.replace(system, balancer=dataclasses.replace(system.balancer, **balancer))


# ============================ tier 1: closed forms ===========================================
@pytest.mark.parametrize("rho", [0.1e-3, 0.0])
def test_three_balls_give_one_family_of_dimension_one_with_the_right_tangent(top, rho):
    """The dozens of points a grid search returns are one closed curve W(alpha) = W*: every
    sample is an equilibrium with |W - W*| ~ 0, the tangent spans the null space of dW/dalpha (checked by
    finite differences: W moves by O(eps^2) along it, O(eps) across), and find_equilibria
    returns the isolated points plus one representative."""
    s = _with(top, eccentricity=rho)
    w = 83.7758
    es = find_equilibrium_set(s, w)
    assert len(es.families) == 1
    f = es.families[0]
    assert f.dimension == 1 and f.traced and f.n_samples >= 10
    Wt = balanced_unbalance(s, w)
    cap = s.balancer.capacity
    for a, t in zip(f.alpha, f.tangent):
        assert abs(residual_unbalance(s, a) - Wt) < 1e-9 * cap
        assert np.abs(vibratory_forces(s, w, a)).max() < 1e-9 * 0.12 * 0.27 * w * w
        assert t.shape == (3, 1) and np.linalg.norm(t) == pytest.approx(1.0)
        eps = 1e-4
        along = abs(residual_unbalance(s, a + eps * t[:, 0]) - Wt)
        n = np.linalg.svd(t.T)[2][1]                 # a unit vector across the family
        across = abs(residual_unbalance(s, a + eps * n) - Wt)
        assert along < 1e-3 * across
        assert np.allclose(f.points[0].jacobian.shape, (3, 3))
    assert np.allclose(f.residual_unbalance, abs(Wt), rtol=0, atol=1e-9 * cap)
    assert len(es.isolated) <= 2 * (3 + 1)          # (N + 1) sign patterns x 2 roots at most
    assert len(find_equilibria(s, w)) == len(es.isolated) + 1


def test_balanced_unbalance_closed_forms(top):
    """W* = 0 without eccentricity; far above resonance W* -> M_t rho e^{i beta} (the mass
    centre on the race centre); Q = 0 on the family."""
    assert balanced_unbalance(_with(top, eccentricity=0.0), 50.0) == 0
    b = top.balancer
    hi = balanced_unbalance(top, 1e6 * top.natural_frequencies[0])    # c / (M_t w) = 3e-7
    assert hi == pytest.approx(top.total_mass * b.eccentricity * np.exp(1j * b.eccentricity_angle), rel=1e-6)
    f = find_equilibrium_set(top, 83.7758).families[0]
    assert np.abs(force_phasor(top, 83.7758, f.alpha)).max() < 1e-12


def test_aligned_equilibria_are_complete(top):
    """Newton from a 12^3 grid (find_equilibria's search) finds nothing that is neither on the
    family nor one of the closed-form aligned equilibria."""
    w = 30.0
    g = -math.pi + 2 * math.pi * (np.arange(12) + 0.5) / 12
    starts = np.stack(np.meshgrid(g, g, g, indexing="ij"), -1).reshape(-1, 3)
    roots, res = _newton(top, w, starts)
    roots = roots[res < 1e-9 * 0.12 * 0.27 * w * w]
    assert len(roots) > 100
    Wt = balanced_unbalance(top, w)
    al = aligned_equilibria(top, w)
    cap = top.balancer.capacity
    for r in roots:
        on_family = abs(residual_unbalance(top, r) - Wt) < 1e-6 * cap
        d = np.abs(np.angle(np.exp(1j * (np.sort(np.mod(r, 2 * np.pi))
                                         - np.sort(np.mod(al, 2 * np.pi), axis=1))))).max(axis=1)
        assert on_family or d.min() < 1e-6, r


@pytest.mark.slow
@pytest.mark.parametrize("name,sets", [("washer_000", ()), ("vub_jeffcott_004", ()), (CEN, ()),
                                       ("washer_000", ("balancer.eccentricity=0.5 mm",
                                                       "balancer.eccentricity_angle=40 deg"))])
def test_two_balls_closed_form_equals_the_newton_search(name, sets):
    """N = 2: the closed forms (aligned points, the balanced triangle) give exactly the
    equilibria of the unchanged Newton grid search, with the same verdicts."""
    s = load(name, sets).system
    for w in (5.0, 15.0, 40.0, 104.7, 600.0):
        a = find_equilibrium_set(s, w, method="newton")
        b = find_equilibrium_set(s, w, method="closed_form")
        ka = sorted(tuple(np.sort(np.mod(e.alpha, 2 * np.pi))) for e in a.isolated)
        kb = sorted(tuple(np.sort(np.mod(e.alpha, 2 * np.pi))) for e in b.isolated)
        assert np.allclose(ka, kb, atol=1e-7), w
        assert a.balanced == b.balanced
        assert [e.ks_stable for e in a.isolated] == [e.ks_stable for e in b.isolated]
        assert not a.families and not b.families


def test_static_verdict_flips_at_the_natural_frequency(cen, top):
    """000 eq (12) for the balanced state of an isotropic machine: the transverse eigenvalues of
    J = dF/dalpha have trace proportional to cos(phi), negative exactly above w_n (phi > pi/2);
    for 2 balls and for the 3-ball family (its zero eigenvalue removed)."""
    for s in (cen, _with(top, eccentricity=0.0)):
        wn = s.natural_frequencies[0]
        for r, expect in ((0.99, False), (1.01, True)):
            es = find_equilibrium_set(s, r * wn)
            pts = [e for e, b in zip(es.isolated, es.balanced) if b]
            pts += [p for f in es.families for p in f.points]
            assert pts and all(p.static_stable == expect for p in pts)


def test_deflate_sets_an_invariant_subspace_aside():
    """Block-triangular A in a rotated basis: the neutral eigenvalue and the rest come out exactly."""
    rng = np.random.default_rng(1)
    Q = np.linalg.qr(rng.normal(size=(4, 4)))[0]
    B = np.array([[0.0, 1.0, 2.0, 3.0], [0, -1.0, 0.5, 0], [0, 0, -2.0, 1.0], [0, 0, -1.0, -3.0]])
    A = Q @ B @ Q.T
    out = deflate(A, Q[:, :1])
    assert out["neutral"] == pytest.approx([0.0], abs=1e-12)
    assert np.sort_complex(out["transverse"]) == pytest.approx(np.sort_complex(np.linalg.eigvals(B[1:, 1:])))
    assert out["invariance_residual"] < 1e-12
    assert deflate(A, Q[:, 1:2])["invariance_residual"] > 0.1


# ============================ tier 2: properties ==============================================
@settings(max_examples=30, deadline=None)
@given(st.lists(st.floats(-math.pi, math.pi), min_size=3, max_size=3), st.floats(3.0, 300.0),
       st.floats(0.0, 1e-3), st.floats(0.0, 2 * math.pi))
def test_force_phasor_gives_the_vibratory_forces(a, w, rho, beta):
    """F_i = -m_i w^2 Im(e^{i alpha_i} Q) for any angles, speed and eccentricity."""
    s = _with(_machine(TOP), eccentricity=rho, eccentricity_angle=beta)
    a = np.array(a)
    F = -s.balancer.masses * w * w * np.imag(np.exp(1j * a) * force_phasor(s, w, a))
    assert np.allclose(F, vibratory_forces(s, w, a), rtol=1e-10, atol=1e-12 * np.abs(F).max())


@pytest.mark.slow
@settings(max_examples=15, deadline=None)
@given(st.floats(0.3, 3.0), st.floats(0.2, 2.5))
def test_family_exists_exactly_when_the_capacity_suffices(r, u):
    """Over speed and unbalance: one family of dimension 1 when the balls can close the polygon
    sum m_i R e^{i alpha_i} = T = W* - U - sum m_i rho e^{i beta} (|T| < sum m_i R; three equal
    balls need no more), none otherwise; its residual is |W*| everywhere on it."""
    s0 = _machine(TOP)
    s = dataclasses.replace(s0, rotor=dataclasses.replace(s0.rotor, unbalance=0.05 * u))
    w = r * s.natural_frequencies[0]
    b = s.balancer
    T = balanced_unbalance(s, w) - s.rotor.unbalance - b.total_mass * b.eccentricity * np.exp(1j * b.eccentricity_angle)
    cap = b.capacity
    assume(abs(abs(T) - cap) > 1e-3 * cap)
    es = find_equilibrium_set(s, w)
    if abs(T) > cap:
        assert es.families == ()
        return
    assert [f.dimension for f in es.families] == [1]
    lo, hi = es.families[0].residual_range
    assert hi - lo < 1e-9 * cap
    assert lo == pytest.approx(abs(balanced_unbalance(s, w)), abs=1e-9 * cap)


# ============================ tier 3: full model and simulations =============================
def test_family_neutral_multiplier_is_removed_by_both_routes(top):
    """The family's multiplier 1 (1 - 2.4e-11 by shooting) must not be counted.
    Both routes find exactly one multiplier within NEUTRAL_TOL of 1 along the tangent, remove
    it, and agree on the remaining ones."""
    w = 83.7758
    p = next(q for q in find_equilibrium_set(top, w).families[0].points if not q.overlap)
    assert steady_rotor_frame(top)
    fe = linearised_full(top, w, p.alpha, family=True)
    ff = floquet_full(top, w, p.alpha, family=True)
    for f in (fe, ff):
        assert f["neutral_ok"] and f["stable"] and f["converged"]
        assert len(f["neutral_multipliers"]) == 1
        assert abs(f["neutral_multipliers"][0] - 1) < NEUTRAL_TOL
        assert f["neutral_sin_angle"] < 1e-3
        assert f["max_modulus_all"] > 1 - 1e-7 > f["max_modulus"]
    me = np.sort(np.abs(fe["multipliers"]))
    mf = np.sort(np.abs(ff["multipliers"]))
    assert me == pytest.approx(mf, abs=1e-4)     # monodromy differences: integrator tol / step
    assert not floquet_full(top, w, p.alpha)["stable"]      # counted, it decides by rounding


@pytest.mark.parametrize("r,expect", [(0.8, False), (1.04, False), (1.3, True)])
def test_two_ball_verdicts_agree_with_simulations(cen, r, expect):
    """Centrifuge, balanced pair: unstable below w_n, stable above, and unstable at 1.04 w_n,
    where 000 eq (12) and the kinetic-static model call it stable but the linearised full model
    does not (circulatory forces, weak ball damping). A 30 s nonlinear run from +-0.05 rad agrees."""
    w = r * cen.natural_frequencies[0]
    es = find_equilibrium_set(cen, w)
    e = next(e for e, b in zip(es.isolated, es.balanced) if b)
    assert full_stability(cen, w, e.alpha)["stable"] is expect
    if r == 1.04:
        assert e.static_stable and e.ks_stable
    assert verify_by_simulation(cen, w, e.alpha, duration=30.0)["stays"] is expect


@pytest.mark.parametrize("w,expect", [(10.0, False), (21.8, True), (83.7758, True)])
def test_family_verdicts_agree_with_simulations(top, w, expect):
    """3-ball top-loader: a 60 s run started 0.05 rad off a family point stays on the family
    (|W - W*| -> 0, drift only along it) where the family is stable, and leaves it below
    resonance."""
    es = find_equilibrium_set(top, w)
    p = next(q for q in es.families[0].points if not q.overlap)
    assert full_stability(top, w, p.alpha, family=True)["stable"] is expect
    run = verify_by_simulation(top, w, p.alpha, duration=60.0)
    off = abs(residual_unbalance(top, run["final_alpha_rad"]) - es.target_unbalance) / top.balancer.capacity
    assert bool(off < 1e-6) == expect, off
    if not expect:
        assert off > 0.1


def test_family_under_gravity_is_attracting_with_a_slow_drift(top):
    """Horizontal axis (gravity in the plane): the family is only nearly preserved. The Floquet
    route solves for the drifting orbit, removes the family's multiplier as a slow one (|mu - 1|
    ~ 1e-5 to 2.5e-4, far nearer 1 than the others) and calls it stable; a 60 s run stays balanced: gravity makes the balls wobble by about
    g/(R w^2) = 5e-3 rad per revolution, which the averaged final angles feel, so |W - W*| stays
    below 1e-3 of the capacity instead of 1e-6."""
    s = dataclasses.replace(top, gravity=dataclasses.replace(top.gravity, g=9.81, direction=math.pi))
    w = 83.7758
    es = find_equilibrium_set(s, w)
    p = next(q for q in es.families[0].points[5:] if not q.overlap)
    assert not steady_rotor_frame(s)
    f = full_stability(s, w, p.alpha, family=True)
    assert f["method"] == "floquet" and f["converged"] and f["stable"]
    assert f["neutral_kind"] == "slow" and f["neutral_distance"] > NEUTRAL_TOL
    run = verify_by_simulation(s, w, p.alpha, duration=60.0)
    off = abs(residual_unbalance(s, run["final_alpha_rad"]) - es.target_unbalance) / s.balancer.capacity
    assert off < 1e-3


# ============================ tier 4: the speed map ===========================================
@pytest.mark.slow
def test_speed_map_isotropic_two_balls_against_the_natural_frequency(cen):
    """Isotropic 2-ball machine, capacity sufficing (Chung & Ro 1999; Green et al. 2006 for the
    full model; 000 eq 12): the balanced state exists at every speed, is never stable below w_n,
    stays stable from its lower edge to the grid's end, and the edge falls to w_n as the ball
    damping grows (the circulatory forces need damping): 7.7 %, 0.6 %, 0.05 % above w_n for
    D = 0.1, 1, 10 N*mm*s/rad."""
    cfg = load(CEN)
    wn = cen.natural_frequencies[0]
    speeds = np.geomspace(0.8 * wn, 1.5 * wn, 12)
    edges = []
    for D in ("0.1", "1", "10"):
        ds = compute_speed_map(load(CEN, (f"balancer.damping={D} N*mm*s/rad",)), speeds=speeds,
                               damping_factors=[1.0])
        s = speed_map_summary(ds)
        assert ds["balanced_exists"].values.all()
        (lo, hi), = s["stable_ranges_rad_s"]
        assert hi == speeds[-1] and lo > wn
        stable = ds["balanced_stable"].values.astype(bool)
        assert not stable[speeds < wn].any() and stable[speeds > lo].all()
        edges.append(lo / wn - 1)
    assert edges[0] > edges[1] > edges[2] and edges[2] < 1e-3
    ks = compute_speed_map(cfg, speeds=speeds, damping_factors=[1.0], full=False)
    assert speed_map_summary(ks)["stable_ranges_rad_s"][0][0] > wn


def test_speed_map_refines_edges_and_reports_progress():
    """Range edges lie between the grid neighbours and the verdict flips within range_rtol of
    them; progress runs to its total."""
    calls = []
    vub = load("vub_jeffcott_004")
    wn = vub.system.natural_frequencies[0]
    speeds = np.geomspace(0.9 * wn, 1.2 * wn, 6)
    ds = compute_speed_map(vub, speeds=speeds, damping_factors=[0.5, 1.0], full=True,
                           progress=lambda d, t: calls.append((d, t)))
    assert calls[-1][0] == calls[-1][1] == 12 and [c[0] for c in calls] == list(range(1, 13))
    s = speed_map_summary(ds)
    (lo, hi), = s["stable_ranges_rad_s"]
    k = np.searchsorted(speeds, lo)
    assert speeds[k - 1] < lo < speeds[k]
    rtol = s["range_rtol"]
    assert rtol == 1e-4
    for f, expect in ((1 - rtol, False), (1 + rtol, True)):    # edge = midpoint of a bracket <= rtol
        one = compute_speed_map(vub, speeds=[lo * f], damping_factors=[1.0])
        assert bool(one["balanced_stable"].values[0]) is expect
    d = {x["damping_factor"]: x["stable_ranges_rad_s"] for x in s["damping"]}
    assert d[1.0] == s["stable_ranges_rad_s"] and d[0.5][0][0] > lo


def test_speed_map_capacity_short_reports_the_balls_in_contact():
    """Unbalance 1.5 x the capacity: no balanced state; far above resonance the best stable
    state has all balls opposite the unbalance (residual U - sum m R), far below with it
    (U + sum m R). Only there is H real; the damping (zeta = 5 %) turns the balls by about
    2 zeta w/w_n or 2 zeta w_n/w = 0.002 rad, a relative change of the residual below 1e-5."""
    cfg = load(CEN)
    cap = cfg.system.balancer.capacity
    big = load(CEN, (f"rotor.unbalance={1.5 * cap!r}",))
    wn = cfg.system.natural_frequencies[0]
    ds = compute_speed_map(big, speeds=[0.02 * wn, 50.0 * wn], damping_factors=[1.0])
    assert not ds["balanced_exists"].values.any()
    assert list(ds["best_kind"].values) == [3, 3]
    assert ds["residual_unbalance"].values == pytest.approx([2.5 * cap, 0.5 * cap], rel=1e-5)


@pytest.mark.slow
def test_speed_map_three_balls_netcdf_round_trip_and_figure(tmp_path):
    """The top-loader map (families) survives NetCDF unchanged (no bool or object attributes),
    its summary is JSON, and the figure converts the speed axis with the unit registry."""
    speeds = [10.0, 25.0, 83.7758]
    ds = compute_speed_map(TOP, speeds=speeds, damping_factors=[1.0, 2.0], quick=True)
    assert list(ds["n_families"].values) == [1, 1, 1]
    assert list(ds["balanced_stable"].values) == [0, 1, 1]
    assert list(ds["best_kind"].values)[1:] == [2, 2]
    for v in ds.attrs.values():
        assert not isinstance(v, (bool, np.bool_, list, dict))
    p = tmp_path / "map.nc"
    ds.to_netcdf(p)
    import xarray as xr

    back = xr.open_dataset(p)
    s = speed_map_summary(ds)
    assert speed_map_summary(back) == s
    json.dumps(s, allow_nan=False)
    from autobalance.plotting.speed_map import plot_speed_map

    fig = plot_speed_map(back, "rpm")
    ax = fig.axes[1]
    assert ax.get_xlim() == pytest.approx((10.0 * 60 / (2 * np.pi), 83.7758 * 60 / (2 * np.pi)))
    with pytest.raises(ConfigError, match="speed_unit"):
        plot_speed_map(back, "kg")


# ============================ tier 5: bad input ================================================
@pytest.mark.parametrize("kw,field", [
    (dict(speeds=[100.0, -5.0]), "speeds"),
    (dict(speeds=[]), "speeds"),
    (dict(speeds=[float("nan")]), "speeds"),
    (dict(damping_factors=[]), "damping_factors"),
    (dict(damping_factors=[1.0, 0.0]), "damping_factors"),
])
def test_speed_map_bad_input(kw, field):
    with pytest.raises(ParameterError, match=f"^{field} = "):
        compute_speed_map("vub_jeffcott_004", **{"speeds": [600.0], **kw})


def test_equilibrium_set_bad_input(top):
    with pytest.raises(ParameterError, match="^method = "):
        find_equilibrium_set(top, 50.0, method="newton")
    with pytest.raises(ParameterError, match="^n_samples = "):
        find_equilibrium_set(top, 50.0, n_samples=1)
    with pytest.raises(ParameterError, match="^step = "):
        find_equilibrium_set(top, 50.0, step=0.0)
    with pytest.raises(ParameterError, match="^speed = "):
        find_equilibrium_set(top, -1.0)
    with pytest.raises(ParameterError, match="^method = "):
        full_stability(top, 50.0, [0.0, 2.0, 4.0], method="shooting")


def test_family_tangent_dimension(top):
    """N - rank: 1 for three balls in general position, 2 where they lie on one line."""
    assert family_tangent(top, [0.3, 2.0, -2.0]).shape == (3, 1)
    assert family_tangent(top, [0.0, math.pi, 0.0]).shape == (3, 2)


# ============================ tier 6: the CLI ==================================================
@pytest.mark.slow
def test_cli_lists_the_family_as_a_family():
    """`analyze equilibria` on the 3-ball top-loader: no balanced isolated points, one family of
    dimension 1, every reachable sample stable in the full model (neutral direction removed)."""
    from typer.testing import CliRunner

    from autobalance.cli.analyze import app

    r = CliRunner().invoke(app, ["equilibria", TOP, "--full-model", "--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert not any(e["balanced"] for e in out["equilibria"])
    (f,) = out["families"]
    assert f["dimension"] == 1
    reach = [v for v, o in zip(f["full_stable"], f["overlap"]) if not o]
    assert reach and all(reach) and all(v for v, o in zip(f["full_neutral_ok"], f["overlap"]) if not o)
    text = CliRunner().invoke(app, ["equilibria", TOP, "--set", "balancer.eccentricity=0"])
    assert text.exit_code == 0 and "1 family of balanced states" in text.stdout
