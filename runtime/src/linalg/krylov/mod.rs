//! Krylov solvers for the sparse Newton matrices of particle and field models: how a run
//! chooses them ([`LinearSolver`], [`KrylovOptions`], [`Preconditioner`]), here; the iteration,
//! on faer's conjugate gradient (`faer::matrix_free`) and our BiCGSTAB (`bicgstab.rs`), in
//! `solve.rs`; the backend with its preconditioners ([`Krylov`]) in `backend.rs`, and `Auto`'s
//! state in `auto.rs`.

mod auto;
mod backend;
mod bicgstab;
mod solve;

pub(crate) use auto::{AutoState, Move};
pub(crate) use backend::{Krylov, Unprepared};
pub(crate) use solve::{KrylovSolver, NoConvergence};

/// How implicit methods (implicit Euler, Rosenbrock23, Rodas5P, BDF) solve the sparse linear
/// systems of particle and field models; dense models always factorize.
///
/// A direct solve factorizes every new matrix, at a cost growing like N^1.4–N^1.5; a
/// preconditioned Krylov solve costs a few sparse products per iteration, and its iteration
/// count grows with the matrix's condition. On reaction–diffusion grids (I − h·J with h·D/Δx² of
/// a few) that count is small and Krylov wins; on a stiff cloth (M − h²·∂f/∂x with
/// h²k/m ≈ 6·10³ at 32²) block-Jacobi CG needs hundreds of iterations and the direct solve wins
/// (the guide's *Linear solvers* chapter; measured in `BENCHMARKS.md`). Set it with
/// [`crate::NewtonOptions::linear`].
#[derive(Clone, Copy, Debug, PartialEq)]
#[non_exhaustive]
pub enum LinearSolver {
    /// [`KrylovOptions::default()`] (block Jacobi) for field models of at least
    /// [`AutoPolicy::krylov_from`] unknowns, [`LinearSolver::Direct`] otherwise — particle
    /// models included, for the reason above. On a periodic grid a slow block-Jacobi solve (more
    /// iterations than one Fourier iteration costs, [`AutoPolicy::fourier_iteration_cost`]) has
    /// the next solve tried with [`Preconditioner::Fourier`], which stays for the run if that
    /// solve cost less ([`crate::KrylovWork::switched_to_fourier`]). A field model whose Krylov
    /// solve needs more than [`AutoPolicy::direct_above`] iterations goes on, for the rest of the
    /// run, with [`Preconditioner::Fourier`] on a periodic grid, else (or when Fourier too needs
    /// more) with [`Preconditioner::Multigrid`] from [`AutoPolicy::multigrid_from`] unknowns
    /// ([`crate::KrylovWork::switched_to_multigrid`]), else with the direct solver
    /// ([`crate::KrylovWork::switched_to_direct`]), as it does when multigrid too needs more.
    /// The default, with [`AutoPolicy::default()`].
    Auto(AutoPolicy),
    /// Sparse Cholesky when the matrix is symmetric positive definite, else LU (faer).
    Direct,
    /// A preconditioned Krylov method: conjugate gradient when the matrix is symmetric,
    /// BiCGSTAB otherwise (and when CG finds the matrix indefinite). A matrix of 2³² stored
    /// entries or more (its products index columns in 32 bits) is solved directly instead.
    Krylov(KrylovOptions),
}

/// Which kind of model a sparse matrix belongs to, for [`LinearSolver::Auto`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Structure {
    Particles,
    Field,
}

impl Default for LinearSolver {
    /// [`LinearSolver::Auto`] with [`AutoPolicy::default()`].
    fn default() -> Self {
        LinearSolver::Auto(AutoPolicy::default())
    }
}

/// The thresholds of [`LinearSolver::Auto`]'s choices, each a measured default; the fields
/// are plain so that a run can move them (a test of where `Auto` switches, a model whose
/// matrices are known to favour one side).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AutoPolicy {
    /// Unknowns from which a field model's solves are Krylov iterations (default 1 024). From
    /// there block-Jacobi BiCGSTAB beats the sparse LU on Gray–Scott at Pearson's set-up
    /// (`benches/gray_scott.rs`, `run_direct`/`run_krylov`). 0 makes every field model's solves
    /// Krylov ones, `usize::MAX` none.
    pub krylov_from: usize,
    /// Iterations of one solve above which `Auto` gives up block Jacobi for the run (for
    /// Fourier or multigrid, else for the direct solver), and multigrid or Fourier for the
    /// direct solver (default 50, well above the 6–30 iterations of the solves where Krylov
    /// pays: Gray–Scott at Pearson's set-up, 64² to 256²).
    pub direct_above: usize,
    /// Unknowns from which `Auto` answers block Jacobi's slow convergence with multigrid rather
    /// than a direct solve (default 8 192). Below it the sparse LU and multigrid draw on the
    /// Brusselator under BDF; above it multigrid wins, by about 2× at 64² and 128² cells.
    pub multigrid_from: usize,
    /// What one iteration preconditioned by [`Preconditioner::Fourier`] costs, in iterations
    /// preconditioned by block Jacobi, per log₂ of the unknowns (default 0.33: two transforms
    /// of each field per application against a few flops per unknown; a coarse model, which
    /// measurements on Pearson's Gray–Scott, 32² to 256² cells, scatter about). Finite and
    /// positive. `Auto` tries Fourier on a periodic grid once a block-Jacobi solve takes more
    /// iterations than one Fourier iteration costs, and again each time block Jacobi needs twice
    /// the iterations of the solve before the last trial Fourier lost; a trial's Fourier solve
    /// decides: Fourier stays for the run unless its iterations, at that cost each, cost more
    /// than the block-Jacobi solve before it. On the 2-D Brusselator this matches Fourier chosen
    /// by hand; on Gray–Scott at Pearson's set-up Fourier is tried and given back; a model whose
    /// diffusion grows in time is given it back twice and keeps it the third time
    /// (`tests/continua/krylov/fourier.rs`).
    pub fourier_cost_per_log2: f64,
}

impl Default for AutoPolicy {
    fn default() -> Self {
        AutoPolicy {
            krylov_from: 1024,
            direct_above: 50,
            multigrid_from: 8192,
            fourier_cost_per_log2: 0.33,
        }
    }
}

impl AutoPolicy {
    /// What one Fourier-preconditioned iteration costs, in block-Jacobi iterations, on a system
    /// of `n` unknowns: [`AutoPolicy::fourier_cost_per_log2`]·log₂ n.
    pub fn fourier_iteration_cost(&self, n: usize) -> f64 {
        self.fourier_cost_per_log2 * (n.max(2) as f64).log2()
    }

    fn check(&self) -> crate::Result<()> {
        let cost = self.fourier_cost_per_log2;
        if !(cost.is_finite() && cost > 0.0) {
            return Err(crate::Error::invalid(
                "AutoPolicy::fourier_cost_per_log2",
                format!("must be finite and positive, got {cost:?}"),
            ));
        }
        Ok(())
    }
}

impl LinearSolver {
    /// The Krylov options for a system of `n` unknowns of a model of kind `structure`, with
    /// `Auto`'s policy when it chose them; None for a direct solve.
    pub(crate) fn krylov_for(
        &self,
        n: usize,
        structure: Structure,
    ) -> Option<(KrylovOptions, Option<AutoPolicy>)> {
        match *self {
            LinearSolver::Auto(policy)
                if structure == Structure::Field && n >= policy.krylov_from =>
            {
                Some((KrylovOptions::default(), Some(policy)))
            }
            LinearSolver::Krylov(krylov) => Some((krylov, None)),
            _ => None,
        }
    }

    /// Checks the Krylov options, if any.
    pub(crate) fn check(&self) -> crate::Result<()> {
        match self {
            LinearSolver::Krylov(krylov) => krylov.check(),
            LinearSolver::Auto(policy) => policy.check(),
            LinearSolver::Direct => Ok(()),
        }
    }
}

/// The options of a preconditioned Krylov solve.
///
/// A solve stops when the relative residual ‖b − A·x‖₂ ≤ η·‖b‖₂, with η = `newton_rtol` for
/// the updates of a Newton iteration (full-Newton implicit Euler; `bdf_rtol` in BDF's on these
/// models) and η = `rtol` for the
/// one-step methods (the linearized implicit Euler, the Rosenbrock stages). Inside Newton this
/// is an inexact Newton method (Dembo, Eisenstat & Steihaug, "Inexact Newton methods", SIAM J.
/// Numer. Anal. 19, 1982): each update is off by at most about κ·η relatively, so Newton still
/// converges, linearly at that rate once it is below its own, and stops by its own test on the
/// update. In one-step methods nothing corrects the linear error, so `rtol`'s default is tight:
/// 1e-8, well below the tolerances these methods are run at. (To make BDF's solves as tight,
/// set `newton_rtol` too: `rtol` alone no longer reaches them.)
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct KrylovOptions {
    /// Relative residual that ends a solve of a one-step method — the Rosenbrock stages, the
    /// linearized implicit Euler — where nothing corrects the linear error (default 1e-8; at
    /// most 1e-2). For an adaptive run keep it below a hundredth of the run's rtol: a stage's
    /// linear error enters the step's error estimate, and the controller then shrinks the steps
    /// until that error is below the tolerance. Rodas5P on a periodic 3 × 1000 heat grid at
    /// rtol 1e-6 (t to 10, D = 1): 21 steps with solves to 1e-8 or 1e-6, 30 to 1e-5, 66 to
    /// 1e-4, 513 to 1e-3.
    pub rtol: f64,
    /// Relative residual that ends a solve inside a Newton iteration — implicit Euler with full
    /// Newton, and BDF where it keeps SciPy's Newton test (`refactor_ratio` 0; see `bdf_rtol`) —
    /// whose next iteration corrects the linear error (default 1e-3): the
    /// forcing term η of an inexact Newton method, constant here. Each Newton update is then
    /// within about κ·η of the exact one, so Newton converges at a rate of about κ·η per
    /// iteration at worst, and its own test on the update decides when to stop. At most 0.1.
    /// (CVODE bounds the same residual by 0.05 × its Newton tolerance.) Looser than about 1e-2,
    /// Newton needs more Jacobians.
    pub newton_rtol: f64,
    /// Relative residual that ends a solve inside BDF's Newton iteration where it stops by
    /// CVODE's test (particle and field models; default 0.05, CVODE's `eplifac`, the same
    /// forcing term): that test accepts an update once its remaining error is a tenth of the
    /// step's error allowance, so a tighter solve buys nothing: on the Brusselator the final
    /// error is the same from 1e-3 to 1e-1, and the looser solves take less time; at most 0.1.
    /// (Full-Newton implicit Euler, whose test is tight, needs more iterations when its solves
    /// are this loose: it keeps `newton_rtol`.)
    pub bdf_rtol: f64,
    /// Iterations allowed per solve (default 500). A solve that has not converged by then —
    /// or breaks down — is redone by the direct solver and counted
    /// ([`crate::KrylovWork::fallbacks`]): never a wrong answer.
    pub max_iterations: usize,
    /// What approximates the matrix's inverse (default [`Preconditioner::BlockJacobi`]).
    pub preconditioner: Preconditioner,
    /// Start each solve from the previous solution, scaled to the best multiple for the new
    /// right-hand side (default true): the warm start of Baraff & Witkin (1998, §5.3) from the
    /// previous step's Δv. It costs one product with the matrix and never starts worse than
    /// from zero.
    pub warm_start: bool,
}

impl Default for KrylovOptions {
    fn default() -> Self {
        KrylovOptions {
            rtol: 1e-8,
            newton_rtol: 1e-3,
            bdf_rtol: 0.05,
            max_iterations: 500,
            preconditioner: Preconditioner::BlockJacobi,
            warm_start: true,
        }
    }
}

impl KrylovOptions {
    fn check(&self) -> crate::Result<()> {
        for (name, rtol, most, why) in [
            (
                "Krylov::rtol",
                self.rtol,
                1e-2,
                "nothing corrects a one-step method's linear error, so a stage solved to a \
                 residual of more than 1 % is wrong by as much, and an adaptive run shrinks its \
                 steps to see through it (keep it below a hundredth of the run's rtol)",
            ),
            (
                "Krylov::newton_rtol",
                self.newton_rtol,
                0.1,
                "an inexact Newton iteration converges at about this rate per iteration at \
                 best, so a looser solve spends more iterations and Jacobians than it saves",
            ),
            (
                "Krylov::bdf_rtol",
                self.bdf_rtol,
                0.1,
                "an inexact Newton iteration converges at about this rate per iteration at \
                 best, so a looser solve spends more iterations and Jacobians than it saves",
            ),
        ] {
            if !(rtol.is_finite() && rtol > 0.0 && rtol <= most) {
                return Err(crate::Error::invalid(
                    name,
                    format!("must be in (0, {most:e}], got {rtol:?}: {why}"),
                ));
            }
        }
        if self.max_iterations == 0 {
            return Err(crate::Error::invalid(
                "Krylov::max_iterations",
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

/// What the solves with a Newton matrix are for, which decides where a Krylov solve stops
/// ([`crate::NewtonMatrix::configure`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Solves {
    /// The stages of a one-step method (the Rosenbrock methods, the linearized implicit Euler),
    /// whose error nothing corrects: [`KrylovOptions::rtol`].
    OneStep,
    /// The updates of a Newton iteration run to a tight tolerance (full-Newton implicit Euler,
    /// BDF under SciPy's Newton test): [`KrylovOptions::newton_rtol`].
    Newton,
    /// The updates of BDF's Newton iteration under CVODE's test, which stops once an update's
    /// error is a tenth of the step's error allowance: [`KrylovOptions::bdf_rtol`].
    LooseNewton,
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
    /// Field models on periodic grids: I − c·J with each of the cells' Jacobian blocks replaced
    /// by its mean over the grid, which the two-dimensional discrete Fourier transform
    /// diagonalises, inverted exactly wave number by wave number (T. Chan's optimal circulant
    /// preconditioner, SIAM J. Sci. Stat. Comput. 9, 1988), rebuilt at every factorization: two
    /// transforms of each field per application, O(N log N), with no coarse levels to set up.
    /// Exact where J is the same at every cell (constant diffusion, a uniform reaction), so a
    /// solve then takes one iteration; the more the reaction varies over the grid against the
    /// diffusion, the more iterations it needs. A particle model, a field that is not periodic,
    /// or more than 8 fields get [`Preconditioner::BlockJacobi`] instead.
    Fourier,
    /// The sparse Cholesky or LU factors of an earlier matrix, applied by substitution, and
    /// refactorized when a solve needs more than `refresh_above` iterations: a factorization
    /// reused over many steps while the matrix changes slowly (the reuse of CVODE's and
    /// Julia's BDF codes, inside a Krylov iteration that keeps each solve exact to its tolerance).
    Factorization {
        /// Iterations of one solve above which the next factorization is a real one.
        refresh_above: usize,
    },
}
