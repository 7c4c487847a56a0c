//! The augmented system's Jacobian, for the implicit methods.
//!
//! For z = (y, s₁, …, s_c) and F(z) = (f(y), J(y)·s₁ + ∂f/∂p₁(y), …, J(y)·s_c [+ ∂f/∂p_c(y)]),
//!
//! ∂F/∂z = ⎡ J   0   ⋯  0 ⎤
//!         ⎢ H₁  J   ⋯  0 ⎥      Hⱼ = ∂(J(y)·sⱼ + ∂f/∂pⱼ(y))/∂y,
//!         ⎢ ⋮        ⋱   ⎥
//!         ⎣ H_c 0   ⋯  J ⎦
//!
//! block lower-triangular with J on the diagonal: W = I − γh·∂F/∂z is solved with one
//! factorization of the model's own I − γh·J ([`AugmentedJacobian`]; M − γh·J for a model with
//! a mass matrix, whose sensitivities solve M·sⱼ′ = J·sⱼ + ∂f/∂pⱼ), in exact arithmetic — the
//! structure CVODES's simultaneous corrector rests on. The Hⱼ hold second derivatives of f, which the macro does not
//! generate: they are central differences of the exact J and ∂f/∂p along each component of y,
//! step δₖ = ε^⅓·max(|yₖ|, 1), so accurate to ~ε^⅔ ≈ 4e-11 relative on smooth f and exact
//! (up to rounding) where J is linear in y — mass-action kinetics such as Robertson's. BDF and
//! full-Newton implicit Euler use the Jacobian only to iterate, so their sensitivities are
//! those of the discretisation whatever its error; Rosenbrock methods build it into their
//! stages, where an error of 1e-10 relative is far below any tolerance they are run at.

use nalgebra::DMatrix;

use super::Sensitive;
use crate::linalg::{FactorizeError, NewtonMatrix, SolveError};
use crate::{DenseMatrix, Jacobian, NewtonOptions, Parameters, State};

/// The augmented Jacobian: the model's own J (in the model's matrix type) and the coupling
/// blocks H₁ … H_c below it, row block j of `coupling`.
///
/// W = I − c·∂F/∂z is factorized by factorizing the model's I − c·J alone, and solved by block
/// forward substitution: x₀ = W₀⁻¹b₀, xⱼ = W₀⁻¹(bⱼ + c·Hⱼ·x₀) — one factorization of the model's
/// size however many sensitivities ride along (the reuse CVODES's simultaneous corrector makes).
#[derive(Clone, Debug)]
pub struct AugmentedJacobian<J> {
    jacobian: J,
    coupling: DMatrix<f64>,
}

/// The factors of an [`AugmentedJacobian`]'s W: the model's, and the c they were made with.
#[derive(Clone, Debug)]
pub struct AugmentedFactors<F> {
    factors: F,
    c: f64,
    product: Vec<f64>,
}

impl<J: DenseMatrix> AugmentedJacobian<J> {
    /// Entry (row, column) of ∂F/∂z: J on the diagonal blocks, Hⱼ in the first block column,
    /// zero elsewhere.
    pub fn entry(&self, row: usize, column: usize) -> f64 {
        let n = self.jacobian.dim();
        let (block_row, block_column) = (row / n, column / n);
        if block_row == block_column {
            self.jacobian.entry(row % n, column % n)
        } else if block_column == 0 {
            self.coupling[(row - n, column)]
        } else {
            0.0
        }
    }

    /// Rows (= columns): n·(1 + c).
    pub fn dim(&self) -> usize {
        self.jacobian.dim() + self.coupling.nrows()
    }
}

impl<J: NewtonMatrix + DenseMatrix> NewtonMatrix for AugmentedJacobian<J> {
    type Factors = AugmentedFactors<J::Factors>;

    fn factors(&self) -> Self::Factors {
        AugmentedFactors {
            factors: self.jacobian.factors(),
            c: 0.0,
            product: vec![0.0; self.jacobian.dim()],
        }
    }

    fn factorize(&mut self, c: f64, f: &mut Self::Factors) -> Result<(), FactorizeError> {
        f.c = c;
        self.jacobian.factorize(c, &mut f.factors)
    }

    /// W = M̂ − c·∂F/∂z for the block-diagonal M̂ = diag(M, …, M) of a differential–algebraic
    /// model ([`Sensitive::mass`](crate::Model::mass) lists M's entries once per block, the
    /// model's own first): the model's M − c·J is factorized, and the solve's block forward
    /// substitution is unchanged (the blocks below the diagonal are −c·Hⱼ either way).
    fn factorize_mass(
        &mut self,
        c: f64,
        mass: &[(usize, usize, f64)],
        f: &mut Self::Factors,
    ) -> Result<(), FactorizeError> {
        f.c = c;
        let blocks = self.dim() / self.jacobian.dim().max(1);
        let own = &mass[..mass.len() / blocks.max(1)];
        self.jacobian.factorize_mass(c, own, &mut f.factors)
    }

    fn solve(&mut self, f: &mut Self::Factors, b: &mut [f64]) -> Result<(), SolveError> {
        let n = self.jacobian.dim();
        if b.len() != self.dim() {
            return Err(SolveError::WrongLength {
                expected: self.dim(),
                found: b.len(),
            });
        }
        let (x0, rest) = b.split_at_mut(n);
        self.jacobian.solve(&mut f.factors, x0)?;
        for (block, bj) in rest.chunks_exact_mut(n).enumerate() {
            for (i, p) in f.product.iter_mut().enumerate() {
                let row = self.coupling.row(block * n + i);
                *p = row.iter().zip(x0.iter()).map(|(h, x)| h * x).sum();
            }
            for (b, p) in bj.iter_mut().zip(&f.product) {
                *b += f.c * p;
            }
            self.jacobian.solve(&mut f.factors, bj)?;
        }
        Ok(())
    }

    fn work(&self) -> crate::LinearWork {
        self.jacobian.work()
    }

    fn configure(&mut self, newton: &NewtonOptions, solves: crate::Solves) {
        self.jacobian.configure(newton, solves);
    }

    /// The model's J, then the coupling blocks below it.
    fn non_finite_entry(&self) -> Option<(usize, usize, f64)> {
        if let Some(entry) = self.jacobian.non_finite_entry() {
            return Some(entry);
        }
        let n = self.jacobian.dim();
        (0..self.coupling.ncols())
            .flat_map(|column| (0..self.coupling.nrows()).map(move |row| (row, column)))
            .map(|(row, column)| (row + n, column, self.coupling[(row, column)]))
            .find(|(_, _, value)| !value.is_finite())
    }
}

impl<M> Jacobian for Sensitive<'_, M>
where
    M: Parameters + Jacobian,
    M::Matrix: DenseMatrix,
{
    type Matrix = AugmentedJacobian<M::Matrix>;
    /// Not known at compile time (it depends on the model's pattern and the columns asked for).
    const NONZEROS: &'static [(usize, usize)] = &[];
    const TIME_DEPENDENT: bool = M::TIME_DEPENDENT;

    fn jacobian_matrix(&self, state: &Self::State) -> Self::Matrix {
        let y = self.model.state();
        let n = y.as_slice().len();
        AugmentedJacobian {
            jacobian: self.model.jacobian_matrix(&y),
            coupling: DMatrix::zeros(state.as_slice().len() - n, n),
        }
    }

    fn jacobian(&self, t: f64, z: &Self::State, out: &mut Self::Matrix) {
        let scratch = &mut *self.scratch.borrow_mut();
        let values = z.as_slice();
        let n = scratch.y.as_slice().len();
        let columns = (values.len() - n) / n;
        let parameters = M::NAMES.len();
        self.count(0, 1 + 2 * n as u64, 2 * n as u64);
        scratch.y.as_mut_slice().copy_from_slice(&values[..n]);
        self.model.jacobian(t, &scratch.y, &mut out.jacobian);
        for k in 0..n {
            let yk = values[k];
            let delta = crate::math::Transcendental::cbrt(f64::EPSILON) * yk.abs().max(1.0);
            let (up, down) = (yk + delta, yk - delta);
            scratch.y.as_mut_slice()[k] = up;
            self.model.jacobian(t, &scratch.y, &mut scratch.jacobian);
            self.model
                .parameter_jacobian(t, &scratch.y, &mut scratch.dfdp);
            scratch.y.as_mut_slice()[k] = down;
            self.model
                .jacobian(t, &scratch.y, &mut scratch.jacobian_minus);
            self.model
                .parameter_jacobian(t, &scratch.y, &mut scratch.dfdp_minus);
            scratch.y.as_mut_slice()[k] = yk;
            // The step as represented: (yₖ + δ) − (yₖ − δ) in floating point.
            let width = up - down;
            for c in 0..columns {
                let s = &values[n * (1 + c)..n * (2 + c)];
                for i in 0..n {
                    let mut difference = if c < parameters {
                        scratch.dfdp[(i, c)] - scratch.dfdp_minus[(i, c)]
                    } else {
                        0.0
                    };
                    for (l, sl) in s.iter().enumerate() {
                        difference += (scratch.jacobian.entry(i, l)
                            - scratch.jacobian_minus.entry(i, l))
                            * sl;
                    }
                    out.coupling[(n * c + i, k)] = difference / width;
                }
            }
        }
    }
}
