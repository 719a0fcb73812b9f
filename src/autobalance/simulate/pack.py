"""Strip units/objects into the flat float arrays of the kernels (layout.py), and back."""
from __future__ import annotations

import functools
import math
from typing import NamedTuple

import numpy as np

from ..core.layout import N_S, alpha_dot_slice, alpha_slice, n_q, psi_index, speed_index
from ..limits import check_memory
from ..models import InitialState, MotorDrive, SimOptions, SpeedProfile, System
from ..physics.response import steady_orbit_start
from ..core.layout import (B_CC, B_D, B_I, B_KC, B_M, B_MU, B_MUS, B_RR, N_B, N_P, P_BAX, P_BAY,
                     P_BETA, P_ETD, P_BPX, P_BPY, P_BW, P_BZ, P_CPHI, P_CX, P_CY, P_DELTA, P_FDRY,
                     P_FLAW, P_G, P_GDIR, P_GDRY, P_HC, P_HOLDS, P_ISO, P_SYM, P_KX, P_KY, P_LAW, P_MROT, P_MT, P_NMODEL,
                     P_R, P_RAMPS, P_RHO, P_SPIN, P_T0, P_VDRY, P_VSAT, P_WF, P_WHOLD, P_WNOM)

LAW_ID = {"constant": 0.0, "linear": 1.0, "harmonic": 2.0}
#: options.friction_law -> core.layout.P_FLAW
FRICTION_LAW_ID = {"stick": 0.0, "tanh": 1.0, "creep": 2.0}


@functools.lru_cache(maxsize=64)
def contact_step(zeta: float) -> float:
    """The largest DOPRI5 step while two balls touch, times their contact frequency w_c [-]:
    two thirds of the largest |h lambda| on the ray of the contact's modes lambda = w_c (-zeta
    +- i sqrt(1 - zeta^2)) for which DOPRI5 is stable, |R(h lambda)| <= 1 with its stability
    function R(z) = sum_{k<=5} z^k / k! + z^6 / 600 (Hairer & Wanner, *Solving ODEs II*, IV.2;
    the same as 1 + z b^T (I - z A)^-1 1 of the tableau in core/integrate.py), and at least 1.

    At the edge of that region the integrator's error estimate let the balls chatter
    spuriously: 2400 stick-slip events per run of 004 instead of about 400, and grades off by
    up to 0.15 mm/s (docs/numerics/contacts.md, "Resting contacts"). For 004's restitution 0.5
    (zeta = 0.215) the edge is at 3.04 and the step 2.03 / w_c; 2 and 3 gave the same grades
    to 9e-4 mm/s over 1092 runs.

    Parameters
    ----------
    zeta : float
        Damping ratio of the contact [-] (from the restitution, docs/model.md).

    Returns
    -------
    float
        h_max w_c [-].
    """
    d = complex(-zeta, math.sqrt(max(0.0, 1.0 - zeta * zeta)))
    k = np.arange(0.05, 6.0, 1e-3)
    z = k * d
    R = 1.0 + z * (1.0 + z / 2.0 * (1.0 + z / 3.0 * (1.0 + z / 4.0 * (1.0 + z / 5.0 * (
        1.0 + z / 5.0)))))
    bad = np.abs(R) > 1.0
    edge = k[np.argmax(bad)] if bad.any() else k[-1]
    return max(1.0, 2.0 / 3.0 * float(edge))


def spin_arrays(spin: SpeedProfile | MotorDrive) -> tuple[np.ndarray, np.ndarray, float]:
    """Profile knots (times [s], speeds [rad/s]) and the end time [s].

    Parameters
    ----------
    spin : SpeedProfile or MotorDrive
        The spin; a motor drive gives two knots at its initial speed (the kernel integrates its
        spin as a degree of freedom and ignores the table).

    Returns
    -------
    times : ndarray
        Knot times [s].
    speeds : ndarray
        Spin speed at each knot [rad/s].
    t_end : float
        End of the run [s].
    """
    if isinstance(spin, MotorDrive):
        return np.array([0.0, spin.duration]), np.array([spin.initial_speed] * 2), spin.duration
    t, w = spin.arrays()
    return t, w, spin.duration


def fast_paths(system: System, spin: SpeedProfile | MotorDrive,
               options: SimOptions) -> tuple[bool, bool, bool, bool, bool]:
    """The kernels' fast paths, derived from the model here and nowhere else.

    Parameters
    ----------
    system : System
        The machine (suspension, gravity, unbalance schedule).
    spin : SpeedProfile or MotorDrive
        The spin (a motor drive has no closed-form holds).
    options : SimOptions
        The friction law.

    Returns
    -------
    (holds, ramps, slip_jumps, isotropic, symmetric) : tuple of bool
        ``isotropic``: kx = ky, cx = cy, no base motion, no suspension dry friction, so the
        suspension force is -k w - c (w' + i psi' w) in the rotor frame (004 eq 8-9; rhs.py).
        ``symmetric``: isotropic and no gravity, so max|x| = max|y| = max|w| (integrate.py).
        ``holds``: symmetric, exact stick-slip law (with or without creep), prescribed spin,
        constant unbalance, no liquid beside the balls (its moment is not in the closed
        forms): stuck constant-speed holds are solved in closed form (core/hold.py). A new
        effect that breaks a closed form must be added here.
        ``ramps``: holds and the exact stick-slip law without creep: stuck linear speed ramps
        are solved without stepping (core/ramp.py).
        ``slip_jumps``: under the ramps' conditions, phases where a ball slips are jumped by
        ETDRK4-B (core/expo.py).
        Where a flag is False the kernel steps that phase by DOPRI5 (the general path, exact
        to the tolerances; docs/numerics/stuck-phases.md).
    """
    s, g = system.suspension, system.gravity
    isotropic = (s.kx == s.ky and s.cx == s.cy and s.base_frequency == 0.0
                 and s.dry_friction_force == 0.0)
    symmetric = isotropic and g.g == 0.0
    holds = (symmetric and options.friction_law in ("stick", "creep")
             and not isinstance(spin, MotorDrive) and system.rotor.unbalance_table()[0].size == 1
             and system.liquid is None)
    ramps = holds and options.friction_law == "stick"
    return holds, ramps, ramps, isotropic, symmetric


def pack_params(system: System, spin: SpeedProfile | MotorDrive, options: SimOptions,
                liquid_ok: bool = False) -> tuple[np.ndarray, np.ndarray]:
    """Scalar vector P (N_P,) and ball table B (N, N_B) in SI.

    The slots are named in :mod:`autobalance.core.layout` (P_*, B_*). Besides the parameters
    as given, P holds M_t [kg], the contact angle 2 asin(r/R) [rad], the motor law and hold
    speed [rad/s], the model switches and the :func:`fast_paths` flags; B holds per ball m [kg],
    I [kg*m^2], R/r [-], D [N*m*s/rad], mu and mu_s [-], and the ball-ball contact stiffness
    [N*m/rad] and damping [N*m*s/rad] from the contact frequency [rad/s] and restitution [-]
    (the effective inertia of two neighbours, zeta from ln e).

    Parameters
    ----------
    system : System
        The machine.
    spin : SpeedProfile or MotorDrive
        The spin (nominal speed; motor torque law).
    options : SimOptions
        Friction law, v_sat [rad/s], normal-force model.
    liquid_ok : bool
        True for the run of balls beside a liquid (:mod:`autobalance.simulate.hybrid`, which
        sets the liquid's moment P_LQ* step by step; M_t includes the liquid's mass).

    Returns
    -------
    P : ndarray (N_P,)
        Scalar parameters [SI].
    B : ndarray (N, N_B)
        Ball table [SI].

    Raises
    ------
    ParameterError
        A motor drive on a rotor without polar inertia; a system with a liquid balancer unless
        ``liquid_ok``.
    """
    if system.liquid is not None and not liquid_ok:
        from ..models import ParameterError
        raise ParameterError("liquid", "a [liquid] section",
                             "the ball kernel alone has no liquid model: a liquid balancer, "
                             "alone or beside balls, runs with autobalance.simulate.simulate "
                             "(and `autobalance simulate`)")
    r, s, b, g = system.rotor, system.suspension, system.balancer, system.gravity
    P = np.zeros(N_P)
    P[P_MT] = system.total_mass
    P[P_MROT] = r.mass
    P[P_KX], P[P_KY], P[P_CX], P[P_CY] = s.kx, s.ky, s.cx, s.cy
    P[P_FDRY], P[P_GDRY], P[P_VDRY] = s.dry_friction_force, s.dry_friction_angle, s.dry_friction_velocity
    P[P_BAX], P[P_BAY], P[P_BW] = s.base_amplitude_x, s.base_amplitude_y, s.base_frequency
    P[P_BPX], P[P_BPY] = s.base_phase_x, s.base_phase_y
    P[P_R] = b.race_radius if b.n_balls else 0.0
    P[P_RHO], P[P_BETA] = b.eccentricity, b.eccentricity_angle
    P[P_G], P[P_GDIR] = g.g, g.direction
    P[P_BZ], P[P_CPHI] = r.polar_inertia, r.spin_damping
    P[P_WNOM] = spin.nominal_speed
    if isinstance(spin, MotorDrive):
        if r.polar_inertia <= 0.0:
            from ..models import ParameterError
            raise ParameterError("rotor.polar_inertia", r.polar_inertia,
                                 "must be > 0 when the spin is driven by a motor torque")
        P[P_SPIN] = 1.0
        P[P_LAW] = LAW_ID[spin.law]
        P[P_T0], P[P_WF] = spin.torque, spin.final_speed
        P[P_WHOLD] = spin.hold_fraction * spin.final_speed
    P[P_FLAW] = FRICTION_LAW_ID[options.friction_law]
    if options.friction_law == "creep" and any(
            st != mu for st, mu in zip(b.stiction, b.rolling_resistance)):
        from ..models import ParameterError
        raise ParameterError("options.friction_law", "creep",
                             "needs balancer.stiction equal to balancer.rolling_resistance "
                             "(the tanh law it emulates has no separate static coefficient)")
    P[P_VSAT] = options.v_sat
    P[P_NMODEL] = 0.0 if options.normal_force == "ball" else 1.0
    P[P_DELTA] = b.contact_angle
    P[P_HOLDS], P[P_RAMPS], P[P_ETD], P[P_ISO], P[P_SYM] = (
        1.0 if f else 0.0 for f in fast_paths(system, spin, options))
    n = b.n_balls
    B = np.zeros((n, N_B))
    if n:
        B[:, B_M] = b.masses
        B[:, B_I] = b.inertias
        B[:, B_RR] = b.race_radius / b.ball_radius
        B[:, B_D] = b.damping
        B[:, B_MU] = b.rolling_resistance
        B[:, B_MUS] = b.stiction
        J = B[:, B_M] * b.race_radius**2 + B[:, B_I] * B[:, B_RR] ** 2
        Jn = np.roll(J, -1)
        jeff = J * Jn / (J + Jn)
        wc = b.contact_frequency or 5.0 * spin.nominal_speed
        e = b.restitution
        zeta = 1.0 if e <= 0.0 else -math.log(e) / math.sqrt(math.pi**2 + math.log(e) ** 2)
        if b.contact == "compliant":          # "none": no ball-ball force (004's points)
            B[:, B_KC] = jeff * wc**2
            B[:, B_CC] = 2.0 * zeta * jeff * wc
            P[P_HC] = contact_step(zeta) / wc
    return P, B


def initial_vector(system: System, spin: SpeedProfile | MotorDrive, initial: InitialState) -> tuple[np.ndarray, np.ndarray]:
    """State y0 (2*nq,) and the ball order (kernel index -> user index).

    The kernel keeps balls sorted by angle (they cannot pass each other); alpha is unwrapped so
    that alpha_0 <= alpha_1 <= ... < alpha_0 + 2 pi.

    The rotor's position and velocity are given in the inertial frame at psi = 0 and converted
    to the rotor frame (u' = vx + w0 y, v' = vy - w0 x); with ``initial.steady_state`` they are
    the steady orbit of :func:`autobalance.physics.response.steady_orbit_start` (000 eq 6-7).

    Parameters
    ----------
    system : System
        The machine.
    spin : SpeedProfile or MotorDrive
        The spin; its speed at t = 0 [rad/s] is the initial spin speed.
    initial : InitialState
        Ball angles [rad] and speeds [rad/s], rotor displacement [m] and velocity [m/s].

    Returns
    -------
    y0 : ndarray (2*nq,)
        Initial state (u, v [m], alpha_1..N, psi [rad], then their rates [m/s], [rad/s];
        :mod:`autobalance.core.layout`).
    order : ndarray of int
        order[k] = the user's index of the kernel's ball k.
    """
    b = system.balancer
    n = b.n_balls
    nq = n_q(n)
    a = initial.angles_for(b)
    ad = initial.speeds_for(b)
    order = np.argsort(np.mod(a, 2 * np.pi), kind="stable")
    a_sorted = np.mod(a[order], 2 * np.pi)
    y = np.zeros(2 * nq)
    if isinstance(spin, MotorDrive):
        w0 = spin.initial_speed
    else:
        w0 = float(spin.speeds[0])
    x0, y0_, vx, vy = initial.x, initial.y, initial.vx, initial.vy
    if initial.steady_state and w0 > 0.0:
        x0, y0_, vx, vy = steady_orbit_start(system, w0, a)
    # initial rotor position/velocity given in the inertial frame at psi = 0
    y[0], y[1] = x0, y0_
    y[nq], y[nq + 1] = vx + w0 * y0_, vy - w0 * x0
    y[alpha_slice(n)] = a_sorted
    y[alpha_dot_slice(n)] = ad[order]
    y[psi_index(n)] = 0.0
    y[speed_index(n)] = w0
    return y, order


def atol_vector(system: System, spin: SpeedProfile | MotorDrive, options: SimOptions) -> np.ndarray:
    """Absolute tolerances: atol_scale times a length, an angle and their rates.

    The length scale is the larger of the rotor's and the balls' eccentricity
    max(U, sum(m_i) R) / M_t and the base amplitudes [m]; the angle scale is 1 rad; the rates
    multiply them by max(nominal speed, 1 rad/s) (docs/numerics/kernel.md).

    Parameters
    ----------
    system : System
        The machine.
    spin : SpeedProfile or MotorDrive
        The spin (its nominal speed [rad/s]).
    options : SimOptions
        ``atol_scale`` [-].

    Returns
    -------
    ndarray (2*nq,)
        Absolute tolerance of each state component in its unit (u, v [m], alpha_1..N,
        psi [rad], then their rates [m/s], [rad/s]; :mod:`autobalance.core.layout`).
    """
    b = system.balancer
    nq = n_q(b.n_balls)
    sus = system.suspension
    L = max(max(system.rotor.unbalance, b.capacity, 1e-9) / system.total_mass,
            sus.base_amplitude_x, sus.base_amplitude_y)
    W = max(spin.nominal_speed, 1.0)
    a = np.empty(2 * nq)
    a[:2] = L
    a[2:nq] = 1.0
    a[nq:nq + 2] = L * W
    a[nq + 2:] = W
    return options.atol_scale * a


#: Floats per output sample held while a run's history is in memory, beyond 3 per state
#: component (the stored state, its unpacked copy in :class:`Simulation` and the NetCDF's):
#: the series derived from it (fixed-frame whirl, amplitude, residual unbalance as a complex
#: number, its modulus and angle, grade, their temporaries and their copies in the dataset).
DERIVED_SERIES = 24


def history_bytes(n_samples: float, n_state: int) -> float:
    """Memory of a run's time history with everything derived from it [B].

    Parameters
    ----------
    n_samples : float
        Output samples [-].
    n_state : int
        State components per sample [-].
    """
    return float(n_samples) * 8.0 * (3 * max(n_state, 1) + DERIVED_SERIES)


def _time_grid(spin, options: SimOptions, n_state: int = 1) -> np.ndarray:
    """Output times [s]; refuses (ResourceError naming ``options.save_dt``) a grid whose
    history with what is derived from it (:func:`history_bytes`) exceeds the memory limit,
    before allocating it."""
    t_end = spin.duration
    cps = np.asarray(spin.checkpoints, float)
    if options.save_dt < 0:
        return np.unique(np.concatenate([[0.0], cps, [t_end]]))
    dt = options.save_dt
    if dt == 0.0:
        dt = 2 * np.pi / max(spin.nominal_speed, 1e-9) / 20.0
        dt = max(dt, t_end / 200_000)
    n_est = t_end / dt + 2.0 + cps.size   # float: t_end / dt may overflow an int
    check_memory("options.save_dt", f"{dt:g} s", history_bytes(n_est, n_state),
                 f"time history and what is derived from it ({n_est:.3g} samples)")
    n = int(np.floor(t_end / dt + 1e-9)) + 1
    grid = np.arange(n) * dt
    t = np.sort(np.concatenate([grid[grid < t_end], cps, [t_end]]))
    keep = np.concatenate([[True], np.diff(t) > 1e-9 * max(t_end, 1.0)])
    return t[keep]


def _h_max(spin, options: SimOptions) -> float:
    if options.max_step > 0:
        return options.max_step
    return min(0.05, spin.duration / 20.0)


class RunInputs(NamedTuple):
    """The kernel's inputs of one run (:func:`run_inputs`): P, B (pack_params), the initial
    state y0 and the balls' order, the profile's knots [s], [rad/s] and end [s], the unbalance
    table [s], [kg*m], the output times [s] with their empty history and statistics, atol per
    state component and the largest step [s]."""

    P: np.ndarray
    B: np.ndarray
    y0: np.ndarray
    order: np.ndarray
    prof_t: np.ndarray
    prof_w: np.ndarray
    t_end: float
    unb_t: np.ndarray
    unb_u: np.ndarray
    out_t: np.ndarray
    out_y: np.ndarray
    stats: np.ndarray
    atol: np.ndarray
    h_max: float


def run_inputs(system: System, spin: SpeedProfile | MotorDrive, initial: InitialState,
               options: SimOptions, liquid_ok: bool = False) -> RunInputs:
    """The kernel's inputs of one run of :func:`simulate` (and of balls beside a liquid,
    ``liquid_ok``: :mod:`.hybrid`), packed once here.

    Parameters
    ----------
    system : System
        The machine (SI dataclasses) [-].
    spin : SpeedProfile or MotorDrive
        The spin: speed [rad/s] over time [s], or a motor torque law [-].
    initial : InitialState
        Ball angles [rad] and rotor state at t = 0 [-].
    options : SimOptions
        Friction law, tolerances, output spacing [-].
    liquid_ok : bool
        As :func:`.pack.pack_params` [-].
    """
    P, B = pack_params(system, spin, options, liquid_ok)
    y0, order = initial_vector(system, spin, initial)
    prof_t, prof_w, t_end = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    out_t = _time_grid(spin, options, y0.size)
    return RunInputs(P, B, y0, order, prof_t, prof_w, t_end, unb_t, unb_u, out_t,
                     np.zeros((out_t.size, y0.size)), np.zeros(N_S),
                     atol_vector(system, spin, options), _h_max(spin, options))
