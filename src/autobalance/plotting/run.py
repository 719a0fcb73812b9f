"""The figure of one run of any machine: the one place that tells a liquid's run from a run
with balls when drawing it."""
from __future__ import annotations

from typing import TYPE_CHECKING

from .timeplot import plot_simulation

if TYPE_CHECKING:
    from matplotlib.figure import Figure

__all__ = ["plot_run"]


def plot_run(run: object, *, grade_limit: float = 16.0, grade_label: str | None = None,
             speed_unit: str = "rpm", speed_factor: float | None = None) -> Figure:
    """The figure of one run of any machine (:func:`autobalance.simulate.simulate`'s result): a
    liquid alone over time (:func:`autobalance.plotting.liquid.liquid_run_figure`), otherwise
    :func:`autobalance.plotting.timeplot.plot_simulation`.

    Parameters
    ----------
    run : Simulation or LiquidSimulation
        The run.
    grade_limit : float
        Target grade G [mm/s], drawn as a line.
    grade_label : str, optional
        Its label (default ``"G<grade_limit>"``).
    speed_unit : str
        Unit of the spin-speed axis of a run with balls: "rpm", "Hz", "rad/s", or any label
        with ``speed_factor``.
    speed_factor : float, optional
        Display units per rad/s of ``speed_unit``.

    Returns
    -------
    matplotlib.figure.Figure
    """
    from ..liquid.simulate import LiquidSimulation      # the liquid models load on demand

    if isinstance(run, LiquidSimulation):
        from .liquid import liquid_run_figure

        return liquid_run_figure(run, grade_limit, grade_label)
    return plot_simulation(run, grade_limit=grade_limit, grade_label=grade_label,
                           speed_unit=speed_unit, speed_factor=speed_factor)
