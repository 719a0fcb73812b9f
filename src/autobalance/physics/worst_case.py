"""Worst-case residual unbalance of a ball balancer whose balls are at rest: a true bound for
N balls, with rolling resistance, race eccentricity and suspension dry friction together.

**Force on a ball.** Averaged over one revolution (000 eq 5, 8, 39-42) the tangential force on
ball i, at angle alpha_i from the unbalance, is

    F_i = m_i w^2 Im(e^{-i alpha_i} z),      z = (X + iY)/2 + rho e^{i beta}          [N]

where x = Re(X e^{iwt}), y = Re(Y e^{iwt}) are the first harmonics of the rotor motion: z is
the forward (synchronous) whirl of the race centre O_1, the rotor-frame deflection of 004 eq
(8)-(9) for an isotropic rotor. Only the first harmonic of the rotor motion survives the
average. For the viscous suspension of 000 eq (2)-(3) (X = w^2 W/D_x, Y = -i w^2 W/D_y with
D = k - M_t w^2 + i c w, :func:`~.response.dynamic_stiffness`), z = h W + rho e^{i beta} with
h = (w^2/2)(1/D_x + 1/D_y) = conj(H)/2 of :mod:`.vibratory`, and this F_i is exactly
:func:`~.vibratory.vibratory_forces`. W = U + sum m_j (R e^{i alpha_j} + rho e^{i beta}) is
the residual unbalance (:func:`~.unbalance.residual_unbalance`).

**Suspension dry friction** (000 eq 48, two dampers at +-gamma, force F each): the first
harmonic of a force bounded by F has an amplitude <= 4F/pi, so it shifts z by
eps_f = -(Phi_x/D_x + i Phi_y/D_y)/2 with
|eps_f| <= e_f = (2F/pi)(|cos g/D_x + i sin g/D_y| + |cos g/D_x - i sin g/D_y|) [m].

**Rest** (000 eq 20-21): a ball stays at rest while |F_i| <= mu_i N_i, N_i <= m_i (R w^2 + g),
i.e. while |Im(e^{-i alpha_i} z)| <= a_i = mu_i (R + g/w^2) [m] (mu_i the static coefficient,
``balancer.stiction``). The masses and w^2 cancel: the test is geometric.

**The bound.** For z = zeta e^{i theta} every ball at rest lies within s_i = asin(a_i/zeta) of
the line through 0 along theta, so the balls' moment sum_j m_j R e^{i alpha_j}, rotated by
-theta, lies in a union of boxes (one per side of the line each ball is on; exact X and Y ranges
of each arc; for one or two balls the exact set of their moments). The balls' sum is also
fixed by z: it is W - U - M_b rho e^{i beta} with
W = (z - rho e^{i beta} - eps_f)/h. A circle |z| = zeta1 on which no point can be a rest state
(checked on K angles with the Lipschitz margin of the angle step, eps_f anywhere in its disc and,
when the angle is unknown, beta anywhere) separates the balanced state z = 0 from every other
rest state: every rest state connected to the balanced one has |z| < zeta1, hence

    |W| <= (zeta1 + rho + e_f) / |h|                                                  [kg*m]

The smallest such circle is found by a scan in zeta (steps of 10 %) and bisection. No
Jacobian is inverted, so a continuous family of balanced states (N >= 3) needs no special case. With mu = 0 the bound is
exact: rho/|h| is the exact residual of 000 eq (46)-(47) for N >= 2 (F_i = 0 for every ball
that spans the plane means z = 0), and for one ball with m R = Me at w >> w_n the rolling part
tends to 000 eq (61)'s m R Delta alpha = M_t R f/r.

**A liquid beside the balls** (:class:`SyncLiquid`). In a synchronous whirl the liquid of a
Leblanc chamber turns rigidly about the rotation axis while the chamber is displaced by the
rotor's whirl z_r = z - rho e^{i beta}; while its rings stay intact its moment about the chamber
centre is U_L = kappa z_r, kappa the mass of the missing core (intact ring, Ehrich 1992 sec. 5;
:func:`autobalance.liquid.synchronous.synchronous_liquid`). The rotor's whirl then obeys
D z_r = w^2 (W_b + kappa z_r) + Phi, i.e. the rotor with the added mass kappa:
z_r = h_b W_b + eps_b, h_b and eps_b the gain and friction shift with M_t + kappa. The balls'
rest test and the circle test take h_b (and e_f with M_t + kappa); the residual the rotor feels,
W = W_b + U_L = (z_r - eps_f)/h with the rotor's own h, is bounded by the same
(zeta1 + rho + e_f)/|h|. The bound holds while the liquid is linear on the separating circle:
|z_r| <= zeta1 + rho within the liquid's ``linear_range``; otherwise it is not claimed
(``separated`` false, ``liquid_linear`` false).

Assumptions (returned with every bound): the kinetic-static averaged force (000 eq 13; balls
slow against the spin); the rest test of 000 eq (21) with the normal force m (R w^2 + g);
no ball-ball contact at rest; the balls' rest state belongs to the balanced state's region at
this speed (they last moved at this speed, which is above the balancing onset, 000 eq 12).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, NamedTuple

import numpy as np

from ..models import ParameterError
from ..models._validate import finite as _finite
from ..models._validate import nonneg as _nonneg
from .response import dynamic_stiffness

from .reachable_set import _Circle, _separating_radius

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import System

__all__ = ["ASSUMPTIONS", "SyncLiquid", "attained_residual", "friction_displacement",
           "residual_bound", "rest_limits", "synchronous_gain"]

#: What the bound of :func:`residual_bound` assumes (JSON-ready, quoted with every result).
ASSUMPTIONS = (
    "kinetic-static averaged forces on the balls (000 eq 8, 13): the balls move slowly "
    "against the spin",
    "a ball rests while |F_i| <= mu_i m_i (R w^2 + g) (000 eq 20-21; mu_i = its stiction)",
    "suspension dry friction enters through its first harmonic, at most 4F/pi per damper "
    "(000 eq 48)",
    "no ball-ball contact at rest",
    "the balls last moved at this speed and stopped in the region of the balanced state",
)

#: What a bound beside a liquid assumes in addition (quoted with it).
LIQUID_ASSUMPTIONS = (
    "the liquid in rigid rotation about the rotation axis with the chamber displaced by the "
    "rotor's synchronous whirl (quasi-static: moment kappa z_r while its rings stay intact; "
    "first order in z_r with partitions)",
    "that synchronous whirl is reached: the liquid's own waves do not destabilise it (study "
    "speed-map judges the balanced state with the films)",
)


class SyncLiquid(NamedTuple):
    """A liquid beside the balls as their averaged model sees it in a synchronous whirl
    (module docstring; made by :func:`autobalance.liquid.synchronous.synchronous_liquid`).

    Parameters
    ----------
    added_mass : float
        kappa [kg]: the liquid's moment about the chamber centre per unit whirl of the rotor,
        U_L = kappa z_r (0 for a pool).
    linear_range : float
        Largest whirl |z_r| [m] over which U_L = kappa z_r holds (the rings stay intact).
    capacity : float
        Largest |U_L| [kg*m]: all the liquid gathered at the wall (rho V R).
    """

    added_mass: float
    linear_range: float
    capacity: float


def synchronous_gain(system: System, speed: float, added_mass: float = 0.0) -> complex:
    """h = (w^2/2)(1/D_x + 1/D_y) [m/(kg*m)]: the forward whirl of the rotor per unit rotating
    unbalance (000 eq 6-7; conj(H)/2 of :mod:`.vibratory`).

    Parameters
    ----------
    system : autobalance.models.System
        Suspension kx, ky [N/m], cx, cy [N*s/m] and the translating mass M_t [kg].
    speed : float
        Spin speed w [rad/s], > 0.
    added_mass : float
        kappa [kg] added to M_t in D (a liquid's synchronous moment, :class:`SyncLiquid`).

    Returns
    -------
    complex
        h [m/(kg*m)]; its modulus tends to 1/M_t for w >> w_n.
    """
    w = _speed(speed)
    s, mt = system.suspension, system.total_mass + float(added_mass)
    return complex(0.5 * w * w * (1.0 / dynamic_stiffness(mt, s.kx, s.cx, w)
                                  + 1.0 / dynamic_stiffness(mt, s.ky, s.cy, w)))


def rest_limits(system: System, speed: float,
                rolling_resistance: float | npt.ArrayLike | None = None) -> np.ndarray:
    """a_i = mu_i (R + g/w^2) [m]: ball i rests while the tangential part of the race-centre
    whirl z on it is at most a_i (000 eq 20-21 divided by m_i w^2).

    Parameters
    ----------
    system : autobalance.models.System
        R [m] and the stiction mu_i [-] of the balancer; g [m/s^2] of the gravity.
    speed : float
        Spin speed w [rad/s], > 0.
    rolling_resistance : float or array_like, optional
        mu [-] per ball (or one for all), within [0, 1]; default ``balancer.stiction``.

    Returns
    -------
    ndarray (N,)
        a_i [m].
    """
    w = _speed(speed)
    b = system.balancer
    mu = np.asarray(b.stiction if rolling_resistance is None else rolling_resistance, float)
    mu = np.broadcast_to(mu, (b.n_balls,)) if mu.ndim == 0 else mu
    if mu.shape != (b.n_balls,) or not np.all(np.isfinite(mu)) or np.any(mu < 0) or np.any(mu > 1):
        raise ParameterError("rolling_resistance", np.asarray(rolling_resistance).tolist(),
                             f"must be one or {b.n_balls} coefficients f/r within [0, 1] [-]")
    return mu * (b.race_radius + system.gravity.g / (w * w))


def friction_displacement(system: System, speed: float, friction_force: float | None = None,
                          friction_angle: float | None = None, added_mass: float = 0.0) -> float:
    """e_f [m]: the largest shift of the race-centre whirl z by the suspension dry friction.

    Two dampers along (cos g, +-sin g), each a force of magnitude <= F (000 eq 48); the first
    harmonic of each is at most 4F/pi, and it moves the forward whirl by
    (Phi_x/D_x + i Phi_y/D_y)/2, hence
    e_f = (2F/pi)(|cos g/D_x + i sin g/D_y| + |cos g/D_x - i sin g/D_y|).

    Parameters
    ----------
    system : autobalance.models.System
        Suspension (kx, ky [N/m], cx, cy [N*s/m], F [N], gamma [rad]) and M_t [kg].
    speed : float
        Spin speed w [rad/s], > 0.
    friction_force : float, optional
        F per damper [N], >= 0; default ``suspension.dry_friction_force``.
    friction_angle : float, optional
        gamma [rad]; default ``suspension.dry_friction_angle``.
    added_mass : float
        kappa [kg] added to M_t in D (:class:`SyncLiquid`).

    Returns
    -------
    float
        e_f [m].
    """
    w = _speed(speed)
    s, mt = system.suspension, system.total_mass + float(added_mass)
    F = s.dry_friction_force if friction_force is None else _nonneg("friction_force", friction_force)
    g = s.dry_friction_angle if friction_angle is None else _finite("friction_angle", friction_angle)
    dx = dynamic_stiffness(mt, s.kx, s.cx, w)
    dy = dynamic_stiffness(mt, s.ky, s.cy, w)
    c, sn = math.cos(g), math.sin(g)
    return float(2.0 * F / math.pi * (abs(c / dx + 1j * sn / dy) + abs(c / dx - 1j * sn / dy)))


def _speed(speed) -> float:
    w = _finite("speed", speed)
    if w <= 0.0:
        raise ParameterError("speed", speed, "must be > 0 [rad/s]")
    return w


def _balanced_exists(c, V: complex, tol: float) -> bool:
    """V is a sum of vectors of lengths c (the balanced state exists: 000 eq 12's capacity)."""
    total = float(np.sum(c))
    inner = max(0.0, 2.0 * float(np.max(c)) - total)
    return inner - tol <= abs(V) <= total + tol


def residual_bound(system: System, speed: float, *,
                   rolling_resistance: float | npt.ArrayLike | None = None,
                   eccentricity: float | None = None,
                   eccentricity_angle: float | str | None = "system",
                   friction_force: float | None = None, friction_angle: float | None = None,
                   n_theta: int = 1024, n_beta: int = 24,
                   liquid: SyncLiquid | None = None) -> dict:
    """A true upper bound on the residual unbalance |W| of any rest state of the balls near
    their balanced state (module docstring: the circle test), for N balls, with rolling
    resistance (000 eq 20-22), race eccentricity (eq 46-47) and suspension friction (eq 48-49).

    Parameters
    ----------
    system : autobalance.models.System
        The machine; the tolerances below default to its own.
    speed : float
        Spin speed w [rad/s], > 0; the balls balance only above the onset Re(h) < 0 (000 eq 12).
    rolling_resistance : float or array_like, optional
        Static rolling-resistance coefficient mu = f/r per ball [-] (default
        ``balancer.stiction``).
    eccentricity : float, optional
        Race eccentricity rho [m], >= 0 (default ``balancer.eccentricity``).
    eccentricity_angle : float or None or str
        beta [rad]; None = any angle (the bound holds for all); "system" = the balancer's.
    friction_force : float, optional
        Dry friction F per damper [N] (default the suspension's).
    friction_angle : float, optional
        Damper inclination gamma [rad] (default the suspension's).
    n_theta : int
        Angles on each test circle (>= 64); the margin shrinks as 1/n_theta.
    n_beta : int
        Eccentricity angles tested when beta is unknown (>= 4); the margin shrinks as 1/n_beta.
    liquid : SyncLiquid, optional
        A liquid beside the balls (module docstring): its added mass kappa [kg], linear range
        [m] and capacity [kg*m]. The residual is then the rotor's W_b + U_L.

    Returns
    -------
    dict
        "worst_residual_kg_m" (the bound, capped by the trivial |U| + M_b rho + sum m_i R
        (+ the liquid's capacity)),
        "eccentricity_kg_m" (rho/|h|), "friction_kg_m" (e_f/|h|), "rolling_kg_m"
        (zeta1/|h|), "displacement_bound_m" (zeta1), "rest_limits_m" (a_i),
        "friction_displacement_m" (e_f), "gain_m_per_kg_m" (|h|), "capacity_kg_m",
        "trivial_bound_kg_m", "separated" (a separating circle was found below the trivial
        bound), "balancing" (Re h < 0), "balanced_exists", "assumptions"; beside a liquid
        also "liquid_added_mass_kg", "liquid_linear_range_m" and "liquid_linear" (the
        separating circle within the linear range).
    """
    w = _speed(speed)
    n_theta = int(n_theta)
    if n_theta < 64:
        raise ParameterError("n_theta", n_theta, "must be an integer >= 64")
    if int(n_beta) < 4:
        raise ParameterError("n_beta", n_beta, "must be an integer >= 4")
    b = system.balancer
    if b.n_balls < 1:
        raise ParameterError("balancer.n_balls", b.n_balls, "needs at least one ball")
    rho = b.eccentricity if eccentricity is None else _nonneg("eccentricity", eccentricity)
    if rho >= b.race_radius:
        raise ParameterError("eccentricity", rho, f"must be < the race radius {b.race_radius} m")
    if isinstance(eccentricity_angle, str):
        if eccentricity_angle != "system":
            raise ParameterError("eccentricity_angle", eccentricity_angle,
                                 "must be an angle [rad], None (any) or 'system'")
        beta = b.eccentricity_angle
    else:
        beta = None if eccentricity_angle is None else _finite("eccentricity_angle", eccentricity_angle)
    a = rest_limits(system, w, rolling_resistance)
    e_f = friction_displacement(system, w, friction_force, friction_angle)
    h = synchronous_gain(system, w)
    kappa = 0.0 if liquid is None else float(liquid.added_mass)
    # the balls' rest states see the rotor with the liquid's added mass (module docstring)
    h_b = synchronous_gain(system, w, kappa) if kappa else h
    e_b = friction_displacement(system, w, friction_force, friction_angle, kappa) if kappa else e_f
    c = b.masses * b.race_radius
    U = system.rotor.unbalance
    mb = b.total_mass
    cap = float(np.sum(c))
    trivial_b = U + mb * rho + cap                 # rotor and balls
    trivial = trivial_b + (0.0 if liquid is None else float(liquid.capacity))
    # balanced state z = 0 with eps_f = 0: W = -rho e^{i beta}/h
    betas = (2 * math.pi * (np.arange(int(n_beta)) + 0.5) / int(n_beta) if beta is None and rho > 0
             else np.array([0.0 if beta is None else beta]))
    # balanced state z = 0, eps_f = 0: the balls cancel V = U + rho e^{i beta} (1/h + M_b)
    shift = rho * abs(1.0 / h_b + mb)
    if beta is None:
        exists = (_balanced_exists(c, U + shift, 1e-9 * cap)
                  and _balanced_exists(c, max(U - shift, 0.0), 1e-9 * cap))
    else:
        exists = _balanced_exists(c, U + rho * np.exp(1j * beta) * (1.0 / h_b + mb), 1e-9 * cap)
    out = {"speed_rad_s": w, "rest_limits_m": a, "friction_displacement_m": e_f,
           "gain_m_per_kg_m": abs(h), "eccentricity_kg_m": rho / abs(h),
           "friction_kg_m": e_f / abs(h), "capacity_kg_m": cap, "trivial_bound_kg_m": trivial,
           "balancing": bool(h_b.real < 0), "balanced_exists": bool(exists),
           "assumptions": list(ASSUMPTIONS) + (list(LIQUID_ASSUMPTIONS) if liquid else [])}
    circle = _Circle(c, a, U, h_b, rho, betas, mb, e_b, n_theta)
    zeta1 = _separating_radius(circle, a, trivial_b * abs(h_b) + rho + e_b)
    bound = (zeta1 + rho + e_f) / abs(h) if zeta1 is not None else math.inf
    linear = liquid is None or (zeta1 is not None and zeta1 + rho <= liquid.linear_range)
    separated = bool(exists and h_b.real < 0 and bound < trivial and linear)
    out.update({"displacement_bound_m": zeta1 if zeta1 is not None else math.inf,
                "rolling_kg_m": zeta1 / abs(h) if zeta1 is not None else math.inf,
                "separated": separated,
                "worst_residual_kg_m": bound if separated else trivial})
    if liquid is not None:
        out.update({"liquid_added_mass_kg": kappa,
                    "liquid_linear_range_m": float(liquid.linear_range),
                    "liquid_linear": bool(linear)})
    return out


def attained_residual(system: System, speed: float, *,
                      rolling_resistance: float | npt.ArrayLike | None = None,
                      eccentricity: float | None = None,
                      eccentricity_angle: float | str | None = "system",
                      friction_force: float | None = None, friction_angle: float | None = None,
                      zeta_max: float | None = None, n_starts: int = 16, seed: int = 0,
                      liquid: SyncLiquid | None = None) -> dict:
    """The largest residual unbalance of a rest state found by optimisation (a lower bound on the
    true worst case; :func:`residual_bound` is the upper one).

    Maximises |W(alpha)| over the ball angles, the friction shift eps_f (|eps_f| <= e_f) and,
    when unknown, beta, subject to the rest test |Im(e^{-i alpha_i} z)| <= a_i of every ball
    with z = h W + rho e^{i beta} + eps_f (module docstring) and |z| <= ``zeta_max`` (the
    separating circle), by SLSQP from ``n_starts`` balanced states, continued over |z| <=
    zeta_max/4, /2, 3/4, 1 (a narrow region of rest states is followed outwards); for two
    balls also the exact rest state on the outermost circle that holds one (triangle law).

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speed : float
        Spin speed w [rad/s], > 0.
    rolling_resistance, eccentricity, eccentricity_angle, friction_force, friction_angle
        As for :func:`residual_bound` (mu [-], rho [m], beta [rad], F [N], gamma [rad]).
    zeta_max : float, optional
        Largest |z| [m] (default: the separating radius of :func:`residual_bound`).
    n_starts : int
        Starting configurations (>= 1).
    seed : int
        Seed of the random starts.
    liquid : SyncLiquid, optional
        A liquid beside the balls (:func:`residual_bound`): the rest test takes the rotor
        with its added mass, the residual is W_b + kappa z_r, and |z| stays within the
        liquid's linear range less rho.

    Returns
    -------
    dict
        "attained_residual_kg_m", "alpha_rad" (the configuration), "eccentricity_angle_rad",
        "friction_shift_m" (|eps_f|).
    """
    from scipy.optimize import least_squares, minimize

    w = _speed(speed)
    b = system.balancer
    bnd = residual_bound(system, w, rolling_resistance=rolling_resistance, eccentricity=eccentricity,
                         eccentricity_angle=eccentricity_angle, friction_force=friction_force,
                         friction_angle=friction_angle, liquid=liquid)
    kappa = 0.0 if liquid is None else float(liquid.added_mass)
    h = synchronous_gain(system, w, kappa)          # the balls' rest states: with kappa
    zmax = bnd["displacement_bound_m"] if zeta_max is None else _nonneg("zeta_max", zeta_max)
    if not math.isfinite(zmax):
        zmax = bnd["trivial_bound_kg_m"] * abs(h)
    n = b.n_balls
    c = b.masses * b.race_radius
    a = bnd["rest_limits_m"]
    e_f = friction_displacement(system, w, friction_force, friction_angle, kappa)
    U = system.rotor.unbalance
    mb = b.total_mass
    rho = b.eccentricity if eccentricity is None else float(eccentricity)
    if liquid is not None:            # the rest states the linear liquid models: |z_r| in range
        zmax = min(zmax, max(float(liquid.linear_range) - rho, 0.0))
    free_beta = eccentricity_angle is None
    beta0 = b.eccentricity_angle if isinstance(eccentricity_angle, str) or free_beta \
        else float(eccentricity_angle)
    scale = float(np.sum(c))
    if not np.any(a > 0) and bnd["separated"]:
        # no rolling resistance: z = 0 is the only rest state near balance, and W = (eps_f -
        # rho e^{i beta})/h reaches the bound with eps_f opposite rho e^{i beta}
        return {"attained_residual_kg_m": bnd["worst_residual_kg_m"],
                "alpha_rad": np.full(n, math.nan),
                "eccentricity_angle_rad": beta0, "friction_shift_m": e_f}
    if not zmax > 0.0:
        # no circle to search: no rolling resistance where the balls do not balance (0/0 in
        # the rest test before), or beside a liquid whose rings are not intact
        return {"attained_residual_kg_m": math.nan, "alpha_rad": [math.nan] * n,
                "eccentricity_angle_rad": math.nan, "friction_shift_m": math.nan}
    zs = max(zmax, float(a.max()), 1e-12 * b.race_radius)

    def unpack(x):
        al = x[:n]
        ef = (x[n] + 1j * x[n + 1]) * e_f
        be = x[n + 2] if free_beta else beta0
        return al, ef, be

    def W_of(x):
        al, _, be = unpack(x)
        return U + np.sum(c * np.exp(1j * al)) + mb * rho * np.exp(1j * be)

    def z_of(x):
        al, ef, be = unpack(x)
        return h * W_of(x) + rho * np.exp(1j * be) + ef

    def Wt(x):                      # the rotor's residual: + the liquid's kappa z_r
        return W_of(x) + kappa * (z_of(x) - rho * np.exp(1j * unpack(x)[2])) if kappa else W_of(x)

    def cons(x):
        al, _, _ = unpack(x)
        z = z_of(x)
        proj = np.imag(np.exp(-1j * al) * z) / zs
        return np.concatenate([(a / zs) ** 2 - proj ** 2,
                               [1.0 - x[n] ** 2 - x[n + 1] ** 2, (zmax / zs) ** 2 - abs(z / zs) ** 2]])

    rng = np.random.default_rng(int(seed))
    best, best_x = -1.0, None
    for k in range(max(1, int(n_starts))):
        be = rng.uniform(0, 2 * math.pi) if free_beta else beta0
        target = -rho * np.exp(1j * be) / h - U - mb * rho * np.exp(1j * be)

        def resid(al):
            d = np.sum(c * np.exp(1j * al)) - target
            return np.array([d.real, d.imag]) / scale

        al0 = least_squares(resid, rng.uniform(-math.pi, math.pi, n)).x
        x = np.concatenate([al0 + rng.normal(0, 1e-3, n), [0.0, 0.0], [be] if free_beta else []])
        for frac in np.linspace(0.25, 1.0, 4):     # continuation: |z| <= frac zeta_max
            lim = frac * zmax
            r = minimize(lambda x: -abs(Wt(x) / scale) ** 2, x, method="SLSQP",
                         constraints=[{"type": "ineq", "fun": lambda x, lim=lim: np.concatenate(
                             [cons(x)[:-1], [(lim / zs) ** 2 - abs(z_of(x) / zs) ** 2]])}],
                         options={"maxiter": 300, "ftol": 1e-14})
            if np.all(cons(r.x) >= -1e-9):
                x = r.x
                v = abs(Wt(x))
                if v > best:
                    best, best_x = v, x
    if n == 2:                         # exact: the outermost rest state on the circles
        for be in ([beta0] if not free_beta else 2 * math.pi * np.arange(12) / 12):
            x = _outermost_two_balls(c, a, U, h, rho, be, mb, zmax)
            if x is not None:
                x = np.concatenate([x, [0.0, 0.0], [be] if free_beta else []])
                if np.all(cons(x) >= -1e-9) and abs(Wt(x)) > best:
                    best, best_x = abs(Wt(x)), x
    if best_x is None:
        return {"attained_residual_kg_m": math.nan, "alpha_rad": [math.nan] * n,
                "eccentricity_angle_rad": math.nan, "friction_shift_m": math.nan}
    al, ef, be = unpack(best_x)
    return {"attained_residual_kg_m": float(best), "alpha_rad": np.mod(al, 2 * math.pi),
            "eccentricity_angle_rad": float(be), "friction_shift_m": float(abs(ef))}


def _outermost_two_balls(c, a, U, h, rho, beta, m_balls, zeta_max, n_theta: int = 4096):
    """Ball angles of a rest state of two balls (no friction shift) on the largest circle
    |z| <= zeta_max that holds one (circles 0.2 % apart, angles n_theta apart), or None."""
    theta = 2.0 * math.pi * np.arange(n_theta) / n_theta
    eb = np.exp(1j * beta)
    t0 = -(rho * eb / h + U + m_balls * rho * eb) * np.exp(-1j * theta)
    c1, c2 = float(c[0]), float(c[1])
    for frac in np.arange(1.0, 0.0, -0.002):
        zeta = frac * zeta_max
        s = np.arcsin(np.minimum(1.0, a / zeta))
        T = t0 + zeta / h
        r = np.abs(T)
        reach = (r <= c1 + c2) & (r >= abs(c1 - c2))
        g = np.arccos(np.clip((c1 * c1 + r * r - c2 * c2) / (2 * c1 * np.maximum(r, 1e-300)), -1, 1))
        for sg in (1.0, -1.0):
            al1 = np.angle(T) + sg * g
            al2 = np.angle(T - c1 * np.exp(1j * al1))
            ok = reach & (np.abs(np.sin(al1)) <= np.sin(s[0])) & (np.abs(np.sin(al2)) <= np.sin(s[1]))
            if np.any(ok):
                k = int(np.argmax(ok))
                return np.array([al1[k] + theta[k], al2[k] + theta[k]])
    return None
