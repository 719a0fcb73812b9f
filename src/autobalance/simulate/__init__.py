"""Running the model: the one state layout's packing (``pack``), :func:`simulate` (one run) and
:func:`simulate_batch` (many runs in one compiled call), their results with one status
(``result``), and an independent scipy reference of the same equations (``reference``)."""
from .result import BatchResult, Simulation, SimulationError
from .run import simulate, simulate_batch

__all__ = ["BatchResult", "Simulation", "SimulationError", "simulate", "simulate_batch"]
