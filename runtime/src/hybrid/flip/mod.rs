//! A FLIP/APIC liquid in 2-D: particles carry the velocity, a MAC grid makes it
//! divergence-free (Zhu & Bridson 2005; Bridson, *Fluid Simulation for Computer Graphics*, 2nd
//! ed., 2015, ch. 7; the APIC transfer of Jiang et al. 2015).
//!
//! One step of Δt:
//!
//! 1. **Particles to grid**: each face of the MAC grid gets the B-spline-weighted mean of the
//!    particles' velocity component (under APIC, each particle's affine velocity Cₚ·(xᵢ − xₚ)
//!    too) — the same quadratic B-splines and deterministic parallel scatter as MPM, once for
//!    the u faces and once for the v faces.
//! 2. **Cells**: the border ring is solid; a cell holding a particle is fluid; the rest is air.
//! 3. **Forces and walls**: gravity on every face; zero velocity through the walls.
//! 4. **Projection**: the pressure that makes every fluid cell's outflow zero, by odyn's
//!    preconditioned conjugate gradient (`pressure.rs`), with p = 0 in the air; velocity is
//!    then extrapolated two faces into the air.
//! 5. **Grid to particles**: APIC, vₚ = Σ wᵢₚvᵢ and Cₚ = 4/h²·Σ wᵢₚvᵢ(xᵢ − xₚ)ᵀ; or the PIC/FLIP
//!    blend, vₚ ← flip·(vₚ + Σ wᵢₚΔvᵢ) + (1 − flip)·Σ wᵢₚvᵢ ([`Transfer`]).
//! 6. **Advection**: each particle moves through the grid's divergence-free velocity by the
//!    midpoint rule (Bridson's recommended second-order Runge–Kutta), and is pushed back out of
//!    the walls if it entered them.
//!
//! The fluid's mass is its particle count (never changed); its volume is kept only as well as
//! the particles stay evenly spread, which [`Flip::filled_area`] measures
//! (`tests/continua/flip.rs`). Bit-identical on any thread count, like MPM.

mod bodies;
mod mac;
mod measures;
mod particles;
mod pressure;
mod volume;

use nalgebra::{Matrix2, Vector2};

use super::strips::{Strips, parallel};
use super::transfer::Transfer;
use crate::{Error, Preconditioner, Result};
use mac::{Cell, Mac};
use pressure::Pressure;

/// The most cells a grid may have: 2²⁰ (1024²).
pub const MAX_CELLS: usize = 1 << 20;

/// The grid, the transfer and the pressure solve: plain data with a [`Default`].
#[derive(Clone, Debug, PartialEq)]
pub struct FlipOptions {
    /// Cells across, the solid border ring included (default 66: 64 of fluid room).
    pub nx: usize,
    /// Cells up, the border included (default 34).
    pub ny: usize,
    /// Cell size h (m; default 1/64).
    pub cell: f64,
    /// Gravity (m/s²; default (0, −9.81)).
    pub gravity: Vector2<f64>,
    /// The velocity transfer (default a blend of 0.95 FLIP, Bridson's suggestion for liquids;
    /// [`Transfer::Apic`] and [`Transfer::PIC`] are the others).
    pub transfer: Transfer,
    /// Relative residual at which the pressure solve stops (default 10⁻⁸).
    pub tolerance: f64,
    /// The pressure solve's preconditioner (default [`Preconditioner::Multigrid`], odyn's
    /// aggregation multigrid; [`Preconditioner::Ilu0`], incomplete Cholesky on the Poisson
    /// matrix, is the MIC(0) of Bridson's book without its modification).
    pub preconditioner: Preconditioner,
    /// Particles along each side of a cell in blocks made by [`Flip::add_block`] (default 2).
    pub sampling: usize,
    /// The share of each fluid cell's excess particle density the step removes by moving
    /// particles apart, in [0, 1] (default 1; 0 turns the correction off). The displacement is
    /// −∇φ with Lφ = the excess, a second solve with the projection's matrix, applied to the
    /// positions only, so it adds no velocity: the implicit density projection of Kugelstadt,
    /// Longva, Thuerey & Bender (IEEE TVCG 2019) with the step's cells. Without it, the
    /// particles of a dam break bunch until the liquid fills 70 % of its area after 4 s
    /// (`tests/continua/flip.rs`).
    pub volume_correction: f64,
}

impl Default for FlipOptions {
    fn default() -> Self {
        FlipOptions {
            nx: 66,
            ny: 34,
            cell: 1.0 / 64.0,
            gravity: Vector2::new(0.0, -9.81),
            transfer: Transfer::Blend { flip: 0.95 },
            tolerance: 1e-8,
            preconditioner: Preconditioner::Multigrid,
            sampling: 2,
            volume_correction: 1.0,
        }
    }
}

/// A 2-D FLIP/APIC liquid in a box with solid walls (the border ring of cells).
pub struct Flip {
    options: FlipOptions,
    /// Particle positions (m).
    pub x: Vec<Vector2<f64>>,
    /// Particle velocities (m/s).
    pub v: Vec<Vector2<f64>>,
    /// APIC's affine velocity: row 0 for u, row 1 for v.
    c: Vec<Matrix2<f64>>,
    mac: Mac,
    pressure: Pressure,
    /// Stencil rows of each particle on the u and the v grid, and their strips.
    rows: [Vec<u32>; 2],
    strips: [Strips; 2],
    steps: u64,
    t: f64,
}

impl Flip {
    /// An empty box; fill it with [`Flip::add_block`] or [`Flip::add_particles`].
    ///
    /// Errors: [`Error::InvalidInput`] for fewer than 4 cells a side or more than [`MAX_CELLS`],
    /// a cell size that is not finite and positive, a gravity that is not finite, a FLIP
    /// fraction outside [0, 1], a tolerance outside (0, 1), a preconditioner other than
    /// block Jacobi, ILU(0) or multigrid (Fourier needs a periodic grid, a reused factorization
    /// a slowly changing matrix), a sampling of 0 or above 16, or a volume correction outside
    /// [0, 1].
    pub fn new(options: FlipOptions) -> Result<Flip> {
        let FlipOptions {
            nx,
            ny,
            cell,
            gravity,
            transfer,
            tolerance,
            preconditioner,
            sampling,
            volume_correction,
        } = options.clone();
        if nx < 4 || ny < 4 {
            return Err(Error::invalid(
                "grid",
                format!("{nx}×{ny} cells is too small; at least 4×4 (the border is solid)"),
            ));
        }
        if nx.checked_mul(ny).is_none_or(|n| n > MAX_CELLS) {
            return Err(Error::invalid(
                "grid",
                format!(
                    "{nx}×{ny} cells is more than the {MAX_CELLS} the pressure solver takes (its \
                     pattern's symbolic Cholesky analysis, made once, grows faster than the grid)"
                ),
            ));
        }
        if !(cell.is_finite() && cell > 0.0) {
            return Err(Error::invalid(
                "cell",
                format!("must be finite and positive, got {cell:?}"),
            ));
        }
        if !gravity.iter().all(|g| g.is_finite()) {
            return Err(Error::invalid(
                "gravity",
                format!("must be finite, got ({:?}, {:?})", gravity.x, gravity.y),
            ));
        }
        transfer.flip()?;
        if !(tolerance > 0.0 && tolerance < 1.0) {
            return Err(Error::invalid(
                "tolerance",
                format!("must be in (0, 1), got {tolerance:?}"),
            ));
        }
        if !matches!(
            preconditioner,
            Preconditioner::BlockJacobi | Preconditioner::Ilu0 | Preconditioner::Multigrid
        ) {
            return Err(Error::invalid(
                "preconditioner",
                format!(
                    "{preconditioner:?} does not fit the pressure solve; choose BlockJacobi, \
                     Ilu0 or Multigrid"
                ),
            ));
        }
        if !(1..=16).contains(&sampling) {
            return Err(Error::invalid(
                "sampling",
                format!("particles per cell side must be 1 to 16, got {sampling}"),
            ));
        }
        if !(0.0..=1.0).contains(&volume_correction) {
            return Err(Error::invalid(
                "volume_correction",
                format!("must be in [0, 1], got {volume_correction:?}"),
            ));
        }
        Ok(Flip {
            mac: Mac::new(nx, ny),
            pressure: Pressure::new(nx, ny, tolerance, preconditioner),
            options,
            x: Vec::new(),
            v: Vec::new(),
            c: Vec::new(),
            rows: [Vec::new(), Vec::new()],
            strips: [Strips::default(), Strips::default()],
            steps: 0,
            t: 0.0,
        })
    }

    /// The settings.
    pub fn options(&self) -> &FlipOptions {
        &self.options
    }

    /// Steps taken, and the time they covered.
    pub fn steps(&self) -> (u64, f64) {
        (self.steps, self.t)
    }

    /// The pressure solves' work so far: conjugate-gradient iterations, and solves that fell
    /// back to the direct (Cholesky) solver.
    pub fn pressure_work(&self) -> (u64, u64) {
        self.pressure.work()
    }

    /// One step of `dt` seconds.
    ///
    /// Errors, before the step (nothing changed): [`Error::InvalidInput`] for a `dt` that is not
    /// finite and positive or above 5 × [`Flip::stable_dt`], position or velocity lists whose
    /// length changed, a particle outside
    /// the fluid's room ([h, (nx − 1)h] × [h, (ny − 1)h], inside the walls) or with a velocity
    /// that is not finite. After it: [`Error::InvalidInput`] (field `pressure`) when the
    /// pressure solve failed, or [`Error::NotFinite`] when a velocity overflowed; the particles
    /// are then as the failed step left them.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::invalid(
                "dt",
                format!("must be finite and positive, got {dt:?}"),
            ));
        }
        // A parallel step runs whole on one of rayon's threads (see `Mpm::step`).
        if parallel(self.x.len()) {
            rayon::scope(|_| self.advance(dt))?;
        } else {
            self.advance(dt)?;
        }
        self.steps += 1;
        self.t += dt;
        if let Some(p) = self.v.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
            return Err(Error::NotFinite {
                solver: "Flip",
                step: self.steps,
                t: self.t,
                dt,
                component: format!("v[{p}]"),
                value: if self.v[p].x.is_finite() {
                    self.v[p].y
                } else {
                    self.v[p].x
                },
                advice: "take shorter steps (see `Flip::stable_dt`)",
            });
        }
        Ok(())
    }

    /// The step's stages after the check of `dt`.
    fn advance(&mut self, dt: f64) -> Result<()> {
        self.check_particles()?;
        let limit = 5.0 * self.stable_dt();
        if dt > limit {
            return Err(Error::invalid(
                "dt",
                format!(
                    "{dt:?} is more than 5 times the stable step (Courant number 5, the most \
                     FLIP's particle advection takes: Bridson 2015, §3.1), {limit:e}"
                ),
            ));
        }
        self.scatter();
        let inv_h = 1.0 / self.options.cell;
        self.mac.classify(
            self.x
                .iter()
                .map(|x| ((x.x * inv_h) as usize, (x.y * inv_h) as usize)),
        );
        self.mac.normalise();
        let g = self.options.gravity;
        self.mac.accelerate([g.x, g.y], dt);
        self.mac.walls();
        self.pressure.assemble(&self.mac)?;
        let Mac { nx, ny, .. } = self.mac;
        let mac = &self.mac;
        self.pressure.solve(mac, |i, j| {
            -(mac.u[i + 1 + j * (nx + 1)][0] - mac.u[i + j * (nx + 1)][0]
                + mac.v[i + (j + 1) * nx][0]
                - mac.v[i + j * nx][0])
        })?;
        let Mac { u, v, cells, .. } = &mut self.mac;
        self.pressure.subtract_gradient(cells, (nx, ny), u, v);
        self.correct_volume()?;
        self.mac.extrapolate(2);
        self.gather(dt);
        Ok(())
    }

    /// Bridson's step bound (2015, §3.1) at a Courant number of 1: h/(max|v| + √(5h|g|)), the
    /// √ term bounding what gravity adds over the step. Infinite when nothing moves and
    /// nothing pulls (an empty box, or liquid at rest without gravity), which [`Flip::step`]
    /// refuses as a step: choose one yourself there.
    pub fn stable_dt(&self) -> f64 {
        let h = self.options.cell;
        let fastest = self.v.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        let speed = fastest + (5.0 * h * self.options.gravity.norm()).sqrt();
        if speed > 0.0 {
            h / speed
        } else {
            f64::INFINITY
        }
    }

    /// The cell labels after the last step: (nx·ny, i + j·nx) 0 solid, 1 fluid, 2 air.
    pub fn cells(&self) -> Vec<u8> {
        self.mac
            .cells
            .iter()
            .map(|c| match c {
                Cell::Solid => 0,
                Cell::Fluid => 1,
                Cell::Air => 2,
            })
            .collect()
    }

    /// The face velocities after the last step: u ((nx + 1)·ny, i + j·(nx + 1)) and v
    /// (nx·(ny + 1), i + j·nx).
    pub fn face_velocities(&self) -> (Vec<f64>, Vec<f64>) {
        (
            self.mac.u.iter().map(|f| f[0]).collect(),
            self.mac.v.iter().map(|f| f[0]).collect(),
        )
    }
}
