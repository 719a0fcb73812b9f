"""`study immobility` beside a liquid on a horizontal axis (studies/_immobility.py,
docs/liquid/stability.md sec. 3k): the balls at rest on the steady orbit with the planar quasi-static liquid, gravity's
pull on the balls kept; checked against the fill map's steady amplitude, the pool machine below
the film's start, and the run of balls beside the films under gravity (core/hybrid.py)."""
from __future__ import annotations

import math

import numpy as np
import pytest

from autobalance.config import load_config
from autobalance.models.liquid_balancer import VerticalRotor
from autobalance.liquid.start import film_start_speed, pool_machine
from autobalance.liquid.steady import chambers_steady_response, steady_amplitude
from autobalance.liquid.synchronous import synchronous_liquid
from autobalance.models import InitialState, SimOptions, SpeedProfile
from autobalance.physics.immobility import configurations, steady_deflection
from autobalance.physics.unbalance import residual_unbalance
from autobalance.simulate.hybrid import simulate_hybrid
from autobalance.studies._immobility import compute_immobility, liquid_response

# two 0.5 kg balls on 0.3 m beside the washer's ring (1 l on R = 0.26 m, horizontal axis)
BALLS = ("balancer.n_balls=2", "balancer.ball_mass=0.5 kg", "balancer.race_radius=0.3 m",
         "balancer.ball_radius=15 mm", "balancer.damping=20 N*mm*s/rad",
         "balancer.rolling_resistance=0.01")


def washer(*sets):
    return load_config("leblanc_washer", [*BALLS, *sets])


def test_horizontal_steady_response_is_the_fill_maps():
    """chambers_steady_response on a horizontal axis is the fill map's steady amplitude
    (steady_amplitude, axis "horizontal": a puddle below g/Omega^2 = R/10, the planar ring
    above) at every speed, to the root's tolerance; the vertical axis is not that."""
    s = washer().system
    liq, c = s.liquid, s.liquid.chambers[0]
    ch = [(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume)]
    rotor = VerticalRotor(s.rotor.mass, s.suspension.kx, s.suspension.cx, 0.1)
    w_f = film_start_speed(liq, s.gravity.g)
    W = np.array([0.5, 0.9, 1.1, 1.6, 2.5, 5.0]) * w_f
    got = chambers_steady_response(rotor, ch, liq.density, W, s.gravity.g, "horizontal")
    ref = [steady_amplitude(rotor, ch, liq.density, w, s.gravity.g, axis="horizontal")
           for w in W]
    np.testing.assert_allclose(got["amplitude_m"], ref, rtol=1e-8)
    assert np.isnan(got["liquid_angle_deg"][W < w_f]).all()
    assert np.isfinite(got["liquid_angle_deg"][W >= w_f]).all()
    vert = chambers_steady_response(rotor, ch, liq.density, W)      # 003 eq 6's pool instead
    assert not np.allclose(vert["amplitude_m"], ref, rtol=1e-3)


def test_immobility_beside_a_liquid_on_a_horizontal_axis():
    """Below the film's start the liquid is a puddle and the shares are the pool machine's
    with gravity on the balls (to 1e-12: the Jeffcott orbit is linear in U_t); above it they
    differ. ring_holds is 0 below the film's start and, at each speed, the share of
    configurations whose orbit stays within synchronous_liquid's linear range (counted here
    directly); the method says what is left out."""
    cfg = washer()
    s = cfg.system
    w_f = film_start_speed(s.liquid, s.gravity.g)
    f = np.array([0.5, 0.9, 1.5, 2.4, 4.0, 5.5]) * w_f / (2 * np.pi)        # [Hz]
    ds = compute_immobility(cfg, G_ini=20.0, speeds=2 * np.pi * np.asarray(f), n_conf=24)
    from autobalance.config import from_models

    pool = compute_immobility(from_models(pool_machine(s), cfg.spin), G_ini=20.0,
                              speeds=2 * np.pi * np.asarray(f), n_conf=24)
    below = f * 2 * np.pi < w_f
    np.testing.assert_allclose(ds["immobility"].values[..., below],
                               pool["immobility"].values[..., below], atol=1e-12)
    assert not np.allclose(ds["immobility"].values[..., ~below],
                           pool["immobility"].values[..., ~below])
    holds = ds["ring_holds"].sel(c_r=1.0).values
    assert (holds[below] == 0.0).all() and 0.0 < holds[~below].max() <= 1.0
    W = 2 * np.pi * f
    s20 = _with_unbalance(s, _unbalance(cfg, ds.attrs["G_ini"]))     # the study's U (G20)
    resp = liquid_response(s20, W, 33)
    alpha = configurations(24, 2)
    for k in np.flatnonzero(~below):
        reach = synchronous_liquid(s.liquid, W[k], s.gravity.g).linear_range
        direct = np.mean(np.abs(steady_deflection(s20, W[k], alpha, resp)) <= reach)
        assert holds[k] == direct
    assert "planar" in ds.attrs["method"] and "gravity" in ds.attrs["method"]
    assert np.isnan(ds["G_stick"].values).all()


def _unbalance(cfg, G):
    from autobalance.physics.iso1940 import unbalance_value

    return float(unbalance_value(G, cfg.system.total_mass, cfg.spin.nominal_speed))


def _with_unbalance(s, U):
    import dataclasses

    return dataclasses.replace(s, rotor=dataclasses.replace(s.rotor, unbalance=U))


def _start_on_orbit(s, W, alpha, w0, T=3.0, n_cells=64):
    """The run of balls beside the films at constant speed W [rad/s] for T [s], the balls at
    rest at ``alpha`` [rad] and the rotor on the orbit w0 [m] (rotor frame, about the sag;
    psi = 0 at t = 0, so the inertial state is w0 and i W w0); the films start on the wall
    displaced by it (simulate_hybrid's start)."""
    init = InitialState(ball_angles=tuple(float(a) for a in alpha), x=w0.real, y=w0.imag,
                        vx=-W * w0.imag, vy=W * w0.real)
    return simulate_hybrid(s, SpeedProfile.constant(W, T), initial=init,
                           options=SimOptions(save_dt=0.002), n_cells=n_cells)


@pytest.mark.slow
def test_horizontal_immobility_is_the_runs_of_balls_beside_the_films():
    """At 1000 rpm (mu_s R = 3 mm, gravity's limit 3 mm - g sqrt(1 + mu_s^2)/Omega^2 = 2.11
    mm) the balls start at rest on the study's orbit, the rotor on it, the films on the wall it
    displaces, and run 3 s beside the films under gravity (core/hybrid.py, 64 cells):
    * at 0.49 of the limit both stay: the start's transient (the films' O(eta/R) from the
      quasi-static ring) moves them by 1.8e-4 rad (4.2e-4 on 128 cells); bound 2e-3;
    * at 0.85 mu_s R (1.21 of gravity's limit: immobile without gravity, mobile with it) the
      ball moves 0.12 rad; at 2 mu_s R both move (0.25 and 0.88 rad); bound 0.05.
    The study's mask says the same of each."""
    from autobalance.physics.immobility import immobile_mask

    s = washer().system
    W = 1000 * 2 * np.pi / 60
    resp = liquid_response(s, [W], 33)
    mu, R, g = 0.01, 0.3, s.gravity.g
    lim_g, lim_0 = mu * R - g * math.sqrt(1 + mu * mu) / W ** 2, mu * R
    a1 = np.linspace(0.0, 2 * np.pi, 721)
    al = np.stack([a1, np.full_like(a1, 2.0)], axis=1)          # ball 2 at 2 rad
    wq = resp(W, residual_unbalance(s, al))
    force = np.abs(np.imag(wq[:, None] * np.exp(-1j * al))).max(axis=1)     # [m]
    for target, stays in ((0.5 * lim_g, True), (0.85 * lim_0, False), (2.0 * lim_0, False)):
        k = int(np.argmin(np.abs(force - target)))
        assert bool(immobile_mask(s, W, al[k], resp)) is stays
        sim = _start_on_orbit(s, W, al[k], wq[k])
        moved = float(np.ptp(sim.alpha, axis=0).max())
        assert (moved < 2e-3) if stays else (moved > 0.05), (target, moved)


@pytest.mark.slow
def test_horizontal_orbit_is_the_planar_quasi_static_one():
    """Balls held (rolling resistance 0.5) beside a thin ring (0.25 l: eta = 5.1 mm, eta/R =
    0.020) at 800 rpm (g/(Omega^2 R) = 0.0054): the run's whirl over its last revolution (12 s,
    128 cells) is the study's orbit to 0.32 % (bound eta/R + g/(Omega^2 R), the two first-order
    terms left out: the films put the liquid at R, and gravity's offset of the surface), and
    the same run without gravity (a vertical axis) to 0.30 % (bound g/(Omega^2 R); that run is
    0.62 % from the orbit). The
    rigid-pool machine's orbit (no ring) is 18 % away."""
    s = washer("liquid.volume=0.25 l", "balancer.rolling_resistance=0.5").system
    W = 800 * 2 * np.pi / 60
    alpha = np.array([0.4, 1.9])
    Ut = residual_unbalance(s, alpha)
    wq = liquid_response(s, [W], 33)(W, np.array([Ut]))[0]
    per = 2 * np.pi / W

    def last_revolution(system):
        sim = _start_on_orbit(system, W, alpha, wq, T=12.0, n_cells=128)
        assert float(np.ptp(sim.alpha, axis=0).max()) < 1e-12      # held
        m = sim.t >= sim.t[-1] - per
        return complex(np.mean(sim.u[m] + 1j * sim.v[m]))

    w_h = last_revolution(s)
    eta = s.liquid.chambers[0].volume / (2 * np.pi * 0.26 * 0.03)
    assert abs(w_h - wq) <= (eta / 0.26 + g_ratio(s, W)) * abs(wq)
    v = washer("liquid.volume=0.25 l", "balancer.rolling_resistance=0.5", "liquid.axis=vertical",
               "gravity.g=0").system
    w_v = last_revolution(v)
    assert abs(w_h - w_v) <= g_ratio(s, W) * abs(w_v)
    w_pool = steady_deflection(pool_machine(s), W, alpha)
    assert abs(w_pool - wq) > 0.15 * abs(wq)


def g_ratio(s, W):
    """g/(Omega^2 R) of the washer's ring [-]."""
    return s.gravity.g / (W * W * s.liquid.chambers[0].chamber_radius)


def test_cli_immobility_on_a_horizontal_axis(tmp_path):
    """`autobalance study immobility` on the washer with balls: exit 0, ring_holds in the JSON
    and the NetCDF, the text says what the orbit leaves out and from which speed every
    configuration's ring holds, in the user's speed unit; the figure draws the share."""
    import json

    import xarray as xr
    from typer.testing import CliRunner

    from autobalance.cli import app

    sets = [x for b in BALLS for x in ("--set", b)]
    runner = CliRunner()
    r = runner.invoke(app, ["study", "immobility", "leblanc_washer", *sets, "--quick", "--json",
                            "--out", str(tmp_path / "i.nc")])
    assert r.exit_code == 0, r.output
    d = json.loads(r.output)
    assert len(d["ring_holds"]) == len(d["immobility"]) == len(d["speeds_rad_s"])
    assert min(d["ring_holds"]) == 0.0 and max(d["ring_holds"]) == 1.0
    ds = xr.load_dataset(tmp_path / "i.nc")
    np.testing.assert_array_equal(ds["ring_holds"].sel(c_r=1.0).values, d["ring_holds"])
    r = runner.invoke(app, ["study", "immobility", "leblanc_washer", *sets, "--quick",
                            "--units", "speed=rpm", "--plot", str(tmp_path / "i.png")])
    assert r.exit_code == 0, r.output
    line = r.output.splitlines()[-1]
    assert "planar" in line and "every configuration's from" in line and "rpm" in line
    assert (tmp_path / "i.png").stat().st_size > 10_000
