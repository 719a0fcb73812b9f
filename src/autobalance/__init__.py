"""autobalance: simulation and design of passive automatic balancers for rotors."""
__version__ = "0.1.0"

from .models import (BallBalancer, Gravity, InitialState, MotorDrive, ParameterError, Rotor,  # noqa: E402
                     SimOptions, SpeedProfile, Suspension, System)


def simulate(*args, **kwargs):
    """Lazy alias of :func:`autobalance.simulate.simulate` (keeps `import autobalance` light)."""
    from .simulate import simulate as _simulate
    return _simulate(*args, **kwargs)


def simulate_batch(*args, **kwargs):
    """Lazy alias of :func:`autobalance.simulate.simulate_batch`."""
    from .simulate import simulate_batch as _sb
    return _sb(*args, **kwargs)


__all__ = ["BallBalancer", "Gravity", "InitialState", "MotorDrive", "ParameterError", "Rotor",
           "SimOptions", "SpeedProfile", "Suspension", "System", "simulate", "simulate_batch",
           "__version__"]
