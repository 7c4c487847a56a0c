//! The storage of multigrid's matrices, b × b blocks between groups, and the block kernels the
//! set-up and the V-cycle share (each inlined, so a constant b unrolls it).

/// A square matrix of b × b blocks in block-row order: row k's blocks are `start[k]..start[k+1]`
/// with block columns `column` (ascending) and values `value[p·b²..(p+1)·b²]`, row-major. P is
/// stored the same way, with aggregates as its block columns.
#[derive(Clone, Debug, Default)]
pub(super) struct Blocks {
    pub(super) start: Vec<usize>,
    pub(super) column: Vec<usize>,
    pub(super) value: Vec<f64>,
}

impl Blocks {
    /// Block rows from sorted column lists.
    pub(super) fn from_rows(rows: &[Vec<usize>], b: usize) -> Self {
        let mut start = Vec::with_capacity(rows.len() + 1);
        let mut column = Vec::new();
        start.push(0);
        for row in rows {
            column.extend_from_slice(row);
            start.push(column.len());
        }
        let value = vec![0.0; column.len() * b * b];
        Blocks {
            start,
            column,
            value,
        }
    }

    #[inline]
    pub(super) fn rows(&self) -> usize {
        self.start.len() - 1
    }

    #[inline]
    pub(super) fn row(&self, k: usize) -> std::ops::Range<usize> {
        self.start[k]..self.start[k + 1]
    }

    /// Position of block (k, c), which must be in the pattern.
    #[inline]
    pub(super) fn find(&self, k: usize, c: usize) -> usize {
        let row = self.row(k);
        row.start
            + self.column[row]
                .binary_search(&c)
                .expect("the block is in the pattern worked out for it")
    }

    #[inline]
    pub(super) fn block(&self, p: usize, b: usize) -> &[f64] {
        &self.value[p * b * b..(p + 1) * b * b]
    }
}

/// Writes into `position` where each block column of row k of `m` is.
#[inline(always)]
pub(super) fn mark(m: &Blocks, k: usize, position: &mut [usize]) {
    for p in m.row(k) {
        position[m.column[p]] = p;
    }
}

/// out += m·n.
#[inline(always)]
pub(super) fn multiply_add(b: usize, m: &[f64], n: &[f64], out: &mut [f64]) {
    for r in 0..b {
        for k in 0..b {
            let mrk = m[r * b + k];
            if mrk != 0.0 {
                for c in 0..b {
                    out[r * b + c] += mrk * n[k * b + c];
                }
            }
        }
    }
}

/// out += mᵀ·n.
#[inline(always)]
pub(super) fn transpose_multiply_add(b: usize, m: &[f64], n: &[f64], out: &mut [f64]) {
    for k in 0..b {
        for r in 0..b {
            let mkr = m[k * b + r];
            if mkr != 0.0 {
                for c in 0..b {
                    out[r * b + c] += mkr * n[k * b + c];
                }
            }
        }
    }
}

/// s −= m·v.
#[inline(always)]
pub(super) fn subtract_product(b: usize, m: &[f64], v: &[f64], s: &mut [f64]) {
    for (r, sr) in s.iter_mut().enumerate() {
        *sr -= m[r * b..(r + 1) * b]
            .iter()
            .zip(v)
            .map(|(a, x)| a * x)
            .sum::<f64>();
    }
}
