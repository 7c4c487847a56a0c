//! The algebraic components' sensitivities of a differential–algebraic model, made consistent
//! with the differential ones: the algebraic equations differentiated.

use nalgebra::{DMatrix, DVector};

use crate::{DenseMatrix, Error, Jacobian, Parameters, Result, State};

/// For each sensitivity column sⱼ of `values` (the augmented state: y, then the columns, `n`
/// components each), solves ∂g/∂z·s_z = −(∂g/∂y·s_y + ∂g/∂pⱼ) for the algebraic components z
/// (`M::ALGEBRAIC`), with ∂g/∂(y, z) the rows of `jacobian` and ∂g/∂pⱼ those of `dfdp` (zero for
/// the columns of ∂y/∂y₀) at the consistent state `y`, time `t`: the sensitivities of
/// 0 = g(t, y, z; p). A consistent start (and, by a change event, a consistent state) has them.
///
/// Errors: [`Error::InconsistentStart`] when ∂g/∂z is singular there (which the consistent
/// solve for z itself reports first).
pub(super) fn consistent_sensitivities<M: Parameters + Jacobian>(
    jacobian: &M::Matrix,
    dfdp: &DMatrix<f64>,
    values: &mut [f64],
    n: usize,
    t: f64,
    y: &M::State,
) -> Result<()>
where
    M::Matrix: DenseMatrix,
{
    let algebraic = M::ALGEBRAIC;
    let k = algebraic.len();
    let mut block = DMatrix::<f64>::zeros(k, k);
    for (a, &i) in algebraic.iter().enumerate() {
        for (b, &j) in algebraic.iter().enumerate() {
            block[(a, b)] = jacobian.entry(i, j);
        }
    }
    let lu = block.lu();
    let columns = values.len() / n - 1;
    let parameters = dfdp.ncols();
    let mut rhs = DVector::<f64>::zeros(k);
    for c in 0..columns {
        let s = &mut values[n * (1 + c)..n * (2 + c)];
        for (a, &i) in algebraic.iter().enumerate() {
            let mut sum = if c < parameters { dfdp[(i, c)] } else { 0.0 };
            for (l, sl) in s.iter().enumerate() {
                if !algebraic.contains(&l) {
                    sum += jacobian.entry(i, l) * sl;
                }
            }
            rhs[a] = -sum;
        }
        let Some(solution) = lu.solve(&rhs) else {
            return Err(Error::InconsistentStart {
                t,
                residual: y.component_name(algebraic[0]),
                value: 0.0,
                component: y.component_name(algebraic[0]),
                reason: "∂g/∂z is singular, so the algebraic sensitivities are not determined",
            });
        };
        for (a, &i) in algebraic.iter().enumerate() {
            s[i] = solution[a];
        }
    }
    Ok(())
}
