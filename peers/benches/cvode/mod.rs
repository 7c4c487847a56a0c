//! SUNDIALS CVODE (6.4, C) through its C API: variable-order BDF with Newton iterations on a
//! dense matrix and the caller's analytic Jacobian — the anchor users trust for stiff problems.
//! Linked from the system library (`apt-get install libsundials-dev`; see `peers/build.rs`).

use std::ffi::{c_int, c_long, c_void};

type Context = *mut c_void;
type Vector = *mut c_void;
type Matrix = *mut c_void;
type LinearSolver = *mut c_void;
type Rhs = extern "C" fn(f64, Vector, Vector, *mut c_void) -> c_int;
type Jac =
    extern "C" fn(f64, Vector, Vector, Matrix, *mut c_void, Vector, Vector, Vector) -> c_int;

/// `CV_BDF` and `CV_NORMAL` of `cvode.h`.
const CV_BDF: c_int = 2;
const CV_NORMAL: c_int = 1;

unsafe extern "C" {
    fn SUNContext_Create(comm: *mut c_void, ctx: *mut Context) -> c_int;
    fn SUNContext_Free(ctx: *mut Context) -> c_int;
    fn N_VNew_Serial(length: i64, ctx: Context) -> Vector;
    fn N_VGetArrayPointer(v: Vector) -> *mut f64;
    fn N_VDestroy(v: Vector);
    fn SUNDenseMatrix(rows: i64, columns: i64, ctx: Context) -> Matrix;
    fn SUNDenseMatrix_Data(a: Matrix) -> *mut f64;
    fn SUNMatDestroy(a: Matrix);
    fn SUNLinSol_Dense(y: Vector, a: Matrix, ctx: Context) -> LinearSolver;
    fn SUNLinSolFree(solver: LinearSolver) -> c_int;
    fn CVodeCreate(lmm: c_int, ctx: Context) -> *mut c_void;
    fn CVodeInit(mem: *mut c_void, f: Rhs, t0: f64, y0: Vector) -> c_int;
    fn CVodeSStolerances(mem: *mut c_void, rtol: f64, atol: f64) -> c_int;
    fn CVodeSetUserData(mem: *mut c_void, data: *mut c_void) -> c_int;
    fn CVodeSetMaxNumSteps(mem: *mut c_void, steps: c_long) -> c_int;
    fn CVodeSetStopTime(mem: *mut c_void, t: f64) -> c_int;
    fn CVodeSetLinearSolver(mem: *mut c_void, solver: LinearSolver, a: Matrix) -> c_int;
    fn CVodeSetJacFn(mem: *mut c_void, jac: Jac) -> c_int;
    fn CVode(mem: *mut c_void, tout: f64, y: Vector, t: *mut f64, task: c_int) -> c_int;
    fn CVodeGetNumSteps(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn CVodeGetNumErrTestFails(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn CVodeGetNumRhsEvals(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn CVodeGetNumJacEvals(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn CVodeGetNumLinSolvSetups(mem: *mut c_void, n: *mut c_long) -> c_int;
    fn CVodeFree(mem: *mut *mut c_void);
}

/// The equations CVODE integrates: f, and J written column-major into an n × n slice.
pub struct Equations<'a> {
    pub n: usize,
    pub rhs: &'a dyn Fn(f64, &[f64], &mut [f64]),
    pub jacobian: &'a dyn Fn(f64, &[f64], &mut [f64]),
}

/// A finished run: the final state and CVODE's own counts.
pub struct Run {
    pub y: Vec<f64>,
    pub steps: u64,
    /// Error-test failures.
    pub rejected: u64,
    pub evaluations: u64,
    pub jacobians: u64,
    /// Linear-solver setups: dense LU factorizations of I − γJ.
    pub factorizations: u64,
}

extern "C" fn rhs(t: f64, y: Vector, dy: Vector, data: *mut c_void) -> c_int {
    // SAFETY: `data` is the `Equations` `solve` passed, alive for the whole run; y and dy are
    // CVODE's serial vectors of length n.
    unsafe {
        let equations = &*(data as *const Equations<'_>);
        let n = equations.n;
        let y = std::slice::from_raw_parts(N_VGetArrayPointer(y), n);
        let dy = std::slice::from_raw_parts_mut(N_VGetArrayPointer(dy), n);
        (equations.rhs)(t, y, dy);
    }
    0
}

extern "C" fn jacobian(
    t: f64,
    y: Vector,
    _: Vector,
    j: Matrix,
    data: *mut c_void,
    _: Vector,
    _: Vector,
    _: Vector,
) -> c_int {
    // SAFETY: as in `rhs`; J is CVODE's n × n dense matrix, column-major with leading
    // dimension n.
    unsafe {
        let equations = &*(data as *const Equations<'_>);
        let n = equations.n;
        let y = std::slice::from_raw_parts(N_VGetArrayPointer(y), n);
        let j = std::slice::from_raw_parts_mut(SUNDenseMatrix_Data(j), n * n);
        (equations.jacobian)(t, y, j);
    }
    0
}

/// Integrates from `y0` at t = 0 to `t_end` with CVODE's BDF, dense direct solver and the
/// analytic Jacobian at scalar tolerances; `None` when CVODE reports a failure.
pub fn solve(equations: &Equations<'_>, y0: &[f64], t_end: f64, rtol: f64, atol: f64) -> Option<Run> {
    let n = equations.n as i64;
    // SAFETY: the SUNDIALS 6.4 C API used as its documentation says: every object created here
    // is freed before returning, and `equations` outlives the CVODE memory that points to it.
    unsafe {
        let mut ctx: Context = std::ptr::null_mut();
        if SUNContext_Create(std::ptr::null_mut(), &mut ctx) != 0 {
            return None;
        }
        let y = N_VNew_Serial(n, ctx);
        std::slice::from_raw_parts_mut(N_VGetArrayPointer(y), y0.len()).copy_from_slice(y0);
        let mut mem = CVodeCreate(CV_BDF, ctx);
        let a = SUNDenseMatrix(n, n, ctx);
        let solver = SUNLinSol_Dense(y, a, ctx);
        let set_up = CVodeInit(mem, rhs, 0.0, y) == 0
            && CVodeSStolerances(mem, rtol, atol) == 0
            && CVodeSetUserData(mem, equations as *const Equations<'_> as *mut c_void) == 0
            && CVodeSetMaxNumSteps(mem, c_long::MAX) == 0
            && CVodeSetStopTime(mem, t_end) == 0
            && CVodeSetLinearSolver(mem, solver, a) == 0
            && CVodeSetJacFn(mem, jacobian) == 0;
        let mut t = 0.0;
        let solved = set_up && CVode(mem, t_end, y, &mut t, CV_NORMAL) >= 0;
        let count = |get: unsafe extern "C" fn(*mut c_void, *mut c_long) -> c_int| {
            let mut k: c_long = 0;
            get(mem, &mut k);
            k as u64
        };
        let run = solved.then(|| Run {
            y: std::slice::from_raw_parts(N_VGetArrayPointer(y), y0.len()).to_vec(),
            steps: count(CVodeGetNumSteps),
            rejected: count(CVodeGetNumErrTestFails),
            evaluations: count(CVodeGetNumRhsEvals),
            jacobians: count(CVodeGetNumJacEvals),
            factorizations: count(CVodeGetNumLinSolvSetups),
        });
        CVodeFree(&mut mem);
        SUNLinSolFree(solver);
        SUNMatDestroy(a);
        N_VDestroy(y);
        SUNContext_Free(&mut ctx);
        run
    }
}
