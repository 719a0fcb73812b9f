"""Reference solution with scipy.integrate.solve_ivp on the same equations (tanh friction law).

Used to validate the exact stick-slip kernel against 004's regularised model and as the
baseline of the speed benchmark. The right-hand side is the compiled kernel `rhs` called from
Python with the friction law forced to 004's tanh law (F = mu N R tanh(alpha_dot / v_sat)).
"""
from __future__ import annotations

import numpy as np
from scipy.integrate import solve_ivp

from ..models import InitialState, MotorDrive, SimOptions, SpeedProfile, System
from .layout import N_S, P_FLAW, P_VSAT
from .pack import initial_vector, pack_params, spin_arrays
from .rhs import profile_segment, rhs


def make_rhs(system: System, spin: SpeedProfile | MotorDrive, v_sat: float = 1e-6,
             normal_force: str = "ball"):
    """Return f(t, y) -> dy for solve_ivp (tanh law with saturation speed v_sat [rad/s])."""
    options = SimOptions(friction_law="tanh", v_sat=v_sat, normal_force=normal_force)
    P, B = pack_params(system, spin, options)
    P[P_FLAW], P[P_VSAT] = 1.0, v_sat
    N = system.balancer.n_balls
    nq = N + 3
    prof_t, prof_w, _ = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    stuck = np.zeros(N, dtype=np.int64)
    sgn = np.ones(N)
    spin_state = np.array([1.0 if isinstance(spin, MotorDrive) else 0.0, 0.0])
    lam = np.zeros(3 * N + 1)
    Mm, A = np.zeros((nq, nq)), np.zeros((nq, nq))
    fv, bb = np.zeros(nq), np.zeros(nq)
    idx = np.zeros(nq, dtype=np.int64)

    def f(t, y):
        dy = np.empty(2 * nq)
        seg = profile_segment(t, prof_t)
        rhs(t, np.ascontiguousarray(y), P, B, N, seg, prof_t, prof_w, unb_t, unb_u, stuck, sgn,
            spin_state, dy, lam, Mm, fv, A, bb, idx)
        return dy

    return f


def solve_reference(system: System, spin: SpeedProfile | MotorDrive, t_end: float, *,
                    initial: InitialState | None = None, v_sat: float = 1e-6,
                    method: str = "Radau", rtol: float = 1e-6, atol: float = 1e-9,
                    t_eval=None, normal_force: str = "ball"):
    """solve_ivp on the tanh-law equations from t = 0 to t_end [s]; returns the OdeResult with
    y re-ordered so that balls follow the user's order (like `simulate`)."""
    y0, order = initial_vector(system, spin, initial or InitialState())
    f = make_rhs(system, spin, v_sat, normal_force)
    sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, t_eval=t_eval)
    sol.order = order
    return sol


__all__ = ["make_rhs", "solve_reference", "N_S"]
