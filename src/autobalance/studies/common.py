"""What every study of :mod:`autobalance.studies` shares: the machine with overrides (``load``),
004's friction and damping cases as overrides (``case_sets``), resumable stores (``store_path``),
the start grid run as one sweep (``run_start_grid``), the default starts per ball count and the
read-out labels of a profile.

Every study takes ``base``, the machine: a preset name, a TOML config path or a Config built in
Python (:func:`autobalance.config.from_models`).
"""
from __future__ import annotations

import math
import tempfile
from collections.abc import Iterable, Iterator, Sequence
from contextlib import contextmanager
from pathlib import Path
from typing import TYPE_CHECKING

import numpy as np

if TYPE_CHECKING:
    from ..config import Config
    from ..models import MotorDrive, SpeedProfile

__all__ = ["capacity_grades", "case_sets", "checkpoint_labels", "default_starts", "load",
           "run_start_grid", "starts_for_runs", "store_path", "sweep_root"]


def load(base: str | Path | Config, sets: Sequence[str] = (),
         allow_liquid: bool = False, liquid_alone: bool = False) -> Config:
    """The machine of a study with ``sets`` overrides ("path=value" as for ``--set``) applied: a
    ball balancer, with a liquid beside it if ``allow_liquid``, or a liquid alone if
    ``liquid_alone`` too (the fill map loads its liquid machines itself).

    Parameters
    ----------
    base : str, Path or Config
        A preset name, a TOML config path, or a :class:`autobalance.config.Config` built in
        Python (:func:`autobalance.config.from_models`).
    sets : sequence of str
        Overrides "path=value" (values with units, as for ``--set``).
    allow_liquid : bool
        Accept a liquid beside the balls (a study that only simulates, the start-position
        Monte Carlo: autobalance.simulate.hybrid models it).
    liquid_alone : bool
        With ``allow_liquid``, accept a liquid balancer without balls too (a study that only
        simulates and needs no ball starts: the film model of
        :func:`autobalance.simulate.simulate` of a liquid alone, a profile or a motor).

    Returns
    -------
    Config

    Raises
    ------
    ParameterError
        A machine without balls, or with a liquid balancer unless ``allow_liquid`` (one line).
    """
    from ..config import Config, load_config, replace_values
    from ..config.overrides import parse_override

    if isinstance(base, Config):
        cfg = replace_values(base, dict(parse_override(s) for s in sets)) if sets else base
    else:
        cfg = load_config(base, list(sets))
    s = cfg.system
    s.require_balls("the studies", allow_liquid=allow_liquid,
                    allow_empty=allow_liquid and liquid_alone and s.liquid is not None)
    return cfg


def capacity_grades(cfg: Config) -> tuple[float, float]:
    """The ISO 1940 grades [mm/s] of the balls' capacity sum m R and of the liquid's rho V R
    (all of it gathered at the wall, 003 sec. 5.3; 0 without a liquid) on the total mass at
    the nominal speed: the scale of the studies' default unbalance grids.

    Parameters
    ----------
    cfg : Config
        The machine (its balancer [kg*m], liquid, total mass [kg] and nominal speed [rad/s]).

    Returns
    -------
    (float, float)
        (G_balls, G_liquid) [mm/s].
    """
    from ..physics.iso1940 import grade_value

    s, W = cfg.system, cfg.spin.nominal_speed
    liquid = s.liquid.capacity if s.liquid is not None else 0.0
    return (float(grade_value(s.balancer.capacity, s.total_mass, W)),
            float(grade_value(liquid, s.total_mass, W)))


def case_sets(base: str | Path | Config, mu_r: float, c_r: float) -> list:
    """Overrides scaling the base machine's rolling resistance by ``mu_r`` [-] and its suspension
    damping by ``c_r`` [-] (004 sec. 4.5 varies mu and c around its Table 1 values).

    Parameters
    ----------
    base : str, Path or Config
        The machine: a preset name, a TOML config path or a loaded Config (as for :func:`load`).
    mu_r : float
        Factor on each ball's rolling-resistance coefficient mu [-].
    c_r : float
        Factor on the suspension damping cx, cy [-].

    Returns
    -------
    list of str
        Three "path=value" overrides (balancer.rolling_resistance, suspension.cx, suspension.cy;
        the first left out for a machine without balls).
    """
    s = load(base, allow_liquid=True, liquid_alone=True).system   # the caller checked it
    mu = [float(x) * mu_r for x in s.balancer.rolling_resistance]     # each ball's own, scaled
    out = [f"suspension.cx={s.suspension.cx * c_r!r}", f"suspension.cy={s.suspension.cy * c_r!r}"]
    if not mu:                                  # a liquid alone: no balls to scale
        return out
    mu_text = repr(mu[0]) if len(set(mu)) <= 1 else "[" + ", ".join(map(repr, mu)) + "]"
    return [f"balancer.rolling_resistance={mu_text}", *out]


def store_path(store_dir: str | Path | None, name: str) -> Path | None:
    """``store_dir / name`` (a resumable sweep store) or None (a temporary store).

    Parameters
    ----------
    store_dir : str or Path or None
        Directory of the study's sweep stores; None = temporary stores.
    name : str
        Name of this sweep's store.

    Returns
    -------
    Path or None
    """
    return None if store_dir is None else Path(store_dir) / name


def run_start_grid(base: str | Path | Config, name: str, sets: Iterable[str],
                   grid: dict[str, list], n: int, *, store: str | Path | None = None,
                   executor: str = "local", workers: int | None = None,
                   scheduler: str | None = None, history_dt: float = 0.0,
                   samples: int | None = None,
                   seed: int = 0, progress: bool = False):
    """Run an autobalance.sweep start-grid Monte Carlo (004 sec. 4.2: n x n equispaced start
    positions of two identical balls, n(n+1)/2 runs) of the machine ``base`` with ``sets``
    overrides over ``grid`` (path -> values) and return its Dataset. A liquid balancer alone
    has no starts: one run per grid cell, in a ``sample`` dimension of length 1.

    ``store``: a directory (reused with resume: same description -> nothing rerun) or None for
    a temporary one.

    Parameters
    ----------
    base : str or Path
        The machine: a preset name or a TOML config path (its system, profile, options and
        balls).
    name : str
        Name of the sweep.
    sets : iterable of str
        "path=value" overrides applied to ``base`` for every run.
    grid : dict of str to list
        Config path -> values of the sweep grid, in the units of that path (e.g.
        "rotor.unbalance" [kg*m], "profile.plateau" [rad/s]); empty = one cell.
    n : int
        Start positions per ball of the start grid (n(n+1)/2 runs per grid cell).
    store : str or Path or None
        The sweep's directory, or None for a temporary store: it holds one store per identity
        of the sweep (:func:`autobalance.sweep.sweep` with ``keyed``), so a rerun resumes its
        own and a changed machine, option or package version starts a new one beside it.
    executor : str
        "serial", "local" (processes on this machine) or "dask" (:func:`autobalance.sweep.sweep`).
    workers : int or None
        Local worker processes (None: the sweep's default); the batch size assumes 2.
    scheduler : str or None
        Dask scheduler address, e.g. "tcp://127.0.0.1:8786".
    history_dt : float
        Spacing of the stored grade history [s]; 0 = checkpoints only.
    samples : int or None
        Uniform random start angles instead of the grid: this many per grid cell (``n`` is then
        ignored); None = the start grid.
    seed : int
        Seed of the random start angles.
    progress : bool
        Show the sweep's progress bar on stderr.

    Returns
    -------
    xarray.Dataset
        The sweep's assembled result (grade_G [mm/s] per sample and checkpoint, status,
        start_angle [rad], and the history when ``history_dt`` > 0).
    """
    from ..sweep import spec_from_dict, sweep
    from ..sweep.plan import identical_balls, n_start_grid

    n_cells = int(np.prod([len(v) for v in grid.values()])) if grid else 1
    b = load(base, sets, allow_liquid=True, liquid_alone=True).system.balancer  # caller checked
    if b.n_balls == 0:
        per_cell = 1                            # a liquid alone: no starts to sample
    elif samples is None:
        per_cell = n_start_grid(n, b.n_balls, identical_balls(b))   # 2 balls: n(n+1)/2
    else:
        per_cell = int(samples)
    n_runs = n_cells * per_cell
    w = workers or 2
    bs = max(1, min(64, math.ceil(n_runs / (4 * w))))
    from ..config import Config

    python_base = isinstance(base, Config)
    head = {"name": name, "set": list(sets), "batch_size": bs}
    if not python_base:
        head["base"] = str(base)
    mc = ({} if b.n_balls == 0 else
          {"monte_carlo": ({"kind": "start_grid", "n": int(n)} if samples is None
                           else {"kind": "random", "samples": int(samples), "seed": int(seed)})})
    spec = spec_from_dict({"sweep": head,
                           "grid": grid, **mc,
                           **({"outputs": {"history_dt": float(history_dt)}} if history_dt else {})},
                          base=base if python_base else None)
    with sweep_root(store) as root:
        ds = sweep(spec, root / name if store is None else root, executor=executor,
                   workers=workers, scheduler=scheduler, resume=store is not None,
                   progress=progress, keyed=store is not None).load()
    return ds if "sample" in ds.dims else ds.expand_dims("sample")


@contextmanager
def sweep_root(store: str | Path | None) -> Iterator[Path]:
    """Context manager: the directory a study's sweeps go in, ``store`` itself (durable: run
    them with ``resume=True, keyed=True`` so that a rerun resumes its own) or, for None, a
    temporary directory removed at the end; a Ctrl-C or SIGTERM inside it then says that
    nothing was kept (a temporary store offers no resume).

    Parameters
    ----------
    store : str or Path or None
        The study's store directory, or None.

    Yields
    ------
    Path

    Raises
    ------
    autobalance.sweep.SweepInterrupted
        Interrupted with a temporary store: ``resumable`` False, "interrupted; nothing kept
        (pass --store DIR to make it resumable)".
    """
    if store is not None:
        yield Path(store)
        return
    import signal

    from ..sweep import SweepInterrupted

    with tempfile.TemporaryDirectory() as d:
        try:
            yield Path(d)
        except KeyboardInterrupt as e:      # the temporary store goes with the directory
            sig = getattr(e, "signal", signal.SIGINT)
            what = "terminated (SIGTERM)" if sig == signal.SIGTERM else "interrupted"
            raise SweepInterrupted(f"{what}; nothing kept (pass --store DIR to make it "
                                   "resumable)", sig, resumable=False) from None


def checkpoint_labels(spin: SpeedProfile | MotorDrive) -> list:
    """Names of a profile's read-outs: "STD" and "TSR" for 004's temporary speed reduction
    (Fig. 3), otherwise "t=<time> s".

    Parameters
    ----------
    spin : SpeedProfile or MotorDrive
        The profile (its ``name`` and ``checkpoints`` [s]).

    Returns
    -------
    list of str
        One label per checkpoint.
    """
    cps = [float(c) for c in spin.checkpoints]
    if getattr(spin, "name", "") == "tsr" and len(cps) == 2:
        return ["STD", "TSR"]
    return [f"t={c:g} s" for c in cps]


def default_starts(n_balls: int, quick: bool) -> int:
    """Start positions per ball of the default start grid: 004's 50 (1275 runs) for two balls,
    fewer for more balls so that the grid stays near a thousand runs (20 for three: 1540);
    quick: 12 for two balls (78 runs), 8 for three (120).

    Parameters
    ----------
    n_balls : int
        Number of balls N >= 1.
    quick : bool
        The coarse grid.

    Returns
    -------
    int
        Positions per ball n.
    """
    if quick:
        return {1: 24, 2: 12}.get(n_balls, 8 if n_balls == 3 else 5)
    return {1: 360, 2: 50}.get(n_balls, 20 if n_balls == 3 else 10)


def starts_for_runs(n_balls: int, runs: int, identical: bool = True) -> int:
    """The largest number of positions per ball n >= 1 whose start grid (004 sec. 4.2:
    n(n+1)/2 runs for two identical balls, C(n+N-1, N) for N, n^N for unequal balls) has at
    most ``runs`` configurations, so that a study's cost per cell stays the same whatever the
    ball count (e.g. 210 runs: n = 20 for two balls as 004 Fig. 14-15, 9 for three).

    Parameters
    ----------
    n_balls : int
        Number of balls N >= 1.
    runs : int
        Most start configurations per cell (>= 1).
    identical : bool
        Identical balls (the grid keeps one ordering of each configuration).

    Returns
    -------
    int
        Positions per ball n (>= 1).
    """
    from ..sweep.plan import n_start_grid

    n = 1
    while n_start_grid(n + 1, n_balls, identical) <= runs:
        n += 1
    return n
