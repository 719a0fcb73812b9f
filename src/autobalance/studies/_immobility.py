"""Immobility of the balls against speed for any isotropic machine (004 Fig. 8/10 generalised):
the closed form of :mod:`autobalance.physics.immobility` over (friction, damping) factors."""
from __future__ import annotations

import time
from typing import TYPE_CHECKING

import numpy as np

from ..physics.immobility import check_immobility, immobility, stick_threshold_grade
from ..physics.iso1940 import unbalance_value as grade_to_unbalance
from .common import load
from .statistics import plateau_speed

if TYPE_CHECKING:
    from collections.abc import Callable, Sequence
    from pathlib import Path

    import numpy.typing as npt
    import xarray as xr

    from ..config import Config
    from ..models import System

__all__ = ["compute_immobility", "immobility_summary", "liquid_response", "machine_grade"]

#: Magnitudes of the residual unbalance |U_t| on which the liquid's steady orbit is tabulated
#: (full, quick) [-]. Each costs one quasi-static whirl over the speeds (~0.1-0.2 s per 91
#: speeds). Measured on leblanc_003 + two 80 g balls (quick grid, 1296 configurations): 5 / 9 /
#: 17 magnitudes differ from 33 by at most 26 / 10 / 4 configurations at one speed.
LIQUID_MAGNITUDES, LIQUID_MAGNITUDES_QUICK = 33, 17


def liquid_response(system: System, speeds: npt.ArrayLike, n_mag: int = LIQUID_MAGNITUDES):
    """The steady orbit of balls at rest beside a liquid, as
    :func:`autobalance.physics.immobility.steady_deflection` takes it: the rotor with the balls'
    mass and the residual unbalance U_t (rotor and balls) and the quasi-static liquid of its
    chambers (:func:`autobalance.liquid.steady.chambers_steady_response`: a pool below a
    chamber's entrainment speed, 003 eq 6; a ring on the displaced wall above it, followed up
    the speeds). On a horizontal axis a puddle below the film's start (g/Omega^2 = R/10) and
    the planar ring above it: the whirl's orbit about the static sag, exact while the rings
    hold under gravity's offset (:func:`ring_holds`; docs/liquid/stability.md sec. 3k). The liquid
    is axisymmetric, so w(U_t) = w(|U_t|) U_t / |U_t|; w(|U_t|) is
    tabulated on ``n_mag`` magnitudes from 0 to |U| + the balls' capacity and interpolated
    linearly.

    Parameters
    ----------
    system : autobalance.models.System
        Balls beside a ``[liquid]`` section (isotropic suspension; [gravity] in the plane on a
        horizontal axis): M [kg], k [N/m], c [N*s/m], the balls' masses [kg] and capacity
        [kg*m], the chambers.
    speeds : array_like
        The increasing speeds [rad/s] the callable will be asked at.
    n_mag : int
        Magnitudes of the table [-].

    Returns
    -------
    callable
        (speed [rad/s], one of ``speeds``; U_t [kg*m], complex array) -> w [m] (rotor frame).
    """
    from ..models.liquid_balancer import G_STANDARD, VerticalRotor
    from ..liquid.steady import chambers_steady_response

    W = np.asarray(speeds, float)
    r, s, b, liq = system.rotor, system.suspension, system.balancer, system.liquid
    g = system.gravity.g if liq.axis == "horizontal" else G_STANDARD
    mags = np.linspace(0.0, abs(r.unbalance) + b.capacity, n_mag)
    ch = [(c.chamber_radius, c.chamber_height, c.inner_radius, c.volume) for c in liq.chambers]
    table = np.zeros((W.size, n_mag), complex)
    for k, D in enumerate(mags[1:], 1):
        rotor = VerticalRotor(r.mass + b.total_mass, s.kx, s.cx, float(D))
        table[:, k] = chambers_steady_response(rotor, ch, liq.density, W, g,
                                               liq.axis)["deflection_m"]

    def response(speed, Ut):
        i = int(np.argmin(np.abs(W - float(speed))))
        u = np.asarray(Ut, complex)
        a = np.abs(u)
        w = np.interp(a, mags, table[i].real) + 1j * np.interp(a, mags, table[i].imag)
        return np.where(a > 0, w * u / np.where(a > 0, a, 1.0), 0j)

    return response


def ring_holds(system: System, speeds: npt.ArrayLike, n_conf: int,
               response: Callable) -> np.ndarray:
    """On a horizontal axis, the share [-] of the ball configurations (n_conf positions per
    ball, as :func:`autobalance.physics.immobility.immobility`) whose steady orbit keeps every
    chamber's ring intact under gravity's offset g/Omega^2 of the surface, at each speed
    [rad/s]: |w| within :func:`autobalance.liquid.synchronous.synchronous_liquid`'s linear
    range (the whirl up to which the core stays inside the outer wall and clear of the inner
    one in the worst direction; 0 below the film's start, where the liquid is a puddle). There
    the planar orbit of :func:`liquid_response` is exact; beyond it, first order in
    g/(Omega^2 R) (docs/liquid/stability.md sec. 3k).

    Parameters
    ----------
    system : autobalance.models.System
        Balls beside a horizontal-axis ``[liquid]`` section, [gravity] g [m/s^2] in the plane.
    speeds : array_like
        Spin speeds [rad/s].
    n_conf : int
        Equispaced positions per ball [-].
    response : callable
        :func:`liquid_response` over ``speeds``.
    """
    from ..liquid.synchronous import synchronous_liquid
    from ..physics.immobility import configurations, steady_deflection

    alpha = configurations(n_conf, system.balancer.n_balls)
    W = np.atleast_1d(np.asarray(speeds, float))
    out = np.empty(W.size)
    for j, w in enumerate(W):
        reach = synchronous_liquid(system.liquid, float(w), system.gravity.g).linear_range
        if reach <= 0.0:                # a puddle (or a ring broken by gravity alone)
            out[j] = 0.0
            continue
        out[j] = np.mean(np.abs(steady_deflection(system, float(w), alpha, response)) <= reach)
    return out


#: Positions per ball of the grid of balls at rest: the default, and with ``quick``.
DEFAULT_N_CONF, QUICK_N_CONF = 100, 36


def compute_immobility(base: str | Path, *, G_ini: float | None = None,
                       mu_r: Sequence[float] = (1.0,), c_r: Sequence[float] = (1.0,),
                       speeds: npt.ArrayLike | None = None, n_conf: int | None = None,
                       quick: bool = False, field: str = "n_conf",
                       speeds_hz: npt.ArrayLike | None = None) -> xr.Dataset:
    """004 Fig. 8/10: immobility [-] against speed for the mu_r x c_r factors [-] on the machine's
    rolling resistance and damping, at G_ini [mm/s]
    (closed form :func:`immobility`; no time integration). ``n_conf`` positions per ball [-];
    a grid beyond the memory or run-time limit is refused before computing (ResourceError
    naming ``field``).

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    G_ini : float or None
        Initial grade of the rotor [mm/s] at the profile's nominal speed (sets U); None: the
        machine's own unbalance (:func:`machine_grade`).
    mu_r : sequence of float
        Factors on the machine's rolling-resistance coefficient [-] (stiction follows it).
    c_r : sequence of float
        Factors on the suspension damping [-].
    speeds : array_like or None
        Spin speeds [rad/s]; None = 361 speeds (91 when ``quick``) from 0.2 x the natural
        frequency to 1.2 x the nominal speed (004 Fig. 8: 20-200 Hz).
    n_conf : int or None
        Equispaced positions per ball (None: :data:`DEFAULT_N_CONF`, 36 when ``quick``); a
        value given is used as given, also with ``quick``.
    quick : bool
        Coarser speed and configuration grids.
    field : str
        Parameter name a refused grid's error names.
    speeds_hz : array_like or None
        Deprecated: the speeds in Hz; use ``speeds`` [rad/s] (a DeprecationWarning).

    Returns
    -------
    xarray.Dataset
        immobility [-] over (mu_r, c_r, speed [Hz]); the stick threshold G_stick [mm/s] of the
        machine as given over speed; attrs f_n_hz, nominal_hz, plateau_hz [Hz] (plateau_hz
        NaN for a profile without a reduction).
    """
    import dataclasses

    import xarray as xr

    t0 = time.perf_counter()
    cfg = load(base, allow_liquid=True)
    s0 = cfg.system
    sus = s0.suspension
    if not sus.is_isotropic:
        from ..models import ParameterError

        raise ParameterError("suspension", f"kx={sus.kx:g}, ky={sus.ky:g}, cx={sus.cx:g}, "
                             f"cy={sus.cy:g}", "the immobility closed form (004 eq 1) needs an "
                             "isotropic suspension (kx = ky, cx = cy)")
    wn = cfg.spin.nominal_speed
    fn = s0.natural_frequencies[0] / (2 * np.pi)
    if speeds_hz is not None:
        import warnings

        warnings.warn("compute_immobility(speeds_hz=...) is deprecated: give speeds [rad/s]",
                      DeprecationWarning, stacklevel=2)
        speeds = 2 * np.pi * np.asarray(speeds_hz, float)
    w = (2 * np.pi * np.linspace(0.2 * fn, 1.2 * wn / (2 * np.pi), 91 if quick else 361)
         if speeds is None else np.asarray(speeds, float))
    f = w / (2 * np.pi)
    G_ini = machine_grade(cfg) if G_ini is None else float(G_ini)
    if n_conf is None:
        n_conf = QUICK_N_CONF if quick else DEFAULT_N_CONF
    check_immobility(n_conf, s0.balancer.n_balls, f.size, len(mu_r) * len(c_r), field)
    U = float(grade_to_unbalance(G_ini, s0.total_mass, wn))
    horizontal = s0.liquid is not None and s0.liquid.axis == "horizontal"
    if s0.liquid is not None:                   # beside a liquid: its steady orbit (sec. 3k)
        s0.liquid.unpartitioned("study immobility beside a liquid (its steady orbit)")
    mu0 = np.asarray(s0.balancer.rolling_resistance, float)      # each ball's own
    out = np.empty((len(mu_r), len(c_r), f.size))
    holds = np.full((len(c_r), f.size), np.nan)
    resps = {}
    for i, mr in enumerate(mu_r):
        for j, cr in enumerate(c_r):
            s = dataclasses.replace(
                s0, rotor=dataclasses.replace(s0.rotor, unbalance=U),
                suspension=dataclasses.replace(s0.suspension, cx=s0.suspension.cx * cr,
                                               cy=s0.suspension.cy * cr),
                balancer=dataclasses.replace(
                    s0.balancer, rolling_resistance=tuple(float(m) for m in mu0 * mr),
                    stiction=None))
            if s0.liquid is not None and j not in resps:     # the orbit depends on c, not mu
                resps[j] = liquid_response(s, w, LIQUID_MAGNITUDES_QUICK if quick
                                           else LIQUID_MAGNITUDES)
                if horizontal:
                    holds[j] = ring_holds(s, w, n_conf, resps[j])
            out[i, j] = immobility(s, w, n_conf, resps.get(j))
    ds = xr.Dataset({"immobility": (("mu_r", "c_r", "speed"), out,
                                    {"units": "-", "long_name": "share of immobile configurations"}),
                     "G_stick": ("speed", stick_threshold_grade(s0, w, wn)
                                 if s0.liquid is None else np.full(f.size, np.nan),
                                 {"units": "mm/s", "long_name": "stick threshold G* (mu_r = c_r = 1)"})},
                    coords={"mu_r": list(mu_r), "c_r": list(c_r),
                            "speed": ("speed", f, {"units": "Hz"})})
    if horizontal:
        ds["ring_holds"] = (("c_r", "speed"), holds,
                            {"units": "-", "long_name": "share of configurations whose orbit "
                             "keeps the rings intact under gravity's offset (there the orbit is "
                             "exact; elsewhere first order in g/(Omega^2 R))"})
    ds.attrs.update({"study": "immobility", "G_ini": float(G_ini), "n_conf": n_conf,
                     "f_n_hz": fn, "nominal_hz": wn / (2 * np.pi), "plateau_hz": _plateau_hz(cfg.spin),
                     "method": "closed form |Im(w e^-i alpha)| <= mu R (004 eq 1), checked "
                               "against the kernel's stuck-ball friction"
                               + ("; w: the steady orbit with the quasi-static liquid"
                                  if s0.liquid is not None else "")
                               + (" (planar: gravity's offset g/Omega^2 of its surface left "
                                  "out; in-plane gravity on the balls kept)" if horizontal
                                  else ""),
                     "wall_s": time.perf_counter() - t0})
    return ds


def machine_grade(cfg: Config) -> float:
    """The ISO 1940 grade [mm/s] of the machine's own rotor unbalance at its profile's nominal
    speed (ISO 1940-1: G = e Omega, :func:`autobalance.physics.iso1940.grade_value`): the
    default initial grade of the immobility study.

    Parameters
    ----------
    cfg : Config
        The machine (its rotor unbalance [kg m], total mass [kg] and nominal speed [rad/s]).
    """
    from ..physics.iso1940 import grade_value

    s = cfg.system
    return float(grade_value(s.rotor.unbalance, s.total_mass, cfg.spin.nominal_speed))


def _plateau_hz(spin) -> float:
    """The plateau [Hz] of a temporary-speed-reduction profile, else NaN."""
    return plateau_speed(spin) / (2 * np.pi) if getattr(spin, "name", "") == "tsr" else float("nan")


def immobility_summary(ds: xr.Dataset, nominal_speed: float) -> dict:
    """The answer of a :func:`compute_immobility` map, JSON-ready: the immobility and the stick
    threshold over speed, the least immobility of the case mu_r = c_r = 1 (or the first) and
    where, and the stick threshold at the nominal speed.

    Parameters
    ----------
    ds : xarray.Dataset
        A :func:`compute_immobility` result.
    nominal_speed : float
        The profile's nominal speed [rad/s].

    Returns
    -------
    dict
        G_ini_mm_s, speeds_rad_s, immobility (of the case read), stick_threshold_grade_G_mm_s,
        mu_r, c_r, immobility_by_case, least_immobility [-], least_immobility_speed_rad_s,
        natural_frequency_rad_s, nominal_speed_rad_s, stick_threshold_at_nominal_grade_G_mm_s,
        and ring_holds beside a liquid on a horizontal axis.
    """
    mus, cs = list(ds["mu_r"].values), list(ds["c_r"].values)
    mu, c = (1.0 if 1.0 in mus else mus[0]), (1.0 if 1.0 in cs else cs[0])
    w = 2 * np.pi * ds["speed"].values
    imm = ds["immobility"].sel(mu_r=mu, c_r=c).values
    k = int(np.argmin(imm))
    out = {"G_ini_mm_s": float(ds.attrs["G_ini"]), "speeds_rad_s": w, "immobility": imm,
           "stick_threshold_grade_G_mm_s": ds["G_stick"].values,
           "mu_r": [float(x) for x in mus], "c_r": [float(x) for x in cs],
           "immobility_by_case": ds["immobility"].values,
           "least_immobility": float(imm[k]), "least_immobility_speed_rad_s": float(w[k]),
           "natural_frequency_rad_s": 2 * np.pi * float(ds.attrs["f_n_hz"]),
           "nominal_speed_rad_s": float(nominal_speed),
           "stick_threshold_at_nominal_grade_G_mm_s": float(np.interp(
               nominal_speed, w, ds["G_stick"].values))}
    if "ring_holds" in ds:          # beside a liquid on a horizontal axis
        out["ring_holds"] = ds["ring_holds"].sel(c_r=c).values
    return out
