"""The ``[liquid]`` section of a System: a Leblanc liquid balancer, flat and in SI.

The liquid analyses (:mod:`autobalance.liquid`) take the composite
:class:`autobalance.liquid.LiquidBalancer` (chamber + liquid + fill); ``LiquidBalancer.of``
builds it from this section. docs/liquid/index.md gives the model and the sources of the defaults.
"""
from __future__ import annotations

import math
from dataclasses import dataclass, replace

from ._validate import ParameterError, count, nonneg, positive

#: Directions of the rotation axis: "vertical" (003's bench: gravity along the axis, the free
#: surface a paraboloid) or "horizontal" (a washer's Leblanc ring: gravity in the plane).
AXES = ("vertical", "horizontal")
#: Most radial partitions of a chamber [-] (each compartment keeps >= 4 film cells of 256).
MAX_PARTITIONS = 64


#: The keys of ``[liquid]`` that may differ between concentric chambers: a scalar (every
#: chamber) or a list with one value per chamber, listed from the axis outwards.
PER_CHAMBER = ("chamber_radius", "chamber_height", "inner_radius", "volume", "partitions")


def _check_chamber(v: dict, idx: str) -> dict:
    """Validate one chamber's keys (``v``: the PER_CHAMBER values as given); ``idx`` ("" or
    "[i]") is appended to the field names of the one-line errors. Returns the values, SI."""
    R = positive(f"liquid.chamber_radius{idx}", v["chamber_radius"])
    h = positive(f"liquid.chamber_height{idx}", v["chamber_height"])
    ri = nonneg(f"liquid.inner_radius{idx}", v["inner_radius"])
    if ri >= R:
        raise ParameterError(f"liquid.inner_radius{idx}", v["inner_radius"],
                             f"must be >= 0 and < chamber_radius{idx} {R!r} m")
    vc = math.pi * (R * R - ri * ri) * h
    vol = positive(f"liquid.volume{idx}", v["volume"])
    if vol >= vc:
        raise ParameterError(f"liquid.volume{idx}", v["volume"], "must be < the chamber volume "
                             f"pi (R^2 - r_i^2) h = {vc:.6g} m^3 ({vc * 1e6:.6g} ml)")
    parts = count(f"liquid.partitions{idx}", v["partitions"], 0)
    if parts == 1 or parts > MAX_PARTITIONS:
        raise ParameterError(f"liquid.partitions{idx}", v["partitions"],
                             f"must be 0 (none) or an integer in 2..{MAX_PARTITIONS}")
    return {"chamber_radius": R, "chamber_height": h, "inner_radius": ri, "volume": vol,
            "partitions": parts}


@dataclass(frozen=True)
class LiquidDevice:
    """A closed cylindrical or annular chamber, coaxial with the rotor, partly filled with a
    liquid (003 Fig. 4; 001 Fig. 1), with optional radial partitions; or several concentric
    chambers (003 sec. 4.2's device has three): then the keys of :data:`PER_CHAMBER` are tuples
    with one value per chamber, from the axis outwards (a scalar given for one of them holds for
    every chamber), and the liquid's keys (density, viscosity, axis) are shared.
    :attr:`chambers` gives each chamber as a one-chamber device (docs/liquid/machine.md sec. 3g).

    Parameters
    ----------
    chamber_radius : float or tuple
        Outer (wall) radius R [m] (003 bench: 0.1, 0.15, 0.2 m).
    chamber_height : float or tuple
        Inner height h [m] (003 bench: 0.05 m).
    volume : float or tuple
        Liquid volume V [m^3], 0 < V < pi (R^2 - r_i^2) h.
    density : float
        Liquid density rho [kg/m^3] (001: 670-1650 kg/m^3; default water).
    kinematic_viscosity : float
        nu [m^2/s] (001: 1.01e-6-97e-6 m^2/s; default water at 20 C, 003 sec. 4.2).
    partitions : int or tuple
        Equally spaced radial walls dividing the ring into compartments [-]: 0 (none) or 2-64.
    friction_arc : float
        Arc xi the gathered liquid covers along the wall, for 001's friction force (001 eq
        5-6 leave it open; default pi, half the wall) [rad].
    axis : str
        Direction of the rotation axis, one of :data:`AXES`.
    inner_radius : float or tuple
        Inner wall radius r_i [m], 0 <= r_i < R (0: a cylinder); a chamber's inner wall is at or
        outside the previous chamber's outer wall.
    """

    chamber_radius: float | tuple[float, ...]
    chamber_height: float | tuple[float, ...]
    volume: float | tuple[float, ...]
    density: float = 1000.0
    kinematic_viscosity: float = 1.01e-6
    partitions: int | tuple[int, ...] = 0
    friction_arc: float = math.pi
    axis: str = "vertical"
    inner_radius: float | tuple[float, ...] = 0.0

    def __post_init__(self):
        given = {k: getattr(self, k) for k in PER_CHAMBER}
        lists = {k: v for k, v in given.items() if isinstance(v, (list, tuple))}
        n = max((len(v) for v in lists.values()), default=1)
        longest = next((k for k, v in lists.items() if len(v) == n), "")
        for k, v in lists.items():
            if len(v) not in (1, n):
                raise ParameterError(f"liquid.{k}", list(v), f"needs {n} values (one per "
                                     f"chamber, as liquid.{longest}) or one scalar")
            if n == 0:
                raise ParameterError(f"liquid.{k}", [], "needs at least one value")
        cols = {k: (tuple(v) * (n if len(v) == 1 else 1) if k in lists else (v,) * n)
                for k, v in given.items()}
        if n == 1:
            for k, v in _check_chamber({k: c[0] for k, c in cols.items()}, "").items():
                object.__setattr__(self, k, v)
        else:
            rows = [_check_chamber({k: c[i] for k, c in cols.items()}, f"[{i}]")
                    for i in range(n)]
            for i in range(1, n):
                if rows[i]["inner_radius"] < rows[i - 1]["chamber_radius"] * (1 - 1e-12):
                    raise ParameterError(
                        f"liquid.inner_radius[{i}]", rows[i]["inner_radius"],
                        f"must be >= chamber_radius[{i - 1}] {rows[i - 1]['chamber_radius']!r} "
                        "m: concentric chambers are listed from the axis outwards and do not "
                        "overlap")
            for k in PER_CHAMBER:
                object.__setattr__(self, k, tuple(r[k] for r in rows))
        positive("liquid.density", self.density)
        positive("liquid.kinematic_viscosity", self.kinematic_viscosity)
        a = positive("liquid.friction_arc", self.friction_arc)
        if a > 2 * math.pi * (1 + 1e-12):
            raise ParameterError("liquid.friction_arc", self.friction_arc, "must be in (0, 2 pi] rad")
        if self.axis not in AXES:
            raise ParameterError("liquid.axis", self.axis, f"must be one of {list(AXES)}")

    @property
    def n_chambers(self) -> int:
        """Number of concentric chambers [-]."""
        return len(self.volume) if isinstance(self.volume, tuple) else 1

    @property
    def chambers(self) -> tuple[LiquidDevice, ...]:
        """Each chamber as a one-chamber device with the shared liquid, from the axis outwards
        (``(self,)`` for one chamber)."""
        if self.n_chambers == 1:
            return (self,)
        return tuple(replace(self, **{k: getattr(self, k)[i] for k in PER_CHAMBER})
                     for i in range(self.n_chambers))

    def single(self, what: str) -> LiquidDevice:
        """This device if it has one chamber; a one-line ParameterError naming ``what`` (the
        analysis that takes one chamber only) otherwise.

        Parameters
        ----------
        what : str
            The analysis, for the message [-].
        """
        if self.n_chambers == 1:
            return self
        raise ParameterError("liquid.chamber_radius", list(self.chamber_radius),
                             f"{self.n_chambers} concentric chambers: {what} takes one chamber "
                             "(simulate, sweep, study fill-map and response's physical model take "
                             "several; docs/liquid/machine.md sec. 3g)")

    def vertical(self, why: str) -> LiquidDevice:
        """This device if it turns about a vertical axis; a one-line ParameterError on
        ``liquid.axis`` otherwise, "must be vertical " + ``why``.

        Parameters
        ----------
        why : str
            What needs the vertical axis and why, for the message [-].
        """
        if self.axis != "vertical":
            raise ParameterError("liquid.axis", self.axis, f"must be vertical {why}")
        return self

    def unpartitioned(self, what: str) -> LiquidDevice:
        """This device if no chamber has radial partitions; a one-line ParameterError naming
        ``what`` (an analysis on the quasi-static liquid, which has none) otherwise.

        Parameters
        ----------
        what : str
            The analysis, for the message [-].
        """
        parts = [c.partitions for c in self.chambers]
        if any(parts):
            raise ParameterError("liquid.partitions", parts[0] if len(parts) == 1 else parts,
                                 f"must be 0 for {what} (the quasi-static liquid has no "
                                 "partitions; autobalance simulate and the studies that run "
                                 "the films have)")
        return self

    @property
    def chamber_volume(self) -> float:
        """Inner volume pi (R^2 - r_i^2) h [m^3], summed over the chambers."""
        return sum(math.pi * (c.chamber_radius ** 2 - c.inner_radius ** 2) * c.chamber_height
                   for c in self.chambers)

    @property
    def total_volume(self) -> float:
        """Liquid volume of all chambers [m^3]."""
        return sum(c.volume for c in self.chambers)

    @property
    def mass(self) -> float:
        """Liquid mass rho V [kg], all chambers."""
        return self.density * self.total_volume

    @property
    def capacity(self) -> float:
        """Unbalance capacity rho V R [kg*m]: all liquid gathered at the wall (003 sec. 5.3),
        summed over the chambers."""
        return sum(self.density * c.volume * c.chamber_radius for c in self.chambers)
