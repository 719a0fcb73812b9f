"""TOML configuration files and presets -> the :mod:`autobalance.models` dataclasses.

Units live only at this boundary. Every physical value in a TOML file (or a ``--set`` override)
is either a bare number, meaning SI, or a string ``"<number> <unit expression>"`` that
:mod:`pint` parses (``"20 N/mm"``, ``"0.025 kg*m"``, ``"3000 g*cm"``, ``"61 deg"``,
``"1000 rpm"``, ``"167 Hz"``); any other expression is refused before pint evaluates it
(:func:`.units.check_unit_expression`). Rotational speeds in a pure inverse time (``min^-1``,
``1/min``, ``Hz``, ``1/s``) count revolutions, as on drawings and motor plates, and become
``2*pi`` times their value in 1/s [rad/s]; a unit carrying an angle (``rpm``, ``rev/min``,
``rad/s``, ``deg/s``) is an angle per time and is converted to [rad/s]. Radians are
dimensionless. Command-line ranges ``LO:HI:N`` and lists ``a, b, c unit`` are read by
:mod:`.ranges`.

Every problem raises :class:`ConfigError` with one line naming the dotted field, the value and
what is allowed, e.g. ``suspension.kx = '5 kg': expected a stiffness [N/m], e.g. '20 N/mm'``.

File layout (sections and their keys: :data:`SECTIONS` and :data:`PROFILE_KINDS`)::

    name = "..."            description = "..."
    [rotor]       mass, unbalance, polar_inertia, spin_damping, unbalance_schedule
    [suspension]  kx, ky, cx, cy, dry_friction_*, base_*
    [balancer]    n_balls, ball_mass, race_radius, ball_radius, element, damping, ...
    [gravity]     g, direction
    [liquid]      chamber_radius, chamber_height, volume, density, kinematic_viscosity,
                  partitions, friction_arc, axis, inner_radius  (a Leblanc liquid
                  balancer; the chamber keys take a list for concentric chambers)
    [profile]     kind = constant | ramp | table | std | tsr | motor, and the kind's keys
    [initial]     ball_angles, ball_speeds, x, y, vx, vy, steady_state
    [options]     friction_law, v_sat, normal_force, rtol, atol_scale, max_step, save_dt, max_steps

Keys left out take the defaults of the model dataclasses.

Modules: :mod:`.units` (pint registry, SI by kind), :mod:`.ranges` (ranges and lists of
values on the command line), :mod:`.schema` (the keys of each section),
:mod:`.load` (:class:`Config`, :func:`from_dict`, :func:`load_config`), :mod:`.presets`,
:mod:`.overrides` (``--set``), :mod:`.edit` (configs built and changed in Python:
:func:`from_models`, :func:`replace_values`) and :mod:`.describe`.
"""
from .describe import describe
from .edit import from_models, replace_values
from .load import Config, _read, from_dict, load_config, source_comments
from .overrides import apply_overrides
from .presets import list_presets, preset_path
from .ranges import parse_interval, parse_list, parse_range, parse_values
from .schema import PROFILE_KINDS, SECTIONS, F
from .units import KINDS, UNIT_LABEL, ConfigError, parse_quantity, registry, speed_si


def __getattr__(name: str):
    if name == "ureg":                  # the unit registry, made on first use (units.registry)
        return registry()
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")

__all__ = ["KINDS", "PROFILE_KINDS", "SECTIONS", "UNIT_LABEL", "Config", "ConfigError", "F",
           "_read", "apply_overrides", "describe", "from_dict", "from_models", "list_presets",
           "load_config", "parse_interval", "parse_list", "parse_quantity", "parse_range",
           "parse_values", "preset_path", "registry", "replace_values", "source_comments",
           "speed_si", "ureg"]
