"""Annular chambers: ``liquid.inner_radius`` in the config, the entrainment speed of
an annulus, the quasi-static liquid and the film model with an inner wall, 003's concentric
chambers."""
from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from autobalance.config import ConfigError, describe, load_config
from autobalance.liquid.free_surface import entrainment_speed
from autobalance.liquid.quasistatic import quasi_static
from autobalance.liquid.simulate import liquid_parts, simulate_liquid
from autobalance.models import LiquidDevice, ParameterError, SpeedProfile

G = 9.80665


# -- the closed forms ---------------------------------------------------------------------------
@settings(max_examples=200, deadline=None)
@given(R=st.floats(0.05, 0.5), ri_f=st.floats(0.0, 0.95), h=st.floats(0.01, 0.2),
       fill=st.floats(0.01, 0.99))
def test_annulus_entrainment_speed_spans_bottom_to_lid(R, ri_f, h, fill):
    """At omega_0 the surface r^2 = r_b^2 + 2 g z / omega^2 spans bottom to lid inside the
    annulus (r_i <= r_b, r_t <= R, one of them an equality) and holds exactly V:
    V = pi h (R^2 - r_b^2) - pi g h^2 / omega^2 (our derivation, free_surface.py)."""
    ri = ri_f * R
    vc = math.pi * (R * R - ri * ri) * h
    V = fill * vc
    w = entrainment_speed(V, R, h, G, inner_radius=ri)
    s = 2 * G * h / w ** 2                                    # r_t^2 - r_b^2
    rb2 = R * R - V / (math.pi * h) - 0.5 * s                  # from the volume balance
    assert rb2 >= ri * ri * (1 - 1e-9) - 1e-15 and rb2 + s <= R * R * (1 + 1e-9)
    assert min(rb2 - ri * ri, R * R - rb2 - s) == pytest.approx(0.0, abs=1e-9 * R * R)
    assert math.pi * h * (R * R - rb2) - math.pi * G * h * h / w ** 2 == \
        pytest.approx(V, rel=1e-9)


def test_annulus_entrainment_equals_003_eq6_up_to_half_filling():
    """003 eq 6 (the cylinder) holds in the annulus for V <= V_c/2 of the annulus."""
    for V in (50e-6, 150e-6, 350e-6):
        assert entrainment_speed(V, 0.2, 0.05, G, inner_radius=0.15) == \
            entrainment_speed(V, 0.2, 0.05, G)
    vc = math.pi * (0.2 ** 2 - 0.15 ** 2) * 0.05
    assert entrainment_speed(0.9 * vc, 0.2, 0.05, G, inner_radius=0.15) == \
        pytest.approx(math.sqrt(math.pi * G * 0.05 ** 2 / (0.1 * vc)), rel=1e-12)


@settings(max_examples=60, deadline=None)
@given(ri_f=st.floats(0.0, 0.9), fill=st.floats(0.05, 0.6), c=st.floats(0.0, 0.02),
       w=st.floats(25.0, 120.0))
def test_quasi_static_annulus_keeps_the_volume_and_equals_the_cylinder_off_the_inner_wall(
        ri_f, fill, c, w):
    """The annulus' liquid keeps its mass; while the free surface stays off the inner wall (the
    surface of the same liquid in the cylinder lies outside r_i + |c| at every height) the
    liquid cannot tell the inner wall is there: the same unbalance as in the cylinder."""
    R, h, rho = 0.2, 0.05, 1000.0
    ri = ri_f * R
    V = fill * math.pi * (R * R - ri * ri) * h
    qa = quasi_static(R, h, V, rho, w, complex(c, 0.0), inner_radius=ri, g=G)
    assert qa.mass == pytest.approx(rho * V, rel=1e-12)
    qc = quasi_static(R, h, V, rho, w, complex(c, 0.0), g=G)
    # the cylinder's surface at the lid z = h: r_s^2 = (h - z*) 2 g / w^2 (z* its vertex)
    r_lid = math.sqrt(max((h - qc.surface) * 2 * G / w ** 2, 0.0))
    if r_lid > ri + c + 1e-6 and not qc.dry_bottom:
        assert qa.unbalance == pytest.approx(qc.unbalance, rel=1e-7, abs=1e-12)


# -- the config -----------------------------------------------------------------------------
def test_config_key_volume_and_one_line_errors():
    cfg = load_config("leblanc_003")
    L = cfg.system.liquid
    assert L.inner_radius == pytest.approx(0.15)              # 003's outer concentric chamber
    assert L.chamber_volume == pytest.approx(math.pi * (0.2 ** 2 - 0.15 ** 2) * 0.05)
    assert describe(cfg)["liquid"]["inner_radius_m"] == pytest.approx(0.15)
    assert load_config("leblanc_003", ["liquid.inner_radius=10 cm"]).system.liquid.inner_radius \
        == pytest.approx(0.1)
    for bad in ("liquid.inner_radius=0.2 m", "liquid.inner_radius=-1 cm"):
        with pytest.raises((ConfigError, ParameterError), match="liquid.inner_radius") as e:
            load_config("leblanc_003", [bad])
        assert "\n" not in str(e.value)
    with pytest.raises(ParameterError, match="pi \\(R\\^2 - r_i\\^2\\) h"):     # over the annulus
        LiquidDevice(0.2, 0.05, 3e-3, inner_radius=0.15)
    assert LiquidDevice(0.2, 0.05, 3e-3).chamber_volume > 3e-3     # fits the cylinder


def test_bench_chambers_are_concentric():
    """003's three concentric chambers: each one's inner wall is the next smaller one's."""
    from autobalance.papers.p003.bench import bench

    b = bench()
    assert [b.balancer_with(radius=R).chamber.inner_radius for R in b.radii] == [0.0, 0.1, 0.15]
    assert b.balancer.chamber.inner_radius == 0.15
    with pytest.raises(ParameterError, match="radius"):
        b.balancer_with(radius=0.3)


# -- the film model -------------------------------------------------------------------------
def test_film_run_does_not_see_an_inner_wall_it_does_not_reach():
    """The wall film of 003's bench gives the same run in the annulus as in the cylinder: the
    film (a few mm) stays far from the inner wall 50 mm inside."""
    spin = SpeedProfile.constant(40.0, 1.0)
    a = simulate_liquid(load_config("leblanc_003").system, spin, n_cells=64, n_out=101)
    c = simulate_liquid(load_config("leblanc_003", ["liquid.inner_radius=0 m"]).system, spin,
                        n_cells=64, n_out=101)
    assert a.status == "ok" and a.message == ""
    np.testing.assert_array_equal(a.deflection, c.deflection)


def test_film_reaching_the_inner_wall_is_outside_the_model():
    """A nearly full narrow annulus: the displaced film gathers and reaches the inner wall;
    the run says so (status outside_model, with the time), it does not pass as a result."""
    s = load_config("leblanc_003", ["liquid.inner_radius=0.195 m", "liquid.volume=290 ml"]).system
    sim = simulate_liquid(s, SpeedProfile.constant(70.0, 2.0), n_cells=64, n_out=101)
    assert sim.status == "outside_model"
    assert "inner wall" in sim.message and "\n" not in sim.message
    assert sim.summary()["status"] == "outside_model"


def test_liquid_parts_carries_the_inner_wall():
    rotor, bal = liquid_parts(load_config("leblanc_003").system)
    assert bal.chamber.inner_radius == 0.15
    assert bal.chamber.volume == pytest.approx(math.pi * (0.2 ** 2 - 0.15 ** 2) * 0.05)
