//! What a step checks of the particles before it touches them, and the error of a step that
//! lost one.

use rayon::prelude::*;

use super::Mpm;
use nalgebra::Vector2;

use crate::hybrid::bspline::base_row;
use crate::hybrid::strips::parallel;
use crate::{Error, Result};

/// Particles a parallel task of the check takes.
const CHUNK: usize = 2048;

/// A chunk of the check: its index, its stencil rows to write, its positions and velocities.
type Chunk<'a> = (
    usize,
    ((&'a mut [u32], &'a [Vector2<f64>]), &'a [Vector2<f64>]),
);

impl Mpm {
    /// Checks the public lists and finds each particle's stencil row for the scatter.
    ///
    /// Errors: [`Error::InvalidInput`] for position or velocity lists whose length changed, or
    /// the first particle outside the grid's reach or with a velocity that is not finite.
    pub(super) fn check_particles(&mut self) -> Result<()> {
        let n = self.mass.len();
        if self.x.len() != n || self.v.len() != n {
            return Err(Error::invalid(
                "particles",
                format!(
                    "{} positions and {} velocities for {n} particles; add particles with \
                     `add_block`, `add_disc` or `add_particles`",
                    self.x.len(),
                    self.v.len()
                ),
            ));
        }
        let (nx, ny) = (self.options.nx, self.options.ny);
        let inv_h = 1.0 / self.options.cell;
        self.base.resize(n, 0);
        let chunk = |(k, ((base, x), v)): Chunk<'_>| {
            let mut bad = None;
            for (i, ((b, x), v)) in base.iter_mut().zip(x).zip(v).enumerate() {
                let row = base_row(x.y * inv_h, ny);
                let column = base_row(x.x * inv_h, nx);
                *b = row.unwrap_or(0) as u32;
                let ok = row.is_some() && column.is_some() && v.iter().all(|c| c.is_finite());
                if !ok && bad.is_none() {
                    bad = Some(k * CHUNK + i);
                }
            }
            bad
        };
        let first = |a: Option<usize>, b: Option<usize>| a.into_iter().chain(b).min();
        let bad = if !parallel(n) {
            self.base
                .chunks_mut(CHUNK)
                .zip(self.x.chunks(CHUNK))
                .zip(self.v.chunks(CHUNK))
                .enumerate()
                .map(chunk)
                .fold(None, first)
        } else {
            self.base
                .par_chunks_mut(CHUNK)
                .zip(self.x.par_chunks(CHUNK))
                .zip(self.v.par_chunks(CHUNK))
                .enumerate()
                .map(chunk)
                .reduce(|| None, first)
        };
        match bad {
            None => Ok(()),
            Some(p) => {
                let (x, v) = (self.x[p], self.v[p]);
                if !v.iter().all(|c| c.is_finite()) {
                    return Err(Error::invalid(
                        format!("v[{p}]"),
                        format!("({:?}, {:?}) is not finite", v.x, v.y),
                    ));
                }
                Err(Error::invalid(
                    format!("x[{p}]"),
                    format!(
                        "({:?}, {:?}) is outside the region the grid reaches, {}; move it inside",
                        x.x,
                        x.y,
                        self.reach()
                    ),
                ))
            }
        }
    }

    /// The region particles may occupy, as text.
    pub(super) fn reach(&self) -> String {
        let h = self.options.cell;
        let (nx, ny) = (self.options.nx as f64, self.options.ny as f64);
        format!(
            "[{:?}, {:?}) × [{:?}, {:?}) (half a cell to one and a half cells inside the {:?} × \
             {:?} box)",
            0.5 * h,
            (nx - 1.5) * h,
            0.5 * h,
            (ny - 1.5) * h,
            nx * h,
            ny * h
        )
    }

    /// The error of a step after which particle `p` is outside the grid's reach.
    pub(super) fn escape_error(&self, p: usize, dt: f64) -> Error {
        let x = self.x[p];
        if !x.iter().all(|c| c.is_finite()) {
            let value = if x.x.is_finite() { x.y } else { x.x };
            return Error::NotFinite {
                solver: "Mpm",
                step: self.steps,
                t: self.t,
                dt,
                component: format!("x[{p}]"),
                value,
                advice: "take shorter steps (see `Mpm::stable_dt`) or soften the materials",
            };
        }
        Error::invalid(
            format!("x[{p}]"),
            format!(
                "particle {p} left the region the grid reaches, {}, at step {} (t = {:?}) to \
                 ({:?}, {:?}); take shorter steps (see `Mpm::stable_dt`) or thicker walls",
                self.reach(),
                self.steps,
                self.t,
                x.x,
                x.y
            ),
        )
    }
}
