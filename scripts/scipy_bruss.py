"""SciPy's BDF and SUNDIALS CVODE on the 2-D Brusselator at equal final error (not run by CI):
the reference anchors of odyn's Brusselator benchmark.

The problem is scripts/bruss_reference.py's (SciMLBenchmarks' BRUSS without its source term,
N x N periodic cells, alpha = 10, t from 0 to 11.5, 2 N^2 unknowns); the references are its
files /work/ref/bruss_<N>.csv (SciPy Radau or BDF at rtol = atol = 1e-12, cross-checked against
CVODE).

Tools:
  scipy-bdf-sparsity  scipy.integrate.BDF with jac_sparsity (grouped finite-difference
                      Jacobians, SuperLU);
  scipy-bdf-jac       scipy.integrate.BDF with the analytic sparse Jacobian;
  cvode-klu           peers/cvode/bruss ... klu: CVODE BDF, analytic CSC Jacobian, KLU with
                      SUNDIALS' default ordering (COLAMD);
  cvode-klu-amd       the same with KLU's AMD ordering;
  cvode-spgmr         CVODE BDF, SPGMR right-preconditioned by the 2 x 2 block-Jacobi matrix,
                      maxl = 2N, analytic Jacobian-vector products (why: peers/cvode/bruss.c).
The SciPy solvers are the classes behind solve_ivp, stepped to t = 11.5 without storing steps
(so that steps can be counted); the time covers construction and stepping. CVODE's time is
the harness's own (the CVode call alone).

Calibration: rtol = atol swept over 1e-3, 3e-4, 1e-4, ..., 3e-10, 1e-10 from the loosest; error
= max |y - ref| over u and v at t = 11.5 over max |ref|; the tool's configuration is the
loosest tolerance whose error is at most 1e-6 (the sweep stops there). That run is timed again:
best of 3 wall times when it took under 10 s, else the sweep's one. cvode-klu integrates the
same steps as cvode-klu-amd up to round-off, so its sweep is cvode-klu-amd's and only its
chosen run is timed (its step and LU counts are checked to match).

    pip install numpy scipy && make -C peers/cvode && \
        python3 scripts/scipy_bruss.py [--n 32 64 128] [--tools scipy-bdf-sparsity ...] \
            [--from-tol 3e-8]
"""

import argparse
import os
import tempfile

import numpy as np
import scipy

from bruss_reference import REF_DIR, Bruss, cvode, integrate, relative_error

TARGET = 1e-6
# 1e-3, 3e-4, 1e-4, ..., 3e-10, 1e-10
TOLERANCES = sorted({float(f"1e-{e}") for e in range(3, 11)} | {float(f"3e-{e}") for e in range(4, 11)},
                    reverse=True)
TOOLS = ["scipy-bdf-sparsity", "scipy-bdf-jac", "cvode-klu-amd", "cvode-klu", "cvode-spgmr"]
REPEAT_BELOW = 10.0  # seconds: runs shorter than this are timed best of 3
REPEATS = 3


def run(tool, n, model, tol):
    """One run: (final state, stats dict with seconds, steps, nfev, njev, nlu)."""
    if tool.startswith("scipy-"):
        jac = "sparsity" if tool == "scipy-bdf-sparsity" else "analytic"
        y, steps, nfev, njev, nlu, seconds = integrate(model, "BDF", tol, tol, jac=jac)
        return y, dict(seconds=seconds, steps=steps, nfev=nfev, njev=njev, nlu=nlu, extra="")
    solver = tool[len("cvode-"):]
    with tempfile.NamedTemporaryFile(suffix=".csv", delete=False) as f:
        out = f.name
    try:
        s = cvode(n, tol, tol, solver, out)
        y = np.loadtxt(out)
    finally:
        os.unlink(out)
    extra = f"nni {int(s['nni'])}, ncfn {int(s['ncfn'])}, netf {int(s['netf'])}"
    if "nli" in s:
        extra += f", nli {int(s['nli'])}, njv {int(s['njv'])}"
    return y, dict(seconds=s["seconds"], steps=int(s["steps"]), nfev=int(s["nfe"]),
                   njev=int(s["nje"]), nlu=int(s["nsetups"]), extra=extra)


def calibrate(tool, n, model, reference, swept):
    """The tool's calibrated run: (tol, error, stats), or None if no tolerance meets the target.
    cvode-klu reuses cvode-klu-amd's sweep when that ran first."""
    sweep_tool = "cvode-klu-amd" if tool == "cvode-klu" else tool
    if sweep_tool in swept:
        tol, _, stats = swept[sweep_tool]
        y, again = run(tool, n, model, tol)
        error = relative_error(y, reference)
        if (again["steps"], again["nlu"]) != (stats["steps"], stats["nlu"]):
            print(f"  note: {tool} took {again['steps']} steps / {again['nlu']} LUs against "
                  f"{sweep_tool}'s {stats['steps']} / {stats['nlu']} (pivoting's round-off)",
                  flush=True)
        if error > TARGET:  # not the same path after all: sweep on its own
            print(f"  note: {tool} misses the target at {sweep_tool}'s tolerance", flush=True)
            return calibrate_sweep(tool, n, model, reference, swept)
        return tol, error, again
    return calibrate_sweep(tool, n, model, reference, swept)


def calibrate_sweep(tool, n, model, reference, swept):
    """Sweep from the loosest tolerance and stop at the first that meets the target."""
    for tol in TOLERANCES:
        try:
            y, stats = run(tool, n, model, tol)
        except Exception as failure:  # a failed run: try the next tolerance
            print(f"  sweep N={n} {tool} tol {tol:.0e}: failed ({failure})", flush=True)
            continue
        error = relative_error(y, reference)
        print(f"  sweep N={n} {tool} tol {tol:.0e}: error {error:.2e}, {stats['seconds']:.2f} s, "
              f"steps {stats['steps']}, nfev {stats['nfev']}, njev {stats['njev']}, "
              f"nlu {stats['nlu']} {stats['extra']}", flush=True)
        if error <= TARGET:
            swept[tool] = (tol, error, stats)
            return tol, error, stats
    return None


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--n", type=int, nargs="+", default=[32, 64, 128])
    parser.add_argument("--tools", nargs="+", choices=TOOLS, default=TOOLS)
    parser.add_argument("--from-tol", type=float, default=None,
                        help="start the sweeps at this tolerance (for slow tools at large N)")
    args = parser.parse_args()
    if args.from_tol is not None:
        TOLERANCES[:] = [tol for tol in TOLERANCES if tol <= args.from_tol * (1 + 1e-9)]
        print(f"sweeps start at {TOLERANCES[0]:g}")
    print(f"scipy {scipy.__version__}, numpy {np.__version__}; BRUSS to t = 11.5, target "
          f"{TARGET:g} (max abs error over max |ref|)", flush=True)
    rows = []
    for n in args.n:
        reference = np.loadtxt(os.path.join(REF_DIR, f"bruss_{n}.csv"))
        model = Bruss(n)
        swept = {}
        for tool in args.tools:
            found = calibrate(tool, n, model, reference, swept)
            if found is None:
                rows.append((n, tool, None, None, None))
                print(f"  N={n} {tool}: no tolerance reaches the target", flush=True)
                continue
            tol, error, stats = found
            seconds = stats["seconds"]
            if seconds < REPEAT_BELOW:
                for _ in range(REPEATS - 1):
                    seconds = min(seconds, run(tool, n, model, tol)[1]["seconds"])
            rows.append((n, tool, tol, error, dict(stats, seconds=seconds)))
            print(f"  N={n} {tool}: tol {tol:.0e}, error {error:.2e}, {seconds:.3f} s", flush=True)
    print()
    print(f"{'N':>4} {'tool':<19} {'tol':>6} {'error':>9} {'seconds':>9} {'steps':>6} "
          f"{'nfev':>6} {'Jacs':>5} {'LUs':>5}  other")
    for n, tool, tol, error, stats in rows:
        if tol is None:
            print(f"{n:>4} {tool:<19} does not reach {TARGET:g} down to 1e-10")
            continue
        print(f"{n:>4} {tool:<19} {tol:>6.0e} {error:>9.2e} {stats['seconds']:>9.3f} "
              f"{stats['steps']:>6} {stats['nfev']:>6} {stats['njev']:>5} {stats['nlu']:>5}  "
              f"{stats['extra']}")


if __name__ == "__main__":
    main()
