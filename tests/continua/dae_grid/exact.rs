//! Exact solutions, orders, and the field model against the fixed-size one.

use super::*;
use crate::common::max_abs_difference;

/// U′ = u on every grid, boundary and implicit method; z = 2u everywhere.
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

/// The field model against the fixed-size one, same method and options.
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
        let d = max_abs_difference(&fa, &fb);
        eprintln!(
            "{method}: field {:?} fixed {:?} diff {d:.1e}; steps {} / {}",
            fa, fb, a.stats.steps, b.stats.steps
        );
        assert!(d < 1e-9, "{method}: {d}");
    }
}

/// Orders at fixed steps, u′ = u to t = 1 on a 3×1 grid.
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

/// An algebraic field coupled through neighbours. u′ = ∇²_h u from an eigenvector:
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

/// A model with no differential component.
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
