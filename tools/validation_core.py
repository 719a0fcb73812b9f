"""Compute the core-simulator rows of docs/VALIDATION.md (published vs computed).

Run: .venv/bin/python tools/validation_core.py > /tmp/rows.md  (prints a markdown table).
The same cases are asserted in tests/test_washer_000.py and tests/test_vub_004.py; issue 7's
reproduction report will generate this table from the studies package.
"""
import sys

import numpy as np

sys.path.insert(0, "tests")
import autobalance as ab  # noqa: E402
from autobalance.config import load_config  # noqa: E402
from autobalance.result import grade_G  # noqa: E402
from autobalance.simulate import simulate  # noqa: E402
from conftest import RPM, washer_000  # noqa: E402

W = 1000 * RPM
rows = []


def row(q, pub, comp, tol, ok, note):
    rows.append(f"| {q} | {pub} | {comp} | {tol} | {'yes' if ok else '**miss**'} | {note} |")


cfg = load_config("vub_jeffcott_004")
s = cfg.system
f_n = s.natural_frequencies[0] / 2 / np.pi
row("004 resonance [Hz]", "94.2", f"{f_n:.2f}", "±0.05", abs(f_n - 94.2) <= 0.05, "sqrt(k/M_t)")
g0 = grade_G(s.rotor.unbalance, s.total_mass, cfg.spin.nominal_speed)
row("004 initial unbalance G [mm/s]", "20", f"{g0:.2f}", "±0.5", abs(g0 - 20) <= 0.5, "ε = 19.3 µm at 167 Hz, mass M_t")
gb = grade_G(s.balancer.capacity, s.total_mass, cfg.spin.nominal_speed)
row("004 total ball unbalance G [mm/s]", "34", f"{gb:.2f}", "±0.5", abs(gb - 34) <= 0.5, "2 × 7.6 g at 35 mm")
e = 0.05 / 37.0
d32 = np.degrees(2 * 0.28 / e * 1e-4)
row("000 eq 32 Δα for f/r = 1e-4 [deg]", "2.4", f"{d32:.2f}", "±0.05", abs(d32 - 2.4) <= 0.05, "closed form 2(R/e)(f/r)")


def settle(c_i):
    sysm = washer_000(c_i=c_i)
    sim = simulate(sysm, ab.SpeedProfile.constant(W, 10.0),
                   initial=ab.InitialState(ball_angles=(np.radians(90), np.radians(150)), steady_state=True),
                   options=ab.SimOptions(save_dt=2e-3))
    k = np.nonzero(sim.amplitude > 0.05 * 0.025 / sysm.total_mass)[0]
    return sim.t[k[-1]], np.sort(np.degrees(np.angle(np.exp(1j * sim.alpha[-1]))))


t2, a2 = settle(2.0)
t7, _ = settle(7.1)
row("000 Fig. 5 final ball angles [deg]", "±120", f"{a2[0]:.2f}, {a2[1]:.2f}", "±0.5", np.allclose(np.abs(a2), 120, atol=0.5), "c_i = 2 1/s, gravity on")
row("000 Fig. 5 balancing time [s] (preset c_i = 2 1/s)", "≈1.5 (t < 250/ω = 2.4)", f"{t2:.2f}", "< 2.4", t2 < 2.4, "amplitude < 5 % of unbalanced; c_i = 2 chosen for Tables 1-2; paper's c_i unknown")
row("000 Fig. 5 balancing time [s] (c_i = 7.1 1/s)", "≈1.5 (t < 250/ω = 2.4)", f"{t7:.2f}", "< 2.4", t7 < 2.4, "same start, stiffer ball damping")

TAB = {
    (0.025, "constant"): (2.23, 4.6, 4.1, 8.0), (0.025, "linear"): (8.2, 4.9, 4.9, 7.6),
    (0.025, "harmonic"): (8.6, 5.1, 5.2, 6.0), (0.05, "constant"): (1.7, 8.5, 8.7, 7.0),
    (0.05, "linear"): (7.2, 9.2, 8.6, 8.0), (0.05, "harmonic"): (8.3, 9.9, 9.7, 5.5),
}
for (Me, law), (tf, xm, ym, rv) in TAB.items():
    sysm = washer_000(Me=Me, polar_inertia=0.532)
    d = sysm.balancer.contact_angle
    drive = ab.MotorDrive(law, 25.0, W, 25.0, hold_fraction=1.0 if law == "constant" else 0.99)
    S = simulate(sysm, drive, initial=ab.InitialState(ball_angles=(np.pi - d / 2 - 1e-3, np.pi + d / 2 + 1e-3)),
                 options=ab.SimOptions(save_dt=2e-3)).summary()
    tab = "1" if Me == 0.025 else "2"
    t_sim = S["time_to_final_speed_s"]
    note = {"constant": "B_z calibrated on Table 1 row" if Me == 0.025 else "larger unbalance can only slow the run-up with the same B_z",
            "linear": "t to 0.99 n_f; the printed law reaches 0.975 n_f at 8.2 s (closed form)",
            "harmonic": "printed law needs 34.6 s to reach 0.95 n_f (closed form): not reachable"}[law]
    ts = "not reached in 25 s" if t_sim is None else f"{t_sim:.2f}"
    okt = t_sim is not None and abs(t_sim - tf) <= 0.05 * tf
    row(f"000 Table {tab} {law} t_f [s]", f"{tf}", ts, "±5 %", okt, note)
    x = S["x_max_m"] * 1e3
    y = S["y_max_m"] * 1e3
    r = float(np.mean(np.abs(S["ball_revolutions"])))
    row(f"000 Table {tab} {law} x_max [mm]", f"{xm}", f"{x:.2f}", "±30 %", abs(x - xm) <= 0.3 * xm, "tolerance = sensitivity to unknown c_i")
    row(f"000 Table {tab} {law} y_max [mm]", f"{ym}", f"{y:.2f}", "±30 %", abs(y - ym) <= 0.3 * ym, "")
    row(f"000 Table {tab} {law} ball revolutions", f"{rv}", f"{r:.1f}", "±2.5", abs(r - rv) <= 2.5, "mean of the two balls, relative to the drum")

print("| quantity | published | computed | tolerance | ok | note |")
print("|---|---|---|---|---|---|")
print("\n".join(rows))
n_ok = sum("**miss**" not in r for r in rows)
print(f"\n{n_ok} of {len(rows)} reproduced within tolerance.")
