"""Step counts of SciPy's DOP853 and RK45 on Arenstorf and Lorenz (not run by CI).

odyn's explicit adaptive solvers can be configured with exactly SciPy's step-size controller, so
that their accepted/rejected step counts can be compared one-to-one with a reference
implementation.  This script records SciPy's numbers: for each problem, method and tolerance it
prints nfev, accepted and rejected steps, the initial step chosen, the first accepted step and the
final error against the high-accuracy references of scripts/reference_adaptive.py.

    pip install numpy scipy && python3 scripts/scipy_dop853_steps.py

Problems (the f64 data of reference_adaptive.py, i.e. exactly what an f64 program integrates)
-------------------------------------------------------------------------------------------
* Arenstorf (HNW I, Sec. II.0, eq. (0.1)): MU = 0.012277471, MU' = 1.0 - MU (f64 arithmetic),
  y0 = (0.994, 0, 0, -2.00158510637908252240537862224) rounded to f64, t in [0, fl(T)],
  T = 17.0652165601579625588917206249.  Layout (y1, y2, y1', y2').
* Lorenz: sigma = 10, rho = 28, beta = 8.0/3.0 (f64), y0 = (1, 0, 0), t in [0, 20].
Tolerances rtol = atol in {1e-6, 1e-9, 1e-12}; no first_step, max_step = inf (SciPy defaults),
dense output off, t_eval None.

How the counts are obtained
---------------------------
The solver object API is driven directly: `DOP853(fun, 0, y0, t_end, rtol=, atol=)` (or RK45) and
`.step()` until status is 'finished'.  A subclass overrides `_estimate_error_norm`, which
`RungeKutta._step_impl` calls exactly once per attempted step; each returned error norm E is
recorded; the attempt is accepted iff E < 1, otherwise rejected.  So
    accepted = #{E < 1} (= number of .step() calls = len(sol.t) - 1 of solve_ivp),
    rejected = #{E >= 1}.
Both are cross-checked against the f-evaluation count, which in SciPy is exactly
    nfev = 2 + n_stages * (accepted + rejected),
where the 2 are f(t0, y0) in RungeKutta.__init__ and the one evaluation f(t0 + h0, y0 + h0 f0)
in select_initial_step, and every attempt costs n_stages evaluations (rk_step evaluates stages
2..n_stages, then f(t+h, y_new), which is reused as stage 1 of the next step, FSAL):
n_stages = 12 for DOP853 (so 12 per attempt), 6 for RK45 (Dormand-Prince 5(4), 7 stages FSAL).
Neither count includes the 3 extra stages DOP853 spends on dense output (off here).  Running
solve_ivp with the same arguments is checked to give the same nfev and len(t) - 1.

SciPy's controller (read from scipy/integrate/_ivp/rk.py and common.py of the installed
SciPy 1.17.1; identical for RK23/RK45/DOP853 except where noted)
--------------------------------------------------------------------------------------------
* error scale: sc_i = atol + rtol * max(|y_i|, |y_new_i|)   (old and new solution).
* error norm: RK45: E = rms_i( h * (K^T E_coef)_i / sc_i )  (RMS over the n components,
  E_coef = the 7 differences b - b_hat, with the 7th stage = f(t+h, y_new)).
  DOP853 (Hairer's combined 5th/3rd-order estimate): with e5 = K^T E5 / sc, e3 = K^T E3 / sc,
      E = |h| * ||e5||_2^2 / sqrt( (||e5||_2^2 + 0.01 ||e3||_2^2) * n ),  and E = 0 if both vanish.
* error exponent: -1 / (error_estimator_order + 1) = -1/8 for DOP853 (estimator order 7),
  -1/5 for RK45 (estimator order 4).  No PI/Lund stabilisation (pure I controller).
* SAFETY = 0.9, MIN_FACTOR = 0.2, MAX_FACTOR = 10.
* accepted (E < 1): factor = MAX_FACTOR if E == 0 else min(MAX_FACTOR, SAFETY * E^exponent);
  if any attempt of this same step was rejected, factor = min(1, factor) (no growth right after a
  rejection); h_next = h_used * factor, where h_used is the (possibly end-clipped) step taken.
* rejected (E >= 1): h *= max(MIN_FACTOR, SAFETY * E^exponent); retry from the same point.
* end of interval: if t + h would pass t_bound, the step is shortened to t_bound - t, and the
  next-step proposal is computed from that shortened h.
* min step: min_step = 10 * |nextafter(t, +-inf) - t|; a proposed |h| below it is first raised to
  it, and if a rejection drives |h| below it the solver fails (TOO_SMALL_STEP).
* max step: |h| is clipped to max_step (default inf) at the start of each step.
* rtol below 100 * eps (2.22e-14) is raised to 100 * eps with a warning.
* select_initial_step (HNW I, Sec. II.4, "starting step size"; RMS norms, sc = atol + rtol |y0|):
      d0 = ||y0 / sc||,  d1 = ||f0 / sc||
      h0 = 1e-6 if d0 < 1e-5 or d1 < 1e-5 else 0.01 * d0 / d1;   h0 = min(h0, |t_bound - t0|)
      y1 = y0 + h0 f0,  f1 = f(t0 + h0, y1),  d2 = ||(f1 - f0) / sc|| / h0
      h1 = max(1e-6, 1e-3 h0) if max(d1, d2) <= 1e-15 else (0.01 / max(d1, d2))^(1/(q+1))
      h = min(100 h0, h1, |t_bound - t0|, max_step)
  with q = error_estimator_order (7 for DOP853, 4 for RK45), so the exponent is 1/8 resp. 1/5.
Note that SciPy's DOP853 is a port of Hairer's Fortran DOP853 (same tableau, error estimator and
starting-step algorithm) but not of its controller constants: the Fortran code's defaults are
safety 0.9 with 0.333 <= h_new/h <= 6 (WORK(3) = FAC1 = 0.333, WORK(4) = FAC2 = 6; SciPy: 0.2
and 10), Lund stabilisation beta = 0 (so also a pure I controller, exponent 1/8), and it accepts
err <= 1 where SciPy needs err < 1.  So the counts here are SciPy's, not the Fortran code's.

Final error: max_i |y_i(t_end) - ref_i| (absolute, inf-norm over the 4 resp. 3 components)
against the f64-variant references of reference_adaptive.py, whose own error is < 1e-25.
"""

import numpy as np
import scipy
from scipy.integrate import solve_ivp
from scipy.integrate import DOP853, RK45

MU = 0.012277471
MUP = 1.0 - MU
ARENSTORF_Y0 = [0.994, 0.0, 0.0, -2.00158510637908252240537862224]
ARENSTORF_T = 17.0652165601579625588917206249
BETA = 8.0 / 3.0

# From scripts/reference_adaptive.py (f64-data variants; Taylor series in mpmath at 50 digits).
ARENSTORF_REF = ["9.93999999999908840338072090236e-1", "-3.03094302298241833090839410873e-13",
                 "-4.92853658105505273256413481987e-11", "-2.00158510639327023849822360732"]
LORENZ20_REF = ["-8.02114361331721523823061618398", "-1.19054647491712239672921148920e+1",
                "1.98563748583986446619238665641e+1"]


def arenstorf(t, y):
    y1, y2, v1, v2 = y
    d1 = ((y1 + MU) ** 2 + y2 ** 2) ** 1.5
    d2 = ((y1 - MUP) ** 2 + y2 ** 2) ** 1.5
    return np.array([v1, v2, y1 + 2 * v2 - MUP * (y1 + MU) / d1 - MU * (y1 - MUP) / d2,
                     y2 - 2 * v1 - MUP * y2 / d1 - MU * y2 / d2])


def lorenz(t, y):
    return np.array([10.0 * (y[1] - y[0]), y[0] * (28.0 - y[2]) - y[1], y[0] * y[1] - BETA * y[2]])


def counting(base):
    class Counting(base):
        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            self.error_norms = []
            self.h_initial = self.h_abs  # select_initial_step's result

        def _estimate_error_norm(self, K, h, scale):
            e = super()._estimate_error_norm(K, h, scale)
            self.error_norms.append((abs(h), float(e)))
            return e

    Counting.__name__ = "Counting" + base.__name__
    return Counting


def run(method, fun, y0, t_end, tol):
    cls = counting({"DOP853": DOP853, "RK45": RK45}[method])
    solver = cls(fun, 0.0, np.array(y0, float), t_end, rtol=tol, atol=tol)
    accepted_h = []
    while solver.status == "running":
        msg = solver.step()
        if solver.status == "failed":
            raise RuntimeError(msg)
        accepted_h.append(solver.step_size)
    attempts = len(solver.error_norms)
    rejected = sum(1 for _, e in solver.error_norms if e >= 1.0)
    accepted = attempts - rejected
    assert accepted == len(accepted_h), (accepted, len(accepted_h))
    assert solver.nfev == 2 + solver.n_stages * attempts, (solver.nfev, attempts)
    sol = solve_ivp(fun, (0.0, t_end), y0, method=method, rtol=tol, atol=tol)
    assert sol.success and sol.nfev == solver.nfev and len(sol.t) - 1 == accepted
    assert np.array_equal(sol.y[:, -1], solver.y)
    first_rej = [i for i, (_, e) in enumerate(solver.error_norms) if e >= 1.0][:5]
    return dict(nfev=solver.nfev, accepted=accepted, rejected=rejected,
                h0=solver.h_initial, h_first=accepted_h[0], h_first3=accepted_h[:3],
                y=solver.y, first_rejected_attempts=first_rej, n_stages=solver.n_stages)


def main():
    print(f"scipy {scipy.__version__}, numpy {np.__version__}")
    problems = [("Arenstorf", arenstorf, ARENSTORF_Y0, ARENSTORF_T, ARENSTORF_REF),
                ("Lorenz", lorenz, [1.0, 0.0, 0.0], 20.0, LORENZ20_REF)]
    rows = []
    for pname, fun, y0, t_end, ref in problems:
        ref = np.array([float(v) for v in ref])
        for method in ("DOP853", "RK45"):
            for tol in (1e-6, 1e-9, 1e-12):
                r = run(method, fun, y0, t_end, tol)
                r["err"] = np.max(np.abs(r["y"] - ref))
                rows.append((pname, method, tol, r))
    print()
    print(f"{'problem':<10} {'method':<7} {'tol':>6} {'nfev':>7} {'accepted':>9} {'rejected':>9}"
          f" {'h0 (select_initial_step)':>25} {'first accepted h':>24} {'max|err|':>9}")
    for pname, method, tol, r in rows:
        print(f"{pname:<10} {method:<7} {tol:>6.0e} {r['nfev']:>7d} {r['accepted']:>9d} "
              f"{r['rejected']:>9d} {r['h0']:>25.17e} {r['h_first']:>24.17e} {r['err']:>9.2e}")
    print()
    print("nfev = 2 + n_stages * (accepted + rejected), n_stages = 12 (DOP853), 6 (RK45): "
          "checked for every row.")
    print()
    print("Details: first three accepted step sizes; 0-based indices of the first rejected "
          "attempts; final state")
    for pname, method, tol, r in rows:
        hs = ", ".join(f"{h:.17e}" for h in r["h_first3"])
        print(f"  {pname} {method} tol={tol:.0e}: h[0..3] = {hs}; "
              f"first rejected attempts {r['first_rejected_attempts']}")
        print(f"      y(t_end) = [{', '.join(f'{v:.17e}' for v in r['y'])}]")


if __name__ == "__main__":
    main()
