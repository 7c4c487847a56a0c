//! FLIP/APIC: the dam-break front against Martin & Moyce (1952), the liquid's volume kept by the
//! density correction and lost without it, a resting pool that stays at rest, the projection's
//! divergence at the solver's tolerance, results independent of the thread count, and typed
//! errors for bad input.

use odyn::hybrid::Transfer;
use odyn::hybrid::flip::{Flip, FlipOptions};
use odyn::nalgebra::Vector2;
use odyn::{Error, Preconditioner};
// The dam break and Martin & Moyce's data (`scenes/src/fluids.rs`).
use scenes::{MARTIN_MOYCE, flip_dam_break};

/// Runs `flip` (a column `a` wide) to each of Martin & Moyce's times T = t·√(2g/a) and returns
/// the relative differences of the front Z = z/a from theirs.
fn front_errors(flip: &mut Flip, a: f64) -> Vec<f64> {
    let scale = (2.0 * 9.81 / a).sqrt();
    let mut t = 0.0;
    MARTIN_MOYCE
        .iter()
        .map(|&(time, z)| {
            while t * scale < time {
                let dt = flip.stable_dt();
                flip.step(dt).unwrap();
                t += dt;
            }
            flip.front() / a / z - 1.0
        })
        .collect()
}

/// The surge front of the 0.95 FLIP blend at 16 cells across the column (a = 0.2 m, 2 048
/// particles) against Martin & Moyce's 15 points for n² = 2: mean +2.6 %, every point from
/// T = 2 on within 4 % (SPH at 40 particles across leads them by +11 % on average,
/// `examples/sph.rs`). Inviscid and without the gate's opening, the simulation leads the
/// experiment early on (+11 % at T = 1.2).
#[test]
fn the_dam_break_front_follows_martin_and_moyce() {
    let a = 0.2;
    let mut flip = flip_dam_break(a, 16, Transfer::Blend { flip: 0.95 }).unwrap();
    let errors = front_errors(&mut flip, a);
    let mean = errors.iter().sum::<f64>() / errors.len() as f64;
    eprintln!("front errors {errors:?}, mean {mean}");
    assert!(mean.abs() < 0.05, "{mean}");
    for (&(time, _), e) in MARTIN_MOYCE.iter().zip(&errors) {
        let bound = if time >= 2.0 { 0.04 } else { 0.15 };
        assert!(e.abs() < bound, "T = {time}: {e}");
    }
}

/// The dam break for one second at 16 cells across a: with the density correction the liquid
/// fills its initial area within 5 % at every step (measured: 3.9 % at worst, one cell in 26
/// at the surface, and 100.2 % at the end); without it, the particles bunch and it fills less
/// than 85 % by the end (measured 78.9 %: the volume loss the correction exists for; 68 % after
/// 4 s at 20 cells, `examples/flip.rs`).
#[test]
fn the_density_correction_keeps_the_volume_that_flip_alone_loses() {
    let run = |correction: f64| {
        let a = 0.2;
        let h = a / 16.0;
        let mut flip = Flip::new(FlipOptions {
            nx: 82,
            ny: 50,
            cell: h,
            volume_correction: correction,
            ..FlipOptions::default()
        })
        .unwrap();
        let corner = Vector2::new(h, h);
        flip.add_block(corner, corner + Vector2::new(a, 2.0 * a), |_| {
            Vector2::zeros()
        })
        .unwrap();
        let area = flip.filled_area();
        let (mut t, mut worst): (f64, f64) = (0.0, 0.0);
        while t < 1.0 {
            let dt = flip.stable_dt();
            flip.step(dt).unwrap();
            t += dt;
            worst = worst.max((flip.filled_area() / area - 1.0).abs());
        }
        (flip.filled_area() / area, worst)
    };
    let (kept, worst) = run(1.0);
    let (lost, _) = run(0.0);
    eprintln!("area after 1 s: corrected {kept} (worst {worst}), uncorrected {lost}");
    assert!(worst < 0.05, "{worst}");
    assert!(lost < 0.85, "{lost}");
}

/// A pool at rest stays at rest: the projection balances gravity to the solver's tolerance,
/// the particles move by less than 10⁻⁸ m/s, and every fluid cell's net outflow is below
/// 10⁻⁸ m/s (the Krylov tolerance 10⁻⁸ relative to the gravity impulse g·dt it removes).
#[test]
fn a_resting_pool_stays_at_rest() {
    let h = 1.0 / 32.0;
    let mut flip = Flip::new(FlipOptions {
        nx: 34,
        ny: 24,
        cell: h,
        ..FlipOptions::default()
    })
    .unwrap();
    flip.add_block(Vector2::new(h, h), Vector2::new(33.0 * h, 11.0 * h), |_| {
        Vector2::zeros()
    })
    .unwrap();
    let x0 = flip.x.clone();
    for _ in 0..100 {
        flip.step(0.01).unwrap();
    }
    let fastest = flip.v.iter().fold(0.0f64, |m, v| m.max(v.norm()));
    let moved = flip
        .x
        .iter()
        .zip(&x0)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).norm()));
    eprintln!(
        "fastest {fastest:e} m/s, moved {moved:e} m, outflow {:e}",
        flip.largest_outflow()
    );
    assert!(fastest < 1e-8 && moved < 1e-8, "{fastest} {moved}");
    assert!(flip.largest_outflow() < 1e-8);
}

#[test]
fn results_do_not_depend_on_the_thread_count() {
    let run = |threads| {
        crate::common::in_pool(threads, || {
            // 32 cells across: 8 192 particles, above the count from which passes go
            // parallel.
            let mut flip = flip_dam_break(0.2, 32, Transfer::Apic).unwrap();
            for _ in 0..20 {
                flip.step(flip.stable_dt()).unwrap();
            }
            (flip.x, flip.v)
        })
    };
    let one = run(1);
    assert_eq!(one.0.len(), 8192);
    assert_eq!(one, run(3));
}

#[test]
fn bad_input_is_a_typed_error() {
    let options = FlipOptions::default;
    for bad in [
        FlipOptions { nx: 3, ..options() },
        FlipOptions {
            nx: usize::MAX,
            ..options()
        },
        FlipOptions {
            cell: -1.0,
            ..options()
        },
        FlipOptions {
            gravity: Vector2::new(f64::NAN, 0.0),
            ..options()
        },
        FlipOptions {
            transfer: Transfer::Blend { flip: 1.5 },
            ..options()
        },
        FlipOptions {
            tolerance: 0.0,
            ..options()
        },
        FlipOptions {
            preconditioner: Preconditioner::Fourier,
            ..options()
        },
        FlipOptions {
            sampling: 17,
            ..options()
        },
        FlipOptions {
            volume_correction: f64::NAN,
            ..options()
        },
    ] {
        assert!(
            matches!(Flip::new(bad.clone()), Err(Error::InvalidInput { .. })),
            "{bad:?}"
        );
    }
    let mut flip = Flip::new(options()).unwrap();
    let h = flip.options().cell;
    let still = |_| Vector2::zeros();
    let v = Vector2::new;
    assert!(flip.add_block(v(0.0, 0.0), v(0.2, 0.2), still).is_err());
    assert!(flip.add_block(v(0.2, 0.2), v(0.1, 0.1), still).is_err());
    assert!(flip.add_block(v(h, h), v(h, 0.2), still).is_err());
    assert!(flip.add_particles(&[v(0.5 * h, 0.1)], still).is_err());
    assert!(
        flip.add_particles(&[v(0.1, 0.1)], |_| v(0.0, f64::INFINITY))
            .is_err()
    );
    assert!(flip.x.is_empty());
    flip.add_block(v(h, h), v(0.3, 0.2), still).unwrap();
    for dt in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        assert!(flip.step(dt).is_err());
    }
    flip.x[0] = v(f64::NAN, 0.1);
    assert!(flip.step(1e-3).is_err());
    flip.x[0] = v(0.1, 0.1);
    flip.v[0] = v(1e308 * 10.0, 0.0);
    assert!(flip.step(1e-3).is_err());
    flip.v[0] = v(0.0, 0.0);
    flip.v.pop();
    assert!(flip.step(1e-3).is_err());
    flip.v.push(v(0.0, 0.0));
    flip.step(1e-3).unwrap();
    // Speeds near overflow: an error, never a panic.
    flip.v.iter_mut().for_each(|v| v.x = 1e300);
    assert!(flip.step(1.0).is_err());
}

/// Hostile input probed (issue 53): each is a typed error or a sound result, never a panic.
#[test]
fn hostile_input_never_panics() {
    let v = Vector2::new;
    let still = |_| Vector2::zeros();
    // An empty box steps (nothing to move); its stable step is gravity's bound.
    let mut empty = Flip::new(FlipOptions::default()).unwrap();
    let dt = empty.stable_dt();
    assert!(dt.is_finite() && dt > 0.0);
    empty.step(dt).unwrap();
    assert_eq!((empty.front(), empty.filled_area()), (0.0, 0.0));
    // Liquid at rest without gravity: the stable step is infinite, which step refuses.
    let mut weightless = Flip::new(FlipOptions {
        gravity: Vector2::zeros(),
        ..FlipOptions::default()
    })
    .unwrap();
    let h = weightless.options().cell;
    weightless.add_block(v(h, h), v(0.3, 0.3), still).unwrap();
    assert_eq!(weightless.stable_dt(), f64::INFINITY);
    assert!(matches!(
        weightless.step(f64::INFINITY),
        Err(Error::InvalidInput { .. })
    ));
    // Cells of 10⁻³⁰⁰ m: x·(1/h) and x/h round differently at the room's edge, where a step
    // once panicked; positions are now judged in cells, as the stencils use them.
    let h = 1e-300;
    let mut tiny = Flip::new(FlipOptions {
        nx: 18,
        ny: 18,
        cell: h,
        ..FlipOptions::default()
    })
    .unwrap();
    tiny.add_block(v(h, h), v(9.0 * h, 12.0 * h), still)
        .unwrap();
    for _ in 0..10 {
        tiny.step(tiny.stable_dt()).unwrap();
    }
    assert!(tiny.front() > 0.0);
    // A particle put outside the room (or at NaN) between steps: the measures skip it and the
    // step refuses it.
    let mut flip = Flip::new(FlipOptions::default()).unwrap();
    let h = flip.options().cell;
    flip.add_block(v(h, h), v(0.3, 0.3), still).unwrap();
    let area = flip.filled_area();
    flip.x[0] = v(100.0, -5.0);
    flip.x[1] = v(f64::NAN, 0.2);
    assert!((flip.filled_area() - area).abs() <= 2.0 * h * h);
    assert!(matches!(flip.step(1e-3), Err(Error::InvalidInput { .. })));
    // Gravity whose norm overflows: a zero stable step, refused.
    let mut heavy = Flip::new(FlipOptions {
        gravity: v(0.0, -1e300),
        ..FlipOptions::default()
    })
    .unwrap();
    heavy.add_block(v(h, h), v(0.3, 0.3), still).unwrap();
    assert!(heavy.step(heavy.stable_dt()).is_err());
    assert!(heavy.step(1e-3).is_err());
}
