//! Shard files: [`Members::write_csv`] and [`Members::read_csv`], CSV that reads back to the
//! same bits and tells a complete shard from one cut short or written twice.

use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

use super::members::span;
use super::{Members, Shard};
use crate::output::{number, write_table};
use crate::{Error, Result};

/// The columns before the observations.
const HEADER: [&str; 5] = ["member", "members", "seed", "shard", "shards"];

impl Members {
    /// Writes the rows atomically as CSV: `member,members,seed,shard,shards,y0,y1,…`, every
    /// number printed so it reads back to the same bits. The file appears whole or not at all
    /// (a temporary sibling, hidden by a leading `.`, renamed into place): a task killed while
    /// writing leaves no file that [`Members::read_csv`] or a `shard-*.csv` pattern would take
    /// for its shard.
    ///
    /// Errors: [`Error::InvalidInput`] for rows of different widths, out of member order or
    /// not every member of `shard` (a shard is written whole, so that a reader can tell a file
    /// cut short), or 0 members; nothing is written then. [`Error::Io`] when the file cannot be
    /// written.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        self.check_whole_shard()?;
        let width = self.rows.first().map_or(0, |(_, r)| r.len());
        let mut header: Vec<String> = HEADER.iter().map(|h| h.to_string()).collect();
        header.extend((0..width).map(|k| format!("y{k}")));
        let ensemble = [
            self.members.to_string(),
            self.seed.to_string(),
            self.shard.index.to_string(),
            self.shard.count.to_string(),
        ];
        let rows: Vec<Vec<String>> = self
            .rows
            .iter()
            .map(|(i, values)| {
                let mut row = Vec::with_capacity(HEADER.len() + values.len());
                row.push(i.to_string());
                row.extend(ensemble.iter().cloned());
                row.extend(values.iter().map(|&v| number(v)));
                row
            })
            .collect();
        write_table(path, &header, &rows)
    }

    /// Reads what [`Members::write_csv`] wrote: every member of one shard.
    ///
    /// Errors: [`Error::Read`] when the file is missing or cannot be read;
    /// [`Error::InvalidInput`] naming the file, and the row (and column) where it can, when it
    /// is not what `write_csv` writes: empty, cut short (in a row, or after one: fewer members
    /// than its shard has), written twice (its header again part-way), a header other than
    /// `member,members,seed,shard,shards,y0,…`, a row of another length, text where a number
    /// belongs, rows of another ensemble or shard than the first row's, or rows out of member
    /// order.
    pub fn read_csv(path: impl AsRef<Path>) -> Result<Members> {
        let path = path.as_ref();
        let unread = |source| Error::Read {
            path: path.to_path_buf(),
            source,
        };
        let bad =
            |reason: String| Error::invalid(format!("shard file `{}`", path.display()), reason);
        let again = "copy it again from where its shard wrote it, or run that shard again";
        // Read as a stream: a shard's text is 2.4 times its numbers in memory.
        let mut file = std::fs::File::open(path).map_err(unread)?;
        let length = file.metadata().map_err(unread)?.len();
        if length == 0 {
            return Err(bad(format!("it is empty: the file is truncated; {again}")));
        }
        // Every row `write_csv` writes ends in a newline: a file that does not was cut short.
        let mut last = [0u8];
        file.seek(SeekFrom::End(-1))
            .and_then(|_| file.read_exact(&mut last))
            .and_then(|_| file.rewind())
            .map_err(unread)?;
        if last[0] != b'\n' {
            let bytes = std::fs::read(path).map_err(unread)?;
            let row = bytes.iter().filter(|&&b| b == b'\n').count() + 1;
            return Err(bad(format!(
                "it ends in the middle of row {row}: the file is truncated; {again}"
            )));
        }
        // Lengths are checked below, to say which row is short.
        let mut reader = csv::ReaderBuilder::new()
            .flexible(true)
            .buffer_capacity(1 << 16)
            .from_reader(file);
        let header = reader
            .byte_headers()
            .map_err(|e| bad(format!("row 1: {e}")))?
            .clone();
        if header
            .iter()
            .take(HEADER.len())
            .ne(HEADER.map(str::as_bytes))
        {
            return Err(bad(format!(
                "its header is `{}`, not `{},y0,…`: it is not a shard file written by \
                 `Members::write_csv`",
                String::from_utf8_lossy(header.as_slice()),
                HEADER.join(",")
            )));
        }
        let column = |k: usize| String::from_utf8_lossy(&header[k]).into_owned();
        let mut first: Option<[u64; 4]> = None;
        let mut rows: Vec<(u64, Vec<f64>)> = Vec::new();
        let mut record = csv::ByteRecord::new();
        for row in 2.. {
            match reader.read_byte_record(&mut record) {
                Ok(true) => {}
                Ok(false) => break,
                Err(e) => return Err(bad(format!("row {row}: {e}"))),
            }
            if record == header {
                return Err(bad(format!(
                    "row {row} repeats the header: the file was written twice, one copy after \
                     the other (`write_csv` replaces a file, it never appends); {again}"
                )));
            }
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
                    column(k),
                    String::from_utf8_lossy(&record[k])
                ))
            };
            let text = |k: usize| std::str::from_utf8(&record[k]).ok();
            let int = |k: usize| {
                text(k)
                    .and_then(|t| t.parse::<u64>().ok())
                    .ok_or_else(|| not(k, "a whole number"))
            };
            let i = int(0)?;
            let ensemble = [int(1)?, int(2)?, int(3)?, int(4)?];
            let values = (HEADER.len()..record.len())
                .map(|k| {
                    text(k)
                        .and_then(|t| t.parse::<f64>().ok())
                        .ok_or_else(|| not(k, "a number"))
                })
                .collect::<Result<Vec<f64>>>()?;
            let [members, seed, index, count] = *first.get_or_insert(ensemble);
            if ensemble != [members, seed, index, count] {
                let [m, s, k, n] = ensemble;
                return Err(bad(format!(
                    "row {row} is of shard {k}/{n} of {m} members with seed {s}, row 2 of shard \
                     {index}/{count} of {members} with seed {seed}: one file holds one shard of \
                     one ensemble"
                )));
            }
            let shard = Shard { index, count };
            let range = shard
                .range(members)
                .map_err(|e| bad(format!("row {row}: {e}")))?;
            let last = rows.last().map(|(last, _)| *last);
            if last.is_some_and(|last| last >= i) || !range.contains(&i) {
                return Err(bad(format!(
                    "row {row} is member {i}{}: members must ascend, each within shard {shard} \
                     (members {})",
                    last.map_or(String::new(), |last| format!(" after member {last}")),
                    span(&range)
                )));
            }
            rows.push((i, values));
        }
        let Some([members, seed, index, count]) = first else {
            return Err(bad(format!(
                "it has no rows, and every shard has at least one member: the file is \
                 truncated; {again}"
            )));
        };
        let shard = Shard { index, count };
        let range = shard.range(members)?;
        let expected = range.end - range.start;
        if rows.len() as u64 != expected {
            return Err(bad(format!(
                "it holds {} of the {expected} members of shard {shard} (members {}), ending \
                 after member {}: the file is truncated; {again}",
                rows.len(),
                span(&range),
                rows.last().map_or(0, |(i, _)| *i)
            )));
        }
        let members = Members {
            members,
            seed,
            shard,
            rows,
        };
        members.check()?;
        Ok(members)
    }
}
