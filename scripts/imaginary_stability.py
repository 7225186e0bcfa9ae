#!/usr/bin/env python3
"""How long a step explicit Runge–Kutta pairs may take through the paper case's stick.

The block and its contact springs are undamped: their modes have eigenvalues ±iω, and an
explicit pair multiplies a mode's amplitude by |R(iy)| per step, y = hω. slipfront bounds
Tsitouras' pair's steps so that no mode grows more than 2× over 1000 s
(`slipfront::dynamics::rate_form::tsit5::bounded_growth`). This script applies the same bound
to pairs whose tableaus SciPy ships (Dormand–Prince 5(4), `RK45`; Hairer's DOP853), computing
R(z) = 1 + z bᵀ (I - zA)⁻¹ 1 from the tableau, and prints the largest y and y per evaluation of
the right-hand side, for the paper case's highest frequency, 45 rad/s.

Usage: python3 scripts/imaginary_stability.py
"""

import numpy as np
from scipy.integrate._ivp import dop853_coefficients as dop853
from scipy.integrate._ivp.rk import RK45

OMEGA, SPAN, GROWTH = 45.0, 1000.0, 2.0


def amplification(a, b, y):
    stages = len(b)
    return abs(1 + 1j * y * b @ np.linalg.solve(np.eye(stages) - 1j * y * a, np.ones(stages)))


def bounded_growth(a, b):
    """The largest y below which ln|R(iy)| · SPAN ω / y ≤ ln GROWTH holds everywhere."""
    largest = 0.0
    for y in np.arange(1e-3, 12.0, 1e-3):
        if np.log(amplification(a, b, y)) * SPAN * OMEGA / y > np.log(GROWTH):
            break
        largest = y
    return largest


def main():
    rk45 = np.zeros((6, 6))
    rk45[:, :5] = RK45.A
    pairs = [
        ("Dormand-Prince 5(4) (RK45)", rk45, RK45.B, 6),
        ("DOP853", dop853.A[:12, :12], dop853.B, 12),
    ]
    for name, a, b, evaluations in pairs:
        y = bounded_growth(a, b)
        print(f"{name}: hω ≤ {y:.3f} ({evaluations} evaluations a step, {y / evaluations:.3f} each; "
              f"step {1e3 * y / OMEGA:.0f} ms at ω = {OMEGA:g} rad/s)")


if __name__ == "__main__":
    main()
