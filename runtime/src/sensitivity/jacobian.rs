//! The augmented system's Jacobian, for the implicit methods.
//!
//! For z = (y, s₁, …, s_c) and F(z) = (f(y), J(y)·s₁ + ∂f/∂p₁(y), …, J(y)·s_c [+ ∂f/∂p_c(y)]),
//!
//! ∂F/∂z = ⎡ J   0   ⋯  0 ⎤
//!         ⎢ H₁  J   ⋯  0 ⎥      Hⱼ = ∂(J(y)·sⱼ + ∂f/∂pⱼ(y))/∂y,
//!         ⎢ ⋮        ⋱   ⎥
//!         ⎣ H_c 0   ⋯  J ⎦
//!
//! block lower-triangular with J on the diagonal: W = I − γh·∂F/∂z is solved by one
//! factorization of I − γh·J per block row in exact arithmetic (CVODES's simultaneous corrector
//! rests on the same structure). The Hⱼ hold second derivatives of f, which the macro does not
//! generate: they are central differences of the exact J and ∂f/∂p along each component of y,
//! step δₖ = ε^⅓·max(|yₖ|, 1), so accurate to ~ε^⅔ ≈ 4e-11 relative on smooth f and exact
//! (up to rounding) where J is linear in y — mass-action kinetics such as Robertson's. BDF and
//! full-Newton implicit Euler use the Jacobian only to iterate, so their sensitivities are
//! those of the discretisation whatever its error; Rosenbrock methods build it into their
//! stages, where an error of 1e-10 relative is far below any tolerance they are run at.

use super::Sensitive;
use crate::{DenseMatrix, DynamicDense, Jacobian, Parameters, State};

impl<M> Jacobian for Sensitive<'_, M>
where
    M: Parameters + Jacobian,
    M::Matrix: DenseMatrix,
{
    type Matrix = DynamicDense;
    /// Not known at compile time (it depends on the model's pattern and the columns asked for).
    const NONZEROS: &'static [(usize, usize)] = &[];
    const TIME_DEPENDENT: bool = M::TIME_DEPENDENT;

    fn jacobian_matrix(&self, state: &Self::State) -> DynamicDense {
        DynamicDense::zeros(state.as_slice().len())
    }

    fn jacobian(&self, t: f64, z: &Self::State, out: &mut DynamicDense) {
        let scratch = &mut *self.scratch.borrow_mut();
        let values = z.as_slice();
        let n = scratch.y.as_slice().len();
        let columns = (values.len() - n) / n;
        let parameters = M::NAMES.len();
        out.fill_zero();
        self.count(0, 1 + 2 * n as u64, 2 * n as u64);
        scratch.y.as_mut_slice().copy_from_slice(&values[..n]);
        self.model.jacobian(t, &scratch.y, &mut scratch.jacobian);
        for block in 0..=columns {
            for i in 0..n {
                for k in 0..n {
                    out.set(block * n + i, block * n + k, scratch.jacobian.entry(i, k));
                }
            }
        }
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
                    out.set(n * (1 + c) + i, k, difference / width);
                }
            }
        }
    }
}
