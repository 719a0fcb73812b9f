"""The figures of ``autobalance response`` of a liquid machine (:mod:`autobalance.cli.response`), the one
way the liquid commands save their ``--plot`` (:func:`save_plot`) and name a chamber
(:func:`chamber_label`)."""
from __future__ import annotations

from typing import TYPE_CHECKING

from ..atomic import save_figure

if TYPE_CHECKING:
    from matplotlib.figure import Figure

    from ..config.display import DisplayUnits
    from ..liquid import LiquidModel, RunUp
    from ..models.liquid_balancer import VerticalRotor
    from ..models import LiquidDevice


def chamber_label(du: DisplayUnits, radius: float, volume: float) -> str:
    """A chamber as text: its radius in the config's length unit and its fill in ml, e.g.
    "R = 200 mm, 150 ml" (``du``: :func:`autobalance.config.display.display_units`; radius
    [m], volume [m^3])."""
    return f"R = {du.fmt(radius, 'length')}, {volume * 1e6:.4g} ml"


def save_plot(fig: Figure, plot: str) -> None:
    """Save a liquid command's figure to its ``--plot`` file (120 dpi), atomically: a failed
    write leaves the previous file (:func:`autobalance.atomic.save_figure`, one line naming
    ``--plot``).

    Parameters
    ----------
    fig : matplotlib.figure.Figure
        The figure.
    plot : str
        The file (.png, .pdf, .svg).
    """
    save_figure(fig, plot, "--plot", dpi=120)


def plot_liquid_response(plot: str, st: dict, w0: float, wn: float, ru: RunUp | None,
                         sw: list | None, device: LiquidDevice, name: str, rot: VerticalRotor,
                         model: LiquidModel, label: str | None = None) -> None:
    """The figure of a liquid machine's ``response``: the steady response (with the run-up) or, with a fill
    sweep, the amplitude vs fill.

    Parameters
    ----------
    plot : str
        The figure's file (.png, .pdf, .svg).
    st : dict
        The steady response (:func:`autobalance.liquid.steady.chambers_steady_response`'s keys).
    w0, wn : float
        The film's start speed and the natural frequency [rad/s].
    ru : RunUp or None
        The run-up, if integrated.
    sw : list of dict or None
        The fill sweeps at 0.6-1.2 omega_n (:func:`autobalance.liquid.steady.
        chambers_fill_sweep`'s keys), if computed.
    device : autobalance.models.LiquidDevice
        The machine's ``[liquid]`` section (its chambers and liquid).
    name : str
        Its liquid's name, or "liquid".
    rot : VerticalRotor
        The rotor (D [kg*m] for the title).
    model : LiquidModel
        The lumped model (its placement law names the curve unless ``label``).
    label : str or None
        The model's name in the title.
    """
    import logging

    from ..plotting.liquid import fill_figure, response_figure

    # matplotlib logs a fallback line per missing TeX font when a log axis is drawn
    logging.getLogger("matplotlib.font_manager").setLevel(logging.ERROR)

    R = "/".join(f"{c.chamber_radius:g}" for c in device.chambers)
    rho = name if name != "liquid" else f"rho = {device.density:g} kg/m³"
    if sw is not None:
        # the fill sweep varies V: name the fixed quantities only
        fixed = (f"R = {R} m, {rho}, "
                 f"D = {rot.unbalance * 1e5:.4g} g·cm, {label or model.placement}")
        fig = fill_figure(sw, [f"ω = {s['omega_rad_s']:.3g} rad/s" for s in sw],
                          "Amplitude vs fill (003 Fig. 5)\n" + fixed)
    else:
        title = (f"R = {R} m, V = {device.total_volume * 1e6:.4g} ml "
                 f"({rho}), D = {rot.unbalance * 1e5:.4g} g·cm, {label or model.placement}")
        fig = response_figure(st, w0, wn, ru, title)
    save_plot(fig, plot)
