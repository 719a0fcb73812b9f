"""Closed-form analysis: harmonic (Jeffcott) response and ISO 1940 balance quality grades."""
from .iso1940 import GRADES, grade, grade_class, permissible_eccentricity, unbalance_for_grade
from .response import (BallInfluence, HarmonicResponse, axis_response, ball_influence,
                       damped_peak_speeds, damping_ratios, harmonic_response, natural_frequencies,
                       response_table, steady_displacement)

__all__ = [
    "BallInfluence", "GRADES", "HarmonicResponse", "axis_response", "ball_influence",
    "damped_peak_speeds", "damping_ratios", "grade", "grade_class", "harmonic_response",
    "natural_frequencies", "permissible_eccentricity", "response_table", "steady_displacement",
    "unbalance_for_grade",
]
