"""The synchronous whirl of a rotor with a Leblanc balancer whose liquid sits quasi-statically
in the displaced chamber: no calibrated engagement, no lumped capacity.

A Jeffcott rotor (mass M, stiffness k, damping c, unbalance D along the rotor frame's x axis)
carries a chamber with liquid of mass m_l = rho V. In steady synchronous whirl at Omega the
deflection w (rotor frame) is constant and the liquid is in the rigid rotation of
:func:`autobalance.liquid.quasistatic.quasi_static`: its pull on the rotor is
Omega^2 (m_l w + U_l(w)) (the liquid translating with the chamber plus its first moment about
the chamber centre). The rotor's balance in the rotor frame (004 eq 8-9 with all rates zero;
textbook Jeffcott) is then

    G(w) = (k - (M + m_l) Omega^2 + i c Omega) w - Omega^2 (D + U_l(w)) = 0,

a nonlinear equation in w because the liquid gathers differently as the deflection grows (ring,
then crescent). While the ring is intact U_l = rho (V_c - V) w, so w = Omega^2 D / (k -
(M + rho V_c) Omega^2 + i c Omega): the liquid adds the mass of a *full* chamber and balances
nothing (:func:`ring_response`). It balances only once the film breaks, where U_l bends away from
the deflection's proportion. The equation has several roots near resonance; :func:`response_curve`
follows them up and down in speed. Validity: the liquid must turn with the rotor (003's mode 4,
Omega above the entrainment speed, liquid/free_surface.py) and the whirl must be steady; the
stability of these states is not decided here (partly filled rotors can whirl asynchronously
above resonance: Kollmann 1962; Ehrich 1992).
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from scipy.optimize import fsolve

from ..models._validate import ParameterError, positive
from ..models.liquid_balancer import G_STANDARD, LiquidBalancer, VerticalRotor
from .quasistatic import quasi_static

if TYPE_CHECKING:
    from collections.abc import Sequence

    import numpy.typing as npt

__all__ = ["GRAVITY_OFFSET_MAX", "chambers_fill_sweep", "chambers_steady_response",
           "increasing_speeds",
           "physical_fill_sweep", "physical_steady_response", "pool_response", "response_curve",
           "ring_response", "start_speed", "steady_amplitude", "synchronous_deflection"]

#: Largest offset of the potential's centre g/Omega^2 by in-plane gravity, as a fraction of R,
#: for the liquid models on a horizontal axis (first order in g/(Omega^2 R), core/shallow_water.py)
#: [-]; our criterion.
GRAVITY_OFFSET_MAX = 0.1


def increasing_speeds(speeds: npt.ArrayLike) -> np.ndarray:
    """The speed grid of the liquid analyses, checked: one line naming ``speeds`` unless it is
    a non-empty 1-D array of increasing speeds > 0 [rad/s].

    Parameters
    ----------
    speeds : array_like
        Speeds [rad/s].

    Returns
    -------
    ndarray of float
    """
    w = np.asarray(speeds, float)
    if w.ndim != 1 or w.size < 1 or np.any(~np.isfinite(w)) or np.any(w <= 0) \
            or np.any(np.diff(w) <= 0):
        raise ParameterError("speeds", [float(x) for x in np.atleast_1d(w).ravel()[:8]],
                             "must be increasing speeds > 0 [rad/s]")
    return w


def start_speed(volume: float, radius: float, height: float, g: float = G_STANDARD, *,
                axis: str = "vertical", inner_radius: float = 0.0) -> float:
    """Speed from which the liquid is a ring on the wall and the ring models hold [rad/s]: on a
    vertical axis the entrainment speed omega_0 (003 eq 6, :func:`.free_surface.
    entrainment_speed`); on a horizontal one sqrt(g / (f R)), f = :data:`GRAVITY_OFFSET_MAX`,
    where gravity's offset g/Omega^2 of the centrifugal potential is f R (our criterion: the
    models are first order in it). Below it the liquid is a pool (vertical) or a puddle held by
    gravity (horizontal): a mass that translates with the chamber and balances nothing.

    Parameters
    ----------
    volume : float
        Liquid volume V [m^3].
    radius, height : float
        Chamber R, h [m].
    g : float
        Gravity [m/s^2]: along a vertical axis, in the plane of a horizontal one.
    axis : str
        "vertical" or "horizontal".
    inner_radius : float
        Inner wall r_i [m] (0: a cylinder).
    """
    if axis == "horizontal":
        return math.sqrt(positive("gravity.g", g) / (GRAVITY_OFFSET_MAX * radius))
    from .free_surface import entrainment_speed

    return entrainment_speed(volume, radius, height, g, inner_radius=inner_radius)


def _G(w, rotor, Wsp, chambers, density, g, axis, pool_mass):
    """G(w) of the module docstring summed over the chambers (R, H, r_i, V) whose liquid is a
    ring; ``pool_mass`` [kg] is liquid below its start speed, a mass without unbalance."""
    mass, unb = pool_mass, 0j
    for R, H, ri, V in chambers:
        q = quasi_static(R, H, V, density, Wsp, w, inner_radius=ri, g=g, axis=axis)
        mass += q.mass
        unb += q.unbalance
    dyn = rotor.stiffness - (rotor.mass + mass) * Wsp ** 2 + 1j * rotor.damping * Wsp
    return dyn * w - Wsp ** 2 * (rotor.unbalance + unb)


def ring_response(rotor: VerticalRotor, chamber_volume: float, volume: float, density: float,
                  speed: float) -> complex:
    """Deflection [m] while the liquid is an intact ring: Omega^2 D / (k - (M + rho V_c)
    Omega^2 + i c Omega) (module docstring; a full chamber's mass, no balancing).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    chamber_volume : float
        V_c [m^3] of the outer wall's cylinder.
    volume : float
        Liquid volume V [m^3].
    density : float
        rho [kg/m^3].
    speed : float
        Omega [rad/s].
    """
    return complex(pool_response(rotor, chamber_volume, density, speed))


def synchronous_deflection(rotor: VerticalRotor, radius: float | Sequence[float],
                           height: float | Sequence[float], volume: float | Sequence[float],
                           density: float, speed: float, *,
                           inner_radius: float | Sequence[float] = 0.0, g: float = G_STANDARD,
                           axis: str = "vertical", guess: complex | None = None,
                           pool_mass: float = 0.0) -> complex:
    """A root w [m] of G(w) = 0 (module docstring) near ``guess``; with several concentric
    chambers on the rotor (sequences of R, h, V, r_i) their liquids' masses and moments add up
    in G, every chamber at the same deflection.

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    radius, height : float or sequence
        Chamber R, h [m] (a sequence: one chamber each; a scalar key holds for every chamber).
    volume : float or sequence
        Liquid volume V [m^3].
    density : float
        rho [kg/m^3].
    speed : float
        Omega [rad/s], > 0.
    inner_radius : float or sequence
        Inner wall r_i [m].
    g : float
        Gravity [m/s^2].
    axis : str
        "vertical", "horizontal" or "planar" (:func:`~autobalance.liquid.quasistatic.quasi_static`).
    guess : complex or None
        Start of the Newton iteration [m] (None: the rotor without liquid's unbalance).
    pool_mass : float
        Liquid of other chambers below their start speed (:func:`pool_response`): a mass that
        translates with the chamber and balances nothing [kg].

    Returns
    -------
    complex
        w [m]; NaN if the iteration does not converge.
    """
    W = positive("speed", speed)
    cols = [np.atleast_1d(np.asarray(x, float)) for x in (radius, height, inner_radius, volume)]
    n = max(c.size for c in cols)
    if any(c.size not in (1, n) for c in cols):
        raise ParameterError("volume", [float(v) for v in cols[3]], f"needs {n} values (one "
                             "per chamber) or one scalar, as the other chamber keys")
    chambers = list(zip(*(np.broadcast_to(c, n).tolist() for c in cols)))
    if guess is None:
        m = rotor.mass + pool_mass + density * sum(c[3] for c in chambers)
        guess = W * W * rotor.unbalance / (rotor.stiffness - m * W * W + 1j * rotor.damping * W)
    scale = max(abs(guess), 1e-6 * float(np.max(cols[0])))

    def f(x):
        r = _G(complex(x[0], x[1]) * scale, rotor, W, chambers, density, g, axis, pool_mass)
        return [r.real / (rotor.stiffness * scale), r.imag / (rotor.stiffness * scale)]

    sol, info, _, _ = fsolve(f, [guess.real / scale, guess.imag / scale], full_output=True,
                               xtol=1e-12)
    w = complex(sol[0], sol[1]) * scale
    if not np.max(np.abs(info["fvec"])) <= 1e-9:         # |G| <= 1e-9 k |w|: a root
        return complex(math.nan, math.nan)
    return w


def response_curve(rotor: VerticalRotor, radius: float, height: float, volume: float,
                   density: float, speeds: npt.ArrayLike, *, inner_radius: float = 0.0,
                   g: float = G_STANDARD,
                   axis: str = "vertical") -> tuple[np.ndarray, np.ndarray]:
    """Synchronous deflections [m] over ``speeds``, followed by continuation upwards and downwards
    (two branches; they differ where the response jumps).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    radius, height : float
        Chamber R, h [m].
    volume : float
        Liquid volume V [m^3].
    density : float
        rho [kg/m^3].
    speeds : array_like
        Increasing speeds Omega [rad/s], > 0.
    inner_radius : float
        Inner wall r_i [m].
    g : float
        Gravity [m/s^2].
    axis : str
        As for :func:`synchronous_deflection`.

    Returns
    -------
    (ndarray, ndarray)
        Complex deflections [m] of the upward and the downward sweep.
    """
    w = increasing_speeds(speeds)
    kw = dict(inner_radius=inner_radius, g=g, axis=axis)

    def sweep(order):
        out = np.empty(w.size, complex)
        guess = None
        for i in order:                 # continuation: each root starts from the previous one
            out[i] = synchronous_deflection(rotor, radius, height, volume, density, w[i],
                                            guess=guess, **kw)
            guess = out[i] if np.isfinite(out[i]) else None
        return out

    return sweep(range(w.size)), sweep(range(w.size - 1, -1, -1))


def pool_response(rotor: VerticalRotor, volume: float, density: float,
                  speed: float | npt.ArrayLike) -> complex | np.ndarray:
    """Deflection [m] of the rotor carrying its liquid as a centred pool, below the entrainment
    speed (003 eq 6: the liquid is not yet a ring on the wall): a rigid mass that translates with
    the chamber and balances nothing, w = Omega^2 D / (k - (M + rho V) Omega^2 + i c Omega)
    (Jeffcott, :func:`autobalance.physics.response.dynamic_stiffness`).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    volume : float
        Liquid volume V [m^3].
    density : float
        rho [kg/m^3].
    speed : float or array_like
        Omega [rad/s].
    """
    from ..physics.response import dynamic_stiffness

    W = np.asarray(speed, float)
    return W * W * rotor.unbalance / dynamic_stiffness(rotor.mass + density * volume,
                                                       rotor.stiffness, rotor.damping, W)


def physical_steady_response(rotor: VerticalRotor, bal: LiquidBalancer, speeds: npt.ArrayLike,
                             g: float = G_STANDARD) -> dict:
    """The bench's steady whirl over ``speeds`` with the quasi-static liquid of one chamber
    (:func:`chambers_steady_response` with the balancer's chamber).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    bal : LiquidBalancer
        Chamber (R, h [m]), liquid (rho [kg/m^3]) and volume V [m^3].
    speeds : array_like
        Increasing speeds [rad/s], > 0.
    g : float
        Gravity [m/s^2].

    Returns
    -------
    dict
        As :func:`chambers_steady_response`.
    """
    c = bal.chamber
    return chambers_steady_response(rotor, [(c.radius, c.height, c.inner_radius, bal.volume)],
                                    bal.liquid.density, speeds, g)


def _split(chambers, omega, g, axis):
    """The chambers (R, h, r_i, V) whose liquid is a ring at ``omega`` (at or above its
    :func:`start_speed`) and the mass [kg per kg/m^3] of the others' (a pool): (ring, V_pool)."""
    ring = [c for c in chambers if omega >= start_speed(c[3], c[0], c[1], g, axis=axis,
                                                        inner_radius=c[2])]
    return ring, sum(c[3] for c in chambers) - sum(c[3] for c in ring)


def chambers_steady_response(rotor: VerticalRotor,
                             chambers: Sequence[tuple[float, float, float, float]],
                             density: float, speeds: npt.ArrayLike,
                             g: float = G_STANDARD, axis: str = "vertical") -> dict:
    """A rotor's steady whirl over ``speeds`` with the quasi-static liquid of one or
    more concentric chambers (:func:`synchronous_deflection`, followed upwards in speed from
    root to root as :func:`response_curve`), in the keys of
    :func:`autobalance.liquid.steady_response` (the lumped model), so that the CLI and the
    figures take either. A chamber below its start speed (:func:`start_speed`: 003 eq 6's
    entrainment speed on a vertical axis) holds a centred pool, or a puddle held by gravity on
    a horizontal axis: a mass without unbalance (:func:`pool_response` if every chamber does;
    the liquid's angle is then NaN). On a horizontal axis the ring is the planar quasi-static
    liquid, as :func:`steady_amplitude`'s: gravity's offset g/Omega^2 of the surface (below
    R/10 there) is left out. While the rings stay intact that is exact for the whirl (the
    core's moment is linear in the chamber's offset and gravity's part stands still in the
    inertial frame, :mod:`.synchronous`); once they break it is first order in g/(Omega^2 R).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    chambers : sequence of (float, float, float, float)
        Per chamber (R [m], h [m], r_i [m], V [m^3]).
    density : float
        rho [kg/m^3].
    speeds : array_like
        Increasing speeds [rad/s], > 0.
    g : float
        Gravity [m/s^2] (along a vertical axis, in the plane of a horizontal one).
    axis : str
        "vertical" or "horizontal".

    Returns
    -------
    dict
        omega_rad_s, amplitude_m, amplitude_dry_m (empty chambers), efficiency [-],
        deflection_m (complex, rotor frame), liquid_angle_deg (of U_l from D) [deg],
        liquid_unbalance_kg_m (summed over the chambers), phase_deg (of w from D).
    """
    if axis not in ("vertical", "horizontal"):
        raise ParameterError("axis", axis, "must be 'vertical' or 'horizontal'")
    qs_axis = "planar" if axis == "horizontal" else "vertical"
    om = increasing_speeds(speeds)
    w = np.full(om.size, complex(math.nan, math.nan))
    U = np.zeros(om.size, complex)
    ok = np.zeros(om.size, bool)
    guess = None
    for i, W in enumerate(om):
        ring, v_pool = _split(chambers, W, g, axis)
        if not ring:
            w[i] = pool_response(rotor, v_pool, density, W)
            guess = None
            continue
        ok[i] = True
        R, h, ri, V = (list(x) for x in zip(*ring))
        w[i] = synchronous_deflection(rotor, R, h, V, density, W, inner_radius=ri, g=g,
                                      axis=qs_axis, guess=guess, pool_mass=density * v_pool)
        guess = w[i] if np.isfinite(w[i]) else None
        U[i] = (sum(quasi_static(*c[:2], c[3], density, W, w[i], inner_radius=c[2],
                                 g=g, axis=qs_axis).unbalance for c in ring)
                if np.isfinite(w[i]) else complex(math.nan, math.nan))
    dry = np.abs(pool_response(rotor, 0.0, density, om))        # the empty chambers
    amp = np.abs(w)
    with np.errstate(divide="ignore", invalid="ignore"):
        eff = dry / amp
    return {"omega_rad_s": om, "amplitude_m": amp, "amplitude_dry_m": dry, "efficiency": eff,
            "deflection_m": w,
            "liquid_angle_deg": np.where(ok, np.degrees(np.angle(U)), math.nan),
            "liquid_unbalance_kg_m": np.abs(U),
            "phase_deg": np.degrees(np.angle(w))}


def physical_fill_sweep(rotor: VerticalRotor, bal: LiquidBalancer, volumes: npt.ArrayLike,
                        omega: float, g: float = G_STANDARD, axis: str = "vertical") -> dict:
    """Steady amplitude [m] at one speed for several fills with the quasi-static liquid, in the
    keys of :func:`autobalance.liquid.fill_sweep` (003 Fig. 5); a fill whose start speed
    (:func:`start_speed`) is above ``omega`` is a mass without unbalance (:func:`pool_response`).
    On a horizontal axis the ring is the planar quasi-static liquid (gravity's offset of the
    potential, below R/10 there, is left out: the steady synchronous whirl exists in that limit
    only; the film model of ``simulate`` keeps it).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    bal : LiquidBalancer
        Chamber and liquid (its volume is replaced by each of ``volumes``).
    volumes : array_like
        Fill volumes [m^3], > 0 (0 is the empty chamber).
    omega : float
        Speed [rad/s].
    g : float
        Gravity [m/s^2] (along a vertical axis, in the plane of a horizontal one).
    axis : str
        "vertical" or "horizontal".

    Returns
    -------
    dict
        volume_m3, amplitude_m, efficiency, optimum_volume_m3, omega_rad_s.
    """
    c = bal.chamber
    return chambers_fill_sweep(rotor, [[(c.radius, c.height, c.inner_radius, V)]
                                       for V in np.asarray(volumes, float)],
                               bal.liquid.density, omega, g, axis)


def chambers_fill_sweep(rotor: VerticalRotor,
                        fills: Sequence[Sequence[tuple[float, float, float, float]]],
                        density: float, omega: float, g: float = G_STANDARD,
                        axis: str = "vertical") -> dict:
    """:func:`physical_fill_sweep` for one or more concentric chambers: the steady amplitude
    (:func:`steady_amplitude`) at one speed for each fill, a fill being every chamber's (R, h,
    r_i, V); its volume is the total of its chambers.

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    fills : sequence of sequence of (float, float, float, float)
        Per fill, per chamber (R [m], h [m], r_i [m], V [m^3]); a total of 0 is the empty
        chamber.
    density : float
        rho [kg/m^3].
    omega : float
        Speed [rad/s].
    g : float
        Gravity [m/s^2] (along a vertical axis, in the plane of a horizontal one).
    axis : str
        "vertical" or "horizontal".

    Returns
    -------
    dict
        volume_m3 (total), amplitude_m, efficiency, optimum_volume_m3, omega_rad_s.
    """
    vols = np.array([sum(c[3] for c in p) for p in fills], float)
    dry = float(np.abs(pool_response(rotor, 0.0, density, omega)))   # the empty chamber
    amps = np.array([dry if V <= 0 else steady_amplitude(rotor, p, density, omega, g, axis=axis)
                     for V, p in zip(vols, fills)])
    return {"volume_m3": vols, "amplitude_m": amps, "efficiency": dry / amps,
            "optimum_volume_m3": float(vols[int(np.nanargmin(amps))]), "omega_rad_s": float(omega)}


def steady_amplitude(rotor: VerticalRotor, chambers: Sequence[tuple[float, float, float, float]],
                     density: float, omega: float, g: float = G_STANDARD,
                     axis: str = "vertical") -> float:
    """Steady whirl amplitude |w| [m] at ``omega`` of a rotor with the liquid of one or more
    concentric chambers: the liquid of each chamber at or above its start speed
    (:func:`start_speed`) is the quasi-static ring (:func:`synchronous_deflection`; planar on a
    horizontal axis, as :func:`physical_fill_sweep`), the others a centred pool or a puddle held
    by gravity (a mass, no unbalance; :func:`pool_response` if no chamber has a ring).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg], k [N/m], c [N*s/m], D [kg*m].
    chambers : sequence of (float, float, float, float)
        Per chamber (R [m], h [m], r_i [m], V [m^3]), V > 0.
    density : float
        rho [kg/m^3].
    omega : float
        Speed [rad/s], > 0.
    g : float
        Gravity [m/s^2] (along a vertical axis, in the plane of a horizontal one).
    axis : str
        "vertical" or "horizontal".
    """
    if axis not in ("vertical", "horizontal"):
        raise ParameterError("axis", axis, "must be 'vertical' or 'horizontal'")
    ring, v_pool = _split(chambers, omega, g, axis)
    if not ring:
        return float(abs(pool_response(rotor, v_pool, density, omega)))
    pool = density * v_pool if len(ring) < len(chambers) else 0.0
    R, h, ri, V = (list(x) for x in zip(*ring))
    return abs(synchronous_deflection(rotor, R, h, V, density, omega, inner_radius=ri, g=g,
                                      axis="planar" if axis == "horizontal" else "vertical",
                                      pool_mass=pool))
