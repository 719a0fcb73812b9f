"""Resource guards: estimate memory and run time *before* allocating or integrating, and refuse
with one line naming the field, the estimate and the limit.

The limits are settings (environment variables), documented in docs/sweeps.md:

``AUTOBALANCE_MAX_MEMORY``   largest single allocation of results, e.g. ``"8 GiB"``
                             (default: half of this machine's memory);
``AUTOBALANCE_MAX_HOURS``    largest estimated run time of one command [h] (default 48);
``AUTOBALANCE_MAX_BALLS``    most balls in one balancer (default 64);
``AUTOBALANCE_MAX_FILE_SIZE``  largest config or sweep file read, e.g. ``"4 MiB"`` (default
                             1 MiB);
``AUTOBALANCE_MAX_NESTING``  deepest nesting of arrays and tables in a config file, a sweep
                             file or a ``--set`` value (default 32 levels).

Steps of one run. DOPRI5's stability region reaches about 3.3 along the imaginary axis and
the rotor-frame eigenvalues reach Omega + omega_n, so a run integrated step by step takes
about ``int (Omega(t) + omega_max) / 3.3 dt`` steps (the *estimate*: 38.1k for 004's 90 s TSR
run, which takes 35.8k with its 167 Hz hold in closed form; 4.6k for a 12 s TSR run that takes
5.6k). A hold at constant speed may be solved in closed form (``simulate.pack.fast_paths``) and
cost nothing, so the *lower bound* counts the speed ramps only, with a safety factor of 2. A run
whose lower bound exceeds ``options.max_steps`` cannot finish and is refused before it starts;
a run whose estimated time (estimate x the measured cost of a step) exceeds the run-time limit
is refused too (a ``duration = "1e12 s"``).
"""
from __future__ import annotations

import math
import os
import re
from typing import Any

#: Imaginary-axis stability limit of DOPRI5 (Hairer-Wanner I, Fig. II.4.4: about 3.3).
DOPRI5_STABILITY = 3.3
#: Measured kernel cost of one step with N balls [s] (README "Speed": 39 ms / 35.8k steps at
#: N = 2); the N-dependence (ball-ball contact pairs) is a conservative linear model.
STEP_COST_S = 0.5e-6
STEP_COST_PER_BALL_S = 0.25e-6

_UNITS = {"": 1, "b": 1, "k": 1e3, "kb": 1e3, "m": 1e6, "mb": 1e6, "g": 1e9, "gb": 1e9,
          "t": 1e12, "tb": 1e12, "kib": 2**10, "mib": 2**20, "gib": 2**30, "tib": 2**40}


class ResourceError(ValueError):
    """An input whose estimated memory or run time exceeds a limit, or a bad limit setting
    (one line naming the field, the estimate and the limit; the CLI exits with code 2)."""

    def __init__(self, message: str):
        super().__init__(" ".join(str(message).split()))


#: The default step budget of a run (``SimOptions.max_steps``) [-].
DEFAULT_MAX_STEPS = 20_000_000


def _physical_memory() -> int:
    try:
        return int(os.sysconf("SC_PAGE_SIZE") * os.sysconf("SC_PHYS_PAGES"))
    except (ValueError, OSError, AttributeError):
        return 8 * 2**30


def parse_bytes(text: str, where: str = "AUTOBALANCE_MAX_MEMORY") -> int:
    """``"8 GiB"``, ``"500MB"``, ``"1e9"`` -> bytes."""
    m = re.fullmatch(r"\s*([0-9.eE+]+)\s*([a-zA-Z]*)\s*", str(text))
    unit = m.group(2).lower() if m else None
    if not m or unit not in _UNITS:
        raise ResourceError(f"{where} = {text!r}: expected a size such as '8 GiB' or '500 MB'")
    try:
        v = float(m.group(1)) * _UNITS[unit]
    except ValueError:
        raise ResourceError(f"{where} = {text!r}: expected a size such as '8 GiB'") from None
    if not math.isfinite(v) or v <= 0:
        raise ResourceError(f"{where} = {text!r}: must be a positive size")
    return int(v)


def max_memory() -> int:
    """The memory limit [bytes] (``AUTOBALANCE_MAX_MEMORY``, default half the machine's)."""
    env = os.environ.get("AUTOBALANCE_MAX_MEMORY")
    return parse_bytes(env) if env else _physical_memory() // 2


def _env_number(name: str, default: float) -> float:
    env = os.environ.get(name)
    if not env:
        return default
    try:
        v = float(env)
    except ValueError:
        v = float("nan")
    if not math.isfinite(v) or v <= 0:
        raise ResourceError(f"{name} = {env!r}: expected a positive number")
    return v


def max_hours() -> float:
    """The run-time limit [h] of one command (``AUTOBALANCE_MAX_HOURS``, default 48)."""
    return _env_number("AUTOBALANCE_MAX_HOURS", 48.0)


def max_balls() -> int:
    """The most balls in one balancer (``AUTOBALANCE_MAX_BALLS``, default 64)."""
    return int(_env_number("AUTOBALANCE_MAX_BALLS", 64))


def fmt_bytes(n: float) -> str:
    """``n`` bytes [B] as text with a binary unit ("1.5 GiB").

    Parameters
    ----------
    n : float
        Size [B].
    """
    for unit, f in (("TiB", 2**40), ("GiB", 2**30), ("MiB", 2**20), ("KiB", 2**10)):
        if n >= f:
            return f"{n / f:.3g} {unit}"
    return f"{int(n)} B"


def fmt_seconds(s: float) -> str:
    """A duration [s] as text in days, hours, minutes or seconds ("2.5 h").

    Parameters
    ----------
    s : float
        Duration [s].
    """
    if s >= 86400:
        return f"{s / 86400:.3g} days"
    if s >= 3600:
        return f"{s / 3600:.3g} h"
    if s >= 60:
        return f"{s / 60:.3g} min"
    return f"{s:.2g} s"


def check_memory(field: str, value: object, nbytes: float, what: str = "results") -> None:
    """Refuse ``field = value`` if its ``nbytes`` [B] exceed the memory limit."""
    lim = max_memory()
    if not math.isfinite(nbytes) or nbytes > lim:
        raise ResourceError(
            f"{field} = {value!r}: the {what} would need about {fmt_bytes(nbytes)}, more than the "
            f"limit of {fmt_bytes(lim)} (set AUTOBALANCE_MAX_MEMORY to raise it)")


def check_runtime(field: str, value: object, seconds: float, what: str = "run") -> None:
    """Refuse ``field = value`` if the estimated run time [s] exceeds the limit."""
    lim = max_hours() * 3600.0
    if not math.isfinite(seconds) or seconds > lim:
        raise ResourceError(
            f"{field} = {value!r}: the {what} would take about {fmt_seconds(seconds)} (estimate), "
            f"more than the limit of {fmt_seconds(lim)} (set AUTOBALANCE_MAX_HOURS to raise it)")


def _speed_integrals(spin) -> tuple[float, float, float]:
    """(int_0^T Omega dt over the whole run [rad], over its ramps only [rad], the ramps'
    duration [s]) of a prescribed piecewise-linear profile; a motor run-up (speed not known in
    advance) gives (0, 0, duration)."""
    times = getattr(spin, "times", None)
    if times is None:
        return 0.0, 0.0, float(spin.duration)
    w = spin.speeds
    total = ramps = ramp_time = 0.0
    for i in range(len(times) - 1):
        dt = times[i + 1] - times[i]
        seg = 0.5 * (w[i] + w[i + 1]) * dt
        total += seg
        if w[i] != w[i + 1]:
            ramps += seg
            ramp_time += dt
    return total, ramps, ramp_time


def steps_estimate(system: Any, spin: Any, options: Any) -> float:
    """Steps of one run integrated step by step (see the module docstring) [-]."""
    T = float(spin.duration)
    w_n = max(system.natural_frequencies)
    h_max = options.max_step if options.max_step > 0 else min(0.05, T / 20.0)
    total, _, _ = _speed_integrals(spin)
    return max((total + w_n * T) / DOPRI5_STABILITY, T / h_max)


def steps_lower_bound(system: Any, spin: Any, options: Any) -> float:
    """A lower bound of the steps of one run: its speed ramps (never solved in closed form)
    at half the stability-limited step count [-]."""
    w_n = max(system.natural_frequencies)
    _, ramps, ramp_time = _speed_integrals(spin)
    return (ramps + w_n * ramp_time) / (2.0 * DOPRI5_STABILITY)


def step_cost(n_balls: int) -> float:
    """Estimated kernel time of one step [s]."""
    return STEP_COST_S + STEP_COST_PER_BALL_S * n_balls


def check_run(system: Any, spin: Any, options: Any, field: str = "profile.duration") -> float:
    """Refuse a run that cannot finish: its steps (lower bound) exceed the step budget, or its
    estimated time exceeds the run-time limit; returns the step estimate.

    A budget lowered below the default ``SimOptions.max_steps`` asks for a partial run (it ends
    with status "max_steps" and the history so far), so the bound is compared with the larger
    of ``options.max_steps`` and that default."""
    budget = max(options.max_steps, DEFAULT_MAX_STEPS)
    n = steps_lower_bound(system, spin, options)
    if n > budget:
        raise ResourceError(
            f"{field} = {spin.duration:g} s: needs at least {n:.3g} integration steps, more than "
            f"options.max_steps = {budget}; shorten the run or raise options.max_steps")
    est = steps_estimate(system, spin, options)
    check_runtime(field, f"{spin.duration:g} s", est * step_cost(system.balancer.n_balls))
    return est


#: Default of ``AUTOBALANCE_MAX_FILE_SIZE`` [B]: configs and sweep files are a few KiB.
DEFAULT_MAX_FILE_BYTES = 2**20
#: Default of ``AUTOBALANCE_MAX_NESTING`` [-]: a config nests three levels (table, section,
#: per-ball list), a sweep file four.
DEFAULT_MAX_NESTING = 32


def max_file_bytes() -> int:
    """The largest config or sweep file read [B] (``AUTOBALANCE_MAX_FILE_SIZE``, default 1 MiB)."""
    env = os.environ.get("AUTOBALANCE_MAX_FILE_SIZE")
    return parse_bytes(env, "AUTOBALANCE_MAX_FILE_SIZE") if env else DEFAULT_MAX_FILE_BYTES


def max_nesting() -> int:
    """The deepest nesting of arrays and tables read from a file or a ``--set`` value [-]
    (``AUTOBALANCE_MAX_NESTING``, default 32)."""
    return int(_env_number("AUTOBALANCE_MAX_NESTING", DEFAULT_MAX_NESTING))


__all__ = ["DEFAULT_MAX_STEPS", "ResourceError", "check_memory", "check_run", "check_runtime",
           "fmt_bytes", "fmt_seconds", "max_balls", "max_file_bytes", "max_hours", "max_memory",
           "max_nesting", "parse_bytes", "step_cost", "steps_estimate", "steps_lower_bound"]
