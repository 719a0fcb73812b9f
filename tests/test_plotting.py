"""Smoke tests of the figures: they build, save readable PNGs and cope with N = 0 and long runs."""
import types

import numpy as np
import pytest
from matplotlib.figure import Figure

from autobalance.physics import response_table
from autobalance.models import BallBalancer, Rotor, Suspension, System
from autobalance.plotting import plot_response, plot_simulation
from autobalance.plotting.timeplot import MAX_POINTS


def fake_result(n=2000, n_balls=2, duration=10.0):
    t = np.linspace(0.0, duration, n)
    speed = np.interp(t, [0.0, 0.3 * duration, duration], [0.0, 1000.0, 1000.0])
    psi = np.cumsum(speed) * (t[1] - t[0])
    amp = 1e-4 / (1.0 + ((speed - 600.0) / 50.0) ** 2) + 1e-5
    alpha = np.pi / 4 + np.outer(np.exp(-t), np.arange(1, n_balls + 1)) + 0.2 * t[:, None]
    resid = 3e-4 * (1.0 + 0.5 * np.cos(t))
    return types.SimpleNamespace(
        t=t, x=amp * np.cos(psi), y=amp * np.sin(psi), amplitude=amp,
        alpha=alpha.reshape(n, n_balls), speed=speed, grade_G=20.0 * resid / 3e-4,
        residual_unbalance=resid, residual_angle=0.3 * t, title="fake run")


@pytest.mark.slow
def test_plot_simulation_png(tmp_path):
    fig = plot_simulation(fake_result())
    assert isinstance(fig, Figure)
    out = tmp_path / "sim.png"
    fig.savefig(out)
    assert out.stat().st_size > 10_000
    assert len(fig.axes) >= 7  # 5 time panels, speed twin axis, 2 polar plots


@pytest.mark.slow
def test_plot_simulation_without_balls(tmp_path):
    sim = fake_result(n_balls=0)
    assert sim.alpha.shape == (2000, 0)
    fig = plot_simulation(sim, speed_unit="Hz")
    out = tmp_path / "sim0.png"
    fig.savefig(out)
    assert out.stat().st_size > 10_000


@pytest.mark.slow
def test_plot_simulation_decimates_long_history(tmp_path):
    sim = fake_result(n=100_003, n_balls=3, duration=50.0)
    fig = plot_simulation(sim)
    for ax in fig.axes:
        for line in ax.get_lines():
            assert len(line.get_xdata()) <= MAX_POINTS + 1 or len(line.get_xdata()) == 361
    fig.savefig(tmp_path / "long.png")


def test_plot_simulation_bad_input():
    with pytest.raises(ValueError, match="speed_unit"):
        plot_simulation(fake_result(), speed_unit="furlong")
    with pytest.raises(ValueError, match="sim.t"):
        plot_simulation(types.SimpleNamespace(t=np.array([])))


@pytest.mark.slow
def test_plot_response_png(tmp_path):
    s = System(Rotor(37.0, 0.025), Suspension(20e3, 6e3, 200.0, 110.0),
               BallBalancer(2, 0.0893, 0.28, 0.01))
    fig = plot_response(response_table(s, np.linspace(0.0, 60.0, 300)))
    assert isinstance(fig, Figure)
    out = tmp_path / "resp.png"
    fig.savefig(out)
    assert out.stat().st_size > 10_000
    fig = plot_response(response_table(s, np.linspace(1.0, 60.0, 50)), log_amplitude=True)
    fig.savefig(tmp_path / "resp_log.png")


@pytest.mark.slow
def test_plot_sweep_png(tmp_path):
    """A real (tiny) sweep: figure with the PDF, the checkpoint scatter and one grid panel."""
    from autobalance.plotting import plot_sweep
    from autobalance.sweep import spec_from_dict, sweep

    d = {"sweep": {"name": "p", "base": "vub_jeffcott_004",
                   "set": ["profile.duration=12 s", "profile.runup_fraction=0.5",
                           "profile.down_time=1 s", "profile.plateau_time=2 s",
                           "profile.up_time=1 s"]},
         "grid": {"balancer.rolling_resistance": [0.001, 0.003]},
         "monte_carlo": {"kind": "start_grid", "n": 3}}
    ds = sweep(spec_from_dict(d), tmp_path / "s", executor="serial", progress=False)
    fig = plot_sweep(ds)
    assert len(fig.axes) == 3
    out = tmp_path / "sweep.png"
    fig.savefig(out, dpi=80)
    assert out.stat().st_size > 10_000
