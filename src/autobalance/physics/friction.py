"""The rolling-friction laws of the balls (004 eq 10's friction term) and the slow manifold of
004's tanh law, which the exact stick-slip kernel can emulate (``options.friction_law = "creep"``).

004 models the ball-race friction as F_f = mu F_n tanh(phi_dot / v_sat) (004 sec. 3.1, eq 10;
v_sat = 1e-6 rad/s in our reading). For a ball whose other forces need a friction torque lambda
[N*m] to keep it at rest relative to the race, the tanh law does not hold it at rest: the ball's
equation J phi_ddot = -lambda_app - mu N R tanh(phi_dot / v_sat) relaxes, on the time scale
J v_sat / (mu N R (1 - (lambda/mu N R)^2)), to the slow manifold where friction balances the
applied torque (Tikhonov's theorem on singularly perturbed systems; Khalil, *Nonlinear
Systems*, 3rd ed., sec. 11.2):

    -mu N R tanh(phi_dot / v_sat) = lambda   =>   phi_dot = -v_sat atanh(lambda / (mu N R)),

a creep at a fraction of v_sat while |lambda| < mu N R. The exact stick-slip model is its limit
v_sat -> 0. docs/numerics/kernel.md sec. "The tanh law's slow manifold" gives the accuracy tests.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..core.rhs import CREEP_RATIO_MAX

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["CREEP_RATIO_MAX", "creep_speed"]


def creep_speed(required_torque: npt.ArrayLike, kinetic_limit: npt.ArrayLike, v_sat: float):
    """Creep speed of a ball held by 004's tanh friction law on its slow manifold [rad/s]:
    phi_dot = -v_sat atanh(lambda / (mu N R)) (004 eq 10 with tanh(phi_dot/v_sat) solved for
    phi_dot; module docstring).

    Parameters
    ----------
    required_torque : array_like
        Friction torque lambda the ball needs to stay at rest relative to the race [N*m]
        (the exact-stick kernel's constraint torque, positive along +alpha).
    kinetic_limit : array_like
        mu N R, the largest friction torque of the tanh law [N*m]; 0 gives no creep.
    v_sat : float
        Saturation speed of the tanh law [rad/s].

    Returns
    -------
    ndarray
        phi_dot [rad/s], the ball's speed relative to the race; |lambda| >= mu N R is clipped
        to :data:`CREEP_RATIO_MAX` (where the tanh law's ball slips, the stick-slip kernel
        releases it as well).
    """
    lam = np.asarray(required_torque, float)
    lim = np.asarray(kinetic_limit, float)
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        r = np.where(lim > 0.0, lam / np.where(lim > 0.0, lim, 1.0), 0.0)
    return -v_sat * np.arctanh(np.clip(r, -CREEP_RATIO_MAX, CREEP_RATIO_MAX))
