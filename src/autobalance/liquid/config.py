"""Liquid presets (TOML with units, in ``autobalance/liquid/presets``) -> SI model objects."""
from __future__ import annotations

import math
import tomllib
from dataclasses import dataclass, replace
from importlib import resources
from pathlib import Path

from ..config import ConfigError, parse_quantity
from .models import Chamber, Liquid, LiquidBalancer, LiquidModel, VerticalRotor

__all__ = ["Bench", "load_bench", "load_liquids", "list_liquid_presets"]


def _read(name: str) -> dict:
    p = Path(name)
    if p.suffix == ".toml" and p.exists():
        text = p.read_text()
    else:
        f = resources.files("autobalance.liquid") / "presets" / f"{name}.toml"
        if not f.is_file():
            raise ConfigError(f"preset = {name!r}: no such liquid preset or .toml file "
                              f"(known: {', '.join(list_liquid_presets())})")
        text = f.read_text()
    try:
        return tomllib.loads(text)
    except tomllib.TOMLDecodeError as e:
        raise ConfigError(f"{name}: invalid TOML ({e})") from None


def list_liquid_presets() -> list[str]:
    """Names of the packaged liquid presets."""
    d = resources.files("autobalance.liquid") / "presets"
    return sorted(p.name[:-5] for p in d.iterdir() if p.name.endswith(".toml"))


def load_liquids(name: str = "liquids_001") -> dict[str, Liquid]:
    """Liquids of a liquids preset, by name (SI).

    Parameters
    ----------
    name : str
        Preset name (``liquids_001``) or path of a TOML file.

    Returns
    -------
    dict
        Liquid name -> :class:`Liquid` (density [kg/m^3], kinematic viscosity [m^2/s]).
    """
    out = {}
    for key, sec in _read(name).items():
        out[key] = Liquid(parse_quantity(sec["density"], "density", f"{key}.density"),
                          parse_quantity(sec["kinematic_viscosity"], "kin_viscosity",
                                         f"{key}.kinematic_viscosity"), key)
    return out


@dataclass(frozen=True)
class Bench:
    """A bench preset in SI: rotor, balancer, model and the sweep values of the paper."""

    rotor: VerticalRotor
    balancer: LiquidBalancer
    model: LiquidModel
    radii: tuple
    volumes: tuple
    sweep_volumes: tuple
    video_volume: float
    omega_r: float
    omega_end: float
    duration: float

    def balancer_with(self, volume: float | None = None, radius: float | None = None,
                      liquid: Liquid | None = None) -> LiquidBalancer:
        """The bench's balancer with another fill, chamber radius (same height) or liquid.

        Parameters
        ----------
        volume : float or None
            Liquid volume V [m^3]; None keeps the preset's.
        radius : float or None
            Chamber radius R [m]; None keeps the preset's.
        liquid : Liquid or None
            Working liquid; None keeps the preset's.
        """
        bal = self.balancer
        if radius is not None:
            bal = replace(bal, chamber=Chamber(radius, bal.chamber.height))
        if liquid is not None:
            bal = replace(bal, liquid=liquid)
        return bal if volume is None else replace(bal, volume=volume)


def load_bench(name: str = "bench_003") -> Bench:
    """Load a bench preset (default 003's bench) into SI model objects.

    Parameters
    ----------
    name : str
        Preset name (``bench_003``) or path of a TOML file.

    Returns
    -------
    Bench
        Rotor, balancer, model and the sweep values of the paper, in SI.
    """
    d = _read(name)
    q = parse_quantity
    r, ch, lq, fl, md, ru = (d[k] for k in ("rotor", "chamber", "liquid", "fill", "model",
                                            "run_up"))
    chamber = Chamber(q(ch["radius"], "length", "chamber.radius"),
                      q(ch["height"], "length", "chamber.height"))
    liquid = Liquid(q(lq["density"], "density", "liquid.density"),
                    q(lq["kinematic_viscosity"], "kin_viscosity", "liquid.kinematic_viscosity"),
                    lq.get("name", "liquid"))
    V = q(fl["volume"], "volume", "fill.volume")
    bal = LiquidBalancer(chamber, liquid, V, math.degrees(q(fl["arc"], "angle", "fill.arc")))
    M = q(r["mass"], "mass", "rotor.mass")
    wr = q(r["resonance"], "speed", "rotor.resonance")
    k = (M + bal.mass) * wr * wr
    zeta = q(r["damping_ratio"], "ratio", "rotor.damping_ratio")
    rotor = VerticalRotor(M, k, 2.0 * zeta * math.sqrt(k * (M + bal.mass)),
                          q(r["unbalance"], "unbalance", "rotor.unbalance"))
    model = LiquidModel(md["placement"], float(md["engagement_ratio"]),
                        q(md["lag_time"], "time", "model.lag_time"), q(md["g"], "acceleration",
                                                                        "model.g"))
    step = q(fl["sweep_step"], "volume", "fill.sweep_step")
    vmax = q(fl["sweep_max"], "volume", "fill.sweep_max")
    n = int(round(vmax / step))
    return Bench(rotor, bal, model,
                 tuple(q(x, "length", "chamber.radii") for x in ch["radii"]),
                 tuple(q(x, "volume", "fill.volumes") for x in fl["volumes"]),
                 tuple(step * i for i in range(1, n + 1)),
                 q(fl["video_volume"], "volume", "fill.video_volume"), wr,
                 q(ru["omega_end"], "speed", "run_up.omega_end"),
                 q(ru["duration"], "time", "run_up.duration"))
