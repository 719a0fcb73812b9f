"""Statistics of study results, for any machine: 004 Table 2's regions, the mode of a grade
sample with its bootstrap error, the shares at or below a grade, valid initial-unbalance ranges
(004 sec. 4.3), and read-outs of percentile curves along a speed descent (004 Fig. 13)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    import numpy.typing as npt

    from ..models import MotorDrive, SpeedProfile

__all__ = ["REGION_NAMES", "TIE_MM_S", "half_drop", "mode", "mode_value", "plateau_speed", "profile_text",
           "regions", "rise_after_min", "start_position_stats", "valid_ranges"]


#: 004 Table 2's regions, in its order.
REGION_NAMES = ("I.A", "I.B", "II", "III", "IV")

#: Tie tolerance of the region table [mm/s]: grades closer than this are taken as equal. It is
#: the integration's own resolution: halving the step changes a 004 Monte-Carlo grade by at most
#: 0.0155 mm/s (``make bench``, half-step check over 1275 runs).
TIE_MM_S = 0.02


def regions(g_std: npt.ArrayLike, g_tsr: npt.ArrayLike, g_ini: float, tie: float = 0.0):
    """004 Table 2 regions: shares [-] of I.A, I.B, II, III, IV (every run in exactly one).

    I.A G_STD < G_TSR <= G_INI; I.B G_TSR <= G_STD <= G_INI; II G_TSR <= G_INI < G_STD (004:
    G_TSR < G_INI; the two differ only when G_TSR equals G_INI exactly, which 004's five
    regions leave out); III G_INI < G_STD and G_INI < G_TSR; IV G_STD <= G_INI < G_TSR.

    The strict comparisons split ties by round-off: many runs end the speed reduction where
    they began it (G_TSR - G_STD ~ 1e-6 mm/s). With ``tie`` > 0, grades within ``tie`` of each
    other are equal: G_TSR is first set to G_STD when |G_TSR - G_STD| <= tie, then each of the
    two to G_INI when within ``tie`` of it (so an unchanged run counts in I.B, not I.A).

    Parameters
    ----------
    g_std : array_like
        Grades at the STD read-out [mm/s], one per run.
    g_tsr : array_like
        Grades at the TSR read-out [mm/s], same shape.
    g_ini : float
        Initial grade G_INI [mm/s].
    tie : float
        Tie tolerance [mm/s], >= 0 (0: strict, as 004's definitions read;
        :data:`TIE_MM_S`: the integration's resolution).

    Returns
    -------
    dict of str to float
        Region name -> share of the runs [-].
    """
    s, t, i = np.asarray(g_std, float), np.asarray(g_tsr, float), float(g_ini)
    if tie > 0:
        t = np.where(np.abs(t - s) <= tie, s, t)
        s = np.where(np.abs(s - i) <= tie, i, s)
        t = np.where(np.abs(t - i) <= tie, i, t)
    m = {"I.A": (s < t) & (t <= i), "I.B": (t <= s) & (s <= i), "II": (t <= i) & (i < s),
         "III": (i < s) & (i < t), "IV": (s <= i) & (i < t)}
    return {k: float(v.mean()) for k, v in m.items()}


def mode(g: npt.ArrayLike, width: float = 1.0, n_boot: int = 200,
         seed: int = 0) -> tuple[float, float]:
    """Mode of a sample [mm/s] (centre of the fullest 1 mm/s bin, 004 Fig. 5 reads integer G) and
    its bootstrap standard error [mm/s].

    Parameters
    ----------
    g : array_like
        Grades [mm/s]; non-finite values are dropped.
    width : float
        Bin width [mm/s]; bins start at 0.
    n_boot : int
        Bootstrap resamples.
    seed : int
        Seed of the bootstrap's random generator.

    Returns
    -------
    mode, se : float
        Centre of the fullest bin [mm/s] and the standard deviation of the bootstrap modes
        [mm/s].
    """
    g = np.asarray(g, float)
    g = g[np.isfinite(g)]
    rng = np.random.default_rng(seed)
    boots = [mode_value(rng.choice(g, g.size), width, g.max()) for _ in range(n_boot)]
    return mode_value(g, width), float(np.std(boots))


def mode_value(g: npt.ArrayLike, width: float = 1.0, top: float | None = None) -> float:
    """Centre of the fullest ``width`` bin of a sample [mm/s] (bins start at 0; the first of
    equally full bins).

    Parameters
    ----------
    g : array_like
        Grades [mm/s], finite.
    width : float
        Bin width [mm/s].
    top : float or None
        Largest value the bins must cover [mm/s] (None: the sample's own maximum).

    Returns
    -------
    float
        The mode [mm/s].
    """
    g = np.asarray(g, float)
    hi = g.max() if top is None else top
    edges = np.arange(0.0, max(hi, 1.0) + 2 * width, width)
    h, _ = np.histogram(g, edges)
    return float(edges[np.argmax(h)] + width / 2)


def valid_ranges(G_ini: npt.ArrayLike, p95: npt.ArrayLike, limit: float = 16.0,
                 span: float = 50.0):
    """Valid initial-unbalance ranges (004 sec. 4.3): where the 95th percentile of the residual
    grade is <= limit. Boundaries by linear interpolation between grid points.

    Parameters
    ----------
    G_ini : array_like
        Initial-unbalance grades of the grid [mm/s], increasing.
    p95 : array_like
        95th percentile of the residual grade at each grid point [mm/s].
    limit : float
        Target grade [mm/s] (004: G16).
    span : float
        Length of the G_ini range the efficiency refers to [mm/s] (004 Tables 3-4: [G0, G50]).

    Returns
    -------
    (ranges, efficiency)
        ranges [(lo, hi)] in G [mm/s]; efficiency = total length / span [-]."""
    x = np.asarray(G_ini, float)
    f = np.asarray(p95, float) - limit
    ok = f <= 0
    ranges = []
    start = x[0] if ok[0] else None
    for k in range(1, x.size):
        if ok[k] and not ok[k - 1]:
            start = x[k - 1] + (x[k] - x[k - 1]) * f[k - 1] / (f[k - 1] - f[k])
        if not ok[k] and ok[k - 1]:
            end = x[k - 1] + (x[k] - x[k - 1]) * f[k - 1] / (f[k - 1] - f[k])
            ranges.append((float(start), float(end)))
            start = None
    if start is not None:
        ranges.append((float(start), float(x[-1])))
    # an isolated valid grid point is a range of zero length: keep it (it has a boundary)
    eff = sum(hi - lo for lo, hi in ranges) / span
    return ranges, float(eff)


def start_position_stats(s: np.ndarray, t: np.ndarray, g_ini: float,
                         limit: float = 16.0) -> dict:
    """Mode (1 mm/s bins, bootstrap SE), median, shares at or below ``limit`` [mm/s] and G_ini
    and 004 Table 2 regions of the grades [mm/s] at a first (s, 004: STD) and a second (t, 004:
    TSR) read-out over start positions. The ``share_G16_*`` keys keep 004's name whatever the
    limit.

    Parameters
    ----------
    s : ndarray
        Grades at the first read-out [mm/s], one per start.
    t : ndarray
        Grades at the second read-out [mm/s], same shape.
    g_ini : float
        Initial grade [mm/s].
    limit : float
        Target grade [mm/s] (004: G16).

    Returns
    -------
    dict of str to float
        mode_*, mode_*_se, median_* [mm/s]; share_G16_*, success_* (share <= G_ini),
        region_* (:func:`regions`, strict) and region_tied_* (ties within :data:`TIE_MM_S`) [-].
    """
    (ms, ses), (mt, set_) = mode(s), mode(t)
    return {"mode_STD": ms, "mode_STD_se": ses, "mode_TSR": mt, "mode_TSR_se": set_,
            "median_STD": float(np.median(s)), "median_TSR": float(np.median(t)),
            "share_G16_STD": float(np.mean(s <= limit)), "share_G16_TSR": float(np.mean(t <= limit)),
            "success_STD": float(np.mean(s <= g_ini)), "success_TSR": float(np.mean(t <= g_ini)),
            **{f"region_{k}": v for k, v in regions(s, t, g_ini).items()},
            **{f"region_tied_{k}": v for k, v in regions(s, t, g_ini, TIE_MM_S).items()}}


def half_drop(ratio: np.ndarray, g: np.ndarray) -> float:
    """Speed ratio [-] at which g, followed from the start of the descent (highest speed), first
    falls halfway from its start value to its minimum over ratio >= 1 (linear interpolation
    between samples); NaN if it never drops.

    Parameters
    ----------
    ratio : ndarray
        Speed ratio Omega/Omega_n along the descent [-], decreasing.
    g : ndarray
        Grade (a percentile curve) at each ratio [mm/s].

    Returns
    -------
    float
        The ratio [-], or NaN.
    """
    sup = ratio >= 1.0
    g0, gmin = g[0], g[sup].min()
    if not g0 > gmin:
        return math.nan
    level = g0 - 0.5 * (g0 - gmin)
    j = int(np.argmax(g <= level))                 # first sample at or below the level
    if j == 0:
        return float(ratio[0])
    f = (g[j - 1] - level) / (g[j - 1] - g[j])
    return float(ratio[j - 1] + f * (ratio[j] - ratio[j - 1]))


def rise_after_min(ratio: np.ndarray, g: np.ndarray, rise: float = 1.0) -> dict:
    """Where g [mm/s], after its minimum over ratio >= 1, first exceeds that minimum by more than
    ``rise`` later in the descent: {"p95_min", "p95_min_ratio", "p95_rise_ratio" (NaN if never),
    "p95_max_after"}.

    Parameters
    ----------
    ratio : ndarray
        Speed ratio Omega/Omega_n along the descent [-], decreasing.
    g : ndarray
        Grade (004: the 95th percentile) at each ratio [mm/s].
    rise : float
        Rise above the minimum that counts [mm/s].

    Returns
    -------
    dict of str to float
        p95_min and p95_max_after [mm/s], p95_min_ratio and p95_rise_ratio [-].
    """
    sup = np.flatnonzero(ratio >= 1.0)
    j = int(sup[np.argmin(g[sup])])
    later = np.flatnonzero(g[j:] > g[j] + rise)
    return {"p95_min": float(g[j]), "p95_min_ratio": float(ratio[j]),
            "p95_rise_ratio": float(ratio[j + later[0]]) if later.size else math.nan,
            "p95_max_after": float(g[j:].max())}


def plateau_speed(spin: SpeedProfile | MotorDrive) -> float:
    """Lowest speed [rad/s] of a profile after its first read-out: the TSR plateau (Fig. 3).

    Parameters
    ----------
    spin : SpeedProfile or MotorDrive
        A profile with knots after its first checkpoint (a tsr); a motor drive, whose speed
        follows its torque law, has none and is refused.

    Returns
    -------
    float
        The plateau speed [rad/s].

    Raises
    ------
    ParameterError
        A motor drive, or a profile without a knot after its first read-out (one line).
    """
    from ..models import ParameterError

    kind = getattr(spin, "name", type(spin).__name__)
    if not hasattr(spin, "times"):
        raise ParameterError("profile.kind", kind, "a motor drive has no speed plateau (its "
                             "speed follows the torque law); the plateau needs a tsr profile")
    after = [w for t, w in zip(spin.times, spin.speeds) if t > spin.checkpoints[0]]
    if not after:
        raise ParameterError("profile.kind", kind, "has no speed after its first read-out; "
                             "the plateau needs a tsr profile")
    return min(after)


def profile_text(spin: SpeedProfile | MotorDrive) -> str:
    """The profile's knots as "t s: f Hz; ..." for reports; a motor drive as its torque law,
    torque, final and initial speeds and duration ("motor: linear law, T0 = 25 N*m to 16.7
    Hz (held at 100 %), from 0.0 Hz, 12 s").

    Parameters
    ----------
    spin : SpeedProfile or MotorDrive
        The profile (knot times [s], speeds [rad/s]) or the motor drive (torque [N*m], final
        speed [rad/s], duration [s]).

    Returns
    -------
    str
    """
    if not hasattr(spin, "times"):                  # a motor drive (000 eq 15-18)
        return (f"motor: {spin.law} law, T0 = {spin.torque:g} N*m to "
                f"{spin.final_speed / (2 * np.pi):.1f} Hz (held at "
                f"{100 * spin.hold_fraction:g} %), from {spin.initial_speed / (2 * np.pi):.1f} "
                f"Hz, {spin.duration:g} s")
    return "; ".join(f"{t:g} s: {w / (2 * np.pi):.1f} Hz" for t, w in zip(spin.times, spin.speeds))
