"""Published numbers and statements of seed 003 (Drach, Dykha, Matiukh, Dykha 2025: Leblanc
balancer on a vertical rotor), one section per reproduction target (key = target id).

Every leaf is a number or a statement the seed publishes and becomes one row
``<target id>/<path>`` (:class:`autobalance.validation.target.Rows`); ``source`` and keys
starting with ``_`` are descriptions. A (lo, hi) tuple is a published range.

Thresholds that the seed does not give (ours, fixed before comparing, docs/liquid/validation.md
sec. 4): "balancing" means efficiency A_dry/A_wet > :data:`BALANCING`; "liquid opposite the
unbalance" means |theta| > :data:`OPPOSITE_DEG`; printed numbers get half a unit of their last
digit (:func:`printed_tolerance`).
"""
from __future__ import annotations

from ...validation.target import Rows

__all__ = ["BALANCING", "ITEMS_003", "OPPOSITE_DEG", "PUBLISHED", "printed_tolerance", "rows"]

#: Every figure and numbered equation of seed 003 with a published number or statement.
ITEMS_003 = ("Fig. 1", "Fig. 2", "Fig. 3", "Fig. 4", "Fig. 5", "Fig. 6", "Fig. 7", "eq 4", "eq 6")

#: Efficiency A_dry/A_wet above which we say "the liquid balances" (our threshold, docs sec. 4).
BALANCING = 1.3
#: |liquid angle| [deg] above which the liquid is "opposite the unbalance" (our threshold).
OPPOSITE_DEG = 150.0

PUBLISHED = {
    "003-fig1-3": {
        "source": "003 sec. 4.2-4.3, Fig. 1 (bench photo), Fig. 2 (balancer sample, three "
                  "concentric transparent chambers), Fig. 3 (video set-up schematic)",
        "_parameters": "R = 0.1, 0.15, 0.2 m; h = 0.05 m; water 1000 kg/m^3, 1.01e-6 m^2/s; "
                       "D = 0-3000 g*cm; V = 0-350 ml; suspension ~9-10 Hz; omega_r 49-57 1/s "
                       "(the last two are compared in 003-fig5)",
    },
    "003-eq4-6": {
        "source": "003 sec. 5.2: R = 0.2 m, h = 0.05 m; eq 4 at z* = 0 (bottom touch) and eq 6 "
                  "(entrainment); each printed speed is compared with g = 10 m/s^2 and with "
                  "standard gravity (003 does not state g)",
        "bottom_touch_rad_s": {"_case": "V = 100 ml", "g10": 0.89, "g_standard": 0.89},
        "omega0_rad_s": {"V100ml": {"g10": 28.0, "g_standard": 28.0},
                         "V200ml": {"g10": 19.8, "g_standard": 19.8},
                         "V300ml": {"g10": 16.2, "g_standard": 16.2}},
    },
    "003-fig4": {
        "source": "003 sec. 5.1-5.2, Fig. 4 (free surface in the four modes), eq 1-5",
        "four_modes": "1 full priority of gravity -> 2 partial priority of gravity -> 3 partial "
                      "priority of centrifugal forces -> 4 full priority of centrifugal forces",
        "mode2_end": "mode 2 ends when the paraboloid touches the bottom, z* = 0",
        "mode3_end": "mode 3 ends when the paraboloid touches the lid at the wall, z0 = h at "
                     "r0 = R (eq 6)",
        "volume_balance": "the material balance of the volume holds (eq 4, eq 5)",
        "shape_above_omega0": "R >> h: above omega_0 the free surface almost does not change",
        "density_free": "z* and H do not depend on the density of the liquid",
    },
    "003-fig5": {
        "source": "003 sec. 4.2-4.3, 5.3, 6, Fig. 5 a-c: D = 3000 g*cm (150 g), water in 50 ml "
                  "portions, 0.6, 0.8, 1.0, 1.2 omega_r",
        "optimum_fill_ml": {"R200mm": 150.0, "R150mm": (150.0, 200.0), "R100mm": (150.0, 200.0)},
        "sufficient_fill_unbalance": "the sufficient volume creates an unbalance about equal to "
                                     "the rotor's (150 ml in R = 0.2 m, 150 g imbalance mass)",
        "liquid_reduces_amplitude": "with liquid the amplitudes are significantly smaller than "
                                    "at V = 0 ml (all chambers, 0.6-1.2 omega_r)",
        "off_optimum": {"direction": "amplitudes increase where the sufficiency condition is "
                                     "not met",
                        "strength": "they increase slightly"},
        "resonance_rad_s": (49.0, 57.0),
        "critical_speed_falls_with_fluid_mass": "more correction fluid lowers the critical speed "
                                                "(sec. 6)",
        "suspension_frequency_hz": (9.0, 10.0),
    },
    "003-fig6": {
        "source": "003 sec. 5.3, Fig. 6 a-c: efficiency A(no liquid)/A(liquid) at optimal "
                  "filling, D = 1000, 2000, 3000 g*cm, R = 0.1, 0.15, 0.2 m",
        "effective_all_speeds": "with sufficient liquid, effective balancing over the whole "
                                "studied speed range, whatever the chamber radius",
        "larger_radius_better": "R = 0.2 m is significantly more effective than 0.1 and 0.15 m",
        "peak_near_resonance": "the efficiency increases in the vicinity of resonance (every "
                               "chamber, every D)",
    },
    "003-fig7": {
        "source": "003 sec. 5.4, 7, abstract, Fig. 7 a-d: R = 0.2 m, h = 0.05 m, 300 ml water, "
                  "D = 3000 g*cm, omega_r = 54 1/s",
        "a_entrained_rad_s": 18.0,
        "b_opposite_at_30": "at 30 1/s the liquid sits almost opposite the imbalance",
        "c_against_at_54": "at resonance (54 1/s) the liquid sits against the imbalance",
        "d_effective_at_80": "at 80 1/s effective balancing",
        "surface_cylindrical": "with speed the paraboloid becomes a cylinder",
        "ring_shifted_centre": "the horizontal section becomes a ring with a shifted centre",
        "entrainment_observed_rad_s": (15.0, 21.0),
        "entrainment_falls_with_fill": "the entrainment speed depends on the fill with negative "
                                       "feedback",
        "entrainment_depends_on_unbalance": "... and on the simulated imbalance",
        "omega0_over_omega_r": 1.0 / 3.0,
        "no_balancing_before_entrainment": "mode 4 (omega_0) is the lower limit of the "
                                           "balancing range (concl. 3)",
        "balancing_onset_over_omega_r": 0.5,
    },
}


def rows(target_id: str) -> Rows:
    """The (empty) comparison rows of a 003 target: key prefix = the target id, paths in its
    section of PUBLISHED.

    Parameters
    ----------
    target_id : str
        The target's id, e.g. ``"003-eq4-6"``.
    """
    return Rows(target_id, PUBLISHED[target_id])


def printed_tolerance(printed: str) -> float:
    """Half a unit of the last printed digit of a number as printed, e.g. '19.8' -> 0.05.

    Parameters
    ----------
    printed : str
        The number as the seed prints it; the result has its unit.
    """
    dec = len(printed.partition(".")[2])
    return 0.5 * 10.0 ** -dec
