"""High-accuracy reference solutions for odyn's non-stiff adaptive-solver tests (not run by CI).

Three problems, each solved by at least two unrelated methods so that their agreement bounds the
reference's own error:

* Arenstorf orbit -- Hairer, Norsett & Wanner, "Solving Ordinary Differential Equations I",
  2nd ed., Springer 1993, Sec. II.0, eq. (0.1):
      y1'' = y1 + 2 y2' - mu' (y1 + mu) / D1 - mu (y1 - mu') / D2
      y2'' = y2 - 2 y1' - mu' y2 / D1        - mu y2 / D2
      D1 = ((y1 + mu)^2 + y2^2)^(3/2),  D2 = ((y1 - mu')^2 + y2^2)^(3/2),
      mu = 0.012277471, mu' = 1 - mu,
      y(0) = (0.994, 0, 0, -2.00158510637908252240537862224) for (y1, y2, y1', y2'),
      period T = 17.0652165601579625588917206249 (both from HNW I, (0.2)).
  State layout (y1, y2, y1', y2').  Two variants are solved:
    "decimal": the data above taken as exact decimals and t_end = T exactly.  The orbit is
               periodic, so y(T) must reproduce y(0) to about the 30 digits the data carry.
    "f64":     every datum rounded to IEEE double as a Rust program would hold it:
               MU = 0.012277471_f64, MU' = 1.0 - MU evaluated in f64, y0 = f64 values,
               t_end = 17.065216560157962_f64 (= fl(T)).  This is the IVP an f64 solver really
               integrates, so this is the value an f64 test should compare against.
* Pleiades -- HNW I, Sec. II.10, eq. (10.12) (also problem PLEI of the Bari test set, below):
  7 bodies in the plane, G = 1, masses m_i = i,
      x_i'' = sum_{j != i} m_j (x_j - x_i) / r_ij^3,  y_i'' likewise,
      x(0) = ( 3,  3, -1, -3,  2, -2,  2),   y(0) = ( 3, -3,  2,  0,  0, -4,  4),
      x'(0) = (0, 0, 0, 0, 0, 1.75, -1.5),   y'(0) = (0, 0, 0, -1.25, 1, 0, 0),
  integrated to t = 3.  State layout (28 components, that of the test set's plei.f):
      (x1..x7, y1..y7, x1'..x7', y1'..y7').  All data are exact binary numbers, so there is a
  single variant.  The published reference (F. Mazzia & C. Magherini, "Test Set for Initial Value
  Problem Solvers", release 2.4, Univ. of Bari, Feb. 2008, problem PLEI, file plei.f rev. 1.2,
  subroutine pleiasoln: PSIDE on a Cray C90 at rtol = atol = 1e-16) is printed next to ours.
* Lorenz -- sigma = 10, rho = 28, beta = 8/3, y(0) = (1, 0, 0), outputs at t = 1, 5, 10, 20.
  The system is chaotic (largest Lyapunov exponent ~0.9), so a relative change of 1e-16 in beta
  moves y(20) by ~1e-8.  Two variants again:
    "f64":   beta = 8.0 / 3.0 rounded to double (what `8.0 / 3.0` gives in Rust) -- the one to cite;
    "exact": beta = 8/3 exactly.

Methods
-------
1. taylor  -- a Taylor-series integrator written here in mpmath: the Taylor coefficients of the
   solution are generated exactly (to working precision) by the standard recurrences of automatic
   differentiation (Cauchy products, and u = s^(-3/2) via  k s_0 u_k = sum_{j=1..k} (a j - (k-j))
   s_j u_{k-j}  with a = -3/2), order N = ceil(-ln(tol)/2) + 1 and step h = rho / e^2, where
   rho = min_{j in {N-1, N}} (||y||_inf-scaled ||c_j||_inf)^(-1/j) (Jorba & Zou, Experimental
   Math. 14 (2005) 99-117).  It is run twice, at mp.dps = 40 / tol = 1e-40 and at
   mp.dps = 50 / tol = 1e-50 (Pleiades, for speed: 34 / 1e-34 and 44 / 1e-44); the difference of
   the two runs is printed, and the higher-precision run is the reference.
2. odefun  -- mpmath.odefun (mpmath's own Taylor method, which obtains the Taylor coefficients by
   finite differences of Euler steps at raised precision -- a different algorithm from 1),
   mp.dps = 40.  Used for the f64 variants of Lorenz and Arenstorf.
3. SciPy DOP853 at rtol = 100*eps = 2.22e-14 (SciPy's floor; asking for 1e-14 is silently
   raised to it with a warning) and atol = 1e-14, and SciPy Radau at rtol = atol = 1e-13
   (Arenstorf and Pleiades), i.e. ordinary double-precision solvers, whose error against the
   mp reference is printed.

    pip install numpy scipy mpmath && python3 scripts/reference_adaptive.py

Runtime: 5-9 minutes (Pleiades Taylor runs and mpmath.odefun dominate).
"""

import math
import time

import mpmath
import numpy as np
import scipy
from mpmath import mp, mpf
from scipy.integrate import solve_ivp

EPS = np.finfo(float).eps
DOP_RTOL = 100 * EPS  # SciPy's minimum rtol
DOP_ATOL = 1e-14


# --------------------------------------------------------------------------------------------
# Taylor-series integrator (jet generators return, per component, the list of Taylor
# coefficients c_0..c_N of the local solution about the current point).
# --------------------------------------------------------------------------------------------

def cauchy(a, b):
    """Coefficient k of the product of two series known to order k (len(a) == len(b) == k+1)."""
    return mp.fdot(a, b[::-1])


def power_coeff(s, u, alpha):
    """Next coefficient u_k of u = s^alpha, given s_0..s_k and u_0..u_{k-1}."""
    k = len(s) - 1
    acc = mp.fdot([(alpha * j - (k - j)) * s[j] for j in range(1, k + 1)],
                  [u[k - j] for j in range(1, k + 1)])
    return acc / (k * s[0])


def lorenz_jet(y, n, sigma, rho, beta):
    x, yy, z = [y[0]], [y[1]], [y[2]]
    for k in range(n):
        xz = cauchy(x, z)
        xy = cauchy(x, yy)
        x.append(sigma * (yy[k] - x[k]) / (k + 1))
        yy.append((rho * x[k] - xz - yy[k]) / (k + 1))
        z.append((xy - beta * z[k]) / (k + 1))
    return [x, yy, z]


def arenstorf_jet(y, n, mu, mup):
    y1, y2, v1, v2 = [y[0]], [y[1]], [y[2]], [y[3]]
    a, b, s1, s2, p1, p2 = [], [], [], [], [], []
    alpha = mpf(-3) / 2
    for k in range(n):
        a.append(y1[k] + (mu if k == 0 else 0))
        b.append(y1[k] - (mup if k == 0 else 0))
        yy = cauchy(y2, y2)
        s1.append(cauchy(a, a) + yy)
        s2.append(cauchy(b, b) + yy)
        if k == 0:
            p1.append(1 / (s1[0] * mp.sqrt(s1[0])))
            p2.append(1 / (s2[0] * mp.sqrt(s2[0])))
        else:
            p1.append(power_coeff(s1, p1, alpha))
            p2.append(power_coeff(s2, p2, alpha))
        ap1, bp2 = cauchy(a, p1), cauchy(b, p2)
        y2p1, y2p2 = cauchy(y2, p1), cauchy(y2, p2)
        y1.append(v1[k] / (k + 1))
        y2.append(v2[k] / (k + 1))
        v1.append((y1[k] + 2 * v2[k] - mup * ap1 - mu * bp2) / (k + 1))
        v2.append((y2[k] - 2 * v1[k] - mup * y2p1 - mu * y2p2) / (k + 1))
    return [y1, y2, v1, v2]


PLEI_N = 7
PLEI_M = [mpf(i + 1) for i in range(PLEI_N)]
PLEI_PAIRS = [(i, j) for i in range(PLEI_N) for j in range(i + 1, PLEI_N)]


def pleiades_jet(y, n):
    N = PLEI_N
    X = [[y[i]] for i in range(N)]
    Y = [[y[N + i]] for i in range(N)]
    U = [[y[2 * N + i]] for i in range(N)]
    V = [[y[3 * N + i]] for i in range(N)]
    alpha = mpf(-3) / 2
    pair = {ij: ([], [], [], []) for ij in PLEI_PAIRS}  # dx, dy, s, p
    for k in range(n):
        ax = [mpf(0)] * N
        ay = [mpf(0)] * N
        for (i, j) in PLEI_PAIRS:
            dx, dy, s, p = pair[(i, j)]
            dx.append(X[j][k] - X[i][k])
            dy.append(Y[j][k] - Y[i][k])
            s.append(cauchy(dx, dx) + cauchy(dy, dy))
            if k == 0:
                p.append(1 / (s[0] * mp.sqrt(s[0])))
            else:
                p.append(power_coeff(s, p, alpha))
            fx, fy = cauchy(dx, p), cauchy(dy, p)
            ax[i] += PLEI_M[j] * fx
            ay[i] += PLEI_M[j] * fy
            ax[j] -= PLEI_M[i] * fx
            ay[j] -= PLEI_M[i] * fy
        for i in range(N):
            X[i].append(U[i][k] / (k + 1))
            Y[i].append(V[i][k] / (k + 1))
            U[i].append(ax[i] / (k + 1))
            V[i].append(ay[i] / (k + 1))
    return X + Y + U + V


def taylor_solve(jet, y0, t0, touts, dps, tol_exp):
    """Integrate from t0 through the increasing output times touts; returns (states, steps)."""
    with mp.workdps(dps):
        order = int(math.ceil(tol_exp * math.log(10) / 2)) + 1  # truncation error ~ e^(-2N)
        t = mpf(t0)
        y = [mpf(v) for v in y0]
        out, steps = [], 0
        for tout in touts:
            tout = mpf(tout)
            while t < tout:
                c = jet(y, order)
                scale = max(1, max(abs(v) for v in y))
                rho = mp.inf
                for j in (order - 1, order):
                    cj = max(abs(ci[j]) for ci in c) / scale
                    if cj > 0:
                        rho = min(rho, cj ** (mpf(-1) / j))
                h = rho / mp.e ** 2
                last = t + h >= tout
                if last:
                    h = tout - t
                # Horner evaluation of each component's series at h.
                y = [mp.polyval(ci[::-1], h) for ci in c]
                t = tout if last else t + h
                steps += 1
            out.append([+v for v in y])
        return out, steps


# --------------------------------------------------------------------------------------------
# double-precision right-hand sides for SciPy
# --------------------------------------------------------------------------------------------

def arenstorf_f64(mu, mup):
    def f(t, y):
        y1, y2, v1, v2 = y
        d1 = ((y1 + mu) ** 2 + y2 ** 2) ** 1.5
        d2 = ((y1 - mup) ** 2 + y2 ** 2) ** 1.5
        return [v1, v2, y1 + 2 * v2 - mup * (y1 + mu) / d1 - mu * (y1 - mup) / d2,
                y2 - 2 * v1 - mup * y2 / d1 - mu * y2 / d2]
    return f


def pleiades_f64(t, y):
    x, yy, u, v = y[0:7], y[7:14], y[14:21], y[21:28]
    m = np.arange(1.0, 8.0)
    dx = x[None, :] - x[:, None]   # dx[i, j] = x_j - x_i
    dy = yy[None, :] - yy[:, None]
    r2 = dx * dx + dy * dy
    np.fill_diagonal(r2, 1.0)
    p = r2 ** -1.5
    np.fill_diagonal(p, 0.0)
    ax = (dx * p) @ m
    ay = (dy * p) @ m
    return np.concatenate([u, v, ax, ay])


def lorenz_f64(beta):
    def f(t, y):
        return [10.0 * (y[1] - y[0]), y[0] * (28.0 - y[2]) - y[1], y[0] * y[1] - beta * y[2]]
    return f


def scipy_solve(f, y0, t_end, method, rtol, atol):
    sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol)
    assert sol.success, sol.message
    return sol.y[:, -1], sol.nfev, len(sol.t) - 1


# --------------------------------------------------------------------------------------------
# printing helpers
# --------------------------------------------------------------------------------------------

def s30(x):
    return mp.nstr(x, 30, min_fixed=0, max_fixed=0, strip_zeros=False)


def show_state(names, ref, other=None, other_name=None):
    for i, name in enumerate(names):
        line = f"    {name:>6} = {s30(ref[i]):>38}   f64: {float(ref[i]):+.16e}"
        if other is not None:
            line += f"   |{other_name}| = {float(abs(mpf(other[i]) - ref[i])):.2e}"
        print(line)


def maxdiff(a, b):
    return max(abs(mpf(x) - mpf(y)) for x, y in zip(a, b))


# --------------------------------------------------------------------------------------------

def arenstorf():
    print("=" * 100)
    print("ARENSTORF ORBIT (HNW I, Sec. II.0, eq. (0.1)); layout (y1, y2, y1', y2')")
    names = ["y1", "y2", "y1'", "y2'"]
    mp.dps = 60
    mu_dec = mpf("0.012277471")
    y0_dec = [mpf("0.994"), mpf(0), mpf(0), mpf("-2.00158510637908252240537862224")]
    T_dec = mpf("17.0652165601579625588917206249")
    mu64 = 0.012277471
    mup64 = 1.0 - mu64
    y0_64 = [0.994, 0.0, 0.0, -2.00158510637908252240537862224]
    T64 = 17.0652165601579625588917206249
    print(f"  f64 data: MU = {mu64!r} (exact binary value {s30(mpf(mu64))}),")
    print(f"            MU' = 1.0 - MU in f64 = {mup64!r}  (MU + MU' - 1 = "
          f"{mp.nstr(mpf(mu64) + mpf(mup64) - 1, 5)}),")
    print(f"            y2'(0) = {y0_64[3]!r}, t_end = fl(T) = {T64!r} "
          f"(fl(T) - T = {mp.nstr(mpf(T64) - T_dec, 5)})")

    results = {}
    for variant, mu, mup, y0, T in (
            ("decimal", mu_dec, 1 - mu_dec, y0_dec, T_dec),
            ("f64", mpf(mu64), mpf(mup64), [mpf(v) for v in y0_64], mpf(T64))):
        runs = []
        for dps, tol in ((40, 40), (50, 50)):
            t0 = time.perf_counter()
            jet = lambda y, n, mu=mu, mup=mup: arenstorf_jet(y, n, mu, mup)
            (yT,), steps = taylor_solve(jet, y0, 0, [T], dps, tol)
            runs.append(yT)
            print(f"  [{variant}] taylor dps={dps} tol=1e-{tol}: {steps} steps, "
                  f"{time.perf_counter() - t0:.1f} s")
        results[variant] = runs
        print(f"  [{variant}] y(t_end), Taylor dps=50 (|dps40 - dps50| per component):")
        show_state(names, runs[1], runs[0], "taylor40 - taylor50")
        if variant == "decimal":
            print(f"  [decimal] max |y(T) - y(0)| = {mp.nstr(maxdiff(runs[1], y0), 5)}  "
                  f"(periodicity check; the data carry ~30 digits)")

    ref = results["f64"][1]
    with mp.workdps(40):
        mu, mup = mpf(mu64), mpf(mup64)

        def F(t, y):
            y1, y2, v1, v2 = y
            d1 = ((y1 + mu) ** 2 + y2 ** 2) ** mpf(1.5)
            d2 = ((y1 - mup) ** 2 + y2 ** 2) ** mpf(1.5)
            return [v1, v2, y1 + 2 * v2 - mup * (y1 + mu) / d1 - mu * (y1 - mup) / d2,
                    y2 - 2 * v1 - mup * y2 / d1 - mu * y2 / d2]
        t0 = time.perf_counter()
        sol = mp.odefun(F, 0, [mpf(v) for v in y0_64])
        yo = sol(mpf(T64))
        print(f"  [f64] mpmath.odefun dps=40 ({time.perf_counter() - t0:.1f} s): "
              f"max |odefun - taylor50| = {mp.nstr(maxdiff(yo, ref), 5)}")
    print(f"  |y_decimal(T) - y_f64(fl T)| per component: "
          + ", ".join(mp.nstr(abs(a - b), 3) for a, b in zip(results['decimal'][1], ref)))

    f = arenstorf_f64(mu64, mup64)
    for method, rtol, atol in (("DOP853", DOP_RTOL, DOP_ATOL), ("Radau", 1e-13, 1e-13)):
        yT, nfev, nsteps = scipy_solve(f, y0_64, T64, method, rtol, atol)
        print(f"  [f64] SciPy {method} rtol={rtol:.3g} atol={atol:.3g}: {nsteps} steps, "
              f"{nfev} f-evals, max |scipy - ref| = {mp.nstr(maxdiff(yT, ref), 3)}; per component: "
              + ", ".join(f"{float(abs(mpf(a) - b)):.1e}" for a, b in zip(yT, ref)))
    return ref


PLEI_BARI = [
    0.3706139143970502, 0.3237284092057233e1, -0.3222559032418324e1, 0.6597091455775310,
    0.3425581707156584, 0.1562172101400631e1, -0.7003092922212495, -0.3943437585517392e1,
    -0.3271380973972550e1, 0.5225081843456543e1, -0.2590612434977470e1, 0.1198213693392275e1,
    -0.2429682344935824, 0.1091449240428980e1, 0.3417003806314313e1, 0.1354584501625501e1,
    -0.2590065597810775e1, 0.2025053734714242e1, -0.1155815100160448e1, -0.8072988170223021,
    0.5952396354208710, -0.3741244961234010e1, 0.3773459685750630, 0.9386858869551073,
    0.3667922227200571, -0.3474046353808490, 0.2344915448180937e1, -0.1947020434263292e1]


def pleiades():
    print("=" * 100)
    print("PLEIADES (HNW I, Sec. II.10; Bari test set PLEI), t = 3; "
          "layout (x1..x7, y1..y7, x1'..x7', y1'..y7')")
    names = ([f"x{i}" for i in range(1, 8)] + [f"y{i}" for i in range(1, 8)]
             + [f"x{i}'" for i in range(1, 8)] + [f"y{i}'" for i in range(1, 8)])
    y0 = [3, 3, -1, -3, 2, -2, 2, 3, -3, 2, 0, 0, -4, 4,
          0, 0, 0, 0, 0, 1.75, -1.5, 0, 0, 0, -1.25, 1, 0, 0]
    mp.dps = 60
    runs = []
    for dps, tol in ((34, 34), (44, 44)):
        t0 = time.perf_counter()
        (y3,), steps = taylor_solve(pleiades_jet, y0, 0, [3], dps, tol)
        runs.append(y3)
        print(f"  taylor dps={dps} tol=1e-{tol}: {steps} steps, {time.perf_counter() - t0:.1f} s")
    ref = runs[1]
    print(f"  y(3), Taylor dps=44 (|dps34 - dps44| per component; Bari PLEI value in last column):")
    for i, name in enumerate(names):
        print(f"    {name:>4} = {s30(ref[i]):>38}   f64: {float(ref[i]):+.16e}   "
              f"|t34-t44| = {float(abs(runs[0][i] - ref[i])):.1e}   "
              f"Bari {PLEI_BARI[i]:+.16e} (diff {float(abs(mpf(PLEI_BARI[i]) - ref[i])):.1e})")
    print(f"  max |taylor34 - taylor44| = {mp.nstr(maxdiff(runs[0], ref), 3)}, "
          f"max |Bari - taylor44| = {mp.nstr(maxdiff(PLEI_BARI, ref), 3)}")
    for method, rtol, atol in (("DOP853", DOP_RTOL, DOP_ATOL), ("Radau", 1e-13, 1e-13)):
        yT, nfev, nsteps = scipy_solve(pleiades_f64, np.array(y0, float), 3.0, method, rtol, atol)
        print(f"  SciPy {method} rtol={rtol:.3g} atol={atol:.3g}: {nsteps} steps, {nfev} f-evals, "
              f"max |scipy - ref| = {mp.nstr(maxdiff(yT, ref), 3)}")
    return ref


def lorenz():
    print("=" * 100)
    print("LORENZ sigma = 10, rho = 28, y(0) = (1, 0, 0); outputs t = 1, 5, 10, 20")
    names = ["x", "y", "z"]
    touts = [1, 5, 10, 20]
    mp.dps = 60
    beta64 = 8.0 / 3.0
    print(f"  f64 variant: beta = 8.0/3.0 = {s30(mpf(beta64))} (8/3 - beta = "
          f"{mp.nstr(mpf(8) / 3 - mpf(beta64), 5)})")
    res = {}
    for variant, beta in (("f64", mpf(beta64)), ("exact", mpf(8) / 3)):
        runs = []
        for dps, tol in ((40, 40), (50, 50)):
            t0 = time.perf_counter()
            jet = lambda y, n, b=beta: lorenz_jet(y, n, 10, 28, b)
            ys, steps = taylor_solve(jet, [1, 0, 0], 0, touts, dps, tol)
            runs.append(ys)
            print(f"  [{variant}] taylor dps={dps} tol=1e-{tol}: {steps} steps, "
                  f"{time.perf_counter() - t0:.1f} s")
        res[variant] = runs
    # mpmath.odefun on the f64 variant
    with mp.workdps(40):
        b = mpf(beta64)

        def F(t, y):
            return [10 * (y[1] - y[0]), y[0] * (28 - y[2]) - y[1], y[0] * y[1] - b * y[2]]
        t0 = time.perf_counter()
        sol = mp.odefun(F, 0, [mpf(1), mpf(0), mpf(0)])
        odef = [sol(mpf(t)) for t in touts]
        t_odefun = time.perf_counter() - t0
    print(f"  [f64] mpmath.odefun dps=40: {t_odefun:.1f} s")
    for k, t in enumerate(touts):
        ref = res["f64"][1][k]
        print(f"  t = {t}:  [f64 beta] Taylor dps=50; |taylor40 - taylor50|, |odefun40 - taylor50|:")
        for i, name in enumerate(names):
            print(f"    {name} = {s30(ref[i]):>38}   f64: {float(ref[i]):+.16e}   "
                  f"{float(abs(res['f64'][0][k][i] - ref[i])):.1e}   {float(abs(odef[k][i] - ref[i])):.1e}")
        ex = res["exact"][1][k]
        print(f"          [exact 8/3] " + ", ".join(s30(v) for v in ex)
              + f"   |taylor40 - taylor50| = {mp.nstr(maxdiff(res['exact'][0][k], ex), 2)}"
              + f"   |exact - f64 variant| = {mp.nstr(maxdiff(ex, ref), 3)}")
    beta64f = lorenz_f64(beta64)
    for method, rtol, atol in (("DOP853", DOP_RTOL, DOP_ATOL), ("DOP853", 1e-13, 1e-13)):
        errs = []
        for k, t in enumerate(touts):
            yT, nfev, nsteps = scipy_solve(beta64f, [1.0, 0.0, 0.0], float(t), method, rtol, atol)
            errs.append(f"t={t}: {mp.nstr(maxdiff(yT, res['f64'][1][k]), 2)} ({nsteps} steps)")
        print(f"  [f64] SciPy {method} rtol={rtol:.3g} atol={atol:.3g}, max |scipy - ref|: "
              + "; ".join(errs))


if __name__ == "__main__":
    print(f"scipy {scipy.__version__}, numpy {np.__version__}, mpmath {mpmath.__version__}")
    t_start = time.perf_counter()
    arenstorf()
    pleiades()
    lorenz()
    print(f"total {time.perf_counter() - t_start:.0f} s")
