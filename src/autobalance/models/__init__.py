"""Physical parameters as frozen dataclasses in SI units, validated on construction."""
from ._validate import ParameterError
from .balancer import CONTACT_MODELS, INERTIA_FACTOR, BallBalancer
from .liquid import AXES, LiquidDevice
from .liquid_balancer import (G_STANDARD, Chamber, Liquid, LiquidBalancer, LiquidModel,
                              VerticalRotor)
from .profile import PROFILE_KINDS, MotorDrive, SpeedProfile
from .rotor import Gravity, Rotor, Suspension
from .system import FRICTION_LAWS, NORMAL_FORCES, InitialState, SimOptions, System

__all__ = [
    "AXES", "BallBalancer", "CONTACT_MODELS", "Chamber", "FRICTION_LAWS", "G_STANDARD", "Gravity",
    "PROFILE_KINDS", "INERTIA_FACTOR", "InitialState", "Liquid", "LiquidBalancer", "LiquidDevice",
    "LiquidModel", "MotorDrive", "NORMAL_FORCES", "ParameterError", "Rotor", "SimOptions",
    "SpeedProfile", "Suspension", "System", "VerticalRotor",
]
