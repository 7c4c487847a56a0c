/*
 * problems.h: three index-1 DAEs in mass-matrix form M y' = f(t, y) for the IDA peer
 * (ida_dae.c), transcribed from their sources (see problems.c and notes/dae-problems.md):
 *
 *   chemakzo   Chemical Akzo Nobel (Bari test set chemakzo.f), n = 6, t in [0, 180]
 *   transamp   Transistor amplifier (Bari test set transamp.f), n = 8, t in [0, 0.2]
 *   roberdae   Robertson with y1 + y2 + y3 = 1 as its third row, n = 3, t in [0, 1e11]
 *
 * Each gives f, its Jacobian J = df/dy (dense, row i column j at jac[i * n + j]), the constant
 * mass matrix M (same layout), y(0), df/dt at t = 0 (for the consistent y'(0)), the left null
 * vectors of M (one per algebraic row), the reference y(t_end) and the atol scale of the
 * calibration (atol = rtol * atol_scale).
 */
#ifndef ODYN_PEERS_IDA_PROBLEMS_H
#define ODYN_PEERS_IDA_PROBLEMS_H

#define MAX_N 8

typedef struct {
  const char *name;
  int n;
  double t_end;
  double atol_scale;
  void (*f)(double t, const double *y, double *out);
  void (*jac)(double t, const double *y, double *out); /* n * n, row-major */
  double mass[MAX_N * MAX_N];                          /* row-major */
  double y0[MAX_N];
  double dfdt0[MAX_N]; /* df/dt at (0, y0) */
  int n_null;
  double null[3][MAX_N]; /* rows spanning the left null space of M */
  double reference[MAX_N];
} Problem;

/* The problem called `name`, or NULL. */
const Problem *find_problem(const char *name);

/* Solves for a y'(0) consistent with y(0): M y' = f(0, y0) on the rows that M determines, and
 * N (J y' + df/dt) = 0 (the algebraic rows differentiated once) for each null vector N of M.
 * Returns 0, or -1 when that system is singular (the DAE is not index 1 at y0). */
int consistent_yp0(const Problem *p, double *yp0);

#endif
