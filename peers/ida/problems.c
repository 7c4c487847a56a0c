/*
 * problems.c: the DAEs of problems.h, with the constants and operation order of their sources.
 *
 * chemakzo: F. Mazzia & C. Magherini, "Test Set for Initial Value Problem Solvers", release 2.4
 *   (2008), University of Bari, problem file chemakzo.f rev. 1.2 (2006/10/02), as vendored in
 *   MESAHub/mesa num/test/src/bari_chemakzo.f (commit 13fe30d5): feval, jeval, meval
 *   (M = diag(1, 1, 1, 1, 1, 0)), init (y6(0) = Ks y1(0) y4(0)) and solut (PSIDE on a Cray C90,
 *   rtol = atol = 1e-19).
 * transamp: same test set, transamp.f rev. 1.3 (2006/10/25), as vendored in rforge/bvpsolve
 *   pkg/deTestSet/src/Ex_transistor.f (commit 14b319e0), and the banded meval of the test set's
 *   file: M tridiagonal with blocks [[-C1, C1], [C1, -C1]], -C2, [[-C3, C3], [C3, -C3]], -C4,
 *   [[-C5, C5], [C5, -C5]], Ck = k * 1e-6 (rank 5); solut from PSIDE, rtol = atol = 1e-14.
 * roberdae: Robertson kinetics (Hairer & Wanner II, IV.10) with the conservation law as row 3;
 *   reference: the 36-digit Radau IIA run of scripts/reference_dae.py on the ODE form (agrees
 *   with the test set's rober.f value to 1.9e-14).
 */
#include "problems.h"

#include <math.h>
#include <string.h>

/* ---------------------------------------------------------------------------------------- */
/* chemakzo */

#define K1 18.7
#define K2 0.58
#define K3 0.09
#define K4 0.42
#define KBIG 34.4
#define KLA 3.3
#define KS 115.83
#define PO2 0.9
#define HEN 737.0

static void akzo_f(double t, const double *y, double *f) {
  (void)t;
  double sqy2 = sqrt(y[1]);
  double r1 = K1 * y[0] * y[0] * y[0] * y[0] * sqy2;
  double r2 = K2 * y[2] * y[3];
  double r3 = K2 / KBIG * y[0] * y[4];
  double r4 = K3 * y[0] * y[3] * y[3];
  double r5 = K4 * (y[5] * y[5]) * sqy2;
  double fin = KLA * (PO2 / HEN - y[1]);
  f[0] = ((-2.0 * r1 + r2) - r3) - r4;
  f[1] = ((-0.5 * r1 - r4) - 0.5 * r5) + fin;
  f[2] = (r1 - r2) + r3;
  f[3] = (-r2 + r3) - 2.0 * r4;
  f[4] = (r2 - r3) + r5;
  f[5] = KS * y[0] * y[3] - y[5];
}

static void akzo_jac(double t, const double *y, double *j) {
  (void)t;
  double y13 = y[0] * y[0] * y[0], sq = sqrt(y[1]);
  double r11 = 4.0 * K1 * y13 * sq, r12 = 0.5 * K1 * y[0] * y13 / sq;
  double r23 = K2 * y[3], r24 = K2 * y[2];
  double r31 = (K2 / KBIG) * y[4], r35 = (K2 / KBIG) * y[0];
  double r41 = K3 * y[3] * y[3], r44 = 2.0 * K3 * y[0] * y[3];
  double r52 = 0.5 * K4 * y[5] * y[5] / sq, r56 = 2.0 * K4 * y[5] * sq;
  memset(j, 0, 36 * sizeof(double));
  j[0] = (-2.0 * r11 - r31) - r41, j[1] = -2.0 * r12, j[2] = r23, j[3] = r24 - r44, j[4] = -r35;
  j[6] = -0.5 * r11 - r41, j[7] = -0.5 * r12 - 0.5 * r52 - KLA, j[9] = -r44, j[11] = -0.5 * r56;
  j[12] = r11 + r31, j[13] = r12, j[14] = -r23, j[15] = -r24, j[16] = r35;
  j[18] = r31 - 2.0 * r41, j[20] = -r23, j[21] = -r24 - 2.0 * r44, j[22] = r35;
  j[24] = -r31, j[25] = r52, j[26] = r23, j[27] = r24, j[28] = -r35, j[29] = r56;
  j[30] = KS * y[3], j[33] = KS * y[0], j[35] = -1.0;
}

/* ---------------------------------------------------------------------------------------- */
/* transamp */

#define UB 6.0
#define UF 0.026
#define ALPHA 0.99
#define BETA 1e-6
#define R0 1000.0
#define RK 9000.0 /* r1 .. r9 */
#define PI_F 3.1415926535897931086244
#define C1 1e-6
#define C2 2e-6
#define C3 3e-6
#define C4 4e-6
#define C5 5e-6

static void trans_f(double t, const double *y, double *f) {
  double uet = 0.1 * sin(200.0 * PI_F * t);
  double fac1 = BETA * (exp((y[1] - y[2]) / UF) - 1.0);
  double fac2 = BETA * (exp((y[4] - y[5]) / UF) - 1.0);
  f[0] = (y[0] - uet) / R0;
  f[1] = y[1] / RK + (y[1] - UB) / RK + (1.0 - ALPHA) * fac1;
  f[2] = y[2] / RK - fac1;
  f[3] = (y[3] - UB) / RK + ALPHA * fac1;
  f[4] = y[4] / RK + (y[4] - UB) / RK + (1.0 - ALPHA) * fac2;
  f[5] = y[5] / RK - fac2;
  f[6] = (y[6] - UB) / RK + ALPHA * fac2;
  f[7] = y[7] / RK;
}

static void trans_jac(double t, const double *y, double *j) {
  (void)t;
  double g1 = BETA * exp((y[1] - y[2]) / UF) / UF;
  double g2 = BETA * exp((y[4] - y[5]) / UF) / UF;
  memset(j, 0, 64 * sizeof(double));
  j[0] = 1.0 / R0;
  j[9] = 1.0 / RK + 1.0 / RK + (1.0 - ALPHA) * g1, j[10] = -(1.0 - ALPHA) * g1;
  j[17] = -g1, j[18] = 1.0 / RK + g1;
  j[25] = ALPHA * g1, j[26] = -ALPHA * g1, j[27] = 1.0 / RK;
  j[36] = 1.0 / RK + 1.0 / RK + (1.0 - ALPHA) * g2, j[37] = -(1.0 - ALPHA) * g2;
  j[44] = -g2, j[45] = 1.0 / RK + g2;
  j[52] = ALPHA * g2, j[53] = -ALPHA * g2, j[54] = 1.0 / RK;
  j[63] = 1.0 / RK;
}

/* ---------------------------------------------------------------------------------------- */
/* roberdae */

static void rober_f(double t, const double *y, double *f) {
  (void)t;
  f[0] = -0.04 * y[0] + 1e4 * y[1] * y[2];
  f[1] = 0.04 * y[0] - 1e4 * y[1] * y[2] - 3e7 * y[1] * y[1];
  f[2] = y[0] + y[1] + y[2] - 1.0;
}

static void rober_jac(double t, const double *y, double *j) {
  (void)t;
  j[0] = -0.04, j[1] = 1e4 * y[2], j[2] = 1e4 * y[1];
  j[3] = 0.04, j[4] = -1e4 * y[2] - 6e7 * y[1], j[5] = -1e4 * y[1];
  j[6] = 1.0, j[7] = 1.0, j[8] = 1.0;
}

/* ---------------------------------------------------------------------------------------- */

static const Problem PROBLEMS[] = {
    {.name = "chemakzo",
     .n = 6,
     .t_end = 180.0,
     .atol_scale = 1e-4,
     .f = akzo_f,
     .jac = akzo_jac,
     .mass = {1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0,
              0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0, 0, 0},
     .y0 = {0.444, 0.00123, 0.0, 0.007, 0.0, KS * 0.444 * 0.007},
     .dfdt0 = {0},
     .n_null = 1,
     .null = {{0, 0, 0, 0, 0, 1}},
     .reference = {0.1150794920661702e0, 0.1203831471567715e-2, 0.1611562887407974e0,
                   0.3656156421249283e-3, 0.1708010885264404e-1, 0.4873531310307455e-2}},
    {.name = "transamp",
     .n = 8,
     .t_end = 0.2,
     .atol_scale = 1e-4,
     .f = trans_f,
     .jac = trans_jac,
     .mass = {-C1, C1,  0,   0,   0,   0,   0,   0,   C1, -C1, 0,   0,   0,   0,   0,   0,
              0,   0,   -C2, 0,   0,   0,   0,   0,   0,   0,   0,   -C3, C3,  0,   0,   0,
              0,   0,   0,   C3,  -C3, 0,   0,   0,   0,   0,   0,   0,   0,   -C4, 0,   0,
              0,   0,   0,   0,   0,   0,   -C5, C5,  0,   0,   0,   0,   0,   0,   C5,  -C5},
     .y0 = {0.0, UB / (RK / RK + 1.0), UB / (RK / RK + 1.0), UB, UB / (RK / RK + 1.0),
            UB / (RK / RK + 1.0), UB, 0.0},
     /* d/dt of (y1 - 0.1 sin(200 pi t)) / R0 at t = 0 */
     .dfdt0 = {-0.1 * 200.0 * PI_F / R0},
     .n_null = 3,
     .null = {{1, 1, 0, 0, 0, 0, 0, 0}, {0, 0, 0, 1, 1, 0, 0, 0}, {0, 0, 0, 0, 0, 0, 1, 1}},
     .reference = {-0.5562145012262709e-002, 0.3006522471903042e+001, 0.2849958788608128e+001,
                   0.2926422536206241e+001, 0.2704617865010554e+001, 0.2761837778393145e+001,
                   0.4770927631616772e+001, 0.1236995868091548e+001}},
    {.name = "roberdae",
     .n = 3,
     .t_end = 1e11,
     .atol_scale = 1e-8,
     .f = rober_f,
     .jac = rober_jac,
     .mass = {1, 0, 0, 0, 1, 0, 0, 0, 0},
     .y0 = {1.0, 0.0, 0.0},
     .dfdt0 = {0},
     .n_null = 1,
     .null = {{0, 0, 1}},
     .reference = {2.083340149701294e-08, 8.333360770334784e-14, 0.9999999791665152}},
};

const Problem *find_problem(const char *name) {
  for (size_t k = 0; k < sizeof PROBLEMS / sizeof PROBLEMS[0]; k++) {
    if (strcmp(PROBLEMS[k].name, name) == 0) return &PROBLEMS[k];
  }
  return NULL;
}

/* Gaussian elimination with partial pivoting on the n x n row-major a; x = a^-1 b in b. */
static int solve_dense(int n, double *a, double *b) {
  for (int c = 0; c < n; c++) {
    int p = c;
    for (int r = c + 1; r < n; r++)
      if (fabs(a[r * n + c]) > fabs(a[p * n + c])) p = r;
    if (a[p * n + c] == 0.0) return -1;
    if (p != c) {
      for (int k = 0; k < n; k++) {
        double s = a[c * n + k];
        a[c * n + k] = a[p * n + k], a[p * n + k] = s;
      }
      double s = b[c];
      b[c] = b[p], b[p] = s;
    }
    for (int r = c + 1; r < n; r++) {
      double m = a[r * n + c] / a[c * n + c];
      for (int k = c; k < n; k++) a[r * n + k] -= m * a[c * n + k];
      b[r] -= m * b[c];
    }
  }
  for (int r = n - 1; r >= 0; r--) {
    for (int k = r + 1; k < n; k++) b[r] -= a[r * n + k] * b[k];
    b[r] /= a[r * n + r];
  }
  return 0;
}

int consistent_yp0(const Problem *p, double *yp0) {
  int n = p->n;
  double a[MAX_N * MAX_N], f[MAX_N], j[MAX_N * MAX_N];
  p->f(0.0, p->y0, f);
  p->jac(0.0, p->y0, j);
  memcpy(a, p->mass, sizeof(double) * n * n);
  memcpy(yp0, f, sizeof(double) * n);
  /* Null vector k relates rows of M y' = f through its last nonzero entry r: that row is
   * redundant, and its place takes N (J y' + df/dt) = 0. */
  for (int k = 0; k < p->n_null; k++) {
    int r = n - 1;
    while (p->null[k][r] == 0.0) r--;
    yp0[r] = 0.0;
    for (int c = 0; c < n; c++) {
      a[r * n + c] = 0.0;
      for (int i = 0; i < n; i++) a[r * n + c] += p->null[k][i] * j[i * n + c];
      yp0[r] -= p->null[k][c] * p->dfdt0[c];
    }
  }
  return solve_dense(n, a, yp0);
}
