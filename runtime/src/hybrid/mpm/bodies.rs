//! Bodies of particles: a block, a disc, or any set of points, of one material each.

use std::ops::Range;

use nalgebra::{Matrix2, Vector2};

use super::{Material, Mpm};
use crate::hybrid::bspline::base_row;
use crate::{Error, Result};

impl Mpm {
    /// Adds one particle of `material` at each of `positions`, each standing for `volume` m² of
    /// material at rest (mass ρ·volume), moving at `velocity(x)`, undeformed. Returns their
    /// indices.
    ///
    /// Errors: [`Error::InvalidInput`] (and nothing added) for a material
    /// [`Material`]'s checks refuse, a volume that is not finite and positive, a position
    /// outside the grid's reach (see [`Mpm::step`]), a velocity that is not finite, more than
    /// 2³² particles or 2¹⁶ bodies, or more particles than memory holds.
    pub fn add_particles(
        &mut self,
        material: Material,
        positions: &[Vector2<f64>],
        volume: f64,
        velocity: impl Fn(Vector2<f64>) -> Vector2<f64>,
    ) -> Result<Range<usize>> {
        let model = material.model()?;
        if !(volume.is_finite() && volume > 0.0) {
            return Err(Error::invalid(
                "volume",
                format!("must be finite and positive, got {volume:?}"),
            ));
        }
        if self.materials.len() > u16::MAX as usize {
            return Err(Error::invalid(
                "material",
                "at most 65 536 bodies (each `add_*` call is one)",
            ));
        }
        let start = self.mass.len();
        let total = start.checked_add(positions.len());
        if total.is_none_or(|n| n > u32::MAX as usize) {
            return Err(Error::invalid(
                "positions",
                "more than 2³² particles in one simulation",
            ));
        }
        let inv_h = 1.0 / self.options.cell;
        let (nx, ny) = (self.options.nx, self.options.ny);
        let mut speeds = Vec::new();
        speeds
            .try_reserve_exact(positions.len())
            .map_err(|_| too_many(positions.len()))?;
        for (k, &x) in positions.iter().enumerate() {
            if base_row(x.x * inv_h, nx).is_none() || base_row(x.y * inv_h, ny).is_none() {
                return Err(Error::invalid(
                    format!("positions[{k}]"),
                    format!(
                        "({:?}, {:?}) is outside the region the grid reaches, {}",
                        x.x,
                        x.y,
                        self.reach()
                    ),
                ));
            }
            let v = velocity(x);
            if !v.iter().all(|c| c.is_finite()) {
                return Err(Error::invalid(
                    format!("velocity at positions[{k}]"),
                    format!("({:?}, {:?}) is not finite", v.x, v.y),
                ));
            }
            speeds.push(v);
        }
        let n = positions.len();
        self.reserve(n).map_err(|_| too_many(n))?;
        let index = self.materials.len() as u16;
        self.materials.push((material, model));
        self.x.extend_from_slice(positions);
        self.v.extend(speeds);
        self.c.resize(start + n, Matrix2::zeros());
        self.f.resize(start + n, Matrix2::identity());
        self.j.resize(start + n, 1.0);
        self.mass.resize(start + n, material.density() * volume);
        self.volume.resize(start + n, volume);
        self.material.resize(start + n, index);
        Ok(start..start + n)
    }

    /// Adds the rectangle [lower, upper] of `material`, sampled on a square lattice of
    /// h/[`MpmOptions::sampling`](super::MpmOptions::sampling) (the first particle half a
    /// spacing in from `lower`), moving at `velocity(x)`. Returns the particles' indices.
    ///
    /// Errors: [`Error::InvalidInput`] for corners that are not finite or not ordered, a block
    /// too thin for one particle or not inside the box, or what [`Mpm::add_particles`] refuses.
    pub fn add_block(
        &mut self,
        material: Material,
        lower: Vector2<f64>,
        upper: Vector2<f64>,
        velocity: impl Fn(Vector2<f64>) -> Vector2<f64>,
    ) -> Result<Range<usize>> {
        let spacing = self.options.cell / self.options.sampling as f64;
        let size = upper - lower;
        if !(lower.iter().chain(upper.iter()).all(|c| c.is_finite())
            && size.x >= spacing
            && size.y >= spacing)
        {
            return Err(Error::invalid(
                "block",
                format!(
                    "corners ({:?}, {:?}) and ({:?}, {:?}) must be finite, ordered, and at least \
                     a particle spacing ({spacing:?}) apart",
                    lower.x, lower.y, upper.x, upper.y
                ),
            ));
        }
        self.check_in_box("block", lower, upper)?;
        let (cols, rows) = (
            (size.x / spacing).round() as usize,
            (size.y / spacing).round() as usize,
        );
        let count = cols.checked_mul(rows).ok_or_else(|| too_many(usize::MAX))?;
        let mut points = Vec::new();
        points
            .try_reserve_exact(count)
            .map_err(|_| too_many(count))?;
        for j in 0..rows {
            for i in 0..cols {
                let offset = Vector2::new(i as f64 + 0.5, j as f64 + 0.5) * spacing;
                points.push(lower + offset);
            }
        }
        self.add_particles(material, &points, spacing * spacing, velocity)
    }

    /// Adds the disc of `radius` about `centre`, the points of the lattice of
    /// [`Mpm::add_block`] that fall inside it. Returns the particles' indices.
    ///
    /// Errors: [`Error::InvalidInput`] for a centre that is not finite, a radius that is not
    /// finite and at least half a spacing, a disc not inside the box, or what
    /// [`Mpm::add_particles`] refuses.
    pub fn add_disc(
        &mut self,
        material: Material,
        centre: Vector2<f64>,
        radius: f64,
        velocity: impl Fn(Vector2<f64>) -> Vector2<f64>,
    ) -> Result<Range<usize>> {
        let spacing = self.options.cell / self.options.sampling as f64;
        if !(centre.iter().all(|c| c.is_finite()) && radius.is_finite() && radius >= 0.5 * spacing)
        {
            return Err(Error::invalid(
                "disc",
                format!(
                    "centre ({:?}, {:?}) and radius {radius:?} must be finite, the radius at \
                     least half a particle spacing ({:?})",
                    centre.x,
                    centre.y,
                    0.5 * spacing
                ),
            ));
        }
        let reach = Vector2::new(radius, radius);
        self.check_in_box("disc", centre - reach, centre + reach)?;
        let side = (radius / spacing).ceil() as i64;
        let count = usize::try_from((2 * side).pow(2)).map_err(|_| too_many(usize::MAX))?;
        let mut points = Vec::new();
        points
            .try_reserve_exact(count)
            .map_err(|_| too_many(count))?;
        for j in -side..side {
            for i in -side..side {
                let offset = Vector2::new(i as f64 + 0.5, j as f64 + 0.5) * spacing;
                if offset.norm() <= radius {
                    points.push(centre + offset);
                }
            }
        }
        self.add_particles(material, &points, spacing * spacing, velocity)
    }

    /// Reorders the particles by the grid cell they are in, row by row (stably: by index
    /// within a cell), and returns where each came from: particle k is the old particle
    /// `order[k]`. Every per-particle list moves with it, so the run goes on as before, bit for
    /// bit in what it computes per particle (the scatter's sums may round differently).
    ///
    /// Why: the scatter visits particles by row strips, and reads them in index order within a
    /// strip; particles whose indices are in random spatial order (the 88-line program draws its
    /// particles at random) are then read all over memory. At 131 072 particles that made a
    /// step 4.7 times slower than in sorted order (`benches/mpm.rs`'s scene, one thread).
    /// Bodies from [`Mpm::add_block`] and [`Mpm::add_disc`] start sorted; a flow that mixes
    /// its particles for long is worth re-sorting now and then.
    ///
    /// Errors: [`Error::InvalidInput`] (nothing moved) when the public position or velocity
    /// list no longer has one entry a particle.
    pub fn sort_particles(&mut self) -> Result<Vec<usize>> {
        let inv_h = 1.0 / self.options.cell;
        let nx = self.options.nx;
        let cell = |x: &Vector2<f64>| {
            let (i, j) = ((x.x * inv_h) as usize, (x.y * inv_h) as usize);
            j.saturating_mul(nx).saturating_add(i)
        };
        let n = self.mass.len();
        if self.x.len() != n || self.v.len() != n {
            return Err(Error::invalid(
                "particles",
                format!(
                    "{} positions and {} velocities for {n} particles",
                    self.x.len(),
                    self.v.len()
                ),
            ));
        }
        let mut order: Vec<usize> = (0..n).collect();
        order.sort_by_key(|&p| cell(&self.x[p]));
        fn permute<T: Copy>(list: &mut [T], order: &[usize]) {
            let old = list.to_vec();
            for (new, &from) in list.iter_mut().zip(order) {
                *new = old[from];
            }
        }
        permute(&mut self.x, &order);
        permute(&mut self.v, &order);
        permute(&mut self.c, &order);
        permute(&mut self.f, &order);
        permute(&mut self.j, &order);
        permute(&mut self.mass, &order);
        permute(&mut self.volume, &order);
        permute(&mut self.material, &order);
        Ok(order)
    }

    /// [`Error::InvalidInput`] unless [lower, upper] lies in the box: a body's particles are
    /// then checked one by one, and their number is bounded by the grid's size.
    fn check_in_box(&self, what: &str, lower: Vector2<f64>, upper: Vector2<f64>) -> Result<()> {
        let h = self.options.cell;
        let (w, top) = (self.options.nx as f64 * h, self.options.ny as f64 * h);
        if lower.x >= 0.0 && lower.y >= 0.0 && upper.x <= w && upper.y <= top {
            Ok(())
        } else {
            Err(Error::invalid(
                what,
                format!(
                    "spans ({:?}, {:?}) to ({:?}, {:?}), outside the {w:?} × {top:?} box",
                    lower.x, lower.y, upper.x, upper.y
                ),
            ))
        }
    }

    /// Room for `n` more particles in every list.
    fn reserve(&mut self, n: usize) -> std::result::Result<(), std::collections::TryReserveError> {
        self.x.try_reserve(n)?;
        self.v.try_reserve(n)?;
        self.c.try_reserve(n)?;
        self.f.try_reserve(n)?;
        self.j.try_reserve(n)?;
        self.mass.try_reserve(n)?;
        self.volume.try_reserve(n)?;
        self.material.try_reserve(n)?;
        self.base.try_reserve(n)
    }
}

fn too_many(n: usize) -> Error {
    Error::invalid(
        "particles",
        format!("{n} particles are more than this machine can allocate"),
    )
}
