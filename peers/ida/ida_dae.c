/*
 * ida_dae.c: SUNDIALS IDA (6.4) on the index-1 DAEs of problems.c, the C peer of odyn's DAE
 * benchmarks (issue 50).
 *
 * IDA integrates the residual form F(t, y, y') = M y' - f(t, y) = 0 with its variable-order
 * (1..5) variable-step BDF, Newton iterations on the analytic iteration matrix
 * dF/dy + cj dF/dy' = cj M - J (IDASetJacFn), and IDA's defaults otherwise: scalar tolerances
 * (IDASStolerances), every component in the error test (no IDASetSuppressAlg), at most 10^6
 * steps (a run needing more counts as failed), a stop time at t_end. y'(0) is the consistent one of
 * consistent_yp0 (problems.c): IDA needs (y0, y'0) consistent, and the transistor amplifier's
 * non-diagonal M rules out IDACalcIC's IDA_YA_YDP_INIT split into differential and algebraic
 * components.
 *
 * Linear solvers:
 *   dense   SUNDenseMatrix + SUNLinSol_Dense;
 *   klu     SUNSparseMatrix (CSC; the pattern of J and M together) + SUNLinSol_KLU with its
 *           default ordering (COLAMD).
 *
 * Usage:
 *   ida_dae PROBLEM SOLVER RTOL [ATOL]   one solve, repeated for timing; ATOL defaults to
 *                                        RTOL * the problem's atol scale
 *   ida_dae PROBLEM SOLVER sweep         RTOL = 1e-2 ... 1e-11 in quarter decades, ATOL as above;
 *                                        then, for the target errors 1e-4 and 1e-7, the loosest
 *                                        RTOL whose error is at or below it
 * PROBLEM: chemakzo, transamp, roberdae; SOLVER: dense, klu.
 *
 * Prints one line of key=value pairs per solve: problem, solver, rtol, atol, err (largest
 * |y_i - ref_i| / |ref_i| over the components with |ref_i| >= 1e-10, the stiff bench's rule),
 * abserr (largest |y_i - ref_i|), steps, nre (residual evaluations, excluding the ones of the
 * Jacobian: the Jacobian is analytic), nje, nsetups (LU factorizations), nni (Newton iterations),
 * ncfn (Newton convergence failures), netf (error-test failures), us (median wall time of one
 * whole solve, from IDACreate to IDAFree, over repeats filling about 0.3 s;
 * clock_gettime(CLOCK_MONOTONIC)), us_min, and y (the final state, %.17g).
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <ida/ida.h>
#include <nvector/nvector_serial.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#include "problems.h"

enum { MAX_STEPS = 1000000 };

typedef struct {
  const Problem *p;
  int sparse;
  int nnz;
  int pattern[MAX_N * MAX_N]; /* 1 where J or M may be nonzero, row-major */
} Data;

typedef struct {
  double y[MAX_N];
  long steps, nre, nje, nsetups, nni, ncfn, netf;
} Run;

static int residual(realtype t, N_Vector yy, N_Vector yp, N_Vector rr, void *user_data) {
  const Data *d = user_data;
  const Problem *p = d->p;
  int n = p->n;
  const double *y = N_VGetArrayPointer(yy), *dy = N_VGetArrayPointer(yp);
  double *r = N_VGetArrayPointer(rr);
  p->f(t, y, r);
  int finite = 1;
  for (int i = 0; i < n; i++) {
    double my = 0.0;
    for (int k = 0; k < n; k++) my += p->mass[i * n + k] * dy[k];
    r[i] = my - r[i];
    finite &= isfinite(r[i]);
  }
  return finite ? 0 : 1; /* 1: a recoverable error, IDA retries with a smaller step */
}

/* dF/dy + cj dF/dy' = cj M - J, into IDA's dense (column-major) or CSC matrix. */
static int jacobian(realtype t, realtype cj, N_Vector yy, N_Vector yp, N_Vector rr, SUNMatrix jm,
                    void *user_data, N_Vector t1, N_Vector t2, N_Vector t3) {
  (void)yp, (void)rr, (void)t1, (void)t2, (void)t3;
  const Data *d = user_data;
  const Problem *p = d->p;
  int n = p->n;
  double j[MAX_N * MAX_N];
  p->jac(t, N_VGetArrayPointer(yy), j);
  if (!d->sparse) {
    for (int c = 0; c < n; c++) {
      double *col = SUNDenseMatrix_Column(jm, c);
      for (int r = 0; r < n; r++) col[r] = cj * p->mass[r * n + c] - j[r * n + c];
    }
    return 0;
  }
  sunindextype *colptr = SUNSparseMatrix_IndexPointers(jm);
  sunindextype *rowval = SUNSparseMatrix_IndexValues(jm);
  double *val = SUNSparseMatrix_Data(jm);
  int k = 0;
  for (int c = 0; c < n; c++) {
    colptr[c] = k;
    for (int r = 0; r < n; r++) {
      if (!d->pattern[r * n + c]) continue;
      rowval[k] = r;
      val[k++] = cj * p->mass[r * n + c] - j[r * n + c];
    }
  }
  colptr[n] = k;
  return 0;
}

/* The structural pattern of cj M - J: M's nonzeros and J's at y0 and at y0 perturbed (so no
 * entry that happens to vanish at y0, like chemakzo's dfdy(1, 3) = k2 y4 with y3 = 0, is lost). */
static void set_pattern(Data *d) {
  const Problem *p = d->p;
  int n = p->n;
  double j0[MAX_N * MAX_N], j1[MAX_N * MAX_N], y1[MAX_N];
  for (int i = 0; i < n; i++) y1[i] = p->y0[i] * 1.01 + 1e-3;
  p->jac(0.0, p->y0, j0);
  p->jac(0.1, y1, j1);
  d->nnz = 0;
  for (int i = 0; i < n * n; i++) {
    d->pattern[i] = p->mass[i] != 0.0 || j0[i] != 0.0 || j1[i] != 0.0;
    d->nnz += d->pattern[i];
  }
}

/* One solve from t = 0 to t_end; returns 0 or IDA's failure flag. */
static int solve(Data *d, double rtol, double atol, Run *run) {
  const Problem *p = d->p;
  int n = p->n, flag;
  double yp0[MAX_N];
  if (consistent_yp0(p, yp0) != 0) return -100;
  SUNContext ctx;
  if (SUNContext_Create(NULL, &ctx) != 0) return -101;
  N_Vector y = N_VNew_Serial(n, ctx), yp = N_VNew_Serial(n, ctx);
  memcpy(N_VGetArrayPointer(y), p->y0, n * sizeof(double));
  memcpy(N_VGetArrayPointer(yp), yp0, n * sizeof(double));
  void *mem = IDACreate(ctx);
  SUNMatrix a = d->sparse ? SUNSparseMatrix(n, n, d->nnz, CSC_MAT, ctx) : SUNDenseMatrix(n, n, ctx);
  SUNLinearSolver ls = d->sparse ? SUNLinSol_KLU(y, a, ctx) : SUNLinSol_Dense(y, a, ctx);
  flag = IDAInit(mem, residual, 0.0, y, yp);
  if (!flag) flag = IDASStolerances(mem, rtol, atol);
  if (!flag) flag = IDASetUserData(mem, d);
  /* IDA's default is 500 steps per IDASolve call; MAX_STEPS ends a run that creeps (at tight
   * tolerances IDA can shrink h without bound instead of failing). */
  if (!flag) flag = IDASetMaxNumSteps(mem, MAX_STEPS);
  if (!flag) flag = IDASetStopTime(mem, p->t_end);
  if (!flag) flag = IDASetLinearSolver(mem, ls, a);
  if (!flag) flag = IDASetJacFn(mem, jacobian);
  double t = 0.0;
  if (!flag) flag = IDASolve(mem, p->t_end, &t, y, yp, IDA_NORMAL);
  if (flag >= 0) {
    flag = 0;
    memcpy(run->y, N_VGetArrayPointer(y), n * sizeof(double));
    IDAGetNumSteps(mem, &run->steps);
    IDAGetNumResEvals(mem, &run->nre);
    IDAGetNumJacEvals(mem, &run->nje);
    IDAGetNumLinSolvSetups(mem, &run->nsetups);
    IDAGetNumNonlinSolvIters(mem, &run->nni);
    IDAGetNumNonlinSolvConvFails(mem, &run->ncfn);
    IDAGetNumErrTestFails(mem, &run->netf);
  }
  IDAFree(&mem);
  SUNLinSolFree(ls);
  SUNMatDestroy(a);
  N_VDestroy(y);
  N_VDestroy(yp);
  SUNContext_Free(&ctx);
  return flag;
}

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return ts.tv_sec + 1e-9 * ts.tv_nsec;
}

static int cmp(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

/* Solves once, then repeats for timing; prints the key=value line; returns the error or NAN. */
static double report(Data *d, const char *solver, double rtol, double atol, int print_y) {
  const Problem *p = d->p;
  Run run;
  int flag = solve(d, rtol, atol, &run);
  if (flag != 0) {
    printf("problem=%s solver=%s rtol=%.3e atol=%.3e failed=%d\n", p->name, solver, rtol, atol,
           flag);
    return NAN;
  }
  double err = 0.0, abserr = 0.0;
  for (int i = 0; i < p->n; i++) {
    double e = fabs(run.y[i] - p->reference[i]);
    abserr = fmax(abserr, e);
    if (fabs(p->reference[i]) >= 1e-10) err = fmax(err, e / fabs(p->reference[i]));
  }
  enum { MAX_REPEATS = 2000 };
  static double times[MAX_REPEATS];
  int repeats = 0;
  double start = now();
  while (repeats < MAX_REPEATS && (repeats < 3 || now() - start < 0.3)) {
    double t0 = now();
    solve(d, rtol, atol, &run);
    times[repeats++] = now() - t0;
  }
  qsort(times, repeats, sizeof(double), cmp);
  printf("problem=%s solver=%s rtol=%.3e atol=%.3e err=%.3e abserr=%.3e steps=%ld nre=%ld "
         "nje=%ld nsetups=%ld nni=%ld ncfn=%ld netf=%ld us=%.1f us_min=%.1f",
         p->name, solver, rtol, atol, err, abserr, run.steps, run.nre, run.nje, run.nsetups,
         run.nni, run.ncfn, run.netf, 1e6 * times[repeats / 2], 1e6 * times[0]);
  if (print_y) {
    printf(" y=");
    for (int i = 0; i < p->n; i++) printf("%s%.17g", i ? "," : "", run.y[i]);
  }
  printf("\n");
  return err;
}

int main(int argc, char **argv) {
  setvbuf(stdout, NULL, _IOLBF, 0); /* lines in order with IDA's messages on stderr */
  if (argc < 4) {
    fprintf(stderr, "usage: %s chemakzo|transamp|roberdae dense|klu RTOL [ATOL] | sweep\n",
            argv[0]);
    return 2;
  }
  Data d = {.p = find_problem(argv[1])};
  if (!d.p || (strcmp(argv[2], "dense") != 0 && strcmp(argv[2], "klu") != 0)) {
    fprintf(stderr, "unknown problem or solver: %s %s\n", argv[1], argv[2]);
    return 2;
  }
  d.sparse = strcmp(argv[2], "klu") == 0;
  set_pattern(&d);
  if (strcmp(argv[3], "sweep") != 0) {
    double rtol = atof(argv[3]);
    double atol = argc > 4 ? atof(argv[4]) : rtol * d.p->atol_scale;
    if (!(rtol > 0.0 && isfinite(rtol)) || !(atol > 0.0 && isfinite(atol))) {
      fprintf(stderr, "RTOL and ATOL must be positive finite numbers\n");
      return 2;
    }
    return isnan(report(&d, argv[2], rtol, atol, 1)) ? 1 : 0;
  }
  enum { SWEEP = 37 };
  double rtols[SWEEP], errs[SWEEP];
  for (int k = 0; k < SWEEP; k++) {
    rtols[k] = pow(10.0, -2.0 - k / 4.0);
    errs[k] = report(&d, argv[2], rtols[k], rtols[k] * d.p->atol_scale, 0);
  }
  const double targets[2] = {1e-4, 1e-7};
  for (int g = 0; g < 2; g++) {
    int k = 0;
    while (k < SWEEP && !(errs[k] <= targets[g])) k++;
    if (k == SWEEP) {
      printf("target=%.0e not reached\n", targets[g]);
      continue;
    }
    int misses = 0, failures = 0;
    for (int m = k + 1; m < SWEEP; m++) {
      failures += isnan(errs[m]);
      misses += errs[m] > targets[g];
    }
    printf("target=%.0e rtol=%.3e err=%.3e tighter_misses=%d tighter_failures=%d\n", targets[g],
           rtols[k], errs[k], misses, failures);
  }
  return 0;
}
