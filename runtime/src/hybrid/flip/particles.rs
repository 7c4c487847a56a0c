//! The FLIP fluid's transfers: particles to the u and v faces (by strips, as MPM), and the
//! faces back to the particles with the blend or APIC, then the midpoint move.

use nalgebra::{Matrix2, Vector2};
use rayon::prelude::*;

use super::Flip;
use super::mac::Mac;
use crate::hybrid::bspline::{Stencil, base_row};
use crate::hybrid::strips::parallel;
use crate::{Error, Result};

/// Particles a parallel task of the gather takes.
const CHUNK: usize = 512;

/// Where a face grid's nodes sit, in cells: u faces at (i, j + ½), v faces at (i + ½, j).
const OFFSETS: [[f64; 2]; 2] = [[0.0, 0.5], [0.5, 0.0]];

impl Flip {
    /// The fluid's room: particles may be in [h, (n − 1)h) on each axis.
    fn room(&self) -> ([f64; 2], [f64; 2]) {
        let h = self.options.cell;
        let (nx, ny) = (self.options.nx as f64, self.options.ny as f64);
        ([h, h], [(nx - 1.0) * h, (ny - 1.0) * h])
    }

    /// Whether `x` is in the room, judged in cells (x·(1/h) in [1, n − 1) on each axis): the
    /// arithmetic the transfers' stencils use, so that a particle judged inside has every
    /// stencil on the grid even where x·(1/h) rounds differently from x/h (h = 10⁻³⁰⁰ did).
    pub(super) fn inside_room(&self, x: Vector2<f64>) -> bool {
        let inv_h = 1.0 / self.options.cell;
        let (nx, ny) = (self.options.nx as f64, self.options.ny as f64);
        let (cx, cy) = (x.x * inv_h, x.y * inv_h);
        cx >= 1.0 && cx < nx - 1.0 && cy >= 1.0 && cy < ny - 1.0
    }

    /// Checks the public lists and finds each particle's stencil row on both face grids.
    pub(super) fn check_particles(&mut self) -> Result<()> {
        let n = self.c.len();
        if self.x.len() != n || self.v.len() != n {
            return Err(Error::invalid(
                "particles",
                format!(
                    "{} positions and {} velocities for {n} particles; add particles with \
                     `add_block` or `add_particles`",
                    self.x.len(),
                    self.v.len()
                ),
            ));
        }
        let (lo, hi) = self.room();
        if let Some(p) = self.x.iter().position(|x| !self.inside_room(*x)) {
            return Err(Error::invalid(
                format!("x[{p}]"),
                format!(
                    "({:?}, {:?}) is outside the fluid's room [{:?}, {:?}) × [{:?}, {:?}) \
                     inside the walls; move it inside",
                    self.x[p].x, self.x[p].y, lo[0], hi[0], lo[1], hi[1]
                ),
            ));
        }
        if let Some(p) = self.v.iter().position(|v| !v.iter().all(|c| c.is_finite())) {
            return Err(Error::invalid(
                format!("v[{p}]"),
                format!("({:?}, {:?}) is not finite", self.v[p].x, self.v[p].y),
            ));
        }
        let inv_h = 1.0 / self.options.cell;
        let rows = [self.options.ny, self.options.ny + 1];
        for (axis, list) in self.rows.iter_mut().enumerate() {
            list.clear();
            list.extend(self.x.iter().map(|x| {
                let y = x.y * inv_h - OFFSETS[axis][1];
                // In [½, rows − 3/2): `inside_room` judged y·(1/h) in [1, ny − 1).
                base_row(y, rows[axis]).unwrap_or(0) as u32
            }));
            self.strips[axis].sort(list, rows[axis]);
        }
        Ok(())
    }

    /// Each face gets Σ wᵢₚ·(vₚ + Cₚ(xᵢ − xₚ)) of its component (C under APIC only) and Σ wᵢₚ.
    pub(super) fn scatter(&mut self) {
        let h = self.options.cell;
        let inv_h = 1.0 / h;
        let affine = if self.options.transfer == crate::hybrid::Transfer::Apic {
            1.0
        } else {
            0.0
        };
        let nx = self.options.nx;
        let (x, v, c) = (&self.x, &self.v, &self.c);
        let Mac { u, v: vf, .. } = &mut self.mac;
        for (axis, (faces, row_len)) in [(u, nx + 1), (vf, nx)].into_iter().enumerate() {
            let [ox, oy] = OFFSETS[axis];
            let zero = |rows: &mut [[f64; 2]], _| rows.fill([0.0; 2]);
            let scatter = |band: &mut [[f64; 2]], first: usize, particles: &[u32]| {
                for &p in particles {
                    let p = p as usize;
                    let s = Stencil::at([x[p].x * inv_h - ox, x[p].y * inv_h - oy]);
                    let value = v[p][axis];
                    let slope = affine * h * c[p].row(axis).transpose();
                    // vₚ + C·(xᵢ − xₚ), xᵢ − xₚ = ((i, j) − fx)·h.
                    let start = value - slope.x * s.fx[0] - slope.y * s.fx[1];
                    for j in 0..3 {
                        let row = (s.base[1] + j - first) * row_len + s.base[0];
                        for i in 0..3 {
                            let w = s.w[0][i] * s.w[1][j];
                            let face = &mut band[row + i];
                            face[0] += w * (start + slope.x * i as f64 + slope.y * j as f64);
                            face[1] += w;
                        }
                    }
                }
            };
            self.strips[axis].scatter(faces, row_len, zero, scatter, |_, _| {});
        }
    }

    /// New velocities (and C) from the faces, then the midpoint move, clamped into the room.
    pub(super) fn gather(&mut self, dt: f64) {
        let h = self.options.cell;
        let flip = self.options.transfer.flip().ok().flatten();
        let (lo, hi) = self.room();
        // Half a millionth of a cell inside the room's edges, so that the next step's
        // `inside_room`, in cells, agrees whatever x·(1/h) rounds to.
        let lo = [lo[0] + 1e-6 * h, lo[1] + 1e-6 * h];
        let hi = [hi[0] - 1e-6 * h, hi[1] - 1e-6 * h];
        let mac = &self.mac;
        let chunk = |((x, v), c): Chunk<'_>| {
            for ((x, v), c) in x.iter_mut().zip(v.iter_mut()).zip(c.iter_mut()) {
                let now = sample(mac, *x, h);
                match flip {
                    None => {
                        *v = now.velocity;
                        *c = now.gradient;
                    }
                    Some(f) => {
                        *v = f * (*v + now.velocity - now.old) + (1.0 - f) * now.velocity;
                        *c = Matrix2::zeros();
                    }
                }
                let middle = clamp(*x + 0.5 * dt * now.velocity, lo, hi);
                let moved = *x + dt * sample(mac, middle, h).velocity + now.displacement;
                let inside = clamp(moved, lo, hi);
                // A particle pushed out of a wall keeps no velocity into it.
                for a in 0..2 {
                    if inside[a] != moved[a] && (moved[a] - inside[a]) * v[a] > 0.0 {
                        v[a] = 0.0;
                    }
                }
                *x = inside;
            }
        };
        if !parallel(self.x.len()) {
            self.x
                .chunks_mut(CHUNK)
                .zip(self.v.chunks_mut(CHUNK))
                .zip(self.c.chunks_mut(CHUNK))
                .for_each(chunk);
        } else {
            self.x
                .par_chunks_mut(CHUNK)
                .zip(self.v.par_chunks_mut(CHUNK))
                .zip(self.c.par_chunks_mut(CHUNK))
                .for_each(chunk);
        }
    }
}

/// A chunk of the gather: positions, velocities and affine velocities.
type Chunk<'a> = (
    (&'a mut [Vector2<f64>], &'a mut [Vector2<f64>]),
    &'a mut [Matrix2<f64>],
);

/// What the faces say at a point: velocity, the velocity before the forces, and APIC's C.
struct Sample {
    velocity: Vector2<f64>,
    old: Vector2<f64>,
    gradient: Matrix2<f64>,
    /// The volume correction's displacement.
    displacement: Vector2<f64>,
}

/// The B-spline interpolation of both face grids at `x` (inside the room).
fn sample(mac: &Mac, x: Vector2<f64>, h: f64) -> Sample {
    let inv_h = 1.0 / h;
    let mut out = Sample {
        velocity: Vector2::zeros(),
        old: Vector2::zeros(),
        gradient: Matrix2::zeros(),
        displacement: Vector2::zeros(),
    };
    let grids = [
        (&mac.u, &mac.u_old, &mac.du, mac.nx + 1),
        (&mac.v, &mac.v_old, &mac.dv, mac.nx),
    ];
    for (axis, (faces, old, shift, row_len)) in grids.into_iter().enumerate() {
        let [ox, oy] = OFFSETS[axis];
        let s = Stencil::at([x.x * inv_h - ox, x.y * inv_h - oy]);
        let (mut value, mut before, mut slope, mut moved) = (0.0, 0.0, [0.0; 2], 0.0);
        for j in 0..3 {
            let row = (s.base[1] + j) * row_len + s.base[0];
            for i in 0..3 {
                let w = s.w[0][i] * s.w[1][j];
                let wv = w * faces[row + i][0];
                value += wv;
                before += w * old[row + i];
                moved += w * shift[row + i][0];
                slope[0] += wv * (i as f64 - s.fx[0]);
                slope[1] += wv * (j as f64 - s.fx[1]);
            }
        }
        out.velocity[axis] = value;
        out.old[axis] = before;
        out.displacement[axis] = moved;
        // C's row: 4/h²·Σ w·vᵢ·(xᵢ − xₚ)ᵀ, with xᵢ − xₚ = ((i, j) − fx)·h.
        out.gradient[(axis, 0)] = 4.0 * inv_h * slope[0];
        out.gradient[(axis, 1)] = 4.0 * inv_h * slope[1];
    }
    out
}

/// `x` moved into [lo, hi] on each axis.
fn clamp(x: Vector2<f64>, lo: [f64; 2], hi: [f64; 2]) -> Vector2<f64> {
    Vector2::new(x.x.clamp(lo[0], hi[0]), x.y.clamp(lo[1], hi[1]))
}
