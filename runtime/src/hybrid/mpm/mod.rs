//! The moving least squares material point method (MLS-MPM) in 2-D: jelly, water and snow on
//! one background grid.
//!
//! Particles carry mass, velocity, the affine velocity C of APIC and their deformation; a grid
//! of nodes spaced h apart is made afresh every step. One step of Δt (Hu, Fang, Ge, Qu, Zhu,
//! Pradhana & Jiang, "A Moving Least Squares Material Point Method with Displacement
//! Discontinuity and Two-Way Rigid Body Coupling", SIGGRAPH 2018, §4 and its 88-line program):
//!
//! 1. **Particles to grid**: each particle adds, at the 3×3 nodes its quadratic B-spline
//!    reaches, wᵢₚ·mₚ to the mass and wᵢₚ·(mₚvₚ + Aₚ·(xᵢ − xₚ)) to the momentum, with
//!    Aₚ = mₚCₚ − Δt·(4/h²)·Vₚ⁰·τₚ: APIC's affine momentum and the impulse of the particle's
//!    Kirchhoff stress τₚ (from its F and J, [`Material`]) over the step, in one term (MLS's
//!    choice of the force's gradient makes the two share a form).
//! 2. **Grid**: velocity vᵢ = (momentum)/mᵢ + Δt·g; nodes within `wall` nodes of the box's
//!    edge lose the velocity into the wall (or all of it, [`Walls::Sticky`]). Each row is
//!    updated as soon as its particles have all scattered, inside the scatter's passes.
//! 3. **Grid to particles**: vₚ = Σ wᵢₚvᵢ, Cₚ = 4/h²·Σ wᵢₚvᵢ(xᵢ − xₚ)ᵀ (which is also the
//!    velocity gradient), xₚ += Δt·vₚ; the deformation follows, F ← (I + Δt·Cₚ)·F (or
//!    J ← J·(1 + Δt·tr Cₚ) for a fluid), then snow's plasticity ([`Material`]).
//!
//! Mass is conserved exactly (particles are never made or lost); with APIC the transfers also
//! conserve linear and angular momentum exactly, and the stress of an isotropic material exerts
//! no net torque, so a free body keeps its angular momentum to rounding
//! (`tests/continua/mpm.rs`).
//!
//! # Threads, deterministically
//!
//! Step 3 is independent per particle (rayon, fixed chunks). Step 1 is a scatter, which threads
//! would race on: the particles are sorted into strips of grid rows and
//! strips of one parity scatter in parallel (`strips.rs`), so every node sums its particles in
//! an order fixed by the positions. A run is bit-identical on any number of threads.

mod bodies;
mod checks;
mod decompose;
mod grid;
mod material;
mod measures;
mod particles;

use nalgebra::{Matrix2, Vector2};

pub use material::{Elastic, Fluid, Material, Snow};

use super::strips::{Strips, parallel};
use super::transfer::Transfer;
use crate::{Error, Result};
use material::Model;

/// What the walls do to the grid velocity of the nodes they hold.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Walls {
    /// The velocity into the wall is removed; along it, or away from it, stays (free slip and
    /// separation, as the 88-line program does). The default.
    #[default]
    Slip,
    /// All velocity is removed: material touching a wall sticks to it.
    Sticky,
}

/// The grid and the transfer: plain data with a [`Default`] (the 88-line program's grid).
#[derive(Clone, Debug, PartialEq)]
pub struct MpmOptions {
    /// Nodes across (default 128): node i at x = i·h; the box is [0, nx·h].
    pub nx: usize,
    /// Nodes up (default 128).
    pub ny: usize,
    /// Node spacing h (m; default 1/128).
    pub cell: f64,
    /// Gravity (m/s²; default (0, −9.81)).
    pub gravity: Vector2<f64>,
    /// Nodes of wall on each side (default 3): nodes with i < wall or i > nx − wall (and the
    /// same in j) are held by the walls.
    pub wall: usize,
    /// What the walls do (default [`Walls::Slip`]).
    pub walls: Walls,
    /// APIC (the default) or PIC ([`Transfer::PIC`]).
    pub transfer: Transfer,
    /// Particles along each side of a cell in the bodies [`Mpm::add_block`] and [`Mpm::add_disc`]
    /// make (default 2: four a cell).
    pub sampling: usize,
}

impl Default for MpmOptions {
    fn default() -> Self {
        MpmOptions {
            nx: 128,
            ny: 128,
            cell: 1.0 / 128.0,
            gravity: Vector2::new(0.0, -9.81),
            wall: 3,
            walls: Walls::Slip,
            transfer: Transfer::Apic,
            sampling: 2,
        }
    }
}

/// A 2-D MLS-MPM simulation: particles of several materials on one grid, in a walled box.
///
/// Positions and velocities are public (set them between steps as you like); the deformation,
/// the affine velocity and the stress are the method's own.
pub struct Mpm {
    options: MpmOptions,
    /// Particle positions (m).
    pub x: Vec<Vector2<f64>>,
    /// Particle velocities (m/s).
    pub v: Vec<Vector2<f64>>,
    /// APIC's affine velocity, the velocity gradient (1/s).
    c: Vec<Matrix2<f64>>,
    /// Deformation gradient (the elastic part for snow; unused for fluids).
    f: Vec<Matrix2<f64>>,
    /// J for a fluid, J_P for snow, 1 for an elastic solid.
    j: Vec<f64>,
    mass: Vec<f64>,
    volume: Vec<f64>,
    /// Index of each particle's material in `materials`.
    material: Vec<u16>,
    materials: Vec<(Material, Model)>,
    /// Per node: momentum (x, y) and mass, then velocity (x, y) and mass after the grid update.
    grid: Vec<[f64; 3]>,
    /// The row each particle's stencil starts at, this step.
    base: Vec<u32>,
    strips: Strips,
    /// The grid rows the last step wrote (zeroed again before the next scatter).
    written: std::ops::Range<usize>,
    steps: u64,
    t: f64,
}

impl Mpm {
    /// An empty box; add bodies with [`Mpm::add_block`], [`Mpm::add_disc`] or
    /// [`Mpm::add_particles`].
    ///
    /// Errors: [`Error::InvalidInput`] for fewer than 2·wall + 3 nodes a side (or 4), a cell size
    /// that is not finite and positive, a gravity that is not finite, a transfer other than APIC
    /// or PIC, a sampling of 0 or above 16, or a grid larger than memory holds.
    pub fn new(options: MpmOptions) -> Result<Mpm> {
        let MpmOptions {
            nx,
            ny,
            cell,
            gravity,
            wall,
            transfer,
            sampling,
            ..
        } = options;
        let least = (2 * wall.min(usize::MAX / 4) + 3).max(4);
        if nx < least || ny < least {
            return Err(Error::invalid(
                "grid",
                format!(
                    "{nx}×{ny} nodes is too small for walls {wall} nodes thick; at least {least} a side"
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
        if transfer.flip()?.is_some_and(|flip| flip != 0.0) {
            return Err(Error::invalid(
                "transfer",
                "MPM transfers by APIC or PIC (`Transfer::PIC`): MLS-MPM folds the stress into \
                 the transfer, so there is no grid velocity before the forces for FLIP to \
                 difference",
            ));
        }
        if !(1..=16).contains(&sampling) {
            return Err(Error::invalid(
                "sampling",
                format!("particles per cell side must be 1 to 16, got {sampling}"),
            ));
        }
        let nodes = nx.checked_mul(ny).filter(|&n| n <= u32::MAX as usize);
        let mut grid = Vec::new();
        if nodes.is_none_or(|n| grid.try_reserve_exact(n).is_err()) {
            return Err(Error::invalid(
                "grid",
                format!("{nx}×{ny} nodes is more than this machine can allocate"),
            ));
        }
        grid.resize(nx * ny, [0.0; 3]);
        Ok(Mpm {
            options,
            x: Vec::new(),
            v: Vec::new(),
            c: Vec::new(),
            f: Vec::new(),
            j: Vec::new(),
            mass: Vec::new(),
            volume: Vec::new(),
            material: Vec::new(),
            materials: Vec::new(),
            grid,
            base: Vec::new(),
            strips: Strips::default(),
            written: 0..0,
            steps: 0,
            t: 0.0,
        })
    }

    /// The settings.
    pub fn options(&self) -> &MpmOptions {
        &self.options
    }

    /// Steps taken, and the time they covered.
    pub fn steps(&self) -> (u64, f64) {
        (self.steps, self.t)
    }

    /// One step of `dt` seconds.
    ///
    /// Errors, before the step (nothing changed): [`Error::InvalidInput`] for a `dt` that is not
    /// finite and positive, position or velocity lists whose length changed, or a particle
    /// outside the region the grid reaches, [h/2, (n − 3/2)·h) on each axis, or with a velocity
    /// that is not finite. After it: [`Error::NotFinite`] when a particle's position became NaN
    /// or infinite, or [`Error::InvalidInput`] when one left that region (the step was too large
    /// for the flow: see [`Mpm::stable_dt`]); the particles are then as the failed step left
    /// them.
    pub fn step(&mut self, dt: f64) -> Result<()> {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(Error::invalid(
                "dt",
                format!("must be finite and positive, got {dt:?}"),
            ));
        }
        // A parallel step runs whole on one of rayon's threads: its passes then fork from inside
        // the pool, rather than each handing itself over from the caller's thread and waiting.
        let escaped = if parallel(self.mass.len()) {
            rayon::scope(|_| self.transfer(dt))?
        } else {
            self.transfer(dt)?
        };
        self.steps += 1;
        self.t += dt;
        match escaped {
            None => Ok(()),
            Some(p) => Err(self.escape_error(p, dt)),
        }
    }

    /// The step's passes after the checks of `dt`: returns the first particle that left the
    /// grid's reach, if any.
    fn transfer(&mut self, dt: f64) -> Result<Option<usize>> {
        self.check_particles()?;
        self.strips.sort(&self.base, self.options.ny);
        self.scatter(dt);
        Ok(self.gather(dt))
    }

    /// The largest step the explicit update is stable at, about: 0.5·h/(c + |v|) at the
    /// particle where it is least, c the material's fastest wave ([`Material`]). The 88-line
    /// program steps at 0.51·h/c. Infinite for an empty box, which [`Mpm::step`] refuses as a
    /// step: choose one yourself there.
    pub fn stable_dt(&self) -> f64 {
        let h = self.options.cell;
        // Zipped, not indexed: `v` is public and may have been resized (`step` refuses that).
        let fastest = (self.material.iter().zip(&self.j).zip(&self.v)).fold(
            0.0f64,
            |m, ((&material, &j), v)| {
                let (material, model) = &self.materials[material as usize];
                m.max(model.wave_speed(material.density(), j) + v.norm())
            },
        );
        if fastest > 0.0 {
            0.5 * h / fastest
        } else {
            f64::INFINITY
        }
    }

    /// The particles' materials, in the order they were added: particle p is of
    /// `materials()[material_of(p)]`.
    pub fn materials(&self) -> Vec<Material> {
        self.materials.iter().map(|m| m.0).collect()
    }

    /// The index in [`Mpm::materials`] of particle `p`'s material.
    pub fn material_of(&self, p: usize) -> usize {
        self.material[p] as usize
    }

    /// The particles' masses (kg per metre of depth: 2-D).
    pub fn masses(&self) -> &[f64] {
        &self.mass
    }

    /// The particles' affine velocities C (their velocity gradients).
    pub fn affine(&self) -> &[Matrix2<f64>] {
        &self.c
    }

    /// The particles' deformation gradients (the elastic part for snow, the identity for a
    /// fluid).
    pub fn deformation(&self) -> &[Matrix2<f64>] {
        &self.f
    }

    /// The particles' volume ratios: J of a fluid, J_P (the plastic part) of snow, 1 of an
    /// elastic solid.
    pub fn volume_ratios(&self) -> &[f64] {
        &self.j
    }

    /// The grid after the last step: per node (i + j·nx), velocity (x, y) and mass.
    pub fn grid(&self) -> &[[f64; 3]] {
        &self.grid
    }
}
