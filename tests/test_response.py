"""Closed-form checks of analysis.response and analysis.iso1940 against the Jeffcott rotor and
the seed papers (000: washing machine; 004: Table 1 rig, ISO 1940 grades)."""
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from autobalance.physics import (GRADES, axis_response, ball_influence, damped_peak_speeds,
                                  damping_ratios, grade, grade_class, harmonic_response,
                                  natural_frequencies, permissible_eccentricity, response_table,
                                  steady_displacement, unbalance_for_grade)
from autobalance.models import BallBalancer, Rotor, Suspension, System

TWO_PI = 2.0 * math.pi


def rig_004():
    """004 Table 1: M = 16.53 kg, k = 5.8 kN/mm, c = 1.51 kN*s/m, 2 x 7.6 g at R = 35 mm."""
    return System(Rotor(16.53, 16.53 * 19.3e-6), Suspension.isotropic(5.8e6, 1510.0),
                  BallBalancer(2, 0.0076, 0.035, 0.004, element="point"))


def washer_000():
    """000: M = 37 kg, kx = 20 N/mm, ky = 6 N/mm, cx = 200, cy = 110 kg/s, mR = Me = 0.025."""
    return System(Rotor(37.0, 0.025), Suspension(20e3, 6e3, 200.0, 110.0),
                  BallBalancer(2, 0.025 / 0.28, 0.28, 0.01))


# -- Jeffcott closed forms ---------------------------------------------------------------------
M, K, C, U = 10.0, 4.0e5, 300.0, 2.0e-3
WN = math.sqrt(K / M)


def test_amplitude_tends_to_U_over_M_at_high_speed():
    a, phi = axis_response(M, K, C, U, 1e4 * WN)
    assert a == pytest.approx(U / M, rel=1e-6)
    assert phi == pytest.approx(math.pi, abs=1e-3)


def test_amplitude_zero_at_rest():
    a, phi = axis_response(M, K, C, U, 0.0)
    assert a == 0.0 and phi == 0.0
    a, _ = axis_response(M, K, C, U, 1e-3 * WN)
    assert a == pytest.approx(U * (1e-3 * WN) ** 2 / K, rel=1e-5)


def test_resonance_amplitude_and_phase():
    a, phi = axis_response(M, K, C, U, WN)
    assert a == pytest.approx(U * WN / C, rel=1e-12)
    assert phi == pytest.approx(math.pi / 2, abs=1e-12)


def test_undamped_resonance_is_infinite_with_quarter_phase():
    a, phi = axis_response(M, K, 0.0, U, WN)
    assert math.isinf(a) and phi == pytest.approx(math.pi / 2)
    _, phi_above = axis_response(M, K, 0.0, U, 2 * WN)
    assert phi_above == pytest.approx(math.pi)


def test_vectorised_over_speed():
    w = np.linspace(0.0, 3 * WN, 50)
    a, phi = axis_response(M, K, C, U, w)
    assert a.shape == phi.shape == (50,)
    assert np.all(np.diff(phi) >= 0.0)  # phase lag grows monotonically with speed
    for wi, ai in zip(w[::7], a[::7]):
        assert axis_response(M, K, C, U, wi)[0] == pytest.approx(ai)


def test_damped_peak_is_the_maximum():
    s = System(Rotor(M, U), Suspension.isotropic(K, 1000.0))  # zeta = 0.25
    wp = damped_peak_speeds(s)[0]
    z = damping_ratios(s)[0]
    assert wp == pytest.approx(WN / math.sqrt(1 - 2 * z * z))
    w = np.linspace(0.5 * WN, 2 * WN, 20001)
    a = harmonic_response(s, w).a_x
    assert w[np.argmax(a)] == pytest.approx(wp, rel=1e-3)
    heavy = System(Rotor(M, U), Suspension.isotropic(K, 2 * math.sqrt(K * M)))  # zeta = 1
    assert math.isinf(damped_peak_speeds(heavy)[0])


@settings(max_examples=200, deadline=None)
@given(mass=st.floats(1e-3, 1e4), k=st.floats(1.0, 1e9), c=st.floats(1e-3, 1e5),
       u=st.floats(1e-7, 1.0), w=st.floats(1e-3, 1e5))
def test_property_amplitude_phase(mass, k, c, u, w):
    a, phi = axis_response(mass, k, c, u, w)
    assert a > 0.0
    assert 0.0 <= phi <= math.pi
    assert a * abs(complex(k - mass * w * w, c * w)) == pytest.approx(u * w * w, rel=1e-9)
    # the phase is the argument of the dynamic stiffness: tan(phi) = c w / (k - M w^2)
    z = complex(k - mass * w * w, c * w)
    assert complex(math.cos(phi), math.sin(phi)) == pytest.approx(z / abs(z), abs=1e-9)


# -- systems -----------------------------------------------------------------------------------
def test_anisotropic_suspension_gives_two_natural_frequencies():
    s = washer_000()
    wx, wy = natural_frequencies(s)
    assert wx != pytest.approx(wy)
    assert (wx, wy) == pytest.approx(s.natural_frequencies)
    r = harmonic_response(s, [wy, wx])
    assert r.phi_y[0] == pytest.approx(math.pi / 2) and r.phi_x[1] == pytest.approx(math.pi / 2)
    assert r.a_y[0] == pytest.approx(0.025 * wy / 110.0)
    assert r.a_x[1] == pytest.approx(0.025 * wx / 200.0)


def test_washer_000_natural_frequencies():
    s = washer_000()
    assert s.total_mass == pytest.approx(37.0 + 2 * 0.0893, abs=1e-4)
    wx, wy = natural_frequencies(s)
    assert wx == pytest.approx(23.2, abs=0.05)
    assert wy == pytest.approx(12.7, abs=0.05)


def test_rig_004_natural_frequency():
    fx, fy = (w / TWO_PI for w in natural_frequencies(rig_004()))
    assert fx == pytest.approx(94.2, abs=0.1) and fy == fx


def test_harmonic_response_uses_total_mass_and_default_unbalance():
    s = rig_004()
    r = harmonic_response(s, 1000.0)
    a, phi = axis_response(s.total_mass, 5.8e6, 1510.0, s.rotor.unbalance, 1000.0)
    assert r.unbalance == s.rotor.unbalance
    assert (r.a_x, r.a_y, r.phi_x, r.phi_y) == pytest.approx((a, a, phi, phi))
    assert r["a_x"] == r.a_x
    assert harmonic_response(s, 1000.0, unbalance=2 * s.rotor.unbalance).a_x == pytest.approx(2 * a)


def test_ball_influence_same_transfer_as_unbalance():
    s = rig_004()
    w = np.array([300.0, 1049.0])
    b = ball_influence(s, w)
    r = harmonic_response(s, w, unbalance=1.0)
    assert b.gain_x == pytest.approx(r.a_x) and b.gain_y == pytest.approx(r.a_y)
    assert b.phi_x == pytest.approx(r.phi_x)
    assert b.a_x.shape == (2, 2)
    assert b.a_x[:, 0] == pytest.approx(0.0076 * 0.035 * r.a_x)
    none = ball_influence(System(Rotor(1.0, 1e-3), Suspension.isotropic(1e4)), 50.0)
    assert none.a_x.shape == (0,)


def test_balls_opposite_cancel_equal_unbalance():
    """000: with mR = Me and the ball at alpha = pi the quasi-steady vibration vanishes."""
    s = System(Rotor(37.0, 0.025), Suspension(20e3, 6e3, 200.0, 110.0),
               BallBalancer(1, 0.025 / 0.28, 0.28, 0.01))
    t = np.linspace(0.0, 1.0, 101)
    x, y = steady_displacement(s, 104.7, t, [math.pi])
    assert np.max(np.abs(x)) < 1e-15 and np.max(np.abs(y)) < 1e-15
    x0, _ = steady_displacement(s, 104.7, t, [0.0])
    assert np.max(np.abs(x0)) == pytest.approx(2 * harmonic_response(s, 104.7).a_x, rel=1e-3)
    with pytest.raises(ValueError, match="ball_angles"):
        steady_displacement(s, 104.7, t, [0.0, 1.0])


def test_response_table_is_json_and_consistent():
    s = washer_000()
    w = np.linspace(0.0, 60.0, 31)
    tab = response_table(s, w)
    json.loads(json.dumps(tab, allow_nan=False))
    for key in ("speed_rad_s", "amplitude_x_m", "amplitude_y_m", "phase_x_rad", "phase_y_rad"):
        assert len(tab[key]) == 31 and all(isinstance(v, float) for v in tab[key])
    assert tab["natural_frequencies_rad_s"] == pytest.approx(list(natural_frequencies(s)))
    assert tab["natural_frequencies_hz"][0] == pytest.approx(natural_frequencies(s)[0] / TWO_PI)
    assert tab["damping_ratios"] == pytest.approx(list(damping_ratios(s)))
    assert tab["amplitude_y_m"][10] == pytest.approx(harmonic_response(s, 20.0).a_y)


def test_response_table_undamped_resonance_is_json_null():
    s = System(Rotor(1.0, 1e-3), Suspension.isotropic(100.0))
    tab = response_table(s, [5.0, 10.0, 20.0])
    assert tab["amplitude_x_m"][1] is None
    assert tab["peak_speeds_rad_s"] == [10.0, 10.0]
    json.dumps(tab, allow_nan=False)


@pytest.mark.parametrize("call, field", [
    (lambda: axis_response(-1.0, K, C, U, 10.0), "mass"),
    (lambda: axis_response(M, 0.0, C, U, 10.0), "k"),
    (lambda: axis_response(M, K, -1.0, U, 10.0), "c"),
    (lambda: axis_response(M, K, C, -U, 10.0), "unbalance"),
    (lambda: axis_response(M, K, C, U, [1.0, -10.0]), "speed"),
    (lambda: axis_response(M, K, C, U, float("nan")), "speed"),
    (lambda: harmonic_response(rig_004(), -1.0), "speed"),
    (lambda: grade(1e-3, -2.0, 100.0), "mass"),
    (lambda: grade(-1e-3, 2.0, 100.0), "residual_unbalance"),
    (lambda: unbalance_for_grade(16.0, 2.0, 0.0), "nominal_speed"),
    (lambda: Rotor(-5.0), "rotor.mass"),
])
def test_bad_input_names_the_field(call, field):
    with pytest.raises(ValueError, match=field):
        call()


# -- ISO 1940 ----------------------------------------------------------------------------------
def test_iso_grade_004_table1_is_G20():
    g = grade(16.53 * 19.3e-6, 16.53, TWO_PI * 167.0)
    assert g == pytest.approx(20.0, abs=0.5)


def test_iso_grade_004_total_ball_unbalance_is_G34():
    g = grade(2 * 0.0076 * 0.035, 16.53, TWO_PI * 167.0)
    assert g == pytest.approx(34.0, abs=0.5)


def test_iso_inverse_and_vectorised():
    gs = np.array(GRADES)
    u = unbalance_for_grade(gs, 16.53, TWO_PI * 167.0)
    assert u.shape == gs.shape
    assert grade(u, 16.53, TWO_PI * 167.0) == pytest.approx(gs)
    assert permissible_eccentricity(20.0, TWO_PI * 167.0) == pytest.approx(19.06e-6, rel=1e-3)
    assert grade(0.0, 1.0, 1.0) == 0.0


def test_iso_series_and_class():
    assert GRADES[:7] == (0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0)
    assert list(grade_class([0.1, 5.0, 16.0, 20.0, 5000.0])) == [0.4, 6.3, 16.0, 40.0, math.inf]
