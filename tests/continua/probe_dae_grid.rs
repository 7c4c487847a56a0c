//! Hostile probes of field models with `#[algebraic]` fields (commits 483d67d, eafe42b): exact
//! solutions on every boundary and implicit method, inconsistent and singular starts (dense
//! and sparse ∂g/∂z), refusals, linear solvers, events, save_at, Stepper, absurd options.

use odyn::grid::{Boundary, Grid, Stencil};
use odyn::prelude::*;
use odyn::{AutoPolicy, Event, KrylovOptions, LinearSolver, Stepper};

/// u_t = −u + z, 0 = z − 2u: u′ = u, so u = u₀·eᵗ and z = 2u exactly.
#[system]
#[derive(Clone, Debug)]
struct Grow {
    #[field]
    u: Grid,
    #[field]
    #[algebraic]
    z: Grid,
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
struct GrowFixed {
    #[state]
    u: [f64; 3],
    #[algebraic]
    z: [f64; 3],
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

/// u_t = z, 0 = z − ∇²u (five-point, unit spacing): u′ = ∇²_h u, the discrete heat equation,
/// whose eigenvectors are known per boundary.
#[system]
#[derive(Clone, Debug)]
struct Lap {
    #[field]
    u: Grid,
    #[field]
    #[algebraic]
    z: Grid,
}

#[system]
impl Lap {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [z.c, z.c - u.laplacian()]
    }
}

/// u_t = z, 0 = u − 1: g does not read z (index 2).
#[system]
#[derive(Clone, Debug)]
struct IndexTwo {
    #[field]
    u: Grid,
    #[field]
    #[algebraic]
    z: Grid,
}

#[system]
impl IndexTwo {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [z.c, u.c - 1.0]
    }
}

/// u_t = −u, 0 = z³ − 8 (z = 2 whatever u).
#[system]
#[derive(Clone, Debug)]
struct Cubic {
    #[field]
    u: Grid,
    #[field]
    #[algebraic]
    z: Grid,
}

#[system]
impl Cubic {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [-u.c, z.c * z.c * z.c - 8.0]
    }
}

const IMPLICIT: [Method; 4] = [
    Method::Rodas5P,
    Method::Rosenbrock23,
    Method::Bdf,
    Method::ImplicitEuler,
];

fn grid(nx: usize, ny: usize, b: Boundary, f: impl Fn(usize, usize) -> f64) -> Grid {
    Grid::from_fn(nx, ny, b, f).unwrap()
}

fn try_grow(nx: usize, ny: usize, b: Boundary, z0: f64) -> odyn::Result<Grow> {
    Ok(Grow {
        u: Grid::from_fn(nx, ny, b, |i, j| 1.0 + 0.1 * i as f64 + 0.01 * j as f64)?,
        z: Grid::from_fn(nx, ny, b, |_, _| z0)?,
    })
}

fn grow(nx: usize, ny: usize, b: Boundary, z0: f64) -> Grow {
    Grow {
        u: grid(nx, ny, b, |i, j| 1.0 + 0.1 * i as f64 + 0.01 * j as f64),
        z: grid(nx, ny, b, |_, _| z0),
    }
}

fn boundaries() -> [Boundary; 4] {
    [
        Boundary::Periodic,
        Boundary::Neumann,
        Boundary::Dirichlet(0.0),
        Boundary::Dirichlet(3.5),
    ]
}

/// Runs `model` to t = 1 with `method`: adaptive at (1e-8, 1e-10), or 1 000 fixed steps.
fn to_one<M: Simulate>(model: &M, method: Method) -> odyn::Result<odyn::Trajectory<M::State>>
where
    M: odyn::Model,
{
    let s = model.simulate().integrator(method);
    if method.is_adaptive() {
        s.tolerances(1e-8, 1e-10).duration(1.0).run()
    } else {
        s.dt(1e-3).steps(1000).run()
    }
}

/// Case 1: u′ = u on every grid, boundary and implicit method; z = 2u everywhere.
#[test]
fn grow_is_exact_everywhere() {
    let e = 1f64.exp();
    for (nx, ny) in [(1, 1), (3, 1), (1, 3), (4, 4)] {
        for b in boundaries() {
            let model = match try_grow(nx, ny, b, 0.0) {
                Ok(model) => model,
                Err(error) => {
                    // A periodic side below 3 cells is refused by Grid (typed).
                    eprintln!("{nx}x{ny} {b:?}: {error}");
                    assert!(b == Boundary::Periodic && (nx < 3 || ny < 3), "{error}");
                    continue;
                }
            };
            for method in IMPLICIT {
                let run = to_one(&model, method).unwrap();
                let (u0, end) = (run.first().state.field(0), run.last().state.field(0));
                let z = run.last().state.field(1);
                let first_z = run.first().state.field(1);
                let mut err = 0.0f64;
                let mut zerr = 0.0f64;
                for k in 0..u0.len() {
                    err = err.max((end[k] - u0[k] * e).abs() / (u0[k] * e));
                    zerr = zerr.max((z[k] - 2.0 * end[k]).abs());
                    assert_eq!(first_z[k], 2.0 * u0[k], "consistent start");
                }
                eprintln!(
                    "{nx}x{ny} {b:?} {method}: rel err {err:.2e}, |z-2u| {zerr:.1e}, {} steps",
                    run.stats.steps
                );
                // Implicit Euler at dt 1e-3 is first order: error ~ dt/2 = 5e-4.
                let bound = if method == Method::ImplicitEuler {
                    1e-3
                } else if method == Method::Rosenbrock23 {
                    2e-5 // its global error at rtol 1e-8: 1e-6–8e-6 here, the same on GrowFixed
                } else {
                    1e-6
                };
                assert!(err < bound, "{nx}x{ny} {b:?} {method}: {err}");
                assert!(zerr < 1e-8 * end[0].abs(), "{method}: {zerr}");
            }
        }
    }
}

/// Case 1: the field model against the fixed-size one, same method and options.
#[test]
fn grow_field_equals_fixed() {
    let field = grow(3, 1, Boundary::Neumann, 0.0);
    let fixed = GrowFixed {
        u: [1.0, 1.1, 1.2],
        z: [0.0; 3],
    };
    for method in IMPLICIT {
        let a = to_one(&field, method).unwrap();
        let b = to_one(&fixed, method).unwrap();
        let (fa, fb) = (a.last().state.field(0).to_vec(), b.last().state.u);
        let d = (0..3).map(|k| (fa[k] - fb[k]).abs()).fold(0.0, f64::max);
        eprintln!(
            "{method}: field {:?} fixed {:?} diff {d:.1e}; steps {} / {}",
            fa, fb, a.stats.steps, b.stats.steps
        );
        assert!(d < 1e-9, "{method}: {d}");
    }
}

/// Case 1: orders at fixed steps, u′ = u to t = 1 on a 3×1 grid.
#[test]
fn orders_at_fixed_steps() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    let e = 1f64.exp();
    for method in IMPLICIT {
        let err = |n: u64| {
            let run = model
                .simulate()
                .integrator(method)
                .dt(1.0 / n as f64)
                .steps(n)
                .run()
                .unwrap();
            (run.last().state.field(0)[0] - e).abs()
        };
        let (e1, e2) = (err(20), err(40));
        let order = (e1 / e2).log2();
        eprintln!("{method}: err(20) {e1:.2e} err(40) {e2:.2e} order {order:.2}");
        let want = method.info().order as f64;
        // Rosenbrock23 is 2, Rodas5P 5 (may hit rounding), BDF's fixed-step order varies.
        if method != Method::Bdf && e2 > 1e-13 {
            assert!((order - want).abs() < 0.35, "{method}: {order} vs {want}");
        }
    }
}

/// Case 1: an algebraic field coupled through neighbours. u′ = ∇²_h u from an eigenvector:
/// - Dirichlet(0) 3×1: sin((i+1)π/4), λ = 2cos(π/4) − 4 (the two y-neighbours read 0);
/// - Dirichlet(0) 4×4: sin((i+1)π/5)·sin((j+1)π/5), λ = 4cos(π/5) − 4;
/// - Neumann 4×4 (mirror ghost): cos((i+½)π/4), λ = 2cos(π/4) − 2;
/// - Periodic 4×4: cos(2πi/4) = cos(πi/2), λ = 2cos(π/2) − 2 = −2;
/// - Dirichlet(v) 1×1: u′ = 4(v − u), u = v + (u₀ − v)e^(−4t).
#[test]
fn laplacian_coupled_algebraic_field() {
    use std::f64::consts::PI;
    type Mode = (
        usize,
        usize,
        Boundary,
        Box<dyn Fn(usize, usize) -> f64>,
        f64,
    );
    let modes: Vec<Mode> = vec![
        (
            3,
            1,
            Boundary::Dirichlet(0.0),
            Box::new(|i, _| ((i + 1) as f64 * PI / 4.0).sin()),
            2.0 * (PI / 4.0).cos() - 4.0,
        ),
        (
            4,
            4,
            Boundary::Dirichlet(0.0),
            Box::new(|i, j| ((i + 1) as f64 * PI / 5.0).sin() * ((j + 1) as f64 * PI / 5.0).sin()),
            4.0 * (PI / 5.0).cos() - 4.0,
        ),
        (
            4,
            4,
            Boundary::Neumann,
            Box::new(|i, _| ((i as f64 + 0.5) * PI / 4.0).cos()),
            2.0 * (PI / 4.0).cos() - 2.0,
        ),
        (
            4,
            4,
            Boundary::Periodic,
            Box::new(|i, _| (i as f64 * PI / 2.0).cos()),
            -2.0,
        ),
    ];
    for (nx, ny, b, f, lambda) in modes {
        let model = Lap {
            u: grid(nx, ny, b, &f),
            z: grid(nx, ny, b, |_, _| 0.0),
        };
        for method in IMPLICIT {
            let run = to_one(&model, method).unwrap();
            let end = run.last().state.field(0);
            let err = (0..nx * ny)
                .map(|k| (end[k] - f(k % nx, k / nx) * lambda.exp()).abs())
                .fold(0.0, f64::max);
            eprintln!("Lap {nx}x{ny} {b:?} {method}: err {err:.2e}");
            let bound = if method == Method::ImplicitEuler {
                2e-3
            } else if method == Method::Rosenbrock23 {
                2e-5 // its global error at rtol 1e-8: 1e-6–8e-6 here, the same on GrowFixed
            } else {
                1e-6
            };
            assert!(err < bound, "{b:?} {method}: {err}");
        }
    }
    let v = 3.5;
    let model = Lap {
        u: grid(1, 1, Boundary::Dirichlet(v), |_, _| 1.0),
        z: grid(1, 1, Boundary::Dirichlet(v), |_, _| 0.0),
    };
    let exact = v + (1.0 - v) * (-4.0f64).exp();
    for method in IMPLICIT {
        let run = to_one(&model, method).unwrap();
        let err = (run.last().state.field(0)[0] - exact).abs();
        eprintln!("Lap 1x1 Dirichlet({v}) {method}: err {err:.2e}");
        let bound = if method == Method::ImplicitEuler {
            1e-2
        } else if method == Method::Rosenbrock23 {
            2e-5 // its global error at rtol 1e-8: 1e-6–8e-6 here, the same on GrowFixed
        } else {
            1e-6
        };
        assert!(err < bound, "{method}: {err}");
    }
}

/// Case 2: inconsistent starts are repaired; non-finite ones refused with a typed error.
#[test]
fn inconsistent_starts() {
    for z0 in [1e6, -1e6, 1e300, -1e300, -0.0, f64::MIN_POSITIVE, 5e-324] {
        let model = grow(3, 1, Boundary::Neumann, z0);
        let run = model
            .simulate()
            .integrator(Method::Rodas5P)
            .tolerances(1e-8, 1e-10)
            .duration(1.0)
            .run();
        match run {
            Ok(run) => {
                let z = run.first().state.field(1).to_vec();
                let u = run.first().state.field(0).to_vec();
                let end = run.last().state.field(0)[0];
                eprintln!(
                    "z0 = {z0:e}: z {z:?} (want {:?}), u(1) {end}",
                    [2.0, 2.2, 2.4]
                );
                for k in 0..3 {
                    assert!((z[k] - 2.0 * u[k]).abs() < 1e-12 * u[k], "z0 {z0}: {z:?}");
                }
            }
            Err(e) => panic!("z0 = {z0:e}: {e}"),
        }
    }
    for z0 in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
        // Grid::new refuses non-finite values? Use the state directly.
        let model = grow(3, 1, Boundary::Neumann, 0.0);
        let mut state = model.state();
        state.field_mut(1)[1] = z0;
        let error = model
            .simulate()
            .integrator(Method::Rodas5P)
            .initial_state(state)
            .duration(1.0)
            .run()
            .unwrap_err();
        eprintln!("z0 = {z0}: {error}");
        assert!(matches!(error, odyn::Error::InvalidInput { .. }), "{error}");
        let grid_error = Grid::new(3, 1, Boundary::Neumann, vec![0.0, z0, 0.0]);
        eprintln!("Grid::new with {z0}: {:?}", grid_error.map(|_| ()));
    }
}

/// Case 2: index 2 (g does not read z) is InconsistentStart on the dense block (3 cells) and
/// the sparse one (20×20 = 400 algebraic components).
#[test]
fn index_two_is_inconsistent_start() {
    for (nx, ny) in [(3, 1), (20, 20)] {
        let model = IndexTwo {
            u: grid(nx, ny, Boundary::Neumann, |_, _| 0.5),
            z: grid(nx, ny, Boundary::Neumann, |_, _| 0.0),
        };
        for method in IMPLICIT {
            let error = to_one(&model, method).unwrap_err();
            eprintln!("IndexTwo {nx}x{ny} {method}: {error}");
            assert!(
                matches!(&error, odyn::Error::InconsistentStart { residual, component, .. }
                    if residual.starts_with("z[") && component.starts_with("z[")),
                "{error}"
            );
        }
    }
}

/// Case 2: 20×20 consistent (the Laplacian-coupled field, sparse ∂g/∂z = I) repairs z.
#[test]
fn sparse_consistent_start() {
    let n = 20;
    let model = Lap {
        u: grid(n, n, Boundary::Dirichlet(0.0), |i, j| {
            ((i + 1) as f64 * 0.3).sin() * ((j + 1) as f64 * 0.2).cos()
        }),
        z: grid(n, n, Boundary::Dirichlet(0.0), |_, _| 7.0),
    };
    let run = model
        .simulate()
        .integrator(Method::Bdf)
        .tolerances(1e-6, 1e-9)
        .duration(0.1)
        .run()
        .unwrap();
    let first = &run.first().state;
    // z = ∇²u at every cell, by hand.
    let u = first.field(0);
    let at = |i: isize, j: isize| {
        if i < 0 || j < 0 || i >= n as isize || j >= n as isize {
            0.0
        } else {
            u[j as usize * n + i as usize]
        }
    };
    let mut worst = 0.0f64;
    for j in 0..n as isize {
        for i in 0..n as isize {
            let lap = at(i + 1, j) + at(i - 1, j) + at(i, j + 1) + at(i, j - 1) - 4.0 * at(i, j);
            worst = worst.max((first.field(1)[(j as usize) * n + i as usize] - lap).abs());
        }
    }
    eprintln!(
        "20x20 consistent start: |z − ∇²u| ≤ {worst:.1e}; {}",
        run.stats
    );
    assert!(worst < 1e-12, "{worst}");
}

/// Case 2 (own): a nonlinear g beside a huge differential component elsewhere. The consistent
/// start's convergence test is relative to max(|z|, ‖y‖∞), so u = 1e12 in one cell lets it
/// stop after one Newton update on z³ = 8 in another.
#[test]
#[ignore = "finding F1: consistent start accepts z = 6.69 (g = 291) and Rodas5P then takes 1e6 steps at t = 0"]
fn huge_differential_component_stops_newton_early() {
    let model = Cubic {
        u: grid(
            3,
            1,
            Boundary::Neumann,
            |i, _| if i == 2 { 1e12 } else { 1.0 },
        ),
        z: grid(3, 1, Boundary::Neumann, |_, _| 10.0),
    };
    // Duration 0: the consistent start alone.
    let start = model
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(0.0)
        .run()
        .unwrap();
    eprintln!(
        "Cubic, u = [1, 1, 1e12]: consistent start z = {:?}",
        start.first().state.field(1)
    );
    let small = Cubic {
        u: grid(3, 1, Boundary::Neumann, |_, _| 1.0),
        ..model.clone()
    };
    let start = small
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(0.0)
        .run()
        .unwrap();
    eprintln!(
        "Cubic, u = [1, 1, 1]: consistent start z = {:?}",
        start.first().state.field(1)
    );
    let consistent = Cubic {
        z: grid(3, 1, Boundary::Neumann, |_, _| 2.0),
        ..model.clone()
    };
    let run = consistent
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(0.1)
        .run();
    eprintln!(
        "Cubic, u = [1, 1, 1e12], z = 2 given: {:?}",
        run.map(|r| r.stats.steps)
    );
    let result = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-8, 1e-10)
        .duration(0.1)
        .run();
    match result {
        Ok(run) => {
            let z = run.first().state.field(1).to_vec();
            eprintln!(
                "Cubic start z = {z:?} (want [2, 2, 2]); end z {:?}",
                run.last().state.field(1)
            );
            assert!(z.iter().all(|z| (z - 2.0).abs() < 1e-8), "{z:?}");
        }
        Err(e) => panic!("{e}"),
    }
}

/// Case 3: explicit methods refuse the model with Error::Unsupported; a Stepper too.
#[test]
fn explicit_methods_refuse() {
    let model = grow(3, 3, Boundary::Neumann, 0.0);
    for method in Method::ALL {
        if IMPLICIT.contains(&method) {
            continue;
        }
        let s = model.simulate().integrator(method);
        let s = if method.is_adaptive() {
            s.duration(0.1)
        } else {
            s.dt(0.01).steps(10)
        };
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| s.run()));
        match result {
            Ok(Ok(_)) => panic!("{method} ran a DAE"),
            Ok(Err(error)) => {
                eprintln!("{method}: {error}");
                assert!(
                    matches!(error, odyn::Error::Unsupported { .. }),
                    "{method}: {error}"
                );
            }
            Err(_) => panic!("{method} panicked"),
        }
    }
    let refused = Stepper::<_, odyn::integrators::Tsit5<_>>::new(&model, model.state(), 0.0, 0.01);
    assert!(matches!(refused, Err(odyn::Error::Unsupported { .. })));
}

/// Case 3: Krylov and Auto(krylov_from 0) give the direct run's answer.
#[test]
fn linear_solvers_agree() {
    let model = Lap {
        u: grid(5, 4, Boundary::Dirichlet(0.5), |i, j| {
            (i as f64 * 0.7).sin() + j as f64 * 0.1
        }),
        z: grid(5, 4, Boundary::Dirichlet(0.5), |_, _| 0.0),
    };
    for method in IMPLICIT {
        let end = |linear: LinearSolver| {
            let s = model.simulate().integrator(method).newton(NewtonOptions {
                linear,
                ..NewtonOptions::default()
            });
            let s = if method.is_adaptive() {
                s.tolerances(1e-8, 1e-10).duration(1.0)
            } else {
                s.dt(1e-2).steps(100)
            };
            s.run().unwrap().last().state.as_slice().to_vec()
        };
        let direct = end(LinearSolver::Direct);
        for linear in [
            LinearSolver::Krylov(KrylovOptions::default()),
            LinearSolver::Auto(AutoPolicy {
                krylov_from: 0,
                ..AutoPolicy::default()
            }),
            LinearSolver::Auto(AutoPolicy {
                krylov_from: 1,
                ..AutoPolicy::default()
            }),
        ] {
            let other = end(linear.clone());
            let d = direct
                .iter()
                .zip(&other)
                .map(|(a, b)| (a - b).abs())
                .fold(0.0, f64::max);
            eprintln!("{method} {linear:?}: max diff {d:.1e}");
            assert!(d < 1e-12, "{method}: {d}");
        }
    }
}

/// Case 4: an event that changes u restores z = 2u after it.
#[test]
fn event_change_restores_consistency() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    // 0.5004 is inside a step of 1e-3: on a step boundary fixed-step runs hit finding F3
    // (`fixed_step_change_event_on_a_step_boundary`).
    let te = 0.5004;
    for method in IMPLICIT {
        let s =
            model
                .simulate()
                .integrator(method)
                .event(
                    Event::at_times("kick", vec![te]).change(|_, s: &mut GrowState| {
                        s.field_mut(0)[1] = 10.0;
                    }),
                );
        let s = if method.is_adaptive() {
            s.tolerances(1e-8, 1e-10).duration(1.0)
        } else {
            s.dt(1e-3).steps(1000)
        };
        let run = s.run().unwrap();
        let after = &run.events[0].after;
        eprintln!(
            "{method}: event at {} after z {:?} u {:?}; end u[1] {} (want {})",
            run.events[0].t,
            after.field(1),
            after.field(0),
            run.last().state.field(0)[1],
            10.0 * (1.0 - te).exp()
        );
        assert_eq!(after.field(1)[1], 20.0);
        // u[1] = 10·e^(1 − te) exactly after the kick.
        let err = (run.last().state.field(0)[1] / (10.0 * (1.0 - te).exp()) - 1.0).abs();
        let bound = if method == Method::ImplicitEuler {
            1e-2
        } else if method == Method::Rosenbrock23 {
            2e-5 // its global error at rtol 1e-8: 1e-6–8e-6 here, the same on GrowFixed
        } else {
            1e-6
        };
        assert!(err < bound, "{method}: {err}");
    }
    // A crossing event (u[0] = 2) stops the run at t = ln 2.
    let run = model
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(1e-10, 1e-12)
        .duration(1.0)
        .event(Event::crossing("two", |_, s: &GrowState| {
            s.field(0)[0] - 2.0
        }))
        .run()
        .unwrap();
    eprintln!("crossing at {} (want ln 2 = {})", run.last().t, 2f64.ln());
    assert!((run.last().t - 2f64.ln()).abs() < 1e-8);
}

/// Case 4: save_at unsorted, duplicate, outside the span; dense output; Trajectory::at.
#[test]
fn save_at_and_dense_output() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    for times in [
        vec![0.5, 0.25, 0.75],
        vec![0.5, 0.5, 0.5],
        vec![-1.0, 0.5, 2.0],
        vec![f64::NAN],
        vec![],
    ] {
        let result = model
            .simulate()
            .integrator(Method::Rodas5P)
            .tolerances(1e-8, 1e-10)
            .duration(1.0)
            .save_at(&times)
            .run();
        match result {
            Ok(run) => {
                let got: Vec<(f64, f64, f64)> = run
                    .samples
                    .iter()
                    .map(|s| {
                        (
                            s.t,
                            s.state.field(0)[0] / s.t.exp(),
                            s.state.field(1)[0] / (2.0 * s.state.field(0)[0]),
                        )
                    })
                    .collect();
                eprintln!("save_at {times:?}: (t, u/eᵗ, z/2u) {got:?}");
                for (t, ratio, zr) in got {
                    assert!((ratio - 1.0).abs() < 1e-7, "t {t}: {ratio}");
                    assert!((zr - 1.0).abs() < 1e-7, "t {t}: z/2u {zr}");
                }
            }
            Err(e) => eprintln!("save_at {times:?}: {e}"),
        }
    }
    for method in IMPLICIT {
        let s = model.simulate().integrator(method).dense_output(true);
        let s = if method.is_adaptive() {
            s.tolerances(1e-8, 1e-10).duration(1.0)
        } else {
            s.dt(1e-3).steps(1000)
        };
        let run = s.run().unwrap();
        for t in [0.0, 0.123, 0.5, 0.999, 1.0] {
            let at = run.at(t).unwrap();
            let (u, z) = (at.field(0)[0], at.field(1)[0]);
            eprintln!(
                "{method} at({t}): u/eᵗ {:.3e}, z/2u − 1 {:.1e}",
                u / t.exp() - 1.0,
                z / (2.0 * u) - 1.0
            );
            let bound = if method == Method::ImplicitEuler {
                1e-3
            } else if method == Method::Rosenbrock23 {
                2e-5 // its global error at rtol 1e-8: 1e-6–8e-6 here, the same on GrowFixed
            } else {
                1e-6
            };
            assert!((u / t.exp() - 1.0).abs() < bound, "{method} {t}");
            assert!((z / (2.0 * u) - 1.0).abs() < bound, "{method} {t}: z");
        }
        for t in [-0.1, 1.1, f64::NAN] {
            eprintln!("{method} at({t}): {:?}", run.at(t).map(|s| s.field(0)[0]));
        }
    }
}

/// Case 4: a Stepper repairs the start and steps every implicit method.
#[test]
fn stepper_steps_the_field_dae() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    fn go<I: odyn::Integrator<Grow>>(model: &Grow, name: &str) {
        let mut stepper = Stepper::<Grow, I>::new(model, model.state(), 0.0, 0.01).unwrap();
        let z = stepper.state().field(1).to_vec();
        for _ in 0..100 {
            stepper.step().unwrap();
        }
        let u = stepper.state().field(0)[0];
        eprintln!(
            "Stepper {name}: start z {z:?}, u(1)/e − 1 = {:.2e}",
            u / 1f64.exp() - 1.0
        );
        assert_eq!(z[0], 2.0, "{name}: start not repaired");
        assert!((u / 1f64.exp() - 1.0).abs() < 1e-2, "{name}");
    }
    go::<odyn::integrators::Rodas5P<_>>(&model, "Rodas5P");
    go::<odyn::integrators::Rosenbrock23<_>>(&model, "Rosenbrock23");
    go::<odyn::integrators::Bdf<_>>(&model, "Bdf");
    go::<odyn::integrators::ImplicitEuler<_>>(&model, "ImplicitEuler");
}

/// Case 4: absurd tolerances, steps and durations: a typed error or a right answer.
#[test]
fn absurd_options() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    let check = |label: &str, r: odyn::Result<odyn::Trajectory<GrowState>>| match r {
        Ok(run) => {
            let last = run.last();
            let ratio = last.state.field(0)[0] / last.t.exp();
            let zr = last.state.field(1)[0] / (2.0 * last.state.field(0)[0]);
            eprintln!(
                "{label}: ok, t {} u/eᵗ {ratio} z/2u {zr}, {} steps",
                last.t, run.stats.steps
            );
        }
        Err(e) => eprintln!("{label}: Err {e}"),
    };
    for method in [Method::Rodas5P, Method::Rosenbrock23, Method::Bdf] {
        for (rtol, atol) in [
            (1e-14, 1e-14),
            (1e-1, 1e-1),
            (1e-6, 0.0),
            (0.0, 0.0),
            (-1.0, 1e-6),
            (f64::NAN, 1e-6),
        ] {
            let r = model
                .simulate()
                .integrator(method)
                .tolerances(rtol, atol)
                .duration(1.0)
                .run();
            check(&format!("{method} rtol {rtol} atol {atol}"), r);
        }
        for d in [0.0, -1.0, f64::NAN, f64::INFINITY, 1e-300] {
            let r = model
                .simulate()
                .integrator(method)
                .tolerances(1e-6, 1e-8)
                .duration(d)
                .run();
            check(&format!("{method} duration {d}"), r);
        }
    }
    for method in IMPLICIT {
        for dt in [1e3, 1e-300, 0.0, -0.1, f64::NAN, f64::INFINITY] {
            let r = model.simulate().integrator(method).dt(dt).steps(3).run();
            check(&format!("{method} dt {dt} steps 3"), r);
        }
    }
}

/// 0 = z, 0 = w − z: every field algebraic (M = 0). The macro takes it; the solution is the
/// constant z = w = 1 (g = [z − 1, w − z]).
#[system]
#[derive(Clone, Debug)]
struct AllAlg {
    #[field]
    #[algebraic]
    z: Grid,
    #[field]
    #[algebraic]
    w: Grid,
}

#[system]
impl AllAlg {
    #[cell]
    fn rates(&self, z: Stencil, w: Stencil) -> [f64; 2] {
        [z.c - 1.0, w.c - z.c]
    }
}

/// Case 5 (runtime side): a model with no differential component.
#[test]
fn every_field_algebraic() {
    let model = AllAlg {
        z: grid(3, 3, Boundary::Neumann, |i, _| i as f64),
        w: grid(3, 3, Boundary::Neumann, |_, j| -(j as f64)),
    };
    for method in IMPLICIT {
        let result =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| to_one(&model, method)));
        match result {
            Ok(Ok(run)) => {
                let end = run.last().state.as_slice().to_vec();
                eprintln!(
                    "AllAlg {method}: ok, end {:?}.., {} steps",
                    &end[..3],
                    run.stats.steps
                );
                assert!(end.iter().all(|v| (v - 1.0).abs() < 1e-12), "{end:?}");
            }
            Ok(Err(e)) => eprintln!("AllAlg {method}: Err {e}"),
            Err(_) => panic!("AllAlg {method}: panic"),
        }
    }
}

/// u′ = −u, 0 = z − z.e (periodic): ∂g/∂z = I − shift is singular without an empty column (the
/// constants are its null space), so z is determined only up to a constant.
#[system]
#[derive(Clone, Debug)]
struct Shift {
    #[field]
    u: Grid,
    #[field]
    #[algebraic]
    z: Grid,
}

#[system]
impl Shift {
    #[cell]
    fn rates(&self, u: Stencil, z: Stencil) -> [f64; 2] {
        [-u.c, z.c - z.e]
    }
}

/// Case 2: a singular ∂g/∂z with no empty column, dense (3×3) and sparse (20×20): from an
/// inconsistent z, InconsistentStart; from a consistent one (z constant), the pencil M − c·J is
/// singular for every c, so a step cannot be solved: a typed error, not a panic or garbage.
#[test]
fn singular_block_without_an_empty_column() {
    for n in [3, 20] {
        let inconsistent = Shift {
            u: grid(n, n, Boundary::Periodic, |_, _| 1.0),
            z: grid(n, n, Boundary::Periodic, |i, j| (i * 7 + j) as f64),
        };
        for method in IMPLICIT {
            let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                to_one(&inconsistent, method)
            }));
            match r {
                Ok(Ok(run)) => panic!(
                    "Shift {n}² inconsistent {method}: ran, z {:?}",
                    &run.first().state.field(1)[..3]
                ),
                Ok(Err(e)) => {
                    eprintln!("Shift {n}² inconsistent {method}: {e}");
                    assert!(matches!(e, odyn::Error::InconsistentStart { .. }), "{e}");
                }
                Err(_) => panic!("Shift {n}² {method}: panic"),
            }
        }
    }
}

/// Finding F2: from a consistent start of the singular Shift model the pencil M − c·J is
/// singular for every c. Expected: a typed error naming the singular matrix (SingularMatrix or
/// InconsistentStart). Got: Rodas5P, Rosenbrock23 and Bdf take 1 000 000 steps at t = 0 and
/// report "f is probably not smooth there" (20²: minutes); ImplicitEuler says "the model's
/// derivative or Jacobian returned NaN or infinity".
#[test]
#[ignore = "finding F2: singular pencil is a 1e6-step loop with a misleading error"]
fn singular_pencil_is_a_typed_error() {
    for n in [3, 20] {
        let consistent = Shift {
            u: grid(n, n, Boundary::Periodic, |_, _| 1.0),
            z: grid(n, n, Boundary::Periodic, |_, _| 3.0),
        };
        for method in IMPLICIT {
            let error = to_one(&consistent, method).unwrap_err();
            eprintln!("Shift {n}² consistent {method}: {error}");
            assert!(
                matches!(
                    error,
                    odyn::Error::SingularMatrix { .. } | odyn::Error::InconsistentStart { .. }
                ),
                "{method}: {error}"
            );
        }
    }
}

/// Case 4: an event that changes only the algebraic field: the consistent start after it puts
/// z back to 2u, and the run goes on as if nothing happened.
#[test]
fn event_changing_the_algebraic_field() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    for method in IMPLICIT {
        let s = model.simulate().integrator(method).event(
            Event::at_times("poke", vec![0.5004]).change(|_, s: &mut GrowState| {
                s.field_mut(1)[2] = -1e9;
            }),
        );
        let s = if method.is_adaptive() {
            s.tolerances(1e-8, 1e-10).duration(1.0)
        } else {
            s.dt(1e-3).steps(1000)
        };
        let run = s.run().unwrap();
        let after = &run.events[0].after;
        eprintln!(
            "{method}: after poke z {:?} u {:?}",
            after.field(1),
            after.field(0)
        );
        assert!((after.field(1)[2] - 2.0 * after.field(0)[2]).abs() < 1e-9);
    }
}

/// Case 3 (own): Auto on a grid big enough that Auto would pick Krylov by itself (40×40,
/// 3 200 components) ends where Direct does.
#[test]
fn auto_on_a_bigger_grid() {
    let n = 40;
    let model = Lap {
        u: grid(n, n, Boundary::Dirichlet(0.0), |i, j| {
            ((i + 1) as f64 * 0.3).sin() * ((j + 1) as f64 * 0.2).cos()
        }),
        z: grid(n, n, Boundary::Dirichlet(0.0), |_, _| 0.0),
    };
    let end = |linear: LinearSolver| {
        let run = model
            .simulate()
            .integrator(Method::Bdf)
            .tolerances(1e-6, 1e-9)
            .newton(NewtonOptions {
                linear,
                ..NewtonOptions::default()
            })
            .duration(0.5)
            .run()
            .unwrap();
        (run.last().state.as_slice().to_vec(), run.stats.linear)
    };
    let (direct, w0) = end(LinearSolver::Direct);
    let (auto, w1) = end(LinearSolver::Auto(AutoPolicy::default()));
    let d = direct
        .iter()
        .zip(&auto)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    eprintln!("40² Bdf: Direct {w0:?}\n Auto {w1:?}\n max diff {d:.1e}");
    assert!(d < 1e-12, "{d}");
}

/// Case 4 (own): a time event under fixed-step implicit Euler, on the field DAE and the
/// fixed-size one, with an event that only records.
#[test]
fn fixed_step_time_event() {
    let field = grow(3, 1, Boundary::Neumann, 0.0);
    let fixed = GrowFixed {
        u: [1.0, 1.1, 1.2],
        z: [0.0; 3],
    };
    for method in IMPLICIT {
        for at in [0.5, 0.3, 0.123] {
            let a = field
                .simulate()
                .integrator(method)
                .dt(1e-3)
                .steps(1000)
                .event(Event::at_times("mark", vec![at]))
                .run();
            let b = fixed
                .simulate()
                .integrator(method)
                .dt(1e-3)
                .steps(1000)
                .event(Event::at_times("mark", vec![at]))
                .run();
            eprintln!(
                "{method} fixed dt 1e-3, record event at {at}: field {:?}, fixed-size {:?}",
                a.as_ref().map(|r| r.last().state.field(0)[0]),
                b.as_ref().map(|r| r.last().state.u[0])
            );
            // A record event leaves the run as it was: field and fixed-size models agree.
            let (a, b) = (a.unwrap(), b.unwrap());
            assert!((a.last().state.field(0)[0] - b.last().state.u[0]).abs() < 1e-12);
        }
    }
}

/// Finding F3: a change event (even one that changes nothing) at a time that falls on a
/// fixed step's end (0.5 = 500·dt, or the end 1.0) makes the next step dt = 0, whose matrix M
/// is singular: every DAE method fails (`SingularMatrix { t: 0.5, dt: 0.0 }`, or for the
/// field model's Bdf/ImplicitEuler `NewtonDidNotConverge { cause: NotFinite }`, whose message
/// blames NaN from the model). The fixed-size model fails the same way. Inside a step (0.1234)
/// or at 0 the run is fine.
#[test]
#[ignore = "finding F3: change event on a fixed-step boundary → dt = 0 step → singular M"]
fn fixed_step_change_event_on_a_step_boundary() {
    let field = grow(3, 1, Boundary::Neumann, 0.0);
    let fixed = GrowFixed {
        u: [1.0, 1.1, 1.2],
        z: [0.0; 3],
    };
    for method in IMPLICIT {
        for at in [0.5, 1.0] {
            let a = field
                .simulate()
                .integrator(method)
                .dt(1e-3)
                .steps(1000)
                .event(Event::at_times("c", vec![at]).change(|_, _: &mut GrowState| {}))
                .run();
            let b = fixed
                .simulate()
                .integrator(method)
                .dt(1e-3)
                .steps(1000)
                .event(Event::at_times("c", vec![at]).change(|_, _: &mut GrowFixedState| {}))
                .run();
            eprintln!(
                "{method} dt 1e-3, no-op change at {at}: field {:?}, fixed-size {:?}",
                a.as_ref().map(|r| r.last().state.field(0)[0]),
                b.as_ref().map(|r| r.last().state.u[0])
            );
            assert!(a.is_ok() && b.is_ok(), "{method} at {at}");
        }
    }
}

/// The same no-op change event inside a step (0.1234) and at the start: the run is the
/// event-free one's: within each method's error of u(1) = e.
#[test]
fn fixed_step_change_event_inside_a_step() {
    let field = grow(3, 1, Boundary::Neumann, 0.0);
    for method in IMPLICIT {
        let plain = field
            .simulate()
            .integrator(method)
            .dt(1e-3)
            .steps(1000)
            .run()
            .unwrap();
        for at in [0.1234, 0.0] {
            let run = field
                .simulate()
                .integrator(method)
                .dt(1e-3)
                .steps(1000)
                .event(Event::at_times("c", vec![at]).change(|_, _: &mut GrowState| {}))
                .run()
                .unwrap();
            let (u, u0) = (run.last().state.field(0)[0], plain.last().state.field(0)[0]);
            eprintln!(
                "{method}: no-op change at {at}: t {} u {u} (no event {u0})",
                run.last().t
            );
            assert_eq!(run.last().t, 1.0);
            // Against u(1) = e: a change event restarts BDF at order 1 (measured 7.5e-6 against
            // 2.5e-6 without it), implicit Euler is first order (1.4e-3).
            let bound = match method {
                Method::ImplicitEuler => 2e-3,
                _ => 1e-5,
            };
            assert!((u - 1f64.exp()).abs() < bound, "{method} at {at}");
        }
    }
}
