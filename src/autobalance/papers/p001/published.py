"""Published numbers and statements of seed 001 (Drach 2018: the fluid balancer, influence of
the viscosity of the liquid), one section per reproduction target (key = target id).

The Ukrainian text and most figure numbers were lost in the extraction; the formulas (eq 1-7)
and the English abstract survive. Every leaf is a number or a statement and becomes one row
``<target id>/<path>`` (:class:`autobalance.validation.target.Rows`); ``source`` and keys
starting with ``_`` are descriptions.
"""
from __future__ import annotations

from ...validation.target import Rows

__all__ = ["ITEMS_001", "PUBLISHED", "rows"]

#: Every figure and numbered equation of seed 001 with a published number or statement.
ITEMS_001 = ("Fig. 1", "Fig. 2", "Fig. 3", "Fig. 4", "Fig. 5", "Fig. 6", "eq 3", "eq 4", "eq 5",
             "eq 6", "eq 7")

PUBLISHED = {
    "001-fig1-2": {
        "source": "001 Fig. 1 (unbalance vectors D, D0, D_c of the kinetostatic model), Fig. 2 "
                  "(bench schematic)",
        "_parameters": "chambers 200, 300, 400 mm; suspension ~9-10 Hz; 0.5-18 Hz (30-1080 "
                       "rpm); liquids 670-1650 kg/m^3, 1.01e-6-96.97e-6 m^2/s; fills 50-400 ml "
                       "in 50 ml steps",
    },
    "001-eq3-4": {
        "source": "001 eq 2-4 and the text after eq 4; abstract",
        "eq3_solves_eq2": "alpha0 of eq 3 is a root of eq 2",
        "alpha0_range": "delta in (0, pi/2) -> alpha0 in (pi/2, pi)",
        "k1_complete_balance": "k = 1: cos alpha0 = -1 and lambda0 (eq 4) infinite",
        "rises_with_phase_angle": "the efficiency rises with the phase angle, i.e. with the "
                                  "external resistance (abstract)",
    },
    "001-eq5-7": {
        "source": "001 eq 5-7 (laminar friction of the liquid, friction angle beta)",
        "eq5_laminar": "F_T = pi/4 dP d^2 with dP = rho lambda (l/d) v^2/2 and lambda = 64/Re "
                       "gives F_T = 8 pi mu l v (the pipe diameter d cancels)",
        "eq6_offset_cancels": "sin beta = F_T/F = 8 pi^2 mu R xi/(180 m omega): |O1C| cancels",
        "eq7_bound": "|tan beta| <= sin beta / sqrt(1 - sin^2 beta)",
    },
    "001-fig3-6": {
        "source": "001 abstract (English) and Fig. 3-6: densities 670, 1000, 1230, 1370, 1650 "
                  "kg/m^3; viscosities 1.01e-6, 14.4e-6, 96.97e-6 m^2/s",
        "all_regimes": "with liquids of different densities balancing exists before, at and "
                       "after resonance",
        "rises_toward_critical": "the efficiency rises as omega approaches the critical speed",
        "density_optimal_fill": "the density does not significantly influence the optimal "
                                "filling",
        "viscosity_at_optimum": "the viscosity significantly affects the vibration even at the "
                                "optimal filling",
        "viscosity_over_density": "mass forces affect the efficiency less than the viscosity",
        "overfill_worse": "more liquid than the optimal volume deteriorates the balancing",
        "_unreadable": "numbers whose context was lost in extraction (not compared): 150, "
                       "150-200, 100 (D = 2000 g*cm), 2000, 40 %, 6275, D = 1000, 200, 50-100, "
                       "50, '59 38', '59 24 50'",
    },
}


def rows(target_id: str) -> Rows:
    """The (empty) comparison rows of a 001 target: key prefix = the target id, paths in its
    section of PUBLISHED.

    Parameters
    ----------
    target_id : str
        The target's id, e.g. ``"001-eq3-4"``.
    """
    return Rows(target_id, PUBLISHED[target_id])
