//! Consistent initial values of a differential–algebraic model: Newton on its algebraic
//! equations g(t, y, z) = 0 for the algebraic components z, the differential ones y held.

use nalgebra::{DMatrix, DVector};

use crate::linalg::sparse::SparseSolver;
use crate::{Error, Jacobian, NewtonMatrix, NewtonOptions, Result, State};

/// Iterations at most: the iteration converges quadratically from a start in reach, and each
/// one may halve its update up to [`HALVINGS`] times, so this is plenty for any start a
/// damped Newton iteration can repair.
const ITERATIONS: usize = 50;
/// Halvings of one Newton update while it does not reduce ‖g‖.
const HALVINGS: usize = 30;
/// Algebraic components up to which ∂g/∂z is solved dense (LU with partial pivoting, which names
/// the column where it is singular); beyond, sparse (a field model's algebraic grids: 65 536
/// components on a 256² grid would be a 34 GB dense block).
const DENSE_UP_TO: usize = 256;

/// Solves g(t, y, z) = 0 for the algebraic components z of `y` (`M::ALGEBRAIC`), the
/// differential ones held, as IDA's `IDACalcIC` with `IDA_YA_YDP_INIT` does: Newton on the
/// block ∂g/∂z of the generated Jacobian, each update halved while it does not reduce the
/// largest |gᵢ| (at most 30 times), until the update is below 10⁻¹⁰ of max(|zᵢ|, 10⁻⁶·‖y‖∞) (a
/// start that already satisfies g moves by rounding only). The drivers call it before the first step
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
    consistent_components(model, t, y, M::ALGEBRAIC)
}

/// [`consistent`] for the algebraic components `algebraic` (sorted, in the state's layout): a
/// field model's, which depend on its grids' size.
pub(crate) fn consistent_components<M: Jacobian>(
    model: &M,
    t: f64,
    y: &mut M::State,
    algebraic: &[usize],
) -> Result<()> {
    let k = algebraic.len();
    if k == 0 {
        return Ok(());
    }
    let mut f = y.try_clone()?;
    let mut trial = y.try_clone()?;
    let mut jacobian = model.jacobian_matrix(y);
    let mut block = Block::new(k);
    let mut entries = Vec::new();
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
    residual(model, t, y, algebraic, &mut f, &mut g);
    let singular = "∂g/∂z is singular: the equation does not determine the component (index 2 \
                    or more, or a constraint on the differential components alone)";
    for iteration in 0..ITERATIONS {
        if !g.iter().all(|r| r.is_finite()) {
            let (row, _) = largest(&g);
            return Err(inconsistent(y, &g, row, "a residual is not finite there"));
        }
        model.jacobian(t, y, &mut jacobian);
        entries.clear();
        jacobian.entries_among(algebraic, &mut entries);
        if let Some(&(bad, _, _)) = entries.iter().find(|e| !e.2.is_finite()) {
            return Err(inconsistent(y, &g, bad, "∂g/∂z is not finite there"));
        }
        if iteration == 0
            && let Err(column) = regular(&mut block, &entries, k)
        {
            // ∂g/∂z must be regular at the start, consistent or not: else no step can be
            // solved with M − c·J.
            let column = column.unwrap_or_else(|| largest(&g).0);
            return Err(inconsistent(y, &g, column, singular));
        }
        if g.iter().all(|&r| r == 0.0) {
            return Ok(());
        }
        let mut update = -&g;
        if let Err(column) = block.solve(&entries, update.as_mut_slice()) {
            let column = column.unwrap_or_else(|| largest(&g).0);
            return Err(inconsistent(y, &g, column, singular));
        }
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
            residual(model, t, &trial, algebraic, &mut f, &mut g_trial);
            if largest(&g_trial).1 < before {
                reduced = true;
                break;
            }
            scale *= 0.5;
        }
        // The largest update relative to a scale of its component: `floor` of the state's
        // largest component at least.
        let whole = y.as_slice().iter().fold(0.0, |m: f64, v| m.max(v.abs()));
        let step = |floor: f64| {
            algebraic
                .iter()
                .enumerate()
                .map(|(a, &i)| {
                    let scale = y.as_slice()[i].abs().max(floor).max(f64::MIN_POSITIVE);
                    (update[a] / scale).abs()
                })
                .fold(0.0, f64::max)
        };
        if !reduced {
            // At the rounding of g: the full update is below the resolution of z, whose
            // values are computed from the whole state's.
            if step(whole) <= 1e-10 {
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
        // Converged: the update is small against the component itself, or against a
        // millionth of the state's largest for a component near 0 — never against the largest
        // alone, which a huge differential component elsewhere (1e12) would make every update
        // look converged.
        let converged = scale == 1.0 && step(1e-6 * whole) <= 1e-10;
        y.clone_from(&trial);
        g.copy_from(&g_trial);
        if converged {
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

/// Whether the k × k block of `entries` is regular: solved, equilibrated (each row, then each
/// column, divided by its largest |entry|), with every right-hand side 1, a block singular to
/// rounding blows the solution past 10¹⁴ (its LU's last pivot is rounding noise), while
/// equations or components in units far apart (a row of 1e-15 F beside rows of order 1) do not.
///
/// Errors: singular, with the column of a zero pivot or of no non-zero entry when known.
fn regular(
    block: &mut Block,
    entries: &[(usize, usize, f64)],
    k: usize,
) -> Result<(), Option<usize>> {
    let mut rows = vec![0.0f64; k];
    for &(i, _, v) in entries {
        rows[i] = rows[i].max(v.abs());
    }
    let mut columns = vec![0.0f64; k];
    for &(i, j, v) in entries {
        if rows[i] > 0.0 {
            columns[j] = columns[j].max((v / rows[i]).abs());
        }
    }
    if let Some(j) = columns.iter().position(|&c| c == 0.0) {
        return Err(Some(j));
    }
    if rows.contains(&0.0) {
        return Err(None);
    }
    let scaled: Vec<(usize, usize, f64)> = entries
        .iter()
        .map(|&(i, j, v)| (i, j, v / rows[i] / columns[j]))
        .collect();
    let mut probe = vec![1.0; k];
    block.solve(&scaled, &mut probe)?;
    match probe.iter().fold(0.0, |m: f64, x| m.max(x.abs())) <= 1e14 {
        true => Ok(()),
        false => Err(None),
    }
}

/// gᵢ = f(t, y) at the `algebraic` components.
fn residual<M: Jacobian>(
    model: &M,
    t: f64,
    y: &M::State,
    algebraic: &[usize],
    f: &mut M::State,
    g: &mut DVector<f64>,
) {
    model.derivative(t, y, f);
    for (a, &i) in algebraic.iter().enumerate() {
        g[a] = f.as_slice()[i];
    }
}

/// The k × k block ∂g/∂z and its solve: dense up to [`DENSE_UP_TO`] components, sparse (its
/// pattern taken from the first evaluation's entries) beyond.
enum Block {
    Dense(DMatrix<f64>),
    Sparse(Option<Box<SparseSolver>>),
}

impl Block {
    fn new(k: usize) -> Self {
        match k <= DENSE_UP_TO {
            true => Block::Dense(DMatrix::zeros(k, k)),
            false => Block::Sparse(None),
        }
    }

    /// Solves ∂g/∂z·x = b in place, the block given by its `entries` (row, column, value) in
    /// the algebraic components' order. Errors: the block is singular, with the column of the
    /// zero pivot when the dense solve finds one.
    fn solve(
        &mut self,
        entries: &[(usize, usize, f64)],
        b: &mut [f64],
    ) -> Result<(), Option<usize>> {
        let k = b.len();
        match self {
            Block::Dense(block) => {
                block.fill(0.0);
                for &(i, j, v) in entries {
                    block[(i, j)] += v;
                }
                let lu = block.clone().lu();
                let u = lu.u();
                if let Some(column) = (0..k).find(|&i| u[(i, i)] == 0.0) {
                    return Err(Some(column));
                }
                let mut x = DVector::from_column_slice(b);
                if !lu.solve_mut(&mut x) {
                    return Err(None);
                }
                b.copy_from_slice(x.as_slice());
            }
            Block::Sparse(solver) => {
                // The pattern of the first evaluation: the generated Jacobian's structure,
                // which later evaluations share (an entry outside it would be a new one).
                let solver = solver.get_or_insert_with(|| {
                    let pattern: Vec<(usize, usize)> =
                        entries.iter().map(|&(i, j, _)| (i, j)).collect();
                    Box::new(SparseSolver::new(k, &pattern))
                });
                solver.values.fill(0.0);
                for &(i, j, v) in entries {
                    let slot = solver.slot(i, j);
                    solver.values[slot] += v;
                }
                // A singular block names its first column without a non-zero (a component no
                // equation reads), if it has one.
                let empty_column =
                    || (0..k).find(|&j| entries.iter().all(|&(_, c, v)| c != j || v == 0.0));
                solver.factorize().map_err(|_| empty_column())?;
                solver.rhs.copy_from_slice(b);
                solver.substitute().map_err(|_| empty_column())?;
                b.copy_from_slice(&solver.rhs);
                if !b.iter().all(|x| x.is_finite()) {
                    return Err(empty_column());
                }
            }
        }
        match b.iter().all(|x| x.is_finite()) {
            true => Ok(()),
            false => Err(None),
        }
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
