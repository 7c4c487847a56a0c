//! One level of the hierarchy: its patterns (aggregates, the prolongator P, A·P and the coarse
//! matrix Pᵀ·A·P), worked out once, and its values — block inverses, the smoothed prolongator,
//! the Galerkin product — recomputed at every factorization.

use super::blocks::{Blocks, mark, multiply_add, transpose_multiply_add};
use crate::linalg::precond::{PrecondError, invert};

/// One level above the coarsest: its matrix, block inverses, aggregates and prolongator, and the
/// pattern of A·P for the Galerkin product.
#[derive(Clone, Debug)]
pub(super) struct Level {
    pub(super) a: Blocks,
    /// Position of each row's diagonal block in `a`.
    diagonal: Vec<usize>,
    /// The inverse of each diagonal block.
    pub(super) inverse: Vec<f64>,
    /// The aggregate (coarse group) of each group.
    aggregate: Vec<usize>,
    /// 1/√(groups in aggregate), per aggregate.
    weight: Vec<f64>,
    /// The smoothed prolongator.
    pub(super) p: Blocks,
    /// A·P.
    ap: Blocks,
    /// D⁻¹·A, on A's pattern.
    scaled: Vec<f64>,
    /// Pᵀ by coarse rows: row c's (fine group k, position in P) at
    /// `transpose[transpose_start[c]..transpose_start[c + 1]]`.
    transpose_start: Vec<usize>,
    transpose: Vec<(usize, usize)>,
    /// Where each block column is in the row being filled (one entry per aggregate).
    position: Vec<usize>,
}

impl Level {
    /// The level of matrix `a` with groups `aggregate`d into `count` aggregates, and the coarse
    /// matrix's pattern (values zero).
    pub(super) fn new(a: Blocks, aggregate: Vec<usize>, count: usize, b: usize) -> (Self, Blocks) {
        let groups = a.rows();
        let mut size = vec![0usize; count];
        for &agg in &aggregate {
            size[agg] += 1;
        }
        let weight = size.iter().map(|&s| 1.0 / (s as f64).sqrt()).collect();
        // P's row k reaches the aggregates of k's neighbours.
        let p_rows: Vec<Vec<usize>> = (0..groups)
            .map(|k| sorted(a.column[a.row(k)].iter().map(|&g| aggregate[g])))
            .collect();
        // A·P's row k: the aggregates P reaches from k's neighbours.
        let ap_rows: Vec<Vec<usize>> = (0..groups)
            .map(|k| {
                sorted(
                    a.column[a.row(k)]
                        .iter()
                        .flat_map(|&g| p_rows[g].iter().copied()),
                )
            })
            .collect();
        // Pᵀ·A·P's row c: A·P's rows k that P links to c.
        let mut coarse_rows = vec![Vec::new(); count];
        for k in 0..groups {
            for &c in &p_rows[k] {
                coarse_rows[c].extend_from_slice(&ap_rows[k]);
            }
        }
        for row in &mut coarse_rows {
            row.sort_unstable();
            row.dedup();
        }
        let diagonal = (0..groups).map(|k| a.find(k, k)).collect();
        let p = Blocks::from_rows(&p_rows, b);
        let mut transpose_start = vec![0usize; count + 1];
        for &c in &p.column {
            transpose_start[c + 1] += 1;
        }
        for c in 0..count {
            transpose_start[c + 1] += transpose_start[c];
        }
        let mut next = transpose_start.clone();
        let mut transpose = vec![(0, 0); p.column.len()];
        for k in 0..groups {
            for q in p.row(k) {
                let c = p.column[q];
                transpose[next[c]] = (k, q);
                next[c] += 1;
            }
        }
        let level = Level {
            inverse: vec![0.0; groups * b * b],
            scaled: vec![0.0; a.value.len()],
            transpose_start,
            transpose,
            position: vec![0; count],
            diagonal,
            aggregate,
            weight,
            p,
            ap: Blocks::from_rows(&ap_rows, b),
            a,
        };
        (level, Blocks::from_rows(&coarse_rows, b))
    }

    /// Block inverses, P, A·P and the coarse matrix's values. Every block kernel is inlined
    /// here, so a constant `b` (see [`super::Multigrid::update`]) unrolls them.
    ///
    /// Errors: [`PrecondError::SingularBlock`], [`PrecondError::NoSmoothingWeight`].
    #[inline(always)]
    pub(super) fn update(
        &mut self,
        b: usize,
        scratch: &mut [f64],
        coarse: &mut Blocks,
    ) -> Result<(), PrecondError> {
        let bb = b * b;
        let a = &self.a;
        for (k, inverse) in self.inverse.chunks_mut(bb).enumerate() {
            scratch[..bb].copy_from_slice(a.block(self.diagonal[k], b));
            invert(b, &mut scratch[..bb], inverse)?;
        }
        // D⁻¹·A, and ρ(D⁻¹A) ≤ its largest absolute row sum.
        let mut rho = 0.0f64;
        for k in 0..a.rows() {
            let inverse = &self.inverse[k * bb..(k + 1) * bb];
            let sums = &mut scratch[..b];
            sums.fill(0.0);
            for p in a.row(k) {
                let product = &mut self.scaled[p * bb..(p + 1) * bb];
                product.fill(0.0);
                multiply_add(b, inverse, a.block(p, b), product);
                for (r, sum) in sums.iter_mut().enumerate() {
                    *sum += product[r * b..(r + 1) * b]
                        .iter()
                        .map(|v| v.abs())
                        .sum::<f64>();
                }
            }
            rho = sums.iter().fold(rho, |m, &s| m.max(s));
        }
        if !(rho.is_finite() && rho > 0.0) {
            return Err(PrecondError::NoSmoothingWeight);
        }
        let omega = 4.0 / 3.0 / rho;
        // P = T − ω·D⁻¹·A·T, T(g, aggregate g) = weight·I; `position` finds a block column
        // in the row being filled.
        let position = &mut self.position;
        self.p.value.fill(0.0);
        for k in 0..a.rows() {
            mark(&self.p, k, position);
            for p in a.row(k) {
                let agg = self.aggregate[a.column[p]];
                let q = position[agg];
                let scale = -omega * self.weight[agg];
                for (pv, &m) in self.p.value[q * bb..(q + 1) * bb]
                    .iter_mut()
                    .zip(&self.scaled[p * bb..(p + 1) * bb])
                {
                    *pv += scale * m;
                }
            }
            let own = self.aggregate[k];
            let q = position[own];
            for r in 0..b {
                self.p.value[q * bb + r * b + r] += self.weight[own];
            }
        }
        // A·P, row by row.
        self.ap.value.fill(0.0);
        for k in 0..a.rows() {
            mark(&self.ap, k, position);
            for p in a.row(k) {
                let g = a.column[p];
                for q in self.p.row(g) {
                    let target = position[self.p.column[q]];
                    multiply_add(
                        b,
                        a.block(p, b),
                        self.p.block(q, b),
                        &mut self.ap.value[target * bb..(target + 1) * bb],
                    );
                }
            }
        }
        // Pᵀ·(A·P), coarse row by coarse row through Pᵀ.
        coarse.value.fill(0.0);
        for c in 0..coarse.rows() {
            mark(coarse, c, position);
            for &(k, q) in &self.transpose[self.transpose_start[c]..self.transpose_start[c + 1]] {
                for s in self.ap.row(k) {
                    let target = position[self.ap.column[s]];
                    transpose_multiply_add(
                        b,
                        self.p.block(q, b),
                        self.ap.block(s, b),
                        &mut coarse.value[target * bb..(target + 1) * bb],
                    );
                }
            }
        }
        Ok(())
    }
}

/// Sorted, deduplicated.
fn sorted(items: impl Iterator<Item = usize>) -> Vec<usize> {
    let mut v: Vec<usize> = items.collect();
    v.sort_unstable();
    v.dedup();
    v
}
