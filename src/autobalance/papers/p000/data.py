"""The data behind the 000 targets' figures as NetCDF-ready xarray Datasets, and the run dicts
the time-history figures take."""
from __future__ import annotations

import re
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["dataset", "histories", "run_dict"]


def _name(s: str) -> str:
    """A NetCDF-safe variable name."""
    return re.sub(r"[^A-Za-z0-9_]", "_", s)


def dataset(variables: dict, **attrs: object) -> xr.Dataset:
    """xarray.Dataset from {name: (dims, values, units)}; attrs: str / numbers only.

    Parameters
    ----------
    variables : dict
        Name -> (dims, values, units); names are made NetCDF-safe.
    **attrs
        Dataset attributes (other types are stored as text).
    """
    import xarray as xr

    ds = xr.Dataset({_name(k): xr.Variable(dims, np.asarray(v, dtype=float), {"units": u})
                     for k, (dims, v, u) in variables.items()})
    ds.attrs.update({k: (v if isinstance(v, (int, float, str)) else str(v)) for k, v in attrs.items()})
    return ds


def histories(runs: dict, **attrs: object) -> xr.Dataset:
    """Time histories of constant-speed or run-up runs {name: run dict}, one time axis per run.

    Parameters
    ----------
    runs : dict
        Name -> run dict with ``t_s`` [s], ``x_m``, ``y_m`` [m], ``alpha_rad`` [rad] and
        optionally ``speed_rad_s`` [rad/s].
    **attrs
        Dataset attributes.
    """
    v = {}
    for name, r in runs.items():
        tn = f"time_{_name(name)}"
        v[f"t_{name}"] = ((tn,), r["t_s"], "s")
        v[f"x_{name}"] = ((tn,), r["x_m"], "m")
        v[f"y_{name}"] = ((tn,), r["y_m"], "m")
        a = np.asarray(r["alpha_rad"])
        if a.ndim == 2 and a.shape[1]:
            v[f"alpha_{name}"] = ((tn, "ball"), a, "rad")
        if np.ndim(r.get("speed_rad_s", 0.0)) == 1:
            v[f"speed_{name}"] = ((tn,), r["speed_rad_s"], "rad/s")
    return dataset(v, **attrs)


def run_dict(d: dict, label: str, ideal: tuple[float, float] = (120.0, -120.0)) -> dict:
    """A run dict labelled for :func:`autobalance.plotting.washer.plot_time_histories`.

    Parameters
    ----------
    d : dict
        Run dict (time histories in SI).
    label : str
        Legend label.
    ideal : (float, float)
        Ideal ball angles drawn as reference lines [deg].
    """
    return {**d, "label": label, "ideal_deg": ideal}

