"""Reduced-order dynamics of a vertical rotor with a liquid (Leblanc) balancer.

Model (docs/liquid/models.md sec. 3, derives it and lists its limits):

* Rotor: isotropic Jeffcott rotor in the plane, complex deflection u = x + i y,
  (M + m_l) u'' + c u' + k u = W (Omega^2 - i Omega') e^{i phi}, W = D + D0 e^{i theta}
  (textbook unbalance forcing; the liquid's mass m_l = rho V translates with the rotor).
* Liquid: a lumped unbalance D0 = chi(Omega) * rho V R at angle theta from the rotor's
  unbalance D, in the chamber frame. chi ramps from 0 at the entrainment speed omega_0 of
  003 eq 6 (mode 4 reached) to 1 at ``engagement_ratio * omega_0``.
* Viscous lag: theta' = wrap(theta* - theta) / tau, theta* the equilibrium angle of the chosen
  placement law: "drach" = +-(alpha0(delta, k) - beta) (001 eq 3 and 6, delta the rotor's phase
  between W and u, k = D0/D); "deflection" = arg(u e^{-i phi}) (classical centrifugal law).
"""
from __future__ import annotations

import cmath
import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
from scipy.integrate import solve_ivp

from ..models._validate import ParameterError, nonneg, positive
from .free_surface import entrainment_speed
from .kinetostatic import liquid_angle_scalar
from ..models.liquid_balancer import LiquidBalancer, LiquidModel, VerticalRotor

if TYPE_CHECKING:
    import numpy.typing as npt

__all__ = ["RunUp", "engagement", "run_up", "steady_response", "fill_sweep"]

TWO_PI = 2.0 * math.pi


def _wrap(a: float) -> float:
    return (a + math.pi) % TWO_PI - math.pi


def engagement(omega: float | npt.ArrayLike, omega0: float,
               ratio: float) -> float | np.ndarray:
    """Fraction chi in [0, 1] of the liquid's unbalance capacity that is active [-].

    Smoothstep from 0 at omega_0 (003 eq 6, start of mode 4) to 1 at ratio*omega_0 (our
    reduced-order choice; ratio = 1 gives a step).

    Parameters
    ----------
    omega : float or array
        Speed [rad/s].
    omega0 : float
        Entrainment speed [rad/s].
    ratio : float
        engagement_ratio >= 1 [-].
    """
    w = np.asarray(omega, dtype=float)
    if ratio <= 1.0:
        return (w >= omega0).astype(float) if w.ndim else float(w >= omega0)
    x = np.clip((w - omega0) / ((ratio - 1.0) * omega0), 0.0, 1.0)
    out = x * x * (3.0 - 2.0 * x)
    return out if w.ndim else float(out)


def _target(theta: float, W: complex, ut: complex, D: float, D0: float,
            bal: LiquidBalancer, model: LiquidModel, omega: float) -> float:
    """Equilibrium angle theta* of the liquid (chamber frame, from the rotor's unbalance)."""
    if abs(ut) == 0.0:
        return theta
    if model.placement == "deflection" or D <= 0.0:
        return cmath.phase(ut)
    delta = _wrap(cmath.phase(W) - cmath.phase(ut))
    k = max(D0 / D, 1e-12)
    a = liquid_angle_scalar(delta, k, bal.liquid.dynamic_viscosity, bal.chamber.radius,
                            bal.arc, bal.mass, omega)
    side = math.copysign(1.0, ut.imag) if ut.imag != 0.0 else -1.0
    return side * a


@dataclass(frozen=True)
class RunUp:
    """Result of :func:`run_up` (arrays over time, SI)."""

    t: np.ndarray
    omega: np.ndarray
    amplitude: np.ndarray
    liquid_angle: np.ndarray
    liquid_unbalance: np.ndarray
    amplitude_dry: np.ndarray

    def summary(self) -> dict:
        """Peak and final values of the run-up: amplitudes [m], speeds [rad/s], liquid angle [deg].

        Returns
        -------
        dict
            ``peak_amplitude_m``, ``peak_speed_rad_s``, ``peak_amplitude_dry_m``,
            ``peak_speed_dry_rad_s``, ``final_amplitude_m``, ``final_amplitude_dry_m``,
            ``final_liquid_angle_deg``, ``n_samples``.
        """
        i = int(np.argmax(self.amplitude))
        j = int(np.argmax(self.amplitude_dry))
        return {"peak_amplitude_m": float(self.amplitude[i]),
                "peak_speed_rad_s": float(self.omega[i]),
                "peak_amplitude_dry_m": float(self.amplitude_dry[j]),
                "peak_speed_dry_rad_s": float(self.omega[j]),
                "final_amplitude_m": float(self.amplitude[-1]),
                "final_amplitude_dry_m": float(self.amplitude_dry[-1]),
                "final_liquid_angle_deg": float(np.degrees(self.liquid_angle[-1])),
                "n_samples": int(self.t.size)}


def run_up(rotor: VerticalRotor, bal: LiquidBalancer, model: LiquidModel = LiquidModel(),
           omega_end: float = 100.0, duration: float = 20.0, n_out: int = 2000,
           rtol: float = 1e-6) -> RunUp:
    """Linear run-up 0 -> omega_end in ``duration``, with and without liquid (same rotor).

    Parameters
    ----------
    rotor : VerticalRotor
        Rotor and supports.
    bal : LiquidBalancer
        Chamber, liquid, volume.
    model : LiquidModel
        Reduced-order choices.
    omega_end : float
        Final speed [rad/s] > 0.
    duration : float
        Run-up time [s] > 0.
    n_out : int
        Output samples.
    rtol : float
        Relative tolerance of the RK45 integrator [-].

    Returns
    -------
    RunUp
        Amplitudes are the whirl radius |u| [m].
    """
    positive("omega_end", omega_end)
    T = positive("duration", duration)
    if int(n_out) < 2:
        raise ParameterError("n_out", n_out, "must be >= 2")
    acc = omega_end / T
    D, cap, k_s, c = rotor.unbalance, bal.capacity, rotor.stiffness, rotor.damping
    w0 = entrainment_speed(bal.volume, bal.chamber.radius, bal.chamber.height, model.g,
                           bal.chamber.inner_radius)
    tau = model.lag_time

    def rhs_wet(t, y):
        om = acc * t
        phi = 0.5 * acc * t * t
        u = complex(y[0], y[1])
        v = complex(y[2], y[3])
        th = y[4]
        D0 = cap * engagement(om, w0, model.engagement_ratio)
        W = D + D0 * cmath.exp(1j * th)
        e = cmath.exp(1j * phi)
        a = (W * (om * om - 1j * acc) * e - c * v - k_s * u) / (rotor.mass + bal.mass)
        ut = u / e
        dth = _wrap(_target(th, W, ut, D, D0, bal, model, om) - th) / tau
        return (v.real, v.imag, a.real, a.imag, dth)

    def rhs_dry(t, y):
        om = acc * t
        e = cmath.exp(0.5j * acc * t * t)
        u = complex(y[0], y[1])
        v = complex(y[2], y[3])
        a = (D * (om * om - 1j * acc) * e - c * v - k_s * u) / rotor.mass
        return (v.real, v.imag, a.real, a.imag)

    ts = np.linspace(0.0, T, int(n_out))
    hmax = 0.05 * TWO_PI / max(omega_end, 1e-9)
    wet = solve_ivp(rhs_wet, (0.0, T), [0.0, 0.0, 0.0, 0.0, math.pi], t_eval=ts, rtol=rtol,
                    atol=1e-12, max_step=hmax * 10)
    dry = solve_ivp(rhs_dry, (0.0, T), [0.0, 0.0, 0.0, 0.0], t_eval=ts, rtol=rtol,
                    atol=1e-12, max_step=hmax * 10)
    if not (wet.success and dry.success):
        raise RuntimeError(f"integration failed: {wet.message} / {dry.message}")
    om = acc * ts
    return RunUp(t=ts, omega=om, amplitude=np.hypot(wet.y[0], wet.y[1]),
                 liquid_angle=np.array([_wrap(a) for a in wet.y[4]]),
                 liquid_unbalance=cap * engagement(om, w0, model.engagement_ratio),
                 amplitude_dry=np.hypot(dry.y[0], dry.y[1]))


def steady_response(rotor: VerticalRotor, bal: LiquidBalancer, omegas: npt.ArrayLike,
                    model: LiquidModel = LiquidModel(), iterations: int = 400) -> dict:
    """Steady synchronous whirl at constant speeds, with and without liquid.

    At constant Omega the rotor's response to W is u~ = W Omega^2 H, H = 1/(k - M_t Omega^2
    + i c Omega) (textbook), so the phase delta = -arg H is fixed and theta solves
    theta = theta*(theta); solved by damped fixed-point iteration from theta = pi.

    Parameters
    ----------
    rotor : VerticalRotor
        Rotor and supports (mass [kg], stiffness [N/m], damping [N*s/m], unbalance [kg*m]).
    bal : LiquidBalancer
        Chamber [m], liquid, volume [m^3].
    omegas : array
        Speeds [rad/s] >= 0.
    model : LiquidModel
        Reduced-order choices (placement law, engagement ratio [-], lag time [s], g [m/s^2]).
    iterations : int
        Fixed-point iterations.

    Returns
    -------
    dict
        Arrays ``omega_rad_s``, ``amplitude_m``, ``amplitude_dry_m``, ``efficiency``
        (amplitude dry / wet, 003's empirical efficiency), ``liquid_angle_deg``,
        ``liquid_unbalance_kg_m``, ``phase_deg``.
    """
    om = np.atleast_1d(np.asarray(omegas, dtype=float))
    for w in om:
        nonneg("omega", w)
    w0 = entrainment_speed(bal.volume, bal.chamber.radius, bal.chamber.height, model.g,
                           bal.chamber.inner_radius)
    D, Mt = rotor.unbalance, rotor.mass + bal.mass
    amp, dry, ang, d0s, ph = [], [], [], [], []
    for w in om:
        H = 1.0 / complex(rotor.stiffness - Mt * w * w, rotor.damping * w)
        Hd = 1.0 / complex(rotor.stiffness - rotor.mass * w * w, rotor.damping * w)
        D0 = bal.capacity * engagement(w, w0, model.engagement_ratio)
        th = math.pi
        for _ in range(int(iterations)):
            W = D + D0 * cmath.exp(1j * th)
            th = _wrap(th + 0.5 * _wrap(_target(th, W, W * w * w * H, D, D0, bal, model, w) - th))
        W = D + D0 * cmath.exp(1j * th)
        amp.append(abs(W) * w * w * abs(H))
        dry.append(D * w * w * abs(Hd))
        ang.append(math.degrees(th))
        d0s.append(D0)
        ph.append(math.degrees(-cmath.phase(H)))
    amp, dry = np.array(amp), np.array(dry)
    with np.errstate(divide="ignore", invalid="ignore"):
        eff = np.where(amp > 0, dry / np.where(amp > 0, amp, 1.0), np.inf)
    return {"omega_rad_s": om, "amplitude_m": amp, "amplitude_dry_m": dry, "efficiency": eff,
            "liquid_angle_deg": np.array(ang), "liquid_unbalance_kg_m": np.array(d0s),
            "phase_deg": np.array(ph)}


def fill_sweep(rotor: VerticalRotor, bal: LiquidBalancer, volumes: npt.ArrayLike, omega: float,
               model: LiquidModel = LiquidModel()) -> dict:
    """Steady amplitude [m] at one speed for several fill volumes [m^3] (003 Fig. 5).

    Parameters
    ----------
    rotor : VerticalRotor
        Rotor and supports (mass [kg], stiffness [N/m], damping [N*s/m], unbalance [kg*m]).
    bal : LiquidBalancer
        Chamber [m] and liquid; its volume is replaced by each of ``volumes``.
    volumes : array
        Fill volumes V [m^3].
    omega : float
        Rotor speed [rad/s].
    model : LiquidModel
        Reduced-order choices.

    Returns
    -------
    dict
        ``volume_m3``, ``amplitude_m``, ``efficiency``, ``k`` (= rho V R / D), and
        ``optimum_volume_m3`` (the volume of least amplitude on the grid).
    """
    from dataclasses import replace
    vols = np.atleast_1d(np.asarray(volumes, dtype=float))
    amps, effs = [], []
    for V in vols:
        r = steady_response(rotor, replace(bal, volume=float(V)), [omega], model)
        amps.append(r["amplitude_m"][0])
        effs.append(r["efficiency"][0])
    amps = np.array(amps)
    k = bal.liquid.density * vols * bal.chamber.radius / rotor.unbalance if rotor.unbalance else \
        np.full_like(vols, np.inf)
    return {"volume_m3": vols, "amplitude_m": amps, "efficiency": np.array(effs), "k": k,
            "optimum_volume_m3": float(vols[int(np.argmin(amps))]), "omega_rad_s": float(omega)}
