//! Krylov solvers for the sparse Newton matrices of particle and field models: how a run
//! chooses them ([`LinearSolver`], [`Krylov`], [`Preconditioner`]) and the solve itself, on
//! faer's conjugate gradient and BiCGSTAB (`faer::matrix_free`).

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::matrix_free::bicgstab::{BicgParams, bicgstab, bicgstab_scratch};
use faer::matrix_free::conjugate_gradient::{
    CgParams, conjugate_gradient, conjugate_gradient_scratch,
};
use faer::matrix_free::{IdentityPrecond, InitialGuessStatus, Precond};
use faer::sparse::SparseColMatRef;
use faer::{MatMut, MatRef, Par};

/// How implicit methods (implicit Euler, Rosenbrock23, Rodas5P, BDF) solve the sparse linear
/// systems of particle and field models; dense models always factorize.
///
/// A direct solve factorizes every new matrix, at a cost growing like N^1.4–N^1.5 (see the
/// README's tables); a preconditioned Krylov solve costs a few sparse products per iteration,
/// and its iteration count grows with the matrix's condition. On reaction–diffusion grids
/// (I − h·J with h·D/Δx² of a few) that count is small and Krylov wins by 20–26× from 32²
/// cells; on a stiff cloth (M − h²·∂f/∂x with h²k/m ≈ 6·10³ at 32²) block-Jacobi CG needs
/// hundreds of iterations and the direct solve wins at every size measured. Set it with
/// [`crate::NewtonOptions::linear`].
#[derive(Clone, Copy, Debug, Default, PartialEq)]
#[non_exhaustive]
pub enum LinearSolver {
    /// [`Krylov::default()`] (block Jacobi) for field models of at least
    /// [`LinearSolver::FIELD_KRYLOV_FROM`] unknowns, [`LinearSolver::Direct`] otherwise —
    /// particle models included, for the reason above. A field model whose Krylov solve needs
    /// more than [`LinearSolver::AUTO_DIRECT_ABOVE`] iterations goes on with
    /// [`Preconditioner::Multigrid`] from [`LinearSolver::MULTIGRID_FROM`] unknowns
    /// ([`KrylovCounts::switched_to_multigrid`]), and with the direct solver below that size or
    /// when multigrid too needs more ([`KrylovCounts::switched_to_direct`]). A Brusselator at
    /// α/Δx² ≈ 10⁴ under BDF ran 2–4× slower with block-Jacobi BiCGSTAB than with its sparse
    /// LU, and 2× faster with multigrid BiCGSTAB than with the LU at 64² and 128² (README,
    /// "Big sparse systems"). The default.
    #[default]
    Auto,
    /// Sparse Cholesky when the matrix is symmetric positive definite, else LU (faer).
    Direct,
    /// A preconditioned Krylov method: conjugate gradient when the matrix is symmetric,
    /// BiCGSTAB otherwise (and when CG finds the matrix indefinite).
    Krylov(Krylov),
}

/// Which kind of model a sparse matrix belongs to, for [`LinearSolver::Auto`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Structure {
    Particles,
    Field,
}

impl LinearSolver {
    /// Where [`LinearSolver::Auto`] switches a field model to Krylov iterations: 1 024
    /// unknowns. Gray–Scott at h = 10 (Pearson's setup), full Newton, 32² cells (2 048
    /// unknowns): 0.57 ms a step with block-Jacobi BiCGSTAB against 11.4 ms with sparse LU
    /// (a one-off measurement, 50 steps; `benches/gray_scott.rs` `run_direct`/`run_krylov`
    /// measure 64² and up, where the ratio is 19–24×).
    pub const FIELD_KRYLOV_FROM: usize = 1024;

    /// Iterations of one solve above which [`LinearSolver::Auto`] gives up block Jacobi for
    /// the run (for multigrid from [`LinearSolver::MULTIGRID_FROM`] unknowns, else for the
    /// direct solver), and multigrid for the direct solver: 50. Gray–Scott at h = 10 needs 6–12 per full-Newton solve from 64² to 128² (and wins
    /// 24×), 29 for a linearized step at 256² to 1e-8 (and wins 19×).
    pub const AUTO_DIRECT_ABOVE: usize = 50;

    /// Unknowns from which [`LinearSolver::Auto`] answers block Jacobi's slow convergence with
    /// multigrid rather than a direct solve: 8 192. The Brusselator under BDF (rtol 1e-6): at 32²
    /// cells (2 048 unknowns) the sparse LU took 0.40–0.61 s against multigrid's 0.52 s (a
    /// draw); at 64² (8 192) 4.1 s against 2.1 s, at 128² 26.4 s against 13.0 s (one run each).
    pub const MULTIGRID_FROM: usize = 8192;

    /// The Krylov options for a system of `n` unknowns of a model of kind `structure`, None
    /// for a direct solve.
    pub(crate) fn krylov_for(&self, n: usize, structure: Structure) -> Option<KrylovSolver> {
        match *self {
            LinearSolver::Auto
                if structure == Structure::Field && n >= LinearSolver::FIELD_KRYLOV_FROM =>
            {
                let mut solver = KrylovSolver::new(Krylov::default(), n);
                solver.direct_above = Some(LinearSolver::AUTO_DIRECT_ABOVE);
                Some(solver)
            }
            LinearSolver::Krylov(krylov) => Some(KrylovSolver::new(krylov, n)),
            _ => None,
        }
    }

    /// Checks the Krylov options, if any.
    pub(crate) fn check(&self) -> crate::Result<()> {
        match self {
            LinearSolver::Krylov(krylov) => krylov.check(),
            _ => Ok(()),
        }
    }
}

/// The options of a preconditioned Krylov solve.
///
/// A solve stops when the relative residual ‖b − A·x‖₂ ≤ η·‖b‖₂, with η = `newton_rtol` for
/// the updates of a Newton iteration (BDF, full-Newton implicit Euler) and η = `rtol` for the
/// one-step methods (the linearized implicit Euler, the Rosenbrock stages). Inside Newton this
/// is an inexact Newton method (Dembo, Eisenstat & Steihaug, "Inexact Newton methods", SIAM J.
/// Numer. Anal. 19, 1982): each update is off by at most about κ·η relatively, so Newton still
/// converges, linearly at that rate once it is below its own, and stops by its own test on the
/// update. In one-step methods nothing corrects the linear error, so `rtol`'s default is tight:
/// 1e-8, well below the tolerances these methods are run at. (To make BDF's solves as tight,
/// set `newton_rtol` too: `rtol` alone no longer reaches them.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Krylov {
    /// Relative residual that ends a solve of a one-step method — the Rosenbrock stages, the
    /// linearized implicit Euler — where nothing corrects the linear error (default 1e-8).
    pub rtol: f64,
    /// Relative residual that ends a solve inside a Newton iteration — BDF, implicit Euler
    /// with full Newton — whose next iteration corrects the linear error (default 1e-3): the
    /// forcing term η of an inexact Newton method, constant here. Each Newton update is then
    /// within about κ·η of the exact one, so Newton converges at a rate of about κ·η per
    /// iteration at worst, and its own test on the update decides when to stop, as before.
    /// (CVODE bounds the same residual by 0.05 × its Newton tolerance.) On the Brusselator
    /// at 64² under BDF at rtol 1e-6, multigrid BiCGSTAB took 4.24 s to 1e-8 and 2.54 s to
    /// 1e-4; at 1e-2 Newton needed more Jacobians (7 against 3).
    pub newton_rtol: f64,
    /// Iterations allowed per solve (default 500). A solve that has not converged by then —
    /// or breaks down — is redone by the direct solver and counted
    /// ([`crate::particles::Factorizations::krylov_fallbacks`]): never a wrong answer.
    pub max_iters: usize,
    /// What approximates the matrix's inverse (default [`Preconditioner::BlockJacobi`]).
    pub preconditioner: Preconditioner,
    /// Start each solve from the previous solution, scaled to the best multiple for the new
    /// right-hand side (default true): the warm start of Baraff & Witkin (1998, §5.3) from the
    /// previous step's Δv. It costs one product with the matrix and never starts worse than
    /// from zero.
    pub warm_start: bool,
}

impl Default for Krylov {
    fn default() -> Self {
        Krylov {
            rtol: 1e-8,
            newton_rtol: 1e-3,
            max_iters: 500,
            preconditioner: Preconditioner::BlockJacobi,
            warm_start: true,
        }
    }
}

impl Krylov {
    fn check(&self) -> crate::Result<()> {
        for (name, rtol) in [
            ("Krylov::rtol", self.rtol),
            ("Krylov::newton_rtol", self.newton_rtol),
        ] {
            if !(rtol.is_finite() && rtol > 0.0 && rtol < 1.0) {
                return Err(crate::Error::invalid(
                    name,
                    format!("must be in (0, 1), got {rtol:?}"),
                ));
            }
        }
        if self.max_iters == 0 {
            return Err(crate::Error::invalid(
                "Krylov::max_iters",
                "must be at least 1",
            ));
        }
        if let Preconditioner::Factorization { refresh_above: 0 } = self.preconditioner {
            return Err(crate::Error::invalid(
                "Preconditioner::Factorization::refresh_above",
                "must be at least 1",
            ));
        }
        Ok(())
    }
}

/// What a Krylov solve is preconditioned with.
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum Preconditioner {
    /// The inverse of each particle's D×D diagonal block of M − h·∂f/∂v − h²·∂f/∂x, or of each
    /// cell's fields × fields block of I − h·J (Jacobi for a one-field model), rebuilt at every
    /// factorization: a few flops per unknown.
    BlockJacobi,
    /// The incomplete LU factorization ILU(0) on the matrix's own pattern (Saad 2003,
    /// Algorithm 10.4; IC(0) for a symmetric matrix), rebuilt at every factorization: each
    /// application costs about one sparse product.
    Ilu0,
    /// Smoothed aggregation algebraic multigrid (Vaněk, Mandel & Brezina 1996), one V-cycle
    /// per application with symmetric block Gauss–Seidel smoothing, coarsened by aggregating
    /// neighbouring particles or cells down to at most 300 unknowns, solved there by a dense
    /// LU. Its levels' patterns are built once per run and their values at every
    /// factorization: a few sparse products' cost per application, and an iteration count
    /// that grows slowly with the grid where block Jacobi's grows like its side. Groups coupled
    /// to nothing (unlinked or pinned particles) are lumped eight to an aggregate; a matrix that
    /// still does not coarsen to 1 000 unknowns is preconditioned by block Jacobi instead.
    Multigrid,
    /// The sparse Cholesky or LU factors of an earlier matrix, applied by substitution, and
    /// refactorized when a solve needs more than `refresh_above` iterations: a factorization
    /// reused over many steps while the matrix changes slowly (the reuse of CVODE's and
    /// Julia's BDF codes, inside a Krylov iteration that keeps each solve exact to its tolerance).
    Factorization {
        /// Iterations of one solve above which the next factorization is a real one.
        refresh_above: usize,
    },
}

/// Work counts of the Krylov solves of one matrix.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct KrylovCounts {
    /// Solves by a Krylov method.
    pub solves: u64,
    /// Their iterations, together.
    pub iterations: u64,
    /// Block-Jacobi, ILU(0) and multigrid preconditioners built (a reused factorization counts
    /// as a Cholesky or LU instead).
    pub preconditioners: u64,
    /// Solves redone by the direct solver (no convergence within `max_iters`, or a
    /// breakdown).
    pub fallbacks: u64,
    /// 1 when [`LinearSolver::Auto`] moved from block Jacobi to multigrid for this run.
    pub switched_to_multigrid: u64,
    /// 1 when [`LinearSolver::Auto`] gave up Krylov solves for this run.
    pub switched_to_direct: u64,
}

/// What a Krylov solve keeps between calls: the options, the previous solution for the warm
/// start, and every buffer, allocated once.
pub(crate) struct KrylovSolver {
    pub(crate) options: Krylov,
    /// The previous solution.
    guess: Vec<f64>,
    /// A·guess, for the warm start's scaling.
    product: Vec<f64>,
    /// The right-hand side, kept while faer writes the solution.
    rhs: Vec<f64>,
    scratch: StackReq,
    stack: MemBuffer,
    /// The last solve took more than `refresh_above` iterations.
    pub(crate) refresh: bool,
    /// Give up Krylov for the run after a solve of more iterations (set by `Auto`).
    pub(crate) direct_above: Option<usize>,
    /// Iterations of the last solve.
    pub(crate) last_iterations: usize,
    /// The solves are a Newton iteration's updates: they stop at `newton_rtol`.
    pub(crate) in_newton: bool,
}

/// A Krylov solve that did not converge within `max_iters`, broke down, or ended on a
/// non-finite iterate: the caller solves directly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct NoConvergence;

impl KrylovSolver {
    pub(crate) fn new(options: Krylov, n: usize) -> Self {
        KrylovSolver {
            options,
            guess: vec![0.0; n],
            product: vec![0.0; n],
            rhs: vec![0.0; n],
            scratch: StackReq::EMPTY,
            stack: MemBuffer::new(StackReq::EMPTY),
            refresh: false,
            direct_above: None,
            last_iterations: 0,
            in_newton: false,
        }
    }

    /// Solves a·x = b, b given in `x`, preconditioned by `precond`: conjugate gradient when
    /// `symmetric` (falling back to BiCGSTAB if CG meets an indefinite matrix), BiCGSTAB
    /// otherwise.
    ///
    /// Errors: [`NoConvergence`], with `x` holding b again.
    pub(crate) fn solve<P: Precond<f64> + Copy>(
        &mut self,
        a: SparseColMatRef<'_, usize, f64>,
        symmetric: bool,
        precond: P,
        x: &mut [f64],
        counts: &mut KrylovCounts,
    ) -> Result<(), NoConvergence> {
        let n = x.len();
        self.reserve(a, precond);
        self.rhs.copy_from_slice(x);
        let Krylov {
            rtol,
            newton_rtol,
            max_iters,
            warm_start,
            ..
        } = self.options;
        let rtol = if self.in_newton { newton_rtol } else { rtol };
        // The warm start's scale, found once (one product) for whichever method runs.
        let scale = if warm_start {
            warm_scale(a, &self.guess, &mut self.product, &self.rhs)
        } else {
            0.0
        };
        let b = MatRef::from_column_major_slice(&self.rhs, n, 1);
        let mut iterations = None;
        // Not `InitialGuessStatus::Zero` even from zero: faer 0.24's CG and BiCGSTAB then leave
        // the residual uninitialised (it should be b); a zero start costs one sparse product.
        let initial_guess = InitialGuessStatus::MaybeNonZero;
        if symmetric {
            start(scale, &self.guess, x);
            let params = CgParams {
                initial_guess,
                rel_tolerance: rtol,
                max_iters,
                ..CgParams::default()
            };
            let out = MatMut::from_column_major_slice_mut(x, n, 1);
            let stack = MemStack::new(&mut self.stack);
            // Any error — no convergence, an indefinite matrix — leaves it to BiCGSTAB.
            if let Ok(info) =
                conjugate_gradient(out, precond, a, b, params, |_| {}, Par::Seq, stack)
            {
                iterations = Some(info.iter_count);
            }
        }
        if iterations.is_none() {
            start(scale, &self.guess, x);
            let params = BicgParams {
                initial_guess,
                rel_tolerance: rtol,
                max_iters,
                ..BicgParams::default()
            };
            let out = MatMut::from_column_major_slice_mut(x, n, 1);
            let stack = MemStack::new(&mut self.stack);
            let identity = IdentityPrecond { dim: n };
            if let Ok(info) = bicgstab(
                out,
                identity,
                precond,
                a,
                b,
                params,
                |_| {},
                Par::Seq,
                stack,
            ) {
                iterations = Some(info.iter_count);
            }
        }
        match iterations {
            Some(iters) if x.iter().all(|v| v.is_finite()) => {
                counts.solves += 1;
                counts.iterations += iters as u64;
                self.last_iterations = iters;
                if let Preconditioner::Factorization { refresh_above } = self.options.preconditioner
                {
                    self.refresh = iters > refresh_above;
                }
                self.guess.copy_from_slice(x);
                Ok(())
            }
            _ => {
                counts.fallbacks += 1;
                x.copy_from_slice(&self.rhs);
                self.guess.fill(0.0);
                self.refresh = true;
                Err(NoConvergence)
            }
        }
    }

    /// Makes the stack big enough for both methods with `precond` (allocates only when a
    /// bigger preconditioner appears: the first LU of a run, or multigrid taking over from block
    /// Jacobi under `Auto`, once).
    fn reserve<P: Precond<f64> + Copy>(&mut self, a: SparseColMatRef<'_, usize, f64>, precond: P) {
        let need = conjugate_gradient_scratch(precond, a, 1, Par::Seq).or(bicgstab_scratch(
            IdentityPrecond { dim: a.nrows() },
            precond,
            a,
            1,
            Par::Seq,
        ));
        if need.size_bytes() > self.scratch.size_bytes()
            || need.align_bytes() > self.scratch.align_bytes()
        {
            self.scratch = need.or(self.scratch);
            self.stack = MemBuffer::new(self.scratch);
        }
    }
}

/// The α minimising ‖b − α·A·guess‖₂ (so α·guess never starts worse than zero): 0 when there is
/// no guess yet or the product says nothing.
fn warm_scale(
    a: SparseColMatRef<'_, usize, f64>,
    guess: &[f64],
    product: &mut [f64],
    b: &[f64],
) -> f64 {
    if guess.iter().all(|&v| v == 0.0) {
        return 0.0;
    }
    let n = guess.len();
    faer::sparse::linalg::matmul::sparse_dense_matmul(
        MatMut::from_column_major_slice_mut(product, n, 1),
        faer::Accum::Replace,
        a,
        MatRef::from_column_major_slice(guess, n, 1),
        1.0,
        Par::Seq,
    );
    let (bq, qq) = b
        .iter()
        .zip(product.iter())
        .fold((0.0, 0.0), |(bq, qq), (b, q)| (bq + b * q, qq + q * q));
    let alpha = bq / qq;
    if alpha.is_finite() { alpha } else { 0.0 }
}

/// Writes the starting iterate `scale`·guess into `x`.
fn start(scale: f64, guess: &[f64], x: &mut [f64]) {
    if scale == 0.0 {
        x.fill(0.0);
    } else {
        for (xi, g) in x.iter_mut().zip(guess) {
            *xi = scale * g;
        }
    }
}

impl Clone for KrylovSolver {
    fn clone(&self) -> Self {
        KrylovSolver {
            options: self.options,
            guess: self.guess.clone(),
            product: self.product.clone(),
            rhs: self.rhs.clone(),
            scratch: self.scratch,
            stack: MemBuffer::new(self.scratch),
            refresh: self.refresh,
            direct_above: self.direct_above,
            last_iterations: self.last_iterations,
            in_newton: self.in_newton,
        }
    }
}
