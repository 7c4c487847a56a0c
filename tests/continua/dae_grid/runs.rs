//! Runs: refusals, linear solvers, events, `save_at`, dense output, `Stepper`, options.

use super::*;
use crate::common::max_abs_difference;
use odyn::{AutoPolicy, Event, KrylovOptions, LinearSolver, Stepper};

/// Explicit methods refuse the model with Error::Unsupported; a Stepper too.
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

/// Krylov and Auto(krylov_from 0) give the direct run's answer.
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
            let other = end(linear);
            let d = max_abs_difference(&direct, &other);
            eprintln!("{method} {linear:?}: max diff {d:.1e}");
            assert!(d < 1e-12, "{method}: {d}");
        }
    }
}

/// An event that changes u restores z = 2u after it.
#[test]
fn event_change_restores_consistency() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    // 0.5004 is inside a step of 1e-3 (on a step boundary: `fixed_step_change_event_on_a_step_boundary`)
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

/// An event that changes only the algebraic field: the consistent start after it puts
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

/// Save_at unsorted, duplicate, outside the span; dense output; Trajectory::at.
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

/// A Stepper repairs the start and steps every implicit method.
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

/// Absurd tolerances, steps and durations: `InvalidInput` naming the option, or a run whose
/// algebraic field stays z = 2u (to 1e-8) and whose u follows eᵗ within 100 times the
/// tolerance (1e-9 at the tightest: Rosenbrock23 at 1e-14 ends 1.3e-10 off).
#[test]
fn absurd_options() {
    let model = grow(3, 1, Boundary::Neumann, 0.0);
    let check = |label: &str, r: odyn::Result<odyn::Trajectory<GrowState>>, tol: Option<f64>| {
        let Some(tol) = tol else {
            let error = r.err().unwrap_or_else(|| panic!("{label}: ran"));
            assert!(
                matches!(error, odyn::Error::InvalidInput { .. }),
                "{label}: {error}"
            );
            return;
        };
        let run = r.unwrap_or_else(|e| panic!("{label}: {e}"));
        let last = run.last();
        let (u, z) = (last.state.field(0)[0], last.state.field(1)[0]);
        assert!(
            (z - 2.0 * u).abs() <= 1e-8 * u.abs(),
            "{label}: z {z}, u {u}"
        );
        if tol.is_finite() {
            let ratio = u / last.t.exp();
            assert!(
                (ratio - 1.0).abs() <= (100.0 * tol).max(1e-9),
                "{label}: u/eᵗ {ratio}"
            );
        }
    };
    for method in [Method::Rodas5P, Method::Rosenbrock23, Method::Bdf] {
        for (rtol, atol, ok) in [
            (1e-14, 1e-14, true),
            (1e-1, 1e-1, true),
            (1e-6, 0.0, true),
            (0.0, 0.0, false),
            (-1.0, 1e-6, false),
            (f64::NAN, 1e-6, false),
        ] {
            let r = model
                .simulate()
                .integrator(method)
                .tolerances(rtol, atol)
                .duration(1.0)
                .run();
            let label = format!("{method} rtol {rtol} atol {atol}");
            check(&label, r, ok.then_some(rtol.max(atol)));
        }
        for (d, ok) in [
            (0.0, true),
            (-1.0, false),
            (f64::NAN, false),
            (f64::INFINITY, false),
            (1e-300, true),
        ] {
            let r = model
                .simulate()
                .integrator(method)
                .tolerances(1e-6, 1e-8)
                .duration(d)
                .run();
            check(&format!("{method} duration {d}"), r, ok.then_some(1e-6));
        }
    }
    for method in IMPLICIT {
        // dt = 1e3: eᵗ overflows at t = 3000 and the methods damp u: z = 2u alone is checked.
        for (dt, tol) in [
            (1e3, Some(f64::INFINITY)),
            (1e-300, Some(1e-9)),
            (0.0, None),
            (-0.1, None),
            (f64::NAN, None),
            (f64::INFINITY, None),
        ] {
            let r = model.simulate().integrator(method).dt(dt).steps(3).run();
            check(&format!("{method} dt {dt} steps 3"), r, tol);
        }
    }
}

/// Auto on a grid big enough that Auto would pick Krylov by itself (40×40,
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
    let d = max_abs_difference(&direct, &auto);
    eprintln!("40² Bdf: Direct {w0:?}\n Auto {w1:?}\n max diff {d:.1e}");
    assert!(d < 1e-12, "{d}");
}

/// A time event under fixed-step implicit Euler, on the field DAE and the
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

/// A change event (even one that changes nothing) at a time that falls on a fixed step's end
/// (0.5 = 500·dt, or the end 1.0) once made the next step one of dt = 0, whose matrix M is
/// singular: every DAE method failed (`SingularMatrix { t: 0.5, dt: 0.0 }`), the fixed-size
/// model too. Now the run is the event-free one's within each method's error of u(1) = e (the
/// bounds of `fixed_step_change_event_inside_a_step`).
#[test]
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
            let bound = match method {
                Method::ImplicitEuler => 2e-3,
                _ => 1e-5,
            };
            let (a, b) = (a.unwrap(), b.unwrap());
            assert_eq!((a.last().t, b.last().t), (1.0, 1.0));
            assert!(
                (a.last().state.field(0)[0] - 1f64.exp()).abs() < bound,
                "{method} at {at}"
            );
            assert!(
                (b.last().state.u[0] - 1f64.exp()).abs() < bound,
                "{method} at {at}"
            );
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
