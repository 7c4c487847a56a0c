//! The Newton matrix's sparsity pattern, made once, and its assembly from the blocks at every
//! factorization.

use faer::sparse::SparseColMatRef;
use nalgebra::{SMatrix, SVector};

use super::ParticleJacobian;
use crate::linalg::sparse::SparseSolver;

impl<const D: usize> ParticleJacobian<D> {
    /// Assembles M − h·∂f/∂v − h²·∂f/∂x into the sparse matrix and returns it.
    pub fn newton_matrix(&mut self, h: f64) -> SparseColMatRef<'_, usize, f64> {
        self.assemble(h);
        self.solver.matrix()
    }

    /// Assembles M − h·∂f/∂v − h²·∂f/∂x from the blocks of the last evaluation (projected first
    /// when [`crate::NewtonOptions::definite`] is set): the "assembly" of a step's cost.
    pub fn assemble(&mut self, h: f64) {
        if self.definite {
            self.project();
        }
        let s = &mut self.solver;
        let slots = &self.slots;
        let h2 = h * h;
        s.values.fill(0.0);
        for (i, [bx, bv]) in self.diagonal.iter().enumerate() {
            let diagonal = &slots.diagonal[i * D * D..(i + 1) * D * D];
            for r in 0..D {
                for c in 0..D {
                    let mass = if r == c { self.mass[i] } else { 0.0 };
                    s.values[diagonal[r * D + c]] = if self.pinned[i] {
                        mass
                    } else {
                        mass - h * bv[(r, c)] - h2 * bx[(r, c)]
                    };
                }
            }
        }
        for (k, (&[a, b], [xa, xb, va, vb])) in self.ends.iter().zip(&self.pairs).enumerate() {
            // Row a gets +∂fₐ, row b gets −∂fₐ; the matrix holds −h·∂f/∂v − h²·∂f/∂x.
            let block = |r: usize, c: usize, dx: &SMatrix<f64, D, D>, dv: &SMatrix<f64, D, D>| {
                -h * dv[(r, c)] - h2 * dx[(r, c)]
            };
            let pinned_a = self.pinned[a];
            let pinned_b = self.pinned[b];
            let base = k * 2 * D * D;
            for r in 0..D {
                for c in 0..D {
                    if !pinned_a {
                        s.values[slots.diagonal[a * D * D + r * D + c]] += block(r, c, xa, va);
                    }
                    if !pinned_b {
                        s.values[slots.diagonal[b * D * D + r * D + c]] -= block(r, c, xb, vb);
                    }
                    if !(pinned_a || pinned_b) {
                        s.values[slots.pairs[base + r * D + c]] += block(r, c, xb, vb);
                        s.values[slots.pairs[base + D * D + r * D + c]] -= block(r, c, xa, va);
                    }
                }
            }
        }
    }

    /// rhs ← M·b_v + h·∂f/∂x·bₓ on free particles, M·b_v on pinned ones.
    pub(super) fn velocity_rhs(&mut self, h: f64, bx: &[f64], bv: &[f64]) {
        let rhs = &mut self.solver.rhs;
        rhs.fill(0.0);
        let part = |s: &[f64], i: usize| SVector::<f64, D>::from_column_slice(&s[D * i..D * i + D]);
        let add = |rhs: &mut [f64], i: usize, w: SVector<f64, D>| {
            for (r, wr) in rhs[D * i..D * i + D].iter_mut().zip(w.iter()) {
                *r += wr;
            }
        };
        for (i, [dx, _]) in self.diagonal.iter().enumerate() {
            add(rhs, i, dx * part(bx, i));
        }
        for (&[a, b], [xa, xb, _, _]) in self.ends.iter().zip(&self.pairs) {
            let w = xa * part(bx, a) + xb * part(bx, b);
            add(rhs, a, w);
            add(rhs, b, -w);
        }
        for i in 0..self.particles {
            for r in 0..D {
                let k = D * i + r;
                let force = if self.pinned[i] { 0.0 } else { h * rhs[k] };
                rhs[k] = self.mass[i] * bv[k] + force;
            }
        }
    }
}

/// The slots of a particle model's blocks in the sparse matrix.
#[derive(Clone)]
pub(super) struct Slots {
    /// Slot of entry (D·i + r, D·i + c) at i·D² + r·D + c.
    diagonal: Vec<usize>,
    /// Per link, slots of block (a, b) then block (b, a), row-major; `usize::MAX` when either
    /// particle is pinned.
    pairs: Vec<usize>,
}

/// The sparse matrix of `particles` particles joined by `ends` (pinned particles keep only their
/// own blocks), and where each block goes in it.
pub(super) fn pattern<const D: usize>(
    particles: usize,
    pinned: &[bool],
    ends: &[[usize; 2]],
) -> (SparseSolver, Slots) {
    let mut entries = Vec::new();
    let mut block = |i: usize, j: usize| {
        for r in 0..D {
            for c in 0..D {
                entries.push((D * i + r, D * j + c));
            }
        }
    };
    for i in 0..particles {
        block(i, i);
    }
    for &[a, b] in ends {
        if !(pinned[a] || pinned[b]) {
            block(a, b);
            block(b, a);
        }
    }
    let mut solver = SparseSolver::new(D * particles, &entries);
    // Block Jacobi inverts each particle's D×D block.
    solver.set_blocks(D, (0..D * particles).collect());
    let mut diagonal = Vec::with_capacity(particles * D * D);
    for i in 0..particles {
        for r in 0..D {
            for c in 0..D {
                diagonal.push(solver.slot(D * i + r, D * i + c));
            }
        }
    }
    let mut pairs = Vec::with_capacity(ends.len() * 2 * D * D);
    for &[a, b] in ends {
        for (i, j) in [(a, b), (b, a)] {
            for r in 0..D {
                for c in 0..D {
                    pairs.push(if pinned[a] || pinned[b] {
                        usize::MAX
                    } else {
                        solver.slot(D * i + r, D * j + c)
                    });
                }
            }
        }
    }
    (solver, Slots { diagonal, pairs })
}
