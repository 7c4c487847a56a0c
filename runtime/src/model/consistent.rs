//! Consistent initial values of a differential–algebraic model: Newton on its algebraic
//! equations g(t, y, z) = 0 for the algebraic components z, the differential ones y held.

use nalgebra::{DMatrix, DVector};

use crate::{Error, Jacobian, NewtonMatrix, NewtonOptions, Result, State};

/// Iterations at most: the iteration converges quadratically from a start in reach, and each
/// one may halve its update up to [`HALVINGS`] times, so this is plenty for any start a
/// damped Newton iteration can repair.
const ITERATIONS: usize = 50;
/// Halvings of one Newton update while it does not reduce ‖g‖.
const HALVINGS: usize = 30;

/// Solves g(t, y, z) = 0 for the algebraic components z of `y` (`M::ALGEBRAIC`), the
/// differential ones held, as IDA's `IDACalcIC` with `IDA_YA_YDP_INIT` does: Newton on the
/// block ∂g/∂z of the generated Jacobian, each update halved while it does not reduce the
/// largest |gᵢ| (at most 30 times), until the update is below 10⁻¹⁰ of max(|zᵢ|, ‖y‖∞) (a start that
/// already satisfies g moves by rounding only). The drivers call it before the first step
/// ([`crate::Model::consistent`]) and after an event that changes the state.
///
/// `newton` is unused for now: the iteration's own limits are fixed (50 iterations), so a
/// consistent start does not depend on the options of the method that follows.
///
/// Errors: [`Error::InconsistentStart`] naming the algebraic equation with the largest residual
/// and the algebraic component Newton could not move to zero it (the column where ∂g/∂z is
/// singular: an equation that does not depend on its algebraic components, index 2 or more),
/// or the iteration's failure to converge; [`Error::InvalidInput`] when a copy of the state
/// cannot be allocated.
pub fn consistent<M: Jacobian>(
    model: &M,
    t: f64,
    y: &mut M::State,
    newton: &NewtonOptions,
) -> Result<()> {
    let _ = newton;
    let algebraic = M::ALGEBRAIC;
    let k = algebraic.len();
    if k == 0 {
        return Ok(());
    }
    let mut f = y.try_clone()?;
    let mut trial = y.try_clone()?;
    let mut jacobian = model.jacobian_matrix(y);
    let mut block = DMatrix::<f64>::zeros(k, k);
    let mut g = DVector::<f64>::zeros(k);
    let inconsistent = |y: &M::State, g: &DVector<f64>, column: usize, reason: &'static str| {
        let (row, value) = largest(g);
        Error::InconsistentStart {
            t,
            residual: y.component_name(algebraic[row]),
            value,
            component: y.component_name(algebraic[column]),
            reason,
        }
    };
    residual(model, t, y, &mut f, &mut g);
    for _ in 0..ITERATIONS {
        if !g.iter().all(|r| r.is_finite()) {
            let (row, _) = largest(&g);
            return Err(inconsistent(y, &g, row, "a residual is not finite there"));
        }
        if g.iter().all(|&r| r == 0.0) {
            return Ok(());
        }
        model.jacobian(t, y, &mut jacobian);
        for (a, &i) in algebraic.iter().enumerate() {
            for (b, &j) in algebraic.iter().enumerate() {
                block[(a, b)] = jacobian.dense_entry(i, j).unwrap_or(f64::NAN);
            }
        }
        if let Some(bad) = block.iter().position(|v| !v.is_finite()) {
            return Err(inconsistent(y, &g, bad / k, "∂g/∂z is not finite there"));
        }
        let lu = block.clone().lu();
        let u = lu.u();
        if let Some(column) = (0..k).find(|&i| u[(i, i)] == 0.0) {
            return Err(inconsistent(
                y,
                &g,
                column,
                "∂g/∂z is singular: the equation does not determine the component (index 2 or \
                 more, or a constraint on the differential components alone)",
            ));
        }
        let Some(update) = lu.solve(&(-&g)) else {
            return Err(inconsistent(y, &g, 0, "∂g/∂z is singular"));
        };
        // Damped: halve the update while it does not reduce the largest residual.
        let before = largest(&g).1;
        let mut scale = 1.0;
        let mut g_trial = g.clone();
        let mut reduced = false;
        for _ in 0..=HALVINGS {
            trial.clone_from(y);
            for (a, &i) in algebraic.iter().enumerate() {
                trial.as_mut_slice()[i] += scale * update[a];
            }
            residual(model, t, &trial, &mut f, &mut g_trial);
            if largest(&g_trial).1 < before {
                reduced = true;
                break;
            }
            scale *= 0.5;
        }
        // The update relative to the component, or to the state's largest component for one
        // near zero.
        let whole = y.as_slice().iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let step = algebraic
            .iter()
            .enumerate()
            .map(|(a, &i)| {
                let scale = y.as_slice()[i].abs().max(whole).max(f64::MIN_POSITIVE);
                (update[a] / scale).abs()
            })
            .fold(0.0, f64::max);
        if !reduced {
            // At the rounding of g: the full update is below the resolution of z.
            if step <= 1e-10 {
                return Ok(());
            }
            let (row, _) = largest(&g);
            return Err(inconsistent(
                y,
                &g,
                row,
                "Newton's updates do not reduce the residual (no solution near the start)",
            ));
        }
        y.clone_from(&trial);
        g.copy_from(&g_trial);
        if scale == 1.0 && step <= 1e-10 {
            return Ok(());
        }
    }
    let (row, _) = largest(&g);
    Err(inconsistent(
        y,
        &g,
        row,
        "Newton did not converge in 50 iterations",
    ))
}

/// gᵢ = f(t, y) at the algebraic components.
fn residual<M: Jacobian>(model: &M, t: f64, y: &M::State, f: &mut M::State, g: &mut DVector<f64>) {
    model.derivative(t, y, f);
    for (a, &i) in M::ALGEBRAIC.iter().enumerate() {
        g[a] = f.as_slice()[i];
    }
}

/// The index and |value| of the largest |gᵢ| (NaN counts as largest).
fn largest(g: &DVector<f64>) -> (usize, f64) {
    g.iter()
        .map(|r| r.abs())
        .enumerate()
        .fold((0, -1.0), |(bi, bv), (i, v)| {
            if v > bv || v.is_nan() && !bv.is_nan() {
                (i, v)
            } else {
                (bi, bv)
            }
        })
}
