//! The volume correction of the FLIP fluid: particles that have bunched are moved apart, by
//! positions only (Kugelstadt, Longva, Thuerey & Bender, "Implicit Density Projection for
//! Volume Conserving Liquids", IEEE TVCG 2019).
//!
//! A cell whose particle density ρ (in units of the sampling's, [`Flip::density`]) exceeds 1
//! holds (ρ − 1)·h² too much liquid. The correction finds the displacement field d = −∇φ whose
//! net outflow from every fluid cell is that excess times the `volume_correction` share,
//! L·φ = share·(ρ − 1)₊·h — the projection's own matrix, so one more Krylov solve with the
//! preconditioner already built — and moves each particle by d interpolated at it. Cells short
//! of particles are left alone: at the surface that is what a surface is.

use nalgebra::Vector2;

use super::Flip;
use super::mac::{Cell, Mac};
use crate::Result;
use crate::hybrid::bspline::Stencil;

impl Flip {
    /// Computes the displacement faces `mac.du`, `mac.dv` for this step (zero when the
    /// correction is off), after the velocity projection assembled the step's matrix.
    pub(super) fn correct_volume(&mut self) -> Result<()> {
        let share = self.options.volume_correction;
        self.mac.du.fill([0.0; 2]);
        self.mac.dv.fill([0.0; 2]);
        if share == 0.0 {
            return Ok(());
        }
        let h = self.options.cell;
        let sampling = self.options.sampling;
        cell_density(&self.x, h, sampling, self.mac.nx, &mut self.mac.density);
        let Mac { nx, ny, .. } = self.mac;
        let density = &self.mac.density;
        let mac = &self.mac;
        self.pressure.solve(mac, |i, j| {
            let excess = density[i + j * nx] - 1.0;
            // Inside the liquid (every neighbour fluid) a deficit is a gap to close; at the
            // surface it is the surface.
            let inside =
                (j - 1..=j + 1).all(|b| (i - 1..=i + 1).all(|a| mac.cell(a, b) == Cell::Fluid));
            share * if inside { excess } else { excess.max(0.0) } * h
        })?;
        let Mac { du, dv, cells, .. } = &mut self.mac;
        self.pressure.subtract_gradient(cells, (nx, ny), du, dv);
        Ok(())
    }
}

/// The particle density of every cell (i + j·nx) into `out`: Σₚ N(xₚ − x_c)/sampling²,
/// quadratic B-splines about the cell's centre. A particle outside the fluid's room (which a
/// step refuses, but `x` is public and [`Flip::density`](super::Flip::density) may be asked
/// before one) adds nothing: inside it, every stencil is on the grid.
pub(super) fn cell_density(
    x: &[Vector2<f64>],
    h: f64,
    sampling: usize,
    nx: usize,
    out: &mut [f64],
) {
    let share = 1.0 / (sampling * sampling) as f64;
    // x·(1/h), as `Flip::inside_room` judges positions: x/h may round past the last cell.
    let inv_h = 1.0 / h;
    let (last_x, last_y) = ((nx - 1) as f64, (out.len() / nx - 1) as f64);
    out.fill(0.0);
    for x in x {
        let (cx, cy) = (x.x * inv_h, x.y * inv_h);
        if !(cx >= 1.0 && cx < last_x && cy >= 1.0 && cy < last_y) {
            continue;
        }
        let s = Stencil::at([cx - 0.5, cy - 0.5]);
        for j in 0..3 {
            let row = s.base[0] + (s.base[1] + j) * nx;
            for i in 0..3 {
                out[row + i] += s.w[0][i] * s.w[1][j] * share;
            }
        }
    }
}
