"""Immobility of balls at rest and the stick threshold (004 sec. 4.4, eq 1 against Coulomb
friction): closed forms on the steady synchronous orbit, for any isotropic (Jeffcott) machine.

A ball at rest on the race of a rotor spinning at constant speed Omega feels the tangential
vibratory force F_t = m z Omega^2 sin(gamma) (004 eq 1) and sticks while |F_t| <= mu_s m R Omega^2.
The compiled kernel's stuck-ball friction agrees (tests/test_tsr_004.py, via
:func:`autobalance.simulate.probe.kernel_required_friction`).

Gravity g in the rotor's plane (a horizontal axis; our extension, docs/tsr-studies.md): the
steady orbit is the synchronous one plus the static sag, which does not accelerate the race, but
the ball's weight turns once a revolution in the rotor frame. At the angle phi of the ball from
gravity's direction it adds -m g sin(phi) to the tangential force and m g cos(phi) to the normal
force (000 eq 50; the kernel's ball row). The ball stays at rest through a whole revolution iff
|F_t - m g sin(phi)| <= mu_s m (R Omega^2 + g cos(phi)) for every phi, and the largest of
+-(F_t - m g sin phi) - mu_s m g cos phi over phi is |F_t| + m g sqrt(1 + mu_s^2):
|F_t| + m g sqrt(1 + mu_s^2) <= mu_s m R Omega^2. Below Omega^2 = g sqrt(1 + mu_s^2) / (mu_s R)
no ball stays at rest anywhere.
"""
from __future__ import annotations

from typing import TYPE_CHECKING, Callable

import numpy as np

from .response import axis_response, synchronous_orbit
from .unbalance import residual_unbalance

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = ["IMMOBILITY_BYTES", "IMMOBILITY_BYTES_PER_BALL", "IMMOBILITY_COST_S", "check_immobility",
           "configurations", "immobile_mask", "immobility", "steady_deflection",
           "stick_threshold_grade", "tangential_force"]


def steady_deflection(system: System, speed: npt.ArrayLike, alpha: npt.ArrayLike,
                      response: Callable | None = None):
    """Rotor-frame deflection w = u + i v [m] on the steady orbit with the balls at rest.

    Jeffcott rotor at constant speed (004 eq 8-9 with all time derivatives zero in the rotor
    frame; textbook synchronous response): w = Omega^2 U_t / (k - M_t Omega^2 + i c Omega),
    U_t = U + sum m_i R e^{i alpha_i}. Same as :func:`autobalance.physics.response.steady_orbit_start`
    (isotropic suspension).

    Parameters
    ----------
    system : System
        Isotropic suspension (k, c), rotor unbalance U [kg m], balls m_i [kg] at radius R [m].
    speed : array_like
        Spin speed Omega [rad/s]; broadcast against ``alpha[..., 0]``.
    alpha : array_like (..., N)
        Ball angles from the unbalance [rad].
    response : callable or None
        (speed [rad/s], U_t [kg*m, complex]) -> w [m]: another machine's steady orbit for the
        same U_t (a liquid beside the balls: :func:`autobalance.studies.immobility.
        liquid_response`); None: the Jeffcott response above.

    Returns
    -------
    ndarray of complex
        w [m], shape broadcast(speed, alpha[..., 0]).
    """
    if response is not None:
        return response(speed, residual_unbalance(system, alpha))
    s = system.suspension
    if s.kx != s.ky or s.cx != s.cy:
        raise ValueError("steady_deflection: needs an isotropic (Jeffcott) suspension")
    return synchronous_orbit(system, np.asarray(speed, float), residual_unbalance(system, alpha))[0]

def tangential_force(system: System, speed: npt.ArrayLike, alpha: npt.ArrayLike,
                     response: Callable | None = None):
    """Tangential vibratory force on each ball at rest [N], 004 eq (1): F_t = m z Omega^2 sin(gamma).

    z e^{i gamma} = w e^{-i alpha_i} is the deflection seen from ball i (gamma measured from the
    ball to the deflection); positive F_t drives the ball towards +alpha. Equivalently the ball
    row of 004 eq (10) with phi_dot = phi_ddot = 0, psi_ddot = 0 and the rotor on its steady
    orbit: F_t R = m R Omega^2 (v cos alpha - u sin alpha).

    Parameters
    ----------
    system : System
        Isotropic suspension (k [N/m], c [N s/m]), rotor unbalance U [kg m], balls m_i [kg] at
        radius R [m].
    speed : array_like
        Spin speed Omega [rad/s]; broadcast against ``alpha[..., 0]``.
    alpha : array_like (..., N)
        Ball angles from the unbalance [rad].
    response : callable or None
        The steady orbit, as :func:`steady_deflection` takes it.

    Returns
    -------
    ndarray (..., N)
        F_t [N].
    """
    a = np.asarray(alpha, float)
    w = np.asarray(steady_deflection(system, speed, a, response))
    W = np.asarray(speed, float)
    m = system.balancer.masses
    return m * (W * W)[..., None] * np.imag(w[..., None] * np.exp(-1j * a))

def immobile_mask(system: System, speed: npt.ArrayLike, alpha: npt.ArrayLike,
                  response: Callable | None = None):
    """True where every ball at rest stays stuck: |F_t| <= mu_s N with N = m R Omega^2 (004 eq 1
    against Coulomb friction mu F_n, 004 sec. 3.1; normal force of a ball at rest on the race).

    Omega cancels: ball i sticks iff |Im(w e^{-i alpha_i})| <= mu_s R. With gravity g in the
    plane (module docstring) through a whole revolution: iff |Im(w e^{-i alpha_i})| <= mu_s R -
    g sqrt(1 + mu_s^2) / Omega^2. Shape of ``speed`` broadcast with ``alpha[..., 0]``.

    Parameters
    ----------
    system : System
        Isotropic suspension (k [N/m], c [N s/m]), rotor unbalance U [kg m], balls at radius
        R [m] with static friction coefficients mu_s [-] (``balancer.stiction``); in-plane
        gravity g [m/s^2] (``gravity.g``).
    speed : array_like
        Spin speed Omega [rad/s]; broadcast against ``alpha[..., 0]``.
    alpha : array_like (..., N)
        Ball angles from the unbalance [rad].
    response : callable or None
        The steady orbit, as :func:`steady_deflection` takes it.

    Returns
    -------
    ndarray of bool
        True where all N balls stick, shape broadcast(speed, alpha[..., 0]).
    """
    a = np.asarray(alpha, float)
    w = np.asarray(steady_deflection(system, speed, a, response))
    mus = np.asarray(system.balancer.stiction, float)
    R = system.balancer.race_radius
    return np.all(np.abs(np.imag(w[..., None] * np.exp(-1j * a))) <= _stick_limit(
        system, speed, mus, R), axis=-1)


def _stick_limit(system: System, speed, mus, R: float):
    """mu_s R, less g sqrt(1 + mu_s^2) / Omega^2 with in-plane gravity g (module docstring) [m]:
    the largest |Im(w e^{-i alpha})| at which a ball at rest stays at rest (speed [rad/s],
    broadcast with the balls' axis; mus [-] per ball; R [m])."""
    g = system.gravity.g
    if g == 0.0:
        return mus * R
    W = np.asarray(speed, float)[..., None]
    return mus * R - g * np.sqrt(1.0 + mus * mus) / (W * W)


#: Peak memory of :func:`immobility` per ball configuration and ball [B] (the meshgrid, the
#: stacked angles and the complex temporaries of :func:`immobile_mask`), plus per configuration.
IMMOBILITY_BYTES_PER_BALL = 64
IMMOBILITY_BYTES = 64
#: Measured time of :func:`immobility` per configuration, ball and speed [s] (0.25 us at N = 2).
IMMOBILITY_COST_S = 0.15e-6


def check_immobility(n_conf: int, n_balls: int, n_speeds: int = 1, n_sets: int = 1,
                     field: str = "n_conf") -> None:
    """Refuse (ResourceError naming ``field``) an immobility grid of ``n_conf`` ** ``n_balls``
    configurations [-] whose memory or run time over ``n_speeds`` x ``n_sets`` evaluations
    exceeds the limits of :mod:`autobalance.limits`, before anything is allocated.

    The estimate uses :data:`IMMOBILITY_BYTES_PER_BALL`, :data:`IMMOBILITY_BYTES` [B] and
    :data:`IMMOBILITY_COST_S` [s].

    Parameters
    ----------
    n_conf : int
        Equispaced positions per ball (the grid has n_conf ** n_balls configurations).
    n_balls : int
        Number of balls N.
    n_speeds : int
        Speeds evaluated per set.
    n_sets : int
        Number of such sets (e.g. machines or unbalances) evaluated with the same grid.
    field : str
        Parameter name the error message names.

    Raises
    ------
    ResourceError
        If the grid's memory or run time exceeds the limits.
    """
    from ..limits import check_memory, check_runtime

    k = float(n_conf) ** max(int(n_balls), 1)          # float: no huge-int arithmetic
    check_memory(field, n_conf, k * (IMMOBILITY_BYTES_PER_BALL * n_balls + IMMOBILITY_BYTES),
                 f"grid of {k:.3g} ball configurations")
    check_runtime(field, n_conf, k * n_balls * n_speeds * n_sets * IMMOBILITY_COST_S,
                  f"immobility grid ({k:.3g} configurations x {n_speeds * n_sets} speeds)")


def configurations(n_conf: int, n_balls: int) -> np.ndarray:
    """The ball configurations of :func:`immobility`: n_conf equispaced positions per ball, the
    full product (uniform on the torus).

    Parameters
    ----------
    n_conf : int
        Equispaced positions per ball [-].
    n_balls : int
        Number of balls N [-].

    Returns
    -------
    ndarray (n_conf ** n_balls, n_balls)
        Ball angles [rad].
    """
    pos = 2 * np.pi * np.arange(n_conf) / n_conf
    grids = np.meshgrid(*([pos] * n_balls), indexing="ij")
    return np.stack([g.ravel() for g in grids], axis=-1)


def immobility(system: System, speeds: float | npt.ArrayLike, n_conf: int = 100,
               response: Callable | None = None):
    """004 sec. 4.4 immobility: share [-] of ball configurations (n_conf equispaced positions per
    ball, full product = uniform on the torus) in which no ball can move, at each speed [rad/s].

    Closed form (:func:`immobile_mask`), vectorised; no time integration. A grid beyond the
    memory or run-time limit is refused first (:func:`check_immobility`).

    Parameters
    ----------
    system : System
        Isotropic (Jeffcott) machine: suspension k [N/m], c [N s/m], unbalance U [kg m], balls
        m_i [kg] at radius R [m] with static friction mu_s [-].
    speeds : float or array_like
        Spin speeds Omega [rad/s] (004 Figs. 8, 10: the speed axis).
    n_conf : int
        Equispaced positions per ball (004: 100).
    response : callable or None
        The steady orbit, as :func:`steady_deflection` takes it.

    Returns
    -------
    ndarray
        Immobile share [-] in [0, 1], one per speed.
    """
    b = system.balancer
    check_immobility(n_conf, b.n_balls, np.atleast_1d(speeds).size)
    alpha = configurations(n_conf, b.n_balls)
    out = np.empty(len(np.atleast_1d(speeds)))
    for j, w in enumerate(np.atleast_1d(speeds)):
        out[j] = immobile_mask(system, float(w), alpha, response).mean()
    return out

def stick_threshold_grade(system: System, speed: npt.ArrayLike, nominal_speed: float):
    """Residual grade G* [mm/s] below which every ball configuration at rest is immobile.

    From :func:`immobile_mask` (004 eq 1 against mu_s m R Omega^2): ball i sticks iff
    |Im(w e^{-i alpha_i})| <= mu_s R, and on the steady orbit |w| = A e with the residual
    eccentricity e = |U_t| / M_t [m] and the Jeffcott amplification A = M_t Omega^2 /
    |k - M_t Omega^2 + i c Omega| (textbook synchronous response,
    :func:`autobalance.physics.axis_response` per unit eccentricity).
    So every configuration sticks when A e <= mu_s R, i.e. below
    G* = 1e3 Omega_nom mu_s R / A  (ISO 1940 grade at Omega_nom, 004 sec. 4).
    Above G* only configurations whose balls lie nearly along w can stay at rest, so balls that
    relocate at speed Omega stop near G*. With in-plane gravity mu_s R is the limit of
    :func:`immobile_mask`, mu_s R - g sqrt(1 + mu_s^2) / Omega^2, and G* = 0 where that is <= 0
    (gravity alone moves the balls).

    Parameters
    ----------
    system : System
        Isotropic suspension k [N/m], c [N s/m]; total mass M_t [kg]; race radius R [m]; the
        balls' static friction mu_s [-] (the largest, if they differ).
    speed : array_like
        Spin speed Omega [rad/s].
    nominal_speed : float
        Omega_nom [rad/s] of the grade.

    Returns
    -------
    ndarray
        G* [mm/s], shape of ``speed``.
    """
    s, b = system.suspension, system.balancer
    if s.kx != s.ky or s.cx != s.cy:
        raise ValueError("stick_threshold_grade: needs an isotropic (Jeffcott) suspension")
    mt = system.total_mass
    amp, _ = axis_response(mt, s.kx, s.cx, mt, speed)      # |w| per metre of eccentricity
    mus = float(np.max(b.stiction))
    if system.gravity.g == 0.0:
        return 1e3 * nominal_speed * mus * b.race_radius / amp
    lim = _stick_limit(system, speed, np.array([mus]), b.race_radius)[..., 0]
    return 1e3 * nominal_speed * np.maximum(lim, 0.0) / amp
