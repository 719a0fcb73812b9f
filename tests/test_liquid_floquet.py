"""Linear stability of a rotor with wall films on a horizontal axis (liquid/stability.py
ring_floquet; docs/liquid/horizontal-axis.md sec. 3m): Floquet multipliers about the periodic state that gravity
turning in the rotor frame makes of the centred one. Its limit without gravity (the one-step
map's eigenvalues), the periodic state and the growth rate against the film kernel's own run,
the compartments' volumes, Kollmann's band of the washer, no verdict on a crescent, bad input
and the CLI. Balls beside the films (studies/liquid_floquet.py): the balls alone's Floquet
multipliers beside a liquid of no mass, the growth rate against the run of balls beside the
films, the verdicts over speed and the refusals."""
from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from autobalance.config import load_config
from autobalance.core.hybrid import hybrid_integrate
from autobalance.core.layout import carry_size
from autobalance.core.shallow_water import films_moment, sw_coupled
from autobalance.liquid.film import films_state
from autobalance.liquid.simulate import film_rotor
from autobalance.liquid.stability import (NoPeriodicFilm, _step_map, compartments, linear_modes,
                                          machine_stability, ring_stability)
from autobalance.liquid.start import pool_machine
from autobalance.models import InitialState, ParameterError, SimOptions, SpeedProfile
from autobalance.simulate.pack import run_inputs
from autobalance.studies.equilibria import floquet_full
from autobalance.studies.liquid_balanced import (_balanced_states, balanced_machine_stability,
                                                 balanced_stability)

BENCH = load_config("leblanc_003").system
ROTOR = film_rotor(BENCH)
L = BENCH.liquid
WASHER = load_config("leblanc_washer").system
RPM = 2.0 * math.pi / 60.0


def bench(volume, speed, n=64, gravity=9.81, **kw):
    return ring_stability(ROTOR, L.chamber_radius, L.chamber_height, volume, speed,
                          density=L.density, viscosity=L.kinematic_viscosity, n_cells=n,
                          gravity=gravity, **kw)


def films(volume, n=64, partitions=0):
    return films_state(L.chamber_radius, L.chamber_height, volume, L.density,
                       L.kinematic_viscosity, n, partitions, 0.0, 0j)


@pytest.mark.parametrize("speed", [pytest.param(60.0, marks=pytest.mark.slow), 100.0])
def test_without_gravity_the_monodromy_is_the_step_maps_power(speed):
    """g -> 0: the period map is m steps of the one-step map about the centred state, so its
    multipliers are mu^m of that map's on the same grid dt = T / m (the vertical axis's
    linearisation, sec. 3j). Measured at g = 1e-9 m/s^2: equal to 1.3e-6 1/s (the central
    differences through m steps)."""
    r = bench(150e-6, speed, gravity=1e-9)
    st = films(150e-6)
    Mt = ROTOR.mass + L.density * 150e-6
    dt = r.dt / r.steps
    n = st.h.size
    hs = float(st.h.max())
    scale = np.concatenate([np.full(2, Mt * hs), np.full(2, Mt * hs * speed),
                            np.full(2, hs * speed ** 2), np.full(n, hs),
                            np.full(n, hs * speed * L.chamber_radius)])
    lam = linear_modes(_step_map(ROTOR, st, Mt, speed, dt),
                       np.concatenate([np.zeros(6), st.h, st.q]), scale, dt, 1, "test")
    assert r.steps > 1 and r.dt == pytest.approx(2 * math.pi / speed, rel=1e-15)
    k = 6               # the least stable modes (whirls below Omega / 2: no aliasing)
    assert np.max(np.abs(r.eigenvalues[:k].real - lam[:k].real)) < 1e-5
    assert np.max(np.abs(np.abs(r.eigenvalues[:k].imag) - np.abs(lam[:k].imag))) < 1e-5


def _kernel_run(r, volume, t_end, kick, grid=False):
    """The film kernel's own run (CFL steps; ``grid``: on the period's grid, the outputs at its
    points) from the periodic state with the rotor kicked by ``kick`` [m]: the deflection in
    the inertial frame."""
    st = films(volume)
    x = r.state
    n = st.h.size
    Mt = ROTOR.mass + L.density * volume
    W = r.speed
    h, q = x[6:6 + n].copy(), x[6 + n:].copy()
    out_t = (np.arange(0, round(t_end / r.dt * r.steps)) * (r.dt / r.steps) if grid else
             np.arange(0.0, t_end, 0.01))
    out_h, out_q = np.zeros((out_t.size, n)), np.zeros((out_t.size, n))
    out_w = np.zeros(out_t.size, complex)
    steps, *_ = sw_coupled(h, q, st.theta, st.starts, st.Rs, st.Hs, st.rhos, st.nus, Mt,
                           ROTOR.stiffness, ROTOR.damping, 0.0, complex(x[0], x[1]) + Mt * kick,
                           complex(x[2], x[3]), t_end, np.array([0.0, 2 * t_end]),
                           np.full(2, W), 9.81, -0.5 * math.pi, st.wall, out_t, out_h, out_q,
                           out_w, *[np.zeros(n) for _ in range(9)], complex(x[4], x[5]))
    assert steps > 0
    U, _ = films_moment(x[6:6 + n], x[6 + n:], st.theta, st.starts, st.Rs, st.Hs, st.rhos)
    w0 = (complex(x[0], x[1]) - U) / Mt          # the periodic state's deflection at psi = 0
    return out_t, out_w * np.exp(1j * W * out_t), w0


@pytest.mark.slow
def test_periodic_state_is_the_kernels_steady_whirl():
    """Without a kick the kernel's run from the periodic state stays on it: in the inertial
    frame the chamber hangs at its sag, M_t g / k = 3.34 mm below the axis. On the period's
    grid (10 revolutions) to 1e-11 m, the shooting's residual; on the kernel's own CFL steps
    (3 s) to 3.3e-6 m, 1e-3 of the sag: a first-order scheme on another grid has its own
    periodic state. The film is nearly uniform (the wall passes under the offset potential at
    a Froude number sqrt(R / eta) ~ 9: the liquid turns with the wall), not the hydrostatic
    crescent offset by g / Omega^2."""
    r = bench(300e-6, 100.0)
    sag = (ROTOR.mass + 0.3) * 9.81 / ROTOR.stiffness
    t, w, w0 = _kernel_run(r, 300e-6, 10 * r.dt, 0.0, grid=True)
    assert w0 == pytest.approx(-1j * sag, abs=2e-5)
    on = np.abs(t / r.dt - np.round(t / r.dt)) < 1e-9       # whole revolutions
    assert on.sum() == 10 and np.max(np.abs(w[on] - w0)) < 1e-11
    t, w, w0 = _kernel_run(r, 300e-6, 3.0, 0.0)
    assert np.max(np.abs(w - w0)) < 1e-5
    h = r.state[6:6 + 64]
    assert (h.max() - h.min()) / h.mean() < 0.05 < 9.81 / 100.0 ** 2 / h.mean()


@pytest.mark.slow
def test_growth_rate_is_the_kernels_run():
    """Kicked by 0.1 nm, the kernel's run on 003's bench at 60 1/s (150 ml, in Kollmann's band)
    grows at the Floquet rate lambda = 1.426 1/s (the vertical axis's 1.795: gravity's sag
    narrows the band): the slope of log |w - w_0| in the inertial frame over 2-7 s, w_0 the
    run without the kick, on the period's grid: 1.42618 (the map itself, to 2e-5). On the
    kernel's CFL steps the periodic state is 3e-6 m off its own, a kick that grows at 1.417
    over 0.5-3 s (another grid of a first-order scheme)."""
    r = bench(150e-6, 60.0)
    assert not r.stable
    t, w, _ = _kernel_run(r, 150e-6, 7.0, 1e-10, True)
    _, w0, _ = _kernel_run(r, 150e-6, 7.0, 0.0, True)
    late = t > 2.0
    slope = np.polyfit(t[late], np.log(np.abs(w[late] - w0[late])), 1)[0]
    assert slope == pytest.approx(r.growth_rate, abs=1e-3)
    # the CFL steps: their own periodic state is 3e-6 m off, a kick of its own
    t, w, ws = _kernel_run(r, 150e-6, 3.0, 0.0)
    win = (t > 0.5) & (t < 3.0)
    slope = np.polyfit(t[win], np.log(np.abs(w[win] - ws)), 1)[0]
    assert slope == pytest.approx(r.growth_rate, abs=0.05)


@pytest.mark.slow
def test_shooting_keeps_every_compartments_volume():
    """The shooting's steps keep each compartment's volume (its rows sum(s) = 0): with four
    partitions every compartment of the periodic state holds a quarter of the liquid to
    1e-12."""
    r = bench(300e-6, 100.0, partitions=4)
    st = films(300e-6, partitions=4)
    h = r.state[6:6 + st.h.size]
    parts = compartments(st)
    assert len(parts) == 4 and all(c.size == 16 for c in parts)
    vols = [h[c].sum() for c in parts]
    assert np.allclose(vols, st.h.sum() / 4, rtol=1e-12, atol=0)


@pytest.mark.slow
def test_washers_kollmann_band_on_its_horizontal_axis():
    """The washer preset (liquid alone, horizontal axis, omega_n 295 rpm with the liquid), on 32
    cells: unstable at 450 rpm, stable at 1000 rpm, no verdict at 190 rpm (the film's start is
    185 rpm). Measured on 64 cells over 100-1400 rpm: unstable from 327 to 542 rpm against
    300-596 rpm on a vertical axis (docs/liquid/horizontal-axis.md sec. 3m)."""
    res = machine_stability(WASHER, np.array([190.0, 450.0, 1000.0]) * RPM, n_cells=32)
    g = res["growth_rate_1_s"]
    assert res["axis"] == "horizontal"
    assert np.isnan(g[0]) and res["no_periodic_film_rad_s"] == [pytest.approx(190 * RPM)]
    assert g[1] > 0.1 and g[2] < 0


def test_no_periodic_state_no_verdict():
    """Just above its film's start (185 rpm) the washer's shooting finds no periodic state with
    an intact film: ``speed`` says so in one line, and the speed map leaves it undecided. The
    kernel's run there from a uniform film settles on a crescent (its thinnest 7.5 % of the
    mean after 60 s on 64 cells)."""
    R = film_rotor(WASHER)
    W = WASHER.liquid
    with pytest.raises(NoPeriodicFilm, match="^speed = 19.89"):
        ring_stability(R, W.chamber_radius, W.chamber_height, W.volume, 190 * RPM,
                       density=W.density, viscosity=W.kinematic_viscosity, n_cells=8,
                       gravity=9.81)


@pytest.mark.parametrize("kw, field", [({"gravity": -1.0}, "gravity"),
                                       ({"gravity": math.nan}, "gravity")])
def test_bad_gravity_is_one_line(kw, field):
    with pytest.raises(ParameterError, match=f"^{field}"):
        bench(150e-6, 60.0, **kw)


@pytest.mark.slow
def test_cli_on_a_horizontal_axis():
    """`liquid stability` on the washer (32 cells): the text names the periodic state, the
    unstable range in rpm (measured 392-546 rpm on this grid) and the speed without a verdict;
    the JSON the axis and that speed."""
    args = [sys.executable, "-m", "autobalance", "liquid", "stability", "leblanc_washer",
            "--speeds", "190:1000 rpm:5", "--cells", "32"]
    r = subprocess.run(args + ["--json"], capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert d["axis"] == "horizontal" and len(d["no_periodic_film_rad_s"]) == 1
    lo, hi = d["unstable_ranges_rad_s"][0]
    assert 300 * RPM < lo < 450 * RPM < hi < 600 * RPM
    t = subprocess.run(args, capture_output=True, text=True, timeout=600)
    assert t.returncode == 0, t.stderr
    assert "centred state under gravity" in t.stdout and "unstable at 392.5 rpm" in t.stdout
    assert "no verdict at 190 rpm" in t.stdout


# -- balls beside the liquid on a horizontal axis (studies/liquid_floquet.py) ------------------
BALLS = ("balancer.n_balls=2", "balancer.ball_mass=0.5 kg", "balancer.race_radius=0.27 m",
         "balancer.ball_radius=10 mm", "balancer.damping=20 N*mm*s/rad")


def washer(*sets):
    return load_config("leblanc_washer", [*BALLS, *sets]).system


@pytest.mark.slow
@pytest.mark.parametrize("rpm, tol", [(600, 2e-3), (1000, 3e-4)])
def test_massless_liquid_leaves_the_balls_floquet(rpm, tol):
    """A liquid of 1e-3 kg/m^3 beside two balls on the washer: among the multipliers of the
    balanced state's periodic state are those of the balls alone on the horizontal axis
    (studies/equilibria.floquet_full: Newton shooting on the nonlinear model at rtol 1e-11, an
    independent route). Measured within 1.1e-3 at 600 rpm and 1.5e-4 at 1000 rpm: the balls are
    linear about their balanced angles, so gravity's effect is kept to first order in
    g / (Omega^2 R) = 0.0092 and 0.0033, and the differences scale as its square (ratio 7 against
    7.8)."""
    s = washer("liquid.density=0.001 kg/m^3")
    W = rpm * RPM
    a = _balanced_states(s, W)[0][0]
    r = balanced_stability(s, W, a, n_cells=32)
    f = floquet_full(pool_machine(s), W, a)
    assert f["converged"] and r.dt == pytest.approx(2 * math.pi / W)
    mu = np.exp(r.eigenvalues * r.dt)
    for m in f["multipliers"]:
        assert np.min(np.abs(mu - m)) < tol


def _hybrid_run(s, r, kick, t_end):
    """The run of balls beside the films (core/hybrid.py) on the horizontal axis at the constant
    speed of ``r`` from its periodic state, the first ball ``kick`` [rad] off: the deflection
    (rotor frame, from the static equilibrium) at 0.01 s."""
    N = 2
    W = r.speed
    x = r.state
    spin = SpeedProfile.constant(W, t_end)
    opts = SimOptions(save_dt=0.01, rtol=1e-9)
    P, B, y, _, prof_t, prof_w, te, unb_t, unb_u, out_t, out_y, stats, atol, h_max = \
        run_inputs(s, spin, InitialState(), opts, liquid_ok=True)
    nq = N + 3
    a, ad = x[2:2 + N] % (2 * math.pi), x[N + 4:2 * N + 4]
    order = np.argsort(a)
    y[0], y[1], y[nq], y[nq + 1] = x[0], x[1], x[N + 2], x[N + 3]
    y[2:2 + N], y[nq + 2:nq + 2 + N] = a[order], ad[order]
    y[2 + int(np.argmin(order))] += kick
    liq = s.liquid
    st = films_state(liq.chamber_radius, liq.chamber_height, liq.volume, liq.density,
                     liq.kinematic_viscosity, 32, 0, 0.0, 0j)
    nc = st.h.size
    h, q = x[2 * N + 6:2 * N + 6 + nc].copy(), x[2 * N + 6 + nc:].copy()
    g, gdir = s.gravity.g, s.gravity.direction
    sag = s.total_mass * g / s.suspension.kx * complex(math.cos(gdir), math.sin(gdir))
    none = np.zeros((1, nc))
    steps = hybrid_integrate(P, B, N, prof_t, prof_w, unb_t, unb_u, y, 0.0, te, opts.rtol, atol,
                             h_max, 10 ** 7, out_t, out_y, stats, np.zeros(carry_size(N)), h, q,
                             st.theta, st.starts, st.Rs, st.Hs, st.rhos, st.nus, st.wall, g,
                             gdir, sag, np.zeros(1), none, none.copy(), np.zeros(1))
    assert steps > 100 and stats[0] == 0.0
    return out_t, out_y[:, 0] + 1j * out_y[:, 1]


@pytest.mark.slow
def test_hybrid_run_from_the_periodic_state_stays_balanced():
    """The run of balls beside the films (core/hybrid.py: DOPRI5 on the nonlinear balls, the
    films on their CFL steps) at 1000 rpm from the Floquet periodic state (stable there): the
    chamber's deflection from its static equilibrium stays within 0.3 mm over 6 s (measured at
    most 0.154 mm: the transient from the map's periodic state, 0.037 mm at psi = 0, to the
    run's own on another grid), against the unbalance's free whirl D / M_t = 3.1 mm."""
    s = washer()
    W = 1000 * RPM
    r = balanced_stability(s, W, _balanced_states(s, W)[0][0], n_cells=32)
    assert r.stable
    t, w = _hybrid_run(s, r, 0.0, 6.0)
    assert np.max(np.abs(w)) < 3e-4
    assert s.rotor.unbalance / s.total_mass > 3e-3


@pytest.mark.slow
def test_balanced_machine_stability_on_the_washer():
    """balanced_machine_stability on the washer with two balls (32 cells): at 100 rpm, below the
    film's start (185 rpm), the balls' Floquet multipliers with the liquid as a puddle
    (floquet_full on the pool machine: unstable below resonance); unstable at 400 rpm (in the
    ring's Kollmann band), stable at 1000 rpm."""
    s = washer()
    res = balanced_machine_stability(s, np.array([100.0, 400.0, 1000.0]) * RPM, n_cells=32)
    g = res["growth_rate_1_s"]
    assert res["axis"] == "horizontal" and res["film_from_rad_s"] == pytest.approx(185.5 * RPM,
                                                                                    rel=1e-3)
    f = floquet_full(pool_machine(s), 100 * RPM, res["ball_angles_rad"][0])
    assert g[0] == pytest.approx(math.log(f["max_modulus"]) * 100 * RPM / (2 * math.pi),
                                 rel=1e-12)
    assert g[0] > 0 and g[1] > 0 > g[2]


def test_balls_beside_a_horizontal_liquid_refusals():
    """Three balls under gravity (a family kept only nearly): one line on balancer.n_balls; no
    in-plane gravity: one line on gravity.g."""
    with pytest.raises(ParameterError, match="^balancer.n_balls"):
        balanced_stability(washer("balancer.n_balls=3"), 100.0, [0.0, 2.0, 4.0])
    with pytest.raises(ParameterError, match="^gravity.g"):
        balanced_stability(washer("gravity.g=0"), 100.0, [0.0, 2.0])
