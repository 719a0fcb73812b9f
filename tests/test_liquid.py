"""Liquid (Leblanc) balancer: closed forms, seed numbers (003, 001), properties, trends."""
import math

import numpy as np
from scipy.integrate import trapezoid
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from autobalance.liquid import (WATER, Chamber, Liquid, LiquidBalancer, LiquidModel,
                                VerticalRotor, alpha0, alpha0_residual, balancing_efficiency,
                                bottom_touch_speed, eccentricity_ratio, entrainment_speed,
                                fill_sweep, free_surface, friction_angle, friction_force,
                                jeffcott_phase, lid_touch_speed, liquid_volume,
                                motion_mode, residual_lambda0,
                                run_up, steady_response)
from autobalance.models import ParameterError
from autobalance.papers.p001.liquids import liquids_001 as load_liquids

G = 9.80665
R, H = 0.2, 0.05
ML = 1e-6


# -- tier 1: closed forms ---------------------------------------------------------------------
def test_paraboloid_and_eq4_in_regime_A():
    """Wet bottom: z(r) = z_* + w^2 r^2/2g with z_* = h0 - w^2 R^2/4g (003 eq 3-4)."""
    V, w = 2000 * ML, 3.0
    fs = free_surface(w, V, R, H)
    assert fs.regime == "A"
    h0 = V / (math.pi * R * R)
    assert fs.z_star == pytest.approx(h0 - w * w * R * R / (4 * G), rel=1e-12)
    r = np.linspace(0, R, 7)
    assert np.allclose(fs.depth(r), fs.z_star + w * w * r * r / (2 * G), rtol=1e-12)


def test_eq5_in_regime_D_and_cylinder_limit():
    """Dry centre and lid touched: 003 eq 5; w -> inf: a cylinder r = sqrt(R^2 - V/(pi h))."""
    V, w = 300 * ML, 40.0
    fs = free_surface(w, V, R, H)
    assert fs.regime == "D" and fs.mode == 4
    z5 = (math.pi * G * H * H - (math.pi * R * R * H - V) * w * w) / (2 * math.pi * G * H)
    assert fs.z_star == pytest.approx(z5, rel=1e-12)
    fs = free_surface(1e4, V, R, H)
    r_cyl = math.sqrt(R * R - V / (math.pi * H))
    assert fs.r_dry == pytest.approx(r_cyl, rel=1e-6) and fs.r_lid == pytest.approx(r_cyl, rel=1e-6)


def test_rest_is_flat_and_speeds_are_the_regime_boundaries():
    V = 100 * ML
    fs = free_surface(0.0, V, R, H)
    assert fs.z_star == pytest.approx(V / (math.pi * R * R)) and fs.mode == 1
    wb, w0 = bottom_touch_speed(V, R), entrainment_speed(V, R, H)
    assert free_surface(wb, V, R, H).z_star == pytest.approx(0.0, abs=1e-12)
    assert free_surface(w0, V, R, H).wall_height == pytest.approx(H, rel=1e-9)
    assert lid_touch_speed(V, R, H) == pytest.approx(w0)


def test_more_than_half_full_touches_lid_first():
    """V > V_c/2: regime C (wet bottom, lid touched) between lid touch and omega_0 (our extension)."""
    V = 0.7 * math.pi * R * R * H
    wl, w0 = lid_touch_speed(V, R, H), entrainment_speed(V, R, H)
    assert wl < w0
    fs = free_surface(0.5 * (wl + w0), V, R, H)
    assert fs.regime == "C" and fs.mode == 3
    assert free_surface(1.01 * w0, V, R, H).regime == "D"


# -- tier 2: seed numbers ---------------------------------------------------------------------
def test_003_bottom_touch_speed_100ml():
    """003 sec. 5.2: omega = 0.89 1/s for 100 ml, R = 0.2 m.

    Tolerance: half a unit of the last printed digit (0.005 1/s). 003's printed speeds follow from
    g = 10 m/s^2 (0.892); with standard g we get 0.883, a miss of 0.8 % (reported in
    docs/liquid/index.md), so the published number is checked with g = 10 m/s^2.
    """
    assert bottom_touch_speed(100 * ML, R, 10.0) == pytest.approx(0.89, abs=0.005)
    assert bottom_touch_speed(100 * ML, R, G) == pytest.approx(0.8834, abs=1e-4)


@pytest.mark.parametrize("V_ml, published, tol", [(100, 28.0, 0.5), (200, 19.8, 0.05),
                                                 (300, 16.2, 0.05)])
def test_003_entrainment_speed_eq6(V_ml, published, tol):
    """003 eq 6: omega_0 = 28, 19.8, 16.2 1/s for 100, 200, 300 ml (R = 0.2 m, h = 0.05 m).

    Tolerance: half a unit of the last printed digit. Reproduced with g = 10 m/s^2 (the value
    003's numbers imply); with g = 9.80665 the 200 and 300 ml values (19.62, 16.02) miss by
    0.9-1.1 % -- reported as misses in docs/liquid/index.md, not hidden by a wider tolerance.
    """
    assert entrainment_speed(V_ml * ML, R, H, 10.0) == pytest.approx(published, abs=tol)
    assert entrainment_speed(V_ml * ML, R, H, G) == pytest.approx(
        published * math.sqrt(G / 10.0), rel=0.01)


def test_003_entrainment_within_observed_range():
    """003 sec. 5.4: observed entrainment 15-21 1/s, ~omega_r/3 (omega_r = 54): eq 6 at 200 and
    300 ml falls inside the observed range (100 ml, 27.8 1/s, is outside: 003 does not say
    which volumes the 15-21 1/s range covers)."""
    for V in (200 * ML, 300 * ML):
        assert 15.0 <= entrainment_speed(V, R, H, G) <= 21.0
    assert entrainment_speed(300 * ML, R, H, G) == pytest.approx(54 / 3, rel=0.15)


def test_001_alpha0_solves_eq2_and_limits():
    """001 eq 3 solves eq 2; k = 1 gives alpha0 = pi and lambda0 = inf (001 after eq 4)."""
    d = np.radians([5, 20, 40, 60])
    for k in (0.9, 1.3, 2.0):
        a = alpha0(d, k)
        assert np.all((a > math.pi / 2) & (a <= math.pi))
        assert np.allclose(alpha0_residual(a, d, k), 0.0, atol=1e-12)
    assert np.allclose(alpha0(d, 1.0), math.pi)
    assert np.isinf(residual_lambda0(1.0, math.pi))
    assert eccentricity_ratio(0.5, math.pi) == pytest.approx(0.5)


def test_001_friction_density_cancels():
    """001 eq 6: sin(beta) = 8 pi^2 mu R xi / (180 m omega) (xi in degrees; ours takes xi in
    rad); with mu = rho nu, m = rho V the density cancels, viscosity does not."""
    V, w, xi = 150 * ML, 30.0, math.pi
    assert math.sin(friction_angle(1e-3, R, xi, 0.15, w)) == pytest.approx(
        8 * math.pi ** 2 * 1e-3 * R * 180.0 / (180 * 0.15 * w), rel=1e-12)   # 001's form
    b = [friction_angle(rho * 1e-5, R, xi, rho * V, w) for rho in (670.0, 1000.0, 1650.0)]
    assert np.allclose(b, b[0], rtol=1e-12)
    assert friction_angle(1e-3 * 96.97, R, xi, 1000 * V, w) > 50 * friction_angle(1e-3 * 1.01, R,
                                                                                  xi, 1000 * V, w)
    ft = friction_force(1e-3, R, xi, w, 0.01)
    assert math.sin(friction_angle(1e-3, R, xi, 0.15, w)) == pytest.approx(
        ft / (0.15 * w * w * 0.01), rel=1e-12)


# -- tier 3: properties -----------------------------------------------------------------------
@settings(max_examples=150, deadline=None)
@given(w=st.floats(0, 500), fill=st.floats(1e-4, 0.999), R=st.floats(0.01, 1.0),
       h=st.floats(0.005, 0.5))
def test_volume_conserved_in_every_regime(w, fill, R, h):
    V = fill * math.pi * R * R * h
    fs = free_surface(w, V, R, h)
    assert liquid_volume(fs.z_star, w, R, h) == pytest.approx(V, rel=1e-9)
    # independent check: trapezoid in s = r^2 on a grid holding the kinks (exact for the ramp)
    a = w * w / (2 * G)
    kinks = [(-fs.z_star) / a, (h - fs.z_star) / a] if a > 0 else []
    s = np.unique(np.r_[np.linspace(0, R * R, 201), [k for k in kinks if 0 < k < R * R]])
    num = math.pi * trapezoid(fs.depth(np.sqrt(s)), s)
    assert num == pytest.approx(V, rel=1e-9)


@settings(max_examples=60, deadline=None)
@given(fill=st.floats(1e-3, 0.99), w1=st.floats(0, 200), w2=st.floats(0, 200))
def test_mode_and_vertex_monotone_in_speed(fill, w1, w2):
    V = fill * math.pi * R * R * H
    lo, hi = sorted((w1, w2))
    assert motion_mode(lo, V, R, H) <= motion_mode(hi, V, R, H)
    assert free_surface(lo, V, R, H).z_star >= free_surface(hi, V, R, H).z_star - 1e-12


@settings(max_examples=100, deadline=None)
@given(d=st.floats(0.01, 1.55), k=st.floats(0.05, 5.0))
def test_alpha0_in_balancing_half_plane(d, k):
    a = float(alpha0(d, k))
    assert math.pi / 2 - 1e-12 <= a <= math.pi + 1e-12
    if k >= math.sin(d):
        assert abs(float(alpha0_residual(a, d, k))) < 1e-9


@settings(max_examples=200, deadline=None)
@given(d=st.floats(-3.2, 3.2), k=st.floats(1e-3, 50.0), mu=st.floats(1e-5, 0.5),
       w=st.floats(-1.0, 300.0))
def test_scalar_liquid_angle_is_alpha0_minus_beta(d, k, mu, w):
    """The integrator's scalar alpha0 - beta (kinetostatic.liquid_angle_scalar) is the same
    formula as the vectorised alpha0 (001 eq 3) and friction_angle (001 eq 6)."""
    from autobalance.liquid.kinetostatic import liquid_angle_scalar
    a = liquid_angle_scalar(d, k, mu, 0.2, math.pi, 0.15, w)
    beta = 0.5 * math.pi if w <= 0 else float(friction_angle(mu, 0.2, math.pi, 0.15, w))
    assert isinstance(a, float) and a == pytest.approx(float(alpha0(d, k)) - beta, abs=1e-12)


# -- dynamics: bench behaviour (003) and 001 trends --------------------------------------------
MODEL = LiquidModel()   # the lumped model's defaults (docs/liquid/models.md sec. 3)


@pytest.fixture(scope="module")
def bench():
    from autobalance.papers.p003.bench import bench
    return bench()


def test_bench_preset(bench):
    """003's bench (papers/p003/bench.py) is the leblanc_003 machine through liquid_parts."""
    assert bench.rotor.natural_frequency(bench.balancer.mass) == pytest.approx(54.0)
    assert bench.balancer.arc == pytest.approx(math.pi) and bench.balancer.liquid.name == "water"
    assert (bench.omega_end, bench.duration) == (100.0, 20.0)
    assert bench.balancer.capacity == pytest.approx(bench.rotor.unbalance)  # 150 ml x 0.2 m
    assert set(load_liquids()) >= {"water", "light_670", "heavy_1650", "viscous_97"}


def test_entrainment_and_subcritical_onset(bench):
    """003: no balancing before entrainment (~omega_r/3), balancing from ~omega_r/2.

    The onset is where chi (0 at omega_0 of eq 6, 1 at engagement_ratio*omega_0) makes the
    liquid act; engagement_ratio = 1.5 is an input calibrated on 003 Fig. 7a-b, so this checks
    the chain, not an independent prediction (docs/liquid/index.md).
    """
    wr = 54.0
    r = steady_response(bench.rotor, bench.balancer, [wr / 3, wr / 2, 0.6 * wr], MODEL)
    assert r["efficiency"][0] == pytest.approx(1.0, abs=0.02)
    assert r["efficiency"][1] > 1.3 and r["efficiency"][2] > 10
    r300 = steady_response(bench.rotor, replace_volume(bench, 300 * ML), [30.0], MODEL)
    assert abs(r300["liquid_angle_deg"][0]) > 150  # 003 Fig. 7b: "almost opposite" at 30 1/s


def replace_volume(bench, V):
    from dataclasses import replace
    return replace(bench.balancer, volume=V)


def test_optimum_fill_and_overfill(bench):
    """003 sec. 5.3: optimum ~150 ml (R = 0.2 m, 3000 g*cm); over-filling worsens (001, 003)."""
    vols = np.array(bench.sweep_volumes)
    for f in (0.8, 1.0, 1.2):
        s = fill_sweep(bench.rotor, bench.balancer, vols, f * 54.0, MODEL)
        assert s["optimum_volume_m3"] == pytest.approx(150 * ML)
        amp = dict(zip(np.round(vols / ML), s["amplitude_m"]))
        assert amp[300] > 3 * amp[150] and amp[350] > amp[250]


def test_larger_chamber_balances_better(bench):
    """003 sec. 5.3, Fig. 6: R = 0.2 m more effective than 0.15 and 0.1 m (same 150 ml)."""
    from dataclasses import replace
    amps = [steady_response(bench.rotor, replace(bench.balancer, chamber=Chamber(r, H)), [54.0],
                            MODEL)["amplitude_m"][0] for r in (0.1, 0.15, 0.2)]
    assert amps[0] > amps[1] > amps[2]


def test_001_viscosity_matters_more_than_density(bench):
    """001: "mass forces have less effect on the balancing efficiency than viscosity".

    Each liquid at its own optimum fill (k = 1). The efficiency then depends on beta of 001
    eq 6 only, sin(beta) ~ nu/(V omega) with V = D/(rho R), i.e. ~ nu*rho: over 001's density range
    (670-1650, x2.5) it changes 2.5x, over its viscosity range (1.01e-6-97e-6, x96) ~97x.
    """
    from dataclasses import replace
    out = {}
    for name, L in load_liquids().items():
        V = bench.rotor.unbalance / (L.density * R)  # optimum fill (k = 1) for this liquid
        b = replace(bench.balancer, liquid=L, volume=V)
        out[name] = steady_response(bench.rotor, b, [50.0], MODEL)["efficiency"][0]
    by_density = out["light_670"] / out["heavy_1650"]
    by_viscosity = out["water"] / out["viscous_97"]
    assert by_density == pytest.approx(1650 / 670, rel=0.02)
    assert by_viscosity > 10 * by_density


def test_001_efficiency_rises_toward_critical(bench):
    """001: efficiency rises as omega approaches the critical speed (viscous liquid, k = 1:
    beta of eq 6 falls as 1/omega)."""
    from dataclasses import replace
    L = load_liquids()["viscous_97"]
    b = replace(bench.balancer, liquid=L, volume=bench.rotor.unbalance / (L.density * R))
    e = steady_response(bench.rotor, b, [35.0, 42.0, 50.0], MODEL)["efficiency"]
    assert e[0] < e[1] < e[2]


def test_001_damping_trend_is_a_miss():
    """MISS (docs/liquid/index.md): 001 states that efficiency rises with external damping (larger
    phase angle delta). Its own eq 3 gives, at fixed k != 1, alpha0 moving away from pi as delta
    grows, so e/e_c falls with damping; at k = 1 it is independent of delta. We report the
    computed trend and do not reproduce 001's claim."""
    d = jeffcott_phase(0.8, np.array([0.05, 0.1, 0.2]))
    e = balancing_efficiency(1.2, d)
    assert e[0] > e[1] > e[2]
    assert np.allclose(balancing_efficiency(1.0, d, 0.1), balancing_efficiency(1.0, d[0], 0.1))


def test_classical_law_gives_no_subcritical_balancing(bench):
    """Contrast: with the liquid on the deflection side (classical centrifugal equilibrium) the
    liquid adds to the unbalance below resonance."""
    r = steady_response(bench.rotor, bench.balancer, [35.0, 45.0],
                        LiquidModel(placement="deflection"))
    assert np.all(r["efficiency"] < 1.0)


@pytest.mark.slow
def test_run_up_through_resonance(bench):
    """Run-up 0 -> 100 1/s in 20 s: the liquid removes the resonance peak (efficiency > 5)."""
    ru = run_up(bench.rotor, bench.balancer, MODEL, 100.0, 20.0, n_out=400)
    s = ru.summary()
    assert s["peak_amplitude_dry_m"] > 5 * s["peak_amplitude_m"]
    assert 45.0 < s["peak_speed_dry_rad_s"] < 65.0
    assert abs(s["final_liquid_angle_deg"]) > 170


# -- bad input --------------------------------------------------------------------------------
@pytest.mark.parametrize("call", [
    lambda: free_surface(10.0, 7e-3, R, H),           # V > chamber (6.28 l)
    lambda: free_surface(10.0, 1e-4, -0.2, H),        # negative radius
    lambda: free_surface(10.0, -1e-4, R, H),          # negative volume
    lambda: Chamber(0.2, -0.05),
    lambda: Liquid(1000.0, 0.0),                      # viscosity <= 0
    lambda: Liquid(1000.0, -1e-6),
    lambda: LiquidBalancer(Chamber(0.1, 0.05), WATER, 2e-3),
    lambda: friction_angle(0.0, R, math.pi, 0.15, 30.0),
    lambda: alpha0(0.3, -1.0),
    lambda: VerticalRotor(-1.0, 1e5, 10.0, 0.03),
    lambda: LiquidModel(placement="magic"),
])
def test_bad_input_one_line_errors(call):
    with pytest.raises(ParameterError) as e:
        call()
    assert "\n" not in str(e.value) and "=" in str(e.value)
