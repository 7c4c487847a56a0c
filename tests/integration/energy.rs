//! Energy behaviour of each integrator against its closed form.

use crate::common;

use common::{Oscillator, Spring};
use odyn::prelude::*;

/// Explicit Euler on ẍ = −x maps (x, v) to (x + h·v, v − h·x), whose determinant is 1 + h²:
/// E = (x² + v²)/2 is multiplied by exactly 1 + h² every step (the lab seed's closed form).
#[test]
fn explicit_euler_gains_exactly_one_plus_dt_squared_per_step() {
    let osc = Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 1.0,
    };
    let dt = 0.05;
    let run = osc
        .simulate()
        .integrator(Method::ExplicitEuler)
        .dt(dt)
        .steps(400)
        .run()
        .unwrap();
    for pair in run.samples.windows(2) {
        let ratio = pair[1].energy.unwrap() / pair[0].energy.unwrap();
        assert!(
            (ratio / (1.0 + dt * dt) - 1.0).abs() < 1e-12,
            "step {}: {ratio}",
            pair[1].step
        );
    }
    // 1.0025⁴⁰⁰ ≈ 2.715: "The Skeleton of a Physics Engine" (seed 002) quotes 2.715.
    let expected = 1.0025f64.powi(400);
    let ratio = run.energy_ratio().unwrap();
    assert!(
        (ratio / expected - 1.0).abs() < 1e-12,
        "{ratio} vs {expected}"
    );
    assert!((ratio - 2.715).abs() < 5e-4);
}

/// Symplectic Euler conserves H̃ = E − (h/2)·ω·x·v (ω = 1 here); since |x·v| ≤ E, from
/// x₀ = 1, v₀ = 0 (H̃ = E₀) the energy stays in [2/(2 + h), 2/(2 − h)]·E₀ forever.
/// Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., §I.1.2.
#[test]
fn symplectic_euler_stays_in_its_band_for_a_million_steps() {
    let h = 0.1;
    let osc = Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 1.0,
    };
    let run = osc
        .simulate()
        .integrator(Method::SymplecticEuler)
        .dt(h)
        .steps(1_000_000)
        .run()
        .unwrap();
    let (lo, hi) = (2.0 / (2.0 + h), 2.0 / (2.0 - h));
    let e0 = run.first().energy.unwrap();
    let (min, max) = extremes(run.samples.iter().map(|s| s.energy.unwrap() / e0));
    assert!(
        min >= lo * (1.0 - 1e-9) && max <= hi * (1.0 + 1e-9),
        "[{min}, {max}] ⊄ [{lo}, {hi}]"
    );
    // The band is tight: the orbit passes x = ±v, where |x·v| = E.
    assert!(
        max > hi * (1.0 - 1e-3) && min < lo * (1.0 + 1e-3),
        "[{min}, {max}] vs [{lo}, {hi}]"
    );
}

/// Velocity Verlet on ẍ = −x is the linear map x' = (1 − h²/2)x + h·v,
/// v' = −h(1 − h²/4)x + (1 − h²/2)v, which preserves H̃ = v²/2 + (1 − h²/4)·x²/2 (direct
/// computation; HLW 2006, §I.1.4 and §IX.1 for the general modified Hamiltonian). So from x₀ = 1,
/// v₀ = 0 the energy E = H̃ + h²x²/8 stays in [1 − h²/4, 1]·E₀. Position Verlet and leapfrog are
/// the same map.
#[test]
fn verlet_family_stays_in_its_band_for_a_million_steps() {
    let h = 0.1;
    let osc = Oscillator {
        x: 1.0,
        v: 0.0,
        omega: 1.0,
    };
    for method in [
        Method::VelocityVerlet,
        Method::PositionVerlet,
        Method::Leapfrog,
    ] {
        let run = osc
            .simulate()
            .integrator(method)
            .dt(h)
            .steps(1_000_000)
            .record_every(7)
            .run()
            .unwrap();
        let e0 = run.first().energy.unwrap();
        let (min, max) = extremes(run.samples.iter().map(|s| s.energy.unwrap() / e0));
        let lo = 1.0 - h * h / 4.0;
        assert!(
            min >= lo - 1e-9 && max <= 1.0 + 1e-9,
            "{method}: [{min}, {max}] ⊄ [{lo}, 1]"
        );
        assert!(min < lo + 1e-4, "{method}: the band is tight, min {min}");
    }
}

/// With damping as a force, dE/dt = −b·v² ≤ 0; RK4 at the tutorial's dt = 0.016 reproduces it:
/// the recorded energy never increases from one step to the next.
#[test]
fn rk4_energy_never_increases_with_damping() {
    let spring = Spring {
        x: 1.0,
        v: 0.0,
        k: 50.0,
        b: 0.5,
        m: 1.0,
    };
    let run = spring
        .simulate()
        .integrator(Method::Rk4)
        .duration(10.0)
        .run()
        .unwrap();
    assert_eq!(run.steps(), 625);
    for pair in run.samples.windows(2) {
        assert!(
            pair[1].energy <= pair[0].energy,
            "energy rose at step {}",
            pair[1].step
        );
    }
}

/// Leapfrog keeps the Kepler energy bounded over many orbits: e = 0.5, GM = 1, from pericentre
/// (0.5, 0) with speed √3 (vis-viva: v² = GM(2/r − 1/a), a = 1), E = −1/2, period 2π.
#[test]
fn leapfrog_bounds_the_kepler_energy() {
    let kepler = common::Kepler {
        r: Vector2::new(0.5, 0.0),
        v: Vector2::new(0.0, 3f64.sqrt()),
        gm: 1.0,
    };
    let orbits = 100.0;
    let run = kepler
        .simulate()
        .dt(0.002)
        .duration(orbits * std::f64::consts::TAU)
        .record_every(50)
        .run()
        .unwrap();
    assert!((run.first().energy.unwrap() + 0.5).abs() < 1e-15);
    let (min, max) = extremes(run.samples.iter().map(|s| s.energy.unwrap()));
    assert!(max - min < 1e-4, "energy range {}", max - min);
    // After a whole number of periods the orbit closes (up to the phase error).
    assert!(
        (run.last().state.r - kepler.r).norm() < 0.05,
        "{:?}",
        run.last().state.r
    );
}

fn extremes(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), e| {
        (lo.min(e), hi.max(e))
    })
}
