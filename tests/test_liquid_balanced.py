"""The balanced state of balls beside a liquid (studies/liquid_balanced.py,
docs/liquid/stability.md sec. 3k): its linearisation against the run of balls beside a liquid, against the liquid alone and
the balls alone, and its refusals."""
from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from autobalance.config import load_config
from autobalance.core.hybrid import hybrid_integrate
from autobalance.core.layout import carry_size
from autobalance.liquid.film import films_state
from autobalance.liquid.simulate import film_rotor
from autobalance.liquid.start import pool_machine
from autobalance.liquid.stability import ring_stability
from autobalance.models import InitialState, ParameterError, SimOptions, SpeedProfile
from autobalance.physics.equilibria import find_equilibrium_set
from autobalance.simulate.pack import run_inputs
from autobalance.studies.equilibria import linearised_full
from autobalance.studies.liquid_balanced import balanced_stability

# two 80 g balls on 0.25 m beside 003's chamber (150 ml): capacity 0.04 kg*m > D = 0.03 kg*m
BALLS = ("balancer.n_balls=2", "balancer.ball_mass=0.08 kg", "balancer.race_radius=0.25 m",
         "balancer.ball_radius=10 mm", "balancer.damping=2.7 N*mm*s/rad",
         "balancer.rolling_resistance=0")


def machine(*sets):
    return load_config("leblanc_003", [*BALLS, *sets]).system


def balanced(system, speed, family=False):
    es = find_equilibrium_set(pool_machine(system), speed, method="closed_form", n_samples=4)
    if family:
        return [p.alpha for f in es.families for p in f.points if not p.overlap]
    return [e.alpha for e, b in zip(es.isolated, es.balanced) if b and not e.overlap]


def film_run_slope(system, speed, alpha, end, n_cells=64):
    """The run of balls beside a liquid (core/hybrid.py) at a constant speed from the balanced
    state, every film uniform and at rest on its wall, the first ball 1e-8 rad off: the slope of
    log |w| over the run's second half [1/s]."""
    spin = SpeedProfile.constant(speed, end)
    init = InitialState(ball_angles=tuple(np.asarray(alpha) + [1e-8, 0.0]))
    opts = SimOptions(save_dt=0.01, rtol=1e-9)
    P, B, y, _, prof_t, prof_w, t_end, unb_t, unb_u, out_t, out_y, stats, atol, h_max = \
        run_inputs(system, spin, init, opts, liquid_ok=True)
    liq = system.liquid
    ch = liq.chambers
    st = films_state([c.chamber_radius for c in ch], [c.chamber_height for c in ch],
                     [c.volume for c in ch], liq.density, liq.kinematic_viscosity, n_cells,
                     [c.partitions for c in ch], 0.0, 0j)
    none = np.zeros((1, st.h.size))
    steps = hybrid_integrate(P, B, 2, prof_t, prof_w, unb_t, unb_u, y, 0.0, t_end, opts.rtol,
                             atol, h_max, 10 ** 7, out_t, out_y, stats,
                             np.zeros(carry_size(2)), st.h, st.q, st.theta, st.starts, st.Rs,
                             st.Hs, st.rhos, st.nus, st.wall, 0.0, 0.0, 0j, np.zeros(1), none,
                             none.copy(), np.zeros(1))
    assert steps > 100 and stats[0] == 0.0
    late = out_t > end / 2
    return np.polyfit(out_t[late], np.log(np.hypot(out_y[late, 0], out_y[late, 1])), 1)[0]


@pytest.mark.parametrize("speed, end", [(60.0, 6.0),
                                        pytest.param(80.0, 12.0, marks=pytest.mark.slow),
                                        pytest.param(100.0, 20.0, marks=pytest.mark.slow)])
def test_growth_rate_is_the_runs(speed, end):
    """The run of balls beside a liquid from 1e-8 rad off the balanced state grows or decays at
    the linearisation's rate. Measured: 2.636 vs 2.637, 0.359 vs 0.357, -0.102 vs -0.096 1/s
    (the fit through the beats of two modes: tolerance 0.02 1/s)."""
    s = machine()
    a = balanced(s, speed)[0]
    r = balanced_stability(s, speed, a)
    assert film_run_slope(s, speed, a, end) == pytest.approx(r.growth_rate, abs=0.02)


@pytest.mark.parametrize("n, tol", [(64, 0.02), pytest.param(256, 0.005, marks=pytest.mark.slow)])
def test_massless_balls_leave_the_liquid_alone(n, tol):
    """Balls of 1e-8 kg (D 1e-9 kg*m) do not change the rotor with its films: the growth rate is
    the liquid-alone linearisation's (liquid/stability.ring_stability, sw_coupled's scheme; the
    two couple the films through different rotor steps, RK4 on Z = M_t w + U and the exact
    propagator of w). Measured at 60 1/s: 1.804 vs 1.795 on 64 cells, 1.895 vs 1.893 on 256;
    the rotor's lag of U' dt / M_t every step (core/hybrid.py) would give 1.31."""
    s = machine("balancer.ball_mass=1e-8 kg", "rotor.unbalance=1e-9 kg*m")
    a = balanced(s, 60.0)[0]
    c, liq = s.liquid.chambers[0], s.liquid
    r = balanced_stability(s, 60.0, a, n_cells=n)
    ring = ring_stability(film_rotor(s), c.chamber_radius, c.chamber_height, c.volume, 60.0,
                          density=liq.density, viscosity=liq.kinematic_viscosity, n_cells=n)
    assert r.growth_rate == pytest.approx(ring.growth_rate, abs=tol)


def test_massless_liquid_leaves_the_balls_alone():
    """A liquid of 1e-3 kg/m^3 leaves the balls' linearised full model (studies/equilibria.
    linearised_full) among the eigenvalues: measured within 2e-6 1/s at 100 1/s."""
    s = machine("liquid.density=0.001 kg/m^3")
    a = balanced(s, 100.0)[0]
    r = balanced_stability(s, 100.0, a)
    lam = linearised_full(pool_machine(s), 100.0, a)["eigenvalues_1_s"]
    for v in lam:
        assert np.min(np.abs(r.eigenvalues - v)) < 1e-4


@pytest.mark.slow
def test_three_balls_drop_the_family():
    """Three balls: a balanced family; its one neutral direction is dropped with the volume's
    (the map's size less 2), and every sample point is judged."""
    s = machine("balancer.n_balls=3")
    pts = balanced(s, 100.0, family=True)
    assert len(pts) >= 2
    for a in pts:
        r = balanced_stability(s, 100.0, a, family=True)
        assert r.eigenvalues.size == 2 * 3 + 4 + 2 + 2 * 64 - 2
        assert np.isfinite(r.growth_rate)


@pytest.mark.parametrize("sets, field", [
    (("suspension.ky=80000 N/m",), "suspension"),
    (("liquid.axis=horizontal",), "gravity.g"),        # a horizontal axis needs its gravity
    (("balancer.n_balls=0",), "machine"),
])
def test_refusals_are_one_line(sets, field):
    with pytest.raises(ParameterError) as e:
        balanced_stability(load_config("leblanc_003", [*BALLS, *sets]).system, 60.0, [0.0, 1.0])
    assert str(e.value).startswith(field) and "\n" not in str(e.value)


def test_not_balanced_is_refused():
    s = machine()
    with pytest.raises(ParameterError, match="^alpha.*not a balanced state"):
        balanced_stability(s, 60.0, [0.0, 1.0])
    with pytest.raises(ParameterError, match="^n_cells"):
        balanced_stability(s, 60.0, balanced(s, 60.0)[0], n_cells=4)


def test_pool_machine_keeps_the_total_mass():
    s = machine()
    p = pool_machine(s)
    assert p.liquid is None and p.total_mass == pytest.approx(s.total_mass, rel=1e-15)
    bare = dataclasses.replace(s, liquid=None)
    assert pool_machine(bare) is bare


@pytest.mark.slow
def test_speed_map_beside_a_liquid():
    """`study speed-map` beside a liquid: below the film's start (003 eq 6) the verdicts are the
    balls' on the machine with the liquid's mass in the rotor; from there only the balanced
    states are judged, each as balanced_stability judges it, and a range's edge is where its
    growth rate changes sign. Measured on this machine: stable from 89.8 1/s (quick grid)."""
    from autobalance.config import from_models, load_config
    from autobalance.studies._speed_map import compute_speed_map

    cfg = load_config("leblanc_003", list(BALLS))
    s = cfg.system
    w = [20.0, 40.0, 60.0, 100.0, 125.0]
    ds = compute_speed_map(cfg, speeds=w, damping_factors=[1.0])
    w0 = ds.attrs["film_from_rad_s"]
    assert 20.0 < w0 < 40.0 and ds.attrs["method"] == "eigenvalues+films"
    np.testing.assert_array_equal(ds["liquid_film"].values, [0, 1, 1, 1, 1])
    pool = compute_speed_map(from_models(pool_machine(s), cfg.spin), speeds=[20.0],
                             damping_factors=[1.0])
    for v in ("balanced_exists", "balanced_stable", "n_isolated", "best_kind"):
        assert ds[v].values[0] == pool[v].values[0], v
    for k, wk in enumerate(w[1:], 1):
        r = balanced_stability(s, wk, balanced(s, wk)[0])
        assert ds["balanced_stable"].values[k] == int(r.stable), wk
    assert list(ds["balanced_stable"].values[1:]) == [0, 0, 1, 1]
    (lo, hi), = ds.attrs["stable_ranges_rad_s"].reshape(-1, 2)
    assert hi == 125.0
    assert balanced_stability(s, lo * 0.998, balanced(s, lo)[0]).growth_rate > 0
    assert balanced_stability(s, lo * 1.002, balanced(s, lo)[0]).growth_rate < 0


def test_speed_map_beside_a_liquid_refusals():
    from autobalance.studies._speed_map import compute_speed_map

    cfg = load_config("leblanc_003", list(BALLS))
    with pytest.raises(ParameterError, match="^full"):
        compute_speed_map(cfg, speeds=[50.0], full=False)
    with pytest.raises(ParameterError, match="^balancer.eccentricity"):
        compute_speed_map(load_config("leblanc_003", [*BALLS, "balancer.eccentricity=1 mm"]),
                          speeds=[50.0])


def test_machine_stability_over_speed():
    """balanced_machine_stability: below the film's start the balls' linearised model of the
    pool machine (its largest multiplier over a revolution), from there balanced_stability; NaN
    where the balls' capacity is short. Measured: unstable from the grid's start to 89.8 1/s."""
    from autobalance.studies.liquid_balanced import balanced_machine_stability

    s = machine()
    r = balanced_machine_stability(s, [15.0, 60.0, 100.0])
    assert r["film_from_rad_s"] == pytest.approx(22.66, abs=0.01)
    lf = linearised_full(pool_machine(s), 15.0, r["ball_angles_rad"][0])
    assert r["growth_rate_1_s"][0] == pytest.approx(
        np.log(lf["max_modulus"]) * 15.0 / (2 * np.pi), rel=1e-12)
    for k, w in ((1, 60.0), (2, 100.0)):
        assert r["growth_rate_1_s"][k] == pytest.approx(
            balanced_stability(s, w, r["ball_angles_rad"][k]).growth_rate, rel=1e-12)
    assert r["growth_rate_1_s"][0] > 0 and r["growth_rate_1_s"][1] > 0 > r["growth_rate_1_s"][2]
    short = balanced_machine_stability(machine("balancer.ball_mass=0.05 kg"), [60.0])
    assert np.isnan(short["growth_rate_1_s"]).all() and short["unstable_ranges_rad_s"] == []


@pytest.mark.slow
def test_liquid_stability_cli_takes_balls(tmp_path):
    import json
    import subprocess
    import sys

    png = tmp_path / "s.png"
    r = subprocess.run([sys.executable, "-m", "autobalance", "liquid", "stability",
                        "leblanc_003", *[f"--set={x}" for x in BALLS], "--speeds",
                        "60:120 rad/s:7", "--json", "--plot", str(png)],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert len(d["growth_rate_1_s"]) == 7 and len(d["ball_angles_rad"]) == 7
    assert png.stat().st_size > 0 and "balanced state" in d["model"]
    (lo, hi), = d["unstable_ranges_rad_s"]
    assert lo == 60.0 and 85.0 < hi < 95.0


@pytest.mark.slow
def test_immobility_beside_a_liquid():
    """`study immobility` beside a liquid: the balls at rest on the steady orbit with the
    quasi-static liquid (studies/immobility.liquid_response). Below the film's start the liquid
    is a pool and the shares are the pool machine's (the Jeffcott orbit is linear in U_t, so
    the table's interpolation is exact); the response at a tabulated magnitude is
    chambers_steady_response's, turned to U_t's angle; G* is NaN."""
    from autobalance.config import from_models
    from autobalance.models.liquid_balancer import VerticalRotor
    from autobalance.liquid.start import film_start_speed
    from autobalance.liquid.steady import chambers_steady_response
    from autobalance.studies._immobility import compute_immobility, liquid_response

    cfg = load_config("leblanc_003", [*BALLS, "balancer.rolling_resistance=0.01"])
    s = cfg.system
    w0 = film_start_speed(s.liquid)
    f = np.array([0.5, 0.9, 1.5, 2.4, 3.0]) * w0 / (2 * np.pi)        # [Hz]
    ds = compute_immobility(cfg, G_ini=20.0, speeds=2 * np.pi * np.asarray(f), n_conf=24)
    pool = compute_immobility(from_models(pool_machine(s), cfg.spin), G_ini=20.0,
                              speeds=2 * np.pi * np.asarray(f), n_conf=24)
    below = f * 2 * np.pi < w0
    np.testing.assert_allclose(ds["immobility"].values[..., below],
                               pool["immobility"].values[..., below], atol=1e-12)
    assert not np.allclose(ds["immobility"].values[..., ~below],      # the film matters
                           pool["immobility"].values[..., ~below])
    assert np.isnan(ds["G_stick"].values).all() and np.isfinite(pool["G_stick"].values).all()
    assert "quasi-static liquid" in ds.attrs["method"]
    # the table at a tabulated magnitude, turned to U_t's angle
    W = 2 * np.pi * f
    resp = liquid_response(s, W, 5)
    D = (abs(s.rotor.unbalance) + s.balancer.capacity) / 2          # the table's middle point
    r, sus, b = s.rotor, s.suspension, s.balancer
    ch = [(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume) for c in s.liquid.chambers]
    ref = chambers_steady_response(VerticalRotor(r.mass + b.total_mass, sus.kx, sus.cx, D), ch,
                                   s.liquid.density, W)["deflection_m"]
    for k, w in enumerate(W):
        got = resp(w, np.array([D * np.exp(0.7j)]))[0]
        assert got == pytest.approx(ref[k] * np.exp(0.7j), rel=1e-12)


def test_immobility_refuses_partitions():
    """The steady orbit of `study immobility` beside a liquid is the quasi-static liquid's,
    which has no partitions: one line naming them, not the shares of the open chamber with
    exit 0."""
    from autobalance.studies._immobility import compute_immobility

    cfg = load_config("leblanc_003", [*BALLS, "liquid.partitions=4"])
    with pytest.raises(ParameterError) as e:
        compute_immobility(cfg, speeds=[10.0, 20.0], n_conf=12)
    assert e.value.field == "liquid.partitions" and "quasi-static" in str(e.value)


def test_partitions_take_the_runs_cells():
    """Partitions that do not divide the cells: the films are the runs' own (cells rounded up
    to whole compartments, 64 -> 66 for 3 walls), for balls beside the liquid and for the
    liquid alone. Before, both refused 64 cells, and the speed map counted every speed with a
    film as 'no verdict' and reported the machine stable at no speed with exit 0."""
    from autobalance.liquid.stability import machine_stability, ring_stability
    from autobalance.studies._speed_map import compute_speed_map

    s = machine("liquid.partitions=3")
    a = balanced(s, 100.0)[0]
    r = balanced_stability(s, 100.0, a)
    assert r.eigenvalues.size == 2 * 2 + 4 + 2 + 2 * 66 - 3
    alone = load_config("leblanc_003", ["liquid.partitions=3"]).system
    c, liq = alone.liquid.chambers[0], alone.liquid
    g = machine_stability(alone, [60.0])["growth_rate_1_s"][0]
    assert g == ring_stability(film_rotor(alone), c.chamber_radius, c.chamber_height, c.volume,
                               60.0, density=liq.density, viscosity=liq.kinematic_viscosity,
                               n_cells=66, partitions=3).growth_rate
    ds = compute_speed_map(load_config("leblanc_003", [*BALLS, "liquid.partitions=3"]),
                           speeds=[100.0], damping_factors=[1.0])
    assert ds.attrs["no_verdict"] == 0
    assert ds["balanced_stable"].values[0] == int(r.stable)
