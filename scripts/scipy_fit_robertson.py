"""The `fit_robertson` example done the usual Python way, end to end: SciPy's `least_squares`
driving `solve_ivp`, on the same data, weights, guess and search variables (ln k), so the two fits
land on the same minimum and their times compare at equal accuracy.

Runs the example (target/release/examples/fit_robertson: build it with `cargo build --release
--example fit_robertson`), which writes the data to out/fit_robertson/fit.csv and prints its
fit's parameters and wall time (best of 5); then fits the same data with least_squares (method
"lm", MINPACK's Levenberg–Marquardt, and "trf"; the residuals' Jacobian by their default forward
differences) on solve_ivp (BDF and Radau with the analytic Jacobian, rtol 1e-8, atol 1e-16, as
the example's fit), and prints each run's parameters, cost, solves, wall time (best of 3), its
agreement with odyn's parameters and the time ratio. Not part of CI.
"""

import csv
import re
import subprocess
import time

import numpy as np
from scipy.integrate import solve_ivp
from scipy.optimize import least_squares


def rhs(t, y, k1, k2, k3):
    a, b, c = y
    return [-k1 * a + k2 * b * c, k1 * a - k2 * b * c - k3 * b * b, k3 * b * b]


def jac(t, y, k1, k2, k3):
    a, b, c = y
    return [[-k1, k2 * c, k2 * b], [k1, -k2 * c - 2 * k3 * b, -k2 * b], [0.0, 2 * k3 * b, 0.0]]


def load(path):
    times, values = [], {"a": [], "b": [], "c": []}
    with open(path) as f:
        for row in csv.DictReader(f):
            t = float(row["t"])
            if not times or times[-1] != t:
                times.append(t)
            values[row["species"]].append(float(row["data"]))
    return np.array(times), np.array([values["a"], values["b"], values["c"]])


def fit(times, data, method, solver):
    weights = 1.0 / (0.01 * np.abs(data))
    solves = [0]

    def residuals(q):
        solves[0] += 1
        k = np.exp(q)
        sol = solve_ivp(rhs, (0.0, times[-1]), [1.0, 0.0, 0.0], method=solver, t_eval=times,
                        args=tuple(k), jac=jac, rtol=1e-8, atol=1e-16)
        if not sol.success:
            raise RuntimeError(sol.message)
        return ((sol.y - data) * weights).ravel()

    q0 = np.log([0.01, 1e5, 1e6])
    result = least_squares(residuals, q0, method=method)
    return np.exp(result.x), result.cost, solves[0], result


def odyn_fit():
    out = subprocess.run(["target/release/examples/fit_robertson"], check=True, capture_output=True,
                         text=True).stdout
    print(out.strip())
    seconds = float(re.search(r"in ([0-9.]+) ms", out).group(1)) / 1e3
    k = [float(re.search(rf"^\s*k{j}\s+\S+\s+\S+\s+(\S+)", out, re.M).group(1)) for j in (1, 2, 3)]
    return k, seconds


def main():
    odyn, odyn_seconds = odyn_fit()
    times, data = load("out/fit_robertson/fit.csv")
    for method in ["lm", "trf"]:
        for solver in ["BDF", "Radau"]:
            best = float("inf")
            for _ in range(3):
                start = time.perf_counter()
                k, cost, solves, result = fit(times, data, method, solver)
                best = min(best, time.perf_counter() - start)
            line = (f"{method:>3} {solver:>5}: k = {k[0]:.6e} {k[1]:.6e} {k[2]:.6e}, cost {cost:.4f}, "
                    f"{solves} solves, {result.nfev} fev, best of 3 {best:.3f} s")
            agree = max(abs(k[j] / odyn[j] - 1.0) for j in range(3))
            line += f", max |k/k_odyn - 1| = {agree:.1e}, {best / odyn_seconds:.0f}x odyn's time"
            print(line)


if __name__ == "__main__":
    main()
