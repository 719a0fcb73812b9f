"""Sweeps at scale: grids and Monte Carlo over the simulator, local or on Dask, durable and
resumable. ``sweep(spec, store)`` runs (``sweep(d, store, base=config_or_system, ...)`` for a
base built in Python); ``open_sweep(store)`` reads; ``summary`` reduces."""
from .execute import (EXECUTORS, SweepAborted, SweepInterrupted, check_executor, open_sweep,
                      sweep)
from .plan import Plan, make_plan, start_grid
from .spec import SweepError, SweepSpec, as_spec, load_spec, spec_from_dict
from .store import StoreBusy, StoreMismatch
from .summary import (percentile_intervals, percentiles, reduce_over, share_below,
                      share_intervals, summary_dict)

__all__ = ["EXECUTORS", "Plan", "StoreBusy", "StoreMismatch", "SweepAborted", "SweepError",
           "SweepInterrupted", "SweepSpec", "as_spec", "check_executor", "load_spec",
           "make_plan", "open_sweep", "percentile_intervals", "percentiles", "reduce_over",
           "share_below", "share_intervals",
           "spec_from_dict", "start_grid", "summary_dict", "sweep"]
