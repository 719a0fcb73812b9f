"""Results of a run (`Simulation`) and of a batch (`BatchResult`): arrays + derived quantities."""
from __future__ import annotations

import dataclasses
import json
from typing import TYPE_CHECKING

import numpy as np

from .. import __version__
from ..core.layout import (S_AMAX, S_EVENTS, S_HOLDS, S_IMPACTS, S_RAMPS, S_REJECTED, S_RHS, S_STATUS, S_STEPS,
                          S_TAMAX, S_TFINAL, S_THOLD, S_XMAX, S_YMAX, RunStatus, alpha_dot_slice,
                          alpha_slice, psi_index, speed_index)
from ..models import MotorDrive, System
from ..physics.iso1940 import grade_class, grade_value
from ..physics.unbalance import residual_unbalance

if TYPE_CHECKING:
    from pathlib import Path

    import numpy.typing as npt



class SimulationError(RuntimeError):
    """A numerical failure of a run (raised only when throw=True)."""


def residual_unbalance_history(system: System, alpha: np.ndarray, t: np.ndarray) -> np.ndarray:
    """Complex residual unbalance [kg*m] at the times ``t`` [s] of a run: the rotor's U(t)
    (``Rotor.unbalance_table``) with :func:`autobalance.physics.unbalance.residual_unbalance`.

    Parameters
    ----------
    system : System
        The machine (its unbalance table [kg*m] over time [s], balls and ring eccentricity).
    alpha : ndarray (n_t, N)
        Ball angles from the unbalance [rad].
    t : ndarray (n_t,)
        Times [s].

    Returns
    -------
    ndarray of complex (n_t,)
        W(t) [kg*m] (000 eq 22 / 47).
    """
    unb_t, unb_u = system.rotor.unbalance_table()
    U = np.interp(t, unb_t, unb_u) if unb_t.size > 1 else np.full(np.shape(t), unb_u[0])
    return residual_unbalance(system, alpha, U)


def wrap_degrees(angles: float | npt.ArrayLike) -> np.ndarray:
    """Angles [deg] wrapped to (-180, 180] (the unwrapped history stays in ``alpha``).

    Parameters
    ----------
    angles : float or array_like
        Angles [deg], any winding (e.g. -578).

    Returns
    -------
    ndarray
        The same directions in (-180, 180] [deg] (-578 -> 142, -180 -> 180).
    """
    a = np.asarray(angles, float)
    return 180.0 - np.mod(180.0 - a, 360.0)


def _asdict(obj):
    d = dataclasses.asdict(obj)
    return json.loads(json.dumps(d, default=lambda o: list(o) if isinstance(o, tuple) else str(o)))


@dataclasses.dataclass
class Simulation:
    """Time histories of one run. Angles [rad], lengths [m], unbalance [kg*m], G [mm/s]."""

    system: object
    spin: object
    initial: object
    options: object
    t: np.ndarray
    states: np.ndarray
    stats: np.ndarray
    order: np.ndarray
    #: balls beside a liquid: the liquid's histories (autobalance.simulate.hybrid.LiquidPart)
    liquid: object = None

    def __post_init__(self):
        n = self.system.balancer.n_balls
        y = self.states
        inv = np.argsort(self.order) if n else np.zeros(0, int)
        self.u = y[:, 0]
        self.v = y[:, 1]
        self.psi = y[:, psi_index(n)]
        self.speed = y[:, speed_index(n)]
        self.alpha = y[:, alpha_slice(n)][:, inv]
        self.alpha_dot = y[:, alpha_dot_slice(n)][:, inv]
        c, s = np.cos(self.psi), np.sin(self.psi)
        self.x = self.u * c - self.v * s
        self.y = self.u * s + self.v * c
        self.amplitude = np.hypot(self.u, self.v)
        res = residual_unbalance_history(self.system, self.alpha, self.t)
        if self.liquid is not None:             # the liquid's part turning with the rotor
            res = res + self.liquid.synchronous_unbalance
        self.residual_unbalance = np.abs(res)
        self.residual_angle = np.angle(res)
        self.grade_G = grade_value(self.residual_unbalance, self.system.total_mass, self.spin.nominal_speed)
        status = RunStatus.of(self.stats[S_STATUS])
        self.status = status.label
        self.message = status.message
        if self.status != "ok":
            self.message += f" at t = {self.stats[S_TFINAL]:.6g} s"
        self.title = f"{self.system.name or 'system'} - {getattr(self.spin, 'name', 'profile')}"

    # -- derived scalars -------------------------------------------------------------------
    @property
    def note(self) -> str | None:
        """What a finished run has to say beside its numbers (None: nothing); a run that did not
        finish says why in ``message``."""
        return None

    @property
    def n_balls(self) -> int:
        """Number of balls N of the run's balancer."""
        return self.system.balancer.n_balls

    @property
    def resolves_revolutions(self) -> bool:
        """Whether the stored history samples a revolution at the nominal speed at least twice
        (median spacing <= T_rev / 2), which :meth:`settle` needs: not with ``options.save_dt
        < 0`` (only the checkpoints) or a save_dt longer than half a revolution."""
        if getattr(self.options, "save_dt", 0.0) < 0 or self.t.size < 3:
            return False
        t_rev = 2 * np.pi / max(self.spin.nominal_speed, 1e-300)
        return bool(np.median(np.diff(self.t)) <= 0.5 * t_rev)

    def settle(self, threshold: float | None = None):
        """Per ball: settling time [s] and net revolutions relative to the rotor before it [-].

        The ball counts as moving while its drift averaged over one revolution at the nominal
        speed, |alpha(t) - alpha(t - T_rev)| / T_rev, exceeds ``threshold`` [rad/s] (default
        1e-3 x nominal speed); the average removes the once-per-revolution wobble that gravity
        forces on the balls of a horizontal rotor (000 eq 50-55).

        Parameters
        ----------
        threshold : float or None
            Drift speed above which a ball counts as moving [rad/s] (None: 1e-3 x nominal
            speed).

        Returns
        -------
        times : list of float or None
            Per ball, the last time it was moving [s] (the first sample's if never); None for
            every ball when the stored history does not resolve a revolution
            (:attr:`resolves_revolutions`: ``options.save_dt < 0`` keeps only the checkpoints).
        revolutions : list of float or None
            Per ball, (alpha at that time - alpha(0)) / 2 pi [-]; None as ``times``.
        """
        w = self.spin.nominal_speed
        thr = threshold if threshold is not None else 1e-3 * w
        t_rev = 2 * np.pi / w
        if not self.resolves_revolutions:
            return [None] * self.n_balls, [None] * self.n_balls
        lag = np.searchsorted(self.t, self.t - t_rev)
        times, revs = [], []
        for i in range(self.n_balls):
            a = self.alpha[:, i]
            dt = np.maximum(self.t - self.t[lag], 1e-300)
            drift = np.where(self.t >= t_rev, np.abs(a - a[lag]) / dt, np.abs(self.alpha_dot[:, i]))
            moving = np.nonzero(drift > thr)[0]
            k = moving[-1] if moving.size else 0
            times.append(float(self.t[k]))
            revs.append(float((self.alpha[k, i] - self.alpha[0, i]) / (2 * np.pi)))
        return times, revs

    def at(self, time: float) -> dict:
        """Balancing quality at the output sample closest to ``time`` [s].

        Parameters
        ----------
        time : float
            Time of the read-out [s].

        Returns
        -------
        dict
            time_s [s], grade_G_mm_s [mm/s], iso_class_G_mm_s (the smallest ISO 1940 class
            the grade meets, :func:`autobalance.physics.iso1940.grade_class`; inf above
            G4000) [mm/s], residual_unbalance_kg_m [kg*m], ball_angles_deg (from the
            unbalance, wrapped to (-180, 180]; ``alpha`` keeps the unwrapped history) [deg],
            amplitude_m [m], speed_rad_s [rad/s] of that sample.
        """
        k = int(np.argmin(np.abs(self.t - time)))
        g = float(self.grade_G[k])
        return {
            "time_s": float(self.t[k]),
            "grade_G_mm_s": g,
            "iso_class_G_mm_s": float(grade_class(g)) if np.isfinite(g) else float("nan"),
            "residual_unbalance_kg_m": float(self.residual_unbalance[k]),
            "ball_angles_deg": [float(a) for a in wrap_degrees(np.degrees(self.alpha[k]))],
            "amplitude_m": float(self.amplitude[k]),
            "speed_rad_s": float(self.speed[k]),
        }

    def summary(self) -> dict:
        """JSON-able summary in SI (unit-suffixed keys)."""
        st = self.stats
        settle_t, revs = self.settle()
        out = {
            "status": self.status,
            "message": self.message,
            "system": self.system.name,
            "profile": getattr(self.spin, "name", ""),
            "n_balls": self.n_balls,
            "duration_s": float(self.t[-1]),
            "nominal_speed_rad_s": float(self.spin.nominal_speed),
            "initial_grade_G_mm_s": float(self.grade_G[0]),
            "final": self.at(self.t[-1]),
            "checkpoints": [self.at(c) for c in self.spin.checkpoints],
            "max_amplitude_m": float(st[S_AMAX]),
            "time_of_max_amplitude_s": float(st[S_TAMAX]),
            "x_max_m": float(st[S_XMAX]),
            "y_max_m": float(st[S_YMAX]),
            "ball_settle_time_s": settle_t,
            "ball_revolutions": revs,
            "ball_contacts": int(st[S_IMPACTS]),
            "solver": {"steps": int(st[S_STEPS]), "rejected": int(st[S_REJECTED]),
                       "events": int(st[S_EVENTS]), "rhs_evaluations": int(st[S_RHS]),
                       "exact_holds": int(st[S_HOLDS]), "exact_ramps": int(st[S_RAMPS])},
        }
        if isinstance(self.spin, MotorDrive):
            out["time_to_final_speed_s"] = float(st[S_THOLD]) if st[S_THOLD] >= 0 else None
        if self.liquid is not None:
            L = self.liquid
            U = L.synchronous_unbalance[-1]
            out["liquid"] = {
                "model": "wall film beside the balls (autobalance.simulate.hybrid)",
                "film_start_s": L.film_start, "film_start_speed_rad_s": L.film_start_speed,
                "film_steps": L.steps, "liquid_unbalance_kg_m": float(abs(U)),
                "liquid_angle_deg": float(np.degrees(np.angle(U))),
                "chambers": [{"chamber_radius_m": c.chamber_radius,
                              "liquid_unbalance_kg_m": float(abs(u)),
                              "liquid_angle_deg": float(np.degrees(np.angle(u)))}
                             for c, u in zip(self.system.liquid.chambers,
                                             L.chamber_unbalance[-1])]}
        return out

    def to_netcdf(self, path: str | Path) -> None:
        """Write :meth:`to_xarray` to a NetCDF-4 file with zlib-compressed variables, atomically
        (:func:`autobalance.atomic.atomic_output`: a failed write leaves the previous file).

        Parameters
        ----------
        path : str or Path
            The file to write (replaced whole).

        Raises
        ------
        autobalance.atomic.OutputError
            The file could not be written (one line; the previous file unchanged).
        """
        from ..atomic import atomic_output

        ds = self.to_xarray()
        enc = {name: {"zlib": True, "complevel": 4} for name in ds.data_vars}
        with atomic_output(path) as tmp:
            ds.to_netcdf(tmp, engine="netcdf4", encoding=enc)

    def to_xarray(self):
        """xarray.Dataset with dims (time, ball), units and long names; parameters in attrs."""
        import xarray as xr

        ball = np.arange(self.n_balls)

        def var(data, dims, units, long):
            return xr.Variable(dims, data, {"units": units, "long_name": long})

        ds = xr.Dataset(
            {
                "x": var(self.x, "time", "m", "rotor displacement x (inertial)"),
                "y": var(self.y, "time", "m", "rotor displacement y (inertial)"),
                "u": var(self.u, "time", "m", "rotor displacement along the unbalance (rotor frame)"),
                "v": var(self.v, "time", "m", "rotor displacement across the unbalance (rotor frame)"),
                "amplitude": var(self.amplitude, "time", "m", "whirl amplitude |x + i y|"),
                "alpha": var(self.alpha, ("time", "ball"), "rad",
                             "ball angle from the unbalance, unwrapped (continuous: whole turns "
                             "relative to the rotor kept)"),
                "alpha_dot": var(self.alpha_dot, ("time", "ball"), "rad/s", "ball speed relative to the rotor"),
                "psi": var(self.psi, "time", "rad", "spin angle"),
                "speed": var(self.speed, "time", "rad/s", "spin speed"),
                "residual_unbalance": var(self.residual_unbalance, "time", "kg*m", "residual unbalance |U + sum m R e^(i alpha)|"),
                "residual_angle": var(self.residual_angle, "time", "rad", "direction of the residual unbalance"),
                "grade_G": var(self.grade_G, "time", "mm/s", "ISO 1940-1 balance grade G"),
            },
            coords={"time": ("time", self.t, {"units": "s"}), "ball": ("ball", ball)},
        )
        if self.liquid is not None:
            L = self.liquid
            for name, val, long in (
                    ("liquid_unbalance", L.unbalance, "the liquid's first moment about the "
                     "chamber centre (rotor frame; 0 before the film starts)"),
                    ("synchronous_unbalance", L.synchronous_unbalance, "the liquid's moment "
                     "averaged over one revolution")):
                ds[name + "_x"] = var(val.real, "time", "kg*m", long + ", x")
                ds[name + "_y"] = var(val.imag, "time", "kg*m", long + ", y")
            ds["chamber_unbalance_x"] = var(L.chamber_unbalance.real, ("time", "chamber"),
                                            "kg*m", "each chamber's film moment, x")
            ds["chamber_unbalance_y"] = var(L.chamber_unbalance.imag, ("time", "chamber"),
                                            "kg*m", "each chamber's film moment, y")
            ds = ds.assign_coords(chamber_radius=("chamber", [
                c.chamber_radius for c in self.system.liquid.chambers], {"units": "m"}))
            ds.attrs["film_start_s"] = L.film_start
        ds.attrs.update({
            "title": self.title,
            "autobalance_version": __version__,
            "status": self.status,
            "message": self.message,
            "system": json.dumps(_asdict(self.system)),
            "spin": json.dumps(_asdict(self.spin)),
            "initial": json.dumps(_asdict(self.initial)),
            "options": json.dumps(_asdict(self.options)),
            "summary": json.dumps(self.summary()),
        })
        return ds


@dataclasses.dataclass
class BatchResult:
    """States at the output times of many runs: states (n_runs, n_times, 2*nq)."""

    systems: list
    spin: object
    options: object
    t: np.ndarray
    states: np.ndarray
    stats: np.ndarray
    orders: np.ndarray
    status: list

    def __post_init__(self):
        n = self.systems[0].balancer.n_balls
        inv = np.argsort(self.orders, axis=1) if n else self.orders
        a = self.states[:, :, alpha_slice(n)]
        self.alpha = np.take_along_axis(a, inv[:, None, :], axis=2) if n else a
        res = np.stack([residual_unbalance_history(s, self.alpha[k], self.t) for k, s in enumerate(self.systems)])
        self.residual_unbalance = np.abs(res)
        mt = np.array([s.total_mass for s in self.systems])
        self.grade_G = grade_value(self.residual_unbalance, mt[:, None], self.spin.nominal_speed)
        self.max_amplitude = self.stats[:, S_AMAX]
