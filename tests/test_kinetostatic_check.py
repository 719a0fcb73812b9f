"""001's kinetostatic laws against the liquid from physics (liquid/kinetostatic_check.py,
``autobalance liquid kinetostatic-check``; docs/liquid/kinetostatics.md sec. 2b): the laws compared with
the dynamic results."""
from __future__ import annotations

import json
import subprocess
import sys

import numpy as np
import pytest

from autobalance.liquid import eccentricity_ratio
from autobalance.liquid.kinetostatic_check import kinetostatic_vs_physics
from autobalance.papers.p003.bench import bench

B = bench()                                         # 003's bench: 150 ml of water at 0.2 m
CH = (B.balancer.chamber.radius, B.balancer.chamber.height, B.balancer.chamber.inner_radius,
      B.balancer.volume)
SPEEDS = [65.0, 80.0, 100.0]                         # above resonance (54 1/s): a ring


@pytest.fixture(scope="module")
def water():
    return kinetostatic_vs_physics(B.rotor, CH, 1000.0, 1.0e-6, SPEEDS, settle_time=4.0)


@pytest.fixture(scope="module")
def viscous():
    return kinetostatic_vs_physics(B.rotor, CH, 1000.0, 1.0e-4, SPEEDS, settle_time=4.0)


def test_the_quasi_static_liquid_sits_on_the_deflection_and_the_film_settles_there(water):
    """The quasi-static liquid gathers where the wall is farthest from the axis: its moment
    points along the deflection (the classical law) to round-off. The coupled film, started on
    that whirl, settles within 0.5 deg of it (measured 0.04-0.14 deg) and its |U_l| within
    2.5 eta/R (the thin film's O(eta/R), sec. 3c; measured 1.3-1.8 % against eta/R = 1.2 %)."""
    assert np.allclose(water["alpha_deg"], water["deflection_angle_deg"], atol=1e-9)
    assert np.abs(water["alpha_film_deg"] - water["alpha_deg"]).max() < 0.5
    eta = CH[3] / (2 * np.pi * CH[0] * CH[1])
    assert np.abs(water["k_film"] / water["k"] - 1).max() < 2.5 * eta / CH[0]


def test_001_eq1_is_the_geometry_of_the_residual(water):
    """001 eq 1, e_c/e = sqrt(1 + 2k cos alpha + k^2), at the physical k and alpha is the
    physical |D + U_l|/|D| (to 1e-12)."""
    ec = eccentricity_ratio(water["k"], np.radians(water["alpha_deg"]))
    assert np.allclose(ec, water["ec_over_e"], rtol=1e-12)


def test_001_eq3_puts_the_liquid_short_of_where_physics_puts_it(water):
    """At the physical phase delta and ratio k, 001 eq 3's alpha0 lies 9-14 deg short of the
    physical liquid angle above resonance (measured 9.5, 14.2, 13.3 deg at 65, 80, 100 1/s), on
    the same side: 001's eq 2 makes the *resultant* D_c sit at delta from D, the physics makes
    the liquid sit at the deflection (docs/liquid/kinetostatics.md sec. 2, note on eq 2)."""
    gap = np.abs(water["alpha_deg"]) - np.abs(water["alpha0_deg"])
    assert np.all(gap > 5.0) and np.all(gap < 20.0)
    assert np.all(np.sign(water["alpha0_deg"]) == np.sign(water["alpha_deg"]))
    assert np.all(water["ec_over_e_001"] > water["ec_over_e"])   # 001 predicts a worse residual


def test_viscosity_moves_001s_liquid_but_not_the_settled_film(water, viscous):
    """In the synchronous state the film is at rest on the wall: no wall shear, no friction
    angle. 100 x the viscosity moves the settled film by < 0.3 deg (measured 0.04 deg); 001
    eq 6's beta moves from 0.06-0.09 deg to 6.0-9.3 deg."""
    assert np.abs(viscous["alpha_film_deg"] - water["alpha_film_deg"]).max() < 0.3
    assert np.all(viscous["beta_deg"] - water["beta_deg"] > 5.0)
    assert np.array_equal(viscous["alpha_deg"], water["alpha_deg"])  # quasi-static: no nu


def test_below_the_entrainment_speed_there_is_no_ring():
    r = kinetostatic_vs_physics(B.rotor, CH, 1000.0, 1.0e-6, [10.0, 65.0])
    assert r["k"][0] == 0 and np.isnan(r["alpha_deg"][0]) and np.isnan(r["alpha0_deg"][0])
    assert r["k"][1] > 0 and "alpha_film_deg" not in r


def _cli(*args):
    return subprocess.run([sys.executable, "-m", "autobalance", "liquid", "kinetostatic-check",
                           *args], capture_output=True, text=True, timeout=120)


def test_cli_text_json_and_figure(tmp_path):
    png = tmp_path / "k.png"
    p = _cli("--speeds", "54, 80 rad/s", "--settle", "2 s", "--json", "--plot", str(png))
    assert p.returncode == 0, p.stderr
    d = json.loads(p.stdout)
    assert d["machine"] == "leblanc_003" and d["omega_rad_s"] == [54.0, 80.0]
    assert d["alpha_film_deg"][1] == pytest.approx(d["alpha_deg"][1], abs=0.5)
    assert png.stat().st_size > 10_000
    t = _cli("--speeds", "80 rad/s", "--settle", "0 s", "--liquid", "viscous_97")
    assert t.returncode == 0, t.stderr
    assert "viscous_97" in t.stdout and "alpha0(001)" in t.stdout
    assert "alpha_film" not in t.stdout


def test_cli_text_speaks_the_machines_units():
    """A machine of one's own (examples/toploader-ring.toml, speeds written in rpm): the table's
    speeds in rpm, as written; ``--units speed=rad/s`` switches them."""
    p = _cli("examples/toploader-ring.toml", "--speeds", "300, 600 rpm", "--settle", "0 s")
    assert p.returncode == 0, p.stderr
    lines = p.stdout.splitlines()
    assert lines[1].split()[0] == "omega[rpm]"
    assert [float(x.split()[0]) for x in lines[2:4]] == pytest.approx([300.0, 600.0])
    q = _cli("examples/toploader-ring.toml", "--speeds", "300, 600 rpm", "--settle", "0 s",
             "--units", "speed=rad/s")
    assert q.stdout.splitlines()[1].split()[0] == "omega[rad/s]"
    assert float(q.stdout.splitlines()[2].split()[0]) == pytest.approx(300 * np.pi / 30,
                                                                       rel=1e-3)


@pytest.mark.parametrize("args,field", [
    (["leblanc_washer"], "liquid.axis"),
    (["--speeds", "80, 60 rad/s"], "--speeds"),
    (["--settle", "-1 s"], "--settle"),
    (["leblanc_003_three"], "liquid.chamber_radius"),
    (["--set", "rotor.unbalance=0 kg*m", "--settle", "0 s"], "rotor.unbalance")])
def test_cli_refusals_are_one_line(args, field):
    p = _cli(*args)
    assert p.returncode == 2
    lines = p.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("error:") and field in lines[0], p.stderr


def test_the_001_report_shows_the_comparison():
    """``reproduce 001-eq3-4`` carries the comparison beside 001's closed forms: a figure, a
    dataset over speed and a note with its figures (not a published number: no row)."""
    from autobalance.papers.p001.kinetostatics import run_eq3_4
    from autobalance.validation.target import Context

    out = run_eq3_4(Context(quick=True))
    ds = out.data["vs-physics"]
    assert set(out.figures) == {"eq3_4", "vs-physics"} and ds.sizes["omega_rad_s"] == 7
    ring = np.isfinite(ds["alpha_film_deg"].values)
    assert ring.all()                                # 40-100 1/s: above omega_0 (22.7 1/s)
    assert np.abs(ds["alpha_film_deg"] - ds["alpha_deg"]).max() < 1.5
    assert "Against the physics" in out.notes and len(out.rows) == 4
