//! The symmetric pattern of a matrix from its entries, in compressed columns.

use faer::sparse::SymbolicSparseColMat;

/// The pattern of `entries` (row, column), their transposes and the diagonal of an n × n
/// matrix, as compressed columns with sorted, distinct rows.
///
/// A counting sort by column, then each column's few rows sorted and deduplicated in place:
/// linear in the entries. faer's general `try_new_from_indices` sorts all of them (and returns
/// a map of their order no caller here needs), which was half the set-up of a run on a 256²
/// grid — longer than a step.
///
/// The caller guarantees every index is below `n`.
pub(super) fn symmetric(n: usize, entries: &[(usize, usize)]) -> SymbolicSparseColMat<usize> {
    let mut start = vec![0usize; n + 1];
    for &(row, column) in entries {
        start[column + 1] += 1;
        start[row + 1] += 1;
    }
    for column in 0..n {
        start[column + 1] += start[column] + 1; // + 1: the diagonal
    }
    let mut rows = vec![0usize; start[n]];
    let mut next = start[..n].to_vec();
    let mut push = |column: usize, row: usize| {
        rows[next[column]] = row;
        next[column] += 1;
    };
    for &(row, column) in entries {
        push(column, row);
        push(row, column);
    }
    for i in 0..n {
        push(i, i);
    }
    // Sort each column and drop repeats, compacting towards the front (the write position
    // never passes the read position).
    let mut column_start = vec![0usize; n + 1];
    let mut written = 0;
    for column in 0..n {
        let (from, to) = (start[column], start[column + 1]);
        rows[from..to].sort_unstable();
        column_start[column] = written;
        let mut last = usize::MAX;
        for k in from..to {
            let row = rows[k];
            if row != last {
                rows[written] = row;
                written += 1;
                last = row;
            }
        }
    }
    column_start[n] = written;
    rows.truncate(written);
    SymbolicSparseColMat::new_checked(n, n, column_start, None, rows)
}

#[cfg(test)]
mod tests {
    use faer::sparse::{Pair, SymbolicSparseColMat};

    /// The same pattern as faer's general constructor, on entries with repeats, both triangles
    /// and an empty column.
    #[test]
    fn equals_faers_pattern() {
        let n = 7;
        let entries = [
            (0, 1),
            (1, 0),
            (3, 1),
            (6, 2),
            (2, 6),
            (2, 6),
            (5, 0),
            (4, 4),
        ];
        let ours = super::symmetric(n, &entries);
        let pairs: Vec<_> = entries
            .iter()
            .flat_map(|&(r, c)| [Pair::new(r, c), Pair::new(c, r)])
            .chain((0..n).map(|i| Pair::new(i, i)))
            .collect();
        let (faers, _) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs).unwrap();
        assert_eq!(ours.col_ptr(), faers.col_ptr());
        assert_eq!(ours.row_idx(), faers.row_idx());
    }
}
