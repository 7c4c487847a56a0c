//! The Krylov solve of a sparse Newton matrix with the run's preconditioner, and the moves
//! `Auto`'s state ([`AutoState`], `linalg/krylov/auto.rs`) decides on: to Fourier, back to
//! block Jacobi, or to multigrid or the direct solver when a preconditioner converges too
//! slowly.

use faer::sparse::linalg::cholesky::LltRef;
use faer::sparse::linalg::lu::LuRef;

use super::{Factored, Products, SparseSolver, StencilMatrix};
use crate::linalg::krylov::{AutoState, Move, NoConvergence, Preconditioner};
use crate::linalg::multigrid::{Multigrid, MultigridRef};
use crate::linalg::precond::{Factors, FourierRef, Ilu0Ref};

impl SparseSolver {
    /// The Krylov solve, by `stencil`'s products when given, else by the rows'.
    ///
    /// Errors: [`NoConvergence`] (rhs unchanged then), also when the run has no Krylov solver.
    pub(super) fn solve_iteratively(
        &mut self,
        stencil: Option<&StencilMatrix>,
    ) -> Result<(), NoConvergence> {
        let Some(krylov) = &mut self.krylov else {
            return Err(NoConvergence);
        };
        if !self.rhs.iter().all(|b| b.is_finite()) {
            return Ok(()); // a non-finite right-hand side stays non-finite: the caller reports it
        }
        let rows = match (stencil, &self.rows) {
            (Some(stencil), _) => Products::Stencil(stencil),
            (None, Some(rows)) => Products::Rows(rows),
            (None, None) => return Err(NoConvergence),
        };
        let n = self.rhs.len();
        // One Krylov solve of the rows with preconditioner `$p` (each its own type).
        macro_rules! solve {
            ($p:expr) => {
                krylov.solve(
                    rows,
                    self.symmetric,
                    $p,
                    &mut self.rhs,
                    &mut self.counts.krylov,
                )
            };
        }
        let outcome = match (
            krylov.options.preconditioner,
            self.factored,
            &self.lu,
            &self.cholesky,
        ) {
            (Preconditioner::BlockJacobi, ..) => solve!(self.jacobi.as_precond(n)),
            (Preconditioner::Ilu0, ..) => match &self.ilu {
                Some(ilu) => solve!(Ilu0Ref(ilu)),
                None => Err(NoConvergence),
            },
            (Preconditioner::Fourier, ..) => match &self.fourier {
                Some(fourier) => solve!(FourierRef(fourier)),
                None => Err(NoConvergence),
            },
            (Preconditioner::Multigrid, ..) => match &self.multigrid {
                Some(multigrid) => solve!(MultigridRef(multigrid)),
                None => Err(NoConvergence),
            },
            (_, Some(Factored::Cholesky), _, Some(cholesky)) => solve!(Factors::Cholesky(
                LltRef::new(cholesky, &self.cholesky_values)
            )),
            (_, Some(Factored::Lu), Some((symbolic, numeric)), _) => {
                solve!(Factors::Lu(LuRef::new_unchecked(symbolic, numeric)))
            }
            _ => Err(NoConvergence),
        };
        if outcome.is_ok()
            && let Some(auto) = &mut krylov.auto
        {
            let from = krylov.options.preconditioner;
            let iterations = krylov.last_iterations;
            let multigrid_from = auto.policy.multigrid_from;
            match auto.after(from, iterations, n) {
                Move::Stay => {}
                // This matrix is too ill-conditioned for the preconditioner to pay.
                Move::GiveUp => self.give_up(from, stencil, multigrid_from),
                // Fourier's solve cost more than block Jacobi's: back, its blocks those of the
                // current matrix.
                Move::BackToBlockJacobi(block_jacobi) => {
                    if self.jacobi.update(&self.values).is_ok() {
                        self.switch(Preconditioner::BlockJacobi);
                        self.counts.krylov.switched_to_fourier = 0;
                        self.auto(|auto| auto.given_back(block_jacobi));
                    }
                }
                // A periodic grid: Fourier is tried on the next solve.
                Move::TryFourier => {
                    if self.move_to_fourier(stencil) {
                        self.auto(|auto| auto.trying(iterations));
                    }
                }
            }
        }
        outcome
    }

    /// `Auto`'s move from block Jacobi to Fourier on a periodic grid: true if made.
    fn move_to_fourier(&mut self, stencil: Option<&StencilMatrix>) -> bool {
        if let (Some(fourier), Some(stencil)) = (&mut self.fourier, stencil)
            && fourier.update(stencil).is_ok()
        {
            self.switch(Preconditioner::Fourier);
            self.counts.krylov.switched_to_fourier = 1;
            return true;
        }
        false
    }

    /// `Auto`'s next solver after a solve of too many iterations with `from`: a periodic grid
    /// goes on from block Jacobi with Fourier, a big matrix with multigrid (from block Jacobi
    /// or Fourier), anything else (or a preconditioner that cannot be built) with the direct
    /// solver, for the rest of the run.
    fn give_up(
        &mut self,
        from: Preconditioner,
        stencil: Option<&StencilMatrix>,
        multigrid_from: usize,
    ) {
        let n = self.rhs.len();
        if from == Preconditioner::BlockJacobi && self.move_to_fourier(stencil) {
            return;
        }
        if matches!(from, Preconditioner::BlockJacobi | Preconditioner::Fourier)
            && n >= multigrid_from
        {
            let (size, index) = &self.blocks;
            if self.multigrid.is_none() {
                self.multigrid = Multigrid::new(*size, index.clone(), &self.pattern);
            }
            let values = &self.values;
            if self
                .multigrid
                .as_mut()
                .is_some_and(|multigrid| multigrid.update(values).is_ok())
            {
                self.switch(Preconditioner::Multigrid);
                self.counts.krylov.switched_to_multigrid = 1;
                return;
            }
        }
        self.krylov = None;
        self.counts.krylov.switched_to_direct = 1;
    }

    /// Tells `Auto`'s state, if the run has one, what the solver did.
    fn auto(&mut self, tell: impl FnOnce(&mut AutoState)) {
        if let Some(auto) = self.krylov.as_mut().and_then(|k| k.auto.as_mut()) {
            tell(auto);
        }
    }

    /// The run's Krylov solves go on with `preconditioner`, built for the current values.
    fn switch(&mut self, preconditioner: Preconditioner) {
        if let Some(krylov) = &mut self.krylov {
            krylov.options.preconditioner = preconditioner;
            self.counts.krylov.preconditioners += 1;
        }
    }
}
