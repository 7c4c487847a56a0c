//! Field models on the heat equation u_t = D∇²u on the unit square, u = 0 on the boundary
//! (vertex-centred: the grid holds the n × n interior nodes, dx = 1/(n + 1)).
//!
//! The initial state sin(πx)·sin(πy) + ½·sin(2πx)·sin(3πy) is a sum of eigenvectors of both
//! the continuous and the discrete Laplacian, so both solutions are known in closed form:
//! each mode decays as exp(λt), with λ = −Dπ²(m² + k²) for the PDE and
//! λ_h = −(4D/dx²)(sin²(mπdx/2) + sin²(kπdx/2)) for the five-point grid (the semi-discrete
//! system). Comparing against the first measures the spatial error, against the second the
//! time integrator's alone.
//!
//! The heat equation's tests are in `heat.rs`, Gray–Scott's (two coupled fields) in
//! `gray_scott.rs`, what a cell kernel may read and do in `cells.rs`, typed errors in
//! `errors.rs`; `budget.rs` installs this binary's global allocator. The models and checks they
//! share are here.

mod budget;
mod cells;
mod errors;
mod gray_scott;
mod heat;

use std::f64::consts::PI;

use odyn::grid::{Boundary, Grid, GridState, Stencil};
use odyn::{Jacobian, State, system};

/// u_t = D∇²u.
#[system(integrator = ImplicitEuler, dt = 1e-3)]
pub struct Heat {
    /// Temperature at the interior nodes.
    #[field]
    pub u: Grid,
    /// D.
    pub diffusivity: f64,
    /// Node spacing.
    pub dx: f64,
}

#[system]
impl Heat {
    #[cell]
    fn diffusion(&self, u: Stencil) -> f64 {
        self.diffusivity * u.laplacian() / (self.dx * self.dx)
    }
}

/// The two modes (m, k, amplitude) of the initial state.
const MODES: [(f64, f64, f64); 2] = [(1.0, 1.0, 1.0), (2.0, 3.0, 0.5)];
const D: f64 = 0.1;

fn heat(n: usize) -> Heat {
    let dx = 1.0 / (n as f64 + 1.0);
    let u = Grid::from_fn(n, n, Boundary::Dirichlet(0.0), |i, j| {
        exact(dx, i, j, 0.0, |_, _| 0.0)
    })
    .unwrap();
    Heat {
        u,
        diffusivity: D,
        dx,
    }
}

/// The solution at node (i, j) and time t, each mode decaying at rate `rate(m, k)` (0 uses the
/// PDE's rate).
fn exact(dx: f64, i: usize, j: usize, t: f64, rate: impl Fn(f64, f64) -> f64) -> f64 {
    let (x, y) = ((i + 1) as f64 * dx, (j + 1) as f64 * dx);
    MODES
        .iter()
        .map(|&(m, k, a)| {
            let r = rate(m, k);
            let r = if r == 0.0 {
                -D * PI * PI * (m * m + k * k)
            } else {
                r
            };
            a * (m * PI * x).sin() * (k * PI * y).sin() * (r * t).exp()
        })
        .sum()
}

// Gray–Scott (`scenes/src/fields.rs`): two fields coupled through u·v², for the two-field
// Jacobian, Neumann and periodic boundaries, and every integrator.
pub(crate) use scenes::GrayScott;

/// A small Gray–Scott grid, `boundary` on both fields, with smooth non-uniform fields.
pub(crate) fn gray_scott(n: usize, boundary: Boundary) -> GrayScott {
    let field = |a: f64, b: f64| {
        Grid::from_fn(n, n, boundary, |i, j| {
            a + b * ((i as f64 * 0.7).sin() + (j as f64 * 1.3).cos())
        })
        .unwrap()
    };
    GrayScott {
        u: field(0.7, 0.1),
        v: field(0.2, 0.05),
        du: 2e-5,
        dv: 1e-5,
        feed: 0.037,
        kill: 0.06,
        // Coarse cells keep diffusion slow beside the reaction (D_u/dx² = 0.008): the methods'
        // orders, not their stability, decide the errors.
        dx: 0.05,
    }
}

/// The dense J of `model` at its state against central differences of its f.
fn check_jacobian<M>(model: &M)
where
    M: Jacobian<Matrix = odyn::grid::GridJacobian, State = GridState>,
{
    check_jacobian_at(model, 0.0);
}

/// [`check_jacobian`] at time t.
fn check_jacobian_at<M>(model: &M, t: f64)
where
    M: Jacobian<Matrix = odyn::grid::GridJacobian, State = GridState>,
{
    let state = model.state();
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(t, &state, &mut jacobian);
    let dense = jacobian.to_dense();
    let n = state.as_slice().len();
    let (mut plus, mut minus, mut fp, mut fm) =
        (state.clone(), state.clone(), state.clone(), state.clone());
    let h = 1e-6;
    let scale = dense.norm_max();
    for c in 0..n {
        plus.clone_from(&state);
        minus.clone_from(&state);
        plus.as_mut_slice()[c] += h;
        minus.as_mut_slice()[c] -= h;
        model.derivative(t, &plus, &mut fp);
        model.derivative(t, &minus, &mut fm);
        for r in 0..n {
            let fd = (fp.as_slice()[r] - fm.as_slice()[r]) / (2.0 * h);
            assert!(
                (dense[(r, c)] - fd).abs() <= 1e-7 * scale,
                "J[{r}][{c}] = {} but finite differences give {fd}",
                dense[(r, c)]
            );
        }
    }
}
