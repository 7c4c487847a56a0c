"""SciPy's BDF (with `jac_sparsity`), RK45 and DOP853 on Gray-Scott at equal final error
(not run by CI): the SciPy side of the `equal_accuracy` group of `benches/gray_scott.rs`.

The problem is the bench's: Pearson's Gray-Scott (D_u = 2e-5, D_v = 1e-5, F = 0.0545,
k = 0.062, "coral") on a periodic 2.5 x 2.5 square of 64^2 cells with the five-point Laplacian,
u = 1, v = 0 except a central 4 x 4-cell square at (1/2, 1/4), no noise; t from 0 to 500. (On
128^2 cells one BDF solve took 30-50 s at rtol 1e-2, most of it in SuperLU and the
finite-difference Jacobian, so a sweep to the tight target took too long to be useful.)
The state is every u, then every v, cell k = j*n + i (odyn's layout).

Reference: DOP853 at rtol = atol = 1e-13, cross-checked (with --check) against Radau at rtol =
atol = 1e-10. Its probe values are printed for the Rust test `gray_scott_matches_scipy` in
tests/continua/grid/gray_scott.rs, which checks odyn's own reference (DOP853 at 1e-12, used
by the bench) against them.

Calibration as in scripts/scipy_stiff.py but in half decades: rtol swept over 1e-2 ... 1e-10 with
atol = rtol, error = the largest absolute difference from the reference over all components at
t = 500; for each target (1e-3, 1e-6) the loosest tolerance meeting it is timed, best of 3 wall
times of the whole solve_ivp call. BDF gets the exact sparsity pattern (`jac_sparsity`), from
which SciPy groups columns for finite-difference Jacobians and factorizes with SuperLU.

    pip install numpy scipy && python3 scripts/scipy_gray_scott.py [--check]
"""

import time
import warnings

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.sparse import coo_matrix

N = 64
DU, DV, F, K = 2e-5, 1e-5, 0.0545, 0.062
DX = 2.5 / N
T = 500.0
TARGETS = [1e-3, 1e-6]
TOLERANCES = [10.0 ** (-2 - k / 2) for k in range(17)]
METHODS = ["BDF", "RK45", "DOP853"]
REPEATS = 3


def initial():
    u = np.ones((N, N))
    v = np.zeros((N, N))
    r = N * 10 // 256
    lo, hi = N // 2 - r, N // 2 + r
    u[lo:hi, lo:hi] = 0.5
    v[lo:hi, lo:hi] = 0.25
    return np.concatenate([u.ravel(), v.ravel()])


def laplacian(a):
    # a[j, i]: rolling along axis 1 moves in i (east-west), along axis 0 in j (north-south).
    return (np.roll(a, 1, 0) + np.roll(a, -1, 0) + np.roll(a, 1, 1) + np.roll(a, -1, 1)
            - 4.0 * a)


def rate(_t, y):
    u = y[: N * N].reshape(N, N)
    v = y[N * N:].reshape(N, N)
    uvv = u * v * v
    du = DU * laplacian(u) / DX**2 - uvv + F * (1.0 - u)
    dv = DV * laplacian(v) / DX**2 + uvv - (F + K) * v
    return np.concatenate([du.ravel(), dv.ravel()])


def sparsity():
    rows, cols = [], []
    for j in range(N):
        for i in range(N):
            k = j * N + i
            neighbours = [k, j * N + (i + 1) % N, j * N + (i - 1) % N,
                          ((j + 1) % N) * N + i, ((j - 1) % N) * N + i]
            for field in (0, 1):
                for m in neighbours:
                    rows.append(field * N * N + k)
                    cols.append(field * N * N + m)
                rows.append(field * N * N + k)
                cols.append((1 - field) * N * N + k)
    data = np.ones(len(rows))
    return coo_matrix((data, (rows, cols)), shape=(2 * N * N, 2 * N * N)).tocsc()


def solve(method, rtol, atol, pattern):
    extra = {"jac_sparsity": pattern} if method in ("BDF", "Radau") else {}
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return solve_ivp(rate, (0.0, T), initial(), method=method, rtol=rtol, atol=atol,
                         t_eval=[T], **extra)


def main():
    print(f"scipy {scipy.__version__}, numpy {np.__version__}; Gray-Scott {N}^2, t = {T}")
    pattern = sparsity()
    reference = solve("DOP853", 1e-13, 1e-13, None).y[:, -1]
    if "--check" in __import__("sys").argv:
        check = solve("Radau", 1e-10, 1e-10, pattern).y[:, -1]
        print(f"Radau 1e-10 differs from the reference by {np.abs(check - reference).max():.2e}")
    probes = [0, N * N // 2 + N // 2, N * N // 2 + N // 2 + 7, N * N + N * N // 2 + N // 2,
              N * N + N * N // 2 + N // 2 + 7]
    print("probes (index, value):", [(k, float(f"{reference[k]:.15e}")) for k in probes])
    print(f"mean u {reference[:N * N].mean():.15e}, mean v {reference[N * N:].mean():.15e}")
    print(f"{'target':>6} {'method':<6} {'rtol':>9} {'error':>9} {'nfev':>6} {'njev':>5} "
          f"{'nlu':>5} {'time [s]':>9}")
    for method in METHODS:
        chosen = {}
        for rtol in TOLERANCES:
            start = time.perf_counter()
            solution = solve(method, rtol, rtol, pattern)
            if not solution.success:
                continue
            error = np.abs(solution.y[:, -1] - reference).max()
            print(f"  sweep {method} rtol {rtol:.2e}: error {error:.2e}, nfev {solution.nfev}, "
                  f"{time.perf_counter() - start:.1f} s", flush=True)
            for target in TARGETS:
                if target not in chosen and error <= target:
                    chosen[target] = (rtol, error, solution)
            if len(chosen) == len(TARGETS):
                break
        for target in TARGETS:
            if target not in chosen:
                print(f"{target:>6.0e} {method:<6} does not reach the target")
                continue
            rtol, error, solution = chosen[target]
            best = min(timed(method, rtol, pattern) for _ in range(REPEATS))
            print(f"{target:>6.0e} {method:<6} {rtol:>9.2e} {error:>9.2e} {solution.nfev:>6} "
                  f"{solution.njev:>5} {solution.nlu:>5} {best:>9.3f}")


def timed(method, rtol, pattern):
    start = time.perf_counter()
    solve(method, rtol, rtol, pattern)
    return time.perf_counter() - start


if __name__ == "__main__":
    main()
