"""Why implicit Euler is left out of the van der Pol work-precision sweep (examples/stiff_suite.rs).

Van der Pol, x' = v, v' = mu (1 - x^2) v - x, mu = 1000, from (2, 0) to t = 2000 (problem VDPOLM of
the Bari test set; reference x(2000) = 1.706167732170469). The exact solution changes sign at
t = 807.08 and 1614.29 (SciPy Radau, rtol = atol = 1e-10, events on x = 0). Implicit Euler with
Newton's method (converged to 1e-12) at each dt of the old sweep prints where its x changes sign
and where it ends: late, never, or with spurious sign changes, so its final error says which
branch of the cycle it ends on, not how fast it converges.

    python3 scripts/vdp_implicit_euler.py 0.1 0.03 0.01 0.003 0.001   # ~3 minutes

Measured (2026-11-25): dt 0.1: x(2000) = 2.98, no sign change; 0.03: -3.92, [808.26];
0.01: -2.55, [826.14]; 0.003: -3.92, [844.5, 1039.1, 1267.7, 1476.8, 1667.9];
0.001: -1.13, [807.08, 1205.79, 1616.20].
"""
import sys

import numpy as np
from scipy.integrate import solve_ivp

MU = 1000.0


def f(y):
    return np.array([y[1], MU * (1 - y[0] ** 2) * y[1] - y[0]])


def jac(y):
    return np.array([[0.0, 1.0], [-2 * MU * y[0] * y[1] - 1, MU * (1 - y[0] ** 2)]])


def implicit_euler(dt):
    y = np.array([2.0, 0.0])
    crossings = []
    for k in range(int(round(2000 / dt))):
        z = y.copy()
        for _ in range(20):
            step = np.linalg.solve(np.eye(2) - dt * jac(z), z - y - dt * f(z))
            z -= step
            if abs(step).max() < 1e-12 * (1 + abs(z).max()):
                break
        if np.sign(z[0]) != np.sign(y[0]):
            crossings.append(round((k + 1) * dt, 3))
        y = z
    return y, crossings


def main():
    event = lambda t, y: y[0]
    exact = solve_ivp(lambda t, y: f(y), (0, 2000), [2, 0], method="Radau", rtol=1e-10,
                      atol=1e-10, jac=lambda t, y: jac(y), events=event)
    print("exact: sign changes at", exact.t_events[0], "x(2000) =", exact.y[0, -1])
    for dt in [float(a) for a in sys.argv[1:]]:
        y, crossings = implicit_euler(dt)
        print(f"implicit Euler dt = {dt}: x(2000) = {y[0]:.4f}, sign changes at {crossings}")


if __name__ == "__main__":
    main()
