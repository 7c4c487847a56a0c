//! The stencil a `#[cell]` method reads, and the walk over every cell that hands it out
//! through each field's boundary.

use super::{Boundary, Grid, GridState, GridSystem, Place};

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

/// The index of cell (i + di, j + dj) of an nx × ny grid with `boundary` (|di|, |dj| ≤ 1),
/// `None` for a read of a Dirichlet value.
#[inline]
pub(super) fn neighbour(
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
pub(super) fn stencil_at(
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

/// The stencil of cell (i, j) of a coefficient grid's nx·ny `values` (a `Grid`'s, whose length
/// the type guarantees): interior cells by direct reads
/// (as the fields' own cells are read), edge cells through the grid's boundary. Through
/// [`stencil_at`] alone, every cell paid nine boundary-aware lookups: a 96² diffusion reading κ
/// from a grid cost 8× the same κ computed from the position (`benches/coefficients.rs`).
#[inline(always)]
pub(super) fn coefficient_at(
    values: &[f64],
    nx: usize,
    ny: usize,
    boundary: Boundary,
    i: usize,
    j: usize,
) -> Stencil {
    let k = j * nx + i;
    if i > 0 && j > 0 && i + 1 < nx && j + 1 < ny {
        debug_assert_eq!(values.len(), nx * ny);
        // SAFETY: (i, j) is interior, checked just above, and a `Grid` holds nx·ny values (its
        // constructors check it and nothing resizes them), so k ± 1, k ± nx, k ± nx ± 1 are in
        // bounds.
        unsafe { interior(values, nx, k) }
    } else {
        stencil_at(values, nx, ny, boundary, i, j)
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
pub(super) fn for_each_cell<const F: usize>(
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
pub(super) fn boundaries<M: GridSystem<F>, const F: usize>(model: &M) -> [Boundary; F] {
    model.grids().map(Grid::boundary)
}

/// Where cell (i, j) is at time t, for a first grid of this origin and spacing.
#[inline(always)]
pub(super) fn place(
    (origin, spacing): ((f64, f64), (f64, f64)),
    t: f64,
    i: usize,
    j: usize,
) -> Place {
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
pub(super) fn geometry<M: GridSystem<F>, const F: usize>(model: &M) -> ((f64, f64), (f64, f64)) {
    model
        .grids()
        .first()
        .map_or(((0.0, 0.0), (1.0, 1.0)), |g| (g.origin, g.spacing))
}

/// Writes `rate(stencils, place)` of every cell into `out`, field by field.
#[inline(always)]
pub(super) fn each_cell_into<M: GridSystem<F>, const F: usize>(
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
