//! Stable Fluids (Stam 1999) on a staggered grid.

use crate::linalg::spd::SpdSolver;
use crate::{Error, Result};

/// The grid and the fluid's constants: plain data with a [`Default`].
#[derive(Clone, Debug, PartialEq)]
pub struct FluidOptions {
    /// Cells across (x), at least 3.
    pub nx: usize,
    /// Cells up (y), at least 3.
    pub ny: usize,
    /// Cell size h (the domain is nx·h by ny·h), finite and positive.
    pub cell: f64,
    /// Kinematic viscosity ν ≥ 0 (0 skips the diffusion solve); ν/h² must be finite.
    pub viscosity: f64,
    /// Upward acceleration per unit smoke density (a plume's buoyancy).
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
    fn check_finite(&self, dt: f64) -> Result<()> {
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

    /// Solves (I − νΔt·L)·u = u for each velocity component, no-slip at the walls.
    fn diffuse(&mut self, dt: f64) -> Result<()> {
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
    fn remove_divergence(&mut self) {
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

/// k = ν·Δt/h², formed so that ν·Δt alone cannot overflow (ν/h² is finite, `new` checks), and
/// 0 without viscosity whatever h (h² may underflow to 0).
fn diffusion_number(viscosity: f64, h: f64, dt: f64) -> f64 {
    if viscosity == 0.0 {
        return 0.0;
    }
    viscosity / (h * h) * dt
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

/// −h²·L (the 5-point Neumann Laplacian times −h²: the cells' graph Laplacian) on the cells,
/// cell 0 removed: unknown k is cell k + 1.
///
/// Errors: [`Error::InvalidInput`] when the entries cannot be allocated: the first and largest
/// allocation of a fluid, so a grid too big for the machine is an error rather than an abort.
fn poisson_entries(nx: usize, ny: usize) -> Result<Vec<(usize, usize, f64)>> {
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
