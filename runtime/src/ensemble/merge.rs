//! [`Members::merge`]: shards back into the whole ensemble, bit-identical to one run of all its
//! members, or an error naming the shards that are missing or given twice.

use std::collections::BTreeMap;
use std::ops::Range;
use std::path::Path;

use rayon::prelude::*;

use super::members::span;
use super::{Members, Shard};
use crate::{Error, Result};

impl Members {
    /// Combines every shard of one ensemble into the whole of it, bit-identical to a run of all
    /// members at once. The parts may come in any order.
    ///
    /// Errors: [`Error::BadShards`] naming each shard k/n that is missing (its task failed, or
    /// its file was not gathered) or given more than once: a merge of what is there would be a
    /// silently smaller ensemble. [`Error::InvalidInput`] for no parts, an empty part (0
    /// members, as an empty `Members` has), parts of different ensembles (member count or seed)
    /// or of different splits (shards k/n of different n), or a part whose rows are not the
    /// members of its shard, ascending, of one width.
    pub fn merge(parts: Vec<Members>) -> Result<Members> {
        let Some(first) = parts.first() else {
            return Err(Error::invalid("shards", "nothing to merge"));
        };
        if let Some(k) = parts.iter().position(|p| p.members == 0) {
            return Err(Error::invalid(
                "shards",
                format!(
                    "part {} of {} is empty (0 members), as a `Members` built by hand with \
                     nothing in it is: no run or shard file gives one; leave it out, or merge \
                     the file its shard wrote",
                    k + 1,
                    parts.len()
                ),
            ));
        }
        let (members, seed, count) = (first.members, first.seed, first.shard.count);
        if let Some(other) = parts
            .iter()
            .find(|p| (p.members, p.seed) != (members, seed))
        {
            return Err(Error::invalid(
                "shards",
                format!(
                    "shards of different ensembles: {members} members with seed {seed} and {} \
                     members with seed {}",
                    other.members, other.seed
                ),
            ));
        }
        if let Some(other) = parts.iter().find(|p| p.shard.count != count) {
            return Err(Error::invalid(
                "shards",
                format!(
                    "shards of different splits: {} and {}; merge the shards of one split \
                     (one shard count n)",
                    first.shard, other.shard
                ),
            ));
        }
        for part in &parts {
            part.check()?;
        }
        // By index, so that a split into more shards than are given costs only what is given.
        let mut seen = BTreeMap::<u64, u32>::new();
        for part in &parts {
            *seen.entry(part.shard.index).or_default() += 1;
        }
        let twice: Vec<u64> = seen
            .iter()
            .filter(|&(_, &n)| n > 1)
            .map(|(&k, _)| k)
            .collect();
        let missing = missing_ranges(&seen, count);
        if !missing.is_empty() || !twice.is_empty() {
            return Err(Error::BadShards {
                message: bad_shards_text(members, count, &missing, &twice),
                members,
                count,
                missing,
                twice,
            });
        }
        let mut parts = parts;
        parts.sort_by_key(|p| p.shard.index);
        // Each part's rows ascend within its shard, and the shards follow one another: in shard
        // order the rows are in member order, no sort needed.
        let rows: Vec<(u64, Vec<f64>)> = parts.into_iter().flat_map(|p| p.rows).collect();
        if rows.len() as u64 != members {
            let missing = (0..members)
                .zip(
                    rows.iter()
                        .map(|(i, _)| *i)
                        .chain(std::iter::repeat(u64::MAX)),
                )
                .find(|(want, have)| want != have)
                .map_or(0, |(want, _)| want);
            return Err(Error::invalid(
                "shards",
                format!(
                    "{} of {members} members present; member {missing} is missing (every \
                     shard is here, but one was edited since its run: run it again)",
                    rows.len()
                ),
            ));
        }
        let merged = Members {
            members,
            seed,
            shard: Shard::WHOLE,
            rows,
        };
        merged.check()?;
        Ok(merged)
    }

    /// Reads shard files ([`Members::read_csv`], several at once on rayon's pool) and merges
    /// them ([`Members::merge`]).
    ///
    /// Errors: the first unreadable file's error, in the order given; then those of
    /// [`Members::merge`].
    pub fn merge_files<P: AsRef<Path> + Sync>(paths: &[P]) -> Result<Members> {
        let parts = paths
            .par_iter()
            .map(Members::read_csv)
            .collect::<Result<Vec<Members>>>()?;
        Members::merge(parts)
    }
}

/// The indices below `count` that `seen` lacks, as ascending ranges: at most one more than
/// the shards given, however many shards the split has.
fn missing_ranges(seen: &BTreeMap<u64, u32>, count: u64) -> Vec<Range<u64>> {
    let mut missing = Vec::new();
    let mut next = 0;
    for &k in seen.keys().chain(std::iter::once(&count)) {
        if next < k {
            missing.push(next..k);
        }
        next = k.saturating_add(1);
    }
    missing
}

/// The message of [`Error::BadShards`]: the shards missing (with their members) and given more
/// than once, the first few of each by name.
fn bad_shards_text(members: u64, count: u64, missing: &[Range<u64>], twice: &[u64]) -> String {
    const SHOWN: usize = 5;
    let shard = |index| Shard { index, count };
    let members_of =
        |first: u64, last: u64| match (shard(first).range(members), shard(last).range(members)) {
            (Ok(a), Ok(b)) => format!(" (members {})", span(&(a.start..b.end))),
            _ => String::new(),
        };
    let mut text = Vec::new();
    let how_many: u64 = missing.iter().map(|r| r.end - r.start).sum();
    if how_many > 0 {
        let mut named: Vec<String> = missing
            .iter()
            .take(SHOWN)
            .map(|r| {
                let (first, last) = (r.start, r.end - 1);
                let which = if first == last {
                    shard(first).to_string()
                } else {
                    format!("{} … {}", shard(first), shard(last))
                };
                which + &members_of(first, last)
            })
            .collect();
        if missing.len() > SHOWN {
            named.push("…".into());
        }
        let one = how_many == 1;
        text.push(format!(
            "{} {} {} missing, {how_many} of the {count} shards of {members} members; {} \
             failed or {} not gathered: run {} again (Slurm: `sbatch --array=<k>`) and merge \
             every shard",
            if one { "shard" } else { "shards" },
            named.join(", "),
            if one { "is" } else { "are" },
            if one { "its task" } else { "their tasks" },
            if one {
                "its file was"
            } else {
                "their files were"
            },
            if one { "it" } else { "them" },
        ));
    }
    if !twice.is_empty() {
        let mut named: Vec<String> = twice
            .iter()
            .take(SHOWN)
            .map(|&k| shard(k).to_string() + &members_of(k, k))
            .collect();
        if twice.len() > SHOWN {
            named.push(format!("… ({} in all)", twice.len()));
        }
        text.push(format!(
            "{} given more than once: {}; give each shard's file once",
            if twice.len() == 1 {
                "a shard is"
            } else {
                "shards are"
            },
            named.join(", ")
        ));
    }
    format!("cannot merge: {}; nothing was merged", text.join("; "))
}
