//! The preconditioned Krylov solve: conjugate gradient (faer's, on our products by rows) or
//! BiCGSTAB (ours, in `bicgstab.rs`), warm-started from the previous solution, every buffer kept
//! between solves.

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::matrix_free::InitialGuessStatus;
use faer::matrix_free::conjugate_gradient::{
    CgParams, conjugate_gradient, conjugate_gradient_scratch,
};
use faer::{MatMut, MatRef, Par};

use super::bicgstab::{Vectors, bicgstab};
use super::{KrylovOptions, Preconditioner, Solves};
use crate::linalg::operator::Column;
use crate::linalg::operator::Products;
use crate::linalg::precond::Applied;
use crate::stats::KrylovWork;

/// What a Krylov solve keeps between calls: the options, the previous solution for the warm
/// start, and every buffer, allocated once.
pub(crate) struct KrylovSolver {
    pub(crate) options: KrylovOptions,
    /// The previous solution.
    guess: Vec<f64>,
    /// A·guess, for the warm start's scaling.
    product: Vec<f64>,
    /// The right-hand side, kept while the solution is written.
    rhs: Vec<f64>,
    /// BiCGSTAB's vectors.
    vectors: Vectors,
    scratch: StackReq,
    stack: MemBuffer,
    /// The last solve took more than `refresh_above` iterations.
    pub(crate) refresh: bool,
    /// Iterations of the last solve.
    pub(crate) last_iterations: usize,
    /// What the solves are for: where they stop.
    pub(crate) solves: Solves,
}

/// A Krylov solve that did not converge within `max_iterations`, broke down, or ended on a
/// non-finite iterate: the caller solves directly.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct NoConvergence;

impl KrylovSolver {
    pub(crate) fn new(options: KrylovOptions, n: usize) -> Self {
        KrylovSolver {
            options,
            guess: vec![0.0; n],
            product: vec![0.0; n],
            rhs: vec![0.0; n],
            vectors: Vectors::new(n),
            scratch: StackReq::EMPTY,
            stack: MemBuffer::new(StackReq::EMPTY),
            refresh: false,
            last_iterations: 0,
            solves: Solves::OneStep,
        }
    }

    /// Solves a·x = b, b given in `x`, preconditioned by `precond`: conjugate gradient when
    /// `symmetric` (falling back to BiCGSTAB if CG meets an indefinite matrix), BiCGSTAB
    /// otherwise.
    ///
    /// Errors: [`NoConvergence`], with `x` holding b again.
    pub(crate) fn solve(
        &mut self,
        a: Products<'_>,
        symmetric: bool,
        precond: Applied<'_>,
        x: &mut [f64],
        counts: &mut KrylovWork,
    ) -> Result<(), NoConvergence> {
        let n = x.len();
        self.reserve(a, precond);
        self.rhs.copy_from_slice(x);
        let KrylovOptions {
            rtol,
            newton_rtol,
            max_iterations,
            warm_start,
            ..
        } = self.options;
        let rtol = match self.solves {
            Solves::OneStep => rtol,
            Solves::Newton => newton_rtol,
            Solves::LooseNewton => self.options.bdf_rtol,
        };
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
                max_iters: max_iterations,
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
            let stack = MemStack::new(&mut self.stack);
            if let Ok(iters) = bicgstab(
                a,
                &precond,
                &self.rhs,
                x,
                scale == 0.0,
                rtol,
                max_iterations,
                &mut self.vectors,
                stack,
            ) {
                iterations = Some(iters);
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
    fn reserve(&mut self, a: Products<'_>, precond: Applied<'_>) {
        let need =
            conjugate_gradient_scratch(precond, a, 1, Par::Seq).or(Column::scratch(&precond));
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
fn warm_scale(a: Products<'_>, guess: &[f64], product: &mut [f64], b: &[f64]) -> f64 {
    if guess.iter().all(|&v| v == 0.0) {
        return 0.0;
    }
    let (bq, qq) = a.product(guess, product, b);
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
            vectors: self.vectors.clone(),
            scratch: self.scratch,
            stack: MemBuffer::new(self.scratch),
            refresh: self.refresh,
            last_iterations: self.last_iterations,
            solves: self.solves,
        }
    }
}
