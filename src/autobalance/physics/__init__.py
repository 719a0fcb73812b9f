"""Closed forms, each formula once: residual unbalance, ISO 1940 grades, the harmonic (Jeffcott)
response, the seed-000 washer analysis (vibratory forces, equilibria, error bounds, tolerances)
and 004's immobility and stick threshold. Nothing here integrates the model in time
(:mod:`autobalance.simulate` and :mod:`autobalance.studies` do)."""
from __future__ import annotations

from .iso1940 import (GRADES, grade, grade_class, grade_value, permissible_eccentricity,
                      unbalance_for_grade, unbalance_value)
from .unbalance import residual_unbalance
from .response import (BallInfluence, HarmonicResponse, axis_response, ball_influence,
                       damped_peak_speeds, damping_ratios, dynamic_stiffness, harmonic_response,
                       natural_frequencies, response_table, steady_displacement, steady_orbit_start,
                       synchronous_orbit)
from .vibratory import (DrumResponse, drum_response, force_jacobian, single_ball_force, speed_regime,
                        vibratory_components, vibratory_forces)
from .equilibria import Equilibrium, balancing_onset_speed, find_equilibria, single_ball_stability
from .error_bounds import (ball_natural_frequencies, ball_natural_frequency_single,
                           eccentricity_deviation_single, eccentricity_equilibrium, rolling_deadband,
                           rolling_deadband_single, suspension_friction_deviation,
                           symmetric_rolling_deviation)
from .tolerance import design_tolerances, predict_residual, tolerances_for_grade, worst_case_prediction
from .worst_case import attained_residual, residual_bound
from .friction import creep_speed
from .immobility import immobile_mask, immobility, steady_deflection, stick_threshold_grade, tangential_force

__all__ = [
    "BallInfluence", "GRADES", "HarmonicResponse", "axis_response", "ball_influence",
    "damped_peak_speeds", "damping_ratios", "dynamic_stiffness", "grade", "grade_class",
    "grade_value", "harmonic_response", "natural_frequencies", "permissible_eccentricity",
    "residual_unbalance", "response_table", "steady_displacement", "steady_orbit_start",
    "synchronous_orbit", "unbalance_for_grade", "unbalance_value",
    # seed-000 washer analysis
    "DrumResponse", "Equilibrium", "balancing_onset_speed", "ball_natural_frequencies",
    "ball_natural_frequency_single", "design_tolerances", "drum_response",
    "eccentricity_deviation_single", "eccentricity_equilibrium", "find_equilibria",
    "force_jacobian", "predict_residual", "residual_bound", "attained_residual",
    "tolerances_for_grade", "worst_case_prediction", "rolling_deadband", "rolling_deadband_single",
    "single_ball_force", "single_ball_stability", "speed_regime",
    "suspension_friction_deviation", "symmetric_rolling_deviation",
    "vibratory_components", "vibratory_forces",
    # 004's tanh law's slow manifold
    "creep_speed",
    # 004 immobility
    "immobile_mask", "immobility", "steady_deflection", "stick_threshold_grade", "tangential_force",
]
