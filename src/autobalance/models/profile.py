"""Spin of the rotor: prescribed speed profiles (piecewise linear) or a motor torque law.

Every prescribed profile is compiled to a piecewise-linear table of (time [s], speed [rad/s]); the
spin angle is its exact integral. The 004 profiles (Fig. 3, "standardized speed profile") are not
given numerically in the paper; the shape we use is documented in docs/model.md section 5.
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ._validate import ParameterError, finite, in_range, nonneg, positive

if TYPE_CHECKING:
    import numpy.typing as npt

TWO_PI = 2.0 * math.pi
#: Longest run a profile may describe [s] (about 32 years): the knots of its ramps, seconds
#: apart, stay distinct in double precision within it; a long run is refused before it is
#: integrated anyway (:func:`autobalance.limits.check_run`).
MAX_DURATION = 1e9


def _duration(field: str, value) -> float:
    """A run's duration [s]: > 0 and at most :data:`MAX_DURATION` (ParameterError naming
    ``field``)."""
    v = positive(field, value)
    if v > MAX_DURATION:
        raise ParameterError(field, value, f"must be at most {MAX_DURATION:g} s (about 32 "
                             "years)")
    return v


@dataclass(frozen=True)
class SpeedProfile:
    """Prescribed spin speed, piecewise linear in time.

    Parameters
    ----------
    times : tuple of float
        Knot times [s], strictly increasing, starting at 0; the last is the end of the run.
    speeds : tuple of float
        Spin speed at each knot [rad/s], >= 0.
    nominal_speed : float, optional
        Highest nominal operating speed for the ISO 1940 grade [rad/s]; default max(speeds).
    checkpoints : tuple of float
        Times [s] at which the balancing quality is reported (004: 20 % and 100 % of the run).
    name : str
        Label for reports.
    """

    times: tuple
    speeds: tuple
    nominal_speed: float | None = None
    checkpoints: tuple = ()
    name: str = "table"

    def __post_init__(self):
        t = tuple(finite("profile.times", v) for v in self.times)
        w = tuple(nonneg("profile.speeds", v) for v in self.speeds)
        if len(t) < 2:
            raise ParameterError("profile.times", list(t), "needs at least 2 knots (start and end)")
        if len(t) != len(w):
            raise ParameterError("profile.speeds", list(w), f"needs {len(t)} values, one per time")
        if t[0] != 0.0:
            raise ParameterError("profile.times", list(t), "must start at 0 s")
        if any(b <= a for a, b in zip(t, t[1:])):
            raise ParameterError("profile.times", list(t), "must be strictly increasing")
        object.__setattr__(self, "times", t)
        object.__setattr__(self, "speeds", w)
        nom = max(w) if self.nominal_speed is None else positive("profile.nominal_speed", self.nominal_speed)
        if nom <= 0:
            raise ParameterError("profile.speeds", list(w), "at least one speed must be > 0")
        object.__setattr__(self, "nominal_speed", nom)
        cps = tuple(in_range("profile.checkpoints", c, 0.0, t[-1]) for c in self.checkpoints)
        object.__setattr__(self, "checkpoints", cps or (t[-1],))

    @property
    def duration(self) -> float:
        """Length of the run, the last knot time [s]."""
        return self.times[-1]

    def arrays(self) -> tuple[np.ndarray, np.ndarray]:
        """The knot table as float arrays.

        Returns
        -------
        times : ndarray
            Knot times [s].
        speeds : ndarray
            Spin speed at each knot [rad/s].
        """
        return np.asarray(self.times, float), np.asarray(self.speeds, float)

    def speed(self, t: float | npt.ArrayLike) -> float | np.ndarray:
        """Spin speed at time t (linear interpolation between the knots).

        Parameters
        ----------
        t : float or array_like
            Time [s]; before 0 or after the end the first or last knot's speed holds.

        Returns
        -------
        float or ndarray
            Spin speed w(t) [rad/s], shaped like ``t``.
        """
        tt, ww = self.arrays()
        return np.interp(t, tt, ww)

    # -- constructors -------------------------------------------------------------------------
    @classmethod
    def constant(cls, speed: float, duration: float, *, start_speed: float | None = None) -> "SpeedProfile":
        """Constant speed [rad/s] for ``duration`` [s] (000 Figs. 5, 13, 16, 18 at 1000 rpm).

        Parameters
        ----------
        speed : float
            Spin speed w, held from t = 0 [rad/s], > 0.
        duration : float
            Length of the run [s], > 0.
        start_speed : float or None
            Accepted for call compatibility [rad/s]: None or ``speed`` (a constant profile starts
            at its speed; :meth:`ramp` starts elsewhere). Any other value is refused.

        Returns
        -------
        SpeedProfile
            Two knots (0, ``duration``) at ``speed``, named "constant".
        """
        positive("profile.speed", speed)
        _duration("profile.duration", duration)
        if start_speed is not None and start_speed != speed:
            raise ParameterError("profile.start_speed", start_speed,
                                 f"a constant profile starts at its speed {speed!r} rad/s; "
                                 "use SpeedProfile.ramp to start at another speed")
        return cls((0.0, duration), (speed, speed), name="constant")

    @classmethod
    def ramp(cls, start_speed: float, end_speed: float, ramp_time: float, duration: float) -> "SpeedProfile":
        """Linear ramp from start to end speed [rad/s] over ramp_time [s], then hold to duration.

        Parameters
        ----------
        start_speed : float
            Spin speed at t = 0 [rad/s], >= 0.
        end_speed : float
            Spin speed reached at ``ramp_time`` and held after [rad/s], > 0.
        ramp_time : float
            Length of the linear ramp [s], > 0.
        duration : float
            Length of the run [s], >= ``ramp_time`` (equal: no hold).

        Returns
        -------
        SpeedProfile
            Named "ramp", its quality read at the end.
        """
        nonneg("profile.start_speed", start_speed)
        positive("profile.end_speed", end_speed)
        positive("profile.ramp_time", ramp_time)
        _duration("profile.duration", duration)
        if duration < ramp_time:
            raise ParameterError("profile.duration", duration, f"must be >= ramp_time = {ramp_time}")
        if duration == ramp_time:
            return cls((0.0, ramp_time), (start_speed, end_speed), name="ramp")
        return cls((0.0, ramp_time, duration), (start_speed, end_speed, end_speed), name="ramp")

    @classmethod
    def standard_runup(cls, nominal: float = TWO_PI * 167.0, duration: float = 90.0,
                       runup_fraction: float = 0.2, runup_time: float | None = None) -> "SpeedProfile":
        """004 standard (STD) profile: linear run-up from rest to ``nominal`` [rad/s] and hold.

        The run-up takes ``runup_time`` [s] (default: the first ``runup_fraction`` of the run, 18 s of
        90 s, so that the STD outcome is read at 20 %); a shorter run-up holds ``nominal`` from
        ``runup_time`` on. Quality is read at ``runup_fraction * duration`` [s] (the STD read-out,
        always at nominal speed) and at the end.

        The defaults are 004's (167 Hz, 90 s, 20 %); they serve Python callers only: a config file
        or ``--set``/``--profile`` must give ``nominal`` (:data:`autobalance.config.PROFILE_KINDS`).

        Parameters
        ----------
        nominal : float
            Nominal speed reached at the end of the run-up [rad/s] (004: 2*pi*167 rad/s).
        duration : float
            Length of the run [s] (004: 90 s).
        runup_fraction : float
            Fraction of ``duration`` at which the STD outcome is read [-], within (0, 1]
            (004: 0.2).
        runup_time : float or None
            Length of the linear run-up [s], at most ``runup_fraction * duration``; None = that
            read-out instant.

        Returns
        -------
        SpeedProfile
            Named "std", with checkpoints (``runup_fraction * duration``, ``duration``) [s].
        """
        positive("profile.nominal", nominal)
        _duration("profile.duration", duration)
        in_range("profile.runup_fraction", runup_fraction, 1e-6, 1.0)
        t_read = runup_fraction * duration
        t_ru = t_read
        if runup_time is not None:
            t_ru = positive("profile.runup_time", runup_time)
            if t_ru > t_read:
                raise ParameterError("profile.runup_time", runup_time,
                                     f"must end by the first read-out, runup_fraction x "
                                     f"duration = {t_read:g} s (raise runup_fraction or "
                                     "duration)")
        times = [0.0, t_ru] + ([duration] if duration > t_ru else [])
        speeds = [0.0, nominal] + ([nominal] if duration > t_ru else [])
        return cls(tuple(times), tuple(speeds), nominal_speed=nominal,
                   checkpoints=(t_read, duration), name="std")

    @classmethod
    def tsr(cls, nominal: float = TWO_PI * 167.0, plateau: float = TWO_PI * 100.0,
            duration: float = 90.0, runup_fraction: float = 0.2, runup_time: float | None = None,
            down_time: float = 10.0, plateau_time: float = 20.0, up_time: float = 10.0) -> "SpeedProfile":
        """004 temporary-speed-reduction profile (Fig. 3), piecewise linear.

        0 .. t_ru: run-up from rest to ``nominal``; hold ``nominal`` to ``runup_fraction`` of
        ``duration`` (STD read-out; the hold is kept whenever ``runup_time`` < that instant);
        then ramp down to ``plateau`` (< ``nominal``) in ``down_time``, hold ``plateau_time``,
        ramp back up in ``up_time`` and hold ``nominal`` to the end (TSR read-out at 100 %).
        Times [s], speeds [rad/s].

        The defaults are 004's (167 Hz -> 100 Hz, 90 s, 20 %, 10/20/10 s); they serve Python
        callers only: a config file or ``--set``/``--profile`` must give ``nominal``.

        Parameters
        ----------
        nominal : float
            Nominal speed [rad/s] (004: 2*pi*167 rad/s).
        plateau : float
            Lower plateau speed of the reduction [rad/s], < ``nominal`` (004: 2*pi*100 rad/s,
            above the 94.2 Hz resonance).
        duration : float
            Length of the run [s] (004: 90 s); must exceed the read-out plus the three
            reduction phases.
        runup_fraction : float
            Fraction of ``duration`` at which the STD outcome is read and the reduction starts
            [-], within (0, 1] (004: 0.2).
        runup_time : float or None
            Length of the linear run-up [s], at most ``runup_fraction * duration``; None = that
            read-out instant.
        down_time : float
            Ramp from ``nominal`` down to ``plateau`` [s] (004: 10 s).
        plateau_time : float
            Hold at ``plateau`` [s] (004: 20 s).
        up_time : float
            Ramp from ``plateau`` back up to ``nominal`` [s] (004: 10 s).

        Returns
        -------
        SpeedProfile
            Named "tsr", with checkpoints (STD read-out, ``duration``) [s].
        """
        std = cls.standard_runup(nominal, duration, runup_fraction, runup_time)
        positive("profile.plateau", plateau)
        if plateau >= nominal:
            raise ParameterError("profile.plateau", plateau,
                                 f"must be below profile.nominal = {nominal:g} rad/s (plateau "
                                 f"{plateau / TWO_PI:g} Hz, nominal {nominal / TWO_PI:g} Hz: the "
                                 "TSR is a temporary speed reduction)")
        for name, v in (("profile.down_time", down_time), ("profile.plateau_time", plateau_time),
                        ("profile.up_time", up_time)):
            positive(name, v)
        t_read = std.checkpoints[0]
        t1 = t_read + down_time
        t2 = t1 + plateau_time
        t3 = t2 + up_time
        if t3 >= duration:
            raise ParameterError("profile.duration", duration,
                                 f"must exceed run-up + reduction phases = {t3:g} s")
        t_ru = std.times[1]
        # run-up, then hold nominal up to the STD read-out (no hold if the run-up ends there)
        head_t = [0.0, t_ru] + ([t_read] if t_read > t_ru else [])
        head_w = [0.0, nominal] + ([nominal] if t_read > t_ru else [])
        times = head_t + [t1, t2, t3, duration]
        speeds = head_w + [plateau, plateau, nominal, nominal]
        return cls(tuple(times), tuple(speeds), nominal_speed=nominal,
                   checkpoints=(t_read, duration), name="tsr")


@dataclass(frozen=True)
class MotorDrive:
    """Spin driven by a motor torque law with the spin as a degree of freedom (000 eq 15-18).

    Parameters
    ----------
    law : str
        "constant": T = T0; "linear": T = T0 (1 - w/w_f); "harmonic": T = T0 (1 - sin(pi w / 2 w_f))
        (000 Table 1).
    torque : float
        T0 [N*m] (000 Tables 1-2: 25 N*m).
    final_speed : float
        w_f [rad/s] (000: n_f = 1000 rpm).
    duration : float
        Length of the simulation [s].
    hold_fraction : float
        When the speed first reaches hold_fraction*w_f the speed controller takes over and holds
        that speed (prescribed from then on); t_f is that instant. 1 = exactly w_f.
    initial_speed : float
        Spin speed at t = 0 [rad/s].
    """

    law: str
    torque: float
    final_speed: float
    duration: float
    hold_fraction: float = 1.0
    initial_speed: float = 0.0

    LAWS = ("constant", "linear", "harmonic")

    def __post_init__(self):
        if self.law not in self.LAWS:
            raise ParameterError("drive.law", self.law, f"must be one of {list(self.LAWS)}")
        positive("drive.torque", self.torque)
        positive("drive.final_speed", self.final_speed)
        _duration("drive.duration", self.duration)
        in_range("drive.hold_fraction", self.hold_fraction, 0.01, 1.0)
        nonneg("drive.initial_speed", self.initial_speed)

    @property
    def nominal_speed(self) -> float:
        """Nominal speed for the ISO 1940 grade, the final speed w_f [rad/s]."""
        return self.final_speed

    @property
    def checkpoints(self) -> tuple:
        """Times at which the balancing quality is reported: the end of the run [s]."""
        return (self.duration,)

    name = "motor"

    def torque_at(self, w: float | npt.ArrayLike) -> np.ndarray:
        """Motor torque [N*m] at spin speed w [rad/s] (000 Table 1 laws).

        Parameters
        ----------
        w : float or array_like
            Spin speed [rad/s].

        Returns
        -------
        ndarray
            Torque T(w) [N*m], shaped like ``w``: T0, T0 (1 - w/w_f) or
            T0 (1 - sin(pi w / 2 w_f)) for the constant, linear and harmonic laws.
        """
        w = np.asarray(w, float)
        if self.law == "constant":
            return np.full_like(w, self.torque)
        if self.law == "linear":
            return self.torque * (1.0 - w / self.final_speed)
        return self.torque * (1.0 - np.sin(np.pi * w / (2.0 * self.final_speed)))


#: The registry of speed-profile kinds: name -> constructor taking the kind's parameters in SI.
#: A new kind is a constructor here plus its keys in the config schema
#: (autobalance.config.schema.PROFILE_KINDS); the kernels only see the knots.
PROFILE_KINDS = {"constant": SpeedProfile.constant, "ramp": SpeedProfile.ramp,
                 "table": SpeedProfile, "std": SpeedProfile.standard_runup,
                 "tsr": SpeedProfile.tsr, "motor": MotorDrive}
