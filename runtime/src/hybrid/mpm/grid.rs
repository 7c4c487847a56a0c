//! The grid update of an MPM step: momentum to velocity, gravity, and the walls.

use nalgebra::Vector2;

use super::{MpmOptions, Walls};

/// What updates a row of nodes: the step and the options it reads.
#[derive(Clone, Copy, Debug)]
pub(super) struct Update {
    dt: f64,
    gravity: Vector2<f64>,
    wall: usize,
    nx: usize,
    ny: usize,
    sticky: bool,
}

impl Update {
    pub(super) fn new(options: &MpmOptions, dt: f64) -> Update {
        Update {
            dt,
            gravity: options.gravity,
            wall: options.wall,
            nx: options.nx,
            ny: options.ny,
            sticky: options.walls == Walls::Sticky,
        }
    }

    /// Which side a node's index puts it against: −1 low wall, 1 high wall, 0 none.
    #[inline]
    fn side(&self, i: usize, n: usize) -> i8 {
        if i < self.wall {
            -1
        } else if i > n - self.wall {
            1
        } else {
            0
        }
    }

    /// Row j: vᵢ = pᵢ/mᵢ + Δt·g on every node with mass (others get 0), then the walls: a node
    /// with i < wall or i > nx − wall loses its x velocity into the wall ([`Walls::Slip`]) or
    /// all of it ([`Walls::Sticky`]); likewise in j.
    pub(super) fn row(&self, j: usize, row: &mut [[f64; 3]]) {
        let (dt, g) = (self.dt, self.gravity);
        let wall_y = self.side(j, self.ny);
        for (i, node) in row.iter_mut().enumerate() {
            let m = node[2];
            if m <= 0.0 {
                node[0] = 0.0;
                node[1] = 0.0;
                continue;
            }
            let mut v = [node[0] / m + dt * g.x, node[1] / m + dt * g.y];
            let wall_x = self.side(i, self.nx);
            if self.sticky && (wall_x != 0 || wall_y != 0) {
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
    }
}
