//! The heat equation against its closed-form solutions: the exact Jacobian, the grid's spatial
//! order, each integrator's temporal order, explicit Euler's limit, implicit Euler past it.

use std::f64::consts::PI;

use odyn::grid::GridState;
use odyn::stability::{StabilityProbe, gershgorin_limit, measured_limit};
use odyn::{Jacobian, Method, Model, Simulate, State};

use super::{D, Heat, exact, heat};

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
/// measures the grid's true limit 2/|λ_max|, above it by 1/sin²(nπ/(2(n + 1))) = 1.0056 at
/// n = 20 — within 1 %. (20 cells a side: the bisection's 20 000-step runs cost n².) Stable at
/// 0.99×, diverged at 1.01×. RK4's prediction is its real-axis reach over the same disc,
/// measured within 1 % too.
#[test]
fn explicit_euler_limit_is_predicted_and_measured() {
    let model = heat(20);
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
    let n = 20.0;
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
    // Asserted to 1 %: 4 000-step runs and a bisection to 5e-3 suffice (a run at 1.01× the
    // limit grows by about e^40 over them) at a fifth of the cost of the probe above.
    let coarse = StabilityProbe {
        steps: 4_000,
        precision: 5e-3,
        ..probe
    };
    let rk4_measured = measured_limit(&model, &state, Method::Rk4, rk4, &coarse).unwrap();
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
