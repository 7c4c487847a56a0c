//! What the code `#[system]` generates for a field model calls: the `Model` and `Jacobian`
//! methods of every field model, and the stencils of its coefficient grids. Reached through
//! `odyn::__private::grid`; not a stable API.

use super::stencil::{boundaries, coefficient_at, each_cell_into, for_each_cell, geometry, place};
use super::{Grid, GridJacobian, GridState, GridSystem, Place, Stencil};
use crate::{Error, Mass, Model, NewtonOptions, Result};

/// The stencil of a coefficient grid (a parameter `Grid` a `#[cell]` method reads through a
/// `Stencil`) at the cell of `at`, through the grid's own boundary. Generated code calls it;
/// `Model::check` has made sure the grid has the fields' size.
#[inline(always)]
pub fn coefficient(grid: &Grid, at: Place) -> Stencil {
    coefficient_at(&grid.values, grid.nx, grid.ny, grid.boundary, at.i, at.j)
}

/// [`Model::check`] of a coefficient grid: the size of the state's grids.
pub fn check_coefficient<M: Model>(name: &str, grid: &Grid, state: &GridState) -> Result<()> {
    if (grid.nx, grid.ny) == (state.nx, state.ny) {
        return Ok(());
    }
    Err(Error::BadModel {
        model: M::NAME,
        what: format!("coefficient grid `{name}`"),
        reason: format!(
            "is {}×{} but the model's fields are {}×{}; a coefficient grid is read cell by \
             cell beside them",
            grid.nx, grid.ny, state.nx, state.ny
        ),
    })
}

/// [`Model::derivative`] of a field model: the `#[cell]` method at every cell.
#[inline]
pub fn derivative<M: GridSystem<F>, const F: usize>(
    model: &M,
    t: f64,
    y: &GridState,
    dydt: &mut GridState,
) {
    each_cell_into(model, t, y, dydt, |stencils, at| model.cell(stencils, at));
}

/// [`crate::Jacobian::time_derivative`] of a field model that reads the time: ∂f/∂t at every
/// cell.
#[inline]
pub fn time_derivative<M: GridSystem<F>, const F: usize>(
    model: &M,
    t: f64,
    y: &GridState,
    dfdt: &mut GridState,
) {
    each_cell_into(model, t, y, dfdt, |stencils, at| {
        model.cell_time_derivative(stencils, at)
    });
}

/// [`crate::Jacobian::jacobian`] of a field model: every cell's blocks, placed.
#[inline]
pub fn jacobian<M: GridSystem<F>, const F: usize>(
    model: &M,
    t: f64,
    y: &GridState,
    jacobian: &mut GridJacobian,
) {
    jacobian.begin();
    let geometry = geometry(model);
    for_each_cell(y, boundaries(model), |k, i, j, stencils| {
        let blocks = jacobian.cell_blocks();
        model.cell_jacobian(stencils, place(geometry, t, i, j), blocks);
        jacobian.place(k);
    });
}

/// [`crate::Jacobian::jacobian_matrix`] of a field model.
pub fn jacobian_matrix<M: GridSystem<F>, const F: usize>(
    model: &M,
    state: &GridState,
) -> GridJacobian {
    GridJacobian::new(state.nx, state.ny, &boundaries(model), M::BLOCKS)
}

/// [`Model::check`] of a field model: every grid the same size, and the state that size.
pub fn check<M: GridSystem<F>, const F: usize>(model: &M, state: &GridState) -> Result<()> {
    let bad = |what: String, reason: String| Error::BadModel {
        model: M::NAME,
        what,
        reason,
    };
    let grids = model.grids();
    let Some(first) = grids.first() else {
        return Err(bad("the model".into(), "has no `#[field]` grids".into()));
    };
    for (name, grid) in M::FIELDS.iter().zip(&grids) {
        if (grid.origin, grid.spacing) != (first.origin, first.spacing) {
            return Err(bad(
                format!("`{name}`"),
                format!(
                    "has origin {:?} and spacing {:?} but `{}` has {:?} and {:?}; every field \
                     of a model shares one grid",
                    grid.origin,
                    grid.spacing,
                    M::FIELDS[0],
                    first.origin,
                    first.spacing
                ),
            ));
        }
        if (grid.nx, grid.ny) != (first.nx, first.ny) {
            return Err(bad(
                format!("`{name}`"),
                format!(
                    "is {}×{} but `{}` is {}×{}; every field of a model shares one grid",
                    grid.nx,
                    grid.ny,
                    M::FIELDS[0],
                    first.nx,
                    first.ny
                ),
            ));
        }
    }
    if (state.nx, state.ny, state.values.len()) != (first.nx, first.ny, F * first.nx * first.ny) {
        return Err(bad(
            "the state".into(),
            format!(
                "is {}×{} with {} values; the model's fields are {}×{}, {} values in all",
                state.nx,
                state.ny,
                state.values.len(),
                first.nx,
                first.ny,
                F * first.nx * first.ny
            ),
        ));
    }
    Ok(())
}

/// [`Model::state`](crate::Model::state) of a field model: its grids' values one after another,
/// named `names`.
#[inline]
pub fn state(grids: &[&Grid], names: &'static [&'static str]) -> GridState {
    GridState::from_grids(grids, names)
}

/// The state's components of the `#[algebraic]` fields (field-major: field f's cell k is
/// component f·nx·ny + k).
fn algebraic_components<M: GridSystem<F>, const F: usize>(state: &GridState) -> Vec<usize> {
    let cells = state.nx * state.ny;
    M::ALGEBRAIC_FIELDS
        .iter()
        .flat_map(|&f| f * cells..(f + 1) * cells)
        .collect()
}

/// [`Model::mass`] of a field model with `#[algebraic]` fields: the identity with zeros at
/// their cells.
///
/// Errors: [`Error::BadModel`] when the state is not as large as the model's fields.
pub fn mass<M: GridSystem<F>, const F: usize>(state: &GridState) -> Result<Mass> {
    Mass::identity(
        M::NAME,
        state.values.len(),
        &algebraic_components::<M, F>(state),
    )
}

/// [`Model::consistent`] of a field model with `#[algebraic]` fields: Newton on their cells'
/// residuals, the other fields held ([`crate::consistent`]).
///
/// Errors: [`Error::InconsistentStart`].
pub fn consistent<M: GridSystem<F> + crate::Jacobian, const F: usize>(
    model: &M,
    t: f64,
    y: &mut GridState,
    newton: &NewtonOptions,
) -> Result<()> {
    let _ = newton;
    let algebraic = algebraic_components::<M, F>(y);
    crate::model::consistent::consistent_components(model, t, y, &algebraic)
}
