//! Liquid for the FLIP box: a block, or any set of points.

use std::ops::Range;

use nalgebra::{Matrix2, Vector2};

use super::Flip;
use crate::{Error, Result};

impl Flip {
    /// Adds particles at `positions` moving at `velocity(x)`. Returns their indices.
    ///
    /// Errors: [`Error::InvalidInput`] (nothing added) for a position outside the fluid's room
    /// (see [`Flip::step`]), a velocity that is not finite, or more particles than memory
    /// holds or 2³² in all.
    pub fn add_particles(
        &mut self,
        positions: &[Vector2<f64>],
        velocity: impl Fn(Vector2<f64>) -> Vector2<f64>,
    ) -> Result<Range<usize>> {
        let h = self.options.cell;
        let (w, top) = (
            (self.options.nx - 1) as f64 * h,
            (self.options.ny - 1) as f64 * h,
        );
        let start = self.x.len();
        if start
            .checked_add(positions.len())
            .is_none_or(|n| n > u32::MAX as usize)
        {
            return Err(Error::invalid("positions", "more than 2³² particles"));
        }
        let mut speeds = Vec::new();
        speeds
            .try_reserve_exact(positions.len())
            .map_err(|_| too_many(positions.len()))?;
        for (k, x) in positions.iter().enumerate() {
            if !self.inside_room(*x) {
                return Err(Error::invalid(
                    format!("positions[{k}]"),
                    format!(
                        "({:?}, {:?}) is outside the fluid's room [{h:?}, {w:?}) × [{h:?}, \
                         {top:?}) inside the walls",
                        x.x, x.y
                    ),
                ));
            }
            let v = velocity(*x);
            if !v.iter().all(|c| c.is_finite()) {
                return Err(Error::invalid(
                    format!("velocity at positions[{k}]"),
                    format!("({:?}, {:?}) is not finite", v.x, v.y),
                ));
            }
            speeds.push(v);
        }
        let n = positions.len();
        (self.x.try_reserve(n))
            .and(self.v.try_reserve(n))
            .and(self.c.try_reserve(n))
            .and(self.rows[0].try_reserve(n))
            .and(self.rows[1].try_reserve(n))
            .map_err(|_| too_many(n))?;
        self.x.extend_from_slice(positions);
        self.v.extend(speeds);
        self.c.resize(start + n, Matrix2::zeros());
        Ok(start..start + n)
    }

    /// Fills the rectangle [lower, upper] with liquid at rest or moving at `velocity(x)`:
    /// particles on a square lattice of h/[`FlipOptions::sampling`](super::FlipOptions::sampling),
    /// the first half a spacing in from `lower`. Returns their indices.
    ///
    /// Errors: [`Error::InvalidInput`] for corners that are not finite, not ordered, less than a
    /// spacing apart or outside the fluid's room, or what [`Flip::add_particles`] refuses.
    pub fn add_block(
        &mut self,
        lower: Vector2<f64>,
        upper: Vector2<f64>,
        velocity: impl Fn(Vector2<f64>) -> Vector2<f64>,
    ) -> Result<Range<usize>> {
        let h = self.options.cell;
        let spacing = h / self.options.sampling as f64;
        let (w, top) = (
            (self.options.nx - 1) as f64 * h,
            (self.options.ny - 1) as f64 * h,
        );
        let size = upper - lower;
        let inside = lower.x >= h && lower.y >= h && upper.x <= w && upper.y <= top;
        if !(inside && size.x >= spacing && size.y >= spacing) {
            return Err(Error::invalid(
                "block",
                format!(
                    "corners ({:?}, {:?}) and ({:?}, {:?}) must be ordered, at least a particle \
                     spacing ({spacing:?}) apart and inside the fluid's room [{h:?}, {w:?}] × \
                     [{h:?}, {top:?}]",
                    lower.x, lower.y, upper.x, upper.y
                ),
            ));
        }
        let (cols, rows) = (
            (size.x / spacing).round() as usize,
            (size.y / spacing).round() as usize,
        );
        let mut points = Vec::new();
        points
            .try_reserve_exact(cols * rows)
            .map_err(|_| too_many(cols * rows))?;
        for j in 0..rows {
            for i in 0..cols {
                points.push(lower + Vector2::new(i as f64 + 0.5, j as f64 + 0.5) * spacing);
            }
        }
        self.add_particles(&points, velocity)
    }
}

fn too_many(n: usize) -> Error {
    Error::invalid(
        "particles",
        format!("{n} particles are more than this machine can allocate"),
    )
}
