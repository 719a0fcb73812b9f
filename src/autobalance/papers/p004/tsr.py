"""Seed 004 (temporary speed reduction, TSR): single run, start-position Monte Carlo,
initial-unbalance sweep, speed profiles, immobility, the gradual descent and the lower-plateau
map, against the paper.

Each study has ``compute_<study>(...)`` returning an :class:`xarray.Dataset` (SI, with units in
attrs), its published numbers in :data:`PUBLISHED` and ``compare_<study>(ds)`` returning rows
``{quantity, published, computed, tolerance, ok, note}``. :data:`STUDIES` maps the CLI names to
them. A published number that we do not reproduce is a row with ``ok = False`` and a note; a
published number whose study was not computed in this variant is a row with ``computed = None``,
``ok = False`` and the note "not computed".

Profile (004 Fig. 3 is given only as a figure; docs/model.md sec. 5, the ``vub_jeffcott_004``
preset): linear run-up 0 -> 167 Hz in 18 s (STD read-out at 18 s = 20 %), linear ramp to the
100 Hz plateau over 18-28 s, plateau 28-48 s, linear back to 167 Hz over 48-58 s, hold to 90 s
(TSR read-out). Exact Coulomb stick-slip (mu_s = mu), point-mass balls, no gravity (004 sec. 3.1).

Grades: G = |U_res| / M_t * Omega_nom [mm/s] (ISO 1940-1, 004 sec. 4). The initial unbalance
G_ini is the rotor's own unbalance (without balls); the preset's 0.319 g m is G20.25 (004: G20).
"""
from __future__ import annotations

import math
import tempfile
import time
from pathlib import Path

import numpy as np

from ...validation.target import not_computed, row

__all__ = ["PUBLISHED", "STUDIES", "UNBALANCE_CASES", "PLATEAU_CASES", "compare_immobility",
           "compare_monte_carlo", "compare_plateau", "compare_profile", "compare_single",
           "compare_unbalance", "compare_descent", "compute_descent", "compute_immobility",
           "compute_monte_carlo", "compute_plateau",
           "compute_profile", "compute_single", "start_family", "compute_unbalance", "grade_to_unbalance",
           "check_immobility", "immobility", "immobile_mask", "kernel_required_friction", "plateau_speed",
           "regions", "steady_deflection", "stick_threshold_grade", "tangential_force",
           "valid_ranges"]

PRESET = "vub_jeffcott_004"
G_LIMIT = 16.0          # 004 sec. 4: the rotor must qualify G16
G_SPAN = 50.0           # 004 Tables 3-4: efficiency = valid range / [G0, G50]
G_TSR_RANGE = 34.0      # 004 sec. 4.6: ideal plateau averaged over G_ini <= G34
REGIONS = ("I.A", "I.B", "II", "III", "IV")   # 004 Table 2

#: (mu_r, c_r) of the initial-unbalance cases of 004 Tables 3-4.
UNBALANCE_CASES = {"nominal": (1.0, 1.0), "mu0.5": (0.5, 1.0), "mu0.25": (0.25, 1.0),
                   "c0.6": (1.0, 0.6), "c0.5": (1.0, 0.5)}
#: (mu_r, c_r) of the plateau maps of 004 Fig. 14 and 15.
PLATEAU_CASES = {"nominal": (1.0, 1.0), "c0.5": (1.0, 0.5)}

PUBLISHED = {
    "table1": {"f_n_hz": 94.2, "G_ini": 20.0, "G_balls": 34.0,
               "source": "004 Table 1 (M = 16.53 kg, k = 5.8 kN/mm, eps = 19.3 um, m = 7.6 g, "
                         "R = 35 mm) and sec. 4: resonance 94.2 Hz, G20 rotor, G34 balls"},
    "single": {"G_ini": 20.0, "G_start": 14.0, "G_peak_runup": 38.0, "G_STD": 19.0, "G_TSR": 5.0,
               "run_exists": "a G14 start reproduces the whole run",
               "source": "004 sec. 4.1, Fig. 4: G14 -> G38 -> G19 (STD), G5 after TSR"},
    "monte_carlo": {"mode_STD": 15.0, "mode_TSR": 11.0,
                    "share_G16_STD": 0.85, "share_G16_TSR": 0.80,
                    "success_STD": 0.95, "success_TSR": 0.98,
                    "regions": {"I.A": 0.260, "I.B": 0.675, "II": 0.045, "III": 0.005, "IV": 0.015},
                    "runs": 1275,
                    "source": "004 sec. 4.2, Fig. 5-6, Table 2 (G_ini = G20, 50 x 50 starts)"},
    # case: {STD: {ranges, efficiency}, TSR: ...}; ranges in G [mm/s]
    "unbalance": {
        "nominal": {"STD": {"ranges": [], "efficiency": 0.0},
                    "TSR": {"ranges": [(0, 3), (19, 34)], "efficiency": 0.36}},
        "mu0.5": {"STD": {"ranges": [(21, 43)], "efficiency": 0.44},
                  "TSR": {"ranges": [(0, 17), (21, 44)], "efficiency": 0.80}},
        "mu0.25": {"STD": {"ranges": [(0, 14), (23, 47)], "efficiency": 0.76},
                   "TSR": {"ranges": [(0, 47)], "efficiency": 0.94}},
        "c0.6": {"STD": {"ranges": [(20, 41)], "efficiency": 0.42},
                 "TSR": {"ranges": [(0, 10), (20, 42)], "efficiency": 0.64}},
        "c0.5": {"STD": {"ranges": [(21, 43)], "efficiency": 0.44},
                 "TSR": {"ranges": [(0, 9), (21, 43)], "efficiency": 0.62}},
        "source": "004 sec. 4.3-4.5, Fig. 7, 11, 12, Tables 3-4 (G16, efficiency over [G0, G50])"},
    "profile": {"slow_worse_range": (10.0, 21.0), "slow_better_elsewhere": "< 0",
                "tsr_better": "< 0",
                "source": "004 sec. 4.4, Fig. 9: 3x slower run-up vs STD and TSR (95 % isolines)"},
    "immobility": {"valley_at_resonance": "near resonance (~1)",
                   "nominal_above_plateau": "higher at nominal",
                   "monotone_mu": "more stiction, more immobility",
                   "monotone_c": "more damping, more immobility",
                   "source": "004 sec. 4.4-4.5, Fig. 8 and 10 (G_ini = G20); the figures give "
                             "no numbers, the rows check the text's statements"},
    "descent": {"prompt_reduction": 1.1, "worse_near_resonance": "some outcomes deteriorate",
                "source": "004 sec. 4.6, Fig. 13: G5, mu_r = c_r = 1, gradual speed reduction "
                          "from nominal to 0.9 Omega_n: 'a prompt unbalance reduction near "
                          "Omega = 1.1 Omega_n. Unstable working occurs when nearing resonance "
                          "which deteriorates some of the balancing outcomes.'"},
    "plateau": {"ideal": {"nominal": 1.02, "c0.5": 1.03}, "standard": 1.06,
                "source": "004 sec. 4.6, Fig. 14-15: ideal lower plateau / Omega_n; the "
                          "standard plateau 100 Hz / 94.2 Hz = 1.06"},
}


# -- small helpers -----------------------------------------------------------------------------
def _row(key, quantity, published, computed, tolerance, ok, note=""):
    return row(key, quantity, published, computed, tolerance, ok, note)


def _missing(key, quantity, published, why="not computed in this variant (run the case / --full)"):
    return not_computed(key, quantity, published, why)


def _cfg(overrides=()):
    from ...config import load_config

    return load_config(PRESET, list(overrides))


def _case_sets(mu_r: float, c_r: float) -> list:
    """Overrides scaling 004 Table 1's mu_ref = 0.002 and c_ref = 1.510 kN s/m (sec. 4.5)."""
    base = _cfg().system
    return [f"balancer.rolling_resistance={0.002 * mu_r!r}",
            f"suspension.cx={base.suspension.cx * c_r!r}",
            f"suspension.cy={base.suspension.cy * c_r!r}"]


def grade_to_unbalance(G, total_mass: float, nominal_speed: float):
    """Unbalance U [kg m] of ISO 1940-1 grade G [mm/s]: U = G M_t / (1e3 Omega_nom) (004 sec. 4)."""
    return np.asarray(G, float) * total_mass / (1e3 * nominal_speed)


def _grade(U, total_mass: float, nominal_speed: float):
    """ISO 1940-1 grade [mm/s] of an unbalance U [kg m] (004 sec. 4)."""
    return np.asarray(U, float) / total_mass * 1e3 * nominal_speed


def _run_sweep(name, sets, grid, n, *, store=None, executor="local", workers=None,
               history_dt: float = 0.0, scheduler=None):
    """Run an autobalance.sweep start-grid Monte Carlo (004 sec. 4.2) and return its Dataset.

    ``store``: a directory (reused with resume: same description -> nothing rerun) or None for
    a temporary one."""
    from ...sweep import spec_from_dict, sweep

    n_cells = int(np.prod([len(v) for v in grid.values()])) if grid else 1
    n_runs = n_cells * n * (n + 1) // 2
    w = workers or 2
    bs = max(1, min(64, math.ceil(n_runs / (4 * w))))
    spec = spec_from_dict({"sweep": {"name": name, "base": PRESET, "set": list(sets),
                                     "batch_size": bs},
                           "grid": grid, "monte_carlo": {"kind": "start_grid", "n": int(n)},
                           **({"outputs": {"history_dt": float(history_dt)}} if history_dt else {})})
    if store is None:
        with tempfile.TemporaryDirectory() as d:
            return sweep(spec, Path(d) / name, executor=executor, workers=workers,
                         scheduler=scheduler, progress=False).load()
    return sweep(spec, Path(store), executor=executor, workers=workers, resume=True,
                 scheduler=scheduler, progress=False).load()


def _store(store_dir, name):
    return None if store_dir is None else Path(store_dir) / name


# -- physics: immobility in closed form ---------------------------------------------------------
def steady_deflection(system, speed, alpha):
    """Rotor-frame deflection w = u + i v [m] on the steady orbit with the balls at rest.

    Jeffcott rotor at constant speed (004 eq 8-9 with all time derivatives zero in the rotor
    frame; textbook synchronous response): w = Omega^2 U_t / (k - M_t Omega^2 + i c Omega),
    U_t = U + sum m_i R e^{i alpha_i}. Same as :func:`autobalance.core.pack.steady_orbit_start`
    (isotropic suspension).

    Parameters
    ----------
    system : System
        Isotropic suspension (k, c), rotor unbalance U [kg m], balls m_i [kg] at radius R [m].
    speed : array_like
        Spin speed Omega [rad/s]; broadcast against ``alpha[..., 0]``.
    alpha : array_like (..., N)
        Ball angles from the unbalance [rad].

    Returns
    -------
    ndarray of complex
        w [m], shape broadcast(speed, alpha[..., 0]).
    """
    s, b = system.suspension, system.balancer
    if s.kx != s.ky or s.cx != s.cy:
        raise ValueError("steady_deflection: needs an isotropic (Jeffcott) suspension")
    a = np.asarray(alpha, float)
    ut = system.rotor.unbalance + np.sum(b.masses * b.race_radius * np.exp(1j * a), axis=-1)
    w = np.asarray(speed, float)
    return w * w * ut / (s.kx - system.total_mass * w * w + 1j * s.cx * w)


def tangential_force(system, speed, alpha):
    """Tangential vibratory force on each ball at rest [N], 004 eq (1): F_t = m z Omega^2 sin(gamma).

    z e^{i gamma} = w e^{-i alpha_i} is the deflection seen from ball i (gamma measured from the
    ball to the deflection); positive F_t drives the ball towards +alpha. Equivalently the ball
    row of 004 eq (10) with phi_dot = phi_ddot = 0, psi_ddot = 0 and the rotor on its steady
    orbit: F_t R = m R Omega^2 (v cos alpha - u sin alpha).

    Returns
    -------
    ndarray (..., N)
        F_t [N].
    """
    a = np.asarray(alpha, float)
    w = np.asarray(steady_deflection(system, speed, a))
    W = np.asarray(speed, float)
    m = system.balancer.masses
    return m * (W * W)[..., None] * np.imag(w[..., None] * np.exp(-1j * a))


def immobile_mask(system, speed, alpha):
    """True where every ball at rest stays stuck: |F_t| <= mu_s N with N = m R Omega^2 (004 eq 1
    against Coulomb friction mu F_n, 004 sec. 3.1; normal force of a ball at rest on the race).

    Omega cancels: ball i sticks iff |Im(w e^{-i alpha_i})| <= mu_s R. Shape of ``speed`` broadcast
    with ``alpha[..., 0]``.
    """
    a = np.asarray(alpha, float)
    w = np.asarray(steady_deflection(system, speed, a))
    mus = np.asarray(system.balancer.stiction, float)
    R = system.balancer.race_radius
    return np.all(np.abs(np.imag(w[..., None] * np.exp(-1j * a))) <= mus * R, axis=-1)


#: Peak memory of :func:`immobility` per ball configuration and ball [B] (the meshgrid, the
#: stacked angles and the complex temporaries of :func:`immobile_mask`), plus per configuration.
IMMOBILITY_BYTES_PER_BALL = 64
IMMOBILITY_BYTES = 64
#: Measured time of :func:`immobility` per configuration, ball and speed [s] (0.25 us at N = 2).
IMMOBILITY_COST_S = 0.15e-6


def check_immobility(n_conf, n_balls: int, n_speeds: int = 1, n_sets: int = 1,
                     field: str = "n_conf") -> None:
    """Refuse (ResourceError naming ``field``) an immobility grid of ``n_conf`` ** ``n_balls``
    configurations [-] whose memory or run time over ``n_speeds`` x ``n_sets`` evaluations
    exceeds the limits of :mod:`autobalance.limits`, before anything is allocated."""
    from ...limits import check_memory, check_runtime

    k = float(n_conf) ** max(int(n_balls), 1)          # float: no huge-int arithmetic
    check_memory(field, n_conf, k * (IMMOBILITY_BYTES_PER_BALL * n_balls + IMMOBILITY_BYTES),
                 f"grid of {k:.3g} ball configurations")
    check_runtime(field, n_conf, k * n_balls * n_speeds * n_sets * IMMOBILITY_COST_S,
                  f"immobility grid ({k:.3g} configurations x {n_speeds * n_sets} speeds)")


def immobility(system, speeds, n_conf: int = 100):
    """004 sec. 4.4 immobility: share [-] of ball configurations (n_conf equispaced positions per
    ball, full product = uniform on the torus) in which no ball can move, at each speed [rad/s].

    Closed form (:func:`immobile_mask`), vectorised; no time integration. A grid beyond the
    memory or run-time limit is refused first (:func:`check_immobility`)."""
    b = system.balancer
    check_immobility(n_conf, b.n_balls, np.atleast_1d(speeds).size)
    pos = 2 * np.pi * np.arange(n_conf) / n_conf
    grids = np.meshgrid(*([pos] * b.n_balls), indexing="ij")
    alpha = np.stack([g.ravel() for g in grids], axis=-1)           # (K, N)
    out = np.empty(len(np.atleast_1d(speeds)))
    for j, w in enumerate(np.atleast_1d(speeds)):
        out[j] = immobile_mask(system, float(w), alpha).mean()
    return out


def stick_threshold_grade(system, speed, nominal_speed):
    """Residual grade G* [mm/s] below which every ball configuration at rest is immobile.

    From :func:`immobile_mask` (004 eq 1 against mu_s m R Omega^2): ball i sticks iff
    |Im(w e^{-i alpha_i})| <= mu_s R, and on the steady orbit |w| = A e with the residual
    eccentricity e = |U_t| / M_t [m] and the Jeffcott amplification A = M_t Omega^2 /
    |k - M_t Omega^2 + i c Omega| (textbook synchronous response,
    :func:`autobalance.physics.axis_response` per unit eccentricity).
    So every configuration sticks when A e <= mu_s R, i.e. below
    G* = 1e3 Omega_nom mu_s R / A  (ISO 1940 grade at Omega_nom, 004 sec. 4).
    Above G* only configurations whose balls lie nearly along w can stay at rest, so balls that
    relocate at speed Omega stop near G*.

    Parameters
    ----------
    system : System
        Isotropic suspension k [N/m], c [N s/m]; total mass M_t [kg]; race radius R [m]; the
        balls' static friction mu_s [-] (the largest, if they differ).
    speed : array_like
        Spin speed Omega [rad/s].
    nominal_speed : float
        Omega_nom [rad/s] of the grade.

    Returns
    -------
    ndarray
        G* [mm/s], shape of ``speed``.
    """
    from ...physics import axis_response

    s, b = system.suspension, system.balancer
    if s.kx != s.ky or s.cx != s.cy:
        raise ValueError("stick_threshold_grade: needs an isotropic (Jeffcott) suspension")
    mt = system.total_mass
    amp, _ = axis_response(mt, s.kx, s.cx, mt, speed)      # |w| per metre of eccentricity
    return 1e3 * nominal_speed * float(np.max(b.stiction)) * b.race_radius / amp


def plateau_speed(spin) -> float:
    """Lowest speed [rad/s] of a profile after its first read-out: the TSR plateau (Fig. 3)."""
    return min(w for t, w in zip(spin.times, spin.speeds) if t > spin.checkpoints[0])


def kernel_required_friction(system, speed, alpha):
    """Friction torque [N m] each stuck ball needs and its static limit mu_s N R [N m], from the
    compiled kernel (core/rhs.py, exact stick-slip branch) with both balls stuck, the rotor on its
    steady orbit (core/pack.steady_orbit_start) at constant speed. Also returns the rotor-frame
    accelerations (u'', v'') [m/s^2], zero on the steady orbit. Used to check the closed form."""
    from ...core.layout import P_FLAW
    from ...core.pack import pack_params, spin_arrays, steady_orbit_start
    from ...core.rhs import profile_segment, rhs
    from ...models import SimOptions, SpeedProfile

    spin = SpeedProfile.constant(float(speed), 1.0)
    P, B = pack_params(system, spin, SimOptions(friction_law="stick"))
    P[P_FLAW] = 0.0
    N = system.balancer.n_balls
    nq = N + 3
    a = np.asarray(alpha, float)
    x, y, vx, vy = steady_orbit_start(system, float(speed), a)
    order = np.argsort(np.mod(a, 2 * np.pi))
    st = np.zeros(2 * nq)
    st[0], st[1] = x, y                         # psi = 0: rotor frame = inertial frame
    st[nq], st[nq + 1] = vx + speed * y, vy - speed * x
    st[2:2 + N] = np.mod(a[order], 2 * np.pi)
    st[2 * nq - 1] = speed
    prof_t, prof_w, _ = spin_arrays(spin)
    unb_t, unb_u = system.rotor.unbalance_table()
    dy, lam = np.zeros(2 * nq), np.zeros(3 * N + 1)
    Mm, A = np.zeros((nq, nq)), np.zeros((nq, nq))
    fv, bb, idx = np.zeros(nq), np.zeros(nq), np.zeros(nq, dtype=np.int64)
    rhs(0.0, st, P, B, N, profile_segment(0.0, prof_t), prof_t, prof_w, unb_t, unb_u,
        np.ones(N, dtype=np.int64), np.ones(N), np.array([0.0, 0.0]), dy, lam, Mm, fv, A, bb, idx)
    inv = np.argsort(order)
    return lam[:N][inv], lam[N:2 * N][inv], dy[nq:nq + 2]


# -- statistics ---------------------------------------------------------------------------------
def regions(g_std, g_tsr, g_ini):
    """004 Table 2 regions: shares [-] of I.A, I.B, II, III, IV (every run in exactly one).

    I.A G_STD < G_TSR <= G_INI; I.B G_TSR <= G_STD <= G_INI; II G_TSR < G_INI < G_STD;
    III G_INI < G_STD and G_INI < G_TSR; IV G_STD <= G_INI < G_TSR.
    """
    s, t, i = np.asarray(g_std), np.asarray(g_tsr), float(g_ini)
    m = {"I.A": (s < t) & (t <= i), "I.B": (t <= s) & (s <= i), "II": (t < i) & (i < s),
         "III": (i < s) & (i < t), "IV": (s <= i) & (i < t)}
    return {k: float(v.mean()) for k, v in m.items()}


def _mode(g, width=1.0, n_boot=200, seed=0):
    """Mode of a sample [mm/s] (centre of the fullest 1 mm/s bin, 004 Fig. 5 reads integer G) and
    its bootstrap standard error [mm/s]."""
    g = np.asarray(g, float)
    g = g[np.isfinite(g)]
    edges = np.arange(0.0, max(g.max(), 1.0) + 2 * width, width)

    def mode(x):
        h, _ = np.histogram(x, edges)
        return edges[np.argmax(h)] + width / 2

    rng = np.random.default_rng(seed)
    boots = [mode(rng.choice(g, g.size)) for _ in range(n_boot)]
    return float(mode(g)), float(np.std(boots))


def valid_ranges(G_ini, p95, limit=G_LIMIT, span=G_SPAN):
    """Valid initial-unbalance ranges (004 sec. 4.3): where the 95th percentile of the residual
    grade is <= limit. Boundaries by linear interpolation between grid points.

    Returns (ranges [(lo, hi)] in G [mm/s], efficiency = total length / span [-])."""
    x = np.asarray(G_ini, float)
    f = np.asarray(p95, float) - limit
    ok = f <= 0
    ranges = []
    start = x[0] if ok[0] else None
    for k in range(1, x.size):
        if ok[k] and not ok[k - 1]:
            start = x[k - 1] + (x[k] - x[k - 1]) * f[k - 1] / (f[k - 1] - f[k])
        if not ok[k] and ok[k - 1]:
            end = x[k - 1] + (x[k] - x[k - 1]) * f[k - 1] / (f[k - 1] - f[k])
            ranges.append((float(start), float(end)))
            start = None
    if start is not None:
        ranges.append((float(start), float(x[-1])))
    # an isolated valid grid point is a range of zero length: keep it (it has a boundary)
    eff = sum(hi - lo for lo, hi in ranges) / span
    return ranges, float(eff)


def _fmt_ranges(r):
    return "/" if not r else ", ".join(f"[G{lo:.0f}-G{hi:.0f}]" for lo, hi in r)


# -- 1. single run (Fig. 4) --------------------------------------------------------------------
def start_family(G_start: float, system, nominal_speed: float, n: int = 24) -> np.ndarray:
    """Ball start angles (n, 2) [rad] with the grade G_start [mm/s] at rest: ball 1 at
    alpha_1 = 2 pi k / n, ball 2 on |U + m R (e^{i alpha_1} + e^{i alpha_2})| = U(G_start)
    (law of cosines; the branch with alpha_2 - arg c > 0). Rows without a solution or with
    touching balls (closer than the contact angle) are dropped."""
    U = system.rotor.unbalance
    Ug = float(grade_to_unbalance(G_start, system.total_mass, nominal_speed))
    mR = system.balancer.masses[0] * system.balancer.race_radius
    out = []
    for a1 in 2 * np.pi * np.arange(n) / n:
        c = U + mR * np.exp(1j * a1)
        x = (Ug**2 - abs(c) ** 2 - mR**2) / (2 * mR * abs(c))
        if abs(x) <= 1:
            a2 = float(np.angle(c) + math.acos(x))
            gap = abs(np.angle(np.exp(1j * (a2 - a1))))
            if gap >= system.balancer.contact_angle:
                out.append((a1, a2))
    return np.array(out)


def compute_single(save_dt: float = 0.01, G_start: float | None = 14.0, n_family: int = 24):
    """004 Fig. 4: one TSR run with the balancer and the same run without it, plus the family
    of starts with the same initial grade.

    The paper's start angles are unknown. We run the profile from ``n_family`` starts with the
    paper's initial grade G_start = G14 (:func:`start_family`; ball 1 every 360/n_family deg) and
    plot the first of them (lowest ball-1 angle with a solution: 75/198 deg; chosen before
    looking at the results; ``G_start=None``:
    the preset's 45/135 deg, no family). Rotor at rest at t = 0. attrs report how many of the
    family reproduce the paper's statements about its run."""
    import dataclasses

    import xarray as xr

    from ...models import InitialState
    from ...simulate import simulate, simulate_batch

    t0 = time.perf_counter()
    cfg = _cfg()
    sysm, spin = cfg.system, cfg.spin
    wn = spin.nominal_speed
    fam = None if G_start is None else start_family(G_start, sysm, wn, n_family or 24)
    ang = cfg.initial.ball_angles if fam is None else fam[0]
    opts = dataclasses.replace(cfg.options, save_dt=save_dt)
    sim = simulate(sysm, spin, initial=InitialState(ball_angles=tuple(ang)), options=opts)
    bare = dataclasses.replace(sysm, balancer=dataclasses.replace(sysm.balancer, n_balls=0))
    sim0 = simulate(bare, spin, initial=InitialState(ball_angles=()), options=opts)
    g_ini = float(_grade(sysm.rotor.unbalance, sysm.total_mass, wn))
    cps = np.asarray(spin.checkpoints)
    ds = xr.Dataset(
        {"speed": ("time", sim.speed, {"units": "rad/s"}),
         "amplitude": ("time", sim.amplitude, {"units": "m", "long_name": "with balancer"}),
         "amplitude_no_balancer": ("time", np.interp(sim.t, sim0.t, sim0.amplitude),
                                   {"units": "m", "long_name": "without balancer"}),
         "ball_angle": (("time", "ball"), np.angle(np.exp(1j * sim.alpha)), {"units": "rad"}),
         "grade_G": ("time", sim.grade_G, {"units": "mm/s"}),
         "cog_angle": ("time", sim.residual_angle, {"units": "rad",
                                                     "long_name": "direction of the residual unbalance"})},
        coords={"time": ("time", sim.t, {"units": "s"}), "ball": np.arange(2)})
    k_std = int(np.argmin(np.abs(sim.t - cps[0])))
    attrs = {
        "study": "single", "G_ini": g_ini, "G_start": float(sim.grade_G[0]),
        "G_peak_runup": float(sim.grade_G[:k_std + 1].max()),
        "G_STD": float(sim.grade_G[k_std]), "G_TSR": float(sim.grade_G[-1]),
        "start_angles_deg": [float(x) for x in np.degrees(ang)], "t_std_s": float(cps[0]),
        "t_tsr_s": float(cps[-1]), "status": sim.status, "profile": _profile_text(spin)}
    if fam is not None and n_family:
        tt = np.unique(np.concatenate([np.arange(0.0, cps[0], 0.02), cps]))
        res = simulate_batch([sysm] * len(fam), spin,
                             [InitialState(ball_angles=tuple(a)) for a in fam], options=opts,
                             out_times=tt)
        G = res.grade_G
        ks = int(np.argmin(np.abs(tt - cps[0])))
        peak, gs, gt = G[:, :ks + 1].max(axis=1), G[:, ks], G[:, -1]
        match = (peak > g_ini) & (gs > G_LIMIT) & (gs <= g_ini) & (gt <= G_LIMIT) & (gt < gs)
        ds["family_start_angle"] = (("family", "ball"), fam, {"units": "rad"})
        ds["family_G_peak_runup"] = ("family", peak, {"units": "mm/s"})
        ds["family_G_STD"] = ("family", gs, {"units": "mm/s"})
        ds["family_G_TSR"] = ("family", gt, {"units": "mm/s"})
        ds["family_match"] = ("family", match.astype(np.int8))
        attrs.update({"family_n": int(len(fam)), "family_match": int(match.sum()),
                      "family_peak_gt_ini": int((peak > g_ini).sum()),
                      "family_std_in_16_ini": int(((gs > G_LIMIT) & (gs <= g_ini)).sum()),
                      "family_tsr_le_16": int((gt <= G_LIMIT).sum())})
    attrs["wall_s"] = time.perf_counter() - t0
    ds.attrs.update(attrs)
    return ds


def _profile_text(spin) -> str:
    return "; ".join(f"{t:g} s: {w / (2 * np.pi):.1f} Hz" for t, w in zip(spin.times, spin.speeds))


def compare_single(ds=None) -> list:
    ds = ds if ds is not None else compute_single()
    a, p = ds.attrs, PUBLISHED["single"]
    one = ("our run: balls at %.1f/%.1f deg (a G14 start, our choice); 004 gives neither its "
           "start angles nor the exact profile, so the row checks the paper's statement about "
           "its run, not the number" % tuple(a["start_angles_deg"]))
    fam = (f"; of {a['family_n']} G14 starts: " if "family_n" in a else "")
    rows = [
        _row("single/G_ini", "004 Fig. 4 G_ini (rotor alone) [mm/s]", p["G_ini"], round(a["G_ini"], 2), "+-0.5",
             abs(a["G_ini"] - p["G_ini"]) <= 0.5, "deterministic: U/M_t*Omega_nom; paper rounds"),
        _row("single/G_start", "004 Fig. 4 G at start [mm/s]", p["G_start"], round(a["G_start"], 2), "+-0.1",
             abs(a["G_start"] - p["G_start"]) <= 0.1, "by construction of the start"),
        _row("single/G_peak_runup", "004 Fig. 4 peak G during the run-up [mm/s]", p["G_peak_runup"],
             round(a["G_peak_runup"], 2), f"> G_ini = {a['G_ini']:.1f} (balls slung near resonance)",
             a["G_peak_runup"] > a["G_ini"],
             one + (fam + f"{a['family_peak_gt_ini']} exceed G_ini" if fam else "")),
        _row("single/G_STD", "004 Fig. 4 G_STD at 18 s [mm/s]", p["G_STD"], round(a["G_STD"], 2),
             f"in (16, {a['G_ini']:.1f}]: below G_ini, above G16 (sec. 4.1)",
             G_LIMIT < a["G_STD"] <= a["G_ini"],
             one + (fam + f"{a['family_std_in_16_ini']} in (16, G_ini]" if fam else "")),
        _row("single/G_TSR", "004 Fig. 4 G_TSR at 90 s [mm/s]", p["G_TSR"], round(a["G_TSR"], 2),
             "<= 16 and < G_STD (TSR qualifies G16)",
             a["G_TSR"] <= G_LIMIT and a["G_TSR"] < a["G_STD"],
             one + (fam + f"{a['family_tsr_le_16']} <= G16" if fam else "")),
    ]
    if "family_n" in a:
        rows.append(_row("single/run_exists", "004 Fig. 4 a G14 start reproducing the whole run (peak > G_ini, "
                         "16 < G_STD <= G_ini, G_TSR <= 16)", "the paper's run exists",
                         f"{a['family_match']}/{a['family_n']} starts", ">= 1", a["family_match"] >= 1,
                         "starts with G14 at rest: ball 1 every 15 deg, ball 2 by the law of cosines"))
    return rows


# -- 2. start-position Monte Carlo (Fig. 5-6, Table 2) ------------------------------------------
def compute_monte_carlo(n: int = 50, *, plateau_ratio: float | None = None, store_dir=None,
                        executor="local", workers=None, scheduler=None):
    """004 sec. 4.2: n x n equispaced start positions, identical balls -> n(n+1)/2 runs
    (1275 for n = 50), G at the STD (18 s) and TSR (90 s) read-outs.

    ``plateau_ratio``: run with the TSR plateau at this multiple of Omega_n = sqrt(k/M_t)
    instead of the preset's 100 Hz (a sensitivity study; None = the preset)."""
    import xarray as xr

    t0 = time.perf_counter()
    cfg = _cfg()
    sets, name = [], f"mc-n{n}"
    if plateau_ratio is not None:
        fn = cfg.system.natural_frequencies[0]
        sets, name = [f"profile.plateau={plateau_ratio * fn!r}"], f"{name}-plateau{plateau_ratio:g}"
        cfg = _cfg(sets)
    raw = _run_sweep(f"tsr-{name}", sets, {}, n, store=_store(store_dir, name),
                     executor=executor, workers=workers, scheduler=scheduler)
    g = raw["grade_G"].values                      # (sample, checkpoint)
    ok = raw["status"].values == 0
    g_ini = float(_grade(cfg.system.rotor.unbalance, cfg.system.total_mass, cfg.spin.nominal_speed))
    w_pl = plateau_speed(cfg.spin)
    ds = xr.Dataset({"G_STD": ("sample", g[:, 0], {"units": "mm/s"}),
                     "G_TSR": ("sample", g[:, 1], {"units": "mm/s"}),
                     "start_angle": (("sample", "ball"), raw["start_angle"].values, {"units": "rad"}),
                     "status": ("sample", raw["status"].values)})
    ds.attrs.update({
        "study": "monte_carlo", "n": n, "runs": int(ok.size), "failed": int((~ok).sum()),
        "G_ini": g_ini, "G_balls": float(_grade(cfg.system.balancer.capacity, cfg.system.total_mass,
                                                cfg.spin.nominal_speed)),
        **_mc_stats(g[ok, 0], g[ok, 1], g_ini),
        "plateau_hz": w_pl / (2 * np.pi),
        "G_stick_plateau": float(stick_threshold_grade(cfg.system, w_pl, cfg.spin.nominal_speed)),
        "wall_s": time.perf_counter() - t0, "profile": _profile_text(cfg.spin)})
    return ds


def _mc_stats(s, t, g_ini) -> dict:
    """Mode (1 mm/s bins, bootstrap SE), median, G16 and G_ini shares and Table 2 regions of the
    STD (s) and TSR (t) grades [mm/s]."""
    (ms, ses), (mt, set_) = _mode(s), _mode(t)
    return {"mode_STD": ms, "mode_STD_se": ses, "mode_TSR": mt, "mode_TSR_se": set_,
            "median_STD": float(np.median(s)), "median_TSR": float(np.median(t)),
            "share_G16_STD": float(np.mean(s <= G_LIMIT)), "share_G16_TSR": float(np.mean(t <= G_LIMIT)),
            "success_STD": float(np.mean(s <= g_ini)), "success_TSR": float(np.mean(t <= g_ini)),
            **{f"region_{k}": v for k, v in regions(s, t, g_ini).items()}}


def _share_tol(p: float, n_ours: int, n_paper: int = 1275) -> float:
    """2-sigma tolerance of the difference of two binomial shares (ours with n_ours runs, the
    paper's with n_paper): 2 sqrt(p(1-p)(1/n_ours + 1/n_paper)), p = the published share. A
    floor of 0.5/n_paper covers the paper's rounding of shares near 0."""
    return 2 * math.sqrt(max(p * (1 - p), 1.0 / n_paper) * (1 / n_ours + 1 / n_paper))


def compare_monte_carlo(ds=None) -> list:
    ds = ds if ds is not None else compute_monte_carlo()
    a, p = ds.attrs, PUBLISHED["monte_carlo"]
    n = int(a["runs"])
    rows = [
        _row("monte_carlo/runs", "004 sec. 4.2 runs", p["runs"], n, "= 1275 (full) / n(n+1)/2 (quick)",
             n == a["n"] * (a["n"] + 1) // 2, "50 x 50 starts, swapped duplicates removed"),
    ]
    for cp in ("STD", "TSR"):
        m, se = a[f"mode_{cp}"], a[f"mode_{cp}_se"]
        tol = max(1.0, 2 * se)
        rows.append(_row(f"monte_carlo/mode_{cp}", f"004 Fig. 5 most frequent G_{cp} [mm/s]", p[f"mode_{cp}"], round(m, 2),
                         f"+-{tol:.1f}", abs(m - p[f"mode_{cp}"]) <= tol,
                         f"mode of 1 mm/s bins; tolerance max(1 bin, 2 x bootstrap SE {se:.1f}); "
                         f"median {a[f'median_{cp}']:.1f}"
                         + (f"; closed-form stick threshold at our plateau G* = "
                            f"{a['G_stick_plateau']:.2f} (stick_threshold_grade; 11.45 at "
                            f"1.02 Omega_n)" if cp == "TSR" and "G_stick_plateau" in a else "")))
    for key, lab in (("share_G16", "share qualifying G16"), ("success", "share with G <= G_ini")):
        for cp in ("STD", "TSR"):
            pub = p[f"{key}_{cp}"]
            c = a[f"{key}_{cp}"]
            tol = _share_tol(pub, n)
            rows.append(_row(f"monte_carlo/{key}_{cp}", f"004 sec. 4.2 {lab} {cp} [%]", 100 * pub, round(100 * c, 1),
                             f"+-{100 * tol:.1f}", abs(c - pub) <= tol,
                             f"2 sigma of the difference of two binomial shares ({n} and 1275 runs)"))
    for k, pub in p["regions"].items():
        c = a[f"region_{k}"]
        tol = _share_tol(pub, n)
        rows.append(_row(f"monte_carlo/regions/{k}", f"004 Table 2 region {k} [%]", 100 * pub, round(100 * c, 1),
                         f"+-{100 * tol:.1f}", abs(c - pub) <= tol,
                         "2 sigma binomial (both samples); G_INI = rotor's own grade"))
    return rows


# -- 3. initial-unbalance sweep (Fig. 7, Tables 3-4) --------------------------------------------
def _g_grid(quick: bool):
    return np.arange(0.0, 50.1, 5.0) if quick else np.arange(0.0, 50.1, 2.0)


def compute_unbalance(cases=("nominal",), *, G=None, n: int = 50, quick: bool = False,
                      store_dir=None, executor="local", workers=None, scheduler=None):
    """004 sec. 4.3-4.5: G_ini over [G0, G50] x the start grid for each (mu_r, c_r) case;
    5/50/95 % of G_STD (18 s) and G_TSR (90 s), valid ranges for G16 and efficiencies."""
    import xarray as xr

    t0 = time.perf_counter()
    cfg = _cfg()
    Gv = _g_grid(quick) if G is None else np.asarray(G, float)
    U = grade_to_unbalance(Gv, cfg.system.total_mass, cfg.spin.nominal_speed)
    q = np.array([5.0, 50.0, 95.0])
    data = np.full((len(cases), Gv.size, 2, q.size), np.nan)
    failed = np.zeros(len(cases), int)
    for ci, case in enumerate(cases):
        mu_r, c_r = UNBALANCE_CASES[case]
        raw = _run_sweep(f"tsr-unb-{case}-n{n}-g{Gv.size}", _case_sets(mu_r, c_r),
                         {"rotor.unbalance": [float(u) for u in U]}, n,
                         store=_store(store_dir, f"unbalance-{case}-n{n}-g{Gv.size}"),
                         executor=executor, workers=workers, scheduler=scheduler)
        g = raw["grade_G"].where(raw["status"] == 0)
        data[ci] = g.quantile(q / 100, dim="sample").transpose("rotor__unbalance", "checkpoint",
                                                               "quantile").values
        failed[ci] = int((raw["status"] != 0).sum())
    ds = xr.Dataset({"grade_G": (("case", "G_ini", "procedure", "percentile"), data,
                                 {"units": "mm/s", "long_name": "residual grade percentile"}),
                     "failed_runs": ("case", failed)},
                    coords={"case": list(cases), "G_ini": ("G_ini", Gv, {"units": "mm/s"}),
                            "procedure": ["STD", "TSR"], "percentile": q,
                            "mu_r": ("case", [UNBALANCE_CASES[c][0] for c in cases]),
                            "c_r": ("case", [UNBALANCE_CASES[c][1] for c in cases])})
    G_b = float(_grade(cfg.system.balancer.capacity, cfg.system.total_mass, cfg.spin.nominal_speed))
    ds.attrs.update({"study": "unbalance", "n": n, "G_balls": G_b, "grid_step": float(np.diff(Gv).max()),
                     "wall_s": time.perf_counter() - t0, "profile": _profile_text(cfg.spin)})
    return ds


def _boundaries(r):
    return [v for lo, hi in r for v in (lo, hi) if 0.0 < v < G_SPAN]


def compare_unbalance(ds=None) -> list:
    ds = ds if ds is not None else compute_unbalance()
    pub = PUBLISHED["unbalance"]
    step = float(ds.attrs["grid_step"])
    tb = step / 2 + 1.0          # a boundary: half our grid step + the paper's 1 G reading
    rows = []
    for case in UNBALANCE_CASES:
        mu_r, c_r = UNBALANCE_CASES[case]
        for proc in ("STD", "TSR"):
            pr, pe = pub[case][proc]["ranges"], pub[case][proc]["efficiency"]
            key = f"unbalance/{case}/{proc}"
            lab = f"004 Table {3 if c_r == 1 else 4} mu_r={mu_r:g} c_r={c_r:g} {proc}"
            if case not in ds["case"].values:
                rows.append(_missing(f"{key}/ranges", f"{lab} valid range G16", _fmt_ranges(pr)))
                rows.append(_missing(f"{key}/efficiency", f"{lab} efficiency [%]", 100 * pe))
                continue
            p95 = ds["grade_G"].sel(case=case, procedure=proc, percentile=95.0).values
            cr, ce = valid_ranges(ds["G_ini"].values, p95)
            pb, cb = _boundaries(pr), _boundaries(cr)
            ok_r = len(pr) == len(cr) and len(pb) == len(cb) and all(
                abs(x - y) <= tb for x, y in zip(pb, cb))
            top = ""
            if pr and cr:               # the highest interval: the over-excited range
                d = max(abs(pr[-1][0] - cr[-1][0]), abs(pr[-1][1] - cr[-1][1]))
                top = (f"; highest interval G{cr[-1][0]:.1f}-G{cr[-1][1]:.1f}: its boundaries "
                       f"{'within' if d <= tb else 'outside'} +-{tb:g} G of 004's (max "
                       f"difference {d:.1f} G)")
            rows.append(_row(f"{key}/ranges", f"{lab} valid range G16", _fmt_ranges(pr), _fmt_ranges(cr),
                             f"same intervals, each boundary +-{tb:g} G", ok_r,
                             "p95 <= G16, linear interpolation between grid points" + top))
            nb = max(len(pb), len(cb), 1)
            tol = nb * tb / G_SPAN
            rows.append(_row(f"{key}/efficiency", f"{lab} efficiency [%]", 100 * pe, round(100 * ce, 1),
                             f"+-{100 * tol:.0f}", abs(ce - pe) <= tol + 1e-9,
                             f"{nb} boundaries x +-{tb:g} G over [G0, G50]"))
    return rows


# -- 4. speed profile (Fig. 9) ------------------------------------------------------------------
SLOW_SETS = ["profile.kind=std", "profile.runup_fraction=0.6", "profile.runup_time=54 s",
             "profile.duration=90 s"]


def compute_profile(*, G=None, n: int = 50, quick: bool = False, store_dir=None, executor="local",
                    workers=None, unbalance_ds=None, scheduler=None):
    """004 sec. 4.4, Fig. 9: 95 % isolines of the STD (18 s), TSR (90 s) and a 3x slower run-up
    (0 -> 167 Hz in 54 s, hold to 90 s, read at 90 s) against G_ini (nominal mu, c)."""
    import xarray as xr

    t0 = time.perf_counter()
    cfg = _cfg()
    Gv = _g_grid(quick) if G is None else np.asarray(G, float)
    if unbalance_ds is None or not np.array_equal(unbalance_ds["G_ini"].values, Gv) \
            or "nominal" not in unbalance_ds["case"].values or unbalance_ds.attrs["n"] != n:
        unbalance_ds = compute_unbalance(("nominal",), G=Gv, n=n, store_dir=store_dir,
                                         executor=executor, workers=workers, scheduler=scheduler)
    U = grade_to_unbalance(Gv, cfg.system.total_mass, cfg.spin.nominal_speed)
    raw = _run_sweep(f"tsr-slow-n{n}-g{Gv.size}", SLOW_SETS,
                     {"rotor.unbalance": [float(u) for u in U]}, n,
                     store=_store(store_dir, f"slow-n{n}-g{Gv.size}"), executor=executor,
                     workers=workers, scheduler=scheduler)
    g = raw["grade_G"].where(raw["status"] == 0).isel(checkpoint=-1)
    q = np.array([5.0, 50.0, 95.0])
    slow = g.quantile(q / 100, dim="sample").transpose("rotor__unbalance", "quantile").values
    base = unbalance_ds["grade_G"].sel(case="nominal").values        # (G, procedure, q)
    data = np.concatenate([base, slow[:, None, :]], axis=1)
    ds = xr.Dataset({"grade_G": (("G_ini", "procedure", "percentile"), data, {"units": "mm/s"})},
                    coords={"G_ini": ("G_ini", Gv, {"units": "mm/s"}),
                            "procedure": ["STD", "TSR", "slow"], "percentile": q})
    ds.attrs.update({"study": "profile", "n": n, "wall_s": time.perf_counter() - t0,
                     "profile": _profile_text(cfg.spin),
                     "slow_profile": "0 -> 167 Hz linear in 54 s (3 x 18 s), hold to 90 s"})
    return ds


def compare_profile(ds=None) -> list:
    ds = ds if ds is not None else compute_profile()
    lo, hi = PUBLISHED["profile"]["slow_worse_range"]
    G = ds["G_ini"].values
    p = ds["grade_G"].sel(percentile=95.0)
    std, slow, tsr = (p.sel(procedure=k).values for k in ("STD", "slow", "TSR"))
    inside = (G >= lo) & (G <= hi)
    worse = G[inside & (slow > std)]
    out = ~inside
    d_out = float(np.mean(slow[out] - std[out])) if out.any() else float("nan")
    return [
        _row("profile/slow_worse_range", "004 Fig. 9 slow run-up p95 worse than STD in [G10, G21]", "[G10, G21]",
             ", ".join(f"G{x:g}" for x in worse) or "none", "at least one grid G_ini in [10, 21]",
             worse.size > 0, "grid points of [G10, G21] where slow p95 > STD p95"),
        _row("profile/slow_better_elsewhere", "004 Fig. 9 slow run-up better than STD elsewhere (mean p95 change) [mm/s]", "< 0",
             round(d_out, 2), "< 0", d_out < 0, "mean over grid G_ini outside [G10, G21]"),
        _row("profile/tsr_better", "004 Fig. 9 TSR p95 <= STD p95 (mean change) [mm/s]", "< 0",
             round(float(np.mean(tsr - std)), 2), "< 0", float(np.mean(tsr - std)) < 0,
             "004: TSR improves STD, mostly at low G_ini"),
    ]


# -- 5. immobility (Fig. 8, 10) -----------------------------------------------------------------
MU_R = (0.25, 0.5, 1.0, 2.0, 5.0)
C_R = (0.5, 0.6, 1.0, 1.4)


def compute_immobility(*, G_ini: float = 20.0, mu_r=MU_R, c_r=C_R, speeds_hz=None,
                       n_conf: int = 100, quick: bool = False, field: str = "n_conf"):
    """004 Fig. 8/10: immobility [-] against speed for the mu_r x c_r sets at G_ini [mm/s]
    (closed form :func:`immobility`; no time integration). ``n_conf`` positions per ball [-];
    a grid beyond the memory or run-time limit is refused before computing (ResourceError
    naming ``field``)."""
    import dataclasses

    import xarray as xr

    t0 = time.perf_counter()
    cfg = _cfg()
    s0 = cfg.system
    wn = cfg.spin.nominal_speed
    f = np.linspace(20.0, 200.0, 91 if quick else 361) if speeds_hz is None else np.asarray(speeds_hz, float)
    n_conf = 36 if quick else n_conf
    check_immobility(n_conf, s0.balancer.n_balls, f.size, len(mu_r) * len(c_r), field)
    U = float(grade_to_unbalance(G_ini, s0.total_mass, wn))
    out = np.empty((len(mu_r), len(c_r), f.size))
    for i, mr in enumerate(mu_r):
        for j, cr in enumerate(c_r):
            s = dataclasses.replace(
                s0, rotor=dataclasses.replace(s0.rotor, unbalance=U),
                suspension=dataclasses.replace(s0.suspension, cx=s0.suspension.cx * cr,
                                               cy=s0.suspension.cy * cr),
                balancer=dataclasses.replace(s0.balancer, rolling_resistance=0.002 * mr,
                                             stiction=None))
            out[i, j] = immobility(s, 2 * np.pi * f, n_conf)
    fn = s0.natural_frequencies[0] / (2 * np.pi)
    ds = xr.Dataset({"immobility": (("mu_r", "c_r", "speed"), out,
                                    {"units": "-", "long_name": "share of immobile configurations"})},
                    coords={"mu_r": list(mu_r), "c_r": list(c_r),
                            "speed": ("speed", f, {"units": "Hz"})})
    ds.attrs.update({"study": "immobility", "G_ini": float(G_ini), "n_conf": n_conf,
                     "f_n_hz": fn, "nominal_hz": wn / (2 * np.pi), "plateau_hz": 100.0,
                     "method": "closed form |Im(w e^-i alpha)| <= mu R (004 eq 1), checked "
                               "against the kernel's stuck-ball friction",
                     "wall_s": time.perf_counter() - t0})
    return ds


def compare_immobility(ds=None) -> list:
    ds = ds if ds is not None else compute_immobility()
    rows = []
    fn = ds.attrs["f_n_hz"]
    f = ds["speed"].values
    im = ds["immobility"]
    have = 1.0 in ds["mu_r"].values and 1.0 in ds["c_r"].values
    if not have:
        return [_missing(f"immobility/{k}", f"004 Fig. 8/10 {k}", v, "needs mu_r = c_r = 1")
                for k, v in PUBLISHED["immobility"].items() if k != "source"]
    nom = im.sel(mu_r=1.0, c_r=1.0).values
    fmin = float(f[np.argmin(nom)])
    rows.append(_row("immobility/valley_at_resonance", "004 Fig. 8 speed of least immobility / f_n [-]", "near resonance (~1)",
                     round(fmin / fn, 3), "0.9-1.1", 0.9 <= fmin / fn <= 1.1,
                     f"min immobility {nom.min():.3f} at {fmin:.1f} Hz (G_ini = G{ds.attrs['G_ini']:g})"))
    i_nom = float(np.interp(ds.attrs["nominal_hz"], f, nom))
    i_pl = float(np.interp(ds.attrs["plateau_hz"], f, nom))
    rows.append(_row("immobility/nominal_above_plateau", "004 Fig. 8 immobility at 167 Hz > at the 100 Hz plateau", "higher at nominal",
                     f"{i_nom:.3f} vs {i_pl:.3f}", ">", i_nom > i_pl,
                     "TSR lowers immobility for as long as needed (sec. 4.4)"))
    mono_mu = bool(np.all(np.diff(im.values, axis=0) >= -1e-12))
    rows.append(_row("immobility/monotone_mu", "004 Fig. 10 immobility non-decreasing in mu_r (every c_r, speed)",
                     "more stiction, more immobility", mono_mu, "True", mono_mu,
                     f"mu_r = {list(ds['mu_r'].values)}"))
    near = (f >= 0.95 * fn) & (f <= 1.05 * fn)
    mean_c = im.sel(mu_r=1.0).values[:, near].mean(axis=1)
    order_c = np.argsort(ds["c_r"].values)
    mono_c = bool(np.all(np.diff(mean_c[order_c]) >= -1e-12))
    rows.append(_row("immobility/monotone_c", "004 Fig. 10 immobility near resonance increasing in c_r (mu_r = 1)",
                     "more damping, more immobility", [round(float(x), 3) for x in mean_c[order_c]],
                     "non-decreasing", mono_c, "mean over 0.95-1.05 f_n"))
    return rows


# -- 6. plateau map (Fig. 14-16) ----------------------------------------------------------------
def _plateau_grid(quick: bool):
    if quick:
        return np.array([0.98, 1.02, 1.06, 1.10]), np.array([5.0, 15.0, 25.0])
    return np.round(np.arange(0.96, 1.1201, 0.01), 3), np.arange(0.0, 34.1, 4.0)


def compute_plateau(cases=("nominal",), *, ratios=None, G=None, n: int = 20, quick: bool = False,
                    store_dir=None, executor="local", workers=None, scheduler=None):
    """004 sec. 4.6, Fig. 14-15: the lower TSR plateau (as Omega/Omega_n) x G_ini in [G0, G34] ->
    95th percentile of G_TSR (90 s); ideal plateau = argmin of its mean over G_ini."""
    import xarray as xr

    t0 = time.perf_counter()
    cfg = _cfg()
    s = cfg.system
    fn = s.natural_frequencies[0]
    r0, g0 = _plateau_grid(quick)
    ratios = r0 if ratios is None else np.asarray(ratios, float)
    Gv = g0 if G is None else np.asarray(G, float)
    U = grade_to_unbalance(Gv, s.total_mass, cfg.spin.nominal_speed)
    p95 = np.full((len(cases), ratios.size, Gv.size), np.nan)
    for ci, case in enumerate(cases):
        mu_r, c_r = PLATEAU_CASES[case]
        raw = _run_sweep(f"tsr-plateau-{case}-n{n}", _case_sets(mu_r, c_r),
                         {"profile.plateau": [float(r * fn) for r in ratios],
                          "rotor.unbalance": [float(u) for u in U]}, n,
                         store=_store(store_dir, f"plateau-{case}-n{n}-r{ratios.size}-g{Gv.size}"),
                         executor=executor, workers=workers, scheduler=scheduler)
        g = raw["grade_G"].where(raw["status"] == 0).isel(checkpoint=-1)
        p95[ci] = g.quantile(0.95, dim="sample").transpose("profile__plateau", "rotor__unbalance").values
    ds = xr.Dataset({"grade_G_p95": (("case", "plateau_ratio", "G_ini"), p95, {"units": "mm/s"})},
                    coords={"case": list(cases), "plateau_ratio": ratios,
                            "G_ini": ("G_ini", Gv, {"units": "mm/s"})})
    mean = np.nanmean(np.where(Gv <= G_TSR_RANGE, p95, np.nan), axis=2)
    ds["mean_p95"] = (("case", "plateau_ratio"), mean, {"units": "mm/s"})
    ds.attrs.update({"study": "plateau", "n": n, "f_n_hz": fn / (2 * np.pi),
                     "ideal": [float(ratios[np.nanargmin(m)]) for m in mean],
                     "ratio_step": float(np.diff(ratios).min()) if ratios.size > 1 else 0.0,
                     "wall_s": time.perf_counter() - t0, "profile": _profile_text(cfg.spin)})
    return ds


def compare_plateau(ds=None) -> list:
    ds = ds if ds is not None else compute_plateau()
    rows = []
    step = ds.attrs["ratio_step"]
    tol = step / 2 + 0.005          # half our grid step + the paper's 2-decimal rounding
    cases = list(ds["case"].values)
    rows.append(_row("plateau/standard", "004 sec. 4.6 standard plateau 100 Hz / f_n [-]",
                     round(PUBLISHED["plateau"]["standard"], 2),
                     round(100.0 / ds.attrs["f_n_hz"], 3), "+-0.005",
                     abs(100.0 / ds.attrs["f_n_hz"] - 1.06) <= 0.005, "f_n = sqrt(k/M_t)"))
    for case, pub in PUBLISHED["plateau"]["ideal"].items():
        mu_r, c_r = PLATEAU_CASES[case]
        lab = f"004 Fig. {14 if case == 'nominal' else 15} ideal plateau mu_r={mu_r:g} c_r={c_r:g} [-]"
        if case not in cases:
            rows.append(_missing(f"plateau/ideal/{case}", lab, pub))
            continue
        c = ds.attrs["ideal"][cases.index(case)]
        rows.append(_row(f"plateau/ideal/{case}", lab, pub, c, f"+-{tol:.3f}", abs(c - pub) <= tol + 1e-9,
                         f"argmin over plateau of the mean p95 G_TSR over G_ini <= G34; grid "
                         f"{ds['plateau_ratio'].values.min():g}-{ds['plateau_ratio'].values.max():g}"))
    return rows


# -- 7. gradual descent (Fig. 13) ----------------------------------------------------------------
DESCENT_PCT = (5.0, 25.0, 50.0, 75.0, 95.0)


def compute_descent(*, G_ini: float = 5.0, n: int = 50, ratio_end: float = 0.9,
                    down_time: float = 60.0, history_dt: float = 0.25, store_dir=None,
                    executor="local", workers=None, scheduler=None):
    """004 sec. 4.6, Fig. 13: after the standard run-up (18 s to 167 Hz), a slow linear descent
    to ``ratio_end`` Omega_n in ``down_time`` [s]; the residual grade G [mm/s] of every start is
    read every ``history_dt`` [s] and its percentiles over the n(n+1)/2 starts are returned
    against the speed ratio Omega/Omega_n [-]. Also the stick threshold G*(Omega)
    (:func:`stick_threshold_grade`) at the same speeds.

    004 does not give its descent rate ("a gradual speed reduction"); ours is 82 Hz in 60 s
    (1.4 Hz/s), a fifth of the TSR profile's 6.7 Hz/s."""
    import xarray as xr

    t0 = time.perf_counter()
    base = _cfg()
    s0 = base.system
    fn = s0.natural_frequencies[0]
    U = float(grade_to_unbalance(G_ini, s0.total_mass, base.spin.nominal_speed))
    sets = [f"rotor.unbalance={U!r}", f"profile.plateau={ratio_end * fn!r}",
            f"profile.down_time={down_time!r}", "profile.plateau_time=1.0", "profile.up_time=1.0"]
    cfg = _cfg(sets)
    name = f"descent-g{G_ini:g}-n{n}-r{ratio_end:g}-t{down_time:g}-dt{history_dt:g}"
    raw = _run_sweep(f"tsr-{name}", sets, {}, n, store=_store(store_dir, name),
                     executor=executor, workers=workers, history_dt=history_dt,
                     scheduler=scheduler)
    t = raw["history_time"].values
    t_read = cfg.spin.checkpoints[0]
    sel = (t >= t_read) & (t <= t_read + down_time + 1e-9)
    speed = np.interp(t[sel], cfg.spin.times, cfg.spin.speeds)
    ok = raw["status"].values == 0
    g = raw["grade_G_history"].values[ok][:, sel]                       # (run, time)
    pct = np.percentile(g, DESCENT_PCT, axis=0)
    ratio = speed / fn
    ds = xr.Dataset({"grade_G": (("percentile", "ratio"), pct, {"units": "mm/s"}),
                     "G_stick": ("ratio", stick_threshold_grade(cfg.system, speed,
                                                                 cfg.spin.nominal_speed),
                                 {"units": "mm/s", "long_name": "stick threshold G*"}),
                     "time": ("ratio", t[sel], {"units": "s"})},
                    coords={"percentile": list(DESCENT_PCT),
                            "ratio": ("ratio", ratio, {"long_name": "Omega / Omega_n"})})
    med, p95 = pct[DESCENT_PCT.index(50.0)], pct[DESCENT_PCT.index(95.0)]
    ds.attrs.update({
        "study": "descent", "n": n, "runs": int(ok.size), "failed": int((~ok).sum()),
        "G_ini": G_ini, "G_balls": float(_grade(cfg.system.balancer.capacity, cfg.system.total_mass,
                                                cfg.spin.nominal_speed)),
        "f_n_hz": fn / (2 * np.pi), "standard_ratio": plateau_speed(base.spin) / fn,
        "down_time_s": down_time, "ratio_end": ratio_end,
        "half_drop_median": _half_drop(ratio, med), "half_drop_p95": _half_drop(ratio, p95),
        **_rise_after_min(ratio, p95),
        "wall_s": time.perf_counter() - t0, "profile": _profile_text(cfg.spin)})
    return ds


def _half_drop(ratio, g) -> float:
    """Speed ratio [-] at which g, followed from the start of the descent (highest speed), first
    falls halfway from its start value to its minimum over ratio >= 1 (linear interpolation
    between samples); NaN if it never drops."""
    sup = ratio >= 1.0
    g0, gmin = g[0], g[sup].min()
    if not g0 > gmin:
        return math.nan
    level = g0 - 0.5 * (g0 - gmin)
    j = int(np.argmax(g <= level))                 # first sample at or below the level
    if j == 0:
        return float(ratio[0])
    f = (g[j - 1] - level) / (g[j - 1] - g[j])
    return float(ratio[j - 1] + f * (ratio[j] - ratio[j - 1]))


def _rise_after_min(ratio, g, rise: float = 1.0) -> dict:
    """Where g [mm/s], after its minimum over ratio >= 1, first exceeds that minimum by more than
    ``rise`` later in the descent: {"p95_min", "p95_min_ratio", "p95_rise_ratio" (NaN if never),
    "p95_max_after"}."""
    sup = np.flatnonzero(ratio >= 1.0)
    j = int(sup[np.argmin(g[sup])])
    later = np.flatnonzero(g[j:] > g[j] + rise)
    return {"p95_min": float(g[j]), "p95_min_ratio": float(ratio[j]),
            "p95_rise_ratio": float(ratio[j + later[0]]) if later.size else math.nan,
            "p95_max_after": float(g[j:].max())}


def compare_descent(ds=None) -> list:
    ds = ds if ds is not None else compute_descent()
    a, p = ds.attrs, PUBLISHED["descent"]
    hd = a["half_drop_median"]
    worse = bool(np.isfinite(a["p95_rise_ratio"]))
    return [
        _row("descent/prompt_reduction", "004 Fig. 13 speed of the prompt reduction / Omega_n [-]",
             p["prompt_reduction"], round(hd, 3), "+-0.05", abs(hd - p["prompt_reduction"]) <= 0.05,
             f"half-drop point of the median G along the descent (p95: "
             f"{a['half_drop_p95']:.3f}); tolerance: 004 reads 'near 1.1', one decimal; "
             f"G_ini = G{a['G_ini']:g}, {a['runs']} starts, descent 167 Hz -> "
             f"{a['ratio_end']:g} Omega_n in {a['down_time_s']:g} s"),
        _row("descent/worse_near_resonance", "004 Fig. 13 outcomes deteriorate nearing resonance",
             p["worse_near_resonance"],
             (f"p95 rises from {a['p95_min']:.1f} (at {a['p95_min_ratio']:.3f}) to "
              f"{a['p95_max_after']:.1f}, past +1 at {a['p95_rise_ratio']:.3f} Omega_n") if worse
             else f"no rise: p95 min {a['p95_min']:.1f} at {a['p95_min_ratio']:.3f}",
             "p95 rises > 1 mm/s above its minimum later in the descent", worse,
             "95th percentile of G (the worst outcomes) along the descent to 0.9 Omega_n; its "
             "minimum taken over Omega >= Omega_n"),
    ]


#: CLI name -> (compute, compare, plot function name in plotting.tsr)
STUDIES = {
    "tsr-single": (compute_single, compare_single, "plot_single"),
    "tsr-monte-carlo": (compute_monte_carlo, compare_monte_carlo, "plot_monte_carlo"),
    "tsr-unbalance": (compute_unbalance, compare_unbalance, "plot_unbalance"),
    "tsr-profile": (compute_profile, compare_profile, "plot_profile"),
    "tsr-plateau": (compute_plateau, compare_plateau, "plot_plateau"),
    "tsr-descent": (compute_descent, compare_descent, "plot_descent"),
    "immobility": (compute_immobility, compare_immobility, "plot_immobility"),
}


# -- 0. Table 1 and the speed profile (Fig. 3) --------------------------------------------------
def compute_table1():
    """004 Table 1 derived numbers: resonance f_n = sqrt(k/M_t)/2pi [Hz] (Jeffcott), the rotor's
    grade G_ini and the balls' grade 2 m R / M_t Omega_nom [mm/s] (004 sec. 4), and the profile
    (004 Fig. 3, our reading: docs/model.md sec. 5) sampled every 0.1 s."""
    import xarray as xr

    cfg = _cfg()
    s, spin = cfg.system, cfg.spin
    t = np.arange(0.0, float(spin.duration) + 1e-9, 0.1)
    ds = xr.Dataset({"speed": ("time", np.asarray(spin.speed(t), float), {"units": "rad/s"})},
                    coords={"time": ("time", t, {"units": "s"})})
    ds.attrs.update({
        "study": "table1", "f_n_hz": float(s.natural_frequencies[0] / (2 * np.pi)),
        "G_ini": float(_grade(s.rotor.unbalance, s.total_mass, spin.nominal_speed)),
        "G_balls": float(_grade(s.balancer.capacity, s.total_mass, spin.nominal_speed)),
        "checkpoints_s": [float(c) for c in spin.checkpoints], "profile": _profile_text(spin)})
    return ds


def compare_table1(ds=None) -> list:
    a, p = (ds if ds is not None else compute_table1()).attrs, PUBLISHED["table1"]
    return [
        _row("table1/f_n_hz", "004 sec. 4 resonance f_n [Hz]", p["f_n_hz"], round(a["f_n_hz"], 2),
             "+-0.05", abs(a["f_n_hz"] - p["f_n_hz"]) <= 0.05, "sqrt(k/M_t)/2pi, M_t = M + 2m"),
        _row("table1/G_ini", "004 Table 1 rotor unbalance G_ini [mm/s]", p["G_ini"],
             round(a["G_ini"], 2), "+-0.5", abs(a["G_ini"] - p["G_ini"]) <= 0.5,
             "eps = 19.3 um at 167 Hz, mass M_t; paper rounds to integer G"),
        _row("table1/G_balls", "004 sec. 4.6 total ball unbalance [mm/s]", p["G_balls"],
             round(a["G_balls"], 2), "+-0.5", abs(a["G_balls"] - p["G_balls"]) <= 0.5,
             "2 m R / M_t * Omega_nom (2 x 7.6 g at 35 mm)"),
    ]


# -- reproduction targets (autobalance reproduce) ------------------------------------------------
def _outcome(name, ds, ctx_note=""):
    from ...plotting import tsr as plots
    from ...validation.target import Outcome

    compute, compare, plot = STUDIES[name]
    fig = getattr(plots, plot)(ds)
    return Outcome(rows=compare(ds), figures={name: fig}, data=ds, notes=ctx_note)


def _run_table1(ctx):
    from ...plotting import tsr as plots
    from ...validation.target import Outcome

    ds = compute_table1()
    return Outcome(rows=compare_table1(ds), figures={"profile": plots.plot_speed_profile(ds)},
                   data=ds, notes=ds.attrs["profile"])


def _run_single(ctx):
    return _outcome("tsr-single", compute_single(save_dt=0.02 if ctx.quick else 0.005))


def _mc_n(ctx):
    return 12 if ctx.quick else 50


def _run_mc(ctx):
    n = _mc_n(ctx)
    kw = dict(store_dir=ctx.stores, executor=ctx.executor, workers=ctx.workers,
              scheduler=ctx.scheduler)
    ds = compute_monte_carlo(n, **kw)
    ideal = PUBLISHED["plateau"]["ideal"]["nominal"]
    alt = compute_monte_carlo(n, plateau_ratio=ideal, **kw)
    ds["G_TSR_ideal"] = alt["G_TSR"].assign_attrs(
        long_name=f"G_TSR with the plateau at {ideal:g} Omega_n")
    ds.attrs.update({f"ideal_{k}": alt.attrs[k] for k in
                     ("plateau_hz", "G_stick_plateau", "mode_TSR", "share_G16_TSR",
                      *(f"region_{r}" for r in REGIONS))})
    a = ds.attrs
    note = (f"{n} x {n} start grid: {a['runs']} runs. Sensitivity (not a published number): "
            f"the same starts with the plateau at 004's ideal {ideal:g} Omega_n "
            f"({a['ideal_plateau_hz']:.1f} Hz) give the most frequent G_TSR "
            f"{a['ideal_mode_TSR']:.1f} (004: 11; closed-form stick threshold "
            f"{a['ideal_G_stick_plateau']:.2f}), {100 * a['ideal_share_G16_TSR']:.1f} % <= G16, "
            "regions " + ", ".join(f"{r} {100 * a[f'ideal_region_{r}']:.1f} %" for r in REGIONS)
            + f" (at 100 Hz: mode {a['mode_TSR']:.1f}, G* {a['G_stick_plateau']:.2f}).")
    return _outcome("tsr-monte-carlo", ds, note)


def _unb_n(ctx):
    return 6 if ctx.quick else 50


def _run_unbalance(ctx):
    n = _unb_n(ctx)
    ds = compute_unbalance(tuple(UNBALANCE_CASES), n=n, quick=ctx.quick, store_dir=ctx.stores,
                           executor=ctx.executor, workers=ctx.workers, scheduler=ctx.scheduler)
    return _outcome("tsr-unbalance", ds, f"G_ini every {ds.attrs['grid_step']:g} mm/s x "
                                         f"{n * (n + 1) // 2} starts x {len(UNBALANCE_CASES)} cases")


def _run_profile(ctx):
    n = _unb_n(ctx)
    ds = compute_profile(n=n, quick=ctx.quick, store_dir=ctx.stores, executor=ctx.executor,
                         workers=ctx.workers, scheduler=ctx.scheduler)
    return _outcome("tsr-profile", ds, f"{n * (n + 1) // 2} starts per G_ini; the STD/TSR "
                                       f"isolines reuse the nominal initial-unbalance sweep")


def _run_immobility(ctx):
    return _outcome("immobility", compute_immobility(quick=ctx.quick))


def _run_plateau(ctx):
    n = 6 if ctx.quick else 20
    ds = compute_plateau(tuple(PLATEAU_CASES), n=n, quick=ctx.quick, store_dir=ctx.stores,
                         executor=ctx.executor, workers=ctx.workers, scheduler=ctx.scheduler)
    return _outcome("tsr-plateau", ds, f"{ds.sizes['plateau_ratio']} plateaus x "
                                       f"{ds.sizes['G_ini']} G_ini x {n * (n + 1) // 2} starts")


def _run_descent(ctx):
    n = 6 if ctx.quick else 50
    ds = compute_descent(n=n, history_dt=0.5 if ctx.quick else 0.25, store_dir=ctx.stores,
                         executor=ctx.executor, workers=ctx.workers, scheduler=ctx.scheduler)
    return _outcome("tsr-descent", ds, f"G{ds.attrs['G_ini']:g}, {ds.attrs['runs']} starts, "
                                       f"G read every {0.5 if ctx.quick else 0.25:g} s")


def _targets():
    from ...validation.target import Target

    model = ("Model: 004 Table 1, point-mass balls, exact Coulomb stick-slip (mu_s = mu, not "
             "004's tanh law), rotor at rest at t = 0; profile read off Fig. 3 (docs/model.md "
             "sec. 5). ")
    return [
        Target("004-sketches", "004", ("Fig. 1", "Fig. 2"), "Sketches: one-ball balancer forces, "
               "Jeffcott rotor coordinates", notes="Drawings of the model; nothing to compute. "
               "Their content (004 eq 1, eq 8-10) is the model of docs/model.md."),
        Target("004-table1-fig3", "004", ("Table 1", "Fig. 3"), "Parameters and the 90 s "
               "standardised speed profile", _run_table1, PUBLISHED["table1"], "table1",
               notes=model + "Fig. 3 is given only as a drawing: plateau 100 Hz from 28 to 48 s "
               "is our reading; the STD read-out is at 18 s (20 % of 90 s)."),
        Target("004-fig4", "004", ("Fig. 4",), "A single TSR run from a G14 start",
               _run_single, PUBLISHED["single"], "single",
               notes=model + "004 gives neither its start angles nor the exact profile: we run "
               "every G14 start (ball 1 every 15 deg) and plot the first; the rows check the "
               "paper's statements about its run.", quick="history saved every 20 ms "
                                                        "instead of 5 ms",
               aliases=("tsr-single",)),
        Target("004-fig5-6-table2", "004", ("Fig. 5", "Fig. 6", "Table 2"),
               "Start-position Monte Carlo at G20: residual-grade PDFs, STD vs TSR, outcome "
               "regions", _run_mc, PUBLISHED["monte_carlo"], "monte_carlo",
               notes=model + "Tolerance on shares: 2 sigma of the difference of two binomial "
               "shares. The G16 shares miss: our STD qualifies more often than 004's "
               "(docs/tsr-studies.md). Our most frequent G_TSR is the closed-form stick "
               "threshold at the plateau, G* = mu R Omega_nom |k - M_t Omega^2 + i c Omega| / "
               "(M_t Omega^2) = 13.47 at 100 Hz: below it no ball can move "
               "(stick_threshold_grade); 004's 11 is G* at 1.02 Omega_n (11.45), so the "
               "report also runs that plateau as a sensitivity study.", quick="12 x 12 start grid (78 runs) instead of "
                                               "50 x 50 (1275 runs)", aliases=("tsr-mc",)),
        Target("004-fig7-11-12-table3-4", "004", ("Fig. 7", "Fig. 11", "Fig. 12", "Table 3",
                                                  "Table 4"),
               "Initial-unbalance sweep: valid G16 ranges and efficiency for five friction and "
               "damping cases", _run_unbalance, PUBLISHED["unbalance"], "unbalance",
               notes=model + "Valid range: 95th percentile of the residual grade <= G16, "
               "linear interpolation between grid points; boundary tolerance = half our grid "
               "step + 1 G (the paper's reading).",
               quick="G_ini every 5 mm/s, 6 x 6 start grid (21 runs per point) instead of every "
                     "2 mm/s and 1275 runs; the coarse grid widens every boundary tolerance "
                     "to +-3.5 G", aliases=("tsr-unbalance",)),
        Target("004-fig8-10", "004", ("Fig. 8", "Fig. 10"), "Immobility against speed for "
               "friction and damping sets", _run_immobility, PUBLISHED["immobility"],
               "immobility", notes="Closed form: a ball configuration at rest is immobile when "
               "every ball's tangential force |F_t| <= mu m R Omega^2 (004 eq 1), checked "
               "against the kernel's stuck-ball friction. The figures carry no numbers; the "
               "rows check the text's statements.",
               quick="91 speeds and 36 positions per ball instead of 361 and 100",
               aliases=("tsr-immobility",)),
        Target("004-fig9", "004", ("Fig. 9",), "Speed profile: a 3x slower run-up vs STD and "
               "TSR", _run_profile, PUBLISHED["profile"], "profile",
               notes=model + "Slow run-up: 0 -> 167 Hz linear in 54 s, hold to 90 s, read at "
                             "90 s.",
               quick="G_ini every 5 mm/s, 21 starts per point", aliases=("tsr-profile",)),
        Target("004-fig13", "004", ("Fig. 13",), "Gradual speed reduction at G5: where the "
               "balls relocate", _run_descent, PUBLISHED["descent"], "descent",
               notes=model + "004's descent rate is not given; ours: 167 Hz -> 0.9 Omega_n "
               "linear in 60 s after the 18 s run-up. The curves are the 5-95 % percentiles "
               "of the residual grade over the start grid; the dashed curve is the closed-form "
               "stick threshold G*(Omega) below which no ball at rest can move.",
               quick="6 x 6 start grid (21 runs), G every 0.5 s, instead of 50 x 50 (1275 runs) "
                     "every 0.25 s", aliases=("tsr-descent",)),
        Target("004-fig14-16", "004", ("Fig. 14", "Fig. 15", "Fig. 16"),
               "The lower plateau: residual grade over plateau x G_ini and the ideal plateau",
               _run_plateau, PUBLISHED["plateau"], "plateau",
               notes=model + "Ideal plateau: argmin of the mean 95th percentile of G_TSR over "
               "G_ini <= G34. Fig. 16 (c_r = 0.5, plateau 1.06 vs 1.03) is a slice of the same "
               "map: the lower panels, p95 against the plateau per G_ini (G5 is the plateau "
               "counterpart of Fig. 13). It has no published numbers of its own.",
               quick="plateaus 0.98/1.02/1.06/1.10 x G_ini 5/15/25 x 21 starts instead of "
                     "0.96-1.12 step 0.01 x G0-G32 step 4 x 210 starts",
               aliases=("tsr-plateau",)),
    ]


#: Every table and figure of seed 004 (each covered by exactly one target).
ITEMS_004 = tuple([f"Fig. {i}" for i in range(1, 17)] + [f"Table {i}" for i in range(1, 5)])
TARGETS = _targets()
