"""Stiff test-set references and SciPy's work statistics on them (not run by CI).

Problems (all constants as IEEE doubles, i.e. exactly the IVP an f64 program integrates)
-----------------------------------------------------------------------------------------
* ROBER -- Robertson kinetics (Hairer & Wanner, "Solving ODEs II", 2nd ed., Sec. IV.10;
  problem ROBER of the Bari test set):  y1' = -k1 y1 + k3 y2 y3,  y2' = k1 y1 - k3 y2 y3 - k2 y2^2,
  y3' = k2 y2^2,  k1 = 0.04, k2 = 3e7, k3 = 1e4,  y(0) = (1, 0, 0).
  Outputs t = 0.4, 4, 40, ..., 4e10 (4 * 10^k) and 1e5, 1e11.
* HIRES -- 8 species (HW II, Sec. IV.10; problem HIRES of the Bari test set), t in [0, 321.8122],
  y(0) = (1, 0, 0, 0, 0, 0, 0, 0.0057); right-hand side as in hires.f:
      y1' = -1.71 y1 + 0.43 y2 + 8.32 y3 + 0.0007       y2' = 1.71 y1 - 8.75 y2
      y3' = -10.03 y3 + 0.43 y4 + 0.035 y5              y4' = 8.32 y2 + 1.71 y3 - 1.12 y4
      y5' = -1.745 y5 + 0.43 y6 + 0.43 y7
      y6' = -280 y6 y8 + 0.69 y4 + 1.71 y5 - 0.43 y6 + 0.69 y7
      y7' = 280 y6 y8 - 1.81 y7                         y8' = -y7'
* POLLU -- air-pollution chemistry, 20 species and 25 reactions (J. G. Verwer, SIAM J. Sci. Comput.
  15 (1994) 1243-1250; problem POLLU of the Bari test set), t in [0, 60], rate constants,
  reactions, right-hand side and Jacobian transcribed from pollu.f (see `pollu` below).
* OREGO -- the Oregonator (Field & Noyes 1974; HW II, Sec. IV.10; problem OREGO of the Bari test
  set), t in [0, 360], y(0) = (1, 2, 3), right-hand side as in orego.f:
      y1' = 77.27 (y2 + y1 (1 - 8.375e-6 y1 - y2))    y2' = (y3 - (1 + y1) y2) / 77.27
      y3' = 0.161 (y1 - y3)
* VDPOL -- van der Pol, mu = 1000: y1' = y2, y2' = mu (1 - y1^2) y2 - y1, y(0) = (2, 0),
  outputs t = 1000, 2000, 3000 (t = 2000 is problem VDPOLM, "van der Pol modified", of the Bari
  test set, exactly this system).

Published reference values (F. Mazzia & C. Magherini, "Test Set for Initial Value Problem Solvers",
release 2.4, Feb. 2008, Dept. of Mathematics, Univ. of Bari, http://www.dm.uniba.it/~testset;
Fortran files rev. 1.2 of 2006/10/02, subroutine `solut`/`hiressol`):
* rober.f  (t = 1e11): RADAU5 on an Alphaserver DS20E, uround 1.01e-19, rtol = atol = h0 = 1.1e-18.
* hires.f  (t = 321.8122): "true double precision RADAU5 on Cray C90", uround 1.01e-19,
  rtol = atol = h0 = 1.1e-18.
* pollu.f  (t = 60): same as hires.f.
* orego.f  (t = 360): same as hires.f.
* vdpolm.f (t = 2000): RADAU on an Alphaserver DS20E, uround 1.01e-19, rtol = atol = h0 = 1.1e-18.

How the references here are computed
------------------------------------
* "mpRadau": a Radau IIA collocation method with s stages (order 2s - 1) written below in mpmath
  (nodes = zeros of P_s(2x-1) - P_{s-1}(2x-1), A from the collocation conditions), simplified
  Newton with the Jacobian at the step's start, step-doubling error estimate, run at two settings
  (s = 5, dps = 30, rtol = 1e-20 and s = 7, dps = 36, rtol = 1e-24; atol = rtol * 1e-8 for ROBER,
  rtol * 1e-3 for VDPOL); their difference bounds its error.  Done for ROBER and VDPOL (2 and 3
  unknowns; HIRES and POLLU are too large for mpmath linear algebra in reasonable time and have the
  published values instead).
* SciPy Radau at rtol = 1e-13 (atol: ROBER 1e-24, HIRES 1e-16, POLLU 1e-20, VDPOL 1e-16), LSODA at
  rtol = 1e-13 (same atol, except ROBER 1e-22: LSODA fails with 1e-24) and BDF at rtol = 1e-12
  (VDPOL: rtol 1e-8, atol 1e-14 -- SciPy's BDF fails at the relaxation jumps for rtol <= 1e-9),
  analytic Jacobian.  Every output time is hit as an integration end point (the run restarts from the
  previous output), so no dense-output interpolation error enters.
The reference used for the error column of the table is: mpRadau (s = 7) for ROBER and VDPOL, the
published Bari values for HIRES and POLLU (our Radau 1e-13 agrees with them to ~1e-13 relative).

Work table
----------
SciPy Radau, BDF and LSODA at rtol in {1e-4, 1e-6, 1e-8}, with atol = rtol * 1e-6 (ROBER, since
y2 ~ 1e-5 .. 1e-13), rtol * 1e-4 (HIRES, POLLU), rtol * 1e-3 (VDPOL, y2 ~ 1e-3 on the slow
branches); analytic Jacobian; one integration from 0 to the final time (no t_eval, no dense output).
Columns: steps = len(sol.t) - 1 (accepted steps), nfev, njev, nlu as SciPy reports them, wall time =
best of 3 time.perf_counter() measurements of the whole solve_ivp call (on a shared 2-core machine,
so treat times as +-20 %), and the final error:
    maxrel = max_i |y_i - ref_i| / |ref_i| over components with |ref_i| >= 1e-10
             (excludes ROBER y2(1e11) ~ 8e-14 and POLLU y16(60) ~ 4e-17),
    maxabs = max_i |y_i - ref_i| over all components.

    pip install numpy scipy mpmath && python3 scripts/reference_stiff.py

Runtime: ~4 minutes (the mpmath Radau runs and the tight SciPy Radau runs dominate).
"""

import math
import time
import warnings

import mpmath
import numpy as np
import scipy
from mpmath import mp, mpf, matrix
from scipy.integrate import solve_ivp


# --------------------------------------------------------------------------------------------
# Problems
# --------------------------------------------------------------------------------------------

def robertson(t, y):
    a, b, c = y
    return np.array([-0.04 * a + 1e4 * b * c, 0.04 * a - 1e4 * b * c - 3e7 * b * b, 3e7 * b * b])


def robertson_jac(t, y):
    a, b, c = y
    return np.array([[-0.04, 1e4 * c, 1e4 * b], [0.04, -1e4 * c - 6e7 * b, -1e4 * b],
                     [0.0, 6e7 * b, 0.0]])


def hires(t, y):
    y1, y2, y3, y4, y5, y6, y7, y8 = y
    f7 = 280.0 * y6 * y8 - 1.81 * y7
    return np.array([-1.71 * y1 + 0.43 * y2 + 8.32 * y3 + 0.0007,
                     1.71 * y1 - 8.75 * y2,
                     -10.03 * y3 + 0.43 * y4 + 0.035 * y5,
                     8.32 * y2 + 1.71 * y3 - 1.12 * y4,
                     -1.745 * y5 + 0.43 * y6 + 0.43 * y7,
                     -280.0 * y6 * y8 + 0.69 * y4 + 1.71 * y5 - 0.43 * y6 + 0.69 * y7,
                     f7, -f7])


def hires_jac(t, y):
    J = np.zeros((8, 8))
    J[0, 0], J[0, 1], J[0, 2] = -1.71, 0.43, 8.32
    J[1, 0], J[1, 1] = 1.71, -8.75
    J[2, 2], J[2, 3], J[2, 4] = -10.03, 0.43, 0.035
    J[3, 1], J[3, 2], J[3, 3] = 8.32, 1.71, -1.12
    J[4, 4], J[4, 5], J[4, 6] = -1.745, 0.43, 0.43
    J[5, 3], J[5, 4], J[5, 5], J[5, 6], J[5, 7] = 0.69, 1.71, -280.0 * y[7] - 0.43, 0.69, -280.0 * y[5]
    J[6, 5], J[6, 6], J[6, 7] = 280.0 * y[7], -1.81, 280.0 * y[5]
    J[7, 5], J[7, 6], J[7, 7] = -280.0 * y[7], 1.81, -280.0 * y[5]
    return J


# pollu.f rate constants k1..k25 (index 0 unused)
PK = [None, .35, .266e2, .123e5, .86e-3, .82e-3, .15e5, .13e-3, .24e5, .165e5, .9e4, .22e-1,
      .12e5, .188e1, .163e5, .48e7, .35e-3, .175e-1, .1e9, .444e12, .124e4, .21e1, .578e1,
      .474e-1, .178e4, .312e1]


def pollu(t, yy):
    k = PK
    y = np.concatenate([[0.0], yy])  # 1-based as in pollu.f
    r = np.zeros(26)
    r[1] = k[1] * y[1]
    r[2] = k[2] * y[2] * y[4]
    r[3] = k[3] * y[5] * y[2]
    r[4] = k[4] * y[7]
    r[5] = k[5] * y[7]
    r[6] = k[6] * y[7] * y[6]
    r[7] = k[7] * y[9]
    r[8] = k[8] * y[9] * y[6]
    r[9] = k[9] * y[11] * y[2]
    r[10] = k[10] * y[11] * y[1]
    r[11] = k[11] * y[13]
    r[12] = k[12] * y[10] * y[2]
    r[13] = k[13] * y[14]
    r[14] = k[14] * y[1] * y[6]
    r[15] = k[15] * y[3]
    r[16] = k[16] * y[4]
    r[17] = k[17] * y[4]
    r[18] = k[18] * y[16]
    r[19] = k[19] * y[16]
    r[20] = k[20] * y[17] * y[6]
    r[21] = k[21] * y[19]
    r[22] = k[22] * y[19]
    r[23] = k[23] * y[1] * y[4]
    r[24] = k[24] * y[19] * y[1]
    r[25] = k[25] * y[20]
    return np.array([
        -r[1] - r[10] - r[14] - r[23] - r[24] + r[2] + r[3] + r[9] + r[11] + r[12] + r[22] + r[25],
        -r[2] - r[3] - r[9] - r[12] + r[1] + r[21],
        -r[15] + r[1] + r[17] + r[19] + r[22],
        -r[2] - r[16] - r[17] - r[23] + r[15],
        -r[3] + r[4] + r[4] + r[6] + r[7] + r[13] + r[20],
        -r[6] - r[8] - r[14] - r[20] + r[3] + r[18] + r[18],
        -r[4] - r[5] - r[6] + r[13],
        r[4] + r[5] + r[6] + r[7],
        -r[7] - r[8],
        -r[12] + r[7] + r[9],
        -r[9] - r[10] + r[8] + r[11],
        r[9],
        -r[11] + r[10],
        -r[13] + r[12],
        r[14],
        -r[18] - r[19] + r[16],
        -r[20],
        r[20],
        -r[21] - r[22] - r[24] + r[23] + r[25],
        -r[25] + r[24]])


def pollu_jac(t, yy):
    k = PK
    y = np.concatenate([[0.0], yy])
    D = np.zeros((21, 21))  # 1-based as in pollu.f's jeval
    D[1, 1] = -k[1] - k[10] * y[11] - k[14] * y[6] - k[23] * y[4] - k[24] * y[19]
    D[1, 11] = -k[10] * y[1] + k[9] * y[2]
    D[1, 6] = -k[14] * y[1]
    D[1, 4] = -k[23] * y[1] + k[2] * y[2]
    D[1, 19] = -k[24] * y[1] + k[22]
    D[1, 2] = k[2] * y[4] + k[9] * y[11] + k[3] * y[5] + k[12] * y[10]
    D[1, 13] = k[11]
    D[1, 20] = k[25]
    D[1, 5] = k[3] * y[2]
    D[1, 10] = k[12] * y[2]
    D[2, 4] = -k[2] * y[2]
    D[2, 5] = -k[3] * y[2]
    D[2, 11] = -k[9] * y[2]
    D[2, 10] = -k[12] * y[2]
    D[2, 19] = k[21]
    D[2, 1] = k[1]
    D[2, 2] = -k[2] * y[4] - k[3] * y[5] - k[9] * y[11] - k[12] * y[10]
    D[3, 1] = k[1]
    D[3, 4] = k[17]
    D[3, 16] = k[19]
    D[3, 19] = k[22]
    D[3, 3] = -k[15]
    D[4, 4] = -k[2] * y[2] - k[16] - k[17] - k[23] * y[1]
    D[4, 2] = -k[2] * y[4]
    D[4, 1] = -k[23] * y[4]
    D[4, 3] = k[15]
    D[5, 5] = -k[3] * y[2]
    D[5, 2] = -k[3] * y[5]
    D[5, 7] = 2.0 * k[4] + k[6] * y[6]
    D[5, 6] = k[6] * y[7] + k[20] * y[17]
    D[5, 9] = k[7]
    D[5, 14] = k[13]
    D[5, 17] = k[20] * y[6]
    D[6, 6] = -k[6] * y[7] - k[8] * y[9] - k[14] * y[1] - k[20] * y[17]
    D[6, 7] = -k[6] * y[6]
    D[6, 9] = -k[8] * y[6]
    D[6, 1] = -k[14] * y[6]
    D[6, 17] = -k[20] * y[6]
    D[6, 2] = k[3] * y[5]
    D[6, 5] = k[3] * y[2]
    D[6, 16] = 2.0 * k[18]
    D[7, 7] = -k[4] - k[5] - k[6] * y[6]
    D[7, 6] = -k[6] * y[7]
    D[7, 14] = k[13]
    D[8, 7] = k[4] + k[5] + k[6] * y[6]
    D[8, 6] = k[6] * y[7]
    D[8, 9] = k[7]
    D[9, 9] = -k[7] - k[8] * y[6]
    D[9, 6] = -k[8] * y[9]
    D[10, 10] = -k[12] * y[2]
    D[10, 2] = -k[12] * y[10] + k[9] * y[11]
    D[10, 9] = k[7]
    D[10, 11] = k[9] * y[2]
    D[11, 11] = -k[9] * y[2] - k[10] * y[1]
    D[11, 2] = -k[9] * y[11]
    D[11, 1] = -k[10] * y[11]
    D[11, 9] = k[8] * y[6]
    D[11, 6] = k[8] * y[9]
    D[11, 13] = k[11]
    D[12, 11] = k[9] * y[2]
    D[12, 2] = k[9] * y[11]
    D[13, 13] = -k[11]
    D[13, 11] = k[10] * y[1]
    D[13, 1] = k[10] * y[11]
    D[14, 14] = -k[13]
    D[14, 10] = k[12] * y[2]
    D[14, 2] = k[12] * y[10]
    D[15, 1] = k[14] * y[6]
    D[15, 6] = k[14] * y[1]
    D[16, 16] = -k[18] - k[19]
    D[16, 4] = k[16]
    D[17, 17] = -k[20] * y[6]
    D[17, 6] = -k[20] * y[17]
    D[18, 17] = k[20] * y[6]
    D[18, 6] = k[20] * y[17]
    D[19, 19] = -k[21] - k[22] - k[24] * y[1]
    D[19, 1] = -k[24] * y[19] + k[23] * y[4]
    D[19, 4] = k[23] * y[1]
    D[19, 20] = k[25]
    D[20, 20] = -k[25]
    D[20, 1] = k[24] * y[19]
    D[20, 19] = k[24] * y[1]
    return D[1:, 1:]


MU = 1000.0


def orego(t, y):
    return [77.27 * (y[1] + y[0] * (1 - 8.375e-6 * y[0] - y[1])),
            (y[2] - (1 + y[0]) * y[1]) / 77.27,
            0.161 * (y[0] - y[2])]


def orego_jac(t, y):
    return [[77.27 * (1 - 2 * 8.375e-6 * y[0] - y[1]), 77.27 * (1 - y[0]), 0],
            [-y[1] / 77.27, -(1 + y[0]) / 77.27, 1 / 77.27],
            [0.161, 0, -0.161]]


def vdp(t, y):
    return np.array([y[1], MU * (1.0 - y[0] ** 2) * y[1] - y[0]])


def vdp_jac(t, y):
    return np.array([[0.0, 1.0], [-2.0 * MU * y[0] * y[1] - 1.0, MU * (1.0 - y[0] ** 2)]])


# mpmath versions (constants are the doubles above, converted exactly)
MK1 = mpf(0.04)


def robertson_mp(t, y):
    a, b, c = y
    return [-MK1 * a + 10 ** 4 * b * c, MK1 * a - 10 ** 4 * b * c - 3 * 10 ** 7 * b * b,
            3 * 10 ** 7 * b * b]


def robertson_jac_mp(t, y):
    a, b, c = y
    return [[-MK1, 10 ** 4 * c, 10 ** 4 * b], [MK1, -10 ** 4 * c - 6 * 10 ** 7 * b, -10 ** 4 * b],
            [0, 6 * 10 ** 7 * b, 0]]


def vdp_mp(t, y):
    return [y[1], 1000 * (1 - y[0] ** 2) * y[1] - y[0]]


def vdp_jac_mp(t, y):
    return [[0, 1], [-2000 * y[0] * y[1] - 1, 1000 * (1 - y[0] ** 2)]]


ROBER_TIMES = sorted([4 * 10.0 ** k for k in range(-1, 11)] + [1e5, 1e11])
VDP_TIMES = [1000.0, 2000.0, 3000.0]

BARI = {
    "ROBER": (1e11, [0.2083340149701255e-07, 0.8333360770334713e-13, 0.9999999791665050]),
    "HIRES": (321.8122, [0.7371312573325668e-3, 0.1442485726316185e-3, 0.5888729740967575e-4,
                         0.1175651343283149e-2, 0.2386356198831331e-2, 0.6238968252742796e-2,
                         0.2849998395185769e-2, 0.2850001604814231e-2]),
    "POLLU": (60.0, [0.5646255480022769e-01, 0.1342484130422339e+00, 0.4139734331099427e-08,
                     0.5523140207484359e-02, 0.2018977262302196e-06, 0.1464541863493966e-06,
                     0.7784249118997964e-01, 0.3245075353396018e+00, 0.7494013383880406e-02,
                     0.1622293157301561e-07, 0.1135863833257075e-07, 0.2230505975721359e-02,
                     0.2087162882798630e-03, 0.1396921016840158e-04, 0.8964884856898295e-02,
                     0.4352846369330103e-17, 0.6899219696263405e-02, 0.1007803037365946e-03,
                     0.1772146513969984e-05, 0.5682943292316392e-04]),
    "OREGO": (360.0, [0.1000814870318523e+01, 0.1228178521549917e+04, 0.1320554942846706e+03]),
    "VDPOL": (2000.0, [0.1706167732170469e+01, -0.8928097010248125e-03]),
}


# --------------------------------------------------------------------------------------------
# Radau IIA in mpmath
# --------------------------------------------------------------------------------------------

def radau_tableau(s):
    def shifted_legendre(n):  # coefficients (low to high) of P_n(2x - 1)
        return [mpf((-1) ** (n + k) * math.comb(n, k) * math.comb(n + k, k)) for k in range(n + 1)]
    q = [a - b for a, b in zip(shifted_legendre(s), shifted_legendre(s - 1) + [mpf(0)])]
    roots = mp.polyroots(q[::-1], maxsteps=200, extraprec=4 * mp.prec)
    c = sorted(mp.re(r) for r in roots)
    c[-1] = mpf(1)
    V, Ch = matrix(s, s), matrix(s, s)
    for i in range(s):
        for k in range(s):
            V[i, k] = c[i] ** k               # sum_j a_ij c_j^(k-1) = c_i^k / k
            Ch[i, k] = c[i] ** (k + 1) / (k + 1)
    A = Ch * V ** -1
    return c, [[A[i, j] for j in range(s)] for i in range(s)]


def lu_factor(M):
    n = len(M)
    M = [row[:] for row in M]
    piv = list(range(n))
    for j in range(n):
        p = max(range(j, n), key=lambda i: abs(M[i][j]))
        if p != j:
            M[j], M[p] = M[p], M[j]
            piv[j], piv[p] = piv[p], piv[j]
        for i in range(j + 1, n):
            m = M[i][j] / M[j][j]
            M[i][j] = m
            if m:
                Mi, Mj = M[i], M[j]
                for k in range(j + 1, n):
                    Mi[k] -= m * Mj[k]
    return M, piv


def lu_solve(LU, b):
    M, piv = LU
    n = len(M)
    x = [b[piv[i]] for i in range(n)]
    for i in range(1, n):
        x[i] -= mp.fdot(M[i][:i], x[:i])
    for i in range(n - 1, -1, -1):
        if i < n - 1:
            x[i] -= mp.fdot(M[i][i + 1:], x[i + 1:])
        x[i] /= M[i][i]
    return x


def radau_stages(f, t, y, h, c, A, J0, newton_tol):
    """Solve the collocation equations by simplified Newton; returns y(t + h) or None."""
    s, n = len(c), len(y)
    M = [[mpf(0)] * (s * n) for _ in range(s * n)]
    for i in range(s):
        for k in range(n):
            M[i * n + k][i * n + k] = mpf(1)
            for j in range(s):
                a = h * A[i][j]
                for l in range(n):
                    M[i * n + k][j * n + l] -= a * J0[k][l]
    LU = lu_factor(M)
    Z = [[mpf(0)] * n for _ in range(s)]
    prev = None
    for it in range(40):
        F = [f(t + c[j] * h, [y[k] + Z[j][k] for k in range(n)]) for j in range(s)]
        G = [h * mp.fdot(A[i], [F[j][k] for j in range(s)]) - Z[i][k]
             for i in range(s) for k in range(n)]
        d = lu_solve(LU, G)
        ratio = max(abs(d[i * n + k]) / newton_tol[k] for i in range(s) for k in range(n))
        for i in range(s):
            for k in range(n):
                Z[i][k] += d[i * n + k]
        if ratio < 1:
            return [y[k] + Z[s - 1][k] for k in range(n)]
        if prev is not None and it > 3 and ratio > 0.9 * prev:
            return None
        prev = ratio
    return None


def mp_radau(f, jac, y0, touts, s, rtol, atol, dps, h0=1e-6):
    """Radau IIA (s stages, order 2s-1) with step doubling; returns states at touts, steps."""
    with mp.workdps(dps):
        c, A = radau_tableau(s)
        p = 2 * s - 1
        rtol, atol = mpf(rtol), mpf(atol)
        t, y, h = mpf(0), [mpf(v) for v in y0], mpf(h0)
        eps_newton = mpf(10) ** (-(dps - 4))
        out, steps, rejected = [], 0, 0
        for tout in touts:
            tout = mpf(tout)
            while t < tout:
                last = t + h >= tout
                hh = tout - t if last else h
                ntol = [eps_newton * (abs(v) + atol / rtol) for v in y]
                J0 = jac(t, y)
                y2 = None
                y1 = radau_stages(f, t, y, hh, c, A, J0, ntol)
                if y1 is not None:
                    ym = radau_stages(f, t, y, hh / 2, c, A, J0, ntol)
                    if ym is not None:
                        y2 = radau_stages(f, t + hh / 2, ym, hh / 2, c, A, jac(t + hh / 2, ym), ntol)
                if y2 is None:  # Newton failed to converge
                    h = hh / 4
                    rejected += 1
                    continue
                err = max(abs(a - b) / (atol + rtol * max(abs(a), abs(v)))
                          for a, b, v in zip(y2, y1, y)) / (2 ** p - 1)
                fac = min(mpf(4), max(mpf("0.2"),
                                      mpf("0.9") * (err + mpf(10) ** -80) ** (mpf(-1) / (p + 1))))
                if err <= 1:
                    t = tout if last else t + hh
                    y = y2
                    steps += 1
                    h = max(h, hh * fac) if last else hh * fac
                else:
                    h = hh * fac
                    rejected += 1
            out.append([+v for v in y])
        return out, steps


# --------------------------------------------------------------------------------------------
# helpers
# --------------------------------------------------------------------------------------------

def scipy_chain(f, jac, y0, times, method, rtol, atol):
    """Integrate through the output times, each one an end point (restart from the last)."""
    y, t, out, steps = np.array(y0, float), 0.0, [], 0
    for T in times:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            sol = solve_ivp(f, (t, T), y, method=method, jac=jac, rtol=rtol, atol=atol)
        if not sol.success:
            return None, f"failed at t = {sol.t[-1]:.6g}: {sol.message}"
        y, t = sol.y[:, -1], T
        out.append(y)
        steps += len(sol.t) - 1
    return out, steps


def s20(x):
    return mp.nstr(mpf(x), 20, min_fixed=0, max_fixed=0, strip_zeros=False)


def maxrel(y, ref, floor=1e-10):
    return max(abs(float(a) - float(b)) / abs(float(b)) for a, b in zip(y, ref) if abs(b) >= floor)


def maxabs(y, ref):
    return max(abs(float(a) - float(b)) for a, b in zip(y, ref))


def rel_components(y, ref):
    return [abs(mpf(a) - mpf(b)) / abs(mpf(b)) if b != 0 else abs(mpf(a)) for a, b in zip(y, ref)]


# --------------------------------------------------------------------------------------------
# references
# --------------------------------------------------------------------------------------------

def references():
    mp.dps = 40
    refs = {}

    # ---------------- ROBER and VDPOL: mpRadau + SciPy ----------------
    for name, f, jac, fm, jm, y0, times, atol_scale, scipy_runs in (
            ("ROBER", robertson, robertson_jac, robertson_mp, robertson_jac_mp, [1.0, 0.0, 0.0],
             ROBER_TIMES, 1e-8, (("Radau", 1e-13, 1e-24), ("LSODA", 1e-13, 1e-22),
                                 ("BDF", 1e-12, 1e-24))),
            ("VDPOL", vdp, vdp_jac, vdp_mp, vdp_jac_mp, [2.0, 0.0], VDP_TIMES, 1e-3,
             (("Radau", 1e-13, 1e-16), ("LSODA", 1e-13, 1e-16), ("BDF", 1e-8, 1e-14)))):
        print("=" * 100)
        print(f"{name}: reference = mpRadau (s = 7, dps 36, rtol 1e-24). Per component: the value, "
              f"|mpRadau5 - mpRadau7| / |ref|, then |x - ref| / |ref| for x = "
              + ", ".join(f"SciPy {m} {r:g}" for m, r, _ in scipy_runs))
        mpruns = []
        for s, dps, rtol in ((5, 30, 1e-20), (7, 36, 1e-24)):
            t0 = time.perf_counter()
            out, steps = mp_radau(fm, jm, y0, times, s, rtol, rtol * atol_scale, dps)
            mpruns.append(out)
            print(f"  mpRadau s={s} dps={dps} rtol={rtol:g} atol={rtol * atol_scale:g}: {steps} steps, "
                  f"{time.perf_counter() - t0:.0f} s")
        sp = {}
        for method, rtol, atol_ref in scipy_runs:
            t0 = time.perf_counter()
            out, steps = scipy_chain(f, jac, y0, times, method, rtol, atol_ref)
            sp[method] = out
            print(f"  SciPy {method} rtol={rtol:g} atol={atol_ref:g}: "
                  + (f"{steps} steps, {time.perf_counter() - t0:.1f} s" if out else steps))
        for k, T in enumerate(times):
            ref = mpruns[1][k]
            print(f"  t = {T:g}:")
            for i, v in enumerate(ref):
                d57 = abs(mpruns[0][k][i] - v) / abs(v)
                line = f"    y{i + 1} = {s20(v):>28}   f64: {float(v):+.16e}   rel|mp5-mp7| = {float(d57):.1e}"
                for method in sp:
                    if sp[method] is not None:
                        line += f"   {method} {float(abs(mpf(sp[method][k][i]) - v) / abs(v)):.1e}"
                print(line)
            if name in BARI and BARI[name][0] == T:
                bari = BARI[name][1]
                print(f"    Bari published ({name}): " + ", ".join(f"{v:.16e}" for v in bari))
                print("    |Bari - ref| / |ref| per component: "
                      + ", ".join(f"{float(r):.1e}" for r in rel_components(bari, ref)))
            if name == "ROBER":
                print(f"    conservation: y1 + y2 + y3 - 1 = {mp.nstr(sum(ref) - 1, 3)} (mpRadau7)"
                      + (f", {mp.nstr(sum(mpf(v) for v in BARI['ROBER'][1]) - 1, 3)} (Bari)"
                         if T == 1e11 else ""))
        refs[name] = {T: [float(v) for v in mpruns[1][k]] for k, T in enumerate(times)}

    # ---------------- HIRES and POLLU: published + SciPy ----------------
    for name, f, jac, y0, atol_ref in (
            ("HIRES", hires, hires_jac, [1, 0, 0, 0, 0, 0, 0, 0.0057], 1e-16),
            ("POLLU", pollu, pollu_jac,
             [0, 0.2, 0, 0.04, 0, 0, 0.1, 0.3, 0.01, 0, 0, 0, 0, 0, 0, 0, 0.007, 0, 0, 0], 1e-20),
            ("OREGO", orego, orego_jac, [1, 2, 3], 1e-16)):
        T, bari = BARI[name]
        print("=" * 100)
        print(f"{name} at t = {T:.10g}: reference = Bari published value. Per component: Bari, SciPy "
              f"Radau 1e-13, then |x - Bari| / |Bari| for x = SciPy Radau 1e-13, LSODA 1e-13, "
              f"BDF 1e-12 (atol {atol_ref:g})")
        sp = {}
        for method, rtol in (("Radau", 1e-13), ("LSODA", 1e-13), ("BDF", 1e-12)):
            t0 = time.perf_counter()
            out, steps = scipy_chain(f, jac, y0, [T], method, rtol, atol_ref)
            sp[method] = out[0]
            print(f"  SciPy {method} rtol={rtol:g}: {steps} steps, {time.perf_counter() - t0:.1f} s")
        for i, v in enumerate(bari):
            line = f"    y{i + 1:<2} Bari {v:+.16e}   Radau {sp['Radau'][i]:+.16e}  "
            for method in sp:
                line += f"   {method} {abs(sp[method][i] - v) / abs(v):.1e}"
            print(line)
        print(f"  max rel (|Bari| >= 1e-10): " + ", ".join(
            f"{m} {maxrel(sp[m], bari):.1e}" for m in sp))
        refs[name] = {T: bari}
    return refs


# --------------------------------------------------------------------------------------------
# work table
# --------------------------------------------------------------------------------------------

def table(refs):
    print("=" * 100)
    print("SciPy work table: one solve_ivp call from 0 to t_end, analytic Jacobian; "
          "time = best of 3; maxrel over |ref| >= 1e-10")
    problems = [
        ("ROBER", 1e5, robertson, robertson_jac, [1.0, 0.0, 0.0], 1e-6, refs["ROBER"][1e5]),
        ("ROBER", 1e11, robertson, robertson_jac, [1.0, 0.0, 0.0], 1e-6, refs["ROBER"][1e11]),
        ("HIRES", 321.8122, hires, hires_jac, [1, 0, 0, 0, 0, 0, 0, 0.0057], 1e-4,
         refs["HIRES"][321.8122]),
        ("POLLU", 60.0, pollu, pollu_jac,
         [0, 0.2, 0, 0.04, 0, 0, 0.1, 0.3, 0.01, 0, 0, 0, 0, 0, 0, 0, 0.007, 0, 0, 0], 1e-4,
         refs["POLLU"][60.0]),
        ("VDPOL", 3000.0, vdp, vdp_jac, [2.0, 0.0], 1e-3, refs["VDPOL"][3000.0]),
    ]
    print(f"{'problem':<7} {'t_end':>9} {'method':<6} {'rtol':>6} {'atol':>6} {'steps':>6} "
          f"{'nfev':>7} {'njev':>5} {'nlu':>6} {'time [ms]':>10} {'maxrel':>9} {'maxabs':>9}")
    for name, T, f, jac, y0, atol_scale, ref in problems:
        for method in ("Radau", "BDF", "LSODA"):
            for rtol in (1e-4, 1e-6, 1e-8):
                atol = rtol * atol_scale
                best = math.inf
                for _ in range(3):
                    with warnings.catch_warnings():
                        warnings.simplefilter("ignore")
                        t0 = time.perf_counter()
                        sol = solve_ivp(f, (0.0, T), y0, method=method, jac=jac, rtol=rtol, atol=atol)
                        best = min(best, time.perf_counter() - t0)
                if not sol.success:
                    print(f"{name:<7} {T:>9.7g} {method:<6} {rtol:>6.0e} {atol:>6.0e}  FAILED: "
                          f"{sol.message} (t = {sol.t[-1]:.6g})")
                    continue
                y = sol.y[:, -1]
                print(f"{name:<7} {T:>9.7g} {method:<6} {rtol:>6.0e} {atol:>6.0e} {len(sol.t) - 1:>6d} "
                      f"{sol.nfev:>7d} {sol.njev:>5d} {sol.nlu:>6d} {best * 1e3:>10.2f} "
                      f"{maxrel(y, ref):>9.2e} {maxabs(y, ref):>9.2e}")


if __name__ == "__main__":
    print(f"scipy {scipy.__version__}, numpy {np.__version__}, mpmath {mpmath.__version__}")
    t_start = time.perf_counter()
    refs = references()
    table(refs)
    print(f"total {time.perf_counter() - t_start:.0f} s")
