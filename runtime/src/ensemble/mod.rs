//! Monte Carlo ensembles: many members of one experiment, run in parallel, reproducible bit for
//! bit on any number of threads and across any split into shards.
//!
//! A member is a closure of (member index, the member's random generator) that returns a fixed
//! number of observations (a quantity at the recorded times of a run, an estimate, …). Member
//! `i`'s generator is ChaCha8 seeded from the ensemble's `seed` with stream `i`
//! ([`member_rng`]): ChaCha is counter-based, so each member's numbers depend only on
//! (seed, i), never on which thread ran it or which other members ran before. Members run in
//! parallel with rayon and come back in index order; the reductions ([`Members::statistics`])
//! sum in index order, so the mean, variance and quantiles are bit-identical for any thread count.
//!
//! # Ensembles larger than one machine
//!
//! [`Ensemble::shard`] runs a deterministic share of the members: shard `k` of `n` takes members
//! `⌊kM/n⌋ … ⌊(k+1)M/n⌋ − 1` ([`Shard::range`]). Each shard writes its members' raw observations
//! ([`Members::write_csv`], whole or not at all, numbers printed so they read back to the same
//! bits, the shard `k/n` in every row); [`Members::merge`] (or [`Members::merge_files`]) reads
//! them back, checks that they are every shard of one ensemble exactly once, naming any shard
//! missing or given twice ([`Error::BadShards`]), and gives a result bit-identical to a
//! one-machine run. The `monte_carlo` example's `--shard k/n` and `--merge FILES…` do this under
//! any driver; `docs/book/src/distributed.md` has the contract and a Slurm recipe that CI runs
//! on a real Slurm.
mod file;
mod members;
mod merge;
mod shard;
mod statistics;

pub use members::Members;
pub use shard::{MemberRng, Shard, member_rng};
pub use statistics::Statistics;

use rayon::prelude::*;

use crate::error::{bytes_text, count_text};
use crate::{Error, Result};

/// An ensemble's settings: plain data with a [`Default`].
#[derive(Clone, Debug, PartialEq)]
pub struct Ensemble {
    /// Members in the whole ensemble (over all shards), at least 1 (default 100).
    pub members: u64,
    /// The base seed every member's generator derives from (default 0).
    pub seed: u64,
    /// The share of the members this run takes ([`Shard::WHOLE`] by default).
    pub shard: Shard,
    /// Show a progress bar on standard error (not on WebAssembly, which has no terminal;
    /// default false). The results do not depend on it.
    pub progress: bool,
}

impl Default for Ensemble {
    fn default() -> Self {
        Ensemble {
            members: 100,
            seed: 0,
            shard: Shard::WHOLE,
            progress: false,
        }
    }
}

impl Ensemble {
    /// Runs this shard's members in parallel (rayon's global pool, or the pool it is called in)
    /// and returns their observations in member order.
    ///
    /// The results of this shard's members are held until the run ends: their slots are
    /// allocated before the first member runs, and a shard too large for the machine's memory
    /// is an error then, not an abort.
    ///
    /// Errors: [`Error::InvalidInput`] for no members, a shard that does not exist
    /// ([`Shard::range`]) or a shard count above the member count, members whose results cannot
    /// be allocated (2⁴⁰ of them need over 100 TB: split them into shards), or members that return
    /// different numbers of observations; otherwise the error of the lowest-numbered member that
    /// failed (the same one whatever the threads did).
    pub fn run<F>(&self, member: F) -> Result<Members>
    where
        F: Fn(u64, &mut MemberRng) -> Result<Vec<f64>> + Sync,
    {
        if self.members == 0 {
            return Err(Error::invalid(
                "members",
                "an ensemble needs at least one member",
            ));
        }
        let range = self.shard.range(self.members)?;
        if self.shard.count > self.members {
            return Err(Error::invalid(
                "shard",
                format!(
                    "{}/{} of {} members: some shards would be empty; use at most {} shards",
                    self.shard.index, self.shard.count, self.members, self.members
                ),
            ));
        }
        let count = range.end - range.start;
        let mut outputs: Vec<Result<Vec<f64>>> = Vec::new();
        let mut rows = Vec::new();
        let room = usize::try_from(count).is_ok_and(|n| {
            outputs.try_reserve_exact(n).is_ok() && rows.try_reserve_exact(n).is_ok()
        });
        if !room {
            let slot =
                std::mem::size_of::<Result<Vec<f64>>>() + std::mem::size_of::<(u64, Vec<f64>)>();
            return Err(Error::invalid(
                "members",
                format!(
                    "{} members need {} for their results before any runs, which cannot be \
                     allocated; split them into shards (`Ensemble::shard`), each holding only its \
                     own members",
                    count_text(count),
                    bytes_text(u128::from(count) * slot as u128)
                ),
            ));
        }
        let bar = Bar::new(
            self.progress,
            count,
            format!("shard {}/{}", self.shard.index, self.shard.count),
        );
        // Into the slots reserved above (a range knows its length, so `par_extend` reserves
        // only what is missing: nothing).
        outputs.par_extend(range.clone().into_par_iter().map(|i| {
            let out = member(i, &mut member_rng(self.seed, i));
            bar.inc();
            out
        }));
        bar.finish();
        for (i, out) in range.zip(outputs) {
            rows.push((i, out?));
        }
        let members = Members {
            members: self.members,
            seed: self.seed,
            shard: self.shard,
            rows,
        };
        members.check()?;
        Ok(members)
    }
}

/// The ensemble's progress bar on standard error (indicatif), or nothing: when not asked for,
/// and on WebAssembly, which has no terminal.
struct Bar {
    #[cfg(not(target_arch = "wasm32"))]
    bar: indicatif::ProgressBar,
}

impl Bar {
    #[cfg(not(target_arch = "wasm32"))]
    fn new(shown: bool, count: u64, message: String) -> Self {
        use indicatif::{ProgressBar, ProgressStyle};
        let bar = if shown {
            let bar = ProgressBar::new(count);
            if let Ok(style) = ProgressStyle::with_template(
                "{msg} {bar:40} {pos}/{len} members, {elapsed} elapsed, ETA {eta}",
            ) {
                bar.set_style(style);
            }
            bar.set_message(message);
            bar
        } else {
            ProgressBar::hidden()
        };
        Bar { bar }
    }

    #[cfg(target_arch = "wasm32")]
    fn new(_: bool, _: u64, _: String) -> Self {
        Bar {}
    }

    fn inc(&self) {
        #[cfg(not(target_arch = "wasm32"))]
        self.bar.inc(1);
    }

    fn finish(&self) {
        #[cfg(not(target_arch = "wasm32"))]
        self.bar.finish_and_clear();
    }
}
