"""DAE references for issue 50: four index-1 problems in mass-matrix form M y' = f(t, y), their
published or computed reference states at the end time, and independent cross-checks (not run by
CI).  The problems are written out in /work/notes/dae-problems.md; every constant here is the IEEE
double the Fortran/C sources use, in their order of operations.

Problems
--------
* CHEMAKZO -- Chemical Akzo Nobel, Bari test set (F. Mazzia & C. Magherini, "Test Set for Initial
  Value Problem Solvers", release 2.4, 2008, Univ. of Bari), file chemakzo.f rev. 1.2
  (2006/10/02), vendored as MESAHub/mesa num/test/src/bari_chemakzo.f (commit 13fe30d5).
  6 unknowns, M = diag(1, 1, 1, 1, 1, 0), t in [0, 180].
* TRANSAMP -- Transistor amplifier, Bari test set file transamp.f rev. 1.3 (2006/10/25), vendored
  as rforge/bvpsolve pkg/deTestSet/src/Ex_transistor.f (commit 14b319e0).  8 unknowns, singular
  tridiagonal M (rank 5), t in [0, 0.2].
* ROBERDAE -- Robertson kinetics with the conservation law as its third row,
  0 = y1 + y2 + y3 - 1, M = diag(1, 1, 0), t in [0, 1e11].
* PENDULUM -- a planar pendulum in Cartesian coordinates, index 1 (the length constraint
  differentiated twice, the multiplier lambda an algebraic unknown): x' = u, y' = v,
  m u' = -lambda x, m v' = -lambda y - m g, 0 = m (u^2 + v^2) - m g y - lambda (x^2 + y^2);
  m = 1, L = 1, g = 9.81, released from rest at theta0 = 2.5 rad (the `pendulum` example's
  amplitude), t in [0, 10].

References and cross-checks
---------------------------
* CHEMAKZO, TRANSAMP: the published values (PSIDE on a Cray C90, rtol = atol = 1e-19 and 1e-14).
  Cross-checked by (a) "radau_dae" below, a Radau IIA collocation code for M y' = f with s = 5
  stages (order 9), step-doubling error control, in float64, on the mass-matrix form as
  published, and (b) SciPy's Radau and LSODA on the ODE left after eliminating the algebraic
  components (CHEMAKZO: y6 = Ks y1 y4; TRANSAMP: the three node equations solved for y2, y5, y8
  by Newton to machine precision inside every f, five capacitor voltages as unknowns).
* ROBERDAE: the reference is the mpmath Radau IIA run (s = 7, 36 digits, rtol 1e-24) of the ODE
  form (imported from scripts/reference_stiff.py); y1 + y2 + y3 = 1 is an exact invariant of
  the ODE, so the ODE and DAE solutions coincide.  Cross-checked by the test set's rober.f value,
  an s = 5 mpmath run, SciPy Radau on the ODE, and radau_dae on the DAE form.
* PENDULUM: the exact solution theta(t) = 2 asin(k sn(K - w t, k)), k = sin(theta0 / 2),
  w = sqrt(g / L), in mpmath at 40 digits (Jacobi sn, cn by mpmath.ellipfun), mapped to
  x = L sin theta, y = -L cos theta, u = L theta' cos theta, v = L theta' sin theta,
  lambda = m (L theta'^2 + g cos theta) / L, with theta' = -2 k w cn(K - w t, k).  Cross-checked
  by the mpmath Radau run of the angle-form ODE theta'' = -(g / L) sin theta and by radau_dae on
  the Cartesian index-1 form (whose drift off x^2 + y^2 = L^2 is printed).

Every analytic Jacobian below is checked against central differences first (the C and Rust
peers transcribe the same ones).

    pip install numpy scipy mpmath && python3 scripts/reference_dae.py

Runtime: 766 s on a shared 2-core machine at load average 7 (the three mpmath runs dominate).
"""

import math
import sys
import time
import warnings

import mpmath
import numpy as np
import scipy
from mpmath import mp, mpf
from scipy.integrate import solve_ivp

from reference_stiff import mp_radau, radau_tableau, robertson, robertson_jac, robertson_jac_mp, \
    robertson_mp

# --------------------------------------------------------------------------------------------
# CHEMAKZO (chemakzo.f: feval, jeval, init, solut)
# --------------------------------------------------------------------------------------------

K1, K2, K3, K4, KBIG, KLA, KS, PO2, HEN = 18.7, 0.58, 0.09, 0.42, 34.4, 3.3, 115.83, 0.9, 737.0
AKZO_Y0 = [0.444, 0.00123, 0.0, 0.007, 0.0, KS * 0.444 * 0.007]
AKZO_M = np.diag([1.0, 1.0, 1.0, 1.0, 1.0, 0.0])
AKZO_T = 180.0
AKZO_REF = [0.1150794920661702e0, 0.1203831471567715e-2, 0.1611562887407974e0,
            0.3656156421249283e-3, 0.1708010885264404e-1, 0.4873531310307455e-2]


def akzo_f(t, y):
    sqy2 = math.sqrt(y[1])
    r1 = K1 * y[0] * y[0] * y[0] * y[0] * sqy2
    r2 = K2 * y[2] * y[3]
    r3 = K2 / KBIG * y[0] * y[4]
    r4 = K3 * y[0] * y[3] * y[3]
    r5 = K4 * (y[5] ** 2) * sqy2
    fin = KLA * (PO2 / HEN - y[1])
    return np.array([((-2.0 * r1 + r2) - r3) - r4,
                     ((-0.5 * r1 - r4) - 0.5 * r5) + fin,
                     (r1 - r2) + r3,
                     (-r2 + r3) - 2.0 * r4,
                     (r2 - r3) + r5,
                     KS * y[0] * y[3] - y[5]])


def akzo_jac(t, y):
    y13 = y[0] ** 3
    sq = math.sqrt(y[1])
    r11, r12 = 4.0 * K1 * y13 * sq, 0.5 * K1 * y[0] * y13 / sq
    r23, r24 = K2 * y[3], K2 * y[2]
    r31, r35 = (K2 / KBIG) * y[4], (K2 / KBIG) * y[0]
    r41, r44 = K3 * y[3] ** 2, 2.0 * K3 * y[0] * y[3]
    r52, r56 = 0.5 * K4 * y[5] ** 2 / sq, 2.0 * K4 * y[5] * sq
    J = np.zeros((6, 6))
    J[0, :5] = [(-2.0 * r11 - r31) - r41, -2.0 * r12, r23, r24 - r44, -r35]
    J[1, [0, 1, 3, 5]] = [-0.5 * r11 - r41, -0.5 * r12 - 0.5 * r52 - KLA, -r44, -0.5 * r56]
    J[2, :5] = [r11 + r31, r12, -r23, -r24, r35]
    J[3, [0, 2, 3, 4]] = [r31 - 2.0 * r41, -r23, -r24 - 2.0 * r44, r35]
    J[4, :] = [-r31, r52, r23, r24, -r35, r56]
    J[5, [0, 3, 5]] = [KS * y[3], KS * y[0], -1.0]
    return J


def akzo_reduced(t, z):
    """The ODE in y1..y5 after eliminating the algebraic y6 = Ks y1 y4."""
    y = list(z) + [KS * z[0] * z[3]]
    return akzo_f(t, y)[:5]


def akzo_reduced_mp(t, z):
    k1, k2, k3, k4 = mpf(K1), mpf(K2), mpf(K3), mpf(K4)
    y6 = mpf(KS) * z[0] * z[3]
    sqy2 = mp.sqrt(z[1])
    r1 = k1 * z[0] ** 4 * sqy2
    r2 = k2 * z[2] * z[3]
    r3 = k2 / mpf(KBIG) * z[0] * z[4]
    r4 = k3 * z[0] * z[3] ** 2
    r5 = k4 * y6 ** 2 * sqy2
    fin = mpf(KLA) * (mpf(PO2) / mpf(HEN) - z[1])
    return [-2 * r1 + r2 - r3 - r4, -r1 / 2 - r4 - r5 / 2 + fin, r1 - r2 + r3, -r2 + r3 - 2 * r4,
            r2 - r3 + r5]


def akzo_reduced_jac_mp(t, z):
    """d(akzo_reduced_mp)/dz by central differences in mpmath (only steers Newton)."""
    return numeric_jac_mp(akzo_reduced_mp, t, z)


# --------------------------------------------------------------------------------------------
# TRANSAMP (transamp.f: feval, jeval, meval, init, solut)
# --------------------------------------------------------------------------------------------

UB, UF, ALPHA, BETA = 6.0, 0.026, 0.99, 1e-6
R0, RK = 1000.0, 9000.0  # r1 .. r9 are all 9000
C1, C2, C3, C4, C5 = 1e-6, 2e-6, 3e-6, 4e-6, 5e-6
PI_F = 3.1415926535897931086244  # the file's pi, = math.pi in binary64
TRANS_T = 0.2
TRANS_Y0 = [0.0, UB / (RK / RK + 1.0), UB / (RK / RK + 1.0), UB, UB / (RK / RK + 1.0),
            UB / (RK / RK + 1.0), UB, 0.0]
TRANS_REF = [-0.5562145012262709e-002, 0.3006522471903042e+001, 0.2849958788608128e+001,
             0.2926422536206241e+001, 0.2704617865010554e+001, 0.2761837778393145e+001,
             0.4770927631616772e+001, 0.1236995868091548e+001]
TRANS_M = np.zeros((8, 8))
for (i, j, c) in ((0, 0, -C1), (0, 1, C1), (1, 0, C1), (1, 1, -C1), (2, 2, -C2), (3, 3, -C3),
                  (3, 4, C3), (4, 3, C3), (4, 4, -C3), (5, 5, -C4), (6, 6, -C5), (6, 7, C5),
                  (7, 6, C5), (7, 7, -C5)):
    TRANS_M[i, j] = c


def trans_f(t, y):
    uet = 0.1 * math.sin(200.0 * PI_F * t)
    fac1 = BETA * (math.exp((y[1] - y[2]) / UF) - 1.0)
    fac2 = BETA * (math.exp((y[4] - y[5]) / UF) - 1.0)
    return np.array([(y[0] - uet) / R0,
                     y[1] / RK + (y[1] - UB) / RK + (1.0 - ALPHA) * fac1,
                     y[2] / RK - fac1,
                     (y[3] - UB) / RK + ALPHA * fac1,
                     y[4] / RK + (y[4] - UB) / RK + (1.0 - ALPHA) * fac2,
                     y[5] / RK - fac2,
                     (y[6] - UB) / RK + ALPHA * fac2,
                     y[7] / RK])


def trans_jac(t, y):
    g1 = BETA * math.exp((y[1] - y[2]) / UF) / UF
    g2 = BETA * math.exp((y[4] - y[5]) / UF) / UF
    J = np.zeros((8, 8))
    J[0, 0] = 1.0 / R0
    J[1, 1], J[1, 2] = 2.0 / RK + (1.0 - ALPHA) * g1, -(1.0 - ALPHA) * g1
    J[2, 1], J[2, 2] = -g1, 1.0 / RK + g1
    J[3, 1], J[3, 2], J[3, 3] = ALPHA * g1, -ALPHA * g1, 1.0 / RK
    J[4, 4], J[4, 5] = 2.0 / RK + (1.0 - ALPHA) * g2, -(1.0 - ALPHA) * g2
    J[5, 4], J[5, 5] = -g2, 1.0 / RK + g2
    J[6, 4], J[6, 5], J[6, 6] = ALPHA * g2, -ALPHA * g2, 1.0 / RK
    J[7, 7] = 1.0 / RK
    return J


def trans_full_state(t, w):
    """From the capacitor voltages w = (y1 - y2, y3, y4 - y5, y6, y7 - y8), the node equations
    (rows 1+2, 4+5, 7+8 of M y' = f, the left null space of M) solved for y2, y5, y8."""
    u1, y3, u2, y6, u3 = w
    uet = 0.1 * math.sin(200.0 * PI_F * t)

    def newton(g, dg, slope_min, x):
        """The root of g, increasing and convex with g' >= slope_min: first step to the right of
        the root (x - g(x)/slope_min when g(x) < 0), then Newton, which from there decreases
        monotonically; stop when it no longer does (the root to the last bit)."""
        gx = g(x)
        if gx < 0.0:
            x -= gx / slope_min
        for _ in range(200):
            x_new = x - g(x) / dg(x)
            if not x_new < x:
                return x
            x = x_new
        raise RuntimeError("node equation did not converge")

    # (y1 - uet)/R0 + y2/R1 + (y2 - UB)/R2 + (1 - a) b (e^((y2 - y3)/UF) - 1) = 0, y1 = u1 + y2
    y2 = newton(lambda x: (u1 + x - uet) / R0 + 2.0 * x / RK - UB / RK
                + (1.0 - ALPHA) * BETA * (math.exp((x - y3) / UF) - 1.0),
                lambda x: 1.0 / R0 + 2.0 / RK + (1.0 - ALPHA) * BETA * math.exp((x - y3) / UF) / UF,
                1.0 / R0 + 2.0 / RK, y3)
    fac1 = BETA * (math.exp((y2 - y3) / UF) - 1.0)
    # (y4 - UB)/R4 + a fac1 + y5/R5 + (y5 - UB)/R6 + (1 - a) fac2 = 0, y4 = u2 + y5
    y5 = newton(lambda x: (u2 + x - UB) / RK + ALPHA * fac1 + 2.0 * x / RK - UB / RK
                + (1.0 - ALPHA) * BETA * (math.exp((x - y6) / UF) - 1.0),
                lambda x: 3.0 / RK + (1.0 - ALPHA) * BETA * math.exp((x - y6) / UF) / UF,
                3.0 / RK, y6)
    fac2 = BETA * (math.exp((y5 - y6) / UF) - 1.0)
    # (y7 - UB)/R8 + a fac2 + y8/R9 = 0, y7 = u3 + y8: linear
    y8 = (UB - u3 - RK * ALPHA * fac2) / 2.0
    return [u1 + y2, y2, y3, u2 + y5, y5, y6, u3 + y8, y8]


def trans_reduced(t, w):
    """w' from rows 1, 3, 4, 6, 7 of M y' = f: -C1 (y1 - y2)' = f1, -C2 y3' = f3, ..."""
    f = trans_f(t, trans_full_state(t, w))
    return np.array([-f[0] / C1, -f[2] / C2, -f[3] / C3, -f[5] / C4, -f[6] / C5])


# --------------------------------------------------------------------------------------------
# ROBERDAE
# --------------------------------------------------------------------------------------------

ROBER_T = 1e11
ROBER_Y0 = [1.0, 0.0, 0.0]
ROBER_M = np.diag([1.0, 1.0, 0.0])
ROBER_BARI = [0.2083340149701255e-07, 0.8333360770334713e-13, 0.9999999791665050]


def rober_dae_f(t, y):
    return np.array([-0.04 * y[0] + 1e4 * y[1] * y[2],
                     0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1],
                     y[0] + y[1] + y[2] - 1.0])


def rober_dae_jac(t, y):
    return np.array([[-0.04, 1e4 * y[2], 1e4 * y[1]],
                     [0.04, -1e4 * y[2] - 6e7 * y[1], -1e4 * y[1]],
                     [1.0, 1.0, 1.0]])


# --------------------------------------------------------------------------------------------
# PENDULUM
# --------------------------------------------------------------------------------------------

PM, PL, PG, THETA0 = 1.0, 1.0, 9.81, 2.5
PEND_T = 10.0
PEND_Y0 = [PL * math.sin(THETA0), -PL * math.cos(THETA0), 0.0, 0.0,
           PM * PG * PL * math.cos(THETA0) / (PL * PL)]


def pend_f(t, y):
    x, yy, u, v, lam = y
    return np.array([u, v, -lam * x, -lam * yy - PM * PG,
                     PM * (u * u + v * v) - PM * PG * yy - lam * (x * x + yy * yy)])


def pend_jac(t, y):
    x, yy, u, v, lam = y
    return np.array([[0.0, 0.0, 1.0, 0.0, 0.0],
                     [0.0, 0.0, 0.0, 1.0, 0.0],
                     [-lam, 0.0, 0.0, 0.0, -x],
                     [0.0, -lam, 0.0, 0.0, -yy],
                     [-2.0 * lam * x, -PM * PG - 2.0 * lam * yy, 2.0 * PM * u, 2.0 * PM * v,
                      -(x * x + yy * yy)]])


PEND_M = np.diag([1.0, 1.0, PM, PM, 0.0])


def pendulum_exact(t):
    """The Cartesian state (x, y, u, v, lambda) at t from the exact angle solution, in mpmath."""
    with mp.workdps(40):
        th0, w = mpf(THETA0), mp.sqrt(mpf(PG) / mpf(PL))
        k = mp.sin(th0 / 2)
        K = mp.ellipk(k * k)
        arg = K - w * mpf(t)
        sn = mp.ellipfun('sn', arg, k=k)
        cn = mp.ellipfun('cn', arg, k=k)
        th = 2 * mp.asin(k * sn)
        dth = -2 * k * w * cn
        L, m, g = mpf(PL), mpf(PM), mpf(PG)
        return [L * mp.sin(th), -L * mp.cos(th), L * dth * mp.cos(th), L * dth * mp.sin(th),
                m * (L * dth ** 2 + g * mp.cos(th)) / L], th, dth


def pend_angle_mp(t, y):
    return [y[1], -(mpf(PG) / mpf(PL)) * mp.sin(y[0])]


def pend_angle_jac_mp(t, y):
    return [[0, 1], [-(mpf(PG) / mpf(PL)) * mp.cos(y[0]), 0]]


# --------------------------------------------------------------------------------------------
# Radau IIA for M y' = f(t, y) in float64
# --------------------------------------------------------------------------------------------

def radau_dae(f, jac, M, y0, t_end, s=5, rtol=1e-12, atol=1e-14, h0=1e-8):
    """Radau IIA with s stages (order 2s - 1, stiffly accurate, so order 2s - 1 in the algebraic
    components of an index-1 system too) on M y' = f: the stage increments Z_i solve
    M Z_i = h sum_j a_ij f(t + c_j h, y + Z_j) by full Newton (block (i, j) of its matrix is
    delta_ij M - h a_ij J(t + c_j h, y + Z_j); this is a reference code, robustness before
    speed), to a scaled increment below 1e-3 (or below 1e-1 where rounding stalls it); the
    error by step doubling (Richardson).
    Returns y(t_end), accepted steps, error-test rejections and Newton failures."""
    with mp.workdps(30):
        c_mp, a_mp = radau_tableau(s)
    c = np.array([float(v) for v in c_mp])
    A = np.array([[float(v) for v in row] for row in a_mp])
    n, p = len(y0), 2 * s - 1

    def step(t, y, h):
        Z = np.zeros((s, n))
        scale = atol + rtol * np.abs(y)
        prev = None
        for _ in range(25):
            Y = [y + Z[j] for j in range(s)]
            try:  # an iterate may leave f's domain (sqrt of a negative, exp overflow)
                F = np.array([f(t + c[j] * h, Y[j]) for j in range(s)])
                Js = [jac(t + c[j] * h, Y[j]) for j in range(s)]
                big = np.block([[(M if i == j else 0.0 * M) - h * A[i, j] * Js[j]
                                 for j in range(s)] for i in range(s)])
                G = h * (A @ F) - (M @ Z.T).T
                d = np.linalg.solve(big, G.ravel()).reshape(s, n)
            except (ValueError, OverflowError, np.linalg.LinAlgError):
                return None
            Z += d
            norm = np.max(np.abs(d) / scale)
            if not np.isfinite(norm) or (prev is not None and norm > 2.0 * prev):
                return None
            # Converged; or stalled on rounding (quadratic convergence has ended) below 1e-1
            if norm < 1e-3 or (prev is not None and norm > 0.5 * prev and norm < 1e-1):
                return y + Z[-1]
            prev = norm
        return None

    t, y, h = 0.0, np.array(y0, float), h0
    steps = rejected = newton_failures = 0
    while t < t_end:
        last = t + h >= t_end
        hh = t_end - t if last else h
        y2 = None
        y1 = step(t, y, hh)
        if y1 is not None:
            ym = step(t, y, hh / 2)
            if ym is not None:
                y2 = step(t + hh / 2, ym, hh / 2)
        if y2 is None:
            h = hh / 2
            newton_failures += 1
            if h < 1e-14 * t_end:
                raise RuntimeError(f"radau_dae: step size underflow at t = {t:g}")
            continue
        err = np.max(np.abs(y2 - y1) / (atol + rtol * np.maximum(np.abs(y2), np.abs(y)))) / (2 ** p - 1)
        fac = min(3.0, max(0.2, 0.9 * (err + 1e-300) ** (-1.0 / (p + 1))))
        if err <= 1.0:
            t = t_end if last else t + hh
            y = y2
            steps += 1
            h = max(h, hh * fac) if last else hh * fac
        else:
            h = hh * fac
            rejected += 1
    return y, steps, rejected, newton_failures


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------

def numeric_jac_mp(f, t, z):
    n = len(z)
    cols = []
    for j in range(n):
        e = mpf(10) ** (-(mp.dps // 2)) * max(1, abs(z[j]))
        zp, zm = list(z), list(z)
        zp[j] += e
        zm[j] -= e
        fp, fm = f(t, zp), f(t, zm)
        cols.append([(a - b) / (2 * e) for a, b in zip(fp, fm)])
    return [[cols[j][i] for j in range(n)] for i in range(n)]


def check_jacobian(name, f, jac, y, t=0.0):
    y = np.array(y, float)
    J = jac(t, y)
    worst = 0.0
    for j in range(len(y)):
        e = 1e-6 * max(1e-3, abs(y[j]))
        yp, ym = y.copy(), y.copy()
        yp[j] += e
        ym[j] -= e
        col = (f(t, yp) - f(t, ym)) / (2 * e)
        worst = max(worst, np.max(np.abs(col - J[:, j])) / np.max(np.abs(J[:, j])))
    print(f"  {name}: largest |central difference - analytic| in a column, relative to the "
          f"column's largest entry: {worst:.1e}")
    assert worst < 1e-6, name


def rel(a, b):
    return abs(float(a) - float(b)) / abs(float(b)) if float(b) != 0 else abs(float(a))


def print_comparison(names, ref, others):
    """One row per component: the reference, then |x - ref| / |ref| for each candidate."""
    head = "  comp  reference                  " + "".join(f"{n:>16}" for n, _ in others)
    print(head)
    for i, r in enumerate(ref):
        print(f"  {names[i]:<5} {float(r):+.16e}" + "".join(f"{rel(v[i], r):>16.1e}" for _, v in others))
    print("  max   " + " " * 24 + "".join(
        f"{max(rel(v[i], r) for i, r in enumerate(ref) if abs(float(r)) >= 1e-10):>16.1e}"
        for _, v in others) + "   (over |ref| >= 1e-10)")


def scipy_run(f, y0, t_end, method, rtol, atol, jac=None):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        t0 = time.perf_counter()
        sol = solve_ivp(f, (0.0, t_end), y0, method=method, rtol=rtol, atol=atol, jac=jac)
    if not sol.success:
        raise RuntimeError(f"{method}: {sol.message}")
    print(f"    SciPy {method} rtol {rtol:g} atol {atol:g}: {len(sol.t) - 1} steps, "
          f"{time.perf_counter() - t0:.1f} s")
    return sol.y[:, -1]


def radau_run(name, f, jac, M, y0, t_end, rtol, atol, s=5):
    t0 = time.perf_counter()
    y, steps, rejected, failures = radau_dae(f, jac, M, y0, t_end, s=s, rtol=rtol, atol=atol)
    print(f"    radau_dae s={s} rtol {rtol:g} atol {atol:g} on {name}: {steps} steps "
          f"({rejected} rejected, {failures} Newton failures), {time.perf_counter() - t0:.1f} s")
    return y


def rust_array(name, values, comment):
    print(f"    /// {comment}")
    print(f"    pub const {name}: [f64; {len(values)}] = [")
    for v in values:
        print(f"        {float(v)!r},")
    print("    ];")


# --------------------------------------------------------------------------------------------
# main
# --------------------------------------------------------------------------------------------

def main():
    print(f"scipy {scipy.__version__}, numpy {np.__version__}, mpmath {mpmath.__version__}")
    start = time.perf_counter()

    print("=" * 100)
    print("Jacobians, checked at the initial state pushed off by a few percent (and zeros by up to 1e-3)")
    rng = np.random.default_rng(1)
    for name, f, jac, y in (("CHEMAKZO", akzo_f, akzo_jac, AKZO_Y0),
                            ("TRANSAMP", trans_f, trans_jac, TRANS_Y0),
                            ("ROBERDAE", rober_dae_f, rober_dae_jac, [0.9, 1e-5, 0.1]),
                            ("PENDULUM", pend_f, pend_jac, PEND_Y0)):
        y = np.array(y, float)
        y = y * (1 + 0.05 * rng.standard_normal(len(y))) + 1e-3 * rng.random(len(y))
        check_jacobian(name, f, jac, y, t=1e-3)

    print("=" * 100)
    print("Consistency of the initial values: the algebraic rows' residuals at t = 0")
    print(f"  CHEMAKZO row 6: {akzo_f(0.0, AKZO_Y0)[5]:.1e}")
    ft = trans_f(0.0, TRANS_Y0)
    print(f"  TRANSAMP node sums f1+f2, f4+f5, f7+f8: {ft[0] + ft[1]:.1e}, {ft[3] + ft[4]:.1e}, "
          f"{ft[6] + ft[7]:.1e}")
    print(f"  ROBERDAE row 3: {rober_dae_f(0.0, ROBER_Y0)[2]:.1e}")
    print(f"  PENDULUM row 5: {pend_f(0.0, PEND_Y0)[4]:.1e}   (lambda0 = {PEND_Y0[4]!r})")

    # ---------------- CHEMAKZO ----------------
    print("=" * 100)
    print(f"CHEMAKZO at t = {AKZO_T:g}: reference = chemakzo.f solut (PSIDE, Cray C90, rtol = atol = 1e-19)")
    a_radau = radau_run("the DAE", akzo_f, akzo_jac, AKZO_M, AKZO_Y0, AKZO_T, 1e-12, 1e-14)
    z0 = AKZO_Y0[:5]
    a_sr = scipy_run(akzo_reduced, z0, AKZO_T, "Radau", 1e-13, 1e-16)
    a_sl = scipy_run(akzo_reduced, z0, AKZO_T, "LSODA", 1e-13, 1e-16)
    t0 = time.perf_counter()
    out, steps = mp_radau(akzo_reduced_mp, akzo_reduced_jac_mp, z0, [AKZO_T], 5, 1e-18, 1e-21, 30)
    a_mp = list(out[0]) + [mpf(KS) * out[0][0] * out[0][3]]
    print(f"    mpRadau s=5 dps=30 rtol 1e-18 on the reduced ODE: {steps} steps, "
          f"{time.perf_counter() - t0:.0f} s")
    red = lambda z: list(z) + [KS * z[0] * z[3]]
    print_comparison([f"y{i + 1}" for i in range(6)], AKZO_REF,
                     [("radau_dae DAE", a_radau), ("Radau reduced", red(a_sr)),
                      ("LSODA reduced", red(a_sl)), ("mpRadau reduced", a_mp)])

    # ---------------- TRANSAMP ----------------
    print("=" * 100)
    print(f"TRANSAMP at t = {TRANS_T:g}: reference = transamp.f solut (PSIDE, Cray C90, rtol = atol = 1e-14)")
    # rtol = atol = 1e-10: at 1e-12 the Newton increments of the node voltages stall on rounding
    # above the tolerance and the step size collapses.
    tr_radau = radau_run("the DAE", trans_f, trans_jac, TRANS_M, TRANS_Y0, TRANS_T, 1e-10, 1e-10)
    w0 = [TRANS_Y0[0] - TRANS_Y0[1], TRANS_Y0[2], TRANS_Y0[3] - TRANS_Y0[4], TRANS_Y0[5],
          TRANS_Y0[6] - TRANS_Y0[7]]
    check = trans_full_state(0.0, w0)
    print(f"    node equations solved at t = 0 reproduce y0: max |y - y0| = "
          f"{max(abs(a - b) for a, b in zip(check, TRANS_Y0)):.1e}")
    w_r = scipy_run(trans_reduced, w0, TRANS_T, "Radau", 1e-13, 1e-13)
    w_l = scipy_run(trans_reduced, w0, TRANS_T, "LSODA", 1e-13, 1e-13)
    print_comparison([f"y{i + 1}" for i in range(8)], TRANS_REF,
                     [("radau_dae DAE", tr_radau),
                      ("Radau reduced", trans_full_state(TRANS_T, w_r)),
                      ("LSODA reduced", trans_full_state(TRANS_T, w_l))])

    # ---------------- ROBERDAE ----------------
    print("=" * 100)
    print(f"ROBERDAE at t = {ROBER_T:g}: reference = mpRadau s=7 dps=36 rtol 1e-24 atol 1e-32 on the ODE form")
    runs = {}
    for s, dps, rtol in ((5, 30, 1e-20), (7, 36, 1e-24)):
        t0 = time.perf_counter()
        out, steps = mp_radau(robertson_mp, robertson_jac_mp, ROBER_Y0, [ROBER_T], s, rtol,
                              rtol * 1e-8, dps)
        runs[s] = out[0]
        print(f"    mpRadau s={s} dps={dps} rtol {rtol:g} on the ODE: {steps} steps, "
              f"{time.perf_counter() - t0:.0f} s")
    r_ref = runs[7]
    # atol 1e-18: below ~1e-20 the Newton increments of y2 stall on rounding above it.
    r_dae = radau_run("the DAE", rober_dae_f, rober_dae_jac, ROBER_M, ROBER_Y0, ROBER_T, 1e-12, 1e-18)
    r_sr = scipy_run(robertson, ROBER_Y0, ROBER_T, "Radau", 1e-13, 1e-24, jac=robertson_jac)
    print_comparison([f"y{i + 1}" for i in range(3)], r_ref,
                     [("mpRadau s=5", runs[5]), ("Bari rober.f", ROBER_BARI),
                      ("radau_dae DAE", r_dae), ("Radau ODE", r_sr)])
    with mp.workdps(36):
        print(f"    y1 + y2 + y3 - 1 of the reference: {mp.nstr(sum(r_ref) - 1, 3)}; "
              f"36-digit values: " + ", ".join(mp.nstr(v, 25) for v in r_ref))

    # ---------------- PENDULUM ----------------
    print("=" * 100)
    print(f"PENDULUM at t = {PEND_T:g}: reference = exact angle solution (Jacobi sn, cn; 40 digits)")
    exact, th, dth = pendulum_exact(PEND_T)
    with mp.workdps(40):
        k = mp.sin(mpf(THETA0) / 2)
        period = 4 * mp.ellipk(k * k) / mp.sqrt(mpf(PG) / mpf(PL))
    print(f"    theta(T) = {mp.nstr(th, 20)}, theta'(T) = {mp.nstr(dth, 20)}, period = "
          f"{mp.nstr(period, 20)} s")
    t0 = time.perf_counter()
    out, steps = mp_radau(pend_angle_mp, pend_angle_jac_mp, [THETA0, 0.0], [PEND_T], 5, 1e-20,
                          1e-20, 30)
    th_mp, dth_mp = out[0]
    print(f"    mpRadau s=5 dps=30 rtol 1e-20 on theta'' = -(g/L) sin theta: {steps} steps, "
          f"{time.perf_counter() - t0:.0f} s; |theta - exact| = {mp.nstr(abs(th_mp - th), 3)}, "
          f"|theta' - exact| = {mp.nstr(abs(dth_mp - dth), 3)}")
    with mp.workdps(30):
        ang = [mp.sin(th_mp), -mp.cos(th_mp), dth_mp * mp.cos(th_mp), dth_mp * mp.sin(th_mp),
               dth_mp ** 2 + mpf(PG) * mp.cos(th_mp)]
    p_dae = radau_run("the Cartesian DAE", pend_f, pend_jac, PEND_M, PEND_Y0, PEND_T, 1e-12, 1e-12)
    print(f"    radau_dae drift: x^2 + y^2 - L^2 = {p_dae[0] ** 2 + p_dae[1] ** 2 - PL ** 2:.1e}, "
          f"x u + y v = {p_dae[0] * p_dae[2] + p_dae[1] * p_dae[3]:.1e}")
    print_comparison(["x", "y", "u", "v", "lam"], exact,
                     [("mpRadau angle", ang), ("radau_dae DAE", p_dae)])
    print("    exact state at t = 1, 2, ..., 10 (x, y, u, v, lambda):")
    table = {}
    for tt in range(1, 11):
        st, _, _ = pendulum_exact(tt)
        table[tt] = st
        print(f"      t = {tt:2d}: " + ", ".join(f"{float(v)!r}" for v in st))

    # ---------------- summary ----------------
    print("=" * 100)
    print("References as Rust constants (f64, shortest round-trip):")
    rust_array("CHEMAKZO_REFERENCE", AKZO_REF, "chemakzo.f solut, t = 180")
    rust_array("TRANSAMP_REFERENCE", TRANS_REF, "transamp.f solut, t = 0.2")
    rust_array("ROBERTSON_DAE_1E11", r_ref, "mpRadau s = 7, 36 digits, ODE form, t = 1e11")
    rust_array("PENDULUM_10", exact, "exact (elliptic), t = 10: x, y, u, v, lambda")
    rust_array("PENDULUM_Y0", PEND_Y0, "consistent start: theta0 = 2.5 from rest")
    print(f"total {time.perf_counter() - start:.0f} s")


if __name__ == "__main__":
    sys.exit(main())
