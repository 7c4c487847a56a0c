//! Field models with `#[algebraic]` fields under hostile input: exact solutions on every
//! boundary and implicit method, orders, the field model against the same system written
//! fixed-size (`exact.rs`); inconsistent, singular and index-2 starts on the dense and the
//! sparse ∂g/∂z (`starts.rs`); refusals, linear solvers, events, `save_at`, dense output,
//! `Stepper` and absurd options (`runs.rs`).

use odyn::grid::{Boundary, Grid, Stencil};
use odyn::prelude::*;

mod exact;
mod runs;
mod starts;

/// U_t = −u + z, 0 = z − 2u: u′ = u, so u = u₀·eᵗ and z = 2u exactly.
#[system]
#[derive(Clone, Debug)]
pub(crate) struct Grow {
    #[field]
    pub(crate) u: Grid,
    #[field]
    #[algebraic]
    pub(crate) z: Grid,
}

#[system]
impl Grow {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [-u.c + z.c, z.c - 2.0 * u.c]
    }
}

/// The same system, fixed size (3 cells).
#[system]
#[derive(Clone, Copy, Debug)]
pub(crate) struct GrowFixed {
    #[state]
    pub(crate) u: [f64; 3],
    #[algebraic]
    pub(crate) z: [f64; 3],
}

#[system]
impl GrowFixed {
    fn derivative(&self) -> GrowFixedState {
        let mut u = [0.0; 3];
        let mut z = [0.0; 3];
        for i in 0..3 {
            u[i] = -self.u[i] + self.z[i];
            z[i] = self.z[i] - 2.0 * self.u[i];
        }
        GrowFixedState { u, z }
    }
}

/// U_t = z, 0 = z − ∇²u (five-point, unit spacing): u′ = ∇²_h u, the discrete heat equation,
/// whose eigenvectors are known per boundary.
#[system]
#[derive(Clone, Debug)]
pub(crate) struct Lap {
    #[field]
    pub(crate) u: Grid,
    #[field]
    #[algebraic]
    pub(crate) z: Grid,
}

#[system]
impl Lap {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [z.c, z.c - u.laplacian()]
    }
}

/// U_t = z, 0 = u − 1: g does not read z (index 2).
#[system]
#[derive(Clone, Debug)]
pub(crate) struct IndexTwo {
    #[field]
    pub(crate) u: Grid,
    #[field]
    #[algebraic]
    pub(crate) z: Grid,
}

#[system]
impl IndexTwo {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [z.c, u.c - 1.0]
    }
}

/// U_t = −u, 0 = z³ − 8 (z = 2 whatever u).
#[system]
#[derive(Clone, Debug)]
pub(crate) struct Cubic {
    #[field]
    pub(crate) u: Grid,
    #[field]
    #[algebraic]
    pub(crate) z: Grid,
}

#[system]
impl Cubic {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [-u.c, z.c * z.c * z.c - 8.0]
    }
}

/// 0 = z, 0 = w − z: every field algebraic (M = 0). The macro takes it; the solution is the
/// constant z = w = 1 (g = [z − 1, w − z]).
#[system]
#[derive(Clone, Debug)]
pub(crate) struct AllAlg {
    #[field]
    #[algebraic]
    pub(crate) z: Grid,
    #[field]
    #[algebraic]
    pub(crate) w: Grid,
}

#[system]
impl AllAlg {
    #[cell]
    fn rates(&self, z: Stencil, w: Stencil) -> [f64; 2] {
        [z.c - 1.0, w.c - z.c]
    }
}

/// U′ = −u, 0 = z − z.e (periodic): ∂g/∂z = I − shift is singular without an empty column (the
/// constants are its null space), so z is determined only up to a constant.
#[system]
#[derive(Clone, Debug)]
pub(crate) struct Shift {
    #[field]
    pub(crate) u: Grid,
    #[field]
    #[algebraic]
    pub(crate) z: Grid,
}

#[system]
impl Shift {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [-u.c, z.c - z.e]
    }
}

pub(crate) const IMPLICIT: [Method; 4] = [
    Method::Rodas5P,
    Method::Rosenbrock23,
    Method::Bdf,
    Method::ImplicitEuler,
];

pub(crate) fn grid(nx: usize, ny: usize, b: Boundary, f: impl Fn(usize, usize) -> f64) -> Grid {
    Grid::from_fn(nx, ny, b, f).unwrap()
}

pub(crate) fn try_grow(nx: usize, ny: usize, b: Boundary, z0: f64) -> odyn::Result<Grow> {
    Ok(Grow {
        u: Grid::from_fn(nx, ny, b, |i, j| 1.0 + 0.1 * i as f64 + 0.01 * j as f64)?,
        z: Grid::from_fn(nx, ny, b, |_, _| z0)?,
    })
}

pub(crate) fn grow(nx: usize, ny: usize, b: Boundary, z0: f64) -> Grow {
    Grow {
        u: grid(nx, ny, b, |i, j| 1.0 + 0.1 * i as f64 + 0.01 * j as f64),
        z: grid(nx, ny, b, |_, _| z0),
    }
}

pub(crate) fn boundaries() -> [Boundary; 4] {
    [
        Boundary::Periodic,
        Boundary::Neumann,
        Boundary::Dirichlet(0.0),
        Boundary::Dirichlet(3.5),
    ]
}

/// Runs `model` to t = 1 with `method`: adaptive at (1e-8, 1e-10), or 1 000 fixed steps.
pub(crate) fn to_one<M: Simulate + odyn::Model>(
    model: &M,
    method: Method,
) -> odyn::Result<odyn::Trajectory<M::State>> {
    let s = model.simulate().integrator(method);
    if method.is_adaptive() {
        s.tolerances(1e-8, 1e-10).duration(1.0).run()
    } else {
        s.dt(1e-3).steps(1000).run()
    }
}
