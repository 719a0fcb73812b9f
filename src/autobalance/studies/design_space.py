"""The candidates of the design search (:mod:`.design`): the space of ball counts, capacities,
race radii and speed profiles, the profiles a machine's candidates may use, and each candidate
as the overrides that make it from the machine.

Sizing rules (ours, stated): a capacity below the largest unbalance cannot balance it (004 sec.
4.3: the residual is at least U - N m R); 004 sec. 4.3 also finds that an over-sized balancer
balances poorly, hence capacity ratios from 1.1 to 2. Steel balls keep their density: the ball
radius scales with the cube root of the mass. A TSR candidate's plateau is
:data:`PLATEAU_RATIO` x the first natural frequency of the machine with the candidate's balls
(004 sec. 3.2 chooses a plateau just above resonance), raised above the lowest stable speed of
its balanced state where the speed map finds that higher; its ramps and hold are 004's in
units of the machine's own run-up time (:data:`TSR_TIMES`).
"""
from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from ..models import ParameterError
from .common import load
from .statistics import plateau_speed

if TYPE_CHECKING:
    from ..config import Config

__all__ = ["MIN_PLATEAU_REVOLUTIONS", "PLATEAU_RATIO", "STABLE_MARGIN", "TSR_TIMES",
           "DesignSpace", "candidate", "candidate_designs", "profile_variants"]

#: TSR plateau of the candidate profiles as a multiple of the first natural frequency [-].
PLATEAU_RATIO = 1.06
#: 004's speed reduction in units of its run-up (004 sec. 3.2, Fig. 3: an 18 s run-up, then
#: 10 s down to the plateau, 20 s on it, 10 s back up) [-]: a candidate's reduction takes the
#: same multiples of the machine's own run-up time.
TSR_TIMES = (10.0 / 18.0, 20.0 / 18.0, 10.0 / 18.0)
#: Least time on the plateau, in revolutions at the plateau speed [-] (ours: balls released
#: there settle within tens of revolutions, 004 Fig. 8).
MIN_PLATEAU_REVOLUTIONS = 50.0
#: A candidate's plateau lies at least this factor above the lowest speed of the stable range
#: of the balanced state that holds the nominal speed (the speed map, :mod:`.speed_map`) [-].
STABLE_MARGIN = 1.03


@dataclass(frozen=True)
class DesignSpace:
    """The candidates the design search tries.

    Attributes
    ----------
    n_balls : tuple of int
        Ball counts N (>= 1).
    capacity_ratios : tuple of float
        Capacity N m R over the largest expected unbalance [-] (> 1).
    radii : tuple of float or None
        Race radii R [m]; None = the machine's.
    profiles : tuple of str
        Speed profiles from :func:`profile_variants`: "given", "std", "slow", "tsr".
    """

    n_balls: tuple = (2, 3)
    capacity_ratios: tuple = (1.1, 1.4, 2.0)
    radii: tuple | None = None
    profiles: tuple = ("std", "slow", "tsr")

    @classmethod
    def quick(cls) -> "DesignSpace":
        """A small space for a first look: 2 or 3 balls, capacity 1.2 or 1.8 x, std or tsr."""
        return cls(n_balls=(2, 3), capacity_ratios=(1.2, 1.8), profiles=("std", "tsr"))


def profile_variants(cfg: Config, plateau_ratio: float = PLATEAU_RATIO,
                     natural_frequency: float | None = None,
                     stable_onset: float | None = None) -> dict:
    """The speed profiles a design may use, as ``--set`` overrides of the machine's profile
    (004 sec. 4.4: the standard run-up, a 3x slower run-up; 004 sec. 3.2: a temporary speed
    reduction to :data:`PLATEAU_RATIO` x the first natural frequency, its ramps and hold the
    multiples :data:`TSR_TIMES` of the machine's run-up time, the hold at least
    :data:`MIN_PLATEAU_REVOLUTIONS` revolutions; 004's own 18 s run-up gives its 10/20/10 s).
    The plateau is raised to :data:`STABLE_MARGIN` x ``stable_onset`` when that is higher.

    "given" is the machine's own profile as it is (no overrides). Only a std or tsr profile
    has variants; any other profile kind gives {"given": []} alone.

    Parameters
    ----------
    cfg : Config
        The machine (its ``spin``: nominal speed [rad/s], run-up time and read-out [s]).
    plateau_ratio : float
        The TSR plateau over the first natural frequency [-].
    natural_frequency : float or None
        That frequency [rad/s]; None = the machine's first (with its own balls; a candidate
        passes its own, with the candidate's balls).
    stable_onset : float or None
        The lowest speed of the balanced state's stable range that holds the nominal speed
        [rad/s] (None: not known; the plateau is the ratio alone).

    Returns
    -------
    dict of str to list of str
        Variant name -> "path=value" overrides (SI numbers).
    """
    spin = cfg.spin
    if getattr(spin, "name", "") not in ("std", "tsr"):
        return {"given": []}
    wn = spin.nominal_speed
    t_ru, t_read, dur = float(spin.times[1]), float(spin.checkpoints[0]), float(spin.duration)
    std_dur = max(dur if spin.name == "std" else t_read * 1.5, t_read)
    slow_ru = 3.0 * t_ru
    slow_dur = max(std_dur, slow_ru + (std_dur - t_read))
    fn = cfg.system.natural_frequencies[0] if natural_frequency is None else natural_frequency
    wp = plateau_ratio * fn
    if stable_onset is not None and math.isfinite(stable_onset):
        wp = max(wp, STABLE_MARGIN * stable_onset)
    down, hold, up = (f * t_ru for f in TSR_TIMES)
    hold = max(hold, MIN_PLATEAU_REVOLUTIONS * 2 * math.pi / wp)
    tsr_dur = max(dur if spin.name == "tsr" else 0.0,
                  t_read + down + hold + up + max(TSR_TIMES[0] * t_ru, std_dur - t_read))
    out = {
        "given": [],
        "std": ["profile.kind=std", f"profile.nominal={wn!r}", f"profile.runup_time={t_ru!r}",
                f"profile.duration={std_dur!r}", f"profile.runup_fraction={t_read / std_dur!r}"],
        "slow": ["profile.kind=std", f"profile.nominal={wn!r}", f"profile.runup_time={slow_ru!r}",
                 f"profile.duration={slow_dur!r}",
                 f"profile.runup_fraction={slow_ru / slow_dur!r}"],
    }
    if wp < wn:
        out["tsr"] = ["profile.kind=tsr", f"profile.nominal={wn!r}", f"profile.runup_time={t_ru!r}",
                      f"profile.duration={tsr_dur!r}", f"profile.runup_fraction={t_read / tsr_dur!r}",
                      f"profile.plateau={wp!r}", f"profile.down_time={down!r}",
                      f"profile.plateau_time={hold!r}", f"profile.up_time={up!r}"]
    return out


def candidate_designs(cfg: Config, space: DesignSpace, U_max: float,
                      variants: dict | None = None) -> list:
    """Every candidate of ``space`` for a largest expected unbalance ``U_max`` [kg*m].

    Parameters
    ----------
    cfg : Config
        The machine; its balancer (if any) gives the ball radius, element, damping and rolling
        resistance of ball 1, which every candidate keeps (ball radius scaled as m^(1/3)).
    space : DesignSpace
        The candidates to try.
    U_max : float
        Largest expected initial unbalance [kg*m], > 0.
    variants : dict or None
        The machine's :func:`profile_variants` (None: computed here).

    Returns
    -------
    list of dict
        name, n_balls, ball_mass [kg], race_radius [m], capacity [kg*m], profile,
        plateau_ratio [-] (over the first natural frequency with the candidate's balls; NaN
        unless tsr), duration [s], ball_sets and sets (the "path=value"
        overrides that make the candidate's balls, and the whole candidate, from the machine)
        and config (the candidate's Config).
    """
    b = cfg.system.balancer
    variants = profile_variants(cfg) if variants is None else variants
    radii = space.radii or (b.race_radius,)
    m0, r0 = (float(b.masses[0]), b.ball_radius) if b.n_balls else (None, b.ball_radius)
    # ball 1's friction and damping (a machine without balls: 004 Table 1's mu_ref, no damping)
    mu = float(b.rolling_resistance[0]) if b.n_balls else 0.002
    mu_s = float(np.max(b.stiction)) if b.n_balls else mu
    damping = float(b.damping[0]) if b.n_balls else 0.0
    out = []
    for N in space.n_balls:
        for ratio in space.capacity_ratios:
            for R in radii:
                m = ratio * U_max / (N * R)
                r_ball = r0 if m0 is None else r0 * (m / m0) ** (1.0 / 3.0)
                ball = [f"balancer.n_balls={N}", f"balancer.ball_mass={m!r}",
                        f"balancer.race_radius={R!r}", f"balancer.ball_radius={r_ball!r}",
                        f"balancer.rolling_resistance={mu!r}", f"balancer.stiction={mu_s!r}",
                        f"balancer.damping={damping!r}",
                        "initial.ball_angles=[" + ", ".join(
                            repr(2 * math.pi * k / N) for k in range(N)) + "]"]
                for prof in space.profiles:
                    if prof not in variants:
                        continue
                    c = candidate(cfg, N, m, R, ratio, prof, ball, variants,
                                   PLATEAU_RATIO if prof == "tsr" else math.nan)
                    if c is not None:
                        out.append(c)
    return out


def candidate(cfg: Config, N: int, m: float, R: float, ratio: float, prof: str,
              ball_sets: list, variants: dict, plateau_ratio: float) -> dict | None:
    """One candidate design as :func:`candidate_designs` lists it.

    Parameters
    ----------
    cfg : Config
        The machine.
    N : int
        Ball count [-].
    m : float
        Ball mass [kg].
    R : float
        Race radius [m].
    ratio : float
        Capacity N m R over the largest expected unbalance [-].
    prof : str
        Profile variant ("given", "std", "slow", "tsr").
    ball_sets : list of str
        The "path=value" overrides that make the candidate's balls.
    variants : dict
        The machine's :func:`profile_variants` (a TSR candidate makes its own).
    plateau_ratio : float
        A TSR plateau over the first natural frequency of the machine with the candidate's
        balls [-] (raised above the stable onset of :func:`profile_variants`).

    Returns
    -------
    dict or None
        As :func:`candidate_designs` (its "plateau_ratio" the plateau as built over that
        frequency; the name ends in "-tsr" for :data:`PLATEAU_RATIO`, "-tsrR" for another
        requested ratio R); None when a TSR plateau is not below the nominal speed.
    """
    if prof == "tsr":
        balls = load(cfg, ball_sets, allow_liquid=True)
        fn = balls.system.natural_frequencies[0]
        variants = profile_variants(cfg, plateau_ratio, natural_frequency=fn,
                                    stable_onset=_stable_onset(balls, fn))
        if "tsr" not in variants:
            return None
    sets = list(ball_sets) + list(variants[prof])
    cand = load(cfg, sets, allow_liquid=True)
    tag = prof if prof != "tsr" or plateau_ratio == PLATEAU_RATIO else f"tsr{plateau_ratio:.3g}"
    if prof == "tsr":               # the plateau as built: raised above the stable onset
        plateau_ratio = plateau_speed(cand.spin) / fn
    return {"name": f"{N}x{1e3 * m:.3g}g-R{1e3 * R:.3g}mm-{tag}", "n_balls": N, "ball_mass": m,
            "race_radius": R, "capacity": N * m * R, "capacity_ratio": ratio, "profile": prof,
            "plateau_ratio": plateau_ratio, "duration": float(cand.spin.duration),
            "ball_sets": list(ball_sets), "sets": sets, "config": cand}


def _stable_onset(cfg, fn: float) -> float:
    """The lowest speed [rad/s] of the balanced state's stable range that holds the nominal
    speed, from the speed map (:func:`.speed_map.compute_speed_map`, the machine's own damping,
    16 speeds from 0.9 to 3 x ``fn`` [rad/s] with its edges bisected); NaN when the map finds
    no such range or cannot judge this machine."""
    from ._speed_map import compute_speed_map, speed_map_summary

    wn = cfg.spin.nominal_speed
    try:
        ds = compute_speed_map(cfg, speeds=np.geomspace(0.9 * fn, min(wn, 3.0 * fn), 16),
                               damping_factors=(1.0,), quick=True)
    except ParameterError:
        return math.nan
    for lo, hi in speed_map_summary(ds)["stable_ranges_rad_s"]:
        if lo <= min(wn, 3.0 * fn) <= hi * (1 + 1e-9):
            return float(lo)
    return math.nan
