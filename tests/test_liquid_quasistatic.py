"""The liquid in a displaced chamber, quasi-statically (liquid/quasistatic.py): the
circle-circle lens against an independent quadrature, mass conservation, and the classical
limits - the intact ring (rho (V_c - V) d), the thin film gathered at the wall (rho V R),
Newton's bucket in a centred chamber (003's closed forms) and the planar limit of the paraboloid."""
from __future__ import annotations

import math

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from scipy.integrate import quad

from autobalance.liquid.free_surface import free_surface
from autobalance.liquid.quasistatic import (intact_ring_unbalance, layer, lens, quasi_static)
from autobalance.models import ParameterError

RHO = 1000.0
R, H = 0.2, 0.05                                     # 003's largest bench chamber
VC = math.pi * R * R * H


def _lens_by_quadrature(a, b, D):
    """Area and x-moment of disk(a, 0) & disk(b, D) in polar coordinates about the origin: the
    arc of radius r inside disk b spans |phi| <= acos((r^2 + D^2 - b^2) / 2 r D)."""
    def half_angle(r):
        if D == 0 or r == 0:
            return math.pi if r + D < b else 0.0
        cth = (r * r + D * D - b * b) / (2 * r * D)
        return math.acos(min(max(cth, -1.0), 1.0))
    pts = [x for x in (abs(D - b), D + b) if 0 < x < a]
    area = quad(lambda r: 2 * half_angle(r) * r, 0, a, points=pts or None, epsabs=0,
                epsrel=1e-12, limit=200)[0]
    mom = quad(lambda r: 2 * math.sin(half_angle(r)) * r * r, 0, a, points=pts or None,
               epsabs=0, epsrel=1e-12, limit=200)[0]
    return area, mom


@settings(max_examples=60, deadline=None)
@given(a=st.floats(0.01, 1.0), b=st.floats(0.01, 1.0),
       D=st.one_of(st.just(0.0), st.floats(1e-6, 2.0)))
def test_lens_closed_form_against_quadrature(a, b, D):
    area, mom = lens(a, b, D)
    qa, qm = _lens_by_quadrature(a, b, D)
    assert area == pytest.approx(qa, rel=1e-8, abs=1e-12)
    assert mom == pytest.approx(qm, rel=1e-8, abs=1e-12)


@settings(max_examples=40, deadline=None)
@given(V=st.floats(0.01, 0.95), d=st.floats(0.0, 0.05), w=st.floats(5.0, 200.0),
       axis=st.sampled_from(["vertical", "planar", "horizontal"]))
def test_mass_is_conserved(V, d, w, axis):
    """The solved surface holds exactly the liquid's volume (the layers integrated again)."""
    q = quasi_static(R, H, V * VC, RHO, w, complex(d, 0.3 * d), axis=axis)
    assert q.mass == pytest.approx(RHO * V * VC)
    if axis != "vertical":
        x0 = (9.80665 / w ** 2) * 1j if axis == "horizontal" else 0j
        area, _ = layer(R, 0.0, q.surface, x0 - complex(d, 0.3 * d))
        assert area * H == pytest.approx(V * VC, rel=1e-9)


@pytest.mark.parametrize("d", [1e-4, 1e-3, 5e-3])
@pytest.mark.parametrize("V", [0.3, 0.6, 0.9])
def test_intact_ring_is_the_missing_core(V, d):
    """Planar, surface inside the wall: U = rho (V_c - V) d exactly; and along the deflection."""
    q = quasi_static(R, H, V * VC, RHO, 300.0, complex(0.0, d), axis="planar")
    assert q.regime == "ring"
    assert q.unbalance == pytest.approx(intact_ring_unbalance(RHO, VC, V * VC, complex(0.0, d)),
                                        rel=1e-9, abs=1e-15)
    # the vertical axis at high speed (Omega^2 R / g = 3700) tends to the same ring
    qv = quasi_static(R, H, V * VC, RHO, 300.0, complex(0.0, d))
    assert qv.regime == "ring" and abs(qv.unbalance - q.unbalance) <= 2e-3 * abs(q.unbalance)


def test_the_film_breaks_into_a_crescent_that_gathers_the_liquid_at_the_far_wall():
    """003's 150 ml in the 0.2 m chamber is a 2.4 mm ring: it breaks at d = 2.4 mm. As the
    deflection grows, the liquid gathers towards the wall: |U| rises from the ring's
    rho (V_c - V) d towards the all-gathered rho V R, never beyond. At d = 50 t (0.12 m) the
    surface is nearly a chord: the liquid is a thin circular segment whose centroid lies inside
    R (measured 0.92 rho V R); only V -> 0 gathers it at the wall (next test)."""
    V = 150e-6
    t = R - math.sqrt((VC - V) / (math.pi * H))            # ring thickness
    assert t == pytest.approx(2.40e-3, abs=0.01e-3)
    u = []
    for d in (0.5 * t, 0.99 * t, 1.01 * t, 2 * t, 10 * t, 50 * t):
        q = quasi_static(R, H, V, RHO, 300.0, complex(d, 0.0), axis="planar")
        assert q.regime == ("ring" if d < t else "crescent")
        assert q.unbalance.real > 0 and abs(q.unbalance.imag) < 1e-15
        u.append(q.unbalance.real)
    assert all(x < y for x, y in zip(u, u[1:]))             # gathers more as d grows
    assert 0.9 * RHO * V * R < u[-1] < RHO * V * R


def test_thin_film_limit_is_the_capacity_rho_V_R():
    """A vanishing volume in a displaced chamber is a sliver at the far wall: U / (rho V R) -> 1
    (the lumped model's capacity, docs/liquid/models.md sec. 3), from below, as V -> 0."""
    prev = 0.0
    for V in (1e-3 * VC, 1e-5 * VC, 1e-7 * VC):
        q = quasi_static(R, H, V, RHO, 300.0, 0.01 + 0j, axis="planar")
        r = q.unbalance.real / (RHO * V * R)
        assert prev < r < 1.0
        prev = r
    assert prev > 0.999


@pytest.mark.parametrize("w", [10.0, 20.0, 40.0, 80.0])
@pytest.mark.parametrize("V", [150e-6, 1.5e-3, 4.5e-3])
def test_newtons_bucket_in_a_centred_chamber_is_003s_free_surface(w, V):
    """d = 0: the paraboloid about the axis clipped to bottom and lid, i.e. 003 eq 3-5 in all
    four regimes (liquid/free_surface.py, independent closed forms): same vertex, no unbalance."""
    q = quasi_static(R, H, V, RHO, w, 0j, g=10.0)
    fs = free_surface(w, V, R, H, g=10.0)
    assert q.surface == pytest.approx(fs.z_star, rel=1e-8, abs=1e-10)
    assert abs(q.unbalance) < 1e-12
    assert q.dry_bottom == (fs.z_star < 0)


def test_horizontal_axis_liquid_sinks_below_the_axis():
    """On a horizontal axis gravity moves the surface's centre up by g/Omega^2: a centred
    chamber's liquid sits thicker at the bottom, U pointing down, |U| = rho (V_c - V) g/Omega^2
    while the ring is intact."""
    V, w = 0.5 * VC, 100.0
    q = quasi_static(R, H, V, RHO, w, 0j, axis="horizontal", up=1j)
    assert q.regime == "ring"
    assert q.unbalance == pytest.approx(-1j * RHO * (VC - V) * 9.80665 / w ** 2, rel=1e-9)


def test_bad_input_is_one_line():
    with pytest.raises(ParameterError) as e:
        quasi_static(R, H, 2 * VC, RHO, 10.0, 0j)
    assert e.value.field == "volume"
    with pytest.raises(ParameterError) as e:
        quasi_static(R, H, 0.1 * VC, RHO, 10.0, 0j, axis="diagonal")
    assert e.value.field == "axis"
    with pytest.raises(ParameterError) as e:
        quasi_static(R, H, 0.1 * VC, RHO, 0.0, 0j, axis="planar")
    assert e.value.field == "speed"
    with pytest.raises(ParameterError) as e:
        quasi_static(R, H, 0.1 * VC, RHO, 10.0, 0j, inner_radius=0.3)
    assert e.value.field == "chamber.inner_radius"


@pytest.mark.parametrize("w,V,d", [(15.0, 150e-6, 0.01), (30.0, 1.5e-3, 0.004),
                                   (60.0, 150e-6, 0.003), (60.0, 4.5e-3, 0.02),
                                   (120.0, 150e-6, 0.001)])
def test_vertical_axis_against_shells_about_the_axis(w, V, d):
    """The layers (horizontal slices, lens closed forms) against the other order of integration:
    cylindrical shells of radius r about the rotation axis, where the depth clip(z* + Omega^2
    r^2 / 2g, 0, h) is constant and the shell's arc inside the displaced chamber is
    |phi| <= acos((r^2 + d^2 - R^2) / 2 r d). Volume V and moment U / rho about the chamber
    centre agree, for wet, dry, lid-touching, ring and crescent states."""
    g = 9.80665
    q = quasi_static(R, H, V, RHO, w, complex(d, 0.0), g=g)
    a = w * w / (2 * g)

    def theta(r):
        c = (r * r + d * d - R * R) / (2 * r * d)
        return math.acos(min(max(c, -1.0), 1.0))

    def depth(r):
        return min(max(q.surface + a * r * r, 0.0), H)

    kinks = [x for x in (R - d, math.sqrt(max(-q.surface, 0) / a), math.sqrt((H - q.surface) / a))
             if 0 < x < R + d]
    vol = quad(lambda r: depth(r) * 2 * r * theta(r), 0, R + d, points=kinks, epsabs=0,
               epsrel=1e-12, limit=400)[0]
    m_axis = quad(lambda r: depth(r) * 2 * r * r * math.sin(theta(r)), 0, R + d, points=kinks,
                  epsabs=0, epsrel=1e-12, limit=400)[0]
    assert vol == pytest.approx(V, rel=1e-9)
    assert q.unbalance.real / RHO == pytest.approx(m_axis - d * V, rel=1e-7, abs=1e-14)
    assert abs(q.unbalance.imag) < 1e-12
