"""Run-up of the unloaded drum under a motor torque law (000 eq 15, Table 1 laws), in closed
form: B_z w' = T(w) without the unbalance and ball terms."""
from __future__ import annotations

import math

import numpy as np

from ..models import MotorDrive, ParameterError

__all__ = ["runup_fraction_closed_form", "runup_time_closed_form"]


def runup_time_closed_form(law: str, fraction: float | np.ndarray, tau: float):
    """Time [s] for the unloaded drum to reach ``fraction`` of w_f under a 000 Table 1 torque law.

    000 eq (15) without the unbalance and ball terms, B_z w' = T(w), tau = B_z w_f / T0 [s]:
    constant T0: t = s tau; linear T0 (1 - w/w_f): t = -tau ln(1 - s); harmonic
    T0 (1 - sin(pi w / 2 w_f)): t = (2/pi)(tan(pi (1 + s)/4) - 1) tau (the integral of
    1/(1 - sin(pi s/2))).

    Parameters
    ----------
    law : str
        Torque law, one of ``MotorDrive.LAWS``.
    fraction : float or array
        s = w/w_f [-], 0 <= s < 1.
    tau : float
        Time scale B_z w_f / T0 [s].
    """
    s = np.asarray(fraction, float)
    if law == "constant":
        t = s * tau
    elif law == "linear":
        t = -tau * np.log1p(-s)
    elif law == "harmonic":
        t = (2 / math.pi) * (np.tan(math.pi * (1 + s) / 4) - 1) * tau
    else:
        raise ParameterError("law", law, f"must be one of {list(MotorDrive.LAWS)}")
    return float(t) if np.ndim(t) == 0 else t



def runup_fraction_closed_form(law: str, time: float | np.ndarray, tau: float):
    """Fraction of w_f [-] that the unloaded drum reaches at ``time``: the inverse of
    :func:`runup_time_closed_form` (000 eq 15, Table 1 laws).

    Parameters
    ----------
    law : str
        Torque law, one of ``MotorDrive.LAWS``.
    time : float or array
        Time from standstill [s].
    tau : float
        Time scale B_z w_f / T0 [s].
    """
    t = np.asarray(time, float) / tau
    if law == "constant":
        s = np.minimum(t, 1.0)
    elif law == "linear":
        s = -np.expm1(-t)
    elif law == "harmonic":
        s = 4 / math.pi * np.arctan(1 + math.pi * t / 2) - 1
    else:
        raise ParameterError("law", law, f"must be one of {list(MotorDrive.LAWS)}")
    return float(s) if np.ndim(s) == 0 else s
