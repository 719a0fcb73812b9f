"""Published numbers of seed 000 (Majewski et al., washing machine), by section, and what each
reproduction target claims.

The closed-form targets' sections are here (:data:`ANALYSIS`); the simulation targets claim the
sections of :data:`.runup.PUBLISHED` and :data:`.washer.PUBLISHED`. One leaf per number (units in
the key); ``source`` and keys starting with ``_`` describe the case. :data:`SECTIONS` maps each
target id to the published mapping it claims, and :func:`rows` starts its comparison rows
(:class:`autobalance.validation.target.Rows`).
"""
from __future__ import annotations

from ...validation.target import Rows
from . import runup as runup_000, washer as washer_000

__all__ = ["ANALYSIS", "ITEMS_000", "PUBLISHED", "SECTIONS", "rows"]

#: Every figure, table and numbered equation of seed 000 with a published number.
ITEMS_000 = tuple(f"Fig. {k}" for k in range(1, 20)) + tuple(f"Table {k}" for k in range(1, 5)) + (
    "eq 30", "eq 31", "eq 32", "eq 48", "eq 49", "eq 57", "eq 58", "eq 60", "eq 62", "eq 63",
    "eq 65", "eq 66")

#: Published numbers of the closed-form targets; the simulation targets claim the sections of
#: runup_000.PUBLISHED and washer_000.PUBLISHED (merged below).
ANALYSIS = {
    "fig3": {"a_930rpm_m_s2": 11.3, "A_930rpm_mm": 1.2, "A_680rpm_mm": 3.3, "A_720rpm_mm": 1.3,
             "source": "000 p. 3 below Fig. 3: a = 47 mV x 0.24 (m/s^2)/mV = 11.3 m/s^2, A = a/w^2 = "
                       "1.2 mm at 930 rpm; 16 m/s^2 and 3.3 mm at 680 rpm; p. 12: 30 mV at 720 rpm "
                       "gives 1.3 mm"},
    "fig6": {"fig6a": {"stable_alpha_deg": 180.0},
             "fig6b": {"stable_alpha_deg": 180.0, "negative_to_positive_extreme": 2.5},
             "source": "000 Fig. 6 and text: one ball mR = Me; a) w > w_x, w_y, b) w_y < w < w_x: "
                       "'the negative extreme is 2.5 times higher than the positive'; 'for both "
                       "diagrams the stable equilibrium position of the ball is alpha_f = pi'"},
    "fig7": {"force_with_more_damping": "moves downwards",
             "source": "000 Fig. 6-7 text: 'By increasing the damping of the drum, the diagram "
                       "F1(alpha) moves downwards'"},
    "fig9": {"D_x_um": 10.0, "D_y_um": 25.0, "D_alpha_rad": 0.005,
             "source": "000 Fig. 9: full minus kinetic-static model, 'D_x almost 10 um, D_y 25 um, "
                       "D_alpha 0.005 rad' at the beginning"},
    "eq30_32": {"eq30_coefficient": -0.5, "eq31_coefficient": -0.5, "eq32_deg": 2.4,
                "eq32_ratio_f_r_1e-3_to_1e-4": 10.0,
                "source": "000 eq 30-32: |d1 - 0.5 d2| < (R/e)(f/r), |-0.5 d1 + d2| < (R/e)(f/r); "
                          "2.4 deg for Me = 0.05 kg m, R = 0.28 m, f/r = 1e-4; 'about ten times' "
                          "for f/r = 1e-3"},
    "fig15": {"beta_of_max_deviation_deg": 90.0,
              "source": "000 Fig. 15 text: 'In the case of one roller, its maximum deviation occurs "
                        "at the angle beta = pi/2'"},
    "tolerance": {"eq58_fraction_of_Me": 0.05,
                  "eq60_rho_max_um": {"Me_0.025": 34.0, "Me_0.05": 67.0},
                  "eq62_fraction_of_Me": 0.07, "eq63_f_r_max": 5e-5,
                  "eq65_fraction_of_Me": 0.005, "eq66_F_max_N": 57.0,
                  "source": "000 eq 56-66: residual 0.1 Me split 50/35/10/5 %; M = 37 kg, "
                            "R = 0.28 m, 1000 rpm, gamma = 61 deg"},
}


#: All published numbers of seed 000, by section.
PUBLISHED = {**ANALYSIS, **runup_000.PUBLISHED, **washer_000.PUBLISHED}

#: What each computed target claims: target id (= key prefix of its rows) -> published mapping.
SECTIONS = {
    "000-fig3": PUBLISHED["fig3"],
    "000-fig5": PUBLISHED["fig5"],
    "000-fig6-7": {"fig6": PUBLISHED["fig6"], "fig7": PUBLISHED["fig7"]},
    "000-fig9": PUBLISHED["fig9"],
    "000-table1-2": {"table1": PUBLISHED["table1"], "table2": PUBLISHED["table2"]},
    "000-fig10-11": {"fig10": PUBLISHED["fig10"], "fig11": PUBLISHED["fig11"]},
    "000-fig12-eq32": PUBLISHED["eq30_32"],
    "000-fig13": PUBLISHED["fig13"],
    "000-fig15": PUBLISHED["fig15"],
    "000-fig16": PUBLISHED["fig16"],
    "000-fig18": PUBLISHED["fig18"],
    "000-table3-4": {"table3": PUBLISHED["table3"], "table4": PUBLISHED["table4"]},
    "000-tolerance": PUBLISHED["tolerance"],
}


def rows(target_id: str) -> Rows:
    """The (empty) comparison rows of a 000 target: key prefix = the target id, paths in its section
    (:data:`SECTIONS`).

    Parameters
    ----------
    target_id : str
        A computed target's id, e.g. ``"000-fig3"``.
    """
    return Rows(target_id, SECTIONS[target_id])
