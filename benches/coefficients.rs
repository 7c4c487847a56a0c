//! A coefficient read from a coefficient `Grid` against the same coefficient computed in the
//! cell method: a 96² diffusion u̇ = κ·∇²u with κ = 1 on the left half and 0.1 on the right,
//! once as a parameter grid read through a `Stencil` (`Grid`), once as an `if` on the cell's
//! position (`Inline`). Both give the same rates bit for bit (checked before timing); the grid
//! should cost at most 1.3× the inline form (issue 52).
//!
//! `cargo bench --bench coefficients`

use odyn::prelude::*;

fn main() {
    divan::main();
}

const N: usize = 96;

#[system(integrator = Rk4, dt = 1e-5)]
/// κ from a coefficient grid.
pub struct FromGrid {
    #[field]
    /// The diffused field.
    pub u: Grid,
    /// The diffusivity at each cell.
    pub kappa: Grid,
}

#[system]
impl FromGrid {
    #[cell]
    fn rate(&self, u: Stencil, kappa: Stencil) -> f64 {
        kappa.c * u.laplacian()
    }
}

#[system(integrator = Rk4, dt = 1e-5)]
/// κ from the position.
pub struct Inline {
    #[field]
    /// The diffused field.
    pub u: Grid,
}

#[system]
impl Inline {
    #[cell]
    fn rate(&self, u: Stencil, x: f64) -> f64 {
        let kappa = if x < 0.5 { 1.0 } else { 0.1 };
        kappa * u.laplacian()
    }
}

fn start(i: usize, j: usize) -> f64 {
    ((i * 7 + j * 13) % 17) as f64 / 17.0
}

fn spaced(grid: Grid) -> Grid {
    grid.with_spacing(1.0 / N as f64, 1.0 / N as f64)
        .expect("a positive spacing")
}

fn models() -> (FromGrid, Inline) {
    let u = || spaced(Grid::from_fn(N, N, Boundary::Periodic, start).expect("a grid"));
    let kappa = Grid::from_fn(N, N, Boundary::Periodic, |i, _| {
        if (i as f64 / N as f64) < 0.5 {
            1.0
        } else {
            0.1
        }
    })
    .expect("a grid");
    let from_grid = FromGrid {
        u: u(),
        kappa: spaced(kappa),
    };
    let inline = Inline { u: u() };
    // The same rates, bit for bit, or the race is not fair.
    let (a, b) = (from_grid.state(), inline.state());
    let (mut da, mut db) = (a.clone(), b.clone());
    from_grid.derivative(0.0, &a, &mut da);
    inline.derivative(0.0, &b, &mut db);
    assert_eq!(da.as_slice(), db.as_slice(), "the two models differ");
    (from_grid, inline)
}

/// One evaluation of the rate at every cell, κ from the coefficient grid.
#[divan::bench(sample_count = 200)]
fn rate_coefficient_grid(bencher: divan::Bencher) {
    let (model, _) = models();
    let y = model.state();
    let mut dydt = y.clone();
    bencher.bench_local(|| model.derivative(0.0, divan::black_box(&y), &mut dydt));
}

/// One evaluation of the rate at every cell, κ from an `if` on the position.
#[divan::bench(sample_count = 200)]
fn rate_inline(bencher: divan::Bencher) {
    let (_, model) = models();
    let y = model.state();
    let mut dydt = y.clone();
    bencher.bench_local(|| model.derivative(0.0, divan::black_box(&y), &mut dydt));
}
