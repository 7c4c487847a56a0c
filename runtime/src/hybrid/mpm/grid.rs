//! The grid update of an MPM step: momentum to velocity, gravity, and the walls.

use rayon::prelude::*;

use super::{Mpm, Walls};
use crate::hybrid::strips::parallel;

impl Mpm {
    /// vᵢ = pᵢ/mᵢ + Δt·g on every node with mass (others get 0), then the walls: a node with
    /// i < wall or i > nx − wall loses its x velocity into the wall ([`Walls::Slip`]) or all of
    /// it ([`Walls::Sticky`]); likewise in j.
    pub(super) fn update_grid(&mut self, dt: f64) {
        let (nx, ny, wall) = (self.options.nx, self.options.ny, self.options.wall);
        let sticky = self.options.walls == Walls::Sticky;
        let g = self.options.gravity;
        let rows = self.strips.touched_rows();
        // Which side a node's index puts it against: −1 low wall, 1 high wall, 0 none.
        let side = |i: usize, n: usize| -> i8 {
            if i < wall {
                -1
            } else if i > n - wall {
                1
            } else {
                0
            }
        };
        let first = rows.start;
        let update = |(r, row): (usize, &mut [[f64; 3]])| {
            let wall_y = side(first + r, ny);
            for (i, node) in row.iter_mut().enumerate() {
                let m = node[2];
                if m <= 0.0 {
                    node[0] = 0.0;
                    node[1] = 0.0;
                    continue;
                }
                let mut v = [node[0] / m + dt * g.x, node[1] / m + dt * g.y];
                let wall_x = side(i, nx);
                if sticky && (wall_x != 0 || wall_y != 0) {
                    v = [0.0; 2];
                }
                // Into the wall: the velocity's sign matches the wall's side.
                if wall_x as f64 * v[0] > 0.0 {
                    v[0] = 0.0;
                }
                if wall_y as f64 * v[1] > 0.0 {
                    v[1] = 0.0;
                }
                node[0] = v[0];
                node[1] = v[1];
            }
        };
        let rows = &mut self.grid[rows.start * nx..rows.end * nx];
        if !parallel(self.mass.len()) {
            rows.chunks_mut(nx).enumerate().for_each(update);
        } else {
            rows.par_chunks_mut(nx)
                .with_min_len(8)
                .enumerate()
                .for_each(update);
        }
    }
}
