//! Shard files as a scheduler leaves them: cut short, written twice, missing or given twice,
//! each refused with an error naming the file or the shard; a shard run again restores the
//! merge bit for bit.

use odyn::Error;
use odyn::ensemble::{Members, Shard};

use super::ensemble::{pi_ensemble, scratch};

/// Shard `index` of `count` of the 23-member π ensemble, written to `dir`.
fn shard_file(dir: &std::path::Path, index: u64, count: u64) -> std::path::PathBuf {
    let path = dir.join(format!("shard-{index}-of-{count}.csv"));
    pi_ensemble(23, Shard { index, count })
        .write_csv(&path)
        .unwrap();
    path
}

/// A task killed while its file was copied, cut right after a row, used to read as a smaller
/// shard and merge into "member 12 is missing"; the file now says it is truncated, which shard
/// it is short of, and where it ends.
#[test]
fn a_shard_file_cut_after_a_row_is_truncated() {
    let dir = scratch("cut");
    let path = shard_file(&dir, 1, 2); // members ⌊23/2⌋ … 22 = 11 … 22
    let text = std::fs::read_to_string(&path).unwrap();
    let rows: Vec<&str> = text.lines().collect();
    std::fs::write(&path, rows[..3].join("\n") + "\n").unwrap(); // header, members 11 and 12
    let error = Members::read_csv(&path).unwrap_err();
    assert!(
        matches!(&error, Error::InvalidInput { field, .. } if field.contains("shard-1-of-2.csv"))
            && error.to_string().contains(
                "holds 2 of the 12 members of shard 1/2 (members 11 … 22), ending after \
                 member 12: the file is truncated"
            ),
        "{error}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A file written twice, one copy after the other (a task run twice appending to one file),
/// said only that `member` in row 14 is not a whole number.
#[test]
fn a_shard_file_written_twice_is_refused() {
    let dir = scratch("twice");
    let path = shard_file(&dir, 0, 2); // members 0 … 10: rows 2 … 12, the header again in 13
    let text = std::fs::read_to_string(&path).unwrap();
    std::fs::write(&path, text.repeat(2)).unwrap();
    let error = Members::read_csv(&path).unwrap_err().to_string();
    assert!(
        error.contains("row 13 repeats the header: the file was written twice"),
        "{error}"
    );
    // The same file given twice to a merge names the shard.
    let other = shard_file(&dir, 1, 2);
    let first = shard_file(&dir, 0, 2);
    let error = Members::merge_files(&[&first, &other, &first]).unwrap_err();
    assert!(
        matches!(&error, Error::BadShards { twice, .. } if *twice == [0]),
        "{error}"
    );
    // Shards of two splits of one ensemble do not merge, even where they would cover it.
    let error = Members::merge(vec![
        pi_ensemble(23, Shard { index: 0, count: 2 }),
        pi_ensemble(23, Shard { index: 1, count: 2 }),
        pi_ensemble(23, Shard { index: 2, count: 3 }),
    ])
    .unwrap_err()
    .to_string();
    assert!(
        error.contains("shards of different splits: 0/2 and 2/3"),
        "{error}"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Files merged from disk, in any order, give the one-process run bit for bit; with one shard's
/// file gone (its task cancelled) the merge names that shard and merges nothing; written again,
/// the merge is bit-identical. The writer leaves nothing beside the shard files (its temporary
/// is renamed into place).
#[test]
fn a_missing_shard_file_is_named_and_its_rerun_restores_the_merge() {
    let dir = scratch("rerun");
    let whole = pi_ensemble(23, Shard::WHOLE);
    let paths: Vec<_> = (0..5).rev().map(|k| shard_file(&dir, k, 5)).collect();
    assert_eq!(Members::merge_files(&paths).unwrap(), whole);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .collect();
    names.sort();
    assert_eq!(
        names,
        (0..5)
            .map(|k| format!("shard-{k}-of-5.csv"))
            .collect::<Vec<_>>()
    );

    std::fs::remove_file(&paths[1]).unwrap(); // shard 3/5: members ⌊69/5⌋ … ⌊92/5⌋ − 1 = 13 … 17
    let present: Vec<_> = paths.iter().filter(|p| p.exists()).collect();
    let error = Members::merge_files(&present).unwrap_err();
    assert!(
        matches!(&error, Error::BadShards { missing, .. } if missing.first() == Some(&(3..4)) && missing.len() == 1)
            && error
                .to_string()
                .contains("shard 3/5 (members 13 … 17) is missing, 1 of the 5"),
        "{error}"
    );
    shard_file(&dir, 3, 5);
    assert_eq!(Members::merge_files(&paths).unwrap(), whole);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Many shards missing are named by runs, the first few only: the message stays short for a
/// split into 10⁶ shards, and so does the error (ranges, not a list of every index).
#[test]
fn many_missing_shards_are_named_in_ranges() {
    let count = 1_000_000;
    let part = |index| Members {
        members: count,
        seed: 0,
        shard: Shard { index, count },
        rows: vec![(index, vec![0.0])],
    };
    let parts = [0, 7, 8, 20, 30, 40, 50].map(part).to_vec();
    let error = Members::merge(parts).unwrap_err();
    let Error::BadShards { missing, .. } = &error else {
        panic!("{error}");
    };
    assert_eq!(missing[..3], [1..7, 9..20, 21..30]);
    assert_eq!(missing.len(), 6); // … 41..50 and 51..10⁶
    let text = error.to_string();
    assert!(
        text.contains("shards 1/1000000 … 6/1000000 (members 1 … 6), 9/1000000")
            && text.contains("are missing, 999993 of the 1000000 shards")
            && text.len() < 600,
        "{text}"
    );
}

/// A `Members` whose rows are not its shard's is refused, and is never written as a shard file:
/// a file always holds its whole shard.
#[test]
fn rows_outside_their_shard_are_refused() {
    let mut part = pi_ensemble(23, Shard { index: 1, count: 2 });
    part.shard = Shard { index: 0, count: 2 };
    let error = part.statistics().unwrap_err().to_string();
    assert!(
        error.contains("member 11 is not in shard 0/2 (members 0 … 10)"),
        "{error}"
    );
    let mut short = pi_ensemble(23, Shard { index: 1, count: 2 });
    short.rows.pop();
    let path = scratch("short").join("short.csv");
    let error = short.write_csv(&path).unwrap_err().to_string();
    assert!(
        error.contains("11 of the 12 members of shard 1/2 (members 11 … 22) are here"),
        "{error}"
    );
    assert!(!path.exists());
}
