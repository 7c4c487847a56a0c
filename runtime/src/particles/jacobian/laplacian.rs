//! The link Laplacian of a particle model, read from its derivative blocks.

use nalgebra::{DMatrix, SMatrix};

use super::ParticleJacobian;
use crate::LinkLaplacian;

/// The largest eigenvalue of the symmetric part of `block`, or 0 when it is below 0: the
/// stiffness a block contributes in its stiffest direction (a spring's k), never a negative one.
fn stiffest<const D: usize>(block: &SMatrix<f64, D, D>) -> f64 {
    let symmetric = DMatrix::from_fn(D, D, |i, j| 0.5 * (block[(i, j)] + block[(j, i)]));
    let largest = symmetric.symmetric_eigenvalues().max();
    if largest.is_finite() {
        largest.max(0.0)
    } else {
        0.0
    }
}

impl<const D: usize> ParticleJacobian<D> {
    /// Each link's weight is the stiffest direction of ∂fₐ/∂x_b (k for a spring, stretched or
    /// at rest) and of ∂fₐ/∂v_b (its damping c); each particle's, of −∂fᵢ/∂xᵢ and −∂fᵢ/∂vᵢ of the
    /// per-particle kernels (air drag). Negative and non-finite weights count as 0.
    pub(super) fn laplacian(&self) -> LinkLaplacian {
        let links = self
            .ends
            .iter()
            .zip(&self.pairs)
            .map(|(&ends, blocks)| (ends, stiffest(&blocks[1]), stiffest(&blocks[3])))
            .collect();
        let diagonal = self
            .diagonal
            .iter()
            .map(|blocks| [stiffest(&(-blocks[0])), stiffest(&(-blocks[1]))])
            .collect();
        LinkLaplacian {
            dimension: D,
            mass: self.mass.clone(),
            pinned: self.pinned.clone(),
            links,
            diagonal,
        }
    }
}
