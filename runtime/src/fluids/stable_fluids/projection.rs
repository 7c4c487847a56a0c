//! The pressure projection: the Poisson solve that removes the velocity's divergence.

use super::{FluidOptions, StableFluids};
use crate::{Error, Result};

impl StableFluids {
    /// Makes the velocity divergence-free, as a step's last stage does: solves L·p = ∇·u/Δt and
    /// subtracts Δt·∇p, then once more on what is left (one step of iterative refinement: the
    /// Cholesky solve alone leaves a divergence of ~1e-10 on a 33² grid, the refined one
    /// ~1e-14). The result does not depend on Δt (only Δt·p enters), so none is taken.
    ///
    /// Errors: [`Error::InvalidInput`] for what [`StableFluids::check`] finds;
    /// [`Error::NotFinite`] (with the steps taken so far and dt = 0) when velocities near
    /// f64::MAX overflow in the solve.
    pub fn project(&mut self) -> Result<()> {
        self.check()?;
        self.remove_divergence();
        self.check_finite(0.0)
    }

    /// The projection on checked fields.
    pub(super) fn remove_divergence(&mut self) {
        self.correct();
        self.correct();
    }

    /// One pressure correction, solved for r = Δt·p/h: the Poisson equation L·p = ∇·u/Δt becomes
    /// A·r = −(net outflow of each cell) with A = −h²·L, the cells' graph Laplacian, and the
    /// update Δt·(p_i − p_{i−1})/h of a face is r_i − r_{i−1}.
    fn correct(&mut self) {
        let (nx, ny) = (self.options.nx, self.options.ny);
        // Unknowns: every cell but cell 0 (r₀ = 0), solved in place.
        outflow_into(&self.u, &self.v, nx, ny, &mut self.potential);
        self.potential.iter_mut().for_each(|d| *d = -*d);
        self.poisson.solve_in_place(&mut self.potential[1..]);
        self.potential[0] = 0.0;
        let r = &self.potential;
        for j in 0..ny {
            for i in 1..nx {
                self.u[i + j * (nx + 1)] -= r[i + j * nx] - r[i - 1 + j * nx];
            }
        }
        for j in 1..ny {
            for i in 0..nx {
                self.v[i + j * nx] -= r[i + j * nx] - r[i + (j - 1) * nx];
            }
        }
    }

    /// The discrete divergence (u_{i+1,j} − u_{i,j} + v_{i,j+1} − v_{i,j})/h of every cell.
    pub fn divergence(&self) -> Vec<f64> {
        let FluidOptions {
            nx, ny, cell: h, ..
        } = self.options;
        let mut divergence = vec![0.0; nx * ny];
        outflow_into(&self.u, &self.v, nx, ny, &mut divergence);
        divergence.iter_mut().for_each(|d| *d /= h);
        divergence
    }
}

/// Writes the net outflow u_{i+1,j} − u_{i,j} + v_{i,j+1} − v_{i,j} of every cell i + j·nx
/// into `out`: h times its divergence.
fn outflow_into(u: &[f64], v: &[f64], nx: usize, ny: usize, out: &mut [f64]) {
    for j in 0..ny {
        for i in 0..nx {
            out[i + j * nx] =
                u[i + 1 + j * (nx + 1)] - u[i + j * (nx + 1)] + v[i + (j + 1) * nx] - v[i + j * nx];
        }
    }
}

/// −h²·L (the 5-point Neumann Laplacian times −h²: the cells' graph Laplacian) on the cells,
/// cell 0 removed: unknown k is cell k + 1.
///
/// Errors: [`Error::InvalidInput`] when the entries cannot be allocated: the first and largest
/// allocation of a fluid, so a grid too big for the machine is an error rather than an abort.
pub(super) fn poisson_entries(nx: usize, ny: usize) -> Result<Vec<(usize, usize, f64)>> {
    let mut entries = Vec::new();
    entries.try_reserve_exact(5 * nx * ny).map_err(|_| {
        Error::invalid(
            "grid",
            format!("{nx}×{ny} cells is more than this machine can allocate"),
        )
    })?;
    for j in 0..ny {
        for i in 0..nx {
            let c = i + j * nx;
            if c == 0 {
                continue;
            }
            let mut neighbours = Vec::with_capacity(4);
            if i > 0 {
                neighbours.push(c - 1);
            }
            if i + 1 < nx {
                neighbours.push(c + 1);
            }
            if j > 0 {
                neighbours.push(c - nx);
            }
            if j + 1 < ny {
                neighbours.push(c + nx);
            }
            entries.push((c - 1, c - 1, neighbours.len() as f64));
            for nb in neighbours.into_iter().filter(|&nb| nb != 0) {
                entries.push((c - 1, nb - 1, -1.0));
            }
        }
    }
    Ok(entries)
}
