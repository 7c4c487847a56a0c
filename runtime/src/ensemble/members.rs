//! [`Members`]: the raw observations of an ensemble's members, checked, written to and read from
//! CSV, and merged from shards.

use std::path::Path;

use crate::output::{number, write_table};
use crate::{Error, Result};

/// The observations of some or all members of an ensemble, in member order.
///
/// Plain data: what [`Ensemble::run`](super::Ensemble::run), [`Members::read_csv`] and
/// [`Members::merge`] return holds rows of one width in ascending member order below
/// `members`; [`Members::statistics`] and [`Members::write_csv`] check that again, for rows
/// edited since.
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
}

/// "1 observation", "2 observations".
fn observations(n: usize) -> String {
    format!("{n} observation{}", if n == 1 { "" } else { "s" })
}
