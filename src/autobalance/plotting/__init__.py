"""Matplotlib figures (Agg canvas, no pyplot) of simulation results, response tables and
sweeps."""
from .sweep import plot_sweep
from .timeplot import plot_response, plot_simulation

__all__ = ["plot_response", "plot_simulation", "plot_sweep"]
