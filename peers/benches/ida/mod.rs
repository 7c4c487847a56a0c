//! SUNDIALS IDA (6.4, C) through its C API, on M·y′ = f(t, y) as the residual
//! F(t, y, y′) = M·y′ − f(t, y): variable-order BDF, Newton on the caller's analytic iteration
//! matrix ∂F/∂y + c_j·∂F/∂y′ = c_j·M − J, with a dense direct solver or KLU (sparse, CSC) —
//! the same configuration as the standalone `peers/ida/ida_dae.c` — and optionally the
//! algebraic unknowns (the zero columns of M) left out of the local error test
//! (`IDASetId` + `IDASetSuppressAlg`). Linked from the system libraries
//! (`apt-get install libsundials-dev libsuitesparse-dev`; see `peers/build.rs`).

use std::ffi::{c_int, c_long, c_void};

type Context = *mut c_void;
type Vector = *mut c_void;
type Matrix = *mut c_void;
type LinearSolver = *mut c_void;
type Residual = extern "C" fn(f64, Vector, Vector, Vector, *mut c_void) -> c_int;
type Jac = extern "C" fn(
    f64,
    f64,
    Vector,
    Vector,
    Vector,
    Matrix,
    *mut c_void,
    Vector,
    Vector,
    Vector,
) -> c_int;

/// `IDA_NORMAL` of `ida.h`, `CSC_MAT` of `sunmatrix_sparse.h`.
const IDA_NORMAL: c_int = 1;
const CSC_MAT: c_int = 0;

unsafe extern "C" {
    fn SUNContext_Create(comm: *mut c_void, ctx: *mut Context) -> c_int;
    fn SUNContext_Free(ctx: *mut Context) -> c_int;
    fn N_VNew_Serial(length: i64, ctx: Context) -> Vector;
    fn N_VGetArrayPointer(v: Vector) -> *mut f64;
    fn N_VDestroy(v: Vector);
    fn SUNDenseMatrix(rows: i64, columns: i64, ctx: Context) -> Matrix;
    fn SUNDenseMatrix_Data(a: Matrix) -> *mut f64;
    fn SUNSparseMatrix(rows: i64, columns: i64, nnz: i64, kind: c_int, ctx: Context) -> Matrix;
    fn SUNSparseMatrix_Data(a: Matrix) -> *mut f64;
    fn SUNSparseMatrix_IndexValues(a: Matrix) -> *mut i64;
    fn SUNSparseMatrix_IndexPointers(a: Matrix) -> *mut i64;
    fn SUNMatDestroy(a: Matrix);
    fn SUNLinSol_Dense(y: Vector, a: Matrix, ctx: Context) -> LinearSolver;
    fn SUNLinSol_KLU(y: Vector, a: Matrix, ctx: Context) -> LinearSolver;
    fn SUNLinSolFree(solver: LinearSolver) -> c_int;
    fn IDACreate(ctx: Context) -> *mut c_void;
    fn IDAInit(mem: *mut c_void, res: Residual, t0: f64, y0: Vector, yp0: Vector) -> c_int;
    fn IDASStolerances(mem: *mut c_void, rtol: f64, atol: f64) -> c_int;
    fn IDASetUserData(mem: *mut c_void, data: *mut c_void) -> c_int;
    fn IDASetMaxNumSteps(mem: *mut c_void, steps: c_long) -> c_int;
    fn IDASetStopTime(mem: *mut c_void, t: f64) -> c_int;
    fn IDASetLinearSolver(mem: *mut c_void, solver: LinearSolver, a: Matrix) -> c_int;
    fn IDASetJacFn(mem: *mut c_void, jac: Jac) -> c_int;
    fn IDASolve(
        mem: *mut c_void,
        tout: f64,
        t: *mut f64,
        y: Vector,
        yp: Vector,
        task: c_int,
    ) -> c_int;
    fn IDAGetNumSteps(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn IDAGetNumErrTestFails(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn IDAGetNumResEvals(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn IDAGetNumJacEvals(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn IDAGetNumLinSolvSetups(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn IDASetId(mem: *mut c_void, id: Vector) -> c_int;
    fn IDASetSuppressAlg(mem: *mut c_void, suppress: c_int) -> c_int;
    fn IDAFree(mem: *mut *mut c_void);
}

/// A function of (t, y) written into its output slice.
pub type Function<'a> = &'a dyn Fn(f64, &[f64], &mut [f64]);

/// The equations IDA integrates: f, J (column-major n × n) and M (column-major, constant).
pub struct Equations<'a> {
    pub n: usize,
    pub f: Function<'a>,
    pub jacobian: Function<'a>,
    pub mass: &'a [f64],
}

/// The linear solver of the Newton iterations.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Linear {
    /// `SUNLinSol_Dense` on a `SUNDenseMatrix`.
    Dense,
    /// `SUNLinSol_KLU` (default COLAMD ordering) on a CSC `SUNSparseMatrix` holding the union
    /// of the patterns of J and M.
    Klu,
}

/// A finished run: the final state and IDA's own counts.
pub struct Run {
    pub y: Vec<f64>,
    pub steps: u64,
    /// Error-test failures.
    pub rejected: u64,
    /// Residual evaluations (none for the Jacobian, which is analytic).
    pub evaluations: u64,
    pub jacobians: u64,
    /// Linear-solver setups: LU factorizations of c_j·M − J.
    pub factorizations: u64,
}

/// What the callbacks read: the equations, the sparsity pattern (CSC) for KLU and scratch.
struct Data<'a> {
    equations: &'a Equations<'a>,
    linear: Linear,
    /// Column pointers and row indices of the pattern.
    colptr: Vec<i64>,
    rowval: Vec<i64>,
    /// J at the current point, column-major.
    j: std::cell::RefCell<Vec<f64>>,
}

extern "C" fn residual(t: f64, y: Vector, yp: Vector, r: Vector, data: *mut c_void) -> c_int {
    // SAFETY: `data` is the `Data` `solve` passed, alive for the whole run; y, yp and r are
    // IDA's serial vectors of length n.
    unsafe {
        let data = &*(data as *const Data<'_>);
        let n = data.equations.n;
        let y = std::slice::from_raw_parts(N_VGetArrayPointer(y), n);
        let yp = std::slice::from_raw_parts(N_VGetArrayPointer(yp), n);
        let r = std::slice::from_raw_parts_mut(N_VGetArrayPointer(r), n);
        (data.equations.f)(t, y, r);
        let mass = data.equations.mass;
        for (i, ri) in r.iter_mut().enumerate() {
            let my: f64 = (0..n).map(|k| mass[k * n + i] * yp[k]).sum();
            *ri = my - *ri;
        }
        // 1: a recoverable failure, IDA retries with a smaller step.
        c_int::from(!r.iter().all(|v| v.is_finite()))
    }
}

extern "C" fn jacobian(
    t: f64,
    cj: f64,
    y: Vector,
    _: Vector,
    _: Vector,
    a: Matrix,
    data: *mut c_void,
    _: Vector,
    _: Vector,
    _: Vector,
) -> c_int {
    // SAFETY: as in `residual`; `a` is the dense n × n (column-major, leading dimension n) or
    // the CSC matrix with `rowval.len()` entries that `solve` created.
    unsafe {
        let data = &*(data as *const Data<'_>);
        let n = data.equations.n;
        let y = std::slice::from_raw_parts(N_VGetArrayPointer(y), n);
        let mut j = data.j.borrow_mut();
        (data.equations.jacobian)(t, y, &mut j);
        let mass = data.equations.mass;
        match data.linear {
            Linear::Dense => {
                let out = std::slice::from_raw_parts_mut(SUNDenseMatrix_Data(a), n * n);
                for (k, o) in out.iter_mut().enumerate() {
                    *o = cj * mass[k] - j[k];
                }
            }
            Linear::Klu => {
                let nnz = data.rowval.len();
                std::slice::from_raw_parts_mut(SUNSparseMatrix_IndexPointers(a), n + 1)
                    .copy_from_slice(&data.colptr);
                std::slice::from_raw_parts_mut(SUNSparseMatrix_IndexValues(a), nnz)
                    .copy_from_slice(&data.rowval);
                let values = std::slice::from_raw_parts_mut(SUNSparseMatrix_Data(a), nnz);
                // Entry k of column c is (rowval[k], c).
                let mut column = 0;
                for (k, (v, &r)) in values.iter_mut().zip(&data.rowval).enumerate() {
                    while k as i64 >= data.colptr[column + 1] {
                        column += 1;
                    }
                    let e = column * n + r as usize;
                    *v = cj * mass[e] - j[e];
                }
            }
        }
    }
    0
}

/// The CSC pattern of c_j·M − J: M's nonzeros and J's at `y0` and at `y0` perturbed (so an
/// entry that vanishes at the start, like chemakzo's ∂f₁/∂y₃ = k₂·y₄ … with y₃ = 0, is kept).
fn pattern(equations: &Equations<'_>, y0: &[f64]) -> (Vec<i64>, Vec<i64>) {
    let n = equations.n;
    let (mut j0, mut j1) = (vec![0.0; n * n], vec![0.0; n * n]);
    let y1: Vec<f64> = y0.iter().map(|v| v * 1.01 + 1e-3).collect();
    (equations.jacobian)(0.0, y0, &mut j0);
    (equations.jacobian)(0.1, &y1, &mut j1);
    let (mut colptr, mut rowval) = (vec![0], Vec::new());
    for c in 0..n {
        for r in 0..n {
            let e = c * n + r;
            if equations.mass[e] != 0.0 || j0[e] != 0.0 || j1[e] != 0.0 {
                rowval.push(r as i64);
            }
        }
        colptr.push(rowval.len() as i64);
    }
    (colptr, rowval)
}

/// The algebraic unknowns: those whose column of M is zero (F does not depend on their y′).
pub fn algebraic(equations: &Equations<'_>) -> Vec<bool> {
    let n = equations.n;
    (0..n)
        .map(|c| equations.mass[c * n..(c + 1) * n].iter().all(|&m| m == 0.0))
        .collect()
}

/// Integrates from (`y0`, `yp0`) at t = 0 to `t_end` with IDA at scalar tolerances; `None`
/// when IDA reports a failure. (y0, yp0) must be consistent: IDA is not asked to repair them.
/// With `suppress_algebraic`, the unknowns of `algebraic` are left out of the error test.
#[allow(
    clippy::too_many_arguments,
    reason = "one call site; a struct would only rename them"
)]
pub fn solve(
    equations: &Equations<'_>,
    linear: Linear,
    suppress_algebraic: bool,
    y0: &[f64],
    yp0: &[f64],
    t_end: f64,
    rtol: f64,
    atol: f64,
) -> Option<Run> {
    let n = equations.n;
    let (colptr, rowval) = pattern(equations, y0);
    let data = Data {
        equations,
        linear,
        colptr,
        rowval,
        j: std::cell::RefCell::new(vec![0.0; n * n]),
    };
    // SAFETY: the SUNDIALS 6.4 C API used as its documentation says: every object created here
    // is freed before returning, and `data` outlives the IDA memory that points to it.
    unsafe {
        let mut ctx: Context = std::ptr::null_mut();
        if SUNContext_Create(std::ptr::null_mut(), &mut ctx) != 0 {
            return None;
        }
        let y = N_VNew_Serial(n as i64, ctx);
        let yp = N_VNew_Serial(n as i64, ctx);
        std::slice::from_raw_parts_mut(N_VGetArrayPointer(y), n).copy_from_slice(y0);
        std::slice::from_raw_parts_mut(N_VGetArrayPointer(yp), n).copy_from_slice(yp0);
        let mut mem = IDACreate(ctx);
        let (a, solver) = match linear {
            Linear::Dense => {
                let a = SUNDenseMatrix(n as i64, n as i64, ctx);
                (a, SUNLinSol_Dense(y, a, ctx))
            }
            Linear::Klu => {
                let nnz = data.rowval.len() as i64;
                let a = SUNSparseMatrix(n as i64, n as i64, nnz, CSC_MAT, ctx);
                (a, SUNLinSol_KLU(y, a, ctx))
            }
        };
        let set_up = IDAInit(mem, residual, 0.0, y, yp) == 0
            && IDASStolerances(mem, rtol, atol) == 0
            && IDASetUserData(mem, &data as *const Data<'_> as *mut c_void) == 0
            // IDA's default is 500 steps per IDASolve call; at tight tolerances it can shrink
            // h without bound instead of failing, so a run needing more than 10⁶ fails.
            && IDASetMaxNumSteps(mem, 1_000_000) == 0
            && IDASetStopTime(mem, t_end) == 0
            && IDASetLinearSolver(mem, solver, a) == 0
            && IDASetJacFn(mem, jacobian) == 0;
        let id = N_VNew_Serial(n as i64, ctx);
        let ids = std::slice::from_raw_parts_mut(N_VGetArrayPointer(id), n);
        for (i, a) in ids.iter_mut().zip(algebraic(equations)) {
            *i = if a { 0.0 } else { 1.0 };
        }
        let set_up = set_up
            && (!suppress_algebraic || (IDASetId(mem, id) == 0 && IDASetSuppressAlg(mem, 1) == 0));
        let mut t = 0.0;
        let solved = set_up && IDASolve(mem, t_end, &mut t, y, yp, IDA_NORMAL) >= 0;
        let count = |get: unsafe extern "C" fn(*mut c_void, *mut c_long) -> c_int| {
            let mut k: c_long = 0;
            get(mem, &mut k);
            k as u64
        };
        let run = solved.then(|| Run {
            y: std::slice::from_raw_parts(N_VGetArrayPointer(y), n).to_vec(),
            steps: count(IDAGetNumSteps),
            rejected: count(IDAGetNumErrTestFails),
            evaluations: count(IDAGetNumResEvals),
            jacobians: count(IDAGetNumJacEvals),
            factorizations: count(IDAGetNumLinSolvSetups),
        });
        IDAFree(&mut mem);
        SUNLinSolFree(solver);
        SUNMatDestroy(a);
        N_VDestroy(y);
        N_VDestroy(yp);
        N_VDestroy(id);
        SUNContext_Free(&mut ctx);
        run
    }
}
