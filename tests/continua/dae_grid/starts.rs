//! Consistent starts: repaired, refused as inconsistent, singular (dense and sparse ∂g/∂z).

use super::*;

/// Inconsistent starts are repaired; non-finite ones refused with a typed error.
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

/// Index 2 (g does not read z) is InconsistentStart on the dense block (3 cells) and
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

/// 20×20 consistent (the Laplacian-coupled field, sparse ∂g/∂z = I) repairs z.
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

/// A nonlinear g beside a huge differential component elsewhere: the consistent start's
/// convergence test was relative to max(|z|, ‖y‖∞), so u = 1e12 in one cell let it stop after
/// one Newton update on z³ = 8 in another (z = 6.69, g = 291, and Rodas5P then took 10⁶ steps
/// at t = 0). Now relative to max(|z|, 10⁻⁶·‖y‖∞): z = 2, the root.
#[test]
fn a_huge_differential_component_does_not_stop_newton_early() {
    // z³ = 8 in every cell: z = 2 whatever u is; from z = 10, beside u of 1 and of 1e12.
    for far in [1.0, 1e12] {
        let model = Cubic {
            u: grid(
                3,
                1,
                Boundary::Neumann,
                |i, _| if i == 2 { far } else { 1.0 },
            ),
            z: grid(3, 1, Boundary::Neumann, |_, _| 10.0),
        };
        let run = model
            .simulate()
            .integrator(Method::Rodas5P)
            .tolerances(1e-8, 1e-10)
            .duration(0.1)
            .run()
            .unwrap();
        let z = run.first().state.field(1).to_vec();
        assert!(
            z.iter().all(|z| (z - 2.0).abs() < 1e-8),
            "u = {far:e}: {z:?}"
        );
        let end = run.last().state.field(1).to_vec();
        assert!(
            end.iter().all(|z| (z - 2.0).abs() < 1e-8),
            "u = {far:e}: {end:?}"
        );
    }
}

/// A singular ∂g/∂z with no empty column, dense (3×3) and sparse (20×20): from an
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

/// From a consistent start of the Shift model (0 = z − z.e on a periodic grid: ∂g/∂z singular,
/// every row summing to zero), M − c·J is singular for every c. Once Rodas5P, Rosenbrock23 and
/// Bdf took 1 000 000 steps at t = 0 (minutes at 20²) and blamed a non-smooth f; the
/// consistent start now checks ∂g/∂z at the start, consistent or not, and the run stops there
/// with `InconsistentStart`.
#[test]
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
                matches!(error, odyn::Error::InconsistentStart { .. }),
                "{method}: {error}"
            );
        }
    }
}
