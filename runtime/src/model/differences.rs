//! A Jacobian by central differences of the model's own f: what
//! `#[system(jacobian = finite_differences)]` generates for a fixed-size model whose code the
//! macro cannot differentiate, so the implicit methods still run it.

use super::Model;
use crate::State;

/// Writes ∂f/∂y at (t, y), entry by entry, to `entry(row, column, value)`.
///
/// Column j is (f(y + hⱼeⱼ) − f(y − hⱼeⱼ)) / (2hⱼ) with hⱼ = ε^⅓·max(1, |yⱼ|), the step that
/// balances the central difference's truncation error O(h²) against rounding O(ε/h) (Nocedal &
/// Wright, *Numerical Optimization*, 2nd ed., 2006, §8.1): about 1e-10 relative on smooth f,
/// at 2n evaluations of f. The step taken is the one the perturbed components represent
/// exactly, (yⱼ + hⱼ) − (yⱼ − hⱼ), so it adds no rounding of its own. Allocation-free: a
/// fixed-size state is `Copy`.
pub fn central_differences<M>(
    model: &M,
    t: f64,
    y: &M::State,
    mut entry: impl FnMut(usize, usize, f64),
) where
    M: Model,
    M::State: Copy,
{
    let h0 = crate::math::Transcendental::cbrt(f64::EPSILON);
    let (mut plus, mut minus) = (*y, *y);
    let (mut f_plus, mut f_minus) = (*y, *y);
    let n = y.as_slice().len();
    for column in 0..n {
        let yj = y.as_slice()[column];
        let h = h0 * yj.abs().max(1.0);
        plus.as_mut_slice()[column] = yj + h;
        minus.as_mut_slice()[column] = yj - h;
        let width = plus.as_slice()[column] - minus.as_slice()[column];
        model.derivative(t, &plus, &mut f_plus);
        model.derivative(t, &minus, &mut f_minus);
        for (row, (p, m)) in f_plus.as_slice().iter().zip(f_minus.as_slice()).enumerate() {
            entry(row, column, (p - m) / width);
        }
        plus.as_mut_slice()[column] = yj;
        minus.as_mut_slice()[column] = yj;
    }
}
