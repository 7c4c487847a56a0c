//! Smoothed-particle hydrodynamics (SPH): a weakly compressible liquid in 2-D.
//!
//! Each fluid particle carries a fixed mass; its density is the kernel-weighted sum over its
//! neighbours, its pressure follows Tait's stiff equation of state, and the pressure gradient,
//! an artificial viscosity and gravity move it:
//!
//! - ρᵢ = Σⱼ mⱼ·W(|xᵢ − xⱼ|, h), with Wendland's C² kernel in 2-D, W = 7/(4πh²)·(1 − q/2)⁴(1 + 2q)
//!   for q = r/h < 2 (Wendland 1995; Dehnen & Aly 2012 for its use in SPH);
//! - pᵢ = B·((ρᵢ/ρ₀)⁷ − 1), B = c₀²ρ₀/7, with c₀ ten times the fastest expected flow so the
//!   density varies by about 1 % (Monaghan 1994, "Simulating free surface flows with SPH", J.
//!   Comput. Phys. 110, 399); negative pressures are clipped to 0 (no tension at the free
//!   surface);
//! - dvᵢ/dt = −Σⱼ mⱼ(pᵢ/ρᵢ² + pⱼ/ρⱼ² + Πᵢⱼ)∇ᵢWᵢⱼ + g, with Monaghan's artificial viscosity
//!   Πᵢⱼ = −α·c₀·μᵢⱼ/ρ̄ᵢⱼ, μᵢⱼ = h·vᵢⱼ·xᵢⱼ/(|xᵢⱼ|² + 0.01h²) for approaching pairs;
//! - symplectic Euler in time (kick, then drift), at a step the caller chooses below
//!   [`Sph::stable_dt`] (the CFL condition 0.25·h/(c₀ + max|v|)).
//!
//! Walls are fixed boundary particles (three layers, the fluid's spacing) that take part in the
//! density sum and push back with the pressure their own density gives them — the "dummy
//! particle" treatment (Adami, Hu & Adams 2012 refine it). Mass is conserved exactly: particles
//! are never created or removed, so the fluid's mass is the particle count times the particle
//! mass at every step.
//!
//! # How it fits beside the ODE models
//!
//! A particle model's links are fixed for the run; an SPH particle's neighbours change every
//! step. So SPH is its own stepper rather than a `#[system]` model: a uniform grid of cells
//! 2h wide is rebuilt every step (a counting sort of the particles by cell, O(N)), and each
//! particle visits the 3×3 cells around its own. Density and force passes run in parallel over
//! the particles with rayon, each particle writing only its own entries, so results do not
//! depend on the thread count.

mod block;
mod kernel;
mod neighbours;

use nalgebra::Vector2;
use rayon::prelude::*;

use crate::{Error, Result};

use kernel::Wendland;
use neighbours::Grid;

/// Settings: plain data with a [`Default`] (water at 1/100 of a metre's resolution).
#[derive(Clone, Debug, PartialEq)]
pub struct SphOptions {
    /// Initial particle spacing Δx, in m (default 0.01).
    pub spacing: f64,
    /// Smoothing length h as a multiple of the spacing (default 1.3).
    pub smoothing: f64,
    /// Rest density ρ₀, in kg/m³ (default 1000, water).
    pub rest_density: f64,
    /// Numerical speed of sound c₀, in m/s: about 10× the fastest flow keeps density variations
    /// near 1 % (default 30).
    pub sound_speed: f64,
    /// Monaghan's artificial viscosity α, dimensionless (default 0.02).
    pub viscosity: f64,
    /// Gravitational acceleration, in m/s² (default (0, −9.81)).
    pub gravity: Vector2<f64>,
    /// The box [0, width] × [0, height] the walls enclose (open at the top), in m (default
    /// (1, 1)).
    pub domain: (f64, f64),
}

impl Default for SphOptions {
    fn default() -> Self {
        SphOptions {
            spacing: 0.01,
            smoothing: 1.3,
            rest_density: 1000.0,
            sound_speed: 30.0,
            viscosity: 0.02,
            gravity: Vector2::new(0.0, -9.81),
            domain: (1.0, 1.0),
        }
    }
}

/// A 2-D SPH liquid in a box with walls of boundary particles.
pub struct Sph {
    options: SphOptions,
    /// Fluid particle positions.
    pub x: Vec<Vector2<f64>>,
    /// Fluid particle velocities.
    pub v: Vec<Vector2<f64>>,
    /// Boundary particles (fixed).
    walls: Vec<Vector2<f64>>,
    /// Mass of every particle: ρ₀·Δx².
    mass: f64,
    /// Densities of the fluid particles, then of the walls.
    density: Vec<f64>,
    pressure: Vec<f64>,
    acceleration: Vec<Vector2<f64>>,
    /// Fluid then wall positions, the points the grid sorts.
    all: Vec<Vector2<f64>>,
    grid: Grid,
}

impl Sph {
    /// The settings.
    pub fn options(&self) -> &SphOptions {
        &self.options
    }

    /// The particle mass (every particle the same).
    pub fn particle_mass(&self) -> f64 {
        self.mass
    }

    /// The boundary particles.
    pub fn walls(&self) -> &[Vector2<f64>] {
        &self.walls
    }

    /// The largest stable step: the CFL bound 0.25·h/(c₀ + max|v|) (Monaghan 1994).
    pub fn stable_dt(&self) -> f64 {
        let h = self.options.smoothing * self.options.spacing;
        let fastest = self.v.iter().fold(0.0f64, |m, v| m.max(v.norm()));
        0.25 * h / (self.options.sound_speed + fastest)
    }

    /// One step of size `dt`.
    ///
    /// Errors: [`Error::InvalidInput`] before the step for position or velocity lists whose
    /// length changed, a fluid particle set outside the region it may occupy (`x[i]`:
    /// [0, width] × [0, 10·height], the box and the space above its open top; a NaN or infinite
    /// position is outside), a velocity that is not finite (`v[i]`), or a `dt` that is not
    /// finite and positive or above [`Sph::stable_dt`], or more cells of the neighbour grid
    /// than the machine can allocate; after the step for a fluid particle that has left that
    /// region (through a wall: the step was too large for the flow).
    pub fn step(&mut self, dt: f64) -> Result<()> {
        let fluid = self.acceleration.len();
        if self.x.len() != fluid || self.v.len() != fluid {
            return Err(Error::invalid(
                "particles",
                format!(
                    "{} positions and {} velocities for the {fluid} particles the liquid was made \
                     with; particles cannot be added or removed",
                    self.x.len(),
                    self.v.len()
                ),
            ));
        }
        let (w, top) = self.options.domain;
        if let Some(i) = self.x.iter().position(|x| !self.inside(x)) {
            return Err(Error::invalid(
                format!("x[{i}]"),
                format!(
                    "fluid particle {i} is at ({:?}, {:?}), outside the box and the space \
                     above it, [0, {w:?}] × [0, {:?}] (splashes may rise to 10 times the box's \
                     height); move it inside",
                    self.x[i].x,
                    self.x[i].y,
                    10.0 * top
                ),
            ));
        }
        if let Some(i) = self.v.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
            return Err(Error::invalid(
                format!("v[{i}]"),
                format!(
                    "({:?}, {:?}) is not finite; write only finite velocities",
                    self.v[i].x, self.v[i].y
                ),
            ));
        }
        let limit = self.stable_dt();
        if !(dt.is_finite() && dt > 0.0 && dt <= limit * (1.0 + 1e-12)) {
            return Err(Error::invalid(
                "dt",
                format!(
                    "must be finite, positive and at most the stable step {limit:e}, got {dt:?}"
                ),
            ));
        }
        // The walls never move: only the fluid's part of `all` is refreshed.
        self.all[..fluid].copy_from_slice(&self.x);
        self.grid.build(&self.all)?;
        let all = &self.all;
        let o = &self.options;
        let h = o.smoothing * o.spacing;
        let kernel = Wendland::new(h);
        let (m, rho0) = (self.mass, o.rest_density);
        let b = o.sound_speed * o.sound_speed * rho0 / 7.0;
        let grid = &self.grid;
        self.density
            .par_iter_mut()
            .zip(self.pressure.par_iter_mut())
            .enumerate()
            .for_each(|(i, (rho, p))| {
                let mut sum = 0.0;
                grid.neighbours(all[i], |j| {
                    sum += m * kernel.value((all[i] - all[j]).norm())
                });
                *rho = sum;
                *p = (b * ((sum / rho0).powi(7) - 1.0)).max(0.0);
            });
        let (density, pressure) = (&self.density, &self.pressure);
        let (alpha, c0, g) = (o.viscosity, o.sound_speed, o.gravity);
        let v = &self.v;
        let velocity = |j: usize| if j < fluid { v[j] } else { Vector2::zeros() };
        self.acceleration
            .par_iter_mut()
            .enumerate()
            .for_each(|(i, a)| {
                let mut sum = g;
                let pi = pressure[i] / (density[i] * density[i]);
                grid.neighbours(all[i], |j| {
                    if i == j {
                        return;
                    }
                    let r = all[i] - all[j];
                    let distance = r.norm();
                    if distance >= 2.0 * h || distance == 0.0 {
                        return;
                    }
                    let gradient = r * (kernel.derivative(distance) / distance);
                    let mut term = pi + pressure[j] / (density[j] * density[j]);
                    let approach = (velocity(i) - velocity(j)).dot(&r);
                    if approach < 0.0 {
                        let mu = h * approach / (distance * distance + 0.01 * h * h);
                        term += -alpha * c0 * mu / (0.5 * (density[i] + density[j]));
                    }
                    sum -= m * term * gradient;
                });
                *a = sum;
            });
        for ((x, v), a) in self.x.iter_mut().zip(&mut self.v).zip(&self.acceleration) {
            *v += dt * a;
            *x += dt * *v;
        }
        if let Some(i) = self.x.iter().position(|x| !self.inside(x)) {
            return Err(Error::invalid(
                "particles",
                format!(
                    "fluid particle {i} left the box at ({:?}, {:?}); reduce dt",
                    self.x[i].x, self.x[i].y
                ),
            ));
        }
        Ok(())
    }

    /// Whether a fluid particle at `x` is where fluid may be: in the box, or above its open top
    /// up to 10 times the box's height (a splash). False for NaN or infinite coordinates.
    fn inside(&self, x: &Vector2<f64>) -> bool {
        let (w, top) = self.options.domain;
        (0.0..=w).contains(&x.x) && (0.0..=10.0 * top).contains(&x.y)
    }

    /// The fluid's total mass (constant: particles are never created or removed).
    pub fn fluid_mass(&self) -> f64 {
        self.mass * self.x.len() as f64
    }

    /// The surge front: the largest x of the fluid particles whose y is below 2 spacings (on
    /// the floor), as dam-break experiments measure it.
    pub fn front(&self) -> f64 {
        let floor = 2.0 * self.options.spacing;
        self.x
            .iter()
            .filter(|x| x.y < floor)
            .fold(0.0, |m, x| m.max(x.x))
    }

    /// The fluid densities (the walls' are not included).
    pub fn densities(&self) -> &[f64] {
        &self.density[..self.x.len()]
    }
}
