//! Stable Fluids (Stam 1999) on a staggered grid.

mod advection;
mod diffusion;
mod projection;

use crate::linalg::spd::SpdSolver;
use crate::{Error, Result};

use diffusion::diffusion_number;
use projection::poisson_entries;

/// The grid and the fluid's constants: plain data with a [`Default`].
#[derive(Clone, Debug, PartialEq)]
pub struct FluidOptions {
    /// Cells across (x), at least 3 (default 64).
    pub nx: usize,
    /// Cells up (y), at least 3 (default 64).
    pub ny: usize,
    /// Cell size h, in length units (the domain is nx·h by ny·h), finite and positive (default
    /// 1/64).
    pub cell: f64,
    /// Kinematic viscosity ν ≥ 0, in length²/time (0 skips the diffusion solve; default 0);
    /// ν/h² must be finite.
    pub viscosity: f64,
    /// Upward acceleration per unit smoke density, in length/time² (a plume's buoyancy; default
    /// 0).
    pub buoyancy: f64,
}

impl Default for FluidOptions {
    fn default() -> Self {
        FluidOptions {
            nx: 64,
            ny: 64,
            cell: 1.0 / 64.0,
            viscosity: 0.0,
            buoyancy: 0.0,
        }
    }
}

/// An incompressible fluid in a closed box, with a passive smoke density, stepped by Stam's
/// Stable Fluids: forces, semi-Lagrangian advection, implicit diffusion, pressure projection.
///
/// The grid is staggered (MAC, Harlow & Welch 1965): `u` lives on the vertical faces
/// ((nx + 1)·ny values, face (i, j) at x = i·h, y = (j + ½)h), `v` on the horizontal faces
/// (nx·(ny + 1), at ((i + ½)h, j·h)), pressure and `density` at the cell centres. The walls are
/// solid: the normal velocity on the boundary faces (`u` at i = 0 and nx, `v` at j = 0 and ny)
/// must be zero — [`StableFluids::check`] refuses a field that sets one, since no pressure can
/// remove flow through a wall — and the tangential velocity is no-slip in the diffusion solve.
///
/// - **Advection** traces each sample point back along the flow with a second-order
///   (midpoint) step and interpolates bilinearly: unconditionally stable, at any CFL number,
///   and never creates new extrema.
/// - **Diffusion** solves (I − νΔt·L)·u = u* (implicit Euler), stable for any νΔt.
/// - **Projection** solves the Poisson equation L·p = ∇·u/Δt (Neumann walls; the pressure of
///   cell 0 fixed at 0 to remove the constant null space) and subtracts Δt·∇p, then repeats the
///   solve once on the remainder, so the discrete divergence of every cell is zero to rounding
///   (≤ 1e-10 is tested). It is solved for r = Δt·p/h, in which neither Δt nor h is left: the
///   matrix is the cells' graph Laplacian and the right-hand side each cell's net outflow, so
///   any step and cell size project exactly (1/Δt and 1/h² once overflowed).
///
/// Both matrices are SPD and factorized by faer's sparse Cholesky: the Poisson matrix once per
/// grid, the diffusion matrices once per distinct Δt.
///
/// Reference: J. Stam, "Stable Fluids", SIGGRAPH 1999, 121–128; R. Bridson, *Fluid Simulation
/// for Computer Graphics*, 2nd ed., 2015, chapters 2–5 (MAC grid and projection).
pub struct StableFluids {
    options: FluidOptions,
    /// Horizontal velocity on the vertical faces, index i + j·(nx + 1).
    pub u: Vec<f64>,
    /// Vertical velocity on the horizontal faces, index i + j·nx.
    pub v: Vec<f64>,
    /// Smoke density at the cell centres, index i + j·nx.
    pub density: Vec<f64>,
    /// r = Δt·p/h at the cell centres, the projection's unknown.
    potential: Vec<f64>,
    /// The fields before advection (u, v, density), kept so a step allocates nothing.
    before: [Vec<f64>; 3],
    /// Right-hand sides of the diffusion solves.
    rhs: Vec<f64>,
    poisson: SpdSolver,
    /// (Δt, u solver, v solver) of the last diffusion.
    diffusion: Option<(f64, SpdSolver, SpdSolver)>,
    /// Steps taken and the time they covered, to name the step that fails.
    steps: u64,
    t: f64,
}

impl StableFluids {
    /// A fluid at rest with no smoke; builds and factorizes the Poisson matrix.
    ///
    /// Errors: [`Error::InvalidInput`] for a grid under 3×3 cells or of more cells than memory
    /// holds, a cell size that is not finite and positive, a negative or non-finite viscosity, a
    /// viscosity whose ν/h² overflows (a positive viscosity with a cell below about 1e-154), or
    /// a non-finite buoyancy.
    pub fn new(options: FluidOptions) -> Result<StableFluids> {
        let FluidOptions {
            nx,
            ny,
            cell,
            viscosity,
            buoyancy,
        } = options;
        if nx < 3 || ny < 3 {
            return Err(Error::invalid(
                "grid",
                format!("{nx}×{ny} cells is too small; at least 3×3"),
            ));
        }
        let faces = nx
            .checked_add(1)
            .zip(ny.checked_add(1))
            .and_then(|(a, b)| a.checked_mul(b));
        if faces.is_none_or(|n| n > isize::MAX as usize / std::mem::size_of::<f64>()) {
            return Err(Error::invalid(
                "grid",
                format!("{nx}×{ny} cells is more than any memory holds"),
            ));
        }
        if !(cell.is_finite() && cell > 0.0) {
            return Err(Error::invalid(
                "cell",
                format!("must be finite and positive, got {cell:?}"),
            ));
        }
        if !(viscosity.is_finite() && viscosity >= 0.0) {
            return Err(Error::invalid(
                "viscosity",
                format!("must be finite and ≥ 0, got {viscosity:?}"),
            ));
        }
        if viscosity > 0.0 && !(viscosity / (cell * cell)).is_finite() {
            return Err(Error::invalid(
                "viscosity",
                format!(
                    "{viscosity:?}/cell² overflows at a cell size of {cell:?}, and the \
                     diffusion solve needs ν·dt/cell²; measure lengths in a larger unit"
                ),
            ));
        }
        if !buoyancy.is_finite() {
            return Err(Error::invalid(
                "buoyancy",
                format!("must be finite, got {buoyancy:?}"),
            ));
        }
        let poisson = SpdSolver::new(nx * ny - 1, &poisson_entries(nx, ny)?)?;
        Ok(StableFluids {
            u: vec![0.0; (nx + 1) * ny],
            v: vec![0.0; nx * (ny + 1)],
            density: vec![0.0; nx * ny],
            potential: vec![0.0; nx * ny],
            before: [Vec::new(), Vec::new(), Vec::new()],
            rhs: Vec::with_capacity((nx * ny).max((nx + 1) * ny)),
            poisson,
            diffusion: None,
            steps: 0,
            t: 0.0,
            options,
        })
    }

    /// The grid and constants.
    pub fn options(&self) -> &FluidOptions {
        &self.options
    }

    /// One step of size `dt`: buoyancy, advection of velocity and smoke, diffusion, projection.
    ///
    /// Errors, before the step: [`Error::InvalidInput`] for a `dt` that is not finite and
    /// positive or whose ν·dt/h² exceeds 1e300, or what [`StableFluids::check`] finds. After it:
    /// [`Error::NotFinite`] when the step left a velocity or density NaN or infinite (a buoyancy
    /// or a step so large that the velocity overflows); the fields are then those of the failed
    /// step.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::invalid(
                "dt",
                format!("must be finite and positive, got {dt:?}"),
            ));
        }
        let FluidOptions {
            nx,
            ny,
            cell: h,
            viscosity,
            buoyancy,
        } = self.options;
        // The diffusion matrix holds up to 1 + 5k on its diagonal: kept far below f64::MAX for
        // the sums of its Cholesky factorization.
        if diffusion_number(viscosity, h, dt) > 1e300 {
            return Err(Error::invalid(
                "dt",
                format!(
                    "viscosity·dt/cell² = {:e} is more than the diffusion solve holds (1e300); \
                     take shorter steps",
                    diffusion_number(viscosity, h, dt)
                ),
            ));
        }
        self.check()?;
        // Buoyancy on the interior horizontal faces, from the two cells they separate.
        if buoyancy != 0.0 {
            for j in 1..ny {
                for i in 0..nx {
                    let s = 0.5 * (self.density[i + (j - 1) * nx] + self.density[i + j * nx]);
                    self.v[i + j * nx] += dt * buoyancy * s;
                }
            }
        }
        self.advect(dt);
        if viscosity > 0.0 {
            self.diffuse(dt)?;
        }
        self.remove_divergence();
        self.steps += 1;
        self.t += dt;
        self.check_finite(dt)
    }

    /// Checks the fields ([`StableFluids::step`] and [`StableFluids::project`] do, each time).
    ///
    /// Errors: [`Error::InvalidInput`] for a velocity or density field that was resized or holds
    /// a value that is not finite (a user-set source gone wrong), or a velocity through a wall
    /// (`u[k]` on a face at i = 0 or nx, `v[k]` at j = 0 or ny) that is not 0.
    pub fn check(&self) -> Result<()> {
        let (nx, ny) = (self.options.nx, self.options.ny);
        let fields = [&self.u, &self.v, &self.density];
        let names = ["u", "v", "density"];
        let sizes = [(nx + 1) * ny, nx * (ny + 1), nx * ny];
        if let Some(k) = (0..3).find(|&k| fields[k].len() != sizes[k]) {
            return Err(Error::invalid(
                names[k],
                format!("must keep its {} values", sizes[k]),
            ));
        }
        for (field, name) in fields.iter().zip(names) {
            if let Some(k) = field.iter().position(|x| !x.is_finite()) {
                return Err(Error::invalid(
                    format!("{name}[{k}]"),
                    format!("{:?} is not finite; write only finite values", field[k]),
                ));
            }
        }
        let through_walls = (0..ny)
            .flat_map(|j| [("left", 0, j), ("right", nx, j)])
            .map(|(wall, i, j)| ("u", wall, i, j, i + j * (nx + 1)))
            .chain(
                (0..nx)
                    .flat_map(|i| [("bottom", i, 0), ("top", i, ny)])
                    .map(|(wall, i, j)| ("v", wall, i, j, i + j * nx)),
            );
        for (name, wall, i, j, k) in through_walls {
            let value = if name == "u" { self.u[k] } else { self.v[k] };
            if value != 0.0 {
                return Err(Error::invalid(
                    format!("{name}[{k}]"),
                    format!(
                        "the face (i = {i}, j = {j}) is on the {wall} wall and holds {value:?}, \
                         but the walls are solid: the velocity through them must be 0; set \
                         flows on the interior faces"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// [`Error::NotFinite`] if the fields hold a NaN or an infinity after step `self.steps`.
    pub(super) fn check_finite(&self, dt: f64) -> Result<()> {
        for (field, name) in [&self.u, &self.v, &self.density]
            .into_iter()
            .zip(["u", "v", "density"])
        {
            if let Some(k) = field.iter().position(|x| !x.is_finite()) {
                return Err(Error::NotFinite {
                    solver: "StableFluids",
                    step: self.steps,
                    t: self.t,
                    dt,
                    component: format!("{name}[{k}]"),
                    value: field[k],
                    advice: "reduce dt or the buoyancy, or the velocities and densities set as \
                             sources",
                });
            }
        }
        Ok(())
    }

    /// The largest face speed |u| or |v|.
    pub fn max_speed(&self) -> f64 {
        self.u
            .iter()
            .chain(&self.v)
            .fold(0.0, |m, x| m.max(x.abs()))
    }

    /// Kinetic energy ½·Σ (u² + v²)·h² over the faces (unit density).
    pub fn kinetic_energy(&self) -> f64 {
        let h = self.options.cell;
        0.5 * h * h * self.u.iter().chain(&self.v).map(|x| x * x).sum::<f64>()
    }
}
