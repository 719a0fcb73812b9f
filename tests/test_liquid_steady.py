"""The synchronous whirl with the liquid quasi-static in the displaced chamber
(liquid/steady.py): the intact-ring limit in closed form (a full chamber's mass), the
empty-chamber limit, the roots really solve the rotor's balance, and the classical direction of
the effect: the liquid reduces the whirl above resonance and increases it below."""
from __future__ import annotations

import math

import numpy as np
import pytest

from autobalance.models.liquid_balancer import VerticalRotor
from autobalance.liquid.quasistatic import quasi_static
from autobalance.liquid.steady import response_curve, ring_response, synchronous_deflection
from autobalance.models import ParameterError

M, RHO, R, H = 25.0, 1000.0, 0.2, 0.05                 # 003's bench (mass: our choice)
VC = math.pi * R * R * H
K = (M + RHO * 150e-6) * 54.0 ** 2                       # resonance 54 1/s with 150 ml (003)
C = 0.1 * 2 * math.sqrt(K * (M + RHO * 150e-6))
BENCH = VerticalRotor(M, K, C, 0.03)                     # D = 3000 g cm (003)


def _dry(W, m=M):
    return W * W * BENCH.unbalance / (K - m * W * W + 1j * C * W)


@pytest.mark.parametrize("W", [40.0, 54.0, 80.0])
def test_an_intact_ring_adds_a_full_chambers_mass_and_balances_nothing(W):
    """Planar axis, small unbalance (the ring stays intact): w = Omega^2 D / (k - (M + rho V_c)
    Omega^2 + i c Omega) exactly."""
    rot = VerticalRotor(M, K, C, 1e-5)
    V = 0.5 * VC
    w = synchronous_deflection(rot, R, H, V, RHO, W, axis="planar")
    assert quasi_static(R, H, V, RHO, W, w, axis="planar").regime == "ring"
    assert w == pytest.approx(ring_response(rot, VC, V, RHO, W), rel=1e-9)


def test_a_vanishing_fill_is_the_empty_rotor():
    """1 mm^3 of water: a sliver gathered at the wall, |U_l| <= rho V R = 2e-7 kg m against
    D = 0.03 kg m: the empty rotor to that ratio."""
    V = 1e-9
    w = synchronous_deflection(BENCH, R, H, V, RHO, 60.0)
    assert w == pytest.approx(_dry(60.0), rel=2 * RHO * V * R / BENCH.unbalance)


@pytest.mark.parametrize("W", [35.0, 50.0, 65.0])
def test_the_roots_solve_the_rotor_balance(W):
    """G(w) = (k - (M + m_l) W^2 + i c W) w - W^2 (D + U_l(w)) = 0, U_l from quasi_static with
    gravity along the axis."""
    V = 150e-6
    w = synchronous_deflection(BENCH, R, H, V, RHO, W)
    q = quasi_static(R, H, V, RHO, W, w)
    G = (K - (M + q.mass) * W * W + 1j * C * W) * w - W * W * (BENCH.unbalance + q.unbalance)
    assert abs(G) <= 1e-8 * K * abs(w)


@pytest.mark.slow
def test_the_liquid_helps_only_above_resonance():
    """003's bench with 150 ml: the liquid lowers the resonance and the whirl above it, and
    raises the whirl below it (measured: peak 54.5 -> 50.5 1/s; at 0.8 omega_r 1.92 -> 2.87 mm,
    at 1.2 omega_r 3.48 -> 2.08 mm)."""
    sp = np.linspace(40.0, 70.0, 61)
    up, down = response_curve(BENCH, R, H, 150e-6, RHO, sp)
    assert np.all(np.isfinite(up)) and np.allclose(up, down)
    dry = np.abs(_dry(sp))
    assert sp[np.argmax(np.abs(up))] < sp[np.argmax(dry)] - 2.0
    below, above = sp < 0.85 * 54.0, sp > 1.15 * 54.0
    assert np.all(np.abs(up[below]) > dry[below])
    assert np.all(np.abs(up[above]) < dry[above])


def test_bad_speeds_are_refused():
    with pytest.raises(ParameterError) as e:
        response_curve(BENCH, R, H, 150e-6, RHO, [50.0, 40.0])
    assert e.value.field == "speeds"
