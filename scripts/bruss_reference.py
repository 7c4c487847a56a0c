"""Reference solutions of the 2-D Brusselator benchmark (not run by CI), and the model shared with
scripts/scipy_bruss.py.

The problem is SciMLBenchmarks' BRUSS (Hairer & Wanner, Solving ODEs II, section IV.10) without
its source term, as in examples/brusselator.rs and peers/cvode/bruss.c: N x N cells, periodic,
x_i = i dx, y_j = j dx (i, j = 0 .. N-1), dx = 1/(N-1),

    du/dt = 1 + u^2 v - 4.4 u + alpha L(u) / dx^2,
    dv/dt = 3.4 u - u^2 v + alpha L(v) / dx^2,        alpha = 10,

L the periodic five-point Laplacian (w_E + w_W + w_N + w_S - 4 w), u(0) = 22 (y(1-y))^1.5,
v(0) = 27 (x(1-x))^1.5, t from 0 to 11.5. The state is every u, then every v, cell
k = i + N j (odyn's layout; a[j, i] after reshape(N, N)).

Reference: SciPy's Radau (N = 32) or BDF (larger N; `--method` overrides) at rtol = atol = 1e-12
with the analytic sparse Jacobian, written to /work/ref/bruss_<N>.csv (2 N^2 values, one per
line, %.17g). Cross-check: CVODE BDF + KLU (AMD ordering) at rtol = atol = 1e-12 through
peers/cvode/bruss, written beside it as bruss_<N>_cvode.csv; the script prints the two runs'
largest difference over max |ref|.

    pip install numpy scipy && make -C peers/cvode && \
        python3 scripts/bruss_reference.py [--n 32 64 128] [--method Radau|BDF] [--tol 1e-12]
"""

import argparse
import os
import subprocess
import time
import warnings

import numpy as np
import scipy
from scipy.integrate import BDF, Radau
from scipy.sparse import coo_matrix, csc_matrix

ALPHA = 10.0
T = 11.5
REF_DIR = "/work/ref"
HARNESS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "peers", "cvode", "bruss")


class Bruss:
    """The BRUSS right-hand side, its analytic sparse Jacobian and its sparsity on an n x n grid."""

    def __init__(self, n):
        self.n = n
        self.nn = n * n
        self.dx = 1.0 / (n - 1)
        self.c = ALPHA / self.dx**2
        self._build_pattern()

    def initial(self):
        s = np.arange(self.n) * self.dx
        x, y = np.meshgrid(s, s)  # x[j, i] = s[i], y[j, i] = s[j]
        u = 22.0 * (y * (1.0 - y)) ** 1.5
        v = 27.0 * (x * (1.0 - x)) ** 1.5
        return np.concatenate([u.ravel(), v.ravel()])

    @staticmethod
    def laplacian(a):
        # a[j, i]: axis 1 is i (east-west), axis 0 is j (north-south); np.roll wraps (periodic).
        return (np.roll(a, 1, 0) + np.roll(a, -1, 0) + np.roll(a, 1, 1) + np.roll(a, -1, 1)
                - 4.0 * a)

    def rate(self, _t, y):
        n, nn = self.n, self.nn
        u = y[:nn].reshape(n, n)
        v = y[nn:].reshape(n, n)
        uuv = u * u * v
        du = 1.0 + uuv - 4.4 * u + self.c * self.laplacian(u)
        dv = 3.4 * u - uuv + self.c * self.laplacian(v)
        return np.concatenate([du.ravel(), dv.ravel()])

    def _build_pattern(self):
        """The CSC structure of the Jacobian and where each kind of entry lands in its data.

        Entries: d(du_k)/du_k = 2uv - 4.4 - 4c, d(du_k)/dv_k = u^2, d(dv_k)/du_k = 3.4 - 2uv,
        d(dv_k)/dv_k = -u^2 - 4c, and c for each periodic neighbour m of k in both fields
        (d(du_k)/du_m, d(dv_k)/dv_m); 12 N^2 in all (N >= 3)."""
        n, nn = self.n, self.nn
        k = np.arange(nn)
        i, j = k % n, k // n
        east, west = (i + 1) % n + n * j, (i - 1) % n + n * j
        north, south = i + n * ((j + 1) % n), i + n * ((j - 1) % n)
        rows = [k, k, nn + k, nn + k]          # the 2 x 2 cell blocks: uu, uv, vu, vv
        cols = [k, nn + k, k, nn + k]
        for m in (east, west, north, south):   # the neighbours' diffusion
            rows += [k, nn + k]
            cols += [m, nn + m]
        rows, cols = np.concatenate(rows), np.concatenate(cols)
        order = np.arange(1, len(rows) + 1, dtype=float)
        mat = coo_matrix((order, (rows, cols)), shape=(2 * nn, 2 * nn)).tocsc()
        mat.sort_indices()
        assert mat.nnz == 12 * nn, "duplicate entries: N must be at least 3"
        where = np.empty(mat.nnz, dtype=np.int64)
        where[mat.data.astype(np.int64) - 1] = np.arange(mat.nnz)
        self.indices, self.indptr = mat.indices.copy(), mat.indptr.copy()
        self.pos_uu, self.pos_uv = where[0:nn], where[nn:2 * nn]
        self.pos_vu, self.pos_vv = where[2 * nn:3 * nn], where[3 * nn:4 * nn]
        self.base = np.full(mat.nnz, self.c)
        self.base[self.pos_uu] = -4.0 * self.c
        self.base[self.pos_vv] = -4.0 * self.c

    def jac(self, _t, y):
        nn = self.nn
        u, v = y[:nn], y[nn:]
        data = self.base.copy()
        data[self.pos_uu] += 2.0 * u * v - 4.4
        data[self.pos_uv] = u * u
        data[self.pos_vu] = 3.4 - 2.0 * u * v
        data[self.pos_vv] -= u * u
        return csc_matrix((data, self.indices, self.indptr), shape=(2 * nn, 2 * nn))

    def sparsity(self):
        return csc_matrix((np.ones(12 * self.nn), self.indices, self.indptr),
                          shape=(2 * self.nn, 2 * self.nn))


def integrate(model, method, rtol, atol, jac="analytic"):
    """Step SciPy's `method` (the solver class behind solve_ivp) from 0 to T without storing the
    steps; returns (final state, steps, nfev, njev, nlu, seconds). jac: "analytic" (the sparse
    Jacobian) or "sparsity" (jac_sparsity: grouped finite differences)."""
    extra = {"jac": model.jac} if jac == "analytic" else {"jac_sparsity": model.sparsity()}
    cls = {"BDF": BDF, "Radau": Radau}[method]
    start = time.perf_counter()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        solver = cls(model.rate, 0.0, model.initial(), T, rtol=rtol, atol=atol, **extra)
        steps = 0
        while solver.status == "running":
            message = solver.step()
            steps += 1
    seconds = time.perf_counter() - start
    if solver.status != "finished":
        raise RuntimeError(f"{method} failed at t = {solver.t}: {message}")
    return solver.y.copy(), steps, solver.nfev, solver.njev, solver.nlu, seconds


def cvode(n, rtol, atol, solver, out=None):
    """Run peers/cvode/bruss; returns its key=value line as a dict (and writes out if given)."""
    args = [HARNESS, str(n), repr(rtol), repr(atol), solver] + ([out] if out else [])
    line = subprocess.run(args, check=True, capture_output=True, text=True).stdout.strip()
    fields = dict(item.split("=", 1) for item in line.split())
    for key, value in fields.items():
        if key not in ("solver",):
            fields[key] = float(value)
    return fields


def relative_error(state, reference):
    return np.abs(state - reference).max() / np.abs(reference).max()


def check_jacobian(n=5):
    """The analytic Jacobian against central differences of the right-hand side."""
    model = Bruss(n)
    rng = np.random.default_rng(1)
    y = model.initial() + rng.uniform(0.1, 1.0, 2 * model.nn)
    jac = model.jac(0.0, y).toarray()
    fd = np.empty_like(jac)
    for col in range(2 * model.nn):
        h = 1e-6 * max(1.0, abs(y[col]))
        e = np.zeros_like(y)
        e[col] = h
        fd[:, col] = (model.rate(0.0, y + e) - model.rate(0.0, y - e)) / (2 * h)
    return np.abs(jac - fd).max() / np.abs(jac).max()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, nargs="+", default=[32, 64, 128])
    parser.add_argument("--method", choices=["Radau", "BDF"], default=None,
                        help="default: Radau for N <= 32, BDF above")
    parser.add_argument("--tol", type=float, default=1e-12)
    parser.add_argument("--no-cvode", action="store_true")
    args = parser.parse_args()
    print(f"scipy {scipy.__version__}, numpy {np.__version__}; BRUSS to t = {T}, "
          f"rtol = atol = {args.tol:g}")
    print(f"analytic Jacobian vs central differences (N = 5): {check_jacobian():.1e}")
    os.makedirs(REF_DIR, exist_ok=True)
    for n in args.n:
        model = Bruss(n)
        method = args.method or ("Radau" if n <= 32 else "BDF")
        y, steps, nfev, njev, nlu, seconds = integrate(model, method, args.tol, args.tol)
        path = os.path.join(REF_DIR, f"bruss_{n}.csv")
        np.savetxt(path, y, fmt="%.17g")
        nn = n * n
        print(f"N = {n}: SciPy {method} {seconds:.1f} s, {steps} steps, nfev {nfev}, "
              f"njev {njev}, nlu {nlu}; u in [{y[:nn].min():.6f}, {y[:nn].max():.6f}], "
              f"v in [{y[nn:].min():.6f}, {y[nn:].max():.6f}] -> {path}", flush=True)
        if args.no_cvode:
            continue
        out = os.path.join(REF_DIR, f"bruss_{n}_cvode.csv")
        stats = cvode(n, args.tol, args.tol, "klu-amd", out)
        diff = relative_error(np.loadtxt(out), y)
        print(f"N = {n}: CVODE KLU {stats['seconds']:.1f} s, {int(stats['steps'])} steps, "
              f"{int(stats['nsetups'])} LUs -> {out}; max |SciPy - CVODE| / max |ref| = "
              f"{diff:.2e}", flush=True)


if __name__ == "__main__":
    main()
