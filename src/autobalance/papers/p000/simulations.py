"""Seed 000's simulation targets: two balls balancing at 1000 rpm (Fig. 5), the run-ups of
Tables 1-2 and Fig. 10-11, the constant-speed runs of Fig. 13, 16, 18 and Tables 3-4 (Fig. 19).
The runs and their rows are in :mod:`.runup` and :mod:`.washer`, the figures in
:mod:`autobalance.plotting.washer`; this module assembles each target's outcome.
"""
from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from ...validation.target import Context, Outcome
from . import runup as runup_000, washer as washer_000
from .data import dataset, histories, run_dict
from .published import SECTIONS
from .washer import RHOS_M

if TYPE_CHECKING:
    from collections.abc import Callable

__all__ = ["constant_speed_target", "run_fig10_11", "run_fig5", "run_table1_2", "run_table3_4"]


# -- Fig. 5 ------------------------------------------------------------------------------------
def run_fig5(ctx: Context) -> Outcome:
    """000 Fig. 5: two balls balancing the drum at 1000 rpm (c_i = 2 and 7.1 1/s).

    Parameters
    ----------
    ctx : Context
        Variant (the quick and full variants compute the same).
    """
    from ...plotting.washer import plot_time_histories

    d = runup_000.compute_fig5()
    rows = runup_000.compare_fig5(d, prefix="000-fig5")
    runs = [run_dict(d[c], f"c_i = {d[c]['c_i']:g} 1/s: balanced after {d[c]['balancing_time_s']:.2f} s")
            for c in d]
    fig = plot_time_histories(runs, "000 Fig. 5: two balls, Me = mR = 0.025 kg m, 1000 rpm (ours)")
    data = histories(d, balancing_time_c_i_2_s=d["c_i_2"]["balancing_time_s"],
                     balancing_time_c_i_7_1_s=d["c_i_7.1"]["balancing_time_s"])
    return Outcome(rows, {"fig5": fig}, data, "10 s at 1000 rpm from (90, 150) deg, c_i = 2 and 7.1 1/s.")

# -- Tables 1-2, Fig. 10-11 --------------------------------------------------------------------
def run_table1_2(ctx: Context) -> Outcome:
    """000 Tables 1-2: six run-ups to 1000 rpm (t_f [s], x_max, y_max [mm], revolutions).

    Parameters
    ----------
    ctx : Context
        Variant (the quick and full variants compute the same).
    """
    from ...plotting.washer import plot_published_vs_computed, plot_runups

    section = SECTIONS["000-table1-2"]
    d = runup_000.compute_tables(histories=True)
    rows = runup_000.compare_tables(d, prefix="000-table1-2")
    styles = {"constant": "-", "linear": "--", "harmonic": ":"}
    panels = [(f"Table {tab}: Me = mR = {Me:g} kg m",
               [{**d[(tab, law)], "label": law, "style": {"ls": styles[law]}} for law in runup_000.LAWS])
              for tab, Me in runup_000.TABLE_ME.items()]
    keys = list(d)
    labels = [f"T{tab} {law}" for tab, law in keys]
    cols = (("t_f_s", "t_f [s]", 1.0, "rel", 0.05), ("x_max_mm", "x_max [mm]", 1e3, "rel", 0.30),
            ("y_max_mm", "y_max [mm]", 1e3, "rel", 0.30), ("revolutions", "ball revolutions [-]", 1.0, "abs", 2.5))
    cmp_panels = []
    for col, lab, scale, kind, tol in cols:
        pub = np.array([section[f"table{tab}"][law][col] for tab, law in keys])
        src = col.replace("_mm", "_m")
        comp = np.array([np.nan if d[k][src] is None else d[k][src] * scale for k in keys])
        half = tol * pub if kind == "rel" else np.full(pub.shape, tol)
        cmp_panels.append({"title": lab, "ylabel": lab, "xlabel": "case", "labels": labels, "published": pub,
                           "computed": comp,
                           "lo": pub - half, "hi": pub + half})
    figs = {"table1_2_runups": plot_runups(panels, "000 Tables 1-2: run-ups to 1000 rpm, T0 = 25 N m (ours)",
                                           envelope=True),
            "table1_2_comparison": plot_published_vs_computed(cmp_panels, "000 Tables 1-2: published vs ours")}
    v = {}
    for col, _, scale, _, _ in cols:
        src = col.replace("_mm", "_m")
        v[col] = (("case",), [np.nan if d[k][src] is None else d[k][src] * scale for k in keys],
                  col.rsplit("_", 1)[-1] if col != "revolutions" else "1")
        v[f"published_{col}"] = (("case",), [section[f"table{tab}"][law][col] for tab, law in keys],
                                 col.rsplit("_", 1)[-1] if col != "revolutions" else "1")
    data = dataset(v, cases=", ".join(labels), t_f_nan="not reached within 25 s")
    return Outcome(rows, figs, data, "Six run-ups of 25 s (000 eq 15-18), balls together at the bottom.")


def run_fig10_11(ctx: Context) -> Outcome:
    """000 Fig. 10-11: run-ups under constant and linear torque, with and without the balls.

    Parameters
    ----------
    ctx : Context
        Variant (the quick and full variants compute the same).
    """
    from ...plotting.washer import plot_runups

    d = runup_000.compute_fig10_11()
    rows = runup_000.compare_fig10_11(d, prefix="000-fig10-11")
    nob = {"color": "0.55", "ls": "--"}
    panels = [(f"Fig. {fig}: {law} torque", [{**d[(law, False)], "label": "without balls", "style": nob},
                                              {**d[(law, True)], "label": "with balls", "style": {"color": "C0"}}])
              for fig, law in ((10, "constant"), (11, "linear"))]
    fig = plot_runups(panels, "000 Fig. 10-11: run-up to 1000 rpm, Me = 0.025 kg m (ours)")
    data = histories({f"{law}_{'balls' if b else 'no_balls'}": r for (law, b), r in d.items()})
    return Outcome(rows, {"fig10_11": fig}, data,
                   "Constant and linear torque (T0 = 25 N m), Me = 0.025 kg m, with and without the balls.")

# -- Fig. 13, 16, 18 ---------------------------------------------------------------------------
def constant_speed_target(target_id: str, compute: Callable[[], dict],
                          compare: Callable[..., list], label: str, title: str,
                          note: str) -> Callable[[Context], Outcome]:
    """The run of a constant-speed target (000 Fig. 13, 16, 18): compute, compare, one time-history
    figure and its data.

    Parameters
    ----------
    target_id : str
        Target id (= key prefix of its rows); the figure is named after its part after "000-".
    compute : callable() -> dict
        The run (:mod:`.washer`'s ``compute_*``).
    compare : callable(dict, prefix=str) -> list
        Its rows (:mod:`.washer`'s ``compare_*``).
    label : str
        Legend label of the run.
    title : str
        Figure title.
    note : str
        What the run did (the outcome's notes).
    """
    def run(ctx: Context) -> Outcome:
        from ...plotting.washer import plot_time_histories

        d = compute()
        rows = compare(d, prefix=target_id)
        fig = plot_time_histories([run_dict(d, label)], title)
        keep = ("amplitude_m", "residual_unbalance_kg_m", "rme", "ball_contacts")
        data = histories({"run": d}, **{k: d[k] for k in keep},
                         final_deviation_deg=", ".join(f"{v:.2f}" for v in np.degrees(d["deviation_rad"])))
        return Outcome(rows, {target_id.split("-", 1)[1]: fig}, data, note)
    return run

# -- Tables 3-4, Fig. 19 -----------------------------------------------------------------------
def run_table3_4(ctx: Context) -> Outcome:
    """000 Tables 3-4 and Fig. 19: eccentricity and rolling resistance together at 100 rad/s.

    Parameters
    ----------
    ctx : Context
        Variant (the quick and full variants compute the same).
    """
    from ...plotting.washer import plot_published_vs_computed, plot_time_histories

    d = {3: washer_000.compute_table(3), 4: washer_000.compute_table(4, histories=True)}
    rows = []
    for k in (3, 4):
        rows += washer_000.compare_table(k, d[k], prefix=f"000-table3-4/table{k}")
    labels = [f"{r * 1e3:g}" for r in RHOS_M]
    panels = []
    v = {"rho": (("rho",), RHOS_M, "m")}
    for k in (3, 4):
        pub = SECTIONS["000-table3-4"][f"table{k}"]
        acc = [washer_000.acceptance(d[k][r]["band"]) for r in RHOS_M]
        for col, lab, comp, lo_hi in (
                ("d_alpha1_deg", "d_alpha1 [deg]", [abs(math.degrees(d[k][r]["deviation_rad"][0])) for r in RHOS_M],
                 [a["d_alpha_deg"][0] for a in acc]),
                ("d_alpha2_deg", "d_alpha2 [deg]", [abs(math.degrees(d[k][r]["deviation_rad"][1])) for r in RHOS_M],
                 [a["d_alpha_deg"][1] for a in acc]),
                ("RMe_pct", "RMe [%]", [100 * d[k][r]["rme"] for r in RHOS_M], [100 * a["rme"] for a in acc]),
                ("A_mm", "A [mm]", [1e3 * d[k][r]["amplitude_m"] for r in RHOS_M],
                 [1e3 * a["amplitude_m"] for a in acc])):
            p = [pub[washer_000.rho_key(r)][col] for r in RHOS_M]
            lo_hi = np.array(lo_hi)
            panels.append({"title": f"Table {k} (f = 1e-{k} r): {lab}", "ylabel": lab, "xlabel": "rho [mm]",
                           "labels": labels, "published": p, "computed": comp,
                           "lo": lo_hi[:, 0], "hi": lo_hi[:, 1]})
            unit = col.rsplit("_", 1)[-1]
            v[f"table{k}_{col}"] = (("rho",), comp, unit)
            v[f"table{k}_{col}_published"] = (("rho",), p, unit)
            v[f"table{k}_{col}_lo"] = (("rho",), lo_hi[:, 0], unit)
            v[f"table{k}_{col}_hi"] = (("rho",), lo_hi[:, 1], unit)
    f19 = d[4][0.5e-3]
    figs = {"table3_4_comparison": plot_published_vs_computed(
                panels, "000 Tables 3-4: published vs ours (grey: our dead band about our equilibrium)", ncols=4),
            "fig19": plot_time_histories([run_dict(f19, "rho = 0.5 mm, beta = pi/2, f = 1e-4 r")],
                                         "000 Fig. 19: Me = mR = 0.05 kg m, w = 100 rad/s, gravity (ours)")}
    for name in ("t", "x", "y", "alpha"):
        u = "s" if name == "t" else ("rad" if name == "alpha" else "m")
        dims = ("time_fig19", "ball") if name == "alpha" else ("time_fig19",)
        v[f"fig19_{name}"] = (dims, f19[f"{name}_s" if name == "t" else f"{name}_{u}"], u)
    data = dataset(v, speed_rad_s=100.0, Me_kg_m=0.05, beta_rad=math.pi / 2)
    return Outcome(rows, figs, data, "10 runs of 12 s at 100 rad/s (rho = 0-1 mm, f = 1e-3 r and 1e-4 r), "
                   "gravity on; Fig. 19 is the Table 4 run with rho = 0.5 mm.")
