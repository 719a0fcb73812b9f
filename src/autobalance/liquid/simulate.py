"""One run of a System whose balancer is a liquid (its ``[liquid]`` section), through its speed
profile, with the wall film coupled two-way to the rotor (:func:`.film.coupled_run`).

The film model holds once the liquid is a ring on the wall (:func:`film_start`): from rest on
a vertical axis, where the liquid's spin-up from a flat layer at rest reaches the lid
(:mod:`.spinup`, 003's mode 4, docs/liquid/spin-up.md sec. 3h), the film lagging the chamber as the
spin-up leaves it; otherwise from the first time the profile reaches the film's start speed
omega_f (:func:`film_start_speed`: on a vertical axis the entrainment speed of 003 eq 6; on a
horizontal one the speed where gravity's offset of the potential g/Omega^2 is R/10), the film
at rest on the wall. Before it the liquid lies as a pool; the run starts on the synchronous
orbit of the rotor carrying the liquid as a rigid centred mass (a quasi-steady start: the
Jeffcott closed form, valid for a run-up slow against the rotor's decay time), plus the static
sag M_t g / k under in-plane gravity, with the film on the displaced wall.
The reported deflection is the whirl about the static sag. docs/liquid/machine.md sec. 3e gives the
scope and what is not modelled yet.
"""
from __future__ import annotations

import json
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..core.layout import RunStatus
from ..models import MotorDrive, ParameterError, SpeedProfile, System
from ..models._validate import positive
from ..physics.iso1940 import grade_value
from .dynamics import RunUp
from .film import FilmsState, coupled_run, films_state
from ..models.liquid_balancer import G_STANDARD, LiquidBalancer, VerticalRotor
from .start import FilmStart, _film_table, film_start, film_start_speed
from .series import film_samples, revolution_average, spin_angle
from .steady import pool_response

if TYPE_CHECKING:
    from collections.abc import Sequence
    from pathlib import Path

    import numpy.typing as npt

    from ..models import LiquidDevice

__all__ = ["FilmStart", "LiquidSimulation", "check_liquid_run", "film_rotor", "film_start",
           "film_start_speed", "chamber_films",
           "liquid_parts", "ramp_run_up", "require_axis_gravity", "require_liquid_machine",
           "revolution_average",
           "run_seconds_estimate", "simulate_liquid"]


#: Wall time of one film step on 256 cells with its 4 rotor sub-steps [s] (measured on the
#: 2-core machine of docs/benchmarks.md: 15232 steps of the leblanc_003 run-up in 1.0 s).
STEP_COST_256 = 6.6e-5
#: Film steps per CFL estimate of the uniform film's wave speed (measured on leblanc_003: the
#: film's own velocity and thickness variations shorten the step) [-].
STEP_FACTOR = 1.6


@dataclass(frozen=True)
class LiquidSimulation:
    """A run of :func:`simulate_liquid`; every array is over the output times ``t``.

    Parameters
    ----------
    system : System
        The machine (its ``liquid`` is the balancer).
    t : ndarray
        Output times from the start of the profile [s] (from ``film_start``).
    speed : ndarray
        Spin Omega [rad/s].
    deflection : ndarray of complex
        Rotor (chamber) deflection about its static sag, rotor frame, x along the unbalance [m].
    liquid_unbalance : ndarray of complex
        The liquid's first moment U about the chamber centre, rotor frame [kg*m].
    synchronous_unbalance : ndarray of complex
        U averaged over one revolution of the spin angle (:func:`revolution_average`): the
        part turning with the rotor, without the gravity-held part that stands still in the
        inertial frame and loads the supports statically [kg*m].
    film_start : float
        Time the film starts (:func:`film_start`) [s].
    film_start_speed : float
        The profile's speed at ``film_start`` [rad/s] (:func:`film_start`).
    nominal_speed : float
        The profile's nominal speed, for the ISO grade [rad/s].
    steps : int
        Film time steps [-].
    status : str
        ``"ok"`` or ``"outside_model"`` (a film reached its chamber's inner wall).
    message : str
        Why, for a status other than ok.
    chamber_unbalance : ndarray (nt, chambers) of complex or None
        Each chamber's film moment, from the axis outwards, for several concentric chambers
        (their sum is ``liquid_unbalance``) [kg*m]; None for one chamber.
    motor : bool
        Whether the spin was a motor drive (``autobalance.simulate.hybrid.simulate_liquid_motor``)
        rather than a prescribed profile [-].
    time_to_final_speed : float or None
        Under a motor, when the spin first reached the drive's hold speed (None: never) [s].
    """

    system: System
    t: np.ndarray
    speed: np.ndarray
    deflection: np.ndarray
    liquid_unbalance: np.ndarray
    synchronous_unbalance: np.ndarray
    film_start: float
    film_start_speed: float
    nominal_speed: float
    steps: int
    status: str = "ok"
    message: str = ""
    chamber_unbalance: np.ndarray | None = None
    motor: bool = False
    time_to_final_speed: float | None = None

    @property
    def note(self) -> str | None:
        """What a finished run has to say beside its numbers, e.g. that the liquid stayed a
        pool (None: nothing); a run that did not finish says why in ``message``."""
        return self.message if self.status == "ok" and self.message else None

    @property
    def amplitude(self) -> np.ndarray:
        """Whirl amplitude |w| [m]."""
        return np.abs(self.deflection)

    @property
    def residual_unbalance(self) -> np.ndarray:
        """|D + U_s| [kg*m]: the rotor's unbalance with the liquid's synchronous moment."""
        return np.abs(self.system.rotor.unbalance + self.synchronous_unbalance)

    @property
    def grade(self) -> np.ndarray:
        """ISO 1940 grade of the residual unbalance on the total mass at the nominal speed
        (004 sec. 4) [mm/s]."""
        return grade_value(self.residual_unbalance, self.system.total_mass, self.nominal_speed)

    @property
    def amplitude_without_liquid(self) -> np.ndarray:
        """Synchronous amplitude of the same rotor without the liquid at each speed (Jeffcott
        closed form, :func:`.steady.pool_response` of no liquid) [m]."""
        return np.abs(pool_response(film_rotor(self.system), 0.0, 0.0, self.speed))

    @property
    def max_amplitude_before_film(self) -> float:
        """Largest synchronous amplitude before the film forms [m]: the rotor with its liquid as
        a rigid centred mass, quasi-steady over the profile's speeds up to omega_0 (Jeffcott
        closed form; exact for a slow run-up, an upper bound of its transient otherwise). Under
        a motor the run itself from its start (the pool's spin-up, sec. 3i; 0 when the film
        starts with the run)."""
        if self.motor:
            before = ~(self.t >= self.film_start)            # all of it when no film formed
            return float(np.max(self.amplitude[before], initial=0.0))
        L = self.system.liquid
        w = np.linspace(0.0, self.film_start_speed, 2001)
        return float(np.max(np.abs(pool_response(film_rotor(self.system), L.total_volume,
                                                 L.density, w))))

    def at(self, times: npt.ArrayLike) -> dict:
        """Grade [mm/s] and residual unbalance [kg*m] at ``times`` [s]: the run's, linearly
        interpolated; before the film forms the liquid is a centred pool (U = 0).

        Parameters
        ----------
        times : array_like
            Times [s] within the profile.
        """
        t = np.asarray(times, float)
        u = np.interp(t, self.t, self.residual_unbalance)
        u = np.where(t < self.film_start, abs(self.system.rotor.unbalance), u)
        return {"residual_unbalance": u,
                "grade_G": grade_value(u, self.system.total_mass, self.nominal_speed)}

    def summary(self) -> dict:
        """Start, final state and peak of the run (SI, unit-suffixed keys, as the ball
        simulator's summary where they mean the same)."""
        i = int(np.argmax(self.amplitude))
        U = self.synchronous_unbalance[-1]
        return {
            "status": self.status, "message": self.message, "system": self.system.name,
            "model": "liquid wall film",
            "duration_s": float(self.t[-1]),
            "nominal_speed_rad_s": self.nominal_speed,
            "film_start_speed_rad_s": self.film_start_speed,
            "film_start_s": self.film_start,
            "initial_grade_G_mm_s": float(grade_value(abs(self.system.rotor.unbalance),
                                                      self.system.total_mass,
                                                      self.nominal_speed)),  # D alone
            "final": {
                "time_s": float(self.t[-1]), "speed_rad_s": float(self.speed[-1]),
                "amplitude_m": float(self.amplitude[-1]),
                "amplitude_without_liquid_m": float(self.amplitude_without_liquid[-1]),
                "liquid_unbalance_kg_m": float(abs(U)),
                "liquid_angle_deg": float(np.degrees(np.angle(U))),
                "residual_unbalance_kg_m": float(self.residual_unbalance[-1]),
                "grade_G_mm_s": float(self.grade[-1]),
            },
            "max_amplitude_m": float(self.amplitude[i]),
            "time_of_max_amplitude_s": float(self.t[i]),
            "speed_of_max_amplitude_rad_s": float(self.speed[i]),
            "max_amplitude_without_liquid_m": float(np.max(self.amplitude_without_liquid)),
            "max_amplitude_before_film_m": self.max_amplitude_before_film,
            "film_steps": self.steps,
            **({"time_to_final_speed_s": self.time_to_final_speed} if self.motor else {}),
            **({} if self.chamber_unbalance is None else {"chambers": [
                {"chamber_radius_m": c.chamber_radius,
                 "liquid_unbalance_kg_m": float(abs(u)),
                 "liquid_angle_deg": float(np.degrees(np.angle(u)))}
                for c, u in zip(self.system.liquid.chambers, self.chamber_unbalance[-1])]}),
        }

    def to_xarray(self):
        """The histories as an :class:`xarray.Dataset` (SI; complex values split into x, y)."""
        import xarray as xr

        w, U = self.deflection, self.liquid_unbalance
        data = {"speed": ("time", self.speed, {"units": "rad/s"}),
                "x": ("time", w.real, {"units": "m", "long_name": "deflection along the unbalance"}),
                "y": ("time", w.imag, {"units": "m", "long_name": "deflection, rotor frame y"}),
                "amplitude": ("time", self.amplitude, {"units": "m"}),
                "amplitude_without_liquid": ("time", self.amplitude_without_liquid, {"units": "m"}),
                "liquid_unbalance_x": ("time", U.real, {"units": "kg m"}),
                "liquid_unbalance_y": ("time", U.imag, {"units": "kg m"}),
                "synchronous_unbalance_x": ("time", self.synchronous_unbalance.real,
                                            {"units": "kg m", "long_name": "revolution average"}),
                "synchronous_unbalance_y": ("time", self.synchronous_unbalance.imag,
                                            {"units": "kg m"}),
                "grade": ("time", self.grade, {"units": "mm/s"})}
        coords = {"time": ("time", self.t, {"units": "s"})}
        if self.chamber_unbalance is not None:
            Uc = self.chamber_unbalance
            data["chamber_unbalance_x"] = (("time", "chamber"), Uc.real,
                                           {"units": "kg m", "long_name": "each chamber's film"})
            data["chamber_unbalance_y"] = (("time", "chamber"), Uc.imag, {"units": "kg m"})
            coords["chamber_radius"] = ("chamber", [c.chamber_radius for c in
                                                    self.system.liquid.chambers], {"units": "m"})
        attrs = {"model": "wall film coupled with the rotor (autobalance.liquid.simulate)",
                 "film_start_speed_rad_s": self.film_start_speed,
                 "film_start_s": self.film_start, "status": self.status,
                 "spin": "motor" if self.motor else "profile",
                 "system": json.dumps({"name": self.system.name})}
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def to_netcdf(self, path: str | Path) -> None:
        """Write :meth:`to_xarray` to a NetCDF file, atomically
        (:func:`autobalance.atomic.atomic_output`: a failed write leaves the previous file).

        Parameters
        ----------
        path : str or Path
            The file [-] (replaced whole).

        Raises
        ------
        autobalance.atomic.OutputError
            The file could not be written (one line; the previous file unchanged).
        """
        from ..atomic import atomic_output

        ds = self.to_xarray()
        with atomic_output(path) as tmp:
            ds.to_netcdf(tmp, engine="netcdf4",
                         encoding={name: {"zlib": True, "complevel": 4} for name in ds.data_vars})


def film_rotor(system: System) -> VerticalRotor:
    """The liquid models' rotor of a System (isotropic suspension, checked by the callers).

    Parameters
    ----------
    system : System
        The machine.

    Returns
    -------
    VerticalRotor
        M without the liquid [kg], k = kx [N/m], c = cx [N*s/m], D [kg*m].
    """
    r, s = system.rotor, system.suspension
    return VerticalRotor(r.mass, s.kx, s.cx, r.unbalance)


def liquid_parts(system: System) -> tuple[VerticalRotor, LiquidBalancer]:
    """The liquid analyses' view of a machine with a ``[liquid]`` section: its rotor
    (:func:`film_rotor`) and its balancer (:meth:`LiquidBalancer.of`). The one adapter from a
    System to the liquid package's analyses (papers, studies and the CLI use it).

    Parameters
    ----------
    system : System
        The machine; ParameterError (one line) for what the liquid models do not cover
        (:func:`require_liquid_machine`) and for partitions (:meth:`LiquidBalancer.of`).

    Returns
    -------
    tuple
        (VerticalRotor, LiquidBalancer).
    """
    require_liquid_machine(system)
    return film_rotor(system), LiquidBalancer.of(system.liquid)


def require_liquid_machine(system: System) -> None:
    """One-line errors for a machine the liquid models (quasi-static, lumped, wall film) do not
    cover: no ``[liquid]`` section, balls beside it, gravity that does not fit the axis, an
    anisotropic suspension, dry friction, base motion, an unbalance schedule.

    Parameters
    ----------
    system : System
        The machine.
    """
    liq, s, r = system.liquid, system.suspension, system.rotor
    if liq is None:
        raise ParameterError("liquid", None, "needs a [liquid] section (e.g. the preset "
                             "leblanc_003)")
    if system.balancer.n_balls:
        raise ParameterError("balancer.n_balls", system.balancer.n_balls,
                             "must be 0 for the liquid analyses and studies (balls beside a "
                             "liquid run with `autobalance simulate` and `sweep`)")
    require_axis_gravity(system)
    if s.kx != s.ky or s.cx != s.cy:
        raise ParameterError("suspension.ky", s.ky, "must equal kx (and cy cx): the liquid "
                             "models' rotor is isotropic")
    for name in ("dry_friction_force", "base_amplitude_x", "base_amplitude_y"):
        if getattr(s, name) != 0.0:
            raise ParameterError(f"suspension.{name}", getattr(s, name),
                                 "must be 0 with a liquid balancer (not modelled yet)")
    if r.unbalance_schedule:
        raise ParameterError("rotor.unbalance_schedule", list(r.unbalance_schedule),
                             "must be empty with a liquid balancer (not modelled yet)")


def require_axis_gravity(system: System) -> None:
    """One-line errors for [gravity] that does not fit the liquid's axis: none in the plane of
    a vertical axis (gravity is along it), some in the plane of a horizontal one.

    Parameters
    ----------
    system : System
        A machine with a ``[liquid]`` section.
    """
    axis, g = system.liquid.axis, system.gravity.g
    if axis == "vertical" and g != 0.0:
        raise ParameterError("gravity.g", g, "must be 0 with a vertical-axis liquid balancer "
                             "([gravity] acts in the rotor's plane)")
    if axis == "horizontal" and not g > 0.0:
        raise ParameterError("gravity.g", g, "must be > 0 with a horizontal-axis liquid "
                             "balancer (e.g. '9.81 m/s^2'; [gravity] is in the plane)")


def _check(system: System, spin: SpeedProfile | MotorDrive) -> None:
    """One-line errors for what the film model does not cover: the machine's
    (:func:`require_liquid_machine`) and a motor drive."""
    require_liquid_machine(system)
    if isinstance(spin, MotorDrive) or not isinstance(spin, SpeedProfile):
        raise ParameterError("profile.kind", "motor", "simulate_liquid needs a prescribed "
                             "speed profile (constant, ramp, table, std or tsr); a motor drive "
                             "runs with autobalance.simulate.simulate")


def check_liquid_run(system: System, spin: SpeedProfile, g_axial: float = G_STANDARD) -> float:
    """Refuse, before any work, a machine or profile outside the film model; return the speed
    where its film starts (:func:`film_start`: from rest on a vertical axis, where the spin-up
    puts the liquid on the lid).

    Parameters
    ----------
    system : System
        The machine (a ``liquid`` section, no balls).
    spin : SpeedProfile
        Its profile.
    g_axial : float
        Gravity along the vertical axis [m/s^2].

    Returns
    -------
    float
        The profile's speed at the film's start [rad/s].

    Raises
    ------
    ParameterError
        As :func:`simulate_liquid` (one line).
    """
    _check(system, spin)
    fs = film_start(system, spin, g_axial)
    chamber_films(system, fs, 256, 0j)            # the wall film's checks (a thin film)
    return fs.speed


def chamber_films(system: System, fs: FilmStart, n_cells: int, centre: complex) -> FilmsState:
    """The chambers' films at the film's start (:func:`autobalance.liquid.film.films_state`:
    the wall film's one-line checks, a thin film per chamber), each lagging its wall as the
    spin-up leaves it (``fs.lag``), on a wall at ``centre`` [m] from the potential's centre;
    ``n_cells`` [-] cells per chamber before :func:`chamber_cells`.

    Parameters
    ----------
    system : System
        The machine (its ``liquid`` section: chambers [m], volumes [m^3], rho [kg/m^3], nu
        [m^2/s]).
    fs : FilmStart
        Where the film starts (:func:`film_start`; its lag per chamber [-]).
    n_cells : int
        Film cells per chamber [-].
    centre : complex
        The wall's centre from the potential's centre [m].

    Returns
    -------
    FilmsState
    """
    liq = system.liquid
    ch = liq.chambers
    return films_state([c.chamber_radius for c in ch], [c.chamber_height for c in ch],
                       [c.volume for c in ch], liq.density, liq.kinematic_viscosity,
                       chamber_cells(ch, n_cells), [c.partitions for c in ch],
                       [lag * c.chamber_radius for lag, c in zip(fs.lag, ch)], centre)


def run_seconds_estimate(system: System, spin: SpeedProfile | MotorDrive,
                         n_cells: int = 256) -> float:
    """Estimated wall time of :func:`simulate_liquid` [s], or of a run of balls beside the
    liquid (the films' steps dominate it): film steps from the CFL condition on the uniform film
    (wave speed Omega sqrt(R eta), cell 2 pi R / n) over the profile from omega_0, times the
    measured cost of a step.

    Parameters
    ----------
    system : System
        The machine (checked by :func:`check_liquid_run` without balls).
    spin : SpeedProfile or MotorDrive
        Its profile, or a motor drive (at its larger end speed throughout: an upper bound).
    n_cells : int
        Film cells [-].
    """
    from ..core.shallow_water import CFL

    if isinstance(spin, MotorDrive):
        tt, ww = np.array([0.0, spin.duration]), np.full(2, max(spin.initial_speed, spin.final_speed))
    else:
        w0 = (film_start_speed(system.liquid, system.gravity.g) if system.balancer.n_balls
              else check_liquid_run(system, spin))
        _, tt, ww = _film_table(spin, w0)
    mean_speed = float(np.sum(0.5 * (ww[1:] + ww[:-1]) * np.diff(tt)) / tt[-1])
    chambers = system.liquid.chambers
    # the step is the most restrictive chamber's; a step costs as many cells as all films hold
    rate = max(np.sqrt(c.chamber_radius * c.volume / (2 * np.pi * c.chamber_radius
                                                      * c.chamber_height))
               / (2 * np.pi * c.chamber_radius / n_cells) for c in chambers)
    steps = STEP_FACTOR * tt[-1] * mean_speed * rate / CFL
    return float(steps * STEP_COST_256 * n_cells * len(chambers) / 256)


def chamber_cells(chambers: Sequence[LiquidDevice], n_cells: int) -> list[int]:
    """Film cells per chamber [-]: ``n_cells`` rounded up to whole compartments of its
    partitions."""
    return [c.partitions * -(-int(n_cells) // c.partitions) if c.partitions else int(n_cells)
            for c in chambers]


def inner_wall_status(films: Sequence, chambers: Sequence[LiquidDevice],
                      t0: float) -> tuple[str, str]:
    """("ok", "") or (``outside_model``, the one-line reason) when a chamber's film reaches
    its inner wall (:meth:`.film.FilmRun.inner_wall_time`; the earliest, named when there are
    several chambers); ``films`` one :class:`.film.FilmRun` per chamber, their times from t0
    [s] on the profile."""
    touches = [(tc, c) for f, c in zip(films, chambers)
               if (tc := f.inner_wall_time(c.inner_radius)) is not None]
    if not touches:
        return "ok", ""
    touch, c = min(touches, key=lambda x: x[0])
    which = "" if len(chambers) == 1 else f" of the chamber R = {c.chamber_radius:.4g} m"
    return (RunStatus.OUTSIDE_MODEL.label,
            f"the film{which} reaches the inner wall (r_i = {c.inner_radius:.4g} m) at t = "
            f"{t0 + touch:.4g} s: the wall-film model does not hold from there")


def simulate_liquid(system: System, spin: SpeedProfile, *, n_cells: int = 256,
                    n_out: int | None = None, g_axial: float = G_STANDARD) -> LiquidSimulation:
    """Run a liquid-balancer System through a speed profile (module docstring).

    Parameters
    ----------
    system : System
        Rotor (mass [kg], unbalance [kg*m]), isotropic suspension (k [N/m], c [N*s/m]) and a
        ``liquid`` section; no balls; [gravity] in the plane for a horizontal axis.
    spin : SpeedProfile
        Prescribed speed [rad/s] over time [s].
    n_cells : int
        Film cells around the wall [-] (rounded up to a multiple of the partitions).
    n_out : int or None
        Output samples from the film's start to the end [-]; None: 1001, or 8 per revolution
        if more (for the revolution average), at most 200 001.
    g_axial : float
        Gravity along the vertical axis, for the entrainment speed [m/s^2].

    Returns
    -------
    LiquidSimulation

    Raises
    ------
    ParameterError
        One line for a machine or profile outside the film model (balls beside the liquid, an
        anisotropic suspension, a motor drive, in-plane gravity that does not fit the axis, a
        profile that never reaches or later falls below omega_f).
    """
    _check(system, spin)
    fs = film_start(system, spin, g_axial)
    liq, s = system.liquid, system.suspension
    t0, tt, ww = _film_table(spin, film_start_speed(liq, system.gravity.g, g_axial), fs.time)
    w0 = fs.speed
    if n_out is None:
        n_out = film_samples(tt, ww)
    if isinstance(n_out, bool) or int(n_out) != n_out or n_out < 2:
        raise ParameterError("n_out", n_out, "must be an integer >= 2")
    T = float(tt[-1])
    rotor = film_rotor(system)
    gp = system.gravity.g if liq.axis == "horizontal" else 0.0
    gdir = system.gravity.direction
    sag = system.total_mass * gp / s.kx * np.exp(1j * gdir)      # static, inertial frame
    start = pool_response(rotor, liq.total_volume, liq.density, ww[0])  # liquid as rigid mass
    ch = liq.chambers
    cells = chamber_cells(ch, n_cells)
    run = coupled_run(rotor, [c.chamber_radius for c in ch], [c.chamber_height for c in ch],
                      [c.volume for c in ch], (tt, ww), T, density=liq.density,
                      viscosity=liq.kinematic_viscosity, n_cells=cells,
                      partitions=[c.partitions for c in ch],
                      save_dt=T / (int(n_out) - 1), deflection=complex(start + sag),
                      velocity=complex(-1j * ww[0] * sag), gravity=gp, gravity_direction=gdir,
                      film_speed=[lag * c.chamber_radius for lag, c in zip(fs.lag, ch)])
    psi = spin_angle(run.t, tt, ww)
    whirl = run.deflection - sag * np.exp(-1j * psi)
    U = run.unbalance
    status, message = inner_wall_status(run.films, ch, t0)
    per = None if len(ch) == 1 else np.stack([f.unbalance for f in run.films], axis=-1)
    return LiquidSimulation(system, t0 + run.t, np.interp(run.t, tt, ww), whirl, U,
                            revolution_average(psi, U), t0, w0, float(spin.nominal_speed),
                            run.steps, status, message, per)


def ramp_run_up(system: System, omega_end: float, duration: float, *,
                n_cells: int = 256) -> RunUp:
    """A machine's linear run-up from rest to ``omega_end`` in ``duration`` through the film
    model (:func:`simulate_liquid`: the film starts where the spin-up says, every chamber's
    film coupled with the rotor), as the lumped model's :class:`autobalance.liquid.RunUp`, for
    the liquid models' linear run-up with several chambers or on a horizontal axis (one chamber on
    a vertical axis keeps :func:`autobalance.liquid.film.physical_run_up`, which starts the film
    at 003 eq 6's speed).

    Parameters
    ----------
    system : System
        The machine (a ``[liquid]`` section; [gravity] in the plane on a horizontal axis).
    omega_end : float
        Final speed [rad/s].
    duration : float
        Time of the run-up [s].
    n_cells : int
        Film cells per chamber [-].

    Returns
    -------
    RunUp
        t [s] from rest (the samples from the film's start on), omega [rad/s], amplitude and
        amplitude_dry [m] (the chambers empty), liquid_angle [rad] and liquid_unbalance
        [kg*m] of the films' summed moment.
    """
    sim = simulate_liquid(system, SpeedProfile.ramp(0.0, positive("omega_end", omega_end),
                                                    positive("duration", duration), duration),
                          n_cells=n_cells)
    if sim.status != "ok":
        raise ParameterError("liquid", "the run-up", sim.message)
    U = sim.liquid_unbalance
    return RunUp(t=sim.t, omega=sim.speed, amplitude=sim.amplitude,
                 liquid_angle=np.angle(U), liquid_unbalance=np.abs(U),
                 amplitude_dry=sim.amplitude_without_liquid)
