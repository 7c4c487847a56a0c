//! Implicit viscous diffusion: I − νΔt·L on each velocity component, no-slip at the walls.

use super::{FluidOptions, StableFluids};
use crate::Result;
use crate::linalg::spd::SpdSolver;

impl StableFluids {
    /// Solves (I − νΔt·L)·u = u for each velocity component, no-slip at the walls.
    pub(super) fn diffuse(&mut self, dt: f64) -> Result<()> {
        let FluidOptions {
            nx,
            ny,
            cell: h,
            viscosity,
            ..
        } = self.options;
        if self
            .diffusion
            .as_ref()
            .is_none_or(|(last, _, _)| *last != dt)
        {
            let k = diffusion_number(viscosity, h, dt);
            let u = SpdSolver::new((nx - 1) * ny, &diffusion_entries(nx - 1, ny, k))?;
            let v = SpdSolver::new(nx * (ny - 1), &diffusion_entries_transposed(nx, ny - 1, k))?;
            self.diffusion = Some((dt, u, v));
        }
        let Some((_, solve_u, solve_v)) = &mut self.diffusion else {
            return Ok(());
        };
        let rhs = &mut self.rhs;
        rhs.clear();
        rhs.extend(
            (0..ny)
                .flat_map(|j| (1..nx).map(move |i| (i, j)))
                .map(|(i, j)| self.u[i + j * (nx + 1)]),
        );
        solve_u.solve_in_place(rhs);
        for (k, value) in rhs.iter().enumerate() {
            let (i, j) = (1 + k % (nx - 1), k / (nx - 1));
            self.u[i + j * (nx + 1)] = *value;
        }
        rhs.clear();
        rhs.extend(
            (1..ny)
                .flat_map(|j| (0..nx).map(move |i| (i, j)))
                .map(|(i, j)| self.v[i + j * nx]),
        );
        solve_v.solve_in_place(rhs);
        for (k, value) in rhs.iter().enumerate() {
            let (i, j) = (k % nx, 1 + k / nx);
            self.v[i + j * nx] = *value;
        }
        Ok(())
    }
}

/// k = ν·Δt/h², formed so that ν·Δt alone cannot overflow (ν/h² is finite, `new` checks), and
/// 0 without viscosity whatever h (h² may underflow to 0).
pub(super) fn diffusion_number(viscosity: f64, h: f64, dt: f64) -> f64 {
    if viscosity == 0.0 {
        return 0.0;
    }
    viscosity / (h * h) * dt
}

/// I − k·L for an mx×my block of unknowns with zero (wall) values just past the x ends and
/// no-slip ghosts (−u) just past the y ends: the u faces.
fn diffusion_entries(mx: usize, my: usize, k: f64) -> Vec<(usize, usize, f64)> {
    let mut entries = Vec::with_capacity(5 * mx * my);
    for j in 0..my {
        for i in 0..mx {
            let c = i + j * mx;
            let mut diagonal = 1.0 + 4.0 * k;
            if i > 0 {
                entries.push((c, c - 1, -k));
            }
            if i + 1 < mx {
                entries.push((c, c + 1, -k));
            }
            for inside in [j > 0, j + 1 < my] {
                if !inside {
                    diagonal += k; // the ghost −u adds k to the diagonal
                }
            }
            if j > 0 {
                entries.push((c, c - mx, -k));
            }
            if j + 1 < my {
                entries.push((c, c + mx, -k));
            }
            entries.push((c, c, diagonal));
        }
    }
    entries
}

/// The same for the v faces: walls just past the y ends, ghosts just past the x ends.
fn diffusion_entries_transposed(mx: usize, my: usize, k: f64) -> Vec<(usize, usize, f64)> {
    let index = |i: usize, j: usize| i + j * mx;
    diffusion_entries(my, mx, k)
        .into_iter()
        .map(|(r, c, v)| {
            let swap = |n: usize| index(n / my, n % my);
            (swap(r), swap(c), v)
        })
        .collect()
}
