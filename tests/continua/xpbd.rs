//! XPBD: rigid links stretch less with more substeps, a compliance α behaves as a spring of
//! stiffness 1/α whatever the iterations and the step, colliders are never entered, and bad
//! input is a typed error.

use odyn::Error;
use odyn::nalgebra::Vector2;
use odyn::xpbd::{Collider, Constraint, Xpbd, XpbdOptions};

/// A chain of `n` links of length `link`, pinned at the origin, hanging straight down at rest
/// (or horizontal, `horizontal`), unit masses, g = 9.81, every link of compliance `compliance`.
fn chain(n: usize, link: f64, compliance: f64, horizontal: bool) -> Xpbd<2> {
    let x = (0..=n)
        .map(|i| {
            let s = i as f64 * link;
            if horizontal {
                Vector2::new(s, 0.0)
            } else {
                Vector2::new(0.0, -s)
            }
        })
        .collect();
    let mut xpbd = Xpbd::new(
        x,
        vec![Vector2::zeros(); n + 1],
        &vec![1.0; n + 1],
        &[0],
        Vector2::new(0.0, -9.81),
    )
    .unwrap();
    xpbd.constraints = (0..n)
        .map(|i| Constraint::Distance {
            ends: [i, i + 1],
            rest: link,
            compliance,
        })
        .collect();
    xpbd
}

/// Zero compliance: a 20-link rope released horizontally keeps its length better with more
/// substeps (one iteration each), the Small Steps result: the largest stretch over 2 s falls
/// with the substep count, and from 4 to 64 substeps by at least 100× (it falls like h²).
#[test]
fn rigid_links_stretch_less_with_more_substeps() {
    let mut worst = Vec::new();
    for substeps in [1, 4, 16, 64] {
        let mut rope = chain(20, 0.1, 0.0, true);
        rope.options = XpbdOptions {
            substeps,
            iterations: 1,
        };
        let mut max = 0.0f64;
        for _ in 0..120 {
            rope.step(1.0 / 60.0).unwrap();
            max = max.max(rope.max_stretch());
        }
        eprintln!("{substeps} substeps: max stretch {max:e}");
        worst.push(max);
    }
    assert!(worst.windows(2).all(|w| w[1] < w[0]), "{worst:?}");
    assert!(worst[1] / worst[3] > 100.0, "{worst:?}");
}

/// A 5-link chain with compliance α per link hangs, on average over 20 s of oscillation, at the
/// spring equilibrium: link k from the top carries the weight of the 5 − k masses below it, so
/// the total extension is m·g·α·(5 + 4 + 3 + 2 + 1) = 15·m·g·α. Within 2 % for every iteration
/// count (1, 4, 16) and step (1/60 s with 1 or 10 substeps, 1/240 s with 1) once the sweeps
/// converge: the stiffness is 1/α, independent of how the constraint is solved (Macklin et al.
/// 2016, §4). The exception is one sweep of one 1/60 s step, which leaves the chain softer.
#[test]
fn compliance_is_the_inverse_stiffness_whatever_the_iterations_and_step() {
    let (alpha, link, g) = (1e-3, 0.2, 9.81);
    let theory = 15.0 * g * alpha;
    for iterations in [1, 4, 16] {
        for (dt, substeps) in [(1.0 / 60.0, 1), (1.0 / 60.0, 10), (1.0 / 240.0, 1)] {
            let mut chain = chain(5, link, alpha, false);
            chain.options = XpbdOptions {
                substeps,
                iterations,
            };
            let steps = (20.0 / dt) as usize;
            let mut sum = 0.0;
            for _ in 0..steps {
                chain.step(dt).unwrap();
                sum += -chain.x[5].y - 5.0 * link;
            }
            let mean = sum / steps as f64;
            eprintln!(
                "iterations {iterations}, dt {dt:.4}, substeps {substeps}: extension {mean:.6e} \
                 (theory {theory:.6e})"
            );
            if (iterations, substeps, dt) == (1, 1, 1.0 / 60.0) {
                // One Gauss–Seidel sweep of one big step has not converged along the chain: the
                // chain is softer than 1/α (measured 18.5 % more extension). Substeps fix it.
                assert!(mean > 1.1 * theory, "{mean} vs {theory}");
            } else {
                assert!(
                    (mean / theory - 1.0).abs() < 0.02,
                    "iterations {iterations}, dt {dt}, substeps {substeps}: {mean} vs {theory}"
                );
            }
        }
    }
}

/// One mass on one compliant link oscillates at ω = 1/√(m·α): the period measured from the
/// upward crossings of the equilibrium over 5 s is 2π√(mα) within 2 % at 10 substeps of 1/60 s.
#[test]
fn a_compliant_link_oscillates_at_its_spring_frequency() {
    let (alpha, g) = (1e-2, 9.81);
    let mut pendulum = chain(1, 1.0, alpha, false);
    pendulum.options = XpbdOptions {
        substeps: 10,
        iterations: 1,
    };
    let dt = 1.0 / 600.0;
    let equilibrium = 1.0 + g * alpha;
    let (mut t, mut last, mut crossings) = (0.0, -1.0, Vec::new());
    while t < 5.0 {
        pendulum.step(dt).unwrap();
        t += dt;
        let displacement = -pendulum.x[1].y - equilibrium;
        if last < 0.0 && displacement >= 0.0 {
            crossings.push(t - dt * displacement / (displacement - last));
        }
        last = displacement;
    }
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    let theory = std::f64::consts::TAU * alpha.sqrt();
    eprintln!("period {period} vs {theory}");
    assert!((period / theory - 1.0).abs() < 0.02, "{period} vs {theory}");
}

#[test]
fn colliders_are_never_entered() {
    let mut rope = chain(30, 0.1, 0.0, true);
    rope.x.iter_mut().for_each(|x| x.y += 2.0);
    rope.colliders = vec![
        Collider::Plane {
            normal: Vector2::new(0.0, 1.0),
            offset: 0.0,
        },
        Collider::Sphere {
            centre: Vector2::new(1.5, 1.0),
            radius: 0.5,
        },
    ];
    rope.options.iterations = 2;
    for _ in 0..300 {
        rope.step(1.0 / 60.0).unwrap();
        for (i, x) in rope.x.iter().enumerate() {
            assert!(x.y >= -1e-12, "particle {i} below the ground: {x:?}");
            assert!(
                (x - Vector2::new(1.5, 1.0)).norm() >= 0.5 - 1e-12,
                "particle {i} inside the sphere"
            );
        }
    }
    // Something came to rest on the ground or the sphere.
    assert!(
        rope.x
            .iter()
            .any(|x| x.y < 1e-6 || (x - Vector2::new(1.5, 1.0)).norm() < 0.5 + 1e-6)
    );
}

#[test]
fn bad_input_is_a_typed_error() {
    let g = Vector2::new(0.0, -9.81);
    let one = || vec![Vector2::zeros()];
    assert!(Xpbd::new(one(), vec![], &[1.0], &[], g).is_err());
    assert!(Xpbd::new(one(), one(), &[0.0], &[], g).is_err());
    assert!(Xpbd::new(one(), one(), &[1.0], &[3], g).is_err());
    assert!(Xpbd::new(vec![Vector2::new(f64::NAN, 0.0)], one(), &[1.0], &[], g).is_err());
    let mut rope = chain(3, 1.0, 0.0, true);
    rope.constraints.push(Constraint::Distance {
        ends: [0, 9],
        rest: 1.0,
        compliance: 0.0,
    });
    assert!(
        rope.step(0.01)
            .unwrap_err()
            .to_string()
            .contains("particle 9 does not exist")
    );
    let mut rope = chain(3, 1.0, -1.0, true);
    assert!(
        rope.step(0.01)
            .unwrap_err()
            .to_string()
            .contains("compliance")
    );
    let mut rope = chain(3, 1.0, 0.0, true);
    rope.colliders.push(Collider::Plane {
        normal: Vector2::new(0.0, 2.0),
        offset: 0.0,
    });
    assert!(rope.step(0.01).is_err());
    let mut rope = chain(3, 1.0, 0.0, true);
    rope.options.substeps = 0;
    assert!(rope.step(0.01).is_err());
    let mut rope = chain(3, 1.0, 0.0, true);
    rope.x.push(Vector2::zeros());
    rope.v.push(Vector2::zeros());
    assert!(
        rope.step(0.01)
            .unwrap_err()
            .to_string()
            .contains("cannot be added")
    );
    let mut rope = chain(3, 1.0, 0.0, true);
    for dt in [0.0, -1.0, f64::NAN] {
        assert!(rope.step(dt).is_err());
    }
}

/// A skip-one bending constraint of zero compliance keeps a two-link arm straight: with particles
/// 0 and 1 pinned, particle 2 hangs on its link to 1 and its bending constraint to 0 holds
/// |x₂ − x₀| = 2L, so it stays near the line (it would swing down without it). A `Pin` moved
/// between steps carries its particle along.
#[test]
fn bending_keeps_an_arm_straight_and_pins_hold() {
    let x = vec![
        Vector2::new(0.0, 0.0),
        Vector2::new(0.5, 0.0),
        Vector2::new(1.0, 0.0),
    ];
    let arm = |bending: bool| {
        let mut arm = Xpbd::new(
            x.clone(),
            vec![Vector2::zeros(); 3],
            &[1.0; 3],
            &[0, 1],
            Vector2::new(0.0, -9.81),
        )
        .unwrap();
        arm.constraints.push(Constraint::Distance {
            ends: [1, 2],
            rest: 0.5,
            compliance: 0.0,
        });
        if bending {
            arm.constraints.push(Constraint::Bending {
                particles: [0, 1, 2],
                rest: 1.0,
                compliance: 0.0,
            });
        }
        arm.options.substeps = 20;
        for _ in 0..120 {
            arm.step(1.0 / 60.0).unwrap();
        }
        arm.x[2]
    };
    let (straight, limp) = (arm(true), arm(false));
    // The two rigid constraints are tangent at the straight pose (their gradients are parallel),
    // so Gauss–Seidel converges slowly there: the arm sags by 0.027 m (3°) against 0.3+ without.
    assert!(straight.y.abs() < 0.05, "{straight:?}");
    assert!(limp.y < -0.3, "{limp:?}");

    let mut held = chain(2, 1.0, 0.0, true);
    let target = Vector2::new(0.3, 0.7);
    held.constraints.push(Constraint::Pin {
        particle: 2,
        at: target,
    });
    for _ in 0..10 {
        held.step(1.0 / 60.0).unwrap();
    }
    assert_eq!(held.x[2], target);
}

/// The field and message of an `InvalidInput`, or a panic naming what came instead.
fn invalid(result: odyn::Result<()>) -> (String, String) {
    let error = result.expect_err("expected InvalidInput, got Ok");
    let message = error.to_string();
    match error {
        Error::InvalidInput { field, .. } => (field, message),
        other => panic!("expected InvalidInput, got {other}"),
    }
}

/// Settings that used to return `Ok` with NaN positions are rejected before the step, each with
/// what is wrong: a compliance whose α/h² overflows (1e308 at 1/60 s), a substep so short that
/// 1/h² overflows (1e-200 with rigid links), a NaN position or velocity written into the public
/// lists after `new`, a non-finite gravity. `u32::MAX` substeps used to run for hours: the
/// substeps and iterations are at most `XpbdOptions::MAX`.
#[test]
fn extreme_settings_are_rejected_before_the_step() {
    let mut rope = chain(3, 1.0, 1e308, true);
    let (field, message) = invalid(rope.step(1.0 / 60.0));
    assert_eq!(field, "constraints[0]");
    assert!(message.contains("compliance 1e308"), "{message}");

    let mut rope = chain(3, 1.0, 0.0, true);
    let (field, message) = invalid(rope.step(1e-200));
    assert_eq!(field, "dt");
    assert!(
        message.contains("1e-200") && message.contains("at least"),
        "{message}"
    );

    let mut rope = chain(3, 1.0, 0.0, true);
    rope.x[2].x = f64::NAN;
    assert_eq!(invalid(rope.step(1.0 / 60.0)).0, "x[2]");
    let mut rope = chain(3, 1.0, 0.0, true);
    rope.v[1].y = f64::INFINITY;
    assert_eq!(invalid(rope.step(1.0 / 60.0)).0, "v[1]");
    let mut rope = chain(3, 1.0, 0.0, true);
    rope.gravity.y = f64::NAN;
    assert_eq!(invalid(rope.step(1.0 / 60.0)).0, "gravity");

    for options in [
        XpbdOptions {
            substeps: u32::MAX,
            iterations: 1,
        },
        XpbdOptions {
            substeps: 1,
            iterations: XpbdOptions::MAX + 1,
        },
    ] {
        let mut rope = chain(3, 1.0, 0.0, true);
        rope.options = options;
        let (field, message) = invalid(rope.step(1.0 / 60.0));
        assert_eq!(field, "options");
        assert!(message.contains("at most 10000"), "{message}");
    }
}

/// A step so large that the fall overflows (1e300 s under gravity) used to return `Ok` with
/// NaN positions; now the state is checked after every step and the error names the step.
#[test]
fn a_step_that_overflows_is_a_typed_error_naming_it() {
    let mut rope = chain(3, 1.0, 0.0, true);
    rope.step(1.0 / 60.0).unwrap();
    let error = rope.step(1e300).unwrap_err();
    match &error {
        Error::NotFinite {
            solver, step, t, ..
        } => {
            assert_eq!((*solver, *step), ("Xpbd", 2));
            assert_eq!(*t, 1.0 / 60.0 + 1e300);
        }
        other => panic!("expected NotFinite, got {other}"),
    }
    let message = error.to_string();
    assert!(
        message.contains("non-finite at step 2") && message.contains("reduce dt"),
        "{message}"
    );
}

/// A particle exactly at a sphere's centre has no direction out; it used to stay inside for
/// ever. It is now pushed out towards where it was at the start of the substep, or along +y
/// when that was the centre too.
#[test]
fn a_particle_at_a_sphere_centre_is_pushed_out() {
    let sphere = Collider::Sphere {
        centre: Vector2::zeros(),
        radius: 0.5,
    };
    let one = |x: Vector2<f64>, v: Vector2<f64>| {
        let mut xpbd = Xpbd::new(vec![x], vec![v], &[1.0], &[], Vector2::zeros()).unwrap();
        xpbd.colliders.push(sphere.clone());
        xpbd.options.substeps = 1;
        xpbd
    };
    // Placed at the centre: out along +y.
    let mut placed = one(Vector2::zeros(), Vector2::zeros());
    placed.step(0.5).unwrap();
    assert_eq!(placed.x[0], Vector2::new(0.0, 0.5));
    // Arriving at the centre from (1, 0) in one substep (1 − 0.5·2 = 0 exactly): back out the
    // way it came.
    let mut arriving = one(Vector2::new(1.0, 0.0), Vector2::new(-2.0, 0.0));
    arriving.step(0.5).unwrap();
    assert_eq!(arriving.x[0], Vector2::new(0.5, 0.0));
}

/// XPBD dissipates: position-based projection removes the velocity along each correction, so a
/// rigid pendulum (one link of 1 m, released horizontally) loses swing every substep, and loses
/// less the more substeps a step takes (the loss per unit time falls with the substep). Measured
/// as the height the bob still reaches in the last 3 s of 20 s, over the 1 m it started at.
#[test]
fn a_rigid_pendulum_keeps_more_of_its_swing_with_more_substeps() {
    let mut kept = Vec::new();
    for substeps in [1, 4, 16, 64] {
        let mut pendulum = chain(1, 1.0, 0.0, true);
        pendulum.options = XpbdOptions {
            substeps,
            iterations: 1,
        };
        let mut top = f64::NEG_INFINITY;
        for frame in 0..1200 {
            pendulum.step(1.0 / 60.0).unwrap();
            if frame >= 1020 {
                top = top.max(pendulum.x[1].y);
            }
        }
        eprintln!(
            "{substeps} substeps: keeps {:.1} % of its swing",
            100.0 * (top + 1.0)
        );
        kept.push(top + 1.0);
    }
    assert!(kept.windows(2).all(|w| w[1] > w[0]), "{kept:?}");
    assert!(kept[0] < 0.5 && kept[3] > 0.9, "{kept:?}");
}

/// A held particle stays exactly where it is held, at rest, while the chain swings from it (a
/// drag); let go, it falls with its own mass again; a pinned particle stays pinned when let go.
/// Holding a particle that does not exist, or at a non-finite point, is a typed error.
#[test]
fn a_held_particle_stays_where_it_is_held_until_let_go() {
    let mut rope = chain(10, 0.1, 0.0, true);
    let hand = Vector2::new(0.5, 0.3);
    for _ in 0..30 {
        rope.hold(10, Some(hand)).unwrap();
        rope.step(1.0 / 60.0).unwrap();
        assert_eq!(rope.x[10], hand);
        assert_eq!(rope.v[10], Vector2::zeros());
    }
    // The chain hangs between the pin and the hand: its middle sags below both.
    assert!(rope.x[5].y < 0.0, "{:?}", rope.x[5]);
    rope.hold(10, None).unwrap();
    rope.step(1.0 / 60.0).unwrap();
    assert!(rope.x[10].y < hand.y, "falls once let go: {:?}", rope.x[10]);
    rope.hold(0, None).unwrap();
    rope.step(1.0 / 60.0).unwrap();
    assert_eq!(rope.x[0], Vector2::zeros(), "the pin holds");
    assert!(matches!(
        rope.hold(11, None),
        Err(Error::InvalidInput { .. })
    ));
    assert!(matches!(
        rope.hold(3, Some(Vector2::new(f64::NAN, 0.0))),
        Err(Error::InvalidInput { .. })
    ));
}
