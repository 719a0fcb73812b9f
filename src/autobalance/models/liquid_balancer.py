"""Liquid (Leblanc) balancer parameters as frozen dataclasses in SI, validated on construction.

Every class raises :class:`autobalance.models.ParameterError` (one line: field, value, what is
allowed) from ``__post_init__``. See docs/liquid/index.md for the sources of the defaults.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._validate import ParameterError, finite, nonneg, positive

if TYPE_CHECKING:
    import numpy.typing as npt

    from .liquid import LiquidDevice

#: Standard gravity [m/s^2] (CGPM 1901). 003's printed speeds follow from g = 10 m/s^2.
G_STANDARD = 9.80665

#: Liquid placement laws of the reduced-order dynamics (docs/liquid/models.md sec. 3).
PLACEMENT_LAWS = ("drach", "deflection")


@dataclass(frozen=True)
class Chamber:
    """Closed cylindrical or annular balancer chamber, coaxial with the rotor (003 Fig. 4).

    Parameters
    ----------
    radius : float
        Outer wall radius R [m] (003 bench: 0.1, 0.15, 0.2 m).
    height : float
        Inner height h [m] (003 bench: 0.05 m).
    inner_radius : float
        Inner wall radius r_i [m], 0 <= r_i < R (0: a cylinder).
    """

    radius: float
    height: float
    inner_radius: float = 0.0

    def __post_init__(self):
        R = positive("chamber.radius", self.radius)
        positive("chamber.height", self.height)
        if nonneg("chamber.inner_radius", self.inner_radius) >= R:
            raise ParameterError("chamber.inner_radius", self.inner_radius,
                                 f"must be >= 0 and < the radius {R!r} m")

    @property
    def volume(self) -> float:
        """Inner volume pi (R^2 - r_i^2) h [m^3]."""
        return math.pi * (self.radius ** 2 - self.inner_radius ** 2) * self.height

    def check_fill(self, volume: float, field: str = "volume") -> float:
        """Validate a liquid volume 0 < V < pi*R^2*h for this chamber; return it.

        Parameters
        ----------
        volume : float
            Liquid volume V [m^3].
        field : str
            Field name for the error message.
        """
        v = positive(field, volume)
        if v >= self.volume:
            raise ParameterError(field, volume, f"must be < the chamber volume "
                                 f"pi (R^2 - r_i^2) h = {self.volume:.6g} m^3 "
                                 f"({self.volume * 1e6:.6g} ml)")
        return v


@dataclass(frozen=True)
class Liquid:
    """Working liquid (001 sec. 3: densities 670-1650 kg/m^3, viscosities 1.01e-6-97e-6 m^2/s).

    Parameters
    ----------
    density : float
        Density rho [kg/m^3].
    kinematic_viscosity : float
        Kinematic viscosity nu [m^2/s]; must be > 0.
    name : str
        Label.
    """

    density: float
    kinematic_viscosity: float
    name: str = "liquid"

    def __post_init__(self):
        positive("liquid.density", self.density)
        positive("liquid.kinematic_viscosity", self.kinematic_viscosity)

    @property
    def dynamic_viscosity(self) -> float:
        """Dynamic viscosity mu = rho*nu [Pa*s]."""
        return self.density * self.kinematic_viscosity


WATER = Liquid(1000.0, 1.01e-6, "water")  # 003 sec. 4.2: fresh water at 20 C


@dataclass(frozen=True)
class LiquidBalancer:
    """A chamber partly filled with a liquid: the liquid analyses' view of a System's
    ``[liquid]`` section (:meth:`of`).

    Parameters
    ----------
    chamber : Chamber
        Geometry.
    liquid : Liquid
        Working liquid.
    volume : float
        Liquid volume V [m^3], 0 < V < pi*R^2*h.
    arc : float
        Arc xi [rad] the gathered liquid occupies along the wall, for the friction force of
        001 eq 5-6 (001 leaves it open; our default pi: a crescent over half the wall).
    """

    chamber: Chamber
    liquid: Liquid
    volume: float
    arc: float = math.pi

    def __post_init__(self):
        self.chamber.check_fill(self.volume, "balancer.volume")
        v = positive("balancer.arc", self.arc)
        if v > 2.0 * math.pi * (1.0 + 1e-12):
            raise ParameterError("balancer.arc", self.arc, "must be in (0, 2 pi] rad")

    @classmethod
    def of(cls, device: LiquidDevice) -> "LiquidBalancer":
        """The balancer of a System's ``[liquid]`` section.

        Parameters
        ----------
        device : autobalance.models.LiquidDevice
            The section (SI); ParameterError (one line) with partitions or several chambers,
            which the analyses taking a LiquidBalancer (one chamber's quasi-static, lumped or
            kinetostatic liquid) do not model (the film model of ``simulate`` does; the
            quasi-static liquid of several chambers is liquid/steady.chambers_steady_response).
        """
        device = device.single("this analysis (one chamber's quasi-static, lumped or "
                               "kinetostatic liquid)").unpartitioned("this analysis")
        return cls(Chamber(device.chamber_radius, device.chamber_height, device.inner_radius),
                   Liquid(device.density, device.kinematic_viscosity), device.volume,
                   device.friction_arc)

    @property
    def mass(self) -> float:
        """Liquid mass rho*V [kg]."""
        return self.liquid.density * self.volume

    @property
    def capacity(self) -> float:
        """Unbalance capacity D0_max = rho*V*R [kg*m]: all liquid gathered at the wall (003 sec. 5.3)."""
        return self.mass * self.chamber.radius


def sufficient_volume(unbalance: float, density: float, radius: float) -> float:
    """Fill V [m^3] whose capacity rho V R equals the rotor's unbalance D (k = 1: 003's
    "sufficient volume", sec. 5.3, with our capacity of :attr:`LiquidBalancer.capacity`).

    Parameters
    ----------
    unbalance : float
        Rotor unbalance D [kg*m].
    density : float
        Liquid density rho [kg/m^3].
    radius : float
        Chamber radius R [m].
    """
    return unbalance / (density * radius)


@dataclass(frozen=True)
class VerticalRotor:
    """Isotropic vertical-axis rotor on elastic supports (Jeffcott model, textbook).

    Parameters
    ----------
    mass : float
        Translating mass M without the liquid [kg].
    stiffness : float
        Support stiffness k [N/m].
    damping : float
        Viscous support damping c [N*s/m] (the "external resistance" of 001).
    unbalance : float
        Rotor unbalance D [kg*m] (003 bench: 1000-3000 g*cm).
    """

    mass: float
    stiffness: float
    damping: float
    unbalance: float

    def __post_init__(self):
        positive("rotor.mass", self.mass)
        positive("rotor.stiffness", self.stiffness)
        nonneg("rotor.damping", self.damping)
        nonneg("rotor.unbalance", self.unbalance)

    def natural_frequency(self, added_mass: float = 0.0) -> float:
        """Undamped natural frequency sqrt(k/(M + added_mass)) [rad/s].

        Parameters
        ----------
        added_mass : float
            Mass translating with the rotor, e.g. the liquid's rho V [kg].
        """
        return math.sqrt(self.stiffness / (self.mass + nonneg("added_mass", added_mass)))

    def damping_ratio(self, added_mass: float = 0.0) -> float:
        """Damping ratio c / (2 sqrt(k (M + added_mass))) [-].

        Parameters
        ----------
        added_mass : float
            Mass translating with the rotor, e.g. the liquid's rho V [kg].
        """
        return self.damping / (2.0 * math.sqrt(self.stiffness * (self.mass + added_mass)))

    def support_force(self, amplitude: float | npt.ArrayLike,
                      omega: float | npt.ArrayLike) -> np.ndarray:
        """Dynamic force on the supports |u| |k + i c omega| [N] of a synchronous whirl.

        Parameters
        ----------
        amplitude : float or array
            Whirl amplitude |u| [m].
        omega : float or array
            Rotor speed [rad/s].
        """
        return np.asarray(amplitude) * np.hypot(self.stiffness,
                                                self.damping * np.asarray(omega, float))


@dataclass(frozen=True)
class LiquidModel:
    """Choices of the reduced-order liquid dynamics (docs/liquid/models.md sec. 3 lists the
    reasons).

    Parameters
    ----------
    placement : str
        ``"drach"``: the liquid settles at 001's kinetostatic angle alpha0(delta, k) (001 eq 3)
        minus the friction angle beta (001 eq 6); ``"deflection"``: the liquid settles on the
        side of the rotor deflection (classical Thearle/centrifugal equilibrium).
    engagement_ratio : float
        omega_full / omega_0 [-] >= 1: the liquid's unbalance ramps from 0 at the entrainment
        speed omega_0 (003 eq 6) to its capacity at engagement_ratio*omega_0 (003 sec. 5.4:
        "the fluid gradually begins to be involved"; default 1.5, from 003 Fig. 7a-b).
    lag_time : float
        Relaxation time tau [s] of the liquid's angle toward its equilibrium (viscous lag).
    g : float
        Gravity [m/s^2] for the entrainment speed.
    """

    placement: str = "drach"
    engagement_ratio: float = 1.5
    lag_time: float = 0.2
    g: float = G_STANDARD

    def __post_init__(self):
        if self.placement not in PLACEMENT_LAWS:
            raise ParameterError("model.placement", self.placement,
                                 f"must be one of {', '.join(PLACEMENT_LAWS)}")
        if finite("model.engagement_ratio", self.engagement_ratio) < 1.0:
            raise ParameterError("model.engagement_ratio", self.engagement_ratio, "must be >= 1")
        positive("model.lag_time", self.lag_time)
        positive("model.g", self.g)
