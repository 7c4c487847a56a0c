//! The liquid a run starts from: a block of fluid particles on a square lattice, and the
//! walls' three layers of boundary particles.

use nalgebra::Vector2;

use super::neighbours::Grid;
use super::{Sph, SphOptions};
use crate::{Error, Result};

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
}
