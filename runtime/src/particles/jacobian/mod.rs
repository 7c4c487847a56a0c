//! The sparse Jacobian of a particle model and its Newton solve.

mod assembly;
mod blocks;
mod laplacian;

use std::fmt;

use nalgebra::SMatrix;

use crate::linalg::dense::finite;
use crate::linalg::sparse::SparseSolver;
use crate::particles::ParticleSystem;
use crate::stats::LinearWork;
use crate::{FactorizeError, NewtonMatrix, SolveError};

use assembly::{Slots, pattern};

/// The Jacobian of a particle model's forces, in D×D blocks, and the sparse Newton matrix of
/// implicit Euler built from it.
///
/// The blocks are what the kernels' generated derivatives write: for every link of every pair
/// kernel ∂fₐ/∂xₐ, ∂fₐ/∂x_b, ∂fₐ/∂vₐ, ∂fₐ/∂v_b (the force on b is −fₐ), and for every particle
/// the sum of the per-particle kernels' ∂fᵢ/∂xᵢ, ∂fᵢ/∂vᵢ.
///
/// Implicit Euler's Newton system for y = (x, v), (I − h·J)·(Δx, Δv) = (bₓ, b_v) with
/// J = [[0, I], [M⁻¹·∂f/∂x, M⁻¹·∂f/∂v]], is solved through its Schur complement, the system of
/// Baraff & Witkin (1998, eq. 18):
///
/// (M − h·∂f/∂v − h²·∂f/∂x)·Δv = M·b_v + h·∂f/∂x·bₓ,  Δx = bₓ + h·Δv,
///
/// of dimension D·n instead of 2·D·n. Pinned particles' rows and columns are replaced by M (their
/// Δv is zero). The sparsity pattern — a block per particle and two per link — is built once,
/// in [`ParticleJacobian::new`], together with the symbolic Cholesky factorization (AMD
/// ordering); each solve then only refills values, factorizes numerically and substitutes, with
/// no allocation. Conservative spring forces make the matrix symmetric, and positive definite
/// unless springs are compressed hard: then Cholesky (LLᵀ) is used. When the assembled matrix
/// is not symmetric, or Cholesky meets a non-positive pivot, the solve falls back to sparse LU,
/// whose symbolic analysis is made the first time it is needed and kept.
pub struct ParticleJacobian<const D: usize> {
    particles: usize,
    mass: Vec<f64>,
    pinned: Vec<bool>,
    ends: Vec<[usize; 2]>,
    /// Per link: ∂fₐ/∂xₐ, ∂fₐ/∂x_b, ∂fₐ/∂vₐ, ∂fₐ/∂v_b.
    pub(in crate::particles) pairs: Vec<[SMatrix<f64, D, D>; 4]>,
    /// Per particle: ∂fᵢ/∂xᵢ, ∂fᵢ/∂vᵢ of the per-particle kernels.
    pub(in crate::particles) diagonal: Vec<[SMatrix<f64, D, D>; 2]>,
    /// Links written so far in this evaluation.
    pub(in crate::particles) cursor: usize,
    /// Project the blocks to definite stiffness before assembly ([`crate::NewtonOptions::definite`]).
    definite: bool,
    /// The c of the last factorization of I − c·J.
    scale: f64,
    solver: SparseSolver,
    slots: Slots,
}

impl<const D: usize> ParticleJacobian<D> {
    /// The Jacobian of `model` with `particles` particles (its topology already checked by
    /// [`crate::Model::check`]): the pattern and the symbolic Cholesky factorization are computed
    /// here, once.
    pub fn new<M: ParticleSystem<D>>(model: &M, particles: usize) -> Self {
        let mut pinned = vec![false; particles];
        for &p in model.pinned() {
            if let Some(flag) = pinned.get_mut(p) {
                *flag = true;
            }
        }
        let ends: Vec<[usize; 2]> = model
            .link_lists()
            .into_iter()
            .flat_map(|(_, links)| (0..links.len()).map(move |k| links.ends(k)))
            .filter(|&[a, b]| a < particles && b < particles && a != b)
            .collect();
        let (solver, slots) = pattern::<D>(particles, &pinned, &ends);
        ParticleJacobian {
            particles,
            mass: model.masses().to_vec(),
            pinned,
            pairs: vec![[SMatrix::zeros(); 4]; ends.len()],
            diagonal: vec![[SMatrix::zeros(); 2]; particles],
            ends,
            cursor: 0,
            definite: false,
            scale: 0.0,
            solver,
            slots,
        }
    }

    /// Number of particles.
    pub fn particles(&self) -> usize {
        self.particles
    }

    /// How often this Jacobian has factorized.
    pub fn factorizations(&self) -> LinearWork {
        self.solver.counts
    }

    /// Structural non-zeros of the D·n × D·n Newton matrix.
    pub fn nonzeros(&self) -> usize {
        self.solver.values.len()
    }

    /// Factorizes the assembled matrix numerically (Cholesky, else LU).
    ///
    /// Errors: [`FactorizeError::Singular`].
    pub fn factorize(&mut self) -> Result<(), FactorizeError> {
        self.solver.factorize()
    }

    /// Solves the factorized matrix against `rhs` (D·n long) in place.
    ///
    /// Errors: [`SolveError::WrongLength`]; [`SolveError::Singular`] when a Krylov solve
    /// failed and the direct solve that took over found the matrix singular (`rhs`'s contents
    /// unspecified then).
    pub fn substitute(&mut self, rhs: &mut [f64]) -> Result<(), SolveError> {
        if rhs.len() != self.solver.rhs.len() {
            return Err(SolveError::WrongLength {
                expected: self.solver.rhs.len(),
                found: rhs.len(),
            });
        }
        self.solver.rhs.copy_from_slice(rhs);
        self.solver.substitute()?;
        rhs.copy_from_slice(&self.solver.rhs);
        Ok(())
    }
}

impl<const D: usize> NewtonMatrix for ParticleJacobian<D> {
    const COSTLY_SOLVES: bool = true;
    const LINKS: bool = true;

    fn work(&self) -> LinearWork {
        self.solver.counts
    }

    fn configure(&mut self, newton: &crate::NewtonOptions, solves: crate::Solves) {
        self.definite = newton.definite;
        self.solver.configure(
            &newton.linear,
            crate::linalg::krylov::Structure::Particles,
            solves,
        );
    }

    /// The factorization lives in the sparse solver inside the matrix.
    type Factors = ();

    fn factors(&self) {}

    /// Assembles M − c·∂f/∂v − c²·∂f/∂x and factorizes it: (I − c·J)·x = b for the first-order
    /// system is solved through this velocity form.
    fn factorize(&mut self, c: f64, _: &mut ()) -> Result<(), FactorizeError> {
        self.assemble(c);
        self.scale = c;
        self.solver.factorize()
    }

    fn solve(&mut self, _: &mut (), b: &mut [f64]) -> Result<(), SolveError> {
        let n = D * self.particles;
        if b.len() != 2 * n {
            return Err(SolveError::WrongLength {
                expected: 2 * n,
                found: b.len(),
            });
        }
        let c = self.scale;
        let (bx, bv) = b.split_at_mut(n);
        self.velocity_rhs(c, bx, bv);
        self.solver.substitute()?;
        for ((x, v), dv) in bx.iter_mut().zip(bv.iter_mut()).zip(&self.solver.rhs) {
            *v = *dv;
            *x += c * dv;
        }
        finite(b)
    }

    /// Only when some link has stiffness: without it the Laplacian is M and the quasi-Newton
    /// solve would be a gradient method.
    fn link_laplacian(&self) -> Option<crate::LinkLaplacian> {
        let laplacian = self.laplacian();
        laplacian
            .links
            .iter()
            .any(|&(_, k, _)| k > 0.0)
            .then_some(laplacian)
    }

    /// In the first-order layout (every position, then every velocity): a force block of
    /// particle a with respect to particle b's position or velocity is J's rows of a's velocity,
    /// columns of b's position or velocity.
    fn non_finite_entry(&self) -> Option<(usize, usize, f64)> {
        let n = D * self.particles;
        let find = |block: &SMatrix<f64, D, D>, a: usize, b: usize, of_velocity: bool| {
            let column = if of_velocity { n + D * b } else { D * b };
            block
                .iter()
                .position(|x| !x.is_finite())
                .map(|k| (n + D * a + k % D, column + k / D, block[k]))
        };
        let pairs = self
            .ends
            .iter()
            .zip(&self.pairs)
            .find_map(|(&[a, b], blocks)| {
                find(&blocks[0], a, a, false)
                    .or_else(|| find(&blocks[1], a, b, false))
                    .or_else(|| find(&blocks[2], a, a, true))
                    .or_else(|| find(&blocks[3], a, b, true))
            });
        pairs.or_else(|| {
            self.diagonal.iter().enumerate().find_map(|(i, blocks)| {
                find(&blocks[0], i, i, false).or_else(|| find(&blocks[1], i, i, true))
            })
        })
    }
}

impl<const D: usize> Clone for ParticleJacobian<D> {
    fn clone(&self) -> Self {
        ParticleJacobian {
            particles: self.particles,
            mass: self.mass.clone(),
            pinned: self.pinned.clone(),
            ends: self.ends.clone(),
            pairs: self.pairs.clone(),
            diagonal: self.diagonal.clone(),
            cursor: self.cursor,
            definite: self.definite,
            scale: self.scale,
            solver: self.solver.clone(),
            slots: self.slots.clone(),
        }
    }
}

impl<const D: usize> fmt::Debug for ParticleJacobian<D> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ParticleJacobian")
            .field("particles", &self.particles)
            .field("links", &self.ends.len())
            .field("nonzeros", &self.solver.values.len())
            .field("factorizations", &self.solver.counts)
            .finish_non_exhaustive()
    }
}
