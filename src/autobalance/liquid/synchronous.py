"""The liquid of a Leblanc chamber as the balls' averaged (kinetic-static) model sees it: its
moment in a synchronous whirl of the rotor, for the worst-case bound of balls beside a liquid
(:func:`autobalance.physics.worst_case.residual_bound`, ``liquid=``;
docs/liquid/balls-beside-liquid.md sec. 3l).

In a synchronous whirl the rotor frame is steady: the liquid turns rigidly about the rotation
axis while the chamber's centre is displaced by the rotor's whirl z_r. While every layer's
free-surface circle stays inside the outer wall and clear of the inner one (an intact ring),
the liquid's first moment about the chamber centre is exactly that of the missing core,
U_L = rho (pi R^2 h - V) z_r (:func:`.quasistatic.intact_ring_unbalance`; Ehrich, *Handbook of
Rotordynamics*, 1992, sec. 5; Kollmann 1962): the liquid pulls like a full chamber, an added
mass kappa = rho (pi R^2 h - V) on the rotor.

**Partitions.** With p equally spaced radial walls each compartment keeps its volume, so its
surface level shifts by the compartment's mean of Re(z_r e^{-i phi}). To first order in z_r the
moment is then kappa f(p) z_r with

    f(p) = 1 - (p/pi)^2 sin^2(pi/p)                                                   [-]

(the moment of the open ring, pi z_r per unit r_s^2 h, minus sum_k m_k e_k, e_k the integral of
e^{i phi} over compartment k: for p >= 3, sum_k Re(z e^{-i phi_k}) e^{i phi_k} = p z / 2).
f(3) = 0.316, f(4) = 1 - 8/pi^2 = 0.189, f(8) = 0.050; f -> 0 as p grows (the liquid moves with
the chamber). Two walls make the response depend on the whirl's direction (1 along them,
1 - 8/pi^2 across): not a scalar added mass, refused. The films of ``simulate`` at rest on a displaced
wall give f(p) within 1e-4 on 960 cells (6.7e-5 for p = 8; tests/test_tolerances_liquid.py).

**A horizontal axis**. Gravity in the plane moves the surface's axis by
x0 = g/Omega^2 from the rotation axis (:func:`.quasistatic.quasi_static`, "horizontal"): the
surface is the cylinder |x - x0| = r_s, pi r_s^2 h = pi R^2 h - V, through the whole height. The
core's moment is linear in the chamber's offset from x0, so the whirl's part is the same
kappa z_r; gravity's part stands still in the inertial frame (a static load, not in the
synchronous residual). The ring stays intact while |z_r| + g/Omega^2 keeps the core inside the
outer wall and clear of the inner one, in the worst relative direction.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

from ..models._validate import ParameterError, positive
from ..physics.worst_case import SyncLiquid
from ..models.liquid_balancer import G_STANDARD
from .quasistatic import intact_ring_unbalance, quasi_static
from .steady import start_speed

if TYPE_CHECKING:
    from ..models import LiquidDevice

__all__ = ["check_synchronous", "partition_factor", "synchronous_liquid"]


def partition_factor(partitions: int, field: str = "liquid.partitions") -> float:
    """f(p) = 1 - (p/pi)^2 sin^2(pi/p) [-]: the share of the open ring's synchronous moment
    that p equally spaced radial partitions leave, to first order in the whirl (module
    docstring); 1 without partitions.

    Parameters
    ----------
    partitions : int
        Radial walls p [-]: 0 or >= 3 (two walls make the response direction-dependent).
    field : str
        The config key named in the error [-] (a chamber's index with several).
    """
    p = int(partitions)
    if p != partitions or p < 0 or p in (1, 2):
        raise ParameterError(field, partitions,
                             "must be 0 or >= 3 for the synchronous liquid (two walls make its "
                             "moment depend on the whirl's direction: 1 along them, 1 - 8/pi^2 "
                             "across)")
    return 1.0 if p == 0 else 1.0 - (p / math.pi) ** 2 * math.sin(math.pi / p) ** 2


def check_synchronous(device: LiquidDevice) -> None:
    """One-line errors, before any work, for a liquid :func:`synchronous_liquid` does not take:
    two partitions.

    Parameters
    ----------
    device : autobalance.models.LiquidDevice
        The ``[liquid]`` section (partitions [-]).
    """
    many = device.n_chambers > 1
    for i, c in enumerate(device.chambers):
        partition_factor(c.partitions, f"liquid.partitions[{i}]" if many else "liquid.partitions")


def _chamber(c, speed: float, g: float) -> tuple[float, float]:
    """(kappa [kg], linear range [m]) of one chamber at ``speed``; g along a vertical axis or
    in the plane of a horizontal one."""
    R, h, ri, V = c.chamber_radius, c.chamber_height, c.inner_radius, c.volume
    f = partition_factor(c.partitions)
    kappa = f * intact_ring_unbalance(c.density, math.pi * R * R * h, V, 1.0).real
    shift = 2.0 if c.partitions else 1.0    # a compartment's surface moves by up to 2 |offset|
    if c.axis == "horizontal":
        if speed < start_speed(V, R, h, g, axis="horizontal", inner_radius=ri):
            return 0.0, 0.0               # a puddle held by gravity, not a ring: no bound
        r_s = math.sqrt(R * R - V / (math.pi * h))
        margin = min(R - r_s, r_s - ri) if ri > 0.0 else R - r_s
        return kappa, max(margin / shift - g / speed ** 2, 0.0)
    if speed < start_speed(V, R, h, g, inner_radius=ri):
        return 0.0, math.inf              # a pool: a mass moving with the chamber (003 eq 6)
    zs = quasi_static(R, h, V, c.density, speed, 0j, inner_radius=ri, g=g).surface
    a = speed * speed / (2.0 * g)
    r_top = math.sqrt(max(h - zs, 0.0) / a)       # the surface's radius at the lid
    r_bottom = math.sqrt(max(-zs, 0.0) / a)       # ... at the bottom (0: wet centre)
    margin = R - r_top
    if ri > 0.0:
        margin = min(margin, r_bottom - ri)
    return kappa, max(margin, 0.0) / shift


def synchronous_liquid(device: LiquidDevice, speed: float, g: float = G_STANDARD) -> SyncLiquid:
    """A machine's liquid in a synchronous whirl at ``speed`` (module docstring): its added
    mass kappa (summed over the chambers; 0 for a chamber below its entrainment speed, 003
    eq 6, whose liquid is a pool), the whirl up to which every chamber's ring stays intact
    (0 if one is not a ring from bottom to lid at this speed, or, on a horizontal axis, below
    the film's start g/Omega^2 = R/10: a puddle) and its capacity rho V R.

    Parameters
    ----------
    device : autobalance.models.LiquidDevice
        The ``[liquid]`` section: chambers (R, h, r_i [m], V [m^3], partitions [-]), density
        [kg/m^3], axis.
    speed : float
        Spin speed Omega [rad/s], > 0.
    g : float
        Gravity along a vertical axis, or in the plane of a horizontal one [m/s^2].

    Returns
    -------
    autobalance.physics.worst_case.SyncLiquid
    """
    check_synchronous(device)
    w = positive("speed", speed)
    kappa, reach = 0.0, math.inf
    for c in device.chambers:
        k, r = _chamber(c, w, g)
        kappa, reach = kappa + k, min(reach, r)
    return SyncLiquid(kappa, reach, device.capacity)
