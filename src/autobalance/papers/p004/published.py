"""Seed 004 (Van De Velde et al. 2020, temporary speed reduction): the machine, the paper's
constants and every published number with its source."""
from __future__ import annotations

__all__ = ["C_R", "G_LIMIT", "G_SPAN", "G_TSR_RANGE", "ITEMS_004", "MU_R", "PLATEAU_CASES", "PRESET",
           "PUBLISHED", "REGIONS", "SLOW_SETS", "UNBALANCE_CASES", "immobility_speeds_hz",
           "plateau_grid", "unbalance_grid"]

import numpy as np

from ...studies.statistics import REGION_NAMES

PRESET = "vub_jeffcott_004"
G_LIMIT = 16.0          # 004 sec. 4: the rotor must qualify G16
G_SPAN = 50.0           # 004 Tables 3-4: efficiency = valid range / [G0, G50]
G_TSR_RANGE = 34.0      # 004 sec. 4.6: ideal plateau averaged over G_ini <= G34
REGIONS = REGION_NAMES   # 004 Table 2

#: (mu_r, c_r) of the initial-unbalance cases of 004 Tables 3-4.
UNBALANCE_CASES = {"nominal": (1.0, 1.0), "mu0.5": (0.5, 1.0), "mu0.25": (0.25, 1.0),
                   "c0.6": (1.0, 0.6), "c0.5": (1.0, 0.5)}
#: (mu_r, c_r) of the plateau maps of 004 Fig. 14 and 15.
PLATEAU_CASES = {"nominal": (1.0, 1.0), "c0.5": (1.0, 0.5)}



def unbalance_grid(quick: bool) -> np.ndarray:
    """004 sec. 4.3's initial grades [mm/s]: [G0, G50] every 2 mm/s (quick: every 5).

    Parameters
    ----------
    quick : bool
        Steps of 5 mm/s instead of 2 mm/s.
    """
    return np.arange(0.0, 50.1, 5.0) if quick else np.arange(0.0, 50.1, 2.0)


def plateau_grid(quick: bool) -> tuple:
    """004 Fig. 14-15's map: plateau / Omega_n ratios 0.96-1.12 every 0.01 [-] x G_ini in
    [G0, G32] every 4 mm/s (quick: 4 ratios x 3 grades).

    Parameters
    ----------
    quick : bool
        The coarse map.
    """
    if quick:
        return np.array([0.98, 1.02, 1.06, 1.10]), np.array([5.0, 15.0, 25.0])
    return np.round(np.arange(0.96, 1.1201, 0.01), 3), np.arange(0.0, 34.1, 4.0)


def immobility_speeds_hz(quick: bool) -> np.ndarray:
    """004 Fig. 8 and 10's speed axis: 20-200 Hz every 0.5 Hz (quick: every 2 Hz) [Hz].

    Parameters
    ----------
    quick : bool
        The coarse axis.
    """
    return np.linspace(20.0, 200.0, 91 if quick else 361)


PUBLISHED = {
    "table1": {"f_n_hz": 94.2, "G_ini": 20.0, "G_balls": 34.0,
               "source": "004 Table 1 (M = 16.53 kg, k = 5.8 kN/mm, eps = 19.3 um, m = 7.6 g, "
                         "R = 35 mm) and sec. 4: resonance 94.2 Hz, G20 rotor, G34 balls"},
    "single": {"G_ini": 20.0, "G_start": 14.0, "G_peak_runup": 38.0, "G_STD": 19.0, "G_TSR": 5.0,
               "run_exists": "a G14 start reproduces the whole run",
               "source": "004 sec. 4.1, Fig. 4: G14 -> G38 -> G19 (STD), G5 after TSR"},
    "monte_carlo": {"mode_STD": 15.0, "mode_TSR": 11.0,
                    "share_G16_STD": 0.85, "share_G16_TSR": 0.80,
                    "success_STD": 0.95, "success_TSR": 0.98,
                    "regions": {"I.A": 0.260, "I.B": 0.675, "II": 0.045, "III": 0.005, "IV": 0.015},
                    "runs": 1275,
                    "source": "004 sec. 4.2, Fig. 5-6, Table 2 (G_ini = G20, 50 x 50 starts)"},
    # case: {STD: {ranges, efficiency}, TSR: ...}; ranges in G [mm/s]
    "unbalance": {
        "nominal": {"STD": {"ranges": [], "efficiency": 0.0},
                    "TSR": {"ranges": [(0, 3), (19, 34)], "efficiency": 0.36}},
        "mu0.5": {"STD": {"ranges": [(21, 43)], "efficiency": 0.44},
                  "TSR": {"ranges": [(0, 17), (21, 44)], "efficiency": 0.80}},
        "mu0.25": {"STD": {"ranges": [(0, 14), (23, 47)], "efficiency": 0.76},
                   "TSR": {"ranges": [(0, 47)], "efficiency": 0.94}},
        "c0.6": {"STD": {"ranges": [(20, 41)], "efficiency": 0.42},
                 "TSR": {"ranges": [(0, 10), (20, 42)], "efficiency": 0.64}},
        "c0.5": {"STD": {"ranges": [(21, 43)], "efficiency": 0.44},
                 "TSR": {"ranges": [(0, 9), (21, 43)], "efficiency": 0.62}},
        "source": "004 sec. 4.3-4.5, Fig. 7, 11, 12, Tables 3-4 (G16, efficiency over [G0, G50])"},
    "profile": {"slow_worse_range": (10.0, 21.0), "slow_better_elsewhere": "< 0",
                "tsr_better": "< 0",
                "source": "004 sec. 4.4, Fig. 9: 3x slower run-up vs STD and TSR (95 % isolines)"},
    "immobility": {"valley_at_resonance": "near resonance (~1)",
                   "nominal_above_plateau": "higher at nominal",
                   "monotone_mu": "more stiction, more immobility",
                   "monotone_c": "more damping, more immobility",
                   "source": "004 sec. 4.4-4.5, Fig. 8 and 10 (G_ini = G20); the figures give "
                             "no numbers, the rows check the text's statements"},
    "descent": {"prompt_reduction": 1.1, "worse_near_resonance": "some outcomes deteriorate",
                "source": "004 sec. 4.6, Fig. 13: G5, mu_r = c_r = 1, gradual speed reduction "
                          "from nominal to 0.9 Omega_n: 'a prompt unbalance reduction near "
                          "Omega = 1.1 Omega_n. Unstable working occurs when nearing resonance "
                          "which deteriorates some of the balancing outcomes.'"},
    "plateau": {"ideal": {"nominal": 1.02, "c0.5": 1.03}, "standard": 1.06,
                "source": "004 sec. 4.6, Fig. 14-15: ideal lower plateau / Omega_n; the "
                          "standard plateau 100 Hz / 94.2 Hz = 1.06"},
}

MU_R = (0.25, 0.5, 1.0, 2.0, 5.0)


C_R = (0.5, 0.6, 1.0, 1.4)

SLOW_SETS = ["profile.kind=std", "profile.runup_fraction=0.6", "profile.runup_time=54 s",
             "profile.duration=90 s"]


ITEMS_004 = tuple([f"Fig. {i}" for i in range(1, 17)] + [f"Table {i}" for i in range(1, 5)])

