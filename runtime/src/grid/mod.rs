//! Field models: state that is one or more 2-D grids of values (`u` and `v` of Gray–Scott), a
//! right-hand side written per cell from the cell and its neighbours, and the sparse Jacobian
//! assembled from stencil × grid × boundary.
//!
//! A field model marks its grids `#[field]` (type [`Grid`], all the same size) and writes one
//! `#[cell]` method taking a [`Stencil`] per field it reads, named like the field, and returning
//! the time derivative of every field at the cell — `f64` for one field, `[f64; F]` for F, in
//! declaration order:
//!
//! ```ignore
//! #[cell]
//! fn reaction(&self, u: Stencil, v: Stencil) -> [f64; 2] {
//!     let uvv = u.c * v.c * v.c;
//!     [self.du * u.laplacian() / (self.dx * self.dx) - uvv + self.feed * (1.0 - u.c),
//!      self.dv * v.laplacian() / (self.dx * self.dx) + uvv - (self.feed + self.kill) * v.c]
//! }
//! ```
//!
//! `#[system]` differentiates the method into one block per (output field, input field,
//! neighbour) it reads — [`GridSystem::BLOCKS`] — and the runtime places those blocks for every
//! cell, through each field's [`Boundary`], into a sparse matrix whose pattern and symbolic
//! factorization are made once per run ([`GridJacobian`]). Every integrator runs on field models;
//! the implicit ones solve with sparse Cholesky when I − c·J is symmetric positive definite
//! (diffusion), else sparse LU.
//!
//! Cells are indexed k = j·nx + i, with i along x (east is i + 1) and j along y (north is j + 1).
//!
//! The `#[cell]` method may also take the cell's position and the time, as `f64` arguments named
//! `x`, `y` and `t`: cell (i, j) is at (x₀ + i·Δx, y₀ + j·Δy), from the first field's
//! [`Grid::with_origin`] and [`Grid::with_spacing`] (origin (0, 0) and spacing 1 unless set).
//! A spatial source, a coefficient that varies in space or a forcing switched on at a time are
//! written that way; the position is a parameter of the cell (not differentiated), and a kernel
//! that reads `t` gets its ∂f/∂t generated for the Rosenbrock methods. A coefficient that varies
//! in space may also be a `Grid` field of the model without `#[field]` (a parameter grid of the
//! fields' size, with its own boundary), read through a `Stencil` argument named like it: its
//! values enter the rate but are not differentiated.
//!
//! A `#[field]` also marked `#[algebraic]` is an algebraic grid ([`GridSystem::ALGEBRAIC_FIELDS`]):
//! its rows of the `#[cell]` method are residuals 0 = g, and the model is M·y′ = f with M the
//! identity but zero at its cells. The methods that take a mass matrix factorize M − c·J
//! directly ([`GridJacobian`]), after a consistent start ([`crate::consistent`]).

pub(crate) mod glue;
mod jacobian;
mod state;
mod stencil;

use crate::{Error, Model, Result};

pub use jacobian::GridJacobian;
pub use state::GridState;
pub use stencil::{Block, NEIGHBOURS, Stencil};

/// What a stencil reads beyond the edge of a grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Boundary {
    /// The grid wraps around: east of the last column is the first. Needs at least 3 cells a
    /// side, so that a cell's east and west neighbours differ.
    Periodic,
    /// Zero flux: a read past the edge gives the nearest cell inside (a cell-centred grid
    /// whose ghost cells mirror the edge cells, so the normal gradient is zero).
    Neumann,
    /// A fixed value past the edge: the grid holds the interior nodes of a vertex-centred mesh
    /// whose boundary nodes all have this value.
    Dirichlet(f64),
}

/// One field of a field model: an nx × ny grid of values, its boundary, and where its cells
/// are (an origin and a spacing, read by `#[cell]` methods that take `x` and `y`).
#[derive(Clone, Debug, PartialEq)]
pub struct Grid {
    nx: usize,
    ny: usize,
    boundary: Boundary,
    values: Vec<f64>,
    origin: (f64, f64),
    spacing: (f64, f64),
}

/// Where and when a field model's cell rate is evaluated: the cell's position and the time
/// (what a `#[cell]` method's `x`, `y` and `t` arguments receive).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Place {
    /// x₀ + i·Δx.
    pub x: f64,
    /// y₀ + j·Δy.
    pub y: f64,
    /// The time.
    pub t: f64,
    /// The cell's column (k = j·nx + i).
    pub i: usize,
    /// The cell's row.
    pub j: usize,
}

impl Grid {
    /// A grid of `values`, k = j·nx + i.
    ///
    /// Errors: [`Error::InvalidInput`] when `values` does not have nx·ny entries, a side is 0,
    /// a periodic side has fewer than 3 cells, or a Dirichlet value is not finite.
    pub fn new(nx: usize, ny: usize, boundary: Boundary, values: Vec<f64>) -> Result<Self> {
        let cells = Grid::cells(nx, ny, boundary)?;
        if values.len() != cells {
            return Err(Error::invalid(
                "grid",
                format!(
                    "is {nx}×{ny} = {cells} cells but was given {} values",
                    values.len()
                ),
            ));
        }
        Ok(Grid {
            nx,
            ny,
            boundary,
            values,
            origin: (0.0, 0.0),
            spacing: (1.0, 1.0),
        })
    }

    /// The same grid with cell (0, 0) at (x₀, y₀) (default (0, 0)).
    ///
    /// Errors: [`Error::InvalidInput`] when a coordinate is not finite.
    pub fn with_origin(mut self, x0: f64, y0: f64) -> Result<Self> {
        if !(x0.is_finite() && y0.is_finite()) {
            return Err(Error::invalid(
                "grid origin",
                format!("must be finite, got ({x0}, {y0})"),
            ));
        }
        self.origin = (x0, y0);
        Ok(self)
    }

    /// The same grid with cells Δx apart along x and Δy along y (default 1, 1): cell (i, j) is
    /// at (x₀ + i·Δx, y₀ + j·Δy).
    ///
    /// Errors: [`Error::InvalidInput`] when a spacing is not finite and positive.
    pub fn with_spacing(mut self, dx: f64, dy: f64) -> Result<Self> {
        if !(dx.is_finite() && dx > 0.0 && dy.is_finite() && dy > 0.0) {
            return Err(Error::invalid(
                "grid spacing",
                format!("must be finite and positive, got ({dx}, {dy})"),
            ));
        }
        self.spacing = (dx, dy);
        Ok(self)
    }

    /// The position of cell (0, 0).
    pub fn origin(&self) -> (f64, f64) {
        self.origin
    }

    /// The distance between neighbouring cells along x and along y.
    pub fn spacing(&self) -> (f64, f64) {
        self.spacing
    }

    /// The position of cell (i, j): (x₀ + i·Δx, y₀ + j·Δy).
    pub fn position(&self, i: usize, j: usize) -> (f64, f64) {
        (
            self.origin.0 + i as f64 * self.spacing.0,
            self.origin.1 + j as f64 * self.spacing.1,
        )
    }

    /// A grid whose cell (i, j) holds `value(i, j)`.
    ///
    /// Errors: as [`Grid::new`], and [`Error::InvalidInput`] when the nx·ny values cannot be
    /// allocated.
    pub fn from_fn(
        nx: usize,
        ny: usize,
        boundary: Boundary,
        mut value: impl FnMut(usize, usize) -> f64,
    ) -> Result<Self> {
        let cells = Grid::cells(nx, ny, boundary)?;
        let mut values = Vec::new();
        values.try_reserve_exact(cells).map_err(|_| {
            Error::invalid(
                "grid",
                format!("is {nx}×{ny}; its {cells} values cannot be allocated"),
            )
        })?;
        values.extend(
            (0..ny)
                .flat_map(|j| (0..nx).map(move |i| (i, j)))
                .map(|(i, j)| value(i, j)),
        );
        Grid::new(nx, ny, boundary, values)
    }

    /// The number of cells of an nx × ny grid with `boundary`, once the shape is checked.
    fn cells(nx: usize, ny: usize, boundary: Boundary) -> Result<usize> {
        let invalid = |reason: String| Err(Error::invalid("grid", reason));
        if nx == 0 || ny == 0 {
            return invalid(format!("is {nx}×{ny}; both sides need at least one cell"));
        }
        if boundary == Boundary::Periodic && (nx < 3 || ny < 3) {
            return invalid(format!(
                "is {nx}×{ny} and periodic; a periodic side needs at least 3 cells, or a cell's \
                 east and west neighbours are the same cell"
            ));
        }
        if let Boundary::Dirichlet(value) = boundary
            && !value.is_finite()
        {
            return invalid(format!("has Dirichlet value {value}; it must be finite"));
        }
        // A Vec of f64 holds at most isize::MAX bytes.
        match nx.checked_mul(ny) {
            Some(cells) if cells <= isize::MAX as usize / std::mem::size_of::<f64>() => Ok(cells),
            _ => invalid(format!("is {nx}×{ny}: more cells than any memory holds")),
        }
    }

    /// Cells along x.
    pub fn nx(&self) -> usize {
        self.nx
    }

    /// Cells along y.
    pub fn ny(&self) -> usize {
        self.ny
    }

    /// The boundary.
    pub fn boundary(&self) -> Boundary {
        self.boundary
    }

    /// The values, k = j·nx + i.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The values, mutably (the grid's size cannot change).
    pub fn values_mut(&mut self) -> &mut [f64] {
        &mut self.values
    }
}

/// A field model with F fields, implemented by `#[system]`.
pub trait GridSystem<const F: usize>: Model<State = GridState> {
    /// The fields' names, in declaration order.
    const FIELDS: [&'static str; F];

    /// The structural non-zeros of one cell's Jacobian, in the order
    /// [`GridSystem::cell_jacobian`] writes them (empty with `jacobian = false`).
    const BLOCKS: &'static [Block];

    /// The `#[algebraic]` fields, by their index in [`GridSystem::FIELDS`]: their rows of the
    /// `#[cell]` method are residuals 0 = g rather than rates (empty for an ODE).
    const ALGEBRAIC_FIELDS: &'static [usize] = &[];

    /// The model's grids, in declaration order.
    fn grids(&self) -> [&Grid; F];

    /// The time derivative of every field at a cell whose stencils are `stencils`, at `at`.
    fn cell(&self, stencils: &[Stencil; F], at: Place) -> [f64; F];

    /// The values of [`GridSystem::BLOCKS`] at a cell, into `blocks` (as long as `BLOCKS`).
    fn cell_jacobian(&self, stencils: &[Stencil; F], at: Place, blocks: &mut [f64]);

    /// ∂/∂t of every field's rate at a cell (zero unless the `#[cell]` method reads `t`).
    fn cell_time_derivative(&self, stencils: &[Stencil; F], at: Place) -> [f64; F];
}
