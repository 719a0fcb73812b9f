"""Liquid (Leblanc) balancers: free surface and motion modes (003), kinetostatics (001),
the liquid in a displaced chamber (quasi-static), reduced-order run-up dynamics. See
docs/liquid/index.md."""
from .dynamics import RunUp, engagement, fill_sweep, run_up, steady_response
from .free_surface import (MODE_NAMES, FreeSurface, bottom_touch_speed, entrainment_speed,
                           free_surface, gravity_mode_speed, lid_touch_speed, liquid_volume,
                           mode_speeds, motion_mode, surface_height,
                           surface_profiles)
from .kinetostatic import (alpha0, alpha0_residual, balancing_efficiency, eccentricity_ratio,
                           friction_angle, friction_force, friction_tan_bound, jeffcott_phase,
                           laminar_pipe_force, residual_lambda0)
from .film import (CoupledRun, FilmRun, coupled_run, film_equilibrium, film_run, film_unbalance,
                   film_wave_speed)
from .steady import response_curve, ring_response, synchronous_deflection
from .quasistatic import QuasiStatic, intact_ring_unbalance, lens, quasi_static
from ..models.liquid_balancer import (G_STANDARD, PLACEMENT_LAWS, WATER, Chamber, Liquid,
                                      LiquidBalancer, LiquidModel, VerticalRotor,
                                      sufficient_volume)

__all__ = [
    "Chamber", "CoupledRun", "FilmRun", "FreeSurface", "G_STANDARD", "Liquid", "LiquidBalancer",
    "LiquidModel", "MODE_NAMES", "PLACEMENT_LAWS", "QuasiStatic", "RunUp", "VerticalRotor",
    "WATER", "alpha0", "alpha0_residual", "balancing_efficiency", "bottom_touch_speed",
    "coupled_run", "eccentricity_ratio", "engagement", "entrainment_speed", "film_equilibrium",
    "film_run", "film_unbalance", "film_wave_speed", "fill_sweep", "free_surface",
    "friction_angle", "friction_force", "friction_tan_bound", "gravity_mode_speed",
    "intact_ring_unbalance", "jeffcott_phase", "laminar_pipe_force", "lens", "lid_touch_speed",
    "liquid_volume", "mode_speeds", "motion_mode", "quasi_static", "residual_lambda0",
    "response_curve", "ring_response", "run_up", "steady_response", "sufficient_volume",
    "surface_height", "surface_profiles", "synchronous_deflection",
]
