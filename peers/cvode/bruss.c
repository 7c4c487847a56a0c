/*
 * bruss.c: SUNDIALS CVODE on the 2-D Brusselator, the C peer of odyn's Brusselator benchmark.
 *
 * The problem is SciMLBenchmarks' BRUSS (StiffODE/Bruss; Hairer & Wanner, "Solving Ordinary
 * Differential Equations II", 2nd ed., section IV.10) without its source term
 * (the disc switched on at t = 1.1), as in odyn's examples/brusselator.rs:
 *
 *   N x N cells, periodic in x and y, x_i = i*dx, y_j = j*dx (i, j = 0 .. N-1), dx = 1/(N-1);
 *   du/dt = 1 + u^2 v - 4.4 u + alpha * L(u) / dx^2
 *   dv/dt = 3.4 u - u^2 v     + alpha * L(v) / dx^2,      alpha = 10,
 *   L(w)_k = w_E + w_W + w_N + w_S - 4 w_k                (five-point, periodic wrap),
 *   u(0) = 22 (y (1 - y))^{3/2},  v(0) = 27 (x (1 - x))^{3/2},  t in [0, 11.5].
 *
 * Unknowns: 2 N^2, every u and then every v, cell k = i + N j (i the x index): the layout of
 * odyn's grids (scripts/bruss_reference.py uses the same one).
 *
 * Integrator: CVODE's variable-order BDF (CV_BDF) with its default Newton iteration, CVODE's
 * default options otherwise (apart from the step limit and a stop time at t = 11.5), and one of
 * these linear solvers:
 *
 *   klu         SUNSparseMatrix (CSC) filled with the analytic Jacobian, SUNLinSol_KLU with
 *               its default fill-reducing ordering (COLAMD);
 *   klu-amd     the same with KLU's AMD ordering (SUNLinSol_KLUSetOrdering(LS, 0)), which suits
 *               this structurally symmetric pattern: 2.4x (N = 32) to 3.6x (N = 64) faster;
 *   spgmr       SUNLinSol_SPGMR with right preconditioning by the 2 x 2 block-Jacobi matrix
 *               P = I - gamma * D (D: the per-cell blocks of the Jacobian, reaction plus the
 *               -4 alpha/dx^2 diagonal of the diffusion; the preconditioner of CVODE's
 *               cvDiurnal_kry example), analytic Jacobian-vector products;
 *   spgmr-none  SUNLinSol_SPGMR, no preconditioner, analytic Jacobian-vector products;
 *   dense       SUNDenseMatrix with the analytic Jacobian, SUNLinSol_Dense (N <= 16: a check).
 *
 * SPGMR settings. Block Jacobi leaves the diffusion unpreconditioned: P^{-1}(I - gamma J) has
 * eigenvalues from about 1/(1 + 4 gamma c) (smooth modes) to 2 (c = alpha/dx^2), so the
 * iterations per solve grow like N (about 23 at N = 32, 44 at N = 64, rtol 1e-6). Hence:
 *   - right preconditioning: SPGMR then tests the true residual. With left preconditioning it
 *     tests P^{-1} r, which shrinks the smooth (non-stiff) components by 1 + 4 gamma c; their
 *     unresolved errors pollute CVODE's local error estimate, and at N = 32, rtol 1e-6, CVODE
 *     took 5 500-7 300 steps instead of 335;
 *   - maxl = 2N Krylov vectors, no restarts (SPGMR's default maxl of 5 fails most linear solves
 *     here: at N = 64, thousands of Newton convergence failures); BRUSS_MAXL overrides it.
 * Modified Gram-Schmidt (the default) orthogonalization then dominates the run time.
 *
 * Usage: bruss N rtol atol solver [out.csv]
 *
 * Prints one line of key=value pairs: N, solver, rtol, atol, seconds (wall time of the CVode
 * call alone, clock_gettime(CLOCK_MONOTONIC)), steps, nfe (right-hand sides, CVODE's own), nje
 * (Jacobian evaluations; for the Krylov solvers: preconditioner evaluations), nsetups (linear
 * solver setups: each is one LU for klu/dense, one preconditioner setup for spgmr), nni
 * (Newton iterations), ncfn (Newton convergence failures), netf (error test failures), and for
 * the Krylov solvers nli (linear iterations), njv (Jacobian-vector products), nps
 * (preconditioner solves), nlcf (linear convergence failures). If out.csv is given, writes the
 * state at t = 11.5 to it, 2 N^2 values in the layout above, %.17g, one per line.
 *
 * API: SUNDIALS 6.4 (CVODE 6.4.1): SUNContext_Create(NULL, ...), CVodeCreate(CV_BDF, ctx).
 */

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <cvode/cvode.h>
#include <nvector/nvector_serial.h>
#include <sundials/sundials_types.h>
#include <sunlinsol/sunlinsol_dense.h>
#include <sunlinsol/sunlinsol_klu.h>
#include <sunlinsol/sunlinsol_spgmr.h>
#include <sunmatrix/sunmatrix_dense.h>
#include <sunmatrix/sunmatrix_sparse.h>

#define T_END 11.5
#define ALPHA 10.0

/* Problem data shared by the callbacks. */
typedef struct {
  sunindextype n;  /* cells per side */
  sunindextype nn; /* cells, n * n: the offset of v in the state */
  realtype c;      /* alpha / dx^2, the diffusion factor */
  /* 2 x 2 block-Jacobi preconditioner (spgmr): per cell, the Jacobian block D_k (saved so
   * that CVODE may reuse it with a new gamma) and the inverse of I - gamma D_k. */
  realtype *block; /* 4 per cell: d(fu)/du, d(fu)/dv, d(fv)/du, d(fv)/dv */
  realtype *inv;   /* 4 per cell: the inverse, same order */
} Problem;

/* Periodic neighbours of cell k = i + n j: east (i+1), west (i-1), north (j+1), south (j-1). */
static void neighbours(const Problem *p, sunindextype i, sunindextype j, sunindextype nb[4]) {
  sunindextype n = p->n;
  sunindextype ie = (i + 1 == n) ? 0 : i + 1, iw = (i == 0) ? n - 1 : i - 1;
  sunindextype jn = (j + 1 == n) ? 0 : j + 1, js = (j == 0) ? n - 1 : j - 1;
  nb[0] = ie + n * j;
  nb[1] = iw + n * j;
  nb[2] = i + n * jn;
  nb[3] = i + n * js;
}

/* Right-hand side: the BRUSS equations above (Hairer & Wanner II, IV.10, without f(x,y,t)). */
static int rhs(realtype t, N_Vector y, N_Vector ydot, void *user_data) {
  (void)t;
  const Problem *p = (const Problem *)user_data;
  const sunindextype n = p->n, nn = p->nn;
  const realtype c = p->c;
  const realtype *u = N_VGetArrayPointer(y), *v = u + nn;
  realtype *du = N_VGetArrayPointer(ydot), *dv = du + nn;
  for (sunindextype j = 0; j < n; j++) {
    for (sunindextype i = 0; i < n; i++) {
      sunindextype k = i + n * j, nb[4];
      neighbours(p, i, j, nb);
      realtype lu = u[nb[0]] + u[nb[1]] + u[nb[2]] + u[nb[3]] - 4.0 * u[k];
      realtype lv = v[nb[0]] + v[nb[1]] + v[nb[2]] + v[nb[3]] - 4.0 * v[k];
      realtype uuv = u[k] * u[k] * v[k];
      du[k] = 1.0 + uuv - 4.4 * u[k] + c * lu;
      dv[k] = 3.4 * u[k] - uuv + c * lv;
    }
  }
  return 0;
}

/* The per-cell 2 x 2 Jacobian block, by differentiating the right-hand side: the reaction
 * terms plus the diagonal -4c of the diffusion.
 *   d(du_k)/du_k = 2 u v - 4.4 - 4c,  d(du_k)/dv_k = u^2,
 *   d(dv_k)/du_k = 3.4 - 2 u v,       d(dv_k)/dv_k = -u^2 - 4c.
 * The off-diagonal cells contribute d(dw_k)/dw_m = c for each periodic neighbour m of k. */
static void cell_block(realtype u, realtype v, realtype c, realtype b[4]) {
  b[0] = 2.0 * u * v - 4.4 - 4.0 * c;
  b[1] = u * u;
  b[2] = 3.4 - 2.0 * u * v;
  b[3] = -u * u - 4.0 * c;
}

/* Sparse (CSC) analytic Jacobian. Column u_k holds rows u_k, u of k's four neighbours, v_k;
 * column v_k holds rows u_k, v_k, v of k's four neighbours: 6 entries a column, 12 N^2 in all
 * (N >= 3 keeps the four neighbours distinct). Rows are sorted within each column. */
static void sort_column(sunindextype *rows, realtype *vals, int len) {
  for (int a = 1; a < len; a++) { /* insertion sort: six entries */
    sunindextype r = rows[a];
    realtype x = vals[a];
    int b = a - 1;
    while (b >= 0 && rows[b] > r) {
      rows[b + 1] = rows[b];
      vals[b + 1] = vals[b];
      b--;
    }
    rows[b + 1] = r;
    vals[b + 1] = x;
  }
}

static int jac_sparse(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user_data,
                      N_Vector tmp1, N_Vector tmp2, N_Vector tmp3) {
  (void)t; (void)fy; (void)tmp1; (void)tmp2; (void)tmp3;
  const Problem *p = (const Problem *)user_data;
  const sunindextype n = p->n, nn = p->nn;
  const realtype c = p->c;
  const realtype *u = N_VGetArrayPointer(y), *v = u + nn;
  sunindextype *colptrs = SUNSparseMatrix_IndexPointers(J);
  sunindextype *rowvals = SUNSparseMatrix_IndexValues(J);
  realtype *data = SUNSparseMatrix_Data(J);
  SUNMatZero(J);
  for (sunindextype j = 0; j < n; j++) {
    for (sunindextype i = 0; i < n; i++) {
      sunindextype k = i + n * j, nb[4];
      neighbours(p, i, j, nb);
      realtype b[4];
      cell_block(u[k], v[k], c, b);
      /* column u_k (index k) */
      sunindextype start = 6 * k;
      colptrs[k] = start;
      sunindextype *r = rowvals + start;
      realtype *x = data + start;
      r[0] = k;      x[0] = b[0];
      r[1] = nb[0];  x[1] = c;
      r[2] = nb[1];  x[2] = c;
      r[3] = nb[2];  x[3] = c;
      r[4] = nb[3];  x[4] = c;
      r[5] = nn + k; x[5] = b[2];
      sort_column(r, x, 6);
      /* column v_k (index nn + k) */
      start = 6 * (nn + k);
      colptrs[nn + k] = start;
      r = rowvals + start;
      x = data + start;
      r[0] = k;          x[0] = b[1];
      r[1] = nn + k;     x[1] = b[3];
      r[2] = nn + nb[0]; x[2] = c;
      r[3] = nn + nb[1]; x[3] = c;
      r[4] = nn + nb[2]; x[4] = c;
      r[5] = nn + nb[3]; x[5] = c;
      sort_column(r, x, 6);
    }
  }
  colptrs[2 * nn] = 12 * nn;
  return 0;
}

/* Dense analytic Jacobian (the check solver): the same entries as jac_sparse. */
static int jac_dense(realtype t, N_Vector y, N_Vector fy, SUNMatrix J, void *user_data,
                     N_Vector tmp1, N_Vector tmp2, N_Vector tmp3) {
  (void)t; (void)fy; (void)tmp1; (void)tmp2; (void)tmp3;
  const Problem *p = (const Problem *)user_data;
  const sunindextype n = p->n, nn = p->nn;
  const realtype c = p->c;
  const realtype *u = N_VGetArrayPointer(y), *v = u + nn;
  SUNMatZero(J);
  for (sunindextype j = 0; j < n; j++) {
    for (sunindextype i = 0; i < n; i++) {
      sunindextype k = i + n * j, nb[4];
      neighbours(p, i, j, nb);
      realtype b[4];
      cell_block(u[k], v[k], c, b);
      SM_ELEMENT_D(J, k, k) = b[0];
      SM_ELEMENT_D(J, k, nn + k) = b[1];
      SM_ELEMENT_D(J, nn + k, k) = b[2];
      SM_ELEMENT_D(J, nn + k, nn + k) = b[3];
      for (int m = 0; m < 4; m++) {
        SM_ELEMENT_D(J, k, nb[m]) += c;
        SM_ELEMENT_D(J, nn + k, nn + nb[m]) += c;
      }
    }
  }
  return 0;
}

/* Analytic Jacobian-vector product Jw (the Krylov solvers): the linearization of rhs,
 *   (Jw)_u = (2uv - 4.4) w_u + u^2 w_v + c L(w_u),
 *   (Jw)_v = (3.4 - 2uv) w_u - u^2 w_v + c L(w_v). */
static int jtimes(N_Vector w, N_Vector Jw, realtype t, N_Vector y, N_Vector fy,
                  void *user_data, N_Vector tmp) {
  (void)t; (void)fy; (void)tmp;
  const Problem *p = (const Problem *)user_data;
  const sunindextype n = p->n, nn = p->nn;
  const realtype c = p->c;
  const realtype *u = N_VGetArrayPointer(y), *v = u + nn;
  const realtype *wu = N_VGetArrayPointer(w), *wv = wu + nn;
  realtype *ju = N_VGetArrayPointer(Jw), *jv = ju + nn;
  for (sunindextype j = 0; j < n; j++) {
    for (sunindextype i = 0; i < n; i++) {
      sunindextype k = i + n * j, nb[4];
      neighbours(p, i, j, nb);
      realtype lu = wu[nb[0]] + wu[nb[1]] + wu[nb[2]] + wu[nb[3]] - 4.0 * wu[k];
      realtype lv = wv[nb[0]] + wv[nb[1]] + wv[nb[2]] + wv[nb[3]] - 4.0 * wv[k];
      realtype uv2 = 2.0 * u[k] * v[k], uu = u[k] * u[k];
      ju[k] = (uv2 - 4.4) * wu[k] + uu * wv[k] + c * lu;
      jv[k] = (3.4 - uv2) * wu[k] - uu * wv[k] + c * lv;
    }
  }
  return 0;
}

/* Preconditioner setup (CVLsPrecSetupFn in cvode_ls.h; see the CVODE user guide): P = I - gamma D with
 * D the block diagonal of cell_block. When CVODE passes jok, the saved blocks are reused
 * (only gamma changed); otherwise they are recomputed from y and *jcurPtr says so. Each 2 x 2
 * block of P is inverted in closed form. */
static int psetup(realtype t, N_Vector y, N_Vector fy, booleantype jok, booleantype *jcurPtr,
                  realtype gamma, void *user_data) {
  (void)t; (void)fy;
  Problem *p = (Problem *)user_data;
  const sunindextype nn = p->nn;
  const realtype *u = N_VGetArrayPointer(y), *v = u + nn;
  if (!jok) {
    for (sunindextype k = 0; k < nn; k++) cell_block(u[k], v[k], p->c, p->block + 4 * k);
  }
  *jcurPtr = !jok;
  for (sunindextype k = 0; k < nn; k++) {
    const realtype *b = p->block + 4 * k;
    realtype a00 = 1.0 - gamma * b[0], a01 = -gamma * b[1];
    realtype a10 = -gamma * b[2], a11 = 1.0 - gamma * b[3];
    realtype det = a00 * a11 - a01 * a10;
    if (det == 0.0) return 1; /* recoverable: CVODE retries with a smaller step */
    realtype *q = p->inv + 4 * k;
    q[0] = a11 / det;
    q[1] = -a01 / det;
    q[2] = -a10 / det;
    q[3] = a00 / det;
  }
  return 0;
}

/* Preconditioner solve (CVLsPrecSolveFn): z = P^{-1} r, cell by cell. */
static int psolve(realtype t, N_Vector y, N_Vector fy, N_Vector r, N_Vector z, realtype gamma,
                  realtype delta, int lr, void *user_data) {
  (void)t; (void)y; (void)fy; (void)gamma; (void)delta; (void)lr;
  const Problem *p = (const Problem *)user_data;
  const sunindextype nn = p->nn;
  const realtype *ru = N_VGetArrayPointer(r), *rv = ru + nn;
  realtype *zu = N_VGetArrayPointer(z), *zv = zu + nn;
  for (sunindextype k = 0; k < nn; k++) {
    const realtype *q = p->inv + 4 * k;
    realtype a = ru[k], b = rv[k];
    zu[k] = q[0] * a + q[1] * b;
    zv[k] = q[2] * a + q[3] * b;
  }
  return 0;
}

/* Initial state: u = 22 (y(1-y))^{3/2}, v = 27 (x(1-x))^{3/2} (the BRUSS initial condition). */
static void initial(const Problem *p, realtype dx, N_Vector y) {
  const sunindextype n = p->n, nn = p->nn;
  realtype *u = N_VGetArrayPointer(y), *v = u + nn;
  for (sunindextype j = 0; j < n; j++) {
    for (sunindextype i = 0; i < n; i++) {
      realtype x = (realtype)i * dx, yy = (realtype)j * dx;
      u[i + n * j] = 22.0 * pow(yy * (1.0 - yy), 1.5);
      v[i + n * j] = 27.0 * pow(x * (1.0 - x), 1.5);
    }
  }
}

static int check(int flag, const char *call) {
  if (flag < 0) {
    fprintf(stderr, "bruss: %s failed with flag %d\n", call, flag);
    exit(1);
  }
  return flag;
}

static void *check_ptr(void *ptr, const char *call) {
  if (ptr == NULL) {
    fprintf(stderr, "bruss: %s returned NULL\n", call);
    exit(1);
  }
  return ptr;
}

int main(int argc, char **argv) {
  if (argc < 5 || argc > 6) {
    fprintf(stderr, "usage: %s N rtol atol klu|klu-amd|spgmr|spgmr-none|dense [out.csv]\n", argv[0]);
    return 2;
  }
  long n_arg = strtol(argv[1], NULL, 10);
  realtype rtol = strtod(argv[2], NULL), atol = strtod(argv[3], NULL);
  const char *solver = argv[4];
  const char *out = (argc == 6) ? argv[5] : NULL;
  int is_amd = !strcmp(solver, "klu-amd");
  int is_klu = is_amd || !strcmp(solver, "klu"), is_dense = !strcmp(solver, "dense");
  int is_spgmr = !strcmp(solver, "spgmr"), is_none = !strcmp(solver, "spgmr-none");
  if (n_arg < 3 || !(is_klu || is_dense || is_spgmr || is_none)) {
    fprintf(stderr, "bruss: need N >= 3 and solver klu, klu-amd, spgmr, spgmr-none or dense\n");
    return 2;
  }
  if (is_dense && n_arg > 16) {
    fprintf(stderr, "bruss: the dense solver is for N <= 16\n");
    return 2;
  }
  int maxl = 2 * (int)n_arg; /* Krylov dimension: see "SPGMR settings" above */
  const char *maxl_env = getenv("BRUSS_MAXL");
  if (maxl_env != NULL) maxl = atoi(maxl_env);

  Problem p;
  p.n = (sunindextype)n_arg;
  p.nn = p.n * p.n;
  realtype dx = 1.0 / (realtype)(p.n - 1);
  p.c = ALPHA / (dx * dx);
  p.block = NULL;
  p.inv = NULL;
  sunindextype neq = 2 * p.nn;

  SUNContext ctx;
  check(SUNContext_Create(NULL, &ctx), "SUNContext_Create");
  N_Vector y = check_ptr(N_VNew_Serial(neq, ctx), "N_VNew_Serial");
  initial(&p, dx, y);

  void *cvode = check_ptr(CVodeCreate(CV_BDF, ctx), "CVodeCreate");
  check(CVodeInit(cvode, rhs, 0.0, y), "CVodeInit");
  check(CVodeSStolerances(cvode, rtol, atol), "CVodeSStolerances");
  check(CVodeSetUserData(cvode, &p), "CVodeSetUserData");
  check(CVodeSetMaxNumSteps(cvode, 10000000), "CVodeSetMaxNumSteps");
  check(CVodeSetStopTime(cvode, T_END), "CVodeSetStopTime");

  SUNMatrix A = NULL;
  SUNLinearSolver LS = NULL;
  int krylov = 0;
  if (is_klu) {
    A = check_ptr(SUNSparseMatrix(neq, neq, 12 * p.nn, CSC_MAT, ctx), "SUNSparseMatrix");
    LS = check_ptr(SUNLinSol_KLU(y, A, ctx), "SUNLinSol_KLU");
    if (is_amd) check(SUNLinSol_KLUSetOrdering(LS, 0), "SUNLinSol_KLUSetOrdering"); /* 0: AMD */
    check(CVodeSetLinearSolver(cvode, LS, A), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(cvode, jac_sparse), "CVodeSetJacFn");
  } else if (is_dense) {
    A = check_ptr(SUNDenseMatrix(neq, neq, ctx), "SUNDenseMatrix");
    LS = check_ptr(SUNLinSol_Dense(y, A, ctx), "SUNLinSol_Dense");
    check(CVodeSetLinearSolver(cvode, LS, A), "CVodeSetLinearSolver");
    check(CVodeSetJacFn(cvode, jac_dense), "CVodeSetJacFn");
  } else {
    krylov = 1;
    int prec = is_spgmr ? SUN_PREC_RIGHT : SUN_PREC_NONE;
    LS = check_ptr(SUNLinSol_SPGMR(y, prec, maxl, ctx), "SUNLinSol_SPGMR");
    check(CVodeSetLinearSolver(cvode, LS, NULL), "CVodeSetLinearSolver");
    check(CVodeSetJacTimes(cvode, NULL, jtimes), "CVodeSetJacTimes");
    if (is_spgmr) {
      p.block = check_ptr(malloc(sizeof(realtype) * 4 * p.nn), "malloc");
      p.inv = check_ptr(malloc(sizeof(realtype) * 4 * p.nn), "malloc");
      check(CVodeSetPreconditioner(cvode, psetup, psolve), "CVodeSetPreconditioner");
    }
  }

  realtype t = 0.0;
  struct timespec start, stop;
  clock_gettime(CLOCK_MONOTONIC, &start);
  int flag = CVode(cvode, T_END, y, &t, CV_NORMAL);
  clock_gettime(CLOCK_MONOTONIC, &stop);
  double seconds = (double)(stop.tv_sec - start.tv_sec) + 1e-9 * (double)(stop.tv_nsec - start.tv_nsec);
  check(flag, "CVode");

  long steps, nfe, nsetups, nni, ncfn, netf, nje = 0;
  CVodeGetNumSteps(cvode, &steps);
  CVodeGetNumRhsEvals(cvode, &nfe);
  CVodeGetNumLinSolvSetups(cvode, &nsetups);
  CVodeGetNumNonlinSolvIters(cvode, &nni);
  CVodeGetNumNonlinSolvConvFails(cvode, &ncfn);
  CVodeGetNumErrTestFails(cvode, &netf);
  if (krylov) {
    long nli, njv, npe, nps, nlcf;
    CVodeGetNumLinIters(cvode, &nli);
    CVodeGetNumJtimesEvals(cvode, &njv);
    CVodeGetNumPrecEvals(cvode, &npe);
    CVodeGetNumPrecSolves(cvode, &nps);
    CVodeGetNumLinConvFails(cvode, &nlcf);
    printf("N=%ld solver=%s rtol=%g atol=%g t=%g seconds=%.6f steps=%ld nfe=%ld nje=%ld "
           "nsetups=%ld nni=%ld ncfn=%ld netf=%ld nli=%ld njv=%ld nps=%ld nlcf=%ld\n",
           n_arg, solver, rtol, atol, t, seconds, steps, nfe, npe, nsetups, nni, ncfn, netf,
           nli, njv, nps, nlcf);
  } else {
    CVodeGetNumJacEvals(cvode, &nje);
    printf("N=%ld solver=%s rtol=%g atol=%g t=%g seconds=%.6f steps=%ld nfe=%ld nje=%ld "
           "nsetups=%ld nni=%ld ncfn=%ld netf=%ld\n",
           n_arg, solver, rtol, atol, t, seconds, steps, nfe, nje, nsetups, nni, ncfn, netf);
  }

  if (out != NULL) {
    FILE *f = fopen(out, "w");
    if (f == NULL) {
      fprintf(stderr, "bruss: cannot write %s\n", out);
      return 1;
    }
    const realtype *s = N_VGetArrayPointer(y);
    for (sunindextype k = 0; k < neq; k++) fprintf(f, "%.17g\n", s[k]);
    fclose(f);
  }

  free(p.block);
  free(p.inv);
  CVodeFree(&cvode);
  SUNLinSolFree(LS);
  if (A != NULL) SUNMatDestroy(A);
  N_VDestroy(y);
  SUNContext_Free(&ctx);
  return 0;
}
