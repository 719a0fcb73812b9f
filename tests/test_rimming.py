"""The liquid on a horizontal axis in time (core/rimming.py, liquid/rimming.py;
docs/liquid/horizontal-axis.md sec. 3n): the puddle at rest (the thin layer's horizontal chord) kept to round-off, volume to
round-off, the friction's lag under a constant spin-up and the ring's forced wave under gravity
against their closed forms, grid convergence, the model's quasi-static ring, and the runs'
events: a ring breaking on a run-down, a puddle leaving the model on a run-up."""
from __future__ import annotations

import math

import numpy as np
import pytest

from autobalance.liquid.rimming import (closing_centroid, closing_ring, horizontal_spinup,
                                        puddle_at_rest, rimming_run)
from autobalance.models import ParameterError

R, H, V, G = 0.26, 0.03, 1e-3, 9.81            # the preset leblanc_washer's ring
DOWN = -math.pi / 2
RPM = math.pi / 30
T_MEAN = V / (2 * math.pi * R * H)             # 20.4 mm


def test_the_puddle_at_rest_is_the_chord_and_holds_the_volume():
    """At Omega = 0 the model's surface P + G h = const is (R - h) cos(theta - gamma) = const
    (the horizontal chord in the thin layer's radial depth); R H sum(h) dtheta = V."""
    n = 256
    h = puddle_at_rest(R, H, V, G, DOWN, n)
    th = (np.arange(n) + 0.5) * 2 * math.pi / n
    wet = h > 0
    level = (R - h[wet]) * np.cos(th[wet] - DOWN)
    assert np.ptp(level) < 1e-12 * R
    assert h.sum() * R * H * 2 * math.pi / n == pytest.approx(V, rel=1e-12)
    assert 0 < wet.sum() < n


def test_a_puddle_at_rest_stays_at_rest_to_round_off():
    """Well balanced, dry cells included: the chamber at rest for 2 s."""
    r = rimming_run(R, H, V, ([0.0, 10.0], [0.0, 0.0]), 2.0, g=G, n_cells=128)
    assert r.status == "end" and r.steps > 100
    assert np.abs(r.depth[-1] - r.depth[0]).max() < 1e-15
    assert np.abs(r.discharge[-1]).max() < 1e-15


def test_volume_is_kept_to_round_off_through_a_run_up():
    """0 -> 1000 rpm in 30 s, 128 cells, until the run leaves the model."""
    r = rimming_run(R, H, V, ([0.0, 30.0], [0.0, 1000 * RPM]), 30.0, g=G, n_cells=128)
    assert r.steps > 1000
    assert np.abs(r.volume / V - 1).max() < 1e-13
    assert np.all(r.depth >= 0)


def test_a_uniform_ring_lags_at_the_laminar_friction_balance():
    """No gravity's pull to speak of, a uniform ring under a constant spin-up: the relative
    velocity settles on v = -Omega' R h_h^2 / (3 nu), h_h = h H / (H + 2 h) the hydraulic depth
    (outer and side walls), as the wall film's lag (tests/test_liquid_film.py) with the side
    walls added."""
    n, h0, nu, acc, w0 = 64, 2e-3, 1e-4, 1.0, 50.0
    hh = h0 * H / (H + 2 * h0)
    v = -acc * R * hh * hh / (3 * nu)
    r = rimming_run(R, H, 2 * math.pi * R * H * h0, ([0.0, 10.0], [w0, w0 + 10 * acc]), 1.0,
                    g=1e-9, n_cells=n, viscosity=nu, stop_at_event=False)
    assert 4 * hh * abs(v) / nu < 2000                          # laminar
    assert r.discharge[-1] / r.depth[-1] == pytest.approx(np.full(n, v), rel=1e-6)


def _forced_wave(w, nu):
    """The linearised model's response to gravity of a uniform ring (thickness T_MEAN) turning
    with the chamber at w [rad/s]: h = t + A e^{i(theta + w t)}, v = B e^{...}; mass
    i w A + i t B / R = 0; momentum (i w + k) t B = -i t / R (-g (R - t) + w^2 R A + 2 w t B)
    (the surface potential P + G h with G = (w + v/R)^2 R + g cos, linear in A, B); k the
    laminar rate 3 nu / h_h^2. Returns |A| / t."""
    t = T_MEAN
    hh = t * H / (H + 2 * t)
    k = 3 * nu / hh ** 2
    # B = -w R A / t from the mass balance, into the momentum balance: solve for A
    lhs = (1j * w + k) * t * (-w * R / t) + 1j * t / R * (w * w * R + 2 * w * t * (-w * R / t))
    A = 1j * t / R * G * (R - t) / lhs
    return abs(A) / t


@pytest.mark.parametrize("rpm, rel", [(150.0, 0.03), (300.0, 0.002)])
def test_a_ring_under_gravity_is_the_supercritical_forced_wave(rpm, rel):
    """A ring turning with the chamber at constant speed under gravity settles on the forced
    wave: gravity's pattern passes the ring at Omega R, much faster than its waves
    (sqrt(Omega^2 R t)), so the ring thins at the top by only about g / (Omega^2 R), not by
    the quasi-static offset g / Omega^2 (which would dry the top below 205 rpm). Viscous
    (nu = 1e-4 m^2/s) so that the free waves of the start die out. The first harmonic against
    the linear _forced_wave on 256 cells: 3.2 % of the thickness at 300 rpm, 0.04 % from it;
    13 % at 150 rpm, 1.9 % above it (measured; 2.1 % on 512 cells: the nonlinear part, of the
    order of the amplitude squared)."""
    w, nu, n = rpm * RPM, 1e-4, 256
    r = rimming_run(R, H, V, ([0.0, 100.0], [w, w]), 8.0, g=G, n_cells=n, viscosity=nu)
    assert r.status == "end"
    h = r.depth[-1]
    first = abs((h * np.exp(-1j * r.theta)).sum()) * 2 / n / T_MEAN
    assert first == pytest.approx(_forced_wave(w, nu), rel=rel)
    assert h.min() > 0.5 * T_MEAN                   # intact, far from the quasi-static crescent


def test_the_forced_wave_converges_under_refinement():
    """The first harmonic at 300 rpm on 64, 128, 256 cells: -0.48, -0.21, -0.04 % from the
    linear theory (measured; +0.05 % on 512), the change shrinking by 1.6 with each doubling
    (minmod clips the slopes at the wave's crests: about first order there)."""
    w, nu = 300 * RPM, 1e-4
    a = []
    for n in (64, 128, 256):
        r = rimming_run(R, H, V, ([0.0, 100.0], [w, w]), 8.0, g=G, n_cells=n, viscosity=nu)
        a.append(abs((r.depth[-1] * np.exp(-1j * r.theta)).sum()) * 2 / n / T_MEAN)
    assert abs(a[2] - a[1]) < 0.75 * abs(a[1] - a[0])
    assert abs(a[2] / _forced_wave(w, nu) - 1) < abs(a[0] / _forced_wave(w, nu) - 1)


def test_the_models_quasi_static_ring():
    """closing_ring: a thin ring (thickness t) in rigid rotation closes where g / Omega^2 = t,
    to O(t/R); its centre of mass at the closing sits R/2 below the axis (h ~ 1 + cos)."""
    t = 1e-4 * R
    thin = 2 * math.pi * R * H * t
    assert closing_ring(R, H, thin) * G / R == pytest.approx(G / t, rel=2 * t / R)
    assert closing_centroid(R, H, thin, 1024) == pytest.approx(R / 2, rel=1e-3)


@pytest.mark.parametrize("nu, lo, hi, leads", [(1e-6, 50.0, 60.0, True),
                                               (1e-4, 85.0, 95.0, False)])
def test_a_ring_breaks_on_a_run_down_where_its_top_is_no_longer_held(nu, lo, hi, leads):
    """300 -> 0 rpm in 20 s from a ring turning with the chamber: the ring breaks when liquid
    at the top is no longer held (G <= 0), still thick all round. Water keeps turning faster
    than the slowing chamber (88-91 rpm at the break) and holds to about Omega^2 R / g = 1
    (measured 57.7, 57.3, 54.9 rpm on 128-512 cells). A viscous liquid follows the wall and
    the drag of gravity's wave in it (at 84 rpm) and breaks earlier (89.8, 89.9, 90.0 rpm).
    Both far below the film model's start of 185 rpm: a ring once formed outlives it."""
    r = rimming_run(R, H, V, ([0.0, 20.0], [300 * RPM, 0.0]), 20.0, g=G, n_cells=128,
                    viscosity=nu)
    assert r.status == "broken"
    assert lo < r.stop_speed / RPM < hi
    assert (r.liquid_speed[-1] > r.stop_speed) == leads
    assert r.depth[-1].min() > 0.5 * T_MEAN           # broken at the top by G, not dried


def test_a_water_puddle_leaves_the_model_on_the_washers_run_up():
    """0 -> 1000 rpm in 30 s from the puddle at rest: the wall drags the puddle up its rising
    side, the liquid barely turning (6-7 rpm), until more than 1 % of it lies where nothing
    holds it on the wall (measured at 216, 233, 242 rpm on 128, 256, 512 cells). The
    single-layer model stops there (docs/liquid/horizontal-axis.md sec. 3n)."""
    r = rimming_run(R, H, V, ([0.0, 30.0], [0.0, 1000 * RPM]), 30.0, g=G, n_cells=128)
    assert r.status == "unheld" and r.ring_time is None
    assert r.loose[-1] > 0.01
    assert r.liquid_speed[-1] < 0.05 * r.stop_speed
    m = r.moment[-1]
    assert abs(m) > 0.8 * V * R                               # still gathered, not a ring


def test_a_machines_chambers_run_through_its_profile():
    """horizontal_spinup: the preset leblanc_washer's one chamber through its own profile, as
    rimming_run with its values; a vertical axis and partitions are refused in one line."""
    from autobalance.config import load_config

    cfg = load_config("leblanc_washer")
    (r,) = horizontal_spinup(cfg.system, cfg.spin, n_cells=64)
    ref = rimming_run(R, H, V, (cfg.spin.times, cfg.spin.speeds), cfg.spin.times[-1], g=9.81,
                      n_cells=64)
    assert r.status == ref.status and r.stop_time == ref.stop_time
    with pytest.raises(ParameterError, match="^liquid.axis"):
        horizontal_spinup(load_config("leblanc_003").system, cfg.spin)
    part = load_config("leblanc_washer", ["liquid.partitions=4"])
    with pytest.raises(ParameterError, match="^liquid.partitions"):
        horizontal_spinup(part.system, part.spin)


def test_bad_input_is_one_line():
    with pytest.raises(ParameterError, match="liquid.volume"):
        puddle_at_rest(R, H, 0.6 * math.pi * R * R * H, G, DOWN, 128)      # above the axis
    with pytest.raises(ParameterError, match="inner wall"):
        puddle_at_rest(R, H, V, G, DOWN, 128, inner_radius=0.2)
    with pytest.raises(ParameterError, match="n_cells"):
        rimming_run(R, H, V, ([0, 1], [0, 1]), 1.0, g=G, n_cells=8)
    with pytest.raises(ParameterError, match="gravity.g"):
        rimming_run(R, H, V, ([0, 1], [0, 1]), 1.0, g=0.0)
    with pytest.raises(ParameterError, match="speed"):
        rimming_run(R, H, V, ([0, 1], [0, -1]), 1.0, g=G)
    with pytest.raises(ParameterError, match="liquid.volume"):
        rimming_run(R, H, V, ([0, 1], [10, 10]), 1.0, g=G, inner_radius=0.25)  # ring > gap


DOWN_SETS = ["--set", "profile.start_speed=300 rpm", "--set", "profile.end_speed=1 rpm",
             "--set", "profile.ramp_time=20 s", "--set", "profile.duration=20 s"]


def test_cli_spinup_on_a_horizontal_axis(tmp_path):
    """`liquid spinup` on the washer: from rest it reports where the puddle leaves the model
    (as horizontal_spinup on 256 cells), in the machine's rpm, with the film model's start
    beside it; from a ring on a run-down, where the ring breaks; JSON in SI; the figure."""
    import json

    from typer.testing import CliRunner

    from autobalance.cli.liquid import app
    from autobalance.config import load_config

    runner = CliRunner()
    r = runner.invoke(app, ["spinup", "leblanc_washer", "--cells", "128", "--json",
                            "--plot", str(tmp_path / "r.png")])
    assert r.exit_code == 0, r.output
    d = json.loads(r.stdout)
    cfg = load_config("leblanc_washer")
    (ref,) = horizontal_spinup(cfg.system, cfg.spin, n_cells=128)
    c = d["chambers"][0]
    assert d["axis"] == "horizontal" and c["status"] == "unheld"
    assert c["stop_speed_rad_s"] == ref.stop_speed and c["steps"] == ref.steps
    assert 0 < c["centre_of_mass_from_bottom_deg"] < 90           # up the rising wall
    assert (tmp_path / "r.png").stat().st_size > 10_000
    t = runner.invoke(app, ["spinup", "leblanc_washer", "--cells", "128", *DOWN_SETS])
    assert t.exit_code == 0, t.output
    line = t.output.splitlines()[0]
    assert line.startswith("R = 0.26 m, 1000 ml: ")                # the radius as written
    assert "the ring broke" in line and " rpm, t = " in line
    assert "the film model starts at 185.49 rpm" in t.output


def test_cli_spinup_refusals_are_one_line():
    """Through the entry point: partitions on a horizontal axis; a motor drive."""
    import subprocess
    import sys

    for sets in (["liquid.partitions=4"], ["profile.kind=motor"]):
        r = subprocess.run([sys.executable, "-m", "autobalance", "liquid", "spinup",
                            "leblanc_washer", *[x for s in sets for x in ("--set", s)]],
                           capture_output=True, text=True, timeout=300)
        lines = r.stderr.strip().splitlines()
        assert r.returncode == 2 and len(lines) == 1 and lines[0].startswith("error:"), r.stderr
