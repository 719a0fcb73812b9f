"""The figure of 001's kinetostatic laws against the liquid from physics
(:func:`autobalance.liquid.kinetostatic_check.kinetostatic_vs_physics`; docs/liquid/kinetostatics.md
sec. 2b): data in, a matplotlib Figure out (angles in degrees as computed), nothing saved here."""
from __future__ import annotations

import numpy as np
from matplotlib.figure import Figure

from .liquid import curves_figure

__all__ = ["kinetostatic_check_figure"]


def kinetostatic_check_figure(res: dict, title: str = "") -> Figure:
    """Two panels against speed: the liquid's angle from D (physics: quasi-static, and the
    settled film where run; 001 eq 3 and eq 3 - eq 6) and the residual ratio e_c/e (physics,
    001 eq 1).

    Parameters
    ----------
    res : dict
        :func:`kinetostatic_vs_physics`'s result (omega_rad_s [rad/s], angles [deg], ratios [-]).
    title : str
        Figure title.
    """
    w = res["omega_rad_s"]
    ang = [("quasi-static liquid", np.abs(res["alpha_deg"]), "k-"),
           ("001 eq 3: α0", np.abs(res["alpha0_deg"]), "b--"),
           ("001 eq 3 − eq 6: α0 − β", np.abs(res["alpha_001_deg"]), "c:")]
    if "alpha_film_deg" in res:
        ang.insert(1, ("coupled film (settled)", np.abs(res["alpha_film_deg"]), "ro"))
    return curves_figure(
        [{"x": w, "xlabel": "speed Ω [1/s]", "ylabel": "liquid angle from D |α| [deg]",
          "title": "where the liquid sits", "curves": ang},
         {"x": w, "xlabel": "speed Ω [1/s]", "ylabel": "residual e_c/e = |D + U_l|/|D| [-]",
          "title": "residual unbalance",
          "curves": [("physics", res["ec_over_e"], "k-"),
                     ("001 eq 1 at α0 − β", res["ec_over_e_001"], "c:")]}], title)
