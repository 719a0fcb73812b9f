"""The state at a located stick-slip event from DOPRI5's continuous extension (core/step.py
``_dense``; docs/numerics/index.md): the extension's order on a closed-form solution, and the
kernel's runs against the same runs at a thousand times tighter tolerances (grades within the
Monte Carlo's 0.02 mm/s)."""
from __future__ import annotations

import numpy as np
import pytest

import autobalance as ab
from autobalance.config import load_config
from autobalance.core import step as K
from autobalance.sweep.plan import separate, start_grid

from oracles import stepped


def _stages(y0, h):
    """DOPRI5's stages of one step of y' = (y1, -y0) from (0, y0) (the kernel's tableau)."""
    f = lambda y: np.array([y[1], -y[0]])                                   # noqa: E731
    k1 = f(y0)
    k2 = f(y0 + h * K.A21 * k1)
    k3 = f(y0 + h * (K.A31 * k1 + K.A32 * k2))
    k4 = f(y0 + h * (K.A41 * k1 + K.A42 * k2 + K.A43 * k3))
    k5 = f(y0 + h * (K.A51 * k1 + K.A52 * k2 + K.A53 * k3 + K.A54 * k4))
    k6 = f(y0 + h * (K.A61 * k1 + K.A62 * k2 + K.A63 * k3 + K.A64 * k4 + K.A65 * k5))
    y1 = y0 + h * (K.A71 * k1 + K.A73 * k3 + K.A74 * k4 + K.A75 * k5 + K.A76 * k6)
    return k1, np.array([k1, k2, k3, k4, k5, k6]), y1, f(y1)


@pytest.mark.parametrize("th", [0.0, 0.31, 0.77, 1.0])
def test_continuous_extension_is_fourth_order_and_exact_at_the_ends(th):
    """On y'' = -y (exact sin, cos) the extension's error at any fraction falls as h^5 (local
    order 4: ratio ~32 per halving), and it returns the step's ends exactly."""
    errs = []
    for h in (0.2, 0.1, 0.05):
        y0 = np.array([0.0, 1.0])
        f0, st, y1, f1 = _stages(y0, h)
        out = np.empty(2)
        K._dense(y0, f0, y1, f1, st, h, th, out)
        errs.append(np.abs(out - [np.sin(th * h), np.cos(th * h)]).max())
        if th in (0.0, 1.0):
            assert np.array_equal(out, y0 if th == 0.0 else y1)
    if 0.0 < th < 1.0:
        assert errs[0] / errs[1] > 25 and errs[1] / errs[2] > 25
        assert errs[0] < 2e-7


def test_events_from_the_continuous_extension_keep_the_grades():
    """Thirteen starts of 004's 90 s TSR run: the grades at every checkpoint within 0.02 mm/s
    (the Monte Carlo's resolution) of the same runs at rtol and atol_scale 1e-9 (measured: at
    most 6.1e-5 mm/s, median 2.1e-5). DOPRI5 steps every phase here (no slip jumps): the
    events it locates are what the continuous extension gives the state of."""
    cfg = load_config("vub_jeffcott_004")
    angles = start_grid(50, 2, True)[::106]
    dG = []
    for a in angles:
        ini = ab.InitialState(ball_angles=tuple(separate(a, cfg.system.balancer.contact_angle)))
        runs = [stepped(cfg.system, cfg.spin, initial=ini, slip_jumps=False,
                        options=ab.SimOptions(save_dt=-1.0, rtol=tol, atol_scale=tol))
                for tol in (1e-6, 1e-9)]
        dG.append(np.abs(runs[0].grade_G - runs[1].grade_G).max())
    assert len(angles) == 13 and max(dG) < 0.02
