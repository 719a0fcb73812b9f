"""Equilibria of the balls checked on the full model (000 sec. 3 / Fig. 10-11): the linearised
full model and a perturbed simulation from an equilibrium. The closed-form equilibria and their
kinetic-static stability are :mod:`autobalance.physics.equilibria`.

Two routes to the linearised full model, :func:`full_stability` picks the right one:

* :func:`linearised_full` - an isotropic suspension without gravity, base motion or a varying
  unbalance (``simulate.pack.fast_paths``' ``symmetric`` flag) has a steady rotor frame at
  constant speed (004 eq 8-10): an equilibrium is a fixed point there and the eigenvalues of
  the finite-difference Jacobian of the kernel's right-hand side decide (cheap);
* :func:`floquet_full` - otherwise the state in the inertial frame is periodic with
  T = 2 pi / w: Newton shooting for the periodic orbit and the eigenvalues of the
  finite-difference monodromy matrix (Floquet multipliers).

Both report multipliers over one revolution (mu = exp(lambda T) for the first). On a balanced
family (N >= 3) d = N - 2 of them are 1 with eigenvectors along the family: they are neutral.
They are removed when they lie within ``NEUTRAL_TOL`` of 1 and their eigenvectors span the
family's tangent (largest principal-angle sine below ``NEUTRAL_ANGLE_TOL``).

Gravity in the plane of an N >= 3 balancer breaks the family as a set of periodic orbits: every
revolution the balls move along it by a drift of order (g / (R w^2))^2 rad that vanishes at
isolated points of the family at most, so at a given family point no periodic orbit exists and
a shooting for one cannot converge. :func:`floquet_full` solves for the drifting orbit
instead, P(z) = z + V s (V the family's eigenvectors of the monodromy, s the drift per
revolution), and removes the family's multipliers as *slow* ones when they are
closer to 1 than ``SLOW_RATIO`` x every other multiplier's distance to 1 and span the tangent
to ``SLOW_ANGLE_TOL``: the balls wander along the family while W stays at W*, and the verdict
is on the transverse multipliers. The verdict is "stable" when every other multiplier has
|mu| < 1 - ``STABLE_MARGIN``, and only for a converged orbit (``SHOOTING_TOL``)."""
from __future__ import annotations

import dataclasses
import math
from typing import TYPE_CHECKING

import numpy as np

from ..core.layout import psi_index, rate_index
from ..models import ParameterError
from ..models._validate import finite as _finite
from ..physics.equilibria import TWO_PI, _wrap
from ..physics.vibratory import _speed

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import SimOptions, System

__all__ = ["NEUTRAL_ANGLE_TOL", "NEUTRAL_TOL", "SHOOTING_TOL", "SLOW_ANGLE_TOL", "SLOW_RATIO",
           "STABLE_MARGIN", "floquet_full", "full_stability",
           "linearised_full", "steady_rotor_frame", "verify_by_simulation"]

#: A neutral multiplier lies within this distance of 1 [-] (finite-difference accuracy).
NEUTRAL_TOL = 1e-6
#: The neutral eigenvectors span the tangent: largest principal-angle sine below this [-].
NEUTRAL_ANGLE_TOL = 1e-3
#: A family only nearly preserved (gravity in the plane: the balls drift along it): its
#: multipliers lie closer to 1 than this fraction of every other multiplier's distance to 1, so
#: that their eigenvectors are well separated from the transverse ones [-] ...
SLOW_RATIO = 0.2
#: ... and span the tangent to this principal-angle sine [-] (the drifting orbit's wobble tilts
#: them by a few g / (R w^2) out of the ball-angle plane).
SLOW_ANGLE_TOL = 0.3
#: Stable when every counted multiplier has |mu| < 1 - STABLE_MARGIN [-].
STABLE_MARGIN = 1e-7
#: Shooting (or fixed-point) residual, scaled by the rotor motion L and 0.1 rad, below which the
#: periodic (on a family under gravity: drifting) orbit counts as found [-]; otherwise no
#: verdict is claimed ("stable" is False).
SHOOTING_TOL = 1e-6


def _ideal(system):
    """The machine without rolling resistance and suspension dry friction (smooth, so it can be
    linearised: the stability of the ideal model)."""
    bal = dataclasses.replace(system.balancer, rolling_resistance=0.0, stiction=None)
    sus = dataclasses.replace(system.suspension, dry_friction_force=0.0)
    return dataclasses.replace(system, balancer=bal, suspension=sus)


def steady_rotor_frame(system: System) -> bool:
    """Whether the ideal machine has a steady rotor frame at constant speed: isotropic
    suspension, no base motion, no gravity (``simulate.pack.fast_paths``' ``symmetric``) and a
    constant unbalance. Then an equilibrium is a fixed point of the rotor-frame equations.

    Parameters
    ----------
    system : autobalance.models.System
        The machine.

    Returns
    -------
    bool
    """
    from ..models import SimOptions, SpeedProfile
    from ..simulate.pack import fast_paths

    sysl = _ideal(system)
    symmetric = fast_paths(sysl, SpeedProfile.constant(1.0, 1.0), SimOptions())[4]
    return bool(symmetric and system.rotor.unbalance_table()[0].size == 1)


def _scales(system, w: float) -> tuple[float, float]:
    """Length L [m] of the rotor motion (max(U, capacity) / M_t) and the speed w [rad/s]."""
    b = system.balancer
    return max(system.rotor.unbalance, b.capacity) / system.total_mass, w


def _neutral_split(mu, V, E, scale) -> dict:
    """Which d multipliers belong to the family with tangent columns E (state coordinates).

    The d multipliers nearest 1 whose eigenvectors (columns of V, scaled by ``scale``) align
    best with span E are taken. They are *exact* neutral ones when within NEUTRAL_TOL of 1 and
    spanning E to NEUTRAL_ANGLE_TOL; *slow* ones (a family only nearly preserved, e.g. by
    gravity: the balls drift slowly along it) when they span E to SLOW_ANGLE_TOL and lie
    closer to 1 than SLOW_RATIO x the distance min |mu_j - 1| of every other multiplier, so
    that their eigenvectors are well separated from the transverse ones. Otherwise none."""
    d = E.shape[1]
    Vs = V / scale[:, None]
    Es, _ = np.linalg.qr(E / scale[:, None])
    dist = np.abs(mu - 1.0)
    out = {"neutral_index": np.zeros(0, int), "neutral_ok": False, "neutral_kind": "none",
           "neutral_distance": float(np.sort(dist)[d - 1]), "neutral_sin_angle": 1.0,
           "neutral_separation": 0.0}
    near = np.argsort(dist)[:d + 2]                 # a few nearest 1; the best aligned d of them
    align = np.linalg.norm(Es.T @ Vs[:, near], axis=0) / np.linalg.norm(Vs[:, near], axis=0)
    pick = near[np.argsort(-align)[:d]]
    Qv, _ = np.linalg.qr(Vs[:, pick])
    cosines = np.linalg.svd(Es.T @ Qv, compute_uv=False)
    sin = float(np.sqrt(max(0.0, 1.0 - float(cosines.min()) ** 2)))
    rest = np.ones(mu.size, bool)
    rest[pick] = False
    sep = float(dist[rest].min()) if rest.any() else 1.0
    far = float(dist[pick].max())
    out.update(neutral_distance=far, neutral_sin_angle=sin, neutral_separation=sep)
    if far < NEUTRAL_TOL and sin < NEUTRAL_ANGLE_TOL:
        out.update(neutral_index=pick, neutral_ok=True, neutral_kind="exact")
    elif far < SLOW_RATIO * sep and sin < SLOW_ANGLE_TOL:
        out.update(neutral_index=pick, neutral_ok=True, neutral_kind="slow")
    return out


def _verdict(mu, V, E, scale) -> dict:
    """Multipliers -> the stability verdict, the family's neutral ones removed (E given)."""
    info = {"neutral_index": np.zeros(0, int), "neutral_ok": True}
    if E is not None and E.shape[1]:
        info = _neutral_split(mu, V, E, scale)
    keep = np.ones(mu.size, bool)
    keep[info["neutral_index"]] = False
    mx = float(np.abs(mu[keep]).max()) if keep.any() else 0.0
    res = {"multipliers": mu, "neutral_multipliers": mu[~keep], "max_modulus": mx,
           "max_modulus_all": float(np.abs(mu).max()), "stable": mx < 1.0 - STABLE_MARGIN,
           "neutral_ok": bool(info["neutral_ok"])}
    if E is not None and E.shape[1]:
        res.update(family_dimension=int(E.shape[1]), neutral_distance=info["neutral_distance"],
                   neutral_sin_angle=info["neutral_sin_angle"], neutral_kind=info["neutral_kind"],
                   neutral_separation=info["neutral_separation"])
    return res


# -- linearised full model ---------------------------------------------------------------------
def _period_map(system, w, z, options):
    """One revolution of the full model from state z = (x, y, vx, vy, alpha, alpha_dot) at psi = 0."""
    from ..models import InitialState, SpeedProfile
    from ..simulate import simulate

    n = system.balancer.n_balls
    T = TWO_PI / w
    init = InitialState(ball_angles=tuple(z[4:4 + n]), ball_speeds=tuple(z[4 + n:]),
                        x=z[0], y=z[1], vx=z[2], vy=z[3])
    sim = simulate(system, SpeedProfile.constant(w, T), initial=init, options=options)
    st = sim.states[-1]
    u, v, ud, vd = st[0], st[1], st[rate_index(0, n)], st[rate_index(1, n)]
    psi = st[psi_index(n)]
    c, s = math.cos(psi), math.sin(psi)
    x, y = u * c - v * s, u * s + v * c
    gx, gy = ud - w * v, vd + w * u          # inertial velocity in the rotor frame
    vx, vy = gx * c - gy * s, gx * s + gy * c
    a = sim.alpha[-1]
    a = z[4:4 + n] + _wrap(a - z[4:4 + n])
    return np.concatenate([[x, y, vx, vy], a, sim.alpha_dot[-1]])


def _monodromy(sysl, w: float, z, h, opts) -> np.ndarray:
    """dP/dz of the one-revolution map P at z by central differences (steps h, state units):
    the monodromy matrix of Floquet theory (Nayfeh & Balachandran 1995)."""
    M = np.empty((z.size, z.size))
    for k in range(z.size):
        dz = np.zeros_like(z)
        dz[k] = h[k]
        M[:, k] = (_period_map(sysl, w, z + dz, opts) - _period_map(sysl, w, z - dz, opts)) / (2 * h[k])
    return M


def _slow_basis(M, E, scale) -> np.ndarray:
    """Real basis V of the d eigenvectors of M that align best with span E among the d + 2
    multipliers nearest 1 (columns, state units; scaled by ``scale`` for the comparison),
    normalised so that E' V = I: the direction in which a point of a nearly preserved family
    moves along it in one revolution. E itself where that basis is degenerate."""
    d = E.shape[1]
    mu, W = np.linalg.eig(M)
    near = np.argsort(np.abs(mu - 1.0))[:d + 2]       # as _neutral_split: near 1, best aligned
    Ws = W[:, near] / scale[:, None]
    Es, _ = np.linalg.qr(E / scale[:, None])
    align = np.linalg.norm(Es.T @ Ws, axis=0) / np.linalg.norm(Ws, axis=0)
    pick = near[np.argsort(-align)[:d]]
    V = np.concatenate([W[:, pick].real, W[:, pick].imag], axis=1)
    u, sv, _ = np.linalg.svd(V / scale[:, None], full_matrices=False)
    if sv.size < d or sv[d - 1] < 1e-8 * sv[0]:
        return E
    V = scale[:, None] * u[:, :d]
    try:
        return V @ np.linalg.inv(E.T @ V)
    except np.linalg.LinAlgError:       # pragma: no cover - E' V singular: not the family's
        return E


def floquet_full(system: System, speed: float, alpha: npt.ArrayLike, iters: int = 6,
                 rtol: float = 1e-11, family: bool = False) -> dict:
    """Floquet multipliers of the full model about an equilibrium (linearised full model).

    The full model (our ``simulate``: 000 eq 2-4 with ball inertia, gravity, eccentricity) at
    constant speed w is periodic with T = 2 pi / w in the inertial frame. Newton shooting finds
    the periodic orbit z* = P(z*) of the one-revolution map P from the kinetic-static equilibrium
    (drum on its harmonic orbit, balls at rest); the multipliers are the eigenvalues of
    M = dP/dz (central finite differences; Floquet theory and shooting as in Nayfeh &
    Balachandran 1995, *Applied Nonlinear Dynamics*, Wiley). Rolling resistance and suspension
    dry friction are switched off (they make P non-smooth; stability of the ideal model).
    |mu| < 1 for all counted multipliers: asymptotically stable.

    On a balanced family (N >= 3 balls, tangent basis t) without gravity every point is a
    periodic orbit. Gravity in the plane breaks that: the balls drift along the family every
    revolution (on tests/data/grinder_3balls.toml by -3e-4 rad at every sample at 170 rad/s),
    so at a given family point no periodic orbit exists. The shooting then solves the
    drifting-orbit condition

        P(z) = z + V s,    t' (alpha - alpha_0) = 0,

    for z and the drift s [rad per revolution] (d unknowns): V are the d eigenvectors of M that
    belong to the family (:func:`_slow_basis`, updated at every Newton step, normalised so that
    their ball-angle part has unit component along t) and the phase condition keeps the point
    at alpha_0's place on the family. Without gravity s -> 0 and V -> (0, 0, t, 0, 0, 0).

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speed : float
        Spin speed w [rad/s], > 0.
    alpha : array_like (N,)
        Starting ball angles [rad] (an equilibrium of :func:`find_equilibria`).
    iters : int
        Newton iterations [-] (>= 1; at most 16 on a family, fewer once converged: the
        drifting orbit converges linearly where the drift is large).
    rtol : float
        Integrator tolerance of each revolution [-].
    family : bool
        alpha lies on a balanced family (N >= 3): solve the drifting-orbit condition above and
        remove the family's N - 2 multipliers before the verdict: exact ones (1 within
        NEUTRAL_TOL) or slow ones (gravity; :data:`SLOW_RATIO`).

    Returns
    -------
    dict
        "multipliers" (complex ndarray), "neutral_multipliers" (the removed ones),
        "max_modulus" [-] of the counted multipliers, "max_modulus_all" [-], "stable" (bool:
        max |mu| < 1 - STABLE_MARGIN), "neutral_ok" (the neutral ones were found; True without
        a family), with a family also "neutral_kind" ("exact", "slow" or "none"),
        "neutral_distance" (max |mu - 1| of the chosen ones), "neutral_sin_angle",
        "family_drift_rad" (max |s| [rad per revolution]) and "family_drift_rad_per_rev" (s,
        signed, along t), "orbit_alpha_rad" (ball angles on the orbit at psi = 0),
        "shooting_residual" [-] (max |P(z) - z - V s| over 1e4 x the difference steps: L for the
        rotor, 0.1 rad for the balls), "converged" (below SHOOTING_TOL; "stable" needs it),
        "method" ("floquet").
    """
    from ..physics.response import steady_orbit_start
    from ..models import SimOptions

    w = _speed(speed)
    b = system.balancer
    n = b.n_balls
    sysl = _ideal(system)
    opts = SimOptions(save_dt=-1.0, rtol=rtol, atol_scale=1e-9)

    a0 = np.asarray(alpha, float)
    z = np.concatenate([steady_orbit_start(sysl, w, a0), a0, np.zeros(n)])
    L = max(system.rotor.unbalance, b.capacity) / system.total_mass
    h = np.concatenate([[1e-4 * L] * 2, [1e-4 * L * w] * 2, [1e-5] * n, [1e-5 * w * 1e-2] * n])
    scale = np.concatenate([[L] * 2, [L * w] * 2, [1.0] * n, [w] * n])
    E0 = np.zeros((z.size, 0))
    if family:      # the phase condition and the drift act along the family's tangent at alpha_0
        from ..physics.equilibria import family_tangent

        t0 = family_tangent(sysl, a0)
        E0 = np.zeros((z.size, t0.shape[1]))
        E0[4:4 + n] = t0
    d = E0.shape[1]
    s = np.zeros(d)
    res = np.inf
    for _ in range(max(int(iters), 16) if family else int(iters)):
        P0 = _period_map(sysl, w, z, opts)
        M = _monodromy(sysl, w, z, h, opts)
        V = _slow_basis(M, E0, scale) if d else E0
        G = P0 - z - V @ s
        res = float(np.max(np.abs(G / np.maximum(h * 1e4, 1e-300))))
        J = np.zeros((z.size + d, z.size + d))
        J[:z.size, :z.size] = M - np.eye(z.size)
        J[:z.size, z.size:] = -V
        J[z.size:, :z.size] = E0.T
        rhs = -np.concatenate([G, E0[4:4 + n].T @ (z[4:4 + n] - a0)])
        try:
            step = np.linalg.lstsq(J, rhs, rcond=1e-10)[0]
        except np.linalg.LinAlgError:   # pragma: no cover
            break
        z = z + step[:z.size]
        s = s + step[z.size:]
        if res < 1e-9:
            break
    mu, Vm = np.linalg.eig(M)
    E = None
    if family:
        from ..physics.equilibria import family_tangent

        t = family_tangent(sysl, z[4:4 + n])
        E = np.zeros((z.size, t.shape[1]))
        E[4:4 + n] = t
    out = {**_verdict(mu, Vm, E, scale), "orbit_alpha_rad": _wrap(z[4:4 + n]),
           "shooting_residual": res, "converged": res < SHOOTING_TOL, "method": "floquet"}
    if family:
        out["family_drift_rad"] = float(np.abs(s).max()) if d else 0.0
        out["family_drift_rad_per_rev"] = s
    out["stable"] = bool(out["stable"] and out["converged"])
    return out


def linearised_full(system: System, speed: float, alpha: npt.ArrayLike,
                    family: bool = False) -> dict:
    """Eigenvalues of the full model linearised about an equilibrium in the steady rotor frame.

    Valid when :func:`steady_rotor_frame` holds (isotropic suspension, no gravity: 004 eq 8-10
    at constant speed have the balls' equilibria as fixed points). The state is z = (u, v,
    alpha, u', v', alpha'); f(z) is the compiled kernel's right-hand side
    (:func:`autobalance.simulate.probe.rotor_frame_derivative`) with rolling resistance and dry
    friction off. The fixed point starts at the kinetic-static equilibrium with the rotor on its
    steady orbit (``physics.response.steady_orbit_start``) and is refined by Newton (least-norm
    steps: the family directions are singular); the Jacobian is central finite differences. The
    eigenvalues lambda give the multipliers over one revolution, mu = exp(lambda 2 pi / w),
    judged as in :func:`floquet_full`.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (steady rotor frame).
    speed : float
        Spin speed w [rad/s], > 0.
    alpha : array_like (N,)
        Equilibrium ball angles [rad].
    family : bool
        alpha lies on a balanced family: remove its N - 2 neutral directions.

    Returns
    -------
    dict
        The keys of :func:`floquet_full` ("method" = "eigenvalues", "shooting_residual" = the
        fixed point's scaled residual max |f| / (L w^2, w^2) [-]) and "eigenvalues_1_s" [1/s].
    """
    from ..physics.response import steady_orbit_start
    from ..simulate.probe import rotor_frame_derivative

    w = _speed(speed)
    if not steady_rotor_frame(system):
        raise ParameterError("system", system.name or "machine",
                             "has no steady rotor frame (anisotropic, gravity or base motion): "
                             "use floquet_full")
    sysl = _ideal(system)
    n = sysl.balancer.n_balls
    a0 = np.asarray(alpha, float)
    L, _ = _scales(system, w)
    x, y, _, _ = steady_orbit_start(sysl, w, a0)
    z = np.concatenate([[x, y], a0, np.zeros(n + 2)])
    h = np.concatenate([[1e-4 * L] * 2, [1e-5] * n, [1e-4 * L * w] * 2, [1e-7 * w] * n])
    fscale = np.concatenate([[L * w] * 2, [w] * n, [L * w * w] * 2, [w * w] * n])

    def jac(z):
        dz = np.diag(h)
        F = rotor_frame_derivative(sysl, w, np.concatenate([z + dz, z - dz]))
        return ((F[:z.size] - F[z.size:]) / (2 * h)[:, None]).T

    f = rotor_frame_derivative(sysl, w, z)
    res = float(np.max(np.abs(f / fscale)))
    for _ in range(3):
        if res < 1e-12:
            break
        z = z + np.linalg.lstsq(jac(z), -f, rcond=1e-10)[0]
        f = rotor_frame_derivative(sysl, w, z)
        res = float(np.max(np.abs(f / fscale)))
    A = jac(z)
    lam, V = np.linalg.eig(A)
    E = None
    if family:
        from ..physics.equilibria import family_tangent

        t = family_tangent(sysl, z[2:2 + n])
        E = np.zeros((z.size, t.shape[1]))
        E[2:2 + n] = t
    scale = np.concatenate([[L] * 2, [1.0] * n, [L * w] * 2, [w] * n])
    mu = np.exp(lam * TWO_PI / w)
    out = {**_verdict(mu, V, E, scale), "eigenvalues_1_s": lam, "orbit_alpha_rad": _wrap(z[2:2 + n]),
           "shooting_residual": res, "converged": res < SHOOTING_TOL, "method": "eigenvalues"}
    out["stable"] = bool(out["stable"] and out["converged"])
    return out


def full_stability(system: System, speed: float, alpha: npt.ArrayLike, family: bool = False,
                   method: str = "auto") -> dict:
    """Stability of an equilibrium in the linearised full model by the right route.

    ``auto``: :func:`linearised_full` (eigenvalues) when :func:`steady_rotor_frame` holds,
    :func:`floquet_full` (shooting + monodromy) otherwise.

    Parameters
    ----------
    system : autobalance.models.System
        The machine.
    speed : float
        Spin speed w [rad/s], > 0.
    alpha : array_like (N,)
        Equilibrium ball angles [rad].
    family : bool
        alpha lies on a balanced family (N >= 3): its neutral directions are removed.
    method : str
        "auto", "eigenvalues" or "floquet".

    Returns
    -------
    dict
        As :func:`floquet_full`.
    """
    if method not in ("auto", "eigenvalues", "floquet"):
        raise ParameterError("method", method, "must be 'auto', 'eigenvalues' or 'floquet'")
    if method == "auto":
        method = "eigenvalues" if steady_rotor_frame(system) else "floquet"
    if method == "eigenvalues":
        return linearised_full(system, speed, alpha, family=family)
    return floquet_full(system, speed, alpha, family=family)


def verify_by_simulation(system: System, speed: float, alpha: npt.ArrayLike,
                         perturbation: float = 0.05, duration: float = 20.0,
                         options: SimOptions | None = None) -> dict:
    """Run the full nonlinear model from a perturbed equilibrium and report where the balls go.

    Parameters
    ----------
    system : autobalance.models.System
        The machine (gravity, friction etc. as given).
    speed : float
        Constant spin speed w [rad/s], > 0.
    alpha : array_like (N,)
        Equilibrium ball angles [rad].
    perturbation : float
        Initial offset added to ball i: +perturbation * (-1)^i [rad], > 0.
    duration : float
        Simulated time [s], > 0.
    options : SimOptions, optional
        Default: save_dt = 2 pi / w * 4.

    Returns
    -------
    dict
        "final_alpha_rad" (mean over the last revolution), "drift_rad" (max |final - alpha|,
        wrapped), "stays" (drift < 2 x perturbation and the balls stopped moving; a
        stable-looking outcome), "final_amplitude_m".
    """
    from ..models import InitialState, SimOptions, SpeedProfile
    from ..simulate import simulate

    w = _speed(speed)
    p = _finite("perturbation", perturbation)
    dur = _finite("duration", duration)
    if p <= 0 or dur <= 0:
        raise ParameterError("perturbation" if p <= 0 else "duration",
                             perturbation if p <= 0 else duration, "must be > 0")
    a = np.asarray(alpha, float)
    n = a.size
    a0 = a + p * (-1.0) ** np.arange(n)
    opts = options or SimOptions(save_dt=TWO_PI / w / 8)
    sim = simulate(system, SpeedProfile.constant(w, dur),
                   initial=InitialState(ball_angles=tuple(a0), steady_state=True), options=opts)
    k = sim.t >= sim.t[-1] - TWO_PI / w
    fin = np.angle(np.exp(1j * sim.alpha[k]).mean(axis=0))
    drift = float(np.abs(_wrap(fin - a)).max())
    moving = float(np.abs(sim.alpha_dot[k]).mean(axis=0).max())
    return {"final_alpha_rad": fin, "drift_rad": drift,
            "stays": bool(drift < 2 * p and moving < 1e-2 * w),
            "final_amplitude_m": float(sim.amplitude[-1]), "duration_s": dur}
