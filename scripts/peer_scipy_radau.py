#!/usr/bin/env python3
"""The spring block against SciPy's solve_ivp(method="Radau") on the same equations (issue 6).

What a user would otherwise script: the spring-block ODEs (MODEL.md conventions, as slipfront
states them: the block's displacement x is measured from the initial equilibrium, where the
spring balances the initial traction -f0), y = (x, xdot, f_t, 1/R*), integrated by SciPy's
implicit Radau IIA method with an event at the first slip (plastic slip rate above the
threshold). Both tools are timed in one run of this script, and both are judged by the same
number: the relative error of the first slip onset against a reference computed here by an
independent method, SciPy's DOP853 (8th order) at rtol 1e-13, shown converged against rtol 1e-12.

Usage (from the repository root, after `cargo build --release`):

    python3 -m pip install scipy numpy
    python3 scripts/peer_scipy_radau.py

Wall times are medians of 3 runs; slipfront's include the process start and the event CSV,
SciPy's the integration only.
"""

import csv
import math
import statistics
import subprocess
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

ROOT = Path(__file__).resolve().parent.parent
BINARY = ROOT / "target" / "release" / "slipfront"

# The shipped case (cases/spring_block.toml): Table 1 friction, k = 500 Pa/m, M = 1000 kg/m^2,
# sigma_n = 1000 Pa, v = 1 mm/s; slip threshold 10 v.
MU_S, MU_K, ALPHA, R, KAPPA, XI = 0.4, 0.2, 1e6, 100.0, 10.0, 0.1
MASS, K, V, F_N, F0, THRESHOLD = 1000.0, 500.0, 1e-3, 1000.0, 1e-7, 1e-2


def plastic_multiplier(y):
    xd, s, z = y[1], y[2], y[3]
    if s == 0.0:
        return 0.0
    sigma = math.copysign(1.0, s)
    mu_f = MU_K * F_N
    ratio = abs(s) / (mu_f * z)
    a = MU_K / MU_S
    numerator = -ALPHA * xd * sigma - XI * ratio * (1.0 - a * z) * mu_f
    denominator = ALPHA + R * (-math.log(ratio)) * z * mu_f - KAPPA * ratio * (z - 1.0) * mu_f
    return max(numerator / denominator, 0.0)


def rhs(t, y):
    lam = plastic_multiplier(y)
    sigma = math.copysign(1.0, y[2])
    a = MU_K / MU_S
    return [
        y[1],
        (K * (V * t - y[0]) + y[2] + F0) / MASS,
        -ALPHA * (y[1] + lam * sigma),
        -KAPPA * (y[3] - 1.0) * lam + XI * (1.0 - a * y[3]),
    ]


def slips(t, y):
    return plastic_multiplier(y) - THRESHOLD


slips.terminal = True
slips.direction = 1


def scipy_onset(rtol, method="Radau"):
    # atol per component: displacement, velocity, traction, structure.
    atol = np.array([1e-9, 1e-12, 1e-6, 1e-12]) * (rtol / 1e-9)
    started = time.perf_counter()
    solution = solve_ivp(rhs, (0.0, 1000.0), [0.0, 0.0, -F0, 2.0], method=method, rtol=rtol, atol=atol,
                         events=slips)
    wall = time.perf_counter() - started
    onset = solution.t_events[0][0] if len(solution.t_events[0]) else float("nan")
    return onset, wall, solution.nfev


def slipfront_onset(settings):
    with tempfile.TemporaryDirectory() as out:
        events = Path(out) / "events.csv"
        overrides = [arg for setting in settings for arg in ("--set", setting)]
        started = time.perf_counter()
        subprocess.run([str(BINARY), "run", str(ROOT / "cases" / "spring_block.toml"), "--quiet", "--no-rrd",
                        "--set", "time.t_end=800", *overrides, "--out-dir", out, "--events", str(events)],
                       check=True)
        wall = time.perf_counter() - started
        with events.open() as f:
            onset = float(next(csv.DictReader(f))["onset_s"])
    return onset, wall


def median_of_3(run):
    results = [run() for _ in range(3)]
    return results[-1][0], statistics.median(r[1] for r in results), results[-1][2:]


def main():
    if not BINARY.exists():
        raise SystemExit(f"{BINARY} is missing: run `cargo build --release` first")
    reference, _, _ = scipy_onset(1e-13, "DOP853")
    check, _, _ = scipy_onset(1e-12, "DOP853")
    print(f"reference first onset: {reference:.9f} s (DOP853, rtol 1e-13); at rtol 1e-12 {check:.9f} s, "
          f"relative difference {abs(check - reference) / reference:.1e}")
    print()
    rows = []
    for rtol in [1e-5, 1e-6, 1e-7, 1e-8, 1e-9]:
        onset, wall, (nfev,) = median_of_3(lambda: scipy_onset(rtol))
        rows.append(("SciPy Radau", f"rtol = {rtol:g}", onset, wall, f"{nfev} rhs evaluations"))
    for dt in [0.02, 0.01, 0.005, 0.002]:
        onset, wall, _ = median_of_3(lambda: (*slipfront_onset([f"time.dt={dt}"]),))
        rows.append(("slipfront Wilson-θ", f"dt = {dt} s", onset, wall, f"{round(800 / dt)} steps"))
    for tolerance in [1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13]:
        settings = ["time.integrator=tsit5", f"time.tolerance={tolerance:g}"]
        onset, wall, _ = median_of_3(lambda: (*slipfront_onset(settings),))
        rows.append(("slipfront Tsit5", f"tolerance = {tolerance:g}", onset, wall, "adaptive"))
    print("| solver | setting | first onset (s) | relative error | wall (s), median of 3 | work |")
    print("|---|---|---|---|---|---|")
    for solver, setting, onset, wall, work in rows:
        error = abs(onset - reference) / reference
        print(f"| {solver} | {setting} | {onset:.9f} | {error:.2e} | {wall:.3f} | {work} |")
    # Speed-up at equal accuracy: for each slipfront row, the fastest SciPy row at least as accurate.
    print()
    for solver, setting, onset, wall, _ in rows:
        if not solver.startswith("slipfront"):
            continue
        error = abs(onset - reference) / reference
        peers = [r for r in rows if r[0].startswith("SciPy") and abs(r[2] - reference) / reference <= error]
        if peers:
            best = min(peers, key=lambda r: r[3])
            print(f"{solver} {setting} (error {error:.1e}): SciPy needs {best[1]} and {best[3]:.3f} s, "
                  f"{best[3] / wall:.1f}x slipfront's {wall:.3f} s")
        else:
            most = min((r for r in rows if r[0].startswith("SciPy")), key=lambda r: abs(r[2] - reference))
            print(f"{solver} {setting} (error {error:.1e}): no SciPy row is as accurate; its most accurate, "
                  f"{most[1]} ({abs(most[2] - reference) / reference:.1e}), takes {most[3]:.3f} s, "
                  f"{most[3] / wall:.1f}x slipfront's {wall:.3f} s")


if __name__ == "__main__":
    main()
