"""The fill map of a liquid balancer (any machine with a ``[liquid]`` section): the steady whirl
over fill x speed with the liquid from physics (the quasi-static liquid in the displaced
chamber, :func:`autobalance.liquid.steady.physical_fill_sweep`; a centred pool below each
fill's entrainment speed), beside the rotor without liquid. It answers the design questions of
003 Fig. 5-6 for any machine: which fill balances at which speed, how much, and where the
resonance moves. docs/liquid.md sec. 3f.
"""
from __future__ import annotations

import time

import numpy as np

from ..models import ParameterError

__all__ = ["compute_fill_map", "fill_map_summary"]

#: Default speeds, as fractions of the natural frequency with the chamber's liquid [-].
SPEED_RATIOS = (0.3, 2.0)
#: Efficiencies within this fraction of the best count as equal [-] (above resonance the
#: physical model's efficiency is flat in the fill once the film breaks).
TIE = 0.01


def compute_fill_map(base, *, fills=None, speeds=None, quick: bool = False, sets=()):
    """Steady whirl amplitude over fill x speed for a liquid-balancer machine.

    Parameters
    ----------
    base : str, Path or Config
        The machine (a ``[liquid]`` section; its volume is replaced by each fill).
    fills : sequence of float or None
        Fills [m^3], > 0 and below the chamber volume; None: 10 fills from 0.25 to 2.5 times
        the machine's (at most 0.9 of the chamber).
    speeds : sequence of float or None
        Increasing speeds [rad/s]; None: 0.3-2.0 times the natural frequency with the machine's
        liquid as rigid mass, 36 speeds (quick) or 121.
    quick : bool
        Coarser default speed grid.
    sets : sequence of str
        Overrides "path=value" (as --set).

    Returns
    -------
    xarray.Dataset
        ``amplitude`` (fill, speed) [m], ``amplitude_without_liquid`` (speed) [m], ``efficiency``
        (fill, speed) [-] (> 1: the liquid lowers the whirl), ``entrained`` (fill, speed) (the
        speed is above the fill's entrainment speed, 003 eq 6), ``resonance`` (fill) [rad/s]
        (the speed of the largest whirl on the grid).
    """
    import xarray as xr

    from ..config import Config, load_config, replace_values
    from ..config.overrides import parse_override
    from ..liquid.free_surface import entrainment_speed
    from ..liquid.models import Chamber, Liquid, LiquidBalancer
    from ..liquid.simulate import film_rotor
    from ..liquid.steady import physical_fill_sweep, pool_response

    t0 = time.perf_counter()
    cfg = (replace_values(base, dict(parse_override(s) for s in sets)) if sets else base) \
        if isinstance(base, Config) else load_config(base, list(sets))
    s = cfg.system
    if s.liquid is None:
        raise ParameterError("liquid", None, "the fill map needs a machine with a [liquid] "
                             "section")
    if s.balancer.n_balls:
        raise ParameterError("balancer.n_balls", s.balancer.n_balls, "must be 0: the fill map "
                             "is of a liquid balancer alone")
    L = s.liquid
    if L.axis != "vertical":
        raise ParameterError("liquid.axis", L.axis, "the fill map covers a vertical axis (003's "
                             "entrainment and pool); a horizontal machine runs with simulate "
                             "or sweep (the film model with gravity)")
    if L.partitions:
        raise ParameterError("liquid.partitions", L.partitions, "must be 0 for the fill map "
                             "(the quasi-static liquid has no partitions; simulate has)")
    if s.suspension.kx != s.suspension.ky or s.suspension.cx != s.suspension.cy:
        raise ParameterError("suspension.ky", s.suspension.ky, "must equal kx (and cy cx): the "
                             "liquid model's rotor is isotropic")
    rotor = film_rotor(s)
    bal = LiquidBalancer(Chamber(L.chamber_radius, L.chamber_height),
                         Liquid(L.density, L.kinematic_viscosity), L.volume,
                         float(np.degrees(L.friction_arc)))
    V = np.asarray(np.minimum(np.linspace(0.25, 2.5, 10) * L.volume, 0.9 * L.chamber_volume)
                   if fills is None else fills, float)
    if V.ndim != 1 or V.size < 1 or np.any(V <= 0) or np.any(V >= L.chamber_volume):
        raise ParameterError("fills", [float(x) for x in np.atleast_1d(V)], f"must be volumes in (0, "
                             f"{L.chamber_volume:.4g}) m^3 (the chamber)")
    wn = np.sqrt(s.suspension.kx / s.total_mass)
    W = np.asarray(np.linspace(SPEED_RATIOS[0] * wn, SPEED_RATIOS[1] * wn, 36 if quick else 121)
                   if speeds is None else speeds, float)
    if W.ndim != 1 or W.size < 2 or np.any(W <= 0) or np.any(np.diff(W) <= 0):
        raise ParameterError("speeds", [float(x) for x in np.atleast_1d(W)], "must be >= 2 increasing "
                             "speeds > 0 [rad/s]")
    amp = np.array([physical_fill_sweep(rotor, bal, V, w)["amplitude_m"] for w in W]).T
    dry = np.abs(pool_response(rotor, 0.0, L.density, W))
    w0 = np.array([entrainment_speed(v, L.chamber_radius, L.chamber_height) for v in V])
    ds = xr.Dataset(
        {"amplitude": (("fill", "speed"), amp, {"units": "m", "long_name": "steady whirl"}),
         "amplitude_without_liquid": ("speed", dry, {"units": "m"}),
         "efficiency": (("fill", "speed"), dry[None, :] / amp,
                        {"units": "1", "long_name": "A(no liquid) / A(liquid)"}),
         "entrained": (("fill", "speed"), W[None, :] >= w0[:, None]),
         "entrainment_speed": ("fill", w0, {"units": "rad/s", "long_name": "003 eq 6"}),
         "resonance": ("fill", W[np.argmax(amp, axis=1)], {"units": "rad/s"})},
        coords={"fill": ("fill", V, {"units": "m^3"}), "speed": ("speed", W, {"units": "rad/s"})},
        attrs={"machine": cfg.name, "model": "quasi-static liquid in the displaced chamber "
               "(vertical axis); a centred pool below the entrainment speed",
               "nominal_speed_rad_s": float(cfg.spin.nominal_speed),
               "resonance_without_liquid_rad_s": float(W[np.argmax(dry)]),
               "wall_time_s": time.perf_counter() - t0})
    return ds


def fill_map_summary(ds) -> dict:
    """The fill map's answers (SI): per fill its resonance, the speeds where it balances
    (efficiency > 1) and its efficiency at the nominal speed; the fills within :data:`TIE` of
    the best efficiency at the nominal speed and the least of them (the design's fill: no more
    liquid than balances).

    Parameters
    ----------
    ds : xarray.Dataset
        :func:`compute_fill_map`'s result.

    Returns
    -------
    dict
    """
    W = ds["speed"].values
    wn = float(ds.attrs["nominal_speed_rad_s"])
    k = int(np.argmin(np.abs(W - wn)))
    fills = []
    for i, v in enumerate(ds["fill"].values):
        e = ds["efficiency"].values[i]
        helps = W[e > 1.0]
        fills.append({"fill_m3": float(v), "resonance_rad_s": float(ds["resonance"].values[i]),
                      "entrainment_speed_rad_s": float(ds["entrainment_speed"].values[i]),
                      "balances_from_rad_s": float(helps.min()) if helps.size else None,
                      "efficiency_at_nominal": float(e[k])})
    e = ds["efficiency"].values[:, k]
    good = ds["fill"].values[e >= (1 - TIE) * e.max()]
    return {"machine": ds.attrs["machine"], "nominal_speed_rad_s": wn,
            "speed_on_grid_rad_s": float(W[k]),
            "resonance_without_liquid_rad_s": ds.attrs["resonance_without_liquid_rad_s"],
            "best_efficiency_at_nominal": float(e.max()),
            "least_fill_within_tie_m3": float(good.min()),
            "fills_within_tie_m3": [float(v) for v in good], "tie": TIE,
            "fills": fills}
