"""Reference solution with scipy.integrate.solve_ivp on the same equations (tanh friction law).

Used to validate the exact stick-slip kernel against 004's regularised model and as the
baseline of the speed benchmark. The right-hand side is the compiled kernel `rhs` called from
Python with the friction law forced to 004's tanh law (F = mu N R tanh(alpha_dot / v_sat)).
"""
from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np
from scipy.integrate import solve_ivp

from ..models import InitialState, MotorDrive, SimOptions, SpeedProfile, System
from ..core.layout import P_FLAW, P_VSAT, n_q
from .pack import initial_vector, pack_params, spin_arrays
from ..core.rhs import profile_segment, rhs
from ..core.work import rhs_work

if TYPE_CHECKING:
    import numpy.typing as npt


def make_rhs(system: System, spin: SpeedProfile | MotorDrive, v_sat: float = 1e-6,
             normal_force: str = "ball"):
    """Return f(t, y) -> dy for solve_ivp (tanh law with saturation speed v_sat [rad/s]).

    The compiled kernel's right-hand side (core/rhs.py: 000 eq 2-4 / 004 eq 8-10) with 004's
    regularised friction F = mu N R tanh(alpha_dot / v_sat) forced.

    Parameters
    ----------
    system : System
        The machine.
    spin : SpeedProfile or MotorDrive
        The spin.
    v_sat : float
        Saturation speed of the tanh law [rad/s] (004: 1e-6 rad/s).
    normal_force : str
        "ball" or "drum" (:class:`~autobalance.models.SimOptions`).

    Returns
    -------
    callable
        f(t [s], y) -> dy/dt, y in the kernel's layout (u, v [m], alpha_1..N, psi [rad], then
        their rates [m/s], [rad/s]; :mod:`autobalance.core.layout`).
    """
    options = SimOptions(friction_law="tanh", v_sat=v_sat, normal_force=normal_force)
    P, B = pack_params(system, spin, options)
    P[P_FLAW], P[P_VSAT] = 1.0, v_sat
    N = system.balancer.n_balls
    nq = n_q(N)
    prof_t, prof_w, _ = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    stuck = np.zeros(N, dtype=np.int64)
    sgn = np.ones(N)
    spin_state = np.array([1.0 if isinstance(spin, MotorDrive) else 0.0, 0.0])
    rw = rhs_work(N)
    sched = (prof_t, prof_w, unb_t, unb_u)

    def f(t, y):
        dy = np.empty(2 * nq)
        seg = profile_segment(t, prof_t)
        rhs(t, np.ascontiguousarray(y), P, B, N, seg, sched, (stuck, sgn, spin_state), dy, rw)
        return dy

    return f


def solve_reference(system: System, spin: SpeedProfile | MotorDrive, t_end: float, *,
                    initial: InitialState | None = None, v_sat: float = 1e-6,
                    method: str = "Radau", rtol: float = 1e-6, atol: float = 1e-9,
                    t_eval: npt.ArrayLike | None = None, normal_force: str = "ball",
                    equations: str = "kernel"):
    """solve_ivp on the tanh-law equations from t = 0 to t_end [s].

    ``equations="kernel"`` uses the compiled right-hand side of `rhs.py`; ``"paper"`` the NumPy
    transcription of 004 eq (8)-(10) (`paper_004_rhs`). The state keeps the kernel's ball order
    (`sol.order` maps it to the user's order).

    Parameters
    ----------
    system : System
        The machine.
    spin : SpeedProfile or MotorDrive
        The spin (a prescribed profile for ``equations="paper"``).
    t_end : float
        End time [s].
    initial : InitialState or None
        The state at t = 0 (None: the default :class:`~autobalance.models.InitialState`).
    v_sat : float
        Saturation speed of the tanh law [rad/s].
    method : str
        solve_ivp method, e.g. "Radau", "LSODA", "RK45".
    rtol : float
        Relative tolerance [-].
    atol : float
        Absolute tolerance, applied to every state component in its own unit
        [m], [rad], [m/s], [rad/s].
    t_eval : array_like or None
        Output times [s] (None: the solver's steps).
    normal_force : str
        "ball" or "drum" (kernel equations only; the paper's are "ball" without gravity).
    equations : str
        "kernel" (:func:`make_rhs`) or "paper" (:func:`paper_004_rhs`).

    Returns
    -------
    scipy.integrate.OdeResult
        ``sol.t`` [s], ``sol.y`` (2*nq, n_t) in the kernel's layout (u, v [m], alpha_1..N,
        psi [rad], then their rates [m/s], [rad/s]), plus ``sol.order``.
    """
    y0, order = initial_vector(system, spin, initial or InitialState())
    if equations == "paper":
        f = paper_004_rhs(system, spin, v_sat)
    elif equations == "kernel":
        f = make_rhs(system, spin, v_sat, normal_force)
    else:
        raise ValueError(f"equations = {equations!r}: must be 'kernel' or 'paper'")
    sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)
    sol.order = order
    return sol




def paper_004_rhs(system: System, spin: SpeedProfile, v_sat: float = 1e-6):
    """f(t, y) transcribing 004 eq (8)-(10) literally in NumPy (Jeffcott rotor, isotropic k, c,
    point-mass balls, tanh friction F_f = mu F_n tanh(phi_dot / v_sat) with F_n = m R (psi_dot +
    phi_dot)^2, gravity omitted as in 004 sec. 3.1). Same state layout as the kernel.

    Independent of `rhs.py`: it is what a researcher would write from the paper, used as the
    scipy baseline of the benchmark and to check the kernel against the printed equations.

    Parameters
    ----------
    system : System
        Isotropic suspension k [N/m], c [N*s/m]; M_t [kg], U [kg*m]; balls m_i [kg] on R [m]
        with damping D_i [N*m*s/rad] and friction mu_i [-].
    spin : SpeedProfile
        The prescribed speed profile.
    v_sat : float
        Saturation speed of the tanh law [rad/s] (004: 1e-6 rad/s).

    Returns
    -------
    callable
        f(t [s], y) -> dy/dt in the kernel's layout (u, v [m], alpha_1..N, psi [rad], then their
        rates [m/s], [rad/s]; :mod:`autobalance.core.layout`).
    """
    b = system.balancer
    n = b.n_balls
    if system.suspension.kx != system.suspension.ky or system.suspension.cx != system.suspension.cy:
        raise ValueError("paper_004_rhs: 004's model has an isotropic suspension")
    Mt = system.total_mass
    Me = system.rotor.unbalance
    k, c = system.suspension.kx, system.suspension.cx
    m = b.masses
    R = b.race_radius
    D = np.asarray(b.damping, float)
    mu = np.asarray(b.rolling_resistance, float)
    tt, ww = spin.arrays()
    nq = n_q(n)

    def f(t, y):
        u, v = y[0], y[1]
        phi = y[2:2 + n]
        ud, vd = y[nq], y[nq + 1]
        phid = y[nq + 2:nq + 2 + n]
        kseg = min(np.searchsorted(tt, t, side="right") - 1, len(tt) - 2)
        psid = np.interp(t, tt, ww)
        psidd = (ww[kseg + 1] - ww[kseg]) / (tt[kseg + 1] - tt[kseg]) if t < tt[-1] else 0.0
        s, co = np.sin(phi), np.cos(phi)
        th = psid + phid
        Ff = mu * m * R * th**2 * np.tanh(phid / v_sat)
        # unknowns a = (u'', v'', phi''); rows = eq (8), (9), (10) moved to A a = rhs
        A = np.zeros((n + 2, n + 2))
        r = np.zeros(n + 2)
        A[0, 0] = Mt
        A[0, 2:] = -m * R * s
        r[0] = (Mt * psidd * v + 2 * Mt * psid * vd + Mt * psid**2 * u + Me * psid**2 - k * u
                - c * (ud - v * psid) + np.sum(m * R * s * psidd) + np.sum(m * R * th**2 * co))
        A[1, 1] = Mt
        A[1, 2:] = m * R * co
        r[1] = (-Mt * psidd * u - 2 * Mt * psid * ud + Mt * psid**2 * v - Me * psidd - k * v
                - c * (vd + u * psid) - np.sum(m * R * co * psidd) + np.sum(m * R * th**2 * s))
        for i in range(n):
            A[2 + i, 2 + i] = m[i] * R**2
            A[2 + i, 0] = -m[i] * R * s[i]
            A[2 + i, 1] = m[i] * R * co[i]
            r[2 + i] = (-m[i] * R * psidd * (u * co[i] + v * s[i])
                        - 2 * m[i] * R * psid * (ud * co[i] + vd * s[i])
                        + m[i] * R * psid**2 * (-u * s[i] + v * co[i]) - D[i] * phid[i]
                        - Ff[i] * R - m[i] * R**2 * psidd)
        a = np.linalg.solve(A, r)
        dy = np.empty(2 * nq)
        dy[:nq] = y[nq:]
        dy[nq - 1] = psid
        dy[nq:nq + 2] = a[:2]
        dy[nq + 2:nq + 2 + n] = a[2:]
        dy[2 * nq - 1] = psidd
        return dy

    return f


__all__ = ["make_rhs", "paper_004_rhs", "solve_reference"]
