"""Residual unbalance of a rotor with a ball balancer: the one home of the formula.

In the rotor-fixed frame, with the rotor's own unbalance U = M e along the reference direction,
N balls of masses m_i at angles alpha_i on a race of radius R whose centre is offset by the ring
eccentricity rho at angle beta (000 eq 33-36), the resultant static unbalance is

    W = U + sum_i m_i (R e^{i alpha_i} + rho e^{i beta})       [kg*m]

(000 eq 22 for rho = 0, eq 47 with the eccentricity; 004 sec. 4 reads the grade from |W|).
The compiled twin inside the kernel (core/hold.py ``ball_unbalance``) is tested against it.
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = ["residual_unbalance"]


def residual_unbalance(system: System, alpha: npt.ArrayLike,
                       unbalance: float | npt.ArrayLike | None = None):
    """Complex residual unbalance W = U + sum_i m_i (R e^{i alpha_i} + rho e^{i beta}) [kg*m].

    Parameters
    ----------
    system : autobalance.models.System
        Ball masses m_i [kg], race radius R [m], ring eccentricity rho [m] and its angle beta
        [rad] from ``system.balancer``; U [kg*m] from ``system.rotor.unbalance``.
    alpha : array_like
        Ball angles from the unbalance direction [rad], shape (..., N).
    unbalance : float or array_like, optional
        The rotor's own unbalance U [kg*m] to use instead of ``system.rotor.unbalance``
        (e.g. a time-varying U(t), broadcast against ``alpha[..., 0]``).

    Returns
    -------
    ndarray of complex
        W [kg*m], shape ``alpha.shape[:-1]`` broadcast with ``unbalance``; its modulus is the
        residual unbalance and its argument the residual's angle in the rotor frame [rad].
    """
    b = system.balancer
    U = system.rotor.unbalance if unbalance is None else unbalance
    a = np.asarray(alpha, float)
    res = np.asarray(U).astype(complex)
    if b.n_balls:
        m = b.masses
        res = res + (m * b.race_radius * np.exp(1j * a)).sum(axis=-1)
        res = res + m.sum() * b.eccentricity * np.exp(1j * b.eccentricity_angle)
    else:
        res = res + np.zeros(a.shape[:-1])
    return res
