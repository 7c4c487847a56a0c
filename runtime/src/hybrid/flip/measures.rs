//! What a FLIP run is checked by: the surge front, the area the liquid fills, its particle
//! density, its kinetic energy and the divergence the projection left.

use nalgebra::Vector2;

use super::Flip;
use super::mac::Cell;
use super::volume::cell_density;

impl Flip {
    /// The surge front: how far from the left wall (x = h) the liquid runs along the floor —
    /// the largest x − h of the particles within two particle spacings of the floor (y = h), as
    /// dam-break experiments measure it.
    pub fn front(&self) -> f64 {
        let h = self.options.cell;
        let floor = h + 2.0 * h / self.options.sampling as f64;
        self.x
            .iter()
            .filter(|x| x.y < floor)
            .fold(0.0, |m, x| m.max(x.x - h))
    }

    /// The particle density of every cell (i + j·nx), in units of the density the blocks are
    /// sampled at: Σₚ N(xₚ − x_c)·s²/h², quadratic B-splines about the cell's centre, s the
    /// particle spacing. 1 inside liquid at rest, falling to 0 across the surface; above 1
    /// where particles bunch, below where they part.
    pub fn density(&self) -> Vec<f64> {
        let (nx, ny) = (self.options.nx, self.options.ny);
        let mut density = vec![0.0; nx * ny];
        cell_density(
            &self.x,
            self.options.cell,
            self.options.sampling,
            nx,
            &mut density,
        );
        density
    }

    /// The area the liquid fills (m²): h² times the cells whose [`Flip::density`] is at least ½
    /// (the surface where the density crosses half). A block fills exactly its own area at the
    /// start; particles that bunch (FLIP's volume loss) or part (its gain) change it.
    pub fn filled_area(&self) -> f64 {
        let h = self.options.cell;
        self.density().iter().filter(|&&d| d >= 0.5).count() as f64 * h * h
    }

    /// Kinetic energy per unit density and depth: ½·Σ |vₚ|²·s², s the particle spacing
    /// (m⁴/s²; multiply by ρ for J/m).
    pub fn kinetic_energy(&self) -> f64 {
        let s = self.options.cell / self.options.sampling as f64;
        0.5 * s * s * self.v.iter().map(|v| v.norm_squared()).sum::<f64>()
    }

    /// The mean particle velocity.
    pub fn mean_velocity(&self) -> Vector2<f64> {
        if self.v.is_empty() {
            return Vector2::zeros();
        }
        self.v.iter().sum::<Vector2<f64>>() / self.v.len() as f64
    }

    /// The largest |∇·u|·h of a fluid cell on the grid after the last step (its net outflow,
    /// m/s): what the projection leaves, the solve's tolerance times the divergence it removed.
    pub fn largest_outflow(&self) -> f64 {
        let (nx, ny) = (self.options.nx, self.options.ny);
        let mac = &self.mac;
        let mut largest: f64 = 0.0;
        for j in 1..ny - 1 {
            for i in 1..nx - 1 {
                if mac.cell(i, j) == Cell::Fluid {
                    let outflow = mac.u[i + 1 + j * (nx + 1)][0] - mac.u[i + j * (nx + 1)][0]
                        + mac.v[i + (j + 1) * nx][0]
                        - mac.v[i + j * nx][0];
                    largest = largest.max(outflow.abs());
                }
            }
        }
        largest
    }
}
