//! Smoothed aggregation algebraic multigrid (Vaněk, Mandel & Brezina, "Algebraic multigrid by
//! smoothed aggregation for second and fourth order elliptic problems", Computing 56, 1996),
//! used as a Krylov preconditioner: one V-cycle per application.
//!
//! The unknowns come in groups of `b` (a particle's D coordinates, a cell's fields), and every
//! level keeps that shape: its matrix is stored as b × b blocks between groups.
//!
//! - **Aggregation** (once per run, from the pattern): a group whose neighbours are all free
//!   starts an aggregate with them; a group left over joins an aggregate next to it, or starts
//!   one with its free neighbours (Vaněk et al., §4, phases 1–3). Every connection counts as
//!   strong: the pattern is all the run fixes.
//! - **Prolongation**: the tentative prolongator T maps aggregate a's b unknowns to each of its
//!   groups' b unknowns with weight 1/√|a| (the near-kernel of the b constant vectors, one per
//!   coordinate or field, orthonormalised); the smoothed one is P = (I − ω·D⁻¹A)·T with D the
//!   block diagonal and ω = (4/3)/ρ, ρ ≥ ρ(D⁻¹A) bounded by the largest absolute row sum of D⁻¹A.
//! - **Coarse matrices** by the Galerkin product A_c = Pᵀ·A·P, down to at most
//!   [`COARSE_UNKNOWNS`] unknowns, where a dense LU (faer) solves exactly.
//! - **Smoothing**: one forward block Gauss–Seidel sweep before the coarse correction and one
//!   backward sweep after it, so the V-cycle is a symmetric operator for a symmetric matrix and
//!   conjugate gradients may use it.
//!
//! The patterns of every level are worked out once; each factorization recomputes the values
//! (block inverses, P, A·P, Pᵀ·A·P, the coarse LU) with no allocation.

use std::fmt;

use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::sparse::SymbolicSparseColMat;
use faer::{Mat, Par};

use super::{Column, PrecondError, Preconditioning};
use crate::linalg::solver::SparseView;
use aggregate::aggregate;
use blocks::Blocks;
use level::Level;

mod aggregate;
mod blocks;
mod cycle;
mod level;
#[cfg(test)]
mod tests;

/// The coarsest level is solved by a dense LU when it has at most this many unknowns (its
/// factorization then costs at most about 2·300³/3 ≈ 2·10⁷ flops).
pub(crate) const COARSE_UNKNOWNS: usize = 300;

/// At most this many levels, fine and coarsest included.
const MAX_LEVELS: usize = 12;

/// A hierarchy whose coarsest level would still have more unknowns than this is not built
/// ([`Multigrid::new`] gives `None`): its dense LU would cost more than the rest together.
const MAX_COARSEST: usize = 1000;

/// The hierarchy: levels fine to coarse, the coarsest matrix's dense LU, and how the fine
/// matrix's values fill the first level.
#[derive(Clone)]
pub(crate) struct Multigrid {
    /// Unknowns per group, at every level.
    b: usize,
    /// Fine group k's unknowns are `index[k·b..(k+1)·b]`.
    index: Vec<usize>,
    /// Slot in the sparse matrix's values of each scalar entry of the first level's blocks;
    /// `usize::MAX` where the pattern has none.
    source: Vec<usize>,
    levels: Vec<Level>,
    /// The coarsest matrix (blocks), then its dense LU in place.
    coarsest: Blocks,
    lu: Mat<f64>,
    forward: Vec<usize>,
    inverse: Vec<usize>,
    lu_stack: Scratch,
    /// One b × b block's room.
    work: Vec<f64>,
}

impl fmt::Debug for Multigrid {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Multigrid")
            .field("block", &self.b)
            .field("unknowns per level", &self.sizes())
            .finish()
    }
}

impl Multigrid {
    /// The hierarchy's patterns for groups of `b` unknowns listed in `index` (every unknown
    /// once) over a structurally symmetric `pattern`; `None` when it does not coarsen to
    /// [`MAX_COARSEST`] unknowns in [`MAX_LEVELS`] levels.
    pub(crate) fn new(
        b: usize,
        index: Vec<usize>,
        pattern: &SymbolicSparseColMat<usize>,
    ) -> Option<Self> {
        let b = b.max(1);
        let groups = index.len() / b;
        let mut group_of = vec![0; index.len()];
        for (position, &unknown) in index.iter().enumerate() {
            group_of[unknown] = position / b;
        }
        // The fine block pattern: group k couples to the groups of every row in its columns.
        let rows: Vec<Vec<usize>> = (0..groups)
            .map(|k| {
                let mut row: Vec<usize> = index[k * b..(k + 1) * b]
                    .iter()
                    .flat_map(|&col| pattern.row_idx_of_col_raw(col).iter())
                    .map(|&row| group_of[row])
                    .chain([k])
                    .collect();
                row.sort_unstable();
                row.dedup();
                row
            })
            .collect();
        let fine = Blocks::from_rows(&rows, b);
        let mut source = Vec::with_capacity(fine.value.len());
        for k in 0..groups {
            for &g in &fine.column[fine.row(k)] {
                for r in 0..b {
                    for c in 0..b {
                        let (row, col) = (index[k * b + r], index[g * b + c]);
                        let start = pattern.col_ptr()[col];
                        let rows = pattern.row_idx_of_col_raw(col);
                        source.push(rows.binary_search(&row).map_or(usize::MAX, |p| start + p));
                    }
                }
            }
        }
        let mut levels = Vec::new();
        let mut a = fine;
        while a.rows() * b > COARSE_UNKNOWNS && levels.len() + 1 < MAX_LEVELS {
            let (aggregate, count) = aggregate(&a);
            if count == a.rows() {
                break; // no coarsening: solve this level directly
            }
            let (level, coarse) = Level::new(a, aggregate, count, b);
            levels.push(level);
            a = coarse;
        }
        let n = a.rows() * b;
        if n > MAX_COARSEST {
            return None;
        }
        let lu_stack = Scratch::new(factor::lu_in_place_scratch::<usize, f64>(
            n,
            n,
            Par::Seq,
            Default::default(),
        ));
        Some(Multigrid {
            b,
            index,
            source,
            levels,
            coarsest: a,
            lu: Mat::zeros(n, n),
            forward: vec![0; n],
            inverse: vec![0; n],
            lu_stack,
            work: vec![0.0; b * b],
        })
    }

    /// Unknowns of each level, fine to coarsest.
    pub(crate) fn sizes(&self) -> Vec<usize> {
        self.levels
            .iter()
            .map(|l| l.a.rows() * self.b)
            .chain([self.coarsest.rows() * self.b])
            .collect()
    }

    /// Computes every level's values from the fine matrix's `values`.
    ///
    /// Errors: a [`PrecondError`] when a diagonal block or the coarsest matrix is singular.
    pub(crate) fn update(&mut self, values: &[f64]) -> Result<(), PrecondError> {
        let b = self.b;
        let first = match self.levels.first_mut() {
            Some(level) => &mut level.a,
            None => &mut self.coarsest,
        };
        for (v, &slot) in first.value.iter_mut().zip(&self.source) {
            *v = values.get(slot).copied().unwrap_or(0.0);
        }
        for l in 0..self.levels.len() {
            let (this, rest) = self.levels[l..].split_first_mut().expect("l is a level");
            let coarse = match rest.first_mut() {
                Some(next) => &mut next.a,
                None => &mut self.coarsest,
            };
            // Constant block sizes unroll the block kernels (about 3× faster at b = 2, 3).
            match b {
                1 => this.update(1, &mut self.work, coarse),
                2 => this.update(2, &mut self.work, coarse),
                3 => this.update(3, &mut self.work, coarse),
                _ => this.update(b, &mut self.work, coarse),
            }?;
        }
        self.factorize_coarsest()
    }

    /// The coarsest matrix's dense LU.
    ///
    /// Errors: [`PrecondError::SingularCoarsest`].
    fn factorize_coarsest(&mut self) -> Result<(), PrecondError> {
        let b = self.b;
        let a = &self.coarsest;
        self.lu.fill(0.0);
        for k in 0..a.rows() {
            for p in a.row(k) {
                let g = a.column[p];
                for r in 0..b {
                    for c in 0..b {
                        self.lu[(k * b + r, g * b + c)] = a.value[(p * b + r) * b + c];
                    }
                }
            }
        }
        factor::lu_in_place(
            self.lu.as_mut(),
            &mut self.forward,
            &mut self.inverse,
            Par::Seq,
            MemStack::new(&mut self.lu_stack.buffer),
            Default::default(),
        );
        let regular = (0..self.lu.nrows()).all(|i| {
            let pivot = self.lu[(i, i)];
            pivot != 0.0 && pivot.is_finite()
        });
        if regular {
            Ok(())
        } else {
            Err(PrecondError::SingularCoarsest)
        }
    }
}

/// A faer work buffer that clones as a fresh one of the same size.
struct Scratch {
    buffer: MemBuffer,
    size: StackReq,
}

impl Scratch {
    fn new(size: StackReq) -> Self {
        Scratch {
            buffer: MemBuffer::new(size),
            size,
        }
    }
}

impl Clone for Scratch {
    fn clone(&self) -> Self {
        Scratch::new(self.size)
    }
}

impl Column for Multigrid {
    fn n(&self) -> usize {
        self.index.len()
    }
    fn scratch(&self) -> StackReq {
        let n = self.coarsest.rows() * self.b;
        StackReq::new::<f64>(self.work_len()).and(solve::solve_in_place_scratch::<usize, f64>(
            n,
            1,
            Par::Seq,
        ))
    }
    fn apply_column(&self, out: &mut [f64], r: &[f64], stack: &mut MemStack) {
        self.apply(out, r, stack);
    }
}

impl Preconditioning for Multigrid {
    fn update_from(&mut self, a: &SparseView<'_>) -> Result<(), PrecondError> {
        self.update(a.values)
    }
}
