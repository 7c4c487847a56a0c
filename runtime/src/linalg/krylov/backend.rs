//! [`Krylov`]: the preconditioned Krylov backend. It owns the iteration ([`KrylovSolver`]: conjugate
//! gradient or BiCGSTAB), the preconditioners a run asks for, each built the first time it is
//! needed, and `Auto`'s state, whose moves ([`AutoState`], `auto.rs`) it carries out: to
//! Fourier, back to block Jacobi, or to multigrid or the direct solver when a preconditioner
//! converges too slowly.

use super::{AutoPolicy, AutoState, KrylovOptions, KrylovSolver, Move, NoConvergence};
use super::{Preconditioner, Solves};
use crate::linalg::direct::Direct;
use crate::linalg::precond::{
    Applied, BlockJacobi, Fourier, Ilu0, Multigrid, PrecondError, Preconditioning,
};
use crate::linalg::solver::{LinearSolve, SparseView};
use crate::stats::LinearWork;

/// Conjugate gradient when the values are symmetric, BiCGSTAB otherwise, preconditioned by
/// [`KrylovOptions::preconditioner`] (or `Auto`'s current choice).
#[derive(Clone)]
pub(crate) struct Krylov {
    iteration: KrylovSolver,
    /// The preconditioner of the next solves.
    active: Preconditioner,
    preconditioners: Preconditioners,
    /// `Auto`'s thresholds and state, when `Auto` chose these solves.
    auto: Option<AutoState>,
    /// `Auto` gave the Krylov solves up for the rest of the run.
    exhausted: bool,
}

/// Each preconditioner, made the first time the run asks for it and kept (a trial of Fourier
/// given back keeps its transforms).
#[derive(Clone)]
struct Preconditioners {
    jacobi: Option<BlockJacobi>,
    ilu: Option<Ilu0>,
    fourier: Option<Fourier>,
    multigrid: Option<Multigrid>,
    /// The factorization [`Preconditioner::Factorization`] substitutes in.
    factors: Direct,
}

/// Why [`Krylov::set_linearisation`] could not prepare a solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Unprepared {
    /// The preconditioner could not be built from these values (a singular block or pivot):
    /// solve directly this time, which decides whether the matrix is singular.
    Unbuilt(PrecondError),
    /// The factorization [`Preconditioner::Factorization`] needs found the matrix singular.
    Singular,
}

impl Krylov {
    /// The solves of a system of `n` unknowns with `options`, whose relative residual is set
    /// by what they are for (`solves`), under `Auto`'s `policy` when given.
    pub(crate) fn new(
        options: KrylovOptions,
        policy: Option<AutoPolicy>,
        solves: Solves,
        n: usize,
    ) -> Self {
        let mut iteration = KrylovSolver::new(options, n);
        iteration.solves = solves;
        Krylov {
            iteration,
            active: options.preconditioner,
            preconditioners: Preconditioners {
                jacobi: None,
                ilu: None,
                fourier: None,
                multigrid: None,
                factors: Direct::new(),
            },
            auto: policy.map(AutoState::new),
            exhausted: false,
        }
    }

    /// The solves with new options (what they are for changed: BDF's first attempt), keeping
    /// the preconditioners made so far, their structures and the last factorization: the
    /// iteration, the active preconditioner and `Auto`'s state start again.
    pub(crate) fn reconfigured(
        self,
        options: KrylovOptions,
        policy: Option<AutoPolicy>,
        solves: Solves,
        n: usize,
    ) -> Self {
        Krylov {
            preconditioners: self.preconditioners,
            ..Krylov::new(options, policy, solves, n)
        }
    }

    /// `Auto` gave the Krylov solves up for the rest of the run: the caller solves directly.
    pub(crate) fn exhausted(&self) -> bool {
        self.exhausted
    }

    /// The run's solves go on with `which`, built for the current values: true if it could be.
    fn switch(&mut self, which: Preconditioner, a: &SparseView<'_>, work: &mut LinearWork) -> bool {
        let built = self
            .preconditioners
            .made(which, a)
            .map(|p| p.update_from(a));
        if let Some(Ok(())) = built {
            self.active = which;
            work.krylov.preconditioners += 1;
            return true;
        }
        false
    }

    /// `Auto`'s move after a converged solve of `iterations`.
    fn after(&mut self, iterations: usize, a: &SparseView<'_>, work: &mut LinearWork) {
        let Some(auto) = &mut self.auto else {
            return;
        };
        let from = self.active;
        let multigrid_from = auto.policy.multigrid_from;
        let n = a.pattern.nrows();
        match auto.after(from, iterations, n) {
            Move::Stay => {}
            // This matrix is too ill-conditioned for the preconditioner to pay.
            Move::GiveUp => self.give_up(from, a, multigrid_from, work),
            // Fourier's solve cost more than block Jacobi's: back, its blocks those of the
            // current matrix.
            Move::BackToBlockJacobi(block_jacobi) => {
                if self.switch(Preconditioner::BlockJacobi, a, work) {
                    work.krylov.switched_to_fourier = 0;
                    self.tell(|auto| auto.given_back(block_jacobi));
                }
            }
            // A periodic grid: Fourier is tried on the next solve.
            Move::TryFourier => {
                if self.switch(Preconditioner::Fourier, a, work) {
                    work.krylov.switched_to_fourier = 1;
                    self.tell(|auto| auto.trying(iterations));
                }
            }
        }
    }

    /// `Auto`'s next solver after a solve of too many iterations with `from`: a periodic grid
    /// goes on from block Jacobi with Fourier, a big matrix with multigrid (from block Jacobi
    /// or Fourier), anything else (or a preconditioner that cannot be built) with the direct
    /// solver, for the rest of the run.
    fn give_up(
        &mut self,
        from: Preconditioner,
        a: &SparseView<'_>,
        multigrid_from: usize,
        work: &mut LinearWork,
    ) {
        if from == Preconditioner::BlockJacobi && self.switch(Preconditioner::Fourier, a, work) {
            work.krylov.switched_to_fourier = 1;
            return;
        }
        if matches!(from, Preconditioner::BlockJacobi | Preconditioner::Fourier)
            && a.pattern.nrows() >= multigrid_from
            && self.switch(Preconditioner::Multigrid, a, work)
        {
            work.krylov.switched_to_multigrid = 1;
            return;
        }
        self.exhausted = true;
        work.krylov.switched_to_direct = 1;
    }

    /// Tells `Auto`'s state, if the run has one, what the solver did.
    fn tell(&mut self, tell: impl FnOnce(&mut AutoState)) {
        if let Some(auto) = &mut self.auto {
            tell(auto);
        }
    }
}

impl Preconditioners {
    /// Block Jacobi for `a`'s groups of unknowns, made the first time: the preconditioner every
    /// matrix has.
    fn block_jacobi(&mut self, a: &SparseView<'_>) -> &mut BlockJacobi {
        let (size, index) = a.blocks;
        self.jacobi
            .get_or_insert_with(|| BlockJacobi::new(size, index.to_vec(), a.pattern))
    }

    /// The preconditioner `which`, its structure made for `a`'s pattern the first time; `None`
    /// when it cannot be made (Fourier off a periodic grid, multigrid on a matrix that does not
    /// coarsen) and for [`Preconditioner::Factorization`], which is the direct solver's.
    fn made(
        &mut self,
        which: Preconditioner,
        a: &SparseView<'_>,
    ) -> Option<&mut dyn Preconditioning> {
        let (size, index) = a.blocks;
        match which {
            Preconditioner::BlockJacobi => Some(self.block_jacobi(a)),
            Preconditioner::Ilu0 => Some(self.ilu.get_or_insert_with(|| Ilu0::new(a.pattern))),
            Preconditioner::Fourier => {
                if self.fourier.is_none() {
                    self.fourier = a.stencil.and_then(|stencil| {
                        let (nx, ny, fields) = stencil.shape();
                        Fourier::new(nx, ny, fields, stencil.blocks())
                    });
                }
                self.fourier.as_mut().map(|p| p as _)
            }
            Preconditioner::Multigrid => {
                if self.multigrid.is_none() {
                    self.multigrid = Multigrid::new(size, index.to_vec(), a.pattern);
                }
                self.multigrid.as_mut().map(|p| p as _)
            }
            Preconditioner::Factorization { .. } => None,
        }
    }

    /// The active preconditioner, as the iteration applies it.
    fn applied(&self, active: Preconditioner) -> Option<Applied<'_>> {
        Some(match active {
            Preconditioner::BlockJacobi => Applied::Built(self.jacobi.as_ref()?),
            Preconditioner::Ilu0 => Applied::Built(self.ilu.as_ref()?),
            Preconditioner::Fourier => Applied::Built(self.fourier.as_ref()?),
            Preconditioner::Multigrid => Applied::Built(self.multigrid.as_ref()?),
            Preconditioner::Factorization { .. } => match self.factors.factors() {
                Some(factors) => Applied::Factors(factors),
                None => return None,
            },
        })
    }
}

impl LinearSolve for Krylov {
    type SetupError = Unprepared;
    type SolveError = NoConvergence;

    /// Builds the active preconditioner from `a`'s values, counted in `krylov.preconditioners`
    /// ([`Preconditioner::Factorization`] keeps an earlier factorization until a solve asks
    /// for a fresh one). A preconditioner that cannot be made for this matrix at all (Fourier
    /// off a periodic grid, multigrid on a matrix that does not coarsen) is replaced by block
    /// Jacobi for the run.
    fn set_linearisation(
        &mut self,
        a: &SparseView<'_>,
        work: &mut LinearWork,
    ) -> Result<(), Unprepared> {
        let refresh = std::mem::take(&mut self.iteration.refresh);
        if let Preconditioner::Factorization { .. } = self.active {
            let factors = &mut self.preconditioners.factors;
            if !factors.factored() || refresh {
                factors
                    .set_linearisation(a, work)
                    .map_err(|_| Unprepared::Singular)?;
            }
            return Ok(());
        }
        let built = match self.preconditioners.made(self.active, a) {
            Some(preconditioner) => preconditioner.update_from(a),
            None => {
                self.active = Preconditioner::BlockJacobi;
                self.preconditioners.block_jacobi(a).update_from(a)
            }
        };
        built.map_err(Unprepared::Unbuilt)?;
        work.krylov.preconditioners += 1;
        Ok(())
    }

    /// Solves by the Krylov method, warm-started, then makes `Auto`'s move. A right-hand side
    /// that is not finite is left as it is, for the caller to report.
    ///
    /// Errors: [`NoConvergence`] (`x` unchanged then).
    fn solve_in_place(
        &mut self,
        a: &SparseView<'_>,
        x: &mut [f64],
        work: &mut LinearWork,
    ) -> Result<(), NoConvergence> {
        if !x.iter().all(|b| b.is_finite()) {
            return Ok(());
        }
        let (Some(products), Some(precond)) =
            (a.products, self.preconditioners.applied(self.active))
        else {
            return Err(NoConvergence);
        };
        self.iteration
            .solve(products, a.symmetric, precond, x, &mut work.krylov)?;
        let iterations = self.iteration.last_iterations;
        self.after(iterations, a, work);
        Ok(())
    }
}
