"""The step cap while balls touch (simulate/pack.contact_step, core/integrate.py; docs/numerics/index.md,
"Resting contacts"): the cap is two thirds of DOPRI5's stability edge on the contact's modes,
computed here from the kernel's own tableau, and 004's runs whose balls settle in contact
give the grade of a run whose steps are twenty times smaller (before the cap they missed it by
0.019 mm/s, the balls chattering at the integrator's stability edge)."""
from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from autobalance.core import step as K
from autobalance.core.layout import P_HC, S_STEPS
from autobalance.models import InitialState
from autobalance.simulate import simulate
from autobalance.simulate.pack import contact_step, pack_params
from autobalance.studies.common import case_sets, load


def _R(z):
    """DOPRI5's stability function from the kernel's tableau: 1 + z b^T (I - z A)^-1 1."""
    A = np.zeros((7, 7), complex)
    A[1, 0] = K.A21
    A[2, :2] = K.A31, K.A32
    A[3, :3] = K.A41, K.A42, K.A43
    A[4, :4] = K.A51, K.A52, K.A53, K.A54
    A[5, :5] = K.A61, K.A62, K.A63, K.A64, K.A65
    A[6, :6] = K.A71, 0.0, K.A73, K.A74, K.A75, K.A76
    return 1.0 + z * A[6] @ np.linalg.solve(np.eye(7) - z * A, np.ones(7))


@pytest.mark.parametrize("e", [0.05, 0.3, 0.5, 0.7, 0.9])
def test_contact_step_is_two_thirds_of_the_stability_edge(e):
    zeta = -math.log(e) / math.sqrt(math.pi ** 2 + math.log(e) ** 2)
    d = complex(-zeta, math.sqrt(1.0 - zeta ** 2))
    k = contact_step(zeta)
    edge = 1.5 * k
    assert abs(_R(0.999 * edge * d)) <= 1.0 < abs(_R(1.002 * edge * d))
    assert all(abs(_R(s * d)) <= 1.0 for s in np.linspace(0.05, edge * 0.999, 200))


def test_the_cap_is_packed_for_touching_balls_only():
    cfg = load("vub_jeffcott_004")
    P, B = pack_params(cfg.system, cfg.spin, cfg.options)
    wc = 5.0 * cfg.spin.nominal_speed
    zeta = -math.log(0.5) / math.sqrt(math.pi ** 2 + math.log(0.5) ** 2)
    assert P[P_HC] == pytest.approx(contact_step(zeta) / wc)
    assert 2.0 < P[P_HC] * wc < 2.1
    points = load("vub_jeffcott_004", ["balancer.contact=none"])
    assert pack_params(points.system, points.spin, points.options)[0][P_HC] == 0.0


@pytest.mark.parametrize("angles", [(0.0, 2.0 * math.pi / 3.0), (math.pi / 3.0, math.pi)])
def test_balls_settling_in_contact_give_the_resolved_grade(angles):
    """004 at a quarter of the rolling resistance and G_ini = 36.7 mm/s: the balls settle
    pressed together. The kernel's grades equal those of steps <= 0.1 ms (about 1/12 of the
    contact's period) to 2e-3 mm/s; caps of 2 and 3 / w_c agreed to 9e-4 mm/s over 1092 runs,
    and without the cap these runs gave 6.5486 instead of 6.5299 mm/s."""
    base = load("vub_jeffcott_004")
    cfg = load("vub_jeffcott_004", list(case_sets(base, 0.25, 1.0)) + ["rotor.unbalance=5.7456e-4"])
    init = InitialState(ball_angles=angles)
    opts = dataclasses.replace(cfg.options, save_dt=-1.0)
    run = simulate(cfg.system, cfg.spin, initial=init, options=opts)
    fine = simulate(cfg.system, cfg.spin, initial=init,
                    options=dataclasses.replace(opts, max_step=1e-4, rtol=1e-8))
    assert run.status == fine.status == "ok"
    np.testing.assert_allclose(run.grade_G[1:], fine.grade_G[1:], atol=2e-3)


def test_a_stuck_pair_in_contact_is_not_capped():
    """A pair of touching balls that are both stuck has no contact mode (exact stick holds
    their angles): the cap applies only while one of them slips. 004 at half the damping,
    G_ini 36.4 mm/s: the balls stick pressed together at 10.6 s, and DOPRI5 steps the rotor's
    transients after the profile's knots. With the cap there too the run took 3138 steps (877
    without); the grades are those of steps <= 0.1 ms to 2e-3 mm/s."""
    base = load("vub_jeffcott_004")
    cfg = load("vub_jeffcott_004", list(case_sets(base, 1.0, 0.5)) + ["rotor.unbalance=5.7456e-4"])
    init = InitialState(ball_angles=(math.radians(43.2), math.radians(151.2)))
    opts = dataclasses.replace(cfg.options, save_dt=-1.0)
    run = simulate(cfg.system, cfg.spin, initial=init, options=opts)
    fine = simulate(cfg.system, cfg.spin, initial=init,
                    options=dataclasses.replace(opts, max_step=1e-4, rtol=1e-8))
    assert run.status == fine.status == "ok"
    assert run.stats[S_STEPS] < 1500
    np.testing.assert_allclose(run.grade_G[1:], fine.grade_G[1:], atol=2e-3)
