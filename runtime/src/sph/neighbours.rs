//! The neighbour search: a uniform grid of cells 2h wide, rebuilt every step.

use nalgebra::Vector2;

use crate::{Error, Result};

/// A uniform grid of square cells, rebuilt by a counting sort every step.
pub(super) struct Grid {
    cell: f64,
    origin: Vector2<f64>,
    dims: (usize, usize),
    /// Start of each cell's particles in `order`, one more than there are cells.
    starts: Vec<usize>,
    order: Vec<usize>,
    /// Scratch of `build`: each point's cell, and the next free slot of each cell.
    cell_of: Vec<usize>,
    next: Vec<usize>,
}

impl Grid {
    pub(super) fn new(cell: f64) -> Grid {
        Grid {
            cell,
            origin: Vector2::zeros(),
            dims: (0, 0),
            starts: Vec::new(),
            order: Vec::new(),
            cell_of: Vec::new(),
            next: Vec::new(),
        }
    }

    fn coordinates(&self, x: Vector2<f64>) -> (usize, usize) {
        let c = (x - self.origin) / self.cell;
        (
            (c.x.max(0.0) as usize).min(self.dims.0 - 1),
            (c.y.max(0.0) as usize).min(self.dims.1 - 1),
        )
    }

    /// Sorts `points` (finite) into the cells of their bounding box.
    ///
    /// Errors: [`Error::InvalidInput`] when that box has more cells than this machine can
    /// allocate (a domain far larger than the spacing).
    pub(super) fn build(&mut self, points: &[Vector2<f64>]) -> Result<()> {
        let (lo, hi) = points.iter().fold(
            (
                Vector2::repeat(f64::INFINITY),
                Vector2::repeat(f64::NEG_INFINITY),
            ),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        let cell = self.cell;
        // Cells along an extent; `as` would saturate, so a count past usize::MAX (or ∞) is
        // refused here.
        let side = |extent: f64| {
            let whole = (extent / cell).floor();
            (whole < usize::MAX as f64).then(|| whole as usize + 1)
        };
        let too_many = || {
            Error::invalid(
                "domain",
                format!(
                    "the particles span {:e} × {:e}: more cells of the neighbour grid ({cell:e} \
                     wide) than this machine can allocate; use a larger spacing or a smaller box",
                    hi.x - lo.x,
                    hi.y - lo.y
                ),
            )
        };
        let (Some(nx), Some(ny)) = (side(hi.x - lo.x), side(hi.y - lo.y)) else {
            return Err(too_many());
        };
        // One start more than there are cells, so their count must be below usize::MAX.
        let cells = nx
            .checked_mul(ny)
            .filter(|&cells| cells < usize::MAX)
            .ok_or_else(too_many)?;
        self.origin = lo;
        self.dims = (nx, ny);
        self.starts.clear();
        self.starts
            .try_reserve_exact(cells + 1)
            .map_err(|_| too_many())?;
        self.starts.resize(cells + 1, 0);
        self.cell_of.clear();
        for p in points {
            let (i, j) = self.coordinates(*p);
            self.cell_of.push(i + j * self.dims.0);
        }
        for &c in &self.cell_of {
            self.starts[c + 1] += 1;
        }
        for c in 0..cells {
            self.starts[c + 1] += self.starts[c];
        }
        self.next.clone_from(&self.starts);
        self.order.resize(points.len(), 0);
        for (p, &c) in self.cell_of.iter().enumerate() {
            self.order[self.next[c]] = p;
            self.next[c] += 1;
        }
        Ok(())
    }

    /// Calls `visit` with every point in the 3×3 cells around `x`.
    pub(super) fn neighbours(&self, x: Vector2<f64>, mut visit: impl FnMut(usize)) {
        let (ci, cj) = self.coordinates(x);
        for j in cj.saturating_sub(1)..=(cj + 1).min(self.dims.1 - 1) {
            for i in ci.saturating_sub(1)..=(ci + 1).min(self.dims.0 - 1) {
                let c = i + j * self.dims.0;
                for &p in &self.order[self.starts[c]..self.starts[c + 1]] {
                    visit(p);
                }
            }
        }
    }
}
