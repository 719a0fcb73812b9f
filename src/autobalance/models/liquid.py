"""The ``[liquid]`` section of a System: a Leblanc liquid balancer, flat and in SI.

The liquid analyses (:mod:`autobalance.liquid`) take the composite
:class:`autobalance.liquid.LiquidBalancer` (chamber + liquid + fill); ``LiquidBalancer.of``
builds it from this section. docs/liquid.md gives the model and the sources of the defaults.
"""
from __future__ import annotations

import math
from dataclasses import dataclass

from ._validate import ParameterError, count, nonneg, positive

#: Directions of the rotation axis: "vertical" (003's bench: gravity along the axis, the free
#: surface a paraboloid) or "horizontal" (a washer's Leblanc ring: gravity in the plane).
AXES = ("vertical", "horizontal")
#: Most radial partitions of a chamber [-] (each compartment keeps >= 4 film cells of 256).
MAX_PARTITIONS = 64


@dataclass(frozen=True)
class LiquidDevice:
    """A closed cylindrical or annular chamber, coaxial with the rotor, partly filled with a
    liquid (003 Fig. 4; 001 Fig. 1), with optional radial partitions. Several concentric
    chambers in one machine are not modelled yet (docs/liquid.md sec. 3e): one chamber of such a
    device is an annulus (``inner_radius``).

    Parameters
    ----------
    chamber_radius : float
        Outer (wall) radius R [m] (003 bench: 0.1, 0.15, 0.2 m).
    chamber_height : float
        Inner height h [m] (003 bench: 0.05 m).
    volume : float
        Liquid volume V [m^3], 0 < V < pi R^2 h.
    density : float
        Liquid density rho [kg/m^3] (001: 670-1650 kg/m^3; default water).
    kinematic_viscosity : float
        nu [m^2/s] (001: 1.01e-6-97e-6 m^2/s; default water at 20 C, 003 sec. 4.2).
    partitions : int
        Equally spaced radial walls dividing the ring into compartments [-]: 0 (none) or 2-64.
    friction_arc : float
        Arc xi the gathered liquid covers along the wall, for 001's friction force (001 eq
        5-6 leave it open; default pi, half the wall) [rad].
    axis : str
        Direction of the rotation axis, one of :data:`AXES`.
    inner_radius : float
        Inner wall radius r_i [m], 0 <= r_i < R (0: a cylinder; 003's concentric chambers: the
        next chamber's radius).
    """

    chamber_radius: float
    chamber_height: float
    volume: float
    density: float = 1000.0
    kinematic_viscosity: float = 1.01e-6
    partitions: int = 0
    friction_arc: float = math.pi
    axis: str = "vertical"
    inner_radius: float = 0.0

    def __post_init__(self):
        R = positive("liquid.chamber_radius", self.chamber_radius)
        positive("liquid.chamber_height", self.chamber_height)
        if nonneg("liquid.inner_radius", self.inner_radius) >= R:
            raise ParameterError("liquid.inner_radius", self.inner_radius,
                                 f"must be >= 0 and < chamber_radius {R!r} m")
        v = positive("liquid.volume", self.volume)
        if v >= self.chamber_volume:
            raise ParameterError("liquid.volume", self.volume, "must be < the chamber volume "
                                 f"pi (R^2 - r_i^2) h = {self.chamber_volume:.6g} m^3 "
                                 f"({self.chamber_volume * 1e6:.6g} ml)")
        positive("liquid.density", self.density)
        positive("liquid.kinematic_viscosity", self.kinematic_viscosity)
        parts = count("liquid.partitions", self.partitions, 0)
        if parts == 1 or parts > MAX_PARTITIONS:
            raise ParameterError("liquid.partitions", self.partitions,
                                 f"must be 0 (none) or an integer in 2..{MAX_PARTITIONS}")
        object.__setattr__(self, "partitions", parts)
        a = positive("liquid.friction_arc", self.friction_arc)
        if a > 2 * math.pi * (1 + 1e-12):
            raise ParameterError("liquid.friction_arc", self.friction_arc, "must be in (0, 2 pi] rad")
        if self.axis not in AXES:
            raise ParameterError("liquid.axis", self.axis, f"must be one of {list(AXES)}")

    @property
    def chamber_volume(self) -> float:
        """Inner volume pi (R^2 - r_i^2) h [m^3]."""
        return math.pi * (self.chamber_radius ** 2 - self.inner_radius ** 2) * self.chamber_height

    @property
    def mass(self) -> float:
        """Liquid mass rho V [kg]."""
        return self.density * self.volume

    @property
    def capacity(self) -> float:
        """Unbalance capacity rho V R [kg*m]: all liquid gathered at the wall (003 sec. 5.3)."""
        return self.mass * self.chamber_radius
