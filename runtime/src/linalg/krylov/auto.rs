//! [`LinearSolver::Auto`](super::LinearSolver::Auto)'s state over a run: after each converged
//! Krylov solve, whether to keep the preconditioner, try Fourier on a periodic grid, give a
//! trial of Fourier back to block Jacobi, or give the preconditioner up. The decision is a pure
//! function of the policy, the trial's state and the solve's iterations; the Krylov backend
//! carries it out (`linalg/krylov/backend.rs`), and tells this state when a move it was told
//! to make could be made.

use super::{AutoPolicy, Preconditioner};

/// `Auto`'s trials of [`Preconditioner::Fourier`] on a periodic grid after a slow block-Jacobi
/// solve: each trial's Fourier solve decides whether it stays.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum FourierTrial {
    /// Not tried yet.
    Untried,
    /// The next solve is Fourier's, after a block-Jacobi solve of this many iterations.
    Trying(usize),
    /// Tried and given back after a block-Jacobi solve of this many iterations: tried again
    /// once block Jacobi needs twice as many (the problem has stiffened since).
    GivenBack(usize),
    /// Tried and kept for the run.
    Kept,
}

/// What `Auto` does after a converged solve.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Move {
    /// Keep the preconditioner.
    Stay,
    /// The solve took more than [`AutoPolicy::direct_above`] iterations: give the
    /// preconditioner up for the run (for Fourier, multigrid or the direct solve).
    GiveUp,
    /// A trial's Fourier solve cost more than the block-Jacobi solve of this many iterations
    /// before it: back to block Jacobi ([`AutoState::given_back`] once done).
    BackToBlockJacobi(usize),
    /// A block-Jacobi solve costs more than one Fourier iteration would: try Fourier on the
    /// next solve ([`AutoState::trying`] once done).
    TryFourier,
}

/// `Auto`'s thresholds and where its trial of Fourier stands.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AutoState {
    pub(crate) policy: AutoPolicy,
    trial: FourierTrial,
}

impl AutoState {
    pub(crate) fn new(policy: AutoPolicy) -> Self {
        AutoState {
            policy,
            trial: FourierTrial::Untried,
        }
    }

    /// The move after a converged solve of `iterations` preconditioned by `from`, on `n`
    /// unknowns. A trial's Fourier solve is kept unless the move says otherwise.
    ///
    /// `Auto` tries Fourier once a block-Jacobi solve costs more than one Fourier iteration
    /// would ([`AutoPolicy::fourier_iteration_cost`]), and again once block Jacobi needs twice
    /// the iterations of the solve before a trial Fourier lost.
    pub(crate) fn after(&mut self, from: Preconditioner, iterations: usize, n: usize) -> Move {
        let trial = self.trial;
        if let FourierTrial::Trying(_) = trial {
            self.trial = FourierTrial::Kept;
        }
        if iterations > self.policy.direct_above {
            return Move::GiveUp;
        }
        let cost = self.policy.fourier_iteration_cost(n);
        if let FourierTrial::Trying(block_jacobi) = trial
            && from == Preconditioner::Fourier
            && iterations as f64 * cost > block_jacobi as f64
        {
            return Move::BackToBlockJacobi(block_jacobi);
        }
        let try_fourier = match trial {
            FourierTrial::Untried => iterations as f64 > cost,
            FourierTrial::GivenBack(before) => iterations > 2 * before,
            FourierTrial::Trying(_) | FourierTrial::Kept => false,
        };
        if from == Preconditioner::BlockJacobi && try_fourier {
            return Move::TryFourier;
        }
        Move::Stay
    }

    /// The solver went back to block Jacobi after a trial that lost to a block-Jacobi solve
    /// of `block_jacobi` iterations.
    pub(crate) fn given_back(&mut self, block_jacobi: usize) {
        self.trial = FourierTrial::GivenBack(block_jacobi);
    }

    /// The solver moved to Fourier for a trial, after a block-Jacobi solve of `block_jacobi`
    /// iterations.
    pub(crate) fn trying(&mut self, block_jacobi: usize) {
        self.trial = FourierTrial::Trying(block_jacobi);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use Preconditioner::{BlockJacobi, Fourier};

    /// On 4 096 unknowns one Fourier iteration costs 0.33·12 = 3.96 block-Jacobi iterations
    /// (the default policy): a block-Jacobi solve of 3 stays, one of 4 has Fourier tried; the
    /// trial's solve of 1 Fourier iteration (3.96) beats the 4 and is kept, one of 2 (7.92)
    /// loses and is given back; Fourier is then tried again only past twice the 4; a solve
    /// past `direct_above` gives up whatever the trial's state.
    #[test]
    fn the_trial_of_fourier_is_decided_by_cost() {
        let n = 4096;
        let mut auto = AutoState::new(AutoPolicy::default());
        assert_eq!(auto.after(BlockJacobi, 3, n), Move::Stay);
        assert_eq!(auto.after(BlockJacobi, 4, n), Move::TryFourier);
        auto.trying(4);
        assert_eq!(auto.after(Fourier, 1, n), Move::Stay);
        assert_eq!(auto.trial, FourierTrial::Kept);
        assert_eq!(auto.after(Fourier, 40, n), Move::Stay);
        assert_eq!(auto.after(Fourier, 51, n), Move::GiveUp);

        let mut auto = AutoState::new(AutoPolicy::default());
        assert_eq!(auto.after(BlockJacobi, 4, n), Move::TryFourier);
        auto.trying(4);
        assert_eq!(auto.after(Fourier, 2, n), Move::BackToBlockJacobi(4));
        auto.given_back(4);
        assert_eq!(auto.after(BlockJacobi, 8, n), Move::Stay);
        assert_eq!(auto.after(BlockJacobi, 9, n), Move::TryFourier);
        // A move the solver could not make leaves the trial where it was.
        assert_eq!(auto.after(BlockJacobi, 9, n), Move::TryFourier);
        assert_eq!(auto.after(BlockJacobi, 51, n), Move::GiveUp);
    }
}
