"""Seed-000 washer analysis (vibratory forces, equilibria, error bounds, tolerances,
kinetic-static model, studies, CLI).

Choices the paper leaves open (docs/washer-analysis.md): ball damping c_i = 2 1/s (D = c_i m R^2)
unless stated; M_t = M + sum(m_i) as the translating mass; full model = ``simulate`` with
normal_force = "drum" (000 eq 20); gravity off except in Tables 3-4 (000 eq 50, Fig. 19); balls
start at rest at 90 and 150 deg with the drum on its harmonic orbit.

Tiers: 1 closed forms, 2 the paper's numbers, 3 hypothesis properties, 4 CLI, 5 bad input.
"""
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from typer.testing import CliRunner

from autobalance.physics import error_bounds as eb
from autobalance.physics.equilibria import balancing_onset_speed, find_equilibria, single_ball_stability
from autobalance.studies.equilibria import floquet_full, verify_by_simulation
from autobalance.simulate.kinetic_static import compare_with_full, simulate_kinetic_static
from autobalance.physics.response import ball_influence, harmonic_response
from autobalance.physics.tolerance import design_tolerances, predict_residual
from autobalance.physics.vibratory import (drum_response, force_jacobian, single_ball_force,
                                            speed_regime, vibratory_components, vibratory_forces)
from autobalance.cli.analyze import app
from autobalance.models import ParameterError
from autobalance.papers.p000 import washer as study

from conftest import RPM, washer_000

W = 1000 * RPM
E05 = 0.05 / 37.0       # e = Me/M of 000 eq 32 (M = 37 kg as printed)


# ============================ tier 1: closed forms ============================================
def test_components_sum_and_harmonic_response_agree():
    """eq 40: F = F_x + F_y + F_rho; eq 6-7 amplitudes = response.py gains (same M_t)."""
    s = washer_000(Me=0.05, rho=0.3e-3, beta=1.0)
    a = np.radians([100.0, -140.0])
    c = vibratory_components(s, W, a)
    assert np.allclose(c["F"], vibratory_forces(s, W, a), rtol=1e-12, atol=1e-14)
    assert np.allclose(c["F_x"], c["F_x0"] + c["F_xball"] + c["F_xrho"])
    r = drum_response(s, W, a)
    h = harmonic_response(s, W)
    bi = ball_influence(s, W)
    assert r.a_0x == pytest.approx(h.a_x) and r.a_0y == pytest.approx(h.a_y)
    assert np.allclose(r.a_ix, bi.a_x) and r.phi_y == pytest.approx(h.phi_y)


def test_one_ball_eq11_force_zero_at_pi_and_matches_general_form():
    """eq 11: one ball with mR = Me: F(pi) = 0 exactly, and the normalised curve is F/(mRw^2)."""
    s = washer_000(Me=0.025, n=1)
    for w in (8.0, 18.0, W):
        assert vibratory_forces(s, w, [math.pi])[0] == pytest.approx(0.0, abs=1e-15)
        al = np.linspace(0, 2 * math.pi, 13)
        c = single_ball_force(s, w, al)
        F = vibratory_forces(s, w, al[:, None])[:, 0]
        m = s.balancer.masses[0]
        assert np.allclose(c["F_norm"] * m * 0.28 * w * w, F, rtol=1e-10, atol=1e-14)


def test_jacobian_matches_finite_differences():
    s = washer_000(Me=0.05, rho=0.5e-3, beta=0.7, n=3)
    a = np.array([0.3, 2.2, -1.9])
    J = force_jacobian(s, W, a)
    h = 1e-6
    Jn = np.array([(vibratory_forces(s, W, a + h * e) - vibratory_forces(s, W, a - h * e)) / (2 * h)
                   for e in np.eye(3)]).T
    assert np.allclose(J, Jn, rtol=1e-6, atol=1e-9)


def test_eq12_onset_lies_between_the_suspension_frequencies():
    """eq 12: alpha_f = pi stable (dF/dalpha < 0) only above an onset speed between w_y and w_x,
    and always above both ("the ball can compensate for the unbalance")."""
    s = washer_000(Me=0.025, n=1)
    wx, wy = s.natural_frequencies
    w0 = balancing_onset_speed(s)
    assert wy < w0 < wx
    r = single_ball_stability(s, [0.5 * wy, 0.99 * w0, 1.01 * w0, 1.5 * wx, W])
    assert list(r["stable"]) == [False, False, True, True, True]
    assert [speed_regime(s, w) for w in (0.5 * wy, 18.0, W)] == ["below", "between", "above"]


def test_equilibria_of_two_balls_at_1000rpm():
    """F_i = 0: the balanced pair +-120 deg (Me = mR) is the only stable non-overlapping state."""
    s = washer_000(Me=0.05, g=0.0)
    eqs = find_equilibria(s, W)
    good = [e for e in eqs if not e.overlap]
    assert np.degrees(np.sort(good[0].alpha)) == pytest.approx([-120.0, 120.0], abs=1e-6)
    assert good[0].static_stable and good[0].ks_stable
    assert all(not e.ks_stable for e in eqs[1:])


def test_rolling_bounds_tend_to_eq24_and_eq32_at_high_speed():
    """eq 24 -> (R/e)(f/r) and the dead-band vertex (eq 27-31) -> 2 (R/e)(f/r) for w >> w_x, w_y
    (a = e, phi = pi), with e = Me/M_t."""
    s1 = washer_000(Me=0.025, n=1)
    s2 = washer_000(Me=0.05, g=0.0)
    w = 3000.0
    e1 = 0.025 / s1.total_mass
    assert eb.rolling_deadband_single(s1, w, 1e-4) == pytest.approx(0.28 / e1 * 1e-4, rel=2e-3)
    db = eb.rolling_deadband(s2, w, 1e-4)
    assert db["max_deviation_rad"] == pytest.approx([2 * 0.28 / (0.05 / s2.total_mass) * 1e-4] * 2, rel=2e-3)


def test_eq45_agrees_with_exact_root_and_eq47_with_exact_residual():
    """eq 45 vs the exact root of eq 44 at beta = pi/2 (rho/e = 0.07: 1 %); eq 47 vs |W|."""
    s = washer_000(Me=0.025, n=1, rho=0.05e-3, beta=math.pi / 2, g=0.0)
    ex = [e for e in find_equilibria(s, 3000.0) if e.ks_stable][0]
    dev = np.angle(np.exp(1j * (ex.alpha[0] - math.pi)))
    assert dev == pytest.approx(eb.eccentricity_deviation_single(0.025 / s.total_mass, 0.05e-3,
                                                                 math.pi / 2), rel=0.01)
    s2 = washer_000(Me=0.05, rho=0.02e-3, g=0.0)
    r = eb.eccentricity_equilibrium(s2, W)
    assert r["residual_linear_kg_m"] == pytest.approx(r["residual_unbalance_kg_m"], rel=0.02)


def test_ball_natural_frequency_eq54_eq55():
    """eq 54 equals the linearised point-mass ball (m_z = m); eq 55 is its w >> w_n limit."""
    import dataclasses
    s = washer_000(Me=0.025, n=1)
    sp = dataclasses.replace(s, balancer=dataclasses.replace(s.balancer, element="point"))
    w54 = eb.ball_natural_frequency_single(sp, W)
    assert eb.ball_natural_frequencies(sp, W, [math.pi])[0] == pytest.approx(w54, rel=1e-9)
    w = 5000.0
    assert eb.ball_natural_frequency_single(sp, w) == pytest.approx(
        eb.ball_natural_frequency_approx(w, 0.025 / sp.total_mass, 0.28), rel=1e-3)
    assert w54 < 0.1 * W                           # "w_alpha << w"


@pytest.mark.slow
def test_kinetic_static_settles_to_the_balanced_state_and_respects_the_dead_band():
    s = washer_000(Me=0.05, g=0.0)
    ks = simulate_kinetic_static(s, W, np.radians([90, 150]), 20.0)
    assert np.degrees(np.sort(np.angle(np.exp(1j * ks.alpha[-1])))) == pytest.approx([-120, 120], abs=0.05)
    s3 = washer_000(Me=0.05, g=0.0, f_r=1e-3)
    ks = simulate_kinetic_static(s3, W, np.radians([90, 150]), 20.0)
    assert np.all(ks.alpha_dot[-1] == 0.0)
    d = np.angle(np.exp(1j * (ks.alpha[-1] - np.radians([120, -120]))))
    J = force_jacobian(s3, W, np.radians([120, -120]))
    Fr = s3.balancer.masses * 0.28 * W * W * 1e-3
    assert np.all(np.abs(J @ d) <= 1.15 * Fr)      # linearised dead band, 15 % for curvature


# ============================ tier 2: the paper's numbers =====================================
def test_eq32_delta_alpha_2_4_deg():
    """000 eq 32: 2 (R/e)(f/r) = 2.4 deg for Me = 0.05, M = 37 kg, f/r = 1e-4 (abs 0.05 deg =
    the rounding of the printed value)."""
    assert math.degrees(eb.symmetric_rolling_deviation(0.28, E05, 1e-4)) == pytest.approx(2.4, abs=0.05)


def test_eq49_0_071_rad():
    """000 eq 49: F cos(gamma)/(Me sin(2pi/3) w^2) = 0.071 rad, 2F = 140 N, 61 deg, 1000 rpm
    (abs 5e-4: printed to 2 digits)."""
    assert eb.suspension_friction_deviation(70.0, math.radians(61), 0.05, W) == pytest.approx(0.071, abs=5e-4)


def test_eq60_rho_max_34_and_67_um():
    """000 eq 60: rho_max = 0.05 Me/M = 34 um (Me = 0.025) and 67 um (Me = 0.05); abs 0.5 um
    (printed to whole um)."""
    for Me, pub in ((0.025, 34e-6), (0.05, 67e-6)):
        d = design_tolerances(Me, 37.0, 0.28, W)
        assert d["rho_max_m"] == pytest.approx(pub, abs=0.5e-6 + 0.4e-6)


def test_eq63_f_r_max_is_a_documented_miss():
    """000 eq 63: f/r <= 0.07 e/R; the paper prints "f/r ~ 5e-5" for Me = 0.025 kg m. The printed
    formula gives 0.07 * (0.025/37)/0.28 = 1.69e-4 (3.4x); MISS: no reading of eq 61-63 with
    the paper's numbers gives 5e-5 (it would need Me = 0.0074 kg m)."""
    d = design_tolerances(0.025, 37.0, 0.28, W)
    assert d["f_r_max"] == pytest.approx(0.07 * 0.025 / 37 / 0.28, rel=1e-12)
    assert d["f_r_max"] == pytest.approx(1.69e-4, rel=0.01)
    assert not d["f_r_max"] == pytest.approx(5e-5, rel=0.5)          # documented miss


def test_eq66_friction_force_is_a_documented_miss():
    """000 eq 66 prints F < 57 N at 1000 rpm. The printed chain (eq 65: 2 m R d_f <= 0.005 Me)
    gives 2.45 N (Me = 0.05); eq 66 as printed, 0.005 Me w^2 sin(2pi/3)/cos(gamma), gives
    4.90 N (Me = 0.05). MISS: 57 N needs ~0.058 Me w^2 sin/cos; the nearest reading, friction
    taking the whole 10 % budget (0.1 Me / 2 balls), gives 49 N."""
    d = design_tolerances(0.05, 37.0, 0.28, W, friction_angle=math.radians(61))
    assert d["friction_force_max_n"] == pytest.approx(2.45, abs=0.01)
    assert d["friction_force_eq66_printed_n"] == pytest.approx(4.90, abs=0.01)
    whole_budget = eb.friction_force_for_deviation(0.1 * 0.05 / (2 * 0.05), math.radians(61), 0.05, W)
    assert whole_budget == pytest.approx(49.0, abs=0.5)


@pytest.mark.slow
def test_fig9_kinetic_static_vs_full_model():
    """000 Fig. 9: differences "almost 10 um" (x), "25 um" (y), 0.005 rad (alpha) at the start,
    vanishing "in a matter of seconds". With c_i = 7.1 1/s (the Fig. 5 settling, VALIDATION.md)
    and the Fig. 5 start we get 35 um / 34 um / 0.058 rad, below 1e-4 rad after 5 s.
    D_x, D_y are of the paper's order (within 4x); D_alpha is a documented MISS (12x): it grows
    with the distance the balls travel before settling, which depends on the start and c_i the
    paper does not give (c_i = 2 1/s: 0.10 rad)."""
    s = washer_000(Me=0.025, g=0.0, c_i=7.1)
    c = compare_with_full(s, W, np.radians([90, 150]), 6.0)
    assert 10e-6 / 4 < c["max_D_x_m"] < 4 * 10e-6
    assert 25e-6 / 4 < c["max_D_y_m"] < 4 * 25e-6
    assert c["max_D_alpha_rad"] == pytest.approx(0.058, rel=0.1)     # documented miss vs 0.005
    late = c["t_s"] > 5.0
    assert np.abs(c["D_alpha_rad"][late]).max() < 1e-4
    assert np.abs(c["D_x_m"][late]).max() < 0.01 * c["max_D_x_m"]


@pytest.fixture(scope="module")
def rows():
    return {r["quantity"]: r for r in study.compare()}


@pytest.mark.slow
def test_table4_reproduced(rows):
    """000 Table 4 (f = 1e-4 r): every Delta alpha, RMe and A lies in our dead band about our
    equilibrium (docs: tolerance = dead band, the start is unknown); ours e.g. rho = 0.5 mm:
    18.5 / 21.4 deg vs 18.4 / 21.1, RMe 64.0 vs 64.7 %."""
    t4 = [r for q, r in rows.items() if "Table 4" in q]
    assert len(t4) == 20 and all(r["ok"] for r in t4)
    assert rows["000 Table 4 rho = 0.5 mm d_alpha1 [deg]"]["computed"] == pytest.approx(18.4, abs=1.2)
    assert rows["000 Table 4 rho = 1 mm RMe [%]"]["computed"] == pytest.approx(29.3, abs=2.0)


@pytest.mark.slow
def test_table3_documented_misses(rows):
    """000 Table 3 (f = 1e-3 r): 17 of 20 published values lie in our dead band. MISSES:
    rho = 0.5 mm d_alpha2 = 0.3 deg and rho = 1 mm d_alpha2 = 7.8 deg, A = 0.38 mm: in our model
    the eccentricity fixes the equilibrium (21.5 and 43.4 deg) and friction only adds a band of
    +-16-21 deg about it; the paper's smaller deviation with the larger friction is not
    reachable."""
    miss = {q for q, r in rows.items() if "Table 3" in q and not r["ok"]}
    assert miss == {"000 Table 3 rho = 0.5 mm d_alpha2 [deg]", "000 Table 3 rho = 1 mm d_alpha2 [deg]",
                    "000 Table 3 rho = 1 mm A [mm]"}


@pytest.mark.slow
def test_fig13_fig16_fig18_rows(rows):
    """Fig. 13: 21 deg in the band; 25 deg is a MISS (it exceeds the paper's own eq 32 bound,
    23.7 deg); the impact at w t = 35 is a MISS (from our start the balls never meet). Fig. 16:
    MISS, ours 43.5 / 29.4 deg vs 45 / 34 and 0.98 vs 1.2 mm (deterministic; the paper's Table 4
    at rho = 1 mm agrees with us: 42.9 / 29.9 deg, 1 mm). Fig. 18: eq 49 ok;
    0.22 rad reproduced (0.238), 0.12 rad MISS (ours 0.004; start-dependent stick of the tub)."""
    ok = {q: r["ok"] for q, r in rows.items() if "Fig." in q or "eq 49" in q}
    assert ok == {
        "000 Fig. 13 (f/r = 1e-3) d_alpha1 [deg]": False, "000 Fig. 13 (f/r = 1e-3) d_alpha2 [deg]": True,
        "000 Fig. 13 first ball impact [w t]": False,
        "000 Fig. 16 d_alpha1 [deg] (larger first)": False, "000 Fig. 16 d_alpha2 [deg] (larger first)": False,
        "000 Fig. 16 residual amplitude [mm]": False, "000 eq 49 bound [rad]": True,
        "000 Fig. 18 d_alpha1 [rad]": True, "000 Fig. 18 d_alpha2 [rad]": False}
    assert rows["000 Fig. 16 d_alpha1 [deg] (larger first)"]["computed"] == pytest.approx(43.5, abs=0.3)


@pytest.mark.slow
def test_predicted_residual_matches_table4_simulation():
    """Reverse of eq 56-66: the kinetic-static prediction for rho = 0.5 mm, f = 1e-4 r brackets the
    simulated Table 4 efficiency (64.0 %)."""
    s = washer_000(Me=0.05, f_r=1e-4, rho=0.5e-3)
    p = predict_residual(s, 100.0)
    assert p["rme_worst"] < 0.640 < 1 - p["eccentricity_kg_m"] / 0.05 + 0.02


# ---------------- stability verdicts vs long full simulations ---------------------------------
CASES = [(dict(Me=0.05, g=0.0), W), (dict(Me=0.025, n=1, g=0.0), W), (dict(Me=0.025, n=1, g=0.0), 18.0)]


@pytest.mark.slow
@pytest.mark.parametrize("kw,w", CASES)
def test_stability_verdicts_agree_with_full_model(kw, w):
    """eq 12 / linearised KS / Floquet of the full model / 20 s full simulation from +-0.05 rad all
    give the same verdict for every non-overlapping equilibrium."""
    s = washer_000(**kw)
    for e in find_equilibria(s, w):
        if e.overlap:
            continue
        fl = floquet_full(s, w, e.alpha)
        run = verify_by_simulation(s, w, e.alpha, duration=20.0 if w > 50 else 60.0)
        assert e.ks_stable == fl["stable"] == run["stays"], (e.alpha, fl["max_modulus"], run)
        if len(e.alpha) == 1:
            assert e.static_stable == e.ks_stable


# ============================ tier 3: properties ==============================================
@settings(max_examples=40, deadline=None)
@given(st.floats(-math.pi, math.pi), st.floats(-math.pi, math.pi), st.floats(5.0, 300.0),
       st.floats(0.0, 1e-3), st.floats(0.0, 2 * math.pi))
def test_force_properties(a1, a2, w, rho, beta):
    """Vectorised == scalar; components sum; a common shift of the unbalance frame leaves the
    forces of a balanced-free drum (U = 0, rho = 0) invariant; the ball force is odd about any
    equilibrium of one isolated ball (sin form)."""
    s = washer_000(Me=0.05, rho=rho, beta=beta)
    a = np.array([a1, a2])
    F = vibratory_forces(s, w, a)
    assert np.allclose(F, vibratory_forces(s, w, a[None, :])[0])
    assert np.allclose(F, vibratory_components(s, w, a)["F"], atol=1e-12)
    import dataclasses
    s0 = washer_000(Me=0.05)
    s0 = dataclasses.replace(s0, rotor=dataclasses.replace(s0.rotor, unbalance=0.0))
    sh = 0.37
    assert np.allclose(vibratory_forces(s0, w, a), vibratory_forces(s0, w, a + sh), atol=1e-12)


@settings(max_examples=30, deadline=None)
@given(st.floats(0.01, 0.5), st.floats(0.005, 0.1), st.floats(20.0, 200.0))
def test_tolerances_scale_linearly(q, Me, w):
    """eq 58-66 are linear in the residual budget q Me."""
    d1 = design_tolerances(Me, 37.0, 0.28, w, residual_fraction=q)
    d2 = design_tolerances(Me, 37.0, 0.28, w, residual_fraction=q / 2)
    for k in ("rho_max_m", "f_r_max", "friction_force_max_n"):
        assert d2[k] == pytest.approx(d1[k] / 2, rel=1e-12)


# ============================ tier 4: CLI =====================================================
runner = CliRunner()


@pytest.mark.parametrize("args,key", [
    (["forces", "washer_000", "--speed", "1000 rpm"], "F_n"),
    (["equilibria", "washer_000", "--set", "gravity.g=0"], "equilibria"),
    (["bounds", "washer_000", "--f-r", "1e-4", "--set", "balancer.eccentricity=0.1 mm"], "rolling_eq32_rad"),
    (["kinetic-static", "washer_000", "--set", "gravity.g=0", "--duration", "2 s"], "max_D_x_m"),
    (["washer-study", "fig16"], "rows"),
])
@pytest.mark.slow
def test_cli_json(args, key):
    r = runner.invoke(app, args + ["--json"])
    assert r.exit_code == 0, r.output
    out = json.loads(r.stdout)
    assert key in out


@pytest.mark.slow
def test_cli_plots(tmp_path):
    for cmd in (["forces", "washer_000"], ["bounds", "washer_000", "--f-r", "1e-3"],
                ["kinetic-static", "washer_000", "--duration", "1 s"]):
        p = tmp_path / f"{cmd[0]}.png"
        r = runner.invoke(app, cmd + ["--plot", str(p)])
        assert r.exit_code == 0, r.output
        assert p.stat().st_size > 5000


@pytest.mark.slow
def test_plotting_module_figures():
    from autobalance.studies.washer_figures import plot_eccentricity_deviation, plot_vibratory_force_damping
    s = washer_000(Me=0.025, n=1)
    f = plot_vibratory_force_damping(s, [W, 18.0])
    assert len(f.axes) == 2
    f = plot_eccentricity_deviation(0.025 / 37, [0.1e-3], system=s, speed=W)
    assert len(f.axes[0].lines) >= 2


# ============================ tier 5: bad input ===============================================
@pytest.mark.parametrize("fn", [
    lambda s: vibratory_forces(s, -1.0, [0.0, 1.0]),
    lambda s: vibratory_forces(s, W, [0.0, 1.0, 2.0]),
    lambda s: vibratory_forces(s, W, [0.0, float("nan")]),
    lambda s: eb.rolling_deadband_single(s, W, -1e-3),
    lambda s: eb.symmetric_rolling_deviation(0.28, 0.0, 1e-4),
    lambda s: design_tolerances(0.05, 37, 0.28, W, split={"eccentricity": 0.5}),
    lambda s: design_tolerances(0.05, 37, 0.28, W, residual_fraction=2.0),
    lambda s: simulate_kinetic_static(s, W, [0.0, 1.0], -1.0),
    lambda s: find_equilibria(s, W, n_grid=1),
])
def test_bad_input_raises_parameter_error(fn):
    with pytest.raises(ParameterError) as ei:
        fn(washer_000())
    assert "\n" not in str(ei.value)


@pytest.mark.parametrize("args", [
    ["forces", "washer_000", "--angles", "1,2,3"],
    ["bounds", "washer_000", "--f-r", "-1"],
    ["kinetic-static", "washer_000", "--duration", "-2 s"],
    ["washer-study", "fig99"],
    ["equilibria", "no_such_preset"],
    ["forces", "washer_000", "--plot", "out.pdf"],
])
def test_cli_bad_input_exit_2(args):
    r = runner.invoke(app, args)
    assert r.exit_code == 2
    assert r.stderr.startswith("error: ") and r.stderr.count("\n") == 1


@pytest.mark.slow
def test_cli_forces_damping_plot_fig7(tmp_path):
    """000 Fig. 7 from the CLI: the one-ball force for suspension damping x0.5/1/2."""
    from typer.testing import CliRunner

    from autobalance.cli.analyze import app

    out = tmp_path / "fig7.png"
    r = CliRunner().invoke(app, ["forces", "washer_000", "--damping-plot", str(out), "--json"])
    assert r.exit_code == 0, r.output
    assert json.loads(r.output)["damping_plot"] == str(out)
    assert out.stat().st_size > 10_000
