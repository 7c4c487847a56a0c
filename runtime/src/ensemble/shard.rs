//! The sharding and the random streams: which members a shard takes, and each member's
//! generator, a function of (seed, member) only.

use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::{Error, Result};

/// The random generator each member gets: ChaCha8, a counter-based generator with 2⁶⁴ streams.
pub type MemberRng = ChaCha8Rng;

/// Member `member`'s generator: ChaCha8 seeded from `seed`, on stream `member`.
pub fn member_rng(seed: u64, member: u64) -> MemberRng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(member);
    rng
}

/// Which share of the members a run takes: shard `index` of `count` (0-based).
///
/// Plain data: [`Shard::range`] and [`Ensemble::run`](super::Ensemble::run) check that
/// `index < count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0 ≤ index < count`.
    pub index: u64,
    /// How many shards the members are split into.
    pub count: u64,
}

impl std::fmt::Display for Shard {
    /// `k/n`, as [`Shard::parse`] reads it.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

impl Shard {
    /// All members in one run.
    pub const WHOLE: Shard = Shard { index: 0, count: 1 };

    /// Parses `k/n` (as `--shard 3/10` gives it).
    ///
    /// Errors: [`Error::InvalidInput`] unless it is two integers with `0 ≤ k < n`.
    pub fn parse(text: &str) -> Result<Shard> {
        let bad = || {
            Error::invalid(
                "shard",
                format!("expected `k/n` with 0 ≤ k < n, got `{text}`"),
            )
        };
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let shard = Shard {
            index: k.trim().parse().map_err(|_| bad())?,
            count: n.trim().parse().map_err(|_| bad())?,
        };
        if shard.index >= shard.count {
            return Err(bad());
        }
        Ok(shard)
    }

    /// The members this shard runs, out of `members`: ⌊kM/n⌋ … ⌊(k+1)M/n⌋ − 1, a part of
    /// 0 … M − 1 (empty when there are more shards than members).
    ///
    /// Errors: [`Error::InvalidInput`] unless `index < count`: shard 5 of 2 would take members
    /// past the last (25 … 29 of 10), and a count of 0 has no shares.
    pub fn range(self, members: u64) -> Result<std::ops::Range<u64>> {
        if self.index >= self.count {
            return Err(Error::invalid(
                "shard",
                format!(
                    "{}/{} does not exist: shard k of n needs 0 ≤ k < n \
                     (`Shard {{ index: k, count: n }}`)",
                    self.index, self.count
                ),
            ));
        }
        // Below `members` for k ≤ n, so the conversion back is exact.
        let edge = |k: u64| (u128::from(k) * u128::from(members) / u128::from(self.count)) as u64;
        Ok(edge(self.index)..edge(self.index + 1))
    }
}
