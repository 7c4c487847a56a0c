//! [`Members`]: the raw observations of an ensemble's members, or of one shard of them, and the
//! checks that they are what a run returns.

use super::Shard;
use crate::{Error, Result};

/// The observations of the members of one shard of an ensemble (all of them for
/// [`Shard::WHOLE`]), in member order.
///
/// Plain data: what [`Ensemble::run`](super::Ensemble::run), [`Members::read_csv`] and
/// [`Members::merge`] return holds every member of `shard` (members
/// [`shard.range(members)`](Shard::range)), ascending, in rows of one width;
/// [`Members::statistics`], [`Members::write_csv`] and [`Members::merge`] check that again, for
/// rows edited since.
#[derive(Clone, Debug, PartialEq)]
pub struct Members {
    /// Members in the whole ensemble (over all shards).
    pub members: u64,
    /// The ensemble's base seed.
    pub seed: u64,
    /// The share of the ensemble these rows are ([`Shard::WHOLE`] for a run of every member,
    /// and for a merge).
    pub shard: Shard,
    /// (member index, its observations), ascending by index.
    pub rows: Vec<(u64, Vec<f64>)>,
}

impl Members {
    /// Whether every member of the ensemble is here.
    pub fn is_complete(&self) -> bool {
        self.rows.len() as u64 == self.members
    }

    /// Checks that the rows have one width and ascend by member index within the shard's
    /// members (which need not all be present).
    pub(super) fn check(&self) -> Result<()> {
        if let Some((first, rest)) = self.rows.split_first()
            && let Some((i, row)) = rest.iter().find(|(_, r)| r.len() != first.1.len())
        {
            return Err(Error::invalid(
                "members",
                format!(
                    "member {i} has {}, member {} has {}; every member must return as many \
                     observations",
                    observations(row.len()),
                    first.0,
                    observations(first.1.len())
                ),
            ));
        }
        let range = self.shard.range(self.members)?;
        let mut previous: Option<u64> = None;
        for &(i, _) in &self.rows {
            let reason = if i >= self.members {
                format!("member {i} is past the last of {} members", self.members)
            } else if !range.contains(&i) {
                format!(
                    "member {i} is not in shard {} (members {})",
                    self.shard,
                    span(&range)
                )
            } else if let Some(p) = previous.filter(|&p| p >= i) {
                format!("member {i} comes after member {p}")
            } else {
                previous = Some(i);
                continue;
            };
            return Err(Error::invalid(
                "members",
                format!(
                    "{reason}: rows must ascend by member index, each once, within their shard"
                ),
            ));
        }
        Ok(())
    }

    /// [`Members::check`], and that every member of the shard is here: a shard file holds its
    /// whole shard, so that a reader can tell one cut short.
    pub(super) fn check_whole_shard(&self) -> Result<()> {
        self.check()?;
        if self.members == 0 {
            return Err(Error::invalid(
                "members",
                "nothing to write: 0 members (an ensemble has at least one)",
            ));
        }
        let range = self.shard.range(self.members)?;
        if self.rows.len() as u64 != range.end - range.start {
            return Err(Error::invalid(
                "members",
                format!(
                    "{} of the {} members of shard {} (members {}) are here: a shard is written \
                     whole, so that a file cut short can be told from a complete one",
                    self.rows.len(),
                    range.end - range.start,
                    self.shard,
                    span(&range)
                ),
            ));
        }
        Ok(())
    }
}

/// "1 observation", "2 observations".
fn observations(n: usize) -> String {
    format!("{n} observation{}", if n == 1 { "" } else { "s" })
}

/// Members `a … b` (inclusive), or "none" for an empty range.
pub(super) fn span(range: &std::ops::Range<u64>) -> String {
    if range.is_empty() {
        "none".into()
    } else {
        format!("{} … {}", range.start, range.end - 1)
    }
}
