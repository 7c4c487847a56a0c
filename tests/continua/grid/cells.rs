//! What a cell kernel may read and do: branch on the state, read its position and the time,
//! switch a source on in time, read coefficient grids, shadow the time.

use odyn::grid::{Boundary, Grid, Stencil};
use odyn::{Error, Jacobian, Model, Simulate, system};

use super::{check_jacobian, check_jacobian_at};

/// A threshold reaction written as an `if` on the cell's value (a bistable medium: growth above
/// 1/2, decay below) and a flux that switches on against a neighbour: the cell kernel's branches
/// on the state are differentiated arm by arm, placed through the grid like any block.
#[system]
pub struct Threshold {
    /// The medium.
    #[field]
    pub u: Grid,
    /// Diffusivity over dx².
    pub d: f64,
}

#[system]
impl Threshold {
    #[cell]
    fn rate(&self, u: Stencil) -> f64 {
        let reaction = if u.c > 0.5 {
            u.c * (1.0 - u.c)
        } else {
            -u.c * u.c
        };
        let mut flux = self.d * u.laplacian();
        if u.e >= u.c {
            flux += 0.3 * (u.e - u.c);
        }
        reaction + flux
    }
}

#[test]
fn a_cell_branching_on_the_state_has_the_jacobian_of_its_arms() {
    // Values spread over [0, 1] so both arms of each branch are taken, none within 1e-6 (the
    // difference step) of a switching surface: 0.5, or a neighbour's value.
    let value =
        |i: usize, j: usize| 0.05 + 0.9 * (((7 * i + 3 * j) % 11) as f64 / 10.0) + 0.001 * j as f64;
    for boundary in [Boundary::Periodic, Boundary::Neumann] {
        let u = Grid::from_fn(6, 5, boundary, value).unwrap();
        check_jacobian(&Threshold { u, d: 0.7 });
    }
}

/// u_t = −k·u + (x + 2y)·cos t and w_t = D∇²w − w·u·sin(x·t): a cell that reads its position
/// and the time.
#[system(integrator = Rodas5P, rtol = 1e-9, atol = 1e-12)]
pub struct Placed {
    /// Driven at each cell by its position.
    #[field]
    pub u: Grid,
    /// Diffusing, damped by u.
    #[field]
    pub w: Grid,
    /// k.
    pub k: f64,
}

#[system]
impl Placed {
    #[cell]
    fn rate(&self, u: Stencil, w: Stencil, t: f64, x: f64, y: f64) -> [f64; 2] {
        [
            -self.k * u.c + (x + 2.0 * y) * t.cos(),
            0.1 * w.laplacian() - w.c * u.c * (x * t).sin(),
        ]
    }
}

/// An 8 × 6 Neumann grid with cell (0, 0) at (−0.5, 0.25), Δx = 0.2, Δy = 0.3.
fn placed() -> Placed {
    let grid = |value: &dyn Fn(usize, usize) -> f64| {
        Grid::from_fn(8, 6, Boundary::Neumann, value)
            .and_then(|g| g.with_origin(-0.5, 0.25))
            .and_then(|g| g.with_spacing(0.2, 0.3))
            .unwrap()
    };
    Placed {
        u: grid(&|i, j| 0.1 * i as f64 - 0.05 * j as f64),
        w: grid(&|i, j| 1.0 + 0.01 * (i * j) as f64),
        k: 1.0,
    }
}

#[test]
fn a_cell_reads_its_position_and_the_time() {
    let model = placed();
    let state = model.state();
    let t = 0.7;
    // f at every cell: the position from the origin and spacing, k = j·nx + i.
    let mut rate = state.clone();
    model.derivative(t, &state, &mut rate);
    for j in 0..6 {
        for i in 0..8 {
            let (x, y) = (-0.5 + i as f64 * 0.2, 0.25 + j as f64 * 0.3);
            assert_eq!(model.u.position(i, j), (x, y));
            let u = state.field(0)[j * 8 + i];
            let expected = -u + (x + 2.0 * y) * t.cos();
            assert_eq!(rate.field(0)[j * 8 + i], expected, "cell ({i}, {j})");
        }
    }
    // J against central differences, at t = 0.7 (the position and time are parameters of J).
    check_jacobian_at(&model, t);
    // ∂f/∂t generated: −(x + 2y)·sin t and −w·u·x·cos(x·t), against the closed form.
    const { assert!(<Placed as Jacobian>::TIME_DEPENDENT) };
    let mut dfdt = state.clone();
    model.time_derivative(t, &state, &mut dfdt);
    for j in 0..6 {
        for i in 0..8 {
            let (x, y) = (-0.5 + i as f64 * 0.2, 0.25 + j as f64 * 0.3);
            let k = j * 8 + i;
            let (u, w) = (state.field(0)[k], state.field(1)[k]);
            let expected = [-(x + 2.0 * y) * t.sin(), -w * u * x * (x * t).cos()];
            for (f, e) in expected.iter().enumerate() {
                let got = dfdt.field(f)[k];
                assert!(
                    (got - e).abs() <= 1e-15 * (1.0 + e.abs()),
                    "{got} against {e}"
                );
            }
        }
    }
}

#[test]
fn rodas5p_follows_a_placed_time_dependent_source() {
    // u_t = −u + (x + 2y)·cos t from u = 0: u = (x + 2y)·(cos t + sin t − e^(−t))/2 at every cell.
    let mut model = placed();
    model.u = Grid::from_fn(8, 6, Boundary::Neumann, |_, _| 0.0)
        .and_then(|g| g.with_origin(-0.5, 0.25))
        .and_then(|g| g.with_spacing(0.2, 0.3))
        .unwrap();
    let run = model
        .simulate()
        .duration(2.0)
        .dense_output(false)
        .run()
        .unwrap();
    let t: f64 = 2.0;
    let u = run.last().state.field(0).to_vec();
    for j in 0..6 {
        for i in 0..8 {
            let (x, y) = (-0.5 + i as f64 * 0.2, 0.25 + j as f64 * 0.3);
            let exact = (x + 2.0 * y) * (t.cos() + t.sin() - (-t).exp()) / 2.0;
            assert!(
                (u[j * 8 + i] - exact).abs() < 1e-8,
                "cell ({i}, {j}): {} against {exact}",
                u[j * 8 + i]
            );
        }
    }
    // Fields placed differently are a typed error.
    let mut misplaced = placed();
    misplaced.w = misplaced.w.clone().with_spacing(0.2, 0.2).unwrap();
    let error = misplaced.simulate().duration(1.0).run().unwrap_err();
    assert!(
        matches!(&error, Error::BadModel { .. }) && error.to_string().contains("spacing"),
        "{error}"
    );
}

/// A source switched on at t = 1.1 in the half x ≤ 0.3 (SciMLBenchmarks' Brusselator forcing,
/// simplified).
#[system]
pub struct Switched {
    /// The field.
    #[field]
    pub u: Grid,
}

#[system]
impl Switched {
    #[cell]
    fn rate(&self, u: Stencil, x: f64, t: f64) -> f64 {
        let source = if t >= 1.1 && x <= 0.3 { 5.0 } else { 0.0 };
        u.laplacian() - u.c + source
    }
}

#[test]
fn a_source_switched_on_in_time_has_the_time_derivative_of_its_arms() {
    // A branch on the time is a select in the IR, like a branch on the state: ∂f/∂t is that of
    // the arm taken (here 0 on both sides), exact even a hair past the switch, where a central
    // difference of f in t would straddle it.
    let model = Switched {
        u: Grid::from_fn(5, 5, Boundary::Periodic, |i, j| (i + 2 * j) as f64 * 0.1)
            .and_then(|g| g.with_spacing(0.1, 0.1))
            .unwrap(),
    };
    const { assert!(<Switched as Jacobian>::TIME_DEPENDENT) };
    let state = model.state();
    let mut rate = state.clone();
    let mut dfdt = state.clone();
    for (t, on) in [(1.0, false), (1.1 + 1e-12, true), (2.0, true)] {
        model.derivative(t, &state, &mut rate);
        model.time_derivative(t, &state, &mut dfdt);
        for j in 0..5 {
            for i in 0..5 {
                let k = j * 5 + i;
                let s = state.field(0);
                let laplacian = s[j * 5 + (i + 1) % 5]
                    + s[j * 5 + (i + 4) % 5]
                    + s[((j + 1) % 5) * 5 + i]
                    + s[((j + 4) % 5) * 5 + i]
                    - 4.0 * s[k];
                let source = if on && i as f64 * 0.1 <= 0.3 {
                    5.0
                } else {
                    0.0
                };
                let expected = laplacian - s[k] + source;
                assert!(
                    (rate.field(0)[k] - expected).abs() < 1e-12,
                    "t = {t}, cell {k}"
                );
                assert_eq!(dfdt.field(0)[k], 0.0, "t = {t}, cell {k}");
            }
        }
    }
}

/// u_t = ∇·(κ∇u) in the five-point flux form with a coefficient grid κ (a parameter, not
/// differentiated), plus a source read from a second coefficient grid.
#[system(integrator = ImplicitEuler, dt = 0.01)]
pub struct Varying {
    /// The diffusing field.
    #[field]
    pub u: Grid,
    /// κ at each cell: a parameter grid.
    pub kappa: Grid,
    /// A source at each cell.
    pub source: Grid,
}

#[system]
impl Varying {
    #[cell]
    fn rate(&self, u: Stencil, kappa: Stencil, source: Stencil) -> f64 {
        // Face conductivities by the arithmetic mean of the two cells.
        let east = 0.5 * (kappa.c + kappa.e) * (u.e - u.c);
        let west = 0.5 * (kappa.c + kappa.w) * (u.w - u.c);
        let north = 0.5 * (kappa.c + kappa.n) * (u.n - u.c);
        let south = 0.5 * (kappa.c + kappa.s) * (u.s - u.c);
        east + west + north + south + source.c * u.c.sin()
    }
}

fn varying() -> Varying {
    let n = 7;
    Varying {
        u: Grid::from_fn(n, n, Boundary::Neumann, |i, j| {
            0.1 * (i * i) as f64 - 0.2 * j as f64
        })
        .unwrap(),
        kappa: Grid::from_fn(n, n, Boundary::Neumann, |i, j| {
            1.0 + 0.3 * i as f64 + 0.1 * j as f64
        })
        .unwrap(),
        source: Grid::from_fn(n, n, Boundary::Periodic, |i, j| ((i + j) % 3) as f64).unwrap(),
    }
}

#[test]
fn coefficient_grids_are_parameters_read_through_stencils() {
    let model = varying();
    let state = model.state();
    assert_eq!(state.fields(), 1, "coefficient grids are not state");
    let mut rate = state.clone();
    model.derivative(0.0, &state, &mut rate);
    // An interior cell by hand.
    let (n, i, j) = (7, 3, 2);
    let at = |g: &Grid, i: usize, j: usize| g.values()[j * n + i];
    let (u, k) = (&model.u, &model.kappa);
    let flux = |(i2, j2): (usize, usize)| {
        0.5 * (at(k, i, j) + at(k, i2, j2)) * (at(u, i2, j2) - at(u, i, j))
    };
    let expected = flux((i + 1, j))
        + flux((i - 1, j))
        + flux((i, j + 1))
        + flux((i, j - 1))
        + at(&model.source, i, j) * at(u, i, j).sin();
    assert!((rate.field(0)[j * n + i] - expected).abs() < 1e-14);
    // J (κ and the source as parameters) against central differences: at every boundary cell
    // too, the Neumann folds of u and κ.
    check_jacobian(&model);
    // A coefficient grid of another size is a typed error.
    let mut wrong = varying();
    wrong.kappa = Grid::from_fn(6, 7, Boundary::Neumann, |_, _| 1.0).unwrap();
    let error = wrong.simulate().steps(1).run().unwrap_err();
    assert!(error.to_string().contains("kappa"), "{error}");
}

/// A cell whose state-free code shadows the time: u_t = −u + sin(t − t₀)·u.
#[system]
pub struct Delayed {
    /// The field.
    #[field]
    pub u: Grid,
    /// t₀.
    pub t0: f64,
}

#[system]
impl Delayed {
    #[cell]
    fn rate(&self, u: Stencil, t: f64) -> f64 {
        let t = t - self.t0;
        -u.c + t.sin() * u.c
    }
}

#[test]
fn a_shadowed_time_keeps_a_cells_jacobian_and_time_derivative_right() {
    // The derivative code reads its own copy of the time, taken before the user's `let t`.
    let model = Delayed {
        u: Grid::from_fn(4, 4, Boundary::Periodic, |i, j| 0.1 * (i + j) as f64 + 0.2).unwrap(),
        t0: 0.5,
    };
    let (t, state) = (1.3, model.state());
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(t, &state, &mut jacobian);
    let dense = jacobian.to_dense();
    let mut dfdt = state.clone();
    model.time_derivative(t, &state, &mut dfdt);
    for k in 0..16 {
        let u = state.field(0)[k];
        assert!((dense[(k, k)] - (-1.0 + (t - 0.5f64).sin())).abs() < 1e-15);
        assert!((dfdt.field(0)[k] - (t - 0.5f64).cos() * u).abs() < 1e-15);
    }
}
