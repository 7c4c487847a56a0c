//! The D×D blocks of ∂f/∂x and ∂f/∂v: written by the kernels' generated derivatives, read
//! densely for tests, and projected to definite stiffness.

use nalgebra::SMatrix;

use super::ParticleJacobian;

impl<const D: usize> ParticleJacobian<D> {
    /// Starts a new evaluation: per-particle blocks to zero, the link cursor to the first link.
    pub(crate) fn begin(&mut self) {
        self.cursor = 0;
        self.diagonal.fill([SMatrix::zeros(); 2]);
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

    /// Replaces every block by its definite counterpart: a link's ∂fₐ/∂x_b by P = the symmetric
    /// part with negative eigenvalues clamped to zero, and ∂fₐ/∂xₐ by −P (as for any force of
    /// x_b − xₐ alone), likewise for the velocity blocks; a particle's own blocks by −P of
    /// their negated symmetric part. Then M − h·∂f/∂v − h²·∂f/∂x is symmetric positive definite.
    pub(super) fn project(&mut self) {
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
}
