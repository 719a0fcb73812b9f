"""autobalance: simulation and design of passive automatic balancers for rotors.

Public API: the parameter dataclasses, :func:`simulate` (one run), :func:`simulate_batch`
(many runs in one compiled call) and :func:`simulate_branches` (many runs under several speed
profiles that share their start). Configs and presets: :mod:`autobalance.config`.
"""
__version__ = "0.3.2"

import os as _os

# One BLAS thread unless the user set it (before numpy's first import): the package's linear
# algebra is many small matrices (Jacobians, propagators, <= a few hundred rows) where BLAS
# threads gain nothing, and beside another busy process on 2 cores their spin-waits made the
# liquid speed map 11x slower (70 s against 6.1 s; docs/numerics/index.md).
for _v in ("OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"):
    _os.environ.setdefault(_v, "1")

from .models import (BallBalancer, Gravity, InitialState, MotorDrive, ParameterError, Rotor,  # noqa: E402
                     SimOptions, SpeedProfile, Suspension, System)
# Bind the functions after importing the submodule of the same name, so that the package
# attribute stays the function even after ``import autobalance.simulate``.
from .simulate import simulate, simulate_batch, simulate_branches  # noqa: E402
from .simulate import BatchResult, Simulation, SimulationError  # noqa: E402
from .sweep import sweep  # noqa: E402  (the function; autobalance.sweep.* stays importable)

__all__ = ["BallBalancer", "BatchResult", "Gravity", "InitialState", "MotorDrive",
           "ParameterError", "Rotor", "SimOptions", "Simulation", "SimulationError",
           "SpeedProfile", "Suspension", "System", "simulate", "simulate_batch",
           "simulate_branches", "sweep", "__version__"]
