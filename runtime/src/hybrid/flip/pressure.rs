//! The pressure projection of the FLIP fluid: the Poisson equation on the fluid cells, solved
//! by odyn's own preconditioned conjugate gradient (`linalg::sparse::SparseSolver`, the solver of
//! the implicit methods' Newton matrices).
//!
//! The unknown is r = Δt·p/(ρh) on every interior cell (the solve never sees Δt, ρ or h: see
//! [`crate::fluids::StableFluids`]), so a face's correction is the difference of its cells' r.
//! A fluid cell's row is the graph Laplacian of its non-solid neighbours (Bridson 2015, §5.3):
//! its diagonal counts fluid and air neighbours (an air cell's pressure is 0, the free
//! surface's condition), its off-diagonals are −1 to fluid neighbours (a solid neighbour adds
//! nothing: no flow through the wall); its right-hand side is minus its net outflow. Air and
//! solid cells keep identity rows with zero right-hand sides, so the pattern — every interior
//! cell and its four neighbours — is made and analysed once, and each step only refills values.

use super::mac::{Cell, Mac};
use crate::linalg::krylov::{KrylovOptions, LinearSolver, Preconditioner, Solves, Structure};
use crate::linalg::sparse::SparseSolver;
use crate::{Error, Result};

/// The projection's matrix and solver, kept across steps.
pub(crate) struct Pressure {
    solver: SparseSolver,
    /// Slots in the solver's values of each interior cell's diagonal and its (left, right,
    /// below, above) neighbours (usize::MAX where the neighbour is a border cell).
    slots: Vec<[usize; 5]>,
    /// The solution of the last solve, r per cell (0 outside fluid).
    pub r: Vec<f64>,
    /// The unknown pinned to 0 when no fluid cell meets air.
    pinned: Option<usize>,
}

impl Pressure {
    /// The pattern of an nx × ny grid's interior cells, solved by CG to `tolerance` (relative
    /// residual) with `preconditioner`, warm-started from the previous step's pressure.
    pub fn new(nx: usize, ny: usize, tolerance: f64, preconditioner: Preconditioner) -> Self {
        let (w, h) = (nx - 2, ny - 2);
        let unknown = |i: usize, j: usize| (i - 1) + (j - 1) * w;
        let mut entries = Vec::with_capacity(2 * w * h);
        for j in 1..=h {
            for i in 1..=w {
                if i < w {
                    entries.push((unknown(i, j), unknown(i + 1, j)));
                }
                if j < h {
                    entries.push((unknown(i, j), unknown(i, j + 1)));
                }
            }
        }
        let mut solver = SparseSolver::new(w * h, &entries);
        let krylov = KrylovOptions {
            rtol: tolerance,
            preconditioner,
            ..KrylovOptions::default()
        };
        solver.configure(
            &LinearSolver::Krylov(krylov),
            Structure::Field,
            Solves::OneStep,
        );
        let mut slots = Vec::with_capacity(w * h);
        for j in 1..=h {
            for i in 1..=w {
                let k = unknown(i, j);
                let slot = |inside: bool, other: usize| {
                    if inside {
                        solver.slot(k, other)
                    } else {
                        usize::MAX
                    }
                };
                slots.push([
                    solver.slot(k, k),
                    slot(i > 1, k.wrapping_sub(1)),
                    slot(i < w, k + 1),
                    slot(j > 1, k.wrapping_sub(w)),
                    slot(j < h, k + w),
                ]);
            }
        }
        Pressure {
            solver,
            slots,
            r: vec![0.0; nx * ny],
            pinned: None,
        }
    }

    /// Krylov iterations so far, and the solves that fell back to the direct solver.
    pub fn work(&self) -> (u64, u64) {
        let k = self.solver.counts.krylov;
        (k.iterations, k.fallbacks)
    }

    /// Fills the matrix for the cells of `mac` and prepares its solves (the multigrid
    /// hierarchy's values, or the incomplete factorization).
    ///
    /// Errors: [`Error::InvalidInput`] (field `pressure`) if even the direct factorization
    /// finds the matrix singular (it never is: each fluid region touches air or is pinned).
    pub fn assemble(&mut self, mac: &Mac) -> Result<()> {
        let (nx, ny) = (mac.nx, mac.ny);
        let w = nx - 2;
        let values = &mut self.solver.values;
        values.fill(0.0);
        let mut any_air = false;
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                let slots = self.slots[(i - 1) + (j - 1) * w];
                if mac.cell(i, j) != Cell::Fluid {
                    any_air |= mac.cell(i, j) == Cell::Air;
                    values[slots[0]] = 1.0;
                    continue;
                }
                let neighbours = [(i - 1, j), (i + 1, j), (i, j - 1), (i, j + 1)];
                let mut diagonal = 0.0;
                for (n, &(a, b)) in neighbours.iter().enumerate() {
                    match mac.cell(a, b) {
                        Cell::Solid => {}
                        Cell::Air => diagonal += 1.0,
                        Cell::Fluid => {
                            diagonal += 1.0;
                            values[slots[n + 1]] = -1.0;
                        }
                    }
                }
                values[slots[0]] = diagonal;
            }
        }
        self.pinned = None;
        if !any_air {
            // No free surface: the pressure is fixed only up to a constant. Pin the first
            // fluid cell's to 0 (as the Stable Fluids projection pins cell 0): its row and
            // column become the identity's.
            let first = (0..self.slots.len()).find(|&k| values[self.slots[k][0]] != 1.0);
            if let Some(k) = first {
                let (i, j) = (k % w, k / w);
                let h = ny - 2;
                let neighbours = [
                    (i > 0).then(|| k - 1),
                    (i + 1 < w).then(|| k + 1),
                    (j > 0).then(|| k - w),
                    (j + 1 < h).then(|| k + w),
                ];
                let column: Vec<usize> = neighbours
                    .into_iter()
                    .flatten()
                    .map(|m| self.solver.slot(m, k))
                    .collect();
                let values = &mut self.solver.values;
                for s in self.slots[k][1..].iter().copied().chain(column) {
                    if s != usize::MAX {
                        values[s] = 0.0;
                    }
                }
                values[self.slots[k][0]] = 1.0;
                self.pinned = Some(k);
            }
        }
        self.solver
            .factorize()
            .map_err(|_| Error::invalid("pressure", "the Poisson matrix is singular"))
    }

    /// Solves the assembled matrix for `rhs(i, j)` on the fluid cells (0 elsewhere) and keeps
    /// the solution, per cell of the grid (0 outside the fluid), in [`Pressure::r`].
    ///
    /// Errors: [`Error::InvalidInput`] (field `pressure`) when the solve fails: a right-hand side
    /// so large that it overflows.
    pub fn solve(&mut self, mac: &Mac, rhs: impl Fn(usize, usize) -> f64) -> Result<()> {
        let (nx, ny) = (mac.nx, mac.ny);
        let w = nx - 2;
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                let k = (i - 1) + (j - 1) * w;
                self.solver.rhs[k] = if mac.cell(i, j) == Cell::Fluid && self.pinned != Some(k) {
                    rhs(i, j)
                } else {
                    0.0
                };
            }
        }
        self.solver.substitute().map_err(|error| {
            Error::invalid("pressure", format!("the pressure solve failed: {error}"))
        })?;
        if let Some(k) = self.solver.rhs.iter().position(|r| !r.is_finite()) {
            return Err(Error::invalid(
                "pressure",
                format!(
                    "the pressure solve left cell {k} at {:?}",
                    self.solver.rhs[k]
                ),
            ));
        }
        self.r.fill(0.0);
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                if mac.cell(i, j) == Cell::Fluid {
                    self.r[i + j * nx] = self.solver.rhs[(i - 1) + (j - 1) * w];
                }
            }
        }
        Ok(())
    }

    /// Subtracts the gradient of the last solution from the face values `u` and `v` (laid out
    /// as [`Mac`]'s, on the nx × ny `cells`) on every face beside a fluid cell and not on a wall:
    /// the face between cells a and b (b to the right or above) loses r_b − r_a.
    pub fn subtract_gradient(
        &self,
        cells: &[Cell],
        (nx, ny): (usize, usize),
        u: &mut [[f64; 2]],
        v: &mut [[f64; 2]],
    ) {
        let r = &self.r;
        let fluid = |a: usize, b: usize| cells[a + b * nx] == Cell::Fluid;
        let solid = |a: usize, b: usize| cells[a + b * nx] == Cell::Solid;
        for j in 1..ny - 1 {
            for i in 1..nx {
                if (fluid(i - 1, j) || fluid(i, j)) && !solid(i - 1, j) && !solid(i, j) {
                    u[i + j * (nx + 1)][0] -= r[i + j * nx] - r[i - 1 + j * nx];
                }
            }
        }
        for j in 1..ny {
            for i in 1..nx - 1 {
                if (fluid(i, j - 1) || fluid(i, j)) && !solid(i, j - 1) && !solid(i, j) {
                    v[i + j * nx][0] -= r[i + j * nx] - r[i + (j - 1) * nx];
                }
            }
        }
    }
}
