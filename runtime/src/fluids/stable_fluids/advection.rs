//! Semi-Lagrangian advection on the staggered grid: each sample point is traced back along
//! the flow and the field interpolated there.

use super::{FluidOptions, StableFluids};

impl StableFluids {
    /// Advects u, v and the smoke through the velocity they had before: each face or cell
    /// centre is traced back by dt with a midpoint step, clamped to the box, and the field
    /// sampled there bilinearly.
    pub(super) fn advect(&mut self, dt: f64) {
        let FluidOptions {
            nx, ny, cell: h, ..
        } = self.options;
        let [u0, v0, s0] = &mut self.before;
        u0.clone_from(&self.u);
        v0.clone_from(&self.v);
        s0.clone_from(&self.density);
        let (u0, v0, s0) = (&*u0, &*v0, &*s0);
        let velocity = |x: f64, y: f64| {
            (
                sample(u0, nx + 1, ny, 0.0, 0.5, x, y, h),
                sample(v0, nx, ny + 1, 0.5, 0.0, x, y, h),
            )
        };
        let (width, height) = (nx as f64 * h, ny as f64 * h);
        let back = |x: f64, y: f64| {
            let (a, b) = velocity(x, y);
            let (mx, my) = (x - 0.5 * dt * a, y - 0.5 * dt * b);
            let (a, b) = velocity(mx, my);
            (
                (x - dt * a).clamp(0.0, width),
                (y - dt * b).clamp(0.0, height),
            )
        };
        for j in 0..ny {
            for i in 1..nx {
                let (x, y) = back(i as f64 * h, (j as f64 + 0.5) * h);
                self.u[i + j * (nx + 1)] = sample(u0, nx + 1, ny, 0.0, 0.5, x, y, h);
            }
        }
        for j in 1..ny {
            for i in 0..nx {
                let (x, y) = back((i as f64 + 0.5) * h, j as f64 * h);
                self.v[i + j * nx] = sample(v0, nx, ny + 1, 0.5, 0.0, x, y, h);
            }
        }
        for j in 0..ny {
            for i in 0..nx {
                let (x, y) = back((i as f64 + 0.5) * h, (j as f64 + 0.5) * h);
                self.density[i + j * nx] = sample(s0, nx, ny, 0.5, 0.5, x, y, h);
            }
        }
    }
}

/// Bilinear interpolation of a grid whose point (i, j) sits at ((i + ox)h, (j + oy)h), clamped
/// to the grid.
#[allow(
    clippy::too_many_arguments,
    reason = "a grid, its offset and a point: all needed"
)]
fn sample(f: &[f64], w: usize, hgt: usize, ox: f64, oy: f64, x: f64, y: f64, h: f64) -> f64 {
    let fx = (x / h - ox).clamp(0.0, (w - 1) as f64);
    let fy = (y / h - oy).clamp(0.0, (hgt - 1) as f64);
    let (i, j) = ((fx as usize).min(w - 2), (fy as usize).min(hgt - 2));
    let (a, b) = (fx - i as f64, fy - j as f64);
    let at = |i: usize, j: usize| f[i + j * w];
    (1.0 - a) * (1.0 - b) * at(i, j)
        + a * (1.0 - b) * at(i + 1, j)
        + (1.0 - a) * b * at(i, j + 1)
        + a * b * at(i + 1, j + 1)
}
