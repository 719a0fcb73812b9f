"""Machine-agnostic studies of a System + profile: statistics and analyses that take any
machine. Each study is a function of this package (:mod:`.api`): the machine and keyword
arguments in, a :class:`StudyResult` out (``.to_xarray()``, ``.summary()``, ``.plot()``). The
modules beside hold their computations; the seed papers' reproductions live in
:mod:`autobalance.papers`."""
from .api import (StudyResult, as_config, design, fill_map, immobility, plateau, runup,
                  sensitivity, speed_map, start_positions, tolerances, unbalance_range)

__all__ = ["StudyResult", "as_config", "design", "fill_map", "immobility", "plateau", "runup",
           "sensitivity", "speed_map", "start_positions", "tolerances", "unbalance_range"]
