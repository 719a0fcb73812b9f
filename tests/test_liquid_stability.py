"""Linear stability of the centred state of a rotor with wall films (liquid/stability.py;
docs/liquid/stability.md sec. 3j): the rotor's own eigenvalues with a film of no mass, the film runs' own
growth rates from a small deflection, the instability band above resonance on 003's bench that
the film runs show, convergence in the cells, partitions, refusals and the CLI."""
from __future__ import annotations

import dataclasses
import json
import math
import subprocess
import sys

import numpy as np
import pytest

from autobalance.config import load_config
from autobalance.liquid.film import coupled_run
from autobalance.models.liquid_balancer import VerticalRotor
from autobalance.liquid.simulate import film_rotor
from autobalance.liquid.stability import ring_stability
from autobalance.models import ParameterError

BENCH = load_config("leblanc_003").system
ROTOR = film_rotor(BENCH)
L = BENCH.liquid


def bench(volume, speed, n=64, **kw):
    return ring_stability(ROTOR, L.chamber_radius, L.chamber_height, volume, speed,
                          density=kw.pop("density", L.density),
                          viscosity=L.kinematic_viscosity, n_cells=n, **kw)


def test_a_film_of_no_mass_leaves_the_jeffcott_rotor():
    """rho = 1e-6 kg/m^3: among the eigenvalues are the isotropic Jeffcott rotor's in the rotor
    frame, -zeta w_n +- i (w_d -+ Omega) (textbook; the real state gives each with its
    conjugate). Measured: 2e-7 and 4e-4 relative (the map's step, RK4 on the rotor)."""
    W = 40.0
    r = ring_stability(VerticalRotor(25.0, 73337.4, 271.62, 0.0), 0.2, 0.05, 150e-6, W,
                       density=1e-6, n_cells=32)
    wn = math.sqrt(73337.4 / 25.0)
    zw = 271.62 / 50.0
    wd = math.sqrt(wn * wn - zw * zw)
    for target in (complex(-zw, wd - W), complex(-zw, wd + W)):
        d = np.abs(r.eigenvalues - target) / abs(target)
        assert d.min() < 1e-3, (target, r.eigenvalues[np.argmin(d)])


@pytest.mark.parametrize("speed, volume, end", [(60.0, 150e-6, 6.0), (45.0, 150e-6, 12.0),
                                                (80.0, 300e-6, 10.0)])
def test_growth_rate_is_the_film_runs(speed, volume, end):
    """A film run of 003's bench without unbalance, started 10 nm off the axis, grows or decays
    at the linearisation's rate: the slope of log |w| over the run's second half (a fit through
    the whirl's beats). Measured: 1.772 vs 1.795, -0.217 vs -0.195, 0.618 vs 0.642 1/s."""
    r = bench(volume, speed)
    run = coupled_run(dataclasses.replace(ROTOR, unbalance=0.0), L.chamber_radius,
                      L.chamber_height, volume, speed, end, density=L.density,
                      viscosity=L.kinematic_viscosity, n_cells=64, save_dt=0.01,
                      deflection=1e-8)
    late = run.t > end / 2
    slope = np.polyfit(run.t[late], np.log(np.abs(run.deflection[late])), 1)[0]
    assert slope == pytest.approx(r.growth_rate, abs=0.035)


def test_003_bench_is_unstable_just_above_resonance():
    """Kollmann's band on 003's bench (omega_r = 54 1/s): 150 ml is stable at 45 and 100 1/s
    and unstable at 60 and 68.7 1/s, where the fill map's film runs do not reach a synchronous
    whirl (docs/liquid/machine.md sec. 3f). The band widens with the fill: 300 ml is unstable at 80."""
    assert bench(150e-6, 45.0).stable and bench(150e-6, 100.0).stable
    assert not bench(150e-6, 60.0).stable and not bench(150e-6, 68.7).stable
    assert not bench(300e-6, 80.0).stable and bench(75e-6, 80.0).stable


def test_growth_rate_converges_at_first_order_in_the_cells():
    """First-order finite volumes: doubling the cells halves the change of the growth rate.
    Measured at 60 1/s, 150 ml on 64 / 128 / 256 cells: 1.795, 1.87, 1.91 (changes 0.09, 0.04)."""
    g = [bench(150e-6, 60.0, n).growth_rate for n in (64, 128, 256)]
    d1, d2 = g[1] - g[0], g[2] - g[1]
    assert d1 > 0 and d2 > 0 and 0.35 < d2 / d1 < 0.65, g


def test_partitions_keep_each_compartments_volume():
    """Radial walls keep each compartment's volume (one neutral mode each, dropped) and stop the
    film's travelling waves that drive the whirl. Measured at 60 1/s, 150 ml: growth rate 1.80
    (open), 0.61 (2 walls), -0.71 (4), -3.12 (8) 1/s."""
    g = []
    for p in (0, 2, 4):
        r = bench(150e-6, 60.0, partitions=p)
        assert r.eigenvalues.size == 6 + 2 * 64 - max(1, p)
        g.append(r.growth_rate)
    assert g[0] > g[1] > 0 > g[2]


@pytest.mark.parametrize("kw, field", [({"speed": 0.0}, "speed"), ({"n_cells": 4}, "n_cells"),
                                       ({"volume": 1e-3}, "volume")])
def test_refusals_are_one_line(kw, field):
    args = {"volume": 150e-6, "speed": 60.0, "n_cells": 64, **kw}
    with pytest.raises(ParameterError) as e:
        ring_stability(ROTOR, 0.1 if field == "volume" else L.chamber_radius, L.chamber_height,
                       args["volume"], args["speed"], n_cells=args["n_cells"])
    assert str(e.value).startswith(field) and "\n" not in str(e.value)


@pytest.mark.slow
def test_cli_end_to_end(tmp_path):
    png = tmp_path / "s.png"
    r = subprocess.run([sys.executable, "-m", "autobalance", "liquid", "stability",
                        "leblanc_003", "--speeds", "40:100 rad/s:13", "--json", "--plot", str(png)],
                       capture_output=True, text=True, timeout=600)
    assert r.returncode == 0, r.stderr
    d = json.loads(r.stdout)
    assert len(d["growth_rate_1_s"]) == 13 and png.stat().st_size > 0
    lo, hi = d["unstable_ranges_rad_s"][0]
    assert 45.0 < lo < 60.0 < hi < 100.0
    # the text gives speeds in the unit --speeds was written in
    t = subprocess.run([sys.executable, "-m", "autobalance", "liquid", "stability",
                        "leblanc_003", "--speeds", "400:900 rpm:6"],
                       capture_output=True, text=True, timeout=600)
    assert t.returncode == 0, t.stderr
    assert "rpm - " in t.stdout and "rad/s" not in t.stdout
    bad = subprocess.run([sys.executable, "-m", "autobalance", "liquid", "stability",
                          "leblanc_003", "--cells", "4"], capture_output=True, text=True,
                         timeout=600)
    lines = bad.stderr.strip().splitlines()
    assert bad.returncode == 2 and len(lines) == 1 and lines[0].startswith("error: --cells")


def test_unstable_ranges_start_at_the_first_film_or_grid_speed():
    """A range that is unstable from the first speed with a film (NaN before: a pool) starts
    there, not at an interpolation with NaN (the top-loader ring's 125 ml printed 'nan rpm')."""
    from autobalance.liquid.stability import unstable_ranges

    w = np.array([10.0, 20.0, 30.0, 40.0, 50.0])
    assert unstable_ranges(w, np.array([np.nan, 1.0, 1.0, -1.0, 1.0])) == [(20.0, 35.0),
                                                                         (45.0, 50.0)]
    assert unstable_ranges(w, np.array([1.0, -1.0, np.nan, 1.0, np.nan])) == [(10.0, 15.0),
                                                                           (40.0, 40.0)]
    assert unstable_ranges(w, np.full(5, -1.0)) == []


def test_three_chambers_are_one_system():
    """003's three concentric chambers: one volume mode per chamber is dropped, and the band of
    the three films together (44.0-85.4 1/s on 64 cells each, sec. 3j) contains the outer
    chamber's own (47.5-82 1/s)."""
    three = load_config("leblanc_003_three").system
    L3 = three.liquid
    r = ring_stability(film_rotor(three), [c.chamber_radius for c in L3.chambers],
                       [c.chamber_height for c in L3.chambers], [c.volume for c in L3.chambers],
                       45.0, density=L3.density, viscosity=L3.kinematic_viscosity)
    assert r.eigenvalues.size == 6 + 2 * 3 * 64 - 3
    assert not r.stable and bench(150e-6, 45.0).stable
