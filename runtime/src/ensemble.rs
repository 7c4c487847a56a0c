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
//! ([`Members::write_csv`], numbers printed so they read back to the same bits); [`Members::merge`]
//! reads them back, checks that together they are every member exactly once under one seed, and
//! gives a result bit-identical to a one-machine run. With a batch scheduler's job array (e.g.
//! Slurm's `sbatch --array=0-9`), each job runs `--shard $SLURM_ARRAY_TASK_ID/10` and a final job
//! merges the ten files; the `monte_carlo` example's `--shard` and `--merge` flags do exactly this.

use std::path::Path;

use indicatif::{ProgressBar, ProgressStyle};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use crate::error::{bytes_text, count_text};
use crate::output::{number, write_table};
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
/// Plain data: [`Shard::range`] and [`Ensemble::run`] check that `index < count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0 ≤ index < count`.
    pub index: u64,
    /// How many shards the members are split into.
    pub count: u64,
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

/// An ensemble's settings: plain data with a [`Default`].
#[derive(Clone, Debug, PartialEq)]
pub struct Ensemble {
    /// Members in the whole ensemble (over all shards).
    pub members: u64,
    /// The base seed every member's generator derives from.
    pub seed: u64,
    /// The share of the members this run takes ([`Shard::WHOLE`] by default).
    pub shard: Shard,
    /// Show a progress bar on standard error.
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
        let bar = if self.progress {
            let bar = ProgressBar::new(count);
            if let Ok(style) = ProgressStyle::with_template(
                "{msg} {bar:40} {pos}/{len} members, {elapsed} elapsed, ETA {eta}",
            ) {
                bar.set_style(style);
            }
            bar.set_message(format!("shard {}/{}", self.shard.index, self.shard.count));
            bar
        } else {
            ProgressBar::hidden()
        };
        // Into the slots reserved above (a range knows its length, so `par_extend` reserves
        // only what is missing: nothing).
        outputs.par_extend(range.clone().into_par_iter().map(|i| {
            let out = member(i, &mut member_rng(self.seed, i));
            bar.inc(1);
            out
        }));
        bar.finish_and_clear();
        for (i, out) in range.zip(outputs) {
            rows.push((i, out?));
        }
        let members = Members {
            members: self.members,
            seed: self.seed,
            rows,
        };
        members.check()?;
        Ok(members)
    }
}

/// The observations of some or all members of an ensemble, in member order.
///
/// Plain data: what [`Ensemble::run`], [`Members::read_csv`] and [`Members::merge`] return holds
/// rows of one width in ascending member order below `members`; [`Members::statistics`] and
/// [`Members::write_csv`] check that again, for rows edited since.
#[derive(Clone, Debug, PartialEq)]
pub struct Members {
    /// Members in the whole ensemble.
    pub members: u64,
    /// The ensemble's base seed.
    pub seed: u64,
    /// (member index, its observations), ascending by index.
    pub rows: Vec<(u64, Vec<f64>)>,
}

impl Members {
    /// Whether every member of the ensemble is here.
    pub fn is_complete(&self) -> bool {
        self.rows.len() as u64 == self.members
    }

    /// Checks that the rows have one width and ascend by member index below `members`.
    fn check(&self) -> Result<()> {
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
        let mut previous: Option<u64> = None;
        for &(i, _) in &self.rows {
            let reason = if i >= self.members {
                format!("member {i} is past the last of {} members", self.members)
            } else if let Some(p) = previous.filter(|&p| p >= i) {
                format!("member {i} comes after member {p}")
            } else {
                previous = Some(i);
                continue;
            };
            return Err(Error::invalid(
                "members",
                format!("{reason}: rows must ascend by member index, each once, below `members`"),
            ));
        }
        Ok(())
    }

    /// Writes the rows atomically as CSV: `member,members,seed,y0,y1,…`, every number printed so
    /// it reads back to the same bits.
    ///
    /// Errors: [`Error::InvalidInput`] for rows of different widths or out of member order
    /// (nothing is written); [`Error::Io`] when the file cannot be written.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        self.check()?;
        let width = self.rows.first().map_or(0, |(_, r)| r.len());
        let mut header = vec!["member".to_string(), "members".into(), "seed".into()];
        header.extend((0..width).map(|k| format!("y{k}")));
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|(i, values)| {
                let mut row = vec![
                    i.to_string(),
                    self.members.to_string(),
                    self.seed.to_string(),
                ];
                row.extend(values.iter().map(|&v| number(v)));
                row
            })
            .collect();
        write_table(path, &header, &rows)
    }

    /// Reads what [`Members::write_csv`] wrote.
    ///
    /// Errors: [`Error::Read`] when the file is missing or cannot be read;
    /// [`Error::InvalidInput`] naming the row (and column) when it is not what `write_csv`
    /// writes: empty, cut short in a row (truncated), a header other than
    /// `member,members,seed,y0,…`, a row of another length, text where a number belongs, or rows
    /// out of member order.
    pub fn read_csv(path: impl AsRef<Path>) -> Result<Members> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|source| Error::Read {
            path: path.to_path_buf(),
            source,
        })?;
        let bad =
            |reason: String| Error::invalid(format!("shard file `{}`", path.display()), reason);
        if bytes.is_empty() {
            return Err(bad(
                "it is empty: the file is truncated; copy it again from where its shard wrote it, \
                 or run that shard again"
                    .into(),
            ));
        }
        // Every row `write_csv` writes ends in a newline: a file that does not was cut short.
        if bytes.last().is_some_and(|&b| b != b'\n') {
            let row = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
            return Err(bad(format!(
                "it ends in the middle of row {row}: the file is truncated; copy it again from \
                 where its shard wrote it, or run that shard again"
            )));
        }
        // Lengths are checked below, to say which row is short.
        let mut reader = csv::ReaderBuilder::new()
            .flexible(true)
            .from_reader(bytes.as_slice());
        let header = reader
            .headers()
            .map_err(|e| bad(format!("row 1: {e}")))?
            .clone();
        if header.iter().take(3).ne(["member", "members", "seed"]) {
            return Err(bad(format!(
                "its header is `{}`, not `member,members,seed,y0,…`: it is not a shard file \
                 written by `Members::write_csv`",
                header.iter().collect::<Vec<_>>().join(",")
            )));
        }
        let mut members = Members {
            members: 0,
            seed: 0,
            rows: Vec::new(),
        };
        for (line, record) in reader.records().enumerate() {
            let row = line + 2;
            let record = record.map_err(|e| bad(format!("row {row}: {e}")))?;
            if record.len() != header.len() {
                return Err(bad(format!(
                    "row {row} has {} fields but the header {}: the file is truncated or was \
                     changed; run its shard again",
                    record.len(),
                    header.len()
                )));
            }
            let not = |k: usize, what: &str| {
                bad(format!(
                    "row {row}, column `{}`: `{}` is not {what}; the file was changed since \
                     `Members::write_csv` wrote it: run its shard again",
                    &header[k], &record[k]
                ))
            };
            let int = |k: usize| {
                record[k]
                    .parse::<u64>()
                    .map_err(|_| not(k, "a whole number"))
            };
            let (i, total, seed) = (int(0)?, int(1)?, int(2)?);
            let values = (3..record.len())
                .map(|k| record[k].parse::<f64>().map_err(|_| not(k, "a number")))
                .collect::<Result<Vec<f64>>>()?;
            if line == 0 {
                (members.members, members.seed) = (total, seed);
            } else if (total, seed) != (members.members, members.seed) {
                return Err(bad(format!(
                    "row {row} is of {total} members with seed {seed}, row 2 of {} with seed {}: \
                     one file holds one shard of one ensemble",
                    members.members, members.seed
                )));
            }
            let last = members.rows.last().map(|(last, _)| *last);
            if last.is_some_and(|last| last >= i) || i >= total {
                return Err(bad(format!(
                    "row {row} is member {i}{}: members must ascend, each below `members` \
                     ({total})",
                    last.map_or(String::new(), |last| format!(" after member {last}"))
                )));
            }
            members.rows.push((i, values));
        }
        if members.rows.is_empty() {
            return Err(bad(
                "it has no rows, and every shard has at least one member: the file is truncated; \
                 copy it again, or run its shard again"
                    .into(),
            ));
        }
        members.check()?;
        Ok(members)
    }

    /// Combines shards into one result, bit-identical to a run of all members at once.
    ///
    /// Errors: [`Error::InvalidInput`] when a part is empty (0 members, as an empty `Members` has),
    /// the parts disagree on the member count or seed, or they do not hold every member exactly
    /// once.
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
        let (total, seed) = (first.members, first.seed);
        if let Some(other) = parts.iter().find(|p| (p.members, p.seed) != (total, seed)) {
            return Err(Error::invalid(
                "shards",
                format!(
                    "shards of different ensembles: {total} members with seed {seed} and {} \
                     members with seed {}",
                    other.members, other.seed
                ),
            ));
        }
        let mut rows: Vec<(u64, Vec<f64>)> = parts.into_iter().flat_map(|p| p.rows).collect();
        rows.sort_by_key(|(i, _)| *i);
        if let Some(pair) = rows.windows(2).find(|w| w[0].0 == w[1].0) {
            return Err(Error::invalid(
                "shards",
                format!("member {} appears twice", pair[0].0),
            ));
        }
        if rows.len() as u64 != total {
            let missing = (0..total)
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
                    "{} of {total} members present; member {missing} is missing",
                    rows.len()
                ),
            ));
        }
        let merged = Members {
            members: total,
            seed,
            rows,
        };
        merged.check()?;
        Ok(merged)
    }

    /// Mean, sample variance and sorted values of each observation over the members.
    ///
    /// Errors: [`Error::InvalidInput`] unless every member is present, once, in order, with as
    /// many observations as the others.
    pub fn statistics(&self) -> Result<Statistics> {
        self.check()?;
        if !self.is_complete() {
            return Err(Error::invalid(
                "members",
                format!(
                    "statistics need every member: {} of {} present (merge the shards first)",
                    self.rows.len(),
                    self.members
                ),
            ));
        }
        let width = self.rows.first().map_or(0, |(_, r)| r.len());
        let n = self.rows.len() as f64;
        let column = |k: usize| self.rows.iter().map(move |(_, r)| r[k]);
        let mean: Vec<f64> = (0..width).map(|k| column(k).sum::<f64>() / n).collect();
        let variance = (0..width)
            .map(|k| {
                if self.rows.len() < 2 {
                    return 0.0;
                }
                column(k)
                    .map(|v| (v - mean[k]) * (v - mean[k]))
                    .sum::<f64>()
                    / (n - 1.0)
            })
            .collect();
        let sorted = (0..width)
            .map(|k| {
                let mut values: Vec<f64> = column(k).collect();
                values.sort_by(f64::total_cmp);
                values
            })
            .collect();
        Ok(Statistics {
            mean,
            variance,
            sorted,
        })
    }
}

/// Reductions over the members, one entry per observation.
#[derive(Clone, Debug, PartialEq)]
pub struct Statistics {
    /// Mean, summed in member order.
    pub mean: Vec<f64>,
    /// Sample variance Σ(v − mean)²/(M − 1) (0 for one member).
    pub variance: Vec<f64>,
    /// Each observation's values over the members, ascending (NaN last).
    pub sorted: Vec<Vec<f64>>,
}

impl Statistics {
    /// The `q`-quantile of observation `k`, interpolated linearly between order statistics
    /// (Hyndman & Fan 1996, definition 7, NumPy's and R's default): position (M − 1)·q.
    ///
    /// NaN when any member's value is NaN (NumPy's rule), as the mean is.
    ///
    /// Errors: [`Error::InvalidInput`] for `q` outside [0, 1] or `k` out of range.
    pub fn quantile(&self, k: usize, q: f64) -> Result<f64> {
        let values = self.sorted.get(k).ok_or_else(|| {
            Error::invalid("observation", format!("{k} of {}", self.sorted.len()))
        })?;
        if !(0.0..=1.0).contains(&q) {
            return Err(Error::invalid(
                "quantile",
                format!("must be in [0, 1], got {q:?}"),
            ));
        }
        // NumPy's rule: a NaN among the values makes every quantile NaN, as it does the mean
        // (`total_cmp` sorts NaNs to the ends, where they would shift the others silently).
        if values.first().is_some_and(|v| v.is_nan()) || values.last().is_some_and(|v| v.is_nan()) {
            return Ok(f64::NAN);
        }
        let position = q * (values.len() - 1) as f64;
        let (lo, frac) = (position.floor() as usize, position.fract());
        let hi = (lo + 1).min(values.len() - 1);
        Ok(values[lo] + frac * (values[hi] - values[lo]))
    }
}

/// "1 observation", "2 observations".
fn observations(n: usize) -> String {
    format!("{n} observation{}", if n == 1 { "" } else { "s" })
}
