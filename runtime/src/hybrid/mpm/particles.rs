//! The two transfers of an MPM step: particles to grid (the scatter, by strips, with each
//! particle's stress) and grid to particles (the gather, with the deformation update).

use nalgebra::{Matrix2, Vector2};
use rayon::prelude::*;

use super::Mpm;
use super::grid::Update;
use crate::hybrid::bspline::Stencil;
use crate::hybrid::strips::parallel;
use crate::hybrid::transfer::Transfer;

/// Particles a parallel task of the gather takes: fixed, so the work is split the same way on
/// any pool (each particle's result depends on nothing else anyway).
const CHUNK: usize = 512;

impl Mpm {
    /// Mass and momentum to the grid, and the grid update: each particle adds wᵢₚ·mₚ and
    /// wᵢₚ·(mₚvₚ + Aₚ·(xᵢ − xₚ)), Aₚ = mₚCₚ (APIC only) − Δt·4/h²·Vₚ⁰τₚ; each row, once all
    /// its particles have added to it, gets its velocities ([`Update::row`]). Rows no particle
    /// reaches are zero.
    pub(super) fn scatter(&mut self, dt: f64) {
        let (nx, h) = (self.options.nx, self.options.cell);
        let inv_h = 1.0 / h;
        // Rows written last step or this one: every other node is zero already.
        let now = self.strips.touched_rows();
        let clear = now.start.min(self.written.start)..now.end.max(self.written.end);
        self.written = now.clone();
        let update = Update::new(&self.options, dt);
        let prepare = |rows: &mut [[f64; 3]], first: usize| {
            let (low, high) = (
                clear.start.max(first),
                clear.end.min(first + rows.len() / nx),
            );
            if low < high {
                rows[(low - first) * nx..(high - first) * nx].fill([0.0; 3]);
            }
        };
        let finish = |rows: &mut [[f64; 3]], first: usize| {
            let (low, high) = (now.start.max(first), now.end.min(first + rows.len() / nx));
            for j in low..high {
                update.row(j, &mut rows[(j - first) * nx..(j - first + 1) * nx]);
            }
        };
        let affine = if self.options.transfer == Transfer::Apic {
            1.0
        } else {
            0.0
        };
        let impulse = -dt * 4.0 * inv_h * inv_h;
        let (x, v, c, mass) = (&self.x, &self.v, &self.c, &self.mass);
        let (f, j, volume) = (&self.f, &self.j, &self.volume);
        let (material, materials) = (&self.material, &self.materials);
        let scatter = |band: &mut [[f64; 3]], first: usize, particles: &[u32]| {
            for &p in particles {
                let p = p as usize;
                let s = Stencil::at([x[p].x * inv_h, x[p].y * inv_h]);
                let m = mass[p];
                // Vₚ⁰·τₚ, computed here from F and J rather than stored by the gather: a
                // fluid reads J (8 bytes) where a stored stress is written and read (24 each).
                let model = &materials[material[p] as usize].1;
                let [sxx, sxy, syy] = model.kirchhoff(&f[p], j[p]).map(|t| volume[p] * t);
                let a = (affine * m) * c[p] + impulse * Matrix2::new(sxx, sxy, sxy, syy);
                // A·(xᵢ − xₚ) with xᵢ − xₚ = ((i, j) − fx)·h, split so the loop adds columns.
                let q = m * v[p] - h * (a * Vector2::new(s.fx[0], s.fx[1]));
                let (a0, a1) = (h * a.column(0), h * a.column(1));
                for j in 0..3 {
                    let row = (s.base[1] + j - first) * nx + s.base[0];
                    let qj = q + a1 * j as f64;
                    let wy = s.w[1][j];
                    for i in 0..3 {
                        let w = s.w[0][i] * wy;
                        let momentum = qj + a0 * i as f64;
                        let node = &mut band[row + i];
                        node[0] += w * momentum.x;
                        node[1] += w * momentum.y;
                        node[2] += w * m;
                    }
                }
            }
        };
        self.strips
            .scatter(&mut self.grid, nx, prepare, scatter, finish);
    }

    /// Velocity and affine velocity from the grid, the move and the deformation of every
    /// particle (the stress is the scatter's, from the deformation). Returns the first particle that left the grid's reach, if any.
    pub(super) fn gather(&mut self, dt: f64) -> Option<usize> {
        let (nx, ny, h) = (self.options.nx, self.options.ny, self.options.cell);
        let inv_h = 1.0 / h;
        let (reach_x, reach_y) = (nx as f64 - 1.5, ny as f64 - 1.5);
        let grid = &self.grid;
        let (material, materials) = (&self.material, &self.materials);
        let chunk = |(k, ((((x, v), c), f), j)): Chunk<'_>| {
            let mut escaped = None;
            for i in 0..x.len() {
                let p = k * CHUNK + i;
                let s = Stencil::at([x[i].x * inv_h, x[i].y * inv_h]);
                let (mut vx, mut vy) = (0.0, 0.0);
                let mut b = [0.0; 4];
                for jj in 0..3 {
                    let row = (s.base[1] + jj) * nx + s.base[0];
                    let dy = jj as f64 - s.fx[1];
                    let wy = s.w[1][jj];
                    for ii in 0..3 {
                        let w = s.w[0][ii] * wy;
                        let node = grid[row + ii];
                        let (wvx, wvy) = (w * node[0], w * node[1]);
                        let dx = ii as f64 - s.fx[0];
                        vx += wvx;
                        vy += wvy;
                        b[0] += wvx * dx;
                        b[1] += wvy * dx;
                        b[2] += wvx * dy;
                        b[3] += wvy * dy;
                    }
                }
                // C = 4/h²·Σ w·v·(xᵢ − xₚ)ᵀ, with xᵢ − xₚ = ((i, j) − fx)·h.
                let scale = 4.0 * inv_h;
                c[i] = Matrix2::new(b[0], b[2], b[1], b[3]) * scale;
                v[i] = Vector2::new(vx, vy);
                x[i] += dt * v[i];
                let model = &materials[material[p] as usize].1;
                model.deform(&mut f[i], &mut j[i], &c[i], dt);
                let (gx, gy) = (x[i].x * inv_h, x[i].y * inv_h);
                let inside = gx >= 0.5 && gx < reach_x && gy >= 0.5 && gy < reach_y;
                if !inside && escaped.is_none() {
                    escaped = Some(p);
                }
            }
            escaped
        };
        let first = |a: Option<usize>, b: Option<usize>| a.into_iter().chain(b).min();
        if !parallel(self.mass.len()) {
            self.x
                .chunks_mut(CHUNK)
                .zip(self.v.chunks_mut(CHUNK))
                .zip(self.c.chunks_mut(CHUNK))
                .zip(self.f.chunks_mut(CHUNK))
                .zip(self.j.chunks_mut(CHUNK))
                .enumerate()
                .map(chunk)
                .fold(None, first)
        } else {
            self.x
                .par_chunks_mut(CHUNK)
                .zip(self.v.par_chunks_mut(CHUNK))
                .zip(self.c.par_chunks_mut(CHUNK))
                .zip(self.f.par_chunks_mut(CHUNK))
                .zip(self.j.par_chunks_mut(CHUNK))
                .enumerate()
                .map(chunk)
                .reduce(|| None, first)
        }
    }
}

/// A chunk of the particles the gather updates: its index, and its slices of x, v, C, F and J.
type Chunk<'a> = (
    usize,
    (
        (
            (
                (&'a mut [Vector2<f64>], &'a mut [Vector2<f64>]),
                &'a mut [Matrix2<f64>],
            ),
            &'a mut [Matrix2<f64>],
        ),
        &'a mut [f64],
    ),
);
