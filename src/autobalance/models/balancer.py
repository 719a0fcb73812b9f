"""Ball/roller balancer parameters, SI units (000 eq 2-4, 19-20, 33-36; 004 eq 8-10, Table 1)."""
from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ..limits import max_balls
from ._validate import ParameterError, count, finite, in_range, nonneg, per_ball, positive

#: Rotational inertia factor kappa in I = kappa*m*r^2 for the rolling elements.
INERTIA_FACTOR = {"ball": 0.4, "roller": 0.5, "point": 0.0}

#: Ball-ball contact models: "compliant" (a spring-dashpot between neighbours, which keep
#: their order; 000's impacts) or "none" (points that pass through each other, 004's model).
CONTACT_MODELS = ("compliant", "none")

_COEFFICIENTS = {
    "balancer.rolling_resistance": "rolling-resistance coefficient f/r = F_r/N",
    "balancer.stiction": "static (break-away) friction coefficient F_s/N",
}


def _coefficient(field: str, value) -> float:
    """A friction coefficient [-] (force / normal force) within [0, 1]; ParameterError otherwise."""
    v = finite(field, value)
    if not 0.0 <= v <= 1.0:
        what = _COEFFICIENTS.get(field.split("[")[0], "friction coefficient")
        raise ParameterError(field, value, f"must be within [0, 1]: the {what} [-] "
                                           "(steel balls typically 0.001-0.01)")
    return v


@dataclass(frozen=True)
class BallBalancer:
    """N balls or rollers running in one circular race fixed to the rotor.

    Parameters
    ----------
    n_balls : int
        Number of balls N (0 = rotor without balancer).
    ball_mass : float or tuple
        Mass m_i of each ball [kg] (004: 7.6 g; 000: m = Me/R for mR = Me).
    race_radius : float
        Radius R of the circle of the ball centres [m] (000: 0.28 m; 004: 35 mm).
    ball_radius : float
        Rolling radius r of the element [m]; sets the contact angle between neighbours and the
        rolling inertia (000: m_z = m + I/r^2).
    element : str
        "ball" (I = 2/5 m r^2), "roller" (I = 1/2 m r^2) or "point" (I = 0, 004's point masses).
    damping : float or tuple
        Viscous damping D_i of the ball motion relative to the race [N*m*s/rad]
        (004 Table 1: 2.7 N*mm*s/rad; 000 writes it c_i*m*R^2 with c_i in 1/s).
    rolling_resistance : float or tuple
        Coefficient of the resisting force F_r = coef * N_i (000 eq 20: f/r; 004: mu) [-],
        within [0, 1] (steel balls typically 0.001-0.01).
    stiction : float or tuple, optional
        Static (break-away) coefficient >= rolling_resistance [-], within [0, 1]; defaults to it.
    eccentricity : float
        Distance rho between the race centre and the spin axis [m] (000 eq 33).
    eccentricity_angle : float
        Angle beta of that offset from the unbalance direction [rad] (000 eq 33).
    restitution : float
        Coefficient of restitution of ball-ball impacts [-] (000: impacts between balls).
    contact_frequency : float
        Natural frequency of the compliant ball-ball contact [rad/s]; 0 = 5x the run's top speed.
    contact : str
        "compliant" (default: balls touch at the contact angle 2 asin(r/R) and keep their
        order) or "none" (004's point masses: no ball-ball force, balls pass through each other
        and may coincide; the contact angle is 0).
    """

    n_balls: int
    ball_mass: float | tuple = 0.0
    race_radius: float = 0.0
    ball_radius: float = 0.0
    element: str = "ball"
    damping: float | tuple = 0.0
    rolling_resistance: float | tuple = 0.0
    stiction: float | tuple | None = None
    eccentricity: float = 0.0
    eccentricity_angle: float = 0.0
    restitution: float = 0.5
    contact_frequency: float = 0.0
    # not in the generated repr: _repr below adds it when not the default, so that the
    # identities of sweep stores made before the field existed stay valid (sweep/store.py)
    contact: str = field(default="compliant", repr=False)

    def __post_init__(self):
        n = count("balancer.n_balls", self.n_balls, 0)
        lim = max_balls()
        if n > lim:  # before anything per ball is built (a tuple of 1e9 masses would hang)
            raise ParameterError("balancer.n_balls", n,
                                 f"at most {lim} balls in one balancer (limit "
                                 f"AUTOBALANCE_MAX_BALLS = {lim}; set it to raise the limit)")
        object.__setattr__(self, "n_balls", n)
        if self.element not in INERTIA_FACTOR:
            raise ParameterError("balancer.element", self.element,
                                 f"must be one of {sorted(INERTIA_FACTOR)}")
        if self.contact not in CONTACT_MODELS:
            raise ParameterError("balancer.contact", self.contact,
                                 f"must be one of {', '.join(CONTACT_MODELS)} (compliant: balls "
                                 "touch and keep their order; none: points that pass through)")
        if n == 0:
            for name in ("ball_mass", "damping", "rolling_resistance"):
                object.__setattr__(self, name, ())
            object.__setattr__(self, "stiction", ())
            if self.race_radius:
                positive("balancer.race_radius", self.race_radius)
            return
        positive("balancer.race_radius", self.race_radius)
        positive("balancer.ball_radius", self.ball_radius)
        if self.ball_radius >= self.race_radius:
            raise ParameterError("balancer.ball_radius", self.ball_radius,
                                 f"must be < race_radius = {self.race_radius}")
        if (self.contact == "compliant"
                and n * 2 * math.asin(self.ball_radius / self.race_radius) > 2 * math.pi + 1e-12):
            fit = int((2 * math.pi + 1e-12) // (2 * math.asin(self.ball_radius / self.race_radius)))
            raise ParameterError("balancer.n_balls", n,
                                 f"that many balls of this radius do not fit in the race "
                                 f"(at most {fit})")
        object.__setattr__(self, "ball_mass", per_ball("balancer.ball_mass", self.ball_mass, n, positive))
        object.__setattr__(self, "damping", per_ball("balancer.damping", self.damping, n, nonneg))
        mu = per_ball("balancer.rolling_resistance", self.rolling_resistance, n, _coefficient)
        object.__setattr__(self, "rolling_resistance", mu)
        st = mu if self.stiction is None else per_ball("balancer.stiction", self.stiction, n,
                                                       _coefficient)
        for i, (a, b) in enumerate(zip(mu, st)):
            if b < a:
                raise ParameterError(f"balancer.stiction[{i}]", b,
                                     f"must be >= rolling_resistance = {a}")
        object.__setattr__(self, "stiction", st)
        nonneg("balancer.eccentricity", self.eccentricity)
        if self.eccentricity >= self.race_radius:
            raise ParameterError("balancer.eccentricity", self.eccentricity,
                                 f"must be < race_radius = {self.race_radius}")
        finite("balancer.eccentricity_angle", self.eccentricity_angle)
        in_range("balancer.restitution", self.restitution, 0.0, 1.0)
        nonneg("balancer.contact_frequency", self.contact_frequency)

    # -- derived quantities -------------------------------------------------------------------
    @property
    def masses(self) -> np.ndarray:
        """Ball masses m_i as an array of length N [kg] (empty without balls)."""
        return np.asarray(self.ball_mass, float)

    @property
    def total_mass(self) -> float:
        """Total ball mass sum(m_i) [kg] (0 without balls)."""
        return float(np.sum(self.masses)) if self.n_balls else 0.0

    @property
    def inertias(self) -> np.ndarray:
        """Rolling inertia I_i = kappa*m_i*r^2 [kg*m^2]."""
        return INERTIA_FACTOR[self.element] * self.masses * self.ball_radius**2

    @property
    def capacity(self) -> float:
        """Total ball unbalance sum(m_i)*R [kg*m] (all balls in phase)."""
        return self.total_mass * self.race_radius

    @property
    def contact_angle(self) -> float:
        """Smallest centre-angle between neighbouring balls, 2*asin(r/R) [rad]; 0 without
        contact (``contact = "none"``: the balls may coincide)."""
        if not self.n_balls or self.contact == "none":
            return 0.0
        return 2 * math.asin(self.ball_radius / self.race_radius)


_generated_repr = BallBalancer.__repr__


def _repr(self) -> str:
    """The dataclass repr, with ``contact`` only when it is not the default."""
    r = _generated_repr(self)
    return r if self.contact == "compliant" else f"{r[:-1]}, contact={self.contact!r})"


BallBalancer.__repr__ = _repr
