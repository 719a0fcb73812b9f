"""Seed 004 (temporary speed reduction, TSR): single run, start-position Monte Carlo,
initial-unbalance sweep, speed profiles, immobility, the gradual descent and the lower-plateau
map, against the paper.

Each study has ``compute_<study>(...)`` returning an :class:`xarray.Dataset` (SI, with units in
attrs), its published numbers in :data:`PUBLISHED` and ``compare_<study>(ds)`` returning rows
``{quantity, published, computed, tolerance, ok, note}``. :data:`STUDIES` maps the CLI names to
them. A published number that we do not reproduce is a row with ``ok = False`` and a note; a
published number whose study was not computed in this variant is a row with ``computed = None``,
``ok = False`` and the note "not computed".

Profile (004 Fig. 3 is given only as a figure; docs/model.md sec. 5, the ``vub_jeffcott_004``
preset): linear run-up 0 -> 167 Hz in 18 s (STD read-out at 18 s = 20 %), linear ramp to the
100 Hz plateau over 18-28 s, plateau 28-48 s, linear back to 167 Hz over 48-58 s, hold to 90 s
(TSR read-out). Exact Coulomb stick-slip (mu_s = mu), point-mass balls, no gravity (004 sec. 3.1).

Grades: G = |U_res| / M_t * Omega_nom [mm/s] (ISO 1940-1, 004 sec. 4). The initial unbalance
G_ini is the rotor's own unbalance (without balls); the preset's 0.319 g m is G20.25 (004: G20).

This module is the seed's facade: it re-exports what the paper package uses from the studies
(:mod:`autobalance.studies`), the physics (:mod:`autobalance.physics.immobility`), the 004
wrappers (:mod:`.compute`), the comparison rows (:mod:`.compare`) and the targets (:mod:`.targets`).
"""
from __future__ import annotations

from ...physics.immobility import (IMMOBILITY_BYTES, IMMOBILITY_BYTES_PER_BALL, IMMOBILITY_COST_S,
                                   check_immobility, immobile_mask, immobility, steady_deflection,
                                   stick_threshold_grade, tangential_force)
from ...physics.iso1940 import grade_value as _grade
from ...physics.iso1940 import unbalance_value as grade_to_unbalance
from ...simulate.probe import kernel_required_friction
from ...studies._plateau import DESCENT_PCT
from ...studies._start_positions import start_family
from ...studies.statistics import half_drop as _half_drop
from ...studies.statistics import mode as _mode
from ...studies.statistics import plateau_speed, regions, valid_ranges
from ...studies.statistics import rise_after_min as _rise_after_min
from .compare import (_share_tol, compare_descent, compare_immobility, compare_monte_carlo,
                      compare_plateau, compare_profile, compare_single, compare_table1,
                      compare_unbalance)
from .compute import (_cfg, compute_descent, compute_immobility, compute_monte_carlo,
                      compute_plateau, compute_profile, compute_single, compute_table1,
                      compute_unbalance)
from .published import (C_R, G_LIMIT, G_SPAN, G_TSR_RANGE, ITEMS_004, MU_R,
                         PLATEAU_CASES, PRESET, PUBLISHED, REGIONS, SLOW_SETS, UNBALANCE_CASES)
from .targets import STUDIES, TARGETS

__all__ = ["C_R", "G_LIMIT", "G_SPAN", "G_TSR_RANGE", "IMMOBILITY_BYTES", "IMMOBILITY_BYTES_PER_BALL",
           "IMMOBILITY_COST_S", "ITEMS_004", "MU_R", "PLATEAU_CASES", "PRESET", "PUBLISHED", "REGIONS",
           "SLOW_SETS", "STUDIES", "TARGETS", "UNBALANCE_CASES", "check_immobility", "compare_descent",
           "compare_immobility", "compare_monte_carlo", "compare_plateau", "compare_profile",
           "compare_single", "compare_table1", "compare_unbalance", "compute_descent",
           "compute_immobility", "compute_monte_carlo", "compute_plateau", "compute_profile",
           "compute_single", "compute_table1", "compute_unbalance", "grade_to_unbalance",
           "immobile_mask", "immobility", "kernel_required_friction", "plateau_speed", "regions",
           "start_family", "steady_deflection", "stick_threshold_grade", "tangential_force",
           "valid_ranges", "DESCENT_PCT", "_cfg", "_grade", "_half_drop", "_mode",
           "_rise_after_min", "_share_tol"]
