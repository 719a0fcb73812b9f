"""Steady harmonic response of the rotor on its linear (anisotropic) suspension.

With the balls held fixed relative to the rotor, the drum equations 000 eq (2)-(3) are linear:

    M_t x'' + c_x x' + k_x x = U w^2 cos(w t),
    M_t y'' + c_y y' + k_y y = U w^2 sin(w t),

where U = M e [kg*m] is the static unbalance and M_t = M + sum(m_i) [kg] the translating mass
(the balls move with the drum centre; 004 eq (8)-(9) writes M_t). Their steady solution has the
form of 000 eq (6)-(7),

    x = a_x cos(w t - phi_x),      y = a_y sin(w t - phi_y),

with the textbook Jeffcott amplitude and phase lag for each axis,

    a   = U w^2 / sqrt((k - M_t w^2)^2 + (c w)^2),
    tan(phi) = c w / (k - M_t w^2),   phi in [0, pi].

Each ball of static moment m_i R at angle alpha_i adds the same transfer function rotated by
alpha_i (000 eq (6)-(7), the a_ix, a_iy terms). Dry friction and base excitation of the
:class:`~autobalance.models.Suspension` are nonlinear / not synchronous and are ignored here.

All functions are pure numpy; angular speeds are in [rad/s].
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from ..models._validate import array as _array

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

    from ..models import System

__all__ = ["displacement_from_acceleration", "steady_orbit_start", "dynamic_stiffness", "synchronous_orbit", 
    "BallInfluence", "HarmonicResponse", "axis_response", "ball_influence", "damped_peak_speeds",
    "damping_ratios", "harmonic_response", "natural_frequencies", "response_table",
    "steady_displacement",
]


# -- validation --------------------------------------------------------------------------------


def _out(a: np.ndarray):
    """Return a Python float for 0-d results, the array otherwise."""
    return float(a) if np.ndim(a) == 0 else a


# -- one axis ----------------------------------------------------------------------------------
def dynamic_stiffness(mass: float | npt.ArrayLike, k: float | npt.ArrayLike,
                      c: float | npt.ArrayLike, speed: float | npt.ArrayLike):
    """Complex dynamic stiffness k - M w^2 + i c w [N/m] of one suspension axis (Jeffcott rotor,
    000 eq 6-7, 004 eq 8-9): the one home of the denominator of every synchronous response.

    Parameters
    ----------
    mass : float or array_like
        Translating mass M (M_t with balls) [kg].
    k : float or array_like
        Stiffness [N/m].
    c : float or array_like
        Viscous damping [N*s/m].
    speed : float or array_like
        Spin speed w [rad/s].

    Returns
    -------
    complex or ndarray of complex
        k - M w^2 + i c w [N/m].
    """
    return k - mass * speed * speed + 1j * c * speed


def synchronous_orbit(system: System, speed: float | npt.ArrayLike,
                      unbalance: complex | npt.ArrayLike):
    """Complex amplitudes (X, Y) [m] of the steady synchronous orbit x = Re(X e^{i w t}),
    y = Re(Y e^{i w t}) of the rotor under the rotating unbalance W (000 eq 6-7 with the balls
    fixed; each axis a 1-DOF oscillator): X = w^2 W / D_x, Y = -i w^2 W / D_y with
    D = :func:`dynamic_stiffness`. For an isotropic suspension X is also the constant deflection
    in the rotor frame (004 eq 8-9 at constant speed).

    Parameters
    ----------
    system : autobalance.models.System
        Suspension kx, ky [N/m], cx, cy [N*s/m] and total mass M_t [kg].
    speed : float or array_like
        Spin speed w [rad/s].
    unbalance : complex or array_like of complex
        Resultant unbalance W in the rotor frame [kg*m]
        (:func:`autobalance.physics.unbalance.residual_unbalance`).

    Returns
    -------
    (X, Y) : complex or ndarray of complex
        [m], broadcast shape of ``speed`` and ``unbalance``.
    """
    s, mt = system.suspension, system.total_mass
    w = speed
    return (w * w * unbalance / dynamic_stiffness(mt, s.kx, s.cx, w),
            -1j * w * w * unbalance / dynamic_stiffness(mt, s.ky, s.cy, w))


def _transfer(mass, k, c, speed):
    """Gain w^2/|k - M w^2 + i c w| [m/(kg*m)] and phase lag [rad] (shared by U and m_i R)."""
    w = speed
    d = dynamic_stiffness(mass, k, c, w)
    re = np.real(d)
    im = np.abs(np.imag(d))
    den = np.hypot(re, im)
    with np.errstate(divide="ignore", invalid="ignore"):
        gain = np.where(w == 0.0, 0.0, w * w / den)
    phase = np.arctan2(im, re)
    # undamped exact resonance: infinite gain, phase lag pi/2 by continuity of the damped case
    phase = np.where((den == 0.0) & (w > 0.0), 0.5 * np.pi, phase)
    return gain, phase


def axis_response(mass: float, k: float, c: float, unbalance: float, speed: float | npt.ArrayLike):
    """Steady response of one suspension axis to the rotating unbalance force U w^2.

    Implements 000 eq (2) (or (3)) with the balls fixed and its solution in the form of
    000 eq (6)-(7): x = a cos(w t - phi), with the Jeffcott rotor closed form
    a = U w^2 / sqrt((k - M w^2)^2 + (c w)^2) and tan(phi) = c w / (k - M w^2).

    Parameters
    ----------
    mass : float
        Translating mass M (use M_t = M + sum(m_i) with balls) [kg], > 0.
    k : float
        Suspension stiffness along the axis [N/m], > 0.
    c : float
        Viscous damping along the axis [N*s/m], >= 0.
    unbalance : float
        Static unbalance U = M e (or a ball moment m_i R) [kg*m], >= 0.
    speed : float or array_like
        Spin speed w [rad/s], >= 0 (vectorised).

    Returns
    -------
    amplitude : float or ndarray
        Displacement amplitude a [m]; inf at an undamped (c = 0) exact resonance.
    phase : float or ndarray
        Phase lag phi of the displacement behind the force [rad], in [0, pi]
        (0 below resonance, pi/2 at w = sqrt(k/M), -> pi above).

    Raises
    ------
    ParameterError
        (a ValueError) naming the offending argument when it is out of range.
    """
    m = float(_array("mass", mass, strict=True))
    kk = float(_array("k", k, strict=True))
    cc = float(_array("c", c, strict=False))
    u = float(_array("unbalance", unbalance, strict=False))
    w = _array("speed", speed, strict=False)
    gain, phase = _transfer(m, kk, cc, w)
    return _out(u * gain), _out(phase)


# -- whole system ------------------------------------------------------------------------------
@dataclass(frozen=True)
class HarmonicResponse:
    """Steady unbalance response x = a_x cos(w t - phi_x), y = a_y sin(w t - phi_y) (000 eq 6-7).

    Attributes
    ----------
    speed : ndarray or float
        Spin speed w [rad/s].
    unbalance : float
        Static unbalance U [kg*m] that was applied.
    a_x, a_y : ndarray or float
        Amplitudes along x and y [m].
    phi_x, phi_y : ndarray or float
        Phase lags along x and y [rad], in [0, pi].
    """

    speed: np.ndarray | float
    unbalance: float
    a_x: np.ndarray | float
    a_y: np.ndarray | float
    phi_x: np.ndarray | float
    phi_y: np.ndarray | float

    def __getitem__(self, key: str):
        """Dict-style access, e.g. ``resp["a_x"]``."""
        return getattr(self, key)

    def as_dict(self) -> dict:
        """The six fields by name: speed [rad/s], unbalance [kg*m], a_x, a_y [m], phi_x, phi_y
        [rad] (arrays stay arrays)."""
        return {k: getattr(self, k) for k in ("speed", "unbalance", "a_x", "a_y", "phi_x", "phi_y")}


def harmonic_response(system: System, speed: float | npt.ArrayLike,
                      unbalance: float | None = None) -> HarmonicResponse:
    """Steady response of the drum to its static unbalance with the balls fixed.

    000 eq (2)-(3) without the ball terms, solved in the form of 000 eq (6)-(7) (a_ox, a_oy,
    phi_x, phi_y); the mass is M_t = ``system.total_mass`` because the balls translate with the
    drum centre (004 eq (8)-(9)).

    Parameters
    ----------
    system : autobalance.models.System
        Rotor, suspension (kx, ky [N/m], cx, cy [N*s/m]) and balancer (ball masses [kg]).
    speed : float or array_like
        Spin speed w [rad/s], >= 0.
    unbalance : float, optional
        Static unbalance U [kg*m]; default ``system.rotor.unbalance``.

    Returns
    -------
    HarmonicResponse
        a_x, a_y [m] and phi_x, phi_y [rad] (same shape as ``speed``).
    """
    u = system.rotor.unbalance if unbalance is None else float(_array("unbalance", unbalance, strict=False))
    w = _array("speed", speed, strict=False)
    s, mt = system.suspension, system.total_mass
    gx, px = _transfer(mt, s.kx, s.cx, w)
    gy, py = _transfer(mt, s.ky, s.cy, w)
    return HarmonicResponse(_out(w), float(u), _out(u * gx), _out(u * gy), _out(px), _out(py))


def natural_frequencies(system: System) -> tuple[float, float]:
    """Undamped natural frequencies w_x = sqrt(k_x/M_t), w_y = sqrt(k_y/M_t) [rad/s].

    Parameters
    ----------
    system : autobalance.models.System
        Stiffnesses [N/m] and total translating mass M_t [kg] (rotor plus balls).

    Returns
    -------
    (w_x, w_y) : tuple of float
        [rad/s]. 000: w_x != w_y (anisotropic washer suspension); 004: 94.2 Hz.
    """
    return system.natural_frequencies          # the one home: models/system.py


def damping_ratios(system: System) -> tuple[float, float]:
    """Damping ratios zeta = c / (2 sqrt(k M_t)) per axis [-].

    Parameters
    ----------
    system : autobalance.models.System
        cx, cy [N*s/m], kx, ky [N/m], M_t [kg].
    """
    mt, s = system.total_mass, system.suspension
    return s.cx / (2.0 * math.sqrt(s.kx * mt)), s.cy / (2.0 * math.sqrt(s.ky * mt))


def damped_peak_speeds(system: System) -> tuple[float, float]:
    """Spin speeds of maximum unbalance response amplitude per axis [rad/s].

    For the rotating-unbalance force U w^2 the amplitude a(w) above peaks at
    w_peak = w_n / sqrt(1 - 2 zeta^2) when zeta < 1/sqrt(2) (slightly above w_n); for heavier
    damping a(w) rises monotonically to U/M_t and there is no peak (returned as inf).

    Parameters
    ----------
    system : autobalance.models.System
        Suspension and masses, see :func:`natural_frequencies` and :func:`damping_ratios`.

    Returns
    -------
    (w_peak_x, w_peak_y) : tuple of float
        [rad/s]; ``math.inf`` where there is no finite peak.
    """
    out = []
    for wn, z in zip(natural_frequencies(system), damping_ratios(system)):
        q = 1.0 - 2.0 * z * z
        out.append(wn / math.sqrt(q) if q > 0.0 else math.inf)
    return out[0], out[1]


def _floats(a) -> list:
    """JSON-safe list: floats, None for non-finite values (undamped resonance)."""
    return [float(v) if math.isfinite(v) else None for v in np.atleast_1d(a).tolist()]


def response_table(system: System, speeds: npt.ArrayLike) -> dict:
    """Unbalance response over a speed grid as a JSON-serialisable dict (CLI ``response``).

    Parameters
    ----------
    system : autobalance.models.System
        The machine; U = ``system.rotor.unbalance`` [kg*m], M_t = ``system.total_mass`` [kg].
    speeds : array_like
        Spin speeds w [rad/s], >= 0.

    Returns
    -------
    dict
        "speed_rad_s", "amplitude_x_m", "amplitude_y_m", "phase_x_rad", "phase_y_rad" (lists of
        float, one per speed; amplitude None at an undamped exact resonance),
        "natural_frequencies_rad_s", "natural_frequencies_hz", "damping_ratios",
        "peak_speeds_rad_s" (None where there is no finite peak) - lists of two (x, y) - and
        "unbalance_kg_m", "total_mass_kg" (floats).
    """
    w = np.atleast_1d(_array("speeds", speeds, strict=False)).ravel()
    r = harmonic_response(system, w)
    wn = natural_frequencies(system)
    return {
        "speed_rad_s": _floats(w),
        "amplitude_x_m": _floats(r.a_x),
        "amplitude_y_m": _floats(r.a_y),
        "phase_x_rad": _floats(r.phi_x),
        "phase_y_rad": _floats(r.phi_y),
        "natural_frequencies_rad_s": [float(v) for v in wn],
        "natural_frequencies_hz": [float(v / (2.0 * math.pi)) for v in wn],
        "damping_ratios": [float(v) for v in damping_ratios(system)],
        "peak_speeds_rad_s": _floats(damped_peak_speeds(system)),
        "unbalance_kg_m": float(system.rotor.unbalance),
        "total_mass_kg": float(system.total_mass),
    }


# -- balls -------------------------------------------------------------------------------------
@dataclass(frozen=True)
class BallInfluence:
    """Drum response to the balls' static moments (000 eq (6)-(7), the a_ix, a_iy terms).

    Attributes
    ----------
    speed : ndarray or float
        Spin speed w [rad/s].
    gain_x, gain_y : ndarray or float
        Amplitude per unit static moment, w^2/|k - M_t w^2 + i c w| [m/(kg*m)].
    a_x, a_y : ndarray
        a_ix, a_iy = m_i R * gain for each ball [m], shape speed.shape + (N,).
    phi_x, phi_y : ndarray or float
        Phase lags [rad], the same as for the unbalance.
    """

    speed: np.ndarray | float
    gain_x: np.ndarray | float
    gain_y: np.ndarray | float
    a_x: np.ndarray
    a_y: np.ndarray
    phi_x: np.ndarray | float
    phi_y: np.ndarray | float

    def __getitem__(self, key: str):
        return getattr(self, key)


def ball_influence(system: System, speed: float | npt.ArrayLike) -> BallInfluence:
    """Amplitudes a_ix, a_iy that ball i (static moment m_i R) adds to the drum motion.

    000 eq (6)-(7): a ball at angle alpha_i acts as an unbalance m_i R rotated by alpha_i, so it
    sees the same transfer function as the static unbalance (same phases phi_x, phi_y).

    Parameters
    ----------
    system : autobalance.models.System
        Ball masses m_i [kg], race radius R [m], suspension and M_t [kg].
    speed : float or array_like
        Spin speed w [rad/s], >= 0.

    Returns
    -------
    BallInfluence
        Per-unit gains [m/(kg*m)], per-ball amplitudes [m] and phases [rad].
    """
    w = _array("speed", speed, strict=False)
    s, mt, b = system.suspension, system.total_mass, system.balancer
    gx, px = _transfer(mt, s.kx, s.cx, w)
    gy, py = _transfer(mt, s.ky, s.cy, w)
    moments = b.masses * b.race_radius if b.n_balls else np.zeros(0)
    ax = np.asarray(gx)[..., None] * moments
    ay = np.asarray(gy)[..., None] * moments
    return BallInfluence(_out(w), _out(gx), _out(gy), ax, ay, _out(px), _out(py))


def steady_displacement(system: System, speed: float, t: npt.ArrayLike,
                        ball_angles: Sequence[float] = ()):
    """Quasi-steady drum displacement of 000 eq (6)-(7) for fixed ball angles.

    x = a_ox cos(w t - phi_x) + sum_i a_ix cos(w t + alpha_i - phi_x),
    y = a_oy sin(w t - phi_y) + sum_i a_iy sin(w t + alpha_i - phi_y).

    Parameters
    ----------
    system : autobalance.models.System
        The machine (U [kg*m], m_i [kg], R [m], suspension, M_t [kg]).
    speed : float
        Constant spin speed w [rad/s], >= 0.
    t : array_like
        Times [s].
    ball_angles : sequence of float
        alpha_i relative to the unbalance [rad], one per ball (empty = balls ignored).

    Returns
    -------
    x, y : ndarray
        Displacements from static equilibrium [m], same shape as ``t``.
    """
    w = float(_array("speed", speed, strict=False))
    t = np.asarray(t, float)
    r = harmonic_response(system, w)
    wt = w * t
    x = r.a_x * np.cos(wt - r.phi_x)
    y = r.a_y * np.sin(wt - r.phi_y)
    alphas = np.asarray(ball_angles, float).ravel()
    if alphas.size:
        if alphas.size != system.balancer.n_balls:
            raise ParameterError("ball_angles", list(alphas),
                                 f"needs {system.balancer.n_balls} values, one per ball")
        bi = ball_influence(system, w)
        for a, aix, aiy in zip(alphas, bi.a_x, bi.a_y):
            x = x + aix * np.cos(wt + a - bi.phi_x)
            y = y + aiy * np.sin(wt + a - bi.phi_y)
    return x, y


def steady_orbit_start(system: System, w: float,
                       alpha: npt.ArrayLike) -> tuple[float, float, float, float]:
    """x, y [m] and vx, vy [m/s] at psi = 0 on the steady orbit of the rotor spinning at w
    [rad/s] with the balls fixed at alpha [rad] (000 eq 6-7; each axis a 1-DOF oscillator)::

        x = Re(Hx w^2 Ut e^{i w t}),  y = Re(-i Hy w^2 Ut e^{i w t}),
        H = 1 / (k - M_t w^2 + i c w),  Ut = U + sum m_i (R e^{i alpha_i} + rho e^{i beta}).

    The simulation starts here when ``InitialState.steady_state`` is set (000 Fig. 5: the drum
    already vibrates when the balls are released).

    Parameters
    ----------
    system : autobalance.models.System
        The machine: suspension kx, ky [N/m], cx, cy [N*s/m], M_t [kg], the balls and the
        rotor's unbalance at t = 0 (the first entry of its unbalance table) [kg*m].
    w : float
        Spin speed [rad/s].
    alpha : array_like
        Ball angles from the unbalance [rad], one per ball.

    Returns
    -------
    x, y : float
        Displacement from static equilibrium at spin angle psi = 0 [m].
    vx, vy : float
        Velocity there (inertial frame) [m/s].
    """
    from .unbalance import residual_unbalance

    ut = complex(residual_unbalance(system, np.asarray(alpha, float),
                                    system.rotor.unbalance_table()[1][0]))
    fx, fy = synchronous_orbit(system, w, ut)
    return fx.real, fy.real, (1j * w * fx).real, (1j * w * fy).real


def displacement_from_acceleration(acceleration: float | np.ndarray, n_rpm: float | np.ndarray):
    """Harmonic displacement amplitude A = a / w^2 [m] (000 p. 3, below Fig. 3: A = a_x / (pi n /
    30)^2).

    Parameters
    ----------
    acceleration : float or array
        Acceleration amplitude a [m/s^2].
    n_rpm : float or array
        Drum speed n [rpm].
    """
    return np.asarray(acceleration, float) / (np.asarray(n_rpm, float) * (2.0 * math.pi / 60.0)) ** 2
