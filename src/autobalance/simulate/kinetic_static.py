"""Kinetic-static model of the washer (000 eq 13) and its comparison with the full model (Fig. 9).

The drum follows 000 eq (2)-(3) (with the eccentricity terms of eq 34-35) at constant speed w,
driven by the balls' actual angles, rates and accelerations:

    M_t x'' + c_x x' + k_x x = w^2 Re(U e^{i w t}) + sum_i m_i R [(w + a_i')^2 cos(th_i) + a_i'' sin(th_i)]
                               + sum_i m_i rho w^2 cos(w t + beta),
    M_t y'' + c_y y' + k_y y = w^2 Im(U e^{i w t}) + sum_i m_i R [(w + a_i')^2 sin(th_i) - a_i'' cos(th_i)]
                               + sum_i m_i rho w^2 sin(w t + beta),      th_i = w t + a_i,

while the balls feel only the averaged vibratory force (eq 13, with eq 10 / 40 for F_i):

    I_eff,i a_i'' = R F_i(a_1..a_N) - D_i a_i' - R F_ir sign(a_i'),   F_ir = m_i R w^2 f/r (eq 20),

I_eff = m R^2 + I (R/r)^2 (000: m_z R^2), D_i = c_i m_i R^2. Gravity averages out (eq 51) and is
not in the model; ball-ball contacts are not modelled. A ball sticks when its rate crosses zero
and |F_i| <= F_ir, and breaks away when |F_i| > F_ir (Coulomb; stiction = kinetic).

The mass is M_t = M + sum(m_i) (the balls translate with the drum), as in the full model.
Integration: classical RK4 with a fixed step (default 1/200 of a revolution), compiled with
numba. Angles [rad], lengths [m], speeds [rad/s].
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numba as nb
import numpy as np

from ..models import ParameterError
from ..models._validate import finite as _finite
from ..physics.unbalance import residual_unbalance
from ..physics.vibratory import _angles, _speed, gain_phase

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = ["KineticStaticResult", "compare_with_full", "simulate_kinetic_static"]


@nb.njit(cache=True)
def _rhs(t, z, n, w, p, m, ieff, D, Fr, H_re, H_im, stuck, dz):
    # p: 0 Mt, 1 kx, 2 ky, 3 cx, 4 cy, 5 U, 6 R, 7 rho, 8 beta
    Mt, kx, ky, cx, cy, U, R, rho, beta = p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7], p[8]
    msum = 0.0
    Wr = U
    Wi = 0.0
    for j in range(n):
        a = z[4 + j]
        Wr += m[j] * R * math.cos(a)
        Wi += m[j] * R * math.sin(a)
        msum += m[j]
    Wr += msum * rho * math.cos(beta)
    Wi += msum * rho * math.sin(beta)
    fx = w * w * (U * math.cos(w * t) + msum * rho * math.cos(w * t + beta))
    fy = w * w * (U * math.sin(w * t) + msum * rho * math.sin(w * t + beta))
    for i in range(n):
        a = z[4 + i]
        ad = z[4 + n + i]
        # Im(e^{ia} conj(W) H)
        cr = math.cos(a) * Wr + math.sin(a) * Wi      # Re(e^{ia} conj W)
        ci = math.sin(a) * Wr - math.cos(a) * Wi      # Im(e^{ia} conj W)
        F = -0.5 * m[i] * w * w * (cr * H_im + ci * H_re) - m[i] * rho * w * w * math.sin(a - beta)
        if stuck[i]:
            add = 0.0
            dz[4 + i] = 0.0
        else:
            s = 1.0 if ad > 0 else (-1.0 if ad < 0 else (1.0 if F > 0 else -1.0))
            add = (R * F - D[i] * ad - R * Fr[i] * s) / ieff[i]
            dz[4 + i] = ad
        dz[4 + n + i] = add
        th = w * t + a
        fx += m[i] * R * ((w + ad) ** 2 * math.cos(th) + add * math.sin(th))
        fy += m[i] * R * ((w + ad) ** 2 * math.sin(th) - add * math.cos(th))
    dz[0] = z[2]
    dz[1] = z[3]
    dz[2] = (fx - cx * z[2] - kx * z[0]) / Mt
    dz[3] = (fy - cy * z[3] - ky * z[1]) / Mt


@nb.njit(cache=True)
def _force(z, n, w, p, m, i, H_re, H_im):
    U, R, rho, beta = p[5], p[6], p[7], p[8]
    Wr = U
    Wi = 0.0
    msum = 0.0
    for j in range(n):
        Wr += m[j] * R * math.cos(z[4 + j])
        Wi += m[j] * R * math.sin(z[4 + j])
        msum += m[j]
    Wr += msum * rho * math.cos(beta)
    Wi += msum * rho * math.sin(beta)
    a = z[4 + i]
    cr = math.cos(a) * Wr + math.sin(a) * Wi
    ci = math.sin(a) * Wr - math.cos(a) * Wi
    return -0.5 * m[i] * w * w * (cr * H_im + ci * H_re) - m[i] * rho * w * w * math.sin(a - beta)


@nb.njit(cache=True)
def _integrate(z0, n, w, p, m, ieff, D, Fr, H_re, H_im, dt, nsteps, every, out):
    z = z0.copy()
    k1 = np.empty_like(z)
    k2 = np.empty_like(z)
    k3 = np.empty_like(z)
    k4 = np.empty_like(z)
    tmp = np.empty_like(z)
    stuck = np.zeros(n, np.bool_)
    out[0, :] = z
    row = 1
    t = 0.0
    for step in range(nsteps):
        _rhs(t, z, n, w, p, m, ieff, D, Fr, H_re, H_im, stuck, k1)
        for q in range(z.size):
            tmp[q] = z[q] + 0.5 * dt * k1[q]
        _rhs(t + 0.5 * dt, tmp, n, w, p, m, ieff, D, Fr, H_re, H_im, stuck, k2)
        for q in range(z.size):
            tmp[q] = z[q] + 0.5 * dt * k2[q]
        _rhs(t + 0.5 * dt, tmp, n, w, p, m, ieff, D, Fr, H_re, H_im, stuck, k3)
        for q in range(z.size):
            tmp[q] = z[q] + dt * k3[q]
        _rhs(t + dt, tmp, n, w, p, m, ieff, D, Fr, H_re, H_im, stuck, k4)
        old = z.copy()
        for q in range(z.size):
            z[q] += dt / 6.0 * (k1[q] + 2 * k2[q] + 2 * k3[q] + k4[q])
        t = (step + 1) * dt
        for i in range(n):
            F = _force(z, n, w, p, m, i, H_re, H_im)
            if stuck[i]:
                if abs(F) > Fr[i]:
                    stuck[i] = False
            elif Fr[i] > 0 and abs(F) <= Fr[i]:
                # rate crossed zero, or is smaller than what the net friction removes in one step
                # (RK4 stages straddling the sign change would otherwise creep)
                vmin = p[6] * (Fr[i] - abs(F)) * dt / ieff[i]
                if old[4 + n + i] * z[4 + n + i] <= 0.0 or abs(z[4 + n + i]) < vmin:
                    stuck[i] = True
                    z[4 + n + i] = 0.0
        if (step + 1) % every == 0 and row < out.shape[0]:
            out[row, :] = z
            row += 1
    return row


@dataclass(frozen=True)
class KineticStaticResult:
    """Time histories of the kinetic-static model.

    Attributes
    ----------
    t : ndarray
        Times [s].
    x, y : ndarray
        Drum displacement [m] (inertial frame).
    alpha, alpha_dot : ndarray (n_t, N)
        Ball angles [rad] and rates [rad/s] relative to the drum.
    residual_unbalance : ndarray
        |W(t)| [kg*m].
    """

    t: np.ndarray
    x: np.ndarray
    y: np.ndarray
    alpha: np.ndarray
    alpha_dot: np.ndarray
    residual_unbalance: np.ndarray


def simulate_kinetic_static(system: System, speed: float, ball_angles: npt.ArrayLike,
                            duration: float, f_r: float | None = None,
                            drum_state: npt.ArrayLike | None = None,
                            steps_per_rev: int = 200, save_every: int = 10) -> KineticStaticResult:
    """Integrate the kinetic-static model (000 eq 13 with the drum by eq 2-3, 34-35).

    Parameters
    ----------
    system : autobalance.models.System
        The machine (gravity ignored: it averages out, 000 eq 51).
    speed : float
        Constant spin speed w [rad/s], > 0.
    ball_angles : array_like (N,)
        alpha_i(0) [rad]; the balls start at rest relative to the drum.
    duration : float
        Simulated time [s], > 0.
    f_r : float, optional
        f/r [-] (eq 20); default the balancer's rolling_resistance of ball 0.
    drum_state : array_like (4,), optional
        x, y [m], vx, vy [m/s] at t = 0; default the harmonic orbit for the initial ball angles
        (000 eq 6-7), as the full model's ``steady_state`` start.
    steps_per_rev : int
        RK4 steps per revolution (>= 20).
    save_every : int
        Store every k-th step (>= 1).

    Returns
    -------
    KineticStaticResult
    """
    from .pack import steady_orbit_start

    w = _speed(speed)
    a0 = _angles(system, ball_angles)
    dur = _finite("duration", duration)
    if dur <= 0:
        raise ParameterError("duration", duration, "must be > 0 [s]")
    if int(steps_per_rev) != steps_per_rev or steps_per_rev < 20:
        raise ParameterError("steps_per_rev", steps_per_rev, "must be an integer >= 20")
    if int(save_every) != save_every or save_every < 1:
        raise ParameterError("save_every", save_every, "must be an integer >= 1")
    b = system.balancer
    n = b.n_balls
    fr = (b.rolling_resistance[0] if n else 0.0) if f_r is None else _finite("f_r", f_r)
    if fr < 0:
        raise ParameterError("f_r", f_r, "must be >= 0")
    s = system.suspension
    p = np.array([system.total_mass, s.kx, s.ky, s.cx, s.cy, system.rotor.unbalance,
                  b.race_radius, b.eccentricity, b.eccentricity_angle])
    m = b.masses
    R = b.race_radius
    ieff = m * R * R + b.inertias * (R / b.ball_radius) ** 2
    D = np.asarray(b.damping, float)
    Fr = m * R * w * w * fr
    gx, px, gy, py = gain_phase(system, w)
    H = gx * np.exp(1j * px) + gy * np.exp(1j * py)
    if drum_state is None:
        drum = np.asarray(steady_orbit_start(system, w, a0), float)
    else:
        drum = np.asarray(drum_state, float)
        if drum.shape != (4,) or not np.all(np.isfinite(drum)):
            raise ParameterError("drum_state", drum.tolist(), "needs 4 finite values x, y, vx, vy")
    z0 = np.concatenate([drum, a0, np.zeros(n)])
    dt = 2 * math.pi / w / steps_per_rev
    nsteps = int(math.ceil(dur / dt))
    nout = nsteps // save_every + 1
    out = np.zeros((nout, z0.size))
    rows = _integrate(z0, n, w, p, m, ieff, D, Fr, H.real, H.imag, dt, nsteps, int(save_every), out)
    out = out[:rows]
    t = np.arange(rows) * dt * save_every
    al = out[:, 4:4 + n]
    W = residual_unbalance(system, al)
    return KineticStaticResult(t, out[:, 0], out[:, 1], al, out[:, 4 + n:], np.abs(W))


def compare_with_full(system: System, speed: float, ball_angles: npt.ArrayLike,
                      duration: float = 6.0, steps_per_rev: int = 200) -> dict:
    """Differences between the full model and the kinetic-static model (000 Fig. 9).

    Both start from the same state (balls at rest at ``ball_angles``, drum on its harmonic orbit)
    and use the same parameters; the full model is :func:`autobalance.simulate.simulate` with
    normal_force = "drum" (000 eq 20). D_x = x - x_k, D_y = y - y_k, D_alpha = alpha - alpha_k.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (use g = 0 for a like-for-like comparison: the KS model has no gravity).
    speed : float
        w [rad/s], > 0.
    ball_angles : array_like (N,)
        Initial ball angles [rad].
    duration : float
        [s], > 0.
    steps_per_rev : int
        RK4 steps per revolution of the kinetic-static model.

    Returns
    -------
    dict
        "t_s", "D_x_m", "D_y_m", "D_alpha_rad" (n_t, N) arrays; "max_D_x_m", "max_D_y_m",
        "max_D_alpha_rad" over the run; "final_D_x_m", "final_D_y_m", "final_D_alpha_rad" (max
        over the last second); plus "ks" and "full" histories of alpha.
    """
    from ..models import InitialState, SimOptions, SpeedProfile
    from . import simulate

    w = _speed(speed)
    a0 = _angles(system, ball_angles)
    save_every = max(1, steps_per_rev // 20)
    ks = simulate_kinetic_static(system, w, a0, duration, steps_per_rev=steps_per_rev,
                                 save_every=save_every)
    dt_save = ks.t[1] - ks.t[0]
    sim = simulate(system, SpeedProfile.constant(w, float(duration)),
                   initial=InitialState(ball_angles=tuple(a0), steady_state=True),
                   options=SimOptions(normal_force="drum", save_dt=dt_save, rtol=1e-9))
    t = ks.t[ks.t <= sim.t[-1]]
    fx = np.interp(t, sim.t, sim.x)
    fy = np.interp(t, sim.t, sim.y)
    fa = np.stack([np.interp(t, sim.t, np.unwrap(sim.alpha[:, i])) for i in range(a0.size)], axis=1)
    ka = ks.alpha[:t.size]
    dal = np.angle(np.exp(1j * (fa - ka)))
    Dx, Dy = fx - ks.x[:t.size], fy - ks.y[:t.size]
    last = t >= t[-1] - 1.0
    return {"t_s": t, "D_x_m": Dx, "D_y_m": Dy, "D_alpha_rad": dal,
            "max_D_x_m": float(np.abs(Dx).max()), "max_D_y_m": float(np.abs(Dy).max()),
            "max_D_alpha_rad": float(np.abs(dal).max()),
            "final_D_x_m": float(np.abs(Dx[last]).max()), "final_D_y_m": float(np.abs(Dy[last]).max()),
            "final_D_alpha_rad": float(np.abs(dal[last]).max()),
            "ks_alpha_rad": ka, "full_alpha_rad": fa}
