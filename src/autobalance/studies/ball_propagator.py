"""The rotor and balls of a machine beside a liquid, linearised about their balanced state over
one step: the propagator that the balanced state's linear stability
(:mod:`autobalance.studies.liquid_balanced`) and its Floquet map on a horizontal axis
(:mod:`autobalance.studies.liquid_floquet`) both step the balls with (docs/liquid/stability.md
sec. 3k, docs/liquid/horizontal-axis.md sec. 3m).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..models import System

__all__ = ["ball_propagator", "flat"]


def flat(pool: System) -> System:
    """The machine without in-plane gravity (its rotor frame's steadiness and its balanced
    angles are those of the machine without gravity).

    Parameters
    ----------
    pool : System
        The machine (gravity [m/s^2] set to 0 in the copy).
    """
    import dataclasses

    return dataclasses.replace(pool, gravity=dataclasses.replace(pool.gravity, g=0.0))


def ball_propagator(pool: System, W: float, alpha: np.ndarray, dt: float, L: float,
                    phase: float | None = None) -> tuple:
    """(Phi, Gamma, c, res): the ideal pool machine's rotor and balls over dt [s] at W [rad/s],
    linear about the balanced angles alpha [rad], z -> z_ref + Phi (z - z_ref) + Gamma (U, U')
    (real pairs) + c, and the balanced state's scaled residual. With the spin angle ``phase``
    [rad] (a horizontal axis) the right-hand side is taken there, frozen over the step (the
    exponential midpoint rule when ``phase`` is the step's middle), and c is the drift of
    gravity's pull on the balls (the affine term; 0 without a phase).

    Parameters
    ----------
    pool : System
        The ideal pool machine (:func:`autobalance.liquid.start.pool_machine`).
    W : float
        Spin speed [rad/s].
    alpha : ndarray
        Balanced ball angles [rad].
    dt : float
        Step [s].
    L : float
        Length scale of the finite differences [m].
    phase : float, optional
        Spin angle [rad] at which the right-hand side is frozen (a horizontal axis).

    Returns
    -------
    tuple
        (Phi, Gamma, c, res): the state map [-], the input map of the held moment (U, U')
        [per kg*m], the affine drift and the scaled residual [-].
    """
    from scipy.linalg import expm

    from ..simulate.probe import rotor_frame_derivative

    ps = 0.0 if phase is None else float(phase)
    n = alpha.size
    z0 = np.concatenate([[0.0, 0.0], alpha, np.zeros(n + 2)])
    h = np.concatenate([[1e-4 * L] * 2, [1e-5] * n, [1e-4 * L * W] * 2, [1e-7 * W] * n])
    F = rotor_frame_derivative(pool, W, np.concatenate([z0 + np.diag(h), z0 - np.diag(h)]),
                               phase=ps)
    m = z0.size
    A = ((F[:m] - F[m:]) / (2 * h)[:, None]).T
    fscale = np.concatenate([[L * W] * 2, [W] * n, [L * W * W] * 2, [W * W] * n])
    f0 = rotor_frame_derivative(pool, W, z0, phase=ps)
    res = float(np.max(np.abs(f0 / fscale)))
    Bm = np.empty((m, 4))
    u = pool.total_mass * L              # the held moment's scale [kg*m]
    for j, (U, Ud) in enumerate([(u, 0j), (1j * u, 0j), (0j, u * W), (0j, 1j * u * W)]):
        d = abs(U) + abs(Ud)
        Bm[:, j] = (rotor_frame_derivative(pool, W, z0, (U, Ud), phase=ps)
                    - rotor_frame_derivative(pool, W, z0, (-U, -Ud), phase=ps)) / (2 * d)
    k = m + 4 if phase is None else m + 5
    aug = np.zeros((k, k))
    aug[:m, :m] = A
    aug[:m, m:m + 4] = Bm
    if phase is not None:
        aug[:m, m + 4] = f0
    E = expm(aug * dt)
    return E[:m, :m], E[:m, m:m + 4], (E[:m, m + 4] if phase is not None else np.zeros(m)), res
