"""ISO 1940-1 balance quality grade G (rigid rotors).

004 section 4 (ISO 1940-11:2016 as quoted there): the grade G is the product of the permissible
residual specific unbalance (mass-centre eccentricity) e_per = U/m in [mm] and the highest
nominal operating speed Omega in [rad/s], expressed in [mm/s]:

    G = e_per[mm] * Omega[rad/s] = 1000 * (U[kg*m] / m[kg]) * Omega[rad/s].

Check (004 Table 1 footnote): e = 19.3 um at 167 Hz gives G = 0.0193 * 2 pi 167 = 20.3 -> "G20".
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from ..models._validate import array as _array

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["GRADES", "grade", "grade_class", "grade_value", "permissible_eccentricity", "unbalance_for_grade",
           "unbalance_value"]

#: The standard ISO 1940-1 series of balance quality grades G [mm/s] (ratio 2.5 between steps).
GRADES = (0.4, 1.0, 2.5, 6.3, 16.0, 40.0, 100.0, 250.0, 630.0, 1600.0, 4000.0)

_M_TO_MM = 1000.0




def _out(a):
    return float(a) if np.ndim(a) == 0 else a


def grade_value(residual_unbalance: float | npt.ArrayLike, mass: float | npt.ArrayLike,
                nominal_speed: float | npt.ArrayLike):
    """G = 1000 (U / m) Omega [mm/s], unchecked (NaN in, NaN out): the one home of the formula.

    Parameters
    ----------
    residual_unbalance : float or array_like
        Residual static unbalance |U| [kg*m].
    mass : float or array_like
        Mass m [kg] (M_t = M + sum m_i for a balancer's rotor, 004 sec. 4).
    nominal_speed : float or array_like
        Highest nominal operating speed Omega [rad/s].

    Returns
    -------
    ndarray
        Grade G [mm/s]; :func:`grade` is the checked form for user input.
    """
    return np.asarray(residual_unbalance) / mass * _M_TO_MM * nominal_speed


def unbalance_value(G: float | npt.ArrayLike, mass: float | npt.ArrayLike,
                    nominal_speed: float | npt.ArrayLike):
    """U = m G / (1000 Omega) [kg*m], unchecked: the inverse of :func:`grade_value`.

    Parameters
    ----------
    G : float or array_like
        Grade [mm/s].
    mass : float or array_like
        Mass m [kg].
    nominal_speed : float or array_like
        Highest nominal operating speed Omega [rad/s].

    Returns
    -------
    ndarray
        Unbalance U [kg*m].
    """
    return np.asarray(G, float) * mass / (_M_TO_MM * nominal_speed)


def grade(residual_unbalance: float | npt.ArrayLike, mass: float | npt.ArrayLike,
          nominal_speed: float | npt.ArrayLike):
    """Balance quality grade G = e_per[mm] * Omega[rad/s] (004 section 4, ISO 1940-1).

    Parameters
    ----------
    residual_unbalance : float or array_like
        Residual static unbalance U [kg*m], >= 0 (e.g. |M e + sum m_i R e^{i alpha_i}|).
    mass : float or array_like
        Rotor mass m [kg], > 0 (004 uses the shaft mass M = 16.53 kg).
    nominal_speed : float or array_like
        Highest nominal operating speed Omega [rad/s], > 0.

    Returns
    -------
    G : float or ndarray
        Grade [mm/s] (broadcast shape of the inputs).

    Examples
    --------
    >>> round(grade(16.53 * 19.3e-6, 16.53, 2 * 3.141592653589793 * 167), 1)
    20.3
    """
    u = _array("residual_unbalance", residual_unbalance, strict=False)
    m = _array("mass", mass, strict=True)
    w = _array("nominal_speed", nominal_speed, strict=True)
    return _out(grade_value(u, m, w))


def unbalance_for_grade(G: float | npt.ArrayLike, mass: float | npt.ArrayLike,
                        nominal_speed: float | npt.ArrayLike):
    """Static unbalance U [kg*m] that corresponds to grade G (inverse of :func:`grade`).

    Parameters
    ----------
    G : float or array_like
        Balance quality grade [mm/s], >= 0.
    mass : float or array_like
        Rotor mass m [kg], > 0.
    nominal_speed : float or array_like
        Highest nominal operating speed Omega [rad/s], > 0.

    Returns
    -------
    U : float or ndarray
        Permissible residual unbalance U = m * G / (1000 * Omega) [kg*m].
    """
    g = _array("G", G, strict=False)
    m = _array("mass", mass, strict=True)
    w = _array("nominal_speed", nominal_speed, strict=True)
    return _out(unbalance_value(g, m, w))


def permissible_eccentricity(G: float | npt.ArrayLike, nominal_speed: float | npt.ArrayLike):
    """Permissible mass-centre eccentricity e_per = G / Omega [m] for grade G [mm/s].

    Parameters
    ----------
    G : float or array_like
        Balance quality grade [mm/s], >= 0.
    nominal_speed : float or array_like
        Highest nominal operating speed Omega [rad/s], > 0.
    """
    g = _array("G", G, strict=False)
    w = _array("nominal_speed", nominal_speed, strict=True)
    return _out(g / (_M_TO_MM * w))


def grade_class(G: float | npt.ArrayLike):
    """Smallest standard grade of :data:`GRADES` that G [mm/s] satisfies (G <= class).

    Parameters
    ----------
    G : float or array_like
        Achieved grade [mm/s], >= 0.

    Returns
    -------
    float or ndarray
        The ISO class [mm/s]; inf when G exceeds G4000.
    """
    g = _array("G", G, strict=False)
    series = np.asarray(GRADES + (np.inf,))
    # small tolerance so that a computed 16.000000001 still counts as G16
    idx = np.searchsorted(series, g * (1.0 - 1e-9), side="left")
    return _out(series[idx])
