"""Matplotlib figures (Agg canvas, no pyplot) of simulation results, response tables and
sweeps."""
from .sweep import plot_sweep
from .run import plot_run
from .timeplot import plot_response, plot_simulation

__all__ = ["plot_response", "plot_run", "plot_simulation", "plot_sweep"]
