"""The assembled machine, its initial state and the numerical options of a run."""
from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..limits import DEFAULT_MAX_STEPS
from ._validate import ParameterError, count, finite, in_range, nonneg, positive
from .balancer import BallBalancer
from .liquid import LiquidDevice
from .rotor import Gravity, Rotor, Suspension

FRICTION_LAWS = ("stick", "tanh", "creep")
NORMAL_FORCES = ("ball", "drum")


@dataclass(frozen=True)
class System:
    """Rotor on its suspension with a ball balancer and/or a liquid balancer, in a gravity field.

    ``dataclasses.replace`` makes sweep points; validation happens in each part.
    """

    rotor: Rotor
    suspension: Suspension
    balancer: BallBalancer = field(default_factory=lambda: BallBalancer(0))
    gravity: Gravity = field(default_factory=Gravity)
    name: str = ""
    description: str = ""
    # out of the repr (stores key on it: repr(System) of a ball machine stays as before the
    # liquid joined); sweep/store.identity adds a liquid explicitly
    liquid: LiquidDevice | None = field(default=None, repr=False)

    def __post_init__(self):
        if self.liquid is not None and not isinstance(self.liquid, LiquidDevice):
            raise ParameterError("liquid", self.liquid, "must be a LiquidDevice or None")

    def require_balls(self, what: str, allow_empty: bool = False,
                      allow_liquid: bool = False) -> None:
        """Refuse, in one line, a machine an analysis of ball balancers cannot take.

        Parameters
        ----------
        what : str
            The analysis, named in the message (e.g. ``"the studies"``).
        allow_empty : bool
            Accept a machine without balls (the bare rotor) [-].
        allow_liquid : bool
            Accept a liquid beside the balls: the analysis runs only simulations, which model
            it (autobalance.simulate.hybrid) [-].

        Raises
        ------
        ParameterError
            A liquid balancer (the ball analyses would take the liquid as a rigid mass) unless
            ``allow_liquid``, or no balls unless ``allow_empty``.
        """
        alone = ("a liquid alone runs with `autobalance simulate`, the studies fill-map, "
                 "unbalance-range and runup, and `autobalance liquid stability`")
        if self.liquid is not None and not allow_liquid:
            other = ("the studies start-positions, unbalance-range, plateau, sensitivity and "
                     "runup (simulations), speed-map, immobility and tolerances (either axis) "
                     "and design take balls beside a liquid; a liquid balancer runs "
                     "with `autobalance simulate` (and `sweep`)" if self.balancer.n_balls
                     else alone)
            raise ParameterError("liquid", "a [liquid] section", f"{what} take ball balancers "
                                 f"only (closed forms without a liquid); {other}")
        if not allow_empty and self.balancer.n_balls == 0:
            alone = "; " + alone if self.liquid is not None else ""
            raise ParameterError("balancer.n_balls", 0,
                                 f"{what} need a ball balancer (>= 1 ball{alone})")

    @property
    def total_mass(self) -> float:
        """M_t = M + sum(m_i) + rho V [kg], the mass carried by the suspension (004: M_t; the
        liquid's mass moves with the chamber)."""
        liquid = self.liquid.mass if self.liquid is not None else 0.0
        return self.rotor.mass + self.balancer.total_mass + liquid

    @property
    def natural_frequencies(self) -> tuple[float, float]:
        """Undamped natural frequencies sqrt(kx/M_t), sqrt(ky/M_t) [rad/s]."""
        mt = self.total_mass
        return float(np.sqrt(self.suspension.kx / mt)), float(np.sqrt(self.suspension.ky / mt))


@dataclass(frozen=True)
class InitialState:
    """State at t = 0.

    Parameters
    ----------
    ball_angles : tuple of float
        alpha_i(0) relative to the unbalance [rad]; default: equispaced starting at pi/4.
    ball_speeds : tuple of float
        d(alpha_i)/dt at t = 0 [rad/s].
    x, y : float
        Rotor displacement from static equilibrium [m].
    vx, vy : float
        Rotor velocity [m/s] (inertial frame).
    steady_state : bool
        If True, x, y, vx, vy are ignored and the rotor starts on its steady harmonic orbit for
        the initial speed and ball positions (000 eq 6-7), i.e. the drum is already vibrating
        when the balls are released, as in 000 Fig. 5.
    """

    ball_angles: tuple | None = None
    ball_speeds: tuple | None = None
    x: float = 0.0
    y: float = 0.0
    vx: float = 0.0
    vy: float = 0.0
    steady_state: bool = False

    def __post_init__(self):
        for name in ("x", "y", "vx", "vy"):
            finite(f"initial.{name}", getattr(self, name))
        if self.ball_angles is not None:
            object.__setattr__(self, "ball_angles",
                               tuple(finite("initial.ball_angles", a) for a in self.ball_angles))
        if self.ball_speeds is not None:
            object.__setattr__(self, "ball_speeds",
                               tuple(finite("initial.ball_speeds", a) for a in self.ball_speeds))

    def angles_for(self, balancer: BallBalancer) -> np.ndarray:
        """Initial ball angles alpha_i(0) for this balancer, checked against it.

        Parameters
        ----------
        balancer : BallBalancer
            The balancer the angles are for (its N and contact angle).

        Returns
        -------
        ndarray
            alpha_i(0) relative to the unbalance [rad], length N: ``ball_angles`` as given, or
            by default N equispaced angles starting at pi/4.

        Raises
        ------
        ParameterError
            If the number of angles is not N or two neighbouring balls overlap (closer than
            the contact angle 2*asin(r/R)).
        """
        n = balancer.n_balls
        if self.ball_angles is None:
            return np.pi / 4 + 2 * np.pi * np.arange(n) / max(n, 1)
        if len(self.ball_angles) != n:
            raise ParameterError("initial.ball_angles", list(self.ball_angles),
                                 f"needs {n} values, one per ball")
        a = np.asarray(self.ball_angles, float)
        order = np.sort(np.mod(a, 2 * np.pi))
        gaps = np.diff(np.concatenate([order, order[:1] + 2 * np.pi]))
        if n > 1 and gaps.min() < balancer.contact_angle * (1 - 1e-9):
            raise ParameterError("initial.ball_angles", list(self.ball_angles),
                                 f"balls overlap: neighbours must be >= {np.degrees(balancer.contact_angle):.3g} deg apart")
        return a

    def speeds_for(self, balancer: BallBalancer) -> np.ndarray:
        """Initial ball speeds d(alpha_i)/dt at t = 0 for this balancer.

        Parameters
        ----------
        balancer : BallBalancer
            The balancer the speeds are for (its N).

        Returns
        -------
        ndarray
            d(alpha_i)/dt(0) relative to the rotor [rad/s], length N; zeros by default.

        Raises
        ------
        ParameterError
            If the number of speeds is not N.
        """
        n = balancer.n_balls
        if self.ball_speeds is None:
            return np.zeros(n)
        if len(self.ball_speeds) != n:
            raise ParameterError("initial.ball_speeds", list(self.ball_speeds),
                                 f"needs {n} values, one per ball")
        return np.asarray(self.ball_speeds, float)


@dataclass(frozen=True)
class SimOptions:
    """Numerical options of one run.

    The kernel takes its fast paths wherever their conditions hold (closed-form holds, stuck
    ramps without stepping, slip jumps; ``autobalance.simulate.pack.fast_paths``) and steps
    everything else by DOPRI5; no option chooses between them (docs/numerics/stuck-phases.md).

    Parameters
    ----------
    friction_law : str
        "stick": exact Coulomb stick-slip (switch model with event location, default);
        "tanh": 004's regularised law mu*N*tanh(alpha_dot/v_sat) (stiff; for comparison);
        "creep": exact stick-slip, stuck balls creeping along the tanh law's slow manifold at
        -v_sat*atanh(lambda/(mu N R)) (physics.friction.creep_speed): 004's law at the speed of
        the stick kernel (needs stiction = rolling resistance).
    v_sat : float
        Saturation speed of the tanh law [rad/s] (004: 1e-6 rad/s); used by "tanh" and "creep".
    normal_force : str
        "ball": N_i = m_i (R (psi_dot + alpha_dot_i)^2 - g.e_r) (our default, docs/model.md);
        "drum": N_i = m_i R psi_dot^2 (000 eq 20 as printed).
    rtol : float
        Relative tolerance of the adaptive Dormand-Prince 5(4) integrator [-].
    atol_scale : float
        Absolute tolerances are atol_scale times characteristic scales (docs/numerics/kernel.md)
        [-].
    max_step : float
        Largest step [s]; 0 = automatic.
    save_dt : float
        Spacing of the stored time history [s]; 0 = automatic (about 20 samples per revolution at
        the nominal speed, at most 200 000 samples); < 0 = store only the checkpoints.
    max_steps : int
        Step budget; exceeding it ends the run with status "max_steps".
    """

    friction_law: str = "stick"
    v_sat: float = 1e-6
    normal_force: str = "ball"
    rtol: float = 1e-6
    atol_scale: float = 1e-6
    max_step: float = 0.0
    save_dt: float = 0.0
    max_steps: int = DEFAULT_MAX_STEPS

    def __post_init__(self):
        if self.friction_law not in FRICTION_LAWS:
            raise ParameterError("options.friction_law", self.friction_law, f"must be one of {list(FRICTION_LAWS)}")
        if self.normal_force not in NORMAL_FORCES:
            raise ParameterError("options.normal_force", self.normal_force, f"must be one of {list(NORMAL_FORCES)}")
        positive("options.v_sat", self.v_sat)
        in_range("options.rtol", self.rtol, 1e-13, 1e-1)
        positive("options.atol_scale", self.atol_scale)
        nonneg("options.max_step", self.max_step)
        finite("options.save_dt", self.save_dt)
        count("options.max_steps", self.max_steps, 1)  # inf/NaN: one line, not OverflowError
