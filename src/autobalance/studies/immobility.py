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
    from collections.abc import Sequence
    from pathlib import Path

    import numpy.typing as npt
    import xarray as xr

__all__ = ["compute_immobility"]


def compute_immobility(base: str | Path, *, G_ini: float = 20.0, mu_r: Sequence[float] = (1.0,),
                       c_r: Sequence[float] = (1.0,), speeds_hz: npt.ArrayLike | None = None,
                       n_conf: int = 100, quick: bool = False,
                       field: str = "n_conf") -> xr.Dataset:
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
    G_ini : float
        Initial grade of the rotor [mm/s] at the profile's nominal speed (sets U).
    mu_r : sequence of float
        Factors on the machine's rolling-resistance coefficient [-] (stiction follows it).
    c_r : sequence of float
        Factors on the suspension damping [-].
    speeds_hz : array_like or None
        Spin speeds [Hz]; None = 361 speeds (91 when ``quick``) from 0.2 x the natural
        frequency to 1.2 x the nominal speed (004 Fig. 8: 20-200 Hz).
    n_conf : int
        Equispaced positions per ball (36 when ``quick``).
    quick : bool
        Coarser speed and configuration grids.
    field : str
        Parameter name a refused grid's error names.

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
    cfg = load(base)
    s0 = cfg.system
    sus = s0.suspension
    if sus.kx != sus.ky or sus.cx != sus.cy:
        from ..models import ParameterError

        raise ParameterError("suspension", f"kx={sus.kx:g}, ky={sus.ky:g}, cx={sus.cx:g}, "
                             f"cy={sus.cy:g}", "the immobility closed form (004 eq 1) needs an "
                             "isotropic suspension (kx = ky, cx = cy)")
    wn = cfg.spin.nominal_speed
    fn = s0.natural_frequencies[0] / (2 * np.pi)
    f = (np.linspace(0.2 * fn, 1.2 * wn / (2 * np.pi), 91 if quick else 361)
         if speeds_hz is None else np.asarray(speeds_hz, float))
    n_conf = 36 if quick else n_conf
    check_immobility(n_conf, s0.balancer.n_balls, f.size, len(mu_r) * len(c_r), field)
    U = float(grade_to_unbalance(G_ini, s0.total_mass, wn))
    mu0 = np.asarray(s0.balancer.rolling_resistance, float)      # each ball's own
    out = np.empty((len(mu_r), len(c_r), f.size))
    for i, mr in enumerate(mu_r):
        for j, cr in enumerate(c_r):
            s = dataclasses.replace(
                s0, rotor=dataclasses.replace(s0.rotor, unbalance=U),
                suspension=dataclasses.replace(s0.suspension, cx=s0.suspension.cx * cr,
                                               cy=s0.suspension.cy * cr),
                balancer=dataclasses.replace(
                    s0.balancer, rolling_resistance=tuple(float(m) for m in mu0 * mr),
                    stiction=None))
            out[i, j] = immobility(s, 2 * np.pi * f, n_conf)
    ds = xr.Dataset({"immobility": (("mu_r", "c_r", "speed"), out,
                                    {"units": "-", "long_name": "share of immobile configurations"}),
                     "G_stick": ("speed", stick_threshold_grade(s0, 2 * np.pi * f, wn),
                                 {"units": "mm/s", "long_name": "stick threshold G* (mu_r = c_r = 1)"})},
                    coords={"mu_r": list(mu_r), "c_r": list(c_r),
                            "speed": ("speed", f, {"units": "Hz"})})
    ds.attrs.update({"study": "immobility", "G_ini": float(G_ini), "n_conf": n_conf,
                     "f_n_hz": fn, "nominal_hz": wn / (2 * np.pi), "plateau_hz": _plateau_hz(cfg.spin),
                     "method": "closed form |Im(w e^-i alpha)| <= mu R (004 eq 1), checked "
                               "against the kernel's stuck-ball friction",
                     "wall_s": time.perf_counter() - t0})
    return ds


def _plateau_hz(spin) -> float:
    """The plateau [Hz] of a temporary-speed-reduction profile, else NaN."""
    return plateau_speed(spin) / (2 * np.pi) if getattr(spin, "name", "") == "tsr" else float("nan")
