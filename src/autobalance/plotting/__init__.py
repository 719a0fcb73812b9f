"""Matplotlib figures (Agg canvas, no pyplot) of simulation results and response tables."""
from .timeplot import plot_response, plot_simulation

__all__ = ["plot_response", "plot_simulation"]
