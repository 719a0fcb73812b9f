"""Figures of a simulated run and of the harmonic response table (matplotlib, Agg, no pyplot).

These functions only draw what they are given; no physics is computed here (unit conversions,
angle wrapping and decimation only). Layout of :func:`plot_simulation` follows 004 Fig. 4
(amplitude, "Ball position" and "COG location" graphs).
"""
from __future__ import annotations

import math

import numpy as np
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.figure import Figure

__all__ = ["MAX_POINTS", "plot_response", "plot_simulation"]

#: Largest number of samples drawn per curve; longer histories are decimated.
MAX_POINTS = 20_000

_SPEED_UNITS = {"Hz": 1.0 / (2.0 * math.pi), "rpm": 60.0 / (2.0 * math.pi), "rad/s": 1.0}
_BALL_COLOURS = ("tab:blue", "tab:orange", "tab:green", "tab:red", "tab:purple", "tab:brown",
                 "tab:pink", "tab:olive", "tab:cyan", "tab:gray")


# -- helpers -----------------------------------------------------------------------------------
def _new_figure(size) -> Figure:
    fig = Figure(figsize=size, layout="constrained")
    FigureCanvasAgg(fig)
    return fig


def _get(sim, name):
    v = getattr(sim, name, None)
    return None if v is None else np.asarray(v, dtype=float)


def _stride_index(n: int, max_points: int) -> np.ndarray:
    """Indices of a uniform sub-sample of n points with at most max_points, keeping the last."""
    if n <= max_points:
        return np.arange(n)
    step = math.ceil(n / (max_points - 1))
    idx = np.arange(0, n, step)
    return idx if idx[-1] == n - 1 else np.append(idx, n - 1)


def _minmax_decimate(t: np.ndarray, y: np.ndarray, max_points: int):
    """Keep the min and the max of each bin (in time order) so fast oscillations keep their
    envelope when thinned to <= max_points samples."""
    n = t.size
    if n <= max_points:
        return t, y
    nbins = max(max_points // 2, 1)
    edges = np.linspace(0, n, nbins + 1).astype(int)
    tt, yy = [], []
    for a, b in zip(edges[:-1], edges[1:]):
        if b <= a:
            continue
        seg = y[a:b]
        if not np.any(np.isfinite(seg)):
            continue
        i, j = a + int(np.nanargmin(seg)), a + int(np.nanargmax(seg))
        for k in sorted({i, j}):
            tt.append(t[k])
            yy.append(y[k])
    return np.asarray(tt), np.asarray(yy)


def _break_wraps(y: np.ndarray, period: float) -> np.ndarray:
    """Insert NaN where a wrapped angle jumps by more than half a period (no vertical streaks)."""
    y = np.array(y, dtype=float)
    if y.size > 1:
        jumps = np.abs(np.diff(y)) > 0.5 * period
        y[1:][jumps] = np.nan
    return y


def _note(ax, text: str):
    ax.text(0.5, 0.5, text, transform=ax.transAxes, ha="center", va="center", color="0.4",
            bbox=dict(fc="white", ec="0.7", pad=3))


# -- simulation figure -------------------------------------------------------------------------
def plot_simulation(sim: object, *, speed_unit: str = "rpm", grade_limit: float = 16.0,
                    max_points: int = MAX_POINTS, figsize: tuple[float, float] = (15.0, 10.0),
                    speed_factor: float | None = None,
                    grade_label: str | None = None) -> Figure:
    """Time histories, ball positions and COG location of one run (cf. 004 Fig. 4).

    Parameters
    ----------
    sim : object
        Result with numpy-array attributes ``t`` [s] (n,), ``x``, ``y`` [m] (n,) inertial rotor
        displacement, ``amplitude`` [m] (n,), ``alpha`` [rad] (n, N) ball angles relative to the
        unbalance, ``speed`` [rad/s] (n,), ``grade_G`` [mm/s] (n,), ``residual_unbalance``
        [kg*m] (n,), ``residual_angle`` [rad] (n,) and ``title`` (str). Missing attributes
        leave their panel empty with a note.
    speed_unit : str
        Unit of the spin-speed twin axis: "rpm", "Hz" or "rad/s"; any label with
        ``speed_factor``.
    grade_limit : float
        ISO 1940 grade drawn dashed in the grade and COG panels [mm/s] (004: G16).
    max_points : int
        Longest drawn history; longer ones are decimated (min/max per bin for x, y).
    figsize : tuple of float
        Figure size [inch].
    speed_factor : float, optional
        Spin speed in ``speed_unit`` per rad/s [speed_unit / (rad/s)], e.g. from
        :meth:`autobalance.config.display.DisplayUnits.factor`; None: from ``speed_unit``.
    grade_label : str, optional
        Legend text of the grade limit line (default ``"ISO G<grade_limit>"``).

    Returns
    -------
    matplotlib.figure.Figure
        Attached to an Agg canvas; ``fig.savefig("run.png")`` works without pyplot.
    """
    if speed_factor is None and speed_unit not in _SPEED_UNITS:
        raise ValueError(f"speed_unit = {speed_unit!r}: must be one of {sorted(_SPEED_UNITS)}")
    if speed_factor is not None and not (math.isfinite(speed_factor) and speed_factor > 0):
        raise ValueError(f"speed_factor = {speed_factor!r}: must be a finite number > 0")
    factor = _SPEED_UNITS[speed_unit] if speed_factor is None else float(speed_factor)
    label = grade_label or f"ISO G{grade_limit:g}"
    t = _get(sim, "t")
    if t is None or t.ndim != 1 or t.size == 0:
        raise ValueError("sim.t: must be a non-empty 1-D array of times [s]")
    n = t.size
    idx = _stride_index(n, max_points)
    ts = t[idx]

    fig = _new_figure(figsize)
    title = getattr(sim, "title", "") or ""
    if title:
        fig.suptitle(str(title), fontsize=13)
    ax_x, ax_y, ax_amp, ax_ang, ax_g, ax_balls, ax_cog = _simulation_axes(fig)
    _draw_displacements(sim, ax_x, ax_y, t, max_points)
    _draw_amplitude(sim, ax_amp, ts, idx, n, speed_unit, factor)
    alpha, n_balls = _ball_angles(sim, n)
    _draw_ball_angles(ax_ang, alpha, n_balls, ts, idx)
    grade = _get(sim, "grade_G")
    _draw_grade(ax_g, grade, ts, idx, n, grade_limit, label)
    liquid = getattr(sim, "liquid", None)
    if liquid is not None and grade is not None and grade.size == n:
        # balls beside a liquid: the liquid's synchronous moment alone, as a grade
        from ..physics.iso1940 import grade_value

        g_liq = grade_value(np.abs(liquid.synchronous_unbalance), sim.system.total_mass,
                            sim.spin.nominal_speed)
        ax_g.plot(ts, g_liq[idx], color="tab:blue", lw=0.9, ls="-.",
                  label="the liquid's moment alone")
        ax_g.legend(loc="upper right", fontsize=8)
    for ax in (ax_x, ax_y, ax_amp, ax_ang):
        ax.tick_params(labelbottom=False)
    for ax in (ax_x, ax_y, ax_amp, ax_ang, ax_g):
        ax.grid(True, alpha=0.3)
    ax_g.set_xlim(float(t[0]), float(t[-1]) if t[-1] > t[0] else float(t[0]) + 1.0)
    _draw_ball_polar(ax_balls, alpha, n_balls, ts, idx, t)
    _draw_cog(ax_cog, grade, _get(sim, "residual_angle"), idx, n, grade_limit, label)
    return fig


def _simulation_axes(fig):
    """The seven panels of :func:`plot_simulation`: x, y, amplitude, ball angle and grade
    against time on the left (shared time axis), ball positions and COG location (polar) on the
    right."""
    gs = fig.add_gridspec(1, 2, width_ratios=(1.6, 1.0))
    left = gs[0].subgridspec(5, 1)
    right = gs[1].subgridspec(2, 1)
    ax_x = fig.add_subplot(left[0])
    ax_y = fig.add_subplot(left[1], sharex=ax_x)
    ax_amp = fig.add_subplot(left[2], sharex=ax_x)
    ax_ang = fig.add_subplot(left[3], sharex=ax_x)
    ax_g = fig.add_subplot(left[4], sharex=ax_x)
    ax_balls = fig.add_subplot(right[0], projection="polar")
    ax_cog = fig.add_subplot(right[1], projection="polar")
    return ax_x, ax_y, ax_amp, ax_ang, ax_g, ax_balls, ax_cog


def _draw_displacements(sim, ax_x, ax_y, t, max_points):
    """x and y [mm], one panel each (they are bands at the spin frequency; min/max decimated)."""
    n = t.size
    for ax, name, colour in ((ax_x, "x", "tab:blue"), (ax_y, "y", "tab:orange")):
        v = _get(sim, name)
        if v is not None and v.size == n:
            tt, vv = _minmax_decimate(t, 1e3 * v, max_points)
            ax.plot(tt, vv, lw=0.6, color=colour)
        else:
            _note(ax, f"no {name} history")
        ax.set_ylabel(f"{name} [mm]")
    ax_x.set_title("Rotor displacement (inertial frame, from static equilibrium)",
                   fontsize=10, loc="left")


def _draw_amplitude(sim, ax_amp, ts, idx, n, speed_unit, factor):
    """Amplitude envelope [mm] and the spin speed [speed_unit] (``factor`` per rad/s) on a
    twin axis."""
    amp = _get(sim, "amplitude")
    if amp is not None and amp.size == n:
        ax_amp.plot(ts, 1e3 * amp[idx], color="k", lw=1.0, label="amplitude")
    else:
        _note(ax_amp, "no amplitude history")
    ax_amp.set_ylabel("amplitude [mm]")
    ax_amp.set_ylim(bottom=0.0)
    ax_amp.set_title("Vibration amplitude and spin speed", fontsize=10, loc="left")
    speed = _get(sim, "speed")
    if speed is not None and speed.size == n:
        ax_sp = ax_amp.twinx()
        ax_sp.plot(ts, factor * speed[idx], color="tab:green", lw=1.0, ls="--")
        ax_sp.set_ylabel(f"spin speed [{speed_unit}]", color="tab:green")
        ax_sp.tick_params(axis="y", colors="tab:green")
        ax_sp.set_ylim(bottom=0.0)


def _ball_angles(sim, n):
    """Ball angles [rad] as an (n, N) array and N (0 when missing or of the wrong length)."""
    alpha = _get(sim, "alpha")
    if alpha is not None and alpha.ndim == 1 and alpha.size == n:
        alpha = alpha[:, None]
    n_balls = 0 if alpha is None or alpha.ndim != 2 or alpha.shape[0] != n else alpha.shape[1]
    return alpha, n_balls


def _draw_ball_angles(ax_ang, alpha, n_balls, ts, idx):
    """Ball angles [deg], wrapped to [0, 360)."""
    for i in range(n_balls):
        deg = np.degrees(np.mod(alpha[idx, i], 2.0 * np.pi))
        ax_ang.plot(ts, _break_wraps(deg, 360.0), lw=1.0,
                    color=_BALL_COLOURS[i % len(_BALL_COLOURS)], label=f"ball {i + 1}")
    ax_ang.set_ylim(0.0, 360.0)
    ax_ang.set_yticks([0, 90, 180, 270, 360])
    if n_balls:
        ax_ang.axhline(180.0, color="0.6", lw=0.8, ls=":")
        if n_balls <= 6:
            ax_ang.legend(loc="upper right", fontsize=8, ncols=min(n_balls, 3))
    else:
        _note(ax_ang, "no balls (N = 0)")
    ax_ang.set_ylabel("ball angle α [deg]")
    ax_ang.set_title("Ball positions relative to the unbalance (180° = opposite)",
                     fontsize=10, loc="left")


def _draw_grade(ax_g, grade, ts, idx, n, grade_limit, label):
    """Grade G [mm/s] with the ISO limit [mm/s] dashed (legend ``label``)."""
    if grade is not None and grade.size == n:
        ax_g.plot(ts, grade[idx], color="k", lw=1.0, label="residual unbalance")
        ax_g.set_ylim(0.0, max(1.2 * float(np.nanmax(grade)) if np.any(np.isfinite(grade)) else 0.0,
                               1.5 * grade_limit))
    else:
        _note(ax_g, "no grade history")
    ax_g.axhline(grade_limit, color="tab:red", ls="--", lw=1.0, label=label)
    ax_g.legend(loc="upper right", fontsize=8)
    ax_g.set_ylabel("grade G [mm/s]")
    ax_g.set_xlabel("time t [s]")
    ax_g.set_title("Balance quality (ISO 1940)", fontsize=10, loc="left")


def _draw_ball_polar(ax_balls, alpha, n_balls, ts, idx, t):
    """Polar: ball positions, angle = alpha [rad], radius = time [s]; open circle start, dot end."""
    for i in range(n_balls):
        th = np.unwrap(alpha[idx, i])
        c = _BALL_COLOURS[i % len(_BALL_COLOURS)]
        ax_balls.plot(th, ts, color=c, lw=1.0, label=f"ball {i + 1}")
        ax_balls.plot(th[:1], ts[:1], "o", mfc="none", color=c, ms=6)
        ax_balls.plot(th[-1:], ts[-1:], "o", color=c, ms=6)
    if not n_balls:
        _note(ax_balls, "no balancer")
    ax_balls.set_title("Ball position (angle α from unbalance, radius = time [s])\n○ start  ● end",
                       fontsize=10)
    ax_balls.set_rlim(0.0, float(t[-1]) if t[-1] > 0 else 1.0)


def _draw_cog(ax_cog, grade, ang, idx, n, grade_limit, label):
    """Polar: COG location, angle = residual angle [rad], radius = grade G [mm/s], with the ISO
    limit [mm/s] as a dashed circle."""
    if grade is not None and ang is not None and grade.size == n and ang.size == n:
        th = np.unwrap(ang[idx])
        ax_cog.plot(th, grade[idx], color="k", lw=0.8)
        ax_cog.plot(th[:1], grade[idx][:1], "o", mfc="none", color="k", ms=7)
        ax_cog.plot(th[-1:], grade[idx][-1:], "o", color="k", ms=7)
        rmax = max(float(np.nanmax(grade)) if np.any(np.isfinite(grade)) else 0.0, grade_limit)
    else:
        _note(ax_cog, "no residual-unbalance history")
        rmax = grade_limit
    circ = np.linspace(0.0, 2.0 * np.pi, 361)
    ax_cog.plot(circ, np.full_like(circ, grade_limit), color="tab:red", ls="--", lw=1.0)
    ax_cog.set_rlim(0.0, 1.1 * rmax)
    ax_cog.set_title("COG location (angle from unbalance, radius = grade G [mm/s])\n"
                     f"○ start  ● end  red dashed: {label}", fontsize=10)


# -- response figure ---------------------------------------------------------------------------
def plot_response(table: dict, *, log_amplitude: bool = False, speed_unit: str = "rad/s",
                  figsize: tuple[float, float] = (10.0, 7.0)) -> Figure:
    """Amplitude and phase lag of the unbalance response versus spin speed, per axis.

    Parameters
    ----------
    table : dict
        Output of :func:`autobalance.physics.response_table`: "speed_rad_s" [rad/s],
        "amplitude_x_m", "amplitude_y_m" [m], "phase_x_rad", "phase_y_rad" [rad],
        "natural_frequencies_rad_s" [rad/s] (None entries are drawn as gaps).
    log_amplitude : bool
        Logarithmic amplitude axis.
    speed_unit : str
        Unit of the speed axis: rad/s, rpm or Hz.
    figsize : tuple of float
        Figure size [inch].

    Returns
    -------
    matplotlib.figure.Figure
    """
    f = _SPEED_UNITS.get(speed_unit)
    if f is None:
        raise ValueError(f"speed_unit = {speed_unit!r}: must be one of {', '.join(_SPEED_UNITS)}")

    def arr(key):
        return np.asarray([np.nan if v is None else v for v in table.get(key, [])], dtype=float)

    w = f * arr("speed_rad_s")
    fig = _new_figure(figsize)
    fig.suptitle(table.get("title", "Unbalance response (balls fixed)"), fontsize=12)
    ax_a = fig.add_subplot(2, 1, 1)
    ax_p = fig.add_subplot(2, 1, 2, sharex=ax_a)
    for axis, colour in (("x", "tab:blue"), ("y", "tab:orange")):
        a, p = arr(f"amplitude_{axis}_m"), arr(f"phase_{axis}_rad")
        if a.size == w.size and w.size:
            ax_a.plot(w, 1e3 * a, color=colour, lw=1.2, label=f"$a_{axis}$")
        if p.size == w.size and w.size:
            ax_p.plot(w, np.degrees(p), color=colour, lw=1.2, label=f"$\\varphi_{axis}$")
    wn = arr("natural_frequencies_rad_s")
    for axis, colour, v in zip(("x", "y"), ("tab:blue", "tab:orange"), wn):
        if np.isfinite(v):
            for ax in (ax_a, ax_p):
                ax.axvline(f * v, color=colour, ls=":", lw=1.0)
            ax_p.annotate(f"$\\omega_{axis}$ = {f * v:.4g} {speed_unit}\n"
                          f"({v / (2 * math.pi):.4g} Hz)",
                          xy=(f * v, 0.03), xycoords=("data", "axes fraction"), xytext=(3, 0),
                          textcoords="offset points", ha="left", va="bottom", fontsize=8,
                          color=colour, bbox=dict(fc="white", ec="none", alpha=0.8, pad=1))
    if log_amplitude:
        ax_a.set_yscale("log")
    else:
        ax_a.set_ylim(bottom=0.0)
    ax_a.set_ylabel("amplitude [mm]")
    ax_p.set_ylabel(r"phase lag $\varphi$ [deg]")
    ax_p.set_ylim(0.0, 180.0)
    ax_p.set_yticks([0, 45, 90, 135, 180])
    ax_p.set_xlabel(rf"spin speed $\omega$ [{speed_unit}]")
    top = ax_a.secondary_xaxis("top", functions=(lambda x: x / f / (2 * math.pi),
                                                 lambda hz: hz * 2 * math.pi * f))
    top.set_xlabel("spin speed [Hz]")
    for ax in (ax_a, ax_p):
        ax.grid(True, alpha=0.3)
        if ax.lines:
            ax.legend(loc="best", fontsize=8)
    ax_a.tick_params(labelbottom=False)
    if w.size and np.nanmax(w) > np.nanmin(w):
        ax_p.set_xlim(float(np.nanmin(w)), float(np.nanmax(w)))
    return fig
