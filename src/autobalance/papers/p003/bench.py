"""The bench of seed 003 as the reproductions of 003 and 001 use it: the machine is the System
preset ``leblanc_003`` (rotor, suspension, ``[liquid]``, run-up profile); this module adds 003's
experimental grid (chamber radii, fills, the video fill), unit factors and the grid sizes of the
quick and full variants. The liquid analyses take the machine through one adapter
(:func:`autobalance.liquid.simulate.liquid_parts`), like any machine's.
"""
from __future__ import annotations

import functools
from dataclasses import dataclass, replace

from ...config import load_config
from ...models import ParameterError
from ...models.liquid_balancer import G_STANDARD, Chamber, Liquid, LiquidBalancer, VerticalRotor
from ...liquid.simulate import liquid_parts
from ...validation.target import Context

__all__ = ["FIG5_RATIOS", "G10", "GCM", "INNER_RADII", "ML", "OMEGA_R", "QUICK", "RADII",
           "SWEEP_VOLUMES",
           "VIDEO_VOLUME", "VOLUMES", "Bench", "bench", "grid"]

ML = 1e-6        # [m^3] per ml
GCM = 1e-5       # [kg*m] per g*cm
G10 = 10.0       # [m/s^2]: the gravity 003's printed speeds imply
#: 003's relative speeds omega/omega_r of Fig. 5 (and our choice for Fig. 6) [-].
FIG5_RATIOS = (0.6, 0.8, 1.0, 1.2)
#: 003 sec. 4.3: the bench's resonance omega_r [rad/s] (range 49-57); leblanc_003's k is set by it.
OMEGA_R = 54.0
#: 003 sec. 4.2: the three concentric chambers' radii [m], used one at a time.
RADII = (0.1, 0.15, 0.2)
#: Their inner walls [m]: our reading of "three concentric cylindrical chambers" (003 sec. 4.2):
#: each chamber's inner wall is the next smaller one's outer wall (the innermost a cylinder).
INNER_RADII = (0.0, 0.1, 0.15)
#: 003 sec. 5.2: the fills of the omega_0 estimates [m^3].
VOLUMES = (100 * ML, 200 * ML, 300 * ML)
#: 003 sec. 4.2, 5.3: 0-350 ml in dosed portions of 50 ml [m^3].
SWEEP_VOLUMES = tuple(50 * ML * i for i in range(1, 8))
#: 003 sec. 5.4: the fill of the video series (Fig. 7) [m^3].
VIDEO_VOLUME = 300 * ML

#: What ``--quick`` changes in the liquid targets.
QUICK = "coarser speed/radius grids in the figures and data; the rows are the same"


@dataclass(frozen=True)
class Bench:
    """003's bench in SI: the liquid models' rotor and balancer of the ``leblanc_003`` machine,
    gravity, and 003's experimental grid.

    Parameters
    ----------
    rotor : VerticalRotor
        Rotor on its isotropic supports (M [kg], k [N/m], c [N*s/m], D [kg*m]).
    balancer : LiquidBalancer
        The outer chamber (R = 0.2 m, inner wall 0.15 m, h = 0.05 m) with 150 ml of water.
    g : float
        Gravity along the axis [m/s^2] (standard; 003's printed speeds imply 10).
    omega_end : float
        End speed of the machine's run-up [rad/s].
    duration : float
        Duration of that run-up [s].
    """

    rotor: VerticalRotor
    balancer: LiquidBalancer
    g: float
    omega_end: float
    duration: float
    omega_r: float = OMEGA_R
    radii: tuple = RADII
    inner_radii: tuple = INNER_RADII
    volumes: tuple = VOLUMES
    sweep_volumes: tuple = SWEEP_VOLUMES
    video_volume: float = VIDEO_VOLUME

    def balancer_with(self, volume: float | None = None, radius: float | None = None,
                      liquid: Liquid | None = None) -> LiquidBalancer:
        """The bench's balancer with another fill, chamber (same height) or liquid.

        Parameters
        ----------
        volume : float or None
            Liquid volume V [m^3]; None keeps the preset's.
        radius : float or None
            Outer radius R [m] of one of the concentric chambers (:data:`RADII`; its inner
            wall from :data:`INNER_RADII`); None keeps the preset's.
        liquid : Liquid or None
            Working liquid; None keeps the preset's.
        """
        bal = self.balancer
        if radius is not None:
            inner = dict(zip(self.radii, self.inner_radii))
            if radius not in inner:
                raise ParameterError("radius", radius, f"must be one of the bench's chambers "
                                     f"{list(self.radii)} m")
            bal = replace(bal, chamber=Chamber(radius, bal.chamber.height, inner[radius]))
        if liquid is not None:
            bal = replace(bal, liquid=liquid)
        return bal if volume is None else replace(bal, volume=volume)


@functools.lru_cache(maxsize=1)
def bench() -> Bench:
    """003's bench: the ``leblanc_003`` preset (the outer chamber R = 0.2 m, r_i = 0.15 m,
    h = 0.05 m, 150 ml water, D = 3000 g*cm, omega_r = 54 1/s) with 003's grid."""
    cfg = load_config("leblanc_003")
    rotor, bal = liquid_parts(cfg.system)
    spin = cfg.spin
    return Bench(rotor, replace(bal, liquid=replace(bal.liquid, name="water")), G_STANDARD,
                 float(spin.nominal_speed), float(spin.duration))


def grid(ctx: Context, quick: int, full: int) -> int:
    """Number of grid points of a figure: ``quick`` in the quick variant, else ``full``.

    Parameters
    ----------
    ctx : Context
        Variant.
    quick, full : int
        Points in the quick and in the full variant.
    """
    return quick if ctx.quick else full
