"""SciPy's DOP853 and RK45 at equal final error on odyn's adaptive benchmark problems (not run by CI).

The SciPy side of `peers/benches/adaptive.rs`: the same three problems, the same reference final
states (from scripts/reference_adaptive.py, Taylor series at 40-50 digits), the same calibration.

* Lorenz, sigma = 10, rho = 28, beta = 8.0/3.0 (f64), y(0) = (1, 0, 0), to t = 20;
* Arenstorf orbit (HNW I, Sec. II.0), mu = 0.012277471, one period t = 17.065216560157964;
* Pleiades (HNW I, Sec. II.10), 7 bodies, masses m_i = i, to t = 3.

For each method, rtol = atol is swept over 1e-3 ... 1e-13 in quarter decades and the final
max-norm error against the reference is recorded. For each target error (1e-6, 1e-9) the method's
configuration is the loosest tolerance whose error is at or below the target (a target it never
reaches is skipped). That configuration is then timed: best of 5 wall times (time.perf_counter) of
a whole solve_ivp call, with its default output (every accepted step, no dense output).

The right-hand sides are plain Python (NumPy for the 28-component Pleiades), as a SciPy user
writes them, so much of SciPy's time is the interpreter calling them.

    pip install numpy scipy && python3 scripts/scipy_adaptive.py
"""

import time

import numpy as np
import scipy
from scipy.integrate import solve_ivp

TARGETS = [1e-6, 1e-9]
TOLERANCES = [10.0 ** (-3 - k / 4) for k in range(41)]
METHODS = ["DOP853", "RK45"]
REPEATS = 5

# --------------------------------------------------------------------------------------------
# Problems: right-hand side, initial state, end time, reference y(t_end).
# --------------------------------------------------------------------------------------------

BETA = 8.0 / 3.0


def lorenz(t, y):
    x, yy, z = y
    return [10.0 * (yy - x), x * (28.0 - z) - yy, x * yy - BETA * z]


MU = 0.012277471
MUP = 1.0 - MU


def arenstorf(t, y):
    y1, y2, v1, v2 = y
    d1 = ((y1 + MU) ** 2 + y2 ** 2) ** 1.5
    d2 = ((y1 - MUP) ** 2 + y2 ** 2) ** 1.5
    return [v1, v2, y1 + 2 * v2 - MUP * (y1 + MU) / d1 - MU * (y1 - MUP) / d2,
            y2 - 2 * v1 - MUP * y2 / d1 - MU * y2 / d2]


MASSES = np.arange(1.0, 8.0)


def pleiades(t, y):
    x, yy, u, v = y[0:7], y[7:14], y[14:21], y[21:28]
    dx = x[None, :] - x[:, None]  # dx[i, j] = x_j - x_i
    dy = yy[None, :] - yy[:, None]
    r2 = dx * dx + dy * dy
    np.fill_diagonal(r2, 1.0)
    p = r2 ** -1.5
    np.fill_diagonal(p, 0.0)
    return np.concatenate([u, v, (dx * p) @ MASSES, (dy * p) @ MASSES])


PROBLEMS = [
    ("lorenz", lorenz, [1.0, 0.0, 0.0], 20.0,
     # [f64 beta] Taylor dps=50 at t = 20
     [-8.0211436133172160e+00, -1.1905464749171223e+01, 1.9856374858398645e+01]),
    ("arenstorf", arenstorf, [0.994, 0.0, 0.0, -2.0015851063790824], 17.065216560157964,
     # y(fl(T)) for the f64 data, Taylor dps=50
     [9.9399999999990885e-01, -3.0309430229824185e-13, -4.9285365810550526e-11,
      -2.0015851063932701e+00]),
    ("pleiades", pleiades,
     np.array([3, 3, -1, -3, 2, -2, 2, 3, -3, 2, 0, 0, -4, 4,
               0, 0, 0, 0, 0, 1.75, -1.5, 0, 0, 0, -1.25, 1, 0, 0], dtype=float), 3.0,
     # y(3), Taylor dps=44; layout (x1..x7, y1..y7, x1'..x7', y1'..y7')
     [3.7061391439705127e-01, 3.2372840920572332e+00, -3.2225590324183235e+00,
      6.5970914557753080e-01, 3.4255817071565797e-01, 1.5621721014006311e+00,
      -7.0030929222124949e-01, -3.9434375855173922e+00, -3.2713809739725499e+00,
      5.2250818434565440e+00, -2.5906124349774693e+00, 1.1982136933922747e+00,
      -2.4296823449358235e-01, 1.0914492404289797e+00, 3.4170038063143147e+00,
      1.3545845016255011e+00, -2.5900655978107756e+00, 2.0250537347142412e+00,
      -1.1558151001604491e+00, -8.0729881702230222e-01, 5.9523963542087188e-01,
      -3.7412449612340084e+00, 3.7734596857506292e-01, 9.3868588695510791e-01,
      3.6679222272005696e-01, -3.4740463538084942e-01, 2.3449154481809371e+00,
      -1.9470204342632920e+00]),
]


def solve(f, y0, t_end, method, tol):
    sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=tol, atol=tol)
    assert sol.success, sol.message
    return sol


def main():
    print(f"scipy {scipy.__version__}, numpy {np.__version__}")
    rows = []
    for name, f, y0, t_end, reference in PROBLEMS:
        reference = np.array(reference)
        for method in METHODS:
            sweep = []
            for tol in TOLERANCES:
                sol = solve(f, y0, t_end, method, tol)
                error = float(np.max(np.abs(sol.y[:, -1] - reference)))
                sweep.append((tol, error, len(sol.t) - 1, sol.nfev))
            for target in TARGETS:
                picks = [row for row in sweep if row[1] <= target]
                if not picks:
                    best = min(e for _, e, _, _ in sweep)
                    rows.append((name, target, method, None, best, None, None, None))
                    continue
                tol, error, steps, nfev = picks[0]
                times = []
                for _ in range(REPEATS):
                    start = time.perf_counter()
                    solve(f, y0, t_end, method, tol)
                    times.append(time.perf_counter() - start)
                rows.append((name, target, method, tol, error, steps, nfev, min(times)))

    print("\nloosest rtol = atol reaching each target; time = best of "
          f"{REPEATS} solve_ivp calls")
    print(f"{'problem':<10}{'target':>8}  {'method':<8}{'tol':>10}{'error':>10}"
          f"{'steps':>8}{'nfev':>8}{'time':>12}")
    for name, target, method, tol, error, steps, nfev, best in rows:
        if tol is None:
            print(f"{name:<10}{target:>8.0e}  {method:<8}  not reached (best error {error:.1e})")
        else:
            print(f"{name:<10}{target:>8.0e}  {method:<8}{tol:>10.2e}{error:>10.2e}"
                  f"{steps:>8}{nfev:>8}{best * 1e3:>10.2f} ms")


if __name__ == "__main__":
    main()
