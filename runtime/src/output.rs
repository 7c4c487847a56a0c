//! Files: atomic writes and CSV. Nothing here touches the numerics.
//!
//! Every file is written to a temporary sibling and renamed into place, so a reader (or a crash)
//! never sees half a file, and a failed write leaves any older file untouched.

use std::fs;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use crate::{Error, Result, State, Trajectory};

/// Writes `bytes` to `path` atomically, creating missing parent directories.
///
/// Errors: [`Error::Io`] when the directory cannot be created or the file written or renamed
/// into place (a read-only target included); an older file at `path` is then left untouched.
pub fn write_atomic(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    let path = path.as_ref();
    with_temporary(path, |temp| {
        let write = || -> std::io::Result<()> {
            let mut file = fs::File::create(temp)?;
            file.write_all(bytes)?;
            file.sync_all()
        };
        write().map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        })
    })
}

/// Runs `write` on a fresh temporary path beside `path`, then renames the result onto `path`. On any failure —
/// an error or a panic inside `write` — the temporary is removed and an older file at `path` is
/// left untouched.
///
/// A symbolic link at `path` is followed: the file it points to is replaced, the link stays. A
/// read-only file at `path` is refused with [`Error::Io`] (`PermissionDenied`) rather than
/// silently replaced, which the rename alone would do.
fn with_temporary(path: &Path, write: impl FnOnce(&Path) -> Result<()>) -> Result<()> {
    static COUNTER: AtomicU64 = AtomicU64::new(0);
    let io = |source| Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let target = match fs::symlink_metadata(path) {
        Ok(meta) if meta.file_type().is_symlink() => fs::canonicalize(path).map_err(io)?,
        _ => path.to_path_buf(),
    };
    if let Ok(meta) = fs::metadata(&target)
        && meta.permissions().readonly()
    {
        return Err(io(std::io::Error::new(
            std::io::ErrorKind::PermissionDenied,
            "the file is read-only; odyn does not replace it",
        )));
    }
    let name = target.file_name().ok_or_else(|| {
        Error::invalid(
            "output path",
            format!("`{}` does not name a file", path.display()),
        )
    })?;
    let parent = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    fs::create_dir_all(parent).map_err(io)?;
    let unique = COUNTER.fetch_add(1, Ordering::Relaxed);
    let mut temp_name = std::ffi::OsString::from(".");
    temp_name.push(name);
    temp_name.push(format!(".{}.{unique}.tmp", std::process::id()));
    let temp = Temporary(parent.join(temp_name));
    write(&temp.0)?;
    fs::rename(&temp.0, &target).map_err(io)
}

/// A temporary file that is removed when dropped, also while a panic unwinds; once renamed into
/// place there is nothing left to remove (its name is unique to this process and call).
struct Temporary(PathBuf);

impl Drop for Temporary {
    fn drop(&mut self) {
        let _ = fs::remove_file(&self.0);
    }
}

/// Writes trajectories as one CSV table, atomically: `method,step,t,<components>[,energy]`,
/// one row per recorded sample, trajectories one after another.
///
/// The energy column is present when the first trajectory's model defines an energy. All
/// trajectories share the state type, so the component columns agree. Every number is printed
/// so that it reads back to the same bits.
///
/// Errors: [`Error::InvalidInput`] for an empty list or a trajectory without samples;
/// [`Error::Csv`] or [`Error::Io`] when the file cannot be written (see [`write_atomic`]).
pub fn write_csv<S: State>(path: impl AsRef<Path>, runs: &[&Trajectory<S>]) -> Result<()> {
    let path = path.as_ref();
    let first = runs
        .first()
        .ok_or_else(|| Error::invalid("trajectories", "nothing to write: the list is empty"))?;
    let sample = first.samples.first().ok_or_else(|| {
        Error::invalid(
            "trajectory",
            "has no samples to write (its `samples` were emptied)",
        )
    })?;
    let has_energy = sample.energy.is_some();
    let mut header = vec!["method".to_owned(), "step".to_owned(), "t".to_owned()];
    header.extend((0..sample.state.as_slice().len()).map(|i| sample.state.component_name(i)));
    if has_energy {
        header.push("energy".to_owned());
    }
    let mut rows = Vec::new();
    for run in runs {
        for s in &run.samples {
            let mut row = vec![
                run.method.name().to_owned(),
                s.step.to_string(),
                number(s.t),
            ];
            row.extend(s.state.as_slice().iter().copied().map(number));
            if has_energy {
                row.push(s.energy.map_or_else(String::new, number));
            }
            rows.push(row);
        }
    }
    write_table(path, &header, &rows)
}

/// Writes a CSV table with a header row, atomically.
///
/// Errors: [`Error::Csv`] when a row cannot be encoded, [`Error::Io`] when the file cannot be
/// written (see [`write_atomic`]).
pub fn write_table<H: AsRef<str>, C: AsRef<str>>(
    path: impl AsRef<Path>,
    header: &[H],
    rows: &[Vec<C>],
) -> Result<()> {
    let path = path.as_ref();
    let csv_error = |source| Error::Csv {
        path: path.to_path_buf(),
        source,
    };
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer
        .write_record(header.iter().map(AsRef::as_ref))
        .map_err(csv_error)?;
    for row in rows {
        writer
            .write_record(row.iter().map(AsRef::as_ref))
            .map_err(csv_error)?;
    }
    let bytes = writer
        .into_inner()
        .map_err(|e| csv_error(e.into_error().into()))?;
    write_atomic(path, &bytes)
}

/// `x` as CSV shows it: the shortest text that reads back to the same `f64`, in exponent form
/// when very large or small (`1e300`, not three hundred digits).
pub fn number(x: f64) -> String {
    format!("{x:?}")
}

// The trajectory's own writer lives with the writers: `output` reads trajectories, and a
// trajectory does not depend on how it is written.
impl<S: State> Trajectory<S> {
    /// Writes the samples as CSV (`method,step,t,<components>,energy`), atomically.
    ///
    /// Errors: [`Error::InvalidInput`] when `samples` is empty; [`Error::Io`] when the file
    /// cannot be written.
    pub fn write_csv(&self, path: impl AsRef<Path>) -> Result<()> {
        write_csv(path, &[self])
    }
}

#[cfg(test)]
mod tests {
    use super::with_temporary;

    /// A panic inside a writer unwinds through the temporary's guard, which removes the file.
    #[test]
    fn a_panic_while_writing_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("odyn-output-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("panic.bin");
        let result = std::panic::catch_unwind(|| {
            with_temporary(&path, |temp| {
                std::fs::write(temp, b"half").unwrap();
                panic!("the writer failed")
            })
        });
        assert!(result.is_err());
        let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
        assert!(left.is_empty(), "{left:?}");
    }
}
