"""Strict-JSON copies of results: the one sanitiser used by the command line's ``--json`` output
and by the reproduction report (``report.json``, NetCDF attributes).

This module sits below both (it imports nothing from autobalance), so the library never has to
import the command-line interface to write JSON.
"""
from __future__ import annotations

import math
from pathlib import Path
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import xarray as xr

__all__ = ["netcdf_safe", "to_jsonable"]


def to_jsonable(obj: Any) -> Any:
    """Return a copy of ``obj`` that ``json.dumps(..., allow_nan=False)`` accepts.

    Dicts are copied with ``str`` keys, lists and tuples become lists, numpy arrays and scalars
    become Python lists and numbers, NaN and +-inf become ``None``, :class:`~pathlib.Path` objects
    become strings and any other object its ``str()``. Values keep their units (SI throughout
    the package); nothing is rounded.

    Parameters
    ----------
    obj : Any
        A (nested) result: dicts, lists, tuples, numpy arrays or scalars, floats, ints, bools,
        strings, paths or None.

    Returns
    -------
    Any
        The JSON-able copy (``obj`` itself is not modified).

    Examples
    --------
    >>> import numpy as np
    >>> to_jsonable({"speed_rad_s": np.array([1.0, np.nan]), 2: (np.int64(3), float("inf"))})
    {'speed_rad_s': [1.0, None], '2': [3, None]}
    """
    if isinstance(obj, dict):
        return {str(k): to_jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [to_jsonable(v) for v in obj]
    if hasattr(obj, "tolist") and not isinstance(obj, (str, bytes)):
        return to_jsonable(obj.tolist())
    if isinstance(obj, float):
        return obj if math.isfinite(obj) else None
    if isinstance(obj, (str, int, bool)) or obj is None:
        return obj
    if isinstance(obj, Path):
        return str(obj)
    if hasattr(obj, "item"):
        return to_jsonable(obj.item())
    return str(obj)


def netcdf_safe(ds: xr.Dataset) -> xr.Dataset:
    """A copy of an xarray Dataset that NetCDF accepts: list, tuple, dict and bool attributes
    become JSON text (:func:`to_jsonable`), None attributes are dropped and object-typed
    variables and coordinates become strings.

    Parameters
    ----------
    ds : xarray.Dataset
        Any result dataset.

    Returns
    -------
    xarray.Dataset
        The copy (``ds`` is not changed).
    """
    import json

    def safe(attrs: dict) -> dict:
        return {k: (json.dumps(to_jsonable(v)) if isinstance(v, (list, tuple, dict, bool)) else v)
                for k, v in attrs.items() if v is not None}

    clean = ds.copy()
    clean.attrs = safe(ds.attrs)
    for name in list(clean.variables):
        var = clean[name]
        var.attrs = safe(var.attrs)
        if var.dtype == object:
            clean = clean.assign({name: var.astype(str)}) if name in clean.data_vars else \
                clean.assign_coords({name: var.astype(str)})
    return clean
