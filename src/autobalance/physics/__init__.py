"""Closed-form analysis: harmonic (Jeffcott) response, ISO 1940 grades, and the seed-000 washer
analysis (vibratory forces, equilibria, error bounds, tolerances, kinetic-static model)."""
from .iso1940 import GRADES, grade, grade_class, permissible_eccentricity, unbalance_for_grade
from .response import (BallInfluence, HarmonicResponse, axis_response, ball_influence,
                       damped_peak_speeds, damping_ratios, harmonic_response, natural_frequencies,
                       response_table, steady_displacement)
from .vibratory import (DrumResponse, drum_response, force_jacobian, single_ball_force, speed_regime,
                        vibratory_components, vibratory_forces)
from .equilibria import (Equilibrium, balancing_onset_speed, find_equilibria, floquet_full,
                         single_ball_stability, verify_by_simulation)
from .error_bounds import (ball_natural_frequencies, ball_natural_frequency_single,
                           eccentricity_deviation_single, eccentricity_equilibrium, rolling_deadband,
                           rolling_deadband_single, suspension_friction_deviation,
                           symmetric_rolling_deviation)
from .tolerance import design_tolerances, predict_residual
from .kinetic_static import compare_with_full, simulate_kinetic_static

__all__ = [
    "BallInfluence", "GRADES", "HarmonicResponse", "axis_response", "ball_influence",
    "damped_peak_speeds", "damping_ratios", "grade", "grade_class", "harmonic_response",
    "natural_frequencies", "permissible_eccentricity", "response_table", "steady_displacement",
    "unbalance_for_grade",
    # seed-000 washer analysis (issue 4)
    "DrumResponse", "Equilibrium", "balancing_onset_speed", "ball_natural_frequencies",
    "ball_natural_frequency_single", "compare_with_full", "design_tolerances", "drum_response",
    "eccentricity_deviation_single", "eccentricity_equilibrium", "find_equilibria", "floquet_full",
    "force_jacobian", "predict_residual", "rolling_deadband", "rolling_deadband_single",
    "simulate_kinetic_static", "single_ball_force", "single_ball_stability", "speed_regime",
    "suspension_friction_deviation", "symmetric_rolling_deviation", "verify_by_simulation",
    "vibratory_components", "vibratory_forces",
]
