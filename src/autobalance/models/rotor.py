"""Rotor (drum) and suspension parameters, SI units.

Conventions (see docs/model.md): the rotor centre O moves in the plane (x, y), measured from its
static equilibrium; the unbalance U = M*e lies along the rotor-fixed axis u (ball angles alpha are
measured from it, as in 000 Fig. 4b and 004 Fig. 2).
"""
from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ._validate import ParameterError, finite, nonneg, positive


@dataclass(frozen=True)
class Rotor:
    """Rigid rotor or drum carrying the balancer.

    Parameters
    ----------
    mass : float
        Translating mass M [kg] without the balls (000: tub + drum + motor, 37 kg;
        004 Table 1: 16.53 kg).
    unbalance : float
        Static unbalance U = M*e [kg*m] (000: Me; 004: M*|eps|).
    polar_inertia : float
        Moment of inertia B_z of the spinning parts about the spin axis [kg*m^2]; used only when
        the spin is driven by a motor torque (000 eq 15).
    spin_damping : float
        Viscous spin loss c_phi [N*m*s/rad] (000 eq 15).
    unbalance_schedule : tuple of (time [s], unbalance [kg*m]) pairs, optional
        Time-varying unbalance Me(t) (000, "variable unbalance", water extraction); linear
        interpolation, held constant outside. Empty = constant ``unbalance``.
    """

    mass: float
    unbalance: float = 0.0
    polar_inertia: float = 0.0
    spin_damping: float = 0.0
    unbalance_schedule: tuple = ()

    def __post_init__(self):
        positive("rotor.mass", self.mass)
        nonneg("rotor.unbalance", self.unbalance)
        nonneg("rotor.polar_inertia", self.polar_inertia)
        nonneg("rotor.spin_damping", self.spin_damping)
        sched = tuple((finite("rotor.unbalance_schedule.time", t),
                       nonneg("rotor.unbalance_schedule.unbalance", u))
                      for t, u in self.unbalance_schedule)
        ts = [t for t, _ in sched]
        if any(b <= a for a, b in zip(ts, ts[1:])):
            raise ParameterError("rotor.unbalance_schedule", ts, "times must be strictly increasing")
        object.__setattr__(self, "unbalance_schedule", sched)

    @property
    def eccentricity(self) -> float:
        """Mass-centre eccentricity e = U/M [m]."""
        return self.unbalance / self.mass

    def unbalance_table(self) -> tuple[np.ndarray, np.ndarray]:
        """(times [s], unbalance [kg*m]) arrays for the kernels."""
        if not self.unbalance_schedule:
            return np.array([0.0]), np.array([self.unbalance])
        t, u = zip(*self.unbalance_schedule)
        return np.asarray(t, float), np.asarray(u, float)


@dataclass(frozen=True)
class Suspension:
    """Linear anisotropic suspension with optional dry friction and base excitation.

    Parameters
    ----------
    kx, ky : float
        Stiffness along x and y [N/m] (000: kx = 20 N/mm, ky = 6 N/mm; 004: k = 5.8 kN/mm).
    cx, cy : float
        Viscous damping along x and y [N*s/m] (000: 200 and 110 kg/s; 004: 1.51 kN*s/m).
    dry_friction_force : float
        Coulomb friction force F of each of two friction dampers [N] (000 eq 48: 2F = 140 N).
    dry_friction_angle : float
        Inclination gamma of the two dampers to the x axis [rad]; they act along (cos g, +-sin g)
        (000 eq 48: gamma = 61 deg, F_x = 2F cos gamma).
    dry_friction_velocity : float
        Velocity scale of the regularised friction law F*tanh(v/v_s) [m/s] (our choice, docs).
    base_amplitude_x, base_amplitude_y : float
        Harmonic base (cabinet/floor) displacement amplitudes [m] (000, "external vibrations").
    base_frequency : float
        Base excitation angular frequency [rad/s].
    base_phase_x, base_phase_y : float
        Phases of the base motion [rad]: x_b = A_x cos(w t + phase_x).
    """

    kx: float
    ky: float
    cx: float = 0.0
    cy: float = 0.0
    dry_friction_force: float = 0.0
    dry_friction_angle: float = 0.0
    dry_friction_velocity: float = 1e-4
    base_amplitude_x: float = 0.0
    base_amplitude_y: float = 0.0
    base_frequency: float = 0.0
    base_phase_x: float = 0.0
    base_phase_y: float = 0.0

    def __post_init__(self):
        positive("suspension.kx", self.kx)
        positive("suspension.ky", self.ky)
        nonneg("suspension.cx", self.cx)
        nonneg("suspension.cy", self.cy)
        nonneg("suspension.dry_friction_force", self.dry_friction_force)
        finite("suspension.dry_friction_angle", self.dry_friction_angle)
        positive("suspension.dry_friction_velocity", self.dry_friction_velocity)
        nonneg("suspension.base_amplitude_x", self.base_amplitude_x)
        nonneg("suspension.base_amplitude_y", self.base_amplitude_y)
        nonneg("suspension.base_frequency", self.base_frequency)
        finite("suspension.base_phase_x", self.base_phase_x)
        finite("suspension.base_phase_y", self.base_phase_y)

    @classmethod
    def isotropic(cls, k: float, c: float = 0.0, **kw: float) -> "Suspension":
        """Jeffcott support: kx = ky = k [N/m], cx = cy = c [N*s/m].

        Parameters
        ----------
        k : float
            Stiffness along both axes [N/m] (004 Table 1: 5.8 kN/mm).
        c : float
            Viscous damping along both axes [N*s/m] (004 Table 1: 1.51 kN*s/m).
        **kw
            Further :class:`Suspension` fields (dry friction, base excitation).

        Returns
        -------
        Suspension
        """
        return cls(kx=k, ky=k, cx=c, cy=c, **kw)

    @property
    def is_isotropic(self) -> bool:
        """True when kx == ky and cx == cy (a Jeffcott support)."""
        return self.kx == self.ky and self.cx == self.cy


@dataclass(frozen=True)
class Gravity:
    """Gravity in the plane of motion.

    Parameters
    ----------
    g : float
        Acceleration of gravity [m/s^2]; 0 for a vertical spin axis.
    direction : float
        Direction of the gravity vector in the (x, y) plane [rad] (000: x vertical, gravity along
        -x = pi; 004: along -Y = -pi/2).
    """

    g: float = 0.0
    direction: float = -np.pi / 2

    def __post_init__(self):
        nonneg("gravity.g", self.g)
        finite("gravity.direction", self.direction)


