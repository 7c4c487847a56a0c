//! A weighted graph Laplacian of links between particles, times the identity in D dimensions:
//! the constant matrix M + h·C + h²·K that stands in for implicit Euler's Newton matrix in the
//! quasi-Newton solve of particle models (Liu, Bargteil, O'Brien & Kavan, "Fast Simulation of
//! Mass-Spring Systems", SIGGRAPH Asia 2013, §4; Liu, Bouaziz & Kavan, "Quasi-Newton Methods for
//! Real-Time Simulation of Hyperelastic Materials", TOG 2017, §3).
//!
//! Each link's D×D stiffness block is replaced by a scalar weight times I: its largest stiffness
//! (a spring's k) in every direction, so one scalar factorization of n unknowns serves all D
//! axes, and the matrix does not change with the state.

use super::spd::SpdSolver;
use crate::Result;

/// A scalar stiffness and damping for every link and every particle, with the masses and pins:
/// the data of M + h·C + h²·K.
#[derive(Clone, Debug, PartialEq)]
pub struct LinkLaplacian {
    /// Space dimension D (the axes one scalar factorization serves).
    pub dimension: usize,
    /// Mass of every particle (kg).
    pub mass: Vec<f64>,
    /// Whether each particle is pinned: its velocity is prescribed, so it drops out.
    pub pinned: Vec<bool>,
    /// Every link: its two particles, its stiffness (N/m) and its damping (N·s/m), both ≥ 0.
    pub links: Vec<([usize; 2], f64, f64)>,
    /// Every particle's own stiffness (N/m) and damping (N·s/m) (drag, a tether), both ≥ 0.
    pub diagonal: Vec<[f64; 2]>,
}

impl LinkLaplacian {
    /// Number of particles whose velocity is unknown.
    pub(crate) fn free(&self) -> usize {
        self.pinned.iter().filter(|p| !**p).count()
    }

    /// Each particle's row in the matrix (pinned ones `usize::MAX`).
    pub(crate) fn rows(&self) -> Vec<usize> {
        let mut next = 0;
        self.pinned
            .iter()
            .map(|&pinned| {
                if pinned {
                    usize::MAX
                } else {
                    next += 1;
                    next - 1
                }
            })
            .collect()
    }

    /// Factorizes the scalar matrix A = M + h·C + h²·K over the free particles, ready for D
    /// right-hand sides at once: Aᵢᵢ = mᵢ + h·cᵢ + h²·kᵢ + Σ over links at i of (h·c + h²·k),
    /// Aᵢⱼ = −(h·c + h²·k) for a link between free i and j. A link to a pinned particle keeps
    /// its diagonal term: the pin holds that end.
    ///
    /// Errors: [`crate::Error::InvalidInput`] when A is not positive definite (a mass that is
    /// not positive).
    pub(crate) fn factorize(&self, h: f64) -> Result<SpdSolver> {
        let rows = self.rows();
        let mut entries = Vec::with_capacity(self.free() + 4 * self.links.len());
        for (&row, (&m, &[k, c])) in rows.iter().zip(self.mass.iter().zip(&self.diagonal)) {
            if row != usize::MAX {
                entries.push((row, row, m + h * c + h * h * k));
            }
        }
        for &([a, b], k, c) in &self.links {
            let w = h * c + h * h * k;
            let (ra, rb) = (rows[a], rows[b]);
            if ra != usize::MAX {
                entries.push((ra, ra, w));
            }
            if rb != usize::MAX {
                entries.push((rb, rb, w));
            }
            if ra != usize::MAX && rb != usize::MAX {
                entries.push((ra, rb, -w));
                entries.push((rb, ra, -w));
            }
        }
        SpdSolver::with_columns(self.free(), &entries, self.dimension)
    }
}
