//! Field models on the heat equation u_t = D∇²u on the unit square, u = 0 on the boundary
//! (vertex-centred: the grid holds the n × n interior nodes, dx = 1/(n + 1)).
//!
//! The initial state sin(πx)·sin(πy) + ½·sin(2πx)·sin(3πy) is a sum of eigenvectors of both
//! the continuous and the discrete Laplacian, so both solutions are known in closed form:
//! each mode decays as exp(λt), with λ = −Dπ²(m² + k²) for the PDE and
//! λ_h = −(4D/dx²)(sin²(mπdx/2) + sin²(kπdx/2)) for the five-point grid (the semi-discrete
//! system). Comparing against the first measures the spatial error, against the second the
//! time integrator's alone.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::f64::consts::PI;

use odyn::grid::{Boundary, Grid, GridState, Stencil};
use odyn::integrators::Rk4;
use odyn::stability::{StabilityProbe, gershgorin_limit, measured_limit};
use odyn::{Error, Jacobian, Method, Model, Simulate, State, Stepper, system};

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

/// The five-point grid's eigenvalue of mode (m, k).
fn grid_rate(dx: f64) -> impl Fn(f64, f64) -> f64 {
    move |m, k| {
        -4.0 * D / (dx * dx)
            * ((m * PI * dx / 2.0).sin().powi(2) + (k * PI * dx / 2.0).sin().powi(2))
    }
}

/// The largest nodal error of `state` at time t against `rate`'s solution.
fn error(model: &Heat, state: &GridState, t: f64, rate: impl Fn(f64, f64) -> f64) -> f64 {
    let n = state.nx();
    state
        .field(0)
        .iter()
        .enumerate()
        .map(|(k, u)| (u - exact(model.dx, k % n, k / n, t, &rate)).abs())
        .fold(0.0, f64::max)
}

fn run(model: &Heat, method: Method, dt: f64, duration: f64) -> GridState {
    let trajectory = model
        .simulate()
        .integrator(method)
        .dt(dt)
        .duration(duration)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    trajectory.samples.last().unwrap().state.clone()
}

/// The exact Jacobian is the five-point Laplacian: D/dx²·(−4 on the diagonal, 1 for each
/// interior neighbour), checked against central finite differences of the generated f.
#[test]
fn jacobian_matches_finite_differences() {
    let model = heat(6);
    let mut state = model.state();
    for (k, x) in state.as_mut_slice().iter_mut().enumerate() {
        *x += 0.01 * (k as f64).sin();
    }
    let mut jacobian = model.jacobian_matrix(&state);
    model.jacobian(0.0, &state, &mut jacobian);
    let dense = jacobian.to_dense();
    let n = state.as_slice().len();
    let (mut plus, mut minus) = (state.clone(), state.clone());
    let (mut fp, mut fm) = (state.clone(), state.clone());
    let h = 1e-6;
    for c in 0..n {
        plus.clone_from(&state);
        minus.clone_from(&state);
        plus.as_mut_slice()[c] += h;
        minus.as_mut_slice()[c] -= h;
        model.derivative(0.0, &plus, &mut fp);
        model.derivative(0.0, &minus, &mut fm);
        for r in 0..n {
            let fd = (fp.as_slice()[r] - fm.as_slice()[r]) / (2.0 * h);
            assert!(
                (dense[(r, c)] - fd).abs() <= 1e-6 * (1.0 + fd.abs()),
                "J[{r}][{c}] = {} but finite differences give {fd}",
                dense[(r, c)]
            );
        }
    }
    let scale = D / (model.dx * model.dx);
    assert!((dense[(7, 7)] + 4.0 * scale).abs() < 1e-9 * scale);
    assert!((dense[(7, 8)] - scale).abs() < 1e-9 * scale);
}

/// Against the PDE's solution, with time error made negligible (Rodas5P at a small step), the
/// five-point grid converges at order 2: the error falls by 4 per halving of dx.
#[test]
fn spatial_order_is_two() {
    let errors: Vec<(f64, f64)> = [7, 15, 31]
        .into_iter()
        .map(|n| {
            let model = heat(n);
            let state = run(&model, Method::Rodas5P, 1e-3, 0.1);
            (model.dx, error(&model, &state, 0.1, |_, _| 0.0))
        })
        .collect();
    for pair in errors.windows(2) {
        let order = (pair[0].1 / pair[1].1).ln() / (pair[0].0 / pair[1].0).ln();
        assert!(
            (order - 2.0).abs() < 0.1,
            "spatial order {order}: {errors:?}"
        );
    }
}

/// Against the semi-discrete solution (the grid's own eigenvalues), only the time integrator's
/// error remains: order 1 for explicit and implicit Euler, 4 for RK4.
#[test]
fn temporal_orders() {
    let model = heat(15);
    let limit = model.dx * model.dx / (4.0 * D);
    for (method, order, steps) in [
        (Method::ExplicitEuler, 1.0, [40.0, 80.0]),
        (Method::ImplicitEuler, 1.0, [40.0, 80.0]),
        (Method::Rk4, 4.0, [20.0, 40.0]),
    ] {
        let duration = 20.0 * limit;
        let errors = steps.map(|s| {
            let dt = duration / s;
            let state = run(&model, method, dt, duration);
            error(&model, &state, duration, grid_rate(model.dx))
        });
        let measured = (errors[0] / errors[1]).log2();
        assert!(
            (measured - order).abs() < 0.15,
            "{method:?}: order {measured}, errors {errors:?}"
        );
    }
}

/// Explicit Euler's limit: Gershgorin's discs give dx²/(4D) exactly; bisection on long runs
/// measures the grid's true limit 2/|λ_max|, above it by 1/sin²(nπ/(2(n + 1))) = 1.0023 at
/// n = 32 — within 1 %. Stable at 0.99×, diverged at 1.01×. RK4's prediction is its real-axis
/// reach over the same disc, measured within 1 % too.
#[test]
fn explicit_euler_limit_is_predicted_and_measured() {
    let model = heat(32);
    let state = model.state();
    let theory = model.dx * model.dx / (4.0 * D);
    let predicted = gershgorin_limit(&model, 0.0, &state, Method::ExplicitEuler).unwrap();
    assert!(
        (predicted / theory - 1.0).abs() < 1e-12,
        "predicted {predicted}, dx²/(4D) = {theory}"
    );
    let probe = StabilityProbe {
        steps: 20_000,
        precision: 1e-3,
        // The heat equation's stable set is one interval (its spectrum is real and negative):
        // no gaps for a fine scan to find, so a coarse one keeps the test short.
        scan_ratio: 1.25,
        ..StabilityProbe::default()
    };
    let measured = measured_limit(&model, &state, Method::ExplicitEuler, theory, &probe).unwrap();
    let n = 32.0;
    let exact = theory / (n * PI / (2.0 * (n + 1.0))).sin().powi(2);
    assert!(
        (measured / predicted - 1.0).abs() < 0.01,
        "measured {measured}, predicted {predicted}"
    );
    assert!(
        (measured / exact - 1.0).abs() < 2e-3,
        "measured {measured}, grid's exact limit {exact}"
    );
    let peak = |dt: f64| {
        let trajectory = model
            .simulate()
            .integrator(Method::ExplicitEuler)
            .dt(dt)
            .steps(20_000)
            .record_every(100)
            .run_partial()
            .unwrap();
        (trajectory.0.samples.iter())
            .flat_map(|s| s.state.as_slice().iter().map(|x| x.abs()))
            .fold(0.0, f64::max)
            .max(if trajectory.1.is_some() {
                f64::INFINITY
            } else {
                0.0
            })
    };
    assert!(peak(0.99 * predicted) <= 1.5, "unstable at 0.99×");
    assert!(peak(1.01 * predicted) > 1e3, "stable at 1.01×");
    // RK4 reaches −2.785293563405282 on the negative real axis, where its stability polynomial
    // returns to R(z) = 1: the real root of 1 + z/2 + z²/6 + z³/24 (numpy.roots; Hairer &
    // Wanner, Solving ODEs II, §IV.2, Fig. 2.1).
    let rk4 = gershgorin_limit(&model, 0.0, &state, Method::Rk4).unwrap();
    let rk4_theory = 2.785293563405282 * model.dx * model.dx / (8.0 * D);
    assert!(
        (rk4 / rk4_theory - 1.0).abs() < 1e-9,
        "RK4 predicted {rk4} vs {rk4_theory}"
    );
    let rk4_measured = measured_limit(&model, &state, Method::Rk4, rk4, &probe).unwrap();
    assert!(
        (rk4_measured / rk4 - 1.0).abs() < 0.01,
        "RK4 measured {rk4_measured}, predicted {rk4}"
    );
}

/// Implicit Euler at 100× the explicit limit: every mode decays (no node grows), the solution
/// stays within first-order distance of the exact one, and sparse Cholesky does the solves (I −
/// h·J is symmetric positive definite for diffusion), its symbolic analysis made once.
#[test]
fn implicit_euler_is_stable_far_past_the_explicit_limit() {
    let model = heat(32);
    let dt = 100.0 * model.dx * model.dx / (4.0 * D);
    let steps = 50;
    let trajectory = model
        .simulate()
        .integrator(Method::ImplicitEuler)
        .dt(dt)
        .steps(steps)
        .run()
        .unwrap();
    let peaks: Vec<f64> = (trajectory.samples.iter())
        .map(|s| {
            s.state
                .as_slice()
                .iter()
                .fold(0.0, |m: f64, x| m.max(x.abs()))
        })
        .collect();
    assert!(peaks.windows(2).all(|w| w[1] <= w[0]), "{peaks:?}");
    let last = trajectory.samples.last().unwrap();
    let e = error(&model, &last.state, last.t, grid_rate(model.dx));
    // One implicit Euler step multiplies the slowest mode by 1/(1 − hλ) instead of exp(hλ):
    // after 50 steps at hλ = −0.12 the amplitude differs by ~1.4e-2 of the initial.
    assert!(e < 0.03, "error {e}");
    let mut jacobian = model.jacobian_matrix(&last.state);
    model.jacobian(0.0, &last.state, &mut jacobian);
    odyn::NewtonMatrix::factorize(&mut jacobian, dt, &mut ()).expect("I − dt·J is regular");
    let counts = jacobian.factorizations();
    assert_eq!((counts.cholesky, counts.lu, counts.symbolic_lu), (1, 0, 0));
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

/// Two coupled fields on every boundary: the generated blocks, placed through the boundary
/// (periodic wrap, Neumann's reads folded onto the edge cell), match finite differences.
#[test]
fn two_field_jacobian_matches_finite_differences_on_every_boundary() {
    for boundary in [
        Boundary::Periodic,
        Boundary::Neumann,
        Boundary::Dirichlet(0.3),
    ] {
        check_jacobian(&gray_scott(5, boundary));
    }
}

/// Pure diffusion (F = k = 0 and no v) conserves the total of u on periodic and Neumann
/// (zero-flux) grids: the five-point fluxes cancel in pairs. Explicit Euler keeps the sum to
/// rounding over 1000 steps.
#[test]
fn diffusion_conserves_the_total_on_periodic_and_neumann_grids() {
    for boundary in [Boundary::Periodic, Boundary::Neumann] {
        let mut model = gray_scott(12, boundary);
        (model.feed, model.kill) = (0.0, 0.0);
        model.v.values_mut().fill(0.0);
        let total = |s: &GridState| s.field(0).iter().sum::<f64>();
        let start = total(&model.state());
        let trajectory = model.simulate().steps(1000).run().unwrap();
        let end = total(&trajectory.samples.last().unwrap().state);
        assert!(
            (end - start).abs() < 1e-11 * start,
            "{boundary:?}: total {start} became {end}"
        );
    }
}

/// Every integrator that needs only f (and J) runs on a field model: against a DOP853 reference
/// at rtol 1e-12 over t = 20, each converges at its order p: the error ratio between dt = 1 and
/// 1/2 gives p − 0.25 < measured < p + 1 (Tsit5 measures 5.9: its fifth-order error constant is
/// tuned small, so the sixth-order term still shows at these steps), and DOP853, whose error at dt = 1
/// is already near the reference's, agrees to 1e-9.
#[test]
fn every_first_order_method_runs_on_a_field_model() {
    let model = gray_scott(8, Boundary::Periodic);
    let reference = model
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-14)
        .duration(20.0)
        .run()
        .unwrap();
    let reference = reference.samples.last().unwrap().state.clone();
    let error = |method: Method, dt: f64| {
        let run = model
            .simulate()
            .integrator(method)
            .dt(dt)
            .duration(20.0)
            .run()
            .unwrap();
        let state = &run.samples.last().unwrap().state;
        crate::common::max_abs_difference(state.as_slice(), reference.as_slice())
    };
    for (method, order, dt) in [
        (Method::ExplicitEuler, 1.0, 1.0),
        (Method::ImplicitEuler, 1.0, 1.0),
        (Method::Rosenbrock23, 2.0, 1.0),
        (Method::Rk4, 4.0, 1.0),
        (Method::Tsit5, 5.0, 1.0),
        (Method::Rodas5P, 5.0, 1.0),
    ] {
        let measured = (error(method, dt) / error(method, dt / 2.0)).log2();
        assert!(
            measured > order - 0.25 && measured < order + 1.0,
            "{method:?}: order {measured}"
        );
    }
    let e = error(Method::Dop853, 1.0);
    assert!(e < 1e-9, "DOP853: {e}");
}

/// At the uniform background (u, v) = (1, 0) the Jacobian is circulant and the checkerboard
/// mode's eigenvalue −8D_u/dx² − F sits on a Gershgorin rim: explicit Euler's predicted limit
/// is 2/(8D_u/dx² + F) exactly (the example's check of the dx²/(4D_u), less F's share).
#[test]
fn gray_scott_explicit_limit_is_predicted_from_the_discs() {
    let mut model = gray_scott(16, Boundary::Periodic);
    // Pearson's cells, where diffusion sets the limit.
    model.dx = 2.5 / 256.0;
    model.u.values_mut().fill(1.0);
    model.v.values_mut().fill(0.0);
    let state = model.state();
    let predicted = gershgorin_limit(&model, 0.0, &state, Method::ExplicitEuler).unwrap();
    let theory = 2.0 / (8.0 * model.du / (model.dx * model.dx) + model.feed);
    assert!(
        (predicted / theory - 1.0).abs() < 1e-12,
        "{predicted} vs {theory}"
    );
    assert_eq!(
        gershgorin_limit(&model, 0.0, &state, Method::ImplicitEuler).unwrap(),
        f64::INFINITY
    );
}

/// Bad input is a typed error: a grid whose values do not fill it, a periodic side too short
/// for distinct neighbours, more cells than memory holds, and fields of different sizes in one
/// model.
#[test]
fn bad_grids_are_typed_errors() {
    let wrong = Grid::new(4, 4, Boundary::Neumann, vec![0.0; 15]).unwrap_err();
    assert!(
        wrong.to_string().contains("16 cells but was given 15"),
        "{wrong}"
    );
    let short = Grid::new(2, 8, Boundary::Periodic, vec![0.0; 16]).unwrap_err();
    assert!(short.to_string().contains("at least 3"), "{short}");
    let nan = Grid::new(3, 3, Boundary::Dirichlet(f64::NAN), vec![0.0; 9]).unwrap_err();
    assert!(nan.to_string().contains("finite"), "{nan}");
    // nx·ny overflowing usize used to panic ("capacity overflow") in `from_fn`.
    let huge = Grid::from_fn(usize::MAX / 2, 4, Boundary::Neumann, |_, _| 0.0).unwrap_err();
    assert!(huge.to_string().contains("more cells"), "{huge}");
    let huge = Grid::new(usize::MAX, 2, Boundary::Neumann, vec![]).unwrap_err();
    assert!(huge.to_string().contains("more cells"), "{huge}");
    // 2⁵⁰ cells (8 PB, beyond any address space) used to abort the process.
    let huge = Grid::from_fn(1 << 40, 1 << 10, Boundary::Neumann, |_, _| 0.0).unwrap_err();
    assert!(huge.to_string().contains("cannot be allocated"), "{huge}");
    let mut model = gray_scott(6, Boundary::Periodic);
    model.v = Grid::new(5, 6, Boundary::Periodic, vec![0.0; 30]).unwrap();
    let error = model.simulate().steps(1).run().unwrap_err();
    assert!(
        matches!(error, odyn::Error::BadModel { .. }) && error.to_string().contains("5×6"),
        "{error}"
    );
}

/// odyn's Gray–Scott against SciPy's: "coral" (F = 0.0545, k = 0.062) on 64² cells from
/// Pearson's square without noise, to t = 500, DOP853 at rtol = atol = 1e-12, against
/// `scripts/scipy_gray_scott.py`'s reference (SciPy DOP853 at 1e-13, which its Radau at 1e-10
/// matches to 1.4e-11): the bench `gray_scott`'s `equal_accuracy` reference.
#[test]
fn gray_scott_matches_scipy() {
    let n = 64;
    let r = n * 10 / 256;
    let inside = |i: usize, j: usize| {
        (n / 2 - r..n / 2 + r).contains(&i) && (n / 2 - r..n / 2 + r).contains(&j)
    };
    let grid = |inner: f64, outer: f64| {
        Grid::from_fn(n, n, Boundary::Periodic, |i, j| {
            if inside(i, j) { inner } else { outer }
        })
        .unwrap()
    };
    let model = GrayScott {
        u: grid(0.5, 1.0),
        v: grid(0.25, 0.0),
        du: 2e-5,
        dv: 1e-5,
        feed: 0.0545,
        kill: 0.062,
        dx: 2.5 / n as f64,
    };
    let run = model
        .simulate()
        .integrator(Method::Dop853)
        .tolerances(1e-12, 1e-12)
        .duration(500.0)
        .record_every(u64::MAX)
        .run()
        .unwrap();
    let y = run.samples.last().unwrap().state.as_slice().to_vec();
    // scripts/scipy_gray_scott.py: (index, value) in odyn's layout (u then v, k = j·n + i).
    let probes = [
        (0, 1.0),
        (2080, 0.444875936730885),
        (2087, 0.9999873470631493),
        (6176, 0.250463872401409),
        (6183, 6.937624869473619e-09),
    ];
    for (k, expected) in probes {
        assert!(
            (y[k] - expected).abs() < 1e-9,
            "y[{k}] = {} vs SciPy {expected}",
            y[k]
        );
    }
    let mean = |s: &[f64]| s.iter().sum::<f64>() / s.len() as f64;
    assert!((mean(&y[..n * n]) - 9.969918721584972e-01).abs() < 1e-10);
    assert!((mean(&y[n * n..]) - 1.407236166694929e-03).abs() < 1e-10);
}

/// Replacing the state through `Stepper::state_mut` by one of another size used to step on
/// silently, the state quietly back at the old size; a grid of the same number of cells but
/// another shape stepped as if the model's grid were that shape.
#[test]
fn a_replaced_state_of_another_size_is_a_typed_error() {
    let model = heat(8);
    let mut stepper = Stepper::<Heat, Rk4<_>>::new(&model, model.state(), 0.0, 1e-4).unwrap();
    stepper.step().unwrap();
    *stepper.state_mut() = heat(6).state();
    let error = stepper.step().unwrap_err();
    assert!(
        matches!(&error, Error::InvalidInput { field, .. } if field == "state")
            && error.to_string().contains("36 components")
            && error.to_string().contains("64"),
        "{error}"
    );
    assert_eq!(stepper.steps(), 1);

    // 4×16 cells in place of 8×8: as many values, another grid.
    let wide = Heat {
        u: Grid::from_fn(4, 16, Boundary::Dirichlet(0.0), |_, _| 1.0).unwrap(),
        ..heat(8)
    };
    *stepper.state_mut() = wide.state();
    let error = stepper.step().unwrap_err();
    assert!(error.to_string().contains("4×16"), "{error}");

    // Values changed in place go on stepping.
    *stepper.state_mut() = model.state();
    stepper.state_mut().as_mut_slice()[9] = 2.0;
    stepper.step().unwrap();
    assert_eq!(stepper.steps(), 2);
}

/// The system allocator, except that a thread given a budget ([`within_budget`]) gets a null
/// pointer for an allocation beyond what is left of it, as from a machine out of memory.
struct Budgeted;

thread_local! {
    /// Bytes this thread may still allocate; `None` for no limit.
    static LEFT: Cell<Option<usize>> = const { Cell::new(None) };
}

/// Whether `bytes` more fit the budget (taking them if so).
fn take(bytes: usize) -> bool {
    LEFT.try_with(|left| match left.get() {
        Some(n) if bytes > n => false,
        Some(n) => {
            left.set(Some(n - bytes));
            true
        }
        None => true,
    })
    .unwrap_or(true)
}

fn give(bytes: usize) {
    let _ = LEFT.try_with(|left| left.set(left.get().map(|n| n.saturating_add(bytes))));
}

// SAFETY: every call is passed on to the system allocator unchanged, or refused with null.
unsafe impl GlobalAlloc for Budgeted {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        if !take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as the caller's contract.
        unsafe { System.alloc(layout) }
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        if !take(layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as the caller's contract.
        unsafe { System.alloc_zeroed(layout) }
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        give(layout.size());
        // SAFETY: as the caller's contract.
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        if new_size > layout.size() && !take(new_size - layout.size()) {
            return std::ptr::null_mut();
        }
        // SAFETY: as the caller's contract.
        let moved = unsafe { System.realloc(ptr, layout, new_size) };
        if new_size < layout.size() && !moved.is_null() {
            give(layout.size() - new_size);
        }
        moved
    }
}

#[global_allocator]
static GLOBAL: Budgeted = Budgeted;

/// `f`, with this thread allowed `bytes` of new allocations.
fn within_budget<T>(bytes: usize, f: impl FnOnce() -> T) -> T {
    LEFT.with(|left| left.set(Some(bytes)));
    let out = f();
    LEFT.with(|left| left.set(None));
    out
}

/// A grid that fits in memory, with room for its state, but not for the copies a run makes of
/// it (the method's stages, the driver's buffers: ten to twenty) used to abort the process at
/// its first run (the probe's 16384² grid). Now the run stops at the first copy that
/// cannot be allocated with a typed error; modelled here by an allocator that refuses
/// allocations beyond a budget of three copies of a 256² grid's state (512 KiB each).
#[test]
fn a_grid_whose_run_copies_do_not_fit_is_a_typed_error() {
    let model = heat(256);
    let copy = 256 * 256 * std::mem::size_of::<f64>();
    for method in [
        Method::ExplicitEuler,
        Method::Rk4,
        Method::Tsit5,
        Method::Dop853,
    ] {
        let run = within_budget(3 * copy + (64 << 10), || {
            model.simulate().integrator(method).dt(1e-6).steps(1).run()
        });
        let error = run.unwrap_err();
        assert!(
            matches!(&error, Error::InvalidInput { field, .. } if field == "grid")
                && error.to_string().contains(
                    "is 256×256 with 1 field: a copy of its state (524 kB) cannot be allocated"
                ),
            "{method}: {error}"
        );
    }
    // With room for them, the same run goes through.
    let run = within_budget(64 * copy, || {
        model
            .simulate()
            .integrator(Method::Rk4)
            .dt(1e-6)
            .steps(1)
            .run()
    });
    assert_eq!(run.unwrap().steps(), 1);
}

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
