//! The staggered (MAC) grid of the FLIP fluid: face velocities, the cells' labels, gravity, the
//! solid walls and the extrapolation of velocity into the air.

/// What a cell holds.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Cell {
    /// A wall (the ring of border cells).
    Solid,
    /// At least one particle.
    Fluid,
    /// Neither: pressure 0.
    Air,
}

/// A MAC grid of nx × ny cells of side h (Harlow & Welch 1965): u on the vertical faces,
/// (nx + 1)·ny values, face (i, j) at (i·h, (j + ½)h); v on the horizontal faces, nx·(ny + 1),
/// at ((i + ½)h, j·h). Each face holds [velocity, weight]: during the transfer, the weighted
/// momentum and the weights' sum; after it, the velocity and that sum.
#[derive(Clone, Debug)]
pub(crate) struct Mac {
    pub nx: usize,
    pub ny: usize,
    pub u: Vec<[f64; 2]>,
    pub v: Vec<[f64; 2]>,
    /// The velocities before the forces and the projection, for FLIP's difference.
    pub u_old: Vec<f64>,
    pub v_old: Vec<f64>,
    /// The volume correction's displacement (m) on the faces, laid out as u and v.
    pub du: Vec<[f64; 2]>,
    pub dv: Vec<[f64; 2]>,
    /// Cell-centred particle density (i + j·nx), see [`super::Flip::density`].
    pub density: Vec<f64>,
    pub cells: Vec<Cell>,
    /// Whether each face's velocity is known (next to fluid, or a wall), while extrapolating.
    known_u: Vec<bool>,
    known_v: Vec<bool>,
    /// What was known before an extrapolation layer.
    before: Vec<bool>,
}

impl Mac {
    /// An empty grid: every border cell solid, the rest air.
    pub fn new(nx: usize, ny: usize) -> Mac {
        let cells = (0..nx * ny)
            .map(|k| {
                let (i, j) = (k % nx, k / nx);
                if i == 0 || j == 0 || i == nx - 1 || j == ny - 1 {
                    Cell::Solid
                } else {
                    Cell::Air
                }
            })
            .collect();
        Mac {
            nx,
            ny,
            u: vec![[0.0; 2]; (nx + 1) * ny],
            v: vec![[0.0; 2]; nx * (ny + 1)],
            u_old: vec![0.0; (nx + 1) * ny],
            v_old: vec![0.0; nx * (ny + 1)],
            du: vec![[0.0; 2]; (nx + 1) * ny],
            dv: vec![[0.0; 2]; nx * (ny + 1)],
            density: vec![0.0; nx * ny],
            cells,
            known_u: vec![false; (nx + 1) * ny],
            known_v: vec![false; nx * (ny + 1)],
            before: Vec::with_capacity((nx + 1) * (ny + 1)),
        }
    }

    /// Cell (i, j).
    #[inline]
    pub fn cell(&self, i: usize, j: usize) -> Cell {
        self.cells[i + j * self.nx]
    }

    /// Marks every non-solid cell that holds a particle (positions in cells) fluid, the rest
    /// air.
    pub fn classify(&mut self, cells_of: impl Iterator<Item = (usize, usize)>) {
        for c in &mut self.cells {
            if *c == Cell::Fluid {
                *c = Cell::Air;
            }
        }
        let nx = self.nx;
        for (i, j) in cells_of {
            let c = &mut self.cells[i + j * nx];
            if *c == Cell::Air {
                *c = Cell::Fluid;
            }
        }
    }

    /// Momentum to velocity on every face with weight (0 elsewhere), and those velocities kept
    /// as the old ones.
    pub fn normalise(&mut self) {
        for (face, old) in self
            .u
            .iter_mut()
            .zip(&mut self.u_old)
            .chain(self.v.iter_mut().zip(&mut self.v_old))
        {
            face[0] = if face[1] > 0.0 {
                face[0] / face[1]
            } else {
                0.0
            };
            *old = face[0];
        }
    }

    /// v += dt·g on the horizontal faces (and u likewise).
    pub fn accelerate(&mut self, g: [f64; 2], dt: f64) {
        for face in &mut self.u {
            face[0] += dt * g[0];
        }
        for face in &mut self.v {
            face[0] += dt * g[1];
        }
    }

    /// The walls: velocity 0 on every face of a solid cell.
    pub fn walls(&mut self) {
        let (nx, ny) = (self.nx, self.ny);
        for j in 0..ny {
            for i in 0..=nx {
                let solid = i == 0 || i == nx || self.cell(i - 1, j) == Cell::Solid || {
                    self.cell(i, j) == Cell::Solid
                };
                if solid {
                    self.u[i + j * (nx + 1)][0] = 0.0;
                }
            }
        }
        for j in 0..=ny {
            for i in 0..nx {
                let solid = j == 0 || j == ny || self.cell(i, j - 1) == Cell::Solid || {
                    self.cell(i, j) == Cell::Solid
                };
                if solid {
                    self.v[i + j * nx][0] = 0.0;
                }
            }
        }
    }

    /// Velocity into the air: a face with no fluid cell beside it (and not a wall) gets the
    /// mean of its known neighbours along the grid, `layers` times outward (Bridson 2015, §4.4),
    /// so particles near the surface read a velocity the projection made.
    pub fn extrapolate(&mut self, layers: usize) {
        let (nx, ny) = (self.nx, self.ny);
        let fluid = |c: Cell| c == Cell::Fluid;
        for j in 0..ny {
            for i in 0..=nx {
                let beside =
                    (i > 0 && fluid(self.cell(i - 1, j))) || (i < nx && fluid(self.cell(i, j)));
                let wall = i == 0
                    || i == nx
                    || self.cell(i - 1, j) == Cell::Solid
                    || self.cell(i, j) == Cell::Solid;
                self.known_u[i + j * (nx + 1)] = beside || wall;
            }
        }
        for j in 0..=ny {
            for i in 0..nx {
                let beside =
                    (j > 0 && fluid(self.cell(i, j - 1))) || (j < ny && fluid(self.cell(i, j)));
                let wall = j == 0
                    || j == ny
                    || self.cell(i, j - 1) == Cell::Solid
                    || self.cell(i, j) == Cell::Solid;
                self.known_v[i + j * nx] = beside || wall;
            }
        }
        for _ in 0..layers {
            extend(&mut self.u, &mut self.known_u, &mut self.before, nx + 1, ny);
            extend(&mut self.v, &mut self.known_v, &mut self.before, nx, ny + 1);
        }
    }
}

/// One layer of extrapolation on a `w` × `h` array of faces: each unknown face with a known
/// neighbour (left, right, below, above) takes their mean and becomes known. `before` is
/// scratch.
fn extend(faces: &mut [[f64; 2]], known: &mut [bool], before: &mut Vec<bool>, w: usize, h: usize) {
    before.clear();
    before.extend_from_slice(known);
    for j in 0..h {
        for i in 0..w {
            let k = i + j * w;
            if before[k] {
                continue;
            }
            let neighbours = [
                (i > 0).then(|| k - 1),
                (i + 1 < w).then(|| k + 1),
                (j > 0).then(|| k - w),
                (j + 1 < h).then(|| k + w),
            ];
            let (mut sum, mut count) = (0.0, 0.0);
            for n in neighbours.into_iter().flatten() {
                if before[n] {
                    sum += faces[n][0];
                    count += 1.0;
                }
            }
            if count > 0.0 {
                faces[k][0] = sum / count;
                known[k] = true;
            }
        }
    }
}
