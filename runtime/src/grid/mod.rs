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

mod jacobian;

use std::fmt;

use crate::{Error, Model, Result, State};

pub use jacobian::GridJacobian;

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

/// The stencil of a coefficient grid (a parameter `Grid` a `#[cell]` method reads through a
/// `Stencil`) at the cell of `at`, through the grid's own boundary. Generated code calls it;
/// `Model::check` has made sure the grid has the fields' size.
#[doc(hidden)]
#[inline(always)]
pub fn coefficient(grid: &Grid, at: Place) -> Stencil {
    stencil_at(&grid.values, grid.nx, grid.ny, grid.boundary, at.i, at.j)
}

/// [`Model::check`] of a coefficient grid: the size of the state's grids.
#[doc(hidden)]
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

/// A cell and its eight neighbours in one field, as a `#[cell]` method reads them: `c` the
/// cell, `e`/`w` east and west (i ± 1), `n`/`s` north and south (j ± 1), and the diagonals.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Stencil {
    /// The cell (i, j).
    pub c: f64,
    /// (i + 1, j).
    pub e: f64,
    /// (i − 1, j).
    pub w: f64,
    /// (i, j + 1).
    pub n: f64,
    /// (i, j − 1).
    pub s: f64,
    /// (i + 1, j + 1).
    pub ne: f64,
    /// (i − 1, j + 1).
    pub nw: f64,
    /// (i + 1, j − 1).
    pub se: f64,
    /// (i − 1, j − 1).
    pub sw: f64,
}

impl Stencil {
    /// The five-point Laplacian times the squared spacing, e + w + n + s − 4c: divide by dx² for
    /// ∇²u to second order.
    #[inline(always)]
    pub fn laplacian(&self) -> f64 {
        self.e + self.w + self.n + self.s - 4.0 * self.c
    }
}

/// The neighbours of a [`Stencil`] in the order of [`Block::neighbour`], with their offsets
/// (di, dj).
pub const NEIGHBOURS: [(&str, isize, isize); 9] = [
    ("c", 0, 0),
    ("e", 1, 0),
    ("w", -1, 0),
    ("n", 0, 1),
    ("s", 0, -1),
    ("ne", 1, 1),
    ("nw", -1, 1),
    ("se", 1, -1),
    ("sw", -1, -1),
];

/// One structural non-zero of a cell's Jacobian: ∂(output field `row` at the cell)/∂(field
/// `column` at neighbour `neighbour`, an index into [`NEIGHBOURS`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Block {
    /// The output field.
    pub row: usize,
    /// The input field.
    pub column: usize,
    /// The neighbour, an index into [`NEIGHBOURS`].
    pub neighbour: usize,
}

/// The state of a field model: every field's values, one field after another.
#[derive(PartialEq)]
pub struct GridState {
    values: Vec<f64>,
    nx: usize,
    ny: usize,
    names: &'static [&'static str],
}

impl GridState {
    /// The state of a model's grids (their sizes checked by [`Model::check`]).
    #[doc(hidden)]
    pub fn from_grids(grids: &[&Grid], names: &'static [&'static str]) -> Self {
        let (nx, ny) = grids.first().map_or((0, 0), |g| (g.nx, g.ny));
        GridState {
            values: grids
                .iter()
                .flat_map(|g| g.values.iter().copied())
                .collect(),
            nx,
            ny,
            names,
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

    /// Number of fields.
    pub fn fields(&self) -> usize {
        self.names.len()
    }

    /// The values of field `k` (declaration order), k = j·nx + i; empty past the last field.
    pub fn field(&self, k: usize) -> &[f64] {
        let n = self.nx * self.ny;
        self.values.get(k * n..(k + 1) * n).unwrap_or(&[])
    }

    /// The values of field `k`, mutably; empty past the last field.
    pub fn field_mut(&mut self, k: usize) -> &mut [f64] {
        let n = self.nx * self.ny;
        self.values.get_mut(k * n..(k + 1) * n).unwrap_or(&mut [])
    }

    /// The values of the field called `name`, if there is one.
    pub fn by_name(&self, name: &str) -> Option<&[f64]> {
        let k = self.names.iter().position(|n| *n == name)?;
        Some(self.field(k))
    }
}

impl fmt::Debug for GridState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("GridState")
            .field("nx", &self.nx)
            .field("ny", &self.ny)
            .field("fields", &self.names)
            .finish_non_exhaustive()
    }
}

impl State for GridState {
    #[inline(always)]
    fn as_slice(&self) -> &[f64] {
        &self.values
    }

    #[inline(always)]
    fn as_mut_slice(&mut self) -> &mut [f64] {
        &mut self.values
    }

    fn component_name(&self, index: usize) -> String {
        let n = (self.nx * self.ny).max(1);
        let name = self.names.get(index / n).copied().unwrap_or("?");
        let k = index % n;
        format!("{name}[{},{}]", k % self.nx.max(1), k / self.nx.max(1))
    }

    /// A copy whose values are reserved with `try_reserve_exact`.
    ///
    /// Errors: [`Error::InvalidInput`] (field `grid`) giving the grid's size when the copy cannot
    /// be allocated.
    fn try_clone(&self) -> Result<Self> {
        let mut values = Vec::new();
        if values.try_reserve_exact(self.values.len()).is_err() {
            let fields = self.names.len();
            let what = format!(
                "is {}×{} with {fields} field{}",
                self.nx,
                self.ny,
                if fields == 1 { "" } else { "s" }
            );
            return Err(Error::copy_refused(
                "grid",
                what,
                self.values.len(),
                "a coarser grid",
            ));
        }
        values.extend_from_slice(&self.values);
        Ok(GridState { values, ..*self })
    }
}

impl Clone for GridState {
    fn clone(&self) -> Self {
        GridState {
            values: self.values.clone(),
            ..*self
        }
    }

    /// Reuses the buffer: the integrators copy states every step and must not allocate.
    fn clone_from(&mut self, source: &Self) {
        self.values.clone_from(&source.values);
        (self.nx, self.ny, self.names) = (source.nx, source.ny, source.names);
    }
}

/// A field model with F fields, implemented by `#[system]`.
pub trait GridSystem<const F: usize>: Model<State = GridState> {
    /// The fields' names, in declaration order.
    const FIELDS: [&'static str; F];

    /// The structural non-zeros of one cell's Jacobian, in the order
    /// [`GridSystem::cell_jacobian`] writes them (empty with `jacobian = false`).
    const BLOCKS: &'static [Block];

    /// The model's grids, in declaration order.
    fn grids(&self) -> [&Grid; F];

    /// The time derivative of every field at a cell whose stencils are `stencils`, at `at`.
    fn cell(&self, stencils: &[Stencil; F], at: Place) -> [f64; F];

    /// The values of [`GridSystem::BLOCKS`] at a cell, into `blocks` (as long as `BLOCKS`).
    fn cell_jacobian(&self, stencils: &[Stencil; F], at: Place, blocks: &mut [f64]);

    /// ∂/∂t of every field's rate at a cell (zero unless the `#[cell]` method reads `t`).
    fn cell_time_derivative(&self, stencils: &[Stencil; F], at: Place) -> [f64; F];
}

/// The index of cell (i + di, j + dj) of an nx × ny grid with `boundary` (|di|, |dj| ≤ 1),
/// `None` for a read of a Dirichlet value.
#[inline]
fn neighbour(
    nx: usize,
    ny: usize,
    boundary: Boundary,
    i: usize,
    j: usize,
    di: isize,
    dj: isize,
) -> Option<usize> {
    let (x, y) = (i as isize + di, j as isize + dj);
    let (w, h) = (nx as isize, ny as isize);
    // Offsets are at most one cell, so a wrap is one add or subtract (rem_euclid's integer
    // division made edge cells several times dearer than interior ones).
    let wrap = |x: isize, w: isize| {
        if x < 0 {
            x + w
        } else if x >= w {
            x - w
        } else {
            x
        }
    };
    let (x, y) = match boundary {
        Boundary::Periodic => (wrap(x, w), wrap(y, h)),
        Boundary::Neumann => (x.clamp(0, w - 1), y.clamp(0, h - 1)),
        Boundary::Dirichlet(_) if x < 0 || y < 0 || x >= w || y >= h => return None,
        Boundary::Dirichlet(_) => (x, y),
    };
    Some(y as usize * nx + x as usize)
}

/// The stencil of cell (i, j) in `values` through `boundary`, for any cell.
#[inline]
fn stencil_at(
    values: &[f64],
    nx: usize,
    ny: usize,
    boundary: Boundary,
    i: usize,
    j: usize,
) -> Stencil {
    let read = |(_, di, dj): (&str, isize, isize)| match neighbour(nx, ny, boundary, i, j, di, dj) {
        Some(k) => values[k],
        None => match boundary {
            Boundary::Dirichlet(value) => value,
            _ => 0.0,
        },
    };
    let [c, e, w, n, s, ne, nw, se, sw] = NEIGHBOURS.map(read);
    Stencil {
        c,
        e,
        w,
        n,
        s,
        ne,
        nw,
        se,
        sw,
    }
}

/// The stencil of interior cell k = j·nx + i of `values` (0 < i < nx − 1, 0 < j < ny − 1).
///
/// # Safety
/// `values` must hold at least (j + 2)·nx values and i, j must be interior as stated, so every
/// index k ± 1, k ± nx, k ± nx ± 1 is in bounds.
#[inline(always)]
unsafe fn interior(values: &[f64], nx: usize, k: usize) -> Stencil {
    debug_assert!(k > nx && k + nx + 1 < values.len());
    // SAFETY: the caller guarantees every index is in bounds. Checked indexing here kept nine
    // bounds checks per field and cell, which also kept the loads of neighbours a kernel never
    // reads alive: the rate of a 256² Gray–Scott grid took 3.3× a hand-written loop.
    unsafe {
        let at = |k: usize| *values.get_unchecked(k);
        Stencil {
            c: at(k),
            e: at(k + 1),
            w: at(k - 1),
            n: at(k + nx),
            s: at(k - nx),
            ne: at(k + nx + 1),
            nw: at(k + nx - 1),
            se: at(k - nx + 1),
            sw: at(k - nx - 1),
        }
    }
}

/// Calls `visit(k, i, j, stencils)` for every cell k = j·nx + i of `y`, interior cells by direct
/// reads and edge cells through their fields' boundaries.
#[inline]
fn for_each_cell<const F: usize>(
    y: &GridState,
    boundaries: [Boundary; F],
    mut visit: impl FnMut(usize, usize, usize, &[Stencil; F]),
) {
    let (nx, ny) = (y.nx, y.ny);
    let fields: [&[f64]; F] = std::array::from_fn(|f| y.field(f));
    let edge = |i: usize, j: usize| -> [Stencil; F] {
        std::array::from_fn(|f| stencil_at(fields[f], nx, ny, boundaries[f], i, j))
    };
    let whole = fields.iter().all(|f| f.len() == nx * ny);
    for j in 0..ny {
        if !(whole && j > 0 && j + 1 < ny && nx > 2) {
            for i in 0..nx {
                visit(j * nx + i, i, j, &edge(i, j));
            }
            continue;
        }
        visit(j * nx, 0, j, &edge(0, j));
        for i in 1..nx - 1 {
            let k = j * nx + i;
            // SAFETY: row j is interior (0 < j < ny − 1) and so is every k here (0 < i < nx − 1);
            // every field holds nx·ny values (`whole`).
            let stencils = std::array::from_fn(|f| unsafe { interior(fields[f], nx, k) });
            visit(k, i, j, &stencils);
        }
        visit((j + 1) * nx - 1, nx - 1, j, &edge(nx - 1, j));
    }
}

/// Each grid's boundary, in field order.
fn boundaries<M: GridSystem<F>, const F: usize>(model: &M) -> [Boundary; F] {
    model.grids().map(Grid::boundary)
}

/// Where cell (i, j) is at time t, for a first grid of this origin and spacing.
#[inline(always)]
fn place((origin, spacing): ((f64, f64), (f64, f64)), t: f64, i: usize, j: usize) -> Place {
    Place {
        x: origin.0 + i as f64 * spacing.0,
        y: origin.1 + j as f64 * spacing.1,
        t,
        i,
        j,
    }
}

/// The origin and spacing of `model`'s first grid (every grid shares them: [`check`]).
#[inline(always)]
fn geometry<M: GridSystem<F>, const F: usize>(model: &M) -> ((f64, f64), (f64, f64)) {
    model
        .grids()
        .first()
        .map_or(((0.0, 0.0), (1.0, 1.0)), |g| (g.origin, g.spacing))
}

/// Writes `rate(stencils, place)` of every cell into `out`, field by field.
#[inline(always)]
fn each_cell_into<M: GridSystem<F>, const F: usize>(
    model: &M,
    t: f64,
    y: &GridState,
    out: &mut GridState,
    rate: impl Fn(&[Stencil; F], Place) -> [f64; F],
) {
    let n = y.nx * y.ny;
    let geometry = geometry(model);
    let mut chunks = out.values.chunks_exact_mut(n.max(1));
    let mut out: [&mut [f64]; F] = std::array::from_fn(|_| chunks.next().unwrap_or_default());
    for_each_cell(y, boundaries(model), |k, i, j, stencils| {
        let values = rate(stencils, place(geometry, t, i, j));
        for (out, value) in out.iter_mut().zip(values) {
            if let Some(slot) = out.get_mut(k) {
                *slot = value;
            }
        }
    });
}

/// [`Model::derivative`] of a field model: the `#[cell]` method at every cell.
#[doc(hidden)]
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
#[doc(hidden)]
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
#[doc(hidden)]
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
#[doc(hidden)]
pub fn jacobian_matrix<M: GridSystem<F>, const F: usize>(
    model: &M,
    state: &GridState,
) -> GridJacobian {
    GridJacobian::new(state.nx, state.ny, &boundaries(model), M::BLOCKS)
}

/// [`Model::check`] of a field model: every grid the same size, and the state that size.
#[doc(hidden)]
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
