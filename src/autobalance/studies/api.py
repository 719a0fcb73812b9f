"""The studies as a Python API: one function per study, each taking the machine and keyword
arguments and returning a :class:`StudyResult` (``.to_xarray()``, ``.summary()``,
``.plot()``). The command line's studies call the same computations.

One naming rule for every argument:

* ``machine``: a preset name, a TOML file, a :class:`autobalance.config.Config`, or a
  :class:`autobalance.models.System` together with ``profile=`` (a speed profile or motor drive
  built in Python, or a ``[profile]`` table as a dict);
* ``changes``: config keys to change, ``{"balancer.rolling_resistance": 0.001,
  "rotor.unbalance": "0.2 g*m"}``; a number is SI, a string or a pint quantity carries its units;
* the study's own values are SI floats or pint quantities: ``grade`` [mm/s], ``speeds``
  [rad/s], ``unbalance`` [kg*m], ...; counts are ``starts`` (per ball of 004's equispaced
  grid), ``random`` (uniform random starts instead), ``seed``, ``budget`` (runs added where a
  decision is undecided);
* where the simulations run: ``store`` (a directory of resumable sweep stores; None:
  temporary), ``executor`` ("serial", "local", "dask"), ``workers``, ``scheduler``,
  ``progress``.

Example::

    from autobalance import studies

    r = studies.start_positions("examples/centrifuge.toml", quick=True,
                                changes={"balancer.rolling_resistance": 0.001})
    r.summary()["checkpoints"]          # the grade's percentiles with their intervals
    r.to_xarray().to_netcdf("sp.nc")
    r.plot("sp.png")
"""
from __future__ import annotations

import dataclasses
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, Mapping, Sequence

import numpy as np

if TYPE_CHECKING:
    import xarray as xr
    from matplotlib.figure import Figure

    from ..config import Config

__all__ = ["StudyResult", "as_config", "design", "fill_map", "immobility", "plateau", "runup",
           "sensitivity", "speed_map", "start_positions", "tolerances", "unbalance_range"]


@dataclasses.dataclass(frozen=True)
class StudyResult:
    """A study's result: its dataset, its summary and its figure.

    Attributes
    ----------
    study : str
        The study's name (as on the command line, e.g. "start-positions").
    config : Config
        The machine the study ran on, with the ``changes`` applied.
    dataset : xarray.Dataset
        Everything the study computed, with units and provenance in attrs.
    """

    study: str
    config: Any
    dataset: Any
    _summary: Callable[[], dict] = dataclasses.field(repr=False)
    _figure: Callable[[], Any] | None = dataclasses.field(default=None, repr=False)

    def to_xarray(self) -> xr.Dataset:
        """The study's dataset (xarray; units in each variable's attrs)."""
        return self.dataset

    def summary(self) -> dict:
        """The study's answer as a JSON-ready dict in SI with unit-suffixed keys (what
        ``--json`` prints), with the intervals and verdicts of every sampled number."""
        return {"study": self.study, "machine": self.config.name, **self._summary()}

    def plot(self, path: str | Path | None = None) -> Figure:
        """The study's figure; written to ``path`` (.png, .svg, .pdf; atomically) if given.

        Parameters
        ----------
        path : str, Path or None
            The file to write.
        """
        if self._figure is None:
            raise ValueError(f"study {self.study} has no figure")
        fig = self._figure()
        if path is not None:
            from ..atomic import save_figure

            save_figure(fig, Path(path))
        return fig


def _si(value: Any, kind: str) -> Any:
    """A value of a study argument in SI: a float (taken as SI), an array of them, a string
    with units or a pint quantity [the SI unit of ``kind``]. A grade is a velocity in [mm/s]
    (ISO 1940's unit), a bare number read as mm/s."""
    from ..config import parse_quantity

    if value is None:
        return None
    value = _config_value(value)
    if isinstance(value, str):
        if kind == "grade":
            return 1e3 * parse_quantity(value, "velocity", "grade")
        return parse_quantity(value, kind, kind)
    if isinstance(value, (list, tuple, np.ndarray)):
        return np.array([_si(v, kind) for v in value], float)
    return float(value)


def _config_value(value: Any) -> Any:
    """A ``changes`` value as :func:`autobalance.config.replace_values` takes it: a pint
    quantity as a string with its units."""
    if hasattr(value, "magnitude") and hasattr(value, "units"):
        if np.ndim(value.magnitude) == 0:
            return f"{value.magnitude!r} {value.units:~}"
        return [f"{m!r} {value.units:~}" for m in np.ravel(value.magnitude)]
    return value


def as_config(machine: Any, changes: Mapping[str, Any] | None = None,
              profile: Any = None) -> Config:
    """The :class:`autobalance.config.Config` of a study's ``machine`` with ``changes``.

    Parameters
    ----------
    machine : str, Path, Config or System
        A preset name, a TOML file, a Config, or a System (then ``profile`` is needed).
    changes : mapping or None
        Config key -> value (SI number, string with units or pint quantity).
    profile : SpeedProfile, MotorDrive, dict or None
        The spin of a System given alone.
    """
    from ..config import Config, from_models, load_config, replace_values
    from ..models import System

    if isinstance(machine, System):
        if profile is None:
            raise ValueError("a System needs profile= (a SpeedProfile, a MotorDrive or a "
                             "[profile] table as a dict)")
        cfg = from_models(machine, profile)
    elif isinstance(machine, Config):
        cfg = machine
    elif isinstance(machine, (str, Path)):
        cfg = load_config(machine)
    else:
        raise TypeError(f"machine = {machine!r}: expected a preset name, a TOML path, a Config "
                        "or a System")
    if changes:
        cfg = replace_values(cfg, {k: _config_value(v) for k, v in changes.items()})
    return cfg


def _du(cfg):
    from ..config.display import display_units

    return display_units(cfg)


def start_positions(machine: Any, *, changes: Mapping[str, Any] | None = None,
                    profile: Any = None, starts: int | None = None, random: int | None = None,
                    seed: int = 0, grade: Any = 16.0, grid: dict | None = None,
                    quick: bool = False, store: str | Path | None = None,
                    executor: str = "local", workers: int | None = None,
                    scheduler: str | None = None, progress: bool = False) -> StudyResult:
    """The grade over ball start positions (004 sec. 4.2):
    :func:`autobalance.studies._start_positions.compute_start_positions`.

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    starts, random, seed : int or None
        Positions per ball of the equispaced grid, or this many uniform random starts, and
        their seed.
    grade : float or pint quantity
        Target grade [mm/s].
    grid : dict or None
        Config path -> values [SI]: the Monte Carlo per grid cell.
    quick : bool
        The coarse start grid.
    store, executor, workers, scheduler, progress : str, Path, int, bool or None
        Where the simulations run (module docstring).
    """
    from ..plotting.tsr import plot_start_positions
    from ._start_positions import compute_start_positions, start_positions_summary

    cfg = as_config(machine, changes, profile)
    ds = compute_start_positions(cfg, n=starts, samples=random, seed=seed, grid=grid,
                                 grade=_si(grade, "grade"), quick=quick, store=store,
                                 executor=executor, workers=workers, scheduler=scheduler,
                                 progress=progress)
    return StudyResult("start-positions", cfg, ds, lambda: start_positions_summary(ds),
                       lambda: plot_start_positions(ds, f"{cfg.name}: grade over ball start "
                                                        "positions"))


def unbalance_range(machine: Any, *, changes: Mapping[str, Any] | None = None,
                    profile: Any = None, grades: Sequence[float] | None = None,
                    starts: int | None = None, grade: Any = 16.0, budget: int | None = None,
                    seed: int = 0, quick: bool = False, store: str | Path | None = None,
                    executor: str = "local", workers: int | None = None,
                    scheduler: str | None = None, progress: bool = False) -> StudyResult:
    """The residual grade against the initial unbalance and the valid ranges for ``grade``
    (004 sec. 4.3): :func:`autobalance.studies.unbalance.compute_unbalance`.

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    grades : sequence of float or None
        Initial grades G_ini [mm/s] (None: 0 to 1.5 x the balancer's grade).
    starts : int or None
        Positions per ball (None: :func:`autobalance.studies.common.default_starts`).
    grade : float or pint quantity
        Target grade [mm/s] the valid ranges are decided for.
    budget, seed : int or None
        Runs added where a grid point is undecided (None: as many as the grid ran), their
        seed.
    quick : bool
        The coarse grid.
    store, executor, workers, scheduler, progress : str, Path, int, bool or None
        Where the simulations run (module docstring).
    """
    from ..plotting.tsr import plot_unbalance
    from .common import default_starts
    from .unbalance import compute_unbalance, unbalance_summary

    cfg = as_config(machine, changes, profile)
    g = _si(grade, "grade")
    n = default_starts(cfg.system.balancer.n_balls, quick) if starts is None else starts
    ds = compute_unbalance(cfg, G=None if grades is None else _si(grades, "grade"), n=n,
                           quick=quick, grade=g, budget=budget, seed=seed, store_dir=store,
                           executor=executor, workers=workers, scheduler=scheduler,
                           progress=progress)
    return StudyResult("unbalance-range", cfg, ds, lambda: unbalance_summary(ds, g),
                       lambda: plot_unbalance(ds, g, f"{cfg.name}: residual grade against "
                                                     "initial unbalance"))


def plateau(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
            ratios: Sequence[float] | None = None, grades: Sequence[float] | None = None,
            starts: int | None = None, grade: Any = 16.0, budget: int | None = None,
            seed: int = 0, quick: bool = False, store: str | Path | None = None,
            executor: str = "local", workers: int | None = None, scheduler: str | None = None,
            progress: bool = False) -> StudyResult:
    """The lower plateau of a temporary speed reduction (004 sec. 4.6):
    :func:`autobalance.studies._plateau.compute_plateau`.

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (a tsr profile; module docstring).
    ratios : sequence of float or None
        Plateau speeds as multiples of the natural frequency [-].
    grades : sequence of float or None
        Initial grades [mm/s].
    starts : int or None
        Positions per ball.
    grade : float or pint quantity
        Target grade [mm/s] (the figure's line).
    budget, seed : int or None
        Runs added while plateaus are not distinguishable from the best, their seed.
    quick : bool
        The coarse map.
    store, executor, workers, scheduler, progress : str, Path, int, bool or None
        Where the simulations run (module docstring).
    """
    from ..plotting.tsr import plot_plateau
    from ._plateau import compute_plateau, plateau_summary

    cfg = as_config(machine, changes, profile)
    g = _si(grade, "grade")
    ds = compute_plateau(cfg, ratios=ratios, G=None if grades is None else _si(grades, "grade"),
                         n=starts, quick=quick, budget=budget, seed=seed, store_dir=store,
                         executor=executor, workers=workers, scheduler=scheduler,
                         progress=progress)
    return StudyResult("plateau", cfg, ds, lambda: plateau_summary(ds),
                       lambda: plot_plateau(ds, g, f"{cfg.name}: lower plateau of the speed "
                                                   "reduction"))


def speed_map(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
              speeds: Any = None, c_r: Sequence[float] | None = None,
              quick: bool = False, full_model: bool = True) -> StudyResult:
    """Where the machine balances: every equilibrium of the balls and its stability over
    speed (:func:`autobalance.studies._speed_map.compute_speed_map`).

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    speeds : array_like, pint quantity or None
        Speeds [rad/s] (None: 0.3 x the first natural frequency to 1.3 x nominal).
    c_r : sequence of float or None
        Factors on the suspension damping [-] for the second map.
    quick : bool
        The coarse grid.
    full_model : bool
        Also the full model's verdict (False: the kinetic-static one only).
    """
    from ..plotting.speed_map import plot_speed_map
    from ._speed_map import compute_speed_map, speed_map_summary

    cfg = as_config(machine, changes, profile)
    ds = compute_speed_map(cfg, speeds=_si(speeds, "speed"), damping_factors=c_r, quick=quick,
                           full=full_model)
    return StudyResult("speed-map", cfg, ds, lambda: speed_map_summary(ds),
                       lambda: plot_speed_map(ds, speed_unit=_du(cfg).unit("speed")))


def immobility(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
               g_ini: Any = None, mu_r: Sequence[float] = (1.0,), c_r: Sequence[float] = (1.0,),
               starts: int | None = None, quick: bool = False) -> StudyResult:
    """Immobility of balls at rest against speed and the stick threshold G* (004 sec.
    4.4-4.5, closed form): :func:`autobalance.studies._immobility.compute_immobility`.

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    g_ini : float, pint quantity or None
        Initial grade [mm/s] (None: the machine's unbalance at its nominal speed).
    mu_r, c_r : sequence of float
        Factors [-] on the rolling resistance and the suspension damping.
    starts : int or None
        Positions per ball of the grid of balls at rest (>= 2; None: 100, 36 when ``quick``).
    quick : bool
        The coarse speed grid (and 36 positions per ball unless ``starts`` is given).
    """
    from ..plotting.tsr import plot_immobility
    from ._immobility import compute_immobility, immobility_summary

    cfg = as_config(machine, changes, profile)
    s = cfg.system
    ds = compute_immobility(cfg, G_ini=None if g_ini is None else _si(g_ini, "grade"),
                            mu_r=tuple(mu_r), c_r=tuple(c_r), n_conf=starts, quick=quick,
                            field="starts")
    gi = ds.attrs["G_ini"]
    return StudyResult("immobility", cfg, ds,
                       lambda: immobility_summary(ds, cfg.spin.nominal_speed),
                       lambda: plot_immobility(ds, f"{cfg.name}: immobility at G_ini = "
                                                   f"G{gi:.3g}", stick=s.liquid is None,
                                               speed_unit=_du(cfg).unit("speed")))


def sensitivity(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
                variants: dict | None = None, starts: int | None = None,
                random: int | None = None, seed: int = 0, grade: Any = 16.0, z: float = 2.0,
                quick: bool = False, store: str | Path | None = None, executor: str = "local",
                workers: int | None = None, scheduler: str | None = None,
                progress: bool = False) -> StudyResult:
    """Which modelling choices move which results:
    :func:`autobalance.studies._sensitivity.compute_sensitivity`.

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    variants : dict or None
        Name -> list of "path=value" overrides (None: the default variants).
    starts, random, seed : int or None
        The start positions (as :func:`start_positions`).
    grade : float or pint quantity
        Target grade [mm/s].
    z : float
        Effects beyond this many standard errors are significant [-].
    quick : bool
        The coarse start grid.
    store, executor, workers, scheduler, progress : str, Path, int, bool or None
        Where the simulations run (module docstring).
    """
    from ..plotting.sensitivity import plot_sensitivity
    from ._sensitivity import compute_sensitivity, sensitivity_summary

    cfg = as_config(machine, changes, profile)
    ds = compute_sensitivity(cfg, variants, n=starts, samples=random, seed=seed,
                             grade=_si(grade, "grade"), quick=quick, store_dir=store,
                             executor=executor, workers=workers, scheduler=scheduler,
                             progress=progress)
    return StudyResult("sensitivity", cfg, ds, lambda: sensitivity_summary(ds, z),
                       lambda: plot_sensitivity(ds, z, f"{cfg.name}: sensitivity"))


def runup(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
          laws: Sequence[str] | None = None, bare: bool = True,
          threshold: float | None = None) -> StudyResult:
    """The run-up through resonance with and without the balls:
    :func:`autobalance.studies._runup.compute_runup`.

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    laws : sequence of str or None
        Motor torque laws to run (None: the machine's own profile).
    bare : bool
        Also run without the balls.
    threshold : float or None
        Balancing threshold as a fraction of e = U/M_t [-] (None: the study's default).
    """
    from ..plotting.runup import plot_runup
    from ._runup import BALANCING_FRACTION, compute_runup, runup_summary

    cfg = as_config(machine, changes, profile)
    ds = compute_runup(cfg, laws=laws, bare=bare,
                       fraction=BALANCING_FRACTION if threshold is None else threshold)
    return StudyResult("runup", cfg, ds, lambda: runup_summary(ds),
                       lambda: plot_runup(ds, _du(cfg).unit("speed"), f"{cfg.name}: run-up"))


def fill_map(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
             fills: Any = None, speeds: Any = None, linear: bool = False,
             dynamic: bool = False, duration: Any = None, quick: bool = False,
             executor: str = "local", workers: int | None = None,
             progress: bool = False) -> StudyResult:
    """A liquid balancer's steady whirl over fill x speed, with the balanced state's linear
    stability and the coupled wall film on request:
    :func:`autobalance.studies._fill_map.compute_fill_study`.

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine, with a ``[liquid]`` section (module docstring).
    fills : array_like, pint quantity or None
        Liquid volumes [m^3].
    speeds : array_like, pint quantity or None
        Speeds [rad/s].
    linear : bool
        Add the linear stability of the balanced state at every fill and speed.
    dynamic : bool
        Add the wall film coupled with the rotor at up to 8 speeds (4 when ``quick``).
    duration : float, pint quantity or None
        Time at each speed of ``dynamic`` [s] (None: 6 s).
    quick : bool
        The coarse grid.
    executor, workers, progress : str, int, bool or None
        Where the coupled runs go (module docstring).
    """
    from ..plotting.liquid import fill_map_figure
    from ._fill_map import compute_fill_study, fill_map_summary

    cfg = as_config(machine, changes, profile)
    ds = compute_fill_study(cfg, fills=_si(fills, "volume"), speeds=_si(speeds, "speed"),
                            quick=quick, linear=linear, dynamic=dynamic,
                            duration=_si(duration, "time"), executor=executor, workers=workers,
                            progress=progress)
    du = _du(cfg)
    return StudyResult("fill-map", cfg, ds, lambda: fill_map_summary(ds),
                       lambda: fill_map_figure(ds, du.unit("speed"), du.factor("speed"),
                                               f"{cfg.name}: fill map (liquid from physics)"))


def tolerances(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
               grade: Any = 16.0, speed: Any = None, split: dict | None = None,
               residual_fraction: float | None = None, method: str = "bound",
               check: int = 0) -> StudyResult:
    """The tolerances a target grade allows (000 eq 56-66 on the true worst-case bound):
    :func:`autobalance.studies._tolerances.compute_tolerances`, with ``check`` simulated runs
    of the machine built with them (:func:`autobalance.studies._tolerances.
    check_tolerances_by_simulation`). Its dataset holds the budget per cause and the
    summary's numbers as attrs (:func:`autobalance.studies._tolerances.tolerances_dataset`).

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    grade : float or pint quantity
        Target grade [mm/s].
    speed : float, pint quantity or None
        Speed of the bound [rad/s] (None: the nominal speed).
    split : dict or None
        Shares of the residual unbalance per cause.
    residual_fraction : float or None
        Also 000's one-ball method with this required residual / M e [-].
    method : str
        "bound" (the true worst case) or "000".
    check : int
        Random starts simulated with the tolerances at their limits (0: none; only where the
        tolerances are feasible).
    """
    from ..plotting.tolerances import plot_tolerances
    from ._tolerances import check_tolerances_by_simulation, compute_tolerances, tolerances_dataset

    if isinstance(check, bool) or not isinstance(check, (int, np.integer)) or check < 0:
        raise ValueError(f"check = {check!r}: must be an integer >= 0 (simulated runs)")
    cfg = as_config(machine, changes, profile)
    res = compute_tolerances(cfg, grade=_si(grade, "grade"), speed=_si(speed, "speed"),
                             split=split, residual_fraction=residual_fraction, method=method)
    if check and res.get("feasible"):
        res["simulation_check"] = check_tolerances_by_simulation(cfg, res, n=int(check))
    ds = tolerances_dataset(res)
    du = _du(cfg)
    return StudyResult("tolerances", cfg, ds, lambda: dict(res),
                       lambda: plot_tolerances(ds, du.unit("unbalance"), du.factor("unbalance"),
                                               f"{cfg.name}: tolerances for "
                                               f"G{res['target_grade_G_mm_s']:.3g}"))


def design(machine: Any, *, changes: Mapping[str, Any] | None = None, profile: Any = None,
           grade: Any = 16.0, confidence: float = 0.95, unbalance: Any = None,
           n_unbalance: int | None = None, random: int | None = None, space: Any = None,
           seed: int = 0, budget: int | None = None, refine_plateau: bool = True,
           quick: bool = False, store: str | Path | None = None, executor: str = "local",
           workers: int | None = None, scheduler: str | None = None,
           progress: bool = False) -> StudyResult:
    """Which balancer to build: ball count, mass, race radius and speed profile that meet
    ``grade`` at ``confidence`` over the unbalances, decided against the intervals
    (:func:`autobalance.studies._design.compute_design`).

    Parameters
    ----------
    machine, changes, profile : str, Path, Config, System, mapping, SpeedProfile, dict or None
        The machine (module docstring).
    grade : float or pint quantity
        Target grade [mm/s].
    confidence : float
        Share of start positions that must meet it [-].
    unbalance : (lo, hi) of float or pint quantities, or None
        Expected initial unbalance [kg*m] (None: 0.5-1.5 x the machine's).
    n_unbalance : int or None
        Unbalances across the range (None: 4; quick 3).
    random : int or None
        Uniform random starts per unbalance and design in the first pass (None: 40; quick 10).
    space : DesignSpace or None
        The candidates (:class:`autobalance.studies.design_space.DesignSpace`).
    seed, budget : int or None
        Seed of the starts; runs added where a verdict is undecided (None: 4 x the first pass).
    refine_plateau : bool
        Run the plateau study on the best TSR candidate.
    quick : bool
        The small space.
    store, executor, workers, scheduler, progress : str, Path, int, bool or None
        Where the simulations run (module docstring).
    """
    from ..plotting.tsr import plot_design
    from ._design import compute_design, design_summary

    cfg = as_config(machine, changes, profile)
    g = _si(grade, "grade")
    rng = None if unbalance is None else tuple(_si(u, "unbalance") for u in unbalance)
    ds = compute_design(cfg, grade=g, confidence=confidence, unbalance_range=rng,
                        n_unbalance=n_unbalance, starts=random, space=space, quick=quick,
                        seed=seed, store_dir=store, executor=executor, workers=workers,
                        scheduler=scheduler, progress=progress, refine_plateau=refine_plateau,
                        budget=budget)
    return StudyResult("design", cfg, ds, lambda: design_summary(ds),
                       lambda: plot_design(ds, f"{cfg.name}: designs for G{g:g} at "
                                               f"{100 * confidence:g} %"))
