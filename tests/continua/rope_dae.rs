//! A rope of rigid rods as a differential–algebraic field model (`scenes::RodRope`):
//! one rod is the Cartesian pendulum, exactly; a rope of 100 rods keeps its length to the
//! tolerance over 10 s under Rodas5P and BDF with the sparse solve, against XPBD's rigid links
//! on the same rope.

use odyn::nalgebra::Vector2;
use odyn::prelude::*;
use odyn::xpbd::{Constraint, Xpbd, XpbdOptions};
use odyn::{AutoPolicy, KrylovOptions, LinearSolver};
use scenes::{PENDULUM_10, RodRope};

/// One rod of 1 m with a 1 kg mass released at θ₀ = 2.5 rad is the Cartesian pendulum
/// (`CartesianPendulum::released`): the field model ends at the exact state of
/// `scenes::PENDULUM_10` (the angle form's solution in Jacobi elliptic functions), λ
/// included, within 1e-6 relative under Rodas5P and BDF at rtol 1e-8.
#[test]
fn one_rod_is_the_pendulum() {
    let theta: f64 = 2.5;
    let rope = RodRope::at_rest(&[[theta.sin(), -theta.cos()]], 1.0, 1.0).unwrap();
    // BDF at 1e-10, as the dense pendulum in `tests/models/dae` (its phase error is 6e-6 at
    // 1e-8).
    for (method, rtol) in [(Method::Rodas5P, 1e-8), (Method::Bdf, 1e-10)] {
        let run = rope
            .simulate()
            .integrator(method)
            .tolerances(rtol, 1e-10)
            .duration(10.0)
            .run()
            .unwrap();
        let end = &run.last().state;
        // (x, y, u, v, λ): fields 0–3 and 6.
        let got = [
            end.field(0)[0],
            end.field(1)[0],
            end.field(2)[0],
            end.field(3)[0],
            end.field(6)[0],
        ];
        eprintln!("{method:?}: {got:?} in {} steps", run.stats.steps);
        for (g, want) in got.iter().zip(PENDULUM_10) {
            assert!(
                (g - want).abs() < 1e-6 * want.abs(),
                "{method:?}: {g} against {want}"
            );
        }
    }
}

/// The same rope as XPBD particles: `links` + 1 of `mass` kg (the first pinned at the origin),
/// held out straight at `angle` from the downward vertical, rigid links (compliance 0).
fn xpbd_rope(links: usize, mass: f64, length: f64, angle: f64, substeps: u32) -> Xpbd<2> {
    let direction = Vector2::new(angle.sin(), -angle.cos());
    let x = (0..=links).map(|i| i as f64 * length * direction).collect();
    let mut rope = Xpbd::new(
        x,
        vec![Vector2::zeros(); links + 1],
        &vec![mass; links + 1],
        &[0],
        Vector2::new(0.0, -9.81),
    )
    .unwrap();
    rope.constraints = (0..links)
        .map(|i| Constraint::Distance {
            ends: [i, i + 1],
            rest: length,
            compliance: 0.0,
        })
        .collect();
    rope.options = XpbdOptions {
        substeps,
        iterations: 1,
    };
    rope
}

/// A rope of 100 rods (2 m, 1 kg) released straight at 45° from the vertical, 3 s under
/// Rodas5P at rtol 1e-6, atol 1e-8, its Newton matrices factorized by sparse LU:
/// - every rod keeps its length within rtol·L over the run (measured 9.4e-8·L), and the energy
///   stays within rtol of its start (measured 7.3e-9 J of 7.0 J): the exact solution conserves
///   both, and Baumgarte's terms keep the drift from growing;
/// - XPBD's rigid links on the same rope, at 60 frames a second with 100 substeps of one sweep,
///   stretch by 2.3e-3·L over the 3 s, four orders more;
/// - XPBD's rope converges to the DAE's: its tip is 2.0e-3 m from the DAE's at t = 0.5 s with
///   100 substeps and 4.2e-5 m with 1 000 (the rope swings through ~1.4 m by then).
#[test]
fn a_hundred_rods_keep_their_length() {
    let (links, mass, length) = (100, 0.01, 0.02);
    let (rtol, atol) = (1e-6, 1e-8);
    let angle = std::f64::consts::FRAC_PI_4;
    let rope = RodRope::straight(links, mass, length, angle).unwrap();
    let frames: Vec<f64> = (0..=180).map(|i| i as f64 / 60.0).collect();
    let run = rope
        .simulate()
        .integrator(Method::Rodas5P)
        .tolerances(rtol, atol)
        .duration(3.0)
        .save_at(&frames)
        .run()
        .unwrap();
    let drift = run
        .samples
        .iter()
        .map(|s| rope.drift(&s.state))
        .fold(0.0, f64::max);
    let e0 = rope.energy(&run.first().state);
    let energy = run
        .samples
        .iter()
        .map(|s| (rope.energy(&s.state) - e0).abs())
        .fold(0.0, f64::max);
    eprintln!(
        "Rodas5P: {}; drift {drift:.2e}·L, energy {energy:.2e} J of {e0:.3} J",
        run.stats
    );
    assert!(drift < rtol, "{drift}");
    assert!(energy < rtol * e0.abs(), "{energy}");
    assert!(run.stats.linear.lu > 0, "{}", run.stats);
    let tip = |frame: usize| {
        let state = &run.samples[frame].state;
        Vector2::new(state.field(0)[links - 1], state.field(1)[links - 1])
    };

    let mut xpbd = xpbd_rope(links, mass, length, angle, 100);
    let mut stretch = 0.0f64;
    let mut apart = Vec::new();
    for frame in 1..=180 {
        xpbd.step(1.0 / 60.0).unwrap();
        stretch = stretch.max(xpbd.max_stretch());
        apart.push((xpbd.x[links] - tip(frame)).norm());
    }
    eprintln!(
        "XPBD, 100 substeps: stretch {stretch:.2e}·L, tip apart {:.2e} m at 0.5 s",
        apart[29]
    );
    assert!(stretch > 1e3 * drift, "{stretch} against {drift}");
    let mut fine = xpbd_rope(links, mass, length, angle, 1000);
    for _ in 0..30 {
        fine.step(1.0 / 60.0).unwrap();
    }
    let fine_apart = (fine.x[links] - tip(30)).norm();
    eprintln!("XPBD, 1 000 substeps: tip apart {fine_apart:.2e} m at 0.5 s");
    assert!(
        fine_apart < 1e-4 && fine_apart < 0.1 * apart[29],
        "{fine_apart} {}",
        apart[29]
    );
}

/// What a hostile user can do to a field model with algebraic fields:
/// - an explicit method refuses it with `Error::Unsupported`;
/// - Krylov solves asked for (or `Auto` past its threshold) give way to the direct solve of
///   M − c·J, whose Krylov products and preconditioners know only I − c·J: the same run;
/// - a start no Newton iteration can make consistent (two particles at one place: the rod
///   between them has no direction, ∂g/∂z is singular) is `Error::InconsistentStart`, on the
///   dense block (one rod) and the sparse one (300 algebraic components);
/// - a non-finite start is refused before the first step.
#[test]
fn bad_input_is_a_typed_error() {
    let rope = RodRope::straight(3, 0.1, 0.5, 1.0).unwrap();
    let error = rope
        .simulate()
        .integrator(Method::Rk4)
        .dt(1e-3)
        .steps(1)
        .run()
        .unwrap_err();
    assert!(matches!(error, odyn::Error::Unsupported { .. }), "{error}");

    let end = |linear: LinearSolver| {
        let run = rope
            .simulate()
            .integrator(Method::Bdf)
            .tolerances(1e-8, 1e-10)
            .newton(NewtonOptions {
                linear,
                ..NewtonOptions::default()
            })
            .duration(1.0)
            .run()
            .unwrap();
        run.last().state.as_slice().to_vec()
    };
    let direct = end(LinearSolver::Direct);
    let krylov = end(LinearSolver::Krylov(KrylovOptions::default()));
    let eager = end(LinearSolver::Auto(AutoPolicy {
        krylov_from: 0,
        ..AutoPolicy::default()
    }));
    assert_eq!(direct, krylov);
    assert_eq!(direct, eager);

    for links in [1, 100] {
        let mut rope = RodRope::straight(links, 0.01, 0.02, 0.5).unwrap();
        let last = links - 1;
        if links == 1 {
            // The particle at the pinned end.
            rope.x.values_mut()[0] = 0.0;
            rope.y.values_mut()[0] = 0.0;
        } else {
            rope.x.values_mut()[last] = rope.x.values()[last - 1];
            rope.y.values_mut()[last] = rope.y.values()[last - 1];
        }
        let error = rope
            .simulate()
            .integrator(Method::Rodas5P)
            .duration(0.1)
            .run()
            .unwrap_err();
        // The rod without a direction is the last: its force's column of ∂g/∂z is zero.
        let named = format!("lambda[{last},0]");
        assert!(
            matches!(&error, odyn::Error::InconsistentStart { component, .. } if *component == named),
            "{error}"
        );
    }

    let mut rope = RodRope::straight(2, 0.1, 0.5, 1.0).unwrap();
    rope.u.values_mut()[1] = f64::NAN;
    let error = rope
        .simulate()
        .integrator(Method::Rodas5P)
        .duration(0.1)
        .run()
        .unwrap_err();
    assert!(matches!(error, odyn::Error::InvalidInput { .. }), "{error}");
}
