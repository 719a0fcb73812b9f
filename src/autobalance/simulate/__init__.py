"""Running the model: the one state layout's packing (``pack``), :func:`simulate` (one run) and
:func:`simulate_batch` (many runs in one compiled call) and
:func:`simulate_branches` (runs that share their history up to a profile knot), their results with one status
(``result``), and an independent scipy reference of the same equations (``reference``)."""
from .result import BatchResult, Simulation, SimulationError
from .run import simulate, simulate_batch, simulate_branches

__all__ = ["BatchResult", "Simulation", "SimulationError", "simulate", "simulate_batch",
           "simulate_branches"]
