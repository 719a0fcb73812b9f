"""The working liquids of seed 001 (``liquids_001.toml`` beside this module: density and
kinematic viscosity with units, each value with its source or "our choice" where 001's text was
lost), as :class:`autobalance.liquid.Liquid` objects in SI."""
from __future__ import annotations

import functools
import tomllib
from importlib import resources

from ...config import parse_quantity
from ...models.liquid_balancer import Liquid

__all__ = ["liquids_001"]


@functools.lru_cache(maxsize=1)
def _table() -> dict:
    text = (resources.files("autobalance.papers.p001") / "liquids_001.toml").read_text()
    return tomllib.loads(text)


def liquids_001() -> dict[str, Liquid]:
    """001's liquids by name (water, light_670, heavy_1650, dense_1230, dense_1370, viscous_14,
    viscous_97).

    Returns
    -------
    dict
        Liquid name -> :class:`Liquid` (density [kg/m^3], kinematic viscosity [m^2/s]).
    """
    return {key: Liquid(parse_quantity(sec["density"], "density", f"{key}.density"),
                        parse_quantity(sec["kinematic_viscosity"], "kin_viscosity",
                                       f"{key}.kinematic_viscosity"), key)
            for key, sec in _table().items()}
