"""Harmonic drum response to each source and the vibratory forces on the balls (seed 000).

While the balls move slowly relative to the drum, the drum of 000 eq (2)-(3) (and (34)-(35) with
a race eccentricity) vibrates harmonically, 000 eq (6)-(7) and (37)-(38):

    x = a_0x cos(w t - phi_x) + sum_i a_ix cos(w t + alpha_i - phi_x) + a_rho_x cos(w t + beta - phi_x),
    y = a_0y sin(w t - phi_y) + sum_i a_iy sin(w t + alpha_i - phi_y) + a_rho_y sin(w t + beta - phi_y).

Each source of static moment S_k (the unbalance U = Me at 0, ball i with m_i R at alpha_i, the
displaced ball masses sum(m_i) rho at beta) has the amplitudes a_k = S_k g(w) with the axis gain
g = w^2 / |k - M_t w^2 + i c w| and the phase lag phi of the axis (``response.py``). The mass is
M_t = M + sum(m_i): the balls translate with the drum (our choice, docs/washer-analysis.md; 000
writes M).

The vibratory force on ball i is the one-period average of its tangential inertial force, 000
eq (5), (8) and (39)-(42):

    F_i = F_ix + F_iy + F_irho,
    F_ix = -1/2 m_i w^2 sum_k a_xk sin(alpha_i - theta_k + phi_x),   (theta_k: angle of source k)
    F_iy = -1/2 m_i w^2 sum_k a_yk sin(alpha_i - theta_k + phi_y),
    F_irho = -m_i rho w^2 sin(alpha_i - beta).

In complex form, with the total rotor-frame unbalance W = U + sum_j m_j R e^{i alpha_j} +
sum_j m_j rho e^{i beta} and H = g_x e^{i phi_x} + g_y e^{i phi_y}:

    F_i = -1/2 m_i w^2 Im(e^{i alpha_i} conj(W) H) - m_i rho w^2 sin(alpha_i - beta).

F_i > 0 pushes ball i towards increasing alpha_i (the sense of rotation). Everything here is a
pure numpy function of SI floats/arrays; angles in [rad], speeds in [rad/s].
"""
from __future__ import annotations

from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from ..models._validate import array as _array
from ..models._validate import finite as _finite
from .response import _transfer
from .unbalance import residual_unbalance

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = [
    "DrumResponse", "SPEED_REGIMES", "drum_response", "force_extreme_ratio", "force_jacobian",
    "gain_phase", "single_ball_force", "speed_regime", "vibratory_components", "vibratory_forces",
]

#: Names of the three speed ranges of 000 Fig. 6-7 (relative to the two suspension frequencies).
SPEED_REGIMES = ("below", "between", "above")


# -- helpers -----------------------------------------------------------------------------------
def _speed(speed) -> float:
    w = _finite("speed", speed)
    if w <= 0.0:
        raise ParameterError("speed", speed, "must be > 0 [rad/s]")
    return w


def _angles(system, ball_angles) -> np.ndarray:
    """alpha as an array (..., N); ParameterError if the last axis is not N or not finite."""
    n = system.balancer.n_balls
    try:
        a = np.asarray(ball_angles, dtype=float)
    except (TypeError, ValueError):
        raise ParameterError("ball_angles", ball_angles, "must be real numbers [rad]") from None
    if a.ndim == 0 or a.shape[-1] != n:
        raise ParameterError("ball_angles", np.asarray(ball_angles).tolist(),
                             f"needs {n} values (one per ball) on the last axis")
    if not np.all(np.isfinite(a)):
        raise ParameterError("ball_angles", a.tolist(), "must be finite [rad]")
    return a


def gain_phase(system: System, speed: float | npt.ArrayLike):
    """Axis gains and phase lags of the drum at spin speed w (000 eq 6-7).

    Parameters
    ----------
    system : autobalance.models.System
        kx, ky [N/m], cx, cy [N*s/m] and the translating mass M_t [kg].
    speed : float or array_like
        Spin speed w [rad/s], >= 0.

    Returns
    -------
    g_x, phi_x, g_y, phi_y : float or ndarray
        Gains w^2/|k - M_t w^2 + i c w| [m/(kg*m)] and phase lags [rad] in [0, pi].
    """
    w = _array("speed", speed, strict=False)
    s, mt = system.suspension, system.total_mass
    gx, px = _transfer(mt, s.kx, s.cx, w)
    gy, py = _transfer(mt, s.ky, s.cy, w)
    out = [gx, px, gy, py]
    return tuple(float(v) if np.ndim(v) == 0 else v for v in out)


def _H(system, w: float) -> complex:
    gx, px, gy, py = gain_phase(system, w)
    return gx * np.exp(1j * px) + gy * np.exp(1j * py)


# -- drum response -----------------------------------------------------------------------------
@dataclass(frozen=True)
class DrumResponse:
    """Harmonic drum response split by source (000 eq 6-7, 37-38).

    Attributes
    ----------
    speed : float
        Spin speed w [rad/s].
    a_0x, a_0y : float
        Amplitudes from the static unbalance Me [m].
    a_ix, a_iy : ndarray (N,)
        Amplitudes from each ball's static moment m_i R [m].
    a_rho_x, a_rho_y : float
        Amplitudes from the ball masses displaced by the race eccentricity, sum(m_i) rho [m].
    phi_x, phi_y : float
        Phase lags of the axes [rad].
    amplitude_x, amplitude_y : float
        Amplitudes of the total motion x(t), y(t) for these ball angles [m].
    residual_unbalance : complex
        Total rotor-frame unbalance W [kg*m] (000 eq 22, 47).
    """

    speed: float
    a_0x: float
    a_0y: float
    a_ix: np.ndarray
    a_iy: np.ndarray
    a_rho_x: float
    a_rho_y: float
    phi_x: float
    phi_y: float
    amplitude_x: float
    amplitude_y: float
    residual_unbalance: complex

    def as_dict(self) -> dict:
        """JSON-ready dict with unit-suffixed keys (SI)."""
        return {
            "speed_rad_s": self.speed, "a_0x_m": self.a_0x, "a_0y_m": self.a_0y,
            "a_ix_m": [float(v) for v in self.a_ix], "a_iy_m": [float(v) for v in self.a_iy],
            "a_rho_x_m": self.a_rho_x, "a_rho_y_m": self.a_rho_y,
            "phi_x_rad": self.phi_x, "phi_y_rad": self.phi_y,
            "amplitude_x_m": self.amplitude_x, "amplitude_y_m": self.amplitude_y,
            "residual_unbalance_kg_m": abs(self.residual_unbalance),
            "residual_unbalance_angle_rad": float(np.angle(self.residual_unbalance)),
        }


def drum_response(system: System, speed: float, ball_angles: npt.ArrayLike) -> DrumResponse:
    """Harmonic response of the drum to the unbalance, each ball and the race eccentricity.

    000 eq (6)-(7) (and (37)-(38) with the eccentricity rho, beta of the balancer): every source
    of static moment S at angle theta adds S g cos(w t + theta - phi_x) to x and
    S g sin(w t + theta - phi_y) to y.

    Parameters
    ----------
    system : autobalance.models.System
        U = Me [kg*m], M_t [kg], kx, ky [N/m], cx, cy [N*s/m], ball masses m_i [kg], R [m],
        rho [m], beta [rad].
    speed : float
        Spin speed w [rad/s], > 0.
    ball_angles : array_like (N,)
        alpha_i relative to the unbalance [rad].

    Returns
    -------
    DrumResponse
    """
    w = _speed(speed)
    a = _angles(system, ball_angles)
    if a.ndim != 1:
        raise ParameterError("ball_angles", a.tolist(), "one configuration (N,) only")
    b = system.balancer
    gx, px, gy, py = gain_phase(system, w)
    mR = b.masses * b.race_radius if b.n_balls else np.zeros(0)
    srho = b.total_mass * b.eccentricity
    W = complex(residual_unbalance(system, a))
    U = system.rotor.unbalance
    return DrumResponse(w, U * gx, U * gy, mR * gx, mR * gy, srho * gx, srho * gy, px, py,
                        abs(W) * gx, abs(W) * gy, W)


# -- vibratory forces --------------------------------------------------------------------------
def vibratory_components(system: System, speed: float, ball_angles: npt.ArrayLike) -> dict:
    """Vibratory force on each ball split by axis and by source (000 eq 9-10, 40-42).

    Parameters
    ----------
    system : autobalance.models.System
        See :func:`drum_response`.
    speed : float
        Spin speed w [rad/s], > 0.
    ball_angles : array_like (..., N)
        alpha_i [rad]; leading axes are configurations (vectorised).

    Returns
    -------
    dict of ndarray (..., N) [N]
        "F_x", "F_y" (000 eq 9, 41), "F_rho" (eq 42), "F" = their sum (eq 40), and by source
        (eq 10): "F_x0", "F_y0" (unbalance), "F_xball", "F_yball" (sum over the balls j,
        including j = i), "F_xrho", "F_yrho" (ball masses displaced by rho).
    """
    w = _speed(speed)
    a = _angles(system, ball_angles)
    b = system.balancer
    gx, px, gy, py = gain_phase(system, w)
    m = b.masses
    U = system.rotor.unbalance
    ai = a[..., :, None]                      # ball i
    aj = a[..., None, :]                      # source ball j
    mR = m * b.race_radius
    rho, beta = b.eccentricity, b.eccentricity_angle
    srho = m.sum() * rho
    pref = -0.5 * m * w * w
    out = {}
    for ax, g, p in (("x", gx, px), ("y", gy, py)):
        f0 = pref * U * g * np.sin(a + p)
        fb = pref * g * (mR * np.sin(ai - aj + p)).sum(axis=-1)
        fr = pref * srho * g * np.sin(a - beta + p)
        out[f"F_{ax}0"], out[f"F_{ax}ball"], out[f"F_{ax}rho"] = f0, fb, fr
        out[f"F_{ax}"] = f0 + fb + fr
    out["F_rho"] = -m * rho * w * w * np.sin(a - beta)
    out["F"] = out["F_x"] + out["F_y"] + out["F_rho"]
    return out


def vibratory_forces(system: System, speed: float, ball_angles: npt.ArrayLike) -> np.ndarray:
    """Vibratory forces F_i(alpha_1..alpha_N) on the balls [N] (000 eq 8, 10-11, 39-43).

    F_i = -1/2 m_i w^2 Im(e^{i alpha_i} conj(W) H) - m_i rho w^2 sin(alpha_i - beta), with W the
    total unbalance and H = g_x e^{i phi_x} + g_y e^{i phi_y} (module docstring); identical to
    the sum of :func:`vibratory_components`.

    Parameters
    ----------
    system : autobalance.models.System
        See :func:`drum_response`.
    speed : float
        Spin speed w [rad/s], > 0.
    ball_angles : array_like (..., N)
        alpha_i [rad] (vectorised over leading axes).

    Returns
    -------
    ndarray (..., N)
        Tangential force on each ball, positive towards increasing alpha [N].
    """
    w = _speed(speed)
    a = _angles(system, ball_angles)
    b = system.balancer
    W = residual_unbalance(system, a)[..., None]
    H = _H(system, w)
    m = b.masses
    return (-0.5 * m * w * w * np.imag(np.exp(1j * a) * np.conj(W) * H)
            - m * b.eccentricity * w * w * np.sin(a - b.eccentricity_angle))


def force_jacobian(system: System, speed: float, ball_angles: npt.ArrayLike) -> np.ndarray:
    """Derivatives dF_i/d alpha_j of the vibratory forces [N/rad] (000 eq 12, 52).

    From F_i above: dF_i/dalpha_j = -1/2 m_i w^2 [delta_ij Re(e^{i alpha_i} conj(W) H)
    + m_j R Re(e^{i(alpha_i - alpha_j)} H)] - delta_ij m_i rho w^2 cos(alpha_i - beta).
    For one ball at alpha = pi with mR = Me this is 000 eq (12).

    Parameters
    ----------
    system : autobalance.models.System
        See :func:`drum_response`.
    speed : float
        Spin speed w [rad/s], > 0.
    ball_angles : array_like (..., N)
        alpha_i [rad].

    Returns
    -------
    ndarray (..., N, N)
        J[i, j] = dF_i/d alpha_j [N/rad].
    """
    w = _speed(speed)
    a = _angles(system, ball_angles)
    b = system.balancer
    n = b.n_balls
    m = b.masses
    W = residual_unbalance(system, a)
    H = _H(system, w)
    ai = a[..., :, None]
    aj = a[..., None, :]
    J = 0.5 * (m * w * w)[:, None] * (m * b.race_radius)[None, :] * np.real(np.exp(1j * (ai - aj)) * H)
    diag = (-0.5 * m * w * w * np.real(np.exp(1j * a) * np.conj(W)[..., None] * H)
            - m * b.eccentricity * w * w * np.cos(a - b.eccentricity_angle))
    idx = np.arange(n)
    J[..., idx, idx] += diag
    return J


def single_ball_force(system: System, speed: float, alphas: npt.ArrayLike,
                      static_moment: float | None = None, damping_scale: float = 1.0) -> dict:
    """Normalised vibratory force on one ball, F/(m R w^2), versus its angle (000 eq 11, Fig. 6-7).

    One ball of static moment S = m R (default S = Me, as in 000 Fig. 6) on the drum of
    ``system``; no eccentricity. From 000 eq (11), with a = S g and a_0 = Me g:

        F_1 = -1/2 m w^2 [a_0x sin(alpha + phi_x) + a_x sin(phi_x) + a_0y sin(alpha + phi_y)
              + a_y sin(phi_y)].

    Parameters
    ----------
    system : autobalance.models.System
        Drum (U [kg*m], M_t [kg], suspension); R [m] of its balancer (or 1 m without balls).
    speed : float
        Spin speed w [rad/s], > 0.
    alphas : array_like
        Ball angles [rad] at which to evaluate.
    static_moment : float, optional
        S = m R [kg*m] of the ball; default the unbalance Me.
    damping_scale : float
        Factor applied to cx and cy [-] (000 Fig. 7: different damping), > 0.

    Returns
    -------
    dict of ndarray
        "alpha_rad", "Fx_norm", "Fy_norm", "F_norm" (all F/(m R w^2) [-]).
    """
    import dataclasses

    w = _speed(speed)
    ds = _finite("damping_scale", damping_scale)
    if ds <= 0:
        raise ParameterError("damping_scale", damping_scale, "must be > 0")
    U = system.rotor.unbalance
    S = U if static_moment is None else _finite("static_moment", static_moment)
    if S <= 0:
        raise ParameterError("static_moment", static_moment, "must be > 0 [kg*m]")
    alphas = np.asarray(alphas, float)
    sus = dataclasses.replace(system.suspension, cx=system.suspension.cx * ds,
                              cy=system.suspension.cy * ds)
    sys2 = dataclasses.replace(system, suspension=sus)
    gx, px, gy, py = gain_phase(sys2, w)
    R = system.balancer.race_radius or 1.0
    # F/(m w^2) = -1/2 [...]; divide by R for F/(m R w^2)
    fx = -0.5 * (U * gx * np.sin(alphas + px) + S * gx * np.sin(px)) / R
    fy = -0.5 * (U * gy * np.sin(alphas + py) + S * gy * np.sin(py)) / R
    return {"alpha_rad": alphas, "Fx_norm": fx, "Fy_norm": fy, "F_norm": fx + fy}


def force_extreme_ratio(system: System, speeds: npt.ArrayLike, n_alpha: int = 721) -> np.ndarray:
    """Ratio of the negative to the positive extreme of the one-ball vibratory force, 000 Fig. 6.

    -min F_1 / max F_1 over the ball angle, F_1 of 000 eq (11) (:func:`single_ball_force`, one
    ball with mR = Me): about 1 far above both natural frequencies (Fig. 6a), larger between them
    (Fig. 6b: "the negative extreme is 2.5 times higher than the positive").

    Parameters
    ----------
    system : autobalance.models.System
        Drum and suspension.
    speeds : array_like
        Spin speeds w [rad/s], > 0.
    n_alpha : int
        Points of the angle grid over [0, 2 pi].

    Returns
    -------
    ndarray
        The ratio [-] per speed; inf where the force has no positive part.
    """
    w = np.atleast_1d(np.asarray(speeds, float))
    al = np.linspace(0.0, 2 * np.pi, int(n_alpha))
    out = np.empty(w.shape)
    for k, wk in enumerate(w):
        F = single_ball_force(system, wk, al)["F_norm"]
        out[k] = -F.min() / F.max() if F.max() > 0 else np.inf
    return out


def speed_regime(system: System, speed: float) -> str:
    """Which of the three speed ranges of 000 Fig. 6-7 the speed lies in.

    Parameters
    ----------
    system : autobalance.models.System
        Suspension and M_t; natural frequencies w_x = sqrt(kx/M_t), w_y = sqrt(ky/M_t) [rad/s].
    speed : float
        Spin speed w [rad/s], > 0.

    Returns
    -------
    str
        "below" (w < min), "between" (min <= w <= max) or "above" (w > max).
    """
    w = _speed(speed)
    wx, wy = system.natural_frequencies
    lo, hi = min(wx, wy), max(wx, wy)
    return "below" if w < lo else ("above" if w > hi else "between")
