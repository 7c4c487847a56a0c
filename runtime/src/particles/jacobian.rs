//! The sparse Jacobian of a particle model and its Newton solve.

use std::fmt;

use faer::sparse::SparseColMatRef;
use nalgebra::{SMatrix, SVector};

use super::ParticleSystem;
use crate::linalg::dense::finite;
use crate::linalg::sparse::{Factorizations, SparseSolver};
use crate::{FactorizeError, NewtonMatrix, SolveError};

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
    pairs: Vec<[SMatrix<f64, D, D>; 4]>,
    /// Per particle: ∂fᵢ/∂xᵢ, ∂fᵢ/∂vᵢ of the per-particle kernels.
    diagonal: Vec<[SMatrix<f64, D, D>; 2]>,
    /// Links written so far in this evaluation.
    cursor: usize,
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
    pub fn factorizations(&self) -> Factorizations {
        self.solver.counts
    }

    /// Structural non-zeros of the D·n × D·n Newton matrix.
    pub fn nonzeros(&self) -> usize {
        self.solver.values.len()
    }

    /// Starts a new evaluation: per-particle blocks to zero, the link cursor to the first link.
    pub(crate) fn begin(&mut self) {
        self.cursor = 0;
        self.diagonal.fill([SMatrix::zeros(); 2]);
    }

    /// Writes the blocks of a pair kernel over `links` (the next links in kernel order):
    /// `kernel(link, xa, xb, va, vb)` returns ∂fₐ/∂xₐ, ∂fₐ/∂x_b, ∂fₐ/∂vₐ, ∂fₐ/∂v_b.
    #[doc(hidden)]
    #[inline]
    #[allow(clippy::type_complexity)]
    pub fn pair_blocks<L: super::Link>(
        &mut self,
        links: &[L],
        x: &[SVector<f64, D>],
        v: &[SVector<f64, D>],
        kernel: impl Fn(
            &L,
            &SVector<f64, D>,
            &SVector<f64, D>,
            &SVector<f64, D>,
            &SVector<f64, D>,
        ) -> [SMatrix<f64, D, D>; 4],
    ) {
        let blocks = &mut self.pairs[self.cursor..self.cursor + links.len()];
        for (link, out) in links.iter().zip(blocks) {
            let [a, b] = link.ends();
            *out = kernel(link, &x[a], &x[b], &v[a], &v[b]);
        }
        self.cursor += links.len();
    }

    /// Adds the blocks of a per-particle kernel: `kernel(i, x, v)` returns ∂fᵢ/∂xᵢ, ∂fᵢ/∂vᵢ.
    #[doc(hidden)]
    #[inline]
    pub fn particle_blocks(
        &mut self,
        x: &[SVector<f64, D>],
        v: &[SVector<f64, D>],
        kernel: impl Fn(usize, &SVector<f64, D>, &SVector<f64, D>) -> [SMatrix<f64, D, D>; 2],
    ) {
        for (i, ((x, v), out)) in x.iter().zip(v).zip(&mut self.diagonal).enumerate() {
            let [dx, dv] = kernel(i, x, v);
            out[0] += dx;
            out[1] += dv;
        }
    }

    /// Factorizes the assembled matrix numerically (Cholesky, else LU).
    ///
    /// Errors: [`FactorizeError::Singular`].
    pub fn factorize(&mut self) -> Result<(), FactorizeError> {
        self.solver.factorize()
    }

    /// Solves the factorized matrix against `rhs` (D·n long) in place.
    pub fn substitute(&mut self, rhs: &mut [f64]) {
        self.solver.rhs.copy_from_slice(rhs);
        self.solver.substitute();
        rhs.copy_from_slice(&self.solver.rhs);
    }

    /// ∂f/∂x and ∂f/∂v as dense D·n × D·n matrices (row = force component), pinned rows
    /// included: for tests and small models.
    pub fn force_jacobians(&self) -> (faer::Mat<f64>, faer::Mat<f64>) {
        let n = D * self.particles;
        let mut dx = faer::Mat::zeros(n, n);
        let mut dv = faer::Mat::zeros(n, n);
        let add = |m: &mut faer::Mat<f64>, i: usize, j: usize, block: &SMatrix<f64, D, D>, s| {
            for r in 0..D {
                for c in 0..D {
                    m[(D * i + r, D * j + c)] += s * block[(r, c)];
                }
            }
        };
        for (i, [bx, bv]) in self.diagonal.iter().enumerate() {
            add(&mut dx, i, i, bx, 1.0);
            add(&mut dv, i, i, bv, 1.0);
        }
        for (&[a, b], [xa, xb, va, vb]) in self.ends.iter().zip(&self.pairs) {
            for (row, sign) in [(a, 1.0), (b, -1.0)] {
                add(&mut dx, row, a, xa, sign);
                add(&mut dx, row, b, xb, sign);
                add(&mut dv, row, a, va, sign);
                add(&mut dv, row, b, vb, sign);
            }
        }
        (dx, dv)
    }

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

    /// Replaces every block by its definite counterpart: a link's ∂fₐ/∂x_b by P = the symmetric
    /// part with negative eigenvalues clamped to zero, and ∂fₐ/∂xₐ by −P (as for any force of
    /// x_b − xₐ alone), likewise for the velocity blocks; a particle's own blocks by −P of
    /// their negated symmetric part. Then M − h·∂f/∂v − h²·∂f/∂x is symmetric positive definite.
    fn project(&mut self) {
        fn clamp2(m: nalgebra::Matrix2<f64>) -> nalgebra::Matrix2<f64> {
            let mut eigen = m.symmetric_eigen();
            eigen.eigenvalues.apply(|l| *l = l.max(0.0));
            eigen.recompose()
        }
        fn clamp3(m: nalgebra::Matrix3<f64>) -> nalgebra::Matrix3<f64> {
            let mut eigen = m.symmetric_eigen();
            eigen.eigenvalues.apply(|l| *l = l.max(0.0));
            eigen.recompose()
        }
        fn definite<const D: usize>(block: &SMatrix<f64, D, D>) -> SMatrix<f64, D, D> {
            let symmetric = (block + block.transpose()) * 0.5;
            // Gershgorin: a symmetric matrix with non-negative diagonal dominance is already
            // semidefinite, the common case (a stretched spring), and needs no eigensolve.
            let dominant = (0..D).all(|r| {
                let off: f64 = (0..D)
                    .filter(|&c| c != r)
                    .map(|c| symmetric[(r, c)].abs())
                    .sum();
                symmetric[(r, r)] >= off
            });
            if dominant {
                return symmetric;
            }
            // nalgebra's eigensolver needs the size as a type: particle models are 2-D or 3-D.
            let copy = |m: &dyn Fn(usize, usize) -> f64| SMatrix::<f64, D, D>::from_fn(m);
            match D {
                2 => {
                    let m = clamp2(nalgebra::Matrix2::from_fn(|r, c| symmetric[(r, c)]));
                    copy(&|r, c| m[(r, c)])
                }
                3 => {
                    let m = clamp3(nalgebra::Matrix3::from_fn(|r, c| symmetric[(r, c)]));
                    copy(&|r, c| m[(r, c)])
                }
                _ => symmetric,
            }
        }
        for [xa, xb, va, vb] in &mut self.pairs {
            *xb = definite(xb);
            *xa = -*xb;
            *vb = definite(vb);
            *va = -*vb;
        }
        for [dx, dv] in &mut self.diagonal {
            *dx = -definite(&-*dx);
            *dv = -definite(&-*dv);
        }
    }

    /// rhs ← M·b_v + h·∂f/∂x·bₓ on free particles, M·b_v on pinned ones.
    fn velocity_rhs(&mut self, h: f64, bx: &[f64], bv: &[f64]) {
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

impl<const D: usize> NewtonMatrix for ParticleJacobian<D> {
    fn configure(&mut self, newton: &crate::NewtonOptions, in_newton: bool) {
        self.definite = newton.definite;
        self.solver.configure(
            &newton.linear,
            crate::linalg::krylov::Structure::Particles,
            in_newton,
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
        self.solver.substitute();
        for ((x, v), dv) in bx.iter_mut().zip(bv.iter_mut()).zip(&self.solver.rhs) {
            *v = *dv;
            *x += c * dv;
        }
        finite(b)
    }
}

/// The slots of a particle model's blocks in the sparse matrix.
#[derive(Clone)]
struct Slots {
    /// Slot of entry (D·i + r, D·i + c) at i·D² + r·D + c.
    diagonal: Vec<usize>,
    /// Per link, slots of block (a, b) then block (b, a), row-major; `usize::MAX` when either
    /// particle is pinned.
    pairs: Vec<usize>,
}

/// The sparse matrix of `particles` particles joined by `ends` (pinned particles keep only their
/// own blocks), and where each block goes in it.
fn pattern<const D: usize>(
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
