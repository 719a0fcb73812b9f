"""001's kinetostatic laws (eq 1, 3, 6) against the liquid from physics, on one machine
(the kinetostatic laws kept as analysis functions and compared with the dynamic results;
docs/liquid/kinetostatics.md sec. 2b).

At each speed the physical model gives the rotor's phase delta (the deflection's angle behind
the unbalance D), the liquid's moment U_l (magnitude k = |U_l|/|D|, angle alpha from D) and the
residual unbalance |D + U_l|. 001's laws are then evaluated at that delta and k: the liquid
angle alpha0 (001 eq 3, the root of eq 2), less the friction angle beta of the liquid's
viscosity (001 eq 6), and the residual ratio e_c/e = sqrt(1 + 2 k cos alpha + k^2) (001 eq 1).
Two physical models: the quasi-static liquid (:func:`autobalance.liquid.steady.
chambers_steady_response`, sec. 3b/3d) and, where asked, the wall film coupled with the rotor
(:func:`autobalance.liquid.film.coupled_run`, sec. 3c), started on the quasi-static whirl and
run until it settles.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ..models._validate import ParameterError
from .kinetostatic import alpha0, eccentricity_ratio, friction_angle
from ..models.liquid_balancer import G_STANDARD
from .steady import chambers_steady_response

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models.liquid_balancer import VerticalRotor  # noqa: F401

__all__ = ["kinetostatic_vs_physics"]


def _angle_deg(z: complex, ref: complex) -> float:
    """Angle of z from ref [deg] in (-180, 180]; NaN for z = 0."""
    return math.degrees(np.angle(z / ref)) if z != 0 else float("nan")


def kinetostatic_vs_physics(rotor: VerticalRotor, chamber: tuple[float, float, float, float],
                            density: float, viscosity: float, speeds: npt.ArrayLike, *,
                            arc: float = math.pi, g: float = G_STANDARD,
                            settle_time: float = 0.0, n_cells: int = 256) -> dict:
    """001's liquid angle, friction angle and residual against the physical liquid of one
    vertical chamber (module docstring).

    Parameters
    ----------
    rotor : VerticalRotor
        M [kg] (without the liquid), k [N/m], c [N*s/m], D [kg*m].
    chamber : (float, float, float, float)
        R [m], h [m], r_i [m], V [m^3].
    density : float
        rho [kg/m^3].
    viscosity : float
        nu [m^2/s] (001 eq 5-6 take mu = rho nu).
    speeds : array_like
        Increasing speeds [rad/s], > 0.
    arc : float
        The gathered liquid's arc xi [rad] of 001 eq 5 (001 gives none; our default pi).
    g : float
        Gravity along the axis [m/s^2] (the entrainment speed of 003 eq 6).
    settle_time : float
        > 0: also run the coupled film from the quasi-static whirl for this long [s] at each
        speed where the liquid is a ring, and read its last revolution's mean moment.
    n_cells : int
        Film cells of those runs [-].

    Returns
    -------
    dict
        Arrays over the speeds: omega_rad_s; delta_deg (physical phase of the deflection behind
        D, quasi-static); k (|U_l|/|D|); alpha_deg (the quasi-static liquid's angle from D);
        deflection_angle_deg (the deflection's angle from D: the classical law's liquid
        angle); alpha0_deg (001 eq 3 at |delta|, k, on the deflection's side of D; NaN where
        eq 2 has no root, k < sin delta); beta_deg (001 eq 6); alpha_001_deg (alpha0 - beta in
        magnitude, same side); ec_over_e (|D + U_l|/|D|, physical) and ec_over_e_001 (001 eq 1
        at k and alpha0 - beta); with ``settle_time``
        also alpha_film_deg, k_film and delta_film_deg (the coupled film's, NaN where not run).

    Raises
    ------
    ParameterError
        A rotor without unbalance: 001's ratio k and every angle are taken from D.
    """
    D = complex(rotor.unbalance)
    if D == 0:
        raise ParameterError("rotor.unbalance", rotor.unbalance, "must be != 0 for 001's laws "
                             "(k = |U_l|/|D| and every angle are taken from D)")
    R, H, ri, V = chamber
    ws = np.asarray(speeds, float)
    st = chambers_steady_response(rotor, [chamber], density, ws, g)
    w = np.asarray(st["deflection_m"], complex)
    U = np.asarray(st["liquid_unbalance_kg_m"], float) * np.exp(
        1j * np.radians(np.nan_to_num(np.asarray(st["liquid_angle_deg"], float)))) * D / abs(D)
    delta = np.array([-_angle_deg(x, D) for x in w])
    k = np.abs(U) / abs(D)
    alpha = np.array([_angle_deg(u, D) for u in U])
    d = np.radians(np.abs(delta))
    root = k >= np.sin(d)                      # 001 eq 2 has a root (alpha0 of eq 3)
    with np.errstate(invalid="ignore", divide="ignore"):
        a0 = np.where(root & (k > 0), np.degrees(alpha0(d, np.where(k > 0, k, 1.0))), np.nan)
    beta = np.degrees(friction_angle(density * viscosity, R, arc, density * V, ws))
    side = np.where(delta < 0, 1.0, -1.0)      # 001's angles on the deflection's side of D
    a0, a001 = side * a0, side * (a0 - beta)
    out = {"omega_rad_s": ws, "delta_deg": delta, "k": k, "alpha_deg": alpha,
           "deflection_angle_deg": -delta, "alpha0_deg": a0, "beta_deg": beta,
           "alpha_001_deg": a001, "ec_over_e": np.abs(D + U) / abs(D),
           "ec_over_e_001": eccentricity_ratio(k, np.radians(a001))}
    if settle_time > 0:
        out.update(_film_angles(rotor, chamber, density, viscosity, ws, w, U, settle_time,
                                n_cells))
    return out


def _film_angles(rotor, chamber, density, viscosity, ws, w, U, settle_time, n_cells):
    """The coupled film's liquid angle, k and phase at each speed where the quasi-static liquid
    is a ring (U != 0), from the quasi-static whirl; its last revolution's means."""
    from .film import coupled_run

    R, H, _, V = chamber
    D = complex(rotor.unbalance)
    n = ws.size
    a, kk, dl = np.full(n, np.nan), np.full(n, np.nan), np.full(n, np.nan)
    for i in range(n):
        if U[i] == 0:
            continue
        T = 2 * math.pi / ws[i]
        r = coupled_run(rotor, R, H, V, float(ws[i]), settle_time, density=density,
                        viscosity=viscosity, n_cells=n_cells, deflection=complex(w[i]),
                        save_dt=T / 32)
        last = r.t >= r.t[-1] - T
        Um, wm = r.unbalance[last].mean(), r.deflection[last].mean()
        a[i], kk[i], dl[i] = _angle_deg(Um, D), abs(Um) / abs(D), -_angle_deg(wm, D)
    return {"alpha_film_deg": a, "k_film": kk, "delta_film_deg": dl}
