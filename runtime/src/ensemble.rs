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
//! `⌊kM/n⌋ … ⌊(k+1)M/n⌋ − 1`. Each shard writes its members' raw observations
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

    /// The members this shard runs, out of `members`.
    pub fn range(self, members: u64) -> std::ops::Range<u64> {
        let edge = |k: u64| (u128::from(k) * u128::from(members) / u128::from(self.count)) as u64;
        edge(self.index)..edge(self.index + 1)
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
    /// Errors: [`Error::InvalidInput`] for no members, a shard count of 0 or above the member
    /// count, or members that return different numbers of observations; otherwise the error of
    /// the lowest-numbered member that failed (the same one whatever the threads did).
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
        if self.shard.count == 0
            || self.shard.count > self.members
            || self.shard.index >= self.shard.count
        {
            return Err(Error::invalid(
                "shard",
                format!(
                    "shard {}/{} of {} members: need 0 ≤ k < n ≤ members",
                    self.shard.index, self.shard.count, self.members
                ),
            ));
        }
        let range = self.shard.range(self.members);
        let bar = if self.progress {
            let bar = ProgressBar::new(range.end - range.start);
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
        let outputs: Vec<Result<Vec<f64>>> = range
            .clone()
            .into_par_iter()
            .map(|i| {
                let out = member(i, &mut member_rng(self.seed, i));
                bar.inc(1);
                out
            })
            .collect();
        bar.finish_and_clear();
        let mut rows = Vec::with_capacity(outputs.len());
        for (i, out) in range.zip(outputs) {
            rows.push((i, out?));
        }
        let members = Members {
            members: self.members,
            seed: self.seed,
            rows,
        };
        members.check_widths()?;
        Ok(members)
    }
}

/// The observations of some or all members of an ensemble, in member order.
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

    fn check_widths(&self) -> Result<()> {
        if let Some((first, rest)) = self.rows.split_first()
            && let Some((i, row)) = rest.iter().find(|(_, r)| r.len() != first.1.len())
        {
            return Err(Error::invalid(
                "members",
                format!(
                    "member {i} returned {} observations, member {} returned {}",
                    row.len(),
                    first.0,
                    first.1.len()
                ),
            ));
        }
        Ok(())
    }

    /// Writes the rows atomically as CSV: `member,members,seed,y0,y1,…`, every number printed so
    /// it reads back to the same bits.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
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
    /// Errors: [`Error::Io`] or [`Error::Csv`] when the file cannot be read; [`Error::InvalidInput`]
    /// for a row that is not `member,members,seed,values…` or rows out of member order.
    pub fn read_csv(path: impl AsRef<Path>) -> Result<Members> {
        let path = path.as_ref();
        let bytes = std::fs::read(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })?;
        let mut reader = csv::Reader::from_reader(bytes.as_slice());
        let field = |what: &str| format!("{} ({what})", path.display());
        let mut members = Members {
            members: 0,
            seed: 0,
            rows: Vec::new(),
        };
        for (line, record) in reader.records().enumerate() {
            let record = record.map_err(|source| Error::Csv {
                path: path.to_path_buf(),
                source,
            })?;
            let bad = |what: &str| Error::invalid(field(what), format!("row {}", line + 2));
            let int = |k: usize| -> Result<u64> {
                record
                    .get(k)
                    .and_then(|s| s.parse().ok())
                    .ok_or_else(|| bad("an integer column"))
            };
            let (i, total, seed) = (int(0)?, int(1)?, int(2)?);
            let values = (3..record.len())
                .map(|k| record[k].parse::<f64>().map_err(|_| bad("a number")))
                .collect::<Result<Vec<f64>>>()?;
            if line == 0 {
                (members.members, members.seed) = (total, seed);
            } else if (total, seed) != (members.members, members.seed) {
                return Err(bad("members and seed must be the same on every row"));
            }
            if members.rows.last().is_some_and(|(last, _)| *last >= i) || i >= total {
                return Err(bad("member indices must ascend and stay below `members`"));
            }
            members.rows.push((i, values));
        }
        members.check_widths()?;
        Ok(members)
    }

    /// Combines shards into one result, bit-identical to a run of all members at once.
    ///
    /// Errors: [`Error::InvalidInput`] when the parts disagree on the member count or seed, or do
    /// not hold every member exactly once.
    pub fn merge(parts: Vec<Members>) -> Result<Members> {
        let Some(first) = parts.first() else {
            return Err(Error::invalid("shards", "nothing to merge"));
        };
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
        merged.check_widths()?;
        Ok(merged)
    }

    /// Mean, sample variance and sorted values of each observation over the members.
    ///
    /// Errors: [`Error::InvalidInput`] unless every member is present.
    pub fn statistics(&self) -> Result<Statistics> {
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
                format!("must be in [0, 1], got {q}"),
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
