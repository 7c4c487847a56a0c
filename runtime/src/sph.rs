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

use nalgebra::Vector2;
use rayon::prelude::*;

use crate::{Error, Result};

/// Settings: plain data with a [`Default`] (water at 1/100 of a metre's resolution).
#[derive(Clone, Debug, PartialEq)]
pub struct SphOptions {
    /// Initial particle spacing Δx.
    pub spacing: f64,
    /// Smoothing length h as a multiple of the spacing.
    pub smoothing: f64,
    /// Rest density ρ₀.
    pub rest_density: f64,
    /// Numerical speed of sound c₀.
    pub sound_speed: f64,
    /// Artificial viscosity α.
    pub viscosity: f64,
    /// Gravitational acceleration.
    pub gravity: Vector2<f64>,
    /// The box [0, width] × [0, height] the walls enclose (open at the top).
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
    /// A liquid filling the rectangle [0, width] × [0, height] of the box (particles on a
    /// square lattice at `spacing`, starting half a spacing from the walls), at rest.
    ///
    /// Errors: [`Error::InvalidInput`] for a non-positive or non-finite setting, a block that
    /// does not fit in the box, a box smaller than 4 spacings a side, or more particles than
    /// the machine can allocate.
    pub fn block(options: SphOptions, width: f64, height: f64) -> Result<Sph> {
        let positive = [
            ("spacing", options.spacing),
            ("smoothing", options.smoothing),
            ("rest_density", options.rest_density),
            ("sound_speed", options.sound_speed),
            ("domain width", options.domain.0),
            ("domain height", options.domain.1),
            ("block width", width),
            ("block height", height),
        ];
        for (name, value) in positive {
            if !(value.is_finite() && value > 0.0) {
                return Err(Error::invalid(
                    name,
                    format!("must be finite and positive, got {value:?}"),
                ));
            }
        }
        if !(options.viscosity.is_finite()
            && options.viscosity >= 0.0
            && options.gravity.iter().all(|g| g.is_finite()))
        {
            return Err(Error::invalid(
                "viscosity/gravity",
                "must be finite (viscosity ≥ 0)",
            ));
        }
        let (w, h) = options.domain;
        let dx = options.spacing;
        if w < 4.0 * dx || h < 4.0 * dx {
            return Err(Error::invalid(
                "domain",
                format!(
                    "{w:?} × {h:?} is too small for a spacing of {dx:?}: at least 4 spacings a \
                     side"
                ),
            ));
        }
        if width > w || height > h {
            return Err(Error::invalid(
                "block",
                format!("{width:?} × {height:?} does not fit in the {w:?} × {h:?} box"),
            ));
        }
        let (nx, ny) = (
            (width / dx).round() as usize,
            (height / dx).round() as usize,
        );
        // Three layers of wall particles below and beside the box (open at the top).
        let layers = 3;
        let (cols, rows) = ((w / dx).round() as i64, (h / dx).round() as i64);
        // Counted before anything is allocated: a spacing far below the box's size would
        // otherwise run the machine out of memory (an abort) or overflow the count.
        let fluid = nx.checked_mul(ny);
        let wall = (cols as u64)
            .checked_add(2 * layers as u64)
            .zip((rows as u64).checked_mul(2))
            .and_then(|(a, b)| a.checked_add(b))
            .and_then(|n| n.checked_mul(layers as u64))
            .and_then(|n| usize::try_from(n).ok());
        let too_many = || {
            Error::invalid(
                "spacing",
                format!(
                    "{dx:?} in a {w:?} × {h:?} box is more particles than this machine can \
                     allocate"
                ),
            )
        };
        let (Some(fluid), Some(wall)) = (fluid, wall) else {
            return Err(too_many());
        };
        let (mut x, mut walls) = (Vec::new(), Vec::new());
        x.try_reserve_exact(fluid).map_err(|_| too_many())?;
        walls.try_reserve_exact(wall).map_err(|_| too_many())?;
        x.extend((0..ny).flat_map(|j| {
            (0..nx).map(move |i| Vector2::new((i as f64 + 0.5) * dx, (j as f64 + 0.5) * dx))
        }));
        for layer in 0..layers {
            let out = -(layer as f64 + 0.5) * dx;
            for i in -layers..cols + layers {
                walls.push(Vector2::new((i as f64 + 0.5) * dx, out));
            }
            for j in 0..rows {
                let y = (j as f64 + 0.5) * dx;
                walls.push(Vector2::new(out, y));
                walls.push(Vector2::new(w - out, y));
            }
        }
        let n = x.len() + walls.len();
        let cell = 2.0 * options.smoothing * dx;
        Ok(Sph {
            mass: options.rest_density * dx * dx,
            v: vec![Vector2::zeros(); x.len()],
            density: vec![options.rest_density; n],
            pressure: vec![0.0; n],
            acceleration: vec![Vector2::zeros(); x.len()],
            grid: Grid::new(cell),
            all: x.iter().chain(&walls).copied().collect(),
            options,
            x,
            walls,
        })
    }

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

/// Wendland's C² kernel in 2-D with support 2h.
#[derive(Clone, Copy)]
struct Wendland {
    h: f64,
    norm: f64,
}

impl Wendland {
    fn new(h: f64) -> Wendland {
        Wendland {
            h,
            norm: 7.0 / (4.0 * std::f64::consts::PI * h * h),
        }
    }

    fn value(&self, r: f64) -> f64 {
        let q = r / self.h;
        if q >= 2.0 {
            return 0.0;
        }
        self.norm * (1.0 - 0.5 * q).powi(4) * (1.0 + 2.0 * q)
    }

    /// dW/dr = norm·(−5q(1 − q/2)³)/h.
    fn derivative(&self, r: f64) -> f64 {
        let q = r / self.h;
        if q >= 2.0 {
            return 0.0;
        }
        -self.norm * 5.0 * q * (1.0 - 0.5 * q).powi(3) / self.h
    }
}

/// A uniform grid of square cells, rebuilt by a counting sort every step.
struct Grid {
    cell: f64,
    origin: Vector2<f64>,
    dims: (usize, usize),
    /// Start of each cell's particles in `order`, one more than there are cells.
    starts: Vec<usize>,
    order: Vec<usize>,
    /// Scratch of `build`: each point's cell, and the next free slot of each cell.
    cell_of: Vec<usize>,
    next: Vec<usize>,
}

impl Grid {
    fn new(cell: f64) -> Grid {
        Grid {
            cell,
            origin: Vector2::zeros(),
            dims: (0, 0),
            starts: Vec::new(),
            order: Vec::new(),
            cell_of: Vec::new(),
            next: Vec::new(),
        }
    }

    fn coordinates(&self, x: Vector2<f64>) -> (usize, usize) {
        let c = (x - self.origin) / self.cell;
        (
            (c.x.max(0.0) as usize).min(self.dims.0 - 1),
            (c.y.max(0.0) as usize).min(self.dims.1 - 1),
        )
    }

    /// Sorts `points` (finite) into the cells of their bounding box.
    ///
    /// Errors: [`Error::InvalidInput`] when that box has more cells than this machine can
    /// allocate (a domain far larger than the spacing).
    fn build(&mut self, points: &[Vector2<f64>]) -> Result<()> {
        let (lo, hi) = points.iter().fold(
            (
                Vector2::repeat(f64::INFINITY),
                Vector2::repeat(f64::NEG_INFINITY),
            ),
            |(lo, hi), p| (lo.inf(p), hi.sup(p)),
        );
        let cell = self.cell;
        // Cells along an extent; `as` would saturate, so a count past usize::MAX (or ∞) is
        // refused here.
        let side = |extent: f64| {
            let whole = (extent / cell).floor();
            (whole < usize::MAX as f64).then(|| whole as usize + 1)
        };
        let too_many = || {
            Error::invalid(
                "domain",
                format!(
                    "the particles span {:e} × {:e}: more cells of the neighbour grid ({cell:e} \
                     wide) than this machine can allocate; use a larger spacing or a smaller box",
                    hi.x - lo.x,
                    hi.y - lo.y
                ),
            )
        };
        let (Some(nx), Some(ny)) = (side(hi.x - lo.x), side(hi.y - lo.y)) else {
            return Err(too_many());
        };
        // One start more than there are cells, so their count must be below usize::MAX.
        let cells = nx
            .checked_mul(ny)
            .filter(|&cells| cells < usize::MAX)
            .ok_or_else(too_many)?;
        self.origin = lo;
        self.dims = (nx, ny);
        self.starts.clear();
        self.starts
            .try_reserve_exact(cells + 1)
            .map_err(|_| too_many())?;
        self.starts.resize(cells + 1, 0);
        self.cell_of.clear();
        for p in points {
            let (i, j) = self.coordinates(*p);
            self.cell_of.push(i + j * self.dims.0);
        }
        for &c in &self.cell_of {
            self.starts[c + 1] += 1;
        }
        for c in 0..cells {
            self.starts[c + 1] += self.starts[c];
        }
        self.next.clone_from(&self.starts);
        self.order.resize(points.len(), 0);
        for (p, &c) in self.cell_of.iter().enumerate() {
            self.order[self.next[c]] = p;
            self.next[c] += 1;
        }
        Ok(())
    }

    /// Calls `visit` with every point in the 3×3 cells around `x`.
    fn neighbours(&self, x: Vector2<f64>, mut visit: impl FnMut(usize)) {
        let (ci, cj) = self.coordinates(x);
        for j in cj.saturating_sub(1)..=(cj + 1).min(self.dims.1 - 1) {
            for i in ci.saturating_sub(1)..=(ci + 1).min(self.dims.0 - 1) {
                let c = i + j * self.dims.0;
                for &p in &self.order[self.starts[c]..self.starts[c + 1]] {
                    visit(p);
                }
            }
        }
    }
}
