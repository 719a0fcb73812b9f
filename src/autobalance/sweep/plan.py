"""Expand a SweepSpec into grid cells, Monte-Carlo samples and tasks (run by ``task.py``).

Runs are numbered r = cell * n_samples + sample (C order over the grid axes, sample fastest).
A task is a range of consecutive runs sharing the spin profile, the numerical options and the
ball count (so one ``simulate_batch`` call serves it with each run's own cell parameters), at
most ``batch_size`` long: tasks never mix two values of an ``options.*``, ``profile.*`` or
``balancer.n_balls`` grid axis. The one exception is a :class:`BranchTask`: grid cells that
differ only in their speed profile after a shared knot (a family, e.g. the plateau speeds of a
temporary speed reduction) run the same samples together, each sample's history up to the knot
integrated once (:func:`autobalance.simulate.simulate_branches`, bit for bit the separate runs).
Everything here is deterministic: the same description gives the same tasks and the same
results, and a run's result does not depend on the task it ran in.

``balancer.n_balls`` may be a grid axis (2 against 3 balls). The values that follow the ball
count follow it in every cell (:func:`_follow_n_balls`): per-ball values given as one number,
or as a list of equal values, are broadcast to N balls; start angles and speeds given for
another N are replaced by the default (N equispaced from pi/4, at rest); a Monte-Carlo
dimension draws its start angles for each N. The ``ball`` dimension then has max N entries
(NaN for the balls a cell does not have).
"""
from __future__ import annotations

import itertools
import math
import os
from dataclasses import dataclass

import numpy as np

from ..config import SECTIONS, ConfigError, _read, apply_overrides, from_dict, replace_values
from ..config.overrides import parse_override
from ..config.schema import check_value
from ..models import BallBalancer
from .spec import CELL_BYTES, SweepError, SweepSpec


@dataclass
class Plan:
    """Grid cells (configs), sample start angles and tasks of a sweep.

    ``angles`` maps each ball count N of the cells to the samples' start angles (n_samples, N)
    [rad]; one entry unless ``balancer.n_balls`` is a grid axis.
    """

    spec: SweepSpec
    cells: list              # Config per grid cell (C order)
    angles: dict             # N -> (n_samples, N) start angles [rad]
    tasks: list              # (first_run, n_runs) pairs and BranchTasks covering every run
    groups: tuple = ()       # (start, stop) run ranges of equal spin, options and N
    families: tuple = ()     # tuples of grid cells that may branch (:func:`_families`)

    def tasks_for(self, todo: np.ndarray, branch: bool = True) -> list:
        """Tasks covering the runs where ``todo`` is True (with every run todo:
        ``self.tasks``): :class:`BranchTask` s of at most about batch_size runs for the
        samples whose runs are todo in at least two cells of a family (``branch``), then
        (first, count) ranges of contiguous runs of one group, at most batch_size long."""
        todo = np.array(todo, bool)
        out = []
        S = self.n_samples
        for fam in self.families if branch else ():
            step = max(1, self.spec.batch_size // len(fam))
            for s0 in range(0, S, step):
                cnt = min(step, S - s0)
                members = tuple(c for c in fam if todo[c * S + s0:c * S + s0 + cnt].all())
                if len(members) >= 2:
                    out.append(BranchTask(members, s0, cnt))
                    for c in members:
                        todo[c * S + s0:c * S + s0 + cnt] = False
        return out + _chunk(self.groups, todo, self.spec.batch_size)

    @property
    def n_balls(self) -> int:
        """Size of the ``ball`` dimension: the largest ball count of the cells."""
        return max(self.angles)

    @property
    def start_angles(self) -> np.ndarray:
        """Start angles (n_samples, N) [rad] of the first cell's ball count N (of every cell
        unless ``balancer.n_balls`` is a grid axis; then see :meth:`cell_angles`)."""
        return self.angles[self.cells[0].system.balancer.n_balls]

    def cell_angles(self, cell: int) -> np.ndarray:
        """Start angles (n_samples, N) [rad] of the samples of grid cell ``cell`` (C order)."""
        return self.angles[self.cells[cell].system.balancer.n_balls]

    @property
    def n_samples(self) -> int:
        return next(iter(self.angles.values())).shape[0]

    @property
    def n_runs(self) -> int:
        return len(self.cells) * self.n_samples

    @property
    def checkpoints(self) -> np.ndarray:
        return np.asarray(self.cells[0].spin.checkpoints, float)


@dataclass(frozen=True)
class BranchTask:
    """The samples ``first`` .. ``first + count - 1`` of the grid cells ``cells``, whose runs
    share their history up to a speed-profile knot (a family, :func:`_families`): one
    :func:`autobalance.simulate.simulate_branches` call; its runs are stored as one task file per
    cell."""

    cells: tuple
    first: int
    count: int

    def ranges(self, n_samples: int) -> list:
        """(first run, count) of each cell's runs."""
        return [(c * n_samples + self.first, self.count) for c in self.cells]


def _families(cells: list) -> tuple:
    """Tuples (two or more) of the grid cells whose runs differ only in their speed profile
    after a shared knot (:func:`autobalance.simulate.run.branch_knot`): the same system, start
    state and options, prescribed profiles of one nominal speed, duration and checkpoints that
    agree up to a knot after t = 0. Ball balancers only."""
    from ..models import SpeedProfile
    from ..simulate.run import branch_knot

    fams = []
    for i, c in enumerate(cells):
        if not isinstance(c.spin, SpeedProfile) or c.system.liquid is not None:
            continue
        for fam in fams:
            r = cells[fam[0]]
            if (c.system == r.system and c.initial == r.initial and c.options == r.options
                    and c.spin.checkpoints == r.spin.checkpoints
                    and branch_knot([cells[j].spin for j in fam] + [c.spin]) > 0.0):
                fam.append(i)
                break
        else:
            fams.append([i])
    return tuple(tuple(f) for f in fams if len(f) > 1)


def start_grid(n: int, n_balls: int, identical: bool) -> np.ndarray:
    """004 sec. 4.2: n equispaced start positions per ball. For identical balls the
    configurations that differ only by swapping balls are removed (combinations with
    repetition: n (n + 1) / 2 = 1275 for n = 50 and two balls); otherwise the full product."""
    pos = 2 * np.pi * np.arange(n) / n
    if n_balls == 0:                             # one start: the rotor without balls
        return np.zeros((1, 0))
    combos = (itertools.combinations_with_replacement(range(n), n_balls) if identical
              else itertools.product(range(n), repeat=n_balls))
    return np.array([[pos[i] for i in c] for c in combos], float).reshape(-1, n_balls)


def _spread_on_line(x: np.ndarray, delta: float) -> np.ndarray:
    """Closest positions (least squares) to sorted x with gaps >= delta: pool-adjacent-
    violators on y_i = x_i - i delta (isotonic regression), then add i delta back."""
    y = x - delta * np.arange(x.size)
    blocks = []                                  # [mean, weight]
    for v in y:
        blocks.append([v, 1])
        while len(blocks) > 1 and blocks[-2][0] > blocks[-1][0]:
            m2, w2 = blocks.pop()
            m1, w1 = blocks.pop()
            blocks.append([(m1 * w1 + m2 * w2) / (w1 + w2), w1 + w2])
    z = np.concatenate([np.full(w, m) for m, w in blocks])
    return z + delta * np.arange(x.size)


def separate(angles: np.ndarray, delta: float) -> np.ndarray:
    """Move balls that start closer than the contact angle delta [rad] apart to at least delta
    (004's point masses may coincide; ours touch).

    Pairs are pushed symmetrically apart (keeping each pair's centroid), which settles in a
    few sweeps for small clusters. Larger clusters (many balls at one start position) are
    spread by the least-squares placement on the circle cut at its widest gap
    (:func:`_spread_on_line`); if that still overlaps across the cut, the balls keep their
    order and are spaced evenly (2 pi / N >= delta whenever they fit), centred on their mean.
    Works up to the race's capacity N delta <= 2 pi."""
    a = np.array(angles, float)
    n = a.size
    if n < 2 or delta <= 0:
        return a
    if n * delta > 2 * np.pi * (1 + 1e-12):
        raise SweepError(f"monte_carlo: {n} balls do not fit on the race (contact angle "
                         f"{np.degrees(delta):.4g} deg, at most {int(2 * np.pi / delta)} balls)")
    a0 = a.copy()
    for _ in range(200):
        order = np.argsort(np.mod(a, 2 * np.pi), kind="stable")
        moved = False
        for k in range(n):
            i, j = order[k], order[(k + 1) % n]
            gap = np.mod(a[j] - a[i], 2 * np.pi)
            if gap < delta * (1 - 1e-12):
                push = 0.5 * (delta - gap) * (1 + 1e-9)
                a[i] -= push
                a[j] += push
                moved = True
        if not moved:
            return a
    # large clusters: least-squares spreading on the circle cut at the widest gap
    w = np.mod(a0, 2 * np.pi)
    order = np.argsort(w, kind="stable")
    ws = w[order]
    gaps = np.diff(np.concatenate([ws, ws[:1] + 2 * np.pi]))
    cut = (int(np.argmax(gaps)) + 1) % n
    line = np.concatenate([ws[cut:], ws[:cut] + 2 * np.pi])
    d = delta * (1 + 1e-9)
    z = _spread_on_line(line, d)
    if z[-1] - z[0] > 2 * np.pi - d:             # overlaps across the cut: even spacing
        step = 2 * np.pi / n
        z = line.mean() - step * (n - 1) / 2 + step * np.arange(n)
    out = np.empty(n)
    out[np.roll(order, -cut)] = z
    # keep each ball's winding as given (only the offset from its start matters)
    return a0 + np.angle(np.exp(1j * (out - a0)))


#: Spacing [rad] that :func:`split_coincident` gives balls starting at one angle without a
#: contact model (docs/sweeps.md: the coincident state is an invariant set of the equations;
#: exactly on it the kernel never leaves it, while round-off would). 1e-9 rad is 0.3 nm on a
#: 0.3 m race: far below any tolerance, far above the angles' round-off (~1e-15 rad).
COINCIDENT_SPLIT = 1e-9


def split_coincident(angles: np.ndarray, eps: float = COINCIDENT_SPLIT) -> np.ndarray:
    """Balls without contact (``balancer.contact = "none"``, 004's points) that start at
    exactly the same angle, spread symmetrically about it by ``eps`` [rad] each.

    Two identical points at one angle with one velocity stay together forever in exact
    arithmetic: the coincident state is an invariant set of the equations of motion. Where it
    is unstable (e.g. a TSR plateau at 1.02 Omega_n) any real pair - and round-off in an
    implicit integrator - leaves it, but the stick kernel's arithmetic is symmetric bit for
    bit and does not. Where it is stable the spread decays and the outcome equals the
    coincident one (to ~eps).

    Parameters
    ----------
    angles : ndarray
        Start angles of one configuration [rad].
    eps : float
        Spacing of the spread balls [rad], > 0.

    Returns
    -------
    ndarray
        The angles, coincident ones (equal mod 2 pi to 1e-12 rad) spread; others unchanged.
    """
    a = np.array(angles, float)
    w = np.mod(a, 2 * np.pi)
    done = np.zeros(a.size, bool)
    for i in range(a.size):
        if done[i]:
            continue
        same = np.nonzero(np.abs(np.angle(np.exp(1j * (w - w[i])))) <= 1e-12)[0]
        done[same] = True
        if same.size > 1:
            a[same] += eps * (np.arange(same.size) - 0.5 * (same.size - 1))
    return a


def _chunk(groups, todo: np.ndarray, batch_size: int) -> list:
    tasks = []
    for g0, g1 in groups:
        r = g0
        while r < g1:
            if not todo[r]:
                r += 1
                continue
            stop = r + 1
            while stop < g1 and todo[stop] and stop - r < batch_size:
                stop += 1
            tasks.append((r, stop - r))
            r = stop
    return tasks


def identical_balls(balancer: BallBalancer) -> bool:
    """Whether swapping two balls changes nothing (equal per-ball values: mass, damping,
    rolling resistance, stiction): the start grid then keeps one of each permutation
    (:func:`start_grid`)."""
    return all(len(set(map(float, np.atleast_1d(getattr(balancer, f))))) <= 1 for f in _PER_BALL)


def n_start_grid(n: int, n_balls: int, identical: bool) -> int:
    """Number of start configurations of :func:`start_grid` (without building them)."""
    return math.comb(n + n_balls - 1, n_balls) if identical else n ** n_balls


#: Bytes per run of a sweep in memory (outputs, start angles, payload; measured order of
#: magnitude, conservative), before the per-checkpoint and per-ball terms.
_RUN_BYTES = 600
_CELL_BYTES = CELL_BYTES


def _guard_size(spec: SweepSpec, n_cells: int, n_samples: int, n_balls: int, n_cp: int,
                n_hist: int, cell0) -> None:
    """Refuse a sweep whose dataset or run time exceeds the limits (autobalance.limits),
    before the samples are built. Counts are Python ints of any size (a start grid of many
    balls); the estimates are capped below float overflow."""
    from ..limits import check_memory, check_runtime, step_cost, steps_estimate

    if spec.mc_kind == "start_grid":
        field, value = "monte_carlo.n", spec.mc_n
    elif spec.mc_kind == "random":
        field, value = "monte_carlo.samples", spec.mc_samples
    else:
        field, value = "grid", f"{n_cells} cells"
    if n_samples > 1 and n_cells > n_samples:
        field, value = "grid", f"{n_cells} cells x {n_samples} samples"
    runs = float(min(n_cells * n_samples, 10**300))
    per_run = _RUN_BYTES + 8 * (n_cp * (2 + n_balls) + 2 * n_balls)
    hist = 8.0 * 3 * n_hist
    where = ("outputs.history_dt", f"{spec.history_dt:g} s") if hist > per_run else (field, value)
    check_memory(*where, runs * (per_run + hist) + _CELL_BYTES * n_cells, "sweep")
    steps = steps_estimate(cell0.system, cell0.spin, cell0.options)
    workers = os.cpu_count() or 1
    check_runtime(field, value, runs * steps * step_cost(n_balls) / workers, "sweep")


def _n_history(spec: SweepSpec, spin) -> int:
    """Decimated history times of a run [-] (0 without ``outputs.history_dt``)."""
    if spec.history_dt <= 0:
        return 0
    return int(min(spin.duration / spec.history_dt, 1e18)) + 1


def _guard_early(spec: SweepSpec, n_cells: int, cell0) -> None:
    """:func:`_guard_size` from the first grid cell, before the other cells are built: the
    ball count is the largest of a ``balancer.n_balls`` axis, the balls are those of the
    first cell."""
    n_axis = next((a for a in spec.grid if a.path == "balancer.n_balls"), None)
    N = cell0.system.balancer.n_balls
    if n_axis is not None:
        N = max([N] + [int(v) for v in n_axis.values if isinstance(v, int)])
    if spec.mc_kind == "start_grid":
        n_samples = n_start_grid(spec.mc_n, N, identical_balls(cell0.system.balancer))
    else:
        n_samples = spec.mc_samples if spec.mc_kind == "random" else 1
    _guard_size(spec, n_cells, n_samples, N, len(cell0.spin.checkpoints),
                _n_history(spec, cell0.spin), cell0)


def _culprit(spec: SweepSpec, message: str, where: str) -> str:
    """Where a cell's error comes from: the grid point if the bad field is a grid axis, else
    ``sweep.set`` if an override set it, else the base config."""
    field = message.split(" ", 1)[0].split("[", 1)[0].rstrip(":")
    if any(a.path == field for a in spec.grid) or not field:
        return f"grid point {where or '(base)'}"
    if any(o.split("=", 1)[0].strip() == field for o in spec.overrides):
        return "sweep.set"
    return f"grid point {where}" if where else f"sweep.base {spec.base!r}"


def _refuse_mc_angles(spec: SweepSpec) -> None:
    """A Monte-Carlo kind sets every run's start angles: angles given beside it are refused."""
    if spec.mc_kind == "none":
        return
    given = [a.path for a in spec.grid] + [o.split("=", 1)[0].strip() for o in spec.overrides]
    if "initial.ball_angles" in given:
        where = "grid" if any(a.path == "initial.ball_angles" for a in spec.grid) else "sweep.set"
        raise SweepError(f"{where}: initial.ball_angles is set by monte_carlo.kind = "
                         f"{spec.mc_kind!r} (each sample's start angles); remove it, or use "
                         "kind = 'none' to run the given angles")


def _without_none(raw: dict, pairs) -> tuple[dict, list]:
    """(raw without the keys that ``pairs`` set to None, the other pairs): a file base's way of
    putting a key back to its default."""
    drop = [p for p, v in pairs if v is None]
    if not drop:
        return raw, list(pairs)
    raw = {k: dict(v) if isinstance(v, dict) else v for k, v in raw.items()}
    for path in drop:
        section, key = path.split(".", 1)
        if isinstance(raw.get(section), dict):
            raw[section].pop(key, None)
    return raw, [(p, v) for p, v in pairs if v is not None]


def _base_builder(spec: SweepSpec):
    """(build, given): ``build`` is a function (path, value) pairs -> Config: the base
    (preset, config file or a Config built in Python) with sweep.set and the pairs (a value
    None puts the key back to its default). ``given`` is the base's TOML dict with sweep.set,
    the keys as written. Without a Monte-Carlo dimension the base's start angles stay; with one
    they are dropped (they may be for another ball count)."""
    if spec.base_config is None:
        try:
            raw, label, _ = _read(spec.base_source)
        except ConfigError as e:
            raise SweepError(f"sweep.base: {e}") from None
        try:
            base_raw = apply_overrides(raw, list(spec.overrides))
        except ConfigError as e:
            raise SweepError(f"sweep.set: {e}") from None
        _refuse_mc_angles(spec)
        if spec.mc_kind != "none" and isinstance(base_raw.get("initial"), dict):
            base_raw["initial"].pop("ball_angles", None)

        def build(pairs):
            r, rest = _without_none(base_raw, pairs)
            return from_dict(apply_overrides(r, rest), source=label)
        return build, base_raw
    try:
        sets = [parse_override(o) for o in spec.overrides]
    except ConfigError as e:
        raise SweepError(f"sweep.set: {e}") from None
    _refuse_mc_angles(spec)
    base = spec.base_config
    if spec.mc_kind != "none":
        base = replace_values(base, {"initial.ball_angles": None})
    given = apply_overrides(base.raw if isinstance(base.raw, dict) else {}, sets)
    return (lambda pairs: replace_values(base, sets + list(pairs))), given


_PER_BALL = ("ball_mass", "damping", "rolling_resistance", "stiction")
#: The keys that follow a balancer.n_balls grid axis (:func:`_follow_n_balls`).
_FOLLOW = tuple(f"balancer.{k}" for k in _PER_BALL) + ("initial.ball_angles",
                                                        "initial.ball_speeds")


def _follow_n_balls(spec: SweepSpec, given: dict, n: int) -> list:
    """The (path, value) pairs that make a cell of ``n`` balls from the base ``given`` (its
    TOML dict with sweep.set) when ``balancer.n_balls`` is a grid axis.

    * A per-ball value (ball_mass, damping, rolling_resistance, stiction) given as a list of
      equal values is given as that one value (identical balls: broadcast to any N); a list of
      N values stays; a list of different values for another N is left to fail (one line
      naming the grid point and the key).
    * ``initial.ball_angles`` and ``initial.ball_speeds`` given for N balls are kept in the
      cells of N balls and put back to their defaults in the others (N equispaced from pi/4,
      at rest). A Monte-Carlo dimension sets the start angles itself.

    Keys that are grid axes themselves are left to the grid.
    """
    axes = {a.path for a in spec.grid}
    out = []
    bal = given.get("balancer") if isinstance(given.get("balancer"), dict) else {}
    for key in _PER_BALL:
        v = bal.get(key)
        path = f"balancer.{key}"
        if path in axes or not isinstance(v, list) or len(v) == n:
            continue
        try:
            si = [check_value(path, SECTIONS["balancer"][key], x) for x in v]
        except ConfigError:
            continue                                 # the cell reports it
        if v and len(set(si)) == 1:
            out.append((path, v[0]))
    init = given.get("initial") if isinstance(given.get("initial"), dict) else {}
    keys = ("ball_speeds",) if spec.mc_kind != "none" else ("ball_angles", "ball_speeds")
    for key in keys:
        v = init.get(key)
        path = f"initial.{key}"
        if path in axes or not isinstance(v, list):
            continue
        out.append((path, v if len(v) == n else None))
    return out


def _sample_angles(spec: SweepSpec, cell, identical: bool) -> np.ndarray:
    """The samples' start angles (n_samples, N) [rad] for the ball count N of ``cell``: the
    start grid, uniform random angles (the same generator call for every N: a cell of N balls
    gets the angles a sweep of N balls alone gets), or the cell's own start angles; balls
    closer than the contact angle moved apart (:func:`separate`); without contact, balls at
    one angle spread by :data:`COINCIDENT_SPLIT` (:func:`split_coincident`)."""
    b = cell.system.balancer
    n = b.n_balls
    if spec.mc_kind == "start_grid":
        angles = start_grid(spec.mc_n, n, identical)
    elif spec.mc_kind == "random":
        rng = np.random.default_rng(spec.seed)
        angles = rng.uniform(0.0, 2 * np.pi, size=(spec.mc_samples, n))
    else:
        angles = np.asarray(cell.initial.angles_for(b), float).reshape(1, n)
    if b.contact == "none":
        return np.array([split_coincident(a) for a in angles]).reshape(len(angles), n)
    return np.array([separate(a, b.contact_angle) for a in angles]).reshape(len(angles), n)


def make_plan(spec: SweepSpec) -> Plan:
    """Build the configs of every grid cell (validated like --set) and the samples.

    The base with sweep.set and the first cell's grid values is built once (from the preset or
    config file, or from the Config built in Python); every other cell is that config with its
    grid values set on the models (:func:`autobalance.config.replace_values`). A base that is
    valid only with the grid values (e.g. ``sweep.set`` gives a stiction that the grid's
    rolling resistances stay below) is therefore accepted, as each cell is. With a
    ``balancer.n_balls`` axis the values that follow the ball count are set with it
    (:func:`_follow_n_balls`) and the start angles are drawn per ball count.

    Parameters
    ----------
    spec : SweepSpec
        The description (``spec.base_config`` for a base built in Python).

    Returns
    -------
    Plan

    Raises
    ------
    SweepError
        A bad base, ``sweep.set`` or grid point, a start grid whose size differs between the
        ball counts of a ``balancer.n_balls`` axis, or a sweep over the limits (one line).
    """
    build, given = _base_builder(spec)
    n_cells = math.prod(len(a.values) for a in spec.grid)
    from ..limits import check_memory
    check_memory("grid", f"{n_cells} cells", _CELL_BYTES * n_cells, "sweep's grid")
    n_axis = next((k for k, a in enumerate(spec.grid) if a.path == "balancer.n_balls"), None)
    cells = []
    for combo in itertools.product(*[range(len(a.values)) for a in spec.grid]):
        pairs = [(a.path, a.values[i]) for a, i in zip(spec.grid, combo)]
        where = ", ".join(f"{a.path}={a.values[i]!r}" for a, i in zip(spec.grid, combo))
        if n_axis is not None and isinstance(pairs[n_axis][1], int) \
                and not isinstance(pairs[n_axis][1], bool):
            pairs += _follow_n_balls(spec, given, pairs[n_axis][1])
        try:
            cells.append(replace_values(cells[0], pairs) if cells else build(pairs))
            c = cells[-1]
            if c.system.liquid is not None:               # the film model's scope, up front
                from ..simulate.hybrid import check_liquid
                check_liquid(c.system, c.spin)
        except Exception as e:   # ConfigError / ParameterError / ResourceError
            field = str(e).split(" ", 1)[0].split("[", 1)[0].rstrip(":")
            culprit = (f"grid point {where}" if n_axis is not None and field in _FOLLOW
                       else _culprit(spec, str(e), where))
            raise SweepError(f"{culprit}: {e}") from None
        if len(cells) == 1:
            _guard_early(spec, n_cells, cells[0])     # before the other cells are built
    if cells[0].system.liquid is not None and not cells[0].system.balancer.n_balls \
            and spec.mc_kind != "none":
        raise SweepError(f"monte_carlo.kind = {spec.mc_kind!r}: a liquid balancer has no ball "
                         "start positions to sample; leave out [monte_carlo]")
    first = {}                                   # N -> its first cell
    for c in cells:
        first.setdefault(c.system.balancer.n_balls, c)
    identical = {n: identical_balls(c.system.balancer) for n, c in first.items()}
    if spec.mc_kind == "start_grid":
        counts = {n: n_start_grid(spec.mc_n, n, identical[n]) for n in first}
        if len(set(counts.values())) > 1:
            shown = ", ".join(f"{k} for {n} balls" for n, k in sorted(counts.items()))
            raise SweepError(f"monte_carlo.kind = 'start_grid' with grid balancer.n_balls: "
                             f"n = {spec.mc_n} gives {shown}, and one sample dimension needs "
                             "one count; use kind = 'random' (the same number of random starts "
                             "for every ball count) or one sweep per ball count")
    N = max(first)
    n_samples = (n_start_grid(spec.mc_n, N, identical[N]) if spec.mc_kind == "start_grid"
                 else spec.mc_samples if spec.mc_kind == "random" else 1)
    n_hist = _n_history(spec, cells[0].spin)
    _guard_size(spec, len(cells), n_samples, N, len(cells[0].spin.checkpoints), n_hist, cells[0])
    angles = {n: _sample_angles(spec, c, identical[n]) for n, c in first.items()}
    # groups of consecutive runs with the same spin, options and N; tasks at most batch_size
    n_runs = len(cells) * n_samples

    def key(c):
        return c.spin, c.options, c.system.balancer.n_balls

    bounds = [0] + [c * n_samples for c in range(1, len(cells))
                    if key(cells[c]) != key(cells[c - 1])]
    groups = tuple(zip(bounds, bounds[1:] + [n_runs]))
    plan = Plan(spec, cells, angles, [], groups, _families(cells))
    plan.tasks = plan.tasks_for(np.ones(n_runs, bool))
    return plan
